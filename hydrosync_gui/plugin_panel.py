"""Base class of every plugin panel: project binding and one worker at a time.

A panel is a thin view over a core method. It gets the project through
:meth:`set_project`, starts its work through :meth:`start_work` (which cancels any
previous task of the same panel) and tells the shell about progress and results through
its signals; the main window shows progress in the status bar and offers Cancel.

Completion: *on_finished(result)* runs on the GUI thread when the task returns; whatever
the outcome (finished, failed, cancelled) :meth:`work_done` runs afterwards — override it
to re-enable buttons instead of reaching into the worker's signals.

Side tasks (:meth:`start_side_task`): short reads a view needs (e.g. the raw data of one
line's plot) run beside the main task, without progress or busy state; their results reach
the panel only while it exists, so closing it meanwhile is harmless.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from PySide6.QtCore import Signal
from PySide6.QtWidgets import QLabel, QWidget

from hydrosync_core.plugins.spec import PluginSpec
from hydrosync_core.project import Project
from hydrosync_gui.workers import Worker, start

_SIDE_TASKS: set[Worker] = set()
"""Side tasks started and not yet pruned: the pool does not own its workers, and a side
task may outlive the panel that started it."""


def _wait_side_tasks_on_quit() -> None:
    """Once: when the application quits, let running side tasks end (a few seconds at
    most) before Qt deletes their signal objects under them."""
    from PySide6.QtCore import QCoreApplication

    app = QCoreApplication.instance()
    if app is None or app.property("hydrosync_side_tasks_hooked"):
        return
    app.setProperty("hydrosync_side_tasks_hooked", True)

    def wait() -> None:
        for worker in list(_SIDE_TASKS):
            worker.cancel()
            worker.finished_event.wait(10.0)

    app.aboutToQuit.connect(wait)


STALE_STYLE = ("QLabel { background: #f8d7da; border: 1px solid #c0392b; border-radius: 3px;"
               " color: #6e1a12; padding: 6px; }")


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
        # Shown above the panel by the tab holding it (PluginTabs) when the stored result
        # no longer matches its inputs.
        self.stale_banner = QLabel()
        self.stale_banner.setObjectName("stale_banner")
        self.stale_banner.setWordWrap(True)
        self.stale_banner.setStyleSheet(STALE_STYLE)
        self.stale_banner.setVisible(False)

    # -------------------------------------------------------------- project
    def set_project(self, project: Project | None) -> None:
        """Bind *project* (or None) and redraw."""
        self.project = project
        self.refresh()
        self.update_stale_banner()

    def stale_reasons(self) -> list[str]:
        """Why the stored result of this analysis is out of date (empty if it is not)."""
        if self.project is None or self.spec is None:
            return []
        from hydrosync_core.provenance import stale_reasons

        return stale_reasons(self.project, f"results/{self.spec.id}")

    def update_stale_banner(self) -> None:
        """Show or hide the "out of date" banner from the project's current state."""
        reasons = self.stale_reasons()
        self.stale_banner.setVisible(bool(reasons))
        if reasons:
            self.stale_banner.setText(
                "<b>Out of date</b>: the results shown no longer match the project — "
                + "; ".join(reasons[:4]) + ("; …" if len(reasons) > 4 else "")
                + ". Run the analysis again before using them.")

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
        self.update_stale_banner()

    def work_done(self) -> None:
        """Called on the GUI thread after every task, whatever its outcome."""

    def cancel_work(self) -> None:
        if self.worker is not None:
            self.worker.cancel()

    def start_side_task(
        self,
        fn: Callable[[Callable, Any], Any],
        on_finished: Callable[[Any], None],
        on_failed: Callable[[str], None] | None = None,
    ) -> Worker:
        """Run ``fn(progress, cancel)`` off the GUI thread beside the main task.

        *on_finished(result)* (or *on_failed(one_line_message)*) runs on the GUI thread,
        and only while this panel exists: pass bound methods of the panel, which Qt
        disconnects when the panel is deleted. Progress is not shown and the task is not
        cancelled by :meth:`start_work`.
        """
        for done in [w for w in _SIDE_TASKS if w.finished_event.is_set()]:
            _SIDE_TASKS.discard(done)
        _wait_side_tasks_on_quit()
        worker = Worker(fn)
        worker.signals.sig_finished.connect(on_finished)
        if on_failed is not None:
            worker.signals.sig_failed.connect(on_failed)
        _SIDE_TASKS.add(worker)
        return start(worker)

    def wait_idle(self, timeout: float = 30.0) -> bool:
        """Block until the current task ends (for tests and shutdown)."""
        return self.worker is None or self.worker.finished_event.wait(timeout)
