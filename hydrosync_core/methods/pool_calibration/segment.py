"""Segmentation of the laser and multibeam clouds into the design faces (seed step 2).

Guided by the design (target ENU, m): for each face, crop the points within ``tol`` of
its plane, inside its polygon shrunk by ``margin`` and on the sensor's side of the water
level (laser above, multibeam below, ``water_margin`` away from the surface, which
removes water-surface returns); the pool floor, self-returns and strays fall outside the
crops. Then RANSAC (:func:`ransac_plane`, seeded) keeps the plane's inliers and DBSCAN keeps
the largest cluster, removing remaining strays that happen to lie near the plane. Large
clouds are first cropped to the target's bounding box; per-face point sets are capped
(random subset) so that RANSAC/DBSCAN cost stays bounded. For the final (refined)
multibeam faces the RANSAC band is replaced by a symmetric ±k·σ band about the face's own
TLS plane (:func:`band_refit`): RANSAC is only the robust starting point, so the kept
points neither depend on the (non-repeatable) RANSAC draw nor lean towards its plane.
Those final selections then give up every point that lies as close to another face
(:func:`drop_intersections`): a sounding near the line where two faces meet cannot be
told to belong to one of them, and the noise truncated there biases both planes.

Where the sensor head of each sounding is known (``heads``: the multibeam's, per sounding),
the cuts that run across a face (its polygon, the water level, the band about another face)
are made where the sounding's beam meets the face's plane (:func:`on_plane`), not at the
sounding itself. A range error moves a sounding along its beam, so both across the face and
off its plane: cutting on the sounding's own position keeps, near each edge, only the
soundings whose range erred one way, a one-sided residual along that edge (about +1σ of
yaw on the #24 passes). Where the beam meets the plane does not depend on the range error
(:mod:`.beams`). A sounding nearer another face's plane than its own is still dropped on
its own position: on a grazing face its beam meets the plane far from where it lies.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hydrosync_core.methods.pool_calibration.beams import beam_meets_plane
from hydrosync_core.methods.pool_calibration.design import DesignFace, inside_polygon
from hydrosync_core.progress import check_cancel, report

#: Largest point set clustered by DBSCAN directly (:func:`_dbscan_labels`).
DBSCAN_MAX_POINTS = 3000


@dataclass(frozen=True)
class FaceSegment:
    """Indices (into the segmented cloud) of the points of one face, and crop counts."""

    name: str
    indices: np.ndarray
    cropped: int
    ransac_inliers: int

    @property
    def n(self) -> int:
        return len(self.indices)


def inradius(face: DesignFace) -> float:
    """2·area / perimeter of the face polygon (m): its inradius for a triangle."""
    perimeter = float(np.sum(np.linalg.norm(np.diff(face.poly2d, axis=0, append=face.poly2d[:1]),
                                            axis=1)))
    return 2.0 * face.area / perimeter


def bbox_mask(points: np.ndarray, faces: list[DesignFace], pad: float) -> np.ndarray:
    """Points inside the design's bounding box grown by *pad* m."""
    corners = np.concatenate([f.corners for f in faces])
    lo, hi = corners.min(axis=0) - pad, corners.max(axis=0) + pad
    return np.all((points >= lo) & (points <= hi), axis=1)


