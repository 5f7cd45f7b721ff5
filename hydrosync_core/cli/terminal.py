"""Progress display for long CLI commands, on stderr.

On a terminal: one line updated in place (at most 10 times a second), as wide as the
terminal. Otherwise (output piped to a file, CI logs, batch jobs): one plain line every few
seconds, so a long run still shows that it is alive and where it is, without filling the
log. ``HYDROSYNC_PROGRESS=lines|tty|off`` overrides the choice.
"""

from __future__ import annotations

import os
import shutil
import sys
import time

LINE_INTERVAL_S = 5.0


class TerminalProgress:
    """A progress callback ``(fraction, message)`` printing ``[ 42%] label: message``."""

    def __init__(self, label: str = "", stream=None, enabled: bool | None = None,
                 mode: str | None = None) -> None:
        self.label = label
        self.stream = stream or sys.stderr
        if mode is None:
            mode = os.environ.get("HYDROSYNC_PROGRESS") or (
                "tty" if _isatty(self.stream) else "lines")
        if enabled is not None:
            mode = ("tty" if _isatty(self.stream) else "lines") if enabled else "off"
        self.mode = mode if mode in ("tty", "lines", "off") else "lines"
        self.enabled = self.mode != "off"
        self._start = time.monotonic()
        self._last = 0.0
        self._last_message = ""
        self._shown = False

    def _width(self) -> int:
        return max(40, shutil.get_terminal_size((100, 24)).columns - 1)

    def _text(self, fraction: float, message: str) -> str:
        return f"[{fraction * 100:5.1f}%] {self.label}{': ' if self.label else ''}{message}"

    def __call__(self, fraction: float, message: str = "") -> None:
        if not self.enabled:
            return
        now = time.monotonic()
        if self.mode == "tty":
            if fraction < 1.0 and now - self._last < 0.1 and message == self._last_message:
                return
            width = self._width()
            self.stream.write("\r" + self._text(fraction, message)[:width].ljust(width))
        else:
            # A short command prints nothing; a long one says where it is every few seconds.
            if now - (self._last if self._shown else self._start) < LINE_INTERVAL_S:
                return
            self.stream.write(self._text(fraction, message) + "\n")
        self._last, self._last_message, self._shown = now, message, True
        self.stream.flush()

    def done(self) -> None:
        if self.mode == "tty" and self._shown:
            self.stream.write("\r" + " " * self._width() + "\r")
            self.stream.flush()


def _isatty(stream) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False
