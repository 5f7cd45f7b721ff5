"""Issue #9 item 8: Ctrl-C never prints a traceback, exits 130 with one line, and tells
the truth about what was saved — also while the modules load and inside an import."""

from __future__ import annotations

import os
import random
import shutil
import signal
import subprocess
import sys
import time

import pytest

from hydrosync_core import interrupts
from hydrosync_core.cli import main
from hydrosync_core.project import Project
from tests.reliability.conftest import (
    SCALE,
    cli_env,
    digest,
    sensors,
    start_cli,
    stderr_lines,
    temporaries,
)


def _check_interrupted(proc, path, sensor: str, before: str) -> list[str]:
    _, err = proc.communicate(timeout=60)
    lines = stderr_lines(err)
    problems = []
    if "Traceback" in err or len(lines) > 1:
        problems.append(f"more than one line: {err[-300:]!r}")
    if proc.returncode == 0:
        if sensor not in sensors(path):
            problems.append("exit 0 but the change is missing")
    elif proc.returncode == 130:
        message = lines[0] if lines else ""
        if "saved before the interrupt" in message:
            if sensor not in sensors(path):
                problems.append("says saved, but the change is missing")
        elif "nothing was saved" in message:
            if digest(path) != before:
                problems.append("says nothing was saved, but the file changed")
        else:
            problems.append(f"unexpected message {message!r}")
    else:
        problems.append(f"exit {proc.returncode}: {err[-300:]!r}")
    if temporaries(path.parent, path.name):
        problems.append("temporary left behind")
    return problems


def test_sigint_at_random_moments(tmp_path, big_project_template, faults):
    path = tmp_path / "P.h5"
    shutil.copyfile(big_project_template, path)
    # How long one run takes, to spread the interrupts over all of it.
    t0 = time.monotonic()
    proc = start_cli("vessel", path, "--set", "calibration", 0, 0, 0)
    proc.communicate(timeout=60)
    duration = time.monotonic() - t0
    rng = random.Random(8)
    for i in range(8 * SCALE):
        before = digest(path)
        proc = start_cli("vessel", path, "--set", f"s{i}", 1, 2, 3)
        time.sleep(rng.uniform(0.05, duration * 1.1))
        proc.send_signal(signal.SIGINT)
        problems = _check_interrupted(proc, path, f"s{i}", before)
        faults.record("SIGINT at a random moment", not problems, "; ".join(problems))
        assert not problems


def _interpreter_start_s() -> float:
    """How long the bare interpreter takes to start here and now (s): a signal before that
    lands in Python's own start-up, before any line of HydroSync can install a handler."""
    times = []
    for _ in range(3):
        t0 = time.monotonic()
        subprocess.run([sys.executable, "-c", "pass"], env=cli_env(), check=True)
        times.append(time.monotonic() - t0)
    return max(times)


def test_sigint_while_modules_load(tmp_path, faults):
    path = tmp_path / "P.h5"
    Project.new("x").save(path)
    rng = random.Random(5)
    for delay in [0.06, 0.1, 0.15, 0.2] + [rng.uniform(0.04, 0.3) for _ in range(4 * SCALE - 4)]:
        before = digest(path)
        # Delays count from the end of the interpreter's start (slow on a loaded machine).
        boot = _interpreter_start_s()
        proc = start_cli("vessel", path, "--set", "x", 1, 2, 3)
        time.sleep(boot + delay)
        proc.send_signal(signal.SIGINT)
        problems = _check_interrupted(proc, path, "x", before)
        faults.record("SIGINT while modules load", not problems, "; ".join(problems))
        assert not problems


