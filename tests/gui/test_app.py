"""``hydrosync-gui`` entry point and the exception hook."""

from __future__ import annotations

import logging

from PySide6.QtCore import QSettings, QTimer
from PySide6.QtWidgets import QApplication, QMessageBox

import hydrosync_core.plugins.registry as registry
from hydrosync_core.errors import InputError
from hydrosync_gui import app as app_module


def test_main_opens_the_project_given_on_the_command_line(
    qapp, tmp_path, project_file, monkeypatch, fake_discover
):
    for fmt in (QSettings.Format.NativeFormat, QSettings.Format.IniFormat):
        QSettings.setPath(fmt, QSettings.Scope.UserScope, str(tmp_path / "config"))
    monkeypatch.setattr(registry, "discover", fake_discover)
    names = (qapp.organizationName(), qapp.applicationName())
    seen = {}

    def poll() -> None:
        from hydrosync_gui.main_window import MainWindow

        windows = [w for w in qapp.topLevelWidgets() if isinstance(w, MainWindow)]
        if windows and windows[0].project.path == project_file and not windows[0].busy:
            window = windows[0]
            seen["title"] = window.windowTitle()
            seen["settings"] = window.settings.fileName()
            seen["plugins"] = [e.name for e in window.host.entries]
            window.close_without_prompt()
            window.deleteLater()
        else:
            QTimer.singleShot(20, poll)

    QTimer.singleShot(0, poll)
    QTimer.singleShot(10_000, qapp.quit)  # never hang the test run
    try:
        assert app_module.main([str(project_file)]) == 0
    finally:
        qapp.setOrganizationName(names[0])
        qapp.setApplicationName(names[1])
    assert seen["title"] == "HydroSync — survey[*]"
    assert seen["settings"].startswith(str(tmp_path / "config"))
    assert seen["plugins"] == ["Fake analysis", "Second analysis", "Broken panel"]


def test_excepthook_logs_and_shows_the_error(qapp, monkeypatch, caplog):
    shown = []
    monkeypatch.setattr(QMessageBox, "exec", lambda box: shown.append(box.text()) or 0)
    hook = app_module.excepthook_for(None)
    try:
        raise InputError("gnss.csv", "not a number", line=3, field="height")
    except InputError as exc:
        with caplog.at_level(logging.ERROR, logger="hydrosync_gui.app"):
            hook(type(exc), exc, exc.__traceback__)
    assert shown == ["gnss.csv:3: field 'height': not a number"]
    assert "Traceback" in caplog.text and "not a number" in caplog.text
    assert QApplication.instance() is qapp  # still alive
