"""Heave statistics of each survey line, and the project entry point that stores them.

Inputs: ``raw/attitude`` (``time`` s, ``heave`` m positive up) and ``raw/lines``
(``name``, ``start``, ``end`` s). Stored under ``/results/heave_stats``: the parameters
(JSON), the provenance record (``hydrosync_core.provenance.record``: input hashes,
``params_schema_version``, ``software_version``, ``run_utc``), and the table
``lines`` with ``name``, ``samples``, ``rms_m``, ``significant_m`` (4 × standard
deviation, m) and ``peak_period_s`` (NaN when no peak lies in the period band).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.progress import check_cancel, report
from hydrosync_core.provenance import record
from hydrosync_heave_stats.params import HeaveStatsParams

RESULT = "results/heave_stats"
INPUTS = ("raw/attitude", "raw/lines")
VERSION = "1.0.0"  # the spec's version, stored with each result


def line_stats(time: np.ndarray, heave: np.ndarray, params: HeaveStatsParams) -> dict:
    """RMS (m), significant heave 4σ (m) and the dominant period (s) of one line's heave."""
    out = {"samples": int(time.size), "rms_m": np.nan, "significant_m": np.nan,
           "peak_period_s": np.nan}
    if time.size < 16:
        return out
    h = heave - heave.mean()
    out["rms_m"] = float(np.sqrt(np.mean(heave**2)))
    out["significant_m"] = float(4.0 * h.std())
    # Periodogram on a regular grid at the median sampling interval.
    dt = float(np.median(np.diff(time)))
    grid = np.arange(time[0], time[-1], dt)
    spectrum = np.abs(np.fft.rfft(np.interp(grid, time, h) * np.hanning(grid.size))) ** 2
    freq = np.fft.rfftfreq(grid.size, dt)
    band = (freq >= 1.0 / params.max_period_s) & (freq <= 1.0 / params.min_period_s)
    if band.any():
        out["peak_period_s"] = float(1.0 / freq[band][np.argmax(spectrum[band])])
    return out


def run(project, params: HeaveStatsParams | Mapping | None = None, progress=None,
        cancel=None) -> dict:
    """Compute the statistics of every line and replace ``/results/heave_stats``."""
    p = params if isinstance(params, HeaveStatsParams) else HeaveStatsParams.from_dict(params)
    attitude, lines = project.get_table("raw/attitude"), project.get_table("raw/lines")
    time = np.asarray(attitude["time"], float)
    heave = np.asarray(attitude["heave"], float)
    rows = []
    names = [str(n) for n in lines["name"]]
    for i, name in enumerate(names):
        check_cancel(cancel)
        report(progress, i / max(len(names), 1), f"line {name}")
        sel = (time >= lines["start"][i] + p.skip_s) & (time <= lines["end"][i])
        rows.append(line_stats(time[sel], heave[sel], p))
    if not any(r["samples"] for r in rows):
        raise InputError("raw/lines", "no line has heave samples (check the time scales)")
    project.delete(RESULT)
    project.put_json(RESULT, p.to_dict())
    table = {"name": np.array(names, dtype=str)}
    for key in ("samples", "rms_m", "significant_m", "peak_period_s"):
        table[key] = np.array([r[key] for r in rows])
    project.put_table(f"{RESULT}/lines", table)
    # Last, so that a result is never recorded as up to date before it is complete; this
    # is what gives the panel and the report their "out of date" banner.
    record(project, RESULT, INPUTS, p, plugin_version=VERSION)
    report(progress, 1.0, "heave statistics stored")
    return table
