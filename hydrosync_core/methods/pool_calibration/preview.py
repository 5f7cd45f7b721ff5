"""What the panel shows after "Segment" alone (Qt-free; runs in the worker thread).

The arrays mirror the stored ``results/pool_calibration/plan`` layout (target ENU, m) so
the same views draw both, except that there is no corrected multibeam yet
(``mbes_after_xyz`` is None): the soundings are georeferenced with the coarse setup.
"""

from __future__ import annotations

import numpy as np

from hydrosync_core.methods.pool_calibration import georef
from hydrosync_core.methods.pool_calibration.estimator import Segmentation


def segmentation_preview(seg: Segmentation, n_max: int = 20000,
                         seed: int = 0) -> tuple[dict, dict]:
    """Per-face counts and decimated clouds of a :class:`Segmentation`.

    Returns
    -------
    faces : dict of 1-D arrays ``face, role, water, points_laser, points_mbes, pairing``,
        one row per design face in design order (the face index used by the clouds).
    clouds : dict ``laser_xyz`` (n, 3), ``laser_face`` (n,), ``mbes_before_xyz`` (m, 3)
        coarse georeference, ``mbes_after_xyz`` None, ``mbes_face`` (m,) (-1 = no face);
        at most *n_max* random points per cloud.
    """
    rng = np.random.default_rng(seed)
    names = list(seg.design)
    n_laser = np.array([len(seg.laser_points.get(n, ())) for n in names], dtype=np.int64)
    n_mbes = np.array([len(seg.mbes_faces.get(n, ())) for n in names], dtype=np.int64)
    faces = {"face": np.array(names, dtype=str),
             "role": np.array([seg.roles[n].role for n in names], dtype=str),
             "water": np.array([seg.roles[n].water for n in names], dtype=str),
             "points_laser": n_laser, "points_mbes": n_mbes,
             "pairing": np.array([seg.pairing.get(n, "") for n in names], dtype=str)}
    parts = [seg.laser_points[n] for n in names if n in seg.laser_points]
    laser = np.concatenate(parts) if parts else np.zeros((0, 3))
    laser_face = np.repeat(np.arange(len(names)), n_laser).astype(np.int32)
    pick = np.sort(rng.choice(len(laser), min(n_max, len(laser)), replace=False))
    face = np.full(len(seg.ctx.x_m), -1, dtype=np.int32)
    for k, name in enumerate(names):
        face[seg.mbes_faces.get(name, [])] = k
    sel = np.sort(rng.choice(len(face), min(n_max, len(face)), replace=False))
    clouds = {"laser_xyz": laser[pick], "laser_face": laser_face[pick],
              "mbes_before_xyz": georef.georeference(seg.ctx, seg.r_m0, seg.lever0, sel),
              "mbes_after_xyz": None, "mbes_face": face[sel]}
    return faces, clouds
