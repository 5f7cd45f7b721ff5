"""Edit → Vessel offsets…: type in, import or export the vessel offset sheet.

The dialog edits a copy of the project's ``/vessel`` sheet (see
:mod:`hydrosync_core.project.vessel`): the vessel name and one table row per sensor with
its offset ``x, y, z`` (body frame FRD: x forward, y starboard, z down; metres) from the
reference point and its mounting angles ``roll, pitch, yaw`` (degrees; blank = not given).
Keys of a sensor the table does not show are kept, also when the sensor is renamed.
Nothing is written into the project until OK, and only if every cell is valid.
"""

from __future__ import annotations

import copy
import math
from pathlib import Path

import numpy as np
from PySide6.QtCore import Qt, Slot
from PySide6.QtGui import QBrush, QColor
from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QFileDialog,
    QFormLayout,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QLineEdit,
    QPushButton,
    QTableWidget,
    QTableWidgetItem,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core.atomic import write_json_atomic
from hydrosync_core.errors import InputError
from hydrosync_core.importers.vessel_json import read_vessel_json
from hydrosync_core.project import Project
from hydrosync_core.project.schema import VESSEL
from hydrosync_core.project.vessel import vessel_config
from hydrosync_gui.vessel_view import VesselSchematic

COLUMNS = ("Name", "x fwd [m]", "y stbd [m]", "z down [m]", "roll [°]", "pitch [°]", "yaw [°]")
ANGLES = ("roll", "pitch", "yaw")
ORIGINAL = Qt.ItemDataRole.UserRole  # name item: the sensor's name in the loaded sheet
JSON_FILTER = "Vessel sheet (*.json);;All files (*)"
BAD_CELL = QBrush(QColor("#f8d0d0"))


def _text(value: float) -> str:
    """Shortest text that reads back to the same float (so OK on an unchanged sheet is a no-op)."""
    text = repr(float(value))
    return text[:-2] if text.endswith(".0") else text


def _number(text: str) -> float | None:
    """The finite number in *text* (a decimal comma is accepted), else None."""
    try:
        value = float(text.strip().replace(",", "."))
    except ValueError:
        return None
    return value if math.isfinite(value) else None


