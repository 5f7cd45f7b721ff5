"""GNSS-array attitude: estimators against known truth (Liu et al.'s methods + Wahba)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from hydrosync_core.methods.gnss_attitude import solve
from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams
from hydrosync_core.methods.gnss_attitude.pipeline import Track, solve_array, statistics
from hydrosync_core.methods.gnss_attitude.precision import monte_carlo, predict
from hydrosync_core.methods.gnss_attitude.simulate import (
    ArrayConfig,
    random_attitudes,
    simulate_array,
)
from hydrosync_core.rotations import euler_zyx_matrix, wrap_pi

#: Liu et al.'s layout (antenna 2 on the forward axis, 3 in the deck plane), in FRD.
SEED_LAYOUT = np.array([[0, 0, 0], [2.0, 0, 0], [0.8, 1.4, 0], [-1.0, 1.2, 0.0]])
#: An arbitrary layout: no antenna on an axis, not coplanar.
ODD_LAYOUT = np.array([[0.1, -0.2, 0.0], [2.5, 0.3, -0.1], [0.3, 1.6, 0.2],
                       [-1.2, -0.9, 0.05]])


def _truth(n=3000, seed=0):
    hpr = random_attitudes(n, seed, max_pitch_deg=85.0)
    # make sure the edges of every quadrant are there
    edges = np.array([[0, 0, 0], [90, 0, 180], [180, 45, -90], [270, -45, 90],
                      [359.9, 10, -179.9], [45, -85, 135], [135, 85, -135], [225, 0, -45]])
    hpr = np.vstack([hpr, edges])
    R = euler_zyx_matrix(*np.radians(hpr[:, [2, 1, 0]]).T)
    return hpr, R


def _err_deg(R, hpr):
    roll, pitch, heading = solve.matrix_angles(R)
    d = np.degrees(np.column_stack([wrap_pi(heading - np.radians(hpr[:, 0])),
                                    pitch - np.radians(hpr[:, 1]),
                                    wrap_pi(roll - np.radians(hpr[:, 2]))]))
    return d


def test_attitude_matrix_is_the_documented_convention():
    hpr, R = _truth(50)
    ref = Rotation.from_euler("ZYX", np.radians(hpr)).as_matrix()
    np.testing.assert_allclose(R, ref, atol=1e-14)
    roll, pitch, heading = solve.matrix_angles(R)
    assert heading.min() >= 0 and heading.max() < 2 * np.pi
    np.testing.assert_allclose(np.degrees(heading), hpr[:, 0] % 360, atol=1e-9)


@pytest.mark.parametrize("layout", [SEED_LAYOUT, ODD_LAYOUT], ids=["seed", "any"])
def test_all_quadrants_recovered_exactly_noise_free(layout):
    hpr, R = _truth()
    body = layout[1:] - layout[0]
    nav = np.einsum("nij,mj->nmi", R, body)
    direct = solve.direct_three(nav[:, 0], nav[:, 1], body[0], body[1])
    assert np.abs(_err_deg(direct, hpr)).max() < 1e-9
    w = solve.wahba(nav, body)
    assert np.abs(_err_deg(w, hpr)).max() < 1e-9
    start = solve.direct_three(nav[:, 0], nav[:, 1], body[0], body[1])
    res = solve.lsq(nav, body, None, start, 1e-12)
    R_lsq = euler_zyx_matrix(*res.angles.T)
    assert np.abs(_err_deg(R_lsq, hpr)).max() < 1e-9
    assert res.converged.all()
    # the reported ranges: heading 0-360, pitch ±90, roll ±180
    assert (res.angles[:, 2] >= 0).all() and (res.angles[:, 2] < 2 * np.pi).all()
    assert np.abs(res.angles[:, 0]).max() <= np.pi


def test_direct_method_quadrants_of_liu_tables_1_and_2():
    """Heading in each quadrant of (N12, E12) and roll in each quadrant of baseline 1→3."""
    body = SEED_LAYOUT[1:3] - SEED_LAYOUT[0]
    for heading in (30, 120, 210, 300):
        for roll in (-150, -30, 30, 150):
            R = euler_zyx_matrix(np.radians(roll), np.radians(5.0), np.radians(heading))
            nav = (R @ body.T).T
            r, p, h = solve.matrix_angles(solve.direct_three(nav[:1], nav[1:2], *body))
            assert np.degrees(h[0]) == pytest.approx(heading, abs=1e-9)
            assert np.degrees(r[0]) == pytest.approx(roll, abs=1e-9)
            assert np.degrees(p[0]) == pytest.approx(5.0, abs=1e-9)


def test_closed_form_and_iterative_lsq_agree():
    hpr, R = _truth(500, seed=2)
    body = ODD_LAYOUT[1:] - ODD_LAYOUT[0]
    nav = np.einsum("nij,mj->nmi", R, body)
    w = solve.wahba(nav, body)
    res = solve.lsq(nav, body, None, w, 1e-13)
    np.testing.assert_allclose(euler_zyx_matrix(*res.angles.T), w, atol=1e-12)
    # under noise too, when the weights are isotropic per baseline (same objective)
    rng = np.random.default_rng(3)
    noisy = nav + 0.01 * rng.standard_normal(nav.shape)
    weights = np.array([1.0, 4.0, 0.5])
    W = np.kron(np.diag(weights), np.eye(3))[None].repeat(len(nav), 0)
    w = solve.wahba(noisy, body, weights)
    res = solve.lsq(noisy, body, W, solve.direct_three(noisy[:, 0], noisy[:, 1], *body[:2]),
                    1e-13)
    np.testing.assert_allclose(euler_zyx_matrix(*res.angles.T), w, atol=1e-10)
    # and scipy's align_vectors gives the same rotation
    for i in range(5):
        rot, _ = Rotation.align_vectors(noisy[i], body, weights=weights)
        np.testing.assert_allclose(rot.as_matrix(), w[i], atol=1e-10)


def test_four_antenna_lsq_beats_three_antenna_direct_under_noise():
    body = SEED_LAYOUT
    mc = monte_carlo(body, 0.006, 0.012, n=4000, seed=5, attitude_deg=(123.0, 3.0, -7.0),
                     triplet=(0, 1, 2))
    assert (mc["lsq"] < mc["direct"]).all(), mc
    # and both agree with the predicted precision within 10 %
    for method in ("lsq", "direct"):
        pred = predict(body, 0.006, 0.012, (123.0, 3.0, -7.0), method, triplet=(0, 1, 2))
        np.testing.assert_allclose(mc[method], pred, rtol=0.1)


def test_prediction_is_inverse_in_baseline_length():
    small = predict(SEED_LAYOUT * 0.5, 0.006, 0.006)
    large = predict(SEED_LAYOUT * 2.0, 0.006, 0.006)
    np.testing.assert_allclose(small / large, 4.0, rtol=1e-6)


def _tracks(sim):
    from hydrosync_core.importers.rtklib_pos import ned_covariance

    return {n: Track(c["gps_s"], np.column_stack([c["x"], c["y"], c["z"]]), c["q"],
                     ned_covariance(c)) for n, c in sim["tracks"].items()}


def test_simulated_array_end_to_end_screening_and_accuracy():
    cfg = ArrayConfig(duration_s=400.0, float_rate_per_h=20.0, dropout=("A3", 100.0, 150.0))
    sim = simulate_array(config=cfg, seed=7)
    tracks = _tracks(sim)
    # a blunder: A2 displaced by 30 cm at ten epochs must be dropped by the length check
    fixed = np.flatnonzero(tracks["A2"].q == 1)
    bad = fixed[fixed > 200][:10]
    tracks["A2"].ecef[bad] += np.array([0.3, -0.1, 0.2])
    sol = solve_array(tracks, sim["antennas"], GnssAttitudeParams())
    c = sol.counts
    assert c["antennas"]["A2"]["length_rejected"] == 10
    assert c["antennas"]["A3"]["present"] <= 401 - 50
    floats = sum(int((t["q"] == 2).sum()) for t in sim["tracks"].values())
    assert sum(a["not_accepted_quality"] for a in c["antennas"].values()) == floats > 0
    assert c["solved"] + c["too_few_antennas"] == c["epochs"]
    truth = sim["truth"]
    idx = np.searchsorted(truth["gps_s"], np.round(sol.gps_s, 3))
    hpr = np.column_stack([truth["heading"], truth["pitch"], truth["roll"]])[idx]
    total = {}
    for name, m in sol.methods.items():
        ok = np.isfinite(m.angles_deg[:, 0])
        d = m.angles_deg[ok] - hpr[ok]
        d[:, 0] = (d[:, 0] + 180) % 360 - 180
        rms = np.sqrt(np.mean(d**2, axis=0))
        pred = np.sqrt(np.mean(m.std_deg[ok] ** 2, axis=0))
        assert (rms < 2.0 * pred).all(), (name, rms, pred)
        four = (sol.n_antennas[ok] == 4)
        rms4 = np.sqrt(np.mean(d[four] ** 2, axis=0))
        limit = {"lsq": 0.4, "wahba": 0.45, "direct": 0.6}[name]
        assert (rms4 < limit).all(), (name, rms4)  # A1-A3-A4 alone see pitch poorly
        total[name] = float(np.sum(rms4**2))
    assert total["lsq"] < total["direct"]
    stats = statistics(sol)
    assert stats["lsq"]["epochs"] == c["solved"]
    # the heading turns through 360°: every quadrant visited
    h = sol.methods["lsq"].angles_deg[:, 0]
    assert all(((h >= q) & (h < q + 90)).any() for q in (0, 90, 180, 270))
