"""Readers and writers of the GNSS/INS files (KF-GINS text formats and documented CSV).

KF-GINS text files (whitespace, comma or tab separated, no header; ``docs/formats.md``):

* IMU, 7 columns: time (GPS s of week, end of the interval), angle increments x y z (rad),
  velocity increments x y z (m/s), body FRD; an 8th column (odometer) is ignored.
* GNSS, 7 columns: time, latitude, longitude (deg), ellipsoidal height (m), std N E D (m)
  of the **antenna**; the 13-column variant carries the std in columns 8-10.
* ``.nav``, 11 columns: week, time, lat, lon (deg), h (m), vN vE vD (m/s), roll, pitch,
  yaw (deg) of the IMU centre.

CSV forms (one header row, names case-insensitive, ``#`` lines skipped):

* ``imu.csv``: ``time`` and either increments ``dtheta_x, dtheta_y, dtheta_z`` (rad) and
  ``dvel_x, dvel_y, dvel_z`` (m/s) over the interval ending at ``time``, or rates
  ``gyro_x, gyro_y, gyro_z`` (deg/s) and ``acc_x, acc_y, acc_z`` (m/s², specific force),
  integrated by the trapezoid rule; body x forward, y right, z down.
* ``gnss.csv``: ``time, lat, lon, height`` (deg, deg, m, antenna) and optional
  ``sd_n, sd_e, sd_d`` (m; default 0.02, 0.02, 0.04).

Every reader returns float64 arrays sorted by time and raises :class:`InputError` naming
file, line and field for bad input.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hydrosync_core.atomic import write_text_atomic
from hydrosync_core.errors import InputError, quote
from hydrosync_core.inputs import input_ok

DEFAULT_GNSS_STD = (0.02, 0.02, 0.04)


@dataclass
class ImuData:
    """IMU increments: ``time`` (n,) s and ``inc`` (n, 6): Δθ xyz (rad), Δv xyz (m/s)."""

    time: np.ndarray
    inc: np.ndarray
    source: str = ""

    @property
    def rate_hz(self) -> float:
        d = np.diff(self.time)
        return float(1.0 / np.median(d)) if d.size else float("nan")


@dataclass
class GnssData:
    """GNSS antenna positions: ``time`` (m,) s, ``llh`` (m, 3) deg/deg/m, ``std`` (m, 3) m.

    ``vel`` (m, 3) NED m/s, optional (NaN where unknown): the receiver's velocity, used
    only by the moving alignment.
    """

    time: np.ndarray
    llh: np.ndarray
    std: np.ndarray
    source: str = ""
    vel: np.ndarray | None = None

    def without(self, windows) -> GnssData:
        """A copy without the epochs strictly inside any ``(start, end)`` window (s)."""
        keep = np.ones(self.time.size, bool)
        for a, b in windows:
            keep &= ~((self.time > a) & (self.time < b))
        return GnssData(self.time[keep], self.llh[keep], self.std[keep], self.source,
                        None if self.vel is None else self.vel[keep])


@dataclass
class NavData:
    """A trajectory: ``time`` (n,) s, ``llh`` (n, 3) deg/deg/m, ``vel`` (n, 3) NED m/s,
    ``att`` (n, 3) roll, pitch, yaw deg."""

    time: np.ndarray
    llh: np.ndarray
    vel: np.ndarray
    att: np.ndarray
    source: str = ""


def _read_text(path) -> tuple[str, str]:
    p = Path(path)
    if p.exists():
        input_ok(p)  # a FIFO, device or sparse file is refused before reading
    try:
        text = p.read_text(encoding="utf-8-sig")
    except FileNotFoundError:
        raise InputError(str(p), "file not found") from None
    except IsADirectoryError:
        raise InputError(str(p), "is a folder, not a file") from None
    except UnicodeDecodeError:
        raise InputError(str(p), "not a text file") from None
    except OSError as exc:
        raise InputError(str(p), f"cannot read: {exc.strerror}") from None
    return str(p), text


def _numeric_table(path, text: str, min_cols: int, names: list[str]) -> np.ndarray:
    """Numbers of a headerless whitespace/comma/tab table with at least *min_cols* columns.

    The first bad line is named in the error (line numbers count every line).
    """
    clean = text.replace(",", " ").replace("\t", " ") if ("," in text or "\t" in text) else text
    try:
        with np.errstate(all="ignore"):
            data = np.loadtxt(_lines(clean), ndmin=2, comments="#")
        if data.size == 0:
            raise InputError(path, "no data lines")
        if data.shape[1] < min_cols:
            raise ValueError
        if np.all(np.isfinite(data[:, :min_cols])):
            return data[:, :min_cols]
    except ValueError:
        pass
    for lineno, line in enumerate(clean.splitlines(), 1):
        parts = line.split("#", 1)[0].split()
        if not parts:
            continue
        if len(parts) < min_cols:
            raise InputError(path, f"{len(parts)} columns, expected {min_cols}", line=lineno,
                             field=names[min(len(parts), min_cols - 1)])
        for c in range(min_cols):
            try:
                v = float(parts[c])
            except ValueError:
                raise InputError(path, f"not a number: {quote(parts[c])}", line=lineno,
                                 field=names[c]) from None
            if not math.isfinite(v):
                raise InputError(path, "not a finite number", line=lineno, field=names[c])
    raise InputError(path, f"lines with different numbers of columns (expected {min_cols})")


def _lines(text: str):
    """The lines of *text* one by one (loadtxt without a second full copy)."""
    start = 0
    n = len(text)
    while start < n:
        end = text.find("\n", start)
        if end < 0:
            end = n
        yield text[start:end]
        start = end + 1


def _data_lines(text: str) -> np.ndarray:
    """1-based line numbers of the non-blank, non-comment lines."""
    return np.array([i for i, ln in enumerate(text.splitlines(), 1)
                     if ln.split("#", 1)[0].strip()], dtype=np.int64)


def _sorted(path, time: np.ndarray, text: str) -> np.ndarray:
    """Order that sorts *time*; an error naming both lines for a repeated time."""
    order = np.argsort(time, kind="stable")
    ts = time[order]
    dup = np.flatnonzero(np.diff(ts) == 0)
    if dup.size:
        lines = _data_lines(text)
        a, b = sorted((int(lines[order[dup[0]]]), int(lines[order[dup[0] + 1]])))
        raise InputError(path, f"time {ts[dup[0]]!r} repeated (also on line {a})", line=b,
                         field="time")
    return order


def _is_csv_with_header(text: str) -> bool:
    for line in text.splitlines():
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        return bool(re.search(r"[A-Za-z_]{2,}", s.split(",")[0]))
    return False


def _csv_columns(path, text: str, required: list[str], optional: list[str] = ()
                 ) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Columns of a CSV with a header (case-insensitive names); line numbers per row."""
    rows = []
    header = None
    lines = []
    for lineno, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if not s or s.startswith("#"):
            continue
        cells = [c.strip() for c in s.split(",")]
        if header is None:
            header = [c.lower() for c in cells]
            continue
        rows.append(cells)
        lines.append(lineno)
    if header is None or not rows:
        raise InputError(path, "no header or no data rows")
    for name in required:
        if name not in header:
            raise InputError(path, f"no column '{name}' in the header", line=1, field=name)
    out = {}
    for name in list(required) + [o for o in optional if o in header]:
        c = header.index(name)
        col = np.empty(len(rows))
        for i, cells in enumerate(rows):
            try:
                col[i] = float(cells[c])
            except (ValueError, IndexError):
                raise InputError(path, "not a number" if c < len(cells) else "missing",
                                 line=lines[i], field=name) from None
            if not math.isfinite(col[i]):
                raise InputError(path, "not a finite number", line=lines[i], field=name)
        out[name] = col
    return out, np.asarray(lines)


