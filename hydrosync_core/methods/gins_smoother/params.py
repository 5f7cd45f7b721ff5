"""Parameters of the GNSS/INS smoother: the one place they are declared.

The sensor description (initial state, IMU noise, antenna lever arm) comes from the
configuration file (KF-GINS YAML); these are the processing options. Imports only the
standard library and the parameter machinery.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hydrosync_core.errors import InputError
from hydrosync_core.params import Params, param

#: What a run did, by whether it smoothed (``counts["ran"]`` of a result; CLI, panel, PDF).
RAN = {True: "forward EKF and RTS smoother", False: "forward EKF only (no smoothing)"}


@dataclass(frozen=True)
class GinsParams(Params):
    """Processing options of the loosely coupled GNSS/INS EKF and RTS smoother.

    Times in seconds, velocities in m/s, angles in degrees (body frame x forward, y right,
    z down).
    """

    SCHEMA_VERSION: ClassVar[int] = 1

    scale_factors: bool = param(
        True, label="Scale-factor states",
        help="estimate gyro and accelerometer scale factors (21 states) besides the 15 "
             "states of Wang et al. (position, velocity, attitude, gyro and accelerometer "
             "biases)")
    smooth: bool = param(
        True, label="RTS smoothing",
        help="run the Rauch-Tung-Striebel backward pass after the forward filter")
    nhc: bool = param(
        False, label="Non-holonomic constraint", group="Motion constraints",
        help="land vehicles: lateral and vertical velocity in the vehicle frame are zero "
             "(Wang et al.); leave off for vessels, which sway and heave")
    nhc_std: float = param(
        0.1, label="NHC σ", unit="m/s", minimum=0.0, min_exclusive=True, maximum=10.0,
        decimals=3, group="Motion constraints",
        help="standard deviation of the lateral and vertical vehicle-frame velocity")
    zupt: bool = param(
        True, label="Zero-velocity updates", group="Motion constraints",
        help="zero velocity when the IMU is quiet and the filter speed is below the ZUPT "
             "speed")
    zupt_std: float = param(
        0.01, label="ZUPT σ", unit="m/s", minimum=0.0, min_exclusive=True, maximum=1.0,
        decimals=4, group="Motion constraints", help="standard deviation of the zero velocity")
    zupt_speed: float = param(
        0.05, label="ZUPT speed limit", unit="m/s", minimum=0.0, min_exclusive=True,
        maximum=5.0, decimals=3, group="Motion constraints", advanced=True,
        help="no ZUPT while the filter speed exceeds this (a quiet IMU at constant speed "
             "is not a standstill)")
    zupt_window_s: float = param(
        1.0, label="Standstill window", unit="s", minimum=0.05, maximum=30.0, decimals=2,
        group="Motion constraints", advanced=True,
        help="window of the IMU statistics that detect a standstill")
    zupt_acc_std: float = param(
        0.2, label="Standstill accel std", unit="m/s²", minimum=0.0, min_exclusive=True,
        maximum=10.0, decimals=4, group="Motion constraints", advanced=True,
        help="largest specific-force standard deviation (any axis) over the window")
    zupt_gyro_dps: float = param(
        1.0, label="Standstill rate", unit="°/s", minimum=0.0, min_exclusive=True,
        maximum=30.0, decimals=3, group="Motion constraints", advanced=True,
        help="largest mean angular-rate magnitude over the window")
    constraint_interval_s: float = param(
        0.5, label="Constraint interval", unit="s", minimum=0.005, maximum=60.0, decimals=3,
        group="Motion constraints",
        help="time between NHC/ZUPT updates (also sets the smoother's node density)")
    mounting_deg: tuple[float, float, float] = param(
        (0.0, 0.0, 0.0), label="IMU mounting angles", unit="°", metavar=("ROLL", "PITCH", "YAW"),
        group="Motion constraints",
        help="roll, pitch, yaw of the IMU body frame relative to the vehicle frame: "
             "C(vehicle ← IMU) = Rz(yaw)·Ry(pitch)·Rx(roll), e.g. yaw 90 when the IMU's x "
             "axis points to the vehicle's starboard (the NHC applies in the vehicle frame)")
    gnss_std_scale: float = param(
        1.0, label="GNSS σ scale", minimum=0.0, min_exclusive=True, maximum=1000.0,
        decimals=2, help="factor on the std of the GNSS file")
    gnss_noise: str = param(
        "auto", label="GNSS noise model", choices=("auto", "file"),
        help="auto: check the file's GNSS σ against the data (forward innovations normalised "
             "by their predicted std: RMS 0.8-1.25, autocorrelation at 1 s below 0.3) and, "
             "if they disagree, re-estimate — white σ scaled to the residual scatter, the "
             "rest as a time-correlated (Gauss-Markov) GNSS error with τ by maximum "
             "likelihood — reported with the result; file: the file's σ (× the scale) as "
             "white noise")
    gnss_corr_time_s: float = param(
        0.0, label="GNSS error correlation time", unit="s", minimum=0.0, maximum=1e5,
        decimals=1, advanced=True,
        help="model the GNSS error as white plus a Gauss-Markov error of this correlation "
             "time (white part scaled from the residuals, the rest of the file's σ "
             "correlated); 0 = chosen by the auto check")
    gnss_gate: float = param(
        0.0, label="GNSS innovation gate", minimum=0.0, maximum=1e6, decimals=1,
        advanced=True,
        help="reject a GNSS fix whose normalised innovation squared exceeds this (3 degrees "
             "of freedom: 16.3 = 99.9 %); 0 = accept all")
    propagation_interval_s: float = param(
        0.02, label="Covariance step", unit="s", minimum=0.001, maximum=1.0, decimals=3,
        advanced=True,
        help="the covariance is propagated over blocks of IMU epochs this long (the "
             "mechanisation runs at every IMU epoch)")
    max_node_interval_s: float = param(
        1.0, label="Smoother node interval", unit="s", minimum=0.01, maximum=60.0,
        decimals=2, advanced=True,
        help="longest time between stored smoother nodes (the smoothed correction is "
             "interpolated between nodes)")
    align_mode: str = param(
        "auto", label="Alignment", choices=("auto", "static", "moving", "given"),
        group="Alignment",
        help="static: level at the rest at the start, heading by gyrocompassing (gyro "
             "better than 1 °/h), the given heading or the GNSS track once moving (walks, "
             "boats at the quay); moving: heading from the GNSS course above the alignment "
             "speed; given: the initial attitude given; auto: the configuration's or given "
             "attitude, gyrocompassing, moving, else static with the track's heading")
    initial_attitude_deg: tuple[float, float, float] | None = param(
        None, label="Initial attitude", unit="°", metavar=("ROLL", "PITCH", "YAW"),
        group="Alignment", none_label="from the data",
        help="roll, pitch, yaw of the body at the first GNSS epoch (C_b^n = "
             "Rz(yaw)·Ry(pitch)·Rx(roll)); used as given")
    initial_heading_deg: float | None = param(
        None, label="Initial heading", unit="°", minimum=-360.0, maximum=360.0, decimals=2,
        group="Alignment", none_label="from the data",
        help="static alignment: the body's heading at the end of the rest (roll and pitch "
             "still from levelling)")
    align_time_s: float = param(
        30.0, label="Static alignment time", unit="s", minimum=1.0, maximum=600.0,
        decimals=1, advanced=True, group="Alignment",
        help="longest part of the quiet start used for levelling and gyrocompassing (at "
             "least 2 s of rest are needed)")
    align_speed: float = param(
        3.0, label="Moving alignment speed", unit="m/s", minimum=0.1, maximum=100.0,
        decimals=2, advanced=True, group="Alignment",
        help="moving alignment: the heading is the GNSS course at the first epoch faster "
             "than this")
    track_speed: float = param(
        0.5, label="Track heading speed", unit="m/s", minimum=0.05, maximum=100.0,
        decimals=2, advanced=True, group="Alignment",
        help="static alignment without gyrocompassing or a given heading: the heading is "
             "the GNSS course at the first epoch after the rest faster than this, carried "
             "back by the gyro")
    align_att_std_deg: float = param(
        2.0, label="Moving alignment σ", unit="°", minimum=0.01, maximum=30.0, decimals=2,
        advanced=True, group="Alignment",
        help="initial roll/pitch/heading std of a moving alignment (and of a given "
             "attitude or heading)")

    def validate(self) -> None:
        if self.max_node_interval_s < self.propagation_interval_s:
            raise InputError(None, "the node interval must not be shorter than the "
                             "covariance step", field="max_node_interval_s")
