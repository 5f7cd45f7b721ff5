"""Dialogs of the shell: File → Import… and Help → Plugins."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import (
    QComboBox,
    QDialog,
    QDialogButtonBox,
    QDoubleSpinBox,
    QFileDialog,
    QFormLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QPushButton,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core.plugins.spec import DataKind
from hydrosync_gui.import_preview import ImportPreview
from hydrosync_gui.plugin_host import PluginHost

FILE_FILTER = (
    "Data files (*.csv *.txt *.json *.ply *.las *.laz *.pos *.log *.nmea *.raw *.Raw *.RAW "
    "*.gga *.dat *.nav);;NMEA logs (*.log *.nmea *.txt *.raw *.Raw *.RAW *.gga *.dat *.nav);;"
    "RTKLIB solutions (*.pos);;CSV tables (*.csv *.txt);;Point clouds (*.ply *.las *.laz);;"
    "All files (*)"
)
"""Every extension a reader knows (the logs' ones as loggers write them), then by kind."""
ACCEPTED_SUFFIXES = frozenset(
    ext[1:].lower() for ext in FILE_FILTER.split(";;")[0].split("(")[1].rstrip(")").split())
"""``.log``, ``.raw``…: what a folder contributes."""
SEPARATOR = "; "
"""Between the files of the File field (several logs of one kind: one table)."""


def folder_files(folder: str | Path) -> list[str]:
    """Files of *folder* (not its subfolders) with an extension of ``FILE_FILTER``'s first
    group, in name order (hourly logs ``…-00.log``, ``…-01.log`` sort by hour)."""
    return sorted(str(p) for p in Path(folder).iterdir()
                  if p.is_file() and p.suffix.lower() in ACCEPTED_SUFFIXES)


def _takes(kind, option: str) -> bool:
    """Whether the kind's reader takes the import option *option* (``"heave_positive"``,
    ``"empty_geoid"``, ``"clock_offset"``): the dialog then asks for it."""
    return option in getattr(kind, "options", ())


class ImportDialog(QDialog):
    """Choose what to import: a kind (from ``KINDS``), its file(s) or a folder of them, the
    reader's options; a preview of what each file holds; several such imports in one go
    (**Add to list**)."""

    def __init__(
        self, kinds: Mapping[str, DataKind], start_dir: str = "", parent: QWidget | None = None
    ) -> None:
        super().__init__(parent)
        self.setWindowTitle("Import data")
        self.start_dir = start_dir
        self._kinds = dict(kinds)
        self._sniffed: str | None = None
        self.queue: list[tuple[str, str | list[str], dict]] = []
        self._build_choices()
        self.preview = ImportPreview()
        self.preview.sig_ready.connect(self._on_kind)
        self.guess_button = QPushButton()
        self.guess_button.setObjectName("use_guessed_kind")
        self.guess_button.setVisible(False)
        self.guess_button.clicked.connect(self._use_guess)
        self.queue_list = QListWidget()
        self.queue_list.setObjectName("import_queue")
        self.queue_list.setMaximumHeight(90)
        self.add_button = QPushButton("Add to list")
        self.add_button.setToolTip("Keep this import and choose another kind or file: OK "
                                   "imports everything listed (and the one above).")
        self.add_button.clicked.connect(self._on_add)
        self.buttons = QDialogButtonBox(
            QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel
        )
        self.buttons.accepted.connect(self.accept)
        self.buttons.rejected.connect(self.reject)
        self._lay_out()
        self.kind_box.currentIndexChanged.connect(self._on_kind)
        self.path_edit.textChanged.connect(self._on_kind)
        self._on_kind()
        self.resize(820, 560)

    def _build_choices(self) -> None:
        self.kind_box = QComboBox()
        for name, kind in self._kinds.items():
            # The description alone: it is what the catalogue translates, and the kind's
            # key is a command-line word (shown in "Add to list" and the tooltip).
            self.kind_box.addItem(kind.description, name)
            flag = name.replace("_", "-")
            self.kind_box.setItemData(self.kind_box.count() - 1,
                                      f"hydrosync import --{flag} … → /{kind.target}",
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
        # A recording's GNSS−IMU clock offset: estimated from the turns unless the user
        # knows it (the lowest value of the box stands for "not given").
        self.clock_box = QDoubleSpinBox()
        self.clock_box.setRange(-10.001, 10.0)
        self.clock_box.setDecimals(3)
        self.clock_box.setSingleStep(0.001)
        self.clock_box.setSuffix(" s")
        self.clock_box.setSpecialValueText("estimated from the turns")
        self.clock_box.setValue(self.clock_box.minimum())
        self.clock_box.setToolTip("GNSS−IMU clock offset S (s): the GNSS epoch tagged t "
                                  "happened at IMU time t + S. Applied and stored; later "
                                  "runs use it.")
        self.clock_label = QLabel("Clock offset:")
        self.path_edit = QLineEdit()
        self.path_edit.setPlaceholderText("file(s) or a folder; several logs of one kind "
                                          "(a day in hourly files) become one table")

    def _lay_out(self) -> None:
        browse = QPushButton("Browse…")
        browse.clicked.connect(self._on_browse)
        folder = QPushButton("Folder…")
        folder.setToolTip("Every file of a folder with an extension the readers accept "
                          "(hourly logs of one device).")
        folder.clicked.connect(self._on_folder)
        row = QHBoxLayout()
        row.addWidget(self.path_edit, 1)
        row.addWidget(browse)
        row.addWidget(folder)
        form = QFormLayout()
        form.setRowWrapPolicy(QFormLayout.RowWrapPolicy.DontWrapRows)
        form.addRow("Kind:", self.kind_box)
        form.addRow("Goes to:", self.target)
        form.addRow("File:", row)
        form.addRow(self.heave_label, self.heave_box)
        form.addRow(self.geoid_label, self.geoid_box)
        form.addRow(self.clock_label, self.clock_box)
        form.addRow("", self.heave_note)
        box = QGroupBox("What the files hold")
        inside = QVBoxLayout(box)
        inside.addWidget(self.preview)
        inside.addWidget(self.guess_button, 0, Qt.AlignmentFlag.AlignLeft)
        queue_row = QHBoxLayout()
        queue_row.addWidget(self.add_button, 0,
                            Qt.AlignmentFlag.AlignTop | Qt.AlignmentFlag.AlignLeft)
        queue_row.addWidget(self.queue_list, 1)
        layout = QVBoxLayout(self)
        layout.addLayout(form)
        layout.addWidget(box, 1)
        layout.addLayout(queue_row)
        layout.addWidget(self.buttons)

    # ------------------------------------------------------------- the choice
    def paths(self) -> list[str]:
        """The files of the File field (``; ``-separated when several); a folder stands
        for its files with an extension the readers accept, in name order, unless the
        kind's input is itself a folder (a recording)."""
        out = []
        kind = self._kinds.get(str(self.kind_box.currentData()))
        for item in (p.strip() for p in self.path_edit.text().split(SEPARATOR.strip())):
            if item and Path(item).is_dir() and not getattr(kind, "folder", False):
                out.extend(folder_files(item))
            elif item:
                out.append(item)
        return out

    def choice(self) -> tuple[str, str | list[str], dict]:
        """The chosen ``(kind, path or paths, options)``; options go to the kind's reader."""
        kind = str(self.kind_box.currentData())
        spec = self._kinds.get(kind)
        options = {}
        if _takes(spec, "heave_positive") and self.heave_box.currentData() is not None:
            options["heave_positive"] = self.heave_box.currentData()
        if _takes(spec, "empty_geoid"):
            options["empty_geoid"] = self.geoid_box.currentData()
        if _takes(spec, "clock_offset") and self.clock_box.value() > self.clock_box.minimum():
            options["clock_offset"] = round(self.clock_box.value(), 3)
        paths = self.paths()
        return kind, paths[0] if len(paths) == 1 else paths, options

    def choices(self) -> list[tuple[str, str | list[str], dict]]:
        """Everything to import, in order: the listed imports, then the one being edited
        (when it names a file)."""
        return self.queue + ([self.choice()] if self.paths() else [])

    @classmethod
    def ask(
        cls, parent: QWidget | None, kinds: Mapping[str, DataKind], start_dir: str = ""
    ) -> list[tuple[str, str | list[str], dict]] | None:
        """Show the dialog modally; the imports chosen, or None if cancelled."""
        dialog = cls(kinds, start_dir, parent)
        try:
            return dialog.choices() if dialog.exec() == QDialog.DialogCode.Accepted else None
        finally:
            dialog.preview.stop()
            dialog.deleteLater()

    def done(self, result: int) -> None:  # noqa: D102 (Qt API)
        self.preview.stop()
        super().done(result)

    # ------------------------------------------------------------------ slots
    def _current_ok(self) -> bool:
        kind = self._kinds.get(str(self.kind_box.currentData()))
        return bool(self.paths()) and (not _takes(kind, "heave_positive")
                                       or self.heave_box.currentData() is not None)

    @Slot()
    def _on_kind(self) -> None:
        kind = self._kinds.get(str(self.kind_box.currentData()))
        self.target.setText(f"/{kind.target}" if kind else "")
        heave = _takes(kind, "heave_positive")
        for widget in (self.heave_box, self.heave_label, self.heave_note):
            widget.setVisible(heave)
        for widget in (self.geoid_box, self.geoid_label):
            widget.setVisible(_takes(kind, "empty_geoid"))
        for widget in (self.clock_box, self.clock_label):
            widget.setVisible(_takes(kind, "clock_offset"))
        paths = self.paths()
        path = paths[0] if paths else ""
        if heave and path != self._sniffed:
            self._sniffed = path
            self._preselect_heave(path, kind)
        self.preview.show_files(paths, str(self.kind_box.currentData()))
        self.add_button.setEnabled(self._current_ok())
        ok = self.buttons.button(QDialogButtonBox.StandardButton.Ok)
        ok.setEnabled(self._current_ok() or (bool(self.queue) and not paths))
        self.queue_list.setVisible(bool(self.queue))
        self._offer_guess()
        self._fit_note()

    def _fit_note(self) -> None:
        """A wrapped label in a form gets its one-line height: give it the lines it needs
        at its width, so the heave-sign note is never clipped."""
        width = max(self.heave_note.width(), 200)
        self.heave_note.setMinimumHeight(max(self.heave_note.heightForWidth(width), 0))

    def resizeEvent(self, event) -> None:  # noqa: N802 (Qt API)
        super().resizeEvent(event)
        self._fit_note()

    def guessed_kind(self) -> str | None:
        """The one import kind every previewed log fits when the chosen kind is not among
        them (a GNSS log picked under "attitude CSV"); None otherwise."""
        logs = [p for p in self.preview.previews if p.kinds and not p.error]
        if not logs or len(logs) < len(self.preview.previews):
            return None
        common = set.intersection(*(set(p.kinds) for p in logs))
        if str(self.kind_box.currentData()) in common:
            return None
        fits = [k for k in logs[0].kinds if k in common and k in self._kinds]
        return fits[0] if len(fits) == 1 else None

    @Slot()
    def _offer_guess(self) -> None:
        kind = self.guessed_kind()
        self.guess_button.setVisible(kind is not None)
        if kind is not None:
            self.guess_button.setText(f"Import as {kind} (what the files hold)")

    @Slot()
    def _use_guess(self) -> None:
        kind = self.guessed_kind()
        if kind is not None:
            self.kind_box.setCurrentIndex(self.kind_box.findData(kind))
        self.guess_button.setVisible(False)

    @Slot()
    def _on_add(self) -> None:
        if not self._current_ok():
            return
        kind, paths, options = self.choice()
        self.queue.append((kind, paths, options))
        names = paths if isinstance(paths, list) else [paths]
        shown = Path(names[0]).name + (f" + {len(names) - 1} more" if len(names) > 1 else "")
        extra = f" (heave positive {options['heave_positive']})" if "heave_positive" in \
            options else ""
        self.queue_list.addItem(f"{kind} ← {shown}{extra}")
        self.queue_list.item(self.queue_list.count() - 1).setToolTip("\n".join(names))
        self.path_edit.clear()

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

    @Slot()
    def _on_folder(self) -> None:
        folder = QFileDialog.getExistingDirectory(self, "Import a folder", self.start_dir)
        if folder:
            self.path_edit.setText(folder)
            self.start_dir = folder


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
