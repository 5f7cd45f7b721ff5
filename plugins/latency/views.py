"""The latency panel's views: line table with 'used' check boxes, R curves, fig. 4 plot."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import QAbstractItemView, QHeaderView, QTableWidget, QTableWidgetItem

from hydrosync_core.methods.latency.texts import line_cells

COLUMNS = ("Line", "Epochs", "R max", "Δt [s]", "± [s]", "σ0 before [m]", "σ0 after [m]", "Used")
USED_COLUMN = COLUMNS.index("Used")
RIGHT = Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter


def line_colour(i: int, n: int) -> pg.Color:
    return pg.intColor(i, hues=max(n, 1), values=1, maxValue=200)


def _fmt(value: float, digits: int) -> str:
    return "–" if not np.isfinite(value) else f"{value:.{digits}f}"


class LineTable(QTableWidget):
    """One row per survey line; the user toggles 'Used' (emits ``sig_used_changed``)."""

    sig_used_changed = Signal()

    def __init__(self, parent=None) -> None:
        super().__init__(0, len(COLUMNS), parent)
        self.setHorizontalHeaderLabels(list(COLUMNS))
        self.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.setSelectionMode(QAbstractItemView.SelectionMode.SingleSelection)
        self.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        self.verticalHeader().setVisible(False)
        self.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.ResizeToContents)
        self.horizontalHeader().setStretchLastSection(True)
        self._filling = False
        self.itemChanged.connect(self._on_item_changed)

    def fill(self, table: dict) -> None:
        self._filling = True
        names = table["name"]
        self.setRowCount(len(names))
        for row in range(len(names)):
            dt, sigma = line_cells(table["latency_s"][row], table["uncertainty_s"][row])
            cells = (str(names[row]), str(int(table["epochs"][row])),
                     _fmt(table["r_max"][row], 4), dt, sigma,
                     _fmt(table["sigma0_before_m"][row], 3),
                     _fmt(table["sigma0_after_m"][row], 3))
            for col, text in enumerate(cells):
                item = QTableWidgetItem(text)
                if col:
                    item.setTextAlignment(RIGHT)
                if col == 0:
                    item.setForeground(line_colour(row, len(names)))
                self.setItem(row, col, item)
            used = QTableWidgetItem("")
            used.setFlags(Qt.ItemFlag.ItemIsUserCheckable | Qt.ItemFlag.ItemIsEnabled
                          | Qt.ItemFlag.ItemIsSelectable)
            used.setCheckState(Qt.CheckState.Checked if table["used"][row]
                               else Qt.CheckState.Unchecked)
            if not np.isfinite(table["latency_s"][row]):
                used.setFlags(Qt.ItemFlag.ItemIsEnabled)  # nothing to use
                used.setToolTip("no correlation peak for this line")
            self.setItem(row, USED_COLUMN, used)
        self._filling = False

    def used(self) -> np.ndarray:
        return np.array([self.item(r, USED_COLUMN).checkState() == Qt.CheckState.Checked
                         for r in range(self.rowCount())], dtype=bool)

    def set_used(self, row: int, value: bool) -> None:
        self.item(row, USED_COLUMN).setCheckState(
            Qt.CheckState.Checked if value else Qt.CheckState.Unchecked)

    def _on_item_changed(self, item: QTableWidgetItem) -> None:
        if not self._filling and item.column() == USED_COLUMN:
            self.sig_used_changed.emit()


class CorrelationPlot(pg.PlotWidget):
    """R against Δt for every line, each line's peak marked, the final Δt as a vertical line."""

    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.setBackground("w")
        self.setLabel("bottom", "Δt (GNSS tag late by)", units="s")
        self.setLabel("left", "correlation R")
        self.showGrid(x=True, y=True, alpha=0.3)
        self.curves: list[pg.PlotDataItem] = []
        self.peaks = pg.ScatterPlotItem(size=9, symbol="o", pen=pg.mkPen("k"))
        self.final_line = pg.InfiniteLine(angle=90, pen=pg.mkPen("k", width=2),
                                          label="Δt = {value:.3f} s",
                                          labelOpts={"position": 0.08, "color": "k"})
        self.threshold = pg.InfiniteLine(
            angle=0, pen=pg.mkPen((120, 120, 120), style=Qt.PenStyle.DashLine))

    def clear_curves(self) -> None:
        """Remove every curve and marker.

        Not named ``clear``: pg.PlotWidget sets its plot item's ``clear`` as an instance
        attribute, which hides a method of that name, and the curves (added to the view
        directly) would then stay and pile up under the next ones.
        """
        box = self.getViewBox()
        for item in self.curves:
            box.removeItem(item)
        self.plotItem.clear()
        self.curves = []

    def item_count(self) -> int:
        """Items drawn in the view (curves, peaks, reference lines), for checks."""
        return len(self.getViewBox().addedItems)

    def show_curves(self, grid, curves, table, final: float, min_r: float, selected: int) -> None:
        self.clear_curves()
        self._styles: list[tuple] = []
        self._selected = selected
        n = len(curves)
        # Auto-ranging after each of a survey day's 500 curves took most of a 1.6 s redraw.
        self.disableAutoRange()
        for i, r in enumerate(curves):
            style = (line_colour(i, n),
                     Qt.PenStyle.SolidLine if bool(table["used"][i]) else Qt.PenStyle.DotLine)
            self._styles.append(style)
            # Lines without data have NaN curves: draw nothing rather than a false zero.
            # Plain curve items straight into the view: a PlotDataItem through the plot
            # item cost 2.6x as much (a survey day's 500 curves: ~1 s).
            item = pg.PlotCurveItem(grid, r, pen=self._pen(i), connect="finite",
                                    name=str(table["name"][i]))
            self.getViewBox().addItem(item)
            self.curves.append(item)
        ok = np.isfinite(table["latency_s"])
        brushes = [pg.mkBrush(line_colour(i, n)) for i in np.flatnonzero(ok)]
        self.peaks.setData(table["latency_s"][ok], table["r_max"][ok], brush=brushes)
        self.addItem(self.peaks)
        self.threshold.setValue(min_r)
        self.addItem(self.threshold)
        self.final_line.setVisible(bool(np.isfinite(final)))
        if np.isfinite(final):
            self.final_line.setValue(final)
        self.addItem(self.final_line)
        self.enableAutoRange()

    def _pen(self, i: int):
        # One-pixel pens for all but the selected line: Qt draws them 14x faster than
        # 1.5-pixel ones (a survey day's 500 curves: 0.62 -> 0.04 s per repaint).
        colour, style = self._styles[i]
        return pg.mkPen(colour, width=3 if i == self._selected else 1, style=style)

    def select(self, selected: int) -> None:
        """Highlight line *selected* (thicker), the previous one back to normal: two pens
        changed instead of every curve drawn again."""
        previous, self._selected = getattr(self, "_selected", -1), selected
        for i in {previous, selected}:
            if 0 <= i < len(self.curves):
                self.curves[i].setPen(self._pen(i))

    def set_final(self, final: float) -> None:
        self.final_line.setVisible(bool(np.isfinite(final)))
        if np.isfinite(final):
            self.final_line.setValue(final)


