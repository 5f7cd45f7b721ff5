"""GUI test set-up: offscreen Qt, isolated settings, scripted dialogs, fake plugins.

Every test gets its own :class:`QSettings` file under ``tmp_path`` (the user's settings are
never touched), message boxes and file dialogs that answer from a script instead of
blocking, and a check that no worker thread is left running afterwards.
"""

from __future__ import annotations

import importlib.util
import os
import sys
from pathlib import Path

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from PySide6.QtCore import QCoreApplication, QEvent, QSettings, QThreadPool  # noqa: E402
from PySide6.QtWidgets import QApplication, QFileDialog, QMessageBox  # noqa: E402

from hydrosync_core.plugins.registry import Discovered  # noqa: E402
from hydrosync_core.project import Project  # noqa: E402

_spec = importlib.util.spec_from_file_location(
    "hydrosync_test_fake_plugin", Path(__file__).with_name("fake_plugin.py"))
fake_plugin = importlib.util.module_from_spec(_spec)
sys.modules["hydrosync_test_fake_plugin"] = fake_plugin
_spec.loader.exec_module(fake_plugin)


class ScriptedUI:
    """Records message boxes; answers questions and file dialogs from attributes."""

    def __init__(self) -> None:
        self.boxes: list[tuple[str, str, str]] = []  # (kind, title, text)
        self.answer = QMessageBox.StandardButton.Cancel
        self.questions = 0
        self.open_path = ""
        self.save_path = ""

    def record(self, kind: str, args) -> QMessageBox.StandardButton:
        title, text = (list(args[1:3]) + ["", ""])[:2]
        self.boxes.append((kind, str(title), str(text)))
        return QMessageBox.StandardButton.Ok

    def texts(self, kind: str) -> list[str]:
        return [text for k, _title, text in self.boxes if k == kind]


@pytest.fixture(autouse=True)
def ui(monkeypatch) -> ScriptedUI:
    script = ScriptedUI()
    for kind in ("warning", "critical", "information", "about"):
        monkeypatch.setattr(QMessageBox, kind,
                            staticmethod(lambda *a, _k=kind, **kw: script.record(_k, a)))

    def question(*args, **kwargs):
        script.questions += 1
        script.record("question", args)
        return script.answer

    monkeypatch.setattr(QMessageBox, "question", staticmethod(question))
    monkeypatch.setattr(QFileDialog, "getOpenFileName",
                        staticmethod(lambda *a, **k: (script.open_path, "")))
    monkeypatch.setattr(QFileDialog, "getSaveFileName",
                        staticmethod(lambda *a, **k: (script.save_path, "")))
    return script


@pytest.fixture
def settings(tmp_path) -> QSettings:
    return QSettings(str(tmp_path / "settings" / "hydrosync.ini"), QSettings.Format.IniFormat)


@pytest.fixture
def fake_discover():
    """Discovery returning two working fake plugins, one broken panel and one broken spec."""
    fake_plugin.FakePanel.instances = 0
    fake_plugin.SecondPanel.instances = 0
    found = [
        Discovered("fake", "hydrosync_test_fake_plugin:FAKE", fake_plugin.FAKE, None),
        Discovered("second", "hydrosync_test_fake_plugin:SECOND", fake_plugin.SECOND, None),
        Discovered("broken_panel", "hydrosync_test_fake_plugin:BROKEN_PANEL",
                   fake_plugin.BROKEN_PANEL, None),
        Discovered("broken", "broken_plugin:SPEC", None,
                   "ModuleNotFoundError: No module named 'broken_plugin'"),
    ]
    return lambda: list(found)


def _make_project(name: str = "survey") -> Project:
    """A small project: GNSS and attitude tables, a laser point array, a setup document."""
    project = Project.new(name)
    t = np.arange(1000) * 0.1
    project.put_table("raw/gnss", {"time": t, "height": 0.05 * np.sin(t)}, source="gnss.csv")
    project.put_table("raw/attitude", {
        "time": t, "roll": np.zeros_like(t), "pitch": np.zeros_like(t),
        "heading": np.full_like(t, 90.0), "heave": 0.05 * np.sin(t - 0.3)})
    project.put("raw/pool/lidar", np.zeros((500, 3)), attrs={"frame": "target ENU", "units": "m"})
    project.put_json("raw/pool/setup", {"boresight_deg": {"roll": 0.0, "pitch": 0.0, "yaw": 0.0}})
    return project


@pytest.fixture
def make_project():
    """Factory of the small sample project (unsaved, so marked modified)."""
    return _make_project


@pytest.fixture
def project_file(tmp_path) -> Path:
    path = tmp_path / "survey.h5"
    _make_project().save(path)
    return path


@pytest.fixture
def make_window(qapp, settings, fake_discover):
    """Factory of main windows, closed without prompt and deleted after the test."""
    from hydrosync_gui.main_window import MainWindow

    windows = []

    def make(project=None, discover=fake_discover, settings=settings):
        window = MainWindow(project, settings=settings, discover=discover)
        window.show()
        windows.append(window)
        return window

    yield make
    for window in windows:
        assert window.wait_idle(10.0)
        window.close_without_prompt()
        window.deleteLater()
    QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)
    QApplication.processEvents()


@pytest.fixture(autouse=True)
def no_leaked_threads(qapp):
    yield
    assert QThreadPool.globalInstance().waitForDone(10_000), "a worker is still running"
    QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)
    leaked = [w for w in QApplication.topLevelWidgets() if w.isVisible()]
    assert not leaked, f"widgets left open: {leaked}"
