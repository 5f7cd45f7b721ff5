"""The three attitude estimators, vectorised over epochs (radians inside).

Frames: body x forward, y starboard, z down (FRD); navigation frame local level NED.
Attitude ``R = Rz(heading)·Ry(pitch)·Rx(roll)`` maps body vectors to NED:
``s_n = R · s_b`` for every baseline *s*. Heading in [0, 2π), pitch in [−π/2, π/2], roll
in (−π, π].

- :func:`direct_three` — Liu et al.'s three-antenna direct method (their eqs. 1–16):
  heading and pitch from baseline 1→2, roll from baseline 1→3 after removing heading and
  pitch, quadrants resolved by ``atan2`` (their tables 1 and 2). Their layout (antenna 2
  on the forward axis, antenna 3 in the body x–y plane) is a special case: any layout is
  solved through the *array frame* whose first axis is baseline 1→2 and whose first two
  axes span baseline 1→3.
- :func:`wahba` — the optimal closed-form rotation of the weighted Wahba problem (SVD,
  Markley 1988), batched; ``scipy``'s ``Rotation.align_vectors`` gives the same.
- :func:`lsq` — Liu et al.'s iterative weighted least squares (eqs. 17–24): linearise
  ``s_n = R(φ, θ, ψ)·s_b`` around the current angles, solve the normal equations for the
  corrections, iterate until every correction is below the threshold; the inverse normal
  matrix is the covariance of (roll, pitch, heading). The weight matrix is the inverse of
  the full covariance of the stacked baselines (which share the reference antenna).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hydrosync_core.rotations import (
    d_rot_x,
    d_rot_y,
    d_rot_z,
    euler_zyx_angles,
    euler_zyx_matrix,
    rot_x,
    rot_y,
    rot_z,
    wrap_pi,
)

TWO_PI = 2.0 * np.pi


def matrix_angles(R: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(roll, pitch, heading) radians of body→NED matrices (..., 3, 3); heading in
    [0, 2π), as this module reports it."""
    R = np.asarray(R, float)
    roll, pitch, yaw = (np.asarray(a) for a in euler_zyx_angles(R))
    heading = np.mod(yaw, TWO_PI)
    heading = np.where(heading >= TWO_PI, 0.0, heading)  # -1e-17 mod 2π rounds to 2π
    return roll, pitch, heading


# --------------------------------------------------------------------------- direct
def array_frame(body12: np.ndarray, body13: np.ndarray) -> np.ndarray:
    """Body coordinates of the array-frame axes as columns, ``M = [a1 a2 a3]`` (3×3).

    ``a1`` along baseline 1→2, ``a2`` the part of baseline 1→3 perpendicular to it,
    ``a3 = a1 × a2``. For Liu et al.'s layout (2 on the forward axis, 3 to starboard in the
    x–y plane) M is the identity.
    """
    b12, b13 = np.asarray(body12, float), np.asarray(body13, float)
    a1 = b12 / np.linalg.norm(b12)
    perp = b13 - (b13 @ a1) * a1
    norm = np.linalg.norm(perp)
    if norm < 1e-6 * np.linalg.norm(b13):
        raise ValueError("antennas 1, 2 and 3 are collinear: no roll from them")
    a2 = perp / norm
    return np.column_stack([a1, a2, np.cross(a1, a2)])


