"""GNSS Attitude panel: the static interval is dragged on the time series with the mouse."""

from __future__ import annotations

import json

import numpy as np
import pytest
from PySide6.QtCore import QEvent, QPoint, QPointF, Qt
from PySide6.QtGui import QCursor, QMouseEvent
from PySide6.QtWidgets import QApplication

from hydrosync_core.methods.gnss_attitude import project_run
from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams
from hydrosync_core.methods.gnss_attitude.simulate import ArrayConfig, simulate_array
from hydrosync_core.params import stored
from hydrosync_core.project import Project


@pytest.fixture()
def solved_project():
    sim = simulate_array(config=ArrayConfig(duration_s=300.0), seed=5)
    project = Project.new("attitude")
    for name, cols in sim["tracks"].items():
        project.put_table(f"{project_run.POS}/{name}", cols)
    project.put_json(project_run.ANTENNAS, {"frame": "FRD", "antennas": sim["antennas"]})
    project_run.run(project, GnssAttitudeParams())
    return project


def _send(widget, kind, pos: QPoint, buttons) -> None:
    button = Qt.MouseButton.LeftButton if kind != QEvent.Type.MouseMove else \
        Qt.MouseButton.NoButton
    event = QMouseEvent(kind, QPointF(pos), QPointF(widget.mapToGlobal(pos)), button,
                        buttons, Qt.KeyboardModifier.NoModifier)
    QApplication.sendEvent(widget, event)


@pytest.fixture()
def no_mouse_rate_limit():
    """pyqtgraph drops mouse moves closer than 1/mouseRateLimit s; synthetic ones are."""
    import pyqtgraph as pg

    old = pg.getConfigOption("mouseRateLimit")
    pg.setConfigOptions(mouseRateLimit=-1)
    yield
    pg.setConfigOptions(mouseRateLimit=old)


def drag(plot, x_from: float, x_to: float) -> None:
    """Press at view x *x_from*, move in steps to *x_to*, release (left button)."""
    vb = plot.getPlotItem().getViewBox()
    y = float(np.mean(vb.viewRange()[1]))

    def at(x):
        return plot.mapFromScene(vb.mapViewToScene(QPointF(x, y)))

    viewport = plot.viewport()
    left = Qt.MouseButton.LeftButton
    # pyqtgraph starts a drag on the item that accepted it in the last hover event, and
    # Qt only hovers the widget under the cursor: put the cursor there first
    QCursor.setPos(viewport.mapToGlobal(at(x_from)))
    QApplication.processEvents()
    _send(viewport, QEvent.Type.MouseMove, at(x_from), Qt.MouseButton.NoButton)
    _send(viewport, QEvent.Type.MouseButtonPress, at(x_from), left)
    for x in np.linspace(x_from, x_to, 8)[1:]:
        QCursor.setPos(viewport.mapToGlobal(at(x)))
        _send(viewport, QEvent.Type.MouseMove, at(x), left)
    _send(viewport, QEvent.Type.MouseButtonRelease, at(x_to), Qt.MouseButton.NoButton)


def test_drag_the_static_interval_updates_form_table_and_project(qtbot, solved_project,
                                                                  no_mouse_rate_limit):
    from plugins.gnss_attitude.panel import GnssAttitudePanel

    project = solved_project
    lsq_before = project.get_table(f"{project_run.RESULT}/lsq")["heading"].copy()
    panel = GnssAttitudePanel()
    qtbot.addWidget(panel)
    panel.resize(1200, 800)
    panel.set_project(project)
    panel.show()
    qtbot.waitExposed(panel)
    region = panel.regions["heading"]
    t0 = panel._t0
    # shrink to a 60 s interval programmatically first, then drag it 100 s to the right
    panel.set_static_interval(t0 + 20.0, t0 + 80.0)
    assert panel.current_stats["lsq"]["epochs"] == pytest.approx(61, abs=2)
    modified = []
    panel.sig_project_modified.connect(lambda: modified.append(1))
    plot = panel.series["heading"]
    plot.getPlotItem().getViewBox().setXRange(0, 300, padding=0)
    QApplication.processEvents()
    drag(plot, 50.0, 150.0)
    lo, hi = region.getRegion()
    assert lo == pytest.approx(120.0, abs=6.0) and hi - lo == pytest.approx(60.0, abs=0.5)
    # the other plots follow, the form and the stored parameters take the interval
    assert panel.regions["roll"].getRegion() == pytest.approx((lo, hi))
    values = panel.form.values()
    assert values["static_start_s"] == pytest.approx(lo + t0, abs=1e-3)
    assert values["static_end_s"] == pytest.approx(hi + t0, abs=1e-3)
    assert modified
    params = stored(GnssAttitudeParams, project, project_run.RESULT)
    assert params.static_start_s == pytest.approx(lo + t0, abs=1e-3)
    stats = json.loads(project.attrs(project_run.RESULT)["statistics"])
    assert stats == panel.current_stats
    expected = project_run.stored_statistics(project, lo + t0, hi + t0)
    assert stats["lsq"]["heading"]["std"] == pytest.approx(expected["lsq"]["heading"]["std"])
    # nothing was solved again
    np.testing.assert_array_equal(project.get_table(f"{project_run.RESULT}/lsq")["heading"],
                                  lsq_before)


def test_readonly_project_updates_the_table_only(qtbot, solved_project):
    from plugins.gnss_attitude.panel import GnssAttitudePanel

    project = solved_project
    before = project.attrs(project_run.RESULT)["statistics"]
    project.readonly = True
    panel = GnssAttitudePanel()
    qtbot.addWidget(panel)
    panel.set_project(project)
    t0 = panel._t0
    panel.set_static_interval(t0 + 100.0, t0 + 160.0)
    assert panel.current_stats["lsq"]["epochs"] == pytest.approx(61, abs=2)
    assert project.attrs(project_run.RESULT)["statistics"] == before


def test_statistics_table_reads_like_the_pdf(qtbot, solved_project):
    """Human labels with units, never raw keys; without a static interval the measured
    scatter is "—" with its reason, as in the PDF; with one, the numbers appear."""
    from plugins.gnss_attitude.panel import GnssAttitudePanel

    panel = GnssAttitudePanel()
    qtbot.addWidget(panel)
    panel.set_project(solved_project)
    model = panel.stats.table_model
    headers = [model.header(c) for c in range(model.columnCount())]
    assert headers[:4] == ["Method", "Epochs", "σ heading [°]", "predicted σ heading [°]"]
    assert not any("sd_" in h or "pred_" in h for h in headers)
    methods = [model.text(r, 0) for r in range(model.rowCount())]
    assert "least squares" in methods
    sd = headers.index("σ heading [°]")
    assert {model.text(r, sd) for r in range(model.rowCount())} == {"\u2014"}
    assert "moving platform" in model.headerData(sd, Qt.Orientation.Horizontal,
                                                 Qt.ItemDataRole.ToolTipRole)
    pred = model.text(methods.index("least squares"), headers.index("predicted σ heading [°]"))
    assert pred.replace(".", "", 1).isdigit() and len(pred.split(".")[1]) == 4
    start, end = project_run_times(solved_project)
    panel.set_static_interval(start, start + 0.3 * (end - start))
    assert model.text(methods.index("least squares"), sd) != "\u2014"


def project_run_times(project):
    t = project.get_table(f"{project_run.RESULT}/lsq")["time"]
    return float(np.nanmin(t)), float(np.nanmax(t))
