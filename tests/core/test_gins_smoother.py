"""GNSS/INS smoother (#12): mechanisation physics, recovery of a simulated truth, RTS
covariance reduction, readers on the shared KF-GINS files, command exit codes."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from hydrosync_core.methods.gins_smoother import kernel as K  # noqa: N812
from hydrosync_core.methods.gins_smoother.evaluate import evaluate
from hydrosync_core.methods.gins_smoother.filter import euler_to_quat, run_gins
from hydrosync_core.methods.gins_smoother.io import read_gnss, read_imu, read_nav
from hydrosync_core.methods.gins_smoother.params import GinsParams
from hydrosync_core.methods.gins_smoother.simulate import simulate

KFGINS = Path(__file__).resolve().parents[3] / "shared" / "data" / "kfgins"


def _stationary(bias_ms2: float, seconds: float = 60.0, rate: float = 100.0):
    """INS-only mechanisation at rest with exact increments plus a north accel bias."""
    lat, h = math.radians(30.0), 20.0
    x = np.zeros(K.NX)
    x[0:3] = (lat, math.radians(114.0), h)
    x[6:10] = euler_to_quat(0.0, 0.0, 0.0)  # body = NED: x north
    dt = 1.0 / rate
    g = K.gravity(lat, h)
    w = np.array([K.WIE * math.cos(lat), 0.0, -K.WIE * math.sin(lat)])
    f = np.array([bias_ms2, 0.0, -g])
    dth, dv = w * dt, f * dt
    for _ in range(int(seconds * rate)):
        K.mechanise(x, dth, dv, dth, dv, dt)
    rm, _ = K.radii(lat)
    north = (x[0] - lat) * (rm + h)
    return north, x


def test_stationary_imu_stays_put():
    north, x = _stationary(0.0)
    assert abs(north) < 1e-3 and abs(x[2] - 20.0) < 1e-3
    assert np.max(np.abs(x[3:6])) < 1e-4


def test_stationary_drift_matches_injected_bias():
    """1 mGal·100 north accelerometer bias over 60 s: ½·b·t² = 18 mm (Schuler negligible)."""
    b = 1e-3
    north, _ = _stationary(b)
    assert north == pytest.approx(0.5 * b * 60.0 ** 2, rel=0.05)


@pytest.fixture(scope="module")
def drive():
    sim = simulate(60.0, "vehicle", "tactical", imu_rate_hz=100.0, seed=3)
    res = run_gins(sim["imu"], sim["gnss"], sim["config"], GinsParams(nhc=True))
    return sim, res


def test_simulated_truth_recovered(drive):
    sim, res = drive
    ev = evaluate(res, sim["truth"])
    for name, pos_cm, yaw_deg in (("forward", 3.0, 0.3), ("smoothed", 2.0, 0.2)):
        a = ev[name]["all"]
        assert a["horizontal"]["rms"] < pos_cm / 100, name
        assert a["down"]["rms"] < pos_cm / 100, name
        assert a["yaw"]["rms"] < yaw_deg, name
        assert max(a[k]["rms"] for k in ("vn", "ve", "vd")) < 0.02, name
    assert ev["smoothed"]["all"]["horizontal"]["rms"] < ev["forward"]["all"]["horizontal"]["rms"]


def test_noise_free_simulation_is_exact():
    sim = simulate(30.0, "vessel", "mems", imu_rate_hz=100.0, seed=1, noise_free=True)
    res = run_gins(sim["imu"], sim["gnss"], sim["config"], GinsParams(zupt=False))
    a = evaluate(res, sim["truth"])["smoothed"]["all"]
    # rolling vessel: the fine-grid finite differences of the simulator leave ~0.01° in yaw
    assert a["horizontal"]["max"] < 2e-3 and a["yaw"]["max"] < 0.02


def test_rts_reduces_covariance_everywhere(drive):
    _, res = drive
    f, s = res.forward, res.smoothed
    for a, b in ((f.pos_std, s.pos_std), (f.vel_std, s.vel_std), (f.att_std, s.att_std)):
        assert np.all(b <= a * (1 + 1e-6) + 1e-12)
    assert np.mean(s.pos_std) < 0.9 * np.mean(f.pos_std)


def test_outage_smoother_beats_forward():
    sim = simulate(90.0, "vehicle", "tactical", imu_rate_hz=100.0, seed=5)
    t0 = sim["imu"].time[0]
    w = [(t0 + 45.0, t0 + 65.0)]
    res = run_gins(sim["imu"], sim["gnss"].without(w), sim["config"], GinsParams())
    o = evaluate(res, sim["truth"], w)
    assert o["smoothed"]["outage"]["max_horizontal_m"] < \
        0.5 * o["forward"]["outage"]["max_horizontal_m"]


needs_kfgins = pytest.mark.skipif(not (KFGINS / "GNSS-RTK.txt").exists(),
                                  reason=f"shared KF-GINS data not found at {KFGINS}")


@needs_kfgins
def test_readers_on_shared_files():
    from hydrosync_core.methods.gins_smoother.config import read_config

    g = read_gnss(KFGINS / "GNSS-RTK.txt")
    assert g.time.size == 3413 and g.time[0] == 456250.0
    assert g.std[0] == pytest.approx([0.010, 0.009, 0.019])
    cfg = read_config(KFGINS / "kf-gins.yaml")
    assert cfg.lever_arm_m == (0.136, -0.301, -0.184) and cfg.start_time == 456300
    assert math.degrees(cfg.init_att[2]) == pytest.approx(185.70235133)
    assert cfg.noise.arw[0] == pytest.approx(math.radians(0.003) / 60)
    assert cfg.noise.corr_time == 4 * 3600
    syn = KFGINS / "synthetic"
    if (syn / "truth-synthetic-50Hz.nav").exists():
        nav = read_nav(syn / "truth-synthetic-50Hz.nav")
        assert nav.time.size == 168100 and nav.att[0, 2] == pytest.approx(177.70002709)


def test_imu_csv_rates_and_increments(tmp_path):
    p = tmp_path / "imu.csv"
    p.write_text("time,gyro_x,gyro_y,gyro_z,acc_x,acc_y,acc_z\n0.00,1,0,0,0,0,-9.8\n"
                 "0.01,1,0,0,0,0,-9.8\n")
    d = read_imu(p)
    assert d.inc[1, 0] == pytest.approx(math.radians(1) * 0.01)
    assert d.inc[1, 5] == pytest.approx(-0.098)
    bad = tmp_path / "imu.txt"
    bad.write_text("1 0 0 0 0 0 0\n2 0 0 x 0 0 0\n")
    with pytest.raises(Exception, match=r"imu.txt:2: field 'dtheta_z'"):
        read_imu(bad)


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "hydrosync_core.cli", "gins", *map(str, args)],
                          capture_output=True, text=True, timeout=120)


def test_cli_bad_input_exit_2(tmp_path):
    imu = tmp_path / "imu.txt"
    imu.write_text("1 0 0 0 0 0 0\n1.005 0 0 0 0 0\n")
    gnss = tmp_path / "gnss.txt"
    gnss.write_text("1 30 114 20 0.01 0.01 0.02\n")
    cfg = tmp_path / "c.yaml"
    cfg.write_text("imunoise: {arw: [1,1,1]}\nantlever: [0,0,0]\n")
    r = _cli("--imu", imu, "--gnss", gnss, "--config", cfg, "--out", tmp_path / "o.nav")
    assert r.returncode == 2 and r.stderr.count("\n") == 1
    assert "c.yaml" in r.stderr and "vrw" in r.stderr
    cfg.write_text("imunoise: {arw: [1,1,1], vrw: [1,1,1], gbstd: [1,1,1], abstd: [1,1,1], "
                   "corrtime: 1}\nantlever: [0,0,0]\n")
    r = _cli("--imu", imu, "--gnss", gnss, "--config", cfg, "--out", tmp_path / "o.nav")
    assert r.returncode == 2 and "imu.txt:2" in r.stderr
    r = _cli("--imu", imu, "--gnss", gnss, "--config", cfg, "--out", tmp_path / "o.nav",
             "--nhc-std", "-1")
    assert r.returncode == 2 and "nhc" in r.stderr


def test_cli_file_form_end_to_end(tmp_path):
    from hydrosync_core.methods.gins_smoother.io import std_path, write_nav

    sim = simulate(40.0, "vehicle", "tactical", imu_rate_hz=100.0, seed=2)
    imu, gnss, truth = sim["imu"], sim["gnss"], sim["truth"]
    np.savetxt(tmp_path / "imu.txt", np.column_stack([imu.time, imu.inc]), fmt="%.10f")
    np.savetxt(tmp_path / "gnss.txt", np.column_stack([gnss.time, gnss.llh, gnss.std]),
               fmt="%.10f")
    write_nav(tmp_path / "truth.nav", truth.time, truth.llh, truth.vel, truth.att)
    import yaml

    (tmp_path / "c.yaml").write_text(yaml.safe_dump(sim["config"].to_dict()))
    out = tmp_path / "traj.nav"
    r = _cli("--imu", tmp_path / "imu.txt", "--gnss", tmp_path / "gnss.txt", "--config",
             tmp_path / "c.yaml", "--out", out, "--truth", tmp_path / "truth.nav", "--json",
             tmp_path / "r.json")
    assert r.returncode == 0, r.stderr
    nav = read_nav(out)
    assert nav.time.size == imu.time.size and std_path(out).exists()
    import json

    doc = json.loads((tmp_path / "r.json").read_text())
    assert doc["evaluation"]["smoothed"]["all"]["horizontal"]["rms"] < 0.03


def test_mounting_angles_are_the_imu_attitude_in_the_vehicle_frame(drive):
    """An IMU mounted with roll -3°, pitch 2°, yaw 30° in the vehicle (its outputs are the
    vehicle's rotated into it): with those angles the non-holonomic constraint holds and
    the drive is recovered as well as with an aligned IMU; the inverse rotation (what the
    filter applied before, against its own help text) breaks the constraint."""
    from scipy.spatial.transform import Rotation

    sim, aligned = drive
    mount = np.array([-3.0, 2.0, 30.0])
    c_vb = Rotation.from_euler("ZYX", np.radians(mount[::-1])).as_matrix()
    inc = sim["imu"].inc
    imu = type(sim["imu"])(sim["imu"].time, np.column_stack([inc[:, :3] @ c_vb,
                                                             inc[:, 3:] @ c_vb]), "mounted")
    cfg = sim["config"]
    c_nv = Rotation.from_euler("ZYX", np.array(cfg.init_att)[::-1]).as_matrix()
    att = Rotation.from_matrix(c_nv @ c_vb).as_euler("ZYX")[::-1]
    cfg = cfg.with_(init_att=tuple(float(a) for a in att),
                    lever_arm_m=tuple(float(v) for v in c_vb.T @ np.array(cfg.lever_arm_m)))
    inverse = Rotation.from_matrix(c_vb.T).as_euler("ZYX", degrees=True)[::-1]
    h_rms = {}
    for label, angles in (("mount", mount), ("inverse", inverse)):
        res = run_gins(imu, sim["gnss"], cfg,
                       GinsParams(nhc=True, mounting_deg=tuple(float(a) for a in angles)))
        h_rms[label] = evaluate(res, sim["truth"])["smoothed"]["all"]["horizontal"]["rms"]
    ref = evaluate(aligned, sim["truth"])["smoothed"]["all"]["horizontal"]["rms"]
    assert h_rms["mount"] < 1.2 * ref + 1e-3, (h_rms, ref)
    assert h_rms["inverse"] > 5 * h_rms["mount"], h_rms


def test_options_given_equal_to_the_default_still_override_a_recording():
    """A recording brings its recommended options (the rtkexplorer drive: NHC on); an
    option the user gives wins even when it equals the schema default (--no-nhc), and only
    the options given are passed on."""
    from hydrosync_core.cli import build_parser
    from hydrosync_core.methods.gins_smoother.cli import _given
    from hydrosync_core.params import from_cli

    args = build_parser().parse_args(["gins", "--recording", "x", "--no-nhc",
                                      "--nhc-std", "0.2"])
    given = _given(args, from_cli(args, GinsParams))
    assert given == {"nhc": False, "nhc_std": 0.2}
    assert GinsParams.from_dict({"nhc": True, "zupt": True, **given}).nhc is False
    args = build_parser().parse_args(["gins", "--recording", "x"])
    assert _given(args, from_cli(args, GinsParams)) == {}
