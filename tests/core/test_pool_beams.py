"""Pool calibration: a range error moves a sounding along its beam, and nothing the fit
differentiates or cuts on may move with it (#24: yaw and lever x at -4σ on simulated passes
without any build error, an errors-in-the-variables bias)."""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from hydrosync_core.methods.pool_calibration import georef, joint
from hydrosync_core.methods.pool_calibration import segment as segmod
from hydrosync_core.methods.pool_calibration.beams import beam_meets_plane, sounding_points
from hydrosync_core.methods.pool_calibration.design import make_face
from hydrosync_core.methods.pool_calibration.planes import PlaneFit

NED2ENU = np.array([[0.0, 1, 0], [1, 0, 0], [0, 0, -1]])


def _plane(normal, d: float) -> PlaneFit:
    n = np.asarray(normal, float) / np.linalg.norm(normal)
    return PlaneFit(n, float(d), n * d, 0.0, 0, 0.0)


def _scene(errors: np.ndarray | None, n_pings: int = 120, n_beams: int = 60):
    """A vessel passing a wall and two oblique faces (target ENU): the exact range of every
    beam to its face, plus *errors* (m) along the beam. Returns ctx, obs, R_m, lever, the
    exact ranges."""
    planes = {"wall": _plane([1, 0, 0], 0.0), "north": _plane([-0.9, 0.42, 0], -0.6),
              "south": _plane([-0.9, -0.42, 0], -0.6)}
    t = np.arange(n_pings) * 0.1
    origin = np.column_stack([np.full(n_pings, -5.0), np.linspace(-4, 4, n_pings),
                              np.zeros(n_pings)])
    att = np.column_stack([np.sin(t), 3 * np.sin(1.3 * t), 2 * np.sin(0.7 * t + 1)])  # y p r
    rot = NED2ENU @ Rotation.from_euler("ZYX", np.deg2rad(att)).as_matrix()
    r_m = georef.boresight_matrix(*np.deg2rad([0.5, -0.3, 1.0]))
    lever = np.array([0.3, 0.8, 1.2])
    ang = np.deg2rad(np.linspace(10, 75, n_beams))
    u_s = np.column_stack([np.zeros(n_beams), np.sin(ang), np.cos(ang)])   # sensor FRD
    heads = origin + rot @ lever
    dirs = np.einsum("pij,kj->pki", rot, u_s @ r_m.T)
    xs, pings, which, exact = [], [], [], []
    for i, plane in enumerate(planes.values()):
        cos = dirs @ plane.normal
        rng_ = (plane.d - heads @ plane.normal)[:, None] / np.where(np.abs(cos) > 0.2, cos,
                                                                     np.nan)
        ok = np.isfinite(rng_) & (rng_ > 0.5) & ((np.arange(n_beams) % 3) == i)[None, :]
        p, k = np.nonzero(ok)
        xs.append(rng_[p, k, None] * u_s[k])
        pings.append(p)
        which.append(np.full(len(p), i))
        exact.append(rng_[p, k])
    xs, pings, which = np.concatenate(xs), np.concatenate(pings), np.concatenate(which)
    if errors is not None:
        xs = xs + errors[:len(xs), None] * xs / np.linalg.norm(xs, axis=1)[:, None]
    ctx = georef.GeorefContext(xs, pings, origin, rot, np.ones(len(xs), bool), 0, 0, t)
    obs = {n: (np.flatnonzero(which == i), pl) for i, (n, pl) in enumerate(planes.items())}
    return ctx, obs, r_m, lever


def test_beam_meets_plane_on_the_beam_and_on_the_plane():
    rng = np.random.default_rng(1)
    y = rng.normal(0, 3, (200, 3))
    n = np.array([0.6, -0.8, 0.0])
    r = y @ n - 0.5
    met = beam_meets_plane(y, n, r)
    cos = (y / np.linalg.norm(y, axis=1)[:, None]) @ n
    ok = np.abs(cos) >= 0.05
    assert np.allclose(met[ok] @ n, 0.5, atol=1e-9)                        # on the plane
    assert np.allclose(np.cross(met[ok], y[ok]), 0.0, atol=1e-9)           # on the beam
    assert np.array_equal(met[~ok], y[~ok])                                # grazing: kept


def test_rotation_columns_do_not_move_with_the_range_error():
    """At the true setup the residual of a sounding is its range error times the cosine of
    incidence; its derivatives, taken where the beam meets the plane, are the same whatever
    the error, so E[Jᵀr] = 0. Taken at the sounding itself they move with the error, the
    fault this guards against (the naive columns differ by up to ~1e-2 here)."""
    errors = np.random.default_rng(2).normal(0.0, 0.05, 20000)
    exact = _scene(None)
    noisy = _scene(errors)
    ctx0, obs, r_m, lever = exact
    theta = np.array(georef.boresight_angles(r_m))
    res0, jac0, _ = joint._system(ctx0, obs, r_m, lever, theta)
    res1, jac1, _ = joint._system(noisy[0], obs, r_m, lever, theta)
    assert np.max(np.abs(res0)) < 1e-9 and np.std(res1) > 0.02
    assert np.max(np.abs(jac1 - jac0)) < 1e-9 * np.max(np.abs(jac0))
    naive = np.vstack([np.cross(noisy[0].x_m[idx] @ r_m.T,
                                np.einsum("nji,j->ni", noisy[0].rot[noisy[0].ping[idx]],
                                          pl.normal)) for idx, pl in obs.values()])
    assert np.max(np.abs(naive - np.vstack([np.cross(ctx0.x_m[idx] @ r_m.T, np.einsum(
        "nji,j->ni", ctx0.rot[ctx0.ping[idx]], pl.normal)) for idx, pl in obs.values()]))) > 1e-3


