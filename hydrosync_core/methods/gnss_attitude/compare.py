"""Comparing array attitude with an independent reference (INS, another solution).

All angles in degrees, order heading, pitch, roll (the project's convention: body FRD →
NED, ``R = Rz(heading)·Ry(pitch)·Rx(roll)``). Heading and roll differences are wrapped to
(−180°, 180°], so 359.9° vs 0.1° is a 0.2° difference.

A difference series ``array − reference`` holds three things that are reported apart:

- a **constant offset** (mounting misalignment of the reference's axes relative to the
  antenna layout, tape-measure errors of the layout, the reference's own heading bias):
  the mean of the inliers;
- the **scatter** about it (std of the inliers), what the array and the reference disagree
  on from epoch to epoch;
- **gross outliers**, more than ``outlier_k`` robust σ (1.4826·MAD, at least
  ``outlier_floor_deg``) from the median: counted, left out of mean and std.

A time offset between the two clocks is applied before interpolation
(``t_array = t_reference + offset_s``); :func:`estimate_time_offset` finds it from the
heading, which changes fastest on a moving vehicle.
"""

from __future__ import annotations

import numpy as np

ANGLES = ("heading", "pitch", "roll")


def wrap180(a):
    """Degrees wrapped to (−180, 180]."""
    return 180.0 - np.mod(180.0 - np.asarray(a, float), 360.0)


def interpolate_reference(ref_t: np.ndarray, ref_deg: np.ndarray, t: np.ndarray,
                          max_gap_s: float = 1.5) -> np.ndarray:
    """Reference attitude (heading, pitch, roll; deg) at times *t*.

    Linear interpolation; heading and roll are unwrapped first so that the 180°/360°
    seams do not produce spurious values. NaN outside the reference's span and where the
    two bracketing reference samples are more than *max_gap_s* apart.
    """
    ref_t = np.asarray(ref_t, float)
    order = np.argsort(ref_t, kind="stable")
    ref_t = ref_t[order]
    ref = np.asarray(ref_deg, float)[order]
    out = np.full((np.size(t), 3), np.nan)
    if ref_t.size < 2:
        return out
    t = np.asarray(t, float)
    for c in range(3):
        col = ref[:, c]
        if c != 1:
            col = np.degrees(np.unwrap(np.radians(col)))
        out[:, c] = np.interp(t, ref_t, col)
    out[:, 0] = np.mod(out[:, 0], 360.0)
    out[:, 2] = wrap180(out[:, 2])
    j = np.searchsorted(ref_t, t)
    inside = (j > 0) & (j < ref_t.size)
    jj = np.clip(j, 1, ref_t.size - 1)
    gap = ref_t[jj] - ref_t[jj - 1]
    exact = np.isin(t, ref_t)
    bad = ~(inside & (gap <= max_gap_s)) & ~exact
    out[bad] = np.nan
    return out


def differences(est_deg: np.ndarray, ref_deg: np.ndarray) -> np.ndarray:
    """``est − ref`` (deg), heading and roll wrapped to (−180, 180]."""
    d = np.asarray(est_deg, float) - np.asarray(ref_deg, float)
    d[:, 0] = wrap180(d[:, 0])
    d[:, 2] = wrap180(d[:, 2])
    return d


def summarize(diff: np.ndarray, outlier_k: float = 5.0,
              outlier_floor_deg: float = 2.0) -> dict:
    """Offset, scatter and outliers of a difference series per angle.

    Returns ``{"epochs": n, angle: {"mean", "std", "median", "robust_std", "outliers",
    "mean_all", "std_all"}}`` (deg): ``mean``/``std`` over the inliers (the constant offset
    and the scatter), ``*_all`` over every epoch, ``robust_std`` = 1.4826·MAD.
    """
    diff = np.asarray(diff, float)
    good = np.isfinite(diff).all(axis=1)
    out: dict = {"epochs": int(good.sum())}
    for c, angle in enumerate(ANGLES):
        d = diff[good, c]
        if d.size < 3:
            out[angle] = dict.fromkeys(("mean", "std", "median", "robust_std", "outliers",
                                        "mean_all", "std_all"))
            continue
        med = float(np.median(d))
        rstd = float(1.4826 * np.median(np.abs(d - med)))
        keep = np.abs(d - med) <= max(outlier_k * rstd, outlier_floor_deg)
        out[angle] = {"mean": float(np.mean(d[keep])), "std": float(np.std(d[keep], ddof=1)),
                      "median": med, "robust_std": rstd, "outliers": int((~keep).sum()),
                      "mean_all": float(np.mean(d)), "std_all": float(np.std(d, ddof=1))}
    return out


def compare(t: np.ndarray, est_deg: np.ndarray, ref_t: np.ndarray, ref_deg: np.ndarray,
            offset_s: float = 0.0, max_gap_s: float = 1.5, select=None, **kw) -> dict:
    """Summary (:func:`summarize`) of ``est − reference`` at the array epochs *t*.

    *ref_t* is on the reference's clock; ``t = ref_t + offset_s`` maps it onto the array's.
    *select* (bool mask over *t*) restricts the epochs (e.g. a static interval).
    """
    ref = interpolate_reference(np.asarray(ref_t, float) + offset_s, ref_deg, t, max_gap_s)
    d = differences(est_deg, ref)
    if select is not None:
        d = d[np.asarray(select, bool)]
    return summarize(d, **kw)


def estimate_time_offset(t: np.ndarray, heading_deg: np.ndarray, ref_t: np.ndarray,
                         ref_heading_deg: np.ndarray, search_s=(-30.0, 30.0),
                         step_s: float = 0.5, fine_step_s: float = 0.1,
                         max_gap_s: float = 1.5) -> tuple[float, float]:
    """Clock offset (s, ``t = ref_t + offset``) that best aligns the two heading series.

    Minimises the robust spread (1.4826·MAD) of the heading differences, first on a
    *step_s* grid over *search_s*, then on a *fine_step_s* grid ±*step_s* around the best.
    Returns (offset_s, spread_deg at the offset). Needs the vehicle to turn.
    """
    t = np.asarray(t, float)
    h = np.asarray(heading_deg, float)
    ok = np.isfinite(h)
    t, h = t[ok], h[ok]
    ref = np.column_stack([ref_heading_deg, np.zeros_like(ref_heading_deg),
                           np.zeros_like(ref_heading_deg)])

    def spread(offset):
        r = interpolate_reference(np.asarray(ref_t, float) + offset, ref, t, max_gap_s)[:, 0]
        d = wrap180(h - r)
        d = d[np.isfinite(d)]
        if d.size < 10:
            return np.inf
        return 1.4826 * float(np.median(np.abs(d - np.median(d))))

    grid = np.arange(search_s[0], search_s[1] + step_s / 2, step_s)
    values = [spread(o) for o in grid]
    best = float(grid[int(np.argmin(values))])
    fine = np.arange(best - step_s, best + step_s + fine_step_s / 2, fine_step_s)
    values = [spread(o) for o in fine]
    k = int(np.argmin(values))
    return round(float(fine[k]), 6), float(values[k])
