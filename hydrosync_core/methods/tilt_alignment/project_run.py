"""Run the tilt-pole alignment on a project and store the results (plugin entry point).

Inputs read from the project (``hydrosync import P.h5 --tilt_imu imu.csv --tilt_gnss
gnss.csv --tilt_pole pole.json``):

* ``raw/tilt/imu``: ``time`` (s), ``gx gy gz`` (rad/s), ``ax ay az`` (m/s²), body frame
  (x forward, y right, z down along the pole);
* ``raw/tilt/gnss``: ``time`` and ``e n u`` (local ENU, m) or ``lat lon height``;
* ``raw/tilt/pole``: ``{"pole_length_m": l}``.

Stored layout — ``/results/tilt_alignment``:

* group attributes: ``json`` = the parameters, ``params_schema_version``,
  ``software_version``, ``run_utc``, ``provenance``; ``method``; ``result`` (JSON: the
  ``result.json`` document of ``hydrosync tilt``); ``frame`` (JSON).
* table ``epochs``: per GNSS epoch ``time`` (s), antenna ``e n u`` (local ENU, m, from the
  first epoch for geodetic input), ``tilt_deg``, ``shot`` (1 in the shot window) and the
  tip of the reported method per epoch ``tip_e tip_n tip_u`` (m).
* table ``j_curve``: ``psi_deg``, ``J`` over the MBGD vectors (all when screening failed).
* tables ``descent_bgd``, ``descent_sgd``, ``descent_mbgd``: the iterates ``psi_deg``, ``J``.
* table ``pair_headings``: ``psi_deg`` per vector and ``used`` (screening).
* table ``montecarlo`` (when ``monte_carlo_runs`` > 0): simulated swings like this record
  (same pole, GNSS rate and σ, tilt up to the record's), errors per method (see
  :func:`.montecarlo.run_monte_carlo`).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.tilt_alignment import VERSION, align
from hydrosync_core.methods.tilt_alignment.geometry import interpolate_vectors, pole_vectors
from hydrosync_core.methods.tilt_alignment.io import check_pole, pole_convention
from hydrosync_core.methods.tilt_alignment.params import TiltParams
from hydrosync_core.progress import check_cancel, report, sub_progress
from hydrosync_core.provenance import record

RESULT = "results/tilt_alignment"
RAW = "raw/tilt"
IMU, GNSS, POLE = f"{RAW}/imu", f"{RAW}/gnss", f"{RAW}/pole"


def run(project, params: TiltParams | Mapping | None = None, progress=None, cancel=None
        ) -> dict:
    """Solve the stored record by every method and replace ``/results/tilt_alignment``.

    Returns the ``result.json`` document. Raises InputError for missing or invalid inputs
    (named by project path) and Cancelled when *cancel* is set (nothing stored then).
    """
    from hydrosync_core.methods.tilt_alignment.montecarlo import run_monte_carlo
    from hydrosync_core.methods.tilt_alignment.solve_files import result_document, solve_columns

    p = params if isinstance(params, TiltParams) else TiltParams.from_dict(params or {})
    check_cancel(cancel)
    for path in (IMU, GNSS, POLE):
        if not project.exists(path):
            raise InputError(f"/{path}", "missing (import imu.csv, gnss.csv and pole.json)")
    pole = project.get_json(POLE, {})
    length = check_pole(pole, f"/{POLE}")
    convention = pole_convention(pole, f"/{POLE}")
    imu = project.get_table(IMU)
    gnss = project.get_table(GNSS)
    report(progress, 0.02, "tilt-pole record read")
    sol, frame = solve_columns(imu, gnss, length, p, (f"/{IMU}", f"/{GNSS}"),
                               sub_progress(progress, 0.02, 0.4), cancel, convention)
    doc = result_document(sol, frame, length, p)
    mc = None
    if p.monte_carlo_runs > 0:
        dt = np.diff(sol.gnss_time)
        rate = float(np.clip(1.0 / np.median(dt), 1.0, 50.0)) if dt.size else 10.0
        top = float(np.clip(math.degrees(float(np.max(sol.epoch_tilt))), 10.0, 70.0))
        mc = run_monte_carlo(
            p.monte_carlo_runs, p, seed=1, tilt_range=(max(5.0, top - 10.0), top),
            overrides={"pole_length_m": length, "gnss_rate_hz": rate,
                       "gnss_sigma_h_m": p.sigma_h_m, "gnss_sigma_v_m": p.sigma_v_m},
            progress=sub_progress(progress, 0.4, 0.95), cancel=cancel)
    check_cancel(cancel)
    # tables
    chosen = sol.methods[p.method]
    ned = sol.gnss_ned
    epochs = {"time": sol.gnss_time, "e": ned[:, 1], "n": ned[:, 0], "u": -ned[:, 2],
              "tilt_deg": np.degrees(sol.epoch_tilt), "shot": sol.tip_window.astype(np.int8)}
    if chosen.ok:
        C = sol.joint.C if p.method == "joint" and sol.joint is not None else None
        if C is None:
            R = chosen.C0 @ sol.C_imu[0].T
            C = np.einsum("ij,kjl->kil", R, sol.C_imu)
        u, _, _ = interpolate_vectors(sol.time, pole_vectors(C, length), sol.gnss_time)
        tip = ned + u
        epochs.update(tip_e=tip[:, 1], tip_n=tip[:, 0], tip_u=-tip[:, 2])
    vec = sol.vectors
    sel = vec.used if sol.screening is None else np.ones(len(vec.nav), bool)
    grid = np.radians(np.linspace(-180.0, 180.0, 721))
    centre = vec.centre
    j_curve = {"psi_deg": np.degrees(grid + centre),
               "J": align.cost(grid + centre, vec.nav[sel], vec.imu[sel]) if sel.any()
               else np.full(grid.size, np.nan)}
    project.delete(RESULT)
    project.put_json(RESULT, p.to_dict())
    project.set_attrs(RESULT, method=p.method, result=json.dumps(_clean(doc)),
                      frame=json.dumps(frame))
    project.put_table(f"{RESULT}/epochs", epochs, units="s, m, deg")
    project.put_table(f"{RESULT}/j_curve", j_curve)
    for name in ("bgd", "sgd", "mbgd"):
        h = sol.methods[name].history
        mask = {"bgd": np.ones(len(vec.nav), bool), "mbgd": sel}.get(name)
        if name == "sgd" and len(vec.nav):
            mask = np.zeros(len(vec.nav), bool)
            mask[int(np.argmax(np.linalg.norm(vec.nav, axis=1)))] = True
        J = align.cost(h, vec.nav[mask], vec.imu[mask]) if h.size and mask is not None \
            else np.zeros(h.size)
        project.put_table(f"{RESULT}/descent_{name}", {"psi_deg": np.degrees(h), "J": J})
    project.put_table(f"{RESULT}/pair_headings", {"psi_deg": np.degrees(vec.psi),
                                                  "used": vec.used.astype(np.int8)})
    if mc is not None:
        project.put_table(f"{RESULT}/montecarlo", mc)
    record(project, RESULT, (IMU, GNSS, POLE), p, plugin_version=VERSION)
    report(progress, 1.0, "tilt alignment stored")
    return doc


def _clean(obj):
    from hydrosync_core.jsonsafe import jsonable

    return jsonable(obj)
