"""``antenna_positions.csv``: ECEF positions of every antenna of an array in one file.

Columns (docs/formats.md, GNSS attitude data set; header row, comma separated, names
matched case-insensitively, extra columns ignored, blank and ``#`` lines skipped):

| column | unit | required |
|---|---|---|
| time | s, any continuous scale shared by the antennas (GPS time of week, Unix s, …) | yes |
| antenna | antenna id: the name used in ``antennas.json`` | yes |
| x, y, z | m, ECEF (WGS84) of the antenna phase centre | yes |
| quality | int, NMEA GGA fix quality, as in ``gnss.csv`` (4 = RTK fixed, 5 = float) | yes |
| sdx, sdy, sdz | m, 1σ of x, y, z (no correlations) | no |

The GGA code is translated to the RTKLIB quality flag the attitude screening uses:
4 → 1 (fixed), 5 → 2 (float), 2 and 3 → 4 (DGPS), 1 → 5 (single), 6, 7 and 8 → 7
(estimated / manual / simulator). Rows with quality 0 (no fix) are dropped and counted.
Times are used as given (the output's ``time`` is this column, not a time of week), and
epochs of different antennas are matched after rounding (``epoch_rounding_s``).
"""

from __future__ import annotations

import csv
import io
import os
import re
from pathlib import Path

import numpy as np

from hydrosync_core.errors import InputError, quote
from hydrosync_core.geodesy import ecef_to_geodetic
from hydrosync_core.importers.csv_table import _data_line_numbers, read_numeric_csv, read_text_file

#: NMEA GGA fix quality → RTKLIB Q (1 fix, 2 float, 4 dgps, 5 single, 7 dead reckoning).
GGA_TO_Q = {4: 1, 5: 2, 2: 4, 3: 4, 1: 5, 6: 7, 7: 7, 8: 7}
ID_COLUMNS = ("antenna", "antenna_id")
_NAME = re.compile(r"[A-Za-z0-9_.\-]{1,64}")


def _antenna_ids(path: Path, text: str) -> tuple[list[str], np.ndarray]:
    """(antenna id per data row, line numbers) — the one non-numeric column."""
    rows = csv.reader(io.StringIO(text))
    header_line = 0
    header: list[str] = []
    for number, row in enumerate(rows, start=1):
        if row and row[0].strip() and not row[0].lstrip().startswith("#"):
            header, header_line = [c.strip().lower() for c in row], number
            break
    col = next((header.index(c) for c in ID_COLUMNS if c in header), None)
    if col is None:
        raise InputError(str(path), "missing column antenna (the antenna id of each row)",
                         line=header_line or None)
    lines = _data_line_numbers(text, header_line)
    all_lines = text.splitlines()
    ids = []
    for n in lines:
        cells = next(csv.reader([all_lines[n - 1]]))
        value = cells[col].strip() if col < len(cells) else ""
        if not _NAME.fullmatch(value):
            raise InputError(str(path), f"antenna id {quote(value, 30)} is not a name "
                             "(1-64 letters, digits, _ . -)", line=int(n), field="antenna")
        ids.append(value)
    return ids, lines


