"""GNSS/INS Smoother plugin: post-processed trajectory from IMU and GNSS (Qt-free declaration).

Importing this module loads only :mod:`hydrosync_core.plugins.spec`; the method, its
parameter schema and the panel are named by dotted path and imported when used.
"""

from hydrosync_core.methods.gins_smoother import VERSION
from hydrosync_core.plugins.spec import DataKind, PluginSpec

CORE = "hydrosync_core.methods.gins_smoother"
RUN = f"{CORE}.project_run"

SPEC = PluginSpec(
    id="gins_smoother",
    name="GNSS/INS Smoother",
    run=f"{RUN}:run",
    panel="plugins.gins_smoother.panel:GinsPanel",
    params=f"{CORE}.params:GinsParams",
    cli=f"{CORE}.cli:register",
    data_kinds=(
        DataKind("gins_imu", "IMU increments (KF-GINS 7-column text or imu.csv; body FRD)",
                 "raw/gins/imu", f"{RUN}:imu_table", "table"),
        DataKind("gins_gnss", "GNSS antenna positions with std (KF-GINS text or gnss.csv)",
                 "raw/gins/gnss", f"{RUN}:gnss_table", "table"),
        DataKind("gins_config", "KF-GINS YAML configuration (initial state, IMU noise, lever "
                 "arm)", "raw/gins/config", f"{RUN}:config_json", "json"),
        DataKind("gins_recording", "a real recording folder: comma2k19 segment or "
                 "rtklibexplorer drive/walk (IMU, GNSS, configuration, reference)",
                 "raw/gins", f"{RUN}:store_recording", "custom",
                 options=("clock_offset",), folder=True),
        DataKind("gins_reference", "reference trajectory, 11-column KF-GINS .nav",
                 "raw/gins/reference", f"{RUN}:nav_table", "table"),
    ),
    requires=("raw/gins/imu", "raw/gins/gnss", "raw/gins/config"),
    description="Loosely coupled GNSS/INS EKF (15 or 21 states) with NHC/ZUPT and RTS "
    "smoothing (Wang et al.); errors against a reference, GNSS outage simulation.",
    demo=f"{CORE}.demo:fill_demo",
    report_section=f"{CORE}.report_section:section",
    order=40,
    warmup=f"{CORE}.warmup:compile_kernels",
    version=VERSION,
)