def test_interrupt_turned_into_import_error_is_still_an_interrupt(tmp_path, monkeypatch,
                                                                  capsys):
    """A Ctrl-C during ``import open3d`` comes out as ImportError: still exit 130."""
    path = tmp_path / "P.h5"
    Project.new("x").save(path)
    real_open = Project.open

    def open_during_a_slow_import(*args, **kwargs):
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.5)  # the handler raises KeyboardInterrupt here
        except KeyboardInterrupt:
            raise ImportError("open3d: initialisation failed") from None
        return real_open(*args, **kwargs)

    monkeypatch.setattr(Project, "open", staticmethod(open_during_a_slow_import))
    assert main(["vessel", str(path), "--set", "gnss", "1", "2", "3"]) == 130
    err = capsys.readouterr().err
    assert stderr_lines(err) == ["hydrosync vessel: interrupted (Ctrl-C): cancelled, nothing "
                                 "was saved"]
    assert "ImportError" not in err


def test_interrupt_turned_into_a_corrupted_project_is_still_an_interrupt(tmp_path,
                                                                         monkeypatch, capsys):
    """A Ctrl-C inside h5py's lock comes out as SystemError ("... returned a result with an
    exception set"), which the opener reports as a corrupted project: the file is intact,
    so it is exit 130 and the interrupt message, never "corrupted project" and exit 2."""
    from hydrosync_core.errors import InputError

    path = tmp_path / "P.h5"
    Project.new("x").save(path)
    before = digest(path)

    def open_interrupted_inside_h5py(*args, **kwargs):
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.5)  # the handler raises KeyboardInterrupt here
        except KeyboardInterrupt:
            raise InputError(str(path), "corrupted project (<cyfunction FastRLock.__exit__> "
                             "returned a result with an exception set)") from None

    monkeypatch.setattr(Project, "open", staticmethod(open_interrupted_inside_h5py))
    assert main(["vessel", str(path), "--set", "gnss", "1", "2", "3"]) == 130
    err = capsys.readouterr().err
    assert stderr_lines(err) == ["hydrosync vessel: interrupted (Ctrl-C): cancelled, nothing "
                                 "was saved"]
    assert digest(path) == before


def test_interrupt_right_after_the_save_says_saved(tmp_path, monkeypatch, capsys):
    """The rename and its record are one step for Ctrl-C: a signal there is deferred."""
    path = tmp_path / "P.h5"
    Project.new("x").save(path)
    real_note = interrupts.note_completed

    def note_then_interrupt(target):
        os.kill(os.getpid(), signal.SIGINT)  # arrives inside the critical section
        time.sleep(0.05)
        real_note(target)

    monkeypatch.setattr(interrupts, "note_completed", note_then_interrupt)
    assert main(["vessel", str(path), "--set", "gnss", "1", "2", "3"]) == 130
    err = capsys.readouterr().err
    assert stderr_lines(err) == ["hydrosync vessel: interrupted (Ctrl-C); saved before the "
                                 "interrupt: P.h5"]
    assert sensors(path)["gnss"]["offset_m"] == [1.0, 2.0, 3.0]
    assert temporaries(tmp_path, "P.h5") == []


def test_interrupt_inside_a_finalizer_is_not_lost():
    """A Ctrl-C handled inside a weakref callback would be printed and dropped by Python:
    it is delivered again and surfaces in ordinary code."""
    import weakref

    class Thing:
        pass

    def finalizer_hit_by_ctrl_c():
        raise KeyboardInterrupt

    undo = interrupts.install()
    try:
        thing = Thing()
        weakref.finalize(thing, finalizer_hit_by_ctrl_c)
        with pytest.raises(KeyboardInterrupt):
            del thing
            for _ in range(200):
                time.sleep(0.005)
    finally:
        undo()


def test_main_restores_the_previous_sigint_handler(tmp_path):
    previous = signal.getsignal(signal.SIGINT)
    path = tmp_path / "P.h5"
    Project.new("x").save(path)
    assert main(["info", str(path)]) == 0
    assert signal.getsignal(signal.SIGINT) is previous


@pytest.fixture(autouse=True)
def _reset_interrupts():
    yield
    interrupts.reset()
