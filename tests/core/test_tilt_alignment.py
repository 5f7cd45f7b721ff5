"""Tilt-pole alignment (Li et al. + joint batch LSQ): numbers against simulated truth."""

from __future__ import annotations

import json
import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from hydrosync_core.methods.tilt_alignment import align
from hydrosync_core.methods.tilt_alignment.align import Undetermined
from hydrosync_core.methods.tilt_alignment.geometry import (
    mahony,
    propagate,
    rz,
    yaw_of,
)
from hydrosync_core.methods.tilt_alignment.params import METHODS, TiltParams
from hydrosync_core.methods.tilt_alignment.pipeline import solve_record
from hydrosync_core.methods.tilt_alignment.simulate import (
    SwingConfig,
    noise_free,
    simulate_swing,
)


def _solve(sim, params=None):
    return solve_record(sim["time"], sim["gyro"], sim["accel"], sim["gnss_time"],
                        sim["gnss_ned"], sim["pole_length_m"], params or TiltParams(),
                        gravity=sim["truth"]["config"].gravity_m_s2,
                        imu_convention=sim["truth"]["config"].imu_convention)


@pytest.mark.parametrize("convention", ["instant", "interval-start"])
def test_gyro_propagation_reproduces_the_simulated_attitude(convention):
    """A fast coning motion (three sweeps of a 50° ellipse with a 15° twist, 50 Hz): the
    model grid's increments (:func:`.imu_convention.to_model_grid`, coning term included)
    chain to the true attitude within 0.1 mrad over the record (measured 0.05 / 0.02
    mrad; without the coning term 1.4 mrad either way, which the adjustment read as
    1.6-1.9× the gyro noise)."""
    from hydrosync_core.methods.tilt_alignment.imu_convention import to_model_grid
    from hydrosync_core.rotations import log_so3

    cfg = SwingConfig(tilt_deg=50, sweeps=3, shape_ratio=0.5, twist_deg=15.0,
                      imu_rate_hz=50.0, imu_convention=convention)
    sim = simulate_swing(noise_free(cfg), seed=4)
    t, w, _ = to_model_grid(sim["time"], sim["gyro"], sim["accel"], convention)
    C = propagate(sim["truth"]["C"][0], t, w)         # interval-start: model times = tags
    err = log_so3(np.einsum("kji,kjl->kil", sim["truth"]["C"], C))
    assert np.max(np.linalg.norm(err, axis=1)) < 1e-4


def test_mahony_levels_a_still_pole_and_keeps_heading_zero():
    cfg = noise_free(SwingConfig(wobble_deg=0.0, heading_deg=40.0))
    sim = simulate_swing(cfg, seed=2)
    C, _ = mahony(sim["time"], sim["gyro"], sim["accel"], 1.0, 0.3, 0.02, cfg.gravity_m_s2)
    true0 = sim["truth"]["C"][0]
    # C = Rz(ψ)·C' with ψ the true heading at the start: equal up to that rotation
    assert np.max(np.abs(rz(math.radians(sim["truth"]["heading_deg"])) @ C[0] - true0)) < 1e-9
    assert abs(yaw_of(C[0])) < 1e-12


@pytest.mark.parametrize(("heading", "convention"), [(123.0, "instant"),
                                                    (-170.0, "interval-end")])
def test_noise_free_swing_recovers_the_misalignment_with_every_method(heading, convention):
    """Noise-free: every heading-only method within 0.002° (joint 0.01°), all within 0.5 mm.
    Not exact: the model grid of instantaneous or end-tagged samples interpolates to
    second order (Δt²/8·ω̈, 10⁻⁴ of the rate at 100 Hz), and the Mahony levelling of a
    moving pole is approximate."""
    cfg = noise_free(SwingConfig(wobble_deg=0.0, heading_deg=heading, shape_ratio=0.3,
                                 imu_convention=convention))
    sim = simulate_swing(cfg, seed=3)
    sol = _solve(sim, TiltParams(stop_deg=1e-9))
    truth = sim["truth"]["heading_deg"]
    for name in METHODS:
        m = sol.methods[name]
        assert m.ok, (name, m.undetermined)
        err = (math.degrees(m.psi) - truth + 180) % 360 - 180
        # the joint heading is weakly tied at small tilt (σ 0.2°): its priors pull 0.005°
        assert abs(err) < (1e-2 if name == "joint" else 2e-3), (name, err)
        assert np.max(np.abs(m.tip - sim["truth"]["tip_ned"])) < 5e-4, name
    # the descent itself, started far away (ψ0 = 0), converges to the closed form
    vec = sol.vectors
    d = align.descend(vec.nav[vec.used], vec.imu[vec.used], 0.0, 0.3, 1e-12, 1000)
    assert d.converged and d.iterations > 10
    assert abs(d.psi - sol.methods["closed_form"].psi) < 1e-9


