"""The Latency panel: parameters, Run, R curves per line, the line table and seed fig. 4.

A thin view over :mod:`hydrosync_core.methods.latency`: the run happens in a worker
(``project_run.run``), toggling a line's *Used* box recombines the stored per-line values
(``project_run.recombine``, no re-scan) and writes them back into the project.
"""

from __future__ import annotations

import json

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QGroupBox,
    QLabel,
    QPushButton,
    QSplitter,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.api import line_series
from hydrosync_core.methods.latency.project_run import RESULT, project_lever_arm, recombine, run
from hydrosync_core.project.vessel import lever_arm as vessel_lever_arm
from hydrosync_gui.plugin_panel import PluginPanel
from hydrosync_gui.widgets.param_form import ParamField, ParamForm
from plugins.latency.views import CorrelationPlot, LineTable, SeriesPlot

FIELDS = [
    ParamField("range_min", "Scan from", -1.0, unit="s", minimum=-10, maximum=10, decimals=3,
               tooltip="smallest delay tried (negative: GNSS tags early)"),
    ParamField("range_max", "Scan to", 1.0, unit="s", minimum=-10, maximum=10, decimals=3),
    ParamField("step_s", "Step", 0.005, unit="s", minimum=0.0005, maximum=0.5, decimals=4),
    ParamField("min_r", "R threshold", 0.85, minimum=-1, maximum=0.999, decimals=3,
               tooltip="lines whose best correlation is above this are used"),
    ParamField("detrend_degree", "Detrend degree", 1, minimum=0, maximum=5,
               tooltip="polynomial removed from each line's heights (tide)"),
    ParamField("skip_s", "Skip at line start", 0.0, unit="s", minimum=0, maximum=600,
               decimals=1, tooltip="unsteady run-in after the line start (seed: 60 s)"),
    ParamField("weighting", "Weights", "r", choices=("r", "inverse_variance"),
               tooltip="r: each line weighted by its R max (seed); inverse_variance: by "
               "1/uncertainty²"),
    ParamField("outlier_k", "Outlier limit", 4.0, unit="σ", minimum=0, maximum=100,
               decimals=1, tooltip="lines whose Δt departs from the median by more than this "
               "many robust σ are not used (0: off)"),
    ParamField("lever_x", "Lever arm x (fwd)", 0.0, unit="m", minimum=-100, maximum=100),
    ParamField("lever_y", "Lever arm y (stbd)", 0.0, unit="m", minimum=-100, maximum=100),
    ParamField("lever_z", "Lever arm z (down)", 0.0, unit="m", minimum=-100, maximum=100),
]


