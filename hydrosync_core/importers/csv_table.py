"""Validated reading of the numeric CSV files of ``formats.md``.

Fast path: numpy's C parser reads the whole file. Only when it fails (or a value is not
finite) is the file re-scanned line by line to name the exact line and field at fault,
so a 10-million-row point file loads at numpy speed while a bad file still gets a
precise one-line error.

Every data row must have as many fields as the header (a row with extra fields is an
error, not silently cut), values must lie in their plausible range when the reader gives
one (:mod:`hydrosync_core.plausible`), and hostile files (a field of megabytes, a header
of thousands of columns) end as one line quoting at most a few dozen characters.
"""

from __future__ import annotations

import csv
import io
import math
import os
import warnings
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np

from hydrosync_core import plausible
from hydrosync_core.errors import InputError, quote
from hydrosync_core.inputs import input_ok

MAX_COLUMNS = 1000
"""More header fields than this is not one of our tables."""

COUNT_BLOCK = 1 << 18
"""Lines whose commas are counted at once (bounds that count's memory)."""

FAST_MIN_BYTES = 1 << 21
"""Files of at least this size try :func:`~hydrosync_core.importers.fastcsv.read_numeric_fast`
first (same columns, or None and this reader decides); smaller ones are read here at once,
sparing the second it takes to load the compiled parser."""


def cells(path: Path, line: str, number: int) -> list[str]:
    """The comma-separated fields of one *line*; a field too long for csv is an InputError."""
    try:
        return next(csv.reader([line]), [])
    except csv.Error as exc:
        text = str(exc)
        if "field larger than field limit" in text:
            text = f"a field is longer than {csv.field_size_limit()} characters"
        raise InputError(str(path), f"unreadable CSV line: {text[:80]}", line=number) from None


def read_text_file(path: str | os.PathLike, allow_empty: bool = False) -> str:
    """The text of *path*, or one-line ``InputError`` naming it: missing, a folder, not
    UTF-8, or (unless *allow_empty*) empty. Shared by every text importer."""
    path = input_ok(path)  # a regular, readable text file (not a FIFO or device)
    try:
        text = path.read_text(encoding="utf-8-sig", errors="strict")
    except UnicodeDecodeError as exc:
        raise InputError(str(path), f"not a text file (byte {exc.start} is not UTF-8)") from None
    if not allow_empty and not text.strip():
        raise InputError(str(path), "file is empty")
    return text



def _header(path: Path, text: str) -> tuple[list[str], int]:
    """Return the lower-cased column names and the 1-based line number of the header."""
    for number, line in enumerate(text.splitlines(), start=1):
        if line.strip() and not line.lstrip().startswith("#"):
            names = [c.strip().lower() for c in cells(path, line, number)]
            if len(names) > MAX_COLUMNS:
                raise InputError(str(path), f"header has {len(names)} columns: not a table "
                                 "of this kind", line=number)
            return names, number
    raise InputError(str(path), "file has no header row")


def header_text(names: list[str]) -> str:
    """The header names for a message, clipped."""
    return quote(", ".join(names), 100)


def _scan_for_error(
    path: Path, text: str, header_line: int, names: list[str], wanted: list[int]
) -> InputError:
    """Find the first line that breaks the numeric parse and describe it."""
    lines = text.splitlines()
    for number in range(header_line + 1, len(lines) + 1):
        line = lines[number - 1]
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        fields = cells(path, line, number)
        if len(fields) != len(names):
            return InputError(
                str(path), f"expected {len(names)} fields, found {len(fields)}", line=number
            )
        for index in wanted:
            raw = fields[index].strip()
            try:
                value = float(raw)
            except ValueError:
                return InputError(
                    str(path), f"{quote(raw)} is not a number", line=number, field=names[index]
                )
            if not math.isfinite(value):
                return InputError(
                    str(path), f"value {quote(raw)} is not finite", line=number,
                    field=names[index]
                )
    return InputError(str(path), "could not parse the numeric columns")


def _check_field_counts(path: Path, body: str, first_line: int, n_fields: int) -> None:
    """Every data row has *n_fields* fields (vectorised comma count, csv on suspects)."""
    raw = np.frombuffer(body.encode("utf-8", "surrogatepass"), dtype=np.uint8)
    if raw.size == 0:
        return
    ends = np.flatnonzero(raw == 10)
    if ends.size == 0 or ends[-1] != raw.size - 1:
        ends = np.append(ends, raw.size)
    starts = np.concatenate([[0], ends[:-1] + 1])
    # Commas per line, a block of lines at a time: a cumulative count over the whole
    # body would take 8 bytes per byte of the file.
    count = np.empty(ends.size, dtype=np.int64)
    for a in range(0, ends.size, COUNT_BLOCK):
        b = min(a + COUNT_BLOCK, ends.size)
        lo = starts[a]
        commas = np.concatenate([[0], np.cumsum(raw[lo:ends[b - 1]] == 44)])
        count[a:b] = commas[ends[a:b] - lo] - commas[starts[a:b] - lo]
        del commas
    suspects = np.flatnonzero(count != n_fields - 1)
    if suspects.size == 0:
        return
    for k in suspects:
        line = bytes(raw[starts[k]:ends[k]]).decode("utf-8", "replace")
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        number = first_line + int(k)
        found = len(cells(path, line.rstrip("\r"), number))
        if found != n_fields:
            raise InputError(str(path), f"expected {n_fields} fields, found {found}",
                             line=number)


