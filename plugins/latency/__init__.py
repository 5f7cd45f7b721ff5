"""Latency plugin: delay between GNSS heights and attitude/heave (Qt-free declaration)."""

from hydrosync_core.plugins.spec import PluginSpec

SPEC = PluginSpec(
    id="latency",
    name="Latency",
    run="hydrosync_core.methods.latency.project_run:run",
    panel="plugins.latency.panel:LatencyPanel",
    requires=("raw/gnss", "raw/attitude", "raw/lines"),
    icon="latency.svg",
    description="Delay of the GNSS time tags relative to the attitude/heave time tags, "
    "by correlating detrended RTK heights with total heave (seed 000).",
    default_params={
        "range_s": [-1.0, 1.0],
        "step_s": 0.005,
        "min_r": 0.85,
        "detrend_degree": 1,
        "skip_s": 0.0,
        "weighting": "r",
        "outlier_k": 4.0,
    },
    demo="hydrosync_core.methods.latency.demo:fill_demo",
    report_section="hydrosync_core.methods.latency.report_section:section",
    order=10,
)
