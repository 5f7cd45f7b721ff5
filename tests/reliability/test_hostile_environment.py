"""Issue #28: nothing lost in a hostile environment — the files around a project.

Symlinked, foreign, dead-owner and hard-linked locks; outputs onto devices, FIFOs and
/proc; another machine's (another pid namespace's) live save; a full disk (tmpfs in a
private mount namespace, where ``unshare`` is allowed); the CLI's exit codes. Every case
must end with exit 2 (or 0 where the command is right to go on) and one line, destroy
nothing and not hang (the subprocess timeouts only guard against a hang).
"""

from __future__ import annotations

import os
import shutil
import stat
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest

from hydrosync_core import atomic
from hydrosync_core.project import Project
from hydrosync_core.project.lock import holder, lock_path
from tests.reliability.conftest import (
    cli_env,
    digest,
    run_cli,
    sensors,
    start_cli,
    stderr_lines,
    temporaries,
)

ROOT = os.name == "posix" and os.geteuid() == 0
HAS_UNSHARE = shutil.which("unshare") is not None




def _refused(done, faults, kind: str, *words: str) -> None:
    lines = stderr_lines(done.stderr)
    ok = done.returncode == 2 and len(lines) == 1 and all(w in lines[0] for w in words)
    faults.record(kind, ok, f"exit {done.returncode}: {done.stderr[-300:]!r}")
    assert ok, (done.returncode, done.stderr)


# ------------------------------------------------------------------------- locks
def test_symlinked_lock_is_refused_and_its_target_kept(project, tmp_path, faults):
    victim = tmp_path / "victim.txt"
    victim.write_text("keep\n")
    lock_path(project).symlink_to(victim)
    before = digest(project)
    done = run_cli("vessel", project, "--set", "gnss", 1, 2, 3)
    _refused(done, faults, "lock: symbolic link", "symbolic link", "P.h5.lock")
    assert victim.read_text() == "keep\n" and digest(project) == before
    assert lock_path(project).is_symlink()  # reported, not removed


@pytest.mark.parametrize("kind", ["folder", "fifo"])
def test_lock_that_is_not_a_file_is_refused(project, faults, kind):
    side = lock_path(project)
    if kind == "folder":
        side.mkdir()
    else:
        os.mkfifo(side)
    done = run_cli("vessel", project, "--set", "gnss", 1, 2, 3, timeout=60)
    _refused(done, faults, f"lock: a {kind} in its place", "P.h5.lock")
    assert "gnss" not in sensors(project)


def _write_record(project: Path, text: str, mode: int = 0o644) -> None:
    side = lock_path(project)
    side.write_text(text)
    side.chmod(mode)


def test_lock_of_another_machine_needs_break_lock_after_60_s(project, faults):
    dead = 2 ** 22 + 77
    old = time.time() - 3600
    _write_record(project, f"{dead}\nhost=elsewhere tag=0badc0de kernel=0badc0de "
                  f"since={old:.3f}\n")
    done = run_cli("vessel", project, "--set", "gnss", 1, 2, 3)
    _refused(done, faults, "lock: another machine's, not broken silently", "elsewhere",
             "--break-lock")
    assert holder(project).host == "elsewhere"  # still there
    # a young one is never broken, even when asked
    young = time.time() - 5
    _write_record(project, f"{dead}\nhost=elsewhere tag=0badc0de kernel=0badc0de "
                  f"since={young:.3f}\n")
    done = run_cli("vessel", project, "--set", "gnss", 1, 2, 3, "--break-lock")
    _refused(done, faults, "lock: young foreign lock kept with --break-lock", "60 s")
    _write_record(project, f"{dead}\nhost=elsewhere tag=0badc0de kernel=0badc0de "
                  f"since={old:.3f}\n")
    done = run_cli("vessel", project, "--set", "gnss", 1, 2, 3, "--break-lock")
    ok = done.returncode == 0 and "removed the stale lock" in done.stdout
    faults.record("lock: --break-lock takes over an old foreign lock", ok, done.stderr)
    assert ok, (done.stdout, done.stderr)
    assert sensors(project)["gnss"]["offset_m"] == [1.0, 2.0, 3.0]
    assert not lock_path(project).exists()


