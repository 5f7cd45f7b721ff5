"""Calendar-time geodetic position files with σ (``.geo``): one antenna per file.

The per-receiver output of the UPV MUIGG course software (network-RTK receivers, e.g.
``VRS-TR8-REC2_0.geo``) and of similar loggers: plain ASCII, no header, whitespace
separated, 12 columns per row::

    year month day hour minute second  lat(deg) lon(deg) h(m)  σlat(m) σlon(m) σh(m)

Coordinates are geodetic (ETRS89/GRS80 ≈ WGS84 at the centimetre level for baselines of
metres), heights ellipsoidal, σ in metres. The file carries **no quality flag**: every
row is taken as an accepted (RTK-fixed, Q=1) solution and left to the baseline-length
screening; the table's attributes say so. Seconds may read ``9.999`` for ``10.000``: times
are rounded to ``round_s`` (default 0.01 s) and the number of tags moved is recorded.

Times: the calendar date/time is converted to continuous seconds since 1980-01-06 (``gps_s``)
and GPS week / time of week on **the file's own scale**, with no leap seconds applied —
files labelled "UTC" that are really GPS time (or the reverse) stay consistent among
themselves, and the offset to another device is the caller's business.

Returns the column set of :func:`hydrosync_core.importers.rtklib_pos.read_pos` for the llh
form (``time week gps_s lat lon height x y z q sdn sde sdu sdne sdeu sdun``), so
``hydrosync attitude`` and the project import treat both alike.
"""

from __future__ import annotations

import os
import re
from datetime import datetime
from pathlib import Path

import numpy as np

from hydrosync_core.errors import InputError, quote
from hydrosync_core.geodesy import geodetic_to_ecef
from hydrosync_core.importers.csv_table import read_text_file

GPS_EPOCH = datetime(1980, 1, 6)
WEEK_S = 604800.0
N_COLUMNS = 12
FIELDS = ("year", "month", "day", "hour", "minute", "second", "latitude", "longitude",
          "height", "sigma_lat", "sigma_lon", "sigma_height")


def looks_like_geo(path: str | os.PathLike) -> bool:
    """True when the first data line has 12 numeric fields starting with a plausible date."""
    try:
        with open(path, encoding="utf-8-sig", errors="replace") as fh:
            for line in fh:
                tokens = line.split()
                if not tokens:
                    continue
                if len(tokens) != N_COLUMNS:
                    return False
                try:
                    values = [float(t) for t in tokens]
                except ValueError:
                    return False
                return 1980 <= values[0] <= 2200 and 1 <= values[1] <= 12
    except OSError:
        return False
    return False


def read_geo(path: str | os.PathLike, round_s: float = 0.01) -> dict[str, np.ndarray]:
    """Read one antenna's ``.geo`` position file.

    Parameters
    ----------
    path : path-like
    round_s : float
        Times are rounded to this (s) — receiver tags like ``9.999`` become ``10.00``.

    Returns
    -------
    dict of str to ndarray
        Sorted by time: ``time`` (time of week, s, file scale), ``week``, ``gps_s``,
        ``lat``, ``lon`` (deg), ``height`` (m), ``x y z`` (ECEF m), ``q`` (1: no flag in
        the file), ``ns`` (0: unknown), ``sdn sde sdu`` (m; σlat, σlon, σh) and
        ``sdne sdeu sdun`` (0: not given). :func:`read_geo_with_info` also returns how
        many time tags were rounded.

    Raises
    ------
    InputError
        Missing/empty file, a row without 12 numbers, an invalid date, a value that is not
        finite or out of range (latitude, longitude, σ ≤ 0), a repeated epoch.
    """
    return read_geo_with_info(path, round_s)[0]


