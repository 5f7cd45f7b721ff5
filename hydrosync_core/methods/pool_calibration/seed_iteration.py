"""The patent's iterative boresight correction (seed 003, steps 3.1-3.6).

Frames: plane normals in target ENU; corrections are small rotations about the body
axes (FRD) of the multibeam mounting. Each iteration re-georeferences the multibeam
face points, fits their planes (TLS) and compares the normals with their reference
planes (:mod:`.twins`): the laser plane of the same face when it crosses the water, or
the laser plane of its above-water twin (same shape and orientation, step 3.3) when it lies
below water — a translation does not change a normal:

* roll  (about body x): the wall P2 normal against the laser's, seen along the roll axis;
* pitch (about body y): P4 = P1 × P2 (P1 an oblique face, P2 the wall), seen along the
  pitch axis;
* yaw   (about body z): the oblique faces P3 (the wall P2 is their reference), seen along
  the yaw axis. A yaw error only slides side-looking wall points within the wall plane,
  so the wall itself carries no yaw signal.

The seed's cosine-comparison sign rules contradict each other between its claims and
its description (claim 1 [0025] vs [0113]); instead the angles are *signed*: both
normals are projected on the plane perpendicular to the rotation axis (world image of
the body axis at the mean attitude) and ``δ = atan2(axis·(n_M × n_L), n_M·n_L)``, the
rotation that carries the multibeam normal onto the laser normal.

Update (eq. [0119]/[0121]): ``R_m <- (I + Ω) R_m``, re-orthonormalised. Note: the seed's Ω
places δγ (roll) in the (0, 2) slot, i.e. about its own y axis; with HydroSync's FRD
body frame (x forward = roll axis) the skew matrix of (δroll, δpitch, δyaw) is used.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hydrosync_core.methods.pool_calibration.georef import (
    GeorefContext,
    boresight_angles,
    georeference,
)
from hydrosync_core.methods.pool_calibration.planes import PlaneFit, angle_deg, fit_plane
from hydrosync_core.methods.pool_calibration.roles import FaceRole
from hydrosync_core.progress import check_cancel, report


@dataclass(frozen=True)
class SeedAngles:
    """Outcome of the angle iteration (radians inside, degrees in the table)."""

    r_m: np.ndarray
    iterations: int
    converged: bool
    table: list[dict]
    undetermined: tuple[str, ...]
    mbes_planes: dict[str, PlaneFit]


def skew(v: np.ndarray) -> np.ndarray:
    """Skew matrix [v]× so that [v]× w = v × w."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def orthonormalise(m: np.ndarray) -> np.ndarray:
    """Nearest rotation matrix (polar decomposition via SVD)."""
    u, _, vt = np.linalg.svd(m)
    r = u @ vt
    if np.linalg.det(r) < 0:
        u[:, -1] *= -1
        r = u @ vt
    return r


def signed_angle(n_m: np.ndarray, n_l: np.ndarray, axis: np.ndarray) -> float:
    """Signed rotation (rad) about *axis* carrying n_m onto n_l, both projected ⟂ axis."""
    pm = n_m - (n_m @ axis) * axis
    pl = n_l - (n_l @ axis) * axis
    return float(np.arctan2(axis @ np.cross(pm, pl), pm @ pl))


def mbes_planes(ctx: GeorefContext, faces: dict[str, np.ndarray], roles: dict[str, FaceRole],
                r_m: np.ndarray, lever: np.ndarray, min_points: int) -> dict[str, PlaneFit]:
    """TLS planes of the multibeam points of each face (normals oriented by role)."""
    out = {}
    for name, idx in faces.items():
        if len(idx) >= min_points:
            out[name] = fit_plane(georeference(ctx, r_m, lever, idx), roles[name].normal)
    return out


