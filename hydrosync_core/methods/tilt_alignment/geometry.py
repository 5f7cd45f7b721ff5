"""Rotations, attitude propagation from gyros, and Mahony levelling (radians inside).

Frames: body x forward, y right, z down along the pole towards the tip; navigation NED.
``C`` is the body→NED rotation matrix, ``C = Rz(heading)·Ry(pitch)·Rx(roll)``.
On the model grid (:mod:`.imu_convention`) gyro sample *k* (rad/s, body frame) is the
constant rate over ``[t_k, t_(k+1))``, so
``C_(k+1) = C_k · Exp((ω_k − b_g)·Δt_k)``; accelerometer sample *k* is the specific
force at ``t_k`` (m/s², body frame), ``f = Cᵀ(a − g·e_down)``.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.spatial.transform import Rotation

from hydrosync_core.rotations import euler_zyx_matrix, exp_so3, rot_z, skew, wrap_pi
from hydrosync_core.rotations import yaw_of as _yaw_of

__all__ = ["E_DOWN", "exp_so3", "skew", "rz", "yaw_of", "wrap", "tilt_of", "propagate",
           "mahony", "coarse_level", "level_from_accel", "pole_vectors",
           "interpolate_vectors"]

E_DOWN = np.array([0.0, 0.0, 1.0])


def rz(psi: float) -> np.ndarray:
    """Rotation about the down axis by *psi* (rad, clockwise seen from above)."""
    return rot_z(float(psi))


def yaw_of(matrix: np.ndarray) -> float:
    """Heading (rad) of ``Rz·Ry·Rx`` (the ZYX yaw), in (−π, π]."""
    return float(_yaw_of(matrix))


def wrap(angle):
    """Angle(s) wrapped to (−π, π]."""
    return wrap_pi(angle)


def tilt_of(C: np.ndarray) -> np.ndarray:
    """Tilt (rad) of the body z axis (the pole) from the vertical, for C of shape (..., 3, 3)."""
    return np.arccos(np.clip(C[..., 2, 2], -1.0, 1.0))


def propagate(C0: np.ndarray, time: np.ndarray, gyro: np.ndarray,
              bias: np.ndarray | None = None) -> np.ndarray:
    """Attitudes (N, 3, 3) at the IMU times from *C0* and the gyro rates.

    Parameters
    ----------
    C0 : (3, 3) body→NED attitude at ``time[0]``.
    time : (N,) s. gyro : (N, 3) rad/s, body frame. bias : (3,) rad/s subtracted.
    """
    dt = np.diff(time)
    w = gyro[:-1] - (0.0 if bias is None else np.asarray(bias, float))
    steps = Rotation.from_rotvec(w * dt[:, None]).as_quat()  # x, y, z, w
    q = Rotation.from_matrix(C0).as_quat()
    x, y, z, s = (float(v) for v in q)
    out = np.empty((time.size, 4))
    out[0] = (x, y, z, s)
    for k, (bx, by, bz, bw) in enumerate(steps.tolist(), start=1):
        x, y, z, s = (s * bx + x * bw + y * bz - z * by,
                      s * by - x * bz + y * bw + z * bx,
                      s * bz + x * by - y * bx + z * bw,
                      s * bw - x * bx - y * by - z * bz)
        out[k] = (x, y, z, s)
    return Rotation.from_quat(out).as_matrix()


def level_from_accel(f_mean: np.ndarray) -> tuple[float, float]:
    """(roll, pitch) rad from a mean specific force at rest (body, m/s²)."""
    fx, fy, fz = (float(v) for v in f_mean)
    return math.atan2(-fy, -fz), math.atan2(fx, math.hypot(fy, fz))


def coarse_level(time: np.ndarray, gyro: np.ndarray, accel: np.ndarray, level_s: float
                 ) -> tuple[float, float]:
    """(roll, pitch) rad at ``time[0]`` from the gyro-compensated mean specific force.

    The specific forces of the first *level_s* seconds are rotated to the attitude at the
    start with the gyros and averaged: a hand-held pole wobbles, but its acceleration
    averages out, so the mean is gravity seen at ``time[0]``.
    """
    n = int(np.searchsorted(time, time[0] + level_s, side="right"))
    n = max(2, min(n, time.size))
    dC = propagate(np.eye(3), time[:n], gyro[:n])
    mean = np.einsum("kij,kj->i", dC, accel[:n]) / n
    return level_from_accel(mean)


def mahony(time: np.ndarray, gyro: np.ndarray, accel: np.ndarray, level_s: float,
           kp: float, ki: float, g: float) -> tuple[np.ndarray, np.ndarray]:
    """Mahony complementary filter: levelled attitude with the heading from the gyros.

    The filter starts from the roll and pitch of :func:`coarse_level` (heading 0),
    corrects roll and pitch with the accelerometers during the first *level_s* seconds
    (proportional gain *kp*, rad/s per unit error; integral gain *ki*, rad/s² — the
    integral becomes a gyro-bias estimate) and then integrates the gyros only (a swung
    pole's accelerations would corrupt the gravity direction). Li et al. level with the
    Mahony filter before the swing. Samples whose specific-force magnitude is off gravity
    by more than 0.5 m/s² are not used for the correction.

    Returns
    -------
    C : (N, 3, 3) body→NED attitudes, heading 0 at ``time[0]`` (so its heading is off
        by the unknown misalignment ψ).
    bias : (3,) rad/s, the gyro bias estimated by the integral term.
    """
    roll, pitch = coarse_level(time, gyro, accel, level_s)
    C = euler_zyx_matrix(roll, pitch, 0.0)
    n_level = int(np.searchsorted(time, time[0] + level_s, side="right"))
    n_level = max(1, min(n_level, time.size))
    out = np.empty((time.size, 3, 3))
    out[0] = C
    integral = np.zeros(3)
    for k in range(n_level - 1):
        dt = time[k + 1] - time[k]
        w = gyro[k] + integral
        f = accel[k]
        norm = float(np.linalg.norm(f))
        if abs(norm - g) < 0.5 and norm > 0:
            measured = -f / norm          # the down direction measured in the body frame
            estimated = C[2, :]           # Cᵀ·e_down
            e = np.cross(measured, estimated)
            integral = integral + ki * e * dt
            w = w + kp * e
        C = C @ exp_so3(w * dt)
        out[k + 1] = C
    if n_level < time.size:
        rest = propagate(C, time[n_level - 1:], gyro[n_level - 1:], -integral)
        out[n_level:] = rest[1:]
    return out, -integral


def pole_vectors(C: np.ndarray, length: float) -> np.ndarray:
    """``C·l_b`` (N, 3) in NED: antenna → tip, *length* m along body z."""
    return C[..., :, 2] * length


def interpolate_vectors(time: np.ndarray, values: np.ndarray, at: np.ndarray
                        ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Linear interpolation of (N, 3) *values* at times *at*.

    Returns the interpolated (M, 3) values, the left sample index k and the fraction
    ``(at − t_k)/(t_(k+1) − t_k)``.
    """
    k = np.clip(np.searchsorted(time, at, side="right") - 1, 0, time.size - 2)
    frac = (at - time[k]) / (time[k + 1] - time[k])
    return values[k] * (1 - frac)[:, None] + values[k + 1] * frac[:, None], k, frac
