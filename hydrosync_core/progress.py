"""Progress and cancel protocols handed to every long method.

A *progress* callback takes a fraction in [0, 1] and a short message. A *cancel* token
is anything with ``is_set() -> bool`` (``threading.Event`` qualifies). Core methods call
:func:`check_cancel` between chunks of work so that a GUI worker or Ctrl-C stops them.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol

from hydrosync_core.errors import Cancelled


class ProgressCallback(Protocol):
    def __call__(self, fraction: float, message: str = "") -> None: ...


class CancelToken(Protocol):
    def is_set(self) -> bool: ...


def report(progress: ProgressCallback | None, fraction: float, message: str = "") -> None:
    """Call *progress* if given, clipping *fraction* to [0, 1]."""
    if progress is not None:
        progress(min(1.0, max(0.0, float(fraction))), message)


def check_cancel(cancel: CancelToken | None) -> None:
    """Raise :class:`Cancelled` if *cancel* is set."""
    if cancel is not None and cancel.is_set():
        raise Cancelled("cancelled by user")


def sub_progress(
    progress: ProgressCallback | None, start: float, stop: float
) -> Callable[[float, str], None] | None:
    """Map a child task's 0..1 progress onto the parent's ``start..stop`` interval."""
    if progress is None:
        return None

    def child(fraction: float, message: str = "") -> None:
        report(progress, start + (stop - start) * fraction, message)

    return child
