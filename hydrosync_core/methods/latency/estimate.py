"""Latency between GNSS heights and attitude/heave by correlative approximation (seed 000):
:func:`estimate_latency`, the entry point of every estimator (qi2010, anti-aliased,
weighted, auto)."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import numpy as np

from hydrosync_core.methods.latency import passes, weighted
from hydrosync_core.methods.latency.fix_quality import screen_fixes
from hydrosync_core.methods.latency.heave_filter import with_declared_filter
from hydrosync_core.methods.latency.inputs import Setup, check_inputs, check_usable, set_up
from hydrosync_core.methods.latency.model_flags import with_model_check
from hydrosync_core.methods.latency.outcome import finish, with_joint_peak, with_quality
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.result import LatencyResult
from hydrosync_core.methods.latency.upsample import band_limited, upsampling_factor
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
    gnss, fix_warnings = screen_fixes(gnss, p.fix_qualities)
    if p.heave_filter == "highpass":
        check_inputs(gnss, attitude, lever_arm)  # a one-line error before filtering
        gnss, attitude = with_declared_filter(gnss, attitude, lever_arm, p.heave_filter_order,
                                              p.heave_filter_period_s)
    factor = upsampling_factor(np.asarray(attitude["time"], dtype=float),
                               gnss.get("time")) \
        if p.estimator != "qi2010" and "time" in attitude else 1
    fine = band_limited(attitude, factor) if factor > 1 else attitude
    if p.estimator == "auto" and factor > 1:
        result = _auto_apart(gnss, attitude, fine, lines, lever_arm, p, progress, cancel)
    elif p.estimator == "auto":
        result = _auto(gnss, attitude, lines, lever_arm, p, progress, cancel)
    else:
        result = _single(set_up(gnss, fine, lines, lever_arm, p), p, progress, cancel)
    if factor > 1:
        result = dataclasses.replace(result, diagnostics={
            **result.diagnostics, "attitude_upsampled": factor})
    result = with_model_check(result, gnss, fine, p)
    if fix_warnings:
        result = dataclasses.replace(result, warnings=result.warnings + tuple(fix_warnings))
    return result


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


def _auto_apart(gnss, attitude, fine, lines, lever_arm, p: LatencyParams, progress, cancel
                ) -> LatencyResult:
    """``auto`` on a low-rate attitude record: qi2010 on the records as published, the
    weighted estimator on the band-limited upsampled ones (:mod:`.upsample`). The weighted
    one is kept whenever it converges: the published linear interpolation of 1 Hz records
    is biased (−9…−15 ms on simulated days where its σ was the smaller, 2 of 20 days
    outside the interval); qi2010 is quoted beside it and the gap is checked."""
    runs = {"qi2010": _single(set_up(gnss, attitude, lines, lever_arm, p), dataclasses.replace(
                p, estimator="qi2010"), sub_progress(progress, 0.0, 0.4), cancel),
            "weighted": _single(set_up(gnss, fine, lines, lever_arm, p), dataclasses.replace(
                p, estimator="weighted"), sub_progress(progress, 0.4, 1.0), cancel)}
    return _chosen(runs, p, prefer="weighted" if runs["weighted"].converged else None)


def _sigma_key(r: LatencyResult) -> float:
    return r.uncertainty_s if r.converged and np.isfinite(r.uncertainty_s) else np.inf


def _chosen(runs: dict, p: LatencyParams, prefer: str | None = None) -> LatencyResult:
    """The run with the smaller σ (or *prefer*), quoting the other (message and
    diagnostics)."""
    best = runs[prefer] if prefer else min(runs.values(), key=_sigma_key)
    other = runs["weighted" if best.estimator == "qi2010" else "qi2010"]
    why = "" if prefer is None else ", upsampled attitude"
    note = (f"auto: {best.estimator}{why} (σ {best.uncertainty_s * 1e3:.2f} ms; {other.estimator} "
            f"{other.uncertainty_s * 1e3:.2f} ms, Δt {other.latency_s:+.4f} s)")
    diagnostics = {**best.diagnostics, "other_estimate": {
        "estimator": other.estimator, "latency_s": other.latency_s,
        "uncertainty_s": other.uncertainty_s}}
    return dataclasses.replace(best, params=p.to_dict(), diagnostics=diagnostics,
                               message=f"{best.message}; {note}" if best.converged
                               else best.message)


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

    best = min((r for r, _ in runs.values()), key=_sigma_key)
    report(progress, 0.95, "quality")
    best = with_joint_peak(with_quality(best, runs[best.estimator][1], before))
    report(progress, 1.0, "done")
    return _chosen({**{name: r for name, (r, _) in runs.items()}, best.estimator: best}, p)
