"""Issue #9 item 3: outputs are checked before any work and published together.

A missing or unwritable output folder fails with exit 2 before any input is read; a command
that fails leaves none of its outputs (``--json ok.json --sync-csv nodir/s.csv`` used to
write ok.json, then fail).
"""

from __future__ import annotations

import numpy as np
import pytest

from hydrosync_core.cli import main
from hydrosync_core.errors import InputError
from hydrosync_core.outputs import Outputs
from tests.reliability.conftest import stderr_lines, temporaries


@pytest.fixture(scope="module")
def latency_files(tmp_path_factory):
    from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day

    folder = tmp_path_factory.mktemp("latency")
    day = simulate_day(DayConfig(n_lines=3, line_s=100.0, turn_s=40.0), seed=2)
    paths = {}
    for name in ("gnss", "attitude"):
        table = day[name]
        path = folder / f"{name}.csv"
        np.savetxt(path, np.column_stack([table[c] for c in table]), delimiter=",",
                   header=",".join(table), comments="", fmt="%.6f")
        paths[name] = path
    lines = day["lines"]
    paths["lines"] = folder / "lines.csv"
    paths["lines"].write_text("name,start,end\n" + "".join(
        f"{n},{s},{e}\n" for n, s, e in zip(lines["name"], lines["start"], lines["end"],
                                            strict=True)))
    return paths, day["truth"]["lever_arm_m"]


def _latency_args(paths, arm, *extra):
    return ["latency", "--gnss", str(paths["gnss"]), "--attitude", str(paths["attitude"]),
            "--lines", str(paths["lines"]), "--lever-arm", *map(str, arm), "--step", "0.01",
            *map(str, extra)]


def test_bad_second_output_fails_first_and_leaves_nothing(latency_files, tmp_path, capsys,
                                                         monkeypatch, faults):
    """Checked first: the refusal comes before any input is read (no reader was called)."""
    from hydrosync_core.methods.latency import readers

    paths, arm = latency_files
    ok_json = tmp_path / "ok.json"
    reads: list[str] = []
    for name in ("prescan_gnss", "prescan_attitude", "read_gnss_csv", "read_attitude_csv"):
        real = getattr(readers, name)
        monkeypatch.setattr(readers, name, lambda *a, _f=real, _n=name, **k: (
            reads.append(_n), _f(*a, **k))[1])
    code = main(_latency_args(paths, arm, "--json", ok_json, "--sync-csv",
                              tmp_path / "nodir" / "s.csv"))
    lines = stderr_lines(capsys.readouterr().err)
    ok = (code == 2 and len(lines) == 1 and "--sync-csv" in lines[0] and "nodir" in lines[0]
          and not ok_json.exists() and reads == [])
    faults.record("output folder missing (checked first)", ok, f"{code} {lines} {reads}")
    assert ok, (code, lines, reads)
    assert list(tmp_path.iterdir()) == []


def test_failure_after_work_leaves_no_output(latency_files, tmp_path, capsys, monkeypatch,
                                             faults):
    paths, arm = latency_files
    out_json, out_csv = tmp_path / "r.json", tmp_path / "s.csv"

    def broken(self, path, columns, precision=6):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(Outputs, "write_csv", broken)
    code = main(_latency_args(paths, arm, "--json", out_json, "--sync-csv", out_csv))
    lines = stderr_lines(capsys.readouterr().err)
    # a full disk is the user's to fix: exit 2 and one line (issue #28), nothing left
    ok = (code == 2 and len(lines) == 1 and "no space left on the disk" in lines[0]
          and list(tmp_path.iterdir()) == [])
    faults.record("failure after work: no partial outputs", ok, str(list(tmp_path.iterdir())))
    assert ok
    monkeypatch.undo()
    assert main(_latency_args(paths, arm, "--json", out_json, "--sync-csv", out_csv)) == 0
    assert out_json.exists() and out_csv.exists()
    assert temporaries(tmp_path, "r.json") == temporaries(tmp_path, "s.csv") == []


@pytest.mark.parametrize("argv", [
    ["pool-calibrate", "--lidar", "L", "--mbes", "M", "--ins", "I", "--setup", "S",
     "--target", "T", "--json", "{tmp}/nodir/r.json"],
    ["report", "{project}", "-o", "{tmp}/nodir/r.pdf"],
    ["latency", "--gnss", "g", "--attitude", "a", "--lines", "l", "--lever-arm", "0", "0",
     "0", "--json", "{tmp}/nodir/r.json"],
    ["import", "{tmp}/nodir/new.h5", "--gnss", "g.csv"],
    ["new", "{tmp}/nodir/new.h5"],
    ["demo", "--out", "{project}/sub"],
])
def test_missing_output_folder_is_exit_2_at_once(argv, tmp_path, capsys, faults):
    from hydrosync_core.project import Project

    project = tmp_path / "p.h5"
    Project.new("p").save(project)
    argv = [a.format(tmp=tmp_path, project=project) for a in argv]
    # The inputs do not exist: naming the output folder proves it was checked first.
    code = main(argv)
    lines = stderr_lines(capsys.readouterr().err)
    ok = code == 2 and len(lines) == 1 and ("nodir" in lines[0] or "sub" in lines[0])
    faults.record("output folder missing (checked first)", ok, f"{argv[0]}: {lines}")
    assert ok, (code, lines)


def test_outputs_unit(tmp_path):
    a, b = tmp_path / "a.json", tmp_path / "b.csv"
    with Outputs({"--gnss": tmp_path / "g.csv"}) as out:
        out.plan(a, "--json")
        with pytest.raises(InputError, match="same file"):
            out.plan(a, "--sync-csv")
        with pytest.raises(InputError, match="overwrite the input --gnss"):
            out.plan(tmp_path / "g.csv", "--json")
        with pytest.raises(InputError, match="is a folder"):
            out.plan(tmp_path, "--json")
        out.write_json(a, {"x": 1})
        out.write_csv(b, {"t": np.arange(3.0)})
        assert not a.exists() and not b.exists()  # nothing published yet
        out.publish()
    assert a.exists() and b.read_text().startswith("t\n")
    with pytest.raises(RuntimeError), Outputs() as out:
        out.write_json(tmp_path / "c.json", {})
        raise RuntimeError("the command failed")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.json", "b.csv"]