def read_imu(path: str | os.PathLike, nominal_rate_hz: float | None = None) -> ImuData:
    """Read KF-GINS IMU increments (7 or 8 columns) or ``imu.csv`` (module docstring)."""
    src, text = _read_text(path)
    if _is_csv_with_header(text):
        inc_names = ["dtheta_x", "dtheta_y", "dtheta_z", "dvel_x", "dvel_y", "dvel_z"]
        rate_names = ["gyro_x", "gyro_y", "gyro_z", "acc_x", "acc_y", "acc_z"]
        head = text.lstrip().splitlines()[0].lower()
        names = inc_names if "dtheta_x" in head else rate_names
        cols, _ = _csv_columns(src, text, ["time"] + names)
        t = cols["time"]
        order = _sorted(src, t, text)
        t = t[order]
        vals = np.column_stack([cols[n][order] for n in names])
        if names is rate_names:
            vals[:, :3] = np.radians(vals[:, :3])
            dt = np.diff(t)
            d0 = 1.0 / nominal_rate_hz if nominal_rate_hz else (float(np.median(dt))
                                                              if dt.size else 0.01)
            inc = np.empty_like(vals)
            inc[0] = vals[0] * d0
            inc[1:] = 0.5 * (vals[1:] + vals[:-1]) * dt[:, None]
            vals = inc
        data = ImuData(t, vals, src)
    else:
        names = ["time", "dtheta_x", "dtheta_y", "dtheta_z", "dvel_x", "dvel_y", "dvel_z"]
        arr = _numeric_table(src, text, 7, names)
        order = _sorted(src, arr[:, 0], text)
        arr = arr[order]
        data = ImuData(np.ascontiguousarray(arr[:, 0]), np.ascontiguousarray(arr[:, 1:7]), src)
    if data.time.size < 2:
        raise InputError(src, "fewer than two IMU epochs")
    big = np.flatnonzero(np.abs(data.inc[:, :3]).max(axis=1) > 1.0)
    if big.size:
        raise InputError(src, "angle increment above 1 rad in one interval: not increments "
                         "in radians (rates or degrees?)", line=int(big[0]) + 1,
                         field="dtheta")
    return data


