"""Above/below-water twins from the design, and the reference plane of every face.

Patent steps 3.3 and 4.2 rest on the target keeping "the same size and orientation above
and below water" (利用检校目标物在水上水下保持尺寸与方位一致) and on "the design height
difference between the above-water and the below-water triangular block": a block exists
twice, above water (seen only by the laser scanner) and below it (seen only by the
multibeam). So a below-water face is compared with the laser plane of its above-water
*twin*, moved by the design translation between the two.

Twins are recognised from the geometry of ``target.json`` alone (names are free text): a
below-water face and an above-water face are congruent when their normals are parallel
(same direction, within ``angle_tol_deg``) and each corner of one, moved by the translation
between the centroids, lands on a corner of the other (within ``tol_m``). Among several
congruent above-water faces (equal blocks in a column) the twin is the one with the
smallest horizontal translation, then the smallest vertical one (the block above it).

Faces are grouped into *bodies* (faces sharing an edge, i.e. two corners): a below-water
body is built as one piece, so its faces share one build error relative to the twin body
(a translation of ±``build_tol_m`` per axis and a rotation of ±``build_tol_deg`` per axis
about the body's centroid). The tolerance is a half-width; as a rectangular distribution
its standard deviation is tol/√3 (GUM 4.3.7).

Frames: target ENU, metres.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hydrosync_core.methods.pool_calibration.design import DesignFace
from hydrosync_core.methods.pool_calibration.planes import PlaneFit
from hydrosync_core.methods.pool_calibration.roles import FaceRole


@dataclass(frozen=True)
class Twin:
    """A below-water face, its above-water twin and the design translation twin -> face."""

    face: str
    twin: str
    translation: np.ndarray
    body: str
    twin_body: str


@dataclass(frozen=True)
class Reference:
    """Reference plane of a face seen by the multibeam (target ENU, m).

    ``source`` is the laser-fitted face whose plane is used, ``translation`` the design
    translation applied to it (zero for a face crossing the water: its own laser plane),
    ``group`` the build-error group (below-water body, twin body) or None, ``pivot`` the
    centroid of the below-water body (centre of its build rotation).
    """

    face: str
    plane: PlaneFit
    source: str
    translation: np.ndarray
    group: tuple[str, str] | None = None
    pivot: np.ndarray | None = None

    @property
    def kind(self) -> str:
        return "own" if self.group is None else "twin"


def bodies(faces: list[DesignFace], tol_m: float = 0.002) -> dict[str, str]:
    """Body label of every face: faces sharing an edge (two corners) form one body.

    The label is the common name prefix of the body's faces (trailing ``_`` removed) or,
    without one, the first face's name.
    """
    parent = list(range(len(faces)))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i, a in enumerate(faces):
        for j in range(i + 1, len(faces)):
            b = faces[j]
            d = np.linalg.norm(a.corners[:, None, :] - b.corners[None, :, :], axis=2)
            if int((d.min(axis=1) < tol_m).sum()) >= 2:
                parent[root(i)] = root(j)
    groups: dict[int, list[str]] = {}
    for i, f in enumerate(faces):
        groups.setdefault(root(i), []).append(f.name)
    out = {}
    for names in groups.values():
        prefix = names[0]
        for n in names[1:]:
            k = 0
            while k < min(len(prefix), len(n)) and prefix[k] == n[k]:
                k += 1
            prefix = prefix[:k]
        label = prefix.rstrip("_-. ") if len(names) > 1 and prefix.strip("_-. ") else names[0]
        for n in names:
            out[n] = label
    return out


def congruent_translation(a: DesignFace, b: DesignFace, tol_m: float = 0.005,
                          angle_tol_deg: float = 0.1) -> np.ndarray | None:
    """Translation (3,) carrying face *a* onto face *b*, or None if not congruent so."""
    if len(a.corners) != len(b.corners):
        return None
    if a.normal @ b.normal < np.cos(np.deg2rad(angle_tol_deg)):
        return None
    t = b.centroid - a.centroid
    moved = a.corners + t
    d = np.linalg.norm(moved[:, None, :] - b.corners[None, :, :], axis=2)
    if d.min(axis=1).max() > tol_m or d.min(axis=0).max() > tol_m:
        return None
    return t


def pair_twins(faces: list[DesignFace], roles: dict[str, FaceRole]) -> dict[str, Twin]:
    """Twin of every below-water face that has a congruent above-water face."""
    body = bodies(faces)
    above = [f for f in faces if roles[f.name].water == "above"]
    out = {}
    for f in faces:
        if roles[f.name].water != "below":
            continue
        best, key = None, None
        for a in above:
            t = congruent_translation(a, f)
            if t is None:
                continue
            k = (round(float(np.hypot(t[0], t[1])), 6), round(abs(float(t[2])), 6), a.name)
            if key is None or k < key:
                best, key = (a, t), k
        if best is not None:
            a, t = best
            out[f.name] = Twin(f.name, a.name, t, body[f.name], body[a.name])
    return out


def body_centroids(faces: list[DesignFace]) -> dict[str, np.ndarray]:
    """Centroid (3,) of each body's corners, by body label."""
    body = bodies(faces)
    pts: dict[str, list[np.ndarray]] = {}
    for f in faces:
        pts.setdefault(body[f.name], []).append(f.corners)
    return {k: np.unique(np.round(np.concatenate(v), 6), axis=0).mean(axis=0)
            for k, v in pts.items()}


def moved_plane(plane: PlaneFit, t: np.ndarray) -> PlaneFit:
    """*plane* translated by *t* (m): same normal, axes and covariance, new offset."""
    t = np.asarray(t, float)
    return PlaneFit(plane.normal, float(plane.d + plane.normal @ t), plane.centroid + t,
                    plane.rms, plane.n, plane.flatness, plane.axes, plane.eigvals, plane.cov)


def reference_planes(faces: list[DesignFace], roles: dict[str, FaceRole],
                     laser: dict[str, PlaneFit],
                     twins: dict[str, Twin] | None = None) -> dict[str, Reference]:
    """Reference plane of every face the multibeam can be compared with.

    A face crossing the water: its own laser plane. A below-water face with an above-water
    twin whose laser plane exists: that plane moved by the design translation.
    """
    twins = pair_twins(faces, roles) if twins is None else twins
    pivots = body_centroids(faces)
    out = {}
    for f in faces:
        role = roles[f.name]
        if role.water == "crossing" and f.name in laser:
            out[f.name] = Reference(f.name, laser[f.name], f.name, np.zeros(3))
        elif f.name in twins and twins[f.name].twin in laser:
            tw = twins[f.name]
            out[f.name] = Reference(f.name, moved_plane(laser[tw.twin], tw.translation),
                                    tw.twin, tw.translation, (tw.body, tw.twin_body),
                                    pivots[tw.body])
    return out
