"""Issue #9 item 1: two processes writing one project never destroy it.

The write lock (``P.h5.lock``) is held from open-for-write to close: a second writer —
CLI or GUI — is refused at once with one line and exit 2; read-only commands still work;
every save uses its own temporary; a file changed on disk since it was opened is never
overwritten silently.
"""

from __future__ import annotations

import random
import signal
import subprocess
import sys
import time

import pytest

from hydrosync_core.atomic import make_temp
from hydrosync_core.errors import ProjectChangedError, ProjectLockedError
from hydrosync_core.project import Project
from hydrosync_core.project.lock import holder_pid, lock_path
from tests.reliability.conftest import (
    SCALE,
    cli_env,
    digest,
    run_cli,
    sensors,
    start_cli,
    stderr_lines,
    temporaries,
)


def _holder(path, seconds: float = 60.0) -> subprocess.Popen:
    """Another HydroSync process holding *path* open for writing."""
    code = ("import sys, time\nfrom hydrosync_core.project import Project\n"
            f"p = Project.open({str(path)!r})\nprint('ready', flush=True)\n"
            f"time.sleep({seconds})\n")
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True,
                            env=cli_env())
    assert proc.stdout.readline().strip() == "ready"
    return proc


@pytest.fixture
def project_file(tmp_path, big_project_template):
    import shutil

    path = tmp_path / "P.h5"
    shutil.copyfile(big_project_template, path)
    return path


def test_second_writer_gets_one_line_and_exit_2(project_file, faults):
    before = digest(project_file)
    holder = _holder(project_file)
    try:
        assert holder_pid(project_file) == holder.pid
        done = run_cli("vessel", project_file, "--set", "gnss", 1, 2, 3)
        # Refused at once, not after waiting for the lock: the holder still holds it.
        still_held = holder.poll() is None and holder_pid(project_file) == holder.pid
        expected = (f"hydrosync vessel: {project_file} is being written by another HydroSync "
                    f"process (pid {holder.pid})")
        ok = (done.returncode == 2 and stderr_lines(done.stderr) == [expected]
              and digest(project_file) == before and still_held)
        faults.record("second writer refused (lock held)", ok, done.stderr)
        assert done.returncode == 2, done.stderr
        assert stderr_lines(done.stderr) == [expected]
        assert digest(project_file) == before
        # Read-only commands need no lock.
        info = run_cli("info", project_file)
        assert info.returncode == 0 and "lidar" in info.stdout, info.stderr
        shown = run_cli("vessel", project_file)
        assert shown.returncode == 0, shown.stderr
        # In-process too: the same exception the GUI turns into a read-only open.
        with pytest.raises(ProjectLockedError) as caught:
            Project.open(project_file)
        assert caught.value.pid == holder.pid
    finally:
        holder.kill()
        holder.wait()
        holder.stdout.close()
    # The kernel released the dead holder's lock: the next writer proceeds.
    done = run_cli("vessel", project_file, "--set", "gnss", 1, 2, 3)
    assert done.returncode == 0, done.stderr
    assert sensors(project_file)["gnss"]["offset_m"] == [1.0, 2.0, 3.0]
    assert not lock_path(project_file).exists()
    assert temporaries(project_file.parent, project_file.name) == []


def test_two_concurrent_cli_writers_never_lose_or_destroy(project_file, faults):
    rng = random.Random(1)
    expected_lock_line = "is being written by another HydroSync process (pid "
    for round_ in range(3 * SCALE):
        a = start_cli("vessel", project_file, "--set", f"a{round_}", 1, 2, 3)
        time.sleep(rng.uniform(0.0, 0.6))
        b = start_cli("vessel", project_file, "--set", f"b{round_}", 4, 5, 6)
        outcomes = []
        for name, proc in (("a", a), ("b", b)):
            _, err = proc.communicate(timeout=60)
            outcomes.append((name, proc.returncode, err))
        now = sensors(project_file)
        problems = []
        for name, code, err in outcomes:
            if code == 0:
                if f"{name}{round_}" not in now:
                    problems.append(f"{name} reported success but its change is lost")
            elif code == 2:
                lines = stderr_lines(err)
                if len(lines) != 1 or expected_lock_line not in lines[0]:
                    problems.append(f"{name}: {err!r}")
            else:
                problems.append(f"{name} exit {code}: {err!r}")
        if temporaries(project_file.parent, project_file.name):
            problems.append("temporary left behind")
        faults.record("two concurrent writers", not problems, "; ".join(problems))
        assert not problems


def test_writer_killed_while_holding_the_lock(project_file, faults):
    proc = start_cli("vessel", project_file, "--set", "killed", 1, 1, 1)
    time.sleep(0.25)
    proc.send_signal(signal.SIGKILL)
    proc.communicate()
    done = run_cli("vessel", project_file, "--set", "after", 2, 2, 2)
    now = sensors(project_file)
    ok = done.returncode == 0 and "after" in now and "motion" in now
    faults.record("writer after a SIGKILLed writer", ok, done.stderr)
    assert ok, done.stderr
    assert temporaries(project_file.parent, project_file.name) == []


def test_changed_on_disk_is_not_overwritten(tmp_path, faults):
    path = tmp_path / "P.h5"
    Project.new("x").save(path)
    first = Project.open(path)
    second = Project.open(path)  # same process: the lock is shared, the check is not
    second.set_attrs("", name="second")
    second.save()
    first.set_attrs("", name="first")
    with pytest.raises(ProjectChangedError, match="changed on disk since it was opened"):
        first.save()
    # Another program replacing the file is detected too (inode/size/mtime).
    other = tmp_path / "other.h5"
    Project.new("other program").save(other)
    import os

    os.replace(other, path)
    with pytest.raises(ProjectChangedError):
        second.save()
    first.close()
    second.close()
    with Project.open(path, readonly=True) as check:
        ok = check.name == "other program"
    faults.record("changed on disk refused", ok)
    assert ok
    # Saving elsewhere (Save As) still works.
    assert Project.new("elsewhere").save(tmp_path / "copy.h5").exists()


def test_every_save_has_its_own_temporary(tmp_path):
    target = tmp_path / "P.h5"
    names = {make_temp(target).name for _ in range(20)}
    assert len(names) == 20
    from hydrosync_core.atomic import machine_tag

    # tagged with the machine (kernel and pid namespace) and the pid: only a process that
    # sees that pid may judge it dead (issue #28)
    assert all(n.startswith(".P.h5.")
               and n.endswith(f".{machine_tag()}-{__import__('os').getpid()}.tmp")
               for n in names)