def read_gnss(path: str | os.PathLike) -> GnssData:
    """Read KF-GINS GNSS positions (7 or 13 columns) or ``gnss.csv`` (module docstring)."""
    src, text = _read_text(path)
    if _is_csv_with_header(text):
        cols, _ = _csv_columns(src, text, ["time", "lat", "lon", "height"],
                               ["sd_n", "sd_e", "sd_d"])
        t = cols["time"]
        llh = np.column_stack([cols["lat"], cols["lon"], cols["height"]])
        std = np.column_stack([cols.get(k, np.full(t.size, d)) for k, d in
                               zip(("sd_n", "sd_e", "sd_d"), DEFAULT_GNSS_STD, strict=True)])
    else:
        first = next((ln for ln in text.splitlines() if ln.split("#", 1)[0].strip()), "")
        ncol = len(first.replace(",", " ").split())
        names = ["time", "lat", "lon", "height", "sd_n", "sd_e", "sd_d"]
        if ncol >= 13:
            arr = _numeric_table(src, text, 10, names[:4] + ["c5", "c6", "c7"] + names[4:])
            arr = arr[:, [0, 1, 2, 3, 7, 8, 9]]
        else:
            arr = _numeric_table(src, text, 7, names)
        t, llh, std = arr[:, 0], arr[:, 1:4], arr[:, 4:7]
    order = _sorted(src, t, text)
    t, llh, std = t[order], llh[order], std[order]
    off = 1 if _is_csv_with_header(text) else 0
    bad = np.flatnonzero(~((np.abs(llh[:, 0]) <= 90) & (np.abs(llh[:, 1]) <= 360)))
    if bad.size:
        raise InputError(src, "latitude/longitude out of range (degrees expected)",
                         line=int(_data_lines(text)[order[bad[0]] + off]), field="lat")
    bad = np.flatnonzero(~(std > 0).all(axis=1))
    if bad.size:
        raise InputError(src, "position std must be positive (KF-GINS gives NaN with 0)",
                         line=int(_data_lines(text)[order[bad[0]] + off]), field="sd_n")
    return GnssData(np.ascontiguousarray(t), np.ascontiguousarray(llh),
                    np.ascontiguousarray(std), src)


def read_nav(path: str | os.PathLike) -> NavData:
    """Read an 11-column KF-GINS ``.nav`` trajectory (module docstring)."""
    src, text = _read_text(path)
    names = ["week", "time", "lat", "lon", "height", "vn", "ve", "vd", "roll", "pitch", "yaw"]
    arr = _numeric_table(src, text, 11, names)
    order = _sorted(src, arr[:, 1], text)
    arr = arr[order]
    return NavData(arr[:, 1].copy(), arr[:, 2:5].copy(), arr[:, 5:8].copy(),
                   arr[:, 8:11].copy(), src)


def read_outages(path: str | os.PathLike) -> list[tuple[float, float]]:
    """Outage windows, one ``start end`` (s) per line (``outages_60s_every180s.txt``)."""
    src, text = _read_text(path)
    arr = _numeric_table(src, text, 2, ["start", "end"])
    bad = np.flatnonzero(arr[:, 1] <= arr[:, 0])
    if bad.size:
        raise InputError(src, "end not after start", line=int(_data_lines(text)[bad[0]]),
                         field="end")
    return [(float(a), float(b)) for a, b in arr]


def std_path(nav_path: str | os.PathLike) -> Path:
    """The sibling standard-deviation file of a ``.nav`` output: ``NAME_std.nav``."""
    p = Path(nav_path)
    return p.with_name(p.stem + "_std" + (p.suffix or ".nav"))


def write_nav(path: str | os.PathLike, time, llh_deg, vel, att_deg, week: int = 0,
              std: tuple | None = None) -> None:
    """Write an 11-column KF-GINS ``.nav`` (atomically); yaw wrapped to [0, 360).

    With *std* = ``(pos_std (n,3) m N/E/D, vel_std (n,3) m/s, att_std (n,3) deg)`` the
    sibling :func:`std_path` file gets the same 11-column layout with the standard
    deviations in place of the values.
    """
    t = np.asarray(time, float)
    llh = np.asarray(llh_deg, float)
    v = np.asarray(vel, float)
    a = np.asarray(att_deg, float).copy()
    a[:, 2] = np.mod(a[:, 2], 360.0)
    body = np.column_stack([np.full(t.size, week), t, llh, v, a])
    fmt = "%d %.9f %.11f %.11f %.5f %.6f %.6f %.6f %.8f %.8f %.8f"

    def writer(fh) -> None:
        np.savetxt(fh, body, fmt=fmt)

    write_text_atomic(path, writer)
    if std is not None:
        ps, vs, as_ = (np.asarray(s, float) for s in std)
        sbody = np.column_stack([np.full(t.size, week), t, ps, vs, as_])
        sfmt = "%d %.9f %.6f %.6f %.6f %.6f %.6f %.6f %.8f %.8f %.8f"
        write_text_atomic(std_path(path), lambda fh: np.savetxt(fh, sbody, fmt=sfmt))