def direct_three(nav12: np.ndarray, nav13: np.ndarray, body12, body13) -> np.ndarray:
    """Liu et al.'s three-antenna direct method for any antenna layout.

    Parameters
    ----------
    nav12, nav13 : ndarray, shape (N, 3)
        Baselines antenna 1→2 and 1→3 in NED (m), per epoch.
    body12, body13 : array_like, shape (3,)
        The same baselines in the body frame (FRD, m).

    Returns
    -------
    ndarray, shape (N, 3, 3)
        Body → NED rotation per epoch. Angles via :func:`matrix_angles`.

    Notes
    -----
    In the array frame (see :func:`array_frame`) baseline 1→2 is ``(L12, 0, 0)`` and 1→3
    is ``(x3, y3, 0)`` with ``y3 > 0``. Heading ψ = atan2(E12, N12) (0–360°, Liu et al.
    table 1), pitch θ = atan2(−D12, √(N12² + E12²)) (±90°); rotating 1→3 back by ψ and θ
    leaves ``(x3, y3·cos φ, y3·sin φ)``, so roll φ = atan2(·z, ·y) (±180°, table 2).
    The array-frame attitude is then carried to the body frame: ``R = R_A · Mᵀ``.
    """
    M = array_frame(body12, body13)
    n12, n13 = np.atleast_2d(nav12), np.atleast_2d(nav13)
    heading = np.arctan2(n12[:, 1], n12[:, 0])
    pitch = np.arctan2(-n12[:, 2], np.hypot(n12[:, 0], n12[:, 1]))
    back = np.swapaxes(rot_z(heading) @ rot_y(pitch), -1, -2)
    v = np.einsum("nij,nj->ni", back, n13)
    roll = np.arctan2(v[:, 2], v[:, 1])
    R_A = euler_zyx_matrix(roll, pitch, heading)
    return R_A @ M.T


# --------------------------------------------------------------------------- Wahba
def wahba(nav: np.ndarray, body: np.ndarray, weights: np.ndarray | None = None) -> np.ndarray:
    """Optimal rotation of the weighted Wahba problem, per epoch (SVD method).

    Minimises ``Σ_i w_i |s_n,i − R·s_b,i|²``.

    Parameters
    ----------
    nav : ndarray, shape (N, m, 3)
        Baselines in NED (m).
    body : ndarray, shape (m, 3) or (N, m, 3)
        The same baselines in the body frame (m).
    weights : ndarray, shape (N, m) or (m,), optional
        Weights (1/m²); equal when omitted.

    Returns
    -------
    ndarray, shape (N, 3, 3)
        Body → NED rotations.
    """
    nav = np.asarray(nav, float)
    body = np.broadcast_to(np.asarray(body, float), nav.shape)
    w = np.ones(nav.shape[:2]) if weights is None else np.broadcast_to(weights, nav.shape[:2])
    B = np.einsum("nm,nmi,nmj->nij", w, nav, body)
    U, _, Vt = np.linalg.svd(B)
    d = np.linalg.det(U) * np.linalg.det(Vt)
    D = np.zeros_like(B)
    D[:, 0, 0] = D[:, 1, 1] = 1.0
    D[:, 2, 2] = d
    return U @ D @ Vt


# --------------------------------------------------------------------------- LSQ
@dataclass
class LsqResult:
    """Least-squares attitude per epoch.

    Attributes
    ----------
    angles : ndarray, shape (N, 3)
        roll, pitch, heading (rad); heading in [0, 2π).
    cov : ndarray, shape (N, 3, 3)
        Covariance of (roll, pitch, heading) (rad²) from the weights (a-priori unit
        variance of weight one).
    sigma0 : ndarray, shape (N,)
        Posterior standard deviation of unit weight √(vᵀPv / (3m − 3)) (NaN when m·3 = 3).
    iterations : ndarray of int, shape (N,)
    converged : ndarray of bool, shape (N,)
    """

    angles: np.ndarray
    cov: np.ndarray
    sigma0: np.ndarray
    iterations: np.ndarray
    converged: np.ndarray


def design(angles: np.ndarray, body: np.ndarray) -> np.ndarray:
    """Jacobian ∂(R·s_b,i)/∂(roll, pitch, heading) stacked over baselines: (N, 3m, 3)."""
    r, p, h = angles[:, 0], angles[:, 1], angles[:, 2]
    Rx, Ry, Rz = rot_x(r), rot_y(p), rot_z(h)
    parts = (Rz @ Ry @ d_rot_x(r), Rz @ d_rot_y(p) @ Rx, d_rot_z(h) @ Ry @ Rx)
    body = np.broadcast_to(body, (angles.shape[0],) + np.shape(body)[-2:])
    cols = [np.einsum("nij,nmj->nmi", d, body).reshape(angles.shape[0], -1) for d in parts]
    return np.stack(cols, axis=-1)


