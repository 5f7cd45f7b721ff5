"""``attitude.csv`` and ``stats.json``: the command's outputs (docs/formats.md)."""

from __future__ import annotations

import os

import numpy as np

from hydrosync_core.atomic import write_json_atomic, write_text_atomic
from hydrosync_core.jsonsafe import jsonable
from hydrosync_core.methods.gnss_attitude.pipeline import ArraySolution

COLUMNS = ("time", "heading", "pitch", "roll", "sd_heading", "sd_pitch", "sd_roll",
           "method", "n_antennas")


def write_attitude_csv(path: str | os.PathLike, sol: ArraySolution, method: str) -> int:
    """One row per solved epoch of *method*: time (GPS TOW, s), angles and 1σ (deg).

    Returns the number of rows written (atomically).
    """
    m = sol.methods[method]
    rows = np.flatnonzero(np.isfinite(m.angles_deg[:, 0]))

    def writer(fh) -> None:
        fh.write(",".join(COLUMNS) + "\n")
        for i in rows:
            a, s = m.angles_deg[i], m.std_deg[i]
            fh.write(f"{sol.time[i]:.3f},{a[0]:.6f},{a[1]:.6f},{a[2]:.6f},"
                     f"{s[0]:.6f},{s[1]:.6f},{s[2]:.6f},{method},{int(sol.n_antennas[i])}\n")

    write_text_atomic(path, writer)
    return int(rows.size)


def stats_document(sol: ArraySolution, stats: dict, predicted: dict, params) -> dict:
    """The ``--json`` document: counts, statistics per method, prediction, parameters."""
    return jsonable({"method": params.method, "antennas": sol.names,
                      "epochs": sol.counts["epochs"], "solved": sol.counts["solved"],
                      "counts": sol.counts, "statistics": stats,
                      "predicted_level_deg": predicted,
                      "array_llh": list(sol.array_llh), "params": params.to_dict()})


def write_stats_json(path: str | os.PathLike, document: dict) -> None:
    write_json_atomic(path, document)
