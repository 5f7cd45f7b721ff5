"""The patent's lever-arm offsets (seed 003, steps 4.1-4.4), after the angle correction.

Axis naming. The seed's ENU has X across the wall (east), Y along it (north), Z up. Here
the axes are taken from the design so that any wall orientation works: ``X`` along the
wall normal ``n_w`` (towards the vessel), ``Y`` along the wall ``t = z × n_w`` horizontal,
``Z`` up. For the demo target (wall x = 0 facing west) X is -east and Y is north.

Every face the multibeam sees is compared with its *reference plane*
(:mod:`.twins`): its own laser plane when it crosses the water, or the laser plane of its
above-water twin moved by the design translation when it lies below water.

* 4.1 X: mean across-wall coordinate of the laser wall points (above water) minus that
  of the multibeam wall points (below water);
* 4.2 Z: for each below-water horizontal face (a block top): the height of its reference
  plane — the above-water twin's laser plane lowered by the design height difference —
  at the multibeam points' centroid, minus their mean height; averaged over the faces;
* 4.3 Y: the oblique-face planes (reference, multibeam) projected on the floor give two
  lines; their intersections with a line parallel to Y (at the face's design X) differ
  by the Y offset (computed after the X offset is applied);
* 4.4 the ENU shift is taken to the body frame with the mean attitude,
  ``Δl_b = (C R_b)ᵀ Δp``, and the three steps are repeated until the shift is < 0.1 mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hydrosync_core.methods.pool_calibration.design import DesignFace
from hydrosync_core.methods.pool_calibration.georef import GeorefContext, georeference
from hydrosync_core.methods.pool_calibration.planes import PlaneFit, fit_plane
from hydrosync_core.methods.pool_calibration.roles import FaceRole

#: Seed lever-arm axes (design frame) and what they are called in messages.
AXIS_LABELS = {"x": "lever arm across the wall (seed X)",
               "y": "lever arm along the wall (seed Y)",
               "z": "lever arm vertical (seed Z)"}


@dataclass(frozen=True)
class SeedLever:
    """Lever arm (body FRD, m) after steps 4.1-4.4 and the ENU shifts found (m)."""

    lever: np.ndarray
    shift_xyz_m: np.ndarray
    iterations: int
    undetermined: tuple[str, ...]
    used: dict
    reasons: dict | None = None


def _shift(ctx, faces, roles, design, refs, laser_pts, r_m, lever, min_points):
    """One pass of steps 4.1-4.3; returns the ENU shift (3,) and per-axis availability."""
    wall = next((n for n, r in roles.items() if r.role == "wall"), None)
    n_w = roles[wall].normal if wall else np.array([1.0, 0.0, 0.0])
    z = np.array([0.0, 0.0, 1.0])
    t_w = np.cross(z, n_w)
    t_w /= np.linalg.norm(t_w)
    got = {"x": None, "y": None, "z": None, "x_faces": [], "y_faces": [], "z_faces": [],
           "axes": {"x": n_w, "y": t_w, "z": z}}
    mb = {n: georeference(ctx, r_m, lever, idx) for n, idx in faces.items()
          if len(idx) >= min_points}
    # 4.1 X: mean across-wall coordinate above (laser) minus below (multibeam) water.
    if wall in mb and wall in laser_pts:
        got["x"] = float(np.mean(laser_pts[wall] @ n_w) - np.mean(mb[wall] @ n_w))
        got["x_faces"] = [wall]
    # 4.2 Z: below-water block tops against their reference (the above-water twin's laser
    # plane moved by the design height difference).
    dz = []
    for name, r in roles.items():
        if r.role != "horizontal" or name not in mb or name not in refs:
            continue
        ref = refs[name]
        c = mb[name].mean(axis=0)
        z_ref = (ref.d - ref.normal[0] * c[0] - ref.normal[1] * c[1]) / ref.normal[2]
        dz.append(z_ref - c[2])
        got["z_faces"].append(name)
    if dz:
        got["z"] = float(np.mean(dz))
    # 4.3 Y: floor projections of the oblique planes cut by a line parallel to Y.
    dx = got["x"] or 0.0
    ys = []
    for name in (n for n, r in roles.items() if r.role == "oblique"):
        if name not in mb or name not in refs:
            continue
        x0 = design[name].centroid @ n_w
        zc = design[name].centroid[2]
        pl = refs[name]
        pm = fit_plane(mb[name] + dx * n_w, pl.normal)
        y_l = (pl.d - pl.normal[2] * zc - (pl.normal @ n_w) * x0) / (pl.normal @ t_w)
        y_m = (pm.d - pm.normal[2] * zc - (pm.normal @ n_w) * x0) / (pm.normal @ t_w)
        ys.append(y_l - y_m)
        got["y_faces"].append(name)
    if ys:
        got["y"] = float(np.mean(ys))
    shift = (got["x"] or 0.0) * n_w + (got["y"] or 0.0) * t_w + (got["z"] or 0.0) * z
    return shift, got


def lever_offsets(ctx: GeorefContext, faces: dict[str, np.ndarray], roles: dict[str, FaceRole],
                  design: dict[str, DesignFace], refs: dict[str, PlaneFit],
                  laser_pts: dict[str, np.ndarray], r_m: np.ndarray, lever0: np.ndarray, *,
                  min_points: int = 30, max_iter: int = 5) -> SeedLever:
    """Steps 4.1-4.4 iterated; returns the corrected lever arm (body FRD, m).

    *refs* are the reference planes per face (own laser plane or moved twin plane).
    A seed axis with no face is not shifted; the body component of the lever arm closest
    to it keeps its start (coarse) value and is reported undetermined (``lever_x`` ...).
    """
    lever0 = np.asarray(lever0, float)
    lever = lever0.copy()
    a_mean = ctx.mean_rot
    total = np.zeros(3)
    got = {}
    held: dict[int, str] = {}
    it = 0
    for it in range(1, max_iter + 1):  # noqa: B007 (it is reported)
        shift, got = _shift(ctx, faces, roles, design, refs, laser_pts, r_m, lever,
                            min_points)
        if it == 1:
            for k in "xyz":
                if got[k] is None:
                    body = int(np.argmax(np.abs(a_mean.T @ got["axes"][k])))
                    held[body] = f"no face for the {AXIS_LABELS[k]}"
        # 4.4: ENU shift -> body frame with the mean attitude.
        lever = lever + a_mean.T @ shift
        for k in held:
            lever[k] = lever0[k]
        total += shift
        if np.linalg.norm(shift) < 1e-4:
            break
    reasons = {f"lever_{'xyz'[k]}": why for k, why in sorted(held.items())}
    return SeedLever(lever, total, it, tuple(reasons),
                     {k: got.get(f"{k}_faces", []) for k in "xyz"}, reasons)