def test_gradient_descent_stops_on_the_threshold_and_matches_the_closed_form():
    sim = simulate_swing(SwingConfig(), seed=4)
    sol = _solve(sim, TiltParams(learning_rate=0.2, stop_deg=1e-7))
    mb, cf = sol.methods["mbgd"], sol.methods["closed_form"]
    assert abs(mb.psi - cf.psi) < math.radians(1e-5)
    h = mb.history
    assert abs(h[-1] - h[-2]) < math.radians(1e-7) <= abs(h[-2] - h[-3])
    coarse = _solve(sim, TiltParams(learning_rate=0.2, stop_deg=0.5))
    assert coarse.methods["mbgd"].iterations < mb.iterations


def test_discordant_vectors_are_rejected():
    sim = simulate_swing(SwingConfig(wobble_deg=0.0, gnss_sigma_h_m=0.003,
                                     gnss_sigma_v_m=0.006), seed=5)
    bad = sim["gnss_ned"].copy()
    bad[[12, 30]] += [0.25, -0.2, 0.0]      # two GNSS epochs off by 30 cm
    sim_bad = dict(sim, gnss_ned=bad)
    sol = _solve(sim_bad)
    vec = sol.vectors
    involved = np.isin(vec.pairs, [12, 30]).any(axis=1)
    assert sol.screening is None
    assert vec.n_rejected > 0
    assert not vec.used[~involved].size or vec.used[~involved].mean() > 0.9
    assert (~vec.used[involved]).mean() > 0.3
    # the mini-batch (screened) beats the batch (all vectors) on the faulty set
    truth = math.radians(sim["truth"]["heading_deg"])
    e_mb = abs(align.wrap(sol.methods["mbgd"].psi - truth))
    e_b = abs(align.wrap(sol.methods["bgd"].psi - truth))
    assert e_mb < e_b


def test_a_faulty_imu_makes_the_vector_set_undetermined():
    # a gyro z axis 20 °/s off: per-pair headings spread over tens of degrees
    cfg = SwingConfig(gyro_bias_deg_s=(0.0, 0.0, 20.0))
    sim = simulate_swing(cfg, seed=6)
    sol = _solve(sim)
    assert sol.screening is not None and "disagree" in sol.screening
    for name in ("mbgd", "svd", "closed_form"):
        assert not sol.methods[name].ok
    rng = np.random.default_rng(0)
    nav = rng.normal(0, 1, (40, 3))
    turn = rng.uniform(-np.pi, np.pi, 40)            # every vector with its own heading
    imu = np.einsum("kij,kj->ki", np.array([rz(-a) for a in turn]), nav)
    vec = align.Vectors(nav, imu, np.zeros((40, 2), int), align.pair_headings(nav, imu),
                        np.ones(40, bool))
    with pytest.raises(Undetermined, match="disagree"):
        align.screen(vec, 3.0, math.radians(1), math.radians(8), 5)


@pytest.mark.parametrize("tilt_deg", [20.0, 40.0, 60.0])
def test_eq17_horizontal_error_from_a_heading_error(tilt_deg):
    """ΔH = ψ·l·sinβ: tilt-compensate with the heading off by ψ and measure the tip shift."""
    length, psi = 1.865, math.radians(0.5)
    beta = math.radians(tilt_deg)
    C = np.array([rz(0.3) @ np.array([[math.cos(beta), 0, math.sin(beta)], [0, 1, 0],
                                       [-math.sin(beta), 0, math.cos(beta)]])])
    antenna = -C[:, :, 2] * length                   # the tip at the origin
    tip_right = align.compensate(antenna, C, length)
    tip_wrong = align.compensate(antenna, rz(psi)[None] @ C, length)
    dh = float(np.hypot(*(tip_wrong - tip_right)[0, :2]))
    assert tip_right == pytest.approx(np.zeros((1, 3)), abs=1e-12)
    assert dh == pytest.approx(align.horizontal_error_from_heading(psi, length, beta),
                               rel=1e-5)
    assert abs((tip_wrong - tip_right)[0, 2]) < 1e-12       # heights untouched (eq. 18)
    # Li et al.: l = 1.865 m, 2.5 cm at 40° needs ψ ≤ 1.19°
    assert math.degrees(0.025 / (length * math.sin(math.radians(40)))) == pytest.approx(1.19,
                                                                                       abs=0.01)


