"""Plugin discovery through entry points. Discovery never raises."""

from __future__ import annotations

import functools
import logging
from dataclasses import dataclass
from importlib.metadata import entry_points

from hydrosync_core.plugins.spec import API_VERSION, ENTRY_POINT_GROUP, PluginSpec

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Discovered:
    """One entry point: its spec, or the error that stopped it loading."""

    entry_point: str
    value: str
    spec: PluginSpec | None
    error: str | None


def check_spec(spec: object, where: str) -> PluginSpec:
    """*spec* if it is a usable PluginSpec, else raise with a reason a user can act on."""
    if not isinstance(spec, PluginSpec):
        raise TypeError(f"{where} is a {type(spec).__name__}, not a PluginSpec")
    if spec.api_version != API_VERSION:
        raise ValueError(f"{where} was written for plugin API {spec.api_version}; this "
                         f"HydroSync provides API {API_VERSION}")
    return spec


@functools.lru_cache(maxsize=8)
def _entry_points(group: str) -> tuple:
    """The installed entry points of *group*, read once per process: the metadata scan
    costs milliseconds on every parser build and import, and the set of installed packages
    does not change while HydroSync runs."""
    return tuple(entry_points(group=group))


def discover(group: str = ENTRY_POINT_GROUP) -> list[Discovered]:
    """Load every plugin spec of *group*; broken ones come back with their error."""
    found: list[Discovered] = []
    for ep in _entry_points(group):
        try:
            spec = check_spec(ep.load(), ep.value)
            found.append(Discovered(ep.name, ep.value, spec, None))
        except Exception as exc:  # a third-party plugin may fail in any way
            message = f"{type(exc).__name__}: {exc}"
            log.error("plugin '%s' (%s) failed to load: %s", ep.name, ep.value, message)
            found.append(Discovered(ep.name, ep.value, None, message))
    found.sort(key=lambda d: (d.spec.order if d.spec else 1000, d.entry_point))
    return found


def plugin_specs() -> list[PluginSpec]:
    """The specs that loaded, in display order."""
    return [d.spec for d in discover() if d.spec is not None]


def get_spec(plugin_id: str) -> PluginSpec:
    for spec in plugin_specs():
        if spec.id == plugin_id:
            return spec
    raise KeyError(f"no plugin with id '{plugin_id}'")
