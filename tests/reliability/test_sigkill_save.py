"""Issue #9 item 4 and the SIGKILL campaign: a process killed during the save of a large
(≥ 50 MB) project never leaves a mixed file, and its temporary is removed — with a note —
at the next open or save."""

from __future__ import annotations

import os
import random
import shutil
import signal
import time

from hydrosync_core.atomic import clean_stale_temporaries, machine_tag
from hydrosync_core.project import Project
from tests.reliability.conftest import (
    SCALE,
    run_cli,
    sensors,
    start_cli,
    temporaries,
    wait_for,
)


def test_sigkill_during_save_of_a_large_project(tmp_path, big_project_template, faults):
    path = tmp_path / "P.h5"
    shutil.copyfile(big_project_template, path)
    assert path.stat().st_size >= 50e6
    rng = random.Random(3)
    killed_mid_save = 0
    for i in range(5 * SCALE):
        proc = start_cli("vessel", path, "--set", f"k{i}", 1, 2, 3)
        saw_temp = wait_for(lambda p=proc: bool(temporaries(tmp_path, path.name))
                            or p.poll() is not None, timeout=20)
        time.sleep(rng.uniform(0.0, 0.03))
        proc.send_signal(signal.SIGKILL)
        proc.communicate()
        left = temporaries(tmp_path, path.name)
        killed_mid_save += bool(left)
        problems = []
        if left:
            # The next open says so and removes the dead process's temporary.
            done = run_cli("info", path)
            if "note: removed the stale temporary file" not in done.stdout:
                problems.append(f"no note about the stale temporary: {done.stdout[-200:]!r}")
            if temporaries(tmp_path, path.name):
                problems.append("stale temporary not removed")
        try:
            now = sensors(path)  # a read-only open: the file is whole, old or new
            with Project.open(path, readonly=True) as project:
                if project.get("raw/pool/lidar").shape[1] != 3:
                    problems.append("lidar damaged")
        except Exception as exc:  # noqa: BLE001 - any failure is a failed case
            problems.append(f"unreadable after kill: {exc}")
            now = {}
        if "motion" not in now:
            problems.append("project lost its content")
        faults.record("SIGKILL during save (>= 50 MB)", not problems and saw_temp,
                      "; ".join(problems))
        assert not problems
    assert killed_mid_save >= 1  # at least one kill really hit the save


def test_stale_temporaries_cleaned_only_when_their_process_is_gone(tmp_path):
    target = tmp_path / "P.h5"
    Project.new("x").save(target)
    dead = 2 ** 22 + 12345  # above pid_max: no such process
    tag = machine_tag()  # written on this machine: the pid can be judged here
    stale = tmp_path / f".P.h5.abcd1234.{tag}-{dead}.tmp"
    stale.write_bytes(b"x" * 1000)
    alive = tmp_path / f".P.h5.efgh5678.{tag}-{os.getppid()}.tmp"
    alive.write_bytes(b"y")
    legacy = tmp_path / "P.h5.tmp"
    legacy.write_bytes(b"z" * 10)
    old = time.time() - 3600
    os.utime(legacy, (old, old))
    other = tmp_path / f".Q.h5.abcd1234.{tag}-{dead}.tmp"  # another project's: untouched
    other.write_bytes(b"q")
    with Project.open(target) as project:  # open for writing: legacy name too
        assert any(f"process {dead}" in n for n in project.notices)
        assert any("older HydroSync" in n for n in project.notices)
    assert not stale.exists() and not legacy.exists()
    assert alive.exists() and other.exists()
    assert clean_stale_temporaries(target) == []
