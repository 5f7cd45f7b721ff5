"""Contract tests open plugin panels: offscreen Qt."""

import os

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
