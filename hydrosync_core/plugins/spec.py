"""The Qt-free declaration of an analysis plugin.

A plugin package exposes a :class:`PluginSpec` through the entry-point group
``hydrosync.plugins``. Everything the host needs from an analysis is declared here by
dotted path (``"package.module:attribute"``) and imported only when used: listing plugins
loads neither Qt nor scipy/open3d nor the method modules (a test checks it). Adding an
analysis therefore touches no shared file: its command, data kinds, parameters, demo,
report section and panel all come through its spec (``docs/plugins.md``).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

ENTRY_POINT_GROUP = "hydrosync.plugins"

#: Version of the contract between the host and a spec; a spec declaring another major
#: version is refused at discovery with a clear message.
API_VERSION = 1


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
class DataKind:
    """A kind of input file an analysis imports (``hydrosync import P --<name> FILE``).

    Attributes
    ----------
    name : str
        Option name (``gnss`` → ``--gnss``); unique across plugins unless two plugins
        declare the same kind with the same *target*.
    description : str
        One line for ``--help`` and the Import dialog.
    target : str
        Project path the data lands in (``raw/gnss``).
    reader : str
        Dotted path of ``read(path) -> data`` (a dict of columns for ``store="table"``,
        an (N, 3) array for ``"points"``, a dict for ``"json"``), or of
        ``store(project, target, path) -> str`` for ``store="custom"``.
    store : str
        ``"table"``, ``"points"``, ``"json"`` or ``"custom"``.
    options : tuple of str
        Import options the reader accepts as keyword arguments (``"heave_positive"``);
        ``hydrosync import`` passes those given on its command line, the Import dialog
        asks for them, and they are recorded as attributes of the imported data.
    repeatable : str
        Empty when one file fills the target (a second one replaces it); else what each
        of several files holds (``"one file per antenna"``): ``--help`` says so.
    folder : bool
        The input is a folder (a recording), not a file: the Import dialog passes the
        folder itself instead of the files in it.
    """

    name: str
    description: str
    target: str
    reader: str
    store: str = "table"
    options: tuple[str, ...] = ()
    repeatable: str = ""
    folder: bool = False


@dataclass(frozen=True)
class TrendSeries:
    """One plotted quantity of a campaign trend: keys of the step's numbers.

    Attributes
    ----------
    label : str
        Legend text (``"Δt"``, ``"roll"``).
    value : str
        Key of the value in the step's numbers (the result group's attributes).
    low, high : str
        Keys of the interval's ends; empty when *sigma* gives the interval.
    sigma : str
        Key of the 1σ; the interval drawn is ±1.96 σ. Empty when *low*/*high* give it.
    """

    label: str
    value: str
    low: str = ""
    high: str = ""
    sigma: str = ""


@dataclass(frozen=True)
class Trend:
    """A campaign summary plot of one analysis: its quantities per survey day."""

    title: str
    unit: str
    series: tuple[TrendSeries, ...]


@dataclass(frozen=True)
class PluginSpec:
    """What a plugin declares.

    Attributes
    ----------
    id : str
        Stable identifier; results are stored under ``/results/<id>``, the core package
        is ``hydrosync_core.methods.<id>`` for first-party analyses.
    name : str
        Human name shown on the tab.
    run : str
        Dotted path of ``run(project, params, progress, cancel) -> result``: headless,
        reads its inputs from the project and stores its results there. *params* is an
        instance of the :attr:`params` schema (a dict is accepted and validated).
    panel : str
        Dotted path of the Qt panel class (constructed with no arguments).
    params : str
        Dotted path of the frozen parameter dataclass (a
        :class:`hydrosync_core.params.Params`); the single source of defaults, limits,
        labels, CLI flags and stored parameters. Empty for an analysis without parameters.
    cli : str
        Dotted path of ``register(subparsers)`` adding the analysis command.
    data_kinds : tuple of DataKind
        The input files the analysis imports.
    requires : tuple of str
        Project paths that must exist before :attr:`run` can work.
    icon : str
        File name under ``resources/icons``.
    description : str
        One sentence for tooltips and the plugin list; cites publications by author.
    demo : str
        Dotted path of ``fill_demo(project, seed=0, progress=None)`` writing a simulated
        data set (``hydrosync demo``, contract tests). Empty if none.
    report_section : str
        Dotted path of ``section(project, ctx) -> list`` returning the reportlab flowables
        of the PDF section. Empty for a generic listing.
    order : int
        Position among the tabs and report sections (lower first).
    report_appendix : str
        Dotted path of ``appendix(project, ctx) -> list`` for long tables placed at the end
        of the PDF (after the data-sources appendix). Empty for none.
    apply : str
        Dotted path of ``apply_to_vessel(project) -> str`` writing the analysis's
        calibrated values into the vessel sheet (``hydrosync vessel P --apply <id>``);
        empty when the analysis calibrates nothing.
    warmup : str
        Dotted path of a no-argument function that compiles and caches the analysis's
        numba kernels (``python -m hydrosync_core.warmup``, run by ``make install``, so that
        no user's first run waits for a compiler). Empty when there is nothing to compile.
    trends : tuple of Trend
        The quantities a campaign summary plots per survey day (``hydrosync batch``).
    api_version : int
        The :data:`API_VERSION` the plugin was written for.
    version : str
        The plugin's own version (stored with its results).
    """

    id: str
    name: str
    run: str
    panel: str
    params: str = ""
    cli: str = ""
    data_kinds: tuple[DataKind, ...] = ()
    requires: tuple[str, ...] = ()
    icon: str = ""
    description: str = ""
    demo: str = ""
    report_section: str = ""
    order: int = 100
    report_appendix: str = ""
    apply: str = ""
    warmup: str = ""
    trends: tuple[Trend, ...] = ()
    api_version: int = API_VERSION
    version: str = "1.0.0"

    def load_run(self) -> Callable:
        return load_object(self.run)

    def load_panel(self) -> type:
        return load_object(self.panel)

    def load_params(self) -> type:
        """The parameter schema class (:class:`hydrosync_core.params.Params`)."""
        if not self.params:
            from hydrosync_core.params import Params

            return Params
        return load_object(self.params)

    @property
    def default_params(self) -> dict:
        """The schema's defaults as a JSON-ready dict (declared once, in the schema)."""
        return self.load_params().defaults()

    def make_params(self, values=None, *, strict: bool = False):
        """A validated parameter instance from *values* (dict, instance or None)."""
        schema = self.load_params()
        if isinstance(values, schema):
            return values
        return schema.from_dict(values, strict=strict)

    def missing_inputs(self, project) -> list[str]:
        """The required project paths that *project* does not hold."""
        return [p for p in self.requires if not project.exists(p)]
