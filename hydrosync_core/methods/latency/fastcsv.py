"""Fast reading of the latency CSV files (gnss.csv, attitude.csv) for ``hydrosync latency``.

A survey day of 100 Hz attitude is ~8 million rows (330 MB). The validated generic reader
(:mod:`hydrosync_core.importers.csv_table`) holds the whole text and its lines in memory
and takes tens of seconds; here pyarrow's multi-threaded CSV parser reads the numeric
columns directly. Only files that are plainly well-formed take this path: pure ASCII,
the header on the first line, no comment (``#``) or quote characters, every row with the
header's field count, every wanted value a finite number inside its plausible range, and
strictly increasing times. Anything else — and any pyarrow failure — goes to the generic
reader, which returns the same columns or raises the same one-line :class:`InputError`
naming file, line and field. The returned dicts are identical (float64 columns, same
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


def _read_fast(path: Path, required: Sequence[str], optional: Sequence[str],
               limits: Mapping[str, plausible.Limits], min_rows: int,
               keep: Sequence[str] | None = None) -> dict | None:
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
