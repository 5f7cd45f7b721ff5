"""Main window: loading a project, lazy plugin tabs, unsaved prompt, recent files,
worker progress and cancel, import/save/report error handling, failed plugins."""

from __future__ import annotations

import sys

import numpy as np
import pytest
from PySide6.QtCore import QSettings, Qt, QTimer
from PySide6.QtWidgets import QMessageBox

from hydrosync_core.project import Project
from hydrosync_gui.recent_files import RecentFiles

fake_plugin = sys.modules["hydrosync_test_fake_plugin"]
Button = QMessageBox.StandardButton


def open_and_wait(qtbot, window, path) -> None:
    window.open_project(str(path))
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)


def test_open_project_shows_groups_and_title(qtbot, make_window, project_file):
    window = make_window()
    assert window.windowTitle() == "HydroSync — Untitled[*]"
    assert not window.isWindowModified()
    open_and_wait(qtbot, window, project_file)

    assert window.project.path == project_file
    assert window.windowTitle() == "HydroSync — survey[*]"
    assert not window.isWindowModified()
    b = window.browser
    assert b.row_texts("raw") == ("raw", "group", "", "66.4 KiB")  # 16000 + 40000 + 12000 B
    assert b.row_texts("raw/gnss") == ("gnss", "table 1000 × 2", "", "15.6 KiB")
    assert b.row_texts("raw/gnss/height") == ("height", "1000", "float64", "7.8 KiB")
    assert b.row_texts("raw/attitude")[1] == "table 1000 × 5"
    assert b.row_texts("raw/pool/lidar") == ("lidar", "500 × 3", "float64", "11.7 KiB")
    assert b.row_texts("raw/pool/setup")[1] == "json"
    assert b.item("raw").isExpanded()
    # the open panel got the project
    panel = window.current_panel()
    assert panel.project is window.project
    assert panel.label.text() == "raw groups: 3"
    assert RecentFiles(window.settings).files() == [str(project_file.resolve())]


def test_panels_are_created_lazily(qtbot, make_window):
    window = make_window()
    assert fake_plugin.FakePanel.instances == 1  # the first tab is shown at start
    assert fake_plugin.SecondPanel.instances == 0
    assert window.host.entries[1].panel is None
    assert window.tabs.tabText(1) == "Second analysis"
    window.tabs.setCurrentIndex(1)
    assert fake_plugin.SecondPanel.instances == 1
    second = window.host.entries[1].panel
    assert second.project is window.project and second.refreshes == 1
    window.tabs.setCurrentIndex(0)
    window.tabs.setCurrentIndex(1)
    assert fake_plugin.SecondPanel.instances == 1  # created once


def test_failed_plugins_are_listed_and_logged(qtbot, make_window):
    window = make_window()
    window.tabs.setCurrentIndex(2)  # the panel whose constructor raises
    assert window.host.entries[2].error == "RuntimeError: panel exploded on purpose"
    dialog = window.show_plugins()
    rows = dialog.rows()
    assert ("Fake analysis (fake)", "loaded, panel open", "Fake analysis for tests") in rows
    assert ("Broken panel (broken_panel)", "panel failed",
            "RuntimeError: panel exploded on purpose") in rows
    broken = [r for r in rows if r[0] == "broken"]
    assert broken == [("broken", "failed to load",
                       "broken_plugin:SPEC: ModuleNotFoundError: No module named 'broken_plugin'")]
    qtbot.waitUntil(lambda: any("broken_plugin" in line for line in window.console.lines()))
    assert any("panel exploded on purpose" in line for line in window.console.lines())
    dialog.close()


def test_broken_panel_tab_shows_the_error(qtbot, make_window):
    from PySide6.QtWidgets import QLabel

    window = make_window()
    window.tabs.setCurrentIndex(2)
    labels = window.tabs.widget(2).findChildren(QLabel)
    assert any("panel exploded on purpose" in label.text() for label in labels)
    window.tabs.setCurrentIndex(0)  # the window still works
    assert window.current_panel() is not None


