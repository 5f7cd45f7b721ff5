"""Rotation conventions shared by every analysis (radians inside, degrees at the edges).

Body frame x forward, y starboard, z down (FRD); local level NED or ENU. The attitude and
boresight rotations are ``R = Rz(yaw/heading) · Ry(pitch) · Rx(roll)`` (``docs/formats.md``).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

#: NED -> ENU (swap north/east, flip down to up); its own inverse.
C_NED_TO_ENU = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])


def euler_zyx_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """``Rz(yaw)·Ry(pitch)·Rx(roll)`` (radians) as a 3×3 matrix."""
    return Rotation.from_euler("ZYX", [yaw, pitch, roll]).as_matrix()


def euler_zyx_angles(matrix: np.ndarray) -> tuple[float, float, float]:
    """(roll, pitch, yaw) radians of ``Rz·Ry·Rx`` (inverse of :func:`euler_zyx_matrix`)."""
    yaw, pitch, roll = Rotation.from_matrix(matrix).as_euler("ZYX")
    return float(roll), float(pitch), float(yaw)