class SeriesPlot(pg.PlotWidget):
    """Detrended GNSS height and total heave of one line, before and after (Qi et al. fig. 4)."""

    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.setBackground("w")
        self.setLabel("bottom", "time since line start", units="s")
        self.setLabel("left", "height / heave", units="m")
        self.showGrid(x=True, y=True, alpha=0.3)
        # One row of legend entries above the curves; show_series leaves headroom for it.
        legend = self.addLegend(offset=(10, 2), brush=pg.mkBrush(255, 255, 255, 200),
                                pen=pg.mkPen((160, 160, 160)), labelTextColor="k",
                                colCount=3)
        legend.setZValue(10)
        self.height_item = self.plot([], [], pen=pg.mkPen("k", width=2),
                                     name="GNSS height")
        self.before_item = self.plot([], [], pen=pg.mkPen((214, 39, 40), width=1.5,
                                                          style=Qt.PenStyle.DashLine),
                                     name="heave, Δt = 0")
        self.after_item = self.plot([], [], pen=pg.mkPen((31, 119, 180), width=1.5),
                                    name="heave, synchronised")

    def show_series(self, series: dict | None, title: str = "") -> None:
        if series is None or series["time"].size == 0:
            for item in (self.height_item, self.before_item, self.after_item):
                item.setData([], [])
            self.setTitle(title)
            return
        t = series["time"] - series["time"][0]
        self.height_item.setData(t, series["height"])
        self.before_item.setData(t, series["heave_before"] - series["heave_before"].mean())
        self.after_item.setData(t, series["heave_after"] - series["heave_after"].mean())
        after = series["heave_after"] - series["heave_after"].mean()
        values = np.concatenate([series["height"], after])
        low, high = float(np.min(values)), float(np.max(values))
        self.setYRange(low, high + 0.3 * (high - low), padding=0.02)
        self.setTitle(title)
