"""Project entry point of the Pool Calibration plugin.

Reads ``raw/pool/lidar`` ((N, 3) target ENU, m), ``raw/pool/mbes`` (table time, x, y, z;
sensor FRD), ``raw/pool/ins`` (table time, e, n, u, roll, pitch, heading), ``raw/pool/setup``
and ``raw/pool/target`` (JSON), and further passes of the session under
``raw/pool/passes/<k>/`` (``mbes``, ``ins``, optionally ``lidar``), runs
:func:`~.estimator.calibrate` and REPLACES
``/results/pool_calibration``. Stable layout (the report section and GUI panel rely on it):

``results/pool_calibration`` attrs
    ``json`` (``PoolParams.to_dict()``, via put_json), ``params_schema_version``,
    ``software_version``,
    ``run_utc``, ``method`` ("joint" or "seed"), ``iterations`` (int), ``converged`` (bool),
    ``roll_deg, pitch_deg, yaw_deg`` (final boresight), ``lever_x_m, lever_y_m,
    lever_z_m`` (final lever arm, body FRD), ``sigma_roll_deg, sigma_pitch_deg,
    sigma_yaw_deg, sigma_lever_x_m, sigma_lever_y_m, sigma_lever_z_m`` (joint 1-σ, NaN
    when no joint solution or when the parameter is undetermined), ``warnings`` (JSON list
    of strings), ``dropped_pings``, ``undetermined`` (JSON object: parameter -> reason;
    such a parameter's final value is the coarse one), ``flagged`` (JSON object: parameter
    -> message, σ above ``max_sigma_deg``/``max_sigma_m``).
``results/pool_calibration/result`` group whose JSON (get_json) is ``PoolResult.to_dict()``.
``results/pool_calibration/faces`` table: face (str), role (str), water (str),
    points_laser, points_mbes (int), rms_laser_m, rms_mbes_m, normal_angle_deg (float,
    NaN when a sensor has no plane), used_for (str, comma-separated parameters the face
    carries in the joint adjustment), reference (str: "own" = its own laser plane, the
    name of its above-water twin, or ""), pairing (str: the rule that gave the reference
    — own laser plane, declared, coplanar, parallel offset, congruent — or why there is
    none), twin_de_m, twin_dn_m, twin_du_m (float, the design translation twin -> face,
    ENU; NaN without reference).
``results/pool_calibration/iterations`` table: iteration, round (int), d_roll_deg,
    d_pitch_deg, d_yaw_deg, roll_deg, pitch_deg, yaw_deg, max_normal_angle_deg.
``results/pool_calibration/plan`` arrays for a plan view (ENU, m; at most
    ``plan_points`` points each, random decimation): ``laser_xyz`` (n, 3) and
    ``laser_face`` (n,) int index into the faces table; ``mbes_before_xyz`` (m, 3)
    (coarse setup) and ``mbes_after_xyz`` (m, 3) (final values) of the same soundings, and
    ``mbes_face`` (m,) int face index (-1 = not on a face).
"""

from __future__ import annotations

import json
from collections.abc import Mapping

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.pool_calibration import VERSION, georef
from hydrosync_core.methods.pool_calibration.estimator import as_params, segment
from hydrosync_core.methods.pool_calibration.params import PoolParams
from hydrosync_core.methods.pool_calibration.solve import solve
from hydrosync_core.params import stored
from hydrosync_core.progress import sub_progress
from hydrosync_core.provenance import record

RESULT = "results/pool_calibration"
PASSES = "raw/pool/passes"
INPUTS = ("raw/pool/lidar", "raw/pool/mbes", "raw/pool/ins", "raw/pool/setup",
          "raw/pool/target", PASSES)


def _plan(project, seg, result, n_max: int, rng: np.random.Generator) -> None:
    names = list(seg.design)
    lx, lf = [], []
    for k, name in enumerate(names):
        pts = seg.laser_points.get(name)
        if pts is not None:
            lx.append(pts)
            lf.append(np.full(len(pts), k))
    lx = np.concatenate(lx) if lx else np.zeros((0, 3))
    lf = np.concatenate(lf) if lf else np.zeros(0, int)
    pick = rng.choice(len(lx), min(n_max, len(lx)), replace=False) if len(lx) else []
    project.put(f"{RESULT}/plan/laser_xyz", lx[pick])
    project.put(f"{RESULT}/plan/laser_face", lf[pick].astype(np.int32))
    face = np.full(len(seg.ctx.x_m), -1, dtype=np.int32)
    for k, name in enumerate(names):
        face[seg.mbes_faces.get(name, [])] = k
    sel = np.sort(rng.choice(len(face), min(n_max, len(face)), replace=False))
    b, la = result.boresight_deg, result.lever_arm_m
    r_f = georef.boresight_matrix(*np.deg2rad([b["roll"], b["pitch"], b["yaw"]]))
    l_f = np.array([la["x"], la["y"], la["z"]])
    before = georef.georeference(seg.ctx, seg.r_m0, seg.lever0, sel)
    project.put(f"{RESULT}/plan/mbes_before_xyz", before)
    project.put(f"{RESULT}/plan/mbes_after_xyz", georef.georeference(seg.ctx, r_f, l_f, sel))
    project.put(f"{RESULT}/plan/mbes_face", face[sel])


def pass_names(project) -> list[str]:
    """Groups of the further passes under ``raw/pool/passes`` (sorted), [] for one pass."""
    if not project.exists(PASSES):
        return []
    return sorted(project.children(PASSES), key=lambda s: (len(s), s))


