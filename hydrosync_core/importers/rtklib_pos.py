"""RTKLIB solution files (``.pos``): every output form RTKLIB and its forks write.

Header lines start with ``%``; the column legend (the last ``%`` line naming ``Q`` and
``ns``) tells the form:

- llh: ``latitude(deg) longitude(deg) height(m) Q ns sdn sde sdu sdne sdeu sdun age ratio``
  (in dms mode latitude and longitude take three tokens each);
- xyz: ``x-ecef(m) y-ecef(m) z-ecef(m) Q ns sdx sdy sdz sdxy sdyz sdzx age ratio``;
- enu: ``e-baseline(m) n-baseline(m) u-baseline(m) Q ns sde sdn sdu sden sdnu sdue age
  ratio`` (relative to the header's ``ref pos``);

optionally followed by velocity columns (``vn ve vu sdvn …`` or ``vx vy vz …``). The time
takes two tokens, ``yyyy/mm/dd hh:mm:ss.sss`` or ``week tow``. Q may be written as a
float. The off-diagonal ``sd`` columns are signed square roots of the covariances,
``sign(c)·sqrt(|c|)``; :func:`ned_covariance` turns them back into covariances.

Columns returned (float64 unless noted, one row per epoch, sorted by time):

``time``
    GPS time of week (s) on the file's time scale (the legend's ``GPST``/``UTC``/…; the
    scale is kept in :attr:`PosData.time_system`). ``week`` (int) and ``gps_s`` =
    ``week·604800 + time`` (continuous seconds since 1980-01-06) come with it.
``x, y, z``
    ECEF (m) — computed for llh, and for enu when the header gives ``ref pos``.
``lat, lon, height``
    WGS84 (deg, deg, m) — computed for xyz.
``e, n, u``
    only for the enu form: baseline from the reference position (m).
``q`` (int8), ``ns`` (int16), the std/covariance columns under RTKLIB's names
(``sdn``, ``sdne``…; m), ``age`` (s), ``ratio`` and any velocity columns (``vn``…, m/s).

Bad input raises :class:`~hydrosync_core.errors.InputError` naming the file, the line
and the field.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from datetime import datetime
from pathlib import Path

import numpy as np

from hydrosync_core.errors import InputError, quote
from hydrosync_core.geodesy import ecef_to_geodetic, ecef_to_ned_matrix, geodetic_to_ecef
from hydrosync_core.importers.csv_table import read_text_file

GPS_EPOCH = datetime(1980, 1, 6)
WEEK_S = 604800.0
Q_NAMES = {1: "fix", 2: "float", 3: "sbas", 4: "dgps", 5: "single", 6: "ppp", 7: "dr"}

#: Legend token (unit stripped, lower case) -> column name.
_NAMES = {
    "latitude": "lat", "longitude": "lon", "height": "height",
    "x-ecef": "x", "y-ecef": "y", "z-ecef": "z",
    "e-baseline": "e", "n-baseline": "n", "u-baseline": "u",
    "q": "q", "ns": "ns", "age": "age", "ratio": "ratio",
}
_FORMS = {"llh": ("lat", "lon", "height"), "xyz": ("x", "y", "z"), "enu": ("e", "n", "u")}
_TIME_SYSTEMS = ("GPST", "UTC", "JST", "GST", "BDT", "TIME")
_FLOAT = re.compile(r"[-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?")


@dataclass
class PosData:
    """One RTKLIB solution file, read and checked.

    Attributes
    ----------
    path : str
    form : str
        ``"llh"``, ``"xyz"`` or ``"enu"``.
    time_system : str
        Time scale named by the legend (``GPST``, ``UTC``…; ``GPST`` when absent).
    time_format : str
        ``"calendar"`` (yyyy/mm/dd hh:mm:ss) or ``"week_tow"``.
    columns : dict of str to ndarray
        See the module docstring.
    ref_llh : tuple of float or None
        The header's ``ref pos`` (deg, deg, m) when given.
    legend_found : bool
        False when the form had to be inferred from the values.
    header : list of str
        The ``%`` lines.
    """

    path: str
    form: str
    time_system: str
    time_format: str
    columns: dict[str, np.ndarray]
    ref_llh: tuple[float, float, float] | None = None
    legend_found: bool = True
    header: list[str] = field(default_factory=list)

    @property
    def epochs(self) -> int:
        return int(self.columns["time"].size)

    def q_counts(self) -> dict[int, int]:
        """Number of epochs per quality flag Q."""
        values, counts = np.unique(self.columns["q"], return_counts=True)
        return {int(v): int(c) for v, c in zip(values, counts, strict=True)}

    def summary(self) -> str:
        qs = ", ".join(f"Q{k} ({Q_NAMES.get(k, '?')}) {v}" for k, v in self.q_counts().items())
        return (f"{self.epochs} epochs, {self.form} form, {self.time_system} "
                f"{self.time_format.replace('_', '/')} times; {qs}")

    def attrs(self) -> dict:
        """Attributes stored with the imported table."""
        out = {"form": self.form, "time_system": self.time_system,
               "time_format": self.time_format, "legend_found": self.legend_found,
               "frame": "ECEF WGS84", "units": "m, deg, s"}
        if self.ref_llh is not None:
            out["ref_llh"] = list(self.ref_llh)
        for k, v in self.q_counts().items():
            out[f"epochs_q{k}"] = v
        return out


def _legend(path: str, header: list[tuple[int, str]]) -> tuple[list[str], str, int] | None:
    """(column names after the time, time system, line number) of the legend, if any."""
    for number, line in reversed(header):
        tokens = line.lstrip("%").split()
        low = [t.split("(")[0].lower() for t in tokens]
        if "q" in low and "ns" in low:
            system = "GPST"
            start = 0
            if tokens and tokens[0].upper() in _TIME_SYSTEMS:
                system = tokens[0].upper()
                start = 1
            names = []
            for token in low[start:]:
                names.append(_NAMES.get(token, token))
            return names, system, number
    return None


def _ref_pos(header: list[tuple[int, str]]) -> tuple[float, float, float] | None:
    """The ``ref pos`` of the header as (lat, lon, height); values may be glued."""
    for _, line in header:
        body = line.lstrip("%").strip()
        if body.lower().startswith("ref pos"):
            values = [float(v) for v in _FLOAT.findall(body.partition(":")[2])]
            if len(values) == 3:
                return values[0], values[1], values[2]
            if len(values) == 7 or len(values) == 9:  # dms
                sign = [-1 if v < 0 else 1 for v in values]
                lat = sign[0] * (abs(values[0]) + values[1] / 60 + values[2] / 3600)
                lon = sign[3] * (abs(values[3]) + values[4] / 60 + values[5] / 3600)
                return lat, lon, values[-1]
    return None


def _infer_names(first: list[str]) -> list[str]:
    """Column names of a file without legend, from its first data row (standard order)."""
    tail = ["q", "ns"]
    try:
        v0 = abs(float(first[2]))
    except (ValueError, IndexError):
        v0 = 0.0
    if v0 > 1.0e5:
        return ["x", "y", "z", *tail, "sdx", "sdy", "sdz", "sdxy", "sdyz", "sdzx", "age",
                "ratio"]
    return ["lat", "lon", "height", *tail, "sdn", "sde", "sdu", "sdne", "sdeu", "sdun", "age",
            "ratio"]


def _time_of(path: str, number: int, t0: str, t1: str) -> tuple[int, float, str]:
    """(week, tow, format) of the two time tokens of a data row."""
    if "/" in t0:
        try:
            day = datetime.strptime(t0, "%Y/%m/%d")
            h, m, s = t1.split(":")
            seconds = (day - GPS_EPOCH).total_seconds() + int(h) * 3600 + int(m) * 60 + float(s)
        except ValueError:
            raise InputError(path, f"{quote(t0 + ' ' + t1)} is not a yyyy/mm/dd hh:mm:ss time",
                             line=number, field="time") from None
        week = int(seconds // WEEK_S)
        return week, seconds - week * WEEK_S, "calendar"
    try:
        week, tow = int(t0), float(t1)
    except ValueError:
        raise InputError(path, f"{quote(t0 + ' ' + t1)} is neither a date/time nor a GPS "
                         "week and TOW",
                         line=number, field="time") from None
    if not (0 <= week < 10000 and 0.0 <= tow < WEEK_S + 1.0):
        raise InputError(path, f"GPS week {week} / time of week {tow} out of range",
                         line=number, field="time")
    return week, tow, "week_tow"


def read_pos(path: str | os.PathLike) -> PosData:
    """Read and check one RTKLIB ``.pos`` file.

    Parameters
    ----------
    path : path-like
        The solution file.

    Returns
    -------
    PosData
        Columns sorted by time (see the module docstring).

    Raises
    ------
    InputError
        Missing or empty file, no data rows, a row with the wrong number of fields, a
        value that is not a finite number, an unknown Q, a repeated epoch.
    """
    name = str(Path(path))
    header, rows = _header_and_rows(name, read_text_file(Path(path), allow_empty=True))
    legend = _legend(name, header)
    names, system = (_infer_names(rows[0][1]), "GPST") if legend is None else legend[:2]
    form = next((f for f, cols in _FORMS.items() if all(c in names for c in cols)), None)
    if form is None:
        raise InputError(name, "the legend names neither lat/lon/height, x/y/z-ecef nor "
                         "e/n/u-baseline columns", line=legend[2] if legend else None)
    # dms mode: latitude and longitude take three tokens each.
    dms = form == "llh" and len(rows[0][1]) == 2 + len(names) + 4
    weeks, tows, values, formats = _parse_rows(name, rows, names, dms)
    out, order = _sorted_columns(name, rows, names, weeks, tows, values)
    ref = _ref_pos(header)
    _add_positions(name, out, form, ref, [rows[i][0] for i in order])
    return PosData(name, form, system, formats.pop(), out, ref, legend is not None,
                   [h for _, h in header])


def _header_and_rows(name: str, text: str) -> tuple[list[tuple[int, str]], list]:
    """``%`` header lines before the first row, and the data rows split into tokens, each
    with its line number."""
    header: list[tuple[int, str]] = []
    rows: list[tuple[int, list[str]]] = []
    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith("%"):
            if not rows:
                header.append((number, stripped))
            continue
        rows.append((number, stripped.split()))
    if not rows:
        raise InputError(name, "no solution rows (only % header lines)" if header
                         else "file is empty")
    return header, rows


def _dms_to_degrees(name: str, number: int, names: list[str], data: list[str]) -> list[str]:
    """Latitude and longitude written as ``d m s`` (three tokens each) as degrees."""
    merged = []
    for k in (0, 3):
        d, m, s = data[k:k + 3]
        sign = -1.0 if d.startswith("-") else 1.0
        try:
            merged.append(str(sign * (abs(float(d)) + float(m) / 60 + float(s) / 3600)))
        except ValueError:
            raise InputError(name, f"{quote(f'{d} {m} {s}')} is not d m s", line=number,
                             field=names[k // 3]) from None
    return merged + data[6:]


def _parse_rows(name: str, rows: list, names: list[str], dms: bool):
    """Week, time of week (s), values and the time formats seen, row by row."""
    n_cols = len(names)
    expected = 2 + n_cols + (4 if dms else 0)
    weeks = np.empty(len(rows), np.int64)
    tows = np.empty(len(rows))
    values = np.empty((len(rows), n_cols))
    formats = set()
    for i, (number, tokens) in enumerate(rows):
        if len(tokens) != expected:
            raise InputError(name, f"expected {expected} fields, found {len(tokens)}",
                             line=number)
        weeks[i], tows[i], fmt = _time_of(name, number, tokens[0], tokens[1])
        formats.add(fmt)
        data = _dms_to_degrees(name, number, names, tokens[2:]) if dms else tokens[2:]
        for j, token in enumerate(data):
            try:
                values[i, j] = float(token)
            except ValueError:
                raise InputError(name, f"'{token[:30]}' is not a number", line=number,
                                 field=names[j]) from None
        if not np.isfinite(values[i]).all():
            j = int(np.flatnonzero(~np.isfinite(values[i]))[0])
            raise InputError(name, "value is not finite", line=number, field=names[j])
    if len(formats) > 1:
        raise InputError(name, "mixes date/time and week/TOW time tags", field="time")
    return weeks, tows, values, formats


def _sorted_columns(name, rows, names, weeks, tows, values) -> tuple[dict, np.ndarray]:
    """Columns sorted by GPS time (``time`` = time of week, ``week``, ``gps_s``), Q and
    satellite counts as integers; a bad Q or a repeated epoch raises."""
    q = values[:, names.index("q")]
    bad = np.flatnonzero((q != np.round(q)) | (q < 0) | (q > 7))
    if bad.size:
        raise InputError(name, f"quality flag {q[bad[0]]:g} is not one of 0-7",
                         line=rows[bad[0]][0], field="Q")
    gps_s = weeks * WEEK_S + tows
    order = np.argsort(gps_s, kind="stable")
    sorted_t = gps_s[order]
    dup = np.flatnonzero(np.diff(sorted_t) == 0.0)
    if dup.size:
        a, b = order[dup[0]], order[dup[0] + 1]
        raise InputError(name, f"epoch {tows[a]:.3f} repeated (also on line {rows[a][0]})",
                         line=rows[b][0], field="time")
    out: dict[str, np.ndarray] = {"time": tows[order], "week": weeks[order],
                                  "gps_s": sorted_t}
    integer = {"q": np.int8, "ns": np.int16}
    for j, n in enumerate(names):
        v = values[order, j]
        out[n] = v.astype(integer[n]) if n in integer else v
    return out, order


def _add_positions(name: str, out: dict, form: str, ref, lines: list[int]) -> None:
    """Check the positions and add the other form (ECEF for llh and a referenced enu
    baseline, geodetic for xyz); *lines* are the sorted rows' line numbers."""
    if form == "llh":
        bad = np.flatnonzero((np.abs(out["lat"]) > 90) | (np.abs(out["lon"]) > 360))
        if bad.size:
            raise InputError(name, "latitude/longitude out of range", line=lines[bad[0]],
                             field="latitude")
        xyz = geodetic_to_ecef(out["lat"], out["lon"], out["height"])
        out["x"], out["y"], out["z"] = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    elif form == "xyz":
        r = np.sqrt(out["x"] ** 2 + out["y"] ** 2 + out["z"] ** 2)
        bad = np.flatnonzero((r < 6.0e6) | (r > 5.0e7))
        if bad.size:
            raise InputError(name, f"ECEF position {r[bad[0]]:.0f} m from the Earth's centre "
                             "is not near the Earth", line=lines[bad[0]], field="x-ecef")
        out["lat"], out["lon"], out["height"] = ecef_to_geodetic(
            np.column_stack([out["x"], out["y"], out["z"]]))
    elif ref is not None:  # enu baseline with a reference position: ECEF too
        c = ecef_to_ned_matrix(ref[0], ref[1])  # rows N, E, D
        ned = np.column_stack([out["n"], out["e"], -out["u"]])
        xyz = geodetic_to_ecef(*ref) + ned @ c
        out["x"], out["y"], out["z"] = xyz[:, 0], xyz[:, 1], xyz[:, 2]


