"""The one set of rotation helpers (``hydrosync_core.rotations``), checked once against
scipy's independent implementation and against finite differences."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from hydrosync_core import rotations as rot

RNG = np.random.default_rng(7)
ANGLES = RNG.uniform([-np.pi, -np.pi / 2 + 0.01, -np.pi], [np.pi, np.pi / 2 - 0.01, np.pi],
                     size=(50, 3))


def test_euler_matrix_matches_scipy_and_inverts():
    roll, pitch, yaw = ANGLES.T
    m = rot.euler_zyx_matrix(roll, pitch, yaw)
    ref = Rotation.from_euler("ZYX", np.column_stack([yaw, pitch, roll])).as_matrix()
    np.testing.assert_allclose(m, ref, atol=1e-15)
    np.testing.assert_allclose(m, rot.rot_z(yaw) @ rot.rot_y(pitch) @ rot.rot_x(roll),
                               atol=1e-15)
    r2, p2, y2 = rot.euler_zyx_angles(m)
    np.testing.assert_allclose(np.column_stack([r2, p2, y2]), ANGLES, atol=1e-12)
    single = rot.euler_zyx_angles(m[0])
    assert all(isinstance(a, float) for a in single)
    np.testing.assert_allclose(rot.euler_zyx_matrix_deg(*np.degrees(ANGLES[0])), m[0],
                               atol=1e-15)
    assert rot.euler_zyx_matrix(0.1, 0.2, 0.3).shape == (3, 3)
    assert rot.euler_zyx_matrix(np.zeros((4, 2)), 0.0, 0.0).shape == (4, 2, 3, 3)
    np.testing.assert_allclose(rot.yaw_of(m), yaw, atol=1e-12)


@pytest.mark.parametrize("fn, dfn", [(rot.rot_x, rot.d_rot_x), (rot.rot_y, rot.d_rot_y),
                                     (rot.rot_z, rot.d_rot_z)])
def test_axis_derivatives_match_finite_differences(fn, dfn):
    a = ANGLES[:, 0]
    h = 1e-6
    numeric = (fn(a + h) - fn(a - h)) / (2 * h)
    np.testing.assert_allclose(dfn(a), numeric, atol=1e-9)


def test_quaternions_agree_with_matrix_and_scipy():
    roll, pitch, yaw = ANGLES.T
    q = rot.euler_to_quat(roll, pitch, yaw)
    np.testing.assert_allclose(np.linalg.norm(q, axis=-1), 1.0, atol=1e-15)
    np.testing.assert_allclose(rot.quat_to_matrix(q), rot.euler_zyx_matrix(roll, pitch, yaw),
                               atol=1e-14)
    scipy_q = Rotation.from_matrix(rot.quat_to_matrix(q)).as_quat(scalar_first=True)
    sign = np.sign(np.sum(scipy_q * q, axis=-1))
    np.testing.assert_allclose(scipy_q * sign[:, None], q, atol=1e-14)
    np.testing.assert_allclose(np.column_stack(rot.quat_to_euler(q)), ANGLES, atol=1e-12)


def test_skew_exp_log_and_orthonormalise():
    v = RNG.normal(size=(20, 3))
    w = RNG.normal(size=(20, 3))
    np.testing.assert_allclose(np.einsum("nij,nj->ni", rot.skew(v), w), np.cross(v, w),
                               atol=1e-15)
    small = 0.5 * v / np.linalg.norm(v, axis=-1, keepdims=True)
    r = rot.exp_so3(small)
    np.testing.assert_allclose(rot.log_so3(r), small, atol=1e-12)
    # exp of a tiny rotation vector is I + [v]× to first order
    tiny = 1e-7 * v[0]
    np.testing.assert_allclose(rot.exp_so3(tiny), np.eye(3) + rot.skew(tiny), atol=1e-13)
    noisy = r + 1e-3 * RNG.normal(size=r.shape)
    o = rot.orthonormalise(noisy)
    np.testing.assert_allclose(o @ np.swapaxes(o, -1, -2), np.broadcast_to(np.eye(3), o.shape),
                               atol=1e-12)
    np.testing.assert_allclose(np.linalg.det(o), 1.0, atol=1e-12)
    np.testing.assert_allclose(o, r, atol=5e-3)
    reflected = np.diag([1.0, 1.0, -1.0])
    assert np.linalg.det(rot.orthonormalise(reflected)) == pytest.approx(1.0)


def test_ned_enu_swap_and_wrap():
    np.testing.assert_array_equal(rot.C_NED_TO_ENU @ rot.C_NED_TO_ENU, np.eye(3))
    np.testing.assert_allclose(rot.C_NED_TO_ENU @ [1.0, 2.0, 3.0], [2.0, 1.0, -3.0])
    np.testing.assert_allclose(rot.wrap_pi([3 * np.pi / 2, -3 * np.pi / 2, 0.1]),
                               [-np.pi / 2, np.pi / 2, 0.1], atol=1e-15)
