"""The pool panel's tables and convergence plot (degrees and metres, as stored)."""

from __future__ import annotations

import numpy as np
import pyqtgraph as pg
from PySide6.QtCore import Qt
from PySide6.QtGui import QColor
from PySide6.QtWidgets import QAbstractItemView, QHeaderView, QTableWidget, QTableWidgetItem

from hydrosync_core.methods.pool_calibration.result import (
    ANGLE_DECIMALS,
    LEVER_DECIMALS,
)
from hydrosync_core.numfmt import fixed, sigma_decimals
from hydrosync_gui.widgets.columns_table import ColumnsTable, ColumnsTableModel
from plugins.pool_calibration.cloud_views import face_colour

#: Face table: stored column -> (header, unit, display scale, format).
FACE_COLUMNS = {
    "face": ("Face", "", 1, None), "role": ("Role", "", 1, None),
    "water": ("Water", "", 1, None),
    # The pairing and the reference first: which plane each face is compared with is what
    # a surveyor checks before any number, and the panel is too narrow for all columns.
    "pairing": ("Pairing", "", 1, None),
    "reference": ("Reference", "", 1, None),
    "used_for": ("Used for", "", 1, None),
    "points_laser": ("Laser pts", "", 1, None),
    "points_mbes": ("MBES pts", "", 1, None),
    "rms_laser_m": ("RMS laser", "mm", 1000, "{:.2f}"),
    "rms_mbes_m": ("RMS MBES", "mm", 1000, "{:.2f}"),
    "normal_angle_deg": ("Normal Δ", "°", 1, "{:.3f}"),
    "twin_de_m": ("Twin ΔE", "m", 1, "{:.3f}"), "twin_dn_m": ("Twin ΔN", "m", 1, "{:.3f}"),
    "twin_du_m": ("Twin ΔU", "m", 1, "{:.3f}"),
}
TEXT_COLUMNS = ("face", "role", "water", "used_for", "reference", "pairing")
FACE_TIPS = {"RMS laser": "RMS distance of the face's laser points to their fitted plane",
             "RMS MBES": "RMS distance of the face's soundings to their fitted plane "
                         "(final values)",
             "Normal Δ": "angle between the laser and multibeam plane normals (final values)",
             "Used for": "parameters this face carries in the joint adjustment (σ grows by "
                         "more than 10 % without it)",
             "Reference": "plane the soundings are compared with: 'own' = the face's own "
                          "laser plane (it crosses the water), else the above-water twin "
                          "whose laser plane is moved by the design translation",
             "Pairing": "the rule that gave the reference plane (own laser plane, declared "
                        "in target.json, coplanar, parallel offset, congruent) or why the "
                        "face has none (an underside, turned away from the vessel, no "
                        "parallel above-water face)",
             "Twin ΔE": "design translation twin -> face, east", "Twin ΔN": "… north",
             "Twin ΔU": "… up (the design height difference of the patent's step 4.2)"}

#: Iteration table: stored column -> (header, unit, format).
ITERATION_COLUMNS = {
    "iteration": ("Iteration", "", None), "round": ("Round", "", None),
    "d_roll_deg": ("Δ roll", "°", "{:+.5f}"), "d_pitch_deg": ("Δ pitch", "°", "{:+.5f}"),
    "d_yaw_deg": ("Δ yaw", "°", "{:+.5f}"), "roll_deg": ("Roll", "°", "{:.5f}"),
    "pitch_deg": ("Pitch", "°", "{:.5f}"), "yaw_deg": ("Yaw", "°", "{:.5f}"),
    "max_normal_angle_deg": ("Max normal angle", "°", "{:.4f}"),
}

#: Final-values table rows: (label, key in boresight_deg / lever_arm_m, group, unit).
VALUE_ROWS = (("Roll", "roll", "boresight_deg", "°"), ("Pitch", "pitch", "boresight_deg", "°"),
              ("Yaw", "yaw", "boresight_deg", "°"), ("Lever x", "x", "lever_arm_m", "m"),
              ("Lever y", "y", "lever_arm_m", "m"), ("Lever z", "z", "lever_arm_m", "m"))
ROW_TIPS = ("boresight roll (+ starboard down)", "boresight pitch (+ bow up)",
            "boresight yaw (+ clockwise)", "lever arm forward", "lever arm starboard",
            "lever arm down")
VALUE_COLUMNS = ("Final", "± σ", "Patent", "Coarse", "Δ coarse")
VALUE_TIPS = ("final values (joint solution unless 'Final values' = seed, the patent's method)",
              "1-σ of the joint least-squares solution", "solution of the patent's iteration",
              "coarse setup from setup.json (installation drawing)", "final − coarse")
RIGHT = Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter
CURVES = (("d_roll_deg", "Δ roll", "#d62728"), ("d_pitch_deg", "Δ pitch", "#1f77b4"),
          ("d_yaw_deg", "Δ yaw", "#2ca02c"))