def test_lock_left_by_a_dead_process_of_this_machine_is_taken_over(project, faults):
    dead = 2 ** 22 + 78
    _write_record(project, f"{dead}\nhost=x tag={atomic.machine_tag()} "
                  f"kernel={atomic.kernel_tag()} since={time.time():.3f}\n")
    done = run_cli("vessel", project, "--set", "gnss", 1, 2, 3)
    ok = done.returncode == 0 and "gnss" in sensors(project)
    faults.record("lock: dead owner on this machine taken over", ok, done.stderr)
    assert ok, done.stderr


@pytest.mark.skipif(not ROOT, reason="needs root to leave a lock as another user")
def test_stale_lock_of_another_user_does_not_block_for_ever(tmp_path, faults, capsys):
    import pwd

    from tests.reliability.test_permissions import _main_as_nobody

    folder = Path(tempfile.mkdtemp(prefix="hydrosync-lock-"))
    try:
        folder.chmod(0o777)
        path = folder / "P.h5"
        Project.new("P").save(path)
        path.chmod(0o666)
        nobody = pwd.getpwnam("nobody")
        os.chown(path, nobody.pw_uid, nobody.pw_gid)
        _write_record(path, f"{2 ** 22 + 79}\n", 0o644)  # root's, its process gone
        code, lines = _main_as_nobody(capsys, "vessel", path, "--set", "gnss", 1, 2, 3)
        ok = code == 0 and "gnss" in sensors(path)
        faults.record("lock: another user's dead lock taken over", ok, str(lines))
        assert ok, (code, lines)
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def _holder(path: Path) -> subprocess.Popen:
    code = ("import sys\nfrom hydrosync_core.project import Project\n"
            f"p = Project.open({str(path)!r})\nprint('ready', flush=True)\nsys.stdin.read()\n")
    proc = subprocess.Popen([sys.executable, "-c", code], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, text=True, env=cli_env())
    assert proc.stdout.readline().strip() == "ready"
    return proc


def test_hard_links_of_one_project_share_one_lock(project, faults):
    other = project.with_name("Q.h5")
    os.link(project, other)
    proc = _holder(project)
    try:
        done = run_cli("vessel", other, "--set", "gnss", 1, 2, 3)
        _refused(done, faults, "lock: hard link of a locked project", "hard link")
    finally:
        proc.communicate("", timeout=60)
    done = run_cli("vessel", other, "--set", "gnss", 1, 2, 3)
    assert done.returncode == 0, done.stderr


def test_lock_in_a_group_folder_is_group_writable(tmp_path):
    folder = tmp_path / "shared"
    folder.mkdir()
    folder.chmod(0o2775)
    path = folder / "P.h5"
    Project.new("P").save(path)
    old = os.umask(0o022)
    try:
        with Project.open(path):
            assert stat.S_IMODE(lock_path(path).stat().st_mode) == 0o664
    finally:
        os.umask(old)


# ------------------------------------------------------------------------ outputs
@pytest.mark.parametrize("kind", ["fifo", "/dev/full", "/proc/version", "link to /dev/null"])
def test_output_onto_a_device_fifo_or_proc_is_refused(kind, project, tmp_path, faults):
    if kind == "fifo":
        target = tmp_path / "out.json"
        os.mkfifo(target)
    elif kind == "link to /dev/null":
        target = tmp_path / "out.json"
        target.symlink_to("/dev/null")
    else:
        target = Path(kind)
    before = os.stat(target).st_mode
    done = run_cli("latency", project, "--json", target, timeout=60)
    _refused(done, faults, f"output onto {kind}", "--json", "cannot be written")
    assert os.stat(target).st_mode == before  # still the device / FIFO


def test_gins_out_in_proc_is_refused(project, faults):
    done = run_cli("gins", project, "--out", "/proc/version")
    _refused(done, faults, "output onto /proc (gins --out)", "/proc")


def test_killed_report_temporary_is_removed_by_the_next_run(project, tmp_path, faults):
    pdf = tmp_path / "R.pdf"
    dead = 2 ** 22 + 80
    left = tmp_path / f".R.pdf.abcdefgh.{atomic.machine_tag()}-{dead}.tmp"
    left.write_bytes(b"%PDF-partial")
    done = run_cli("report", project, "-o", pdf, timeout=300)
    ok = done.returncode == 0 and pdf.exists() and temporaries(tmp_path, "R.pdf") == []
    faults.record("report: a killed run's temporary removed", ok, done.stderr)
    assert ok, (done.returncode, done.stderr, temporaries(tmp_path, "R.pdf"))


