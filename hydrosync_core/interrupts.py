"""Ctrl-C that tells the truth: deferred inside critical sections, completed writes recorded.

The command line installs :func:`handle_sigint` (see :mod:`hydrosync_core.cli`). Inside
:func:`critical` — the rename that publishes a file and the bookkeeping right after it —
a Ctrl-C is held back and raised as ``KeyboardInterrupt`` when the section ends, so a
file is either published *and recorded* in :data:`completed`, or not published at all.
The CLI then says which files were saved before the interrupt.

Without the handler (the GUI, tests) :func:`critical` costs nothing and changes nothing.
"""

from __future__ import annotations

import _thread
import signal
import sys
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager

completed: list[str] = []
"""Files published (saved) by this process, in order, for the interrupt message."""

_state = {"depth": 0, "pending": False, "interrupted": False}


def interrupted() -> bool:
    """True once a Ctrl-C arrived (even if a library turned it into another exception)."""
    return bool(_state["interrupted"])


def reset() -> None:
    """Forget earlier interrupts and completed files (one CLI command = one record)."""
    completed.clear()
    _state.update(depth=0, pending=False, interrupted=False)


def handle_sigint(signum=None, frame=None) -> None:
    """SIGINT handler: raise ``KeyboardInterrupt`` now, or at the end of a critical section."""
    _state["interrupted"] = True
    if _state["depth"] > 0:
        _state["pending"] = True
        return
    raise KeyboardInterrupt


def install() -> Callable[[], None]:
    """Install :func:`handle_sigint` (main thread only); return a function undoing it.

    A ``KeyboardInterrupt`` raised where Python cannot propagate it (inside a
    ``__del__`` or a weakref callback run by the garbage collector) would be printed as
    "Exception ignored in …" and lost: the unraisable hook installed here swallows that
    print and delivers the interrupt again, so it surfaces in ordinary code.
    """
    if threading.current_thread() is not threading.main_thread():
        return lambda: None
    previous_handler = signal.getsignal(signal.SIGINT)
    previous_hook = sys.unraisablehook

    def hook(info) -> None:
        if info.exc_type is not None and issubclass(info.exc_type, KeyboardInterrupt):
            # Deliver it again a moment later, from another thread, so that it is raised
            # in ordinary code rather than here (where it would be lost once more).
            timer = threading.Timer(0.01, _thread.interrupt_main, (signal.SIGINT,))
            timer.daemon = True
            timer.start()
            return
        previous_hook(info)

    signal.signal(signal.SIGINT, handle_sigint)
    sys.unraisablehook = hook

    def undo() -> None:
        if sys.unraisablehook is hook:
            sys.unraisablehook = previous_hook
        if previous_handler is not None:
            signal.signal(signal.SIGINT, previous_handler)

    return undo


def note_completed(path) -> None:
    """Record that *path* was written for good (called inside the critical section)."""
    completed.append(str(path))


def pending() -> bool:
    """True if a Ctrl-C was held back and not raised yet (see :func:`deferred`)."""
    return bool(_state["pending"])


@contextmanager
def deferred() -> Iterator[None]:
    """Hold Ctrl-C back while the body runs and leave it pending (never raises).

    For clean-up code that must not be cut in half and may run where an exception
    cannot go (a ``weakref.finalize`` callback, releasing a lock): the command line
    reports the pending interrupt when the command returns.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _state["depth"] += 1
    try:
        yield
    finally:
        _state["depth"] -= 1


@contextmanager
def critical() -> Iterator[None]:
    """Hold Ctrl-C back while the body runs (main thread); re-raise it afterwards."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    _state["depth"] += 1
    try:
        yield
    finally:
        _state["depth"] -= 1
        if _state["depth"] == 0 and _state["pending"]:
            _state["pending"] = False
            raise KeyboardInterrupt