class _TipModel(ColumnsTableModel):
    """Columns model with header tool tips; *swatch*: colour the first column by face."""

    def __init__(self, tips: dict, swatch: bool, parent=None) -> None:
        super().__init__(parent)
        self.tips, self.swatch = tips, swatch

    def data(self, index, role: int = Qt.ItemDataRole.DisplayRole):
        if (self.swatch and index.isValid() and index.column() == 0
                and role == Qt.ItemDataRole.DecorationRole):
            return QColor(face_colour(index.row()))
        return super().data(index, role)

    def headerData(self, section: int, orientation, role=Qt.ItemDataRole.DisplayRole):  # noqa: N802
        if role == Qt.ItemDataRole.ToolTipRole and orientation == Qt.Orientation.Horizontal:
            name = self._names[section] if section < len(self._names) else ""
            return self.tips.get(name)
        return super().headerData(section, orientation, role)


class FaceTable(ColumnsTable):
    """One row per design face (row k = face index k of the plan arrays)."""

    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.table_model = _TipModel(FACE_TIPS, True, self)
        self.setModel(self.table_model)
        self.verticalHeader().setVisible(False)

    def fill(self, faces: dict) -> None:
        """Show a faces table (stored layout; missing columns are shown blank)."""
        cols, units, formats = {}, {}, {}
        n = len(faces["face"])
        for key, (header, unit, scale, fmt) in FACE_COLUMNS.items():
            if key in faces:
                values = np.asarray(faces[key])
                cols[header] = values * scale if scale != 1 else values
            else:  # e.g. after Segment alone: same columns, blank until a run
                cols[header] = np.full(n, "") if key in TEXT_COLUMNS else np.full(n, np.nan)
            units[header], formats[header] = unit, fmt
        self.set_columns(cols, units, {k: v for k, v in formats.items() if v})


class IterationTable(ColumnsTable):
    """The seed iteration log: one row per angle iteration."""

    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.verticalHeader().setVisible(False)

    def fill(self, table: dict) -> None:
        cols = {h: np.asarray(table[k]) for k, (h, _u, _f) in ITERATION_COLUMNS.items()}
        units = {h: u for h, u, _f in ITERATION_COLUMNS.values()}
        formats = {h: f for h, _u, f in ITERATION_COLUMNS.values() if f}
        self.set_columns(cols, units, formats)


def _fmt(value, digits: int, sign: bool = False) -> str:
    if value is None or not np.isfinite(value):
        return "–"
    return fixed(value, digits, sign=sign)


class ValuesTable(QTableWidget):
    """Final boresight and lever arm beside σ, the seed solution and the coarse setup."""

    def __init__(self, parent=None) -> None:
        super().__init__(len(VALUE_ROWS), len(VALUE_COLUMNS), parent)
        self.setHorizontalHeaderLabels(list(VALUE_COLUMNS))
        for col, tip in enumerate(VALUE_TIPS):
            self.horizontalHeaderItem(col).setToolTip(tip)
        self.setVerticalHeaderLabels([f"{label} [{unit}]" for label, _k, _g, unit in VALUE_ROWS])
        for row, tip in enumerate(ROW_TIPS):
            self.verticalHeaderItem(row).setToolTip(tip)
        self.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        self.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.ResizeToContents)
        self.horizontalHeader().setStretchLastSection(True)
        self.horizontalHeader().setMinimumSectionSize(60)
        self.verticalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Fixed)
        self.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        self.verticalHeader().setDefaultSectionSize(22)
        # Exactly as tall as its rows: the panel's spare height goes to the plots.
        self.setFixedHeight(self.horizontalHeader().sizeHint().height()
                            + 22 * len(VALUE_ROWS) + 2 * self.frameWidth())

    def fill(self, attrs: dict | None, result: dict | None) -> None:
        """*attrs*: stored result attrs (final values and σ); *result*: the result JSON."""
        result = result or {}
        for row, (_label, key, group, unit) in enumerate(VALUE_ROWS):
            attr = f"{key}_deg" if unit == "°" else f"lever_{key}_m"
            final = float(attrs[attr]) if attrs and attr in attrs else None
            sigma = (float(attrs.get(f"sigma_{attr}", np.nan)) if attrs else None)
            # The digits σ supports, as the CLI and the PDF print them (parameter_text);
            # without a σ 0.001° / 0.1 mm.
            digits = sigma_decimals(sigma) or (ANGLE_DECIMALS if unit == "°" else
                                               LEVER_DECIMALS)
            seed = (result.get("seed") or {}).get(group, {}).get(key)
            coarse = (result.get("coarse") or {}).get(group, {}).get(key)
            delta = None if final is None or coarse is None else final - coarse
            name = key if unit == "°" else f"lever_{key}"
            undetermined = (result.get("undetermined") or {}).get(name)
            flagged = (result.get("flagged") or {}).get(name)
            texts = (_fmt(final, digits), "undetermined" if undetermined else
                     _fmt(sigma, digits) + (" ⚑" if flagged else ""), _fmt(seed, digits),
                     _fmt(coarse, digits), _fmt(delta, digits, sign=True))
            for col, text in enumerate(texts):
                item = QTableWidgetItem(text)
                item.setTextAlignment(RIGHT)
                if col == 0:
                    font = item.font()
                    font.setBold(True)
                    item.setFont(font)
                if col == 1 and (undetermined or flagged):
                    item.setForeground(QColor("#b00020"))
                    item.setToolTip(f"not determined by the data: {undetermined}; the coarse "
                                    "value is kept" if undetermined else flagged)
                elif col == 1:
                    item.setToolTip(_budget_text(result, name, unit))
                self.setItem(row, col, item)

    def clear_values(self) -> None:
        self.fill(None, None)

    def value(self, row: int, column: int) -> str:
        return self.item(row, column).text()


