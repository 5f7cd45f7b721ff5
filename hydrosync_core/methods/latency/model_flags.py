"""The delay-model flags of a result: bands that disagree (:mod:`.delay_model`) and two
estimators that disagree beyond σ. Each flag names its likely cause, goes first among the
warnings (CLI, JSON, panel, PDF) and into the message, and widens σ and the 95 % interval
so that they cover what the model and the estimators disagree about."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np

from hydrosync_core.methods.latency.delay_model import (
    ModelCheck,
    band_check,
    coherent_phase,
    pooled_spectra,
)
from hydrosync_core.methods.latency.detrend import detrend
from hydrosync_core.methods.latency.filter_search import search_filter
from hydrosync_core.methods.latency.heave_windows import HeaveWindows
from hydrosync_core.methods.latency.inputs import check_inputs, median_interval
from hydrosync_core.methods.latency.lines import line_selection
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.result import LatencyResult

GAP_SIGMAS = 2.0
"""Two estimates further apart than this many σ of their difference are flagged."""


def gap_sigma(sigma_kept: float, sigma_other: float) -> float:
    """σ of the difference of two estimates of one delay from the same data (s).

    The kept estimate has the smaller σ; when it is the efficient one, the difference is
    uncorrelated with it (Hausman 1978): var(other − kept) = σ_other² − σ_kept². Floored
    at σ_kept. Issue #29 asks for 2 of the kept σ; with coloured noise the published
    estimate scatters by its own σ, 2-4 times the kept one, and that rule flagged one
    clean simulated day in two: the physics of the difference is followed here.
    """
    other = sigma_other if np.isfinite(sigma_other) else sigma_kept
    return math.sqrt(max(other**2 - sigma_kept**2, sigma_kept**2))


def _line_series(result: LatencyResult, gnss: Mapping, attitude: Mapping,
                 p: LatencyParams) -> tuple[list, float]:
    """(sensor heave, rotation-induced heave — both at ``tag − Δt`` — and detrended
    heights) of each used line (m); the GNSS interval (s)."""
    t_g, hgt, att, arm = check_inputs(gnss, attitude, result.lever_arm_m)
    source = HeaveWindows(att, arm)
    series = []
    for ln in result.lines:
        if not ln.used:
            continue
        sel = line_selection(ln.start, ln.end, t_g, att["time"], p)
        tags = t_g[sel]
        if tags.size < 8:
            continue
        h, _ = detrend(tags, hgt[sel], int(p.detrend_degree))
        times = tags - result.latency_s
        sensor = np.interp(times, att["time"], att["heave"])
        series.append((sensor, source.at(times) - sensor, h))
    return series, median_interval(t_g)


def _cause(p: LatencyParams, upsampled: bool = False) -> str:
    if upsampled:
        return ("qi2010 interpolates the low-rate attitude linearly (biased by up to ~20 ms "
                "in simulation), or a heave filter's phase, or INS-blended heights")
    if p.heave_filter == "highpass":
        return ("the declared heave filter does not match the sensor's, or the heights are "
                "INS-blended")
    if p.heave_filter in ("none", "compensated"):
        return ("a heave filter's phase although none was declared, or INS-blended heights")
    return ("likely a motion sensor's heave filter phase (declare it: heave_filter), or "
            "INS-blended heights")


def _flags(result: LatencyResult, check: ModelCheck, p: LatencyParams
           ) -> tuple[float, list[str], list[str]]:
    """(σ widened, warnings, short notes for the message)."""
    sigma = float(result.uncertainty_s)
    warnings, notes = [], []
    if not check.pure_delay:
        sigma = math.hypot(sigma, check.spread_s)
        warnings.append(
            f"delay model: not one pure delay — the frequency bands disagree "
            f"({check.bands_text()}; χ² p = {check.p_value:.1g}): {_cause(p)}; σ widened "
            f"by the band spread {check.spread_s * 1e3:.0f} ms")
        notes.append("not a pure delay")
    elif not check.determined and p.heave_filter == "unknown":
        warnings.append("delay model: not checked (too few coherent frequencies or lines to "
                        "compare bands), so the lead of an undeclared heave filter cannot be "
                        "excluded: declare the heave filter (none, compensated or highpass)")
        notes.append("not checked, heave filter unknown")
    elif not check.determined:
        warnings.append("delay model not checked: too few coherent frequencies or lines to "
                        "compare bands")
    other = result.diagnostics.get("other_estimate")
    if other and np.isfinite(other["latency_s"]) and sigma > 0:
        gap = abs(float(other["latency_s"]) - float(result.latency_s))
        scale = gap_sigma(float(result.uncertainty_s), float(other["uncertainty_s"]))
        if gap > GAP_SIGMAS * scale:
            warnings.append(
                f"delay model: {result.estimator} and {other['estimator']} differ by "
                f"{gap * 1e3:.0f} ms ({gap / scale:.1f} σ of their difference): "
                f"{_cause(p, 'attitude_upsampled' in result.diagnostics)}; σ widened to "
                "cover the gap")
            sigma = max(sigma, gap / GAP_SIGMAS)
            notes.append(f"{result.estimator} and {other['estimator']} disagree")
    return sigma, warnings, notes


def widened_sigma(latency_s: float, sigma_s: float, diagnostics: Mapping,
                  factor: float = 1.959963984540054) -> float:
    """σ (s) of a recombined mean (lines chosen by hand) widened as the run's checks
    widened it: by the band spread when the bands disagreed, to half the gap to the
    other estimator when that exceeds 2 σ of the difference, to cover the joint estimate
    with the heave filter (interval *factor*). From the stored diagnostics."""
    sigma = float(sigma_s)
    model = diagnostics.get("delay_model") or {}
    if model.get("determined") and not model.get("pure_delay", True):
        sigma = math.hypot(sigma, float(model.get("spread_s", 0.0)))
        joint = (diagnostics.get("heave_filter_search") or {}).get("joint")
        if joint and np.isfinite(latency_s):
            sigma = max(sigma, (abs(float(joint[0]) - latency_s) + factor * float(joint[1]))
                        / factor)
    other = diagnostics.get("other_estimate")
    if other and np.isfinite(other.get("latency_s", np.nan)) and np.isfinite(latency_s):
        gap = abs(float(other["latency_s"]) - float(latency_s))
        if gap > GAP_SIGMAS * gap_sigma(float(sigma_s), float(other["uncertainty_s"])):
            sigma = max(sigma, gap / GAP_SIGMAS)
    return sigma


def with_model_check(result: LatencyResult, gnss: Mapping, attitude: Mapping,
                     p: LatencyParams) -> LatencyResult:
    """*result* with the delay-model check in its diagnostics and, when flagged, its
    warnings first, a note in the message and σ and the 95 % interval widened (the
    interval keeps its factor: normal or Student's t)."""
    if not result.converged or not np.isfinite(result.latency_s):
        return result
    old = float(result.uncertainty_s)
    factor = (result.ci95_high - result.latency_s) / old if old > 0 else 1.959964
    series, interval = _line_series(result, gnss, attitude, p)
    spectra = pooled_spectra(series, interval)
    check = band_check(coherent_phase(spectra), result.latency_s)
    sigma, warnings, notes = _flags(result, check, p)
    diagnostics = {**result.diagnostics, "delay_model": check.to_dict()}
    if p.heave_filter == "unknown" and check.determined:
        found = search_filter(spectra, result.latency_s)
        diagnostics["heave_filter_search"] = found.to_dict()
        far = found.far_fits(result.latency_s, GAP_SIGMAS * sigma)
        if not check.pure_delay:
            warnings.insert(1, f"delay model: {found.text()}")
            joint = found.joint()
            if joint is not None:  # the interval covers the joint estimate's
                sigma = max(sigma, (abs(joint[0] - result.latency_s) + factor * joint[1])
                            / factor)
        elif far:
            warnings.insert(0, f"delay model: {found.not_excluded_text(far)}")
            notes.append("a heave filter not excluded")
    changes = {"diagnostics": diagnostics, "warnings": tuple(warnings) + result.warnings}
    if sigma > old:
        changes.update(uncertainty_s=sigma, ci95_low=result.latency_s - factor * sigma,
                       ci95_high=result.latency_s + factor * sigma)
        diagnostics["sigma_before_model_check_s"] = old
    if notes:
        changes["message"] = f"{result.message}; delay model: " + ", ".join(notes)
    return dataclasses.replace(result, **changes)
