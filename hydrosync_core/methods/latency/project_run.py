"""Run the latency module on a project and store its results (plugin entry point).

Inputs read from the project: tables ``raw/gnss`` (time, height), ``raw/attitude``
(time, roll, pitch, heading, heave; degrees, heave m up), ``raw/lines`` (name, start,
end), and the lever arm: the ``lever_arm_m`` parameter if given, else the vessel
sheet's sensor ``gnss`` offset minus sensor ``motion`` offset (body FRD, m).

Stored layout (stable; the PDF report section reads it) — ``/results/latency``:

* group attributes: ``json`` = the parameters (``LatencyParams.to_dict()``, ``put_json``;
  ``lever_arm_m`` null when taken from the vessel sheet), ``params_schema_version``,
  ``software_version``, ``run_utc`` (ISO 8601); ``latency_s``, ``uncertainty_s``,
  ``ci95_low``, ``ci95_high`` (s, NaN when no line was used); ``joint_latency_s`` (s);
  ``n_used`` (int); ``weighting`` ("r" or "inverse_variance"); ``estimator`` (the
  estimator that produced ``latency_s``: "qi2010", "qi2010_antialias" or "weighted";
  absent in results of versions before 1.2, which are "qi2010"); ``converged`` (bool);
  ``message`` (str); ``warnings`` (JSON list of str); ``diagnostics`` (JSON object);
  ``lever_arm_m`` (JSON list [x, y, z], body FRD, m).
* table ``lines`` (one row per survey line): ``name`` (str), ``start``, ``end`` (s),
  ``epochs`` (int), ``r_max``, ``latency_s`` (s), ``uncertainty_s`` (s),
  ``sigma0_before_m``, ``sigma0_after_m`` (m, seed eqs. 5–6 at Δt = 0 and at the final
  Δt), ``used`` (bool, may be changed by the user, see :func:`recombine`),
  ``auto_used`` (bool, the automatic selection), ``at_edge`` (bool).
* dataset ``dt_grid`` (k,) s, and dataset ``r_curves`` (lines, k): R of every line at
  every scanned Δt (NaN for lines without enough data).
* table ``synchronised``: ``time`` (s, corrected GNSS time = tag − latency),
  ``height`` (m), ``roll``, ``pitch``, ``heading`` (deg), ``heave``, ``total_heave``
  (m, up) — absent when no latency could be determined.
"""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Mapping

import numpy as np

from hydrosync_core.importers.import_report import stored_warnings
from hydrosync_core.methods.latency import VERSION
from hydrosync_core.methods.latency.combine import combine
from hydrosync_core.methods.latency.correlation import heave_at
from hydrosync_core.methods.latency.detrend import detrend
from hydrosync_core.methods.latency.estimate import estimate_latency
from hydrosync_core.methods.latency.heave import total_heave_deg
from hydrosync_core.methods.latency.lines import line_slice
from hydrosync_core.methods.latency.model_flags import widened_sigma
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.quality import sigma0
from hydrosync_core.methods.latency.result import LatencyResult
from hydrosync_core.methods.latency.synchronised import synchronise
from hydrosync_core.params import stored
from hydrosync_core.progress import sub_progress
from hydrosync_core.project import Project
from hydrosync_core.project.vessel import lever_arm as vessel_lever_arm
from hydrosync_core.provenance import record

RESULT = "results/latency"


def project_lever_arm(project: Project, params: LatencyParams | None = None) -> np.ndarray:
    """Lever arm (body FRD, m): the parameter if given, else vessel sheet gnss − motion."""
    if params is not None and params.lever_arm_m is not None:
        return np.asarray(params.lever_arm_m, dtype=float)
    return vessel_lever_arm(project, "gnss", "motion")


def as_params(params: LatencyParams | Mapping | None) -> LatencyParams:
    """A validated :class:`LatencyParams` from an instance, a dict or None (defaults)."""
    return params if isinstance(params, LatencyParams) else LatencyParams.from_dict(params)


def stored_params(project: Project) -> LatencyParams | None:
    """The parameters of the stored result (migrated to the current schema), or None."""
    return stored(LatencyParams, project, RESULT)


def read_inputs(project: Project) -> tuple[dict, dict, dict]:
    """The raw GNSS, attitude and lines tables of *project* (read-only, kept decoded by
    the project: a run after a changed lever arm does not read the file again)."""
    return tuple(project.get_table(f"raw/{name}", cached=True)
                 for name in ("gnss", "attitude", "lines"))


def run(project: Project, params: LatencyParams | Mapping | None = None, progress=None,
        cancel=None) -> LatencyResult:
    """Estimate the latency from the project's raw data and replace ``/results/latency``."""
    p = as_params(params)
    arm = project_lever_arm(project, p)
    gnss, attitude, lines = read_inputs(project)
    result = estimate_latency(gnss, attitude, lines, arm, p, sub_progress(progress, 0, 0.9), cancel)
    # Import warnings change what the numbers mean (e.g. heights above the geoid): they
    # travel with the result.
    carried = tuple(f"/{path} import: {w}" for path in ("raw/gnss", "raw/attitude")
                    for w in stored_warnings(project, path))
    if carried:
        result = dataclasses.replace(result, warnings=carried + tuple(result.warnings))
    sync = (synchronise(gnss, attitude, arm, result.latency_s) if result.converged else None)
    store(project, result, sync, p)
    record(project, RESULT, ("raw/gnss", "raw/attitude", "raw/lines"), p,
           vessel_sensors=("gnss", "motion") if p.lever_arm_m is None else (),
           plugin_version=VERSION)
    if progress is not None:
        progress(1.0, "results stored")
    return result


