"""Coarse alignment of the multibeam cloud before the face segmentation is final.

The coarse setup (installation drawing) can be off by a couple of degrees and ~0.15 m; a
side-looking head then puts a face's soundings up to half a metre away from it, farther
than a crop can reach without swallowing its neighbours. So the multibeam faces are
segmented in stages of decreasing crop tolerance (``tolerances``, m): at each stage the
soundings are georeferenced with the current estimate, segmented into the faces that have
a reference plane (:func:`.segment.segment_cloud`, design-guided RANSAC/DBSCAN; the polygon
shrink follows the tolerance), and the estimate is updated by the joint point-to-plane
adjustment (:func:`.joint.adjust`, no covariance) against the reference planes (own laser
plane or moved twin plane). Parameters the faces found cannot determine are held.

The result only serves to select the soundings of each face: the seed method still starts
from the coarse values; the joint adjustment starts from this estimate.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hydrosync_core.methods.pool_calibration import georef
from hydrosync_core.methods.pool_calibration.design import DesignFace
from hydrosync_core.methods.pool_calibration.joint import adjust
from hydrosync_core.methods.pool_calibration.roles import FaceRole
from hydrosync_core.methods.pool_calibration.segment import segment_cloud
from hydrosync_core.methods.pool_calibration.twins import Reference
from hydrosync_core.progress import check_cancel, report


@dataclass(frozen=True)
class Alignment:
    """Boresight matrix and lever arm (body FRD, m) after the staged alignment."""

    r_m: np.ndarray
    lever: np.ndarray
    stages: list[dict]


def structural_fix(roles: dict[str, FaceRole], names) -> dict[str, str]:
    """Parameters that the faces *names* cannot determine, by role, with the reason."""
    out = {}
    if not any(roles[n].role == "horizontal" for n in names):
        out["lever_z"] = ("no horizontal face with a reference plane (a below-water block top "
                          "with an above-water twin) seen by the multibeam")
    return out


def coarse_align(ctx: georef.GeorefContext, faces: list[DesignFace],
                 roles: dict[str, FaceRole], refs: dict[str, Reference], water: float,
                 r_m0: np.ndarray, lever0: np.ndarray, *, tolerances=(0.6, 0.3, 0.15),
                 water_margin: float = 0.1, dbscan_eps: float = 0.5, min_points: int = 30,
                 max_points: int = 20000, huber_m: float = 0.03,
                 max_correction: tuple[float, float] | None = None, progress=None,
                 cancel=None) -> Alignment:
    """Staged segmentation + joint adjustment from the coarse setup (module docstring).

    *max_correction* (rad, m): a stage whose estimate moves an angle or a lever component
    further than this from the coarse setup is not taken (the next stage starts from the
    previous estimate): the setup is vouched for to about that much, and a wide crop can
    catch a neighbour face or the floor that drags the fit away (#24: yaw driven to 47°
    from a coarse yaw 1.35° off, every face lost).
    """
    r_m, lever = r_m0.copy(), np.asarray(lever0, float).copy()
    theta0 = np.array([*georef.boresight_angles(r_m0), *lever])
    use = [f for f in faces if f.name in refs]
    stages = []
    for k, tol in enumerate(tolerances):
        check_cancel(cancel)
        pts = georef.georeference(ctx, r_m, lever)
        seg = segment_cloud(pts, use, water, "below", tol=tol, margin=tol,
                            water_margin=water_margin, ransac_m=max(0.03, tol / 4),
                            dbscan_eps=dbscan_eps, min_points=10, max_points=max_points,
                            cancel=cancel)
        obs = {n: (s.indices, refs[n].plane) for n, s in seg.items() if s.n >= min_points}
        row = {"tol_m": tol, "faces": len(obs), "points": int(sum(len(i) for i, _ in
                                                                  obs.values()))}
        if sum(len(i) for i, _ in obs.values()) >= 100:
            fit = adjust(ctx, obs, r_m, lever, huber_m=max(huber_m, tol / 4), cancel=cancel,
                         fix=structural_fix(roles, obs), covariance=False, max_iter=15,
                         tol=1e-7)
            moved = np.abs(np.array([*georef.boresight_angles(fit.r_m), *fit.lever]) - theta0)
            row["held"] = list(fit.fixed)
            row["taken"] = max_correction is None or bool(
                np.all(moved[:3] <= max_correction[0]) and np.all(moved[3:] <= max_correction[1]))
            if row["taken"]:
                r_m, lever = fit.r_m, fit.lever
        stages.append(row)
        report(progress, (k + 1) / len(tolerances), f"coarse alignment, crop ±{tol:g} m: "
               f"{row['faces']} faces")
    return Alignment(r_m, lever, stages)