def read_geo_with_info(path: str | os.PathLike,
                       round_s: float = 0.01) -> tuple[dict[str, np.ndarray], dict]:
    """:func:`read_geo` plus an info dict (``epochs``, ``rounded``, ``first``, ``last``)."""
    p = Path(path)
    name = str(p)
    text = read_text_file(p, allow_empty=True)
    numbers: list[int] = []
    rows: list[list[float]] = []
    for number, line in enumerate(text.splitlines(), start=1):
        tokens = line.split()
        if not tokens or tokens[0].startswith("#"):
            continue
        if len(tokens) != N_COLUMNS:
            raise InputError(name, f"expected {N_COLUMNS} fields (date, time, lat, lon, h, "
                             f"3 σ), found {len(tokens)}", line=number)
        values = []
        for j, token in enumerate(tokens):
            try:
                v = float(token)
            except ValueError:
                raise InputError(name, f"{quote(token, 30)} is not a number", line=number,
                                 field=FIELDS[j]) from None
            if not np.isfinite(v):
                raise InputError(name, "value is not finite", line=number, field=FIELDS[j])
            values.append(v)
        numbers.append(number)
        rows.append(values)
    if not rows:
        raise InputError(name, "file is empty (no position rows)")
    a = np.array(rows)
    lines = np.array(numbers)
    seconds = np.empty(len(rows))
    for i, r in enumerate(a):
        try:
            day = datetime(int(r[0]), int(r[1]), int(r[2]))
        except ValueError:
            raise InputError(name, f"{int(r[0])}-{int(r[1])}-{int(r[2])} is not a date",
                             line=int(lines[i]), field="day") from None
        if (r[0:3] != np.round(r[0:3])).any() or not (0 <= r[3] < 24 and 0 <= r[4] < 60
                                                       and 0 <= r[5] < 61):
            raise InputError(name, "date/time out of range", line=int(lines[i]), field="hour")
        seconds[i] = (day - GPS_EPOCH).total_seconds() + r[3] * 3600 + r[4] * 60 + r[5]
    rounded = np.round(seconds / round_s) * round_s
    moved = int(np.sum(np.abs(rounded - seconds) > 1e-6))
    lat, lon = a[:, 6], a[:, 7]
    for col, ok, what in ((6, np.abs(lat) <= 90, "latitude"), (7, np.abs(lon) <= 360,
                                                               "longitude"),
                          (9, a[:, 9] > 0, "σ must be positive"),
                          (10, a[:, 10] > 0, "σ must be positive"),
                          (11, a[:, 11] > 0, "σ must be positive")):
        bad = np.flatnonzero(~ok)
        if bad.size:
            raise InputError(name, f"{what} out of range" if col < 9 else what,
                             line=int(lines[bad[0]]), field=FIELDS[col])
    order = np.argsort(rounded, kind="stable")
    t = rounded[order]
    dup = np.flatnonzero(np.diff(t) == 0.0)
    if dup.size:
        first, second = sorted((int(lines[order[dup[0]]]), int(lines[order[dup[0] + 1]])))
        raise InputError(name, f"epoch repeated after rounding to {round_s:g} s (also on "
                         f"line {first})", line=second, field="second")
    a = a[order]
    week = np.floor(t / WEEK_S)
    xyz = geodetic_to_ecef(a[:, 6], a[:, 7], a[:, 8])
    n = t.size
    zeros = np.zeros(n)
    cols = {"time": t - week * WEEK_S, "week": week.astype(np.int64), "gps_s": t,
            "lat": a[:, 6], "lon": a[:, 7], "height": a[:, 8],
            "x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2],
            "q": np.ones(n, np.int8), "ns": np.zeros(n, np.int16),
            "sdn": a[:, 9], "sde": a[:, 10], "sdu": a[:, 11],
            "sdne": zeros, "sdeu": zeros.copy(), "sdun": zeros.copy()}
    info = {"epochs": n, "rounded": moved, "first_gps_s": float(t[0]),
            "last_gps_s": float(t[-1])}
    return cols, info


def store_geo(project, target: str, path: Path, **options) -> str:
    """Import one antenna's ``.geo`` file as table ``<target>/<file stem>``.

    The stem names the antenna (``REC2.geo`` → ``REC2``), as for ``.pos`` files.
    """
    cols, info = read_geo_with_info(path)
    stem = Path(path).stem
    if not re.fullmatch(r"[A-Za-z0-9_.\-]+", stem):
        raise InputError(str(path), f"file name '{stem}' cannot name an antenna "
                         "(letters, digits, _ . - only)")
    project.put_table(f"{target}/{stem}", cols, source=str(path), antenna=stem,
                      form="llh", time_system="as in file (no leap seconds applied)",
                      time_format="calendar", quality="not in file: all rows taken as Q=1",
                      times_rounded=info["rounded"], frame="ECEF WGS84", units="m, deg, s",
                      epochs_q1=info["epochs"])
    return (f"{Path(path).name} -> /{target}/{stem}: {info['epochs']} epochs (.geo, no "
            f"quality flag: all taken as fixed; {info['rounded']} time tags rounded)")