def test_sounding_points_on_the_plane_are_the_error_free_points():
    errors = np.random.default_rng(3).normal(0.0, 0.05, 20000)
    ctx0, obs, r_m, lever = _scene(None)
    ctx1 = _scene(errors)[0]
    for idx, plane in obs.values():
        exact = sounding_points(ctx0, idx, r_m, lever)
        assert np.allclose(sounding_points(ctx1, idx, r_m, lever, plane), exact, atol=1e-9)
        assert not np.allclose(sounding_points(ctx1, idx, r_m, lever), exact, atol=1e-3)


def test_edge_cut_where_the_beam_meets_the_face_does_not_tilt_it():
    """Soundings of a 1 m square face seen at 45° incidence, σ_range = 5 cm. Cutting its
    polygon on the soundings keeps, near the edge the beams run towards, those whose range
    erred short, and near the opposite edge those that erred long: the residuals tilt
    across the face by many standard errors of the slope (16-18 SE over five draws when
    this test was written). Cut where the beams meet the face, they do not (|slope| < 2
    SE on those draws)."""
    rng = np.random.default_rng(4)
    n = 60000
    face = make_face("f", np.array([[0.0, -0.5, -2.5], [0.0, 0.5, -2.5], [0.0, 0.5, -1.5],
                                    [0.0, -0.5, -1.5]]), "test", 0)
    on = np.column_stack([np.zeros(n), rng.uniform(-0.7, 0.7, n), rng.uniform(-2.7, -1.3, n)])
    heads = on + np.array([-1.0, -1.0, 0.0]) * rng.uniform(3, 5, n)[:, None]
    u = (on - heads) / np.linalg.norm(on - heads, axis=1)[:, None]
    pts = on + rng.normal(0.0, 0.05, n)[:, None] * u
    kw = dict(tol=0.4, margin=0.0, water_margin=0.1, ransac_m=0.25, dbscan_eps=0.3,
              band_sigma=6.0)

    def slope(idx):
        """Residual (m) per metre along the face (y), and its standard error."""
        y, r = on[idx, 1], pts[idx, 0]
        b = np.polyfit(y, r, 1)[0]
        return b, np.std(r) / (np.sqrt(len(idx)) * np.std(y))

    b_fair, se = slope(segmod.segment_cloud(pts, [face], 0.0, "below", heads=heads,
                                            **kw)["f"].indices)
    b_cut, _ = slope(segmod.segment_cloud(pts, [face], 0.0, "below", **kw)["f"].indices)
    assert abs(b_fair) < 3.5 * se
    assert b_cut < -8 * se


def test_a_face_no_beam_can_reach_takes_no_soundings_of_its_neighbour():
    """Beams rising towards a block (4° up) hit its side 1-2.5 cm under the top. Where they
    would meet the top's plane lies well inside the top, but each would need a range error
    of decimetres to be the top's: the top keeps none of them (#24: a top with 21 such
    soundings put lever z at -5.9σ)."""
    rng = np.random.default_rng(5)
    top = make_face("top", np.array([[-1.0, 0.0, -1.3], [0.0, 0.0, -1.3], [0.0, 1.0, -1.3],
                                     [-1.0, 1.0, -1.3]]), "test", 0)
    side = make_face("side", np.array([[-1.0, 0.0, -2.3], [-1.0, 1.0, -2.3],
                                       [-1.0, 1.0, -1.3], [-1.0, 0.0, -1.3]]), "test", 1)
    n = 3000
    on = np.column_stack([np.full(n, -1.0), rng.uniform(0.05, 0.95, n),
                          rng.uniform(-1.325, -1.31, n)])
    heads = np.column_stack([np.full(n, -5.0), on[:, 1], np.full(n, -1.6)])
    u = (on - heads) / np.linalg.norm(on - heads, axis=1)[:, None]
    pts = on + rng.normal(0.0, 0.005, n)[:, None] * u
    seg = segmod.segment_cloud(pts, [top, side], 0.0, "below", tol=0.1, margin=0.1,
                               water_margin=0.1, ransac_m=0.03, dbscan_eps=0.3,
                               band_sigma=4.0, heads=heads)
    met = segmod.on_plane(pts, heads, top)
    assert np.mean(np.all((met[:, :2] > [-0.9, 0.1]) & (met[:, :2] < [-0.1, 0.9]), axis=1)) > 0.5
    assert seg["top"].n == 0