class VesselDialog(QDialog):
    """Edit the vessel offset sheet of *project*; OK writes it into ``/vessel``.

    Parameters
    ----------
    project : Project
        The project whose sheet is edited (written only on OK, when valid and changed).
    start_dir : str
        Folder the Import/Export file dialogs open in.
    """

    def __init__(self, project: Project, start_dir: str = "",
                 parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Vessel offsets")
        self.project = project
        self.start_dir = start_dir
        self.changed = False  # True once OK wrote a different sheet into the project
        self._base = copy.deepcopy(vessel_config(project))
        self._loading = False

        self.name_edit = QLineEdit()
        self.name_edit.setPlaceholderText("e.g. MV Example")
        self.table = QTableWidget(0, len(COLUMNS))
        self.table.setHorizontalHeaderLabels(COLUMNS)
        self.table.verticalHeader().setVisible(True)
        header = self.table.horizontalHeader()
        header.setSectionResizeMode(QHeaderView.ResizeMode.Stretch)
        header.setSectionResizeMode(0, QHeaderView.ResizeMode.Interactive)
        self.table.setColumnWidth(0, 130)
        self.table.itemChanged.connect(self._on_edited)
        self.add_button = QPushButton("Add sensor")
        self.add_button.clicked.connect(self.add_row)
        self.remove_button = QPushButton("Remove sensor")
        self.remove_button.clicked.connect(self.remove_selected)
        self.import_button = QPushButton("Import JSON…")
        self.import_button.clicked.connect(self._on_import)
        self.export_button = QPushButton("Export JSON…")
        self.export_button.clicked.connect(self._on_export)
        self.message = QLabel()  # the first invalid cell, in red; empty when all is well
        self.message.setObjectName("vessel_message")
        self.message.setWordWrap(True)
        self.message.setStyleSheet("color: #b00020;")
        self.lever_label = QLabel()
        self.lever_label.setObjectName("vessel_lever_arm")
        self.lever_label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.schematic = VesselSchematic()
        self.buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok
                                        | QDialogButtonBox.StandardButton.Cancel)
        self.buttons.accepted.connect(self.accept)
        self.buttons.rejected.connect(self.reject)

        form = QFormLayout()
        form.addRow("Vessel name", self.name_edit)
        hint = QLabel("Sensor positions from the reference point in the body frame: x forward, "
                      "y starboard, z down (metres). Mounting angles in degrees; leave them "
                      "blank if not given.")
        hint.setWordWrap(True)
        row_buttons = QHBoxLayout()
        for button in (self.add_button, self.remove_button):
            row_buttons.addWidget(button)
        row_buttons.addStretch(1)
        for button in (self.import_button, self.export_button):
            row_buttons.addWidget(button)
        lay = QVBoxLayout(self)
        lay.addLayout(form)
        lay.addWidget(hint)
        lay.addWidget(self.table, 2)
        lay.addLayout(row_buttons)
        lay.addWidget(self.message)
        lay.addWidget(self.lever_label)
        lay.addWidget(self.schematic, 3)
        lay.addWidget(self.buttons)
        self.resize(860, 700)
        self.load_sheet(self._base)

    # ----------------------------------------------------------------- rows
    def load_sheet(self, sheet: dict) -> None:
        """Show *sheet* (replacing the table) and remember it as the base of unknown keys."""
        self._base = copy.deepcopy(sheet)
        self._loading = True
        self.name_edit.setText(str(sheet.get("name", "")))
        self.table.setRowCount(0)
        for name, sensor in sheet.get("sensors", {}).items():
            angles = sensor.get("angles_deg") or {}
            values = [_text(v) for v in sensor.get("offset_m", ["", "", ""])]
            values += [_text(angles[a]) if a in angles else "" for a in ANGLES]
            self._append(name, values, original=name)
        self._loading = False
        self._update()

    def add_row(self) -> int:
        """Append an empty sensor row (offset 0, 0, 0) and start editing its name."""
        row = self._append("", ["0", "0", "0", "", "", ""], original=None)
        self.table.setCurrentCell(row, 0)
        self.table.editItem(self.table.item(row, 0))
        self._update()
        return row

    @Slot()
    def remove_selected(self) -> None:
        """Remove the rows that have a selected cell (or the current row)."""
        rows = {i.row() for i in self.table.selectedIndexes()} or {self.table.currentRow()}
        for row in sorted((r for r in rows if r >= 0), reverse=True):
            self.table.removeRow(row)
        self._update()

    def set_cell(self, row: int, column: int, text: str) -> None:
        """Set one cell's text (as if typed)."""
        self.table.item(row, column).setText(text)

    def _append(self, name: str, values: list[str], original: str | None) -> int:
        loading, self._loading = self._loading, True
        row = self.table.rowCount()
        self.table.insertRow(row)
        item = QTableWidgetItem(name)
        item.setData(ORIGINAL, original)
        self.table.setItem(row, 0, item)
        for column, text in enumerate(values, 1):
            cell = QTableWidgetItem(text)
            cell.setTextAlignment(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
            self.table.setItem(row, column, cell)
        self._loading = loading
        return row

    # ----------------------------------------------------------- validation
    def sheet(self) -> tuple[dict | None, str, tuple[int, int] | None]:
        """The edited sheet, or (None, message naming row and field, (row, column))."""
        sheet = copy.deepcopy(self._base)
        sheet["name"] = self.name_edit.text().strip()
        sensors: dict = {}
        rows_of: dict[str, int] = {}
        for row in range(self.table.rowCount()):
            name = self.table.item(row, 0).text().strip()
            where = f"Row {row + 1}" + (f" ('{name}')" if name else "")
            if not name:
                return None, f"{where}: the sensor name is empty.", (row, 0)
            if name in rows_of:
                return (None, f"{where}: the name '{name}' is already used in row "
                        f"{rows_of[name] + 1}; sensor names must be unique.", (row, 0))
            rows_of[name] = row
            numbers: list[float | None] = []
            for column in range(1, len(COLUMNS)):
                text = self.table.item(row, column).text().strip()
                value = _number(text) if text else None
                if value is None and (text or column <= 3):
                    what = f"'{text}' is not a finite number" if text else "a number is needed"
                    return None, f"{where}, {COLUMNS[column]}: {what}.", (row, column)
                numbers.append(value)
            original = self.table.item(row, 0).data(ORIGINAL)
            entry = copy.deepcopy(self._base.get("sensors", {}).get(original, {}))
            entry["offset_m"] = numbers[:3]
            angles = {a: v for a, v in zip(ANGLES, numbers[3:], strict=True) if v is not None}
            entry.pop("angles_deg", None)
            if angles:
                entry["angles_deg"] = angles
            sensors[name] = entry
        sheet["sensors"] = sensors
        return sheet, "", None

    def _show_error(self, message: str, cell: tuple[int, int] | None) -> None:
        self.message.setText(message)
        if cell is not None:
            self.table.setCurrentCell(*cell)

    def _mark(self, cell: tuple[int, int] | None) -> None:
        """Tint the invalid cell (only that one), so the eye finds what the message names."""
        loading, self._loading = self._loading, True  # a colour change emits itemChanged
        for row in range(self.table.rowCount()):
            for column in range(len(COLUMNS)):
                item = self.table.item(row, column)
                bad = (row, column) == cell
                if bad or item.background().style() != Qt.BrushStyle.NoBrush:
                    item.setBackground(BAD_CELL if bad else QBrush())
        self._loading = loading

    def positions(self) -> dict[str, np.ndarray]:
        """Offsets (body FRD, m) of the named rows whose x, y, z are numbers (for drawing)."""
        out: dict[str, np.ndarray] = {}
        for row in range(self.table.rowCount()):
            name = self.table.item(row, 0).text().strip()
            xyz = [_number(self.table.item(row, c).text()) for c in (1, 2, 3)]
            if name and None not in xyz:
                out[name] = np.asarray(xyz, dtype=float)
        return out

    @Slot(QTableWidgetItem)
    def _on_edited(self, _item: QTableWidgetItem) -> None:
        if not self._loading:
            self._update()

    def _update(self) -> None:
        """Re-check the table: message, derived lever arm and schematic."""
        sheet, message, cell = self.sheet()
        self.message.setText(message)
        self._mark(cell)
        self.remove_button.setEnabled(self.table.rowCount() > 0)
        # Draw what can be drawn even while a cell is wrong: the user sees the rest stay put.
        self.schematic.show_sensors(self.positions())
        if sheet is None:
            self.lever_label.setText("Lever arm gnss − motion: fix the table first.")
            return
        sensors = {n: np.asarray(s["offset_m"], float) for n, s in sheet["sensors"].items()}
        if "gnss" in sensors and "motion" in sensors:
            # Lever arm from the motion sensor to the GNSS antenna (as the Latency plugin uses).
            x, y, z = sensors["gnss"] - sensors["motion"]
            self.lever_label.setText(f"Lever arm gnss − motion (body FRD): x = {x:.3f} m, "
                                     f"y = {y:.3f} m, z = {z:.3f} m")
        else:
            self.lever_label.setText("Lever arm gnss − motion: needs sensors named 'gnss' and "
                                     "'motion' (the Latency plugin uses it).")

    # ---------------------------------------------------------------- files
    @Slot()
    def _on_import(self) -> None:
        path, _ = QFileDialog.getOpenFileName(self, "Import vessel sheet", self.start_dir,
                                              JSON_FILTER)
        if path:
            self.import_json(path)

    def import_json(self, path: str | Path) -> bool:
        """Replace the table by the sheet in *path*; on a bad file show why and keep the table."""
        try:
            sheet = read_vessel_json(path)
        except InputError as exc:
            self._show_error(f"Import failed: {exc}", None)
            return False
        self.start_dir = str(Path(path).parent)
        self.load_sheet(sheet)
        return True

    @Slot()
    def _on_export(self) -> None:
        name = (self.name_edit.text().strip() or "vessel").replace(" ", "_")
        path, _ = QFileDialog.getSaveFileName(self, "Export vessel sheet",
                                              str(Path(self.start_dir) / f"{name}.json"),
                                              JSON_FILTER)
        if path:
            self.export_json(path)

    def export_json(self, path: str | Path) -> bool:
        """Write the edited sheet to *path* (the vessel.json format), atomically."""
        sheet, message, cell = self.sheet()
        if sheet is None:
            self._show_error(f"Not exported. {message}", cell)
            return False
        if not sheet["sensors"]:
            self._show_error("Not exported: add at least one sensor.", None)
            return False
        try:
            write_json_atomic(path, sheet)
        except (OSError, TypeError, ValueError) as exc:
            self._show_error(f"Export failed: {exc}", None)
            return False
        self.start_dir = str(Path(path).parent)
        self.message.setText("")
        return True

    # ------------------------------------------------------------------- OK
    def accept(self) -> None:
        """Write the sheet into the project and close; stay open on an invalid cell."""
        sheet, message, cell = self.sheet()
        if sheet is None:
            self._show_error(message, cell)
            return
        if sheet != vessel_config(self.project):
            self.project.put_json(VESSEL, sheet)
            self.changed = True
        super().accept()
