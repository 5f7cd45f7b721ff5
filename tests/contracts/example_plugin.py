"""Load the example third-party analysis (``examples/heave_stats``) as discovery would.

An installed package is found through its ``hydrosync.plugins`` entry point; the tests
put the example's folder on ``sys.path`` and build the same :class:`Discovered` record,
so the contract tests run on it without installing anything into the environment.
"""

from __future__ import annotations

import sys
from pathlib import Path

from hydrosync_core.plugins.registry import Discovered, check_spec

EXAMPLE_DIR = Path(__file__).resolve().parents[2] / "examples" / "heave_stats"
ENTRY_POINT = "hydrosync_heave_stats:SPEC"  # as in examples/heave_stats/pyproject.toml


def example_discovered() -> Discovered:
    if str(EXAMPLE_DIR) not in sys.path:
        sys.path.insert(0, str(EXAMPLE_DIR))
    try:
        from hydrosync_core.plugins.spec import load_object

        spec = check_spec(load_object(ENTRY_POINT), ENTRY_POINT)
        return Discovered("heave_stats", ENTRY_POINT, spec, None)
    except Exception as exc:  # reported by the contract tests like a broken plugin
        return Discovered("heave_stats", ENTRY_POINT, None, f"{type(exc).__name__}: {exc}")
