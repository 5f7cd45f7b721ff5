"""Readers for the latency and pool-calibration CSV files of ``formats.md``.

Every reader returns a dict of float64 1-D arrays (time-sorted) or raises
:class:`~hydrosync_core.errors.InputError` naming file, line and field. Values outside
their physically plausible range (:mod:`hydrosync_core.plausible`: a roll beyond ±180°,
a coordinate beyond ±1e8 m, …) are errors, and survey lines may neither repeat nor
overlap in time.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from hydrosync_core import plausible
from hydrosync_core.errors import InputError, quote
from hydrosync_core.importers.csv_table import (
    _header,
    cells,
    header_text,
    read_numeric_csv,
    read_text_file,
)


def read_gnss_csv(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """GNSS heights: ``time`` (s), ``height`` (m, ellipsoidal), optional lat/lon (deg), quality."""
    return read_numeric_csv(path, ["time", "height"], ["lat", "lon", "quality"], min_rows=2,
                            limits=plausible.GNSS)


def read_attitude_csv(
    path: str | os.PathLike, heave_positive: str = "up"
) -> dict[str, np.ndarray]:
    """Attitude: time (s), roll, pitch, heading (deg), heave (m).

    ``formats.md`` fixes heave positive up; a file written positive down (Kongsberg
    convention) is read with ``heave_positive="down"`` — stated, never guessed. The
    returned heave is always positive up.
    """
    if heave_positive not in ("up", "down"):
        raise InputError(str(path), f"heave sign must be 'up' or 'down', not {heave_positive!r}")
    table = read_numeric_csv(path, ["time", "roll", "pitch", "heading", "heave"], min_rows=2,
                             limits=plausible.ATTITUDE)
    if heave_positive == "down":
        table["heave"] = -table["heave"]
    return table


def read_lines_csv(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """Survey lines: ``name`` (text), ``start`` and ``end`` (s), one line per row.

    Returns ``{"name": str array, "start": float64, "end": float64}`` sorted by start.
    A line listed twice, or two lines overlapping in time, is an error: each GNSS epoch
    would be counted twice and the 95 % interval of the latency narrowed falsely.
    """
    path = Path(path)
    text = read_text_file(path)
    names, header_line = _header(path, text)
    for column in ("name", "start", "end"):
        if column not in names:
            raise InputError(
                str(path), f"missing column {column} (header has: {header_text(names)})",
                line=header_line,
            )
    rows: list[tuple[str, float, float, int]] = []
    seen: dict[str, int] = {}
    lines = text.splitlines()
    for number in range(header_line + 1, len(lines) + 1):
        raw = lines[number - 1]
        if not raw.strip() or raw.lstrip().startswith("#"):
            continue
        fields = cells(path, raw, number)
        if len(fields) != len(names):
            raise InputError(
                str(path), f"expected {len(names)} fields, found {len(fields)}", line=number
            )
        record = dict(zip(names, (c.strip() for c in fields), strict=True))
        values = []
        for column in ("start", "end"):
            try:
                value = float(record[column])
            except ValueError:
                raise InputError(
                    str(path), f"{quote(record[column])} is not a number", line=number,
                    field=column
                ) from None
            if not math.isfinite(value):
                raise InputError(str(path), "value is not finite", line=number, field=column)
            if plausible.first_outside(np.array([value]), plausible.TIME) is not None:
                raise InputError(str(path), plausible.problem(value, plausible.TIME),
                                 line=number, field=column)
            values.append(value)
        name = record["name"]
        if not name:
            raise InputError(str(path), "empty line name", line=number, field="name")
        if len(name) > 200:
            raise InputError(str(path), f"line name {quote(name)} is too long", line=number,
                             field="name")
        if name in seen:
            raise InputError(
                str(path), f"line name {quote(name)} already used on line {seen[name]}",
                line=number, field="name",
            )
        if values[1] <= values[0]:
            raise InputError(
                str(path), f"end {values[1]} is not after start {values[0]}",
                line=number, field="end",
            )
        seen[name] = number
        rows.append((name, values[0], values[1], number))
    if not rows:
        raise InputError(str(path), "no survey lines in file")
    rows.sort(key=lambda r: r[1])
    table = {
        "name": np.array([r[0] for r in rows], dtype=str),
        "start": np.array([r[1] for r in rows]),
        "end": np.array([r[2] for r in rows]),
    }
    from hydrosync_core.project.validate import check_lines

    check_lines(str(path), None, table, line_numbers=[r[3] for r in rows])
    return table


def read_lidar_csv(path: str | os.PathLike) -> np.ndarray:
    """Laser points ``x, y, z`` in the target ENU frame, metres, shape (N, 3)."""
    table = read_numeric_csv(path, ["x", "y", "z"], time_column=None, min_rows=3,
                             limits=plausible.POINTS)
    return np.column_stack([table["x"], table["y"], table["z"]])


def read_mbes_csv(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """Multibeam soundings: ping ``time`` (s) and x, y, z in the sensor frame FRD (m).

    Several beams share one ping time, so duplicate times are allowed; rows are sorted
    by time (stable, keeping beam order).
    """
    table = read_numeric_csv(path, ["time", "x", "y", "z"], time_column=None, min_rows=3,
                             limits=plausible.MBES)
    order = np.argsort(table["time"], kind="stable")
    return {k: v[order] for k, v in table.items()}


def read_ins_csv(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """INS trajectory: time (s), e, n, u (target ENU, m), roll, pitch, heading (deg)."""
    return read_numeric_csv(
        path, ["time", "e", "n", "u", "roll", "pitch", "heading"], min_rows=2,
        limits=plausible.INS,
    )
