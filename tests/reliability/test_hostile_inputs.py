"""Issue #28: hostile inputs — FIFOs, devices, sparse files, deep or huge settings files,
control characters in names, odd project paths. Each gives exit 2 and one line naming the
file, hangs nowhere (subprocess timeouts only guard a hang) and, where a project is
involved, leaves it and its lock as they were.

Memory is checked on the child's own peak resident size (``wait4`` rusage): a reader
that decoded ``/dev/zero`` or a 1 GB sparse file grew past 4 GB (issue #28); the gate
refuses them before reading, so the peak stays that of a started command (< 1 GB here,
a bound with a 4x margin to the issue's peak, not tuned to this machine).
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from hydrosync_core.errors import InputError
from hydrosync_core.inputs import input_ok
from hydrosync_core.project import Project
from hydrosync_core.project.lock import lock_path
from tests.reliability.conftest import cli_command, cli_env, digest, run_cli, stderr_lines

PEAK_LIMIT_KB = 1_000_000




MEASURE = ("import resource, subprocess, sys\n"
           "p = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, "
           "stderr=subprocess.PIPE, text=True)\n"
           "sys.stderr.write(p.stderr)\n"
           "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
           "sys.exit(p.returncode)\n")
"""Runs the CLI from a small fresh interpreter: a child forked straight from the test
process (1.2 GB under pytest-xdist) would count the parent's pages in its peak before it
replaces itself with the CLI."""


def _run_measured(*args, timeout: float = 120.0) -> tuple[int, str, int]:
    """Run the CLI; return (exit code, stderr, peak resident KB of the CLI process)."""
    proc = subprocess.run([sys.executable, "-c", MEASURE, *cli_command(), *map(str, args)],
                          capture_output=True, text=True, env=cli_env(), timeout=timeout)
    return proc.returncode, proc.stderr, int(proc.stdout.split()[-1])


def _one_line_exit_2(code: int, err: str, faults, kind: str, *words: str) -> None:
    lines = stderr_lines(err)
    ok = code == 2 and len(lines) == 1 and all(w in lines[0] for w in words)
    faults.record(kind, ok, f"exit {code}: {err[-300:]!r}")
    assert ok, (code, err)


# --------------------------------------------------------------- FIFOs and devices
@pytest.mark.parametrize("option", ["--gnss", "--vessel", "--gnss-log"])
def test_fifo_input_is_refused_at_once_and_frees_the_lock(option, project, tmp_path, faults):
    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    before = digest(project)
    done = run_cli("import", project, option, fifo, timeout=120)
    _one_line_exit_2(done.returncode, done.stderr, faults, f"FIFO as import {option}",
                     "named pipe")
    assert digest(project) == before and not lock_path(project).exists()


def test_fifo_as_latency_gnss_is_refused(tmp_path, faults):
    fifo = tmp_path / "gnss.csv"
    os.mkfifo(fifo)
    other = tmp_path / "attitude.csv"
    other.write_text("time,roll,pitch,heading,heave\n")
    lines = tmp_path / "lines.csv"
    lines.write_text("name,start,end\nL1,0,10\n")
    done = run_cli("latency", "--gnss", fifo, "--attitude", other, "--lines", lines,
                   "--lever-arm", 0, 0, 0, "--json", tmp_path / "r.json", timeout=120)
    _one_line_exit_2(done.returncode, done.stderr, faults, "FIFO as latency --gnss",
                     "named pipe")


def test_dev_zero_as_gnss_is_refused_without_reading_it(project, faults):
    code, err, peak_kb = _run_measured("import", project, "--gnss", "/dev/zero")
    _one_line_exit_2(code, err, faults, "/dev/zero as --gnss", "character device")
    assert peak_kb < PEAK_LIMIT_KB, peak_kb


@pytest.mark.parametrize("option", ["--gins-imu", "--gnss-log", "--gnss"])
def test_sparse_gigabyte_input_is_refused_before_reading(option, project, tmp_path, faults):
    sparse = tmp_path / "sparse.txt"
    with open(sparse, "wb") as fh:
        fh.truncate(1 << 30)  # 1 GiB of holes: no disk used
    code, err, peak_kb = _run_measured("import", project, option, sparse)
    _one_line_exit_2(code, err, faults, f"1 GB sparse file as {option}", "NUL")
    assert peak_kb < PEAK_LIMIT_KB, peak_kb
    assert not lock_path(project).exists()


def test_gate_unit(tmp_path):
    text = tmp_path / "ok.csv"
    text.write_text("time,height\n1,2\n")
    assert input_ok(text) == text
    with pytest.raises(InputError, match="no such file"):
        input_ok(tmp_path / "missing.csv")
    with pytest.raises(InputError, match="is a folder"):
        input_ok(tmp_path)
    utf16 = tmp_path / "u16.csv"
    utf16.write_bytes("time,height\n".encode("utf-16"))
    with pytest.raises(InputError, match="UTF-16"):
        input_ok(utf16)
    binary = tmp_path / "cloud.las"
    binary.write_bytes(b"LASF" + bytes(4000))
    assert input_ok(binary, text=False) == binary  # binary kinds are not sniffed
    with pytest.raises(InputError, match="too large"):
        input_ok(text, "settings file", max_bytes=4)


# ----------------------------------------------------------------- settings files
def _deep_json(depth: int) -> str:
    return "[" * depth + "]" * depth


@pytest.mark.parametrize("depth", [100, 5000, 200_000])
def test_deeply_nested_antennas_json_is_exit_2(depth, project, tmp_path, faults):
    path = tmp_path / "antennas.json"
    path.write_text('{"antennas": ' + _deep_json(depth) + "}")
    done = run_cli("import", project, "--antennas", path)
    _one_line_exit_2(done.returncode, done.stderr, faults, "deep JSON (--antennas)",
                     "antennas.json", "nested deeper")


def test_deep_yaml_gins_config_is_exit_2(project, tmp_path, faults):
    path = tmp_path / "kf-gins.yaml"
    path.write_text("a: " + "[" * 3000 + "]" * 3000 + "\n")
    done = run_cli("import", project, "--gins-config", path)
    _one_line_exit_2(done.returncode, done.stderr, faults, "deep YAML (--gins-config)",
                     "kf-gins.yaml", "nested deeper")


def test_deep_toml_and_huge_integer_campaign_are_exit_2(tmp_path, faults):
    deep = tmp_path / "deep.toml"
    deep.write_text("x = " + "[" * 3000 + "]" * 3000 + "\n")
    done = run_cli("batch", deep, "--dry-run")
    _one_line_exit_2(done.returncode, done.stderr, faults, "deep TOML (batch)", "deep.toml",
                     "nested deeper")
    huge = tmp_path / "huge.toml"
    huge.write_text("x = " + "7" * 5001 + "\n")
    done = run_cli("batch", huge, "--dry-run")
    _one_line_exit_2(done.returncode, done.stderr, faults, "5001-digit TOML integer",
                     "huge.toml", "digits")


def test_yaml_alias_bomb_is_bounded(tmp_path):
    from hydrosync_core.configfiles import parse_yaml

    text = "a: &a [x, x, x, x, x, x, x, x, x, x]\n"
    for i in range(1, 9):
        text += f"{chr(97 + i)}: &{chr(97 + i)} [" + ", ".join([f"*{chr(96 + i)}"] * 10) + "]\n"
    with pytest.raises(InputError, match="more than"):
        parse_yaml(text, "bomb.yaml")


def test_batch_output_dir_that_is_a_file_is_refused_before_work(tmp_path, faults):
    (tmp_path / "out").write_text("not a folder")
    campaign = tmp_path / "c.toml"
    Project.new("p").save(tmp_path / "p.h5")
    campaign.write_text('[campaign]\nname = "c"\n[projects]\nfiles = ["p.h5"]\n'
                        '[analyses.latency]\n[outputs]\ndir = "out"\n')
    done = run_cli("batch", campaign, "--dry-run")
    _one_line_exit_2(done.returncode, done.stderr, faults, "batch outputs.dir is a file",
                     "outputs.dir")


# -------------------------------------------------------------- names and paths
def test_nul_in_a_line_name_is_exit_2_naming_the_row(project, tmp_path, faults):
    lines = tmp_path / "lines.csv"
    lines.write_bytes(b"name,start,end\nL1,0,100\nL\x002,200,300\n")
    before = digest(project)
    done = run_cli("import", project, "--lines", lines)
    _one_line_exit_2(done.returncode, done.stderr, faults, "NUL in a line name",
                     "lines.csv", "control character")
    assert digest(project) == before


def test_symlink_loop_as_project_is_exit_2(tmp_path, faults):
    loop = tmp_path / "loop.h5"
    loop.symlink_to(loop)
    for args in (("report", loop, "-o", tmp_path / "r.pdf"), ("info", loop),
                 ("vessel", loop, "--set", "gnss", 1, 2, 3)):
        done = run_cli(*args)
        _one_line_exit_2(done.returncode, done.stderr, faults,
                         f"symlink loop as project ({args[0]})", "loop.h5")


def test_stored_line_ending_before_it_starts_is_named(project):
    """In a project (not through the importer, which checks it too): the validation of
    /raw/lines names the line instead of the later "no line has 30 epochs"."""
    import numpy as np

    from hydrosync_core.errors import ProjectDataError
    from hydrosync_core.project.validate import check_table

    table = {"name": np.array(["L1", "L2"]), "start": np.array([100.0, 200.0]),
             "end": np.array([50.0, 300.0])}
    with pytest.raises(ProjectDataError, match="line 'L1' ends .* before or when it starts"):
        check_table(str(project), "raw/lines", table)
