"""GNSS/INS smoother end to end on real recordings read in place (#12).

comma2k19 (60 s, phone IMU, u-blox, provider's reference) whole; the rtklibexplorer drive
as a 120 s slice (standstill, then moving). Skipped when ``../shared/data`` lacks them.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from hydrosync_core.methods.gins_smoother import recordings as R  # noqa: N812
from hydrosync_core.methods.gins_smoother.evaluate import evaluate
from hydrosync_core.methods.gins_smoother.filter import run_gins, still_correlated
from hydrosync_core.methods.gins_smoother.params import GinsParams

DATA = Path(__file__).resolve().parents[3] / "shared" / "data"
COMMA = DATA / "comma2k19-ex1"
DRIVE = DATA / "rtkexplorer-gnss-imu" / "drive_0708"
need_comma = pytest.mark.skipif(not COMMA.is_dir(), reason=f"{COMMA} absent (real data)")
need_drive = pytest.mark.skipif(not DRIVE.is_dir(), reason=f"{DRIVE} absent (real data)")


def _hrms(r: np.ndarray) -> float:
    ok = np.isfinite(r).all(axis=1)
    return float(np.sqrt(np.mean(np.sum(r[ok, :2] ** 2, axis=1))))


@pytest.fixture(scope="module")
def comma():
    rec = R.read_comma2k19(COMMA)
    shift, _ = R.estimate_time_shift(rec)
    return R.shifted(rec, shift), shift


@need_comma
def test_comma_import_clocks_and_frames(comma):
    rec, shift = comma
    assert 100 < rec.imu.rate_hz < 110 and rec.gnss.time.size > 550
    # body FRD, gravity in the specific force: z ≈ −g
    f = rec.imu.inc[:, 3:6].sum(axis=0) / (rec.imu.time[-1] - rec.imu.time[0])
    assert -10.2 < f[2] < -9.2
    # IMU, GNSS and reference on one GPS time-of-week scale
    assert abs(rec.imu.time[0] - rec.reference.time[0]) < 0.2
    assert abs(rec.gnss.time[0] - rec.imu.time[0]) < 0.5
    # the fixes' own clock offset, found from the residuals alone (SOURCE.md: ≈ +0.1 s)
    assert 0.05 < shift < 0.2


@need_comma
def test_comma_end_to_end_against_reference(comma):
    rec, _ = comma
    res = run_gins(rec.imu, rec.gnss, rec.config, GinsParams.from_dict(rec.params))
    assert res.alignment["method"] == "GNSS course (moving)"
    # the fixes as white noise of the file's σ: smoothing lowers the residuals (with the
    # estimated model the trajectory minus fix includes the fixes' correlated error)
    white = run_gins(rec.imu, rec.gnss, rec.config,
                     GinsParams.from_dict({**rec.params, "gnss_noise": "file"}))
    assert _hrms(white.gnss["residual"]) < _hrms(white.gnss["residual_forward"]) < 0.5
    assert _hrms(res.gnss["residual"]) < 0.5
    ev = evaluate(res, rec.reference)
    s, f = ev["smoothed"]["all"], ev["forward"]["all"]
    assert s["horizontal"]["rms"] < 1.0
    assert max(s[k]["rms"] for k in ("vn", "ve", "vd")) < 0.1
    assert s["vn"]["rms"] < f["vn"]["rms"]
    # heading against the camera: within the unknown camera/IMU misalignment
    assert s["yaw"]["rms"] < 3.0
    # the u-blox fixes are its own filter's output: with the file's σ as white noise their
    # innovations are correlated fix to fix (lag 1 ≥ 0.9); the estimated model (per-axis
    # Gauss–Markov driving noise) and the fewest fixes thinned out that leave them white
    # give a mean square within 0.8–1.2 and no significant autocorrelation (Ljung–Box
    # over 10 lags, p ≥ 0.01 on each axis). Without the thinning p was 1e-4…1e-8.
    m = res.gnss_model
    assert min(m["first_check"]["rho_lag1"]) > 0.9
    assert m["thinned_every"] > 1 and m["corr_q_scale"] is not None
    assert all(0.8 <= r * r <= 1.2 for r in m["check"]["rms"]), m["summary"]
    assert min(m["check"]["ljung_box_p"]) >= 0.01 and not still_correlated(m["check"])


@need_comma
def test_comma_outage_smoother_bridges(comma):
    rec, _ = comma
    a = rec.imu.time[0] + 15.0
    row = R.outage_test(rec, [(a, a + 20.0)])["windows"][0]
    assert row["smoothed_max_h_m"] < 1.0
    assert row["smoothed_max_h_m"] < 0.2 * row["forward_max_h_m"]
    assert row["smoothed_ref_max_h_m"] < 1.0


@need_drive
def test_drive_slice_end_to_end_with_outage():
    rec = R.read_rtkexplorer(DRIVE)
    assert rec.imu.time.size > 50000 and 99 < rec.imu.rate_hz < 101
    t0 = rec.gnss.time[0]
    rec = rec.sliced(t0 + 20.0, t0 + 140.0)  # standstill, then driving off
    res = run_gins(rec.imu, rec.gnss, rec.config, GinsParams.from_dict(rec.params))
    assert "static_gyro_bias_dph" in res.alignment
    assert res.alignment["levelling"].startswith("accelerometers")
    # RTK: the trajectory (forward and smoothed) within centimetres of the fixes
    assert _hrms(res.gnss["residual"]) < 0.05 and _hrms(res.gnss["residual_forward"]) < 0.05
    w = R.moving_windows(rec, 10.0, 30.0)
    assert w
    rows = R.outage_test(rec, w[:1])["windows"]
    assert rows[0]["smoothed_max_h_m"] < 0.6
    assert rows[0]["smoothed_max_h_m"] < rows[0]["forward_max_h_m"]


@need_comma
def test_comma_project_import_run_and_error_series(tmp_path):
    from hydrosync_core.importers.kinds import import_file
    from hydrosync_core.methods.gins_smoother.project_run import run, stored_errors
    from hydrosync_core.project import Project

    project = Project.create(tmp_path / "c.h5")
    msg = import_file(project, "gins_recording", COMMA)
    assert "clock offset" in msg
    run(project)
    assert project.attrs("raw/gins")["recording"] == "comma2k19"
    errs = stored_errors(project)
    assert set(errs) == {"forward", "smoothed"}
    for comp in ("north", "vd", "yaw"):
        assert np.all(errs["smoothed"][f"sd_{comp}"] > 0)
    project.close()


@need_comma
def test_cli_recording(tmp_path):
    out = tmp_path / "c.nav"
    r = subprocess.run([sys.executable, "-m", "hydrosync_core.cli", "gins", "--recording",
                        str(COMMA), "--out", str(out), "--json", str(tmp_path / "c.json")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert out.exists() and (tmp_path / "c_std.nav").exists()
    assert "clock offset" in r.stdout and "smoothed" in r.stdout
