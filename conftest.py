"""Repository-wide pytest set-up: Qt always offscreen, so tests never need a display; the
shared fixtures (one demo run per session, per-plugin demo projects, the plugin contract)
come from ``hydrosync_gui.testing``, which third-party plugins load the same way."""

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

pytest_plugins = ["hydrosync_gui.testing"]


def pytest_collection_modifyitems(config, items):
    """Under pytest-xdist (``make test`` runs ``-n auto --dist loadgroup``) the reliability
    cases stay together on one worker, one after the other: they kill, signal and starve
    their own child processes and lock shared temporary folders, and their faults must not
    race each other's."""
    import pytest

    for item in items:
        if "tests/reliability/" in item.nodeid.replace("\\", "/"):
            item.add_marker(pytest.mark.xdist_group("reliability"))
