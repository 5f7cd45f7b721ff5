"""Heave statistics per survey line: an example third-party HydroSync analysis.

This module is what the ``hydrosync.plugins`` entry point loads. It must stay cheap and
Qt-free: it declares the analysis by dotted paths, imported only when used.
"""

from hydrosync_core.plugins.spec import PluginSpec

PKG = "hydrosync_heave_stats"

SPEC = PluginSpec(
    id="heave_stats",
    name="Heave Statistics",
    run=f"{PKG}.method:run",
    panel=f"{PKG}.panel:HeaveStatsPanel",
    params=f"{PKG}.params:HeaveStatsParams",
    cli=f"{PKG}.cli:register",
    requires=("raw/attitude", "raw/lines"),
    description="RMS heave, significant heave and dominant heave period of every survey "
    "line, from the motion sensor's heave.",
    # Any simulator that writes raw/attitude and raw/lines will do: reuse the latency one.
    demo="hydrosync_core.methods.latency.demo:fill_demo",
    report_section=f"{PKG}.report_section:section",
    order=90,
    version="1.0.0",
)
