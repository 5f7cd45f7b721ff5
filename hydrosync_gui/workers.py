"""Running core work off the GUI thread, with progress, cancel and errors as values.

A :class:`Worker` wraps ``fn(progress, cancel) -> result``; it runs in Qt's global
thread pool and reports through signals that are delivered on the GUI thread. Progress
signals are throttled so a fast loop cannot flood the event queue.
"""

from __future__ import annotations

import threading
import time
import traceback
from collections.abc import Callable
from typing import Any

from PySide6.QtCore import QObject, QRunnable, QThreadPool, Signal

from hydrosync_core.errors import Cancelled, HydroSyncError


class WorkerSignals(QObject):
    sig_progress = Signal(float, str)
    sig_finished = Signal(object)
    sig_failed = Signal(str)
    sig_cancelled = Signal()
    sig_done = Signal()


class Worker(QRunnable):
    """Run ``fn(progress, cancel)`` in a pool thread.

    Signals (on :attr:`signals`): ``sig_progress(fraction, message)``,
    ``sig_finished(result)``, ``sig_failed(one_line_message)``, ``sig_cancelled()`` and
    finally ``sig_done()`` whatever the outcome.
    """

    def __init__(self, fn: Callable[[Callable, threading.Event], Any], min_interval: float = 0.05):
        super().__init__()
        self.setAutoDelete(False)
        self.fn = fn
        self.signals = WorkerSignals()
        self.cancel_event = threading.Event()
        self._min_interval = min_interval
        self._last_emit = 0.0
        self.finished_event = threading.Event()

    def cancel(self) -> None:
        self.cancel_event.set()

    def _progress(self, fraction: float, message: str = "") -> None:
        now = time.monotonic()
        if fraction >= 1.0 or now - self._last_emit >= self._min_interval:
            self._last_emit = now
            self.signals.sig_progress.emit(float(fraction), str(message))

    def run(self) -> None:
        try:
            result = self.fn(self._progress, self.cancel_event)
        except Cancelled:
            self.signals.sig_cancelled.emit()
        except HydroSyncError as exc:
            self.signals.sig_failed.emit(str(exc))
        except Exception as exc:  # shown to the user, never lost
            traceback.print_exc()
            self.signals.sig_failed.emit(f"{type(exc).__name__}: {exc}")
        else:
            if self.cancel_event.is_set():
                self.signals.sig_cancelled.emit()
            else:
                self.signals.sig_finished.emit(result)
        finally:
            self.finished_event.set()
            self.signals.sig_done.emit()


def start(worker: Worker) -> Worker:
    """Start *worker* in the global thread pool and return it."""
    QThreadPool.globalInstance().start(worker)
    return worker
