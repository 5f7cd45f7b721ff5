"""Above/below-water twins from the design, and the reference plane of every face.

Patent steps 3.3 and 4.2 rest on the target keeping "the same size and orientation above
and below water" (利用检校目标物在水上水下保持尺寸与方位一致) and on "the design height
difference between the above-water and the below-water triangular block": a block exists
twice, above water (seen only by the laser scanner) and below it (seen only by the
multibeam). What the method needs of the twin is its **plane**: a below-water face is
compared with the laser plane of its above-water twin, moved by the design offset between
the two planes. The polygons need not be congruent (a below-water block is often taller,
sits on a plinth or is cut by the floor), so twins are paired by plane (names are free text):

* **declared** — ``target.json`` names the twin (``"twin": "NAME"``, optional
  ``"offset_m"``: the design distance from the twin's plane to the face's plane along the
  face's outward normal); this overrides the inference;
* **coplanar** — an above-water face (or a face crossing the water) whose outward normal is
  parallel within the pairing angle tolerance, whose plane coincides within the pairing
  offset tolerance and whose plan-view footprint overlaps the face's (a segment along the
  face for side faces, the polygon for tops): zero offset;
* **parallel offset** — the same but with the planes apart: the design offset between them
  (for horizontal tops the design height difference of step 4.2);
* **congruent** — without an overlapping candidate, a parallel face of the same polygon up
  to a translation (a twin shifted along the column, or another block's top).

Among candidates: coplanar first, then the smallest plane offset, then the nearest. Only a
face the scanner can see serves as a reference: not an underside (outward normal pointing
down), not turned away from the vessel side, and with at least the segmentation minimum of
laser points. Outward normals come from the bodies (faces sharing an edge form a solid;
outward points away from its centroid).

Faces are grouped into *bodies*: a below-water body is built as one piece, so its faces
share one build error relative to the twin body (a translation of ±``build_tol_m`` per axis
and a rotation of ±``build_tol_deg`` per axis about the body's centroid). The tolerance is a
half-width; as a rectangular distribution its standard deviation is tol/√3 (GUM 4.3.7).

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
    #: The rule that paired them: "declared", "coplanar", "parallel offset", "congruent".
    rule: str = "congruent"


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
    without one or when another body has it already, the first face's name.
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
        if label in out.values():  # free names may share a prefix across bodies
            label = names[0]
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


#: Pairing tolerances from the design coordinates (given to 0.1 mm: a 0.1 m edge then
#: tilts a normal by up to 0.06°), widened to the build tolerance when that is larger.
PAIR_ANGLE_DEG = 0.1
PAIR_OFFSET_M = 0.002
#: Outward normal this close to straight down: an underside; this far towards the wall
#: side: turned away from the vessel (and the scanner on it).
HIDDEN_COS = 0.5


def outward_normals(faces: list[DesignFace], towards: np.ndarray | None = None
                    ) -> dict[str, np.ndarray]:
    """Outward unit normal of every face: away from the centroid of its body; a lone face
    (the wall) faces *towards* (default: the other bodies' mean centroid)."""
    body = bodies(faces)
    centre = np.mean([f.centroid for f in faces], axis=0)
    out = {}
    for f in faces:
        group = [g.centroid for g in faces if body[g.name] == body[f.name]]
        if len(group) > 1:
            away = f.centroid - np.mean(group, axis=0)
        else:
            away = towards if towards is not None else centre - f.centroid
        out[f.name] = f.normal if f.normal @ away > 0 else -f.normal
    return out


def hidden_reason(outward: np.ndarray, vessel_side: np.ndarray) -> str | None:
    """Why no scanner position sees a face of this outward normal, or None."""
    if outward[2] < -HIDDEN_COS:
        return "an underside: no scanner sees it"
    if outward @ vessel_side < -HIDDEN_COS:
        return "turned away from the vessel: no scanner sees it"
    return None


def _interval_overlap(a: np.ndarray, b: np.ndarray) -> float:
    return float(min(a.max(), b.max()) - max(a.min(), b.min()))


def _clip_convex(subject: np.ndarray, clip: np.ndarray) -> np.ndarray:
    """Intersection of two convex 2-D polygons (Sutherland-Hodgman; clip made CCW)."""
    e1, e2 = clip[1] - clip[0], clip[2] - clip[0]
    if e1[0] * e2[1] - e1[1] * e2[0] < 0:
        clip = clip[::-1]
    out = subject
    for a, b in zip(clip, np.roll(clip, -1, axis=0), strict=True):
        if len(out) == 0:
            break
        edge = b - a
        side = edge[0] * (out[:, 1] - a[1]) - edge[1] * (out[:, 0] - a[0])
        pts = []
        for k in range(len(out)):
            p, q, sp, sq = out[k], out[(k + 1) % len(out)], side[k], side[(k + 1) % len(out)]
            if sp >= 0:
                pts.append(p)
            if (sp >= 0) != (sq >= 0):
                pts.append(p + sp / (sp - sq) * (q - p))
        out = np.array(pts).reshape(-1, 2)
    return out


def _area2d(poly: np.ndarray) -> float:
    if len(poly) < 3:
        return 0.0
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * abs(float(x @ np.roll(y, -1) - y @ np.roll(x, -1)))


def footprint_overlap(a: DesignFace, b: DesignFace) -> float:
    """Plan-view overlap of two parallel faces: length (m) along a side face, area (m²)
    of the tops' projections; <= 0 when the footprints do not overlap."""
    if abs(a.normal[2]) < np.sin(np.deg2rad(45.0)):       # side face: a segment in plan
        h = np.cross([0.0, 0.0, 1.0], a.normal)
        h /= np.linalg.norm(h)
        return _interval_overlap(a.corners @ h, b.corners @ h)
    return _area2d(_clip_convex(b.corners[:, :2], a.corners[:, :2]))


def _declared(f: DesignFace, a: DesignFace, out_f: np.ndarray, spec: dict,
              body: dict[str, str]) -> Twin:
    move = f.centroid - a.centroid
    if spec.get("offset_m") is not None:   # the declared offset replaces the normal part
        n = out_f
        move = move - (move @ n) * n + float(spec["offset_m"]) * n
    return Twin(f.name, a.name, move, body[f.name], body[a.name], "declared")


def pair_twins(faces: list[DesignFace], roles: dict[str, FaceRole],
               visible: set[str] | None = None, declared: dict[str, dict] | None = None,
               angle_tol_deg: float = PAIR_ANGLE_DEG, offset_tol_m: float = PAIR_OFFSET_M
               ) -> dict[str, Twin]:
    """Twin of every below-water face: declared, else paired by plane (module docstring).

    *visible* are the faces that may serve as a reference (default: every above-water or
    crossing face not hidden from the scanner); *declared* maps a face to its target.json
    entry holding ``twin`` (and ``offset_m``).
    """
    body = bodies(faces)
    by_name = {f.name: f for f in faces}
    vessel = vessel_side(roles)
    outward = outward_normals(faces, vessel)
    if visible is None:
        visible = {f.name for f in faces if roles[f.name].water != "below"
                   and hidden_reason(outward[f.name], vessel) is None}
    cands = [f for f in faces if f.name in visible and roles[f.name].water != "below"]
    cos_tol = np.cos(np.deg2rad(angle_tol_deg))
    out = {}
    for f in faces:
        spec = (declared or {}).get(f.name)
        if spec and spec.get("twin") in by_name:
            out[f.name] = _declared(f, by_name[spec["twin"]], outward[f.name], spec, body)
            continue
        if roles[f.name].water != "below":
            continue
        best, key = None, None
        for a in cands:
            if outward[a.name] @ outward[f.name] < cos_tol:
                continue
            move = f.centroid - a.centroid
            offset = float(move @ outward[f.name])
            if footprint_overlap(f, a) > 1e-3:
                rule = "coplanar" if abs(offset) <= offset_tol_m else "parallel offset"
            elif congruent_translation(a, f, angle_tol_deg=angle_tol_deg) is not None:
                rule = "congruent"
            else:
                continue
            k = (("coplanar", "parallel offset", "congruent").index(rule),
                 round(abs(offset), 6), round(float(np.linalg.norm(move)), 6), a.name)
            if key is None or k < key:
                best, key = (a, move, rule), k
        if best is not None:
            a, move, rule = best
            if rule == "coplanar":       # the design says the same plane: no offset at all
                move = move - (move @ outward[f.name]) * outward[f.name]
            out[f.name] = Twin(f.name, a.name, move, body[f.name], body[a.name], rule)
    return out


def vessel_side(roles: dict[str, FaceRole]) -> np.ndarray:
    """Unit horizontal direction from the wall towards the vessel side (ENU)."""
    wall = next((r for r in roles.values() if r.role == "wall"), None)
    return np.array([-1.0, 0.0, 0.0]) if wall is None else wall.normal


def pairing_notes(faces: list[DesignFace], roles: dict[str, FaceRole],
                  twins: dict[str, Twin], laser_points: dict[str, int], min_points: int
                  ) -> dict[str, str]:
    """Face -> the rule that gave its reference plane, or why it has none."""
    vessel = vessel_side(roles)
    outward = outward_normals(faces, vessel)
    out = {}
    for f in faces:
        water = roles[f.name].water
        hidden = hidden_reason(outward[f.name], vessel)
        n_laser = laser_points.get(f.name, 0)
        if f.name in twins:
            tw = twins[f.name]
            n_twin = laser_points.get(tw.twin, 0)
            hid = hidden_reason(outward[tw.twin], vessel)
            out[f.name] = (f"{tw.rule} with {tw.twin}, {hid.split(':')[0]}: no reference"
                           if hid else f"{tw.rule} with {tw.twin}" if n_twin >= min_points
                           else f"{tw.rule} with {tw.twin}, which has {n_twin} laser points "
                           f"(< {min_points}): no reference")
        elif water == "crossing":
            out[f.name] = ("own laser plane" if n_laser >= min_points else
                           f"crossing, but {n_laser} laser points (< {min_points})")
        elif water == "above":
            out[f.name] = (f"above water ({hidden})" if hidden else
                           "above water (a reference for its twins)")
        elif hidden:
            out[f.name] = f"unpaired: {hidden.split(':')[0]}"
        else:
            out[f.name] = "unpaired: no visible above-water face parallel to it"
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
        tw = twins.get(f.name)
        use_twin = tw is not None and tw.twin in laser and (
            role.water != "crossing" or tw.rule == "declared")
        if role.water == "crossing" and f.name in laser and not use_twin:
            out[f.name] = Reference(f.name, laser[f.name], f.name, np.zeros(3))
        elif use_twin:
            out[f.name] = Reference(f.name, moved_plane(laser[tw.twin], tw.translation),
                                    tw.twin, tw.translation, (tw.body, tw.twin_body),
                                    pivots[tw.body])
    return out
