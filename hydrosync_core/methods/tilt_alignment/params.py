"""Parameters of the tilt-pole alignment: the one place they are declared.

The panel form, the ``hydrosync tilt`` flags, ``hydrosync run tilt_alignment --param``,
the stored parameters and the report's parameter table all derive from
:class:`TiltParams`. Imports only the standard library.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hydrosync_core.errors import InputError
from hydrosync_core.params import Params, param

#: Reported method: the joint batch least-squares (HydroSync, the default: best in the
#: benchmark), Li et al.'s mini-batch / batch / stochastic gradient descent, the SVD
#: (Wahba) solution and the closed-form heading-only least squares.
METHODS = ("joint", "mbgd", "bgd", "sgd", "svd", "closed_form")
HEADING_ONLY = ("mbgd", "bgd", "sgd", "svd", "closed_form")
#: What one row of imu.csv means (see :mod:`.imu_convention`, kept here without imports).
IMU_CONVENTIONS = ("instant", "interval-start", "interval-middle", "interval-end")


@dataclass(frozen=True)
class ImuGrade:
    """Documented numbers of one IMU grade (1σ, per axis; noise as a density).

    The bias σ are the joint method's priors (constant over a swing: the run-to-run bias
    after the pole's own calibration); the noise densities the fallback when a record is
    too short to measure its own, and the level beyond which a record is called noisier
    than its grade. Per sample at rate f the noise is density·√f.
    """

    gyro_bias_deg_s: float
    accel_bias_m_s2: float
    gyro_noise_deg_s_rthz: float
    accel_noise_m_s2_rthz: float


#: ``--imu-grade``: consumer (phone-class), mems (a survey pole's MEMS IMU, the default:
#: gyro bias 0.05°/s, accelerometer bias 0.02 m/s², as issue #30's swings), industrial
#: (a tactical-grade MEMS).
IMU_GRADES = {
    "consumer": ImuGrade(0.10, 0.040, 0.015, 0.0020),
    "mems": ImuGrade(0.05, 0.020, 0.008, 0.0012),
    "industrial": ImuGrade(0.02, 0.008, 0.004, 0.0006),
}


@dataclass(frozen=True)
class TiltParams(Params):
    """Parameters of the heading alignment and tip of a tilt RTK pole.

    Lengths in metres, times in seconds, angles in degrees.
    """

    SCHEMA_VERSION: ClassVar[int] = 1

    method: str = param(
        "joint", label="Reported method", choices=METHODS,
        help="result written as tip and heading misalignment: joint = batch least squares "
             "over the whole swing (attitude, tip, IMU biases; best in the benchmark), "
             "mbgd/bgd/sgd = Li et al.'s gradient descent, svd = Wahba, closed_form = exact "
             "heading-only least squares; all are always computed")
    sigma_h_m: float = param(
        0.01, label="GNSS σ horizontal", unit="m", minimum=0.0, min_exclusive=True,
        maximum=1.0, decimals=4, step=0.001,
        help="a-priori 1σ of one horizontal antenna coordinate (RTK fixed: about 1 cm)")
    sigma_v_m: float = param(
        0.02, label="GNSS σ vertical", unit="m", minimum=0.0, min_exclusive=True,
        maximum=1.0, decimals=4, step=0.001,
        help="a-priori 1σ of the antenna height")
    level_s: float = param(
        1.0, label="Levelling time", unit="s", minimum=0.1, maximum=60.0, decimals=2,
        help="the first seconds of the record, pole held near vertical, used by the Mahony "
             "filter to level the IMU before the swing")
    mahony_kp: float = param(
        0.3, label="Mahony Kp", unit="rad/s", minimum=0.0, maximum=50.0, decimals=3,
        advanced=True, help="proportional gain of the Mahony levelling filter")
    mahony_ki: float = param(
        0.02, label="Mahony Ki", unit="rad/s²", minimum=0.0, maximum=10.0, decimals=3,
        advanced=True, help="integral gain of the Mahony levelling filter (gyro-bias estimate)")
    min_vector_m: float = param(
        0.10, label="Shortest vector", unit="m", minimum=0.0, maximum=10.0, decimals=3,
        help="observation vectors (antenna displacements between two epochs) shorter than "
             "this horizontally are not used: their heading is dominated by noise")
    reject_k: float = param(
        3.0, label="Rejection limit", minimum=1.0, maximum=20.0, decimals=1,
        help="a vector is rejected when its own heading departs from the median by more "
             "than this many robust σ (or the floor below, whichever is larger)")
    reject_floor_deg: float = param(
        1.0, label="Rejection floor", unit="°", minimum=0.0, maximum=90.0, decimals=2,
        advanced=True, help="vectors within this of the median heading are always kept")
    max_spread_deg: float = param(
        8.0, label="Largest spread", unit="°", minimum=0.1, maximum=180.0, decimals=1,
        help="when the per-vector headings spread more than this (robust σ), the vector "
             "set is refused as faulty (noise or IMU fault): undetermined")
    min_vectors: int = param(
        5, label="Fewest vectors", minimum=1, maximum=100000,
        help="fewer retained vectors than this: undetermined")
    learning_rate: float = param(
        0.3, label="Learning rate α", minimum=0.0, min_exclusive=True, maximum=0.99,
        decimals=3, help="gradient-descent step factor on the normalised J(ψ) (whose "
                         "curvature is about 2: 0.5 is a Newton step, above 1 diverges)")
    stop_deg: float = param(
        1e-6, label="Stop threshold ε", unit="°", minimum=0.0, min_exclusive=True,
        maximum=1.0, decimals=9, help="gradient descent stops when its step |L| is below this")
    max_iterations: int = param(
        1000, label="Maximum iterations", minimum=1, maximum=1000000, advanced=True,
        help="gradient-descent iterations before it is reported not converged")
    tip_window_s: float = param(
        1.0, label="Shot window", unit="s", minimum=0.0, min_exclusive=True, maximum=600.0,
        decimals=2, help="heading-only methods: the tip is the mean of the tilt-compensated "
                         "epochs of the last seconds of the record (the pole held on the "
                         "point after the swing)")
    accel_block_s: float = param(
        0.25, label="Accelerometer block", unit="s", minimum=0.02, maximum=5.0, decimals=3,
        advanced=True, help="joint method: accelerometers enter in Hann windows twice this "
                            "long, one every this many seconds (overlapping by half)")
    imu_grade: str = param(
        "mems", label="IMU grade", choices=tuple(IMU_GRADES),
        help="the IMU's class, whose documented bias σ are the joint method's priors: "
             + "; ".join(f"{k} gyro {g.gyro_bias_deg_s:g}°/s, accelerometer "
                         f"{g.accel_bias_m_s2:g} m/s²" for k, g in IMU_GRADES.items()))
    imu_convention: str | None = param(
        None, label="IMU samples", choices=IMU_CONVENTIONS,
        none_label="as pole.json declares (imu_convention), else instant",
        help="what one IMU row is: instant = rate and specific force at the time tag; "
             "interval-start/-middle/-end = their means (increments / interval) over one "
             "sample interval, tagged at its start, middle or end. A wrong choice shows as "
             "a GNSS time offset of half a sample")
    gyro_bias_sigma_deg_s: float | None = param(
        None, label="Gyro bias σ", unit="°/s", minimum=0.0, min_exclusive=True,
        maximum=10.0, decimals=3, advanced=True, none_label="from the IMU grade",
        help="joint method: a-priori 1σ of the gyro bias (datasheet bias stability)")
    accel_bias_sigma_m_s2: float | None = param(
        None, label="Accelerometer bias σ", unit="m/s²", minimum=0.0, min_exclusive=True,
        maximum=5.0, decimals=4, advanced=True, none_label="from the IMU grade",
        help="joint method: a-priori 1σ of the accelerometer bias; a swing in one plane "
             "cannot tell it from the tilt out of that plane, so this bound matters")
    tip_tolerance_m: float = param(
        0.01, label="Tip tolerance", unit="m", minimum=0.0, min_exclusive=True, maximum=1.0,
        decimals=4, step=0.001,
        help="warn when the horizontal circle holding the tip with 95 % probability is "
             "wider than this (a swing nearly in one plane leaves the accelerometer bias "
             "along the swing axis mixed with the tilt out of the plane)")
    gravity_m_s2: float | None = param(
        None, label="Gravity", unit="m/s²", minimum=9.7, maximum=9.9, decimals=5,
        advanced=True, none_label="normal gravity at the latitude (geodetic input), else "
                                  "9.80665",
        help="magnitude of gravity at the point")
    monte_carlo_runs: int = param(
        0, label="Monte-Carlo runs", minimum=0, maximum=10000, advanced=True,
        help="simulated swings like this one (pole, rate, tilt, noise) solved by every method "
             "for the error histogram and tip scatter (about 2-6 s each); 0 = none "
             "(benchmarks/bench_tilt.py runs the full study)")

    @property
    def grade(self) -> ImuGrade:
        return IMU_GRADES[self.imu_grade]

    @property
    def gyro_bias_prior_deg_s(self) -> float:
        """The gyro-bias prior in use (°/s): the option, else the grade's."""
        v = self.gyro_bias_sigma_deg_s
        return self.grade.gyro_bias_deg_s if v is None else v

    @property
    def accel_bias_prior_m_s2(self) -> float:
        """The accelerometer-bias prior in use (m/s²): the option, else the grade's."""
        v = self.accel_bias_sigma_m_s2
        return self.grade.accel_bias_m_s2 if v is None else v

    def validate(self) -> None:
        if self.sigma_v_m < 0.2 * self.sigma_h_m:
            raise InputError(None, "vertical σ below a fifth of the horizontal σ is not a "
                             "GNSS position", field="sigma_v_m")
