"""Start-up of the ``hydrosync`` command: a command loads what it needs, not every command.

A command in a new process registers only its own sub-command (the full parser for help,
an unknown command, or an analysis whose id reads differently); ``hydrosync latency`` from
CSV files never imports h5py nor the project, report or demo modules and starts numpy with
one BLAS thread; the interpreter's final garbage collection is skipped (everything is
frozen at exit).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from hydrosync_core import cli
from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day, write_day_csv

CFG = DayConfig(latency_s=0.08, n_lines=3, line_s=60.0, turn_s=20.0, run_in_s=5.0,
                gnss_hz=5.0, attitude_hz=20.0)


@pytest.mark.parametrize("argv, command", [
    (["latency", "--gnss", "g.csv"], "latency"), (["-v", "info", "P.h5"], "info"),
    (["--verbose", "heave-stats"], "heave-stats"), (["-h"], None), (["--version"], None),
    (["-v", "--", "latency"], None), ([], None),
])
def test_command_named(argv, command):
    assert cli._command_named(argv) == command


@pytest.mark.parametrize("command", ["latency", "info", "import", "demo", "gins", "tilt",
                                     "pool-calibrate", "attitude", "report", "batch"])
def test_one_command_parser_parses_as_the_full_one(command):
    parser = cli.build_parser(command)
    assert command in parser._subparsers._group_actions[0].choices
    full = cli.build_parser()
    one = parser._subparsers._group_actions[0].choices[command]
    assert one.format_help() == full._subparsers._group_actions[0].choices[command].format_help()


def test_unknown_command_gets_the_full_parser(capsys):
    with pytest.raises(SystemExit) as exc:
        cli.main(["latncy", "--gnss", "g.csv"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "invalid choice: 'latncy'" in err and "'latency'" in err and "'import'" in err


PROBE = """
import json, os, sys
from hydrosync_core.cli import main
code = main(sys.argv[1:])
heavy = sorted(m for m in sys.modules if m.split(".")[0] in ("h5py", "open3d", "reportlab",
               "matplotlib", "pyarrow", "dask", "PySide6")
               or m in ("hydrosync_core.project.model", "hydrosync_core.cli.project_cmds",
                        "hydrosync_core.demo", "hydrosync_core.report"))
print(json.dumps({"code": code, "heavy": heavy,
                  "blas_threads": os.environ.get("OPENBLAS_NUM_THREADS")}))
"""


def test_latency_from_csv_files_loads_no_project_modules(tmp_path):
    write_day_csv(simulate_day(CFG, seed=4), tmp_path)
    x, y, z = CFG.lever_arm_m
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    done = subprocess.run(
        [sys.executable, "-c", PROBE, "latency", "--gnss", str(tmp_path / "gnss.csv"),
         "--attitude", str(tmp_path / "attitude.csv"), "--lines", str(tmp_path / "lines.csv"),
         "--lever-arm", str(x), str(y), str(z), "--range", "-0.3", "0.3", "--step", "0.01",
         "--json", str(tmp_path / "result.json")],
        capture_output=True, text=True, timeout=300, env=env)
    assert done.returncode == 0, done.stderr
    probe = json.loads(done.stdout.strip().splitlines()[-1])
    assert probe["code"] == 0 and probe["heavy"] == []
    assert probe["blas_threads"] == "1"  # set before numpy loaded: no spinning BLAS threads
    assert json.loads((tmp_path / "result.json").read_text())["latency_s"] == pytest.approx(
        0.08, abs=0.01)


def test_everything_is_frozen_at_exit():
    """The interpreter's last collections walk nothing (0.2-0.4 s saved after a big run),
    in a ``hydrosync`` process; an in-process caller keeps its own collector."""
    # Registered first, so it runs last (atexit runs in reverse order).
    code = ("import atexit, gc, sys\n"
            "atexit.register(lambda: print(gc.get_freeze_count() > 1000, flush=True))\n"
            "sys.argv[0] = sys.argv[1]\n"
            "from hydrosync_core.cli import main\n"
            "try:\n    main(['--version'])\nexcept SystemExit:\n    pass\n")
    for argv0, frozen in (("/usr/bin/hydrosync", "True"), ("my-gui", "False")):
        done = subprocess.run([sys.executable, "-c", code, argv0], capture_output=True,
                              text=True, timeout=120)
        assert done.returncode == 0, done.stderr
        assert done.stdout.split()[-1] == frozen, argv0


def test_blas_threads_left_alone_once_numpy_is_loaded(monkeypatch):
    from hydrosync_core.methods.latency import cli as latency_cli

    monkeypatch.delenv("OPENBLAS_NUM_THREADS", raising=False)
    latency_cli._one_blas_thread()  # numpy is loaded in this process
    assert "OPENBLAS_NUM_THREADS" not in os.environ