def read_antenna_csv(path: str | os.PathLike) -> dict[str, dict[str, np.ndarray]]:
    """Read the array's positions; ``{antenna id: columns}``.

    Columns per antenna, sorted by time: ``time``, ``gps_s`` (= time), ``x y z`` (ECEF m),
    ``lat lon height`` (deg, m), ``q`` (RTKLIB flag from the GGA code), ``quality`` (the
    GGA code) and, when given, ``sdx sdy sdz`` with zero ``sdxy sdyz sdzx``.

    Raises
    ------
    InputError
        Naming file, line and field: missing column, bad number, unknown quality code,
        a position not near the Earth, an antenna repeating a time, fewer than one row.
    """
    p = Path(path)
    cols = read_numeric_csv(p, ("time", "x", "y", "z", "quality"), ("sdx", "sdy", "sdz"),
                            time_column=None)
    text = read_text_file(p)
    ids, lines = _antenna_ids(p, text)
    if len(ids) != cols["time"].size:  # pragma: no cover - both skip the same lines
        raise InputError(str(p), "could not match antenna ids to rows")
    name = str(p)
    q = cols["quality"]
    bad = np.flatnonzero((q != np.round(q)) | ~np.isin(q, [0, *GGA_TO_Q]))
    if bad.size:
        raise InputError(name, f"quality {q[bad[0]]:g} is not a GGA fix quality 0-8",
                         line=int(lines[bad[0]]), field="quality")
    r = np.sqrt(cols["x"] ** 2 + cols["y"] ** 2 + cols["z"] ** 2)
    bad = np.flatnonzero(((r < 6.0e6) | (r > 5.0e7)) & (q != 0))  # no fix: may be zeros
    if bad.size:
        raise InputError(name, f"ECEF position {r[bad[0]]:.0f} m from the Earth's centre is "
                         "not near the Earth", line=int(lines[bad[0]]), field="x")
    for k in ("sdx", "sdy", "sdz"):
        if k in cols:
            bad = np.flatnonzero(cols[k] <= 0)
            if bad.size:
                raise InputError(name, "σ must be positive", line=int(lines[bad[0]]), field=k)
    ids_arr = np.array(ids)
    out: dict[str, dict[str, np.ndarray]] = {}
    keep_rows = q != 0
    for antenna in dict.fromkeys(ids):
        rows = np.flatnonzero((ids_arr == antenna) & keep_rows)
        if rows.size == 0:
            continue
        order = rows[np.argsort(cols["time"][rows], kind="stable")]
        t = cols["time"][order]
        dup = np.flatnonzero(np.diff(t) == 0.0)
        if dup.size:
            a, b = sorted((int(lines[order[dup[0]]]), int(lines[order[dup[0] + 1]])))
            raise InputError(name, f"antenna {antenna} repeats time {t[dup[0]]!r} (also on "
                             f"line {a})", line=b, field="time")
        table = {"time": t, "gps_s": t.copy()}
        for k in ("x", "y", "z"):
            table[k] = cols[k][order]
        table["lat"], table["lon"], table["height"] = ecef_to_geodetic(
            np.column_stack([table["x"], table["y"], table["z"]]))
        gga = cols["quality"][order].astype(np.int8)
        table["quality"] = gga
        table["q"] = np.array([GGA_TO_Q[int(v)] for v in gga], np.int8)
        if all(k in cols for k in ("sdx", "sdy", "sdz")):
            for k in ("sdx", "sdy", "sdz"):
                table[k] = cols[k][order]
            for k in ("sdxy", "sdyz", "sdzx"):
                table[k] = np.zeros(t.size)
        out[antenna] = table
    if not out:
        raise InputError(name, "no row with a fix (every quality is 0)", field="quality")
    return out


def dropped_no_fix(path: str | os.PathLike) -> int:
    """Rows with GGA quality 0 in the file (dropped by :func:`read_antenna_csv`)."""
    cols = read_numeric_csv(Path(path), ("quality",), time_column=None)
    return int(np.sum(cols["quality"] == 0))


def store_antenna_csv(project, target: str, path: Path, **options) -> str:
    """Import the array's CSV as one table per antenna, ``<target>/<antenna id>``."""
    tables = read_antenna_csv(path)
    for antenna, table in tables.items():
        project.put_table(f"{target}/{antenna}", table, source=str(path), antenna=antenna,
                          form="xyz", time_system="as in file", time_format="seconds",
                          quality="GGA fix quality mapped to RTKLIB Q", frame="ECEF WGS84",
                          units="m, deg, s")
    parts = ", ".join(f"{a} {t['time'].size}" for a, t in tables.items())
    return (f"{Path(path).name} -> /{target}/{{{','.join(tables)}}}: epochs {parts}; "
            f"{dropped_no_fix(path)} rows without fix dropped")
