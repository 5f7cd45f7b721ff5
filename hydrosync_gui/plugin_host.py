"""The plugin host: discovers plugins, creates their panels lazily, routes their signals.

Discovery (:func:`hydrosync_core.plugins.registry.discover`) never raises; a plugin whose
spec fails to load, or whose panel fails to import or construct, is kept in
:attr:`PluginHost.failed` with its one-line error so the GUI can list it (Help → Plugins)
and the log shows it, while every other plugin keeps working. A panel class is imported
only when :meth:`PluginHost.panel` is first called for it (when its tab is first shown),
as npe2 and Spyder do.
"""

from __future__ import annotations

import logging
from collections.abc import Callable
from dataclasses import dataclass

from PySide6.QtCore import QObject, Signal

from hydrosync_core.plugins import registry
from hydrosync_core.plugins.registry import Discovered
from hydrosync_core.plugins.spec import PluginSpec
from hydrosync_core.project import Project
from hydrosync_gui.plugin_panel import PluginPanel

log = logging.getLogger(__name__)


@dataclass
class PluginEntry:
    """A plugin whose spec loaded; its panel once created, or the error that stopped it."""

    discovered: Discovered
    panel: PluginPanel | None = None
    error: str | None = None

    @property
    def spec(self) -> PluginSpec:
        assert self.discovered.spec is not None
        return self.discovered.spec

    @property
    def name(self) -> str:
        return self.spec.name


@dataclass(frozen=True)
class FailedPlugin:
    """A plugin that could not be used: entry-point name, dotted value, one-line error."""

    name: str
    value: str
    error: str
    stage: str  # "spec" (discovery) or "panel" (import/construction of its panel)


class PluginHost(QObject):
    """Owns the plugin panels of one main window.

    Parameters
    ----------
    discover : callable, optional
        Returns a list of :class:`Discovered`; defaults to the entry-point registry
        (looked up when :meth:`load` runs, so tests may monkeypatch it).

    Signals
    -------
    sig_status(panel, message), sig_progress(panel, fraction, message),
    sig_busy(panel, busy), sig_project_modified(panel), sig_panel_created(entry)
    """

    sig_status = Signal(object, str)
    sig_progress = Signal(object, float, str)
    sig_busy = Signal(object, bool)
    sig_project_modified = Signal(object)
    sig_panel_created = Signal(object)

    def __init__(
        self,
        discover: Callable[[], list[Discovered]] | None = None,
        parent: QObject | None = None,
    ) -> None:
        super().__init__(parent)
        self._discover = discover
        self.entries: list[PluginEntry] = []
        self.failed: list[FailedPlugin] = []
        self.project: Project | None = None

    # ------------------------------------------------------------- discovery
    def load(self) -> None:
        """Discover the plugins (again); failed ones go to :attr:`failed` and the log."""
        registry_log = logging.getLogger(registry.__name__)
        quiet = self._discover is None and not registry_log.disabled
        try:
            # The registry logs each failure; the host logs it once below, in its words.
            registry_log.disabled = quiet
            found = (self._discover or registry.discover)()
        except Exception as exc:  # discovery must never stop the app
            log.error("plugin discovery failed: %s: %s", type(exc).__name__, exc)
            found = []
        finally:
            if quiet:
                registry_log.disabled = False
        self.entries = [PluginEntry(d) for d in found if d.spec is not None]
        self.failed = [
            FailedPlugin(d.entry_point, d.value, d.error or "unknown error", "spec")
            for d in found
            if d.spec is None
        ]
        for fail in self.failed:
            log.error("plugin '%s' (%s) is not available: %s", fail.name, fail.value, fail.error)
        log.info("plugins loaded: %s", ", ".join(e.name for e in self.entries) or "none")

    # ---------------------------------------------------------------- panels
    def panel(self, entry: PluginEntry) -> PluginPanel | None:
        """Return *entry*'s panel, importing and creating it on first call.

        Returns None if the panel cannot be created; the error is then in ``entry.error``,
        in :attr:`failed` and in the log.
        """
        if entry.panel is not None or entry.error is not None:
            return entry.panel
        spec = entry.spec
        try:
            cls = spec.load_panel()
            if not (isinstance(cls, type) and issubclass(cls, PluginPanel)):
                raise TypeError(f"{spec.panel} is not a PluginPanel subclass")
            panel = cls()
            if panel.spec is None:
                panel.spec = spec
        except Exception as exc:  # a third-party panel may fail in any way
            entry.error = f"{type(exc).__name__}: {exc}"
            self.failed.append(
                FailedPlugin(entry.discovered.entry_point, spec.panel, entry.error, "panel")
            )
            log.error("panel of plugin '%s' failed to load: %s", spec.name, entry.error)
            log.debug("traceback of the failed panel", exc_info=True)
            return None
        entry.panel = panel
        panel.sig_status.connect(lambda msg, p=panel: self.sig_status.emit(p, msg))
        panel.sig_progress.connect(lambda f, msg, p=panel: self.sig_progress.emit(p, f, msg))
        panel.sig_busy.connect(lambda busy, p=panel: self.sig_busy.emit(p, busy))
        panel.sig_project_modified.connect(lambda p=panel: self.sig_project_modified.emit(p))
        self._bind(entry)
        log.info("opened panel '%s'", spec.name)
        self.sig_panel_created.emit(entry)
        return panel

    def panels(self) -> list[PluginPanel]:
        """The panels created so far."""
        return [e.panel for e in self.entries if e.panel is not None]

    # --------------------------------------------------------------- project
    def set_project(self, project: Project | None) -> None:
        """Bind *project* to every created panel (new panels get it when created)."""
        self.project = project
        for entry in self.entries:
            if entry.panel is not None:
                self._bind(entry)

    def refresh(self) -> None:
        """Ask every created panel to redraw from the project."""
        for entry in self.entries:
            if entry.panel is not None:
                self._call(entry, entry.panel.refresh)
                self._call(entry, entry.panel.update_stale_banner)

    def _bind(self, entry: PluginEntry) -> None:
        panel = entry.panel
        assert panel is not None
        self._call(entry, lambda: panel.set_project(self.project))

    def _call(self, entry: PluginEntry, fn: Callable[[], object]) -> None:
        try:
            fn()
        except Exception as exc:  # a panel bug must not take the window down
            log.error("plugin '%s': %s: %s", entry.name, type(exc).__name__, exc)
            log.debug("traceback", exc_info=True)

    # ----------------------------------------------------------------- tasks
    def busy_panels(self) -> list[PluginPanel]:
        return [p for p in self.panels() if p.busy]

    def cancel_all(self) -> None:
        for panel in self.panels():
            panel.cancel_work()

    def wait_idle(self, timeout: float = 30.0) -> bool:
        """Block until every panel's task has ended (shutdown, tests)."""
        return all(p.wait_idle(timeout) for p in self.panels())
