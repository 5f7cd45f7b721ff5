"""The File → Open Recent list, kept in :class:`QSettings` (most recent first)."""

from __future__ import annotations

import os
from pathlib import Path

from PySide6.QtCore import QSettings

KEY = "recent/files"


class RecentFiles:
    """At most *maximum* absolute paths; files that no longer exist are pruned on read."""

    def __init__(self, settings: QSettings, maximum: int = 8) -> None:
        self.settings = settings
        self.maximum = maximum

    def _read(self) -> list[str]:
        value = self.settings.value(KEY, [])
        if value is None:
            return []
        if isinstance(value, str):  # QSettings returns a lone string for a 1-item list
            return [value] if value else []
        return [str(v) for v in value]

    def _write(self, paths: list[str]) -> None:
        self.settings.setValue(KEY, paths[: self.maximum])
        self.settings.sync()

    def files(self) -> list[str]:
        """The existing recent files, most recent first (missing ones are dropped)."""
        stored = self._read()
        existing = [p for p in stored if os.path.isfile(p)]
        if existing != stored:
            self._write(existing)
        return existing[: self.maximum]

    def add(self, path: str | os.PathLike) -> None:
        """Put *path* first (moving it if already listed)."""
        full = str(Path(path).resolve())
        paths = [p for p in self._read() if p != full]
        self._write([full, *paths])

    def remove(self, path: str | os.PathLike) -> None:
        full = str(Path(path).resolve())
        self._write([p for p in self._read() if p != full])

    def clear(self) -> None:
        self._write([])
