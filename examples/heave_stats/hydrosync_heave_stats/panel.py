"""The GUI panel: the schema's form, a Run button and the per-line table."""

from __future__ import annotations

from PySide6.QtWidgets import QLabel, QPushButton, QVBoxLayout

from hydrosync_core.params import stored
from hydrosync_gui.plugin_panel import PluginPanel
from hydrosync_gui.widgets import ColumnsTable, ParamForm
from hydrosync_heave_stats.method import RESULT, run
from hydrosync_heave_stats.params import HeaveStatsParams


class HeaveStatsPanel(PluginPanel):
    """Heave statistics per line."""

    def __init__(self, spec=None, parent=None) -> None:
        if spec is None:
            from hydrosync_heave_stats import SPEC

            spec = SPEC
        super().__init__(spec, parent)
        self.form = ParamForm(HeaveStatsParams)
        self.run_button = QPushButton("Run")
        self.run_button.clicked.connect(self._on_run)
        self.summary = QLabel()
        self.table = ColumnsTable()
        layout = QVBoxLayout(self)
        for widget in (self.form, self.run_button, self.summary, self.table):
            layout.addWidget(widget)

    def refresh(self) -> None:
        project = self.project
        missing = self.spec.missing_inputs(project) if project is not None else ["a project"]
        self.run_button.setEnabled(not missing and not self.busy)
        if project is None or not project.exists(f"{RESULT}/lines"):
            self.summary.setText("Needs " + ", ".join(missing) if missing else "Press Run.")
            self.table.set_columns({})
            return
        self.form.set_params(stored(HeaveStatsParams, project, RESULT))
        self.table.set_columns(project.get_table(f"{RESULT}/lines"),
                               units={"rms_m": "m", "significant_m": "m", "peak_period_s": "s"})
        self.summary.setText("Heave statistics of the stored run.")

    def _on_run(self) -> None:
        project, params = self.project, self.form.params()
        self.run_button.setEnabled(False)
        self.start_work(lambda progress, cancel: run(project, params, progress, cancel),
                        lambda _table: self.refresh(), label="Heave statistics")

    def work_done(self) -> None:
        self.run_button.setEnabled(True)
