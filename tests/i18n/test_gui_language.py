"""View → Language: switching relabels the open window live, persists, and English returns.

Offscreen Qt. Each plugin panel is opened on its simulated demo data (no results, so the
panel shows only its own texts: forms, buttons, tabs, plot axes) and must then show no
English word in zh_CN but names and units.
"""

from __future__ import annotations

import re

import pytest
from PySide6.QtCore import QSettings
from PySide6.QtWidgets import QAbstractButton, QGroupBox, QLabel, QTabBar

from hydrosync_core.plugins import plugin_specs
from hydrosync_gui import i18n

CJK = re.compile(r"[\u4e00-\u9fff]")


@pytest.fixture
def settings(tmp_path) -> QSettings:
    return QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat)


@pytest.fixture
def window(qapp, qtbot, settings):
    from hydrosync_gui.main_window import MainWindow

    win = MainWindow(settings=settings)
    win.resize(1366, 768)
    qtbot.addWidget(win)
    win.show()
    yield win
    i18n.set_language("en")  # the language is application-wide: leave it English
    win.close_without_prompt()


def _texts(root) -> list[str]:
    """Visible texts of labels, buttons, group boxes and tabs under *root*."""
    out = []
    for widget in root.findChildren(QLabel) + root.findChildren(QAbstractButton):
        if widget.isVisibleTo(root) and widget.text():
            out.append(widget.text())
    out += [g.title() for g in root.findChildren(QGroupBox) if g.isVisibleTo(root)]
    for bar in root.findChildren(QTabBar):
        out += [bar.tabText(i) for i in range(bar.count())]
    return out


def _english(text: str) -> bool:
    """An English word of 4+ letters that is not a name (``N1_up_top``, ``A1,A2``) or
    the name of an acronym-led quantity."""
    plain = re.sub(r"<[^>]+>|&\w+;|--param \w+|\w*_\w*", " ", text)
    return bool(re.search(r"[A-Za-z]{4,}", plain)) and not CJK.search(plain)


def _open(window, spec, project):
    window.set_project(project)
    index = [window.tabs.tabText(i) for i in range(window.tabs.count())].index(
        i18n.tr(spec.name))
    window.tabs.setCurrentIndex(index)
    window.tabs.ensure_current()
    return window.tabs.currentWidget()


def test_switching_relabels_live_persists_and_returns_to_english(qtbot, window, settings):
    window.tabs.ensure_current()
    qtbot.waitUntil(lambda: not any("Loading…" in t for t in _texts(window)), timeout=20000)
    qtbot.wait(100)
    before = sorted(_texts(window))
    menus = [a.text() for a in window.menuBar().actions()]
    assert "&File" in menus and any("Step" in t for t in before)

    i18n.set_language("zh_CN", settings)
    qtbot.wait(50)
    during = _texts(window)
    assert "文件(&F)" in [a.text() for a in window.menuBar().actions()]
    assert any(t.startswith("步长") for t in during), "the Latency form was not relabelled"
    assert i18n.tr("Pool Calibration") in during  # the plugin tabs
    assert settings.value(i18n.SETTINGS_KEY) == "zh_CN"
    assert i18n.chosen_language(settings) == "zh_CN"
    # The View → Language menu offers both, each in its own language.
    names = [a.text() for a in window.language_menu.actions()]
    assert names == ["English", "简体中文"]

    i18n.set_language("en", settings)
    assert sorted(_texts(window)) == before  # English exactly as it was
    assert [a.text() for a in window.menuBar().actions()] == menus


@pytest.mark.parametrize("spec", [s for s in plugin_specs() if s.demo], ids=lambda s: s.id)
def test_every_panel_text_is_chinese(qtbot, window, settings, demo_project_of, spec):
    i18n.set_language("zh_CN", settings)
    panel = _open(window, spec, demo_project_of(spec))
    qtbot.wait(100)
    panel.grab()  # paint: texts set since are translated before they are seen
    # A label scrolled out of view is translated when it is painted on scrolling in; the
    # walk does now what that paint would do.
    i18n.relabel_all()
    left = [t for t in _texts(panel) if _english(t)]
    assert not left, f"{spec.id}: still English: {left[:8]}"


def test_report_action_follows_the_workbench_language(window):
    """The GUI's report export passes the workbench's language to build_report."""
    seen = {}

    def fake_build_report(project, path, progress=None, cancel=None, lang=None):
        seen["lang"] = lang
        return path

    i18n.set_language("zh_CN")
    window.export_report("/dev/null", fake_build_report)
    assert window.wait_idle(30)
    assert seen == {"lang": "zh_CN"}


