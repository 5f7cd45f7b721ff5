"""Pool calibration (issue #4): simulated passes with known boresight and lever-arm errors."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hydrosync_core.errors import InputError
from hydrosync_core.methods.pool_calibration import georef
from hydrosync_core.methods.pool_calibration.api import calibrate, segment
from hydrosync_core.methods.pool_calibration.planes import fit_plane
from hydrosync_core.methods.pool_calibration.simulate import PoolPassConfig, simulate_pool_pass
from hydrosync_core.methods.pool_calibration.solve import solve

# Small, fast data sets: 3 passes, 128 beams, 8 Hz pings.
FAST = dict(beams=128, ping_rate_hz=8.0, laser_density_per_m2=800.0)


def _errors(sim, result_part):
    t = sim["truth"]
    da = {k: result_part.boresight_deg[k] - t["boresight_deg"][k] for k in ("roll", "pitch", "yaw")}
    dl = {k: result_part.lever_arm_m[k] - t["lever_arm_m"][k] for k in "xyz"}
    return da, dl


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_recovers_injected_errors_of_both_signs(sign):
    cfg = PoolPassConfig(boresight_error_deg=(0.8 * sign, -0.6 * sign, 0.7 * sign),
                         lever_error_m=(0.05 * sign, -0.04 * sign, 0.06 * sign), **FAST)
    sim = simulate_pool_pass(cfg, seed=2)
    res = calibrate(sim["lidar"], sim["mbes"], sim["ins"], sim["setup"], sim["target"])
    da, dl = _errors(sim, res.joint)
    # Joint adjustment: realistic noise (1 cm range, 0.03° angle, 1 % outliers).
    assert max(abs(v) for v in da.values()) < 0.03, da
    assert abs(dl["x"]) < 0.003 and abs(dl["y"]) < 0.002 and abs(dl["z"]) < 0.008, dl
    # Seed (patent) method: the corrections go the right way and land close.
    sa, sl = _errors(sim, res.seed)
    assert max(abs(v) for v in sa.values()) < 0.15, sa
    assert max(abs(v) for v in sl.values()) < 0.015, sl
    assert res.boresight_deg == res.joint.boresight_deg  # final = joint
    json.dumps(res.to_dict(), allow_nan=False)


@pytest.mark.parametrize("k", range(3))
def test_each_angle_alone_low_noise(k):
    err = [0.0, 0.0, 0.0]
    err[k] = 0.5 if k != 1 else -0.5
    cfg = PoolPassConfig(boresight_error_deg=tuple(err), lever_error_m=(0.0, 0.0, 0.0),
                         range_noise_m=0.001, angle_noise_deg=0.001,
                         mbes_outlier_fraction=0.0, laser_noise_m=0.0005, **FAST)
    sim = simulate_pool_pass(cfg, seed=5)
    res = calibrate(sim["lidar"], sim["mbes"], sim["ins"], sim["setup"], sim["target"])
    sa, _ = _errors(sim, res.seed)
    ja, jl = _errors(sim, res.joint)
    assert max(abs(v) for v in sa.values()) < 0.01, sa
    assert max(abs(v) for v in ja.values()) < 0.01, ja
    assert max(abs(v) for v in jl.values()) < 0.002, jl


def test_ins_gap_pings_are_dropped_not_interpolated():
    cfg = PoolPassConfig(ins_dropout_s=2.0, **FAST)
    sim = simulate_pool_pass(cfg, seed=1)
    ctx = georef.prepare(sim["mbes"], sim["ins"])
    t_ins = sim["ins"]["time"]
    # The INS gap runs from the last epoch before the dropout to the first one after it.
    t0 = t_ins[t_ins < sim["dropout"][0]].max()
    t1 = t_ins[t_ins > sim["dropout"][1]].min()
    pings = np.unique(sim["mbes"]["time"])
    in_gap = int(((pings > t0) & (pings < t1)).sum())
    assert in_gap > 0 and ctx.dropped_pings == in_gap
    assert not np.any((sim["mbes"]["time"][ctx.keep] > t0) & (sim["mbes"]["time"][ctx.keep] < t1))


def test_plane_fit_tls():
    rng = np.random.default_rng(0)
    n = np.array([0.3, -0.2, 0.93])
    n /= np.linalg.norm(n)
    u = np.cross(n, [1, 0, 0])
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    pts = rng.normal(size=(500, 1)) * u + rng.normal(size=(500, 1)) * v + 2.0 * n
    pts += rng.normal(0, 0.001, (500, 1)) * n
    fit = fit_plane(pts, n)
    assert np.degrees(np.arccos(fit.normal @ n)) < 0.05
    assert fit.d == pytest.approx(2.0, abs=1e-3)
    assert fit.rms == pytest.approx(0.001, rel=0.15)


def test_no_oblique_face_names_undetermined_parameters():
    sim = simulate_pool_pass(PoolPassConfig(**FAST), seed=4)
    target = dict(sim["target"])
    target["faces"] = [f for f in target["faces"] if "oblique" not in f["name"]]
    res = calibrate(sim["lidar"], sim["mbes"], sim["ins"], sim["setup"], target)
    text = " ".join(res.warnings)
    assert "pitch cannot be determined" in text and "yaw cannot be determined" in text
    assert "along the wall" in text
    # Undetermined seed angles stay at the coarse values, never a silent number.
    assert res.seed.boresight_deg["yaw"] == pytest.approx(sim["setup"]["boresight_deg"]["yaw"])


def test_face_without_points_and_bad_input():
    sim = simulate_pool_pass(PoolPassConfig(**FAST), seed=6)
    # A design far away from every point: no face seen by both sensors -> InputError.
    far = json.loads(json.dumps(sim["target"]))
    for f in far["faces"]:
        for c in f["corners"]:
            c[0] += 100.0
    with pytest.raises(InputError, match="no design face has enough points"):
        segment(sim["lidar"], sim["mbes"], sim["ins"], sim["setup"], far)
    with pytest.raises(InputError):
        segment(sim["lidar"][:, :2], sim["mbes"], sim["ins"], sim["setup"], sim["target"])
    bad = dict(sim["ins"])
    bad["roll"] = bad["roll"].copy()
    bad["roll"][3] = np.nan
    with pytest.raises(InputError, match="non-finite"):
        segment(sim["lidar"], sim["mbes"], bad, sim["setup"], sim["target"])


def test_segment_then_iterate_matches_calibrate():
    sim = simulate_pool_pass(PoolPassConfig(**FAST), seed=7)
    seg = segment(sim["lidar"], sim["mbes"], sim["ins"], sim["setup"], sim["target"])
    assert seg.roles["wall"].role == "wall"
    assert seg.roles["N1_oblique"].role == "oblique"
    assert seg.roles["N1_top"].role == "horizontal" and seg.roles["S1_top"].water == "below"
    assert len(seg.mbes_faces["wall"]) > 500 and len(seg.laser_points["wall"]) > 1000
    res = solve(seg)
    faces = {r.face: r for r in res.faces}
    assert "roll" in faces["wall"].used_for and faces["N1_bottom"].points_mbes == 0
    assert res.iteration_table[0]["iteration"] == 1
