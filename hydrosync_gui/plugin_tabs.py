"""The central tab widget: one tab per plugin, each panel created when first shown.

Until its tab is shown a plugin is only its (Qt-free) spec: the tab holds a placeholder
with the plugin's name and description. Showing the tab asks the
:class:`~hydrosync_gui.plugin_host.PluginHost` for the panel (importing it then, as npe2
and Spyder do); a panel that fails to load leaves the error in the tab, and the other
tabs keep working. Tab text is ``spec.name``, the icon ``resources/icons/<spec.icon>``.
"""

from __future__ import annotations

from PySide6.QtCore import Qt, Slot
from PySide6.QtWidgets import QLabel, QScrollArea, QTabWidget, QVBoxLayout, QWidget

from hydrosync_gui.plugin_host import PluginEntry, PluginHost
from hydrosync_gui.plugin_panel import PluginPanel
from hydrosync_gui.resources import icon


class PluginTabs(QTabWidget):
    """Tabs over ``host.entries`` (in their order); see the module docstring."""

    def __init__(self, host: PluginHost, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.host = host
        self.setDocumentMode(True)
        self._placeholders: dict[int, QLabel] = {}
        for entry in host.entries:
            page = QWidget()
            layout = QVBoxLayout(page)
            layout.setContentsMargins(0, 0, 0, 0)
            label = self._label(f"<h3>{entry.name}</h3><p>{entry.spec.description}</p>"
                                "<p><i>Loading…</i></p>")
            layout.addWidget(label)
            index = self.addTab(page, icon(entry.spec.icon, "plugin.svg"), entry.name)
            self.setTabToolTip(index, entry.spec.description or entry.name)
            self._placeholders[index] = label
        if not host.entries:
            self.addTab(self._label("<h3>No analysis plugin is available</h3><p>See Help → "
                                    "Plugins and the log for what failed to load.</p>"),
                        "Welcome")
        self.currentChanged.connect(self._on_current_changed)

    @staticmethod
    def _label(html: str) -> QLabel:
        label = QLabel(html)
        label.setAlignment(Qt.AlignmentFlag.AlignCenter)
        label.setWordWrap(True)
        return label

    def entry_at(self, index: int) -> PluginEntry | None:
        entries = self.host.entries
        return entries[index] if 0 <= index < len(entries) else None

    def current_panel(self) -> PluginPanel | None:
        """The panel of the shown tab (None if not created or failed)."""
        entry = self.entry_at(self.currentIndex())
        return entry.panel if entry is not None else None

    def ensure_current(self) -> None:
        """Create the panel of the shown tab if not yet done (called once at start)."""
        self._on_current_changed(self.currentIndex())

    @Slot(int)
    def _on_current_changed(self, index: int) -> None:
        entry = self.entry_at(index)
        if entry is None or entry.panel is not None or entry.error is not None:
            return
        panel = self.host.panel(entry)
        label = self._placeholders.pop(index)
        if panel is None:
            label.setText(f"<h3>{entry.name}</h3><p style='color:#c00000'>This plugin's panel "
                          f"could not be loaded:</p><pre>{entry.error}</pre>"
                          "<p>Details are in the log.</p>")
            return
        layout = label.parentWidget().layout()
        layout.removeWidget(label)
        label.hide()  # until it is deleted it would lie over the panel at its old size
        label.deleteLater()
        layout.addWidget(panel.stale_banner)
        # A panel taller or wider than the screen scrolls instead of pushing the log,
        # status bar and Cancel off a 1366×768 laptop screen.
        scroll = QScrollArea()
        scroll.setWidget(panel)
        scroll.setWidgetResizable(True)
        scroll.setFrameShape(QScrollArea.Shape.NoFrame)
        scroll.setMinimumSize(320, 240)
        layout.addWidget(scroll, 1)