@pytest.mark.parametrize("answer", [Button.Save, Button.Discard, Button.Cancel])
def test_unsaved_changes_prompt_on_new(qtbot, make_window, project_file, ui, answer):
    window = make_window()
    open_and_wait(qtbot, window, project_file)
    window.project.put_table("raw/lines", {"start": np.array([0.0]), "end": np.array([5.0])})
    window.update_title()
    assert window.isWindowModified()
    ui.answer = answer
    window._on_new()
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert ui.questions == 1
    with Project.open(project_file) as on_disk:
        saved = on_disk.exists("raw/lines")
    if answer == Button.Cancel:
        assert window.project.path == project_file and window.project.dirty
        assert not saved
    else:
        assert window.project.path is None and window.project.name == "Untitled"
        assert not window.isWindowModified()
        assert saved == (answer == Button.Save)


def test_clean_project_is_replaced_without_prompt(qtbot, make_window, project_file, ui):
    window = make_window()
    open_and_wait(qtbot, window, project_file)
    window._on_new()
    assert ui.questions == 0 and window.project.path is None


@pytest.mark.parametrize("answer", [Button.Discard, Button.Cancel])
def test_close_with_unsaved_changes(qtbot, make_window, ui, answer, make_project):
    window = make_window(make_project())  # dirty: never saved
    ui.answer = answer
    window.close()
    qtbot.wait(50)
    assert ui.questions == 1
    assert window.isVisible() == (answer == Button.Cancel)


def test_open_recent_persistence(qtbot, make_window, tmp_path, settings):
    paths = []
    for i in range(10):
        path = tmp_path / f"p{i}.h5"
        Project.new(f"p{i}").save(path)
        paths.append(path)
    window = make_window()
    for path in paths[:3]:
        open_and_wait(qtbot, window, path)
    settings.sync()
    # a fresh QSettings on the same file sees the list, most recent first
    again = RecentFiles(QSettings(settings.fileName(), QSettings.Format.IniFormat))
    assert again.files() == [str(p.resolve()) for p in (paths[2], paths[1], paths[0])]
    window._fill_recent_menu()
    texts = [a.text() for a in window.recent_menu.actions() if a.text()]
    assert texts[:3] == ["&1 p2.h5", "&2 p1.h5", "&3 p0.h5"]
    paths[1].unlink()  # missing files are pruned
    assert again.files() == [str(paths[2].resolve()), str(paths[0].resolve())]
    for path in paths:  # at most 8
        again.add(path) if path.exists() else None
    assert len(again.files()) == 8 and again.files()[0] == str(paths[9].resolve())
    window._on_open_recent(str(paths[9].resolve()))  # the menu's action opens the file
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert window.project.name == "p9"


def test_worker_progress_cancel_and_responsiveness(qtbot, make_window):
    window = make_window()
    panel = window.current_panel()
    ticks = []
    timer = QTimer()
    timer.timeout.connect(lambda: ticks.append(1))
    timer.start(10)
    panel.run_job(steps=1000, dt=0.01)  # 10 s if not cancelled
    qtbot.waitUntil(lambda: window.task_status.bar.value() > 0, timeout=3000)
    assert window.busy and window.task_status.isVisible()
    assert window.task_status.cancel_button.isEnabled()
    assert "Fake analysis: step" in window.task_status.label.text()
    before = len(ticks)
    qtbot.wait(200)
    assert len(ticks) - before >= 5  # the event loop keeps running during the job
    qtbot.mouseClick(window.task_status.cancel_button, Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: not window.busy, timeout=3000)
    timer.stop()
    assert panel.finished_with is None
    assert not window.task_status.isVisible()
    assert not window.project.exists("results/fake")
    qtbot.waitUntil(lambda: any("Fake job cancelled" in line for line in window.console.lines()))


def test_panel_results_refresh_browser_and_mark_modified(qtbot, make_window, project_file):
    window = make_window()
    open_and_wait(qtbot, window, project_file)
    panel = window.current_panel()
    panel.run_job(steps=5, dt=0.001)
    qtbot.waitUntil(lambda: panel.finished_with is not None, timeout=3000)
    qtbot.waitUntil(lambda: not window.busy, timeout=3000)
    assert window.browser.row_texts("results/fake/out")[1] == "table 5 × 1"
    assert window.isWindowModified()


