"""A read-only table of named 1-D columns (a project table) for results and raw data.

Example
-------
>>> table = ColumnsTable()
>>> table.set_columns(project.get_table("results/latency/lines"),
...                   units={"latency_s": "s"}, formats={"latency_s": "{:.4f}"},
...                   labels={"latency_s": "Δt"}, tips={"latency_s": "line latency"})

Headers are human labels (``labels``; the raw key only where none is given) with their
unit, and carry a tooltip (``tips``). A missing value (NaN) shows blank, or the column's
``missing`` text (``"—"``) where a blank would read as a fault.

Cells are formatted only when Qt paints them, so a table of a million rows costs the
arrays it holds and nothing more.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from PySide6.QtCore import QAbstractTableModel, QEvent, QModelIndex, QPersistentModelIndex, Qt
from PySide6.QtWidgets import QAbstractItemView, QHeaderView, QTableView, QWidget

from hydrosync_gui.i18n import tr

_Index = QModelIndex | QPersistentModelIndex


def wrap_header(text: str, width: int = 14) -> str:
    """*text* on two lines, broken at the space nearest its middle, if longer than *width*
    characters ("predicted σ heading [°]" → "predicted σ\nheading [°]"): a wide header
    made a column of four-digit numbers 170 px wide and pushed the table into a
    horizontal scroll. A unit in brackets stays with the word before it."""
    if len(text) <= width:
        return text
    spaces = [i for i, c in enumerate(text) if c == " " and text[i + 1:i + 2] != "["]
    if not spaces:
        return text
    cut = min(spaces, key=lambda i: abs(i - len(text) / 2))
    return f"{text[:cut]}\n{text[cut + 1:]}"


def _default_format(value) -> str:
    if isinstance(value, float | np.floating):
        return "" if np.isnan(value) else f"{value:.6g}"
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    return str(value)


class ColumnsTableModel(QAbstractTableModel):
    """Qt model over ``{name: 1-D array}``; headers ``name [unit]``."""

    def __init__(self, parent=None, wrap_headers: bool = False) -> None:
        super().__init__(parent)
        self.wrap_headers = wrap_headers
        self._names: list[str] = []
        self._columns: list[np.ndarray] = []
        self._headers: list[str] = []
        self._formats: list[str | None] = []
        self._tips: list[str] = []
        self._missing: list[str] = []
        self._rows = 0

    def set_columns(
        self,
        columns: Mapping[str, np.ndarray],
        units: Mapping[str, str] | None = None,
        formats: Mapping[str, str] | None = None,
        labels: Mapping[str, str] | None = None,
        tips: Mapping[str, str] | None = None,
        missing: Mapping[str, str] | None = None,
    ) -> None:
        """Show *columns* (equal-length 1-D arrays); the mappings are keyed by name.

        *formats* are ``str.format`` patterns such as ``"{:.3f}"``; *labels* the header
        texts (the name where absent); *tips* header tooltips; *missing* the text of a
        NaN cell (blank where absent).
        """
        arrays = {k: np.asarray(v) for k, v in columns.items()}
        lengths = {a.shape[0] if a.ndim else 1 for a in arrays.values()}
        if len(lengths) > 1:
            raise ValueError(f"columns of different lengths {sorted(lengths)}")
        units, formats, labels = units or {}, formats or {}, labels or {}
        tips, missing = tips or {}, missing or {}
        self.beginResetModel()
        self._names = list(arrays)
        self._columns = [a.reshape(-1) for a in arrays.values()]
        self._headers = [f"{labels.get(n, n)} [{units[n]}]" if units.get(n)
                         else labels.get(n, n) for n in self._names]
        self._formats = [formats.get(n) for n in self._names]
        self._tips = [tips.get(n, "") for n in self._names]
        self._missing = [missing.get(n, "") for n in self._names]
        self._rows = lengths.pop() if lengths else 0
        self.endResetModel()

    def rowCount(self, parent: _Index = QModelIndex()) -> int:  # noqa: B008, N802
        return 0 if parent.isValid() else self._rows

    def columnCount(self, parent: _Index = QModelIndex()) -> int:  # noqa: B008, N802
        return 0 if parent.isValid() else len(self._columns)

    def text(self, row: int, column: int) -> str:
        """The displayed text of one cell."""
        value = self._columns[column][row]
        if isinstance(value, float | np.floating) and np.isnan(value):
            return self._missing[column]  # a missing value: blank unless stated
        pattern = self._formats[column]
        if pattern:
            return pattern.format(value)
        text = _default_format(value)
        # Words (a method, a role) in the workbench's language; numbers have no entry.
        return tr(text) if self._columns[column].dtype.kind in "USO" else text

    def data(self, index: _Index, role: int = Qt.ItemDataRole.DisplayRole):
        if not index.isValid():
            return None
        if role == Qt.ItemDataRole.DisplayRole:
            return self.text(index.row(), index.column())
        if role == Qt.ItemDataRole.TextAlignmentRole:
            kind = self._columns[index.column()].dtype.kind
            if kind in "iuf":
                return int(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
        return None

    def headerData(self, section: int, orientation, role=Qt.ItemDataRole.DisplayRole):  # noqa: N802
        horizontal = orientation == Qt.Orientation.Horizontal
        if role == Qt.ItemDataRole.ToolTipRole and horizontal and section < len(self._tips):
            return tr(self._tips[section]) or None
        if role != Qt.ItemDataRole.DisplayRole:
            return None
        if horizontal:
            if section >= len(self._headers):
                return None
            text = tr(self._headers[section])
            return wrap_header(text) if self.wrap_headers else text
        return str(section + 1)

    def header(self, column: int) -> str:
        """The header of *column* (label and unit, in the workbench's language) on one
        line."""
        return tr(self._headers[column])


class ColumnsTable(QTableView):
    """Read-only, sortable-looking table view; see :meth:`set_columns`.

    *wrap_headers*: long headers go on two lines (:func:`wrap_header`), so columns are as
    narrow as their numbers.
    """

    def __init__(self, parent: QWidget | None = None, wrap_headers: bool = False) -> None:
        super().__init__(parent)
        self.table_model = ColumnsTableModel(self, wrap_headers=wrap_headers)
        self.setModel(self.table_model)
        self.setEditTriggers(QAbstractItemView.EditTrigger.NoEditTriggers)
        self.setSelectionBehavior(QAbstractItemView.SelectionBehavior.SelectRows)
        self.setAlternatingRowColors(True)
        self.verticalHeader().setDefaultSectionSize(20)
        self.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.Interactive)
        self.horizontalHeader().setStretchLastSection(True)

    def changeEvent(self, event) -> None:  # noqa: N802 (Qt API)
        if event.type() == QEvent.Type.LanguageChange and self.table_model.columnCount():
            self.table_model.headerDataChanged.emit(Qt.Orientation.Horizontal, 0,
                                                    self.table_model.columnCount() - 1)
        super().changeEvent(event)

    def set_columns(
        self,
        columns: Mapping[str, np.ndarray],
        units: Mapping[str, str] | None = None,
        formats: Mapping[str, str] | None = None,
        labels: Mapping[str, str] | None = None,
        tips: Mapping[str, str] | None = None,
        missing: Mapping[str, str] | None = None,
    ) -> None:
        """Show *columns*; see :meth:`ColumnsTableModel.set_columns`."""
        self.table_model.set_columns(columns, units, formats, labels, tips, missing)
        if self.table_model.rowCount() <= 1000:  # sizing reads every cell: only when cheap
            self.resizeColumnsToContents()

    def clear(self) -> None:
        self.table_model.set_columns({})
