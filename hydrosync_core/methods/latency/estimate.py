"""Latency between GNSS heights and attitude/heave by correlative approximation (seed 000):
:func:`estimate_latency`, the entry point of every estimator (qi2010, anti-aliased,
weighted, auto)."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import numpy as np

from hydrosync_core.methods.latency import passes, weighted
from hydrosync_core.methods.latency.inputs import Setup, check_usable, set_up
from hydrosync_core.methods.latency.outcome import finish, with_joint_peak, with_quality
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.result import LatencyResult
from hydrosync_core.progress import report, sub_progress


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
    return _single(set_up(gnss, attitude, lines, lever_arm, p), p, progress, cancel)


def _single(setup: Setup, p: LatencyParams, progress, cancel) -> LatencyResult:
    """One estimator (not auto) from :func:`set_up`'s inputs."""
    if p.estimator == "qi2010":
        scans = passes.first_passes(setup, p, True, False, sub_progress(progress, 0, 0.9), cancel)
        check_usable(setup, p, scans.raw_lines)
        setup = dataclasses.replace(setup, prepared=scans.raw_lines)
        return finish(setup, p, scans.raw_peaks, [], progress, cancel, scans.before)
    is_weighted = p.estimator == "weighted"
    # The weighted estimator keeps only R_max, Δt and the edge flag of its first pass:
    # no σ there (unless the weighting proves impossible, then that pass is the answer).
    scans = passes.first_passes(setup, p, False, True,
                                sub_progress(progress, 0, 0.45 if is_weighted else 0.9),
                                cancel, aa_sigma=not is_weighted, keep=is_weighted)
    check_usable(setup, p, scans.aa_lines)
    setup = dataclasses.replace(setup, prepared=scans.aa_lines)
    first, before = scans.aa_peaks, scans.before
    if not is_weighted:
        return finish(setup, p, first, [], progress, cancel, before)
    peaks, warnings_pre = weighted.weighted_passes(setup, p, first, scans.works,
                                                   sub_progress(progress, 0.45, 0.9), cancel)
    return finish(setup, p, peaks, warnings_pre, progress, cancel, before)


def _auto(gnss, attitude, lines, lever_arm, p: LatencyParams, progress, cancel
          ) -> LatencyResult:
    """``estimator = auto``: qi2010 and weighted, the one with the smaller uncertainty.

    One set-up, and one pass over the lines for the qi2010 scan and the weighted
    estimator's anti-aliased first pass (each line's total heave computed once); the
    σ0 quality figures are computed for the estimator kept only.
    """
    setup = set_up(gnss, attitude, lines, lever_arm, p)  # checked once
    p_qi = dataclasses.replace(p, estimator="qi2010")
    p_w = dataclasses.replace(p, estimator="weighted")
    scans = passes.first_passes(setup, p, True, True, sub_progress(progress, 0.0, 0.6),
                                cancel, aa_sigma=False, keep=True)
    check_usable(setup, p, scans.raw_lines)
    s_qi = dataclasses.replace(setup, prepared=scans.raw_lines)
    s_w = dataclasses.replace(setup, prepared=scans.aa_lines)
    raw, first, works, before = scans.raw_peaks, scans.aa_peaks, scans.works, scans.before
    hints = [(pk.latency_s, pk.uncertainty_s) for pk in raw]
    peaks, warnings_pre = weighted.weighted_passes(
        s_w, p_w, first, works, sub_progress(progress, 0.6, 0.9), cancel, hints=hints)
    runs = {"qi2010": (finish(s_qi, p_qi, raw, [], None, cancel, joint=False), s_qi),
            "weighted": (finish(s_w, p_w, peaks, warnings_pre, None, cancel, joint=False),
                         s_w)}

    def key(r: LatencyResult) -> float:
        return r.uncertainty_s if r.converged and np.isfinite(r.uncertainty_s) else np.inf

    best = min((r for r, _ in runs.values()), key=key)
    other = runs["weighted" if best.estimator == "qi2010" else "qi2010"][0]
    report(progress, 0.95, "quality")
    best = with_joint_peak(with_quality(best, runs[best.estimator][1], before))
    report(progress, 1.0, "done")
    note = (f"auto: {best.estimator} (σ {best.uncertainty_s * 1e3:.2f} ms; {other.estimator} "
            f"{other.uncertainty_s * 1e3:.2f} ms, Δt {other.latency_s:+.4f} s)")
    return dataclasses.replace(best, params=p.to_dict(),
                               message=f"{best.message}; {note}" if best.converged
                               else best.message)
