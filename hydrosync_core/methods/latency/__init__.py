"""Latency between GNSS heights and attitude/heave by correlative approximation.

Qi et al. (2010), *Synchronization model between positioning and attitude data based on
correlative approximation*. The package holds everything headless about the analysis:
``params`` (the parameter schema), ``estimate`` (the method's entry point; its steps in
``inputs``, ``passes``, ``weighted``, ``outcome``, ``threads``), ``synchronised`` (the
synchronised data set), ``series`` (one line's plot series), ``readers`` (the CSV files),
``project_run`` (project I/O),
``simulate`` (the simulator), ``demo``, ``report_section`` and ``cli``.

The public names below are loaded on first use, so importing the package (or its
``params`` module, as the plugin spec does) stays cheap.
"""

from __future__ import annotations

import importlib

#: Version of the analysis (stored with its results; ``PluginSpec.version``).
VERSION = "1.2.0"

_PUBLIC = {
    "LatencyParams": "params", "LatencyResult": "result", "LineResult": "result",
    "estimate_latency": "estimate", "line_series": "series", "synchronise": "synchronised",
}
__all__ = sorted(_PUBLIC)


def __getattr__(name: str):
    if name in _PUBLIC:
        return getattr(importlib.import_module(f"{__name__}.{_PUBLIC[name]}"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
