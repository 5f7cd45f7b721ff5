"""WGS84 geodetic ↔ ECEF conversions and local-level rotations (closed form, vectorised).

Neither pyproj nor pymap3d is a HydroSync dependency, so the standard closed forms are
used: geodetic → ECEF exactly, ECEF → geodetic by Bowring's method with two refinement
steps (sub-millimetre anywhere near the Earth's surface), and the ECEF → local-level
rotation at geodetic latitude B and longitude L (NED and ENU). ETRS89/GRS80 coordinates
use the same ellipsoid to 0.1 mm, so they are accepted as WGS84.

Angles are radians unless a name ends in ``_deg``; lengths are metres.
"""

from __future__ import annotations

import numpy as np

#: WGS84 semi-major axis (m) and flattening.
A_WGS84 = 6378137.0
F_WGS84 = 1.0 / 298.257223563
E2_WGS84 = F_WGS84 * (2.0 - F_WGS84)
B_WGS84 = A_WGS84 * (1.0 - F_WGS84)


def geodetic_to_ecef(lat_deg, lon_deg, height_m) -> np.ndarray:
    """ECEF coordinates (m) of geodetic latitude/longitude (deg) and ellipsoidal height (m).

    Returns an array of shape ``(..., 3)``.
    """
    lat = np.radians(np.asarray(lat_deg, float))
    lon = np.radians(np.asarray(lon_deg, float))
    h = np.asarray(height_m, float)
    n = A_WGS84 / np.sqrt(1.0 - E2_WGS84 * np.sin(lat) ** 2)
    x = (n + h) * np.cos(lat) * np.cos(lon)
    y = (n + h) * np.cos(lat) * np.sin(lon)
    z = (n * (1.0 - E2_WGS84) + h) * np.sin(lat)
    return np.stack(np.broadcast_arrays(x, y, z), axis=-1)


def ecef_to_geodetic(xyz) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Geodetic latitude, longitude (deg) and ellipsoidal height (m) of ECEF points (m).

    *xyz* has shape ``(..., 3)``. Bowring's initial value refined twice by the exact
    latitude iteration: better than 0.1 mm from −10 km to +1000 km height.
    """
    xyz = np.asarray(xyz, float)
    x, y, z = xyz[..., 0], xyz[..., 1], xyz[..., 2]
    p = np.hypot(x, y)
    lon = np.arctan2(y, x)
    ep2 = E2_WGS84 / (1.0 - E2_WGS84)
    theta = np.arctan2(z * A_WGS84, p * B_WGS84)
    lat = np.arctan2(z + ep2 * B_WGS84 * np.sin(theta) ** 3,
                     p - E2_WGS84 * A_WGS84 * np.cos(theta) ** 3)
    for _ in range(2):
        n = A_WGS84 / np.sqrt(1.0 - E2_WGS84 * np.sin(lat) ** 2)
        h = np.where(np.abs(np.cos(lat)) > 1e-9, p / np.maximum(np.cos(lat), 1e-300) - n,
                     np.abs(z) - B_WGS84)
        lat = np.arctan2(z, p * (1.0 - E2_WGS84 * n / (n + h)))
    n = A_WGS84 / np.sqrt(1.0 - E2_WGS84 * np.sin(lat) ** 2)
    h = np.where(np.abs(np.cos(lat)) > 1e-9, p / np.maximum(np.cos(lat), 1e-300) - n,
                 np.abs(z) - B_WGS84)
    return np.degrees(lat), np.degrees(lon), h


def ecef_to_ned_matrix(lat_deg, lon_deg) -> np.ndarray:
    """Rotation taking ECEF vector components to NED at (lat, lon) (deg); shape (..., 3, 3).

    ``v_ned = C @ v_ecef`` with rows north, east, down.
    """
    b = np.radians(np.asarray(lat_deg, float))
    lam = np.radians(np.asarray(lon_deg, float))
    sb, cb, sl, cl = np.sin(b), np.cos(b), np.sin(lam), np.cos(lam)
    zero = np.zeros_like(sb * sl)
    rows = [[-sb * cl, -sb * sl, cb + zero],
            [-sl + zero, cl + zero, zero],
            [-cb * cl, -cb * sl, -sb + zero]]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)