def ransac_plane(pts: np.ndarray, thresh: float, iterations: int,
                 rng: np.random.Generator, chunk: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """RANSAC plane of *pts* (n, 3, m): unit normal (3,) and indices of the points within
    *thresh* m of the plane with most such points.

    numpy rather than open3d's ``segment_plane``: that one draws its samples in several
    threads, so the same cloud can give another plane on another run, and the selected
    points (hence the calibration) were not repeatable. Here the draws come from *rng*
    and ties go to the first hypothesis.
    """
    n = len(pts)
    pick = rng.integers(0, n, (iterations, 3))
    a, b, c = pts[pick[:, 0]], pts[pick[:, 1]], pts[pick[:, 2]]
    normals = np.cross(b - a, c - a)
    length = np.linalg.norm(normals, axis=1)
    ok = length > 1e-12
    normals, a = normals[ok] / length[ok, None], a[ok]
    if not len(normals):
        return np.array([0.0, 0.0, 1.0]), np.arange(0)
    offsets = np.einsum("ij,ij->i", normals, a)
    centre = pts.mean(axis=0)    # distances from a centred cloud: no cancellation
    local = pts - centre
    offsets = offsets - normals @ centre
    counts = np.concatenate([
        (np.abs(local @ normals[k:k + chunk].T - offsets[k:k + chunk]) < thresh).sum(axis=0)
        for k in range(0, len(normals), chunk)])
    best = int(np.argmax(counts))
    inliers = np.flatnonzero(np.abs(local @ normals[best] - offsets[best]) < thresh)
    return normals[best], inliers


def _ransac_dbscan(pts: np.ndarray, thresh: float, eps: float, min_points: int,
                   normal: np.ndarray, max_angle_deg: float, attempts: int = 4) -> np.ndarray:
    """Indices into *pts* of the RANSAC plane inliers' largest DBSCAN cluster.

    A RANSAC plane far from the design orientation is clutter, not the face (a neighbour
    face or the pool floor that dominates a wide crop): its inliers are set aside and
    RANSAC is run again on the rest, up to *attempts* times.
    """
    if len(pts) < max(3, min_points):
        return np.arange(0)
    rng = np.random.default_rng(0)
    left = np.arange(len(pts))
    inliers = None
    for _ in range(attempts):
        if len(left) < max(3, min_points):
            return np.arange(0)
        n_fit, found = ransac_plane(pts[left], thresh, 300, rng)
        if np.degrees(np.arccos(min(1.0, abs(n_fit @ normal)))) <= max_angle_deg:
            inliers = left[found]
            break
        left = np.delete(left, found)
    if inliers is None:
        return np.arange(0)
    if len(inliers) < min_points:
        return inliers
    labels = _dbscan_labels(pts[inliers], eps, min_points)
    if (labels >= 0).sum() == 0:
        return np.arange(0)
    biggest = np.bincount(labels[labels >= 0]).argmax()
    return inliers[labels == biggest]


def _dbscan_labels(pts: np.ndarray, eps: float, min_points: int,
                   max_points: int = DBSCAN_MAX_POINTS) -> np.ndarray:
    """DBSCAN cluster labels (-1: noise) of *pts* (n, 3, m).

    DBSCAN's cost grows with the number of neighbours within *eps*, and a densely sampled
    face has thousands per point (minutes for one oblique face). Above *max_points* the
    clusters are found on an evenly spread subset (every k-th point of a random order, so
    the density drops by k but stays far above *min_points* on a face) and every other
    point takes the label of its nearest subset point within *eps* (noise if none or if
    that point is noise): isolated strays stay noise, a face stays one cluster.
    """
    import open3d as o3d

    if len(pts) <= max_points:
        cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(pts))
        return np.asarray(cloud.cluster_dbscan(eps=eps, min_points=min_points))
    from scipy.spatial import cKDTree

    order = np.random.default_rng(0).permutation(len(pts))
    sub = np.sort(order[:max_points])
    sub_labels = _dbscan_labels(pts[sub], eps, min_points, max_points)
    dist, near = cKDTree(pts[sub]).query(pts, distance_upper_bound=eps)
    found = np.isfinite(dist)
    labels = np.full(len(pts), -1, dtype=np.int64)
    labels[found] = sub_labels[near[found]]
    return labels


def band_refit(pts: np.ndarray, start: np.ndarray, k_sigma: float, limit: float,
               max_iter: int = 10) -> np.ndarray:
    """Indices into *pts* (n, 3, m) within ``k_sigma`` robust σ of their own TLS plane.

    Starts from the RANSAC/DBSCAN selection *start* and iterates fit -> select until the
    selection is stable. Why: the RANSAC band is centred on a 3-point plane, so when that
    plane is slightly tilted the band cuts the noise distribution asymmetrically at one
    end of the face and the kept points lean towards the RANSAC plane (a bias of a few
    hundredths of a degree on a 6 m wall, and a random one: open3d's RANSAC is
    multi-threaded, hence not repeatable). A band of ±k·σ (σ = 1.4826·MAD of the
    distances) around the points' own least-squares plane is symmetric about the fit, so
    its fixed point does not depend on the RANSAC draw and truncates a negligible tail.
    The band never exceeds *limit* m (the crop tolerance).
    """
    from hydrosync_core.methods.pool_calibration.planes import fit_plane

    sel = np.asarray(start)
    if len(sel) < 10:
        return sel
    for _ in range(max_iter):
        plane = fit_plane(pts[sel])
        dist = pts @ plane.normal - plane.d
        d_sel = dist[sel]
        # Robust σ of the current selection (MAD), then a symmetric band about the fit.
        sigma = 1.4826 * float(np.median(np.abs(d_sel - np.median(d_sel))))
        new = np.flatnonzero(np.abs(dist) < min(limit, k_sigma * max(sigma, 1e-6)))
        if len(new) < 10 or np.array_equal(new, sel):
            break
        sel = new
    return sel