# ---------------------------------------------------- another machine's live save
def _unshare_works(*flags: str) -> bool:
    if not HAS_UNSHARE:
        return False
    return subprocess.run(["unshare", *flags, "true"], capture_output=True).returncode == 0


PID_NS = ("--pid", "--fork", "--mount-proc") if ROOT else ("-r", "--pid", "--fork",
                                                            "--mount-proc")


@pytest.mark.skipif(not _unshare_works(*PID_NS), reason="unshare of a pid namespace not "
                    "allowed here")
def test_read_only_command_keeps_a_live_save_of_another_pid_namespace(project, faults):
    """The issue's reproduction: a save paused in another pid namespace (another
    container, a Dask worker on another node), ``info`` run here, then the save resumes."""
    code = ("import sys\nfrom hydrosync_core.atomic import atomic_path\n"
            f"with atomic_path({str(project)!r}) as tmp:\n"
            "    tmp.write_bytes(open(" + repr(str(project)) + ", 'rb').read())\n"
            "    print(tmp.name, flush=True)\n"
            "    sys.stdin.read()\n"
            "print('saved', flush=True)\n")
    # pids 1-200 of the namespace go to short-lived processes first: the saver's pid
    # must be one that does not run out here, as on another machine
    spin = 'i=0; while [ $i -lt 200 ]; do /bin/true; i=$((i+1)); done; "$0" -c "$1"'
    proc = subprocess.Popen(["unshare", *PID_NS, "sh", "-c", spin, sys.executable, code],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, env=cli_env())
    try:
        name = proc.stdout.readline().strip()
        tmp = project.parent / name
        pid = int(name.rsplit("-", 1)[1].split(".")[0])
        assert tmp.exists() and f".{atomic.machine_tag()}-" not in name
        if atomic.pid_alive(pid):
            pytest.skip(f"pid {pid} of the namespace happens to run here too")
        os.utime(tmp, (time.time() - 600, time.time() - 600))  # old: reported, kept
        done = run_cli("info", project)
        kept = tmp.exists()
        out, err = proc.communicate("", timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    ok = done.returncode == 0 and kept and "saved" in out and proc.returncode == 0
    faults.record("another pid namespace's live save kept by info", ok, err + done.stderr)
    assert ok, (done.stdout, done.stderr, out, err)
    assert "left alone the temporary" in done.stdout


# ----------------------------------------------------------------------- full disk
MOUNT_NS = ("--mount",) if ROOT else ("-r", "--mount")


@pytest.mark.skipif(not _unshare_works(*MOUNT_NS), reason="unshare of a mount namespace "
                    "(for a small tmpfs) not allowed here")
@pytest.mark.parametrize("fill", ["almost", "all"])
def test_full_disk_is_exit_2_and_leaves_everything_as_it_was(fill, faults, tmp_path,
                                                             big_project_template):
    """A 64 MB project on a 100 MB tmpfs that is then filled: the copy of the project
    cannot fit ("almost": a few MB left; "all": 0 bytes left)."""
    mount = tmp_path / "disk"
    mount.mkdir()
    keep = "4M" if fill == "almost" else "0"
    hs = " ".join(map(str, [*cli_command_for_shell()]))
    script = f"""
set -e
mount -t tmpfs -o size=100m tmpfs {mount}
cp {big_project_template} {mount}/P.h5
sha256sum {mount}/P.h5 > {tmp_path}/before
free=$(df --output=avail -B1 {mount} | tail -1)
fallocate -l $((free - $(numfmt --from=iec {keep}) )) {mount}/filler 2>/dev/null || \
  dd if=/dev/zero of={mount}/filler bs=1M 2>/dev/null || true
set +e
{hs} vessel {mount}/P.h5 --set gnss 1 2 3 > {tmp_path}/out 2> {tmp_path}/err
echo $? > {tmp_path}/code
sha256sum {mount}/P.h5 > {tmp_path}/after
ls -a {mount} > {tmp_path}/files
{hs} new {mount}/N.h5 > /dev/null 2> {tmp_path}/err_new
echo $? > {tmp_path}/code_new
printf 'name,start,end\nL1,0,10\n' > {tmp_path}/lines.csv
{hs} import {mount}/P.h5 --lines {tmp_path}/lines.csv > /dev/null 2> {tmp_path}/err_import
echo $? > {tmp_path}/code_import
sha256sum {mount}/P.h5 > {tmp_path}/after_import
ls -a {mount} > {tmp_path}/files_after
"""
    subprocess.run(["unshare", *MOUNT_NS, "sh", "-c", script], check=True, timeout=300,
                   env=cli_env())
    code = int((tmp_path / "code").read_text())
    lines = stderr_lines((tmp_path / "err").read_text())
    files = set((tmp_path / "files").read_text().split())
    same = (tmp_path / "before").read_text() == (tmp_path / "after").read_text()
    ok = (code == 2 and len(lines) == 1 and "no space left" in lines[0] and same
          and files == {".", "..", "P.h5", "filler"})
    faults.record(f"full disk ({fill}): vessel --set", ok, f"{code} {lines} {files}")
    assert ok, (code, lines, files, same)
    if fill == "all":  # nothing fits: new and import fail alike, leaving no empty lock
        for command in ("new", "import"):
            code = int((tmp_path / f"code_{command}").read_text())
            lines = stderr_lines((tmp_path / f"err_{command}").read_text())
            ok = code == 2 and len(lines) == 1 and "no space left" in lines[0]
            faults.record(f"full disk (all): {command}", ok, f"{code} {lines}")
            assert ok, (command, code, lines)
        assert set((tmp_path / "files_after").read_text().split()) == files
        assert (tmp_path / "after_import").read_text() == (tmp_path / "after").read_text()


def cli_command_for_shell() -> list[str]:
    from tests.reliability.conftest import cli_command

    return cli_command()


def test_disk_full_inside_the_hdf5_copy_is_an_input_error(project, monkeypatch):
    """ENOSPC raised by the chunk copy (past the free-space check) is a one-line
    DiskFullError naming the file; the old file and the lock stay as they were."""
    from hydrosync_core.errors import DiskFullError
    from hydrosync_core.project import store

    before = digest(project)

    def full(*args, **kwargs):
        raise OSError("Can't write data (file write failed: errno = 28, error message = "
                      "'No space left on device')")

    with Project.open(project) as p:
        p.put("raw/x", list(range(10)))
        monkeypatch.setattr(store, "write_tree", full)
        with pytest.raises(DiskFullError, match="no space left on the disk"):
            p.save()
        assert lock_path(project).exists()  # still ours until closed
    assert digest(project) == before
    assert temporaries(project.parent, project.name) == []
    assert not lock_path(project).exists()


# ------------------------------------------------------------------------ the CLI
def test_negative_numbers_in_exponent_form_are_values():
    from hydrosync_core.cli import build_parser

    args = build_parser("latency").parse_args(["latency", "P.h5", "--range", "-5e-1",
                                               "5E-1"])
    values = [v for k, v in vars(args).items() if "range" in k and v is not None]
    assert [tuple(map(float, v)) for v in values] == [(-0.5, 0.5)]


def test_closed_stdout_exits_0_quietly(tmp_path):
    path = tmp_path / "P.h5"
    p = Project.new("P")
    for i in range(400):  # enough lines to overflow the pipe's buffer
        p.put(f"raw/t{i}/x", list(range(3)))
    p.save(path)
    proc = start_cli("info", path)
    proc.stdout.readline()
    proc.stdout.close()  # the reader leaves, as `| head -1` does
    err = proc.stderr.read()
    proc.stderr.close()
    assert proc.wait(timeout=60) == 0 and err == ""


def test_import_help_says_repeatable_only_where_it_is():
    done = run_cli("import", "--help")
    text = " ".join(done.stdout.split())
    # the antenna kinds and the two device-log kinds (several logs become one table)
    assert text.count("repeatable") == 4
    assert "(repeatable: one .pos per antenna)" in text


def test_library_chatter_stays_out_of_the_gui_log():
    pytest.importorskip("PySide6")
    import logging

    from hydrosync_gui.log_console import QtLogHandler

    handler = QtLogHandler()
    def record(name, level):
        return logging.LogRecord(name, level, __file__, 1, "m", None, None)
    assert not handler.filter(record("OpenGL.acceleratesupport", logging.INFO))
    assert handler.filter(record("OpenGL.acceleratesupport", logging.WARNING))
    assert handler.filter(record("hydrosync.latency", logging.INFO))
