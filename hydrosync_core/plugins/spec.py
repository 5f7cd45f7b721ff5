"""The Qt-free declaration of an analysis plugin.

A plugin package exposes a :class:`PluginSpec` through the entry-point group
``hydrosync.plugins``. The spec names its core run function and its Qt panel by dotted
path (``"package.module:attribute"``); neither is imported until needed, so listing
plugins never imports Qt.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

ENTRY_POINT_GROUP = "hydrosync.plugins"


def load_object(dotted: str) -> Any:
    """Import ``"package.module:attr"`` and return the attribute."""
    module_name, _, attribute = dotted.partition(":")
    if not attribute:
        raise ValueError(f"'{dotted}' is not of the form 'module:attribute'")
    obj = importlib.import_module(module_name)
    for part in attribute.split("."):
        obj = getattr(obj, part)
    return obj


@dataclass(frozen=True)
class PluginSpec:
    """What a plugin declares.

    Attributes
    ----------
    id : str
        Stable identifier; results are stored under ``/results/<id>``.
    name : str
        Human name shown on the tab.
    run : str
        Dotted path of ``run(project, params, progress, cancel) -> result``: headless,
        reads its inputs from the project and stores its results there.
    panel : str
        Dotted path of the Qt panel class (constructed with no arguments).
    requires : tuple of str
        Project paths that must exist before :attr:`run` can work.
    icon : str
        File name under ``resources/icons``.
    description : str
        One sentence for tooltips and the plugin list.
    default_params : dict
        Parameters used when the caller passes none.
    demo : str
        Dotted path of ``fill_demo(project, seed=0, progress=None)`` that writes a
        simulated data set for this plugin into the project (used by ``hydrosync demo``
        and the contract tests). Empty if the plugin has no simulator.
    report_section : str
        Dotted path of ``section(project, ctx) -> list`` returning the reportlab
        flowables of this plugin's PDF report section. Empty for none.
    order : int
        Position among the tabs and report sections (lower first).
    """

    id: str
    name: str
    run: str
    panel: str
    requires: tuple[str, ...] = ()
    icon: str = ""
    description: str = ""
    default_params: dict = field(default_factory=dict)
    demo: str = ""
    report_section: str = ""
    order: int = 100

    def load_run(self) -> Callable:
        return load_object(self.run)

    def load_panel(self) -> type:
        return load_object(self.panel)

    def missing_inputs(self, project) -> list[str]:
        """The required project paths that *project* does not hold."""
        return [p for p in self.requires if not project.exists(p)]
