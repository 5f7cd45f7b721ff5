"""The Pool Calibration panel on an empty and a demo project (pytest-qt, offscreen).

One calibration per module: the module fixture runs ``project_run.run`` once on the demo
project with every third multibeam sounding (about 3 s); the panel tests then read that
stored result. Runs started from the panel work on saved copies so the shared project
stays as stored.
"""

from __future__ import annotations

import json
import os
from dataclasses import replace

import numpy as np
import pytest
from PySide6.QtCore import Qt

from hydrosync_core.methods.pool_calibration import project_run
from hydrosync_core.methods.pool_calibration.demo import DEMO_CONFIG, fill_demo
from hydrosync_core.methods.pool_calibration.project_run import PASSES, pass_names
from hydrosync_core.methods.pool_calibration.result import parameter_text
from hydrosync_core.project import Project
from plugins.pool_calibration.cloud_views import ProjectionView, gl_available
from plugins.pool_calibration.panel import PoolCalibrationPanel
from plugins.pool_calibration.views import FACE_COLUMNS, VALUE_ROWS

RESULT = "results/pool_calibration"
# Screenshots for docs/ only when asked: HYDROSYNC_SCREENSHOTS=docs pytest …
SCREENSHOT_DIR = os.environ.get("HYDROSYNC_SCREENSHOTS")
PLAN = ("laser_xyz", "laser_face", "mbes_before_xyz", "mbes_after_xyz", "mbes_face")


@pytest.fixture(scope="module")
def demo():
    """(project with a stored calibration, truth) — computed once for the module."""
    project = Project.new("pool demo")
    # The demo target (patent kind, three block pairs a side), two passes at 10 Hz: faster.
    truth = fill_demo(project, seed=0, config=replace(
        DEMO_CONFIG, ranges_m=(4.0, 6.0), headings_deg=(3.0, -3.0), ping_rate_hz=10.0))
    _thin(project)  # a third of the soundings: ~3x faster, still well determined
    project_run.run(project, {})
    return project, truth


@pytest.fixture
def panel(qtbot):
    idle = []
    widget = PoolCalibrationPanel()
    # No leaked thread: qtbot closes the widget after the test, once its worker is done.
    qtbot.addWidget(widget, before_close_func=lambda w: idle.append(w.wait_idle(60.0)))
    widget.resize(1400, 900)
    widget.show()
    yield widget
    assert widget.wait_idle(60.0)
    qtbot.wait(20)  # deliver the last worker signals while the widget is alive


def _copy(project: Project, tmp_path) -> Project:
    path = tmp_path / "copy.h5"
    project.save(path)
    return Project.open(path)


def _thin(project: Project, step: int = 3) -> None:
    """Keep every *step*-th multibeam sounding of every pass: a faster worker run."""
    for path in ["raw/pool/mbes"] + [f"{PASSES}/{k}/mbes" for k in pass_names(project)]:
        mbes = project.get_table(path)
        project.put_table(path, {k: v[::step] for k, v in mbes.items()})


def _snapshot(project: Project) -> dict:
    """Everything stored under the result, as comparable plain values."""
    out = {"attrs": dict(project.attrs(RESULT)),
           "faces": project.get_table(f"{RESULT}/faces"),
           "iterations": project.get_table(f"{RESULT}/iterations"),
           "result": project.get_json(f"{RESULT}/result")}
    out.update({k: project.get(f"{RESULT}/plan/{k}") for k in PLAN})
    return out


def _equal(x: np.ndarray, y: np.ndarray) -> bool:
    return np.array_equal(x, y, equal_nan=np.asarray(x).dtype.kind == "f")