def test_joint_lsq_reaches_sub_centimetre_tips_on_a_noisy_swing():
    cfg = SwingConfig(tilt_deg=55.0, shape_ratio=0.4, gyro_bias_deg_s=(0.05, -0.04, 0.05),
                      accel_bias_m_s2=(0.02, -0.02, 0.01), wobble_deg=0.3, gap_s=0.4,
                      gravity_m_s2=9.81)
    sim = simulate_swing(cfg, seed=8)
    sol = _solve(sim)
    j = sol.methods["joint"]
    err = j.tip - sim["truth"]["tip_ned"]
    assert j.ok
    assert np.hypot(*err[:2]) < 0.01 and abs(err[2]) < 0.01
    assert np.all(np.abs(err) < 3.5 * j.tip_std + 1e-3)      # σ is honest
    assert np.all(j.tip_std < 0.01)
    assert np.allclose(np.degrees(sol.joint.gyro_bias), cfg.gyro_bias_deg_s, atol=0.03)
    # the heading-only methods after static levelling miss by more on the same swing
    mb = sol.methods["mbgd"]
    assert np.hypot(*(mb.tip - sim["truth"]["tip_ned"])[:2]) > np.hypot(*err[:2])


def test_simulator_keeps_the_tip_fixed_and_the_tilt_limit():
    cfg = SwingConfig(tilt_deg=47.0, sweeps=3, shape_ratio=0.6)
    sim = simulate_swing(noise_free(cfg), seed=9)
    C, length = sim["truth"]["C"], sim["pole_length_m"]
    k = np.searchsorted(sim["time"], sim["gnss_time"])
    tips = sim["gnss_ned"] + C[k, :, 2] * length
    assert np.max(np.abs(tips)) < 1e-12
    assert sim["truth"]["max_tilt_deg"] == pytest.approx(47.0, abs=0.05)


def test_a_swing_in_one_plane_is_warned_across_the_plane_and_an_ellipse_is_not():
    # 20° swing in one vertical plane, no twist: the accelerometer bias along the swing axis
    # is the tilt out of the plane. The swing plane is body y–z (roll only), at heading
    # 123° the pole leans towards 213°/33°: the weak direction is across it, 123°/303°.
    # A consumer IMU (bias prior 0.04 m/s²: l·b/g = 7.6 mm at 1σ) leaves the tip beyond
    # the tolerance at 95 % (the warning's level).
    planar = SwingConfig(tilt_deg=20.0, shape_ratio=0.0, twist_deg=0.0, wobble_deg=0.1,
                         azimuth_deg=0.0, heading_deg=123.0, accel_bias_m_s2=(0.04, 0.0, 0.0))
    sim = simulate_swing(planar, seed=1)
    sol = _solve(sim, TiltParams(imu_grade="consumer"))
    j = sol.methods["joint"]
    assert j.ok and j.warning is not None and "ellipse" in j.warning
    assert j.warning in sol.warnings
    weak = sol.joint.weak_direction
    assert abs(abs(math.degrees(math.atan2(weak[1], weak[0])) % 180.0 - 123.0)) < 5.0
    assert sol.joint.bias_share > 0.9                 # the bias prior is the weak σ

    assert sol.joint.horizontal_radius_m(0.95) > 0.01          # σ says it, not only the text
    err = j.tip - sim["truth"]["tip_ned"]
    assert abs(err[:2] @ weak) < 1.96 * sol.joint.weak_sigma_m
    # the same pole swung in an ellipse with a twist: no warning, tip well within 1 cm
    sim = simulate_swing(SwingConfig(tilt_deg=35.0, shape_ratio=0.8, twist_deg=15.0,
                                     accel_bias_m_s2=(0.04, 0.0, 0.0)), seed=1)
    sol = _solve(sim)
    j = sol.methods["joint"]
    assert j.ok and j.warning is None and not sol.warnings
    assert 1.96 * sol.joint.weak_sigma_m < 0.01
    assert np.hypot(*(j.tip - sim["truth"]["tip_ned"])[:2]) < 0.01


