"""Atomic writing of output files (JSON, CSV, PDF): temporary file, fsync, rename."""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import IO


@contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path beside *path*; on success fsync and rename it to *path*.

    On any exception the temporary file is removed and *path* is left as it was.
    """
    path = Path(path)
    tmp = path.with_name(path.name + ".tmp")
    try:
        yield tmp
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    _fsync_folder(path.parent)


def _fsync_folder(folder: Path) -> None:
    """Make the rename itself durable (POSIX); silently skipped where unsupported."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def write_text_atomic(path: str | os.PathLike, writer: Callable[[IO[str]], None]) -> None:
    """Call ``writer(file)`` on a temporary text file, then rename it to *path*."""
    with atomic_path(path) as tmp, open(tmp, "w", encoding="utf-8", newline="") as fh:
        writer(fh)


def write_json_atomic(path: str | os.PathLike, document) -> None:
    """Write *document* as indented JSON to *path* atomically."""
    write_text_atomic(path, lambda fh: json.dump(document, fh, indent=2, allow_nan=False))
