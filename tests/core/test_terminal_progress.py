"""CLI progress: updating line on a terminal, a line every few seconds otherwise."""

from __future__ import annotations

import io
import os

from hydrosync_core.cli import terminal
from hydrosync_core.cli.terminal import TerminalProgress


class FakeClock:
    def __init__(self) -> None:
        self.now = 100.0

    def __call__(self) -> float:
        return self.now


def test_lines_every_few_seconds_when_not_a_terminal(monkeypatch):
    clock = FakeClock()
    monkeypatch.setattr(terminal.time, "monotonic", clock)
    stream = io.StringIO()
    progress = TerminalProgress("latency", stream=stream)
    assert progress.mode == "lines"
    for i in range(120):  # 0.1 s apart: 12 s in all
        clock.now += 0.1
        progress(i / 120, f"line {i}")
    progress.done()
    lines = stream.getvalue().splitlines()
    assert len(lines) == 2  # after about 5 s and 10 s; nothing in the first 5 s
    assert lines[0].startswith("[ 4") and "latency: line 49" in lines[0] or \
        "latency: line 50" in lines[0]


def test_updating_line_on_a_terminal(monkeypatch):
    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    monkeypatch.setattr(terminal.shutil, "get_terminal_size",
                        lambda default: os.terminal_size((60, 20)))
    stream = Tty()
    progress = TerminalProgress("pool", stream=stream)
    progress(0.5, "x" * 200)
    assert stream.getvalue().startswith("\r[ 50.0%] pool: xxx")
    assert len(stream.getvalue()) == 1 + 59  # fitted to the terminal width
    progress.done()
    assert "\n" not in stream.getvalue()


def test_mode_from_environment(monkeypatch):
    monkeypatch.setenv("HYDROSYNC_PROGRESS", "off")
    progress = TerminalProgress("x", stream=io.StringIO())
    assert not progress.enabled