def test_the_warning_separates_good_from_bad_consumer_swings():
    """Issue #30, item 3, on the hardest grade: 30 random consumer-grade swings (15-60°,
    every convention, 50-200 Hz; 28 tips within 1 cm, the largest error 18 mm): no tip
    without the warning is beyond 1 cm, and the warning fires on at most a fifth of the
    tips within 1 cm (the issue's bound).

    Power: this fixed draw is a regression check of the rule, not its statistics (those
    are the benchmark's: 20 % of the good consumer tips over 80 swings). Here the 95 %
    rule flags 7 % of the good tips; the former 99 % rule flags 25 % and fails; a σ too
    small (no warning on the two tips beyond 1 cm) fails the first assertion.
    """
    from hydrosync_core.methods.tilt_alignment.montecarlo import run_monte_carlo, statistics

    mc = run_monte_carlo(30, TiltParams(imu_grade="consumer"), seed=31, grade="consumer")
    s = statistics(mc, "joint")
    assert s["undetermined"] == 0 and s["h_within_1cm"] < 1.0   # a draw with bad tips
    assert s["h_within_1cm_quiet"] == 1.0, s
    assert s["warned_within_1cm"] <= 0.2, s


def test_monte_carlo_statistics_give_sigma_coverage_and_the_warned_share():
    from hydrosync_core.methods.tilt_alignment.montecarlo import statistics

    err = np.array([0.001, -0.002, 0.003, 0.02])
    mc = {"run": np.arange(4.0), "joint_heading_err_deg": np.zeros(4),
          "joint_tip_err_e": err, "joint_tip_err_n": np.zeros(4),
          "joint_tip_err_u": np.zeros(4), "joint_tip_std_e": np.full(4, 0.002),
          "joint_tip_std_n": np.full(4, 0.001), "joint_tip_std_u": np.full(4, 0.001),
          "joint_warned": np.array([0.0, 0.0, 0.0, 1.0])}
    s = statistics(mc, "joint")
    assert s["coverage_e"] == 0.75 and s["coverage_n"] == 1.0    # 0.02 > 1.96·0.002
    assert s["warned"] == 0.25 and s["h_within_1cm_quiet"] == 1.0


def test_a_gnss_time_offset_is_found_corrected_and_named():
    cfg = SwingConfig(tilt_deg=50.0, sweeps=3, shape_ratio=0.5, gnss_time_offset_s=0.03)
    sim = simulate_swing(cfg, seed=3)
    sol = _solve(sim)
    j = sol.joint
    assert j.time_offset_applied_s + j.time_offset_s == pytest.approx(0.03, abs=0.003)
    said = [re.search(r"time tags are ([+-][0-9.]+) ms", w) for w in sol.warnings]
    said = [float(x.group(1)) for x in said if x]
    assert len(said) == 1 and abs(said[0] - 30.0) < 3.0
    err = sol.methods["joint"].tip - sim["truth"]["tip_ned"]
    assert np.hypot(*err[:2]) < 0.005
    # tags right: nothing applied, nothing said
    sol = _solve(simulate_swing(replace(cfg, gnss_time_offset_s=0.0), seed=3))
    assert sol.joint.time_offset_applied_s == 0.0
    assert not any("time tags" in w for w in sol.warnings)


def test_accelerometer_windows_are_exact_for_the_discrete_record():
    from hydrosync_core.methods.tilt_alignment.joint import _model, _windows

    cfg = noise_free(SwingConfig(tilt_deg=50.0, shape_ratio=0.3, gravity_m_s2=9.79))
    sim = simulate_swing(cfg, seed=5)
    t, C = sim["time"], sim["truth"]["C"]
    # the specific force of the discrete record: second differences of the antenna
    p = -C[:, :, 2] * sim["pole_length_m"]
    acc = np.zeros_like(p)
    acc[1:-1] = (p[2:] - 2 * p[1:-1] + p[:-2]) / np.diff(t)[0] ** 2
    sim["accel"] = np.einsum("kji,kj->ki", C, acc - 9.79 * np.array([0.0, 0.0, 1.0]))
    Wq, D = _windows(t, 0.25)
    assert Wq.shape[0] > 15 and np.allclose(D.sum(axis=1), 0.0, atol=1e-9)
    # overlapping Hann windows sum to one inside the record
    inner = (t > t[0] + 0.5) & (t < t[-1] - 0.5)
    assert np.allclose((Wq / np.maximum(Wq.sum(axis=0), 1e-300)).sum(axis=0)[inner], 1.0)
    args = (C, t, sim["accel"], sim["gnss_time"], sim["pole_length_m"], np.zeros(3),
            np.zeros(3))
    _, _, ea, _ = _model(*args, 9.79, (Wq, D))
    assert np.max(np.abs(ea)) < 1e-9
    _, _, ea, _ = _model(*args, 9.80, (Wq, D))          # 0.01 m/s² of gravity is seen
    assert np.max(np.abs(ea)) > 1e-3


