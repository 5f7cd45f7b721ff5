"""The scans of every line: the first passes (qi2010 on the raw total heave, the anti-aliased
one of the weighted estimator) and the scan of one line on its attitude window."""

from __future__ import annotations

import dataclasses

import numpy as np

from hydrosync_core.methods.latency import prefilter
from hydrosync_core.methods.latency.correlation import heave_at
from hydrosync_core.methods.latency.heave_windows import HeaveWindows
from hydrosync_core.methods.latency.inputs import Setup
from hydrosync_core.methods.latency.lines import (
    LinePeak,
    line_selection,
    prepare_line,
    scan_line,
    scan_line_window,
)
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.prefilter import Spectrum
from hydrosync_core.methods.latency.quality import sigma0
from hydrosync_core.methods.latency.threads import per_line


@dataclasses.dataclass
class LineWork:
    """What the weighted estimator's later passes need of one line's first pass.

    Kept between the passes instead of recomputed: the line's window, the spectrum of its
    padded total heave (only the bins below the GNSS Nyquist frequency, where the
    coherence weight can be non-zero: ~10 % of them at 10 Hz GNSS and 100 Hz attitude)
    and its anti-aliased total heave (for the pooled spectra, about 50 MB for a survey
    day of 500 two-minute lines, dropped once the weighting is known).
    """

    inner: slice
    padded: slice
    spectrum: Spectrum
    antialiased: np.ndarray | None


@dataclasses.dataclass
class Passes:
    """What :func:`first_passes` returns: per line, in order (None for a scan skipped)."""

    raw_lines: list | None     # LineData of the qi2010 scan (its warnings its own)
    raw_peaks: list | None
    aa_lines: list | None      # LineData of the anti-aliased scan (the weighted estimator's)
    aa_peaks: list | None
    works: list                # LineWork (keep) or None
    before: list               # σ0 before (m), NaN for a line not usable


def first_passes(setup: Setup, p: LatencyParams, raw: bool, antialias: bool, progress,
                  cancel, aa_sigma: bool = True, keep: bool = False) -> Passes:
    """Each line prepared (:func:`prepare_line`) and scanned on its raw total heave
    (qi2010, *raw*) and on the anti-aliased one (*antialias*), one task per line.

    Each line's total heave is computed once, on the window padded for filtering, and
    serves both scans; the line is prepared in its task too (its detrending overlaps the
    other thread's compiled work). *aa_sigma*: the anti-aliased scan's uncertainty;
    *keep*: each line's :class:`LineWork` for the weighted passes. σ0 before (seed
    eqs. 5–6 at Δt = 0) is the same for every estimator and comes from the raw window
    here: :func:`line_quality` then interpolates at the final Δt only.
    """
    dts, a_int, t_g, t_att = setup.dts, setup.a_int, setup.t_g, setup.att["time"]
    source = HeaveWindows(setup.att, setup.arm)
    pad = int(round(prefilter.PAD_S / a_int)) if antialias else 0
    # The lines' epochs (binary searches) and windows first: they size the kept rows.
    sels = [line_selection(setup.starts[i], setup.ends[i], t_g, t_att, p)
            for i in range(len(setup.names))]
    windows = [source.windows(t_g[sel], float(dts[0]), float(dts[-1]), pad)
               if sel.stop - sel.start >= p.min_epochs else None for sel in sels]
    if keep and any(w is not None for w in windows):
        # What the later passes need, in two blocks allocated here rather than per line
        # in the worker threads: long-lived rows scattered among the threads' temporaries
        # would keep their heap from shrinking (~60 MB more peak memory on a survey day).
        spans = [(w[0].stop - w[0].start, w[1].stop - w[1].start) for w in windows if w]
        inner_max = max(n for n, _ in spans)
        bins_max = max(band_bins(prefilter.next_fast_len(2 * n), a_int, setup.g_int)
                       for _, n in spans)
        aa_rows = np.empty((len(sels), inner_max))
        bin_rows = np.empty((len(sels), bins_max), dtype=complex)
    cutoff = prefilter.ANTIALIAS_FRACTION * 0.5 / setup.g_int
    aa_cache: dict = {}

    def response(f):
        return prefilter.antialias_response(f, cutoff)

    def task(i: int):
        line = prepare_line(setup.names[i], setup.starts[i], setup.ends[i], t_g, setup.hgt,
                            t_att, p, setup.g_int, a_int, sels[i])
        # One LineData per estimator: each appends its own warnings.
        line_raw = line if raw else None
        line_aa = (dataclasses.replace(line, warnings=list(line.warnings)) if raw else line
                   ) if antialias else None
        if windows[i] is None:
            return line_raw, unscanned(dts), line_aa, unscanned(dts), None, float("nan")
        inner, padded = windows[i]
        h = source.heave(padded)
        crop = slice(inner.start - padded.start, inner.stop - padded.start)
        ta = source.t[inner]
        # The numbers of HeaveWindows.at(tags): same records, same interpolation formula.
        before = sigma0(line.h, heave_at(line.tags, np.zeros(1), ta, h[crop])[0])
        pk_raw = pk_aa = work = None
        if raw:
            pk_raw = scan(line_raw, ta, h[crop], dts)
        if antialias:
            spec = prefilter.spectrum(h)
            del h
            gains = prefilter.response_gains(response, spec.size, a_int, aa_cache)
            ha = prefilter.filtered(spec, gains, crop, out=aa_rows[i] if keep else None)
            pk_aa = scan(line_aa, ta, ha, dts, uncertainty=aa_sigma)
            if keep:
                work = LineWork(inner, padded, spec.head(
                    band_bins(spec.size, a_int, setup.g_int), out=bin_rows[i]), ha)
        return line_raw, pk_raw, line_aa, pk_aa, work, before

    out = per_line(task, len(sels), setup.names, progress, cancel)
    raw_lines, raw_peaks, aa_lines, aa_peaks, works, before = map(list, zip(*out, strict=True))
    return Passes(raw_lines if raw else None, raw_peaks if raw else None,
                   aa_lines if antialias else None, aa_peaks if antialias else None,
                   works, before)


