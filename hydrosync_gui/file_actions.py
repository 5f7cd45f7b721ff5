"""The File menu's work for :class:`~hydrosync_gui.main_window.MainWindow`.

New, Open, Open Recent, Save, Save As, Import and Export report, with the
unsaved-changes prompt in front of anything that would drop the current project. Every
step that touches the disk runs in a :class:`~hydrosync_gui.workers.Worker` through
``MainWindow.run_shell_task`` so the window never freezes; the steps that must follow it
(open after save, quit after save) are passed on as continuations.

A project another HydroSync process is writing (its write lock is held), or whose file
or folder may not be written, opens read-only: the window shows a banner saying why,
and Save becomes Save As.
"""

from __future__ import annotations

import inspect
import logging
from collections.abc import Callable
from pathlib import Path

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QFileDialog, QMessageBox

from hydrosync_core.errors import ProjectAccessError
from hydrosync_core.importers.kinds import import_file, kinds
from hydrosync_core.project import Project
from hydrosync_core.project.subtree import copy_subtree
from hydrosync_gui.dialogs import ImportDialog
from hydrosync_gui.i18n import current as current_language

log = logging.getLogger("hydrosync_gui.file")

PROJECT_FILTER = "HydroSync projects (*.h5 *.hdf5);;All files (*)"
UNTITLED = "Untitled"  # the name of a new project until it is saved under a file name


def open_for_gui(path: str) -> Project:
    """Open *path* to edit it; read-only (with the reason) when that is refused.

    Refused means another process holds the project's write lock, or the file or its
    folder may not be written: the user can still look at it and save a copy elsewhere.
    """
    try:
        return Project.open(path)
    except ProjectAccessError as exc:
        project = Project.open(path, readonly=True)
        project.readonly_reason = exc.one_line()
        return project


def _import_into_scratch(kind: str, path: str | list[str], options: dict, progress=None,
                         cancel=None):
    """Read *path* (one file, or several of one kind) into a scratch project (worker
    thread): the real one stays untouched. Device logs report progress and stop on
    *cancel*."""
    scratch = Project.new(name="import")
    accepted = {k: v for k, v in options.items() if k in kinds()[kind].options}
    return scratch, import_file(scratch, kind, path, progress=progress, cancel=cancel,
                                **accepted)


def _move_into(scratch: Project, project: Project, target: str) -> None:
    """Put what the scratch project read at *target* into *project*: a streamed table as
    it is (its columns stay in their file), anything else copied."""
    from hydrosync_core.project.table_files import adopt_table, is_file_table

    if is_file_table(scratch, target):
        adopt_table(scratch, project, target)
    else:
        copy_subtree(scratch, project, target)