def band_halfwidth(pts: np.ndarray, k_sigma: float, limit: float) -> float:
    """Half-width (m) of the ±k·σ band of :func:`band_refit` for the kept points *pts*
    (σ = 1.4826·MAD of their distances to their own TLS plane), at most *limit*."""
    from hydrosync_core.methods.pool_calibration.planes import fit_plane

    if len(pts) < 10:
        return limit
    dist = pts @ fit_plane(pts).normal
    sigma = 1.4826 * float(np.median(np.abs(dist - np.median(dist))))
    return min(limit, k_sigma * max(sigma, 1e-6))


def on_plane(points: np.ndarray, heads: np.ndarray | None, face: DesignFace) -> np.ndarray:
    """Where each point's beam, from its sensor head (*heads*, (n, 3) m), meets *face*'s
    plane (n, 3, target ENU m; :func:`~.beams.beam_meets_plane`); without *heads*, the
    points themselves."""
    if heads is None:
        return points
    return heads + beam_meets_plane(points - heads, face.normal, points @ face.normal - face.d)


def range_error(points: np.ndarray, heads: np.ndarray, face: DesignFace) -> np.ndarray:
    """|Range error| (n,) m each point would need to lie on *face*'s plane: its distance to
    the plane over the cosine of its beam's incidence (beams from *heads*, m).

    A sounding off a face's plane by r is the face's only if its range erred by r/cos. Near
    a grazing face a sounding of the next face lies a few centimetres off the plane, but
    needs a range error of decimetres: a block's oblique side just under its top, seen by
    beams rising towards it, would otherwise meet the top's plane well inside the top
    (#24: lever z at -5.9σ from 21 such soundings taken for a top no beam can see).
    """
    ray = points - heads
    cos = np.abs(ray @ face.normal) / np.maximum(np.linalg.norm(ray, axis=1), 1e-12)
    return np.abs(points @ face.normal - face.d) / np.maximum(cos, 1e-3)


