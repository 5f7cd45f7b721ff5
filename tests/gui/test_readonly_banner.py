"""Issue #9 items 1 and 2 in the GUI: a project another HydroSync process is writing, or
a read-only file, opens read-only with a banner saying why; Save becomes Save As."""

from __future__ import annotations

import subprocess
import sys

import pytest

from hydrosync_core.project import Project
from tests.reliability.conftest import cli_env

pytestmark = pytest.mark.reliability


def _open(qtbot, window, path) -> None:
    window.open_project(str(path))
    qtbot.waitUntil(lambda: not window.busy, timeout=10000)


def test_project_locked_by_another_process_opens_read_only(qtbot, make_window, tmp_path, ui):
    path = tmp_path / "P.h5"
    Project.new("shared").save(path)
    code = ("import time\nfrom hydrosync_core.project import Project\n"
            f"p = Project.open({str(path)!r})\nprint('ready', flush=True)\ntime.sleep(60)\n")
    holder = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True,
                              env=cli_env())
    try:
        assert holder.stdout.readline().strip() == "ready"
        window = make_window()
        _open(qtbot, window, path)
        assert window.project.readonly
        assert not window.banner.isHidden()
        text = window.banner.text()
        assert f"being written by another HydroSync process (pid {holder.pid})" in text
        assert "(read-only)" in window.windowTitle()
        # Save becomes Save As: told why, then asked for a name.
        window.project.set_attrs("", name="edited")
        ui.save_path = str(tmp_path / "copy.h5")
        window._on_save()
        qtbot.waitUntil(lambda: not window.busy, timeout=10000)
        assert any("another file name" in t for t in ui.texts("information"))
        assert window.project.path == tmp_path / "copy.h5"
        assert not window.project.readonly and window.banner.isHidden()
        with Project.open(path, readonly=True) as original:
            assert original.name == "shared"  # the locked file is untouched
    finally:
        holder.kill()
        holder.communicate()


def test_read_only_file_opens_read_only(qtbot, make_window, tmp_path):
    path = tmp_path / "ro.h5"
    Project.new("ro").save(path)
    path.chmod(0o444)
    window = make_window()
    _open(qtbot, window, path)
    assert window.project.readonly
    assert "read-only (mode 444" in window.banner.text()
    # A writable project afterwards hides the banner again.
    other = tmp_path / "rw.h5"
    Project.new("rw").save(other)
    _open(qtbot, window, other)
    assert not window.project.readonly and window.banner.isHidden()
