"""The weighted estimator's passes: coherence weighting pooled over the lines, then each
line's heights and total heave filtered with it and scanned again."""

from __future__ import annotations

import dataclasses

import numpy as np

from hydrosync_core.methods.latency import passes, prefilter
from hydrosync_core.methods.latency.correlation import heave_at
from hydrosync_core.methods.latency.detrend import detrend
from hydrosync_core.methods.latency.heave_windows import HeaveWindows
from hydrosync_core.methods.latency.inputs import Setup
from hydrosync_core.methods.latency.lines import line_uncertainty
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.threads import per_line


def filtered_line(line, t_g: np.ndarray, hgt: np.ndarray, response, interval: float,
                   degree: int, cache: dict | None = None):
    """A copy of *line* whose heights are filtered zero-phase on a padded GNSS window."""
    if not line.usable:
        return line
    i0 = int(np.searchsorted(t_g, line.tags[0] - prefilter.PAD_S, side="left"))
    i1 = int(np.searchsorted(t_g, line.tags[-1] + prefilter.PAD_S, side="right"))
    k0 = int(np.searchsorted(t_g, line.tags[0], side="left")) - i0
    filtered = prefilter.fft_filter(hgt[i0:i1], interval, response, cache)[k0:k0 + line.tags.size]
    h, _ = detrend(line.tags, filtered, degree)
    return dataclasses.replace(line, h=h, warnings=line.warnings)


def pooled_weighting(prepared: list, peaks: list, works: list, t_att: np.ndarray,
                      min_r: float, g_int: float):
    """Coherence weighting from all usable lines, aligned at the median first-pass delay.

    The anti-aliased heave at ``tags − Δt0`` comes from each line's first-pass window
    (*works*), filtered once for the whole scan range: it differs from a window filtered
    around Δt0 alone only by the filter's tail beyond the prefilter.PAD_S padding (~1e-11 m; the
    day's Δt changes by < 1e-10 s).
    """
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
    return prefilter.pooled_weighting(pairs, g_int)


def weighted_pass(setup: Setup, p: LatencyParams, works: list, weighting, windows: list,
                   progress, cancel) -> list:
    """The weighted scan: heights and total heave filtered with the coherence weight.

    The heave comes from each line's kept spectrum (:class:`LineWork`), released as
    the line is done.
    """
    dts, a_int, att = setup.dts, setup.a_int, setup.att
    source = HeaveWindows(att, setup.arm)
    gnss_cache: dict = {}
    heave_cache: dict = {}
    degree = int(p.detrend_degree)

    def task(i: int):
        line = setup.prepared[i]
        if not line.usable:
            return passes.unscanned(dts)
        scan_input = filtered_line(line, setup.t_g, setup.hgt, weighting.response,
                                    setup.g_int, degree, gnss_cache)
        work, works[i] = works[i], None
        spec = work.spectrum
        gains = prefilter.response_gains(weighting.response, spec.size, a_int, heave_cache)
        if not spec.covers(gains):  # a weight beyond the kept bins: the whole spectrum
            spec = prefilter.spectrum(source.heave(work.padded))
        crop = slice(work.inner.start - work.padded.start, work.inner.stop - work.padded.start)
        ha = prefilter.filtered(spec, gains, crop)
        return passes.scan(scan_input, source.t[work.inner], ha, dts, window=windows[i])

    return per_line(task, len(setup.prepared), setup.names, progress, cancel)


def weighted_passes(setup: Setup, p: LatencyParams, first: list, works: list, progress, cancel,
              hints=None) -> tuple[list, list]:
    """The weighted estimator's passes after its anti-aliased first pass *first*.

    Returns ``(peaks, run warnings)``: the weighted peaks carrying the first pass's R
    (curve, R_max), or the first pass's own peaks when the weighting is not possible.
    """
    weighting = pooled_weighting(setup.prepared, first, works, setup.att["time"], p.min_r,
                                  setup.g_int)
    if weighting is None:
        add_uncertainty(setup, first, works)
        return first, ["coherence weighting not possible (too few epochs or Welch segments): "
                       "the anti-aliased correlation is used"]
    for work in works:
        if work is not None:
            work.antialiased = None  # the pooled spectra are done: free it before the pass
    peaks = weighted_pass(setup, p, works, weighting, passes.scan_windows(first, hints, setup.dts),
                           progress, cancel)
    # R (the selection threshold, the curves shown) stays on the scale of the published
    # R: the anti-aliased correlation; Δt and σ come from the weighted one.
    for pk, pk1 in zip(peaks, first, strict=True):
        pk.curve, pk.r_max = pk1.curve, pk1.r_max
        pk.at_edge = pk.at_edge or pk1.at_edge
    return peaks, []


def add_uncertainty(setup: Setup, peaks: list, works: list) -> None:
    """The σ of first-pass peaks scanned without it (same window, same Δt)."""
    t_att = setup.att["time"]
    for ln, pk, work in zip(setup.prepared, peaks, works, strict=True):
        if ln.usable and np.isfinite(pk.latency_s) and not pk.at_edge:
            pk.uncertainty_s = line_uncertainty(ln, t_att[work.inner], work.antialiased,
                                                setup.dts, pk.latency_s)
