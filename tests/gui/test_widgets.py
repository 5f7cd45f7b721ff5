"""Reusable widgets: parameter form, columns table, log console, task status."""

from __future__ import annotations

import logging
import threading
from dataclasses import dataclass

import numpy as np
import pytest
from PySide6.QtCore import Qt

from hydrosync_core.params import Params, param
from hydrosync_gui.log_console import LogConsole
from hydrosync_gui.task_status import TaskStatus
from hydrosync_gui.widgets import ColumnsTable, ParamForm


@dataclass(frozen=True)
class DemoParams(Params):
    max_lag: float = param(1.0, label="Max lag", unit="s", minimum=0.01, maximum=10.0)
    window: int = param(60, label="Window", unit="s", minimum=1, maximum=3600)
    detrend: bool = param(True, label="Detrend heights")
    method: str = param("xcorr", label="Method", choices=("xcorr", "lsq"))
    label: str = param("L01", label="Label")
    arm: tuple[float, float, float] | None = param(None, label="Lever arm", unit="m",
                                                   none_label="vessel sheet")
    bins: int = param(8, label="Bins", minimum=1, advanced=True, group="Detail")


def test_param_form_types_units_and_round_trip(qtbot):
    form = ParamForm(DemoParams)
    qtbot.addWidget(form)
    assert form.values() == {"max_lag": 1.0, "window": 60, "detrend": True, "method": "xcorr",
                             "label": "L01", "arm": None, "bins": 8}
    assert form.params() == DemoParams()
    assert form.editors["max_lag"].parts[0].suffix() == " s"
    assert form.editors["max_lag"].toolTip().endswith("(--param max_lag)")
    changes = []
    form.sig_changed.connect(lambda: changes.append(1))
    form.set_params({"max_lag": 20.0, "window": 5, "detrend": False, "method": "lsq",
                     "arm": [1.0, -2.0, 3.5], "unknown": 1})
    values = form.values()
    assert values["max_lag"] == 10.0  # clipped to the declared maximum
    assert values["arm"] == (1.0, -2.0, 3.5)
    assert type(values["window"]) is int and len(changes) >= 5
    form.set_params({"arm": None})
    assert form.values()["arm"] is None
    form.show_unset("arm", (9.0, 9.0, 9.0))  # shown, still not set
    assert form.values()["arm"] is None
    assert form.editors["arm"].parts[0].value() == 9.0


def test_param_form_advanced_fields_are_collapsed(qtbot):
    form = ParamForm(DemoParams)
    qtbot.addWidget(form)
    form.show()
    assert not form.editors["bins"].isVisible() and form.editors["max_lag"].isVisible()
    form.advanced_button.setChecked(True)
    assert form.editors["bins"].isVisible()


def test_columns_table_shows_columns_with_units_and_formats(qtbot):
    table = ColumnsTable()
    qtbot.addWidget(table)
    table.set_columns({"line": np.array(["L1", "L2"]), "latency": np.array([0.2876, np.nan]),
                       "n": np.array([120, 98])},
                      units={"latency": "s"}, formats={"latency": "{:.3f}"})
    model = table.table_model
    assert (model.rowCount(), model.columnCount()) == (2, 3)
    assert [model.headerData(c, Qt.Orientation.Horizontal) for c in range(3)] == [
        "line", "latency [s]", "n"]
    assert [[model.text(r, c) for c in range(3)] for r in range(2)] == [
        ["L1", "0.288", "120"], ["L2", "", "98"]]  # missing values are blank
    table.set_columns({"x": np.array([1.0, np.nan])})
    assert model.text(1, 0) == ""
    with pytest.raises(ValueError, match="different lengths"):
        table.set_columns({"a": np.zeros(2), "b": np.zeros(3)})
    table.clear()
    assert model.columnCount() == 0


def test_log_console_receives_records_from_worker_threads(qtbot):
    console = LogConsole()
    qtbot.addWidget(console)
    logger = logging.getLogger("hydrosync_test_console")
    logger.setLevel(logging.INFO)
    console.install(logger)
    thread = threading.Thread(target=lambda: logger.warning("from a worker %d", 7))
    thread.start()
    thread.join()
    logger.debug("below the level")
    qtbot.waitUntil(lambda: any("from a worker 7" in line for line in console.lines()))
    assert "WARNING hydrosync_test_console: from a worker 7" in console.lines()[-1]
    console.uninstall()
    assert console.handler not in logger.handlers
    logger.warning("after uninstall")
    qtbot.wait(20)
    assert not any("after uninstall" in line for line in console.lines())


def test_task_status_follows_the_latest_task(qtbot):
    status = TaskStatus()
    qtbot.addWidget(status)
    assert status.isHidden() and not status.busy
    cancelled = []
    status.begin("a", "Latency", lambda: cancelled.append("a"))
    assert not status.isHidden()
    status.begin("b", "Saving")  # not cancellable
    status.update("a", 0.5, "line 3")
    assert status.active() == "b" and status.label.text() == "Saving"
    assert not status.cancel_button.isEnabled()
    status.end("b")
    assert status.label.text() == "Latency: line 3" and status.bar.value() == 500
    status.cancel_button.click()
    assert cancelled == ["a"]
    status.end("a")
    assert status.isHidden()


