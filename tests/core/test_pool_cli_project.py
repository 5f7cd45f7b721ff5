"""Pool calibration: command line (formats.md contract), project run layout, plugin spec."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hydrosync_core.cli import main
from hydrosync_core.methods.pool_calibration.demo import fill_demo
from hydrosync_core.methods.pool_calibration.project_run import RESULT, run
from hydrosync_core.methods.pool_calibration.simulate import (
    PoolPassConfig,
    simulate_pool_pass,
    write_pool_files,
)
from hydrosync_core.project import Project

SMALL = PoolPassConfig(beams=128, ping_rate_hz=8.0, laser_density_per_m2=800.0,
                       target_kind="crossing")


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("pool")
    sim = simulate_pool_pass(SMALL, seed=11)
    return write_pool_files(sim, d), sim["truth"]


def _args(paths, out):
    return ["pool-calibrate", "--lidar", str(paths["lidar"]), "--mbes", str(paths["mbes"]),
            "--ins", str(paths["ins"]), "--setup", str(paths["setup"]), "--target",
            str(paths["target"]), "--json", str(out)]


def test_cli_files_contract(files, tmp_path, capsys):
    paths, truth = files
    out = tmp_path / "result.json"
    assert main(_args(paths, out)) == 0
    doc = json.loads(out.read_text())
    for key in ("boresight_deg", "lever_arm_m", "iterations", "converged", "joint", "warnings"):
        assert key in doc
    for k in ("roll", "pitch", "yaw"):
        assert doc["boresight_deg"][k] == pytest.approx(truth["boresight_deg"][k], abs=0.03)
    for k in "xyz":
        assert doc["lever_arm_m"][k] == pytest.approx(truth["lever_arm_m"][k], abs=0.008)
    assert isinstance(doc["iterations"], int) and doc["iterations"] > 0
    assert "boresight roll" in capsys.readouterr().out


def test_cli_bad_input_exit_2_and_no_output(files, tmp_path, capsys):
    paths, _ = files
    bad = tmp_path / "ins.csv"
    bad.write_text("time,e,n,u,roll,pitch\n0,1,2,3,4,5\n1,1,2,3,4,5\n")
    args = _args(dict(paths, ins=bad), tmp_path / "r.json")
    assert main(args) == 2
    err = capsys.readouterr().err
    assert "ins.csv" in err and "heading" in err
    assert not (tmp_path / "r.json").exists()
    assert main(["pool-calibrate", "--lidar", str(paths["lidar"])]) == 2


def test_project_run_layout_and_cli_positional(tmp_path, capsys):
    project = Project.new("pool")
    truth = fill_demo(project, seed=3, config=SMALL)
    path = tmp_path / "p.h5"
    project.save(path)
    capsys.readouterr()
    assert main(["pool-calibrate", str(path)]) == 0
    out = capsys.readouterr().out
    # Final values with their σ and where they were stored (#11 item 8).
    assert "boresight roll" in out and "±" in out and "lever arm z (down" in out
    assert f"stored in {path} under /results/pool_calibration" in out
    with Project.open(path) as p:
        attrs = p.attrs(RESULT)
        assert attrs["method"] == "joint" and isinstance(attrs["converged"], (bool, np.bool_))
        assert attrs["roll_deg"] == pytest.approx(truth["boresight_deg"]["roll"], abs=0.03)
        assert attrs["lever_z_m"] == pytest.approx(truth["lever_arm_m"]["z"], abs=0.008)
        assert attrs["sigma_pitch_deg"] > 0
        faces = p.get_table(f"{RESULT}/faces")
        assert list(faces)[:8] == ["face", "role", "water", "points_laser", "points_mbes",
                                   "rms_laser_m", "rms_mbes_m", "normal_angle_deg"]
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in faces["face"]]
        assert "wall" in names
        its = p.get_table(f"{RESULT}/iterations")
        assert its["iteration"][0] == 1 and "max_normal_angle_deg" in its
        assert p.get(f"{RESULT}/plan/laser_xyz").shape[1] == 3
        before = p.get(f"{RESULT}/plan/mbes_before_xyz")
        assert before.shape == p.get(f"{RESULT}/plan/mbes_after_xyz").shape
        assert p.get(f"{RESULT}/plan/mbes_face").shape == (len(before),)
        doc = p.get_json(f"{RESULT}/result")
        assert doc["boresight_deg"]["roll"] == pytest.approx(attrs["roll_deg"])
        assert p.get_json(RESULT)["min_points"] == 30


def test_rerun_replaces_results():
    project = Project.new("pool")
    fill_demo(project, seed=4, config=SMALL)
    run(project, {"plan_points": 100})
    run(project, {"plan_points": 50})
    assert len(project.get(f"{RESULT}/plan/laser_xyz")) == 50


def test_plugin_spec():
    from plugins.pool_calibration import SPEC

    assert SPEC.id == "pool_calibration" and SPEC.order == 20
    assert SPEC.load_run() is run
    assert SPEC.missing_inputs(Project.new()) == list(SPEC.requires)


def test_cli_ins_accuracy_widens_sigma_and_is_checked(files, tmp_path, capsys):
    paths, _ = files
    plain, with_ins = tmp_path / "plain.json", tmp_path / "ins.json"
    assert main(_args(paths, plain)) == 0
    assert main(_args(paths, with_ins) + ["--ins-sigma", "0.02", "0.02", "0.05"]) == 0
    s0 = json.loads(plain.read_text())["joint"]["sigma_boresight_deg"]
    s1 = json.loads(with_ins.read_text())["joint"]["sigma_boresight_deg"]
    # An INS that is itself uncertain cannot give a tighter boresight.
    assert all(s1[k] > s0[k] for k in ("roll", "pitch", "yaw"))
    assert s1["yaw"] > 1.5 * s0["yaw"]
    bad = tmp_path / "bad.json"
    assert main(_args(paths, bad) + ["--ins-sigma", "-1", "0", "0"]) == 2
    assert "--ins-sigma" in capsys.readouterr().err and not bad.exists()


def test_cli_exit_3_names_undetermined_parameters(tmp_path, capsys, monkeypatch):
    """A patent target whose design lacks the block tops, passed without roll or pitch:
    nothing determines the vertical lever arm (only tops, or the vessel's roll and pitch
    against the wall and obliques, do). The CLI finishes, writes the JSON (coarse value
    kept, σ null, the reason) and exits 3 with one line naming the parameter; --help
    documents the code. (Progress lines are off: on a loaded machine a run past 5 s prints
    one, issue #23.)"""
    monkeypatch.setenv("HYDROSYNC_PROGRESS", "off")
    sim = simulate_pool_pass(PoolPassConfig(beams=128, ping_rate_hz=8.0,
                                            laser_density_per_m2=800.0, roll_amp_deg=0.0,
                                            pitch_amp_deg=0.0), seed=3)
    sim["target"] = dict(sim["target"], faces=[f for f in sim["target"]["faces"]
                                               if not f["name"].endswith("_top")])
    paths = write_pool_files(sim, tmp_path / "in")
    out = tmp_path / "result.json"
    capsys.readouterr()
    assert main(_args(paths, out) + ["--build-tol-m", "0.001", "--build-tol-deg", "0.005"]) == 3
    # Progress lines ("[ 61.4%] …") appear on a slow machine; the verdict is one line.
    err = [line for line in capsys.readouterr().err.strip().splitlines()
           if not line.startswith("[")]
    assert len(err) == 1 and "lever_z" in err[0] and "not determined" in err[0]
    doc = json.loads(out.read_text())
    assert "singular" in doc["undetermined"]["lever_z"] or \
        "σ from the data" in doc["undetermined"]["lever_z"]
    assert doc["lever_arm_m"]["z"] == pytest.approx(sim["setup"]["lever_arm_m"]["z"])
    assert doc["joint"]["sigma_lever_arm_m"]["z"] is None
    assert doc["build_tolerance"] == {"translation_m": 0.001, "rotation_deg": 0.005}
    faces = {f["face"]: f for f in doc["faces"]}
    assert faces["N1_dn_oblique"]["reference"] == "N1_up_oblique"
    with pytest.raises(SystemExit):
        main(["pool-calibrate", "--help"])
    text = capsys.readouterr().out
    assert "3 finished, but some parameters are not determined" in " ".join(text.split())
    assert "--build-tol-m" in text and "--coarse-tol-deg" in text
