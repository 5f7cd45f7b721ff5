"""Roles of the design faces, inferred from geometry (names are free text).

Target ENU frame. Rules (tolerance ``tol_deg``, default 10°):

* horizontal: normal within tol of vertical; vertical: normal within tol of horizontal;
* wall: the vertical face of largest area; its normal is oriented towards the side where
  the other faces (the blocks, hence the vessel) lie;
* perpendicular: vertical, normal at 90° ± tol to the wall normal;
* oblique: vertical, normal between tol and 90° - tol from the wall normal;
* parallel: vertical and parallel to the wall but not the wall; other: anything else.
* water: ``above`` (z_min >= level), ``below`` (z_max <= level) or ``crossing``.

Which face serves which parameter (seed steps 3 and 4): roll <- wall (P2); yaw <- oblique
faces (P3, with the wall P2 as reference); pitch <- oblique faces with the wall (P4 = P1 × P2);
lever X (across the wall) <- wall; lever Y (along the wall) <- oblique faces; lever Z
<- an above-water and a below-water horizontal face of known design height difference.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.pool_calibration.design import DesignFace

PARAMETER_ROLES = {
    "roll": ("wall",),
    "pitch": ("oblique",),
    "yaw": ("oblique",),
    "lever_x": ("wall",),
    "lever_y": ("oblique",),
    "lever_z": ("horizontal",),
}


@dataclass(frozen=True)
class FaceRole:
    """Role of one design face; ``normal`` is oriented towards the vessel side."""

    name: str
    role: str
    water: str
    normal: np.ndarray
    angle_to_wall_deg: float


def infer_roles(faces: list[DesignFace], water_level: float, tol_deg: float = 10.0,
                source: str = "target.json") -> dict[str, FaceRole]:
    """Classify every design face; raise InputError if there is no vertical wall."""
    sin_tol = np.sin(np.deg2rad(tol_deg))
    vertical = [f for f in faces if abs(f.normal[2]) < sin_tol]
    if not vertical:
        raise InputError(source, "no vertical face: cannot identify the wall", field="faces")
    wall = max(vertical, key=lambda f: f.area)
    others = np.array([f.centroid for f in faces if f is not wall])
    n_wall = wall.normal.copy()
    if len(others) and np.mean((others - wall.centroid) @ n_wall) < 0:
        n_wall = -n_wall
    roles = {}
    for f in faces:
        n = f.normal
        if f.z_min >= water_level - 1e-9:
            water = "above"
        elif f.z_max <= water_level + 1e-9:
            water = "below"
        else:
            water = "crossing"
        ang = float(np.degrees(np.arccos(np.clip(abs(n @ n_wall), 0.0, 1.0))))
        if f is wall:
            role, n = "wall", n_wall
        elif abs(n[2]) > np.cos(np.deg2rad(tol_deg)):
            role = "horizontal"
            n = n if n[2] > 0 else -n
        elif abs(n[2]) < sin_tol:
            if ang < tol_deg:
                role = "parallel"
            elif ang > 90.0 - tol_deg:
                role = "perpendicular"
            else:
                role = "oblique"
            n = n if n @ n_wall >= 0 or role == "perpendicular" else -n
        else:
            role = "other"
        roles[f.name] = FaceRole(f.name, role, water, n, ang)
    return roles
