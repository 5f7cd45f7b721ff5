"""Latency between GNSS heights and attitude/heave by correlative approximation (seed 000).

Public entry points: :func:`estimate_latency`, :func:`synchronise`, :func:`line_series`.
Inputs are plain dicts of 1-D arrays as the CSV readers return them: GNSS ``time`` (s,
tags) and ``height`` (m); attitude ``time`` (s, strictly increasing), ``roll``, ``pitch``,
``heading`` (degrees) and ``heave`` (m, positive up); lines ``name``, ``start``, ``end``
(s). The lever arm is the antenna relative to the motion sensor, body FRD, metres.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.combine import combine, find_outliers, select_lines
from hydrosync_core.methods.latency.correlation import heave_at
from hydrosync_core.methods.latency.detrend import detrend
from hydrosync_core.methods.latency.diagnose import diagnose
from hydrosync_core.methods.latency.heave import total_heave, total_heave_deg
from hydrosync_core.methods.latency.lines import (
    LinePeak,
    attitude_window,
    line_epochs,
    line_selection,
    line_uncertainty,
    prepare_line,
    scan_line,
    scan_line_window,
)
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.quality import sigma0
from hydrosync_core.methods.latency.result import LatencyResult, LineResult
from hydrosync_core.progress import check_cancel, report, sub_progress
from hydrosync_core.timespan import span_of

if TYPE_CHECKING:
    from hydrosync_core.methods.latency.prefilter import Spectrum


def _all_finite_py(values):  # pragma: no cover - compiled below
    ok = True
    for i in range(values.size):
        x = values[i]
        ok &= (x - x) == 0.0  # NaN and ±inf give NaN; no branch: the loop vectorises
    return ok


def _increasing_py(times):  # pragma: no cover - compiled below
    ok = True
    for i in range(1, times.size):
        ok &= times[i] > times[i - 1]
    return ok


try:  # numba is a dependency; numpy remains if it cannot load
    from numba import njit

    _all_finite = njit(cache=True, nogil=True)(_all_finite_py)
    _increasing = njit(cache=True, nogil=True)(_increasing_py)
except ImportError:  # pragma: no cover
    def _all_finite(values):
        return bool(np.all(np.isfinite(values)))

    def _increasing(times):
        return not np.any(times[1:] <= times[:-1])


def _column(table: Mapping, name: str, source: str) -> np.ndarray:
    if name not in table:
        raise InputError(source, f"missing column {name}", field=name)
    values = np.asarray(table[name], dtype=float).ravel()
    # One pass without an 8 MB mask per column of a day's attitude (page faults each).
    if not _all_finite(values):
        raise InputError(source, "non-finite values", field=name)
    return values


def _check_inputs(gnss: Mapping, attitude: Mapping, lever_arm) -> tuple:
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


def _joint_peak(curves: np.ndarray, weights: np.ndarray, dts: np.ndarray) -> float:
    """Δt maximising the epoch-weighted mean Fisher-z of the used lines' curves."""
    if curves.size == 0 or not np.any(np.isfinite(curves)):
        return float("nan")
    # In place after the one copy: a survey day's curves are 8 MB, and the temporaries
    # of the expression (np.nansum(np.arctanh(...) * w)) set the estimate's peak memory.
    z = np.clip(curves, -0.999999, 0.999999)
    np.arctanh(z, out=z)
    z *= weights[:, None]
    z[np.isnan(z)] = 0.0  # np.nansum's own replacement, then the same sum
    mean = z.sum(axis=0) / weights.sum()
    k = int(np.argmax(mean))
    if 0 < k < dts.size - 1:
        # Parabola through the three grid points around the maximum.
        a, b, c = mean[k - 1 : k + 2]
        denom = a - 2 * b + c
        if denom < 0:
            return float(dts[k] + 0.5 * (a - c) / denom * (dts[1] - dts[0]))
    return float(dts[k])


RELATIVE_SIGMA_LIMIT = 10.0
"""A line whose σ exceeds this many times the median σ of the selected lines is not used."""


