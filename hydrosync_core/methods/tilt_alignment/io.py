"""The tilt-pole data set of ``docs/formats.md``: ``imu.csv``, ``gnss.csv``, ``pole.json``.

``imu.csv``: ``time, gx, gy, gz, ax, ay, az`` — angular rate (rad/s) and specific force
(m/s²) in the IMU body frame (x forward, y right, z down along the pole towards the tip).
``gnss.csv``: ``time, e, n, u`` (local ENU, m) or ``time, lat, lon, height`` (deg, deg, m
ellipsoidal): the antenna phase centre. ``pole.json``: ``{"pole_length_m": 1.865}``, and
optionally ``"imu_convention"`` (what an ``imu.csv`` row is, :mod:`.imu_convention`).
Every error is one :class:`InputError` naming the file, line and field.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from hydrosync_core import plausible
from hydrosync_core.errors import InputError
from hydrosync_core.importers.csv_table import read_numeric_csv
from hydrosync_core.importers.pool_json import finite_number, read_json
from hydrosync_core.inputs import input_ok

IMU_COLUMNS = ("time", "gx", "gy", "gz", "ax", "ay", "az")
RATE: plausible.Limits = (-100.0, 100.0, "rad/s")
FORCE: plausible.Limits = (-500.0, 500.0, "m/s²")
IMU_LIMITS = {"time": plausible.TIME, "gx": RATE, "gy": RATE, "gz": RATE,
              "ax": FORCE, "ay": FORCE, "az": FORCE}
ENU = ("e", "n", "u")
LLH = ("lat", "lon", "height")
GNSS_LIMITS = {"time": plausible.TIME, "e": plausible.COORDINATE, "n": plausible.COORDINATE,
               "u": plausible.HEIGHT, "lat": plausible.LATITUDE, "lon": plausible.LONGITUDE,
               "height": plausible.HEIGHT}
POLE_LIMITS: plausible.Limits = (0.05, 20.0, "m")


def read_imu_csv(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """Columns of ``imu.csv`` sorted by time (at least 50 rows, gaps checked)."""
    input_ok(path, "IMU CSV")
    cols = read_numeric_csv(path, IMU_COLUMNS, min_rows=50, limits=IMU_LIMITS)
    check_imu_times(cols["time"], str(path))
    return cols


def check_imu_times(time: np.ndarray, source: str) -> None:
    """Refuse an IMU record with gaps (an interval over 5 median intervals)."""
    dt = np.diff(time)
    med = float(np.median(dt))
    bad = np.flatnonzero(dt > 5 * med)
    if bad.size:
        i = int(bad[0])
        raise InputError(source, f"gap of {dt[i]:.3f} s in the IMU record after time "
                         f"{time[i]!r} (median interval {med:.4f} s): the attitude cannot be "
                         "carried across", field="time")


def _header_names(path: Path) -> list[str]:
    try:
        with open(path, encoding="utf-8-sig", errors="replace") as fh:
            for _, line in zip(range(10000), fh, strict=False):
                if line.strip() and not line.lstrip().startswith("#"):
                    return [c.strip().lower() for c in line[:10000].split(",")]
    except OSError:
        pass
    return []


def read_gnss_csv(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """Columns of the tilt ``gnss.csv``: ``time`` and either ``e n u`` or ``lat lon height``.

    The form is decided by the header: ENU when it has ``e, n, u``, else geodetic.
    """
    input_ok(path, "GNSS CSV")
    path = Path(path)
    names = _header_names(path)
    wanted = ENU if all(c in names for c in ENU) or not all(c in names for c in LLH) else LLH
    if not all(c in names for c in ENU) and not all(c in names for c in LLH) and path.is_file():
        missing = [c for c in ENU if c not in names]
        raise InputError(str(path), f"needs columns time, e, n, u (local ENU) or time, lat, "
                         f"lon, height (header has: {', '.join(names[:12]) or 'nothing'})",
                         line=1, field=missing[0] if missing else "e")
    return read_numeric_csv(path, ("time", *wanted), min_rows=5, limits=GNSS_LIMITS)


def check_pole(document, source: str) -> float:
    """The pole length (m) from a parsed ``pole.json``."""
    if not isinstance(document, dict):
        raise InputError(source, "expected a JSON object")
    if "pole_length_m" not in document:
        raise InputError(source, "missing value", field="pole_length_m")
    return finite_number(source, document["pole_length_m"], "pole_length_m", POLE_LIMITS)


def pole_convention(document, source: str) -> str | None:
    """The IMU sample convention ``pole.json`` declares (``imu_convention``), or None."""
    from hydrosync_core.methods.tilt_alignment.imu_convention import CONVENTIONS

    value = document.get("imu_convention") if isinstance(document, dict) else None
    if value is None:
        return None
    if value not in CONVENTIONS:
        raise InputError(source, f"must be one of {', '.join(CONVENTIONS)}, got "
                         f"{str(value)[:40]!r}", field="imu_convention")
    return str(value)


def read_pole_json(path: str | os.PathLike) -> dict:
    """``pole.json`` as a checked document ``{"pole_length_m": l}`` (with
    ``imu_convention`` when it declares one)."""
    doc = read_json(path)
    out: dict = {"pole_length_m": check_pole(doc, str(path))}
    convention = pole_convention(doc, str(path))
    if convention is not None:
        out["imu_convention"] = convention
    return out


def gnss_to_local(cols: dict[str, np.ndarray]) -> tuple[np.ndarray, dict]:
    """Antenna positions in a local NED frame (m) and how to go back.

    Returns (M, 3) NED and a frame description: ``{"form": "enu"}`` or ``{"form": "llh",
    "origin_llh": [lat, lon, h]}`` (the first epoch; NED there).
    """
    if "e" in cols:
        return np.column_stack([cols["n"], cols["e"], -cols["u"]]), {"form": "enu"}
    from hydrosync_core.geodesy import ecef_to_ned_matrix, geodetic_to_ecef

    lat0, lon0, h0 = float(cols["lat"][0]), float(cols["lon"][0]), float(cols["height"][0])
    xyz = geodetic_to_ecef(cols["lat"], cols["lon"], cols["height"])
    x0 = geodetic_to_ecef(lat0, lon0, h0)
    ned = (xyz - x0) @ ecef_to_ned_matrix(lat0, lon0).T
    return ned, {"form": "llh", "origin_llh": [lat0, lon0, h0]}


def local_to_output(ned: np.ndarray, frame: dict) -> list[float]:
    """A NED point back to ``[e, n, u]`` or ``[lat, lon, height]`` (deg, deg, m)."""
    ned = np.asarray(ned, float)
    if frame["form"] == "enu":
        return [float(ned[1]), float(ned[0]), float(-ned[2])]
    from hydrosync_core.geodesy import ecef_to_geodetic, ecef_to_ned_matrix, geodetic_to_ecef

    lat0, lon0, h0 = frame["origin_llh"]
    xyz = geodetic_to_ecef(lat0, lon0, h0) + ecef_to_ned_matrix(lat0, lon0).T @ ned
    lat, lon, h = ecef_to_geodetic(xyz)
    return [float(lat), float(lon), float(h)]


def normal_gravity(lat_deg: float, height_m: float) -> float:
    """Somigliana normal gravity (GRS80) with the free-air reduction (m/s²)."""
    s2 = math.sin(math.radians(lat_deg)) ** 2
    g0 = 9.7803267715 * (1 + 0.001931851353 * s2) / math.sqrt(1 - 0.0066943800229 * s2)
    return g0 - 3.086e-6 * height_m


def ned_std_to_enu(std: np.ndarray) -> list[float]:
    return [float(std[1]), float(std[0]), float(std[2])]
