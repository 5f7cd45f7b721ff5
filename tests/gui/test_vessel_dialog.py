"""Edit → Vessel offsets…: editing, validation, JSON round trip, menu entry, Latency follow-up.

Settings isolation, scripted file dialogs and message boxes come from ``conftest.py``.
"""

from __future__ import annotations

import json
import os
import threading

import numpy as np
import pytest
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QDialog

from hydrosync_core.importers.vessel_json import read_vessel_json
from hydrosync_core.methods.latency.demo import fill_demo
from hydrosync_core.plugins.registry import Discovered
from hydrosync_core.project import Project
from hydrosync_core.project.vessel import lever_arm, set_sensor
from hydrosync_gui.vessel_dialog import VesselDialog

# Screenshots for docs/ only when asked: HYDROSYNC_SCREENSHOTS=docs pytest …
SCREENSHOT_DIR = os.environ.get("HYDROSYNC_SCREENSHOTS")


def _sheet_project() -> Project:
    """A saved-looking project with motion and gnss sensors (gnss carries an extra key)."""
    project = Project.new("boat")
    set_sensor(project, "motion", [0.0, 0.0, 0.0], {"roll": 0, "pitch": 0, "yaw": 0})
    set_sensor(project, "gnss", [-1.5, 2.0, -6.0], model="Trimble R10")
    project.dirty = False
    return project


@pytest.fixture
def dialog(qtbot):
    project = _sheet_project()
    widget = VesselDialog(project)
    qtbot.addWidget(widget)
    widget.show()
    yield widget
    widget.close()


def _row(dialog: VesselDialog, name: str) -> int:
    names = [dialog.table.item(r, 0).text() for r in range(dialog.table.rowCount())]
    return names.index(name)


def test_loads_sheet_and_shows_lever_arm(dialog):
    assert dialog.table.rowCount() == 2
    row = _row(dialog, "gnss")
    assert [dialog.table.item(row, c).text() for c in range(1, 7)] == \
        ["-1.5", "2", "-6", "", "", ""]
    assert "x = -1.500 m, y = 2.000 m, z = -6.000 m" in dialog.lever_label.text()
    assert dialog.message.text() == ""


def test_edit_add_rename_and_accept(dialog):
    project = dialog.project
    dialog.name_edit.setText("MV Test")
    row = _row(dialog, "gnss")
    dialog.set_cell(row, 1, "-2.25")
    dialog.set_cell(row, 3, "-6,5")  # decimal comma accepted
    dialog.set_cell(row, 0, "gnss")
    motion = _row(dialog, "motion")
    dialog.set_cell(motion, 2, "0.5")
    assert "x = -2.250 m, y = 1.500 m, z = -6.500 m" in dialog.lever_label.text()
    new = dialog.add_row()
    dialog.set_cell(new, 0, "multibeam")
    for column, text in zip(range(1, 7), ["1.2", "2.45", "1.8", "-35", "", "0.5"], strict=True):
        dialog.set_cell(new, column, text)
    dialog.buttons.button(dialog.buttons.StandardButton.Ok).click()
    assert dialog.result() == QDialog.DialogCode.Accepted and dialog.changed
    assert project.dirty
    sheet = project.get_json("vessel")
    assert sheet["name"] == "MV Test"
    assert sheet["frame"].startswith("body FRD")  # top-level keys kept
    assert sheet["sensors"]["gnss"]["model"] == "Trimble R10"  # unknown sensor key kept
    assert sheet["sensors"]["multibeam"] == {"offset_m": [1.2, 2.45, 1.8],
                                             "angles_deg": {"roll": -35.0, "yaw": 0.5}}
    np.testing.assert_allclose(lever_arm(project, "gnss", "motion"), [-2.25, 1.5, -6.5])


def test_rename_keeps_unknown_keys_and_remove(dialog):
    dialog.set_cell(_row(dialog, "gnss"), 0, "gnss_primary")
    dialog.table.selectRow(_row(dialog, "motion"))
    dialog.remove_selected()
    assert dialog.table.rowCount() == 1
    assert "needs sensors named 'gnss' and 'motion'" in dialog.lever_label.text()
    dialog.accept()
    sensors = dialog.project.get_json("vessel")["sensors"]
    assert list(sensors) == ["gnss_primary"]
    assert sensors["gnss_primary"] == {"offset_m": [-1.5, 2.0, -6.0], "model": "Trimble R10"}


