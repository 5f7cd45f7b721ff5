"""Band-limited upsampling of a low-rate attitude record (e.g. the 1 Hz PSXN,23 of the
Seapath logs) for the estimators beyond the published one.

Seed eq. 3 interpolates the attitude linearly. At 1 Hz, against 4–10 s waves, a linear
interpolation has a phase error that depends on where the GNSS epochs fall between the
records: in simulation it biased the weighted estimator by −23 ms (RMSE 24 ms for a σ of
10 ms, 95 % coverage 0.42). The records are samples of a band-limited motion, so they are
upsampled first with a linear-phase polyphase FIR (no delay, no phase distortion below the
Nyquist frequency) to at least MIN_RATE_HZ; linear interpolation of that record is then
exact to a fraction of a millisecond (same days: bias +3 ms, coverage 0.92). ``qi2010``
keeps the published linear interpolation of the records as they are.

Records that are fast enough for the signal can still be too slow for the noise. Linear
interpolation between two records of a noisy heave averages their noise: at a fraction μ
of the interval its variance is ((1 − μ)² + μ²) times the records'. While the scan moves
Δt, μ moves with it (the GNSS epochs fall at one μ when both rates are regular), so the
correlation's denominator is modulated with the attitude interval and R is pulled towards
the Δt where the epochs fall midway between records. At equal 10 Hz rates that pull was
+3…+10 ms on simulated days whose σ was 1.4–3.7 ms (95 % coverage 0.62 on INS-blended
days, whose smooth heights leave the heave's noise to set the coherence). Upsampled
band-limited first, neighbouring samples share their noise and the modulation falls as
(π/L)²/12 with the factor L: the record is brought to at least MIN_RATIO times the GNSS
rate.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
from scipy.signal import resample_poly

MIN_RATE_HZ = 10.0
"""Attitude slower than this is upsampled to at least this rate."""

MIN_RATIO = 5.0
"""Attitude slower than this many times the GNSS rate is upsampled to at least that rate
(the noise pull above; ×5 leaves 3 % of the modulation)."""

GAP_FACTOR = 3.0
"""An interval above this many median intervals splits the record."""


def _median_interval(times) -> float:
    """Median step (s) of the first records of *times*; NaN when there is none (bad
    input is reported by the input checks, not here)."""
    try:
        times = np.asarray(times, dtype=float)
    except (TypeError, ValueError):
        return float("nan")
    if times.ndim != 1 or times.size < 2:
        return float("nan")
    return float(np.median(np.diff(times[: 10_001])))


def upsampling_factor(times, gnss_times=None) -> int:
    """Whole factor that brings the attitude record (*times*, s) to MIN_RATE_HZ and to
    MIN_RATIO times the rate of the GNSS epochs *gnss_times* (s), when given (1: none)."""
    interval = _median_interval(times)
    if not interval > 0:
        return 1
    rate = MIN_RATE_HZ
    gnss_interval = _median_interval(gnss_times)
    if gnss_interval > 0:
        rate = max(rate, MIN_RATIO / gnss_interval)
    return max(1, math.ceil(interval * rate - 1e-9))


def band_limited(attitude: Mapping, factor: int) -> dict:
    """*attitude* upsampled *factor* times per gap-free stretch (heading unwrapped, then
    wrapped to 0–360°); only the columns of one-dimensional arrays of the record's length."""
    t = np.asarray(attitude["time"], dtype=float)
    steps = np.diff(t)
    interval = float(np.median(steps))
    cuts = np.r_[0, np.flatnonzero(steps > GAP_FACTOR * interval) + 1, t.size]
    columns = [c for c, v in attitude.items()
               if c != "time" and np.ndim(v) == 1 and len(v) == t.size]
    pieces: dict[str, list] = {"time": []}
    pieces.update({c: [] for c in columns})
    for a, b in zip(cuts[:-1], cuts[1:], strict=True):
        n = b - a
        if n < 2:
            continue
        step = (t[b - 1] - t[a]) / (n - 1)
        pieces["time"].append(t[a] + np.arange((n - 1) * factor + 1) * (step / factor))
        for c in columns:
            x = np.asarray(attitude[c], dtype=float)[a:b]
            if c == "heading":
                x = np.degrees(np.unwrap(np.radians(x)))
            y = resample_poly(x, factor, 1, padtype="line")[: (n - 1) * factor + 1]
            pieces[c].append(y % 360.0 if c == "heading" else y)
    return {c: np.concatenate(v) for c, v in pieces.items()}
