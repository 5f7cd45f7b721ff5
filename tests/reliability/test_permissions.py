"""Issue #9 item 2: a project's permissions are respected.

A read-only file is refused (exit 2, one line), never silently replaced; a replaced
file keeps its mode and owner; a file or folder another user may not write is refused
before any work. The cases "as another user" run the command as ``nobody`` when the
tests run as root (as in CI), and are skipped otherwise: in this process, with the
effective user switched (the interpreter may live where ``nobody`` cannot run it).
"""

from __future__ import annotations

import os
import shutil
import stat
import tempfile
from contextlib import contextmanager
from pathlib import Path

import pytest

from hydrosync_core.cli import main
from hydrosync_core.errors import ProjectReadOnlyError
from hydrosync_core.project import Project
from tests.reliability.conftest import digest, run_cli, sensors, stderr_lines, temporaries

ROOT = os.name == "posix" and os.geteuid() == 0



def _nobody() -> tuple[int, int]:
    import pwd

    entry = pwd.getpwnam("nobody")
    return entry.pw_uid, entry.pw_gid


@contextmanager
def as_nobody():
    """Run the body with the effective user and group ``nobody``; always switch back."""
    uid, gid = _nobody()
    os.setegid(gid)
    try:
        os.seteuid(uid)
        try:
            yield
        finally:
            os.seteuid(0)
    finally:
        os.setegid(0)


def _main_as_nobody(capsys, *argv) -> tuple[int, list[str]]:
    capsys.readouterr()
    with as_nobody():
        code = main([str(a) for a in argv])
    return code, stderr_lines(capsys.readouterr().err)


@pytest.fixture
def shared_folder():
    """A world-writable folder outside pytest's private tmp tree (0700 parents)."""
    folder = Path(tempfile.mkdtemp(prefix="hydrosync-perm-"))
    folder.chmod(0o777)
    yield folder
    shutil.rmtree(folder, ignore_errors=True)


def _project(path: Path, mode: int) -> Path:
    Project.new("perm").save(path)
    path.chmod(mode)
    return path


def test_read_only_file_is_not_replaced(tmp_path, faults):
    path = _project(tmp_path / "ro.h5", 0o444)
    before = digest(path)
    done = run_cli("vessel", path, "--set", "gnss", 1, 2, 3)
    lines = stderr_lines(done.stderr)
    ok = (done.returncode == 2 and len(lines) == 1 and "read-only (mode 444" in lines[0]
          and digest(path) == before and stat.S_IMODE(path.stat().st_mode) == 0o444)
    faults.record("read-only project written", ok, done.stderr)
    assert ok, done.stderr
    with pytest.raises(ProjectReadOnlyError):
        Project.open(path)
    with Project.open(path, readonly=True) as project:  # looking is fine
        assert project.readonly
        with pytest.raises(ProjectReadOnlyError, match="under another name"):
            project.save()
        project.save(tmp_path / "copy.h5")  # Save As works
    assert (tmp_path / "copy.h5").exists()
    assert temporaries(tmp_path, "ro.h5") == []


def test_replaced_file_keeps_its_mode(tmp_path):
    path = _project(tmp_path / "p.h5", 0o640)
    done = run_cli("vessel", path, "--set", "gnss", 1, 2, 3)
    assert done.returncode == 0, done.stderr
    assert stat.S_IMODE(path.stat().st_mode) == 0o640


@pytest.mark.skipif(not ROOT, reason="needs root to act as another user")
def test_as_another_user(shared_folder, faults, capsys):
    uid, gid = _nobody()
    # 1. Root's 644 file: nobody may not write it.
    mine = _project(shared_folder / "root.h5", 0o644)
    before = digest(mine)
    code, lines = _main_as_nobody(capsys, "vessel", mine, "--set", "gnss", 1, 2, 3)
    ok = code == 2 and len(lines) == 1 and "read-only" in lines[0]
    ok = ok and digest(mine) == before and mine.stat().st_uid == 0
    faults.record("another user's read-only project", ok, str(lines))
    assert ok, lines
    # 2. Root's 666 file: writable, but replacing it would make it nobody's: refused.
    shared = _project(shared_folder / "shared.h5", 0o666)
    before = digest(shared)
    code, lines = _main_as_nobody(capsys, "vessel", shared, "--set", "gnss", 1, 2, 3)
    ok = (code == 2 and len(lines) == 1 and "keeping its owner" in lines[0]
          and digest(shared) == before and shared.stat().st_uid == 0)
    faults.record("owner could not be kept", ok, str(lines))
    assert ok, lines
    # 3. nobody's 640 file saved by root: owner and mode kept.
    theirs = _project(shared_folder / "theirs.h5", 0o640)
    os.chown(theirs, uid, gid)
    done = run_cli("vessel", theirs, "--set", "gnss", 1, 2, 3)
    info = theirs.stat()
    ok = (done.returncode == 0 and (info.st_uid, info.st_gid) == (uid, gid)
          and stat.S_IMODE(info.st_mode) == 0o640 and "gnss" in sensors(theirs))
    faults.record("mode and owner kept on replace", ok, done.stderr)
    assert ok, done.stderr
    assert temporaries(shared_folder, "theirs.h5") == []


@pytest.mark.skipif(not ROOT, reason="needs root to act as another user")
def test_unwritable_folder_fails_before_any_work(shared_folder, faults, capsys):
    uid, gid = _nobody()
    folder = shared_folder / "locked"
    folder.mkdir()
    path = _project(folder / "P.h5", 0o666)
    os.chown(path, uid, gid)
    folder.chmod(0o555)
    code, lines = _main_as_nobody(capsys, "vessel", path, "--set", "gnss", 1, 2, 3)
    ok = code == 2 and len(lines) == 1 and "cannot be written" in lines[0]
    faults.record("unwritable project folder", ok, str(lines))
    assert ok, lines
    # A new project in that folder: refused before reading any input.
    code, lines = _main_as_nobody(capsys, "import", folder / "new.h5", "--gnss",
                                  "/nonexistent.csv")
    assert code == 2 and "cannot be written" in lines[0], lines
