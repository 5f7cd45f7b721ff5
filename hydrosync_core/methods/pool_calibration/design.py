"""Geometry of the design faces of ``target.json``: planes, polygons and ray casting.

All coordinates are in the target ENU frame, metres. Each face is a planar convex
polygon; its normal follows the corner order (right-hand rule, Newell's method).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hydrosync_core.errors import InputError


@dataclass(frozen=True)
class DesignFace:
    """One design face: corners (k, 3) ENU m, unit normal, plane offset d = n·x."""

    name: str
    corners: np.ndarray
    normal: np.ndarray
    d: float
    centroid: np.ndarray
    area: float
    u: np.ndarray
    v: np.ndarray
    poly2d: np.ndarray

    @property
    def z_min(self) -> float:
        return float(self.corners[:, 2].min())

    @property
    def z_max(self) -> float:
        return float(self.corners[:, 2].max())


def make_face(name: str, corners: np.ndarray, source: str, index: int) -> DesignFace:
    # Newell's method: normal of a planar polygon, robust to collinear corner triples.
    nxt = np.roll(corners, -1, axis=0)
    newell = np.cross(corners, nxt).sum(axis=0)
    norm = np.linalg.norm(newell)
    if norm < 1e-9:
        raise InputError(source, "face has zero area (degenerate corners)",
                         field=f"faces[{index}] '{name}'")
    normal = newell / norm
    area = 0.5 * norm
    centroid = corners.mean(axis=0)
    off = np.abs((corners - centroid) @ normal)
    if off.max() > 0.01:
        raise InputError(source, f"corners are not coplanar (off by {off.max():.3f} m)",
                         field=f"faces[{index}] '{name}'")
    u = corners[1] - corners[0]
    u = u - (u @ normal) * normal
    u /= np.linalg.norm(u)
    v = np.cross(normal, u)
    poly2d = np.column_stack([(corners - centroid) @ u, (corners - centroid) @ v])
    return DesignFace(name, corners, normal, float(normal @ centroid), centroid, float(area),
                      u, v, poly2d)


def design_faces(target: dict, source: str = "target.json") -> list[DesignFace]:
    """Build :class:`DesignFace` objects from a ``target.json`` document."""
    faces = []
    names = set()
    for i, face in enumerate(target["faces"]):
        name = str(face["name"])
        if name in names:
            raise InputError(source, f"face name '{name}' used twice", field=f"faces[{i}]")
        names.add(name)
        faces.append(make_face(name, np.asarray(face["corners"], dtype=float), source, i))
    return faces


def inside_polygon(face: DesignFace, points: np.ndarray, margin: float = 0.0) -> np.ndarray:
    """Mask of *points* (N, 3) whose projection lies inside *face* shrunk by *margin* m."""
    rel = points - face.centroid
    p2 = np.column_stack([rel @ face.u, rel @ face.v])
    inside = np.ones(len(points), dtype=bool)
    poly = face.poly2d
    for a, b in zip(poly, np.roll(poly, -1, axis=0), strict=True):
        edge = b - a
        length = np.hypot(*edge)
        # 2-D cross product: positive on the left of a CCW edge (inside a convex polygon).
        cross = edge[0] * (p2[:, 1] - a[1]) - edge[1] * (p2[:, 0] - a[0])
        inside &= cross >= margin * length
    return inside


def cast_rays(origins: np.ndarray, dirs: np.ndarray, faces: list[DesignFace],
              t_max: float = 200.0) -> tuple[np.ndarray, np.ndarray]:
    """First hit of rays (N, 3) ENU on the faces; returns range t (m, inf) and face index (-1).

    Vectorised over rays: one pass per face, keeping the nearest positive hit.
    """
    n = len(origins)
    best_t = np.full(n, np.inf)
    best_f = np.full(n, -1, dtype=np.int64)
    for k, face in enumerate(faces):
        denom = dirs @ face.normal
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (face.d - origins @ face.normal) / denom
        ok = (np.abs(denom) > 1e-9) & (t > 1e-6) & (t < np.minimum(best_t, t_max))
        if not ok.any():
            continue
        idx = np.flatnonzero(ok)
        hits = origins[idx] + t[idx, None] * dirs[idx]
        inside = inside_polygon(face, hits)
        idx = idx[inside]
        best_t[idx] = t[idx]
        best_f[idx] = k
    return best_t, best_f