def test_import_good_and_bad_file(qtbot, make_window, tmp_path, ui):
    window = make_window()
    good = tmp_path / "gnss.csv"
    good.write_text("time,height\n0.0,1.5\n0.1,1.6\n0.2,1.7\n")
    bad = tmp_path / "bad.csv"
    bad.write_text("time,height\n0.0,1.5\n0.1,abc\n")
    window.import_data("gnss", str(bad))
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert not window.project.exists("raw/gnss") and not window.project.dirty
    [(kind, title, text)] = ui.boxes
    assert title == "Import failed" and "bad.csv:3" in text and "\n" not in text
    window.import_data("gnss", str(good))
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    np.testing.assert_allclose(window.project.get_table("raw/gnss")["height"], [1.5, 1.6, 1.7])
    assert window.browser.row_texts("raw/gnss")[1] == "table 3 × 2"
    assert window.isWindowModified()


def test_save_failure_keeps_the_project(qtbot, make_window, tmp_path, ui, make_project):
    window = make_window(make_project())
    ui.save_path = str(tmp_path / "no_such_dir" / "x.h5")
    window._on_save()
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert [b[1] for b in ui.boxes] == ["Save failed"]
    assert window.project.dirty and window.project.path is None
    assert window.project.get("raw/pool/lidar").shape == (500, 3)
    ui.save_path = str(tmp_path / "ok")  # suffix added
    window._on_save()
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert window.project.path == tmp_path / "ok.h5" and not window.isWindowModified()


def test_export_report_missing_and_present(
    qtbot, make_window, tmp_path, ui, monkeypatch, make_project
):
    import hydrosync_core.report as report

    window = make_window(make_project())
    monkeypatch.delattr(report, "build_report", raising=False)
    window._on_export_report()
    assert ui.boxes[-1][1] == "Report not available"
    assert "build_report" in ui.boxes[-1][2]

    calls = []

    def build_report(project, pdf_path, progress=None, cancel=None):
        progress(0.5, "half")
        calls.append((project, pdf_path, cancel.is_set()))
        with open(pdf_path, "wb") as fh:
            fh.write(b"%PDF-1.4\n")

    monkeypatch.setattr(report, "build_report", build_report, raising=False)
    ui.save_path = str(tmp_path / "r.pdf")
    window._on_export_report()
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert calls == [(window.project, str(tmp_path / "r.pdf"), False)]
    assert (tmp_path / "r.pdf").read_bytes().startswith(b"%PDF")


def test_geometry_is_persisted(qtbot, make_window, settings):
    window = make_window()
    window.resize(640, 480)  # within the offscreen screen
    window.close_without_prompt()
    assert settings.value("window/geometry") is not None
    again = make_window()
    assert (again.width(), again.height()) == (640, 480)


def test_import_dialog_choice_and_heave_sign(qtbot, tmp_path):
    from hydrosync_core.importers.kinds import KINDS
    from hydrosync_gui.dialogs import ImportDialog

    dialog = ImportDialog(KINDS, "/tmp")
    qtbot.addWidget(dialog)
    ok = dialog.buttons.button(dialog.buttons.StandardButton.Ok)
    assert not ok.isEnabled()  # no file yet
    dialog.kind_box.setCurrentIndex(dialog.kind_box.findData("attitude_log"))
    dialog.path_edit.setText(" /data/motion.log ")
    assert dialog.target.text() == "/raw/attitude"
    assert not dialog.heave_box.isHidden()
    # No sentence recognised (no such file): the sign must be chosen before OK.
    assert not ok.isEnabled() and "choose" in dialog.heave_note.text()
    dialog.heave_box.setCurrentIndex(dialog.heave_box.findData("down"))
    assert ok.isEnabled()
    assert dialog.choice() == ("attitude_log", "/data/motion.log", {"heave_positive": "down"})
    dialog.kind_box.setCurrentIndex(dialog.kind_box.findData("gnss"))
    assert dialog.heave_box.isHidden()
    assert dialog.choice() == ("gnss", "/data/motion.log", {})


