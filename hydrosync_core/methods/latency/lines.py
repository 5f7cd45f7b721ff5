"""Per-line work: epoch selection, gap checks, detrending and the Δt scan of one line."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.methods.latency import fastscan
from hydrosync_core.methods.latency.correlation import (
    DELTA_S,
    MAX_LAG_S,
    SUBDIVISIONS,
    WIDTH_S,
    correlation_curve,
    correlation_curve_direct,
    peak_uncertainty,
    refine_peak,
    unit_centred,
)
from hydrosync_core.methods.latency.detrend import detrend
from hydrosync_core.methods.latency.params import LatencyParams

MARGIN_S = 0.15
"""Attitude needed beyond the scan range (refinement and curvature fit around the peak)."""

FLAT_R_SPAN = 0.05
"""A line whose R varies less than this over the whole scan has no usable peak."""

FLAT_PROBES = 9
"""Candidates spread over the grid that :func:`scan_line_window` evaluates to show that R
is not flat when the window alone does not."""


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
    scan: str = "full"
    """How the grid was scanned: "full", "window" (candidates around a first pass's peak
    only, see :func:`scan_line_window`) or "fallback" (a window that failed its checks,
    then the full grid). Not part of any result."""


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


def line_selection(start: float, end: float, t_g: np.ndarray, t_att: np.ndarray,
                   params: LatencyParams) -> slice:
    """The GNSS epochs (slice of *t_g*) that :func:`prepare_line` keeps for a line (s)."""
    lo, hi = params.range_s
    return line_slice(t_g, start, end, params.skip_s, t_att, lo - MARGIN_S, hi + MARGIN_S)


def prepare_line(
    name: str, start: float, end: float, t_g: np.ndarray, height: np.ndarray,
    t_att: np.ndarray, params: LatencyParams, gnss_interval: float, att_interval: float,
    sel: slice | None = None,
) -> LineData:
    """Select the line's epochs (after *skip_s*, inside the attitude coverage) and detrend.

    *sel*: :func:`line_selection`, when the caller has it.
    """
    lo, hi = params.range_s
    if sel is None:
        sel = line_selection(start, end, t_g, t_att, params)
    tags, hgt = t_g[sel], height[sel]
    line = LineData(name, start, end, tags, hgt)
    if tags.size < params.min_epochs:
        line.usable = False
        line.warnings.append(
            f"line {name}: only {tags.size} GNSS epochs with attitude (need {params.min_epochs})"
        )
        return line
    gap = fastscan.largest_step(tags)
    if gap > params.gap_factor * gnss_interval:
        line.warnings.append(f"line {name}: gap of {gap:.1f} s in the GNSS data")
    window = t_att[attitude_window(t_att, tags, lo, hi)]
    gap = fastscan.largest_step(window) if window.size > 1 else 0.0
    if gap > params.gap_factor * att_interval:
        line.warnings.append(f"line {name}: gap of {gap:.2f} s in the attitude data")
    # Seed eq. 1: remove tide / trend from the heights of the line.
    line.h, _ = detrend(tags, hgt, int(params.detrend_degree))
    return line


def scan_line(
    line: LineData, t_att: np.ndarray, h_att: np.ndarray, dts: np.ndarray,
    refine: bool = True, uncertainty: bool = True,
) -> LinePeak:
    """Seed eqs. 3–4 over the whole Δt grid, then sub-step refinement and uncertainty.

    One compiled call (:func:`.fastscan.scan_core`) where it applies, else the Python
    steps (:func:`correlation_curve`, :func:`refine_peak`, :func:`peak_uncertainty`):
    the same numbers to rounding.
    """
    if not line.usable:
        return LinePeak(np.full(dts.size, np.nan))
    fast = fastscan.scan_core(line.tags, line.h, t_att, h_att, dts, refine, uncertainty,
                              SUBDIVISIONS, MARGIN_S, MAX_LAG_S, DELTA_S, WIDTH_S)
    if fast is not None:
        curve, k, low = fast[:3]
    else:
        win = attitude_window(t_att, line.tags, float(dts[0]), float(dts[-1]))
        ta, ha = t_att[win], h_att[win]
        unit = unit_centred(line.h)  # shared by the scan, the refinement and σ
        curve = correlation_curve(line.tags, line.h, ta, ha, dts, unit)
        k, low = _argmax_min(curve)
    if k < 0:
        line.warnings.append(f"line {line.name}: total heave is constant, no correlation")
        return LinePeak(curve)
    peak = LinePeak(curve, r_max=float(curve[k]), latency_s=float(dts[k]))
    span = float(curve[k] - low)
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
    if fast is not None:
        peak.latency_s, peak.r_max, sigma = fast[3:]
        if uncertainty:
            peak.uncertainty_s = sigma
        return peak
    if refine:
        peak.latency_s, peak.r_max = refine_peak(line.tags, line.h, ta, ha, dts, curve, k,
                                                 unit=unit)
    if uncertainty:
        peak.uncertainty_s = peak_uncertainty(line.tags, line.h, ta, ha, peak.latency_s,
                                              unit=unit)
    return peak


def line_uncertainty(line: LineData, t_att: np.ndarray, h_att: np.ndarray, dts: np.ndarray,
                     latency_s: float) -> float:
    """The σ (s) :func:`scan_line` gives *line* when its peak is at *latency_s*, for a
    peak found without it (same attitude window, same numbers: compiled where the scan
    is, else :func:`peak_uncertainty`)."""
    sigma = fastscan.line_sigma(line.tags, line.h, t_att, h_att, dts, latency_s, MARGIN_S,
                                MAX_LAG_S, DELTA_S, WIDTH_S)
    if sigma is not None:
        return sigma
    return peak_uncertainty(line.tags, line.h, t_att, h_att, latency_s)


def _argmax_min(curve: np.ndarray) -> tuple[int, float]:
    """(``np.nanargmax``, ``np.nanmin``) of *curve*; index −1 when nothing is finite.

    One pass instead of np.any(np.isfinite), nanargmax, nanmax and nanmin (their Python
    overhead, per line and pass, held the GIL the scan threads share)."""
    k, low = fastscan._argmax_min(np.ascontiguousarray(curve, dtype=float))
    return int(k), float(low)


def scan_line_window(
    line: LineData, t_att: np.ndarray, h_att: np.ndarray, dts: np.ndarray, k0: int, k1: int,
    uncertainty: bool = True,
) -> LinePeak | None:
    """:func:`scan_line` with R evaluated at the candidates ``dts[k0:k1]`` only.

    Returns None — the caller then scans the full grid — unless the window settles what
    the full scan decides from the curve: a finite maximum strictly inside the window (so
    not on the scan's edge, and the refinement's ±1 step lies inside), and R varying by
    at least FLAT_R_SPAN between the window's maximum and the window or FLAT_PROBES
    candidates spread over the grid (then it does over the whole grid: no "flat"
    warning).
    The attitude window is that of the full grid, so the refinement and the uncertainty
    see the same samples as :func:`scan_line`. It cannot show that no larger maximum lies
    outside the window: the window must be wide enough for that (the caller's choice).
    The curve outside the window is NaN. Appends no warning when it returns None.
    """
    if not line.usable or not 0 <= k0 < k1 <= dts.size:
        return None
    win = attitude_window(t_att, line.tags, float(dts[0]), float(dts[-1]))
    ta, ha = t_att[win], h_att[win]
    part = correlation_curve(line.tags, line.h, ta, ha, dts[k0:k1])
    if not np.any(np.isfinite(part)):
        return None
    j = int(np.nanargmax(part))
    if not 0 < j < part.size - 1:
        return None
    # Not flat: R must vary by FLAT_R_SPAN over the grid. Near its peak R is broad, so a
    # few candidates spread outside the window give the lower values that show it.
    low = float(np.nanmin(part))
    if part[j] - low < FLAT_R_SPAN + 1e-9:
        out = np.setdiff1d(np.linspace(0, dts.size - 1, FLAT_PROBES).round().astype(int),
                           np.arange(k0, k1))
        if out.size:
            with np.errstate(invalid="ignore"):
                probe = correlation_curve_direct(line.tags, line.h, ta, ha, dts[out])
            if np.any(np.isfinite(probe)):
                low = min(low, float(np.nanmin(probe)))
        if part[j] - low < FLAT_R_SPAN + 1e-9:
            return None
    k = k0 + j
    curve = np.full(dts.size, np.nan)
    curve[k0:k1] = part
    peak = LinePeak(curve, r_max=float(part[j]), latency_s=float(dts[k]), scan="window")
    peak.latency_s, peak.r_max = refine_peak(line.tags, line.h, ta, ha, dts, curve, k)
    if uncertainty:
        peak.uncertainty_s = peak_uncertainty(line.tags, line.h, ta, ha, peak.latency_s)
    return peak
