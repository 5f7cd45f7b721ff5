"""The project browser: the project's tree of groups, tables and arrays.

Columns are *Name*, *Kind / shape*, *dtype* and *Size*. A table (a group whose ``kind``
attribute is ``"table"``) is shown as one row ``table, N rows × C columns`` with its
columns as children; a group carrying a JSON document (setup, parameters, vessel sheet)
without children is marked ``json``. The attributes of the selected node, with any JSON document
pretty-printed, are shown in the detail pane below the tree and as a tooltip.

The tree is built from :meth:`Project.walk`, which reads metadata only, so it is cheap
even for large projects. Items keep copies of what they show: nothing touches the project
between two :meth:`ProjectBrowser.refresh` calls (a save may be rebinding it in a worker).
"""

from __future__ import annotations

import json

from PySide6.QtCore import Qt, Signal, Slot
from PySide6.QtWidgets import (
    QHeaderView,
    QPlainTextEdit,
    QSplitter,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core.project import NodeInfo, Project, schema
from hydrosync_core.timespan import table_span

COLUMNS = ("Name", "Kind / shape", "dtype", "Size")
PATH_ROLE = Qt.ItemDataRole.UserRole
DETAIL_ROLE = Qt.ItemDataRole.UserRole + 1
_MAX_ATTR_CHARS = 2000


def human_size(nbytes: int) -> str:
    """``1536`` -> ``"1.5 KiB"``; bytes below 1 KiB are shown exactly."""
    size = float(nbytes)
    for unit in ("B", "KiB", "MiB", "GiB", "TiB"):
        if size < 1024 or unit == "TiB":
            return f"{int(size)} B" if unit == "B" else f"{size:.1f} {unit}"
        size /= 1024
    return f"{size:.1f} TiB"  # pragma: no cover - loop always returns


def shape_text(shape: tuple[int, ...] | None) -> str:
    """``(1200, 3)`` -> ``"1200 × 3"``; ``()`` -> ``"scalar"``."""
    if shape is None:
        return ""
    return " × ".join(str(n) for n in shape) if shape else "scalar"


def _dtype_text(dtype: str | None) -> str:
    if dtype is None:
        return ""
    return "str" if dtype in ("object", "|O") or dtype.startswith("<U") else dtype


def describe_attrs(path: str, attrs: dict) -> str:
    """Plain-text detail of one node: its path, its attributes, any JSON document."""
    lines = [f"/{path}"]
    document = attrs.get(schema.JSON_ATTR)
    for key, value in sorted(attrs.items()):
        if key == schema.JSON_ATTR:
            continue
        text = repr(value) if not isinstance(value, str) else value
        lines.append(f"  {key}: {text[:_MAX_ATTR_CHARS]}")
    if document is not None:
        try:
            pretty = json.dumps(json.loads(document), indent=2)
        except (TypeError, ValueError):
            pretty = str(document)
        lines.append("  json:")
        lines.extend("    " + line for line in pretty[:_MAX_ATTR_CHARS].splitlines())
    return "\n".join(lines)


class ProjectBrowser(QWidget):
    """Tree of the bound project with a detail pane.

    Signals
    -------
    sig_selected(str)
        Project path of the node the user selected (no leading slash).
    """

    sig_selected = Signal(str)

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.project: Project | None = None
        self.tree = QTreeWidget()
        self.tree.setColumnCount(len(COLUMNS))
        self.tree.setHeaderLabels(list(COLUMNS))
        self.tree.setUniformRowHeights(True)
        self.tree.setAlternatingRowColors(True)
        header = self.tree.header()
        header.setStretchLastSection(False)
        # Every column fits its contents; a narrow dock scrolls rather than hiding names.
        for column in range(len(COLUMNS)):
            header.setSectionResizeMode(column, QHeaderView.ResizeMode.ResizeToContents)
        self.detail = QPlainTextEdit()
        self.detail.setReadOnly(True)
        self.detail.setPlaceholderText("Select a node to see its attributes.")
        splitter = QSplitter(Qt.Orientation.Vertical)
        splitter.addWidget(self.tree)
        splitter.addWidget(self.detail)
        splitter.setStretchFactor(0, 4)
        splitter.setStretchFactor(1, 1)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(splitter)
        self._items: dict[str, QTreeWidgetItem] = {}
        self.tree.currentItemChanged.connect(self._on_current_changed)

    # ---------------------------------------------------------------- public
    def set_project(self, project: Project | None) -> None:
        """Show *project* (or nothing)."""
        self.project = project
        self.refresh()

    def refresh(self) -> None:
        """Rebuild the tree from the project, keeping expanded nodes and the selection."""
        expanded = {p for p, item in self._items.items() if item.isExpanded()}
        first_build = not self._items
        current = self.tree.currentItem()
        selected = current.data(0, PATH_ROLE) if current is not None else None
        self.tree.clear()
        self._items.clear()
        self.detail.clear()
        if self.project is None:
            return
        for info in self.project.walk():
            self._add(info)
        self._label_tables()
        self._mark_stale()
        for path, item in self._items.items():
            top_level = "/" not in path
            item.setExpanded(path in expanded or (first_build and top_level))
        if first_build:
            for group in (schema.RAW, schema.RESULTS):  # show what was imported and computed
                for path, item in self._items.items():
                    if path.startswith(group + "/") and path.count("/") == 1:
                        item.setExpanded(item.data(1, Qt.ItemDataRole.UserRole) != "table")
        if selected in self._items:
            self.tree.setCurrentItem(self._items[selected])

    def item(self, path: str) -> QTreeWidgetItem | None:
        """The tree item of project *path* (no leading slash), if shown."""
        return self._items.get(path.strip("/"))

    def row_texts(self, path: str) -> tuple[str, ...]:
        """The four column texts of *path* (for tests and copy)."""
        item = self.item(path)
        if item is None:
            raise KeyError(path)
        return tuple(item.text(c) for c in range(len(COLUMNS)))

    # --------------------------------------------------------------- private
    def _add(self, info: NodeInfo) -> None:
        parent_path, _, name = info.path.rpartition("/")
        parent = self._items.get(parent_path)
        item = QTreeWidgetItem(parent if parent is not None else self.tree)
        item.setText(0, name)
        item.setData(0, PATH_ROLE, info.path)
        if info.kind == "group":
            is_table = info.attrs.get("kind") == schema.TABLE_KIND
            kind = "table" if is_table else "group"
            if schema.JSON_ATTR in info.attrs:
                kind = "json"
            item.setText(1, kind)
            item.setData(1, Qt.ItemDataRole.UserRole, kind)
        else:
            item.setText(1, shape_text(info.shape))
            item.setText(2, _dtype_text(info.dtype))
            item.setTextAlignment(1, Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
        nbytes = info.nbytes
        if schema.JSON_ATTR in info.attrs:  # the document lives in an attribute
            nbytes += len(str(info.attrs[schema.JSON_ATTR]).encode())
        item.setText(3, human_size(nbytes))
        item.setTextAlignment(3, Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
        detail = describe_attrs(info.path, info.attrs)
        item.setData(0, DETAIL_ROLE, detail)
        item.setToolTip(0, detail)
        self._items[info.path] = item

    def _mark_stale(self) -> None:
        """Mark each stored result whose inputs changed since it was computed."""
        from hydrosync_core.provenance import OUT_OF_DATE, stale_reasons

        for path, item in self._items.items():
            if not (path.startswith(schema.RESULTS + "/") and path.count("/") == 1):
                continue
            reasons = stale_reasons(self.project, path)
            if reasons:
                item.setText(0, f"{item.text(0)} ({OUT_OF_DATE})")
                item.setForeground(0, Qt.GlobalColor.darkRed)
                item.setToolTip(0, f"{OUT_OF_DATE}: " + "; ".join(reasons) + "\n\n"
                                + item.toolTip(0))

    def _label_tables(self) -> None:
        """Give each table row its size (``table N × C``); a JSON group with children
        (a results group holding its parameters) is shown as a group."""
        for item in self._items.values():
            if item.data(1, Qt.ItemDataRole.UserRole) == "json" and item.childCount():
                item.setText(1, "group")
                item.setData(1, Qt.ItemDataRole.UserRole, "group")
            if item.data(1, Qt.ItemDataRole.UserRole) != "table":
                continue
            columns = item.childCount()
            rows = item.child(0).text(1) if columns else "0"
            item.setText(1, f"table {rows} × {columns}")
            tip = f"{rows} rows, {columns} columns"
            path = item.data(0, PATH_ROLE)
            span = table_span(self.project, path) if str(path).startswith("raw/") else None
            if span is not None:
                # The time scale of each data set, so line windows can be checked against it.
                tip += f"\ntime {span.text()}"
                item.setData(0, DETAIL_ROLE, f"time {span.text()}\n\n"
                             + str(item.data(0, DETAIL_ROLE) or ""))
            item.setToolTip(1, tip)

    @Slot(QTreeWidgetItem, QTreeWidgetItem)
    def _on_current_changed(self, current: QTreeWidgetItem | None, _previous) -> None:
        if current is None:
            self.detail.clear()
            return
        self.detail.setPlainText(current.data(0, DETAIL_ROLE) or "")
        self.sig_selected.emit(current.data(0, PATH_ROLE))
