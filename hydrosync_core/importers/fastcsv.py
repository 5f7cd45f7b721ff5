"""Fast reading of large numeric CSV tables (the survey day's gnss.csv and attitude.csv…).

A survey day of 100 Hz attitude is ~8 million rows (330 MB). The validated generic reader
(:func:`hydrosync_core.importers.csv_table.read_numeric_csv`) holds the whole text, its
lines and several byte-sized working arrays in memory (6.5 GiB, tens of seconds for such a
day). :func:`read_numeric_fast` reads the same table into preallocated float64 columns,
without a Python object per row, and returns exactly what the generic reader returns —
or ``None`` whenever it is not certain to, and the caller then runs the generic reader,
which returns the same columns or raises its one-line :class:`InputError` naming file,
line and field. So the fast path never decides an error except one it can word exactly as
the generic reader does (a duplicate time, below); every other bad file goes to the
generic reader.

Only files that are plainly well-formed take the fast path: the header on the first line,
every byte printable ASCII (or a line end), no comment (``#``) or quote character, every
row with the header's field count, every wanted value a finite number inside its
plausible range. Unsorted times are sorted (stable, as the generic reader does).

First choice is a compiled parser (numba, two threads over the two halves of the file,
read through a memory map whose pages are released as they are parsed) for rows of plain
decimals (``-12.3456``): such a number of at most 2**53 as a whole number of digits is a
whole number divided by a power of ten (at most 10**18), both exact in float64, so one
correctly rounded division gives exactly the double any correctly rounding parser (numpy's,
Python's) returns. Columns the caller does not want are skipped whatever printable text
they hold. Any other byte, field count or number shape (exponents, more digits, blank
lines…) hands the file to a pyarrow parser that reads it in pieces of a few MiB into the
preallocated columns, and anything that one does not take to the generic reader.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hydrosync_core import plausible
from hydrosync_core.errors import InputError
from hydrosync_core.inputs import input_ok

CHECK_CHUNK = 1 << 24
"""Bytes scanned per read when screening a file for the pyarrow path."""

PIECE_BYTES = 1 << 22
"""Bytes of CSV parsed per pyarrow call (bounds the parser's memory above the output)."""

COMPILED_CHUNK = 1 << 25
"""Bytes of the memory map parsed between releases of its pages (32 MiB)."""

PRESCAN_CHUNK = 1 << 23
"""Bytes read per call by :class:`Prescan` (each call waits for the interpreter lock,
which the thread loading modules holds; a few dozen waits are a few dozen milliseconds)."""

MAX_COLUMNS = 1000
"""As :data:`hydrosync_core.importers.csv_table.MAX_COLUMNS` (more is not a table)."""

_PRINTABLE = bytes(range(0x20, 0x7F))
_HEADER_BYTES = _PRINTABLE.replace(b"#", b"").replace(b'"', b"")
"""Bytes a header may hold (its line end apart)."""
_DATA_BYTES = _HEADER_BYTES + b"\r\n"
"""Bytes the data rows may hold: anything else (a tab, a form feed — a line break to
:meth:`str.splitlines` —, a quote, a comment, a non-ASCII byte) is left to the generic
reader."""

SKIP = -2
"""Slot of a column nobody wants: its field is skipped, not parsed."""
CHECK = -1
"""Slot of a column that is checked (number, range) but not returned."""


def _header(path: Path) -> tuple[list[str], int] | None:
    """(lower-cased header names, header length in bytes) of a plain ASCII header line."""
    try:
        if not path.is_file() or path.stat().st_size == 0:
            return None
        with open(path, "rb") as fh:
            first = fh.readline(1 << 16)
    except OSError:
        return None
    if not first.endswith(b"\n"):
        return None
    line = first[:-2] if first.endswith(b"\r\n") else first[:-1]
    if not line.strip() or line.translate(None, _HEADER_BYTES):
        return None
    names = [c.strip().lower() for c in line.decode("ascii").split(",")]
    if len(names) > MAX_COLUMNS or len(set(names)) != len(names) or any(not n for n in names):
        return None
    return names, len(first)


def _plain_file(path: Path, header_bytes: int) -> int | None:
    """Newline count of *path* if every byte after the header is one of ``_DATA_BYTES``."""
    try:
        with open(path, "rb") as fh:
            fh.seek(header_bytes)
            newlines = 1
            while chunk := fh.read(CHECK_CHUNK):
                if chunk.translate(None, _DATA_BYTES):
                    return None
                newlines += chunk.count(b"\n")
    except OSError:
        return None
    return newlines


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


def _count_py(buf, start, stop):  # pragma: no cover - compiled below
    n = 0
    for i in range(start, stop):
        if buf[i] == 10:
            n += 1
    return n


def _parse_py(buf, start, stop, ncols, slot, out, row0, lo, hi, pow10):  # pragma: no cover
    """Parse rows of *buf[start:stop]* (whole lines) into ``out[slot[c], row0 + i]``.

    ``slot[c]`` is the output row of column *c*, ``CHECK`` (-1) to check it only, ``SKIP``
    (-2) to skip its field (printable ASCII other than ``#`` and ``"``).
    Returns (rows, status): status 0 when every checked field is a plain decimal inside
    [lo, hi] of its column and every row has *ncols* fields; otherwise 1 (the caller falls
    back to the other readers), also when *out* has no room for another row (the file
    changed since its rows were counted).
    """
    row = row0
    i = start
    room = out.shape[1]
    while i < stop:
        if row >= room:
            return row - row0, 1
        for c in range(ncols):
            s = slot[c]
            if s == -2:
                while i < stop:
                    d = buf[i]
                    if d == 44 or d == 10 or d == 13:
                        break
                    if d < 32 or d > 126 or d == 35 or d == 34:
                        return row - row0, 1
                    i += 1
            else:
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
                # Up to 18 digits fit an int64; exact in float64 up to 2**53; 10**18 is exact.
                if digits == 0 or digits + frac > 18 or mant > 9007199254740992:
                    return row - row0, 1
                value = mant / pow10[frac]
                if neg:
                    value = -value
                if not (lo[c] <= value <= hi[c]):
                    return row - row0, 1
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


_kernels: tuple | None = None


def _compiled():
    """(count, parse) compiled by numba (cached on disk; numba is a dependency). Loaded on
    first use: numba costs about a second to import, which small files do not pay."""
    global _kernels
    if _kernels is None:
        from numba import njit

        _kernels = (njit(cache=True, nogil=True)(_count_py),
                    njit(cache=True, nogil=True)(_parse_py))
    return _kernels


def _release(mm, start: int, stop: int) -> None:
    """Drop the mapped pages of [start, stop) from this process (they stay cached)."""
    import mmap

    page = mmap.PAGESIZE
    a = (start // page) * page
    b = (stop // page) * page
    if b > a and hasattr(mm, "madvise") and hasattr(mmap, "MADV_DONTNEED"):
        mm.madvise(mmap.MADV_DONTNEED, a, b - a)


def _empty_columns(count: int, rows: int) -> np.ndarray:
    """An uninitialised (count, rows) float64 block for parsed columns, in 4 KiB pages.

    numpy asks for transparent huge pages for large arrays. On a virtual machine whose host
    takes back free guest memory (free page reporting: the 2-core benchmark machine), the
    first touch of a fresh huge page cost 2-4 ms per MiB there, 0.6-0.9 s for a survey
    day's 256 MiB of attitude columns (more than parsing them), and 4 KiB pages 0.6 ms per
    MiB, every time; on other machines the difference is tens of milliseconds either way.
    The columns are read in order, so huge pages gain nothing later (the latency estimate
    took the same time on either).
    """
    import mmap

    # Anonymous and private (the default, shared, would be shmem): never madvised huge.
    flags = {"flags": mmap.MAP_PRIVATE | mmap.MAP_ANONYMOUS} if hasattr(mmap, "MAP_ANONYMOUS") \
        else {}
    try:
        block = mmap.mmap(-1, max(count * rows * 8, 1), **flags)
    except (OSError, ValueError):
        return np.empty((count, rows))
    return np.frombuffer(block, dtype=np.float64, count=count * rows).reshape(count, rows)


def _identity(st: os.stat_result) -> tuple[int, int, int, int]:
    return st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns


@dataclass
class _Plan:
    """What :func:`_read_compiled` would find before parsing: the file (as stat saw it),
    its two halves' newline counts, and the output columns, already in memory."""

    identity: tuple[int, int, int, int]
    header_bytes: int
    keep: tuple[str, ...]
    mid: int
    counts: tuple[int, int]
    rows_total: int
    out: np.ndarray


def _newlines(fh, start: int, stop: int, buf: np.ndarray, mask: np.ndarray) -> int:
    """Newlines in bytes [start, stop) of *fh*, read into *buf* (the reads and numpy's
    compare and count run without the interpreter lock)."""
    fh.seek(start)
    n = 0
    while start < stop:
        got = fh.readinto(memoryview(buf)[:min(buf.size, stop - start)])
        if not got:
            raise EOFError("the file is shorter than it was")
        np.equal(buf[:got], 10, out=mask[:got])
        n += int(np.count_nonzero(mask[:got]))
        start += got
    return n


def _plan(path: Path, required: Sequence[str], optional: Sequence[str],
          time_column: str | None, keep: Sequence[str] | None) -> _Plan | None:
    """Count the rows of *path* and allocate (and touch) its kept columns, as
    :func:`_read_compiled` would; None when the fast path would not take it."""
    layout = _layout(path, required, optional, time_column, keep)
    if layout is None:
        return None
    _, header_bytes, _, kept = layout
    with open(path, "rb", buffering=0) as fh:
        st = os.fstat(fh.fileno())
        size = st.st_size
        if size <= header_bytes:
            return None
        buf = np.empty(min(PRESCAN_CHUNK, size - header_bytes), dtype=np.uint8)
        mask = np.empty(buf.size, dtype=np.bool_)
        # The midpoint as _read_compiled finds it: just after the first newline at or after
        # the middle of the rows, or the end of the file.
        mid = header_bytes + (size - header_bytes) // 2
        fh.seek(mid)
        while True:
            got = fh.readinto(memoryview(buf)[:1 << 16])
            k = bytes(buf[:got]).find(b"\n") if got else -1
            if k >= 0:
                mid += k + 1
                break
            if not got:
                mid = size
                break
            mid += got
        counts = (_newlines(fh, header_bytes, mid, buf, mask), _newlines(fh, mid, size, buf, mask))
        fh.seek(size - 1)
        last = fh.read(1)
    del buf, mask
    rows_total = counts[0] + counts[1] + (0 if last == b"\n" else 1)
    out = _empty_columns(len(kept), rows_total)
    out.fill(0.0)  # page faults and zeroing of fresh memory: here, not in the parse
    return _Plan(_identity(st), header_bytes, tuple(kept), mid, counts, rows_total, out)


class Prescan:
    """The first pass over a large CSV file, in a background thread.

    :func:`read_numeric_fast` counts the rows (one pass over the file) and allocates the
    columns before it parses, and its compiled parser first needs numba loaded. Loading
    numba keeps one core busy (~0.4 s) and needs the interpreter; counting (~0.1 s for a
    survey day's attitude.csv) and touching the columns' fresh memory (0.1-0.5 s for its
    256 MiB) need neither. A caller that will read a file and has not loaded numba yet
    starts a prescan first and hands it to :func:`read_numeric_fast` (same columns):
    the two then run side by side.

    A prescan never changes what is read: one that failed, or of a file changed since,
    or of other columns, is not used (the reader counts itself). It holds the columns'
    memory from the count until the read takes it.

    Parameters
    ----------
    path, required, optional, time_column, keep
        As :func:`read_numeric_fast` will be called.
    """

    def __init__(self, path: str | os.PathLike, required: Sequence[str],
                 optional: Sequence[str] = (), *, time_column: str | None = "time",
                 keep: Sequence[str] | None = None) -> None:
        self.path = Path(path)
        self._args = (self.path, tuple(required), tuple(optional), time_column,
                      None if keep is None else tuple(keep))
        self._plan: _Plan | None = None
        # A daemon: Ctrl-C or an error in the caller must not wait for a count.
        self._thread = threading.Thread(target=self._run, name="hydrosync-prescan",
                                        daemon=True)
        self._thread.start()

    def _run(self) -> None:
        try:
            input_ok(self.path)  # a FIFO would hang this thread; the reader then says so
            self._plan = _plan(*self._args)
        except Exception:  # never an error of its own: the reader then counts itself
            self._plan = None

    def take(self) -> _Plan | None:
        """The result (waiting for it), once; later calls give None."""
        self._thread.join()
        plan, self._plan = self._plan, None
        return plan


def _read_compiled(path: Path, names: list[str], header_bytes: int, wanted: Sequence[str],
                   keep: Sequence[str], limits: Mapping[str, plausible.Limits],
                   min_rows: int, prescan: Prescan | None = None) -> dict | None:
    """The compiled parser (module doc): the *keep* columns in file order, or None when the
    file needs another reader. Every row is one line: row *i* is line ``i + 2``. A
    *prescan* of this file saves the counting pass if it is still valid."""
    import mmap
    from concurrent.futures import ThreadPoolExecutor

    kernels = _compiled()  # loading numba first: the prescan goes on meanwhile
    plan = prescan.take() if prescan is not None else None
    count_kernel, parse_kernel = kernels
    ncols = len(names)
    slot = np.full(ncols, SKIP, dtype=np.int64)
    lo = np.full(ncols, -np.inf)
    hi = np.full(ncols, np.inf)
    for c, name in enumerate(names):
        if name in keep:
            slot[c] = list(keep).index(name)
        elif name in wanted:
            slot[c] = CHECK
        if name in wanted and name in limits:
            lo[c], hi[c] = limits[name][0], limits[name][1]
    with open(path, "rb") as fh:
        st = os.fstat(fh.fileno())
        size = st.st_size
        if size <= header_bytes:
            return None
        mm = mmap.mmap(fh.fileno(), 0, access=mmap.ACCESS_READ)
    with mm:
        buf = np.frombuffer(mm, dtype=np.uint8)
        try:
            # Two halves split after a newline; chunks of whole lines inside each half.
            mid = header_bytes + (size - header_bytes) // 2
            k = mm.find(b"\n", mid)
            mid = size if k < 0 else k + 1
            halves = [(header_bytes, mid), (mid, size)]
            if plan is not None and (plan.identity != _identity(st) or plan.mid != mid
                                     or plan.header_bytes != header_bytes
                                     or plan.keep != tuple(keep)):
                plan = None

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
                    n += count_kernel(buf, x, y)
                    _release(mm, x, y)
                return n

            with ThreadPoolExecutor(2) as pool:
                if plan is not None:
                    counts, rows_total, out = list(plan.counts), plan.rows_total, plan.out
                    plan = None  # the columns are ours now
                else:
                    counts = list(pool.map(lambda h: count(*h), halves))
                    # A last row without a newline still counts.
                    rows_total = counts[0] + counts[1] + (0 if mm[size - 1:size] == b"\n"
                                                          else 1)
                    out = None
                if rows_total < min_rows:
                    return None
                if out is None:
                    out = _empty_columns(len(keep), rows_total)

                def parse(a, b, row0, buf=buf):
                    rows = 0
                    for x, y in chunks(a, b):
                        n, status = parse_kernel(buf, x, y, ncols, slot, out, row0 + rows, lo,
                                                 hi, _POW10)
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
    return {c: out[i] for i, c in enumerate(keep)}


def _read_arrow(path: Path, names: list[str], header_bytes: int, wanted: Sequence[str],
                keep: Sequence[str], limits: Mapping[str, plausible.Limits],
                min_rows: int) -> dict | None:
    """pyarrow's CSV parser, piece by piece into preallocated columns (file order), or
    None. Blank lines are skipped (as the generic reader does), so rows are not lines."""
    newlines = _plain_file(path, header_bytes)
    if newlines is None:
        return None
    try:
        import pyarrow as pa
        from pyarrow import csv as pacsv
    except ImportError:  # pragma: no cover - pyarrow is a dependency
        return None
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
    # Rows <= newlines + 1: filled piece by piece, so the parser never holds more than one
    # piece above the output arrays.
    out = {c: np.empty(newlines) for c in keep}
    # The system allocator returns each piece's buffers; arrow's default pool keeps them.
    pool = pa.system_memory_pool()
    rows = 0
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
                if name in out:
                    out[name][rows:rows + n] = values
                del column, values
            rows += n
            del table, piece
    if rows < min_rows:
        return None
    return {c: v[:rows] if rows < newlines else v for c, v in out.items()}


def _sort_by_time(path: Path, columns: dict[str, np.ndarray], key: str,
                  lines_known: bool) -> dict[str, np.ndarray] | None:
    """*columns* sorted by *key* (stable), as the generic reader sorts them; a duplicate
    time raises the generic reader's error when row *i* is known to be line ``i + 2``,
    else gives None (the generic reader then names the lines)."""
    time = columns[key]
    if time.size < 2 or bool(np.all(time[1:] > time[:-1])):
        return columns
    order = np.argsort(time, kind="stable")
    sorted_time = time[order]
    dup = np.flatnonzero(sorted_time[1:] == sorted_time[:-1])
    if dup.size:
        if not lines_known:
            return None
        first, second = sorted((int(order[dup[0]]) + 2, int(order[dup[0] + 1]) + 2))
        raise InputError(
            str(path),
            f"duplicate time {float(sorted_time[dup[0]])!r} (also on line {first})",
            line=second, field=key,
        )
    del sorted_time
    for values in columns.values():  # in place: one column's copy at a time
        values[:] = values[order]
    return columns


def _kept(names: list[str], required: Sequence[str], optional: Sequence[str],
          time_column: str | None, keep: Sequence[str] | None
          ) -> tuple[list[str], list[str]] | None:
    """(the columns :func:`read_numeric_fast` checks, those it returns) from a file with
    header *names* (file order as asked), or None when it leaves the file to the generic
    reader."""
    if any(c not in names for c in required):
        return None  # the generic reader names the missing column
    wanted = list(required) + [c for c in optional if c in names]
    if time_column is not None and time_column not in wanted:
        return None
    return wanted, (wanted if keep is None
                    else [c for c in wanted if c in keep or c == time_column])


def _layout(path: Path, required: Sequence[str], optional: Sequence[str],
            time_column: str | None, keep: Sequence[str] | None
            ) -> tuple[list[str], int, list[str], list[str]] | None:
    """Header names, header length (bytes), checked and kept columns of *path*
    (:func:`_header`, :func:`_kept`), or None when the fast path leaves the file to the
    generic reader."""
    head = _header(path)
    if head is None:
        return None
    names, header_bytes = head
    columns = _kept(names, required, optional, time_column, keep)
    return None if columns is None else (names, header_bytes, *columns)


def read_numeric_fast(
    path: str | os.PathLike,
    required: Sequence[str],
    optional: Sequence[str] = (),
    *,
    time_column: str | None = "time",
    min_rows: int = 1,
    limits: Mapping[str, plausible.Limits] | None = None,
    keep: Sequence[str] | None = None,
    prescan: Prescan | None = None,
) -> dict[str, np.ndarray] | None:
    """What :func:`~hydrosync_core.importers.csv_table.read_numeric_csv` returns for these
    arguments, or None when the file is not plainly well-formed (module doc).

    *keep*, if given, limits the columns returned (*time_column* always is); every wanted
    column is still checked. *prescan*, a :class:`Prescan` of this file started with the
    same columns, saves the first pass. Raises only the duplicate-time
    :class:`InputError`, worded and placed as the generic reader does.
    """
    input_ok(path, "CSV file")  # before any open: not a FIFO, device or sparse file
    path = Path(path)
    limits = limits or {}
    try:
        layout = _layout(path, required, optional, time_column, keep)
        if layout is None:
            return None
        names, header_bytes, wanted, kept = layout
        lines_known = True
        try:
            columns = _read_compiled(path, names, header_bytes, wanted, kept, limits,
                                     min_rows, prescan)
        except (OSError, ValueError):
            columns = None
    finally:
        if prescan is not None:
            prescan.take()  # columns it reserved and nobody took: freed before any other try
    if columns is None:
        lines_known = False
        columns = _read_arrow(path, names, header_bytes, wanted, kept, limits, min_rows)
    if columns is None:
        return None
    if time_column is not None:
        columns = _sort_by_time(path, columns, time_column, lines_known)
    return columns
