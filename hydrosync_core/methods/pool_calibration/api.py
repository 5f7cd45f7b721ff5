"""Pool calibration entry points: :func:`segment`, :func:`iterate`, :func:`calibrate`.

Inputs: laser points (N, 3) in the target ENU frame (m); multibeam soundings dict
``time`` (s), ``x, y, z`` (sensor FRD, m); INS dict ``time, e, n, u`` (ENU, m),
``roll, pitch, heading`` (deg); ``setup`` and ``target`` as read from setup.json and
target.json. :func:`segment` does the heavy, GUI-separable part (face segmentation of
both clouds, laser planes); :func:`iterate` runs the seed angle iteration, the seed
lever-arm steps and the joint adjustment.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.pool_calibration import georef
from hydrosync_core.methods.pool_calibration.design import DesignFace, design_faces
from hydrosync_core.methods.pool_calibration.planes import PlaneFit, fit_plane
from hydrosync_core.methods.pool_calibration.roles import FaceRole, infer_roles
from hydrosync_core.methods.pool_calibration.segment import (
    FaceSegment,
    bbox_mask,
    segment_cloud,
    voxel_downsample,
)
from hydrosync_core.progress import check_cancel, report, sub_progress

DEFAULT_PARAMS = {
    # Segmentation (m): design-guided crop, RANSAC and DBSCAN thresholds.
    "crop_tol_m": 0.3, "refine_tol_m": 0.1, "refine_ransac_m": 0.03,
    "face_margin_m": 0.1, "water_margin_m": 0.1, "refine_band_sigma": 4.0,
    "ransac_laser_m": 0.02, "ransac_mbes_m": 0.1, "dbscan_laser_m": 0.15,
    "dbscan_mbes_m": 0.5, "min_points": 30, "max_points_per_face": 20000,
    "laser_voxel_m": 0.02, "laser_voxel_above_points": 2_000_000, "max_gap_s": None,
    # Seed iteration and joint adjustment.
    "tol_deg": 1e-4, "max_iter": 30, "max_rounds": 6, "lever_tol_m": 1e-4,
    "huber_m": 0.03, "final": "joint",
    # Ping-time block (s) of the cluster-robust check that inflates the joint σ when the
    # residuals are correlated between neighbouring soundings (joint.py).
    "sigma_block_s": 2.0,
    # INS attitude accuracy (1-σ, deg; Gauss-Markov correlation time, s), propagated into
    # the joint σ (joint.py, ins_cov.py); 0 = treat the INS as exact.
    "ins_sigma_roll_deg": 0.0, "ins_sigma_pitch_deg": 0.0, "ins_sigma_heading_deg": 0.0,
    "ins_tau_s": 1.0,
    # Warning limits of the joint solution.
    "max_sigma_deg": 0.02, "max_sigma_m": 0.005, "max_corr": 0.9,
}


@dataclass(frozen=True)
class Segmentation:
    """Everything :func:`iterate` needs; laser points/planes per face are target ENU, m."""

    design: dict[str, DesignFace]
    roles: dict[str, FaceRole]
    water_level: float
    laser_points: dict[str, np.ndarray]
    laser_planes: dict[str, PlaneFit]
    laser_segments: dict[str, FaceSegment]
    ctx: georef.GeorefContext
    mbes_faces: dict[str, np.ndarray]
    r_m0: np.ndarray
    lever0: np.ndarray
    coarse: dict
    params: dict
    warnings: list[str] = field(default_factory=list)


def merged_params(params: dict | None) -> dict:
    out = dict(DEFAULT_PARAMS)
    out.update(params or {})
    return out


def _check_inputs(lidar: np.ndarray, mbes: dict, ins: dict) -> np.ndarray:
    lidar = np.asarray(lidar, dtype=float)
    if lidar.ndim != 2 or lidar.shape[1] != 3:
        raise InputError("lidar", f"expected (N, 3) points, got shape {lidar.shape}")
    if not np.isfinite(lidar).all():
        raise InputError("lidar", "non-finite coordinates")
    for name, table, keys in (("mbes", mbes, ("time", "x", "y", "z")),
                              ("ins", ins, ("time", "e", "n", "u", "roll", "pitch",
                                            "heading"))):
        for k in keys:
            if k not in table:
                raise InputError(name, "missing column", field=k)
            if not np.isfinite(np.asarray(table[k], float)).all():
                raise InputError(name, "non-finite values", field=k)
    return lidar


def segment(lidar_enu, mbes: dict, ins: dict, setup: dict, target: dict,
            params: dict | None = None, progress=None, cancel=None) -> Segmentation:
    """Segment both clouds into the design faces and fit the laser planes."""
    p = merged_params(params)
    lidar = _check_inputs(lidar_enu, mbes, ins)
    faces = design_faces(target)
    water = float(target.get("water_level_m", 0.0))
    roles = infer_roles(faces, water)
    warnings: list[str] = []
    seg_kw = dict(margin=p["face_margin_m"], water_margin=p["water_margin_m"],
                  min_points=10, max_points=p["max_points_per_face"], cancel=cancel)
    # Laser: crop to the design box, voxel-downsample very large clouds, segment.
    report(progress, 0.0, f"cropping {len(lidar)} laser points")
    lidar = lidar[bbox_mask(lidar, faces, p["crop_tol_m"])]
    if len(lidar) > p["laser_voxel_above_points"] and p["laser_voxel_m"] > 0:
        lidar = voxel_downsample(lidar, p["laser_voxel_m"])
    check_cancel(cancel)
    lseg = segment_cloud(lidar, faces, water, "above", tol=p["crop_tol_m"],
                         ransac_m=p["ransac_laser_m"], dbscan_eps=p["dbscan_laser_m"],
                         progress=sub_progress(progress, 0.05, 0.6), **seg_kw)
    lpts = {n: lidar[s.indices] for n, s in lseg.items() if s.n >= p["min_points"]}
    planes = {n: fit_plane(v, roles[n].normal) for n, v in lpts.items()}
    # Multibeam: georeference with the coarse setup, segment below water.
    b, la = setup["boresight_deg"], setup["lever_arm_m"]
    r_m0 = georef.boresight_matrix(*np.deg2rad([b["roll"], b["pitch"], b["yaw"]]))
    lever0 = np.array([la["x"], la["y"], la["z"]], dtype=float)
    ctx = georef.prepare(mbes, ins, p["max_gap_s"])
    if ctx.dropped_pings:
        warnings.append(f"{ctx.dropped_pings} multibeam pings ({ctx.dropped_soundings} "
                        "soundings) fall in INS gaps or outside the INS span: dropped, "
                        "not interpolated")
    pts = georef.georeference(ctx, r_m0, lever0)
    # Coarse georeference: points may be off by crop_tol, so the polygons are shrunk by as
    # much (the pool floor at a face's foot must not leak into the face).
    mseg = segment_cloud(pts, faces, water, "below", tol=p["crop_tol_m"],
                         ransac_m=p["ransac_mbes_m"], dbscan_eps=p["dbscan_mbes_m"],
                         progress=sub_progress(progress, 0.6, 1.0),
                         **{**seg_kw, "margin": max(p["face_margin_m"], p["crop_tol_m"])})
    mfaces = {n: s.indices for n, s in mseg.items()}
    usable = [n for n in planes if len(mfaces.get(n, ())) >= p["min_points"]]
    if not usable:
        raise InputError("target", "no design face has enough points in both the laser and "
                         f"the multibeam cloud (min {p['min_points']}): check the frames, "
                         "the target design and the coarse setup")
    return Segmentation({f.name: f for f in faces}, roles, water, lpts, planes, lseg, ctx,
                        mfaces, r_m0, lever0, setup, p, warnings)


def calibrate(lidar_enu, mbes: dict, ins: dict, setup: dict, target: dict,
              params: dict | None = None, progress=None, cancel=None):
    """Segment then iterate; returns a :class:`~.result.PoolResult`."""
    seg = segment(lidar_enu, mbes, ins, setup, target, params,
                  sub_progress(progress, 0.0, 0.6), cancel)
    return iterate(seg, progress=sub_progress(progress, 0.6, 1.0), cancel=cancel)


def iterate(seg: Segmentation, params: dict | None = None, progress=None, cancel=None):
    """Seed iteration, seed lever arm and joint adjustment on a :class:`Segmentation`."""
    from hydrosync_core.methods.pool_calibration.solve import solve

    return solve(seg, params, progress, cancel)