@pytest.mark.parametrize(("sentence", "sign"), [
    ("$PSXN,23,0.12,-0.45,123.40,0.21*00", "down"),
    ("$PASHR,000000.00,123.40,T,0.12,-0.45,0.21,0.01,0.01,0.02,1,0*00", "up"),
])
def test_import_dialog_preselects_the_documented_sign(qtbot, tmp_path, sentence, sign):
    """A Seapath PSXN,23 log gets 'positive down' preselected: one click (OK) confirms; no
    command-line wording is shown."""
    from hydrosync_core.importers.kinds import KINDS
    from hydrosync_gui.dialogs import ImportDialog

    log = tmp_path / "motion.log"
    log.write_text("\n".join([sentence] * 20) + "\n")
    dialog = ImportDialog(KINDS, str(tmp_path))
    qtbot.addWidget(dialog)
    dialog.kind_box.setCurrentIndex(dialog.kind_box.findData("attitude_log"))
    dialog.path_edit.setText(str(log))
    assert dialog.heave_box.currentData() == sign
    assert dialog.buttons.button(dialog.buttons.StandardButton.Ok).isEnabled()
    note = dialog.heave_note.text()
    assert f"documented heave positive {sign}" in note and "Press OK to confirm" in note
    assert "--" not in note and "heave_positive" not in note
    assert dialog.choice()[2] == {"heave_positive": sign}


def test_import_menu_passes_heave_sign_to_the_motion_log_reader(
    qtbot, make_window, tmp_path, monkeypatch
):
    import hydrosync_core.importers.log_import as log_import
    from hydrosync_gui.dialogs import ImportDialog

    calls = []

    def store(project, target, path, **options):
        calls.append((target, path.name, options))
        project.put_table(target, {"time": np.array([0.0, 1.0]), "heave": np.array([0.1, 0.2])})
        return "2 records"

    monkeypatch.setattr(log_import, "store_attitude_log", store)
    (tmp_path / "m.log").write_text("$PSXN,23,0.1,0.2,90.0,0.1*00\n")  # checked to exist
    monkeypatch.setattr(ImportDialog, "ask", classmethod(
        lambda cls, parent, kinds, start: [("attitude_log", str(tmp_path / "m.log"),
                                           {"heave_positive": "up"})]))
    window = make_window()
    window._on_import()
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert calls == [("raw/attitude", "m.log", {"heave_positive": "up"})]
    assert window.browser.row_texts("raw/attitude")[1] == "table 2 × 2"


def test_restarting_a_panel_task_keeps_the_status_until_the_new_one_ends(qtbot, make_window):
    window = make_window()
    panel = window.current_panel()
    first = panel.run_job(steps=1000, dt=0.01)
    qtbot.waitUntil(lambda: window.task_status.bar.value() > 0, timeout=3000)
    panel.run_job(steps=30, dt=0.01)  # cancels the first
    assert first.finished_event.wait(3.0)
    qtbot.wait(50)  # the first task's late "done" signal is delivered
    assert window.busy or panel.finished_with is not None
    qtbot.waitUntil(lambda: panel.finished_with is not None, timeout=3000)
    qtbot.waitUntil(lambda: not window.busy, timeout=3000)
    assert panel.finished_with == {"steps": 30}


def test_open_missing_or_bad_file_reports_and_prunes_recent(qtbot, make_window, tmp_path, ui):
    window = make_window()
    bad = tmp_path / "not_a_project.h5"
    bad.write_text("hello")
    window.recent.add(bad)
    window.open_project(str(bad))
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    window.open_project(str(tmp_path / "gone.h5"))
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert [b[1] for b in ui.boxes] == ["Cannot open project", "Cannot open project"]
    assert "not_a_project.h5: not a readable HDF5 file" in ui.boxes[0][2]
    assert ui.boxes[1][2] == f"{tmp_path / 'gone.h5'}: no such project file"
    assert window.project.name == "Untitled"  # the current project stays
    assert window.recent.files() == [str(bad.resolve())]  # unreadable but existing: kept


def test_every_panel_fits_a_1366x768_screen(qtbot, make_window, hydrosync_demo):
    """With any tab shown the window's minimum size leaves room on a laptop screen (the
    log, status bar and Cancel stay visible): panels scroll instead of growing."""
    from hydrosync_core.demo import DEMO_PROJECT
    from hydrosync_core.plugins import discover

    project = Project.open(hydrosync_demo / DEMO_PROJECT, readonly=True)
    window = make_window(project, discover=discover)
    for index in range(window.tabs.count()):
        window.tabs.setCurrentIndex(index)
        qtbot.wait(10)
        hint = window.minimumSizeHint()
        assert hint.width() <= 1366 and hint.height() <= 700, (index, hint)


