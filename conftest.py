"""Repository-wide pytest set-up: Qt always offscreen, so tests never need a display; the
shared fixtures (one demo run per session, per-plugin demo projects, the plugin contract)
come from ``hydrosync_gui.testing``, which third-party plugins load the same way."""

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

pytest_plugins = ["hydrosync_gui.testing"]
