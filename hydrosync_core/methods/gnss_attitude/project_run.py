"""Run the GNSS-array attitude on a project and store the results (plugin entry point).

Inputs read from the project:

* ``raw/gnss_attitude/pos/<antenna>``: one table per antenna as imported from its RTKLIB
  ``.pos`` file (``hydrosync import P.h5 --pos A1.pos``; the file stem names the antenna):
  ``gps_s`` (s), ``x y z`` (ECEF m), ``lat lon`` (deg), ``q`` and the std columns;
* ``raw/gnss_attitude/antennas``: ``antennas.json`` (body FRD coordinates, m).

Stored layout — ``/results/gnss_attitude``:

* group attributes: ``json`` = the parameters, ``params_schema_version``,
  ``software_version``, ``run_utc``; ``method`` (the reported estimator);
  ``counts`` (JSON: screening counts, see :func:`.pipeline.solve_array`);
  ``statistics`` (JSON: per method and angle mean, std and predicted std in degrees over
  the static interval); ``antennas`` (JSON list of names); ``array_llh`` (JSON
  [lat deg, lon deg, h m]); ``predicted_deg`` (JSON: level-attitude prediction per
  method, heading/pitch/roll).
* tables ``lsq``, ``wahba``, ``direct`` (one row per matched epoch): ``time`` (GPS time of
  week, s), ``gps_s``, ``heading``, ``pitch``, ``roll`` (deg), ``sd_heading``,
  ``sd_pitch``, ``sd_roll`` (deg, formal 1σ), ``n_antennas``; ``lsq`` also
  ``iterations``, ``converged``, ``sigma0``. NaN where the estimator has no solution.
* table ``baseline_residuals``: ``time`` and one column per antenna pair ``A1-A2``:
  measured minus known distance (m), NaN when an antenna was missing or not accepted.
* table ``precision``: the accuracy-versus-baseline curve (:func:`.precision.
  accuracy_vs_baseline`: predicted and simulated std per method and angle).
"""

from __future__ import annotations

import json
from collections.abc import Mapping

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.importers.rtklib_pos import ned_covariance
from hydrosync_core.methods.gnss_attitude import VERSION
from hydrosync_core.methods.gnss_attitude.antennas import check_antennas
from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams
from hydrosync_core.methods.gnss_attitude.pipeline import (
    ArraySolution,
    Track,
    solve_array,
    statistics,
)
from hydrosync_core.progress import check_cancel, report, sub_progress
from hydrosync_core.provenance import record

RESULT = "results/gnss_attitude"
RAW = "raw/gnss_attitude"
POS = f"{RAW}/pos"
ANTENNAS = f"{RAW}/antennas"
CURVE_LENGTHS_M = (0.2, 0.3, 0.5, 0.8, 1.0, 1.5, 2.0, 3.0, 5.0)


def track_from_columns(columns: Mapping[str, np.ndarray], source: str) -> Track:
    """A :class:`Track` from ``.pos`` columns (as :func:`read_pos` returns or stored)."""
    for key in ("gps_s", "x", "y", "z", "q"):
        if key not in columns:
            raise InputError(source, f"no column '{key}' (ECEF positions are needed; an "
                             "e/n/u file needs its header's ref pos)", field=key)
    xyz = np.column_stack([np.asarray(columns[k], float) for k in ("x", "y", "z")])
    cov = ned_covariance(dict(columns)) if "lat" in columns or "sdn" in columns else None
    return Track(np.asarray(columns["gps_s"], float), xyz, np.asarray(columns["q"], int), cov,
                 week_based="week" in columns)


def solution_tables(sol: ArraySolution) -> dict[str, dict[str, np.ndarray]]:
    """The per-method tables stored in the project (see the module docstring)."""
    out = {}
    for name, m in sol.methods.items():
        table = {"time": sol.time, "gps_s": sol.gps_s}
        for c, a in enumerate(("heading", "pitch", "roll")):
            table[a] = m.angles_deg[:, c]
        for c, a in enumerate(("heading", "pitch", "roll")):
            table[f"sd_{a}"] = m.std_deg[:, c]
        table["n_antennas"] = sol.n_antennas.astype(np.int16)
        table.update(m.extra)
        out[name] = table
    return out