def read_inputs(project) -> tuple:
    """The stored inputs: laser points (N, 3) target ENU m, multibeam and INS tables, setup
    and target JSON (the layout of :data:`INPUTS`). With further passes under
    ``raw/pool/passes/<k>/{mbes, ins[, lidar]}`` the clouds and tables are lists, pass 1
    (``raw/pool/*``) first; a pass without its own cloud uses the shared one."""
    lidar = [np.asarray(project.get("raw/pool/lidar"), dtype=float)]
    mbes, ins = [project.get_table("raw/pool/mbes")], [project.get_table("raw/pool/ins")]
    for name in pass_names(project):
        base = f"{PASSES}/{name}"
        for need in ("mbes", "ins"):
            if not project.exists(f"{base}/{need}"):
                raise InputError(str(project.path or "project"),
                                 f"pass {name} has no /{base}/{need}")
        mbes.append(project.get_table(f"{base}/mbes"))
        ins.append(project.get_table(f"{base}/ins"))
        if project.exists(f"{base}/lidar"):
            lidar.append(np.asarray(project.get(f"{base}/lidar"), dtype=float))
    one = len(mbes) == 1
    return ((lidar[0], mbes[0], ins[0]) if one else (lidar, mbes, ins)) + (
        project.get_json("raw/pool/setup"), project.get_json("raw/pool/target"))


def segment_project(project, params: PoolParams | Mapping | None = None, progress=None,
                    cancel=None):
    """:func:`~.estimator.segment` on the project's stored inputs (what Segment runs)."""
    return segment(*read_inputs(project), as_params(params), progress, cancel)


def run(project, params: PoolParams | Mapping | None = None, progress=None, cancel=None):
    """Run the pool calibration on *project* and store the results (see module doc)."""
    p = as_params(params)
    seg = segment_project(project, p, sub_progress(progress, 0, 0.6), cancel)
    return solve_and_store(project, seg, p, sub_progress(progress, 0.6, 1.0), cancel)


def solve_and_store(project, seg, params: PoolParams | None = None, progress=None,
                    cancel=None):
    """Solve on an existing segmentation (e.g. kept by the GUI) and store the results.

    Nothing is written to *project* unless the solution completes (a cancel leaves the
    previous results untouched).
    """
    p = seg.params if params is None else params
    result = solve(seg, p, sub_progress(progress, 0.0, 0.95), cancel)
    store(project, seg, result, p)
    record(project, RESULT, INPUTS, p, plugin_version=VERSION)
    return result


def stored_params(project) -> PoolParams | None:
    """The parameters of the stored result (migrated to the current schema), or None."""
    return stored(PoolParams, project, RESULT)


def store(project, seg, result, p: PoolParams) -> None:
    """REPLACE ``/results/pool_calibration`` with *result* (layout in the module doc)."""
    project.delete(RESULT)
    project.put_json(f"{RESULT}/result", result.to_dict())
    project.put_json(RESULT, p.to_dict())
    # The joint σ describe the joint solution only: with final = seed they stay NaN here
    # (the joint solution and its σ remain in the result JSON for comparison).
    j = result.joint if result.method == "joint" else None
    sig = ({**{f"sigma_{k}_deg": v for k, v in j.sigma_boresight_deg.items()},
            **{f"sigma_lever_{k}_m": v for k, v in j.sigma_lever_arm_m.items()}}
           if j else {f"sigma_{k}": float("nan") for k in
                      ("roll_deg", "pitch_deg", "yaw_deg", "lever_x_m", "lever_y_m",
                       "lever_z_m")})
    project.set_attrs(
        RESULT, method=result.method,
        iterations=int(result.iterations), converged=bool(result.converged),
        **{f"{k}_deg": float(v) for k, v in result.boresight_deg.items()},
        **{f"lever_{k}_m": float(v) for k, v in result.lever_arm_m.items()},
        **{k: float(v) for k, v in sig.items()},
        warnings=json.dumps(result.warnings), dropped_pings=int(result.dropped_pings),
        undetermined=json.dumps(result.undetermined), flagged=json.dumps(result.flagged))
    rows = result.faces
    project.put_table(f"{RESULT}/faces", {
        "face": np.array([r.face for r in rows], dtype=str),
        "role": np.array([r.role for r in rows], dtype=str),
        "water": np.array([r.water for r in rows], dtype=str),
        "points_laser": np.array([r.points_laser for r in rows], dtype=np.int64),
        "points_mbes": np.array([r.points_mbes for r in rows], dtype=np.int64),
        "rms_laser_m": np.array([r.rms_laser_m for r in rows]),
        "rms_mbes_m": np.array([r.rms_mbes_m for r in rows]),
        "normal_angle_deg": np.array([r.normal_angle_deg for r in rows]),
        "used_for": np.array([r.used_for for r in rows], dtype=str),
        "reference": np.array([r.reference for r in rows], dtype=str),
        "pairing": np.array([r.pairing for r in rows], dtype=str),
        **{f"twin_d{a}_m": np.array([r.design_offset_m[k] for r in rows], dtype=float)
           for k, a in enumerate("enu")}})
    cols = ("iteration", "round", "d_roll_deg", "d_pitch_deg", "d_yaw_deg", "roll_deg",
            "pitch_deg", "yaw_deg", "max_normal_angle_deg")
    project.put_table(f"{RESULT}/iterations", {
        c: np.array([row[c] for row in result.iteration_table],
                    dtype=np.int64 if c in ("iteration", "round") else float) for c in cols})
    _plan(project, seg, result, p.plan_points, np.random.default_rng(0))