def band_bins(size: int, a_int: float, g_int: float) -> int:
    """``rfft`` bins of *size* samples every *a_int* s up to the GNSS Nyquist frequency
    ``0.5/g_int`` (and one more): beyond them the coherence weight is zero."""
    return min(int(np.floor(0.5 / g_int * size * a_int * (1.0 + 1e-9))) + 2, size // 2 + 1)


WINDOWED_SCAN = False
"""True: scan the weighted estimator's second pass only around the first passes' peaks
(:func:`scan_windows`, about 7 % of auto's time on a survey day). Off by default: a
maximum strictly inside the window is only a local one, so a line whose weighted curve
peaks far from its other two estimates could get another answer than the full scan, and
the results must stay those of the full scan."""


WINDOW_MIN_S = 0.1
"""Smallest half-width (s) of a line's window around its first-pass peaks."""


WINDOW_SIGMAS = 10.0
"""Half-width of the window in the line's own σ (qi2010 pass), when that is wider."""


def scan(line, ta: np.ndarray, ha: np.ndarray, dts: np.ndarray, uncertainty: bool = True,
          window: tuple[int, int] | None = None):
    """:func:`scan_line` of one line on its attitude window (times *ta*, heave *ha*), or
    :func:`scan_line_window` over the candidates *window* when that settles the peak."""
    if window is not None:
        peak = scan_line_window(line, ta, ha, dts, *window, uncertainty=uncertainty)
        if peak is not None:
            return peak
    peak = scan_line(line, ta, ha, dts, uncertainty=uncertainty)
    if window is not None:
        peak.scan = "fallback"
    return peak


def scan_windows(first: list, hints, dts: np.ndarray) -> list:
    """Candidate index windows ``(k0, k1)`` (or None: every candidate) for a second pass.

    A line's window spans its first-pass peak and, with *hints* (per-line ``(Δt, σ)``
    of another estimator, e.g. the qi2010 run of ``auto``), that estimator's peak too,
    widened on each side by WINDOW_MIN_S or WINDOW_SIGMAS σ, whichever is wider.
    Lines whose first pass found no interior peak get None.
    """
    if not WINDOWED_SCAN or dts.size < 3:
        return [None] * len(first)
    step = (float(dts[-1]) - float(dts[0])) / (dts.size - 1)
    out = []
    for i, pk in enumerate(first):
        if not np.isfinite(pk.latency_s) or pk.at_edge:
            out.append(None)
            continue
        lo = hi = pk.latency_s
        half = WINDOW_MIN_S
        if hints is not None:
            lat, unc = hints[i]
            if np.isfinite(lat):
                lo, hi = min(lo, lat), max(hi, lat)
            if np.isfinite(unc):
                half = max(half, WINDOW_SIGMAS * unc)
        k0 = max(int(np.floor((lo - half - float(dts[0])) / step)), 0)
        k1 = min(int(np.ceil((hi + half - float(dts[0])) / step)) + 1, dts.size)
        out.append((k0, k1) if k1 - k0 < dts.size else None)
    return out


def unscanned(dts: np.ndarray) -> LinePeak:
    """What :func:`scan_line` gives a line that is not usable."""
    return LinePeak(np.full(dts.size, np.nan))