def test_gyro_noise_covariance_matches_a_monte_carlo_of_the_noise():
    """The random-walk covariance σ²·H·Hᵀ against perturbed gyro records."""
    from hydrosync_core.methods.tilt_alignment.joint import (
        _gyro_noise_design,
        _model,
        _windows,
    )

    cfg = noise_free(SwingConfig(tilt_deg=40.0, shape_ratio=0.4, level_s=0.4, hold_s=0.4,
                                 swing_s=1.5))
    sim = simulate_swing(cfg, seed=6)
    t, gyro, acc = sim["time"], sim["gyro"], sim["accel"]
    C0, length, gt = sim["truth"]["C"][0], sim["pole_length_m"], sim["gnss_time"]
    win = _windows(t, 0.25)
    sw = 0.003

    def observe(g):
        C = propagate(C0, t, g)
        u_at, _, ea, _ = _model(C, t, acc, gt, length, np.zeros(3), np.zeros(3), 9.80665,
                                win)
        return np.concatenate([u_at.ravel(), ea.ravel()])

    C = propagate(C0, t, gyro)
    y = np.einsum("kij,kj->ki", C, acc)
    H = _gyro_noise_design(C, t, gt, C[:, :, 2] * length, y, win, chunk=1)
    Q = sw ** 2 * H @ H.T
    base = observe(gyro)
    rng = np.random.default_rng(0)
    d = np.array([observe(gyro + rng.normal(0, sw, gyro.shape)) - base for _ in range(300)])
    emp = np.std(d, axis=0)
    pred = np.sqrt(np.diag(Q))
    big = pred > 0.2 * pred.max()
    assert big.sum() > 20
    ratio = emp[big] / pred[big]
    assert 0.8 < np.median(ratio) < 1.2 and np.all((ratio > 0.6) & (ratio < 1.5))
    # and the correlation between the last GNSS epoch and the last window
    i, j = 3 * gt.size - 2, Q.shape[0] - 2
    rho_pred = Q[i, j] / math.sqrt(Q[i, i] * Q[j, j])
    rho_emp = np.corrcoef(d[:, i], d[:, j])[0, 1]
    assert abs(rho_pred - rho_emp) < 0.2


def test_horizontal_radius_and_white_noise_level():
    from hydrosync_core.methods.tilt_alignment.joint import horizontal_radius, white_sigma

    assert horizontal_radius(np.eye(2) * 1e-6, 0.99) == pytest.approx(
        1e-3 * math.sqrt(-2 * math.log(0.01)), rel=1e-3)
    assert horizontal_radius(np.diag([4e-6, 0.0]), 0.99) == pytest.approx(2e-3 * 2.5758,
                                                                         rel=1e-3)
    cov = np.array([[2.0, 0.8], [0.8, 1.0]]) * 1e-6
    z = np.random.default_rng(1).multivariate_normal([0, 0], cov, 200000)
    assert horizontal_radius(cov, 0.95) == pytest.approx(
        np.quantile(np.hypot(*z.T), 0.95), rel=0.01)
    sim = simulate_swing(SwingConfig(gyro_noise_deg_s_rthz=0.015,
                                     accel_noise_m_s2_rthz=0.002), seed=2)
    assert white_sigma(sim["gyro"]) == pytest.approx(math.radians(0.015) * 10, rel=0.1)
    assert white_sigma(sim["accel"]) == pytest.approx(0.002 * 10, rel=0.1)


