"""Pool Calibration plugin: multibeam boresight and lever arm against a laser-scanned target.

Qt-free declaration; the panel lives in ``panel.py`` and is imported only when shown.
"""

from hydrosync_core.methods.pool_calibration.api import DEFAULT_PARAMS
from hydrosync_core.plugins.spec import PluginSpec

SPEC = PluginSpec(
    id="pool_calibration",
    name="Pool Calibration",
    run="hydrosync_core.methods.pool_calibration.project_run:run",
    panel="plugins.pool_calibration.panel:PoolCalibrationPanel",
    requires=("raw/pool/lidar", "raw/pool/mbes", "raw/pool/ins", "raw/pool/setup",
              "raw/pool/target"),
    icon="pool.svg",
    description="Multibeam boresight angles and lever arm from a pool target seen by a "
                "calibrated laser scanner (seed 003) plus a joint least-squares adjustment.",
    default_params={**DEFAULT_PARAMS, "plan_points": 20000},
    demo="hydrosync_core.methods.pool_calibration.demo:fill_demo",
    report_section="hydrosync_core.methods.pool_calibration.report_section:section",
    order=20,
)
