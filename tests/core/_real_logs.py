"""Shared helpers for the real-log importer tests (read-only corpus, never copied)."""

from __future__ import annotations

import threading
from pathlib import Path

import pytest

from hydrosync_core.datasets import real_logs_dir

REAL = real_logs_dir()
REAL_LOGS = REAL
needs_real = needs_real_logs = pytest.mark.skipif(
    not (REAL / "README.md").exists(), reason=f"real-log corpus {REAL} not present"
)


def real(name: str) -> Path:
    return REAL / name


def all_files(*folders: str) -> list[Path]:
    if not REAL.exists():
        return []
    return sorted(p for f in folders for p in (REAL / f).glob("*") if p.is_file())


def run_with_timeout(func, timeout: float = 10.0):
    """Run *func* in a daemon thread; fail the test if it takes longer than *timeout*."""
    box: dict = {}

    def target():
        try:
            box["value"] = func()
        except BaseException as exc:  # handed back to the test thread
            box["error"] = exc

    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    thread.join(timeout)
    if thread.is_alive():
        pytest.fail(f"import did not finish within {timeout} s")
    if "error" in box:
        raise box["error"]
    return box.get("value")