def _same(a: dict, b: dict) -> bool:
    for key in a:
        x, y = a[key], b[key]
        if isinstance(x, dict) and key in ("faces", "iterations"):
            if x.keys() != y.keys() or not all(_equal(x[c], y[c]) for c in x):
                return False
        elif isinstance(x, np.ndarray):
            if not _equal(x, y):
                return False
        elif key == "attrs":
            if x.keys() != y.keys() or any(
                    not (x[k] == y[k] or (isinstance(x[k], float) and np.isnan(x[k])
                                          and np.isnan(y[k]))) for k in x):
                return False
        elif x != y:
            return False
    return True


def _shown(text: str) -> tuple[float, float]:
    """A number as shown and half a unit of its last decimal (its rounding)."""
    decimals = len(text.split(".")[1]) if "." in text else 0
    return float(text), 0.5 * 10.0 ** -decimals + 1e-12


def test_empty_project_needs_data(panel):
    panel.set_project(Project.new("empty"))
    text = panel.summary.text()
    assert "Needs data" in text
    for path in ("/raw/pool/lidar", "/raw/pool/mbes", "/raw/pool/ins", "/raw/pool/setup",
                 "/raw/pool/target"):
        assert path in text
    assert not panel.run_button.isEnabled() and not panel.segment_button.isEnabled()
    assert panel.face_table.model().rowCount() == 0
    assert panel.values.value(0, 0) == "–"
    assert not panel.warnings.isVisible()
    assert panel.cloud_box.stack.currentWidget() is panel.cloud_box.placeholder


