"""Record what the NMEA log importers report on the real-log corpus (golden file).

Run once with a known-good importer; ``tests/core/test_log_stream_corpus.py`` then checks
that every later importer gives the same counts, warnings and column summaries. Usage:
``python scripts/log_import_golden.py > tests/core/data/real_log_imports.json``.
"""

from __future__ import annotations

import json
import sys

import numpy as np

from hydrosync_core.datasets import real_logs_dir
from hydrosync_core.errors import InputError
from hydrosync_core.importers.log_import import import_attitude_log, import_gnss_log

CASES = (
    ("gnss", {}),
    ("gnss", {"time_source": "sentence"}),
    ("gnss", {"empty_geoid": "skip"}),
    ("attitude", {"heave_positive": "up"}),
    ("attitude", {"heave_positive": "down", "time_source": "sentence"}),
)


def summary(columns: dict) -> dict:
    """Length and float sums of every column (NaN-aware), enough to spot a changed value."""
    out = {}
    for name, values in columns.items():
        v = np.asarray(values, dtype=np.float64)
        finite = np.isfinite(v)
        f = v[finite]
        out[name] = [int(v.size), int(finite.sum()), float(f.sum()) if f.size else 0.0,
                     float(f[0]) if f.size else None, float(f[-1]) if f.size else None]
    return out


def main() -> None:
    root = real_logs_dir()
    files = sorted(p for f in ("nmea", "tagged", "motion") for p in (root / f).glob("*")
                   if p.is_file())
    result = {}
    for path in files:
        rel = str(path.relative_to(root))
        for what, options in CASES:
            key = f"{rel}|{what}|{json.dumps(options, sort_keys=True)}"
            func = import_gnss_log if what == "gnss" else import_attitude_log
            try:
                columns, rep = func(path, **options)
            except InputError as exc:
                result[key] = {"error": str(exc).replace(str(root), "<root>")}
                continue
            doc = rep.to_dict()
            doc["file"] = rel
            result[key] = {"report": doc, "columns": summary(columns)}
    json.dump(result, sys.stdout, indent=1, sort_keys=True)


if __name__ == "__main__":
    main()