def test_unchanged_ok_leaves_project_clean(dialog):
    dialog.accept()
    assert not dialog.changed and not dialog.project.dirty


@pytest.mark.parametrize("column, text, expected", [
    (2, "abc", "Row 2 ('gnss'), y stbd [m]: 'abc' is not a finite number."),
    (5, "nan", "Row 2 ('gnss'), pitch [°]: 'nan' is not a finite number."),
    (3, "", "Row 2 ('gnss'), z down [m]: a number is needed."),
    (0, "motion", "Row 2 ('motion'): the name 'motion' is already used in row 1; "
                  "sensor names must be unique."),
    (0, "  ", "Row 2: the sensor name is empty."),
])
def test_invalid_cell_is_rejected_with_message(dialog, column, text, expected):
    project = dialog.project
    before = project.get_json("vessel")
    row = _row(dialog, "gnss")
    assert row == 1
    dialog.set_cell(row, column, text)
    assert dialog.message.text() == expected  # shown while typing
    tinted = [(r, c) for r in range(2) for c in range(7)
              if dialog.table.item(r, c).background().style() != Qt.BrushStyle.NoBrush]
    assert tinted == [(row, column)]
    dialog.message.setText("")
    dialog.accept()
    assert dialog.message.text() == expected  # and again on OK, which is refused
    assert dialog.isVisible() and dialog.result() != QDialog.DialogCode.Accepted
    assert (dialog.table.currentRow(), dialog.table.currentColumn()) == (row, column)
    assert project.get_json("vessel") == before and not project.dirty
    dialog.set_cell(row, column, "gnss" if column == 0 else "1")  # fixed: tint goes
    assert dialog.message.text() == ""
    assert all(dialog.table.item(r, c).background().style() == Qt.BrushStyle.NoBrush
               for r in range(2) for c in range(7))


def test_export_import_round_trip(dialog, tmp_path, ui, qtbot):
    dialog.name_edit.setText("MV Round Trip")
    dialog.set_cell(_row(dialog, "gnss"), 4, "0.25")
    path = tmp_path / "sheet.json"
    ui.save_path = str(path)
    dialog.export_button.click()
    assert not path.with_name("sheet.json.tmp").exists()
    exported = dialog.sheet()[0]
    assert read_vessel_json(path) == exported  # the format read_vessel_json reads
    assert json.loads(path.read_text())["sensors"]["gnss"]["angles_deg"] == {"roll": 0.25}

    other = VesselDialog(Project.new("empty"))
    qtbot.addWidget(other)
    assert other.table.rowCount() == 0
    ui.open_path = str(path)
    other.import_button.click()
    assert other.sheet()[0] == exported
    assert other.name_edit.text() == "MV Round Trip"
    other.accept()
    np.testing.assert_allclose(lever_arm(other.project, "gnss", "motion"), [-1.5, 2.0, -6.0])


def test_bad_import_and_invalid_export_change_nothing(dialog, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"sensors": {"gnss": {"offset_m": [1, "x", 2]}}}')
    assert not dialog.import_json(bad)
    assert "bad.json" in dialog.message.text() and "sensors.gnss.offset_m" in dialog.message.text()
    assert dialog.table.rowCount() == 2
    dialog.set_cell(0, 1, "oops")
    target = tmp_path / "out.json"
    assert not dialog.export_json(target)
    assert dialog.message.text().startswith("Not exported. Row 1 ('motion'), x fwd [m]")
    assert not target.exists()


def test_screenshot(dialog, qtbot):
    dialog.add_row()
    dialog.set_cell(2, 0, "multibeam")
    for column, text in zip(range(1, 7), ["1.2", "2.45", "1.8", "-35", "0", "0"], strict=True):
        dialog.set_cell(2, column, text)
    dialog.set_cell(1, 2, "2.O")  # letter O: the message must name the row and field
    assert "Row 2 ('gnss'), y stbd [m]" in dialog.message.text()
    if SCREENSHOT_DIR:
        qtbot.wait(50)
        os.makedirs(SCREENSHOT_DIR, exist_ok=True)
        dialog.grab().save(os.path.join(SCREENSHOT_DIR, "vessel-dialog.png"))


