"""``hydrosync tilt``: the formats.md command (files ENU/geodetic, project), exit codes."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hydrosync_core.cli import main
from hydrosync_core.methods.tilt_alignment.io import local_to_output
from hydrosync_core.methods.tilt_alignment.simulate import SwingConfig, simulate_swing

TIP_ENU = (100.0, 200.0, 10.0)
ORIGIN = [47.5, 8.3, 450.0]


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("tilt")
    cfg = SwingConfig(tilt_deg=45.0, shape_ratio=0.4, heading_deg=-60.0,
                      gyro_bias_deg_s=(0.04, -0.03, 0.05), accel_bias_m_s2=(0.02, 0.01, -0.01))
    sim = simulate_swing(cfg, seed=11)
    rows = ["time,gx,gy,gz,ax,ay,az"] + [
        f"{t + 5e5:.3f},{g[0]:.9f},{g[1]:.9f},{g[2]:.9f},{a[0]:.7f},{a[1]:.7f},{a[2]:.7f}"
        for t, g, a in zip(sim["time"], sim["gyro"], sim["accel"], strict=True)]
    (d / "imu.csv").write_text("\n".join(rows) + "\n")
    e0, n0, u0 = TIP_ENU
    rows = ["time,e,n,u"] + [f"{t + 5e5:.3f},{p[1] + e0:.4f},{p[0] + n0:.4f},{u0 - p[2]:.4f}"
                             for t, p in zip(sim["gnss_time"], sim["gnss_ned"], strict=True)]
    (d / "gnss.csv").write_text("\n".join(rows) + "\n")
    frame = {"form": "llh", "origin_llh": ORIGIN}
    rows = ["time,lat,lon,height"]
    for t, p in zip(sim["gnss_time"], sim["gnss_ned"], strict=True):
        lat, lon, h = local_to_output(p, frame)
        rows.append(f"{t + 5e5:.3f},{lat:.10f},{lon:.10f},{h:.4f}")
    (d / "gnss_llh.csv").write_text("\n".join(rows) + "\n")
    (d / "pole.json").write_text(json.dumps({"pole_length_m": sim["pole_length_m"]}))
    return d, sim


def test_tilt_command_enu(files, capsys):
    d, sim = files
    out = d / "result.json"
    code = main(["tilt", "--imu", str(d / "imu.csv"), "--gnss", str(d / "gnss.csv"),
                 "--pole", str(d / "pole.json"), "--json", str(out)])
    assert code == 0, capsys.readouterr().err
    doc = json.loads(out.read_text())
    assert doc["method"] == "joint"
    assert np.hypot(doc["tip_enu"][0] - 100.0, doc["tip_enu"][1] - 200.0) < 0.01
    assert abs(doc["tip_enu"][2] - 10.0) < 0.01
    assert abs(doc["heading_misalignment_deg"] - sim["truth"]["heading_deg"]) < 0.5
    assert len(doc["tip_std_enu_m"]) == 3 and max(doc["tip_std_enu_m"]) < 0.01
    assert doc["vectors_used"] > 100 and doc["vectors_rejected"] >= 0
    assert set(doc["methods"]) == {"joint", "mbgd", "bgd", "sgd", "svd", "closed_form"}


def test_tilt_command_geodetic_gives_tip_llh(files, capsys):
    d, _ = files
    out = d / "result_llh.json"
    code = main(["tilt", "--imu", str(d / "imu.csv"), "--gnss", str(d / "gnss_llh.csv"),
                 "--pole", str(d / "pole.json"), "--json", str(out), "--method", "mbgd"])
    assert code == 0, capsys.readouterr().err
    doc = json.loads(out.read_text())
    assert "tip_llh" in doc and "tip_enu" not in doc and doc["method"] == "mbgd"
    lat, lon, h = doc["tip_llh"]
    assert lat == pytest.approx(ORIGIN[0], abs=1e-6) and lon == pytest.approx(ORIGIN[1], abs=1e-6)
    assert h == pytest.approx(ORIGIN[2], abs=0.1)


@pytest.mark.parametrize("case", ["imu_value", "gnss_header", "pole_key", "imu_gap",
                                  "pole_convention"])
def test_bad_input_exits_2_with_one_line(files, tmp_path, capsys, case):
    d, _ = files
    imu, gnss, pole = d / "imu.csv", d / "gnss.csv", d / "pole.json"
    if case == "imu_value":
        lines = imu.read_text().splitlines()
        lines[6] = lines[6].split(",")[0] + ",0.1,nan,0,0,0,-9.8"
        imu = tmp_path / "imu.csv"
        imu.write_text("\n".join(lines) + "\n")
        want = ("imu.csv:7", "gy")
    elif case == "gnss_header":
        gnss = tmp_path / "gnss.csv"
        gnss.write_text("time,x,y,z\n" + "\n".join((d / "gnss.csv").read_text()
                                                    .splitlines()[1:]) + "\n")
        want = ("gnss.csv:1", "'e'")
    elif case == "pole_key":
        pole = tmp_path / "pole.json"
        pole.write_text('{"length": 2.0}')
        want = ("pole.json", "pole_length_m")
    elif case == "pole_convention":
        pole = tmp_path / "pole.json"
        pole.write_text('{"pole_length_m": 2.0, "imu_convention": "average"}')
        want = ("pole.json", "imu_convention", "interval-end")
    else:
        lines = imu.read_text().splitlines()
        imu = tmp_path / "imu.csv"
        imu.write_text("\n".join(lines[:100] + lines[160:]) + "\n")
        want = ("imu.csv", "gap")
    out = tmp_path / "r.json"
    code = main(["tilt", "--imu", str(imu), "--gnss", str(gnss), "--pole", str(pole),
                 "--json", str(out)])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1 and all(w in err for w in want), err
    assert not out.exists()


def test_faulty_record_exits_3_and_names_it(files, tmp_path, capsys):
    d, _ = files
    sim = simulate_swing(SwingConfig(gyro_bias_deg_s=(0.0, 0.0, 20.0)), seed=6)
    rows = ["time,gx,gy,gz,ax,ay,az"] + [
        f"{t:.3f},{g[0]:.9f},{g[1]:.9f},{g[2]:.9f},{a[0]:.7f},{a[1]:.7f},{a[2]:.7f}"
        for t, g, a in zip(sim["time"], sim["gyro"], sim["accel"], strict=True)]
    (tmp_path / "imu.csv").write_text("\n".join(rows) + "\n")
    rows = ["time,e,n,u"] + [f"{t:.3f},{p[1]:.4f},{p[0]:.4f},{-p[2]:.4f}"
                             for t, p in zip(sim["gnss_time"], sim["gnss_ned"], strict=True)]
    (tmp_path / "gnss.csv").write_text("\n".join(rows) + "\n")
    out = tmp_path / "r.json"
    code = main(["tilt", "--imu", str(tmp_path / "imu.csv"), "--gnss",
                 str(tmp_path / "gnss.csv"), "--pole", str(d / "pole.json"), "--json",
                 str(out), "--method", "mbgd"])
    err = capsys.readouterr().err.strip()
    assert code == 3 and "undetermined" in err and "mbgd" in err
    doc = json.loads(out.read_text())
    assert doc["undetermined"] and doc["tip_enu"] is None


def test_project_form_stores_results(files, tmp_path, capsys):
    from hydrosync_core.project import Project

    d, _ = files
    p = tmp_path / "t.h5"
    assert main(["import", str(p), "--tilt_imu", str(d / "imu.csv"), "--tilt_gnss",
                 str(d / "gnss.csv"), "--tilt_pole", str(d / "pole.json")]) == 0
    out = tmp_path / "r.json"
    assert main(["tilt", str(p), "--json", str(out), "--monte-carlo-runs", "3"]) == 0, \
        capsys.readouterr().err
    doc = json.loads(out.read_text())
    with Project.open(p) as project:
        attrs = project.attrs("results/tilt_alignment")
        stored = json.loads(attrs["result"])
        assert stored["tip_enu"] == pytest.approx(doc["tip_enu"])
        assert "provenance" in attrs
        assert project.get_table("results/tilt_alignment/montecarlo")["run"].size == 3


def test_convention_from_pole_json_and_the_option_and_the_grade_in_the_json(files, tmp_path,
                                                                            capsys):
    """The data were simulated as instantaneous samples: pole.json declaring them
    end-of-interval shifts the attitude by half a sample, which the result names; the
    option overrides the file; the grade and its priors are in the JSON."""
    d, _ = files
    pole = tmp_path / "pole.json"
    length = json.loads((d / "pole.json").read_text())["pole_length_m"]
    pole.write_text(json.dumps({"pole_length_m": length, "imu_convention": "interval-end"}))
    docs = {}
    for extra in ([], ["--imu-convention", "instant"]):
        out = tmp_path / f"r{len(extra)}.json"
        code = main(["tilt", "--imu", str(d / "imu.csv"), "--gnss", str(d / "gnss.csv"),
                     "--pole", str(pole), "--json", str(out), *extra])
        assert code == 0, capsys.readouterr().err
        docs[len(extra)] = json.loads(out.read_text())
    wrong, right = docs[0], docs[2]
    assert wrong["imu_convention"] == "interval-end" and right["imu_convention"] == "instant"
    assert any("'interval-middle or instant'" in w for w in wrong["warnings"])
    assert not any("half the" in w for w in right["warnings"])
    assert right["imu_grade"] == "mems"
    assert right["priors"] == {"gyro_bias_deg_s": 0.05, "accel_bias_m_s2": 0.02}