def test_joint_sigma_is_honest_over_repeated_noise_of_one_planar_swing():
    """Empirical spread of the tip over 16 noise draws of one short consumer-grade planar
    swing (50 Hz IMU) against the σ the joint method reports, across and along the plane.

    Power: with an honest σ, 16·rms² of the standardised errors is χ²₁₆, so rms lies in
    0.50–1.57 with probability 0.999 per axis (the bounds below). A σ too small by half
    (rms ≈ 2, as with mems priors on these consumer biases) fails with probability 0.87
    per axis, both axes together above 0.95; a σ twice too large (rms ≈ 0.5) half the time.
    """
    rng = np.random.default_rng(3)
    errs, sds = [], []
    params = TiltParams(imu_grade="consumer")
    for _ in range(16):
        # heading 0, azimuth 0: the pole swings in the east-down plane, north is across
        cfg = SwingConfig(tilt_deg=30.0, shape_ratio=0.0, twist_deg=3.0, wobble_deg=0.2,
                          azimuth_deg=0.0, heading_deg=0.0, gyro_noise_deg_s_rthz=0.015,
                          accel_noise_m_s2_rthz=0.002, imu_rate_hz=50.0, level_s=1.0,
                          move_s=0.5, swing_s=2.0, hold_s=0.5,
                          gyro_bias_deg_s=tuple(rng.normal(0, 0.1, 3)),
                          accel_bias_m_s2=tuple(rng.normal(0, 0.04, 3)))
        sim = simulate_swing(cfg, seed=int(rng.integers(1 << 30)))
        sol = _solve(sim, params)
        errs.append(sol.methods["joint"].tip[:2] - sim["truth"]["tip_ned"][:2])
        sds.append(np.sqrt(np.diag(sol.joint.cov[3:5, 3:5])))
    sds = np.array(sds)
    assert np.mean(sds[:, 0]) > 2 * np.mean(sds[:, 1])     # across the plane is the weak one
    z = np.array(errs) / sds
    rms = np.sqrt(np.mean(z ** 2, axis=0))
    assert np.all((rms > 0.5) & (rms < 1.57)), rms


def test_a_gnss_outlier_is_down_weighted_and_named():
    cfg = SwingConfig(tilt_deg=45.0, shape_ratio=0.5, gnss_outliers=2)
    sim = simulate_swing(cfg, seed=4)
    sol = _solve(sim)
    j = sol.methods["joint"]
    assert sol.joint.gnss_downweighted >= 1
    assert any("down-weighted" in w for w in sol.warnings)
    assert np.hypot(*(j.tip - sim["truth"]["tip_ned"])[:2]) < 0.01
    clean = _solve(simulate_swing(replace(cfg, gnss_outliers=0), seed=4))
    assert clean.joint.gnss_downweighted == 0
    assert not any("down-weighted" in w for w in clean.warnings)


@pytest.mark.parametrize("true", ["interval-end", "instant"])
def test_declared_convention_gives_no_offset_and_a_wrong_one_is_named(true):
    """Declared right, the GNSS offset is consistent with 0 (within 3σ, σ ≈ 0.5 ms on this
    three-sweep swing); declared as the other, the half-sample offset (±5 ms at 100 Hz) is
    named with the likely convention."""
    cfg = SwingConfig(tilt_deg=50.0, sweeps=3, shape_ratio=0.5, imu_convention=true,
                      gyro_bias_deg_s=(0.03, -0.04, 0.02), accel_bias_m_s2=(0.01, -0.02, 0.015))
    sim = simulate_swing(cfg, seed=3)
    sol = _solve(sim)
    j = sol.joint
    tau = j.time_offset_s + j.time_offset_applied_s
    assert abs(tau) < max(3 * j.time_offset_std_s, 0.0015)
    assert not any("half the" in w for w in sol.warnings)
    other = "instant" if true != "instant" else "interval-end"
    sol = solve_record(sim["time"], sim["gyro"], sim["accel"], sim["gnss_time"],
                       sim["gnss_ned"], sim["pole_length_m"], TiltParams(imu_convention=other))
    tau = sol.joint.time_offset_s + sol.joint.time_offset_applied_s
    assert 0.003 < abs(tau) < 0.007
    hint = [w for w in sol.warnings if "half the 10 ms" in w]
    likely = "'interval-end'" if true == "interval-end" else "'interval-middle or instant'"
    assert len(hint) == 1 and likely in hint[0], sol.warnings


FOREIGN = Path(__file__).resolve().parents[2] / ".." / "shared" / "data" / "foreign" / "tilt"