def test_param_form_unbounded_tuple_fits_a_narrow_column(qtbot):
    """An unbounded float range must not size a box for 13 digits: a lever arm's three boxes
    fit beside their label in a 420 px column (the GNSS/INS panel at 1366 px scrolled
    sideways before)."""
    form = ParamForm(DemoParams)
    qtbot.addWidget(form)
    form.set_params({"arm": [0.0, 0.0, 0.0]})
    arm = form.editors["arm"]
    widths = [part.minimumWidth() or part.minimumSizeHint().width() for part in arm.parts]
    assert max(widths) < 100
    assert arm.minimumSizeHint().width() < 330
    form.set_params({"arm": [-123.456, 0.0, 999.999]})
    assert form.values()["arm"] == (-123.456, 0.0, 999.999)  # narrow, still every digit kept


def test_long_headers_wrap_onto_two_lines_when_asked(qtbot):
    """A wide header made a column of four-digit numbers 170 px wide (#26)."""
    from hydrosync_gui.widgets.columns_table import wrap_header

    assert wrap_header("predicted σ heading [°]") == "predicted σ\nheading [°]"
    assert wrap_header("Epochs") == "Epochs"
    assert wrap_header("σ heading [°]") == "σ heading [°]"  # short: one line
    assert wrap_header("Joint residual [mm]") == "Joint\nresidual [mm]"  # unit kept
    table = ColumnsTable(wrap_headers=True)
    qtbot.addWidget(table)
    values = {"pred_heading": np.array([0.112, 0.1477]), "n": np.array([592, 592])}
    labels = {"pred_heading": "predicted σ heading"}
    table.set_columns(values, units={"pred_heading": "°"}, labels=labels,
                      formats={"pred_heading": "{:.4f}"})
    model = table.table_model
    assert model.headerData(0, Qt.Orientation.Horizontal) == "predicted σ\nheading [°]"
    assert model.header(0) == "predicted σ heading [°]"
    plain = ColumnsTable()
    qtbot.addWidget(plain)
    plain.set_columns(values, units={"pred_heading": "°"}, labels=labels)
    table.show()
    plain.show()
    qtbot.wait(10)
    assert table.columnWidth(0) < plain.columnWidth(0)


def test_log_console_keeps_library_chatter_out(qtbot):
    """PyOpenGL's "OpenGL_accelerate module loaded" INFO line appeared at start-up (#26):
    other libraries' INFO lines stay out, their warnings and HydroSync's own lines show,
    and with -v (debug) everything shows."""
    console = LogConsole()
    qtbot.addWidget(console)
    root = logging.getLogger()
    old = root.level
    root.setLevel(logging.DEBUG)
    try:
        console.install(level=logging.INFO)
        logging.getLogger("OpenGL.acceleratesupport").info("OpenGL_accelerate module loaded")
        logging.getLogger("OpenGL.acceleratesupport").warning("no GL context")
        logging.getLogger("hydrosync_gui.plugin_host").info("opened panel 'Latency'")
        qtbot.waitUntil(lambda: len(console.lines()) == 2)
        assert [line.split(" ", 1)[1] for line in console.lines()] == [
            "WARNING OpenGL.acceleratesupport: no GL context",
            "INFO hydrosync_gui.plugin_host: opened panel 'Latency'"]
        console.install(level=logging.DEBUG)
        logging.getLogger("OpenGL.acceleratesupport").info("OpenGL_accelerate module loaded")
        qtbot.waitUntil(lambda: len(console.lines()) == 3)
    finally:
        console.uninstall()
        root.setLevel(old)


@pytest.mark.parametrize(("width", "wrapped"), [(260, True), (900, False)])
def test_param_form_rows_wrap_all_or_none(qtbot, width, wrapped):
    """In a narrow column every field goes under its label; in a wide one every field is
    beside it — never a mix of the two (#26)."""
    from PySide6.QtWidgets import QFormLayout, QScrollArea

    from hydrosync_core.methods.pool_calibration.params import PoolParams

    form = ParamForm(PoolParams)
    scroll = QScrollArea()  # as the panels hold it
    scroll.setWidget(form)
    scroll.setWidgetResizable(True)
    qtbot.addWidget(scroll)
    scroll.resize(width, 600)
    scroll.show()
    qtbot.wait(30)
    assert form.width() <= scroll.viewport().width()  # no horizontal scrolling
    policy = (QFormLayout.RowWrapPolicy.WrapAllRows if wrapped
              else QFormLayout.RowWrapPolicy.DontWrapRows)
    assert form.wrapped is wrapped
    assert {f.rowWrapPolicy() for f in form.forms} == {policy}
    qtbot.wait(20)
    # every visible editor starts at the same x within its form: all beside or all under
    for layout in form.forms:
        xs = {layout.itemAt(r, QFormLayout.ItemRole.FieldRole).widget().x()
              for r in range(layout.rowCount())
              if layout.itemAt(r, QFormLayout.ItemRole.LabelRole) is not None
              and layout.itemAt(r, QFormLayout.ItemRole.FieldRole).widget().isVisible()}
        assert len(xs) <= 1, xs


def test_choice_boxes_show_labels_and_return_values(qtbot):
    """"Reported method: lsq" showed the key; the box shows the words of the panel and PDF
    and the form still returns the key (#26)."""
    from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams

    labels = {"lsq": "least squares", "direct": "direct (3 antennas)"}
    form = ParamForm(GnssAttitudeParams, choice_labels={"method": labels})
    qtbot.addWidget(form)
    box = form.editors["method"].parts[0]
    assert box.currentText() == "least squares"
    assert form.values()["method"] == "lsq"
    form.set_params({"method": "direct"})
    assert box.currentText() == "direct (3 antennas)"
    assert form.params().method == "direct"
    assert [box.itemData(i) for i in range(box.count())] == list(
        GnssAttitudeParams.schema()[0].meta.choices)
