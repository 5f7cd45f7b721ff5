"""``hydrosync latency`` on CSV files and on a project; bad input gives exit 2 and no file."""

from __future__ import annotations

import json
from dataclasses import replace

import pytest

from hydrosync_core.cli import main
from hydrosync_core.methods.latency.demo import fill_demo
from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day, write_day_csv
from hydrosync_core.methods.latency.texts import latency_text
from hydrosync_core.project import Project

CFG = DayConfig(latency_s=-0.15, n_lines=4, line_s=90.0, turn_s=20.0, run_in_s=5.0,
                gnss_hz=5.0, attitude_hz=20.0, gnss_white_m=0.02, multipath_m=0.02,
                heave_error_m=0.02)


@pytest.fixture(scope="module")
def csv_dir(tmp_path_factory):
    directory = tmp_path_factory.mktemp("latency_csv")
    write_day_csv(simulate_day(CFG, seed=2), directory)
    return directory


def _args(d, out, *extra):
    x, y, z = CFG.lever_arm_m
    return ["latency", "--gnss", str(d / "gnss.csv"), "--attitude", str(d / "attitude.csv"),
            "--lines", str(d / "lines.csv"), "--lever-arm", str(x), str(y), str(z),
            "--json", str(out), *extra]


def test_cli_csv_writes_result_json(csv_dir, tmp_path, capsys):
    out = tmp_path / "result.json"
    assert main(_args(csv_dir, out, "--range", "-0.5", "0.5", "--step", "0.01")) == 0
    doc = json.loads(out.read_text())
    assert doc["latency_s"] == pytest.approx(-0.15, abs=0.01)
    assert len(doc["lines"]) == 4
    for line in doc["lines"]:
        assert {"name", "r_max", "latency_s", "sigma0_before_m", "sigma0_after_m",
                "used"} <= set(line)
    assert doc["params"]["range_s"] == [-0.5, 0.5]
    table = capsys.readouterr().out
    shown = latency_text(doc["latency_s"], doc["uncertainty_s"])
    assert "L01" in table and f"latency {shown}" in table
    assert "0.000" not in shown
    assert doc["estimator"] in ("qi2010", "weighted") and doc["params"]["estimator"] == "auto"


def _bad(tmp_path, capsys, argv):
    out = tmp_path / "result.json"
    code = main(argv(out))
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1
    assert not out.exists() and not (tmp_path / "result.json.tmp").exists()
    return err


def test_cli_bad_inputs(csv_dir, tmp_path, capsys):
    err = _bad(tmp_path, capsys, lambda o: _args(csv_dir, o)[:2] + ["/nope/gnss.csv"]
               + _args(csv_dir, o)[3:])
    assert "/nope/gnss.csv" in err
    bad_gnss = tmp_path / "gnss.csv"
    bad_gnss.write_text("time,height\n1,42.0\n2,abc\n3,42.1\n")
    err = _bad(tmp_path, capsys, lambda o: _args(csv_dir, o)[:2] + [str(bad_gnss)]
               + _args(csv_dir, o)[3:])
    assert "gnss.csv:3" in err and "height" in err
    err = _bad(tmp_path, capsys, lambda o: _args(csv_dir, o, "--range", "1", "-1"))
    assert "--range" in err
    lines = tmp_path / "lines.csv"
    lines.write_text("name,start,end\nA,1,50\n")
    err = _bad(tmp_path, capsys, lambda o: _args(csv_dir, o)[:6] + [str(lines)]
               + _args(csv_dir, o)[7:])
    assert "no line has 30 or more GNSS epochs" in err
    # Wrong lever-arm side: no line correlates; the message says what is likely wrong.
    x, y, z = CFG.lever_arm_m
    err = _bad(tmp_path, capsys, lambda o: _args(csv_dir, o)[:8] + [str(x), str(-y), str(z)]
               + _args(csv_dir, o)[11:])
    assert "y sign is probably wrong" in err
    err = _bad(tmp_path, capsys, lambda o: ["latency", "--gnss", "g.csv", "--json", str(o)])
    assert "missing option" in err


def test_cli_project_mode_stores_results(tmp_path, capsys):
    path = tmp_path / "demo.h5"
    project = Project.new("demo")
    fill_demo(project, seed=1)
    project.save(path)
    assert main(["latency", str(path), "--step", "0.01"]) == 0
    assert "results stored" in capsys.readouterr().out
    with Project.open(path) as stored:
        attrs = stored.attrs("results/latency")
        assert attrs["latency_s"] == pytest.approx(0.29, abs=0.03)
        table = stored.get_table("results/latency/lines")
        assert table["name"].tolist()[:2] == ["L01", "L02"]
        assert stored.get("results/latency/r_curves").shape == (13, 201)
        assert json.loads(attrs["lever_arm_m"]) == list(replace(DayConfig()).lever_arm_m)


def test_cli_project_without_data(tmp_path, capsys):
    path = tmp_path / "empty.h5"
    Project.new("empty").save(path)
    assert main(["latency", str(path)]) == 2
    assert "raw/gnss" in capsys.readouterr().err


def test_sync_csv_export(tmp_path):
    """--sync-csv writes GNSS epochs at corrected times with the interpolated attitude."""
    import numpy as np

    day = simulate_day(DayConfig(n_lines=3, gnss_hz=2.0), seed=5)
    write_day_csv(day, tmp_path)
    out = tmp_path / "sync.csv"
    code = main(["latency", "--gnss", str(tmp_path / "gnss.csv"), "--attitude",
                 str(tmp_path / "attitude.csv"), "--lines", str(tmp_path / "lines.csv"),
                 "--lever-arm", "-1.5", "2", "-6", "--json", str(tmp_path / "r.json"),
                 "--sync-csv", str(out)])
    assert code == 0
    table = np.loadtxt(out, delimiter=",", skiprows=1)
    header = out.read_text().splitlines()[0].split(",")
    assert header == ["time", "height", "roll", "pitch", "heading", "heave", "total_heave"]
    gnss = np.loadtxt(tmp_path / "gnss.csv", delimiter=",", skiprows=1)
    latency = json.loads((tmp_path / "r.json").read_text())["latency_s"]
    # Corrected time = tag - latency, heights unchanged.
    np.testing.assert_allclose(table[:, 0] + latency, gnss[: len(table), 0], atol=2e-6)
    np.testing.assert_allclose(table[:, 1], gnss[: len(table), 1], atol=1e-6)


def test_background_import_helper():
    """The CLI's preload thread: nothing for a loaded module; a failed import stays quiet
    (the caller's own import reports it) and the thread ends."""
    import sys

    from hydrosync_core.methods.latency.cli import _import_in_background

    assert _import_in_background("json") is None
    thread = _import_in_background("hydrosync_no_such_module_for_this_test")
    assert thread is not None and thread.daemon
    thread.join(10)
    assert not thread.is_alive()
    assert "hydrosync_no_such_module_for_this_test" not in sys.modules
