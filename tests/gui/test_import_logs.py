"""File → Import… with device logs: several files of one kind, the geoid option, progress
and Cancel on the worker, and the streamed table moved into the project unread."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

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
        lambda cls, parent, kinds, start: [("attitude_log", files[::-1],
                                           {"heave_positive": "up"})]))
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
        lambda cls, parent, kinds, start: [("attitude_log", str(path), {"heave_positive": "up"})]))
    window = make_window()
    window._on_import()
    qtbot.waitUntil(lambda: window.task_status.bar.value() > 0, timeout=30000)
    window.shell_worker.cancel()
    qtbot.waitUntil(lambda: not window.busy, timeout=30000)
    assert not window.project.exists("raw/attitude")


REAL_TAGGED = Path("/work/shared/data/real-logs/tagged")
SEAPATH = REAL_TAGGED / "openrvdas_NBP1406_seap-2014-08-01.txt"
GNSS_DAY = REAL_TAGGED / "openrvdas_NBP1406_PCOD-2014-08-01.txt"


def _hourly_folder(folder: Path, source: Path, parts: int = 4) -> list[Path]:
    """*source* cut at whole lines into *parts* files named as a logger names its hourly
    files (the real log is 17 min long: the cut, not the hour, is what is tested)."""
    folder.mkdir()
    lines = source.read_bytes().splitlines(keepends=True)
    step = -(-len(lines) // parts)
    out = []
    for j in range(parts):
        path = folder / f"PCOD-2014-08-01-{j:02d}.log"
        path.write_bytes(b"".join(lines[j * step:(j + 1) * step]))
        out.append(path)
    (folder / "notes.md").write_text("not a log: the folder takes only readable extensions")
    return out


@pytest.mark.skipif(not (SEAPATH.exists() and GNSS_DAY.exists()),
                    reason="the real tagged logs of /work/shared/data/real-logs are absent")
def test_dialog_previews_and_imports_the_seapath_log_and_a_folder_of_hourly_logs(
        qtbot, make_window, tmp_path, monkeypatch):
    """The preview shows each file's sentences and span before OK (read by a worker), the
    heave-sign note is not clipped, and OK imports both in one go: the Seapath log as the
    attitude table (its records as a direct import reads them), the four hourly files as
    one GNSS table equal to the day imported as one file."""
    from hydrosync_core.importers.kinds import KINDS
    from hydrosync_core.importers.log_import import import_gnss_log
    from hydrosync_gui.dialogs import ImportDialog

    hourly = _hourly_folder(tmp_path / "hourly", GNSS_DAY)
    dialog = ImportDialog(KINDS, str(tmp_path))
    qtbot.addWidget(dialog)
    dialog.show()
    dialog.kind_box.setCurrentIndex(dialog.kind_box.findData("attitude_log"))
    dialog.path_edit.setText(str(SEAPATH))
    qtbot.waitUntil(lambda: not dialog.preview.busy(), timeout=10000)
    (seap,) = dialog.preview.previews
    assert seap.sentences["PSXN,23"] == 714 and seap.sentences["GGA"] == 715
    assert seap.kinds == ("gnss_log", "attitude_log") and not seap.partial
    assert seap.span_text().startswith("2014-08-01 00:00:00 – 00:11:54 UTC")
    row = dialog.preview.tree.topLevelItem(0)
    assert "PSXN,23 714" in row.child(0).text(0) and "11 min 54 s" in row.text(2)
    assert dialog.heave_box.currentData() == "down"  # PSXN,23's documented sign
    note = dialog.heave_note
    assert note.height() >= note.heightForWidth(note.width()), "heave-sign note clipped"
    dialog.grab().save(str(tmp_path / "import_preview_seapath.png"))
    dialog.add_button.click()
    assert dialog.paths() == [] and dialog.queue_list.count() == 1

    dialog.kind_box.setCurrentIndex(dialog.kind_box.findData("gnss_log"))
    dialog.path_edit.setText(str(tmp_path / "hourly"))
    assert dialog.paths() == [str(p) for p in hourly]
    qtbot.waitUntil(lambda: not dialog.preview.busy(), timeout=10000)
    assert [p.kinds for p in dialog.preview.previews] == [("gnss_log",)] * 4
    assert sum(p.sentences["GGA"] for p in dialog.preview.previews) == 1000
    assert dialog.buttons.button(dialog.buttons.StandardButton.Ok).isEnabled()
    shot = dialog.grab()
    shot.save(str(tmp_path / "import_preview_hourly.png"))
    artifact = os.environ.get("HYDROSYNC_SCREENSHOTS")
    if artifact and Path(artifact).name != "docs":  # scripts/docs_screenshots.py
        Path(artifact).mkdir(parents=True, exist_ok=True)
        shot.save(str(Path(artifact) / "import-dialog-hourly.png"))
    choices = dialog.choices()
    assert [c[0] for c in choices] == ["attitude_log", "gnss_log"]

    monkeypatch.setattr(ImportDialog, "ask", classmethod(lambda cls, *a: choices))
    window = make_window()
    window._on_import()
    qtbot.waitUntil(lambda: window.project.exists("raw/gnss") and not window.busy,
                    timeout=60000)
    project = window.project
    attitude = project.get_table("raw/attitude")
    assert attitude["time"].size == import_attitude_log(SEAPATH, "down")[1].used
    whole, _ = import_gnss_log(GNSS_DAY)
    gnss = project.get_table("raw/gnss")
    np.testing.assert_array_equal(gnss["time"], whole["time"])
    np.testing.assert_array_equal(gnss["height"], whole["height"])


def test_preview_of_a_large_log_reads_its_two_ends(tmp_path):
    """Above twice the head size only both ends are read: the counts are of that part
    (flagged partial), the span still runs from the first to the last sentence."""
    from hydrosync_core.importers.log_preview import preview_file

    path = tmp_path / "day.log"
    data = awkward_log(120.0)
    path.write_bytes(data)
    whole = preview_file(path)
    part = preview_file(path, head=len(data) // 8)
    assert not whole.partial and part.partial
    assert part.first == whole.first and part.last == whole.last
    assert 0 < sum(part.sentences.values()) < sum(whole.sentences.values())
    assert part.kinds == whole.kinds and "attitude_log" in whole.kinds
    folder = preview_file(tmp_path)  # the input of a recording kind: described
    assert folder.error is None and folder.first_line == "folder of 1 file: day.log"
    assert folder.size == len(data)


def test_preview_marks_a_file_that_does_not_fit_the_kind(qtbot, tmp_path):
    """A heading-only log (HDT) chosen as a motion log is marked before OK; a missing
    file says why in its row, in one line."""
    from hydrosync_gui.import_preview import MISMATCH, ImportPreview

    log = tmp_path / "gyro.log"
    body = "HEHDT,218.83,T"
    checksum = 0
    for char in body:
        checksum ^= ord(char)
    log.write_text(f"${body}*{checksum:02X}\n" * 6)
    preview = ImportPreview()
    qtbot.addWidget(preview)
    preview.show_files([str(log), str(tmp_path / "gone.log")], "attitude_log")
    qtbot.waitUntil(lambda: not preview.busy(), timeout=10000)
    gyro, gone = preview.previews
    assert gyro.sentences.get("HDT", 0) >= 1 and gyro.kinds == ()
    assert "no such file" in gone.error
    row = preview.tree.topLevelItem(0)
    assert row.text(1) == "—"  # fits no import kind
    assert row.foreground(0).color() == MISMATCH
    assert "1 do not look like attitude_log" in preview.status.text()
    assert "1 cannot be read" in preview.status.text()
    missing = preview.tree.topLevelItem(1)
    assert "no such file" in missing.child(0).text(0)
    assert missing.foreground(0).color() != MISMATCH  # an error is red, not orange
    preview.show_files([str(log)], "csv_table_kind")  # a kind no sentence feeds
    qtbot.waitUntil(lambda: not preview.busy(), timeout=10000)
    assert "do not look like" in preview.status.text()


@pytest.mark.skipif(not GNSS_DAY.exists(), reason="the real tagged logs are absent")
def test_dialog_offers_the_kind_the_files_hold(qtbot, tmp_path):
    """A GNSS log chosen under the motion-log kind: the preview offers 'Import as
    gnss_log'; one click switches the kind, and the offer goes."""
    from hydrosync_core.importers.kinds import KINDS
    from hydrosync_gui.dialogs import ImportDialog

    dialog = ImportDialog(KINDS, str(tmp_path))
    qtbot.addWidget(dialog)
    dialog.show()
    dialog.kind_box.setCurrentIndex(dialog.kind_box.findData("attitude_log"))
    dialog.path_edit.setText(str(GNSS_DAY))
    qtbot.waitUntil(lambda: not dialog.preview.busy(), timeout=10000)
    assert dialog.guessed_kind() == "gnss_log"
    assert dialog.guess_button.isVisible() and "gnss_log" in dialog.guess_button.text()
    dialog.guess_button.click()
    assert dialog.kind_box.currentData() == "gnss_log"
    assert not dialog.guess_button.isVisible() and dialog.guessed_kind() is None
    dialog.path_edit.setText(str(SEAPATH))  # fits both log kinds: nothing to offer
    qtbot.waitUntil(lambda: not dialog.preview.busy(), timeout=10000)
    assert not dialog.guess_button.isVisible()


