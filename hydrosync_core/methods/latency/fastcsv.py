"""Fast reading of the latency CSV files (gnss.csv, attitude.csv) for ``hydrosync latency``.

A survey day of 100 Hz attitude is ~8 million rows (330 MB). The validated generic reader
(:mod:`hydrosync_core.importers.csv_table`) holds the whole text and its lines in memory
and takes tens of seconds; here pyarrow's multi-threaded CSV parser reads the numeric
columns directly. Only files that are plainly well-formed take this path: pure ASCII,
the header on the first line, no comment (``#``) or quote characters, every row with the
header's field count, every wanted value a finite number inside its plausible range, and
strictly increasing times. Anything else — and any pyarrow failure — goes to the generic
reader, which returns the same columns or raises the same one-line :class:`InputError`
naming file, line and field.

First choice is a compiled parser (numba, two threads over the two halves of the file,
read through a memory map whose pages are released as they are parsed) for rows of plain
decimals (``-12.3456``): such a number with at most 15 significant digits is a whole
number divided by a power of ten, both exact in float64, so one correctly rounded
division gives exactly the double any correct parser returns. Any other byte, field
count or number shape (exponents, more digits, blank lines, quotes…) hands the file to
the pyarrow path. The returned dicts are identical (float64 columns, same
order) to those of :func:`~hydrosync_core.importers.survey_csv.read_gnss_csv` and
:func:`~hydrosync_core.importers.survey_csv.read_attitude_csv`.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from hydrosync_core import plausible

CHECK_CHUNK = 1 << 24
"""Bytes scanned per read when screening a file for the fast path."""

PIECE_BYTES = 1 << 22
"""Bytes of CSV parsed per pyarrow call (bounds the parser's memory above the output)."""


def _plain_file(path: Path) -> tuple[list[str], int, int] | None:
    """(lower-cased header names, header length in bytes, newline count) if *path* may take
    the fast path, else None."""
    try:
        if not path.is_file() or path.stat().st_size == 0:
            return None
        with open(path, "rb") as fh:
            first = fh.readline(1 << 16)
            if not first.endswith(b"\n") or not first.strip() or not first.isascii():
                return None
            header = first.decode("ascii").strip()
            if header.startswith("#") or '"' in header:
                return None
            names = [c.strip().lower() for c in header.split(",")]
            fh.seek(0)
            newlines = 0
            while chunk := fh.read(CHECK_CHUNK):
                if not chunk.isascii() or b"#" in chunk or b'"' in chunk:
                    return None
                newlines += chunk.count(b"\n")
    except OSError:
        return None
    if len(set(names)) != len(names) or any(not n for n in names):
        return None
    return names, len(first), newlines


def _pieces(fh, start: int):
    """Successive byte strings of *fh* from *start*, about PIECE_BYTES each, whole lines."""
    fh.seek(start)
    rest = b""
    while chunk := fh.read(PIECE_BYTES):
        chunk = rest + chunk
        cut = chunk.rfind(b"\n") + 1
        if cut == 0:
            rest = chunk
            continue
        rest = chunk[cut:]
        yield chunk[:cut]
        del chunk
    if rest:
        yield rest


_POW10 = np.array([10.0 ** k for k in range(23)])

try:  # numba is a dependency; the pyarrow path remains if it cannot load
    from numba import njit
except ImportError:  # pragma: no cover
    njit = None


def _count_py(buf, start, stop):  # pragma: no cover - compiled below
    n = 0
    for i in range(start, stop):
        if buf[i] == 10:
            n += 1
    return n


def _parse_py(buf, start, stop, ncols, slot, out, row0, lo, hi, pow10):  # pragma: no cover
    """Parse rows of *buf[start:stop]* (whole lines) into ``out[slot[c], row0 + i]``.

    Returns (rows, status): status 0 when every field is a plain decimal inside
    [lo, hi] of its column, column 0 strictly increasing within the range, the row's
    field count *ncols*; otherwise 1 (the caller falls back to the general readers).
    """
    row = row0
    i = start
    prev = -np.inf
    while i < stop:
        for c in range(ncols):
            neg = False
            if i < stop and buf[i] == 45:  # '-'
                neg = True
                i += 1
            mant = 0
            digits = 0
            frac = 0
            while i < stop:
                d = buf[i]
                if d < 48 or d > 57:
                    break
                mant = mant * 10 + (d - 48)
                digits += 1
                i += 1
            if i < stop and buf[i] == 46:  # '.'
                i += 1
                while i < stop:
                    d = buf[i]
                    if d < 48 or d > 57:
                        break
                    mant = mant * 10 + (d - 48)
                    frac += 1
                    i += 1
            # Up to 18 digits fit an int64; exact in float64 up to 2**53; 10**22 is exact.
            if digits == 0 or digits + frac > 18 or frac > 22 or mant > 9007199254740992:
                return row - row0, 1
            value = mant / pow10[frac]
            if neg:
                value = -value
            if not (lo[c] <= value <= hi[c]):
                return row - row0, 1
            if c == 0:
                if not value > prev:
                    return row - row0, 1
                prev = value
            s = slot[c]
            if s >= 0:
                out[s, row] = value
            # separator: ',' between fields, then '\n' (or '\r\n', or the end) after the last
            if c < ncols - 1:
                if i >= stop or buf[i] != 44:
                    return row - row0, 1
                i += 1
            else:
                if i < stop and buf[i] == 13:
                    i += 1
                if i < stop:
                    if buf[i] != 10:
                        return row - row0, 1
                    i += 1
        row += 1
    return row - row0, 0


if njit is not None:
    _count = njit(cache=True, nogil=True)(_count_py)
    _parse = njit(cache=True, nogil=True)(_parse_py)
else:  # pragma: no cover
    _count = _parse = None

COMPILED_CHUNK = 1 << 25
"""Bytes of the memory map parsed between releases of its pages (32 MiB)."""


def _release(mm, start: int, stop: int) -> None:
    """Drop the mapped pages of [start, stop) from this process (they stay cached)."""
    import mmap

    page = mmap.PAGESIZE
    a = (start // page) * page
    b = (stop // page) * page
    if b > a and hasattr(mm, "madvise") and hasattr(mmap, "MADV_DONTNEED"):
        mm.madvise(mmap.MADV_DONTNEED, a, b - a)


def _read_compiled(path: Path, names: list[str], header_bytes: int, wanted: Sequence[str],
                   keep: Sequence[str], limits: Mapping[str, plausible.Limits],
                   min_rows: int) -> dict | None:
    """The compiled parser (module doc), or None when the file needs another reader."""
    import mmap
    from concurrent.futures import ThreadPoolExecutor

    if _parse is None or "time" not in names or names[0] != "time":
        return None
    size = path.stat().st_size
    if size <= header_bytes:
        return None
    ncols = len(names)
    slot = np.full(ncols, -1, dtype=np.int64)
    lo = np.full(ncols, -np.inf)
    hi = np.full(ncols, np.inf)
    for c, name in enumerate(names):
        if name in keep:
            slot[c] = list(keep).index(name)
        if name in wanted and name in limits:
            lo[c], hi[c] = limits[name][0], limits[name][1]
        elif name not in wanted:
            return None  # an unknown column: the general readers decide what it means
    with open(path, "rb") as fh, mmap.mmap(fh.fileno(), 0, access=mmap.ACCESS_READ) as mm:
        buf = np.frombuffer(mm, dtype=np.uint8)
        try:
            # Two halves split after a newline; chunks of whole lines inside each half.
            mid = header_bytes + (size - header_bytes) // 2
            k = mm.find(b"\n", mid)
            mid = size if k < 0 else k + 1
            halves = [(header_bytes, mid), (mid, size)]

            def chunks(a, b):
                while a < b:
                    e = min(a + COMPILED_CHUNK, b)
                    if e < b:
                        e = mm.rfind(b"\n", a, e) + 1
                        if e <= a:
                            e = mm.find(b"\n", a + COMPILED_CHUNK, b) + 1 or b
                    yield a, e
                    a = e

            def count(a, b, buf=buf):
                n = 0
                for x, y in chunks(a, b):
                    n += _count(buf, x, y)
                    _release(mm, x, y)
                return n

            with ThreadPoolExecutor(2) as pool:
                counts = list(pool.map(lambda h: count(*h), halves))
                # A last row without a newline still counts.
                rows_total = counts[0] + counts[1] + (0 if mm[size - 1:size] == b"\n" else 1)
                if rows_total < min_rows:
                    return None
                out = np.empty((len(keep), rows_total))

                def parse(a, b, row0, buf=buf):
                    rows = 0
                    for x, y in chunks(a, b):
                        n, status = _parse(buf, x, y, ncols, slot, out, row0 + rows, lo, hi,
                                           _POW10)
                        _release(mm, x, y)
                        if status:
                            return -1
                        rows += n
                    return rows

                got = list(pool.map(lambda h: parse(*h), [(halves[0][0], halves[0][1], 0),
                                                          (halves[1][0], halves[1][1],
                                                           counts[0])]))
        finally:
            count = parse = None
            del buf  # the map closes only without exported buffers
    if got[0] != counts[0] or got[0] < 0 or got[1] < 0 or got[0] + got[1] != rows_total:
        return None
    t = keep.index("time")
    if counts[0] and got[1] and not out[t, counts[0]] > out[t, counts[0] - 1]:
        return None  # not increasing across the halves: the general readers decide
    return {c: out[i] for i, c in enumerate(keep)}


def _header(path: Path) -> tuple[list[str], int] | None:
    """(lower-cased header names, header length in bytes) of a plain ASCII header."""
    try:
        if not path.is_file() or path.stat().st_size == 0:
            return None
        with open(path, "rb") as fh:
            first = fh.readline(1 << 16)
    except OSError:
        return None
    if not first.endswith(b"\n") or not first.strip() or not first.isascii():
        return None
    header = first.decode("ascii").strip()
    if header.startswith("#") or '"' in header:
        return None
    names = [c.strip().lower() for c in header.split(",")]
    if len(set(names)) != len(names) or any(not n for n in names):
        return None
    return names, len(first)


def _read_fast(path: Path, required: Sequence[str], optional: Sequence[str],
               limits: Mapping[str, plausible.Limits], min_rows: int,
               keep: Sequence[str] | None = None) -> dict | None:
    head = _header(path)
    if head is not None and all(c in head[0] for c in required):
        names = head[0]
        wanted = list(required) + [c for c in optional if c in names]
        kept = wanted if keep is None else [c for c in wanted if c in keep or c == "time"]
        try:
            compiled = _read_compiled(path, names, head[1], wanted, kept, limits, min_rows)
        except (OSError, ValueError):
            compiled = None
        if compiled is not None:
            return compiled
    screened = _plain_file(path)
    if screened is None:
        return None
    names, header_bytes, newlines = screened
    if any(c not in names for c in required):
        return None
    try:
        import pyarrow as pa
        from pyarrow import csv as pacsv
    except ImportError:  # pragma: no cover - pyarrow is a dependency
        return None
    wanted = list(required) + [c for c in optional if c in names]
    keep = wanted if keep is None else [c for c in wanted if c in keep or c == "time"]
    raw_names = [f"c{i}" for i in range(len(names))]
    keys = {c: f"c{names.index(c)}" for c in wanted}
    options = (
        pacsv.ReadOptions(column_names=raw_names, block_size=1 << 20),
        pacsv.ParseOptions(delimiter=",", quote_char=False, double_quote=False,
                           newlines_in_values=False),
        pacsv.ConvertOptions(include_columns=[keys[c] for c in wanted],
                             column_types={keys[c]: pa.float64() for c in wanted},
                             null_values=[], strings_can_be_null=False,
                             quoted_strings_can_be_null=False),
    )
    # Rows <= newlines (the header's newline included): filled piece by piece, so the
    # parser never holds more than one piece above the output arrays.
    out = {c: np.empty(newlines) for c in keep}
    # The system allocator returns each piece's buffers; arrow's default pool keeps them.
    pool = pa.system_memory_pool()
    rows = 0
    last_time = -np.inf
    with open(path, "rb") as fh:
        for piece in _pieces(fh, header_bytes):
            try:
                table = pacsv.read_csv(pa.py_buffer(piece), *options, memory_pool=pool)
            except (pa.ArrowException, OSError, ValueError):
                return None
            n = table.num_rows
            if rows + n > newlines:
                return None
            for name in wanted:
                column = table.column(keys[name])
                if column.null_count:
                    return None
                values = column.to_numpy()
                if not np.isfinite(values).all():
                    return None
                if name in limits and plausible.first_outside(values, limits[name]) is not None:
                    return None
                if name == "time" and n and (values[0] <= last_time
                                             or not np.all(np.diff(values) > 0)):
                    return None  # unsorted or duplicate: the generic reader sorts or names them
                if name in out:
                    out[name][rows:rows + n] = values
                del column, values
            if n:
                last_time = float(out["time"][rows + n - 1]) if "time" in out else last_time
            rows += n
            del table, piece
    if rows < min_rows:
        return None
    return {c: v[:rows] if rows < newlines else v for c, v in out.items()}


def read_gnss_csv(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """``gnss.csv`` as :func:`hydrosync_core.importers.survey_csv.read_gnss_csv` reads it."""
    fast = _read_fast(Path(path), ["time", "height"], ["lat", "lon", "quality"],
                      plausible.GNSS, 2)
    if fast is not None:
        return fast
    from hydrosync_core.importers.survey_csv import read_gnss_csv as generic

    return generic(path)


def read_attitude_csv(path: str | os.PathLike, heave_positive: str = "up",
                      columns: Sequence[str] | None = None) -> dict[str, np.ndarray]:
    """``attitude.csv`` as :func:`~hydrosync_core.importers.survey_csv.read_attitude_csv`.

    *columns*, if given, limits the columns returned (``time`` always is); every column is
    still checked. The latency estimate needs no heading, so leaving it out saves 8 bytes
    per record.
    """
    from hydrosync_core.importers.survey_csv import read_attitude_csv as generic

    fast = None
    if heave_positive in ("up", "down"):
        fast = _read_fast(Path(path), ["time", "roll", "pitch", "heading", "heave"], [],
                          plausible.ATTITUDE, 2, columns)
    if fast is None:
        table = generic(path, heave_positive)  # the same columns, or the precise error
        return table if columns is None else {
            c: v for c, v in table.items() if c in columns or c == "time"}
    if heave_positive == "down" and "heave" in fast:
        fast["heave"] = -fast["heave"]
    return fast
