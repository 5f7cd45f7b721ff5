"""The HydroSync main window: project browser, one tab per plugin, log, status bar.

Layout: the project browser docked left, a tab per plugin in the centre
(:class:`~hydrosync_gui.plugin_tabs.PluginTabs`: each panel is imported and created the
first time its tab is shown), the log
console docked at the bottom, and a status bar whose progress bar and Cancel button
follow the running task. File-menu behaviour lives in :mod:`hydrosync_gui.file_actions`.

While a shell task (open, save, import, report) runs, the browser and the panels are
disabled: the project may be rebinding in the worker and must not be touched.

A project opened read-only (another HydroSync process is writing it, or its file or
folder may not be written) shows a yellow banner above the tabs saying why; Save then
asks for another file name.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from pathlib import Path

from PySide6.QtCore import QSettings, Qt, QTimer, Slot
from PySide6.QtGui import QAction, QCloseEvent, QKeySequence
from PySide6.QtWidgets import (
    QDialog,
    QDockWidget,
    QLabel,
    QMainWindow,
    QMessageBox,
    QVBoxLayout,
    QWidget,
)

from hydrosync_core import __version__
from hydrosync_core.project import Project
from hydrosync_gui.dialogs import PluginsDialog
from hydrosync_gui.file_actions import UNTITLED, FileActions
from hydrosync_gui.i18n import add_language_menu
from hydrosync_gui.log_console import LogConsole
from hydrosync_gui.plugin_host import PluginHost
from hydrosync_gui.plugin_panel import PluginPanel
from hydrosync_gui.plugin_tabs import PluginTabs
from hydrosync_gui.project_browser import ProjectBrowser
from hydrosync_gui.recent_files import RecentFiles
from hydrosync_gui.resources import icon
from hydrosync_gui.task_status import TaskStatus
from hydrosync_gui.vessel_dialog import VesselDialog
from hydrosync_gui.window_geometry import (
    DOCK_WIDTH_WIDE,
    LOG_HEIGHT_TALL,
    PREFERRED,
    dock_width,
    fit_window,
    log_height,
)
from hydrosync_gui.workers import Worker, start

log = logging.getLogger("hydrosync_gui.main_window")
SHELL = "shell"  # task key of the window's own workers


class MainWindow(QMainWindow, FileActions):
    """The application window.

    Parameters
    ----------
    project : Project, optional
        Project to show; an empty unsaved one if None.
    settings : QSettings, optional
        Where geometry, recent files and the last directory are kept (tests pass one
        in a temporary file); the application's default settings if None.
    discover : callable, optional
        Plugin discovery function (see :class:`PluginHost`).
    """

    def __init__(self, project: Project | None = None, settings: QSettings | None = None,
                 discover: Callable | None = None) -> None:
        super().__init__()
        self.settings = settings if settings is not None else QSettings()
        self.recent = RecentFiles(self.settings)
        self.project: Project | None = None
        self.shell_worker: Worker | None = None
        self._close_ok = False
        self.setWindowIcon(icon("app.svg"))
        self.resize(PREFERRED)

        self.console = LogConsole()
        # The console shows debug lines only when the application logs them (-v).
        self.console.install(level=min(logging.INFO, logging.getLogger().level or logging.INFO))
        if logging.getLogger("hydrosync_gui").level == logging.NOTSET:
            logging.getLogger("hydrosync_gui").setLevel(logging.INFO)
        self.browser = ProjectBrowser()
        self.browser_dock = self._dock("Project", "project_dock", self.browser,
                                       Qt.DockWidgetArea.LeftDockWidgetArea)
        self.log_dock = self._dock("Log", "log_dock", self.console,
                                   Qt.DockWidgetArea.BottomDockWidgetArea)
        self.task_status = TaskStatus()
        self.statusBar().addPermanentWidget(self.task_status)

        self.host = PluginHost(discover, self)
        self.host.sig_status.connect(self._on_panel_status)
        self.host.sig_progress.connect(self._on_panel_progress)
        self.host.sig_busy.connect(self._on_panel_busy)
        self.host.sig_project_modified.connect(self._on_project_modified)
        self.host.load()
        self.tabs = PluginTabs(self.host)
        self.banner = QLabel()
        self.banner.setObjectName("readonly_banner")
        self.banner.setWordWrap(True)
        self.banner.setStyleSheet("QLabel#readonly_banner { background: #fff3c4; color: #5a4500;"
                                  " border-bottom: 1px solid #e0c060; padding: 6px 10px; }")
        self.banner.hide()
        central = QWidget()
        layout = QVBoxLayout(central)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(0)
        layout.addWidget(self.banner)
        layout.addWidget(self.tabs, 1)
        self.setCentralWidget(central)
        self._build_menus()
        self._restore_settings()
        if project is None:
            project = Project.new(UNTITLED)
            project.dirty = False  # an empty new project has nothing to lose
        self.set_project(project)
        self.tabs.ensure_current()  # the first tab's panel: it is shown from the start
        for fail in self.host.failed:
            self.statusBar().showMessage(f"Plugin '{fail.name}' failed to load "
                                         "(Help → Plugins)", 10000)

    # ------------------------------------------------------------- building
    def _dock(self, title: str, name: str, widget: QWidget, area) -> QDockWidget:
        dock = QDockWidget(title, self)
        dock.setObjectName(name)  # saveState needs names
        dock.setWidget(widget)
        self.addDockWidget(area, dock)
        return dock

    def _action(self, menu, text: str, slot, shortcut=None, tip: str = "") -> QAction:
        action = QAction(text, self)
        if shortcut is not None:
            action.setShortcut(QKeySequence(shortcut))
        action.setStatusTip(tip)
        action.triggered.connect(slot)
        menu.addAction(action)
        return action

    def _build_menus(self) -> None:
        m = self.menuBar().addMenu("&File")
        key = QKeySequence.StandardKey
        self.act_new = self._action(m, "&New", self._on_new, key.New, "Start an empty project")
        self.act_open = self._action(m, "&Open…", self._on_open, key.Open, "Open a project")
        self.recent_menu = m.addMenu("Open &Recent")
        self.recent_menu.aboutToShow.connect(self._fill_recent_menu)
        m.addSeparator()
        self.act_save = self._action(m, "&Save", self._on_save, key.Save, "Save the project")
        self.act_save_as = self._action(m, "Save &As…", self._on_save_as, key.SaveAs,
                                        "Save the project under a new name")
        m.addSeparator()
        self.act_import = self._action(m, "&Import…", self._on_import, "Ctrl+I",
                                       "Import a data file into the project")
        self.act_report = self._action(m, "&Export report…", self._on_export_report, "Ctrl+E",
                                       "Write the PDF report of the project")
        self.act_campaign = self._action(m, "Run &campaign…", self.open_campaign_dialog,
                                         tip="Run a campaign file (many projects x analyses) "
                                         "on Dask")
        self.campaign_dialog = None
        m.addSeparator()
        self._action(m, "&Quit", self.close, key.Quit, "Quit HydroSync")
        edit = self.menuBar().addMenu("&Edit")
        self.act_vessel = self._action(edit, "&Vessel offsets…", self.edit_vessel,
                                       tip="Sensor positions and mounting angles of the vessel")
        edit.aboutToShow.connect(self._update_edit_actions)
        view = self.menuBar().addMenu("&View")
        view.addAction(self.browser_dock.toggleViewAction())
        view.addAction(self.log_dock.toggleViewAction())
        view.addSeparator()
        self.language_menu = add_language_menu(view, self.settings)
        helpm = self.menuBar().addMenu("&Help")
        self._action(helpm, "&Plugins…", self.show_plugins, tip="Loaded and failed plugins")
        self._action(helpm, "&About HydroSync", self._on_about)
        self.plugins_dialog: PluginsDialog | None = None

    @Slot()
    def _fill_recent_menu(self) -> None:
        self.recent_menu.clear()
        files = self.recent.files()
        for number, path in enumerate(files, 1):
            action = self.recent_menu.addAction(f"&{number} {Path(path).name}")
            action.setToolTip(path)
            action.setStatusTip(path)
            action.triggered.connect(lambda _=False, p=path: self._on_open_recent(p))
        if not files:
            self.recent_menu.addAction("(no recent projects)").setEnabled(False)
        self.recent_menu.addSeparator()
        self.recent_menu.addAction("Clear list", self.recent.clear).setEnabled(bool(files))

    # -------------------------------------------------------------- project
    def set_project(self, project: Project) -> None:
        """Show *project* in the browser and every panel (closing the previous one)."""
        old, self.project = self.project, project
        self.host.set_project(project)
        self.browser.set_project(project)
        if old is not None and old is not project:
            old.close()
        self.update_title()
        self.update_banner()
        self._update_edit_actions()

    def update_banner(self) -> None:
        """Show why the project is read-only (and what to do), or hide the banner."""
        project = self.project
        if project is None or not project.readonly:
            self.banner.hide()
            return
        self.banner.setText(f"<b>Read-only.</b> {project.readonly_reason}. You can look at "
                            "the project and work with it; <b>Save</b> asks for another file "
                            "name (File → Save As…).")
        self.banner.show()

    def update_title(self) -> None:
        name = self.project.name if self.project is not None else ""
        if self.project is not None and self.project.readonly:
            self.setWindowTitle(f"HydroSync — {name or 'Untitled'} (read-only)[*]")
            self.setWindowModified(bool(self.project.dirty))
            return
        self.setWindowTitle(f"HydroSync — {name or 'Untitled'}[*]")
        self.setWindowModified(bool(self.project is not None and self.project.dirty))

    @Slot(object)
    def _on_project_modified(self, _panel) -> None:
        self.browser.refresh()
        self.update_title()
        self.setWindowModified(True)

    # ----------------------------------------------------------------- edit
    def _update_edit_actions(self) -> None:
        self.act_vessel.setEnabled(self.project is not None and not self.busy)

    @Slot()
    def edit_vessel(self) -> VesselDialog | None:
        """Edit → Vessel offsets…: the modal sheet editor; on OK refresh browser and panels."""
        if self.project is None or not self.ensure_idle():
            return None
        dialog = VesselDialog(self.project, self.last_dir(), self)
        try:
            if dialog.exec() == QDialog.DialogCode.Accepted and dialog.changed:
                # The path a panel's sig_project_modified takes, then every panel redraws.
                self._on_project_modified(None)
                self.host.refresh()
                self.statusBar().showMessage("Vessel offsets updated", 5000)
        finally:
            dialog.deleteLater()
        return dialog

    # ----------------------------------------------------------------- tabs
    def current_panel(self) -> PluginPanel | None:
        """The panel of the shown plugin tab (None if not created or failed)."""
        return self.tabs.current_panel()

    # ---------------------------------------------------------------- tasks
    @property
    def busy(self) -> bool:
        return self.task_status.busy

    def ensure_idle(self) -> bool:
        """True if no task runs; otherwise tell the user and return False."""
        if not self.busy:
            return True
        QMessageBox.information(self, "A task is running",
                                "Wait for the running task to finish, or press Cancel in "
                                "the status bar, then try again.")
        return False

    def run_shell_task(self, label: str, fn: Callable, on_finished: Callable,
                       on_failed: Callable[[str], None] | None = None,
                       cancellable: bool = False) -> Worker:
        """Run ``fn(progress, cancel)`` in a worker with the project locked.

        *on_finished(result)* or *on_failed(message)* runs on the GUI thread afterwards.
        """
        worker = Worker(fn)
        self.shell_worker = worker
        worker.signals.sig_progress.connect(
            lambda f, msg: self.task_status.update(SHELL, f, msg))
        worker.signals.sig_finished.connect(on_finished)
        worker.signals.sig_failed.connect(
            on_failed or (lambda msg: self.show_error(f"{label} failed", msg)))
        worker.signals.sig_cancelled.connect(lambda: log.info("%s: cancelled", label))
        worker.signals.sig_done.connect(self._on_shell_done)
        self.task_status.begin(SHELL, label, worker.cancel if cancellable else None)
        self._lock(True)
        log.info("%s…", label)
        return start(worker)

    @Slot()
    def _on_shell_done(self) -> None:
        self.task_status.end(SHELL)
        self._lock(False)

    def _lock(self, locked: bool) -> None:
        for widget in (self.tabs, self.browser):
            widget.setEnabled(not locked)
        self._update_edit_actions()

    @Slot(object, str)
    def _on_panel_status(self, panel: PluginPanel, message: str) -> None:
        name = panel.spec.name if panel.spec is not None else type(panel).__name__
        # Panels may name themselves already ("Latency started"): never "Latency: Latency".
        text = message if message.lower().startswith(name.lower()) else f"{name}: {message}"
        level = logging.WARNING if " failed" in message else logging.INFO
        logging.getLogger("hydrosync_gui.plugins").log(level, "%s", text)
        self.statusBar().showMessage(text, 8000)

    @Slot(object, float, str)
    def _on_panel_progress(self, panel: PluginPanel, fraction: float, message: str) -> None:
        self.task_status.update(panel, fraction, message)

    @Slot(object, bool)
    def _on_panel_busy(self, panel: PluginPanel, busy: bool) -> None:
        if busy:
            name = panel.spec.name if panel.spec is not None else type(panel).__name__
            self.task_status.begin(panel, name, panel.cancel_work)
        elif not panel.busy:  # a replaced task's late "done" must not hide its successor
            self.task_status.end(panel)
        self._update_edit_actions()

    def wait_idle(self, timeout: float = 30.0) -> bool:
        """Block until every panel and shell task has ended (shutdown and tests)."""
        ok = self.host.wait_idle(timeout)
        if self.shell_worker is not None:
            ok = self.shell_worker.finished_event.wait(timeout) and ok
        return ok

    # --------------------------------------------------------------- errors
    def show_error(self, title: str, message: str, level: int = logging.ERROR) -> None:
        """Log *message* and show it in a message box."""
        log.log(level, "%s: %s", title, message)
        QMessageBox.warning(self, title, message)

    # ------------------------------------------------------------- settings
    def last_dir(self) -> str:
        return str(self.settings.value("paths/last_dir", str(Path.home())))

    def remember_dir(self, path: str | Path) -> None:
        self.settings.setValue("paths/last_dir", str(Path(path).resolve().parent))

    def _restore_settings(self) -> None:
        """Saved geometry and dock layout, fitted to this screen (a geometry saved on a
        large monitor must not put the status bar below a laptop's screen)."""
        geometry = self.settings.value("window/geometry")
        restored = geometry is not None and self.restoreGeometry(geometry)
        state = self.settings.value("window/state")
        if state is None or not self.restoreState(state):
            screen = self.screen()
            available = screen.availableGeometry() if screen is not None else None
            width = dock_width(available) if available is not None else DOCK_WIDTH_WIDE
            height = log_height(available) if available is not None else LOG_HEIGHT_TALL
            self.resizeDocks([self.browser_dock], [width], Qt.Orientation.Horizontal)
            self.resizeDocks([self.log_dock], [height], Qt.Orientation.Vertical)
        fit_window(self, restored)

    def _save_settings(self) -> None:
        self.settings.setValue("window/geometry", self.saveGeometry())
        self.settings.setValue("window/state", self.saveState())
        self.settings.sync()

    # ----------------------------------------------------------------- help
    def open_campaign_dialog(self):
        """File → Run campaign…: the (non-modal) campaign dialog, made once."""
        from hydrosync_gui.campaign_dialog import CampaignDialog

        if self.campaign_dialog is None:
            self.campaign_dialog = CampaignDialog(self, self.last_dir())
        self.campaign_dialog.show()
        self.campaign_dialog.raise_()
        return self.campaign_dialog

    def show_plugins(self) -> PluginsDialog:
        """Open (non-modally) the list of loaded and failed plugins."""
        if self.plugins_dialog is not None:
            self.plugins_dialog.close()
            self.plugins_dialog.deleteLater()
        self.plugins_dialog = PluginsDialog(self.host, self)
        self.plugins_dialog.open()
        return self.plugins_dialog

    @Slot()
    def _on_about(self) -> None:
        QMessageBox.about(
            self, "About HydroSync",
            f"<h3>HydroSync {__version__}</h3><p>Sensor integration and calibration for "
            "hydrographic survey: latency between RTK heights and heave, pool calibration "
            "of multibeam / laser boresight and lever arms.</p><p>Body frame FRD, degrees "
            "at the edges, heave positive up.</p>",
        )

    # ---------------------------------------------------------------- close
    def close_without_prompt(self) -> None:
        """Close even with unsaved changes (tests, after the user chose Discard)."""
        self._close_ok = True
        self.close()

    def closeEvent(self, event: QCloseEvent) -> None:  # noqa: N802 - Qt override
        if not self._close_ok:
            if self.busy:
                answer = QMessageBox.question(
                    self, "A task is running", "Cancel the running task and quit?",
                    QMessageBox.StandardButton.Yes | QMessageBox.StandardButton.No,
                    QMessageBox.StandardButton.No)
                if answer != QMessageBox.StandardButton.Yes:
                    event.ignore()
                    return
                self.host.cancel_all()
                if self.shell_worker is not None:
                    self.shell_worker.cancel()
                self.wait_idle(60.0)
            if self.project is not None and self.project.dirty:
                event.ignore()
                # After the prompt (and a save if chosen) close again, without asking.
                self.maybe_save(lambda: QTimer.singleShot(0, self.close_without_prompt))
                return
        if self.campaign_dialog is not None:
            self.campaign_dialog.close()  # cancels a running campaign and waits for it
        self.host.cancel_all()
        self.wait_idle(60.0)
        self._save_settings()
        self.console.uninstall()
        if self.project is not None:
            self.project.close()
        event.accept()
