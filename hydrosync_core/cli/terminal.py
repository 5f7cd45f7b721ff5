"""Terminal progress display for long CLI commands (stderr, one updating line)."""

from __future__ import annotations

import sys
import time


class TerminalProgress:
    """A progress callback printing ``[ 42%] message`` on stderr, throttled to 10 Hz."""

    def __init__(self, label: str = "", stream=None, enabled: bool | None = None) -> None:
        self.label = label
        self.stream = stream or sys.stderr
        self.enabled = self.stream.isatty() if enabled is None else enabled
        self._last = 0.0
        self._last_message = ""

    def __call__(self, fraction: float, message: str = "") -> None:
        now = time.monotonic()
        if not self.enabled:
            return
        if fraction < 1.0 and now - self._last < 0.1 and message == self._last_message:
            return
        self._last, self._last_message = now, message
        text = f"\r[{fraction * 100:5.1f}%] {self.label}{': ' if self.label else ''}{message}"
        self.stream.write(text[:120].ljust(120))
        self.stream.flush()

    def done(self) -> None:
        if self.enabled:
            self.stream.write("\r" + " " * 120 + "\r")
            self.stream.flush()