def test_a_replaced_survey_never_shows(qtbot, tmp_path, monkeypatch):
    """Files changed while their survey runs: only the new files' rows are shown."""
    import threading

    from hydrosync_gui import import_preview
    from hydrosync_gui.import_preview import ImportPreview

    first, second = tmp_path / "a.log", tmp_path / "b.log"
    first.write_bytes(awkward_log(60.0, seed=1))
    second.write_bytes(awkward_log(30.0, seed=2))
    # The first survey is held inside its first file until the files are replaced, so the
    # replacement always lands while it runs (a fast machine would otherwise finish it
    # before the test could replace anything).
    running, release = threading.Event(), threading.Event()
    real = import_preview.preview_file

    def held(path, cancel=None):
        if path == str(first):
            running.set()
            release.wait(10)
        return real(path, cancel)

    monkeypatch.setattr(import_preview, "preview_file", held)
    preview = ImportPreview()
    qtbot.addWidget(preview)
    preview.show_files([str(first)] * 3, "attitude_log")
    qtbot.waitUntil(running.is_set, timeout=10000)
    preview.show_files([str(second)], "attitude_log")
    release.set()
    qtbot.waitUntil(lambda: not preview.busy(), timeout=10000)
    qtbot.wait(100)  # any late signal of the first survey is delivered by now
    assert [p.path for p in preview.previews] == [str(second)]
    assert preview.tree.topLevelItemCount() == 1


