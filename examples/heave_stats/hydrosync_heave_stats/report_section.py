"""The PDF section of the heave statistics."""

from __future__ import annotations

from hydrosync_core.params import stored
from hydrosync_core.report.context import fmt
from hydrosync_heave_stats.method import RESULT
from hydrosync_heave_stats.params import HeaveStatsParams


def section(project, ctx) -> list:
    table = project.get_table(f"{RESULT}/lines")
    rows = [[str(n), str(int(table["samples"][i])), fmt(table["rms_m"][i], 3),
             fmt(table["significant_m"][i], 3), fmt(table["peak_period_s"][i], 1)]
            for i, n in enumerate(table["name"])]
    out = [ctx.heading("Heave Statistics")]
    out += ctx.table(["Line", "Samples", "RMS [m]", "Hs = 4σ [m]", "Peak period [s]"], rows,
                     caption="Heave per survey line.")
    out += ctx.params_table(stored(HeaveStatsParams, project, RESULT),
                            "Heave statistics: processing parameters.")
    return out