def store(project: Project, result: LatencyResult, sync: dict | None,
          params: LatencyParams) -> None:
    """Write *result* under ``/results/latency`` (replacing it), layout in the module doc."""
    project.delete(RESULT)
    project.put_json(RESULT, params.to_dict())
    lines = result.lines
    project.put_table(f"{RESULT}/lines", {
        "name": np.array([ln.name for ln in lines], dtype=str),
        "start": np.array([ln.start for ln in lines]),
        "end": np.array([ln.end for ln in lines]),
        "epochs": np.array([ln.epochs for ln in lines], dtype=np.int64),
        "r_max": np.array([ln.r_max for ln in lines]),
        "latency_s": np.array([ln.latency_s for ln in lines]),
        "uncertainty_s": np.array([ln.uncertainty_s for ln in lines]),
        "sigma0_before_m": np.array([ln.sigma0_before_m for ln in lines]),
        "sigma0_after_m": np.array([ln.sigma0_after_m for ln in lines]),
        "used": np.array([ln.used for ln in lines], dtype=bool),
        "auto_used": np.array([ln.used for ln in lines], dtype=bool),
        "at_edge": np.array([ln.at_edge for ln in lines], dtype=bool),
    })
    project.put(f"{RESULT}/dt_grid", result.dt_grid, attrs={"units": "s"})
    project.put(f"{RESULT}/r_curves", result.r_curves, attrs={"rows": "lines", "cols": "dt_grid"})
    if sync is not None:
        project.put_table(f"{RESULT}/synchronised", sync,
                          time="corrected GNSS time (tag - latency)")
    project.set_attrs(
        RESULT, latency_s=float(result.latency_s), uncertainty_s=float(result.uncertainty_s),
        ci95_low=float(result.ci95_low), ci95_high=float(result.ci95_high),
        joint_latency_s=float(result.joint_latency_s), n_used=int(result.n_used),
        weighting=result.weighting, estimator=result.estimator,
        converged=bool(result.converged), message=result.message,
        warnings=json.dumps(list(result.warnings)),
        diagnostics=json.dumps(result.to_dict()["diagnostics"]),
        lever_arm_m=json.dumps(list(result.lever_arm_m)),
    )


def recombine(project: Project, used: np.ndarray, weighting: str | None = None) -> dict:
    """Re-select lines by hand: new weighted mean from the stored per-line values (no scan).

    Updates the ``used`` column, the final-value attributes, ``sigma0_after_m`` and the
    ``synchronised`` table of ``/results/latency``; returns the new final values.
    """
    table = project.get_table(f"{RESULT}/lines")
    used = np.asarray(used, dtype=bool)
    if used.shape != table["used"].shape:
        raise ValueError("used mask does not match the number of lines")
    attrs = project.attrs(RESULT)
    p = stored_params(project)
    weighting = weighting or attrs.get("weighting", "r")
    # Weighted mean of the selected lines from their stored values (seed section 2.4).
    comb = combine(table["latency_s"], table["r_max"], table["uncertainty_s"], used, weighting)
    table["used"] = used
    arm = np.asarray(json.loads(attrs["lever_arm_m"]), dtype=float)
    gnss, attitude, _ = read_inputs(project)
    t_g, hgt = np.asarray(gnss["time"], float), np.asarray(gnss["height"], float)
    t_att = np.asarray(attitude["time"], float)
    h_att = total_heave_deg(np.asarray(attitude["heave"], float),
                            np.asarray(attitude["roll"], float),
                            np.asarray(attitude["pitch"], float), arm)
    after = np.full(table["name"].size, np.nan)
    if comb.n_used:
        for i, (start, end) in enumerate(zip(table["start"], table["end"], strict=True)):
            sel = line_slice(t_g, start, end, p.skip_s, t_att, comb.latency_s, comb.latency_s)
            if sel.stop - sel.start >= 3:
                h, _ = detrend(t_g[sel], hgt[sel], int(p.detrend_degree))
                # Seed eqs. 5–6 at the new final Δt.
                after[i] = sigma0(h, heave_at(t_g[sel], np.array([comb.latency_s]), t_att,
                                              h_att)[0])
    table["sigma0_after_m"] = after
    project.put_table(f"{RESULT}/lines", table)
    if comb.n_used:
        project.put_table(f"{RESULT}/synchronised", synchronise(gnss, attitude, arm,
                                                               comb.latency_s),
                          time="corrected GNSS time (tag - latency)")
    else:
        project.delete(f"{RESULT}/synchronised")
    # The run's delay-model flags still hold for the lines chosen by hand: σ widened alike.
    diagnostics = json.loads(attrs.get("diagnostics", "{}") or "{}")
    factor = (comb.ci95_high - comb.latency_s) / comb.uncertainty_s \
        if comb.n_used and comb.uncertainty_s > 0 else 1.959963984540054
    sigma = widened_sigma(comb.latency_s, comb.uncertainty_s, diagnostics, factor) \
        if comb.n_used else comb.uncertainty_s
    if sigma > comb.uncertainty_s:
        comb = dataclasses.replace(comb, uncertainty_s=sigma,
                                   ci95_low=comb.latency_s - factor * sigma,
                                   ci95_high=comb.latency_s + factor * sigma)
    values = comb.to_dict()
    project.set_attrs(
        RESULT, latency_s=comb.latency_s, uncertainty_s=comb.uncertainty_s,
        ci95_low=comb.ci95_low, ci95_high=comb.ci95_high, n_used=comb.n_used,
        weighting=weighting, converged=bool(comb.n_used),
        message=f"{comb.n_used} of {used.size} lines used ({weighting} weights, "
                f"{attrs.get('estimator', 'qi2010')} estimator, chosen by hand)",
    )
    return values