def implausible_uncertainty(unc: np.ndarray, used: np.ndarray, limit_s: float) -> np.ndarray:
    """Mask of selected lines whose own uncertainty (s) cannot be trusted.

    Not finite or not positive (R is not curved downwards at the peak), above *limit_s*,
    or above RELATIVE_SIGMA_LIMIT times the median of the other selected lines (with 3
    or more). Such a σ would dominate the combined uncertainty — one flat line made a
    day's 95 % interval 7 s wide although the answer was 18 ms from the truth.
    """
    unc = np.asarray(unc, dtype=float)
    used = np.asarray(used, dtype=bool)
    ok = np.isfinite(unc) & (unc > 0) & (unc <= limit_s)
    bad = used & ~ok
    good = used & ok
    if good.sum() >= 3:
        bad |= good & (unc > RELATIVE_SIGMA_LIMIT * np.median(unc[good]))
    return bad


SCAN_THREADS = 2
"""Lines processed concurrently (the compiled kernels and the FFTs release the GIL)."""


class _Attitude:
    """Attitude records and lever arm: total heave (eq. 2) of line windows on demand.

    A day of 100 Hz attitude is ~10⁷ records: the whole-day total heave would be one more
    80 MB array; the windows the lines need are computed when a line needs them.
    """

    def __init__(self, att: dict, arm: np.ndarray):
        self.t, self.att, self.arm = att["time"], att, arm

    def windows(self, tags: np.ndarray, lo: float, hi: float, pad: int = 0
                ) -> tuple[slice, slice]:
        """(records needed for ``tags − Δt``, Δt in [lo, hi]; the same widened by *pad*
        records on each side, for filtering)."""
        inner = attitude_window(self.t, tags, lo, hi)
        return inner, slice(max(inner.start - pad, 0), min(inner.stop + pad, self.t.size))

    def heave(self, win: slice) -> np.ndarray:
        """Total heave (m, up) of the records *win*."""
        a = self.att
        return total_heave_deg(a["heave"][win], a["roll"][win], a["pitch"][win], self.arm)

    def at(self, times: np.ndarray) -> np.ndarray:
        """Total heave linearly interpolated at *times* (eq. 3), unfiltered.

        Only the two records around each time are evaluated: interpolating over that
        subset gives exactly what interpolating over the whole record gives.
        """
        from hydrosync_core.methods.latency.heave import total_heave_at

        a = self.att
        return total_heave_at(times, self.t, a["heave"], a["roll"], a["pitch"], self.arm)


@dataclasses.dataclass
class _LineWork:
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


def _filtered_line(line, t_g: np.ndarray, hgt: np.ndarray, response, interval: float,
                   degree: int, cache: dict | None = None):
    """A copy of *line* whose heights are filtered zero-phase on a padded GNSS window."""
    from hydrosync_core.methods.latency.prefilter import PAD_S, fft_filter

    if not line.usable:
        return line
    i0 = int(np.searchsorted(t_g, line.tags[0] - PAD_S, side="left"))
    i1 = int(np.searchsorted(t_g, line.tags[-1] + PAD_S, side="right"))
    k0 = int(np.searchsorted(t_g, line.tags[0], side="left")) - i0
    filtered = fft_filter(hgt[i0:i1], interval, response, cache)[k0:k0 + line.tags.size]
    h, _ = detrend(line.tags, filtered, degree)
    return dataclasses.replace(line, h=h, warnings=line.warnings)


def _pooled_weighting(prepared: list, peaks: list, works: list, t_att: np.ndarray,
                      min_r: float, g_int: float):
    """Coherence weighting from all usable lines, aligned at the median first-pass delay.

    The anti-aliased heave at ``tags − Δt0`` comes from each line's first-pass window
    (*works*), filtered once for the whole scan range: it differs from a window filtered
    around Δt0 alone only by the filter's tail beyond the PAD_S padding (~1e-11 m; the
    day's Δt changes by < 1e-10 s).
    """
    from hydrosync_core.methods.latency.prefilter import pooled_weighting

    good = [i for i, (ln, pk) in enumerate(zip(prepared, peaks, strict=True))
            if ln.usable and np.isfinite(pk.latency_s) and not pk.at_edge]
    if not good:
        return None
    sel = [i for i in good if peaks[i].r_max > min_r] or good
    dt0 = float(np.median([peaks[i].latency_s for i in sel]))
    pairs = []
    for i in good:
        ln, work = prepared[i], works[i]
        pairs.append((ln.h, heave_at(ln.tags, np.array([dt0]), t_att[work.inner],
                                     work.antialiased)[0]))
    return pooled_weighting(pairs, g_int)


