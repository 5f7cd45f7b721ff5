"""Where the shell finds its icons (``resources/icons`` at the top of the checkout)."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtGui import QIcon

ICON_DIR = Path(__file__).resolve().parents[1] / "resources" / "icons"


def icon_path(name: str) -> Path | None:
    """Return ``resources/icons/<name>`` if *name* is given and the file exists."""
    if not name:
        return None
    path = ICON_DIR / name
    return path if path.is_file() else None


def icon(name: str, fallback: str = "") -> QIcon:
    """A :class:`QIcon` from ``resources/icons``; *fallback*'s icon, or an empty one, if absent."""
    path = icon_path(name) or icon_path(fallback)
    return QIcon(str(path)) if path else QIcon()
