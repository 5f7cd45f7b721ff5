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

FILE_FILTER = (
    "Data files (*.csv *.txt *.json *.ply *.las *.laz *.pos *.log *.nmea *.raw *.Raw *.RAW "
    "*.gga *.dat *.nav);;NMEA logs (*.log *.nmea *.txt *.raw *.Raw *.RAW *.gga *.dat *.nav);;"
    "RTKLIB solutions (*.pos);;CSV tables (*.csv *.txt);;Point clouds (*.ply *.las *.laz);;"
    "All files (*)"
)
"""Every extension a reader knows (the logs' ones as loggers write them), then by kind."""
SEPARATOR = "; "
"""Between the files of the File field (several logs of one kind: one table)."""


def _takes_geoid(kind) -> bool:
    """Whether the kind's reader takes ``empty_geoid`` (a GGA log)."""
    return "empty_geoid" in getattr(kind, "options", ())


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
        # Heave sign of a motion log: stated, never guessed (docs/formats.md, NMEA 0183).
        # The sentence found in the file preselects its documented sign; the user confirms.
        self.heave_box = QComboBox()
        self.heave_box.addItem("choose the heave sign…", None)
        self.heave_box.addItem("positive up", "up")
        self.heave_box.addItem("positive down", "down")
        self.heave_box.setToolTip("Direction of positive heave in the file. The sign documented "
                                  "for the sentence found is preselected: confirm it or change "
                                  "it if your sensor is configured otherwise.")
        self.heave_box.currentIndexChanged.connect(self._on_kind)
        self.heave_note = QLabel()
        self.heave_note.setWordWrap(True)
        self.heave_note.setObjectName("heave_note")
        self.heave_label = QLabel("Heave:")
        # The GGA warning about empty geoid separations names this choice.
        self.geoid_box = QComboBox()
        self.geoid_box.addItem("keep, separation taken as 0 (heights above the geoid)", "zero")
        self.geoid_box.addItem("skip those epochs", "skip")
        self.geoid_box.setToolTip("GGA sentences whose geoid separation field is empty: keep "
                                  "them with N = 0 (their heights are then above the geoid, "
                                  "not ellipsoidal) or leave them out.")
        self.geoid_label = QLabel("Empty geoid:")
        self.path_edit = QLineEdit()
        self.path_edit.setPlaceholderText("file(s) to import; several logs of one kind "
                                          "(a day in hourly files) become one table")
        browse = QPushButton("Browse…")
        browse.clicked.connect(self._on_browse)
        row = QHBoxLayout()
        row.addWidget(self.path_edit, 1)
        row.addWidget(browse)
        self._kinds = dict(kinds)
        self._sniffed: str | None = None
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
        form.addRow(self.geoid_label, self.geoid_box)
        form.addRow("", self.heave_note)
        layout = QVBoxLayout(self)
        layout.addLayout(form)
        layout.addWidget(self.buttons)
        self.kind_box.currentIndexChanged.connect(self._on_kind)
        self.path_edit.textChanged.connect(self._on_kind)
        self._on_kind()
        self.resize(560, self.sizeHint().height())

    def paths(self) -> list[str]:
        """The files of the File field (``; ``-separated when several)."""
        return [p.strip() for p in self.path_edit.text().split(SEPARATOR.strip()) if p.strip()]

    def choice(self) -> tuple[str, str | list[str], dict]:
        """The chosen ``(kind, path or paths, options)``; options go to the kind's reader."""
        kind = str(self.kind_box.currentData())
        options = {}
        if _takes_heave(self._kinds.get(kind)) and self.heave_box.currentData() is not None:
            options["heave_positive"] = self.heave_box.currentData()
        if _takes_geoid(self._kinds.get(kind)):
            options["empty_geoid"] = self.geoid_box.currentData()
        paths = self.paths()
        return kind, paths[0] if len(paths) == 1 else paths, options

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
        heave = _takes_heave(kind)
        for widget in (self.heave_box, self.heave_label, self.heave_note):
            widget.setVisible(heave)
        for widget in (self.geoid_box, self.geoid_label):
            widget.setVisible(_takes_geoid(kind))
        paths = self.paths()
        path = paths[0] if paths else ""
        if heave and path != self._sniffed:
            self._sniffed = path
            self._preselect_heave(path, kind)
        ok = self.buttons.button(QDialogButtonBox.StandardButton.Ok)
        ok.setEnabled(bool(path) and (not heave or self.heave_box.currentData() is not None))

    def _preselect_heave(self, path: str, kind) -> None:
        """Preselect the documented heave sign of the sentence found in *path*."""
        from hydrosync_core.importers.nmea_motion import (
            DOCUMENTED_HEAVE,
            documented_heave_sign,
            sniff_motion_source,
        )

        is_log = kind is not None and kind.store == "custom"
        source = sniff_motion_source(path) if path and is_log else None
        sign = documented_heave_sign(source) if is_log else "up"
        if not is_log:
            note = ("The attitude CSV format is heave positive up; change it only if your "
                    "file differs.")
        elif source is None:
            note = "No motion sentence recognised yet: choose the heave sign of your sensor."
        else:
            note = (f"{source} found: documented heave positive {DOCUMENTED_HEAVE[source]}. "
                    "Press OK to confirm, or change it if your sensor is set up otherwise.")
        self.heave_box.blockSignals(True)
        self.heave_box.setCurrentIndex(max(self.heave_box.findData(sign), 0))
        self.heave_box.blockSignals(False)
        self.heave_note.setText(note)

    @Slot()
    def _on_browse(self) -> None:
        start = self.paths()[0] if self.paths() else self.start_dir
        paths, _ = QFileDialog.getOpenFileNames(self, "Import files", start, FILE_FILTER)
        if paths:
            self.path_edit.setText(SEPARATOR.join(paths))
            self.start_dir = str(Path(paths[0]).parent)


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
