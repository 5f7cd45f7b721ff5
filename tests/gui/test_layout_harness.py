"""The layout harness (#26): every analysis panel, with the demo's results, at 1366×768 and
1920×1080, checked for squashed controls, clipped text, widgets out of reach, overlaps and
clipped legends (:mod:`hydrosync_gui.layout_check`), each inner tab in turn.

Screenshots of every checked view are written to ``$HYDROSYNC_SCREENSHOTS`` (a folder;
default ``<pytest basetemp>/screenshots``) as ``<plugin>-<size>-<tab>.png``, and the view a
panel opens on as ``<plugin>-<size>.png``: the artifact a reviewer opens, and what
``make screenshots`` (``scripts/docs_screenshots.py``) copies into ``docs/``. With
``HYDROSYNC_SCREENSHOTS=docs`` (the convention of the panel tests) only
``docs/main-window-1366x768.png`` is written: the GNSS Attitude panel's first view.

The first tests check the checker itself on widgets built to fail, so that a harness that
finds nothing is known to be able to find something.
"""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

import pytest
from PySide6.QtCore import QEvent, QRect, QSize
from PySide6.QtWidgets import QApplication, QLabel, QPushButton, QTabWidget, QVBoxLayout, QWidget

from hydrosync_gui.layout_check import check_layout

SIZES = {"1366x768": QSize(1366, 768), "1920x1080": QSize(1920, 1080)}
DOCS_VIEW = ("gnss_attitude", "1366x768")  # the docs/ picture of the main window
TASK_BAR = 32  # pixels of a desktop's panel: what the window may not use
PLUGINS = ["latency", "pool_calibration", "gnss_attitude", "gins_smoother", "tilt_alignment"]
#: Known faults of a panel, with the reason (the test then expects them): none now.
KNOWN: dict[tuple[str, str], str] = {}


# ------------------------------------------------------------------- the checker
def _kinds(problems):
    return sorted({p.kind for p in problems})


def test_checker_finds_a_squashed_button_and_clipped_text(qtbot):
    root = QWidget()
    qtbot.addWidget(root)
    root.resize(300, 200)
    button = QPushButton("Run all analyses of the project", root)
    button.setGeometry(10, 10, 60, 12)  # narrower and lower than it needs
    label = QLabel("a long one-line note that cannot fit here", root)
    label.setGeometry(10, 40, 50, 20)
    wrapped = QLabel("a wrapped note " * 12, root)
    wrapped.setWordWrap(True)
    wrapped.setGeometry(10, 70, 120, 16)
    root.show()
    problems = check_layout(root)
    assert _kinds(problems) == ["clipped text", "squashed"], problems
    assert any("Run all" in p.widget for p in problems)
    assert len([p for p in problems if p.kind == "clipped text"]) == 2


def test_checker_finds_widgets_outside_and_overlapping(qtbot):
    root = QWidget()
    qtbot.addWidget(root)
    root.resize(200, 100)
    outside = QLabel("x", root)
    outside.setGeometry(180, 10, 60, 20)  # beyond the right edge, no scroll area
    root.show()
    assert _kinds(check_layout(root)) == ["outside"]

    box = QWidget()
    qtbot.addWidget(box)
    layout = QVBoxLayout(box)
    a, b = QLabel("a"), QLabel("b")
    layout.addWidget(a)
    layout.addWidget(b)
    box.show()
    qtbot.wait(10)
    b.setGeometry(a.geometry())  # as a broken layout would
    assert "overlap" in _kinds(check_layout(box))


def test_checker_finds_a_legend_bigger_than_its_plot(qtbot):
    import numpy as np

    from hydrosync_gui.analysis_panel import plot_widget

    plot = plot_widget("y", "x")
    qtbot.addWidget(plot)
    plot.resize(260, 180)
    for i in range(12):
        plot.plot(np.arange(3), np.arange(3) + i, name=f"forward smoothed series {i}")
    plot.show()
    qtbot.wait(50)
    problems = check_layout(plot)
    assert "legend" in _kinds(problems), problems


def test_checker_finds_raw_keys_in_table_headers(qtbot):
    import numpy as np

    from hydrosync_gui.widgets import ColumnsTable

    table = ColumnsTable()
    qtbot.addWidget(table)
    table.set_columns({"psi_deg": np.zeros(2), "sd_e_mm": np.zeros(2), "n": np.zeros(2)},
                      units={"sd_e_mm": "mm"}, labels={"n": "Vectors used"})
    table.resize(400, 200)
    table.show()
    problems = check_layout(table.parentWidget() or table)
    raw = sorted(p.detail for p in problems if p.kind == "raw label")
    assert raw == ["column header 'psi_deg' is a key, not words",
                   "column header 'sd_e_mm [mm]' is a key, not words"], problems