def run(project, params: GnssAttitudeParams | Mapping | None = None, progress=None,
        cancel=None) -> ArraySolution:
    """Solve the attitude of every epoch and replace ``/results/gnss_attitude``.

    Raises
    ------
    InputError
        Missing or invalid inputs (named by project path), no solvable epoch.
    Cancelled
        When *cancel* is set; nothing is stored then.
    """
    from hydrosync_core.methods.gnss_attitude.precision import accuracy_vs_baseline, predict

    p = params if isinstance(params, GnssAttitudeParams) else \
        GnssAttitudeParams.from_dict(params)
    check_cancel(cancel)
    for path in (POS, ANTENNAS):
        if not project.exists(path):
            raise InputError(f"/{path}", "missing (import the .pos files and antennas.json)")
    antennas = check_antennas(project.get_json(ANTENNAS, {}), f"/{ANTENNAS}")
    tracks = {name: track_from_columns(project.get_table(f"{POS}/{name}"), f"/{POS}/{name}")
              for name in project.children(POS)}
    report(progress, 0.02, "antenna positions read")
    sol = solve_array(tracks, antennas, p, sub_progress(progress, 0.02, 0.85), cancel)
    check_cancel(cancel)
    report(progress, 0.88, "precision versus baseline length")
    body = np.array([antennas[n] for n in sol.names])
    curve = accuracy_vs_baseline(body, CURVE_LENGTHS_M, p.sigma_horizontal_m,
                                 p.sigma_vertical_m, n_mc=300, seed=1)
    predicted = {m: predict(body, p.sigma_horizontal_m, p.sigma_vertical_m,
                            method=m).tolist() for m in ("lsq", "direct")}
    stats = statistics(sol, p.static_start_s, p.static_end_s)
    check_cancel(cancel)
    project.delete(RESULT)
    project.put_json(RESULT, p.to_dict())
    project.set_attrs(RESULT, method=p.method, counts=json.dumps(sol.counts),
                      statistics=json.dumps(stats), antennas=json.dumps(sol.names),
                      array_llh=json.dumps(list(sol.array_llh)),
                      predicted_deg=json.dumps(predicted))
    for name, table in solution_tables(sol).items():
        project.put_table(f"{RESULT}/{name}", table)
    resid = {"time": sol.time}
    resid.update({pair: sol.length_residual_m[:, c] for c, pair in enumerate(sol.pairs)})
    project.put_table(f"{RESULT}/baseline_residuals", resid, units="m")
    project.put_table(f"{RESULT}/precision", curve, units="deg, m")
    record(project, RESULT, (f"{RAW}/pos", f"{RAW}/antennas"), p, plugin_version=VERSION)
    report(progress, 1.0, "attitude stored")
    return sol


def stored_statistics(project, start: float | None, end: float | None) -> dict:
    """Statistics of the stored per-method tables over [start, end] (no solving)."""
    from hydrosync_core.methods.gnss_attitude.pipeline import interval_statistics

    methods, time = {}, None
    for name in ("lsq", "wahba", "direct"):
        if not project.exists(f"{RESULT}/{name}"):
            continue
        t = project.get_table(f"{RESULT}/{name}")
        time = t["time"]
        methods[name] = (np.column_stack([t["heading"], t["pitch"], t["roll"]]),
                         np.column_stack([t["sd_heading"], t["sd_pitch"], t["sd_roll"]]))
    if time is None:
        raise InputError(f"/{RESULT}", "no stored attitude (run the analysis first)")
    return interval_statistics(time, methods, start, end)


def restat(project, start: float | None, end: float | None) -> dict:
    """Change the static interval of the stored result without solving again.

    Recomputes the statistics from the stored tables and stores them with the parameters
    (``static_start_s``/``static_end_s`` replaced; the provenance record too). The other
    results do not depend on the interval. Returns the new statistics.
    """
    from hydrosync_core.params import stored

    old = stored(GnssAttitudeParams, project, RESULT) or GnssAttitudeParams()
    p = GnssAttitudeParams.from_dict({**old.to_dict(), "static_start_s": start,
                                      "static_end_s": end})  # validated
    stats = stored_statistics(project, p.static_start_s, p.static_end_s)
    project.put_json(RESULT, p.to_dict())
    project.set_attrs(RESULT, statistics=json.dumps(stats))
    record(project, RESULT, (f"{RAW}/pos", f"{RAW}/antennas"), p, plugin_version=VERSION)
    return stats