class LatencyPanel(PluginPanel):
    """Latency between GNSS heights and attitude (seed 000)."""

    def __init__(self, spec=None, parent: QWidget | None = None) -> None:
        if spec is None:
            from plugins.latency import SPEC

            spec = SPEC
        super().__init__(spec, parent)
        self.form = ParamForm(FIELDS)
        self.run_button = QPushButton("Run")
        self.run_button.clicked.connect(self._on_run)
        self.summary = QLabel()
        self.summary.setWordWrap(True)
        self.summary.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.summary.setObjectName("latency_summary")
        left = QWidget()
        box = QGroupBox("Parameters")
        QVBoxLayout(box).addWidget(self.form)
        lay = QVBoxLayout(left)
        lay.addWidget(box)
        lay.addWidget(self.run_button)
        lay.addWidget(self.summary)
        lay.addStretch(1)

        self.r_plot = CorrelationPlot()
        self.table = LineTable()
        self.table.sig_used_changed.connect(self._on_used_changed)
        self.table.itemSelectionChanged.connect(self._on_selection)
        self.series_plot = SeriesPlot()
        right = QSplitter(Qt.Orientation.Vertical)
        for widget in (self.r_plot, self.table, self.series_plot):
            right.addWidget(widget)
        right.setSizes([300, 220, 260])
        split = QSplitter(Qt.Orientation.Horizontal)
        split.addWidget(left)
        split.addWidget(right)
        split.setStretchFactor(1, 1)
        split.setSizes([280, 820])
        QVBoxLayout(self).addWidget(split)
        self._table: dict | None = None
        self._bound_project = None
        self._sheet_arm: tuple | None = None  # vessel sheet gnss − motion when last seen

    # ------------------------------------------------------------- parameters
    def params(self) -> dict:
        v = self.form.values()
        return {"range_s": [v["range_min"], v["range_max"]], "step_s": v["step_s"],
                "min_r": v["min_r"], "detrend_degree": v["detrend_degree"],
                "skip_s": v["skip_s"], "weighting": v["weighting"],
                "outlier_k": v["outlier_k"],
                "lever_arm_m": [v["lever_x"], v["lever_y"], v["lever_z"]]}

    def _load_params(self) -> None:
        """Fill the form from the last run's parameters, else defaults + vessel sheet."""
        stored = self.project.get_json(RESULT) if self.project.exists(RESULT) else None
        p = dict(self.spec.default_params) | dict(stored or {})
        values = {"range_min": p["range_s"][0], "range_max": p["range_s"][1]}
        values |= {k: p[k] for k in ("step_s", "min_r", "detrend_degree", "skip_s", "weighting",
                                     "outlier_k") if k in p}
        try:
            arm = project_lever_arm(self.project, stored)
        except InputError:
            arm = np.zeros(3)
        values |= {"lever_x": arm[0], "lever_y": arm[1], "lever_z": arm[2]}
        self.form.set_values(values)
        self._sheet_arm = self._vessel_arm()

    def _vessel_arm(self) -> tuple | None:
        """The vessel sheet's gnss − motion lever arm (body FRD, m), None if not there."""
        try:
            return tuple(float(v) for v in vessel_lever_arm(self.project, "gnss", "motion"))
        except InputError:
            return None

    def _follow_vessel_sheet(self) -> None:
        """Edit → Vessel offsets changed the sheet: show its lever arm for the next run."""
        arm = self._vessel_arm()
        if arm != self._sheet_arm:
            self._sheet_arm = arm
            if arm is not None:
                self.form.set_values({"lever_x": arm[0], "lever_y": arm[1], "lever_z": arm[2]})

    # ---------------------------------------------------------------- drawing
    def refresh(self) -> None:
        project = self.project
        if project is not None and project is not self._bound_project:
            self._bound_project = project
            self._load_params()
        elif project is not None:
            self._follow_vessel_sheet()
        missing = self.spec.missing_inputs(project) if project is not None else ["a project"]
        self.run_button.setEnabled(not missing and not self.busy)
        if missing:
            self._table = None
            self.summary.setText("Needs data: " + ", ".join(f"/{m}" for m in missing)
                                 + ". Import GNSS, attitude and lines files (or create demo data).")
            self.table.setRowCount(0)
            self.r_plot.clear()
            self.series_plot.show_series(None)
            return
        if not project.exists(f"{RESULT}/lines"):
            self._table = None
            self.summary.setText("Data ready. Check the lever arm and press Run.")
            self.table.setRowCount(0)
            self.r_plot.clear()
            self.series_plot.show_series(None)
            return
        self._table = project.get_table(f"{RESULT}/lines")
        self.table.fill(self._table)
        self._update_summary()
        self._draw_curves()
        if self.table.rowCount():
            self.table.selectRow(self._best_row())

    def _best_row(self) -> int:
        r = np.nan_to_num(self._table["r_max"], nan=-2.0)
        return int(np.argmax(r))

    def _selected(self) -> int:
        rows = self.table.selectionModel().selectedRows() if self.table.selectionModel() else []
        return rows[0].row() if rows else -1

    def _update_summary(self) -> None:
        a = self.project.attrs(RESULT)
        warnings = json.loads(a.get("warnings", "[]"))
        if np.isfinite(a["latency_s"]):
            text = (f"<b>Δt = {a['latency_s']:.3f} s</b> ± {a['uncertainty_s']:.3f} s<br>"
                    f"95 % interval {a['ci95_low']:.3f} … {a['ci95_high']:.3f} s<br>"
                    f"{a['message']}")
        else:
            text = f"<b>No latency</b>: {a['message']}"
        if warnings:
            text += "<br><span style='color:#a05000'>" + "<br>".join(
                f"⚠ {w}" for w in warnings[:6]) + "</span>"
        self.summary.setText(text)

    def _draw_curves(self) -> None:
        grid = self.project.get(f"{RESULT}/dt_grid")
        curves = self.project.get(f"{RESULT}/r_curves")
        a = self.project.attrs(RESULT)
        min_r = self.project.get_json(RESULT, {}).get("min_r", 0.85)
        self.r_plot.show_curves(grid, curves, self._table, a["latency_s"], min_r, self._selected())

    # ------------------------------------------------------------------ slots
    def _on_selection(self) -> None:
        row = self._selected()
        if row < 0 or self._table is None:
            return
        self._draw_curves()
        gnss, att = self.project.get_table("raw/gnss"), self.project.get_table("raw/attitude")
        a = self.project.attrs(RESULT)
        params = self.project.get_json(RESULT, {})
        final = a["latency_s"] if np.isfinite(a["latency_s"]) else 0.0
        series = line_series(gnss, att, json.loads(a["lever_arm_m"]), self._table["start"][row],
                             self._table["end"][row], final, params)
        self.series_plot.show_series(
            series, f"line {self._table['name'][row]}: before and after Δt = {final:.3f} s")

    def _on_used_changed(self) -> None:
        if self._table is None:
            return
        recombine(self.project, self.table.used())
        self._table = self.project.get_table(f"{RESULT}/lines")
        row = self._selected()
        self.table.fill(self._table)
        self._update_summary()
        if row >= 0:
            self.table.selectRow(row)
        self._draw_curves()
        self.sig_project_modified.emit()
        self.sig_status.emit(f"latency recomputed: {self.project.attrs(RESULT)['message']}")

    def _on_run(self) -> None:
        if self.project is None:
            return
        project, params = self.project, self.params()
        self.run_button.setEnabled(False)
        self.start_work(lambda progress, cancel: run(project, params, progress, cancel),
                        self._on_finished, label="Latency")
        self.worker.signals.sig_done.connect(lambda: self.run_button.setEnabled(True))

    def _on_finished(self, result) -> None:
        self.refresh()
        self.sig_project_modified.emit()
        self.sig_status.emit(f"Latency: {result.message}")