def _budget_text(result: dict, name: str, unit: str) -> str:
    """Tooltip: the σ budget of one parameter (which source gives how much)."""
    budget = (result.get("joint") or {}).get("sigma_budget") or {}
    scale, shown = (1.0, "°") if unit == "°" else (1000.0, " mm")
    parts = [(src, v[name]) for src, v in budget.items() if v.get(name) is not None]
    if not parts:
        return ""
    return "σ from: " + ", ".join(f"{src} {v * scale:.4g}{shown}" for src, v in parts)


def convergence_legend() -> str:
    """Rich-text legend of :class:`ConvergencePlot`."""
    items = [f"<span style='color:{c}'>━</span>&nbsp;{name}" for _k, name, c in CURVES]
    items += ["<span style='color:#6e6e6e'>╌</span>&nbsp;tolerance",
              "<span style='color:#aaa'>┆</span>&nbsp;new round"]
    return "&nbsp;&nbsp; ".join(items)


class ConvergencePlot(pg.PlotWidget):
    """Angle corrections per iteration; log10 |Δ| (default) or signed, rounds marked."""

    def __init__(self, parent=None) -> None:
        super().__init__(parent)
        self.setBackground("w")
        self.setLabel("bottom", "iteration")
        self.getAxis("left").enableAutoSIPrefix(False)
        self.getAxis("left").setWidth(58)
        self.showGrid(x=True, y=True, alpha=0.3)
        # The legend is outside the plot (:func:`convergence_legend`): the curves fill
        # every corner of it.
        self.curves = {key: self.plot([], [], pen=pg.mkPen(colour, width=2), symbol="o",
                                      symbolSize=5, symbolBrush=colour, symbolPen=None,
                                      connect="finite")
                       for key, _name, colour in CURVES}
        self.tolerance = self.plot([], [], pen=pg.mkPen((110, 110, 110), width=1.5,
                                                        style=Qt.PenStyle.DashLine))
        self.round_lines: list[pg.InfiniteLine] = []
        self.log = True

    def show_table(self, table: dict | None, tol_deg: float | None, log: bool = True) -> None:
        self.log = log
        for line in self.round_lines:
            self.removeItem(line)
        self.round_lines = []
        empty = table is None or len(table.get("iteration", ())) == 0
        self.setLogMode(y=log and not empty)  # an empty log axis shows odd 2…9 ticks
        # A short label with the unit inline: the log axis' tick labels ("1e-4") take the
        # width a long label would need, and it was cut.
        self.setLabel("left", "|Δ angle| [°]" if log else "Δ angle [°]")
        if empty:
            for item in self.curves.values():
                item.setData([], [])
            self.tolerance.setData([], [])
            self.setTitle("<span style='color:#777'>no iterations yet (Run all)</span>")
            return
        self.setTitle(None)
        x = np.asarray(table["iteration"], float)
        for key, item in self.curves.items():
            y = np.asarray(table[key], float)
            if log:  # exact zeros have no logarithm: leave a gap instead of -inf
                y = np.where(y == 0, np.nan, np.abs(y))
            item.setData(x, y)
        # A new round starts after the seed lever-arm step moved the soundings.
        rounds = np.asarray(table["round"])
        for xi in x[1:][np.diff(rounds) != 0]:
            line = pg.InfiniteLine(xi - 0.5, angle=90,
                                   pen=pg.mkPen((170, 170, 170), style=Qt.PenStyle.DotLine))
            self.addItem(line)
            self.round_lines.append(line)
        if log and tol_deg and tol_deg > 0:  # in linear scale it would sit on zero
            self.tolerance.setData([x[0], x[-1]], [tol_deg, tol_deg])
        else:
            self.tolerance.setData([], [])
        self.enableAutoRange()