def _signed_square(sd: np.ndarray) -> np.ndarray:
    """Covariance from RTKLIB's signed square root ``sign(c)·sqrt(|c|)``."""
    return np.sign(sd) * sd**2


def ned_covariance(columns: dict[str, np.ndarray], form: str | None = None) -> np.ndarray | None:
    """Per-epoch position covariance in the local NED frame (m², shape (N, 3, 3)), or None.

    Uses the std/covariance columns of the file's form: ``sdn sde sdu sdne sdeu sdun``
    (llh), ``sde sdn sdu sden sdnu sdue`` (enu) or ``sdx … sdzx`` (xyz, rotated to NED at
    each epoch's position). None when the columns are absent.
    """
    c = columns
    if all(k in c for k in ("sdn", "sde", "sdu")) and ("sdne" in c or "sden" in c):
        n = c["time"].size
        cov = np.zeros((n, 3, 3))
        ne = c["sdne"] if "sdne" in c else c["sden"]
        eu = c["sdeu"] if "sdeu" in c else c["sdue"]
        un = c["sdun"] if "sdun" in c else c["sdnu"]
        cov[:, 0, 0], cov[:, 1, 1], cov[:, 2, 2] = c["sdn"] ** 2, c["sde"] ** 2, c["sdu"] ** 2
        cne, ceu, cun = _signed_square(ne), _signed_square(eu), _signed_square(un)
        # NED: d = -u, so covariances with u change sign.
        cov[:, 0, 1] = cov[:, 1, 0] = cne
        cov[:, 1, 2] = cov[:, 2, 1] = -ceu
        cov[:, 0, 2] = cov[:, 2, 0] = -cun
        return cov
    if all(k in c for k in ("sdx", "sdy", "sdz", "sdxy", "sdyz", "sdzx")):
        n = c["time"].size
        cov = np.zeros((n, 3, 3))
        cov[:, 0, 0], cov[:, 1, 1], cov[:, 2, 2] = c["sdx"] ** 2, c["sdy"] ** 2, c["sdz"] ** 2
        cov[:, 0, 1] = cov[:, 1, 0] = _signed_square(c["sdxy"])
        cov[:, 1, 2] = cov[:, 2, 1] = _signed_square(c["sdyz"])
        cov[:, 0, 2] = cov[:, 2, 0] = _signed_square(c["sdzx"])
        rot = ecef_to_ned_matrix(c["lat"], c["lon"])
        return rot @ cov @ np.swapaxes(rot, -1, -2)
    return None


def store_pos(project, target: str, path: Path, **options) -> str:
    """Import one antenna's ``.pos`` file as table ``<target>/<file stem>``.

    The file's stem names the antenna (``A1.pos`` → ``A1``), as in ``hydrosync attitude``.
    Attributes: the form, time scale and format, Q counts, the source file.
    """
    data = read_pos(path)
    stem = Path(path).stem
    if not re.fullmatch(r"[A-Za-z0-9_.\-]+", stem):
        raise InputError(str(path), f"file name '{stem}' cannot name an antenna "
                         "(letters, digits, _ . - only)")
    project.put_table(f"{target}/{stem}", data.columns, source=str(path), antenna=stem,
                      **data.attrs())
    return f"{Path(path).name} -> /{target}/{stem}: {data.summary()}"
