"""Pool calibration entry points: :func:`segment` and :func:`calibrate`.

Inputs: laser points (N, 3) in the target ENU frame (m); multibeam soundings dict
``time`` (s), ``x, y, z`` (sensor FRD, m); INS dict ``time, e, n, u`` (ENU, m),
``roll, pitch, heading`` (deg); ``setup`` and ``target`` as read from setup.json and
target.json. :func:`segment` does the heavy, GUI-separable part (face segmentation of
both clouds, laser planes); :func:`~.solve.solve` runs the patent's angle iteration and
lever-arm steps and the joint adjustment on a :class:`Segmentation`. Parameters are a
:class:`~.params.PoolParams` (a dict is validated into one).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.pool_calibration import georef
from hydrosync_core.methods.pool_calibration.align import coarse_align
from hydrosync_core.methods.pool_calibration.design import DesignFace, design_faces
from hydrosync_core.methods.pool_calibration.params import PoolParams
from hydrosync_core.methods.pool_calibration.planes import PlaneFit, fit_plane
from hydrosync_core.methods.pool_calibration.roles import FaceRole, infer_roles
from hydrosync_core.methods.pool_calibration.segment import (
    FaceSegment,
    bbox_mask,
    segment_cloud,
    voxel_downsample,
)
from hydrosync_core.methods.pool_calibration.twins import (
    PAIR_ANGLE_DEG,
    PAIR_OFFSET_M,
    Reference,
    Twin,
    hidden_reason,
    outward_normals,
    pair_twins,
    pairing_notes,
    reference_planes,
    vessel_side,
)
from hydrosync_core.progress import check_cancel, report, sub_progress


@dataclass(frozen=True)
class Segmentation:
    """Everything :func:`~.solve.solve` needs; laser points/planes per face are target ENU, m."""

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
    params: PoolParams
    warnings: list[str] = field(default_factory=list)
    #: Below-water face -> its above-water twin; face -> reference plane (:mod:`.twins`).
    twins: dict[str, Twin] = field(default_factory=dict)
    refs: dict[str, Reference] = field(default_factory=dict)
    #: Coarse setup aligned by the staged segmentation (:mod:`.align`); selects the points.
    r_align: np.ndarray | None = None
    lever_align: np.ndarray | None = None
    #: Face -> the rule that gave its reference plane, or why it has none (:mod:`.twins`).
    pairing: dict[str, str] = field(default_factory=dict)


def as_params(params: PoolParams | Mapping | None) -> PoolParams:
    """A validated :class:`PoolParams` from an instance, a dict or None (defaults)."""
    return params if isinstance(params, PoolParams) else PoolParams.from_dict(params)


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


def _as_passes(lidar_enu, mbes, ins) -> tuple[np.ndarray, list[dict], list[dict]]:
    """One laser cloud (the union of the passes' clouds) and the per-pass tables.

    *mbes* and *ins* are one table each (one pass) or equally long lists (several passes);
    *lidar_enu* one (N, 3) array (a shared cloud) or a list of them (one per pass).
    """
    mbes_l = list(mbes) if isinstance(mbes, list | tuple) else [mbes]
    ins_l = list(ins) if isinstance(ins, list | tuple) else [ins]
    if len(mbes_l) != len(ins_l) or not mbes_l:
        raise InputError("passes", f"{len(mbes_l)} multibeam tables but {len(ins_l)} INS "
                         "tables: give one of each per pass")
    clouds = list(lidar_enu) if isinstance(lidar_enu, list | tuple) else [lidar_enu]
    clouds = [_check_inputs(c, mbes_l[0], ins_l[0]) for c in clouds]
    for m, i in zip(mbes_l[1:], ins_l[1:], strict=True):
        _check_inputs(clouds[0], m, i)
    return np.concatenate(clouds), mbes_l, ins_l


def segment(lidar_enu, mbes, ins, setup: dict, target: dict,
            params: PoolParams | Mapping | None = None, progress=None,
            cancel=None) -> Segmentation:
    """Segment both clouds into the design faces and fit the laser planes.

    Several passes are adjusted jointly: give *mbes* and *ins* as lists (one table per
    pass) and *lidar_enu* as one shared cloud or a list of clouds (see :func:`_as_passes`).
    """
    p = as_params(params)
    lidar, mbes_l, ins_l = _as_passes(lidar_enu, mbes, ins)
    faces = design_faces(target)
    water = float(target.get("water_level_m", 0.0))
    roles = infer_roles(faces, water)
    warnings: list[str] = []
    seg_kw = dict(margin=p.face_margin_m, water_margin=p.water_margin_m,
                  min_points=10, max_points=p.max_points_per_face, cancel=cancel)
    # Laser: crop to the design box, voxel-downsample very large clouds, segment.
    report(progress, 0.0, f"cropping {len(lidar)} laser points")
    lidar = lidar[bbox_mask(lidar, faces, p.laser_tol_m)]
    if len(lidar) > p.laser_voxel_above_points and p.laser_voxel_m > 0:
        lidar = voxel_downsample(lidar, p.laser_voxel_m)
    check_cancel(cancel)
    lseg = segment_cloud(lidar, faces, water, "above", tol=p.laser_tol_m,
                         ransac_m=p.ransac_laser_m, dbscan_eps=p.dbscan_laser_m,
                         progress=sub_progress(progress, 0.05, 0.5), **seg_kw)
    lpts = {n: lidar[s.indices] for n, s in lseg.items() if s.n >= p.min_points}
    planes = {n: fit_plane(v, roles[n].normal) for n, v in lpts.items()}
    # Reference plane of each face: its own laser plane (crossing the water) or its
    # above-water twin's, moved by the design translation (below water).
    vessel = vessel_side(roles)
    outward = outward_normals(faces, vessel)
    visible = {n for n in planes if hidden_reason(outward[n], vessel) is None}
    declared = {f["name"]: f for f in target["faces"] if f.get("twin")}
    twins = pair_twins(faces, roles, visible, declared,
                       angle_tol_deg=max(PAIR_ANGLE_DEG, p.build_tol_deg),
                       offset_tol_m=max(PAIR_OFFSET_M, p.build_tol_m))
    refs = reference_planes(faces, roles, {n: planes[n] for n in visible}, twins)
    pairing = pairing_notes(faces, roles, twins, {n: len(v) for n, v in lpts.items()},
                            p.min_points)
    # Multibeam: georeference with the coarse setup, align in stages, segment below water.
    b, la = setup["boresight_deg"], setup["lever_arm_m"]
    r_m0 = georef.boresight_matrix(*np.deg2rad([b["roll"], b["pitch"], b["yaw"]]))
    lever0 = np.array([la["x"], la["y"], la["z"]], dtype=float)
    ctx = georef.merge([georef.prepare(m, i, p.max_gap_s,
                                       source="ins" if len(ins_l) == 1 else f"ins (pass {k + 1})")
                        for k, (m, i) in enumerate(zip(mbes_l, ins_l, strict=True))])
    if ctx.dropped_pings:
        warnings.append(f"{ctx.dropped_pings} multibeam pings ({ctx.dropped_soundings} "
                        "soundings) fall in INS gaps or outside the INS span: dropped, "
                        "not interpolated")
    if not refs:
        raise InputError("target", "no design face has a reference plane: no face crossing "
                         "the water and no below-water face with an above-water twin has "
                         f"enough laser points (min {p.min_points}); check the frames "
                         "and the target design")
    tol = p.crop_tol_m
    align = coarse_align(ctx, faces, roles, refs, water, r_m0, lever0,
                         tolerances=(tol, tol / 2, tol / 4), water_margin=p.water_margin_m,
                         dbscan_eps=p.dbscan_mbes_m, min_points=p.min_points,
                         max_points=p.max_points_per_face, huber_m=p.huber_m,
                         max_correction=(2 * np.deg2rad(p.coarse_tol_deg), 2 * p.coarse_tol_m),
                         progress=sub_progress(progress, 0.5, 0.85), cancel=cancel)
    # Faces as found around the aligned setup (what Segment shows; the solution re-selects
    # the points with the tight tolerances).
    pts = georef.georeference(ctx, align.r_m, align.lever)
    mseg = segment_cloud(pts, faces, water, "below", tol=tol / 4,
                         ransac_m=max(p.refine_ransac_m, tol / 16),
                         dbscan_eps=p.dbscan_mbes_m,
                         progress=sub_progress(progress, 0.85, 1.0),
                         **{**seg_kw, "margin": max(p.face_margin_m, tol / 4)})
    mfaces = {n: s.indices for n, s in mseg.items()}
    usable = [n for n in refs if len(mfaces.get(n, ())) >= p.min_points]
    if not usable:
        raise InputError("target", "no design face with a reference plane has enough "
                         f"multibeam points (min {p.min_points}): check the frames, the "
                         "target design and the coarse setup")
    return Segmentation({f.name: f for f in faces}, roles, water, lpts, planes, lseg, ctx,
                        mfaces, r_m0, lever0, setup, p, warnings, twins, refs, align.r_m,
                        align.lever, pairing)


def calibrate(lidar_enu, mbes, ins, setup: dict, target: dict,
              params: PoolParams | Mapping | None = None, progress=None, cancel=None):
    """Segment then solve (one pass or several, see :func:`segment`); returns a
    :class:`~.result.PoolResult`."""
    from hydrosync_core.methods.pool_calibration.solve import solve

    seg = segment(lidar_enu, mbes, ins, setup, target, params,
                  sub_progress(progress, 0.0, 0.6), cancel)
    return solve(seg, progress=sub_progress(progress, 0.6, 1.0), cancel=cancel)
