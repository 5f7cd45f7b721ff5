"""Per-line work: epoch selection, gap checks, detrending and the Δt scan of one line."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.methods.latency.correlation import (
    correlation_curve,
    peak_uncertainty,
    refine_peak,
)
from hydrosync_core.methods.latency.detrend import detrend
from hydrosync_core.methods.latency.params import LatencyParams

MARGIN_S = 0.15
"""Attitude needed beyond the scan range (refinement and curvature fit around the peak)."""

FLAT_R_SPAN = 0.05
"""A line whose R varies less than this over the whole scan has no usable peak."""


@dataclass
class LineData:
    """The GNSS epochs of one line ready for the scan (tags in s, heights detrended, m)."""

    name: str
    start: float
    end: float
    tags: np.ndarray
    h: np.ndarray
    warnings: list[str] = field(default_factory=list)
    usable: bool = True


@dataclass
class LinePeak:
    """Scan outcome of one line (s, dimensionless R)."""

    curve: np.ndarray
    r_max: float = float("nan")
    latency_s: float = float("nan")
    uncertainty_s: float = float("nan")
    at_edge: bool = False


def attitude_window(t_att: np.ndarray, tags: np.ndarray, lo: float, hi: float) -> slice:
    """Attitude samples needed for ``tags − Δt``, Δt in [lo, hi] widened by MARGIN_S."""
    i0 = max(int(np.searchsorted(t_att, tags[0] - hi - MARGIN_S)) - 1, 0)
    i1 = min(int(np.searchsorted(t_att, tags[-1] - lo + MARGIN_S)) + 1, t_att.size)
    return slice(i0, i1)


def line_epochs(t_g: np.ndarray, start: float, end: float, skip_s: float, t_att: np.ndarray,
                dt_low: float, dt_high: float) -> np.ndarray:
    """Mask of the GNSS tags (s) of one line whose shifted times lie in the attitude record.

    A tag *T* belongs to the line when ``start + skip_s <= T <= end``, and is kept only if
    ``T − Δt`` stays inside ``t_att`` for every Δt in ``[dt_low, dt_high]`` (no
    extrapolation of the attitude).
    """
    sel = np.zeros(t_g.size, dtype=bool)
    sel[line_slice(t_g, start, end, skip_s, t_att, dt_low, dt_high)] = True
    return sel


def line_slice(t_g: np.ndarray, start: float, end: float, skip_s: float, t_att: np.ndarray,
               dt_low: float, dt_high: float) -> slice:
    """:func:`line_epochs` as a slice of the increasing tags *t_g* (same epochs, no mask).

    The conditions are monotone in the tag, so the epochs are contiguous: a binary search
    finds their neighbourhood and the exact tests of :func:`line_epochs` decide its ends.
    """
    pad = 1e-6 * (1.0 + abs(dt_low) + abs(dt_high))
    lo = max(start + skip_s, t_att[0] + dt_high) - pad
    hi = min(end, t_att[-1] + dt_low) + pad
    i0 = int(np.searchsorted(t_g, lo, side="left"))
    i1 = int(np.searchsorted(t_g, hi, side="right"))
    if i1 <= i0:
        return slice(0, 0)
    t = t_g[i0:i1]
    ok = (t >= start + skip_s) & (t <= end) & (t - dt_high >= t_att[0]) & (t - dt_low <= t_att[-1])
    idx = np.flatnonzero(ok)
    if idx.size == 0:
        return slice(0, 0)
    return slice(i0 + int(idx[0]), i0 + int(idx[-1]) + 1)


def prepare_line(
    name: str, start: float, end: float, t_g: np.ndarray, height: np.ndarray,
    t_att: np.ndarray, params: LatencyParams, gnss_interval: float, att_interval: float,
) -> LineData:
    """Select the line's epochs (after *skip_s*, inside the attitude coverage) and detrend."""
    lo, hi = params.range_s
    sel = line_slice(t_g, start, end, params.skip_s, t_att, lo - MARGIN_S, hi + MARGIN_S)
    tags, hgt = t_g[sel], height[sel]
    line = LineData(name, start, end, tags, hgt)
    if tags.size < params.min_epochs:
        line.usable = False
        line.warnings.append(
            f"line {name}: only {tags.size} GNSS epochs with attitude (need {params.min_epochs})"
        )
        return line
    gaps = np.diff(tags)
    if gaps.max() > params.gap_factor * gnss_interval:
        line.warnings.append(f"line {name}: gap of {gaps.max():.1f} s in the GNSS data")
    window = t_att[attitude_window(t_att, tags, lo, hi)]
    if window.size > 1 and np.diff(window).max() > params.gap_factor * att_interval:
        line.warnings.append(
            f"line {name}: gap of {np.diff(window).max():.2f} s in the attitude data"
        )
    # Seed eq. 1: remove tide / trend from the heights of the line.
    line.h, _ = detrend(tags, hgt, int(params.detrend_degree))
    return line


def scan_line(
    line: LineData, t_att: np.ndarray, h_att: np.ndarray, dts: np.ndarray,
    refine: bool = True, uncertainty: bool = True,
) -> LinePeak:
    """Seed eqs. 3–4 over the whole Δt grid, then sub-step refinement and uncertainty."""
    if not line.usable:
        return LinePeak(np.full(dts.size, np.nan))
    win = attitude_window(t_att, line.tags, float(dts[0]), float(dts[-1]))
    ta, ha = t_att[win], h_att[win]
    curve = correlation_curve(line.tags, line.h, ta, ha, dts)
    if not np.any(np.isfinite(curve)):
        line.warnings.append(f"line {line.name}: total heave is constant, no correlation")
        return LinePeak(curve)
    k = int(np.nanargmax(curve))
    peak = LinePeak(curve, r_max=float(curve[k]), latency_s=float(dts[k]))
    span = float(np.nanmax(curve) - np.nanmin(curve))
    if span < FLAT_R_SPAN:
        line.warnings.append(
            f"line {line.name}: R is flat over the scan (varies by {span:.3f}), no clear peak"
        )
    if k in (0, dts.size - 1):
        peak.at_edge = True
        line.warnings.append(
            f"line {line.name}: correlation peak at the edge of the scan range "
            f"({dts[k]:+.3f} s); widen the range"
        )
        return peak
    if refine:
        peak.latency_s, peak.r_max = refine_peak(line.tags, line.h, ta, ha, dts, curve, k)
    if uncertainty:
        peak.uncertainty_s = peak_uncertainty(line.tags, line.h, ta, ha, peak.latency_s)
    return peak