def baseline_weight(cov_antennas: np.ndarray, ref: int = 0) -> np.ndarray:
    """Weight matrix of the stacked baselines antenna ref → others.

    Parameters
    ----------
    cov_antennas : ndarray, shape (N, k, 3, 3)
        Position covariance of each antenna in NED (m²).
    ref : int
        Index of the reference antenna.

    Returns
    -------
    ndarray, shape (N, 3(k−1), 3(k−1))
        Inverse of the baselines' covariance ``Σ_ref + δ_ij Σ_i`` (1/m²).
    """
    cov = np.asarray(cov_antennas, float)
    n, k = cov.shape[:2]
    others = [i for i in range(k) if i != ref]
    m = len(others)
    full = np.tile(cov[:, ref], (1, m, m))
    for j, i in enumerate(others):
        full[:, 3 * j:3 * j + 3, 3 * j:3 * j + 3] += cov[:, i]
    return np.linalg.inv(full)


def lsq(nav: np.ndarray, body: np.ndarray, weight: np.ndarray | None, initial: np.ndarray,
        threshold_rad: float = 1e-9, max_iterations: int = 20) -> LsqResult:
    """Iterative weighted least squares of (roll, pitch, heading), per epoch.

    Parameters
    ----------
    nav : ndarray, shape (N, m, 3)
        Measured baselines from the reference antenna in NED (m).
    body : ndarray, shape (m, 3)
        The same baselines in the body frame (m).
    weight : ndarray, shape (N, 3m, 3m) or None
        Weight matrix (inverse covariance, 1/m²); identity when None.
    initial : ndarray, shape (N, 3, 3)
        Initial body → NED rotations (direct method or Wahba).
    threshold_rad : float
        Convergence threshold on every angle correction (rad).
    max_iterations : int

    Returns
    -------
    LsqResult
    """
    nav = np.asarray(nav, float)
    n, m, _ = nav.shape
    obs = nav.reshape(n, 3 * m)
    W = np.broadcast_to(np.eye(3 * m), (n, 3 * m, 3 * m)) if weight is None else weight
    angles = np.stack(matrix_angles(initial), axis=-1)
    iterations = np.zeros(n, int)
    active = np.ones(n, bool)
    for _ in range(max_iterations):
        if not active.any():
            break
        idx = np.flatnonzero(active)
        a = angles[idx]
        A = design(a, body)
        model = np.einsum("nij,mj->nmi", euler_zyx_matrix(a[:, 0], a[:, 1], a[:, 2]),
                          body).reshape(idx.size, -1)
        AtP = np.swapaxes(A, -1, -2) @ W[idx]
        N = AtP @ A
        rhs = np.einsum("nij,nj->ni", AtP, obs[idx] - model)
        delta = np.linalg.solve(N, rhs[..., None])[..., 0]
        angles[idx] = a + delta
        iterations[idx] += 1
        active[idx] = np.abs(delta).max(axis=1) >= threshold_rad
    converged = ~active
    A = design(angles, body)
    R = euler_zyx_matrix(angles[:, 0], angles[:, 1], angles[:, 2])
    v = obs - np.einsum("nij,mj->nmi", R, body).reshape(n, -1)
    AtP = np.swapaxes(A, -1, -2) @ W
    cov = np.linalg.inv(AtP @ A)
    dof = 3 * m - 3
    vpv = np.einsum("ni,nij,nj->n", v, W, v)
    sigma0 = np.sqrt(vpv / dof) if dof > 0 else np.full(n, np.nan)
    angles[:, 0] = wrap_pi(angles[:, 0])
    # Normalise the Euler triple (pitch beyond ±90° ⇒ equivalent triple).
    roll, pitch, heading = matrix_angles(R)
    angles = np.stack([roll, pitch, heading], axis=-1)
    return LsqResult(angles, cov, sigma0, iterations, converged)


def formal_covariance(R: np.ndarray, body: np.ndarray, weight: np.ndarray) -> np.ndarray:
    """Covariance of (roll, pitch, heading) (rad²) at attitudes *R* for a weight matrix."""
    angles = np.stack(matrix_angles(R), axis=-1)
    A = design(angles, body)
    return np.linalg.inv(np.swapaxes(A, -1, -2) @ weight @ A)