def test_demo_results_shown(panel, demo, qtbot):
    project, truth = demo
    panel.set_project(project)
    attrs = project.attrs(RESULT)
    # The stored calibration is near the simulated truth (otherwise the checks below
    # would compare the panel with a broken result).
    for k in ("roll", "pitch", "yaw"):
        assert attrs[f"{k}_deg"] == pytest.approx(truth["boresight_deg"][k], abs=0.05)
    for k in "xyz":
        assert attrs[f"lever_{k}_m"] == pytest.approx(truth["lever_arm_m"][k], abs=0.01)

    # Face table: one row per stored face, every cell equal to the stored value.
    faces = project.get_table(f"{RESULT}/faces")
    model = panel.face_table.model()
    # The demo target is the patent's: wall + 6 blocks above water + 6 twins below.
    assert model.rowCount() == len(faces["face"]) == 49
    headers = [model.headerData(c, Qt.Orientation.Horizontal)
               for c in range(model.columnCount())]
    for col, key in enumerate(FACE_COLUMNS):
        header, unit, scale, _fmt = FACE_COLUMNS[key]
        assert headers[col].startswith(header)
        for row in range(model.rowCount()):
            text, stored = model.text(row, col), faces[key][row]
            if isinstance(stored, str | np.str_):
                assert text == stored
            elif np.issubdtype(np.asarray(stored).dtype, np.integer):
                assert int(text) == stored
            elif np.isnan(stored):
                assert text == ""
            else:
                assert float(text) / scale == pytest.approx(stored, abs=0.006 / scale)
    # Every below-water face seen by the multibeam names its above-water twin and the
    # design translation (the design height difference of the patent's step 4.2).
    names = [str(n) for n in faces["face"]]
    ref_col = list(FACE_COLUMNS).index("reference")
    row = names.index("N1_dn_top")
    assert model.text(row, ref_col) == "N1_up_top"
    du_col = list(FACE_COLUMNS).index("twin_du_m")
    assert float(model.text(row, du_col)) == pytest.approx(faces["twin_du_m"][row])
    assert model.text(names.index("wall"), ref_col) == "own"
    # The pairing column says which rule paired each face, or why none.
    pair_col = list(FACE_COLUMNS).index("pairing")
    assert model.text(row, pair_col) == "parallel offset with N1_up_top"
    assert model.text(names.index("N1_dn_bottom"), pair_col) == "unpaired: an underside"
    # Iteration table and convergence curves hold the stored iterations.
    iters = project.get_table(f"{RESULT}/iterations")
    assert panel.iteration_table.model().rowCount() == len(iters["iteration"]) > 3
    assert float(panel.iteration_table.model().text(0, 2)) == pytest.approx(
        iters["d_roll_deg"][0], rel=1e-2)
    x, y = panel.convergence.curves["d_yaw_deg"].getData()
    np.testing.assert_array_equal(x, iters["iteration"])
    # Log mode: the item holds log10 |Δ|.
    np.testing.assert_allclose(10 ** y, np.abs(iters["d_yaw_deg"]), rtol=1e-12)
    panel.log_check.setChecked(False)
    np.testing.assert_allclose(panel.convergence.curves["d_yaw_deg"].getData()[1],
                               iters["d_yaw_deg"])
    tol_x = panel.convergence.tolerance.getData()[0]
    assert tol_x is None or len(tol_x) == 0  # tolerance drawn in log scale only
    panel.log_check.setChecked(True)

    # Final values and σ as stored, to the digits σ supports — the very text the CLI and
    # the PDF print (parameter_text).
    result = project.get_json(f"{RESULT}/result")
    for row, (_label, key, group, unit) in enumerate(VALUE_ROWS):
        attr = f"{key}_deg" if unit == "°" else f"lever_{key}_m"
        value, tol = _shown(panel.values.value(row, 0))
        assert value == pytest.approx(attrs[attr], abs=tol)
        sigma_text = panel.values.value(row, 1).rstrip(" ⚑")
        assert float(sigma_text) == pytest.approx(attrs[f"sigma_{attr}"], abs=tol)
        assert (f"{panel.values.value(row, 0)} ± {sigma_text}"
                == parameter_text(attrs[attr], attrs[f"sigma_{attr}"], ""))
        # Seed, coarse and Δ to the same digits (one rounding each).
        assert float(panel.values.value(row, 2)) == pytest.approx(result["seed"][group][key],
                                                                  abs=tol)
        coarse = result["coarse"][group][key]
        assert float(panel.values.value(row, 3)) == pytest.approx(coarse, abs=tol)
        assert float(panel.values.value(row, 4)) == pytest.approx(attrs[attr] - coarse,
                                                                  abs=tol)
    # Warnings as stored: prominent box when present, hidden when none.
    warnings = json.loads(attrs["warnings"])
    assert panel.warnings.isVisible() == bool(warnings)
    for w in warnings:
        assert w in panel.warnings.text()
    assert "converged" in panel.summary.text()

    # Offscreen there is no GL context: the 2-D projections hold the stored plan arrays.
    assert not gl_available()
    view = panel.cloud_view
    assert isinstance(view, ProjectionView)
    plan = {k: project.get(f"{RESULT}/plan/{k}") for k in PLAN}
    assert set(view.laser_items) == set(np.unique(plan["laser_face"]).tolist())
    for k, (plan_item, section_item) in view.laser_items.items():
        pts = plan["laser_xyz"][plan["laser_face"] == k]
        np.testing.assert_array_equal(np.column_stack(plan_item.getData()), pts[:, :2])
        np.testing.assert_array_equal(np.column_stack(section_item.getData()), pts[:, 1:])
        assert faces["points_laser"][k] > 0  # plan face index k is faces-table row k
    assert sum(len(i[0].getData()[0]) for i in view.laser_items.values()) == len(
        plan["laser_xyz"])
    assert set(view.mbes_items) == set(np.unique(plan["mbes_face"]).tolist())
    for name in (str(faces["face"][k]) for k in view.laser_items):
        assert name in panel.cloud_box.legend.toolTip()  # the legend itself: by kind

    # Before/after toggle swaps the multibeam arrays (and only those).
    def mbes_xy(k):
        return np.column_stack(view.mbes_items[k][0].getData())

    k = int(np.flatnonzero(faces["points_mbes"])[0])
    rows = plan["mbes_face"] == k
    assert panel.after_radio.isChecked()  # fresh results open on the corrected soundings
    np.testing.assert_array_equal(mbes_xy(k), plan["mbes_after_xyz"][rows, :2])
    panel.before_radio.setChecked(True)
    np.testing.assert_array_equal(mbes_xy(k), plan["mbes_before_xyz"][rows, :2])
    laser_before = np.column_stack(view.laser_items[k][0].getData())
    panel.after_radio.setChecked(True)
    np.testing.assert_array_equal(mbes_xy(k), plan["mbes_after_xyz"][rows, :2])
    np.testing.assert_array_equal(
        np.column_stack(view.mbes_items[k][1].getData()), plan["mbes_after_xyz"][rows, 1:])
    np.testing.assert_array_equal(np.column_stack(view.laser_items[k][0].getData()),
                                  laser_before)
    assert np.abs(plan["mbes_after_xyz"] - plan["mbes_before_xyz"]).max() > 0.05
    panel.before_radio.setChecked(True)
    np.testing.assert_array_equal(mbes_xy(k), plan["mbes_before_xyz"][rows, :2])

    if SCREENSHOT_DIR:
        os.makedirs(SCREENSHOT_DIR, exist_ok=True)
        panel.after_radio.setChecked(True)
        qtbot.wait(150)  # let the layouts settle before the screenshot
        panel.grab().save(os.path.join(SCREENSHOT_DIR, "pool-panel.png"))