def test_status_bar_names_the_panel_once(qtbot, make_window):
    window = make_window()
    panel = window.current_panel()
    if panel is None:
        pytest.skip("no panel in the fake registry")
    name = panel.spec.name
    panel.sig_status.emit(f"{name} started")
    assert window.statusBar().currentMessage() == f"{name} started"
    panel.sig_status.emit("3 of 4 lines used")
    assert window.statusBar().currentMessage() == f"{name}: 3 of 4 lines used"


def test_save_as_names_an_untitled_project_after_its_file(qtbot, make_window, tmp_path, ui):
    """"Untitled" went on the title and the report cover after Save As (#26); a named
    project keeps its name, and a failed save gives the placeholder back."""
    window = make_window()
    window.project.put_json("raw/note", {"a": 1})
    ui.save_path = str(tmp_path / "no_such_dir" / "harbour.h5")
    window._on_save_as()
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert window.project.name == "Untitled"
    ui.save_path = str(tmp_path / "harbour-2026-11.h5")
    window._on_save_as()
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert window.project.name == "harbour-2026-11"
    assert window.windowTitle() == "HydroSync — harbour-2026-11[*]"
    assert Project.open(tmp_path / "harbour-2026-11.h5", readonly=True).name \
        == "harbour-2026-11"
    ui.save_path = str(tmp_path / "copy.h5")
    window._on_save_as()
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert window.project.name == "harbour-2026-11"  # a real name is the user's: kept


@pytest.mark.parametrize(("available", "wanted", "expected"), [
    # 1366×768 laptop, nothing saved: 1280 wide, as tall as the screen allows, centred.
    ((0, 0, 1366, 768), None, (43, 32, 1280, 728)),
    # A geometry saved on a 1920×1080 monitor, restored on the laptop: shrunk and moved.
    ((0, 0, 1366, 768), (300, 200, 1800, 1000), (8, 32, 1350, 728)),
    # A window partly off the right edge moves in; one that fits stays where it was.
    ((0, 0, 1920, 1080), (1500, 100, 1000, 700), (912, 100, 1000, 700)),
    ((0, 0, 1920, 1080), (100, 100, 1000, 700), (100, 100, 1000, 700)),
    # A second screen to the left (negative coordinates) with a task bar on top.
    ((-1366, 30, 1366, 738), (-2000, 0, 800, 600), (-1358, 62, 800, 600)),
])
def test_window_rectangle_fits_the_available_screen(available, wanted, expected):
    from PySide6.QtCore import QRect

    from hydrosync_gui.window_geometry import FRAME_ALLOWANCE, fit_rect

    area = QRect(*available)
    rect = fit_rect(area, QRect(*wanted) if wanted else None)
    assert (rect.x(), rect.y(), rect.width(), rect.height()) == expected
    frame = rect.adjusted(-FRAME_ALLOWANCE.width() // 2,
                          -(FRAME_ALLOWANCE.height() - FRAME_ALLOWANCE.width() // 2),
                          FRAME_ALLOWANCE.width() // 2, FRAME_ALLOWANCE.width() // 2)
    assert area.contains(frame), (frame, area)


def test_window_opens_inside_the_screen_and_restored_geometry_is_clamped(
        qtbot, make_window, settings):
    """The default 1280×800 put the status bar off a 768-pixel-high screen (#26)."""
    window = make_window()
    screen = window.screen().availableGeometry()
    assert screen.contains(window.geometry()), (window.geometry(), screen)
    assert window.statusBar().isVisible()
    window.setGeometry(50, 50, 4000, 3000)  # as if saved on a much larger monitor
    window.close_without_prompt()
    again = make_window()
    assert screen.contains(again.geometry()), (again.geometry(), screen)
    bar = again.statusBar()
    bottom_left = bar.mapTo(again, bar.rect().bottomLeft())
    assert again.geometry().top() + bottom_left.y() <= screen.bottom()


def test_project_dock_starts_narrow_on_a_small_screen():
    from PySide6.QtCore import QRect

    from hydrosync_gui.window_geometry import DOCK_WIDTH_NARROW, DOCK_WIDTH_WIDE, dock_width

    assert dock_width(QRect(0, 0, 1280, 720)) == DOCK_WIDTH_NARROW
    assert dock_width(QRect(0, 0, 1366, 736)) == DOCK_WIDTH_NARROW
    assert dock_width(QRect(0, 0, 1920, 1080)) == DOCK_WIDTH_WIDE