def angle_corrections(lp: dict[str, PlaneFit], mp: dict[str, PlaneFit], use: dict[str, list[str]],
                      axes: np.ndarray) -> tuple[np.ndarray, float]:
    """(δroll, δpitch, δyaw) rad and the largest normal angle (deg) over the used faces."""
    delta = np.zeros(3)
    wall = use["wall"][0] if use["wall"] else None
    if wall:
        # Roll: wall P2 about the roll axis (steps 3.5, [0113]).
        delta[0] = signed_angle(mp[wall].normal, lp[wall].normal, axes[0])
        pitches = []
        for ob in use["oblique"]:
            # Pitch: P4 ⟂ P1 and P2, normal n1 × n2 ([0104], [0117]).
            n4l = np.cross(lp[ob].normal, lp[wall].normal)
            n4m = np.cross(mp[ob].normal, mp[wall].normal)
            pitches.append(signed_angle(n4m / np.linalg.norm(n4m), n4l / np.linalg.norm(n4l),
                                        axes[1]))
        if pitches:
            delta[1] = float(np.mean(pitches))
    # Yaw: oblique P3 about the yaw axis ([0115]). The wall P2 is only the reference:
    # a yaw error slides side-looking wall points along the wall (no change of its normal).
    yaws = [signed_angle(mp[f].normal, lp[f].normal, axes[2]) for f in use["oblique"]]
    if yaws:
        delta[2] = float(np.mean(yaws))
    names = ([wall] if wall else []) + use["oblique"]
    worst = max((angle_deg(mp[f].normal, lp[f].normal) for f in names), default=0.0)
    return delta, worst


def iterate_angles(ctx: GeorefContext, faces: dict[str, np.ndarray], roles: dict[str, FaceRole],
                   laser: dict[str, PlaneFit], r_m0: np.ndarray, lever: np.ndarray, *,
                   tol_deg: float = 1e-4, max_iter: int = 20, min_points: int = 30,
                   progress=None, cancel=None) -> SeedAngles:
    """Iterate steps 3.3-3.6 until the corrections fall below *tol_deg*.

    *laser* holds the reference plane of each face (own laser plane or moved twin plane).
    """
    mp = mbes_planes(ctx, faces, roles, r_m0, lever, min_points)
    both = [n for n in mp if n in laser]
    walls = [n for n in both if roles[n].role == "wall"]
    use = {"wall": walls[:1],
           "oblique": [n for n in both if roles[n].role == "oblique"]}
    undetermined = []
    if not use["wall"]:
        undetermined += ["roll", "pitch"]
    if not use["oblique"]:
        undetermined += ["pitch"]
    if not use["oblique"]:
        undetermined += ["yaw"]
    undetermined = tuple(dict.fromkeys(undetermined))
    # World images of the body axes at the mean attitude (columns of C·R_b).
    axes = ctx.mean_rot.T
    r_m = r_m0.copy()
    table, converged = [], False
    for it in range(1, max_iter + 1):
        check_cancel(cancel)
        delta, worst = angle_corrections(laser, mp, use, axes)
        for k, name in enumerate(("roll", "pitch", "yaw")):
            if name in undetermined:
                delta[k] = 0.0
        # R <- (I + Ω) R, re-orthonormalised (eq. [0119]).
        r_m = orthonormalise((np.eye(3) + skew(delta)) @ r_m)
        roll, pitch, yaw = np.degrees(boresight_angles(r_m))
        mp = mbes_planes(ctx, faces, roles, r_m, lever, min_points)
        _, after = angle_corrections(laser, mp, use, axes)
        d = np.degrees(delta)
        table.append({"iteration": it, "d_roll_deg": d[0], "d_pitch_deg": d[1],
                      "d_yaw_deg": d[2], "roll_deg": roll, "pitch_deg": pitch, "yaw_deg": yaw,
                      "max_normal_angle_deg": after, "max_normal_angle_before_deg": worst})
        report(progress, it / max_iter, f"seed iteration {it}: max normal angle {after:.4f}°")
        if np.max(np.abs(d)) < tol_deg:
            converged = True
            break
    return SeedAngles(r_m, len(table), converged, table, undetermined, mp)
