"""The GNSS Attitude panel: parameters, Run, statistics and the plots of the stored run.

Plots (pyqtgraph): heading, pitch and roll against time with the direct method and the
least squares overlaid, the baseline-length residuals, and the predicted / simulated
precision versus baseline length.

The static interval of the statistics table is a shaded region on the three time series:
drag it (or its edges) with the mouse. While it moves the table follows, computed from
the stored per-method tables (no solving); when it is released the form's
``static_start_s``/``static_end_s`` are set and, in a writable project, the stored
statistics and parameters are updated (:func:`...project_run.restat`).
"""

from __future__ import annotations

import json

import numpy as np
import pyqtgraph as pg

from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams
from hydrosync_core.methods.gnss_attitude.pipeline import interval_statistics
from hydrosync_core.methods.gnss_attitude.project_run import RESULT, restat
from hydrosync_core.methods.gnss_attitude.report_section import LABELS, MOVING_REASON
from hydrosync_core.params import stored
from hydrosync_gui.analysis_panel import AnalysisPanel, plot_widget
from hydrosync_gui.widgets import ColumnsTable

ANGLES = ("heading", "pitch", "roll")
COLOURS = {"direct": (200, 60, 40), "lsq": (30, 90, 200), "wahba": (40, 150, 60)}


def _plot(ylabel: str, xlabel: str = "time from first epoch [s]") -> pg.PlotWidget:
    return plot_widget(ylabel, xlabel)