def _check_limits(path: Path, text: str, header_line: int,
                  columns: dict[str, np.ndarray], limits: Mapping[str, plausible.Limits]) -> None:
    for name, values in columns.items():
        if name not in limits:
            continue
        i = plausible.first_outside(values, limits[name])
        if i is not None:
            line = int(_data_line_numbers(text, header_line)[i])
            raise InputError(str(path), plausible.problem(float(values[i]), limits[name]),
                             line=line, field=name)


def read_numeric_csv(
    path: str | os.PathLike,
    required: Sequence[str],
    optional: Sequence[str] = (),
    *,
    time_column: str | None = "time",
    min_rows: int = 1,
    limits: Mapping[str, plausible.Limits] | None = None,
    fast: bool = True,
) -> dict[str, np.ndarray]:
    """Read a comma-separated numeric table with a header row.

    Parameters
    ----------
    path : path-like
        The CSV file.
    required, optional : sequence of str
        Column names (case-insensitive). Missing required columns are an error; optional
        ones are returned when present. Other columns are ignored.
    time_column : str or None
        If given, rows are sorted by this column (float64 seconds) and duplicate times
        are rejected with the two offending lines named.
    min_rows : int
        Fewer data rows than this is an error.
    limits : mapping of column name to (low, high, unit), optional
        Plausible range of each column; a value outside is an error naming its line.
    fast : bool
        Try the fast reader (:mod:`~hydrosync_core.importers.fastcsv`) first on files of
        at least :data:`FAST_MIN_BYTES`: it returns exactly what this function returns, or
        leaves the file to the line-by-line reading below (False: always the latter, the
        reference the fast reader is checked against).

    Returns
    -------
    dict of str to ndarray
        float64 1-D arrays keyed by lower-case column name, in *required* then
        *optional* order.

    Raises
    ------
    InputError
        With file, line and field for every problem.
    """
    path = Path(path)
    if fast and _size(path) >= FAST_MIN_BYTES:
        from hydrosync_core.importers.fastcsv import read_numeric_fast

        table = read_numeric_fast(path, required, optional, time_column=time_column,
                                  min_rows=min_rows, limits=limits)
        if table is not None:
            return table
    text = read_text_file(path)
    names, header_line = _header(path, text)
    missing = [c for c in required if c not in names]
    if missing:
        raise InputError(
            str(path),
            f"missing column(s) {', '.join(missing)} (header has: {header_text(names)})",
            line=header_line,
        )
    wanted_names = list(required) + [c for c in optional if c in names]
    wanted = [names.index(c) for c in wanted_names]
    body = "\n".join(text.splitlines()[header_line:])
    _check_field_counts(path, body, header_line + 1, len(names))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # "input contained no data": min_rows says it
            table = np.loadtxt(
                io.StringIO(body), delimiter=",", usecols=wanted, ndmin=2, dtype=np.float64,
                comments="#",
            )
    except (ValueError, IndexError):
        raise _scan_for_error(path, text, header_line, names, wanted) from None
    if table.shape[0] and not np.isfinite(table).all():
        raise _scan_for_error(path, text, header_line, names, wanted)
    if table.shape[0] < min_rows:
        raise InputError(
            str(path), f"has {table.shape[0]} data row(s); at least {min_rows} needed"
        )
    columns = {name: np.ascontiguousarray(table[:, i]) for i, name in enumerate(wanted_names)}
    if limits:
        _check_limits(path, text, header_line, columns, limits)
    if time_column is not None:
        columns = _sort_by_time(path, text, header_line, columns, time_column)
    return columns


def _size(path: Path) -> int:
    """Size of the regular file *path* in bytes, -1 for anything else."""
    try:
        return path.stat().st_size if path.is_file() else -1
    except OSError:
        return -1


def _data_line_numbers(text: str, header_line: int) -> np.ndarray:
    lines = text.splitlines()
    return np.array(
        [
            n
            for n in range(header_line + 1, len(lines) + 1)
            if lines[n - 1].strip() and not lines[n - 1].lstrip().startswith("#")
        ]
    )


def _sort_by_time(
    path: Path, text: str, header_line: int, columns: dict[str, np.ndarray], key: str
) -> dict[str, np.ndarray]:
    time = columns[key]
    order = np.argsort(time, kind="stable")
    sorted_time = time[order]
    dup = np.flatnonzero(np.diff(sorted_time) == 0)
    if dup.size:
        line_numbers = _data_line_numbers(text, header_line)
        first, second = sorted((line_numbers[order[dup[0]]], line_numbers[order[dup[0] + 1]]))
        raise InputError(
            str(path),
            f"duplicate time {float(sorted_time[dup[0]])!r} (also on line {first})",
            line=int(second), field=key,
        )
    if np.all(order == np.arange(order.size)):
        return columns
    return {name: values[order] for name, values in columns.items()}