class FileActions:
    """Mixin of :class:`MainWindow` holding the File menu slots."""

    # ------------------------------------------------------ unsaved changes
    def maybe_save(self, then: Callable[[], None]) -> None:
        """Run *then* once the current project may be dropped.

        If the project has unsaved changes, ask Save / Discard / Cancel: Save saves (in a
        worker) and runs *then* after a successful save; Discard runs *then*; Cancel
        does nothing.
        """
        if self.project is None or not self.project.dirty:
            then()
            return
        answer = QMessageBox.question(
            self, "Unsaved changes",
            f"The project '{self.project.name}' has unsaved changes. Save them first?",
            QMessageBox.StandardButton.Save | QMessageBox.StandardButton.Discard
            | QMessageBox.StandardButton.Cancel,
            QMessageBox.StandardButton.Save,
        )
        if answer == QMessageBox.StandardButton.Save:
            self.save_project(then=then)
        elif answer == QMessageBox.StandardButton.Discard:
            then()

    # ----------------------------------------------------------- new / open
    def _on_new(self) -> None:
        if self.ensure_idle():
            self.maybe_save(self.new_project)

    def new_project(self) -> None:
        """Replace the current project by an empty, unsaved one."""
        project = Project.new(UNTITLED)
        project.dirty = False  # nothing to lose yet
        self.set_project(project)
        log.info("new project")

    def _on_open(self) -> None:
        if self.ensure_idle():
            self.maybe_save(self._choose_and_open)

    def _choose_and_open(self) -> None:
        path, _ = QFileDialog.getOpenFileName(self, "Open project", self.last_dir(),
                                              PROJECT_FILTER)
        if path:
            self.open_project(path)

    def _on_open_recent(self, path: str) -> None:
        if self.ensure_idle():
            self.maybe_save(lambda: self.open_project(path))

    def open_project(self, path: str) -> None:
        """Open *path* in a worker; on success it becomes the current project."""

        def opened(project: Project) -> None:
            self.set_project(project)
            self.recent.add(path)
            self.remember_dir(path)
            for notice in project.notices:
                log.warning("%s", notice)
            if project.readonly:
                log.warning("opened %s read-only: %s", path, project.readonly_reason)
                self.statusBar().showMessage(f"Opened {path} read-only", 8000)
                return
            log.info("opened %s", path)
            self.statusBar().showMessage(f"Opened {path}", 5000)

        def failed(message: str) -> None:
            if not Path(path).exists():
                self.recent.remove(path)
            self.show_error("Cannot open project", message)

        self.run_shell_task(f"Opening {Path(path).name}", lambda p, c: open_for_gui(path),
                            opened, failed)

    # ---------------------------------------------------------------- save
    def _on_save(self) -> None:
        if self.ensure_idle():
            self.save_project()

    def _on_save_as(self) -> None:
        if self.ensure_idle():
            self.save_project(ask=True)

    def save_project(self, then: Callable[[], None] | None = None, ask: bool = False) -> None:
        """Save (atomically, in a worker); ask for a file name if needed; then run *then*.

        On failure the project stays in memory, still marked modified, and the error is
        shown; *then* is not run.
        """
        project = self.project
        if project is None:
            return
        target = project.path
        if project.readonly and not ask:
            QMessageBox.information(
                self, "Project is read-only",
                f"{project.readonly_reason}.\n\nChoose another file name to save your "
                "changes.")
            ask = True
        if ask or target is None:
            start = str(Path(self.last_dir()) / f"{project.name or 'project'}.h5")
            chosen, _ = QFileDialog.getSaveFileName(self, "Save project as", start,
                                                    PROJECT_FILTER)
            if not chosen:
                return
            target = Path(chosen)
            if not target.suffix:
                target = target.with_suffix(".h5")
        old_name = project.name
        if old_name in ("", UNTITLED):
            # The placeholder name would go on the window title and the report cover:
            # a project saved as "harbour-2026-11.h5" is called "harbour-2026-11".
            project.set_attrs("", name=Path(target).stem)

        def saved(path: Path) -> None:
            self.update_banner()
            self.recent.add(path)
            self.remember_dir(path)
            self.browser.refresh()
            self.update_title()
            log.info("saved %s", path)
            self.statusBar().showMessage(f"Saved {path}", 5000)
            if then is not None:
                then()

        def failed(message: str) -> None:
            if project.name != old_name:
                project.set_attrs("", name=old_name)
            self.update_title()
            self.show_error("Save failed", f"{message}\n\nThe project is still open and "
                            "unchanged in memory; save it somewhere else.")

        self.run_shell_task(f"Saving {Path(target).name}",
                            lambda p, c: project.save(target), saved, failed)

    # --------------------------------------------------------------- import
    def _on_import(self) -> None:
        if not self.ensure_idle():
            return
        choices = ImportDialog.ask(self, kinds(), self.last_dir())
        if choices:
            self.import_all(list(choices))

    def import_all(self, choices: list[tuple[str, str | list[str], dict]]) -> None:
        """Import each ``(kind, path(s), options)`` of *choices* in turn (the Import
        dialog's list); a failure or Cancel stops the ones after it."""
        if choices:
            first, rest = choices[0], choices[1:]
            self.import_data(*first, then=lambda: self.import_all(rest))

    def import_data(self, kind: str, path: str | list[str], options: dict | None = None,
                    then: Callable[[], None] | None = None) -> None:
        """Import *path* (a file, or several of one kind) as *kind* (a key of ``KINDS``) in
        a worker, with progress and Cancel.

        *options*: ``{"heave_positive": "up" | "down"}`` for a motion log. *then* runs
        after a successful import.

        The file is read into a scratch project first, so a bad file (``InputError``) is
        reported as its one-line message and leaves the current project untouched.
        """
        project = self.project
        if project is None:
            return

        def imported(result) -> None:
            scratch, message = result
            _move_into(scratch, project, kinds()[kind].target)
            scratch.close()
            self.remember_dir(path if isinstance(path, str) else path[0])
            self.browser.refresh()
            self.host.refresh()
            self.update_title()
            log.info("imported %s", message)
            self.statusBar().showMessage(f"Imported {message}", 8000)
            if then is not None:
                # After the worker's "done" has unlocked the window: the next import
                # must find it idle.
                QTimer.singleShot(0, then)

        name = Path(path).name if isinstance(path, str) else f"{len(path)} files"
        self.run_shell_task(f"Importing {name}",
                            lambda p, c: _import_into_scratch(kind, path, dict(options or {}),
                                                              p, c),
                            imported,
                            lambda msg: self.show_error("Import failed", msg),
                            cancellable=True)

    # --------------------------------------------------------------- report
    def _on_export_report(self) -> None:
        if not self.ensure_idle() or self.project is None:
            return
        try:
            from hydrosync_core.report import build_report
        except ImportError as exc:
            self.show_error(
                "Report not available",
                "The PDF report is not available in this installation: "
                f"hydrosync_core.report.build_report cannot be imported ({exc}).",
                level=logging.WARNING,
            )
            return
        start = str(Path(self.last_dir()) / f"{self.project.name or 'report'}.pdf")
        path, _ = QFileDialog.getSaveFileName(self, "Export report", start, "PDF (*.pdf)")
        if path:
            self.export_report(path, build_report)

    def export_report(self, path: str, build_report: Callable) -> None:
        """Run ``build_report(project, path[, progress, cancel, lang])`` in a worker."""
        project = self.project
        accepted = inspect.signature(build_report).parameters
        cancellable = "cancel" in accepted
        language = current_language()

        def work(progress, cancel):
            kwargs = {}
            if "progress" in accepted:
                kwargs["progress"] = progress
            if cancellable:
                kwargs["cancel"] = cancel
            if "lang" in accepted:  # the report follows the workbench's language
                kwargs["lang"] = language
            return build_report(project, path, **kwargs)

        def done(_result) -> None:
            self.remember_dir(path)
            log.info("report written to %s", path)
            self.statusBar().showMessage(f"Report written to {path}", 8000)

        self.run_shell_task("Exporting report", work, done,
                            lambda msg: self.show_error("Report failed", msg),
                            cancellable=cancellable)
