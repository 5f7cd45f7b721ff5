"""Where the public reference data sets live (read in place, never copied).

The checkout sits beside a ``shared/`` folder (``../shared/data`` from the repository
root); ``HYDROSYNC_SHARED_DATA`` overrides that. Tests and benchmarks skip with a clear
reason when a data set is absent.
"""

from __future__ import annotations

import os
from pathlib import Path


def shared_data_dir() -> Path:
    """Folder holding ``real-logs/``, ``kfgins/`` … (may not exist)."""
    override = os.environ.get("HYDROSYNC_SHARED_DATA")
    if override:
        return Path(override)
    return Path(__file__).resolve().parents[1].parent / "shared" / "data"


def real_logs_dir() -> Path:
    """The real device-log corpus (``shared/data/real-logs``)."""
    return shared_data_dir() / "real-logs"