def test_catalogue_compiles_or_falls_back(qapp, tmp_path, monkeypatch):
    """Without a built .qm the .ts is compiled with pyside6-lrelease; without lrelease the
    Python reader of the same .ts still translates."""
    import shutil as sh

    from PySide6.QtCore import QTranslator

    from hydrosync_core import i18n as core

    ts = tmp_path / "hydrosync_zh_CN.ts"
    sh.copy(core.catalogue_path("zh_CN"), ts)
    qm = i18n.compiled_catalogue(ts)
    if qm is None:
        pytest.skip("pyside6-lrelease is not available")
    translator = QTranslator()
    assert translator.load(str(qm))
    assert translator.translate(i18n.CONTEXT, "&File") == "文件(&F)"

    monkeypatch.setattr(i18n, "_lrelease", lambda: None)
    monkeypatch.setattr(i18n, "_compiled", {})
    ts.touch()
    assert i18n.compiled_catalogue(ts) is None
    monkeypatch.setattr(core, "catalogue_path", lambda lang: ts)
    try:
        i18n.set_language("zh_CN")
        assert i18n.tr("&File") == "文件(&F)"
        assert i18n.tr("page 2 of 9") == "第 2 页,共 9 页"
    finally:
        i18n.set_language("en")


def test_a_dialog_opened_in_chinese_is_chinese(qtbot, window, settings, demo_project_of):
    """Dialogs are relabelled when they are shown (the vessel sheet editor)."""
    from PySide6.QtCore import QTimer

    from hydrosync_gui.vessel_dialog import VesselDialog

    spec = next(s for s in plugin_specs() if s.id == "latency")
    i18n.set_language("zh_CN", settings)
    dialog = VesselDialog(demo_project_of(spec), "", window)
    seen = {}

    def look():
        seen["texts"] = _texts(dialog)
        dialog.reject()

    QTimer.singleShot(200, look)
    dialog.exec()
    assert any(t.startswith("添加传感器") for t in seen["texts"])
    left = [t for t in seen["texts"] if _english(t)]
    assert not left, f"still English: {left}"


@pytest.mark.parametrize("plugin", ["latency", "pool_calibration", "gnss_attitude",
                                    "gins_smoother", "tilt_alignment"])
def test_layout_harness_in_chinese(qtbot, window, settings, hydrosync_demo, plugin):
    """tests/gui/test_layout_harness.py's check at 1366×768 in zh_CN on the demo's results,
    every inner tab: the window still fits the screen, the panel shows its results in
    Chinese, and the Chinese texts clip nothing and push nothing out of reach or over
    another widget (squashed controls, small plots and legends are the panels' own layout,
    checked — with their known faults — in English by that harness)."""
    from PySide6.QtWidgets import QTabWidget

    from hydrosync_core.demo import DEMO_PROJECT
    from hydrosync_core.project import Project
    from hydrosync_gui.layout_check import check_layout

    i18n.set_language("zh_CN", settings)
    window.resize(1366, 768 - 32)
    window.set_project(Project.open(hydrosync_demo / DEMO_PROJECT, readonly=True))
    window.tabs.setCurrentIndex([e.spec.id for e in window.host.entries].index(plugin))
    window.tabs.ensure_current()
    panel = window.current_panel()

    def settle():
        qtbot.wait(30)
        assert window.wait_idle(60.0)
        qtbot.waitUntil(lambda: not getattr(panel, "_loading", False), timeout=60_000)
        window.grab()  # paint: every text in Chinese before it is measured
        qtbot.wait(30)

    settle()
    assert window.minimumSizeHint().height() <= 700  # leaves the log and status bar room
    assert CJK.search(" ".join(_texts(panel))), "the results are not shown in Chinese"
    problems = []
    tabs = [t for t in panel.findChildren(QTabWidget) if t.count() > 1]
    for widget in tabs or [None]:
        for i in range(widget.count() if widget else 1):
            if widget:
                widget.setCurrentIndex(i)
            settle()
            problems += [str(p) for p in check_layout(window)
                         if p.kind in ("clipped text", "outside", "overlap")
                         and (plugin, p.widget.split("/")[-2]) not in SQUASHED_ROWS]
    assert not problems, "\n".join(problems)


#: Rows the English harness already finds squashed (its KNOWN list: the Latency
#: parameter group is squashed at 1366×768, lever-arm row ~8 px high, latency owner);
#: their "not set" note is then clipped in any language.
SQUASHED_ROWS = {("latency", "param_lever_arm_m")}
