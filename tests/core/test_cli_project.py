"""`hydrosync new | import | info`: exit codes and the project left untouched on bad input."""

from __future__ import annotations

import subprocess
import sys

from hydrosync_core.cli import main
from hydrosync_core.project import Project


def test_new_import_info(tmp_path, capsys):
    project = tmp_path / "p.h5"
    assert main(["new", str(project)]) == 0
    gnss = tmp_path / "gnss.csv"
    gnss.write_text("time,height\n1,10\n2,11\n3,12\n")
    lines = tmp_path / "lines.csv"
    lines.write_text("name,start,end\nL01,0,10\n")
    assert main(["import", str(project), "--gnss", str(gnss), "--lines", str(lines)]) == 0
    out = capsys.readouterr().out
    assert "3 rows from gnss.csv into /raw/gnss" in out
    assert main(["info", str(project)]) == 0
    out = capsys.readouterr().out
    assert "gnss/" in out and "height  3 float64" in out
    with Project.open(project) as p:
        assert p.get_table("raw/lines")["name"].tolist() == ["L01"]


def test_bad_file_gives_exit_2_and_leaves_project_unchanged(tmp_path, capsys):
    project = tmp_path / "p.h5"
    assert main(["new", str(project)]) == 0
    before = project.read_bytes()
    good = tmp_path / "gnss.csv"
    good.write_text("time,height\n1,10\n2,11\n")
    bad = tmp_path / "attitude.csv"
    bad.write_text("time,roll,pitch,heading,heave\n1,0,0,0,0\n2,0,x,0,0\n")
    code = main(["import", str(project), "--gnss", str(good), "--attitude", str(bad)])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert err.count("\n") == 0
    assert "attitude.csv:3: field 'pitch': 'x' is not a number" in err
    assert project.read_bytes() == before


def test_new_refuses_to_overwrite(tmp_path, capsys):
    project = tmp_path / "p.h5"
    assert main(["new", str(project)]) == 0
    assert main(["new", str(project)]) == 2
    assert "file exists" in capsys.readouterr().err


def test_help_everywhere():
    for args in (["--help"], ["new", "--help"], ["import", "--help"], ["info", "--help"]):
        result = subprocess.run(
            [sys.executable, "-m", "hydrosync_core.cli", *args], capture_output=True, text=True
        )
        assert result.returncode == 0, result.stderr
        assert "usage: hydrosync" in result.stdout


def test_info_on_garbage_is_exit_2(tmp_path, capsys):
    garbage = tmp_path / "g.h5"
    garbage.write_bytes(b"\x00" * 100)
    assert main(["info", str(garbage)]) == 2
    assert "not a readable HDF5 file" in capsys.readouterr().err


def test_import_attitude_csv_positive_down(tmp_path, capsys):
    project = tmp_path / "p.h5"
    attitude = tmp_path / "attitude.csv"
    attitude.write_text("time,roll,pitch,heading,heave\n1,0,0,0,0.25\n2,0,0,0,-0.5\n")
    args = ["import", str(project), "--attitude", str(attitude), "--heave-positive", "down"]
    assert main(args) == 0
    with Project.open(project) as p:
        assert p.get_table("raw/attitude")["heave"].tolist() == [-0.25, 0.5]
        assert p.attrs("raw/attitude")["heave_positive_in_file"] == "down"
