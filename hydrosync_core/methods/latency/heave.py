"""Rotation-induced and total heave at the GNSS antenna (seed eq. 2).

Frames: body FRD (x forward, y starboard, z down); roll positive starboard down, pitch
positive bow up; heave positive up, metres. ``R = Rz(heading)·Ry(pitch)·Rx(roll)``.
"""

from __future__ import annotations

import threading

import numpy as np
from numba import njit, prange

_LOCK = threading.Lock()
"""numba's default threading layer must not launch parallel kernels from two threads."""

_RAD = np.pi / 180.0
# fdlibm's __kernel_sin / __kernel_cos coefficients (minimax on |x| <= pi/4, < 1 ulp).
_S1, _S2, _S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, \
    -1.98412698298579493134e-04
_S4, _S5, _S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, \
    1.58969099521155010221e-10
_C1, _C2, _C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, \
    2.48015872894767294178e-05
_C4, _C5, _C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, \
    -1.13596475577881948265e-11

LARGE_DEG = 1e12
"""Angles (degrees) beyond which :func:`_sincos_deg`'s quadrant reduction is no longer
exact: kernels first bring such angles into ±360° (``fmod``, exact)."""


def _sincos_deg_py(d):  # pragma: no cover - compiled below
    """(sin, cos) of the angle *d* in degrees, |d| <= LARGE_DEG.

    The quadrant is taken off in degrees, where it is exact (``d - 90 n``), and the rest
    (|r| <= 45°) goes through fdlibm's polynomials, branch-free so that the compiled
    loops calling it run on SIMD lanes. libm's ``sincos`` per sample was the largest
    single cost of a survey day's latency estimate (0.38 ms per line window, 0.035 ms
    this way). Within ±720° the error is below 2e-16 (``sin(d·π/180)`` in double:
    up to 1.1e-15, from rounding d·π/180).
    """
    n = np.floor(d * (1.0 / 90.0) + 0.5)
    r = (d - 90.0 * n) * _RAD
    z = r * r
    s = r + r * z * (_S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6)))))
    c = 1.0 - 0.5 * z + z * z * (_C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * _C6)))))
    q = n - 4.0 * np.floor(n * 0.25)  # quadrant 0..3
    odd = (q == 1.0) | (q == 3.0)
    sv = c if odd else s
    cv = s if odd else c
    sv = -sv if q >= 2.0 else sv
    cv = -cv if (q == 1.0) | (q == 2.0) else cv
    return sv, cv


def _within_range_py(deg):  # pragma: no cover - compiled below
    ok = True
    for i in range(deg.size):
        ok &= abs(deg[i]) <= LARGE_DEG  # no branch: the loop vectorises
    return ok


def _in_range_py(deg):  # pragma: no cover - compiled below
    """*deg* itself, or brought into ±360° (exactly) when an angle exceeds LARGE_DEG."""
    return deg if _within_range(deg) else np.fmod(deg, 360.0)


def _one_in_range_py(d):  # pragma: no cover - compiled below
    """One angle as :func:`_in_range` leaves it (a few samples: a branch costs nothing)."""
    return d if abs(d) <= LARGE_DEG else np.fmod(d, 360.0)


def _total_heave_deg_py(heave, roll_deg, pitch_deg, x, y, z):  # pragma: no cover - compiled
    roll_deg = _in_range(roll_deg)
    pitch_deg = _in_range(pitch_deg)
    out = np.empty(heave.size)
    for i in prange(heave.size):
        sr, cr = _sincos_deg(roll_deg[i])
        sp, cp = _sincos_deg(pitch_deg[i])
        out[i] = heave[i] + (-((-sp * x + cp * sr * y + cp * cr * z) - z))
    return out


_sincos_deg = njit(cache=True, nogil=True, inline="always")(_sincos_deg_py)
_within_range = njit(cache=True, nogil=True)(_within_range_py)
_in_range = njit(cache=True, nogil=True)(_in_range_py)
_one_in_range = njit(cache=True, nogil=True, inline="always")(_one_in_range_py)



_total_heave_deg_nb = njit(cache=True, parallel=True)(_total_heave_deg_py)
_total_heave_deg_nb1 = njit(cache=True, nogil=True)(_total_heave_deg_py)
"""Serial variant for line windows (called from the scan threads)."""


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


