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

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.combine import combine, find_outliers, select_lines
from hydrosync_core.methods.latency.correlation import heave_at
from hydrosync_core.methods.latency.detrend import detrend
from hydrosync_core.methods.latency.diagnose import diagnose
from hydrosync_core.methods.latency.heave import total_heave, total_heave_deg
from hydrosync_core.methods.latency.lines import (
    attitude_window,
    line_epochs,
    prepare_line,
    scan_line,
    scan_line_window,
)
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.quality import sigma0
from hydrosync_core.methods.latency.result import LatencyResult, LineResult
from hydrosync_core.progress import check_cancel, report, sub_progress
from hydrosync_core.timespan import span_of


def _column(table: Mapping, name: str, source: str) -> np.ndarray:
    if name not in table:
        raise InputError(source, f"missing column {name}", field=name)
    values = np.asarray(table[name], dtype=float).ravel()
    if not np.all(np.isfinite(values)):
        raise InputError(source, "non-finite values", field=name)
    return values


def _check_inputs(gnss: Mapping, attitude: Mapping, lever_arm) -> tuple:
    t_g, hgt = _column(gnss, "time", "gnss"), _column(gnss, "height", "gnss")
    att = {c: _column(attitude, c, "attitude") for c in ("time", "roll", "pitch", "heave")}
    if t_g.size < 2 or att["time"].size < 2:
        raise InputError("gnss" if t_g.size < 2 else "attitude", "fewer than 2 epochs")
    if np.any(t_g[1:] <= t_g[:-1]):
        raise InputError("gnss", "time tags are not strictly increasing", field="time")
    if np.any(att["time"][1:] <= att["time"][:-1]):
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
    z = np.arctanh(np.clip(curves, -0.999999, 0.999999))
    mean = np.nansum(z * weights[:, None], axis=0) / weights.sum()
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
"""Lines scanned concurrently (the compiled kernel releases the GIL)."""


