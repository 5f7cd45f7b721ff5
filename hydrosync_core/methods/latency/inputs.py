"""Checked inputs of the latency estimate: the tables' columns, the candidate grid, the lines.

Inputs are plain dicts of 1-D arrays as the CSV readers return them: GNSS ``time`` (s,
tags) and ``height`` (m); attitude ``time`` (s, strictly increasing), ``roll``, ``pitch``,
``heading`` (degrees) and ``heave`` (m, positive up); lines ``name``, ``start``, ``end``
(s). The lever arm is the antenna relative to the motion sensor, body FRD, metres.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import numpy as np
from numba import njit

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.timespan import span_of


@njit(cache=True, nogil=True)
def _all_finite(values) -> bool:
    """True when every value is finite, in one pass without a mask."""
    ok = True
    for i in range(values.size):
        x = values[i]
        ok &= (x - x) == 0.0  # NaN and ±inf give NaN; no branch: the loop vectorises
    return ok


@njit(cache=True, nogil=True)
def _increasing(times) -> bool:
    """True when *times* increase strictly."""
    ok = True
    for i in range(1, times.size):
        ok &= times[i] > times[i - 1]
    return ok


def _column(table: Mapping, name: str, source: str) -> np.ndarray:
    if name not in table:
        raise InputError(source, f"missing column {name}", field=name)
    values = np.asarray(table[name], dtype=float).ravel()
    # One pass without an 8 MB mask per column of a day's attitude (page faults each).
    if not _all_finite(values):
        raise InputError(source, "non-finite values", field=name)
    return values


def check_inputs(gnss: Mapping, attitude: Mapping, lever_arm) -> tuple:
    t_g, hgt = _column(gnss, "time", "gnss"), _column(gnss, "height", "gnss")
    att = {c: _column(attitude, c, "attitude") for c in ("time", "roll", "pitch", "heave")}
    if t_g.size < 2 or att["time"].size < 2:
        raise InputError("gnss" if t_g.size < 2 else "attitude", "fewer than 2 epochs")
    if not _increasing(t_g):
        raise InputError("gnss", "time tags are not strictly increasing", field="time")
    if not _increasing(att["time"]):
        raise InputError("attitude", "time tags are not strictly increasing", field="time")
    arm = np.asarray(lever_arm, dtype=float).ravel()
    if arm.size != 3 or not np.all(np.isfinite(arm)):
        raise InputError(None, "lever arm must be three finite numbers (x y z, m)",
                         field="lever_arm")
    return t_g, hgt, att, arm


def median_interval(times: np.ndarray, block: int = 4096, blocks: int = 64) -> float:
    """Median sampling interval (s) of increasing *times*.

    Long records (a day of 100 Hz attitude) use the intervals of *blocks* evenly spaced
    runs of *block* samples: the median of 8 million intervals costs more than the scan.
    """
    if times.size <= 2 * block * blocks:
        return float(np.median(np.diff(times)))
    starts = np.linspace(0, times.size - block - 1, blocks).astype(int)
    return float(np.median(np.concatenate([np.diff(times[s:s + block + 1]) for s in starts])))


def _span_text(times: np.ndarray) -> str:
    span = span_of(times)
    return span.text() if span is not None else "nothing"


@dataclasses.dataclass
class Setup:
    """Checked inputs: what every estimator starts from; *prepared* (the lines' LineData)
    is filled by :func:`first_passes`, one list per estimator."""

    t_g: np.ndarray
    hgt: np.ndarray
    att: dict
    arm: np.ndarray
    dts: np.ndarray
    g_int: float
    a_int: float
    names: list
    starts: np.ndarray
    ends: np.ndarray
    prepared: list


def set_up(gnss, attitude, lines, lever_arm, p: LatencyParams) -> Setup:
    t_g, hgt, att, arm = check_inputs(gnss, attitude, lever_arm)
    t_att = att["time"]
    lo, hi = p.range_s
    dts = np.linspace(lo, hi, int(round((hi - lo) / p.step_s)) + 1)
    g_int, a_int = median_interval(t_g), median_interval(t_att)
    for column in ("name", "start", "end"):
        if column not in lines:
            raise InputError("lines", f"missing column {column}", field=column)
    names = [str(n) for n in np.asarray(lines["name"]).ravel()]
    starts = np.asarray(lines["start"], dtype=float).ravel()
    ends = np.asarray(lines["end"], dtype=float).ravel()
    if not names:
        raise InputError("lines", "no survey lines")
    return Setup(t_g, hgt, att, arm, dts, g_int, a_int, names, starts, ends, [])


def check_usable(setup: Setup, p: LatencyParams, prepared: list) -> None:
    """Raise InputError when no prepared line has enough epochs with attitude."""
    if not any(line.usable for line in prepared):
        raise InputError("lines", f"no line has {p.min_epochs} or more GNSS epochs with attitude "
                         "data: lines span " + _span_text(np.r_[setup.starts, setup.ends])
                         + ", GNSS " + _span_text(setup.t_g) + ", attitude "
                         + _span_text(setup.att["time"])
                         + " (lines must be on the loggers' time scale)")
