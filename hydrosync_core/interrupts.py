"""Ctrl-C that tells the truth: deferred inside critical sections, completed writes recorded.

The command line installs :func:`handle_sigint` (see :mod:`hydrosync_core.cli`). Inside
:func:`critical` — the rename that publishes a file and the bookkeeping right after it —
a Ctrl-C is held back and raised as ``KeyboardInterrupt`` when the section ends, so a
file is either published *and recorded* in :data:`completed`, or not published at all.
The CLI then says which files were saved before the interrupt.

Without the handler (the GUI, tests) :func:`critical` costs nothing and changes nothing.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
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


def install() -> bool:
    """Install :func:`handle_sigint` (main thread only); return True if installed."""
    if threading.current_thread() is not threading.main_thread():
        return False
    signal.signal(signal.SIGINT, handle_sigint)
    return True


def note_completed(path) -> None:
    """Record that *path* was written for good (called inside the critical section)."""
    completed.append(str(path))


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
