"""Rotation conventions shared by every analysis (radians inside, degrees at the edges).

Body frame x forward, y starboard, z down (FRD); local level NED or ENU. The attitude and
boresight rotations are ``R = Rz(yaw/heading) · Ry(pitch) · Rx(roll)`` (``docs/formats.md``),
mapping body vectors into the local-level frame.

Every function is vectorised: angles of any shape ``S`` give matrices of shape ``S + (3, 3)``
(a scalar gives one 3×3 matrix); vectors are ``(..., 3)``. Quaternions are scalar first,
``[w, x, y, z]``, Hamilton product, and represent the same body→level rotation as the matrix.
numba kernels that cannot call these functions (``gins_smoother/kernel.py``) keep their own
scalar loops, tested against this module.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

#: NED -> ENU (swap north/east, flip down to up); its own inverse.
C_NED_TO_ENU = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])


def _stack_matrix(rows) -> np.ndarray:
    return np.stack([np.stack(row, -1) for row in rows], -2)


def rot_x(a) -> np.ndarray:
    """Rotation about x by *a* (rad): ``[[1,0,0],[0,c,-s],[0,s,c]]``, shape ``a.shape+(3,3)``."""
    a = np.asarray(a, float)
    c, s, o, z = np.cos(a), np.sin(a), np.ones_like(a), np.zeros_like(a)
    return _stack_matrix([[o, z, z], [z, c, -s], [z, s, c]])


def rot_y(a) -> np.ndarray:
    """Rotation about y by *a* (rad): ``[[c,0,s],[0,1,0],[-s,0,c]]``."""
    a = np.asarray(a, float)
    c, s, o, z = np.cos(a), np.sin(a), np.ones_like(a), np.zeros_like(a)
    return _stack_matrix([[c, z, s], [z, o, z], [-s, z, c]])


def rot_z(a) -> np.ndarray:
    """Rotation about z by *a* (rad): ``[[c,-s,0],[s,c,0],[0,0,1]]`` (clockwise seen from
    above when z is down)."""
    a = np.asarray(a, float)
    c, s, o, z = np.cos(a), np.sin(a), np.ones_like(a), np.zeros_like(a)
    return _stack_matrix([[c, -s, z], [s, c, z], [z, z, o]])


def d_rot_x(a) -> np.ndarray:
    """Derivative of :func:`rot_x` with respect to its angle (per rad)."""
    a = np.asarray(a, float)
    c, s, z = np.cos(a), np.sin(a), np.zeros_like(a)
    return _stack_matrix([[z, z, z], [z, -s, -c], [z, c, -s]])


def d_rot_y(a) -> np.ndarray:
    """Derivative of :func:`rot_y` with respect to its angle (per rad)."""
    a = np.asarray(a, float)
    c, s, z = np.cos(a), np.sin(a), np.zeros_like(a)
    return _stack_matrix([[-s, z, c], [z, z, z], [-c, z, -s]])


def d_rot_z(a) -> np.ndarray:
    """Derivative of :func:`rot_z` with respect to its angle (per rad)."""
    a = np.asarray(a, float)
    c, s, z = np.cos(a), np.sin(a), np.zeros_like(a)
    return _stack_matrix([[-s, -c, z], [c, -s, z], [z, z, z]])


def euler_zyx_matrix(roll, pitch, yaw) -> np.ndarray:
    """``Rz(yaw)·Ry(pitch)·Rx(roll)`` (radians, broadcast together) as ``(..., 3, 3)``.

    Body (FRD) → local level (NED) for an attitude; multibeam → body for a boresight.
    """
    r, p, y = np.broadcast_arrays(*(np.asarray(a, float) for a in (roll, pitch, yaw)))
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return _stack_matrix([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                          [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                          [-sp, cp * sr, cp * cr]])


def euler_zyx_matrix_deg(roll_deg, pitch_deg, yaw_deg) -> np.ndarray:
    """:func:`euler_zyx_matrix` of angles in degrees."""
    return euler_zyx_matrix(*(np.radians(np.asarray(a, float))
                              for a in (roll_deg, pitch_deg, yaw_deg)))


def euler_zyx_angles(matrix) -> tuple:
    """(roll, pitch, yaw) radians of ``Rz·Ry·Rx`` matrices ``(..., 3, 3)`` (inverse of
    :func:`euler_zyx_matrix`); yaw and roll in (−π, π], pitch in [−π/2, π/2].

    Scalars (Python floats) for a single matrix, arrays of shape ``...`` otherwise.
    """
    m = np.asarray(matrix, float)
    roll = np.arctan2(m[..., 2, 1], m[..., 2, 2])
    pitch = np.arcsin(np.clip(-m[..., 2, 0], -1.0, 1.0))
    yaw = np.arctan2(m[..., 1, 0], m[..., 0, 0])
    if m.ndim == 2:
        return float(roll), float(pitch), float(yaw)
    return roll, pitch, yaw


def yaw_of(matrix) -> np.ndarray | float:
    """Heading (rad) of ``Rz·Ry·Rx`` matrices (the ZYX yaw), in (−π, π]."""
    m = np.asarray(matrix, float)
    yaw = np.arctan2(m[..., 1, 0], m[..., 0, 0])
    return float(yaw) if m.ndim == 2 else yaw


def skew(v) -> np.ndarray:
    """Cross-product matrices ``[v]×`` (``[v]× w = v × w``) of vectors ``(..., 3)``."""
    v = np.asarray(v, float)
    z = np.zeros(v.shape[:-1])
    return _stack_matrix([[z, -v[..., 2], v[..., 1]], [v[..., 2], z, -v[..., 0]],
                          [-v[..., 1], v[..., 0], z]])


def exp_so3(rotvec) -> np.ndarray:
    """Rotation matrices of rotation vectors ``(..., 3)`` (rad)."""
    v = np.asarray(rotvec, float)
    return Rotation.from_rotvec(v.reshape(-1, 3)).as_matrix().reshape(v.shape[:-1] + (3, 3))


def log_so3(matrix) -> np.ndarray:
    """Rotation vectors (rad) ``(..., 3)`` of rotation matrices ``(..., 3, 3)``."""
    m = np.asarray(matrix, float)
    return Rotation.from_matrix(m.reshape(-1, 3, 3)).as_rotvec().reshape(m.shape[:-2] + (3,))


def orthonormalise(matrix) -> np.ndarray:
    """Nearest rotation matrices (polar decomposition by SVD) of ``(..., 3, 3)``."""
    u, _, vt = np.linalg.svd(np.asarray(matrix, float))
    r = u @ vt
    flip = np.linalg.det(r) < 0
    if np.any(flip):
        u = u.copy()
        u[..., :, 2] = np.where(flip[..., None], -u[..., :, 2], u[..., :, 2])
        r = u @ vt
    return r


def euler_to_quat(roll, pitch, yaw) -> np.ndarray:
    """Quaternions ``[w, x, y, z]`` ``(..., 4)`` of ``Rz(yaw)·Ry(pitch)·Rx(roll)`` (rad)."""
    r, p, y = np.broadcast_arrays(*(np.asarray(a, float) / 2 for a in (roll, pitch, yaw)))
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return np.stack([cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy,
                     cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy], -1)


def quat_to_euler(q) -> tuple:
    """(roll, pitch, yaw) radians of quaternions ``[w, x, y, z]`` ``(..., 4)``; yaw in
    (−π, π]. The inverse of :func:`euler_to_quat`."""
    q = np.asarray(q, float)
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    roll = np.arctan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = np.arcsin(np.clip(2 * (w * y - z * x), -1.0, 1.0))
    yaw = np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    return roll, pitch, yaw


def quat_to_matrix(q) -> np.ndarray:
    """Rotation matrices ``(..., 3, 3)`` of unit quaternions ``[w, x, y, z]``."""
    q = np.asarray(q, float)
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    return _stack_matrix([
        [w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z]])


def wrap_pi(angle):
    """Angle(s) (rad) wrapped to (−π, π]."""
    return np.pi - np.mod(np.pi - np.asarray(angle, float), 2.0 * np.pi)
