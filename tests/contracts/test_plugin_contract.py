"""The contract every plugin of the real registry keeps (``hydrosync_gui.testing``).

Run over each entry point of ``hydrosync.plugins`` and over the example third-party analysis
under ``examples/heave_stats`` (loaded from its folder, as an installed package would be
through its entry point). A broken *built-in* plugin fails here; a broken third-party one is
skipped with its error. Third parties run the same tests by subclassing
:class:`~hydrosync_gui.testing.PluginContract` (``docs/plugins.md``).
"""

from __future__ import annotations

import pytest
from example_plugin import example_discovered

from hydrosync_core.plugins import discover
from hydrosync_core.plugins.registry import Discovered
from hydrosync_gui.testing import PluginContract

BUILT_IN_PREFIXES = ("plugins.", "hydrosync_core.", "hydrosync_gui.", "hydrosync_heave_stats")
FOUND = discover() + [example_discovered()]


def _id(d: Discovered) -> str:
    return d.entry_point


def test_registry_lists_the_built_in_plugins():
    names = {d.entry_point for d in FOUND}
    assert {"latency", "pool_calibration", "gnss_attitude", "tilt_alignment",
            "gins_smoother"} <= names
    ids = [d.spec.id for d in FOUND if d.spec is not None]
    assert len(ids) == len(set(ids)), f"plugin ids are not unique: {ids}"


class TestEveryPlugin(PluginContract):
    @pytest.fixture(params=FOUND, ids=_id)
    def contract_spec(self, request):
        d = request.param
        if d.spec is None:
            if d.value.startswith(BUILT_IN_PREFIXES):
                pytest.fail(f"built-in plugin '{d.entry_point}' ({d.value}) does not load: "
                            f"{d.error}")
            pytest.skip(f"third-party plugin '{d.entry_point}' does not load: {d.error}")
        return d.spec