def test_dialog_offers_a_recordings_clock_offset(qtbot, tmp_path):
    """A GNSS/INS recording folder takes a known GNSS−IMU clock offset (the CLI's
    ``--clock-offset``); left at its lowest value the offset is estimated, and no option
    goes to the reader. Other kinds never see the box."""
    from hydrosync_core.importers.kinds import KINDS
    from hydrosync_gui.dialogs import ImportDialog

    dialog = ImportDialog(KINDS, str(tmp_path))
    qtbot.addWidget(dialog)
    dialog.show()
    dialog.kind_box.setCurrentIndex(dialog.kind_box.findData("gnss_log"))
    assert dialog.clock_box.isHidden()
    dialog.kind_box.setCurrentIndex(dialog.kind_box.findData("gins_recording"))
    assert not dialog.clock_box.isHidden()
    dialog.path_edit.setText(str(tmp_path))
    assert dialog.clock_box.text() == "estimated from the turns"
    assert "clock_offset" not in dialog.choice()[2]
    dialog.clock_box.setValue(-0.25)
    assert dialog.choice()[2] == {"clock_offset": -0.25}


def test_dialog_imports_a_recording_folder_with_its_clock_offset(qtbot):
    """The walk recording through the dialog: the folder itself reaches the reader (not
    the files in it), with the offset typed in, as ``hydrosync import --gins-recording DIR
    --clock-offset S`` does; the stored IMU times move by exactly −S."""
    from hydrosync_core.datasets import shared_data_dir
    from hydrosync_core.importers.kinds import KINDS, import_file
    from hydrosync_core.project import Project
    from hydrosync_gui.dialogs import ImportDialog
    from hydrosync_gui.file_actions import _import_into_scratch

    walk = shared_data_dir() / "rtkexplorer-gnss-imu" / "walk_0827"
    if not walk.is_dir():
        pytest.skip(f"shared recording absent: {walk}")
    dialog = ImportDialog(KINDS, str(walk.parent))
    qtbot.addWidget(dialog)
    dialog.show()
    dialog.kind_box.setCurrentIndex(dialog.kind_box.findData("gins_recording"))
    dialog.path_edit.setText(str(walk))
    dialog.clock_box.setValue(0.25)
    kind, path, options = dialog.choice()
    assert (kind, path, options) == ("gins_recording", str(walk), {"clock_offset": 0.25})
    scratch, _ = _import_into_scratch(kind, path, options)
    plain = Project.new(name="plain")
    import_file(plain, kind, str(walk))
    shifted = scratch.get_table("raw/gins/imu")["time"]
    first = plain.get_table("raw/gins/imu")["time"]
    np.testing.assert_allclose(shifted - first, -0.25, atol=1e-9)