@pytest.mark.skipif(not FOREIGN.is_dir(), reason=f"foreign swings not at {FOREIGN}")
def test_foreign_swings_with_the_defaults():
    """Swings simulated outside the team (MEMS, instantaneous samples, no time offset):
    with the command's defaults every tip within 1 cm and no warning, the GNSS offset
    consistent with 0 (mean within ±1.5 ms, each within 3σ) and the IMU noise the joint
    method reports within 40 % of the data's (0.02°/s, 0.01 m/s² per sample; the record's
    own measure is within 5 %, the variance components may only raise it, and they rest on
    about 60 accelerometer windows: ±18 % in variance at 1σ)."""
    from hydrosync_core.methods.tilt_alignment.io import read_gnss_csv, read_imu_csv
    from hydrosync_core.methods.tilt_alignment.solve_files import result_document, solve_columns

    offsets = []
    swings = sorted(FOREIGN.glob("swing_*"))
    assert swings
    for d in swings:
        length = json.loads((d / "pole.json").read_text())["pole_length_m"]
        truth = json.loads((d / "truth.json").read_text())
        p = TiltParams()
        sol, frame = solve_columns(read_imu_csv(d / "imu.csv"), read_gnss_csv(d / "gnss.csv"),
                                   length, p)
        doc = result_document(sol, frame, length, p)
        err = np.array(doc["tip_enu"]) - truth["tip_enu"]
        assert math.hypot(*err[:2]) < 0.01 and not doc["warnings"], (d.name, err)
        j = doc["joint"]
        assert abs(j["time_offset_ms"]) < 3 * j["time_offset_std_ms"], d.name
        offsets.append(j["time_offset_ms"])
        assert j["gyro_noise_deg_s_per_sample"] == pytest.approx(0.02, rel=0.4)
        assert j["accel_noise_m_s2_per_sample"] == pytest.approx(0.01, rel=0.4)
    assert abs(np.mean(offsets)) < 1.5


def test_an_imu_noisier_than_its_grade_is_named():
    """Consumer noise (0.015°/s/√Hz) declared industrial (0.004): 3.75× the gyro noise,
    beyond the 3× limit; declared consumer, nothing is said."""
    sim = simulate_swing(SwingConfig(gyro_noise_deg_s_rthz=0.015, accel_noise_m_s2_rthz=0.002,
                                     tilt_deg=45.0, shape_ratio=0.5), seed=2)
    said = _solve(sim, TiltParams(imu_grade="industrial")).warnings
    assert any("noisier than its grade" in w and "gyro" in w for w in said), said
    said = _solve(sim, TiltParams(imu_grade="consumer")).warnings
    assert not any("noisier" in w for w in said)


@pytest.mark.parametrize("rate", [100.0, 50.0])
@pytest.mark.parametrize("convention", ["instant", "interval-end"])
def test_model_error_of_a_fast_swing_is_not_read_as_noise(rate, convention):
    """Three sweeps of a 50° ellipse in 2.5 s (peak 2 g at the antenna): the IMU noise the
    joint method reports is within 20 % of the simulated at 100 and 50 Hz, both conventions.

    Measured: 0.98-1.05× (gyro and accelerometer). Before (issue #30) at 50 Hz: 1.9× gyro
    and 2.0× accelerometer (instantaneous: no coning term in the gyro increments, third
    differences reading the swing as noise, the simulator's jump in jerk), 3.4×
    accelerometer (interval means rotated by the mean of the end attitudes). The record's
    own noise measure rests on ~800 fifth differences (MAD): ±4 % at 1σ, so 20 % is 5σ.
    """
    cfg = SwingConfig(tilt_deg=50, sweeps=3, shape_ratio=0.5, imu_rate_hz=rate,
                      wobble_deg=0.0, gyro_bias_deg_s=(0.03, -0.04, 0.02),
                      accel_bias_m_s2=(0.01, -0.02, 0.015), imu_convention=convention)
    sim = simulate_swing(cfg, seed=4)
    sol = solve_record(sim["time"], sim["gyro"], sim["accel"], sim["gnss_time"],
                       sim["gnss_ned"], sim["pole_length_m"], TiltParams(),
                       gravity=cfg.gravity_m_s2, imu_convention=convention)
    root = math.sqrt(rate)
    assert sol.joint.accel_noise_m_s2 == pytest.approx(0.0012 * root, rel=0.2)
    assert sol.joint.gyro_noise_rad_s == pytest.approx(math.radians(0.008) * root, rel=0.2)
