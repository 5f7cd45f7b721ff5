"""Latency core: seed numbers, hand-worked heave and σ0, detrending."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.combine import combine, select_lines, weighted_mean
from hydrosync_core.methods.latency.detrend import detrend
from hydrosync_core.methods.latency.heave import induced_heave, total_heave
from hydrosync_core.methods.latency.quality import sigma0
from hydrosync_core.methods.latency.result import LatencyParams

# Seed 000, table 1: line, R, Δt (s); weighted mean 0.29 s.
SEED_R = np.array([0.8531, 0.8801, 0.8998, 0.8608, 0.9057, 0.9027, 0.8567, 0.9107, 0.8939,
                   0.8691, 0.9307, 0.9328, 0.9464])
SEED_DT = np.array([0.34, 0.26, 0.34, 0.28, 0.30, 0.23, 0.29, 0.32, 0.30, 0.31, 0.28, 0.28,
                    0.29])


def test_seed_table1_weighted_mean_is_029():
    used = select_lines(SEED_R, 0.85)
    assert used.all()  # every line of table 1 has R > 0.85
    comb = combine(SEED_DT, SEED_R, np.full(13, np.nan), used, "r")
    assert round(comb.latency_s, 2) == 0.29
    # Hand value: Σ R·Δt / Σ R = 3.418861 / 11.6425 = 0.293654 s.
    assert comb.latency_s == pytest.approx(3.418861 / 11.6425, abs=1e-9)
    assert comb.latency_s == pytest.approx(float(np.sum(SEED_R * SEED_DT) / SEED_R.sum()))
    assert comb.n_used == 13
    # External scatter (line values 0.23..0.34 s) gives an interval of about ±0.02 s.
    assert comb.ci95_low < 0.29 < comb.ci95_high
    assert 0.01 < comb.ci95_high - comb.ci95_low < 0.06


def test_selection_threshold_is_strict_and_drops_lines():
    used = select_lines(SEED_R, 0.88)
    assert used.sum() == 9  # 0.8531, 0.8608, 0.8567, 0.8691 are out
    assert not select_lines(np.array([0.85]), 0.85)[0]
    comb = combine(SEED_DT, SEED_R, np.full(13, 0.02), used, "inverse_variance")
    assert comb.latency_s == pytest.approx(SEED_DT[used].mean())
    assert weighted_mean([1.0, 3.0], [1.0, 3.0]) == pytest.approx(2.5)


def test_inverse_variance_weights_follow_uncertainties():
    comb = combine(np.array([0.2, 0.4]), np.array([0.9, 0.9]), np.array([0.01, 0.03]),
                   np.array([True, True]), "inverse_variance")
    # Weights 1/0.01² : 1/0.03² = 9 : 1.
    assert comb.latency_s == pytest.approx((9 * 0.2 + 0.4) / 10)


def test_induced_heave_hand_case_roll_10deg():
    # Lever arm (0, 2, -3) m: antenna 2 m to starboard, 3 m above the motion sensor.
    # Roll 10° starboard down: (R·L)_z = 0.173648·2 + 0.984808·(−3) = −2.607127;
    # H_R = −((R·L)_z − L_z) = −(−2.607127 + 3) = −0.392873 m (the antenna goes down).
    hr = induced_heave(np.radians(10.0), 0.0, [0.0, 2.0, -3.0])
    assert hr == pytest.approx(-0.392873, abs=1e-6)
    # Pitch 5° bow up with the antenna 4 m forward: it rises by 4·sin5° (plus a cos term).
    hp = induced_heave(0.0, np.radians(5.0), [4.0, 0.0, 0.0])
    assert hp == pytest.approx(4 * np.sin(np.radians(5.0)), abs=1e-12)


def test_induced_heave_matches_scipy_rotation_and_ignores_heading():
    rng = np.random.default_rng(4)
    roll, pitch, heading = (np.radians(rng.uniform(-20, 20, 50)) for _ in range(3))
    arm = np.array([1.2, -0.7, -4.5])
    rot = Rotation.from_euler("ZYX", np.column_stack([heading * 5, pitch, roll]))
    down = rot.apply(arm)[:, 2]
    np.testing.assert_allclose(induced_heave(roll, pitch, arm), -(down - arm[2]), atol=1e-12)
    np.testing.assert_allclose(total_heave(np.ones(50), roll, pitch, arm),
                               1.0 - (down - arm[2]), atol=1e-12)


def test_sigma0_hand_case():
    h = np.array([0.10, -0.05, 0.02, -0.07])
    H = np.array([0.08, -0.02, 0.01, -0.03])
    # Means: h̄ = 0, H̄ = 0.01; v = (0.02, −0.04, 0.0, −0.05) − ... computed by hand:
    v = (h - 0.0) - (H - 0.01)  # (0.03, −0.02, 0.02, −0.03)
    assert v == pytest.approx([0.03, -0.02, 0.02, -0.03])
    assert sigma0(h, H) == pytest.approx(np.sqrt(0.0026 / 2))


def test_detrend_removes_linear_tide_exactly():
    t = 1000.0 + np.arange(0, 120.0, 1.0)
    wave = 0.2 * np.sin(2 * np.pi * t / 6.0)
    h = 42.0 - 0.03 / 120 * (t - t[0]) + wave
    _, coef = detrend(t, h - wave, 1)
    assert coef[1] == pytest.approx(-0.03 / 120, rel=1e-9)  # the seed's −0.03 m over 2 min
    resid, _ = detrend(t, h, 1)
    expected = h - np.polyval(np.polyfit(t - t.mean(), h, 1), t - t.mean())
    np.testing.assert_allclose(resid, expected, atol=1e-9)
    assert np.abs(resid - wave).max() < 0.03
    resid2, _ = detrend(t, h + 1e-4 * (t - t.mean()) ** 2, 2)
    assert np.abs(resid2 - resid).max() < 0.01


@pytest.mark.parametrize("values, field", [
    ({"range_s": (1.0, -1.0)}, "range_s"), ({"step_s": 0.0}, "step_s"),
    ({"min_r": 1.5}, "min_r"), ({"weighting": "mean"}, "weighting"),
    ({"skip_s": -3}, "skip_s"),
])
def test_bad_params_raise_input_error(values, field):
    with pytest.raises(InputError) as info:
        LatencyParams.from_dict(values)
    assert info.value.field == field


def test_report_figures_draw_at_most_figure_points_per_curve():
    """The PDF's R curves are drawn from evenly spread candidates, first and last kept;
    a short curve is drawn whole."""
    from hydrosync_core.methods.latency.report_section import FIGURE_POINTS, _drawn

    for count in (1, 2, 399, 400, 401, 2001, 20001):
        index = _drawn(count)
        assert index[0] == 0 and index[-1] == count - 1
        assert index.size <= FIGURE_POINTS + 1
        assert np.all(np.diff(index) > 0)
        if count <= FIGURE_POINTS:
            np.testing.assert_array_equal(index, np.arange(count))
        else:
            assert np.ptp(np.diff(index)[:-1]) == 0  # evenly spread but for the last step
    assert _drawn(0).size == 0
