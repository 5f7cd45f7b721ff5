"""The GUI panel: the schema's form, Run, a summary and the per-line table.

Built on :class:`hydrosync_gui.analysis_panel.AnalysisPanel`, which lays out the form
(scrolling), Run and the summary, runs ``spec.run`` in a worker with progress and Cancel,
emits ``sig_project_modified`` when the run has stored its results (so the main window
marks the project changed and the other panels redraw) and then calls :meth:`redraw`.
"""

from __future__ import annotations

from hydrosync_core.params import stored
from hydrosync_gui.analysis_panel import AnalysisPanel
from hydrosync_gui.widgets import ColumnsTable
from hydrosync_heave_stats.method import RESULT
from hydrosync_heave_stats.params import HeaveStatsParams

LABELS = {"name": "Line", "samples": "Samples", "rms_m": "RMS heave",
          "significant_m": "Significant heave (4σ)", "peak_period_s": "Dominant period"}
UNITS = {"rms_m": "m", "significant_m": "m", "peak_period_s": "s"}
FORMATS = {"rms_m": "{:.3f}", "significant_m": "{:.3f}", "peak_period_s": "{:.1f}"}


class HeaveStatsPanel(AnalysisPanel):
    """Heave statistics per line."""

    def __init__(self, spec=None, parent=None) -> None:
        if spec is None:
            from hydrosync_heave_stats import SPEC

            spec = SPEC
        super().__init__(spec, HeaveStatsParams, parent)
        self.table = ColumnsTable()
        self.add_tab("Lines", self.table)
        self.build()

    def redraw(self) -> None:
        project = self.project
        missing = self.spec.missing_inputs(project) if project is not None else ["a project"]
        self.run_button.setEnabled(not missing and not self.busy)
        if project is None or not project.exists(f"{RESULT}/lines"):
            self.summary.setText("Needs " + ", ".join(missing) if missing else "Press Run.")
            self.table.clear()
            return
        self.form.set_params(stored(HeaveStatsParams, project, RESULT))
        self.table.set_columns(project.get_table(f"{RESULT}/lines"), units=UNITS,
                               formats=FORMATS, labels=LABELS,
                               missing={"peak_period_s": "\u2014"})
        self.summary.setText("Heave statistics of the stored run.")
