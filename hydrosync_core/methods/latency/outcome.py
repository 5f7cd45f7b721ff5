"""An estimator's result from its per-line peaks: line selection, combination, joint peak and
the σ0 quality figures (seed eqs. 4–6)."""

from __future__ import annotations

import dataclasses
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from hydrosync_core.methods.latency.combine import combine, find_outliers, select_lines
from hydrosync_core.methods.latency.diagnose import diagnose
from hydrosync_core.methods.latency.heave_windows import HeaveWindows
from hydrosync_core.methods.latency.inputs import Setup
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.quality import sigma0
from hydrosync_core.methods.latency.result import LatencyResult, LineResult
from hydrosync_core.methods.latency.threads import SCAN_THREADS
from hydrosync_core.progress import check_cancel, report

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


def joint_peak(curves: np.ndarray, weights: np.ndarray, dts: np.ndarray) -> float:
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


def finish(setup: Setup, p: LatencyParams, peaks: list, warnings_pre: list, progress,
            cancel, before: list | None = None, joint: bool = True) -> LatencyResult:
    """An estimator's result from its per-line peaks: selection, combination, quality.

    *before*: the lines' σ0 before (:func:`first_passes`); None leaves σ0 before and
    after NaN (:func:`with_quality` adds them). *joint* False leaves the joint peak NaN
    (:func:`with_joint_peak`). ``auto`` computes both for the estimator it keeps only.
    """
    att, arm, dts = setup.att, setup.arm, setup.dts
    t_att = att["time"]
    names, prepared = setup.names, setup.prepared
    lo, hi = p.range_s
    r_max = np.array([pk.r_max for pk in peaks])
    lat = np.array([pk.latency_s for pk in peaks])
    unc = np.array([pk.uncertainty_s for pk in peaks])
    paper = p.paper_screening()
    # A peak on the scan's edge is no maximum of R: the paper's premise (a range that
    # holds the delay) fails for that line, so no rule keeps it — the paper's included.
    usable = np.array([ln.usable and not pk.at_edge
                       for ln, pk in zip(prepared, peaks, strict=True)])
    used = select_lines(r_max, p.min_r, usable)
    not_credible = (np.zeros_like(used) if paper
                    else implausible_uncertainty(unc, used, p.max_line_sigma_s))
    for i in np.flatnonzero(not_credible):
        prepared[i].warnings.append(
            f"line {names[i]}: its uncertainty {unc[i]:.3g} s is not credible (R peak too "
            f"flat to locate; limit {p.max_line_sigma_s:g} s or {RELATIVE_SIGMA_LIMIT:g}x the "
            "median line): not used (tick it to use it anyway)")
    used &= ~not_credible
    outliers = find_outliers(lat, unc, used, 0.0 if paper else p.outlier_k)
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
    joint = joint_peak(curves[used], epochs[used], dts) if joint else float("nan")

    check_cancel(cancel)
    report(progress, 0.92, "quality")
    nan2 = (float("nan"), float("nan"))
    sigmas = (line_quality(setup, comb.latency_s, before) if before is not None
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
    rules = "paper's line rule" if paper else "extended line screening"
    message = (f"{comb.n_used} of {len(names)} lines used ({p.weighting} weights, "
               f"{p.estimator} estimator, {rules})" if converged
               else f"no line with R_max > {p.min_r}: best R_max {best}")
    report(progress, 1.0, "done")
    return LatencyResult(
        comb.latency_s, comb.uncertainty_s, comb.ci95_low, comb.ci95_high, comb.n_used,
        p.weighting, joint, tuple(out_lines), dts, curves, tuple(float(v) for v in arm),
        p.to_dict(), converged, message, tuple(warnings), diagnostics, p.estimator)


def line_quality(setup: Setup, latency_s: float, before: list) -> list[tuple[float, float]]:
    """Per line (σ0 before, σ0 after) in m: seed eqs. 5–6 at Δt = 0 (*before*, from
    :func:`first_passes`) and at *latency_s*.

    Always on the raw series (as published); NaN for lines that are not usable, and
    "after" NaN when *latency_s* is not finite.
    """
    source = HeaveWindows(setup.att, setup.arm)
    final = float(np.nan_to_num(latency_s))

    def after(ln) -> float:
        if not ln.usable or not np.isfinite(latency_s):
            return float("nan")
        return sigma0(ln.h, source.at(ln.tags - final))

    with ThreadPoolExecutor(SCAN_THREADS) as pool:  # the interpolation releases the GIL
        return list(zip(before, pool.map(after, setup.prepared), strict=True))


def with_quality(result: LatencyResult, setup: Setup, before: list) -> LatencyResult:
    """*result* with its lines' σ0 before/after (a :func:`finish` without *before*)."""
    sigmas = line_quality(setup, result.latency_s, before)
    lines = tuple(dataclasses.replace(ln, sigma0_before_m=before, sigma0_after_m=after)
                  for ln, (before, after) in zip(result.lines, sigmas, strict=True))
    return dataclasses.replace(result, lines=lines)


def with_joint_peak(result: LatencyResult) -> LatencyResult:
    """*result* with its joint peak (a :func:`finish` with *joint* False)."""
    used = np.array([ln.used for ln in result.lines], dtype=bool)
    epochs = np.array([ln.epochs for ln in result.lines], dtype=float)
    return dataclasses.replace(result, joint_latency_s=joint_peak(
        result.r_curves[used], epochs[used], result.dt_grid))