# ------------------------------------------------------------------ main window
def _latency_discover():
    from plugins.latency import SPEC

    return [Discovered("latency", "plugins.latency:SPEC", SPEC, None)]


def _shown_arm(panel) -> list[float]:
    return [spin.value() for spin in panel.form.editors["lever_arm_m"].parts]


def test_menu_entry_opens_dialog_and_latency_follows(qtbot, make_window, monkeypatch):
    project = Project.new("demo")
    truth = fill_demo(project, seed=0)
    window = make_window(project, discover=_latency_discover)
    panel = window.current_panel()
    # No lever arm set: the panel shows the vessel sheet's, which a run would use.
    assert panel.form.values()["lever_arm_m"] is None
    assert _shown_arm(panel) == pytest.approx(truth["lever_arm_m"])
    assert window.act_vessel.isEnabled()
    assert window.act_vessel.text() == "&Vessel offsets…"
    assert "&Edit" in [a.text() for a in window.menuBar().actions()]
    opened = []

    def fake_exec(dialog):
        opened.append(dialog)
        row = _row(dialog, "gnss")
        for column, text in zip((1, 2, 3), ("0.5", "-1.25", "-7"), strict=True):
            dialog.set_cell(row, column, text)
        dialog.accept()
        return dialog.result()

    # A hand-typed lever arm survives a redraw; unset again, the sheet's is shown.
    panel.form.set_params({"lever_arm_m": [9.0, 0.0, 0.0]})
    window.host.refresh()
    assert panel.form.values()["lever_arm_m"] == (9.0, 0.0, 0.0)
    panel.form.set_params({"lever_arm_m": None})
    monkeypatch.setattr(VesselDialog, "exec", fake_exec)
    project.dirty = False
    window.setWindowModified(False)
    window.act_vessel.trigger()
    assert len(opened) == 1
    assert project.dirty and window.isWindowModified()
    np.testing.assert_allclose(lever_arm(project, "gnss", "motion"), [0.5, -1.25, -7.0])
    assert panel.form.values()["lever_arm_m"] is None
    assert _shown_arm(panel) == pytest.approx([0.5, -1.25, -7.0])


def test_menu_entry_disabled_while_task_runs(qtbot, make_window):
    window = make_window()
    assert window.act_vessel.isEnabled()
    release = threading.Event()
    window.run_shell_task("Busy", lambda progress, cancel: release.wait(10), lambda _r: None)
    assert not window.act_vessel.isEnabled()
    release.set()
    qtbot.waitUntil(lambda: not window.busy, timeout=5000)
    assert window.act_vessel.isEnabled()


def test_out_of_date_banner_and_browser_mark(qtbot, make_window):
    """Changing the vessel sheet after a run marks the latency result out of date."""
    from hydrosync_core.methods.latency.params import LatencyParams
    from hydrosync_core.methods.latency.project_run import run

    project = Project.new("demo")
    fill_demo(project, seed=0)
    run(project, LatencyParams(step_s=0.02))
    window = make_window(project, discover=_latency_discover)
    panel = window.current_panel()
    assert not panel.stale_banner.isVisible()
    assert "out of date" not in window.browser.row_texts("results/latency")[0]
    set_sensor(project, "gnss", [0.5, -1.25, -7.0])
    window.browser.refresh()
    window.host.refresh()
    assert panel.stale_banner.isVisible()
    assert "Out of date" in panel.stale_banner.text()
    assert "vessel sheet entry 'gnss'" in panel.stale_banner.text()
    assert window.browser.row_texts("results/latency")[0] == "latency (out of date)"


def test_schematic_labels_of_coincident_sensors_do_not_overprint(qtbot):
    from hydrosync_gui.vessel_view import VesselSchematic, label_groups

    assert label_groups(["ins", "motion", "gnss"], [0.0, 0.01, 2.0], [0.0, 0.0, -6.0], 0.1) \
        == [("ins, motion", 0.0, 0.0), ("gnss", 2.0, -6.0)]
    view = VesselSchematic()
    qtbot.addWidget(view)
    view.show_sensors({"ins": np.zeros(3), "motion": np.zeros(3),
                       "gnss": np.array([-1.5, 2.0, -6.0])})
    assert view.plan.labels == ["ins, motion", "gnss"]
