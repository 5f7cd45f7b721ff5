"""The gate every input file passes before a reader opens it.

:func:`input_ok` refuses, with one line naming the file, what cannot be a data file: a
missing path, a folder, a named pipe (reading it would wait for a writer, for ever and
holding the project lock), a device (``/dev/zero`` never ends), a socket, an unreadable
file, a file larger than its kind can be, and — for text kinds — a file whose sampled
blocks are mostly NUL bytes (a sparse or zero-filled file, which a reader would
otherwise decode into gigabytes of nothing). It costs one ``stat`` and at most three
64 KiB reads.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from hydrosync_core.errors import InputError

TEXT_MAX_BYTES = 64 << 30
"""Largest text input (a year of 50 Hz motion log is ~20 GB)."""

SAMPLE_BYTES = 64 << 10
"""Bytes read at the start, middle and end of a text file to tell it is text."""

NUL_SHARE_LIMIT = 0.25
"""A sample with more than this share of NUL bytes is not text."""

_KINDS = {stat.S_ISFIFO: "a named pipe (FIFO)", stat.S_ISCHR: "a character device",
          stat.S_ISBLK: "a block device", stat.S_ISSOCK: "a socket"}


def _size_text(nbytes: int) -> str:
    for unit, scale in (("GB", 1e9), ("MB", 1e6), ("KB", 1e3)):
        if nbytes >= scale:
            return f"{nbytes / scale:.1f} {unit}"
    return f"{nbytes} bytes"


def input_ok(path: str | os.PathLike, what: str | None = None, *,
             max_bytes: int = TEXT_MAX_BYTES, text: bool = True) -> Path:
    """Check that *path* can be read as an input file; return it as a :class:`Path`.

    Parameters
    ----------
    path : path-like
        The file given by the user.
    what : str, optional
        What the file should be ("GNSS log", "campaign file"), for the messages.
    max_bytes : int
        Largest size a file of this kind can have.
    text : bool
        The kind is text: refuse files that sample as mostly NUL bytes.

    Raises
    ------
    InputError
        Naming the file and what is wrong, before anything is read.
    """
    p = Path(path)
    kind = what or "file"
    try:
        info = os.stat(p)
    except FileNotFoundError:
        raise InputError(str(p), "no such file") from None
    except (OSError, ValueError) as exc:  # ELOOP, ENAMETOOLONG, a NUL in the name
        raise InputError(str(p), f"cannot be opened ({getattr(exc, 'strerror', None) or exc})"
                         ) from None
    if stat.S_ISDIR(info.st_mode):
        raise InputError(str(p), "is a folder, not a file")
    for test, name in _KINDS.items():
        if test(info.st_mode):
            raise InputError(str(p), f"is {name}, not a regular file: HydroSync reads "
                             "only plain files (save the data to a file first)")
    if not os.access(p, os.R_OK):
        raise InputError(str(p), "cannot be read (permissions)")
    if info.st_size > max_bytes:
        raise InputError(str(p), f"is {_size_text(info.st_size)}: too large for a {kind} "
                         f"(at most {_size_text(max_bytes)})")
    if text and info.st_size:
        _check_text(p, info.st_size, kind)
    return p


def _check_text(path: Path, size: int, kind: str) -> None:
    offsets = sorted({0, max(0, size // 2 - SAMPLE_BYTES // 2), max(0, size - SAMPLE_BYTES)})
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as exc:
        raise InputError(str(path), f"cannot be opened ({exc.strerror or exc})") from None
    try:
        for offset in offsets:
            block = os.pread(fd, SAMPLE_BYTES, offset)
            if offset == 0 and block[:2] in (b"\xff\xfe", b"\xfe\xff"):
                raise InputError(str(path), "is UTF-16 text: save it as UTF-8 (or ASCII)")
            if block and block.count(0) > NUL_SHARE_LIMIT * len(block):
                raise InputError(str(path), f"is not a {kind}: {block.count(0)} of "
                                 f"{len(block)} bytes at offset {offset} are NUL (a sparse "
                                 "or zero-filled file)")
    except OSError as exc:
        raise InputError(str(path), f"cannot be read ({exc.strerror or exc})") from None
    finally:
        os.close(fd)
