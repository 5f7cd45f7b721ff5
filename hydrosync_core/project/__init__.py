"""HDF5 project file: schema, atomic store, migrations, model.

The public names below are loaded on first use: the submodules that need no HDF5
(``schema``, ``validate``, ``vessel`` checks…) are imported by commands that never open a
project (``hydrosync latency`` from CSV files checks its lines with ``validate``), and the
model imports h5py (about 0.1 s).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from hydrosync_core.project.model import NodeInfo, Project, default_vessel

__all__ = ["NodeInfo", "Project", "default_vessel"]


def __getattr__(name: str):
    if name in __all__:
        return getattr(importlib.import_module(f"{__name__}.model"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
