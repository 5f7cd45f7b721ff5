"""Covariance of the joint solution propagated from the INS attitude accuracy (a priori).

The soundings of one ping share the INS attitude error of that ping, and a real INS error
is correlated over seconds; the residuals cannot reveal the part of it that the boresight
absorbs (a mean heading error over the few seconds the oblique faces are in view *is* a
yaw error), so the accuracy of the INS is an input: 1-σ roll, pitch and heading errors
(rad) modelled as first-order Gauss-Markov processes of correlation time τ (s)::

    C(e_p, e_q) = diag(σ_r², σ_p², σ_h²) · exp(-|t_p - t_q| / τ)       (white when τ = 0)

Small-angle effect on a point ``p_i = o + A (y_i)`` with ``y_i = R_m x_i + l`` (body FRD)
and ``A = C R_b`` (body -> ENU), ``R_b = Rz(h)·Ry(p)·Rx(r)``: a roll error turns about body
x, a pitch error about ``Rx(r)ᵀ ŷ = (0, cos r, -sin r)``, a heading error about NED down::

    ∂r_i/∂e_r = n·A(x̂ × y_i),   ∂r_i/∂e_p = n·A((0, cos r, -sin r) × y_i),
    ∂r_i/∂e_h = n·((0, 0, -1) × A y_i)

The solution moves by ``-N⁻¹ JᵀW D e``; with ``H_p = Σ_{i∈p} w_i J_i D_iᵀ`` per ping
(k × 3), its covariance is ``N⁻¹ (Σ_j σ_j² H_jᵀ K H_j) N⁻¹``, ``K_pq = exp(-|t_p-t_q|/τ)``,
evaluated in chunks of pings against the pings within 8 τ (the kernel is < 3e-4 beyond).
"""

from __future__ import annotations

import numpy as np

from hydrosync_core.methods.pool_calibration.georef import C_NED_TO_ENU, GeorefContext
from hydrosync_core.methods.pool_calibration.planes import PlaneFit


def attitude_derivatives(ctx: GeorefContext, obs: dict[str, tuple[np.ndarray, PlaneFit]],
                         r_m: np.ndarray, lever: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """∂r/∂(roll, pitch, heading) error (n, 3; m/rad) and ping index (n,) of the observations."""
    d_cols, pings = [], []
    for idx, plane in obs.values():
        p = ctx.ping[idx]
        y = ctx.x_m[idx] @ r_m.T + lever                                  # body FRD, m
        rot = ctx.rot[p]
        n = plane.normal
        dr = np.einsum("nij,nj->ni", rot, np.cross([1.0, 0.0, 0.0], y)) @ n
        # Roll of each ping from R_b = C·rot (C is its own inverse): r = atan2(R32, R33).
        r_b = C_NED_TO_ENU @ rot
        roll = np.arctan2(r_b[:, 2, 1], r_b[:, 2, 2])
        axis_p = np.column_stack([np.zeros_like(roll), np.cos(roll), -np.sin(roll)])
        dp = np.einsum("nij,nj->ni", rot, np.cross(axis_p, y)) @ n
        dh = np.cross([0.0, 0.0, -1.0], np.einsum("nij,nj->ni", rot, y)) @ n
        d_cols.append(np.column_stack([dr, dp, dh]))
        pings.append(p)
    return np.vstack(d_cols), np.concatenate(pings)


def ins_covariance(ctx: GeorefContext, obs: dict[str, tuple[np.ndarray, PlaneFit]],
                   r_m: np.ndarray, lever: np.ndarray, jac_f: np.ndarray,
                   weights: np.ndarray, n_inv: np.ndarray, sigma_rad: np.ndarray,
                   tau_s: float, chunk: int = 2000) -> np.ndarray:
    """(k, k) covariance of the free parameters (δ rad, Δl m) from INS attitude errors.

    Parameters
    ----------
    jac_f, weights : Jacobian (n, k) of the free parameters and IRLS weights (n,) of the
        observations, in the order of *obs* (as built by ``joint._system``).
    sigma_rad : (3,) 1-σ roll, pitch, heading errors of the INS, rad.
    tau_s : correlation time of the errors, s (0: independent from ping to ping).
    """
    sigma_rad = np.asarray(sigma_rad, dtype=float)
    k = jac_f.shape[1]
    if not np.any(sigma_rad > 0):
        return np.zeros((k, k))
    d, ping = attitude_derivatives(ctx, obs, r_m, lever)
    uniq, inv = np.unique(ping, return_inverse=True)
    # H_p: (P, k, 3) per-ping sums of w_i J_i D_iᵀ.
    h = np.zeros((len(uniq), k, 3))
    np.add.at(h, inv, (weights[:, None] * jac_f)[:, :, None] * d[:, None, :])
    t = ctx.ping_time[uniq] if ctx.ping_time is not None else uniq.astype(float)
    meat = np.zeros((k, k))
    if tau_s <= 0:
        for j in range(3):
            meat += sigma_rad[j] ** 2 * np.einsum("pa,pb->ab", h[:, :, j], h[:, :, j])
    else:
        reach = 8.0 * tau_s
        for start in range(0, len(t), chunk):
            rows = slice(start, start + chunk)
            lo = np.searchsorted(t, t[rows][0] - reach)
            hi = np.searchsorted(t, t[rows][-1] + reach, side="right")
            kern = np.exp(-np.abs(t[rows, None] - t[None, lo:hi]) / tau_s)
            for j in range(3):
                meat += sigma_rad[j] ** 2 * h[rows, :, j].T @ kern @ h[lo:hi, :, j]
    meat = 0.5 * (meat + meat.T)
    return n_inv @ meat @ n_inv
