"""Tilt Alignment plugin: heading alignment and tip of a tilt RTK pole (Qt-free declaration).

Importing this module loads only :mod:`hydrosync_core.plugins.spec`; the method, its
parameter schema and the panel are named by dotted path and imported when used.
"""

from hydrosync_core.methods.tilt_alignment import VERSION
from hydrosync_core.plugins.spec import DataKind, PluginSpec

CORE = "hydrosync_core.methods.tilt_alignment"

SPEC = PluginSpec(
    id="tilt_alignment",
    name="Tilt Alignment",
    run=f"{CORE}.project_run:run",
    panel="plugins.tilt_alignment.panel:TiltAlignmentPanel",
    params=f"{CORE}.params:TiltParams",
    cli=f"{CORE}.cli:register",
    data_kinds=(
        DataKind("tilt_imu", "tilt-pole imu.csv: time, gx, gy, gz (rad/s), ax, ay, az (m/s²), "
                 "body frame, z down along the pole", "raw/tilt/imu",
                 f"{CORE}.io:read_imu_csv", "table"),
        DataKind("tilt_gnss", "tilt-pole gnss.csv: time, e, n, u (local ENU) or time, lat, "
                 "lon, height: the antenna", "raw/tilt/gnss", f"{CORE}.io:read_gnss_csv",
                 "table"),
        DataKind("tilt_pole", 'tilt-pole pole.json: {"pole_length_m": …, optional '
                 '"imu_convention": instant|interval-start|interval-middle|interval-end}',
                 "raw/tilt/pole",
                 f"{CORE}.io:read_pole_json", "json"),
    ),
    requires=("raw/tilt/imu", "raw/tilt/gnss", "raw/tilt/pole"),
    description="Initial heading of a tilt RTK pole's MEMS IMU from a swing with the tip on "
    "the point, and the tip: Li et al.'s gradient descent (BGD/SGD/MBGD) and SVD, the "
    "closed-form heading-only solution, and a joint batch least squares over the whole "
    "swing with σ.",
    demo=f"{CORE}.demo:fill_demo",
    report_section=f"{CORE}.report_section:section",
    order=40,
    version=VERSION,
)
