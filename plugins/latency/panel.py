"""The Latency panel: parameters, Run, R curves per line, the line table and the
before/after plot (fig. 4 of Qi et al. 2010).

A thin view over :mod:`hydrosync_core.methods.latency`: the run happens in a worker
(``project_run.run``), toggling a line's *Used* box recombines the stored per-line values
(``project_run.recombine``, no re-scan) and writes them back into the project.
"""

from __future__ import annotations

import json
from html import escape

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QGroupBox,
    QLabel,
    QPushButton,
    QScrollArea,
    QSplitter,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.params import LatencyParams, estimator_label
from hydrosync_core.methods.latency.project_run import RESULT, recombine, run, stored_params
from hydrosync_core.methods.latency.series import line_series
from hydrosync_core.methods.latency.texts import interval_text, latency_text, lines_used_text
from hydrosync_core.project.vessel import lever_arm as vessel_lever_arm
from hydrosync_gui.plugin_panel import PluginPanel
from hydrosync_gui.widgets.param_form import ParamForm
from plugins.latency.views import CorrelationPlot, LineTable, SeriesPlot


class LatencyPanel(PluginPanel):
    """Latency between GNSS heights and attitude (Qi et al. 2010)."""

    def __init__(self, spec=None, parent: QWidget | None = None) -> None:
        if spec is None:
            from plugins.latency import SPEC

            spec = SPEC
        super().__init__(spec, parent)
        self.form = ParamForm(LatencyParams)
        self.run_button = QPushButton("Run")
        self.run_button.clicked.connect(self._on_run)
        self.summary = QLabel()
        self.summary.setWordWrap(True)
        self.summary.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.summary.setObjectName("latency_summary")
        left = QWidget()
        box = QGroupBox("Parameters")
        QVBoxLayout(box).addWidget(self.form)
        # On a 768-px screen the form is taller than the column: it scrolls instead of
        # squashing its rows (the lever-arm boxes were 8 px high).
        scroll = QScrollArea()
        scroll.setWidget(box)
        scroll.setWidgetResizable(True)
        scroll.setFrameShape(QScrollArea.Shape.NoFrame)
        lay = QVBoxLayout(left)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addWidget(scroll, 1)
        lay.addWidget(self.run_button)
        lay.addWidget(self.summary)

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
        self._loading = False

    # ------------------------------------------------------------- parameters
    def params(self) -> LatencyParams | None:
        """The form's parameters, validated; None (and the reason shown) if invalid."""
        try:
            return self.form.params()
        except InputError as exc:
            self.summary.setText(f"<b>Parameter error</b>: {exc.one_line()}")
            self.sig_status.emit(f"Latency: {exc.one_line()}")
            return None

    def _load_params(self) -> None:
        """The last run's parameters, else the schema's defaults."""
        self.form.set_params(stored_params(self.project) or LatencyParams())
        self._show_sheet_arm()

    def _show_sheet_arm(self) -> None:
        """With no lever arm set, show the vessel sheet's (what a run would use)."""
        try:
            arm = tuple(float(v) for v in vessel_lever_arm(self.project, "gnss", "motion"))
        except InputError:
            arm = (0.0, 0.0, 0.0)  # not the previous project's arm; a run asks for one
        self.form.show_unset("lever_arm_m", arm)

    # ---------------------------------------------------------------- drawing
    def refresh(self) -> None:
        project = self.project
        if project is not None and project is not self._bound_project:
            self._bound_project = project
            self._load_params()
        elif project is not None:
            self._show_sheet_arm()
        missing = self.spec.missing_inputs(project) if project is not None else ["a project"]
        self.run_button.setEnabled(not missing and not self.busy)
        if missing:
            self._table = None
            self.summary.setText("Needs data: " + ", ".join(f"/{m}" for m in missing)
                                 + ". Import GNSS, attitude and lines files (or create demo data).")
            self.table.setRowCount(0)
            self.r_plot.clear_curves()
            self.series_plot.show_series(None)
            return
        if not project.exists(f"{RESULT}/lines"):
            self._table = None
            self.summary.setText("Data ready. Check the lever arm and press Run.")
            self.table.setRowCount(0)
            self.r_plot.clear_curves()
            self.series_plot.show_series(None)
            return
        self._table = project.get_table(f"{RESULT}/lines")
        self.table.fill(self._table)
        self._update_summary()
        self._draw_curves()
        if self.table.rowCount():
            # The series plot is redrawn whether or not the selected row changes: after a
            # re-run the same row carries a new Δt.
            blocked = self.table.blockSignals(True)
            self.table.selectRow(self._best_row())
            self.table.blockSignals(blocked)
            self._on_selection()
        else:
            self.series_plot.show_series(None)

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
            sigma = a["uncertainty_s"]
            text = (f"<b>Δt = {escape(latency_text(a['latency_s'], sigma))}</b><br>"
                    "95 % interval "
                    f"{escape(interval_text(a['ci95_low'], a['ci95_high'], sigma))}<br>"
                    f"Estimator: {escape(estimator_label(a.get('estimator', 'qi2010')))}<br>"
                    f"Lines used: {escape(self._lines_used(a))}<br>"
                    f"{escape(str(a['message']))}")
        else:
            text = f"<b>No latency</b>: {escape(str(a['message']))}"
        if warnings:
            text += "<br><span style='color:#a05000'>" + "<br>".join(
                f"⚠ {escape(w)}" for w in warnings[:6]) + "</span>"
        self.summary.setText(text)

    def _lines_used(self, attrs) -> str:
        params = stored_params(self.project)
        n_lines = len(self._table["name"]) if self._table is not None else 0
        return lines_used_text(attrs.get("n_used", 0), n_lines,
                               params.min_r if params is not None else None)

    def _draw_curves(self) -> None:
        grid = self.project.get(f"{RESULT}/dt_grid")
        curves = self.project.get(f"{RESULT}/r_curves")
        a = self.project.attrs(RESULT)
        min_r = stored_params(self.project).min_r
        self.r_plot.show_curves(grid, curves, self._table, a["latency_s"], min_r, self._selected())

    # ------------------------------------------------------------------ slots
    def _on_selection(self) -> None:
        row = self._selected()
        if row < 0 or self._table is None:
            return
        if len(self.r_plot.curves) == len(self._table["name"]):
            self.r_plot.select(row)
        else:
            self._draw_curves()
        self._show_series(row)

    def _series_request(self, row: int) -> tuple:
        """What :func:`_line_series` needs for *row*, read here on the GUI thread."""
        a = self.project.attrs(RESULT)
        final = a["latency_s"] if np.isfinite(a["latency_s"]) else 0.0
        return (json.loads(a["lever_arm_m"]), float(self._table["start"][row]),
                float(self._table["end"][row]), final, stored_params(self.project),
                f"line {self._table['name'][row]}: before and after Δt = "
                f"{latency_text(final, a['uncertainty_s'])}")

    def _show_series(self, row: int) -> None:
        """The series plot of *row*: at once when the raw tables are in memory, else read
        on a thread (a survey day's attitude takes seconds to read) and drawn when ready."""
        project, request = self.project, self._series_request(row)
        if project.has_cached_table("raw/gnss") and project.has_cached_table("raw/attitude"):
            self.series_plot.show_series(_line_series(project, request), request[-1])
            return
        self.series_plot.show_series(None, "reading the raw GNSS and attitude data…")
        if self._loading:
            return  # the thread running draws the selected line when it is done
        self._loading = True

        def load(progress, cancel) -> tuple:
            try:
                return project, row, _line_series(project, request), request[-1], ""
            except Exception as exc:  # shown in the plot's title, never a traceback
                return project, row, None, request[-1], str(exc)

        self.start_side_task(load, self._on_series_ready)

    def _on_series_ready(self, ready: tuple) -> None:
        """*ready*: (project, row, series or None, title, error) of :meth:`_show_series`."""
        project, row, series, title, error = ready
        self._loading = False
        if project is not self.project or self._table is None:
            return
        current = self._selected()
        if error:
            self.series_plot.show_series(None, f"raw data not readable: {error}")
        elif current == row:
            self.series_plot.show_series(series, title)
        elif current >= 0:
            self._show_series(current)  # another line was chosen meanwhile: now in memory

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
        project, params = self.project, self.params()
        if project is None or params is None:
            return
        if params.lever_arm_m is None:
            # Never run with a silent zero lever arm: say what is missing and how to fix it.
            try:
                vessel_lever_arm(project, "gnss", "motion")
            except InputError as exc:
                self.summary.setText(
                    "<b>Lever arm needed</b>: " + exc.message.split(": set")[0]
                    + ". Enter the sensors in Edit → Vessel offsets…, or tick "
                    "<i>Lever arm</i> above and type it.")
                self.sig_status.emit("Latency: the vessel sheet lacks the GNSS or motion sensor")
                return
        self.run_button.setEnabled(False)
        self.start_work(lambda progress, cancel: run(project, params, progress, cancel),
                        self._on_finished, label="Latency")

    def work_done(self) -> None:
        self.run_button.setEnabled(True)

    def _on_finished(self, result) -> None:
        self.refresh()
        self.sig_project_modified.emit()
        self.sig_status.emit(result.message)


def _line_series(project, request: tuple) -> dict:
    """One line's series (:func:`line_series`) from the project's raw tables (cached)."""
    arm, start, end, final, params, _ = request
    return line_series(project.get_table("raw/gnss", cached=True),
                       project.get_table("raw/attitude", cached=True), arm, start, end,
                       final, params)
