"""Dialogs of the shell: File → Import… and Help → Plugins."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import (
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QFileDialog,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core.plugins.spec import DataKind
from hydrosync_gui.plugin_host import PluginHost


def _takes_heave(kind) -> bool:
    """Whether the kind's reader takes ``heave_positive`` ("up" / "down")."""
    return "heave_positive" in getattr(kind, "options", ())


class ImportDialog(QDialog):
    """Choose what kind of file to import (from ``KINDS``) and the file itself."""

    def __init__(
        self, kinds: Mapping[str, DataKind], start_dir: str = "", parent: QWidget | None = None
    ) -> None:
        super().__init__(parent)
        self.setWindowTitle("Import data")
        self.start_dir = start_dir
        self.kind_box = QComboBox()
        for name, kind in kinds.items():
            self.kind_box.addItem(f"{name} — {kind.description}", name)
            self.kind_box.setItemData(self.kind_box.count() - 1, f"stored in /{kind.target}",
                                      Qt.ItemDataRole.ToolTipRole)
        self.target = QLabel()
        # Heave sign of a motion log: stated, never guessed (formats.md, "NMEA 0183").
        self.heave_box = QComboBox()
        self.heave_box.addItem("as documented for the sentence", None)
        self.heave_box.addItem("positive up", "up")
        self.heave_box.addItem("positive down", "down")
        self.heave_box.setToolTip("Direction of positive heave in the log. TSS1 carries no "
                                  "documented sign: choose one.")
        self.heave_label = QLabel("Heave:")
        self.path_edit = QLineEdit()
        self.path_edit.setPlaceholderText("file to import")
        browse = QPushButton("Browse…")
        browse.clicked.connect(self._on_browse)
        row = QHBoxLayout()
        row.addWidget(self.path_edit, 1)
        row.addWidget(browse)
        self._kinds = dict(kinds)
        self.buttons = QDialogButtonBox(
            QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel
        )
        self.buttons.accepted.connect(self.accept)
        self.buttons.rejected.connect(self.reject)
        form = QFormLayout()
        form.addRow("Kind:", self.kind_box)
        form.addRow("Goes to:", self.target)
        form.addRow("File:", row)
        form.addRow(self.heave_label, self.heave_box)
        layout = QVBoxLayout(self)
        layout.addLayout(form)
        layout.addWidget(self.buttons)
        self.kind_box.currentIndexChanged.connect(self._on_kind)
        self.path_edit.textChanged.connect(self._on_kind)
        self._on_kind()
        self.resize(560, self.sizeHint().height())

    def choice(self) -> tuple[str, str, dict]:
        """The chosen ``(kind, path, options)``; options go to the kind's reader."""
        kind = str(self.kind_box.currentData())
        options = {}
        if _takes_heave(self._kinds.get(kind)) and self.heave_box.currentData() is not None:
            options["heave_positive"] = self.heave_box.currentData()
        return kind, self.path_edit.text().strip(), options

    @classmethod
    def ask(
        cls, parent: QWidget | None, kinds: Mapping[str, DataKind], start_dir: str = ""
    ) -> tuple[str, str, dict] | None:
        """Show the dialog modally; the choice, or None if cancelled."""
        dialog = cls(kinds, start_dir, parent)
        try:
            return dialog.choice() if dialog.exec() == QDialog.DialogCode.Accepted else None
        finally:
            dialog.deleteLater()

    @Slot()
    def _on_kind(self) -> None:
        kind = self._kinds.get(str(self.kind_box.currentData()))
        self.target.setText(f"/{kind.target}" if kind else "")
        heave = _takes_heave(self._kinds.get(str(self.kind_box.currentData())))
        self.heave_box.setVisible(heave)
        self.heave_label.setVisible(heave)
        ok = self.buttons.button(QDialogButtonBox.StandardButton.Ok)
        ok.setEnabled(bool(self.path_edit.text().strip()))

    @Slot()
    def _on_browse(self) -> None:
        path, _ = QFileDialog.getOpenFileName(
            self, "Import file", self.path_edit.text() or self.start_dir,
            "Data files (*.csv *.txt *.json *.ply *.las *.laz *.nmea *.pos);;All files (*)",
        )
        if path:
            self.path_edit.setText(path)
            self.start_dir = str(Path(path).parent)


class PluginsDialog(QDialog):
    """Every discovered plugin: loaded ones with their state, failed ones with the error."""

    def __init__(self, host: PluginHost, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setWindowTitle("Plugins")
        self.tree = QTreeWidget()
        self.tree.setHeaderLabels(["Plugin", "Status", "Details"])
        self.tree.setRootIsDecorated(False)
        self.tree.setWordWrap(True)
        for entry in host.entries:
            if entry.error:
                status = "panel failed"
            elif entry.panel is not None:
                status = "loaded, panel open"
            else:
                status = "loaded"
            details = entry.error or entry.spec.description or entry.discovered.value
            self._row(f"{entry.name} ({entry.spec.id})", status, details, bool(entry.error))
        for fail in host.failed:
            if fail.stage == "spec":
                self._row(fail.name, "failed to load", f"{fail.value}: {fail.error}", True)
        if self.tree.topLevelItemCount() == 0:
            self._row("(none)", "", "No plugin is installed in the 'hydrosync.plugins' group.",
                      False)
        for column in range(2):
            self.tree.resizeColumnToContents(column)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Close)
        buttons.rejected.connect(self.reject)
        layout = QVBoxLayout(self)
        layout.addWidget(self.tree)
        layout.addWidget(buttons)
        self.resize(720, 300)

    def _row(self, name: str, status: str, details: str, bad: bool) -> None:
        item = QTreeWidgetItem(self.tree, [name, status, details])
        item.setToolTip(2, details)
        if bad:
            item.setForeground(1, Qt.GlobalColor.red)

    def rows(self) -> list[tuple[str, str, str]]:
        """The table's text, row by row (for tests)."""
        return [
            tuple(self.tree.topLevelItem(i).text(c) for c in range(3))
            for i in range(self.tree.topLevelItemCount())
        ]
