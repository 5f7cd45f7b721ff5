"""File → Import… with device logs: several files of one kind, the geoid option, progress
and Cancel on the worker, and the streamed table moved into the project unread."""

from __future__ import annotations

import numpy as np

from hydrosync_core.importers import log_stream
from hydrosync_core.importers.log_import import import_attitude_log
from hydrosync_core.project.table_files import is_file_table
from tests.core.test_log_stream import awkward_log


def test_dialog_takes_several_logs_and_offers_the_geoid_choice(qtbot, tmp_path):
    from hydrosync_core.importers.kinds import KINDS
    from hydrosync_gui.dialogs import FILE_FILTER, ImportDialog

    dialog = ImportDialog(KINDS, str(tmp_path))
    qtbot.addWidget(dialog)
    dialog.show()
    dialog.kind_box.setCurrentIndex(dialog.kind_box.findData("gnss_log"))
    assert not dialog.geoid_box.isHidden() and dialog.heave_box.isHidden()
    dialog.path_edit.setText(f"{tmp_path / 'h01.log'}; {tmp_path / 'h00.log'}")
    dialog.geoid_box.setCurrentIndex(dialog.geoid_box.findData("skip"))
    kind, paths, options = dialog.choice()
    assert kind == "gnss_log" and paths == [str(tmp_path / "h01.log"), str(tmp_path / "h00.log")]
    assert options == {"empty_geoid": "skip"}
    for ext in ("*.log", "*.nmea", "*.raw", "*.pos", "*.csv", "*.las", "*.laz", "*.ply"):
        assert ext in FILE_FILTER
    dialog.grab().save(str(tmp_path / "import_dialog.png"))
    dialog.kind_box.setCurrentIndex(dialog.kind_box.findData("attitude_log"))
    assert dialog.geoid_box.isHidden() and not dialog.heave_box.isHidden()


def test_import_of_hourly_logs_runs_on_the_worker_into_one_table(qtbot, make_window, tmp_path,
                                                                 monkeypatch):
    from hydrosync_gui.dialogs import ImportDialog

    files = []
    for j in range(3):
        path = tmp_path / f"h{j:02d}.log"
        data = awkward_log(20.0, t0=20.0 * j, seed=j)
        path.write_bytes(data[: data.rfind(b"\n") + 1])
        files.append(str(path))
    monkeypatch.setattr(ImportDialog, "ask", classmethod(
        lambda cls, parent, kinds, start: ("attitude_log", files[::-1],
                                           {"heave_positive": "up"})))
    window = make_window()
    window._on_import()
    qtbot.waitUntil(lambda: not window.busy, timeout=30000)
    project = window.project
    assert is_file_table(project, "raw/attitude")  # moved as it is, not read
    t = project.get_table("raw/attitude")["time"]
    each = [import_attitude_log(f, "up")[1].used for f in files]
    assert t.size == sum(each) and np.all(np.diff(t) > 0)
    assert project.dirty
    window.grab().save(str(tmp_path / "window_after_import.png"))


def test_cancel_leaves_the_project_without_the_table(qtbot, make_window, tmp_path,
                                                     monkeypatch):
    from hydrosync_gui.dialogs import ImportDialog

    monkeypatch.setattr(log_stream, "BLOCK_BYTES", 512)  # thousands of blocks: time to cancel
    path = tmp_path / "day.log"
    path.write_bytes(awkward_log(120.0))
    monkeypatch.setattr(ImportDialog, "ask", classmethod(
        lambda cls, parent, kinds, start: ("attitude_log", str(path), {"heave_positive": "up"})))
    window = make_window()
    window._on_import()
    qtbot.waitUntil(lambda: window.task_status.bar.value() > 0, timeout=30000)
    window.shell_worker.cancel()
    qtbot.waitUntil(lambda: not window.busy, timeout=30000)
    assert not window.project.exists("raw/attitude")