def test_parameters_loaded_from_stored_run(panel, demo):
    project, _truth = demo
    panel.set_project(project)
    stored = project.get_json(RESULT)
    values = panel.form.values()
    for key in ("crop_tol_m", "tol_deg", "max_iter", "final"):
        assert values[key] == stored[key]
    panel.form.set_params({"max_iter": 7, "final": "seed"})
    params = panel.params()
    assert params.max_iter == 7 and params.final == "seed"
    assert params.plan_points == 20000  # advanced field, at its default


def test_segment_then_run_in_worker(panel, demo, qtbot, tmp_path):
    project = _copy(demo[0], tmp_path)
    project.delete(RESULT)
    _thin(project)  # 1/9 of the demo soundings: the worker run only has to complete
    panel.set_project(project)
    assert "Data ready" in panel.summary.text()
    statuses = []
    panel.sig_status.connect(statuses.append)

    # Segment: a worker, results kept in memory only, faces with points listed.
    with qtbot.waitSignal(panel.sig_busy, timeout=60_000, check_params_cb=lambda b: not b):
        panel.segment_button.click()
        assert not panel.run_button.isEnabled()  # one task at a time
    assert panel.segmentation is not None and not project.exists(RESULT)
    faces = panel._preview[0]
    model = panel.face_table.model()
    assert model.rowCount() == len(panel.segmentation.design)
    wall = list(faces["face"]).index("wall")
    laser_col, mbes_col = (list(FACE_COLUMNS).index(k) for k in ("points_laser", "points_mbes"))
    assert int(model.text(wall, laser_col)) == len(panel.segmentation.laser_points["wall"]) > 1000
    assert int(model.text(wall, mbes_col)) == len(panel.segmentation.mbes_faces["wall"]) > 1000
    assert panel.cloud_box.stack.currentWidget() is panel.cloud_view
    assert any(s.startswith("Segmentation: wall") for s in statuses)
    assert not panel.after_radio.isEnabled()  # no corrected soundings yet
    assert panel.run_button.isEnabled() and panel.iterate_button.isEnabled()

    # Iterate on the kept segmentation: stores the same solution a direct
    # iterate_and_store on that segmentation gives (joint final values).
    modified = []
    panel.sig_project_modified.connect(lambda: modified.append(1))
    panel.iterate_button.click()
    qtbot.waitUntil(lambda: bool(modified), timeout=120_000)
    iterated = dict(project.attrs(RESULT))
    assert iterated["method"] == "joint"
    scratch = Project.new("scratch")
    expect = project_run.solve_and_store(scratch, panel.segmentation, panel.params())
    assert iterated["roll_deg"] == pytest.approx(expect.boresight_deg["roll"], abs=1e-9)
    assert iterated["lever_y_m"] == pytest.approx(expect.lever_arm_m["y"], abs=1e-12)
    assert np.isfinite(iterated["sigma_roll_deg"])

    # Run all: a worker writes the results, the panel redraws from them.
    modified.clear()
    panel.form.set_params({"final": "seed"})
    panel.run_button.click()
    qtbot.waitUntil(lambda: bool(modified), timeout=120_000)
    attrs = project.attrs(RESULT)
    assert attrs["method"] == "seed" and project.get_json(RESULT)["final"] == "seed"
    assert np.isnan(attrs["sigma_roll_deg"])  # joint σ do not describe the seed solution
    result = project.get_json(f"{RESULT}/result")
    for row, (_label, key, group, _unit) in enumerate(VALUE_ROWS):
        # Final = the seed solution, shown in both columns.
        assert panel.values.value(row, 0) == panel.values.value(row, 2)
        value, tol = _shown(panel.values.value(row, 0))
        assert value == pytest.approx(result["seed"][group][key], abs=tol)
    assert panel.face_table.model().rowCount() == 49
    assert panel.after_radio.isEnabled()
    assert any(s.startswith("Pool calibration: ") for s in statuses)


