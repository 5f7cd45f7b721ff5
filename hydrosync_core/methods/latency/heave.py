"""Rotation-induced and total heave at the GNSS antenna (seed eq. 2).

Frames: body FRD (x forward, y starboard, z down); roll positive starboard down, pitch
positive bow up; heave positive up, metres. ``R = Rz(heading)·Ry(pitch)·Rx(roll)``.
"""

from __future__ import annotations

import numpy as np


def induced_heave(roll: np.ndarray, pitch: np.ndarray, lever_arm) -> np.ndarray:
    """Rotation-induced heave H_R (m, up) of a point at *lever_arm* from the motion sensor.

    Parameters
    ----------
    roll, pitch : ndarray
        Attitude in radians (any matching shapes).
    lever_arm : array-like, shape (3,)
        Antenna relative to the motion-sensor reference point, body FRD, metres.

    Notes
    -----
    The down component of ``R·L`` does not depend on heading, so only roll and pitch
    enter: ``(R·L)_z = −sin p·x + cos p·sin r·y + cos p·cos r·z``.
    """
    x, y, z = (float(v) for v in np.asarray(lever_arm, dtype=float).reshape(3))
    sr, cr = np.sin(roll), np.cos(roll)
    sp, cp = np.sin(pitch), np.cos(pitch)
    # Seed eq. 2 (rotation part): H_R(up) = −[(R·L)_z − L_z]; z is down, heave is up.
    down = -sp * x + cp * sr * y + cp * cr * z
    return -(down - z)


def total_heave(heave: np.ndarray, roll: np.ndarray, pitch: np.ndarray, lever_arm) -> np.ndarray:
    """Total heave H_T = H_M + H_R at the antenna (m, up); angles in radians (seed eq. 2)."""
    return np.asarray(heave, dtype=float) + induced_heave(roll, pitch, lever_arm)


def total_heave_deg(
    heave: np.ndarray, roll_deg: np.ndarray, pitch_deg: np.ndarray, lever_arm,
    chunk: int = 1 << 20,
) -> np.ndarray:
    """:func:`total_heave` from angles in degrees, in chunks to bound temporary memory.

    A day of 100 Hz attitude has ~10⁷ samples; the trigonometric temporaries of one
    pass would cost several hundred MB.
    """
    out = np.empty(len(heave))
    for lo in range(0, len(heave), chunk):
        sl = slice(lo, lo + chunk)
        out[sl] = total_heave(heave[sl], np.radians(roll_deg[sl]), np.radians(pitch_deg[sl]),
                              lever_arm)
    return out