def test_checker_passes_a_plain_form(qtbot):
    from hydrosync_core.methods.latency.params import LatencyParams
    from hydrosync_gui.widgets import ParamForm

    form = ParamForm(LatencyParams)
    qtbot.addWidget(form)
    form.resize(form.sizeHint().expandedTo(QSize(420, 100)))
    form.show()
    qtbot.wait(20)
    assert check_layout(form) == []


# ------------------------------------------------------------------- the panels
@pytest.fixture(scope="session")
def screenshot_dir(tmp_path_factory) -> Path:
    folder = Path(os.environ.get("HYDROSYNC_SCREENSHOTS")
                  or tmp_path_factory.getbasetemp() / "screenshots")
    folder.mkdir(parents=True, exist_ok=True)
    return folder


def _settle(qtbot, window) -> None:
    qtbot.wait(30)
    assert window.wait_idle(60.0)
    panel = window.current_panel()
    # The Latency panel reads the raw series on a thread of its own (not a task).
    qtbot.waitUntil(lambda: not getattr(panel, "_loading", False), timeout=60_000)
    QApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)
    qtbot.wait(30)


def _views(panel: QWidget):
    """(name, select) for every tab of the panel's tab widgets (the panel itself if none)."""
    tabs = [t for t in panel.findChildren(QTabWidget) if t.count() > 1]
    if not tabs:
        yield "main", lambda: None
        return
    for widget in tabs:
        for i in range(widget.count()):
            yield widget.tabText(i), (lambda w=widget, i=i: w.setCurrentIndex(i))


@pytest.mark.parametrize("size", list(SIZES))
@pytest.mark.parametrize("plugin", PLUGINS)
def test_panel_lays_out_on_the_screen(qtbot, make_window, hydrosync_demo, screenshot_dir,
                                      tmp_path, plugin, size):
    """The window fills a screen of *size* (less a task bar) and the panel, bound to the
    demo's results, shows nothing squashed, clipped or out of reach in any of its tabs."""
    from hydrosync_core.demo import DEMO_PROJECT
    from hydrosync_core.plugins import discover
    from hydrosync_core.project import Project
    from hydrosync_gui.window_geometry import dock_width, fit_rect, log_height

    path = hydrosync_demo / DEMO_PROJECT
    if not path.exists():
        pytest.skip("the demo did not run: "
                    + (hydrosync_demo / "stderr.txt").read_text()[-300:])
    screen = QRect(0, 0, SIZES[size].width(), SIZES[size].height() - TASK_BAR)
    # A copy, opened as a user opens a project (no read-only banner); never saved.
    shutil.copy(path, tmp_path / DEMO_PROJECT)
    window = make_window(Project.open(tmp_path / DEMO_PROJECT), discover=discover)
    room = fit_rect(screen, preferred=screen.size())
    window.resize(room.size())
    window.resizeDocks([window.browser_dock], [dock_width(screen)], _horizontal())
    window.resizeDocks([window.log_dock], [log_height(screen)], _vertical())
    ids = [e.spec.id for e in window.host.entries]
    window.tabs.setCurrentIndex(ids.index(plugin))
    _settle(qtbot, window)
    panel = window.current_panel()
    assert panel is not None, f"the {plugin} panel did not load"
    problems = []
    views = list(_views(panel))
    for name, select in views:
        select()
        _settle(qtbot, window)
        slug = re.sub(r"\W+", "_", name).strip("_").lower()
        if screenshot_dir.name != "docs":
            shot = window.grab()
            shot.save(str(screenshot_dir / f"{plugin}-{size}-{slug}.png"))
            if name == views[0][0]:  # the panel as it opens: scripts/docs_screenshots.py
                shot.save(str(screenshot_dir / f"{plugin}-{size}.png"))
        elif (plugin, size) == DOCS_VIEW and name == views[0][0] and not problems:
            window.grab().save(str(screenshot_dir / "main-window-1366x768.png"))
        problems += [f"[{name}] {p}" for p in check_layout(window)]
    if problems and (plugin, size) in KNOWN:
        pytest.xfail(KNOWN[(plugin, size)])
    assert not problems, "\n".join(problems)


def _horizontal():
    from PySide6.QtCore import Qt

    return Qt.Orientation.Horizontal


def _vertical():
    from PySide6.QtCore import Qt

    return Qt.Orientation.Vertical