def drop_intersections(points: np.ndarray, faces: list[DesignFace],
                       selected: dict[str, np.ndarray], bands: dict[str, float],
                       heads: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Selections (indices into *points*, target ENU m) without the points as close to
    another design face as to their own.

    A point of face F is dropped when it lies within the band b of another face G's plane
    and inside G's polygon grown by b, with b the wider of the two faces' bands (*bands*:
    face -> half-width in m; a face with nothing selected, an underside or a face against
    the wall, takes F's). Why: the soundings at the foot of a block standing on a plinth
    (or at any concave edge) are as near the plinth top as the block's side; the band of
    the plinth top then keeps those the range noise put below it and not those above, a
    few millimetres of one-sided bias over a strip that tilts the plinth-top reference
    (#24: roll at +4σ and +8σ on plinth sessions). The same holds where the design
    covers a face with another body (a block's footprint on its plinth, a face flush with
    the wall), where no sounding can come from the covered face. With *heads* (sensor
    head per point) the test is made where the point's beam meets F's plane
    (:func:`on_plane`), so that a range error does not decide it; a point nearer G's plane
    than F's, inside G's polygon grown by b, is dropped too (a sounding of G near F's
    plane, whose beam may meet F's plane far away when it grazes F).
    """
    out = {}
    for f in faces:
        idx = selected.get(f.name, np.arange(0))
        if not len(idx):
            out[f.name] = idx
            continue
        pts = points[idx]
        met = on_plane(pts, None if heads is None else heads[idx], f)
        own = np.abs(pts @ f.normal - f.d)
        keep = np.ones(len(idx), bool)
        for g in faces:
            if g.name == f.name:
                continue
            band = max(bands.get(f.name, 0.0), bands.get(g.name, 0.0))
            near = np.abs(met @ g.normal - g.d) < band
            if heads is not None:
                near |= np.abs(pts @ g.normal - g.d) < np.minimum(own, band)
            near &= keep
            if near.any():
                hit = np.flatnonzero(near)
                keep[hit[inside_polygon(g, met[hit], -band)
                         | inside_polygon(g, pts[hit], -band)]] = False
        out[f.name] = idx[keep]
    return out


def segment_cloud(points: np.ndarray, faces: list[DesignFace], water_level: float,
                  side: str, *, tol: float = 0.3, margin: float = 0.1,
                  water_margin: float = 0.1, ransac_m: float = 0.05, dbscan_eps: float = 0.3,
                  min_points: int = 10, max_points: int = 20000, max_angle_deg: float = 15.0,
                  band_sigma: float = 0.0, seed: int = 0, heads: np.ndarray | None = None,
                  progress=None, cancel=None) -> dict[str, FaceSegment]:
    """Segment *points* (N, 3, target ENU, m) into *faces*.

    *side* is ``"above"`` (laser) or ``"below"`` (multibeam). The polygon shrink *margin*
    is capped at half the face's inradius, so small faces keep a core. With ``band_sigma > 0`` the
    RANSAC/DBSCAN selection is replaced by the symmetric band of :func:`band_refit`
    (±band_sigma robust σ about the face's own TLS plane, within the crop) and the points
    as close to another face are dropped (:func:`drop_intersections`). *heads* (N, 3, m):
    the sensor head of each point; given, the polygon, water-level and intersection cuts are
    made where the point's beam meets the face's plane (module docstring), and a point whose
    range would have to err by more than *tol* to lie on the face is not the face's
    (:func:`range_error`). Returns a
    :class:`FaceSegment` per face name (possibly empty).
    """
    rng = np.random.default_rng(seed)
    cand = np.flatnonzero(bbox_mask(points, faces, tol))
    pts = points[cand]

    def wet_side(z: np.ndarray, margin: float) -> np.ndarray:
        return z > water_level + margin if side == "above" else z < water_level - margin

    # With the heads, the margin is applied per face where the beams meet it; the points
    # themselves need only be on the sensor's side of the surface (surface returns go).
    ok = wet_side(pts[:, 2], water_margin if heads is None else 0.0)
    cand, pts = cand[ok], pts[ok]
    hds = None if heads is None else heads[cand]
    out = {}
    bands: dict[str, float] = {}
    for k, face in enumerate(faces):
        check_cancel(cancel)
        near = np.abs(pts @ face.normal - face.d) < tol
        idx = np.flatnonzero(near)
        shrink = min(margin, 0.5 * inradius(face))
        if hds is not None:
            met = on_plane(pts[idx], hds[idx], face)
            idx = idx[wet_side(met[:, 2], water_margin) & inside_polygon(face, met, shrink)
                      & (range_error(pts[idx], hds[idx], face) < tol)]
        else:
            idx = idx[inside_polygon(face, pts[idx], shrink)]
        cropped = len(idx)
        if len(idx) > max_points:
            idx = np.sort(rng.choice(idx, max_points, replace=False))
        keep = _ransac_dbscan(pts[idx], ransac_m, dbscan_eps, min_points, face.normal,
                              max_angle_deg)
        if band_sigma > 0 and len(keep) >= min_points:
            keep = band_refit(pts[idx], keep, band_sigma, tol)
            bands[face.name] = band_halfwidth(pts[idx[keep]], band_sigma, tol)
        sel = np.sort(cand[idx[keep]])
        out[face.name] = FaceSegment(face.name, sel, cropped, len(keep))
        report(progress, (k + 1) / len(faces), f"segmented {face.name} ({side} water)")
    if bands:
        kept = drop_intersections(points, faces, {n: s.indices for n, s in out.items()},
                                  bands, heads)
        out = {n: FaceSegment(n, kept[n], s.cropped, s.ransac_inliers)
               for n, s in out.items()}
    return out


def voxel_downsample(points: np.ndarray, voxel: float) -> np.ndarray:
    """open3d voxel-grid downsampling (one averaged point per *voxel* m cube)."""
    import open3d as o3d

    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    return np.asarray(cloud.voxel_down_sample(voxel).points)
