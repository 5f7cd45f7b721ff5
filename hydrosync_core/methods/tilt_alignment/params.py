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
    gyro_bias_sigma_deg_s: float = param(
        0.2, label="Gyro bias σ", unit="°/s", minimum=0.0, min_exclusive=True, maximum=10.0,
        decimals=3, advanced=True,
        help="joint method: a-priori 1σ of the gyro bias (datasheet bias stability)")
    accel_bias_sigma_m_s2: float = param(
        0.05, label="Accelerometer bias σ", unit="m/s²", minimum=0.0, min_exclusive=True,
        maximum=5.0, decimals=4, advanced=True,
        help="joint method: a-priori 1σ of the accelerometer bias; a swing in one plane "
             "cannot tell it from the tilt out of that plane, so this bound matters")
    tip_tolerance_m: float = param(
        0.01, label="Tip tolerance", unit="m", minimum=0.0, min_exclusive=True, maximum=1.0,
        decimals=4, step=0.001,
        help="warn when the horizontal circle holding the tip with 99 % probability is "
             "wider than this (a swing nearly in one plane leaves the accelerometer bias "
             "along the swing axis mixed with the tilt out of the plane)")
    gravity_m_s2: float | None = param(
        None, label="Gravity", unit="m/s²", minimum=9.7, maximum=9.9, decimals=5,
        advanced=True, none_label="normal gravity at the latitude (geodetic input), else "
                                  "9.80665",
        help="magnitude of gravity at the point")
    monte_carlo_runs: int = param(
        20, label="Monte-Carlo runs", minimum=0, maximum=10000, advanced=True,
        help="simulated swings like this one (pole, rate, tilt, noise) solved by every method "
             "for the error histogram and tip scatter; 0 = none")

    def validate(self) -> None:
        if self.sigma_v_m < 0.2 * self.sigma_h_m:
            raise InputError(None, "vertical σ below a fifth of the horizontal σ is not a "
                             "GNSS position", field="sigma_v_m")
