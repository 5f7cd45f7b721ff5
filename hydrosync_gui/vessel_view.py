"""Schematic of the vessel offset sheet: plan view and side view of the sensor positions.

Body frame FRD (x forward, y starboard, z down, metres). The plan view puts x forward up
the screen and y starboard to the right, as on a drawing of the deck seen from above;
the side view is seen from starboard with the bow to the right and z down drawn down.
The reference point (origin) is a cross in both views.
"""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtWidgets import QHBoxLayout, QWidget

_PEN = pg.mkPen("#1f5fa8")
_BRUSH = pg.mkBrush("#1f5fa8")


def label_groups(names: list[str], h, v, tol: float) -> list[tuple[str, float, float]]:
    """One label per cluster of sensors closer than *tol* in this view (names joined), so
    sensors at one place ("ins", "motion" at the reference point) do not overprint."""
    groups: list[tuple[list[str], float, float]] = []
    for name, x, y in zip(names, h, v, strict=True):
        for members, gx, gy in groups:
            if abs(gx - x) <= tol and abs(gy - y) <= tol:
                members.append(name)
                break
        else:
            groups.append(([name], float(x), float(y)))
    return [(", ".join(members), gx, gy) for members, gx, gy in groups]


class _View(pg.PlotWidget):
    """One projection: points with their sensor names and the reference-point cross."""

    def __init__(self, title: str, x_label: str, y_label: str, invert_y: bool) -> None:
        super().__init__(background="w")
        self.setTitle(title, color="#333", size="9pt")
        self.setLabel("bottom", x_label)
        self.setLabel("left", y_label)
        self.showGrid(x=True, y=True, alpha=0.25)
        self.setAspectLocked(True)  # true shape: a metre is a metre both ways
        # Fixed axis width: tick labels changing width would resize the aspect-locked view,
        # which changes the range and the labels again.
        self.getAxis("left").setWidth(48)
        self.getPlotItem().invertY(invert_y)
        self.setMenuEnabled(False)
        self.setMinimumSize(220, 200)

    def show_points(self, names: list[str], h: np.ndarray, v: np.ndarray) -> None:
        """Draw sensors at horizontal *h* and vertical *v* (plot units, m)."""
        self.clear()
        self.labels: list[str] = []
        self.addItem(pg.ScatterPlotItem([0.0], [0.0], symbol="+", size=16,
                                        pen=pg.mkPen("#a33", width=2), brush=None))
        if len(names):
            self.addItem(pg.ScatterPlotItem(h, v, size=9, pen=_PEN, brush=_BRUSH))
        # Half a metre of margin at least, so one sensor at the origin is still readable.
        span_h = np.r_[h, 0.0]
        span_v = np.r_[v, 0.0]
        pad = max(0.5, 0.15 * max(np.ptp(span_h), np.ptp(span_v)))
        for text, x, y in label_groups(names, h, v, 0.2 * pad):
            label = pg.TextItem(text, color="#222", anchor=(0, 1))
            label.setPos(x, y)
            self.addItem(label)
            self.labels.append(text)
        # Names are written right of their point: more room on that side.
        self.setXRange(span_h.min() - pad, span_h.max() + 3 * pad, padding=0)
        self.setYRange(span_v.min() - pad, span_v.max() + pad, padding=0)


class VesselSchematic(QWidget):
    """Plan view (x forward up, y starboard right) and side view (x bow right, z down)."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.plan = _View("Plan (from above)", "y starboard [m]", "x forward [m]", False)
        self.side = _View("Side (from starboard)", "x forward [m]", "z down [m]", True)
        lay = QHBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addWidget(self.plan)
        lay.addWidget(self.side)

    def show_sensors(self, sensors: dict[str, np.ndarray]) -> None:
        """Draw *sensors*: name -> offset [x, y, z] (body FRD, m)."""
        names = list(sensors)
        xyz = np.array([sensors[n] for n in names], dtype=float).reshape(-1, 3)
        self.plan.show_points(names, xyz[:, 1], xyz[:, 0])
        self.side.show_points(names, xyz[:, 0], xyz[:, 2])