class _Attitude:
    """Total heave (eq. 2) of the attitude records, computed per line window on demand.

    A day of 100 Hz attitude is ~10⁷ records: the whole-day total heave would be one more
    80 MB array; the windows the lines need are computed when a line needs them. With a
    *response* (callable of f in Hz) the window is padded by ``prefilter.PAD_S`` seconds
    of records, filtered zero-phase and cropped back (anti-alias / coherence weighting).
    """

    def __init__(self, att: dict, arm: np.ndarray, response=None, interval: float = 0.0):
        self.t, self.att, self.arm = att["time"], att, arm
        self.response, self.interval = response, interval
        self.cache: dict = {}  # the response per FFT length (prefilter.fft_filter)

    def window(self, tags: np.ndarray, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
        """(times, total heave) of the records needed for ``tags − Δt``, Δt in [lo, hi]."""
        if tags.size == 0:
            return self.t[:0], self.t[:0]
        win = attitude_window(self.t, tags, lo, hi)
        if self.response is not None:
            from hydrosync_core.methods.latency.prefilter import PAD_S

            pad = int(round(PAD_S / self.interval))
            win = slice(max(win.start - pad, 0), min(win.stop + pad, self.t.size))
        a = self.att
        h = total_heave_deg(a["heave"][win], a["roll"][win], a["pitch"][win], self.arm)
        if self.response is None:
            return self.t[win], h
        from hydrosync_core.methods.latency.prefilter import fft_filter

        inner = attitude_window(self.t, tags, lo, hi)
        crop = slice(inner.start - win.start, inner.stop - win.start)
        return self.t[inner], fft_filter(h, self.interval, self.response, self.cache)[crop]


    def at(self, times: np.ndarray) -> np.ndarray:
        """Total heave linearly interpolated at *times* (eq. 3), unfiltered.

        Only the two records around each time are evaluated: interpolating over that
        subset gives exactly what interpolating over the whole record gives.
        """
        from hydrosync_core.methods.latency.heave import total_heave_at

        a = self.att
        return total_heave_at(times, self.t, a["heave"], a["roll"], a["pitch"], self.arm)


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


def _pooled_weighting(prepared: list, peaks: list, source: _Attitude, min_r: float,
                      g_int: float):
    """Coherence weighting from all usable lines, aligned at the median first-pass delay."""
    from hydrosync_core.methods.latency.prefilter import pooled_weighting

    good = [i for i, (ln, pk) in enumerate(zip(prepared, peaks, strict=True))
            if ln.usable and np.isfinite(pk.latency_s) and not pk.at_edge]
    if not good:
        return None
    sel = [i for i in good if peaks[i].r_max > min_r] or good
    dt0 = float(np.median([peaks[i].latency_s for i in sel]))
    pairs = []
    for i in good:
        ln = prepared[i]
        ta, ha = source.window(ln.tags, dt0, dt0)
        pairs.append((ln.h, heave_at(ln.tags, np.array([dt0]), ta, ha)[0]))
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


def _scan_one(line, source: _Attitude, dts: np.ndarray, uncertainty: bool = True,
              window: tuple[int, int] | None = None):
    ta, ha = source.window(line.tags, float(dts[0]), float(dts[-1]))
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


def _scan_lines(prepared: list, source: _Attitude, dts: np.ndarray, progress, cancel,
                uncertainty: bool = True, windows: list | None = None) -> list:
    """:func:`scan_line` of every line, in order, on up to SCAN_THREADS threads.

    *windows*: per line None (every candidate) or ``(k0, k1)`` (:func:`scan_line_window`,
    with the full scan when the window fails its checks).
    """
    from concurrent.futures import ThreadPoolExecutor

    windows = windows or [None] * len(prepared)
    peaks = []
    with ThreadPoolExecutor(SCAN_THREADS) as pool:
        futures = [pool.submit(_scan_one, line, source, dts, uncertainty, win)
                   for line, win in zip(prepared, windows, strict=True)]
        try:
            for i, future in enumerate(futures):
                check_cancel(cancel)
                report(progress, i / len(futures), f"line {prepared[i].name}")
                peaks.append(future.result())
        except BaseException:
            for future in futures:
                future.cancel()
            raise
    return peaks


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
    """Checked inputs and prepared lines: what every estimator starts from."""

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

    def fresh(self) -> _Setup:
        """A copy whose lines have their own warning lists (an estimator appends to them)."""
        return dataclasses.replace(self, prepared=[
            dataclasses.replace(ln, warnings=list(ln.warnings)) for ln in self.prepared])


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
    prepared = [prepare_line(name, starts[i], ends[i], t_g, hgt, t_att, p, g_int, a_int)
                for i, name in enumerate(names)]
    return _Setup(t_g, hgt, att, arm, dts, g_int, a_int, names, starts, ends, prepared)


def _estimate(setup: _Setup, p: LatencyParams, progress, cancel, hints=None) -> LatencyResult:
    """One estimator (not auto) from :func:`_setup`'s inputs.

    *hints*: per-line ``(Δt, σ)`` of another estimator on the same lines (``auto`` gives
    its qi2010 run's), used only to place the weighted pass's scan windows.
    """
    t_g, hgt, att, arm = setup.t_g, setup.hgt, setup.att, setup.arm
    t_att = att["time"]
    dts, g_int, a_int = setup.dts, setup.g_int, setup.a_int
    names, starts, ends, prepared = setup.names, setup.starts, setup.ends, setup.prepared
    lo, hi = p.range_s
    # Seed eq. 2: total heave at the antenna, at attitude rate (per line window).
    source = _Attitude(att, arm)
    raw_source = source
    weighting = None
    if p.estimator != "qi2010":
        from hydrosync_core.methods.latency import prefilter

        cutoff = prefilter.ANTIALIAS_FRACTION * 0.5 / g_int
        source = _Attitude(att, arm, lambda f: prefilter.antialias_response(f, cutoff), a_int)
    # The weighted estimator keeps only R_max, Δt and the edge flag of its first pass:
    # no σ there (unless the weighting proves impossible, then that pass is the answer).
    weighted = p.estimator == "weighted"
    first_sigma = not (weighted and WINDOWED_SCAN)
    peaks = _scan_lines(prepared, source, dts,
                        sub_progress(progress, 0, 0.45 if weighted else 0.9), cancel,
                        uncertainty=first_sigma)
    if weighted:
        weighting = _pooled_weighting(prepared, peaks, source, p.min_r, g_int)
        if weighting is None:
            warnings_pre = ["coherence weighting not possible (too few epochs): "
                            "the anti-aliased correlation is used"]
            if not first_sigma:
                _add_uncertainty(prepared, peaks, source, dts)
        else:
            warnings_pre = []
            source = _Attitude(att, arm, weighting.response, a_int)
            gnss_cache: dict = {}
            scan_input = [_filtered_line(ln, t_g, hgt, weighting.response, g_int,
                                         int(p.detrend_degree), gnss_cache)
                          for ln in prepared]
            first = peaks
            peaks = _scan_lines(scan_input, source, dts, sub_progress(progress, 0.45, 0.9),
                                cancel, windows=_scan_windows(first, hints, dts))
            # R (the selection threshold, the curves shown) stays on the scale of the
            # published R: the anti-aliased correlation; Δt and σ come from the weighted one.
            for pk, pk1 in zip(peaks, first, strict=True):
                pk.curve, pk.r_max = pk1.curve, pk1.r_max
                pk.at_edge = pk.at_edge or pk1.at_edge
    else:
        warnings_pre = []
    if not any(line.usable for line in prepared):
        raise InputError("lines", f"no line has {p.min_epochs} or more GNSS epochs with attitude "
                         "data: lines span " + _span_text(np.r_[starts, ends])
                         + ", GNSS " + _span_text(t_g) + ", attitude " + _span_text(t_att)
                         + " (lines must be on the loggers' time scale)")

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
    joint = _joint_peak(curves[used], epochs[used], dts)

    check_cancel(cancel)
    report(progress, 0.92, "quality")
    final = float(np.nan_to_num(comb.latency_s))

    def quality(ln) -> tuple[float, float]:
        if not ln.usable:
            return float("nan"), float("nan")
        # Seed eqs. 5–6 before (Δt = 0) and after (final Δt) synchronisation, always on
        # the raw series (as published).
        H0 = raw_source.at(np.concatenate([ln.tags, ln.tags - final])).reshape(2, -1)
        after = sigma0(ln.h, H0[1]) if np.isfinite(comb.latency_s) else float("nan")
        return sigma0(ln.h, H0[0]), after

    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(SCAN_THREADS) as pool:  # the interpolation releases the GIL
        sigmas = list(pool.map(quality, prepared))
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


def _add_uncertainty(prepared: list, peaks: list, source: _Attitude, dts: np.ndarray) -> None:
    """The σ that a pass scanned without uncertainty would have had (same window, same Δt)."""
    from hydrosync_core.methods.latency.correlation import peak_uncertainty

    for ln, pk in zip(prepared, peaks, strict=True):
        if ln.usable and np.isfinite(pk.latency_s) and not pk.at_edge:
            ta, ha = source.window(ln.tags, float(dts[0]), float(dts[-1]))
            pk.uncertainty_s = peak_uncertainty(ln.tags, ln.h, ta, ha, pk.latency_s)


def _auto(gnss, attitude, lines, lever_arm, p: LatencyParams, progress, cancel
          ) -> LatencyResult:
    """``estimator = auto``: qi2010 and weighted, the one with the smaller uncertainty.

    One set-up; the weighted run's second pass scans each line only around its
    anti-aliased and qi2010 peaks (:func:`_scan_windows`), with the full scan for any line
    whose window does not settle the answer (:func:`.lines.scan_line_window`).
    """
    runs = {}
    setup = _setup(gnss, attitude, lines, lever_arm, p)  # checked and prepared once
    runs["qi2010"] = _estimate(setup.fresh(), dataclasses.replace(p, estimator="qi2010"),
                               sub_progress(progress, 0.0, 0.4), cancel)
    hints = [(ln.latency_s, ln.uncertainty_s) for ln in runs["qi2010"].lines]
    runs["weighted"] = _estimate(setup.fresh(), dataclasses.replace(p, estimator="weighted"),
                                 sub_progress(progress, 0.4, 1.0), cancel, hints=hints)

    def key(r: LatencyResult) -> float:
        return r.uncertainty_s if r.converged and np.isfinite(r.uncertainty_s) else np.inf

    best = min(runs.values(), key=key)
    other = runs["weighted" if best.estimator == "qi2010" else "qi2010"]
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
    t_g, hgt, att, arm = _check_inputs(gnss, attitude, lever_arm)
    dt = float(np.nan_to_num(latency_s))
    sel = line_epochs(t_g, start, end, p.skip_s, att["time"], min(dt, 0.0), max(dt, 0.0))
    tags = t_g[sel]
    if tags.size < 3:
        empty = np.empty(0)
        return {"time": empty, "height": empty, "heave_before": empty, "heave_after": empty}
    h, _ = detrend(tags, hgt[sel], int(p.detrend_degree))
    h_att = total_heave_deg(att["heave"], att["roll"], att["pitch"], arm)
    H = heave_at(tags, np.array([0.0, dt]), att["time"], h_att)
    return {"time": tags, "height": h, "heave_before": H[0], "heave_after": H[1]}