def test_cancel_right_after_start_keeps_project(panel, demo, qtbot, tmp_path):
    project = _copy(demo[0], tmp_path)
    before = _snapshot(project)
    panel.set_project(project)
    statuses, modified = [], []
    panel.sig_status.connect(statuses.append)
    panel.sig_project_modified.connect(lambda: modified.append(1))
    with qtbot.waitSignal(panel.sig_busy, timeout=30_000, check_params_cb=lambda b: not b):
        panel.run_button.click()
        panel.cancel_work()  # what the status bar's Cancel does
    assert "Pool calibration cancelled" in statuses
    assert not modified
    assert _same(before, _snapshot(project))
    assert panel.run_button.isEnabled() and panel.segment_button.isEnabled()
    assert panel.face_table.model().rowCount() == 49  # still showing the stored run


@pytest.mark.gl
def test_gl_view_toggle(panel, demo):
    if not gl_available():
        pytest.skip("no OpenGL context on this platform (offscreen): 2-D fallback tested")
    from plugins.pool_calibration.cloud_views import GLCloudView

    project, _truth = demo
    panel.set_project(project)
    view = panel.cloud_view
    assert isinstance(view, GLCloudView)
    np.testing.assert_allclose(view.mbes_item.pos,
                               project.get(f"{RESULT}/plan/mbes_after_xyz"), atol=1e-4)
    panel.before_radio.setChecked(True)
    np.testing.assert_allclose(view.mbes_item.pos,
                               project.get(f"{RESULT}/plan/mbes_before_xyz"), atol=1e-4)


def test_values_table_marks_undetermined_and_flagged(panel, demo):
    project, _truth = demo
    attrs = dict(project.attrs(RESULT))
    result = dict(project.get_json(f"{RESULT}/result"))
    result["undetermined"] = {"lever_z": "no horizontal face"}
    result["flagged"] = {"pitch": "σ = 0.03° exceeds 0.02°"}
    attrs["sigma_lever_z_m"] = float("nan")
    panel.values.fill(attrs, result)
    rows = [key for _label, key, _g, _u in VALUE_ROWS]
    assert panel.values.value(rows.index("z"), 1) == "undetermined"
    assert "no horizontal face" in panel.values.item(rows.index("z"), 1).toolTip()
    assert panel.values.value(rows.index("pitch"), 1).endswith("⚑")
    assert "exceeds" in panel.values.item(rows.index("pitch"), 1).toolTip()
    assert not panel.values.value(rows.index("roll"), 1).endswith("⚑")