def total_heave_deg(heave: np.ndarray, roll_deg: np.ndarray, pitch_deg: np.ndarray,
                    lever_arm) -> np.ndarray:
    """:func:`total_heave` from angles in degrees, compiled without temporaries.

    A day of 100 Hz attitude has ~10⁷ samples: numpy's trigonometric temporaries would
    cost several hundred MB. Above 100 000 records on both cores (one kernel at a time),
    below on the calling thread; the result is the same to the last bit on the machines
    tested.
    """
    x, y, z = (float(v) for v in np.asarray(lever_arm, dtype=float).reshape(3))
    args = (np.ascontiguousarray(heave, dtype=float), np.ascontiguousarray(roll_deg, dtype=float),
            np.ascontiguousarray(pitch_deg, dtype=float), x, y, z)
    if len(heave) <= 100_000:
        return _total_heave_deg_nb1(*args)
    with _LOCK:
        return _total_heave_deg_nb(*args)


WALK_STEPS = 64
"""Records :func:`total_heave_at` steps through before it falls back to a binary search."""


def _total_heave_at_py(times, t, heave, roll_deg, pitch_deg, x, y, z):  # pragma: no cover
    out = np.empty(times.size)
    m = t.size
    last = -1
    h0 = h1 = 0.0
    right = 0
    for i in range(times.size):
        u = times[i]
        # Right neighbour as numpy.interp: t[j-1] <= u < t[j], clipped to the record.
        # Increasing times (a line's tags) are a few records apart: walking on from the
        # previous one beats a binary search over a day's 10⁷ records (cache misses).
        if 1 <= right <= m and t[right - 1] <= u:
            steps = 0
            while right < m and t[right] <= u and steps < WALK_STEPS:
                right += 1
                steps += 1
            if right < m and t[right] <= u:
                right = np.searchsorted(t, u, side="right")
        else:
            right = np.searchsorted(t, u, side="right")
        j = right
        if j < 1:
            j = 1
        if j > m - 1:
            j = m - 1
        if j != last:
            if j == last + 1:
                h0 = h1
            else:
                sr, cr = _sincos_deg(_one_in_range(roll_deg[j - 1]))
                sp, cp = _sincos_deg(_one_in_range(pitch_deg[j - 1]))
                h0 = heave[j - 1] + (-((-sp * x + cp * sr * y + cp * cr * z) - z))
            sr, cr = _sincos_deg(_one_in_range(roll_deg[j]))
            sp, cp = _sincos_deg(_one_in_range(pitch_deg[j]))
            h1 = heave[j] + (-((-sp * x + cp * sr * y + cp * cr * z) - z))
            last = j
        if u <= t[0]:
            out[i] = h0
        elif u >= t[m - 1]:
            out[i] = h1
        else:
            out[i] = h0 + (h1 - h0) / (t[j] - t[j - 1]) * (u - t[j - 1])
    return out


_total_heave_at_nb = njit(cache=True, nogil=True)(_total_heave_at_py)


def total_heave_at(times: np.ndarray, t: np.ndarray, heave: np.ndarray, roll_deg: np.ndarray,
                   pitch_deg: np.ndarray, lever_arm) -> np.ndarray:
    """Total heave (m, up) linearly interpolated at *times* (s) from the attitude records
    (*t* increasing, angles in degrees), as ``numpy.interp`` of :func:`total_heave_deg`
    but evaluating only the records next to each time."""
    times = np.ascontiguousarray(times, dtype=float)
    if t.size < 2:
        k = np.clip(np.searchsorted(t, times, side="right"), 1, max(t.size - 1, 1))
        idx = np.unique(np.concatenate([k - 1, k]))
        idx = idx[idx < t.size]
        return np.interp(times, t[idx], total_heave_deg(heave[idx], roll_deg[idx],
                                                        pitch_deg[idx], lever_arm))
    x, y, z = (float(v) for v in np.asarray(lever_arm, dtype=float).reshape(3))
    return _total_heave_at_nb(times, t, heave, roll_deg, pitch_deg, x, y, z)
