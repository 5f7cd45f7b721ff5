"""Base class of every plugin panel: project binding and one worker at a time.

A panel is a thin view over a core method. It gets the project through
:meth:`set_project`, starts its work through :meth:`start_work` (which cancels any
previous task of the same panel) and tells the shell about progress and results through
its signals; the main window shows progress in the status bar and offers Cancel.

Completion: *on_finished(result)* runs on the GUI thread when the task returns; whatever
the outcome (finished, failed, cancelled) :meth:`work_done` runs afterwards — override it
to re-enable buttons instead of reaching into the worker's signals.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from PySide6.QtCore import Signal
from PySide6.QtWidgets import QWidget

from hydrosync_core.plugins.spec import PluginSpec
from hydrosync_core.project import Project
from hydrosync_gui.workers import Worker, start


class PluginPanel(QWidget):
    """Subclass and implement :meth:`refresh` (redraw from ``self.project``)."""

    sig_status = Signal(str)  # one-line message for the status bar / log
    sig_progress = Signal(float, str)  # fraction 0..1 and message
    sig_busy = Signal(bool)  # a task started (True) or ended (False)
    sig_project_modified = Signal()  # results were written into the project

    def __init__(self, spec: PluginSpec | None = None, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.spec = spec
        self.project: Project | None = None
        self.worker: Worker | None = None

    # -------------------------------------------------------------- project
    def set_project(self, project: Project | None) -> None:
        """Bind *project* (or None) and redraw."""
        self.project = project
        self.refresh()

    def refresh(self) -> None:  # pragma: no cover - overridden
        """Redraw everything from ``self.project`` (results already stored there)."""

    # --------------------------------------------------------------- worker
    @property
    def busy(self) -> bool:
        return self.worker is not None and not self.worker.finished_event.is_set()

    def start_work(
        self,
        fn: Callable[[Callable, Any], Any],
        on_finished: Callable[[Any], None],
        label: str = "",
    ) -> Worker:
        """Run ``fn(progress, cancel)`` off the GUI thread; call *on_finished(result)* after.

        A task already running in this panel is cancelled first.
        """
        self.cancel_work()
        worker = Worker(fn)
        worker.signals.sig_progress.connect(self.sig_progress)
        worker.signals.sig_finished.connect(on_finished)
        worker.signals.sig_failed.connect(
            lambda msg: self.sig_status.emit(f"{label} failed: {msg}")
        )
        worker.signals.sig_cancelled.connect(lambda: self.sig_status.emit(f"{label} cancelled"))
        worker.signals.sig_done.connect(self._on_worker_done)
        self.worker = worker
        self.sig_busy.emit(True)
        self.sig_status.emit(f"{label} started")
        return start(worker)

    def _on_worker_done(self) -> None:
        self.sig_busy.emit(False)
        self.work_done()

    def work_done(self) -> None:
        """Called on the GUI thread after every task, whatever its outcome."""

    def cancel_work(self) -> None:
        if self.worker is not None:
            self.worker.cancel()

    def wait_idle(self, timeout: float = 30.0) -> bool:
        """Block until the current task ends (for tests and shutdown)."""
        return self.worker is None or self.worker.finished_event.wait(timeout)