class GnssAttitudePanel(AnalysisPanel):
    """Attitude from a GNSS antenna array."""

    def __init__(self, spec=None, parent=None) -> None:
        if spec is None:
            from plugins.gnss_attitude import SPEC

            spec = SPEC
        super().__init__(spec, GnssAttitudeParams, parent, choice_labels={"method": LABELS})
        self.stats = ColumnsTable(wrap_headers=True)
        self.series = {a: _plot(f"{a} [°]") for a in ANGLES}
        self.series["pitch"].setXLink(self.series["heading"])
        self.series["roll"].setXLink(self.series["heading"])
        self.residuals = _plot("length residual [mm]")
        self.curve = _plot("1σ [°]", "longest baseline [m]")
        self.add_tab("Heading / pitch / roll", *(self.series[a] for a in ANGLES))
        self.add_tab("Baseline residuals", self.residuals)
        self.add_tab("Precision vs baseline", self.curve)
        self.build(after_summary=[self.stats])
        self.regions: dict[str, pg.LinearRegionItem] = {}
        self._tables: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        self._time = np.zeros(0)
        self._t0 = 0.0
        self._syncing = False

    # ------------------------------------------------------------------ drawing
    def _clear(self) -> None:
        for w in (*self.series.values(), self.residuals, self.curve):
            w.clear()
        self.stats.set_columns({})
        self.regions = {}
        self._tables = {}
        self._time = np.zeros(0)

    def _show_stats(self, stats: dict, static: bool) -> None:
        """The statistics table as the PDF shows it: human labels, degrees to 4 decimals,
        and "—" for the measured scatter without a static interval (on a moving platform it
        is the motion, not the precision)."""
        table: dict[str, list] = {"method": [], "epochs": []}
        labels = {"method": "Method", "epochs": "Epochs"}
        tips = {}
        for a in ANGLES:
            table[f"sd_{a}"], table[f"pred_{a}"] = [], []
            labels[f"sd_{a}"] = f"σ {a}"
            labels[f"pred_{a}"] = f"predicted σ {a}"
            tips[f"sd_{a}"] = (f"standard deviation of the {a} over the static interval"
                               if static else f"no static interval: {MOVING_REASON}")
            tips[f"pred_{a}"] = f"1σ of the {a} predicted from the position covariance"
        for m, s in stats.items():
            table["method"].append(LABELS.get(m, m))
            table["epochs"].append(s["epochs"])
            for a in ANGLES:
                sd = s[a]["std"]
                table[f"sd_{a}"].append(np.nan if sd is None or not static else sd)
                table[f"pred_{a}"].append(np.nan if s[a]["predicted"] is None
                                          else s[a]["predicted"])
        angle_columns = [k for k in table if k[:3] in ("sd_", "pre")]
        self.stats.set_columns({k: np.asarray(v) for k, v in table.items()},
                               units={k: "°" for k in angle_columns},
                               formats={k: "{:.4f}" for k in angle_columns},
                               labels=labels, tips=tips,
                               missing={k: "\u2014" for k in angle_columns})
        self.current_stats = stats

    # ------------------------------------------------------------ static interval
    def static_interval(self) -> tuple[float, float] | None:
        """The selected interval (time of week, s), None before a result is shown."""
        if not self.regions:
            return None
        lo, hi = self.regions["heading"].getRegion()
        return lo + self._t0, hi + self._t0

    def set_static_interval(self, start: float, end: float) -> None:
        """Select [start, end] (time of week, s) as if dragged, and store it."""
        if not self.regions:
            return
        region = self.regions["heading"]
        self._syncing = True  # one update below, whatever signals setRegion emits
        try:
            region.setRegion((start - self._t0, end - self._t0))
        finally:
            self._syncing = False
        self._on_region_finished(region)

    def _on_region_moving(self, region) -> None:
        if self._syncing:
            return
        self._syncing = True
        try:
            lo, hi = region.getRegion()
            for other in self.regions.values():
                if other is not region:
                    other.setRegion((lo, hi))
        finally:
            self._syncing = False
        start, end = self.static_interval()
        self._show_stats(interval_statistics(self._time, self._tables, start, end), True)

    def _on_region_finished(self, region) -> None:
        if self._syncing:
            return
        self._on_region_moving(region)
        start, end = self.static_interval()
        if not end > start:
            return
        self.form.editors["static_start_s"].set_value(round(start, 3))
        self.form.editors["static_end_s"].set_value(round(end, 3))
        project = self.project
        if project is not None and not project.readonly and not self.busy:
            restat(project, start, end)
            self.sig_project_modified.emit()
            self.sig_status.emit(f"statistics interval {start:.1f}–{end:.1f} s "
                                 f"({end - start:.0f} s) stored")

    def redraw(self) -> None:
        project = self.project
        missing = self.spec.missing_inputs(project) if project is not None else ["a project"]
        self.run_button.setEnabled(not missing and not self.busy)
        self._clear()
        if project is None or not project.exists(f"{RESULT}/lsq"):
            self.summary.setText("Needs " + ", ".join(missing) + " (File → Import: --pos, "
                                 "--antennas)." if missing else "Press Run.")
            return
        p = stored(GnssAttitudeParams, project, RESULT)
        self.form.set_params(p)
        attrs = project.attrs(RESULT)
        counts = json.loads(attrs["counts"])
        stats = json.loads(attrs["statistics"])
        self.summary.setText(
            f"{counts['solved']} of {counts['epochs']} epochs solved; "
            f"{counts['too_few_antennas']} with fewer than 3 usable antennas, "
            f"{counts['with_dropped_antenna']} with an antenna dropped by the length check, "
            f"{counts['gaps']} gaps. Statistics: scatter and predicted 1σ (°)"
            + (" over the static interval." if p.static_start_s is not None
               or p.static_end_s is not None else
               " over the <b>whole record</b>: on a moving platform the scatter is its motion, "
               "not the precision — drag the shaded region onto a period when the platform "
               "stood still."))
        self._show_stats(stats, p.static_start_s is not None or p.static_end_s is not None)
        lsq = project.get_table(f"{RESULT}/lsq")
        direct = project.get_table(f"{RESULT}/direct")
        t0 = float(np.nanmin(lsq["time"])) if lsq["time"].size else 0.0
        self._t0, self._time = t0, np.asarray(lsq["time"], float)
        for name in ("lsq", "wahba", "direct"):
            if project.exists(f"{RESULT}/{name}"):
                tab = project.get_table(f"{RESULT}/{name}")
                self._tables[name] = (
                    np.column_stack([tab["heading"], tab["pitch"], tab["roll"]]),
                    np.column_stack([tab["sd_heading"], tab["sd_pitch"], tab["sd_roll"]]))
        for a in ANGLES:
            for name, tab in (("direct", direct), ("lsq", lsq)):
                # One legend, on the heading plot: on the pitch and roll plots it lay
                # over the data the surveyor is reading.
                self.series[a].plot(tab["time"] - t0, tab[a],
                                    name=LABELS[name] if a == "heading" else None,
                                    pen=pg.mkPen(COLOURS[name], width=1), connect="finite")
        params = stored(GnssAttitudeParams, project, RESULT)
        t_end = float(np.nanmax(lsq["time"])) if lsq["time"].size else t0
        lo = (params.static_start_s if params.static_start_s is not None else t0) - t0
        hi = (params.static_end_s if params.static_end_s is not None else t_end) - t0
        for a in ANGLES:
            region = pg.LinearRegionItem((lo, hi), movable=True,
                                         brush=pg.mkBrush(200, 200, 240, 60))
            region.setToolTip("statistics interval: drag it or its edges")
            region.setZValue(-10)
            region.sigRegionChanged.connect(self._on_region_moving)
            region.sigRegionChangeFinished.connect(self._on_region_finished)
            self.series[a].addItem(region)
            self.regions[a] = region
        res = project.get_table(f"{RESULT}/baseline_residuals")
        pairs = [k for k in res if k != "time"]
        for i, pair in enumerate(pairs):
            self.residuals.plot(res["time"] - t0, 1000 * res[pair], name=pair, pen=None,
                                symbol="s", symbolSize=3,
                                symbolBrush=pg.intColor(i, hues=max(len(pairs), 1)),
                                symbolPen=None)
        curve = project.get_table(f"{RESULT}/precision")
        for i, a in enumerate(ANGLES):
            colour = pg.intColor(i, hues=3)
            self.curve.plot(curve["baseline_m"], curve[f"lsq_{a}_deg"],
                            name=f"{a} predicted", pen=pg.mkPen(colour, width=2))
            if f"mc_lsq_{a}_deg" in curve:
                self.curve.plot(curve["baseline_m"], curve[f"mc_lsq_{a}_deg"],
                                name=f"{a} simulated", pen=None, symbol="o", symbolSize=6,
                                symbolBrush=colour)

    # ------------------------------------------------------------------ running