WINDOWED_SCAN = False
"""True: scan the weighted estimator's second pass only around the first passes' peaks
(:func:`_scan_windows`, about 7 % of auto's time on a survey day). Off by default: a
maximum strictly inside the window is only a local one, so a line whose weighted curve
peaks far from its other two estimates could get another answer than the full scan, and
the results must stay those of the full scan."""

WINDOW_MIN_S = 0.1
"""Smallest half-width (s) of a line's window around its first-pass peaks."""

WINDOW_SIGMAS = 10.0
"""Half-width of the window in the line's own σ (qi2010 pass), when that is wider."""


def _scan(line, ta: np.ndarray, ha: np.ndarray, dts: np.ndarray, uncertainty: bool = True,
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


def _scan_windows(first: list, hints, dts: np.ndarray) -> list:
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


LINES_PER_TASK = 4
"""Lines one thread-pool task takes in turn: a future per line cost ~25 µs of the main
thread's interpreter time (1500 per survey day), which the scan threads wait on."""


def _per_line(task, count: int, names: list, progress, cancel) -> list:
    """``task(i)`` for every line index, in order, on up to SCAN_THREADS threads."""
    from concurrent.futures import ThreadPoolExecutor

    def run(lo: int) -> list:
        return [task(i) for i in range(lo, min(lo + LINES_PER_TASK, count))]

    out: list = []
    with ThreadPoolExecutor(SCAN_THREADS) as pool:
        futures = [pool.submit(run, lo) for lo in range(0, count, LINES_PER_TASK)]
        try:
            for future in futures:
                check_cancel(cancel)
                report(progress, len(out) / max(count, 1), f"line {names[len(out)]}")
                out += future.result()
        except BaseException:
            for future in futures:
                future.cancel()
            raise
    return out


def _unscanned(dts: np.ndarray) -> LinePeak:
    """What :func:`scan_line` gives a line that is not usable."""
    return LinePeak(np.full(dts.size, np.nan))


@dataclasses.dataclass
class _Passes:
    """What :func:`_first_passes` returns: per line, in order (None for a scan skipped)."""

    raw_lines: list | None     # LineData of the qi2010 scan (its warnings its own)
    raw_peaks: list | None
    aa_lines: list | None      # LineData of the anti-aliased scan (the weighted estimator's)
    aa_peaks: list | None
    works: list                # _LineWork (keep) or None
    before: list               # σ0 before (m), NaN for a line not usable


def _first_passes(setup: _Setup, p: LatencyParams, raw: bool, antialias: bool, progress,
                  cancel, aa_sigma: bool = True, keep: bool = False) -> _Passes:
    """Each line prepared (:func:`prepare_line`) and scanned on its raw total heave
    (qi2010, *raw*) and on the anti-aliased one (*antialias*), one task per line.

    Each line's total heave is computed once, on the window padded for filtering, and
    serves both scans; the line is prepared in its task too (its detrending overlaps the
    other thread's compiled work). *aa_sigma*: the anti-aliased scan's uncertainty;
    *keep*: each line's :class:`_LineWork` for the weighted passes. σ0 before (seed
    eqs. 5–6 at Δt = 0) is the same for every estimator and comes from the raw window
    here: :func:`_quality` then interpolates at the final Δt only.
    """
    from hydrosync_core.methods.latency import prefilter

    dts, a_int, t_g, t_att = setup.dts, setup.a_int, setup.t_g, setup.att["time"]
    source = _Attitude(setup.att, setup.arm)
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
        bins_max = max(_band_bins(prefilter.next_fast_len(2 * n), a_int, setup.g_int)
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
            return line_raw, _unscanned(dts), line_aa, _unscanned(dts), None, float("nan")
        inner, padded = windows[i]
        h = source.heave(padded)
        crop = slice(inner.start - padded.start, inner.stop - padded.start)
        ta = source.t[inner]
        # The numbers of _Attitude.at(tags): same records, same interpolation formula.
        before = sigma0(line.h, heave_at(line.tags, np.zeros(1), ta, h[crop])[0])
        pk_raw = pk_aa = work = None
        if raw:
            pk_raw = _scan(line_raw, ta, h[crop], dts)
        if antialias:
            spec = prefilter.spectrum(h)
            del h
            gains = prefilter.response_gains(response, spec.size, a_int, aa_cache)
            ha = prefilter.filtered(spec, gains, crop, out=aa_rows[i] if keep else None)
            pk_aa = _scan(line_aa, ta, ha, dts, uncertainty=aa_sigma)
            if keep:
                work = _LineWork(inner, padded, spec.head(
                    _band_bins(spec.size, a_int, setup.g_int), out=bin_rows[i]), ha)
        return line_raw, pk_raw, line_aa, pk_aa, work, before

    out = _per_line(task, len(sels), setup.names, progress, cancel)
    raw_lines, raw_peaks, aa_lines, aa_peaks, works, before = map(list, zip(*out, strict=True))
    return _Passes(raw_lines if raw else None, raw_peaks if raw else None,
                   aa_lines if antialias else None, aa_peaks if antialias else None,
                   works, before)


def _band_bins(size: int, a_int: float, g_int: float) -> int:
    """``rfft`` bins of *size* samples every *a_int* s up to the GNSS Nyquist frequency
    ``0.5/g_int`` (and one more): beyond them the coherence weight is zero."""
    return min(int(np.floor(0.5 / g_int * size * a_int * (1.0 + 1e-9))) + 2, size // 2 + 1)


def _weighted_pass(setup: _Setup, p: LatencyParams, works: list, weighting, windows: list,
                   progress, cancel) -> list:
    """The weighted scan: heights and total heave filtered with the coherence weight.

    The heave comes from each line's kept spectrum (:class:`_LineWork`), released as
    the line is done.
    """
    from hydrosync_core.methods.latency import prefilter

    dts, a_int, att = setup.dts, setup.a_int, setup.att
    source = _Attitude(att, setup.arm)
    gnss_cache: dict = {}
    heave_cache: dict = {}
    degree = int(p.detrend_degree)

    def task(i: int):
        line = setup.prepared[i]
        if not line.usable:
            return _unscanned(dts)
        scan_input = _filtered_line(line, setup.t_g, setup.hgt, weighting.response,
                                    setup.g_int, degree, gnss_cache)
        work, works[i] = works[i], None
        spec = work.spectrum
        gains = prefilter.response_gains(weighting.response, spec.size, a_int, heave_cache)
        if not spec.covers(gains):  # a weight beyond the kept bins: the whole spectrum
            spec = prefilter.spectrum(source.heave(work.padded))
        crop = slice(work.inner.start - work.padded.start, work.inner.stop - work.padded.start)
        ha = prefilter.filtered(spec, gains, crop)
        return _scan(scan_input, source.t[work.inner], ha, dts, window=windows[i])

    return _per_line(task, len(setup.prepared), setup.names, progress, cancel)


def _weighted(setup: _Setup, p: LatencyParams, first: list, works: list, progress, cancel,
              hints=None) -> tuple[list, list]:
    """The weighted estimator's passes after its anti-aliased first pass *first*.

    Returns ``(peaks, run warnings)``: the weighted peaks carrying the first pass's R
    (curve, R_max), or the first pass's own peaks when the weighting is not possible.
    """
    weighting = _pooled_weighting(setup.prepared, first, works, setup.att["time"], p.min_r,
                                  setup.g_int)
    if weighting is None:
        _add_uncertainty(setup, first, works)
        return first, ["coherence weighting not possible (too few epochs): "
                       "the anti-aliased correlation is used"]
    for work in works:
        if work is not None:
            work.antialiased = None  # the pooled spectra are done: free it before the pass
    peaks = _weighted_pass(setup, p, works, weighting, _scan_windows(first, hints, setup.dts),
                           progress, cancel)
    # R (the selection threshold, the curves shown) stays on the scale of the published
    # R: the anti-aliased correlation; Δt and σ come from the weighted one.
    for pk, pk1 in zip(peaks, first, strict=True):
        pk.curve, pk.r_max = pk1.curve, pk1.r_max
        pk.at_edge = pk.at_edge or pk1.at_edge
    return peaks, []


def _add_uncertainty(setup: _Setup, peaks: list, works: list) -> None:
    """The σ of first-pass peaks scanned without it (same window, same Δt)."""
    t_att = setup.att["time"]
    for ln, pk, work in zip(setup.prepared, peaks, works, strict=True):
        if ln.usable and np.isfinite(pk.latency_s) and not pk.at_edge:
            pk.uncertainty_s = line_uncertainty(ln, t_att[work.inner], work.antialiased,
                                                setup.dts, pk.latency_s)


def estimate_latency(
    gnss: Mapping, attitude: Mapping, lines: Mapping, lever_arm,
    params: LatencyParams | Mapping | None = None, progress=None, cancel=None,
) -> LatencyResult:
    """Estimate the GNSS-versus-attitude delay Δt from survey lines (seed sections 2–3).

    Returns a :class:`LatencyResult`; ``latency_s`` is NaN (``converged`` False) when no
    line passes the R threshold. Raises :class:`InputError` for bad input or when no
    line has enough epochs.
    """
    p = params if isinstance(params, LatencyParams) else LatencyParams.from_dict(params)
    if p.estimator == "auto":
        return _auto(gnss, attitude, lines, lever_arm, p, progress, cancel)
    return _estimate(_setup(gnss, attitude, lines, lever_arm, p), p, progress, cancel)


@dataclasses.dataclass
class _Setup:
    """Checked inputs: what every estimator starts from; *prepared* (the lines' LineData)
    is filled by :func:`_first_passes`, one list per estimator."""

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


def _setup(gnss, attitude, lines, lever_arm, p: LatencyParams) -> _Setup:
    t_g, hgt, att, arm = _check_inputs(gnss, attitude, lever_arm)
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
    return _Setup(t_g, hgt, att, arm, dts, g_int, a_int, names, starts, ends, [])


def _check_usable(setup: _Setup, p: LatencyParams, prepared: list) -> None:
    """Raise InputError when no prepared line has enough epochs with attitude."""
    if not any(line.usable for line in prepared):
        raise InputError("lines", f"no line has {p.min_epochs} or more GNSS epochs with attitude "
                         "data: lines span " + _span_text(np.r_[setup.starts, setup.ends])
                         + ", GNSS " + _span_text(setup.t_g) + ", attitude "
                         + _span_text(setup.att["time"])
                         + " (lines must be on the loggers' time scale)")


def _estimate(setup: _Setup, p: LatencyParams, progress, cancel) -> LatencyResult:
    """One estimator (not auto) from :func:`_setup`'s inputs."""
    if p.estimator == "qi2010":
        passes = _first_passes(setup, p, True, False, sub_progress(progress, 0, 0.9), cancel)
        _check_usable(setup, p, passes.raw_lines)
        setup = dataclasses.replace(setup, prepared=passes.raw_lines)
        return _finish(setup, p, passes.raw_peaks, [], progress, cancel, passes.before)
    weighted = p.estimator == "weighted"
    # The weighted estimator keeps only R_max, Δt and the edge flag of its first pass:
    # no σ there (unless the weighting proves impossible, then that pass is the answer).
    passes = _first_passes(setup, p, False, True,
                           sub_progress(progress, 0, 0.45 if weighted else 0.9), cancel,
                           aa_sigma=not weighted, keep=weighted)
    _check_usable(setup, p, passes.aa_lines)
    setup = dataclasses.replace(setup, prepared=passes.aa_lines)
    first, before = passes.aa_peaks, passes.before
    if not weighted:
        return _finish(setup, p, first, [], progress, cancel, before)
    peaks, warnings_pre = _weighted(setup, p, first, passes.works,
                                    sub_progress(progress, 0.45, 0.9), cancel)
    return _finish(setup, p, peaks, warnings_pre, progress, cancel, before)


def _finish(setup: _Setup, p: LatencyParams, peaks: list, warnings_pre: list, progress,
            cancel, before: list | None = None, joint: bool = True) -> LatencyResult:
    """An estimator's result from its per-line peaks: selection, combination, quality.

    *before*: the lines' σ0 before (:func:`_first_passes`); None leaves σ0 before and
    after NaN (:func:`_with_quality` adds them). *joint* False leaves the joint peak NaN
    (:func:`_with_joint_peak`). ``auto`` computes both for the estimator it keeps only.
    """
    att, arm, dts = setup.att, setup.arm, setup.dts
    t_att = att["time"]
    names, prepared = setup.names, setup.prepared
    lo, hi = p.range_s
    r_max = np.array([pk.r_max for pk in peaks])
    lat = np.array([pk.latency_s for pk in peaks])
    unc = np.array([pk.uncertainty_s for pk in peaks])
    usable = np.array([ln.usable and not pk.at_edge
                       for ln, pk in zip(prepared, peaks, strict=True)])
    used = select_lines(r_max, p.min_r, usable)
    not_credible = implausible_uncertainty(unc, used, p.max_line_sigma_s)
    for i in np.flatnonzero(not_credible):
        prepared[i].warnings.append(
            f"line {names[i]}: its uncertainty {unc[i]:.3g} s is not credible (R peak too "
            f"flat to locate; limit {p.max_line_sigma_s:g} s or {RELATIVE_SIGMA_LIMIT:g}x the "
            "median line): not used (tick it to use it anyway)")
    used &= ~not_credible
    outliers = find_outliers(lat, unc, used, p.outlier_k)
    if outliers.any():
        median = float(np.median(lat[used]))
        for i in np.flatnonzero(outliers):
            prepared[i].warnings.append(
                f"line {names[i]}: Δt {lat[i]:+.3f} s departs from the median {median:+.3f} s "
                f"of the selected lines by more than {p.outlier_k:g} robust σ: not used "
                "(outlier; tick it to use it anyway)")
        used &= ~outliers
    comb = combine(lat, r_max, unc, used, p.weighting)
    curves = np.array([pk.curve for pk in peaks])
    epochs = np.array([ln.tags.size for ln in prepared], dtype=float)
    joint = _joint_peak(curves[used], epochs[used], dts) if joint else float("nan")

    check_cancel(cancel)
    report(progress, 0.92, "quality")
    nan2 = (float("nan"), float("nan"))
    sigmas = (_quality(setup, comb.latency_s, before) if before is not None
              else [nan2] * len(prepared))
    out_lines = []
    for ln, pk, u, (before, after) in zip(prepared, peaks, used, sigmas, strict=True):
        out_lines.append(LineResult(
            ln.name, float(ln.start), float(ln.end), int(ln.tags.size), pk.r_max, pk.latency_s,
            pk.uncertainty_s, before, after, bool(u), pk.at_edge, tuple(ln.warnings)))

    warnings = warnings_pre + [w for ln in prepared for w in ln.warnings]
    n_low = int(np.sum(usable & ~used))
    if n_low:
        warnings.append(f"{n_low} line(s) with R_max <= {p.min_r} not used")
    diagnostics: dict = {}
    med = np.nanmedian(r_max) if np.any(np.isfinite(r_max)) else np.nan
    if comb.n_used == 0 or not med > p.min_r:
        report(progress, 0.95, "testing heave sign and lever arm")
        coarse = np.arange(lo, hi + 1e-12, max(p.step_s, 0.02))
        diagnostics, more = diagnose(prepared, t_att, att["heave"], np.radians(att["roll"]),
                                     np.radians(att["pitch"]), arm, coarse)
        warnings += more
    converged = comb.n_used > 0
    best = f"{np.nanmax(r_max):.3f}" if np.any(np.isfinite(r_max)) else "none"
    message = (f"{comb.n_used} of {len(names)} lines used ({p.weighting} weights, "
               f"{p.estimator} estimator)" if converged
               else f"no line with R_max > {p.min_r}: best R_max {best}")
    report(progress, 1.0, "done")
    return LatencyResult(
        comb.latency_s, comb.uncertainty_s, comb.ci95_low, comb.ci95_high, comb.n_used,
        p.weighting, joint, tuple(out_lines), dts, curves, tuple(float(v) for v in arm),
        p.to_dict(), converged, message, tuple(warnings), diagnostics, p.estimator)


def _quality(setup: _Setup, latency_s: float, before: list) -> list[tuple[float, float]]:
    """Per line (σ0 before, σ0 after) in m: seed eqs. 5–6 at Δt = 0 (*before*, from
    :func:`_first_passes`) and at *latency_s*.

    Always on the raw series (as published); NaN for lines that are not usable, and
    "after" NaN when *latency_s* is not finite.
    """
    source = _Attitude(setup.att, setup.arm)
    final = float(np.nan_to_num(latency_s))

    def after(ln) -> float:
        if not ln.usable or not np.isfinite(latency_s):
            return float("nan")
        return sigma0(ln.h, source.at(ln.tags - final))

    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(SCAN_THREADS) as pool:  # the interpolation releases the GIL
        return list(zip(before, pool.map(after, setup.prepared), strict=True))


def _with_quality(result: LatencyResult, setup: _Setup, before: list) -> LatencyResult:
    """*result* with its lines' σ0 before/after (a :func:`_finish` without *before*)."""
    sigmas = _quality(setup, result.latency_s, before)
    lines = tuple(dataclasses.replace(ln, sigma0_before_m=before, sigma0_after_m=after)
                  for ln, (before, after) in zip(result.lines, sigmas, strict=True))
    return dataclasses.replace(result, lines=lines)


def _with_joint_peak(result: LatencyResult) -> LatencyResult:
    """*result* with its joint peak (a :func:`_finish` with *joint* False)."""
    used = np.array([ln.used for ln in result.lines], dtype=bool)
    epochs = np.array([ln.epochs for ln in result.lines], dtype=float)
    return dataclasses.replace(result, joint_latency_s=_joint_peak(
        result.r_curves[used], epochs[used], result.dt_grid))


def _auto(gnss, attitude, lines, lever_arm, p: LatencyParams, progress, cancel
          ) -> LatencyResult:
    """``estimator = auto``: qi2010 and weighted, the one with the smaller uncertainty.

    One set-up, and one pass over the lines for the qi2010 scan and the weighted
    estimator's anti-aliased first pass (each line's total heave computed once); the
    σ0 quality figures are computed for the estimator kept only.
    """
    setup = _setup(gnss, attitude, lines, lever_arm, p)  # checked once
    p_qi = dataclasses.replace(p, estimator="qi2010")
    p_w = dataclasses.replace(p, estimator="weighted")
    passes = _first_passes(setup, p, True, True, sub_progress(progress, 0.0, 0.6), cancel,
                           aa_sigma=False, keep=True)
    _check_usable(setup, p, passes.raw_lines)
    s_qi = dataclasses.replace(setup, prepared=passes.raw_lines)
    s_w = dataclasses.replace(setup, prepared=passes.aa_lines)
    raw, first, works, before = passes.raw_peaks, passes.aa_peaks, passes.works, passes.before
    hints = [(pk.latency_s, pk.uncertainty_s) for pk in raw]
    peaks, warnings_pre = _weighted(s_w, p_w, first, works, sub_progress(progress, 0.6, 0.9),
                                    cancel, hints=hints)
    runs = {"qi2010": (_finish(s_qi, p_qi, raw, [], None, cancel, joint=False), s_qi),
            "weighted": (_finish(s_w, p_w, peaks, warnings_pre, None, cancel, joint=False),
                         s_w)}

    def key(r: LatencyResult) -> float:
        return r.uncertainty_s if r.converged and np.isfinite(r.uncertainty_s) else np.inf

    best = min((r for r, _ in runs.values()), key=key)
    other = runs["weighted" if best.estimator == "qi2010" else "qi2010"][0]
    report(progress, 0.95, "quality")
    best = _with_joint_peak(_with_quality(best, runs[best.estimator][1], before))
    report(progress, 1.0, "done")
    note = (f"auto: {best.estimator} (σ {best.uncertainty_s * 1e3:.2f} ms; {other.estimator} "
            f"{other.uncertainty_s * 1e3:.2f} ms, Δt {other.latency_s:+.4f} s)")
    return dataclasses.replace(best, params=p.to_dict(),
                               message=f"{best.message}; {note}" if best.converged
                               else best.message)


def _attitude_at(attitude: Mapping, times: np.ndarray) -> dict[str, np.ndarray]:
    """Seed eq. 3: attitude linearly interpolated at *times* (deg; heading unwrapped)."""
    t = np.asarray(attitude["time"], dtype=float)
    out = {c: np.interp(times, t, np.asarray(attitude[c], dtype=float))
           for c in ("roll", "pitch", "heave")}
    # Heading wraps at 360 deg: interpolate along the shorter arc between the two
    # neighbouring samples (no unwrapping of the whole record: memory of the output only).
    heading = np.asarray(attitude["heading"], dtype=float)
    k = np.clip(np.searchsorted(t, times), 1, t.size - 1)
    h0, h1 = heading[k - 1], heading[k]
    w = (times - t[k - 1]) / (t[k] - t[k - 1])
    out["heading"] = (h0 + w * ((h1 - h0 + 180.0) % 360.0 - 180.0)) % 360.0
    return out


def synchronise(gnss: Mapping, attitude: Mapping, lever_arm, latency_s: float) -> dict:
    """GNSS heights with attitude at their corrected times ``tag − latency_s`` (seed eq. 3).

    Returns a dict of 1-D arrays: ``time`` (s, corrected), ``height`` (m), ``roll``,
    ``pitch``, ``heading`` (deg), ``heave`` and ``total_heave`` (m, up, seed eq. 2) —
    only the epochs whose corrected time lies inside the attitude record.
    """
    if not np.isfinite(latency_s):
        raise InputError(None, "cannot synchronise without a latency", field="latency_s")
    t_g, hgt, att, arm = _check_inputs(gnss, attitude, lever_arm)
    corrected = t_g - latency_s
    keep = (corrected >= att["time"][0]) & (corrected <= att["time"][-1])
    out = {"time": corrected[keep], "height": hgt[keep]}
    out.update(_attitude_at(attitude, corrected[keep]))
    out["total_heave"] = total_heave(
        out["heave"], np.radians(out["roll"]), np.radians(out["pitch"]), arm)
    return {k: out[k] for k in ("time", "height", "roll", "pitch", "heading", "heave",
                                "total_heave")}


def line_series(
    gnss: Mapping, attitude: Mapping, lever_arm, start: float, end: float, latency_s: float,
    params: LatencyParams | Mapping | None = None,
) -> dict[str, np.ndarray]:
    """One line's detrended heights and total heave before (Δt = 0) and after (seed fig. 4).

    Returns ``time`` (s, tags), ``height`` (m, detrended), ``heave_before`` and
    ``heave_after`` (m, total heave at ``tag`` and at ``tag − latency_s``).
    """
    p = params if isinstance(params, LatencyParams) else LatencyParams.from_dict(params)
    dt = float(np.nan_to_num(latency_s))
    empty = np.empty(0)
    nothing = {"time": empty, "height": empty, "heave_before": empty, "heave_after": empty}
    # The records around the line only (with the one beyond each end, which the
    # interpolation may need across a gap): the same numbers as the whole day's, without
    # checking and transforming a day's 8 million attitude records for one line's plot.
    lo, hi = float(start) - abs(dt) - 1.0, float(end) + abs(dt) + 1.0
    gnss, attitude = _records_within(gnss, lo, hi), _records_within(attitude, lo, hi)
    if gnss is None or attitude is None:
        return nothing
    t_g, hgt, att, arm = _check_inputs(gnss, attitude, lever_arm)
    sel = line_epochs(t_g, start, end, p.skip_s, att["time"], min(dt, 0.0), max(dt, 0.0))
    tags = t_g[sel]
    if tags.size < 3:
        return nothing
    h, _ = detrend(tags, hgt[sel], int(p.detrend_degree))
    h_att = total_heave_deg(att["heave"], att["roll"], att["pitch"], arm)
    H = heave_at(tags, np.array([0.0, dt]), att["time"], h_att)
    return {"time": tags, "height": h, "heave_before": H[0], "heave_after": H[1]}


def _records_within(table: Mapping, lo: float, hi: float) -> dict | None:
    """The rows of *table* (increasing ``time``, s) in [lo, hi] and the one beyond each
    end; None when fewer than 2 rows remain."""
    if "time" not in table:
        return dict(table)  # _check_inputs names what is missing
    t = np.asarray(table["time"], dtype=float)
    i0 = max(int(np.searchsorted(t, lo, side="left")) - 1, 0)
    i1 = min(int(np.searchsorted(t, hi, side="right")) + 1, t.size)
    if i1 - i0 < 2:
        return None
    return {name: np.asarray(values)[i0:i1] for name, values in table.items()
            if np.ndim(values) == 1 and len(values) == t.size}
