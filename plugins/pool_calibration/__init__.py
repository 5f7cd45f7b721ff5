"""Pool Calibration plugin: multibeam boresight and lever arm against a laser-scanned target.

Qt-free declaration that loads only :mod:`hydrosync_core.plugins.spec`: the method (and
with it scipy and open3d), the parameter schema and the panel are named by dotted path
and imported when used.
"""

from hydrosync_core.methods.pool_calibration import VERSION
from hydrosync_core.plugins.spec import DataKind, PluginSpec, Trend, TrendSeries

CORE = "hydrosync_core.methods.pool_calibration"
READERS = "hydrosync_core.importers"

SPEC = PluginSpec(
    id="pool_calibration",
    name="Pool Calibration",
    run=f"{CORE}.project_run:run",
    panel="plugins.pool_calibration.panel:PoolCalibrationPanel",
    params=f"{CORE}.params:PoolParams",
    cli=f"{CORE}.cli:register",
    data_kinds=(
        DataKind("mbes", "multibeam soundings CSV (time, x, y, z; sensor frame)",
                 "raw/pool/mbes", f"{READERS}.survey_csv:read_mbes_csv"),
        DataKind("ins", "INS trajectory CSV (time, e, n, u, roll, pitch, heading)",
                 "raw/pool/ins", f"{READERS}.survey_csv:read_ins_csv"),
        DataKind("lidar", "laser points (CSV x,y,z / PLY / LAS / LAZ; target ENU)",
                 "raw/pool/lidar", f"{READERS}.pointcloud:read_point_cloud", "points"),
        DataKind("setup", "pool setup.json (coarse boresight and lever arm)",
                 "raw/pool/setup", f"{READERS}.pool_json:read_setup_json", "json"),
        DataKind("target", "pool target.json (target design)", "raw/pool/target",
                 f"{READERS}.pool_json:read_target_json", "json"),
    ),
    requires=("raw/pool/lidar", "raw/pool/mbes", "raw/pool/ins", "raw/pool/setup",
              "raw/pool/target"),
    icon="pool.svg",
    description="Multibeam boresight angles and lever arm from a pool target seen by a "
                "calibrated laser scanner (patent CN 105425246 B) plus a joint "
                "least-squares adjustment.",
    demo=f"{CORE}.demo:fill_demo",
    report_section=f"{CORE}.report_section:section",
    order=20,
    report_appendix=f"{CORE}.report_section:appendix",
    apply=f"{CORE}.apply:apply_to_vessel",
    trends=(Trend("Multibeam boresight per calibration, ±1.96 σ", "°",
                  tuple(TrendSeries(a, f"{a}_deg", sigma=f"sigma_{a}_deg")
                        for a in ("roll", "pitch", "yaw"))),),
    version=VERSION,
)
