"""Plugin declaration (spec) and discovery (registry)."""

from hydrosync_core.plugins.registry import Discovered, discover, get_spec, plugin_specs
from hydrosync_core.plugins.spec import DataKind, PluginSpec, load_object

__all__ = [
    "DataKind", "Discovered", "PluginSpec", "discover", "get_spec", "load_object",
    "plugin_specs",
]
