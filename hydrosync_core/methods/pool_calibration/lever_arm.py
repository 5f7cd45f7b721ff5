"""The patent's lever-arm offsets (seed 003, steps 4.1-4.4), after the angle correction.

Axis naming. The seed's ENU has X across the wall (east), Y along it (north), Z up. Here
the axes are taken from the design so that any wall orientation works: ``X`` along the
wall normal ``n_w`` (towards the vessel), ``Y`` along the wall ``t = z × n_w`` horizontal,
``Z`` up. For the demo target (wall x = 0 facing west) X is -east and Y is north.

* 4.1 X: mean across-wall coordinate of the laser wall points (above water) minus that
  of the multibeam wall points (below water);
* 4.2 Z: mean height of an above-water horizontal block face (laser) minus that of a
  below-water one (multibeam), minus their design height difference;
* 4.3 Y: the oblique-face planes (laser, multibeam) projected on the floor give two
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


@dataclass(frozen=True)
class SeedLever:
    """Lever arm (body FRD, m) after steps 4.1-4.4 and the ENU shifts found (m)."""

    lever: np.ndarray
    shift_xyz_m: np.ndarray
    iterations: int
    undetermined: tuple[str, ...]
    used: dict


def _shift(ctx, faces, roles, design, laser, laser_pts, r_m, lever, min_points):
    """One pass of steps 4.1-4.3; returns the ENU shift (3,) and per-axis availability."""
    wall = next((n for n, r in roles.items() if r.role == "wall"), None)
    n_w = roles[wall].normal if wall else np.array([1.0, 0.0, 0.0])
    z = np.array([0.0, 0.0, 1.0])
    t_w = np.cross(z, n_w)
    t_w /= np.linalg.norm(t_w)
    got = {"x": None, "y": None, "z": None}
    mb = {n: georeference(ctx, r_m, lever, idx) for n, idx in faces.items()
          if len(idx) >= min_points}
    # 4.1 X: mean across-wall coordinate above (laser) minus below (multibeam) water.
    if wall in mb and wall in laser:
        got["x"] = float(np.mean(laser_pts[wall] @ n_w) - np.mean(mb[wall] @ n_w))
    # 4.2 Z: above-water laser horizontal face vs below-water multibeam one, design diff.
    above = [n for n, r in roles.items() if r.role == "horizontal" and n in laser
             and design[n].centroid[2] > 0 and r.water == "above"]
    below = [n for n, r in roles.items() if r.role == "horizontal" and n in mb
             and r.water == "below"]
    if above and below:
        a = max(above, key=lambda n: len(laser_pts[n]))
        dz = [(np.mean(laser_pts[a][:, 2]) - np.mean(mb[b][:, 2]))
              - (design[a].centroid[2] - design[b].centroid[2]) for b in below]
        got["z"] = float(np.mean(dz))
        got["z_faces"] = [a, *below]
    # 4.3 Y: floor projections of the oblique planes cut by a line parallel to Y.
    dx = got["x"] or 0.0
    ys = []
    for name in (n for n, r in roles.items() if r.role == "oblique"):
        if name not in mb or name not in laser:
            continue
        x0 = design[name].centroid @ n_w
        zc = design[name].centroid[2]
        pl = laser[name]
        pm = fit_plane(mb[name] + dx * n_w, pl.normal)
        y_l = (pl.d - pl.normal[2] * zc - (pl.normal @ n_w) * x0) / (pl.normal @ t_w)
        y_m = (pm.d - pm.normal[2] * zc - (pm.normal @ n_w) * x0) / (pm.normal @ t_w)
        ys.append(y_l - y_m)
    if ys:
        got["y"] = float(np.mean(ys))
    shift = (got["x"] or 0.0) * n_w + (got["y"] or 0.0) * t_w + (got["z"] or 0.0) * z
    return shift, got


def lever_offsets(ctx: GeorefContext, faces: dict[str, np.ndarray], roles: dict[str, FaceRole],
                  design: dict[str, DesignFace], laser: dict[str, PlaneFit],
                  laser_pts: dict[str, np.ndarray], r_m: np.ndarray, lever0: np.ndarray, *,
                  min_points: int = 30, max_iter: int = 5) -> SeedLever:
    """Steps 4.1-4.4 iterated; returns the corrected lever arm (body FRD, m)."""
    lever = np.asarray(lever0, float).copy()
    a_mean = ctx.mean_rot
    total = np.zeros(3)
    got = {}
    it = 0
    for it in range(1, max_iter + 1):  # noqa: B007 (it is reported)
        shift, got = _shift(ctx, faces, roles, design, laser, laser_pts, r_m, lever, min_points)
        # 4.4: ENU shift -> body frame with the mean attitude.
        lever = lever + a_mean.T @ shift
        total += shift
        if np.linalg.norm(shift) < 1e-4:
            break
    labels = {"x": "lever arm across the wall (seed X)", "y": "lever arm along the wall (seed Y)",
              "z": "lever arm vertical (seed Z)"}
    undetermined = tuple(labels[k] for k in "xyz" if got.get(k) is None)
    return SeedLever(lever, total, it, undetermined, {"z_faces": got.get("z_faces", [])})
