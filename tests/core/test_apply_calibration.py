"""Applying the pool calibration to the vessel sheet (#11 item 9)."""

from __future__ import annotations

import pytest

from hydrosync_core.cli import main
from hydrosync_core.methods.pool_calibration.demo import fill_demo
from hydrosync_core.methods.pool_calibration.project_run import run
from hydrosync_core.project import Project
from hydrosync_core.project.history import events
from hydrosync_core.project.vessel import set_sensor, vessel_config
from tests.core.test_pool_cli_project import SMALL


@pytest.fixture(scope="module")
def calibrated(tmp_path_factory):
    path = tmp_path_factory.mktemp("apply") / "P.h5"
    project = Project.new("p")
    fill_demo(project, seed=3, config=SMALL)
    set_sensor(project, "ins", [0.10, -0.20, 0.30])
    run(project)
    project.save(path)
    project.close()
    return path


def test_apply_writes_offset_angles_and_history(calibrated, tmp_path, capsys):
    path = tmp_path / "a.h5"
    path.write_bytes(calibrated.read_bytes())
    assert main(["vessel", str(path), "--apply", "pool_calibration"]) == 0
    assert "applied multibeam: offset" in capsys.readouterr().out
    with Project.open(path) as p:
        a = p.attrs("results/pool_calibration")
        mb = vessel_config(p)["sensors"]["multibeam"]
        assert mb["offset_m"] == pytest.approx([0.10 + a["lever_x_m"], -0.20 + a["lever_y_m"],
                                                0.30 + a["lever_z_m"]], abs=1e-6)
        assert mb["angles_deg"]["roll"] == pytest.approx(a["roll_deg"], abs=1e-6)
        (event,) = events(p)
        assert event["action"].startswith("applied pool_calibration")
        assert event["new"] == mb and event["old"]["offset_m"] != mb["offset_m"]


def test_apply_refuses_out_of_date_or_unknown(calibrated, tmp_path, capsys):
    path = tmp_path / "b.h5"
    path.write_bytes(calibrated.read_bytes())
    assert main(["vessel", str(path), "--apply", "latency"]) == 2
    assert "has no calibration to apply" in capsys.readouterr().err
    with Project.open(path) as p:
        setup = p.get_json("raw/pool/setup")
        setup["lever_arm_m"]["x"] += 0.01
        p.put_json("raw/pool/setup", setup)
        p.save()
    assert main(["vessel", str(path), "--apply", "pool_calibration"]) == 2
    assert "out of date" in capsys.readouterr().err
    with Project.open(path) as p:
        assert events(p) == []  # nothing applied
