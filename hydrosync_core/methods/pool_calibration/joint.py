"""Joint least-squares adjustment of the boresight angles and lever arm (beyond the seed).

Unknowns: a small rotation δ (rad, about the body FRD axes, applied as
``R_m <- Rot(δ)·R_m``) and a lever-arm change Δl (m, body FRD). Observations: the
signed distances of the multibeam points of each face to that face's reference plane
(the laser plane of the same face, or for a below-water horizontal face its design plane
raised by the as-built height offset measured by the laser on the above-water tops,
i.e. the seed's design height difference of step 4.2)::

    r_i = n_k · p_i - d_k,   p_i = o + A_i (R_m x_i + l)            (A_i = C·R_b)
    ∂r_i/∂Δl = a_i = A_iᵀ n_k,   ∂r_i/∂δ = (R_m x_i) × a_i

Gauss-Newton with Huber iteratively reweighted least squares (outliers left by the
segmentation get small weights). Covariance ``σ0² (JᵀWJ)⁻¹`` with ``σ0²`` the weighted
residual variance, plus the part propagated from the reference planes' own fit
uncertainty (laser TLS planes; the as-built height offset of the design planes). σ and
correlations are reported for the (roll, pitch, yaw) Euler angles of the boresight
(through the numeric Jacobian of the Euler angles with respect to δ) and the three
lever-arm components. A parameter whose column of the normal matrix is (nearly) in its
null space, or that the caller names in ``fix``, is held and reported as undetermined.

Honest σ under correlated errors. ``σ0² (JᵀWJ)⁻¹`` assumes independent soundings; real
errors are shared by the soundings of one ping and by neighbouring pings (INS attitude
and position noise, sound speed, refraction), and then it is optimistic. So the formal
covariance is checked against the block (cluster-robust) sandwich estimator
``N⁻¹ (B/(B-1) Σ_b g_b g_bᵀ) N⁻¹`` with ``N = JᵀWJ`` and ``g_b = Σ_{i∈b} w_i r̃_i J_i`` the
score summed over a block ``b`` of consecutive pings (``block_s`` seconds of ping time,
default 2 s; one ping when 0). r̃ are the residuals less, per face, their weighted fit by
a plane error (two tilts and an offset): that pattern is the reference plane's own error,
already propagated by the reference-plane term, and would otherwise be counted twice
(it alone gave factors of 3-5 on yaw and lever x on error-free INS data). For independent
soundings sandwich and formal agree; for errors correlated within a block the sandwich
grows with the block's effective sample size. Each free parameter's variance is
multiplied by ``F_k = max(1, [sandwich]_kk / [σ̃0² N⁻¹]_kk)`` (``JointFit.variance_factor``,
δ axes; rows and columns scaled by √F_k so correlations keep the formal structure), never
reduced. The reference-plane term is added after.

Monte-Carlo (``benchmarks/bench_pool_accuracy.py``, 16-24 simulated passes, exact INS):
the normalised errors (estimate - truth) / σ have an RMS of 0.65-1.1 per parameter (lever
z is conservative: its σ0 is pooled over faces while the below-water top it rests on is
less noisy). Limits: the check cannot see errors that the parameters absorb (e.g. the
mean INS roll error over the pass is indistinguishable from boresight roll) nor
correlation longer than a block; with simulated INS attitude errors (0.01°, Gauss-Markov
τ = 1 s) the RMS of error/σ improves from up to 3.5 (formal) to 1.0-1.9 only, because
yaw and lever x rest on the few seconds in which the oblique faces are in view (few
informative blocks). Hence the INS attitude accuracy is an input (``ins_sigma_rad``,
``ins_tau_s``; pool params ``ins_sigma_roll_deg`` ... ``ins_tau_s``), propagated a priori
by :mod:`.ins_cov` and added to the covariance (zero by default: exact INS).

A former bias of up to ±0.017° in roll (≈5σ, different on every run: the demo's −44.187°
± 0.003° against −44.200°) came from the segmentation, not from this model: the final
face points were the inliers of a ±3 cm band around open3d's (multi-threaded, hence not
repeatable) RANSAC plane, and a slightly tilted RANSAC plane cut the noise asymmetrically
at one end of the wall. The final selection is now a symmetric ±k·σ band around the
face's own least-squares plane (``segment.band_refit``, ``refine_band_sigma`` = 4).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial.transform import Rotation

from hydrosync_core.methods.pool_calibration.block_sigma import block_factors
from hydrosync_core.methods.pool_calibration.georef import GeorefContext, boresight_angles
from hydrosync_core.methods.pool_calibration.ins_cov import ins_covariance
from hydrosync_core.methods.pool_calibration.planes import PlaneFit
from hydrosync_core.progress import check_cancel

NAMES = ("roll", "pitch", "yaw", "lever_x", "lever_y", "lever_z")


@dataclass(frozen=True)
class JointFit:
    """Joint solution: boresight matrix, lever (body FRD, m), covariance of NAMES order."""

    r_m: np.ndarray
    lever: np.ndarray
    covariance: np.ndarray
    sigma0_m: float
    n_obs: int
    iterations: int
    converged: bool
    fixed: tuple[str, ...]
    residual_rms: dict[str, float]
    variance_factor: np.ndarray | None = None


def _system(ctx: GeorefContext, obs: dict[str, tuple[np.ndarray, PlaneFit]], r_m, lever):
    """Residuals (m), Jacobian (n, 6) and face labels of all observations."""
    res, jac, lab = [], [], []
    for name, (idx, plane) in obs.items():
        p = ctx.ping[idx]
        y = ctx.x_m[idx] @ r_m.T
        a = np.einsum("nji,j->ni", ctx.rot[p], plane.normal)      # A_iᵀ n
        pts = ctx.origin[p] + np.einsum("nij,nj->ni", ctx.rot[p], y + lever)
        res.append(pts @ plane.normal - plane.d)
        jac.append(np.hstack([np.cross(y, a), a]))
        lab.append(np.full(len(idx), name, dtype=object))
    return np.concatenate(res), np.vstack(jac), np.concatenate(lab)


def _reference_cov(ctx, obs, r_m, lever, free, weights, n_inv) -> np.ndarray:
    """Covariance added by the reference planes' own uncertainty (free parameters).

    A plane perturbed by tilts (α, β) about its in-plane axes and an offset γ changes the
    residuals by ``B = [a1·(p - c), a2·(p - c), -1]``; the solution moves by
    ``-N⁻¹ JᵀW B (α, β, γ)``, so each face adds ``M C_plane Mᵀ`` with ``M = N⁻¹ JᵀW B``.
    """
    out = np.zeros((int(free.sum()),) * 2)
    start = 0
    for _name, (idx, plane) in obs.items():
        sub = {_name: (idx, plane)}
        _, jac, _ = _system(ctx, sub, r_m, lever)
        w = weights[start:start + len(idx)]
        start += len(idx)
        if plane.axes is None:
            continue
        p = ctx.ping[idx]
        pts = ctx.origin[p] + np.einsum("nij,nj->ni", ctx.rot[p], ctx.x_m[idx] @ r_m.T + lever)
        rel = pts - plane.centroid
        b = np.column_stack([rel @ plane.axes[:, 1], rel @ plane.axes[:, 2], -np.ones(len(idx))])
        m = n_inv @ (jac[:, free].T @ (b * w[:, None]))
        out += m @ plane.covariance() @ m.T
    return out


def euler_jacobian(r_m: np.ndarray, h: float = 1e-7) -> np.ndarray:
    """d(roll, pitch, yaw)/dδ at δ = 0 for ``R = Rot(δ)·r_m`` (3, 3), numeric."""
    base = np.array(boresight_angles(r_m))
    out = np.zeros((3, 3))
    for k in range(3):
        step = np.zeros(3)
        step[k] = h
        moved = Rotation.from_rotvec(step).as_matrix() @ r_m
        out[:, k] = (np.array(boresight_angles(moved)) - base) / h
    return out


def adjust(ctx: GeorefContext, obs: dict[str, tuple[np.ndarray, PlaneFit]], r_m0: np.ndarray,
           lever0: np.ndarray, *, huber_m: float = 0.03, max_iter: int = 30,
           tol: float = 1e-9, cond_max: float = 1e10, fix: tuple[str, ...] = (),
           cancel=None, block_s: float = 2.0,
           ins_sigma_rad: tuple[float, float, float] = (0.0, 0.0, 0.0),
           ins_tau_s: float = 1.0) -> JointFit:
    """Gauss-Newton / IRLS solution from the start values (r_m0, lever0).

    *fix* names parameters (of NAMES) held at their start values. *block_s* (s) is the
    ping-time block of the cluster-robust variance factor (see the module docstring).
    *ins_sigma_rad* (roll, pitch, heading 1-σ, rad) and *ins_tau_s* (s) describe the INS
    attitude accuracy propagated by :func:`~.ins_cov.ins_covariance` (zero: not added).
    """
    r_m, lever = r_m0.copy(), np.asarray(lever0, float).copy()
    n_obs = sum(len(i) for i, _ in obs.values())
    if n_obs < 6:
        raise ValueError("fewer than 6 multibeam points on reference planes")
    # Observability: scaled normal matrix at the start; weak directions are fixed.
    _, jac, _ = _system(ctx, obs, r_m, lever)
    scale = np.linalg.norm(jac, axis=0)
    scale[scale == 0] = 1.0
    js = jac / scale
    w, v = np.linalg.eigh(js.T @ js)
    free = np.array([n not in fix for n in NAMES])
    for k in np.flatnonzero(w < w.max() / cond_max):
        free[np.argmax(np.abs(v[:, k]))] = False
    fixed = tuple(n for n, f in zip(NAMES, free, strict=True) if not f)
    weights = None
    converged, it = False, 0
    for it in range(1, max_iter + 1):
        check_cancel(cancel)
        res, jac, _ = _system(ctx, obs, r_m, lever)
        scale_r = 1.4826 * np.median(np.abs(res - np.median(res)))
        k = max(huber_m, 2.0 * scale_r) if it > 1 else 10 * huber_m
        weights = np.minimum(1.0, k / np.maximum(np.abs(res), 1e-12))     # Huber weights
        jf = jac[:, free]
        step_f = np.linalg.solve(jf.T @ (jf * weights[:, None]), -jf.T @ (weights * res))
        step = np.zeros(6)
        step[free] = step_f
        r_m = Rotation.from_rotvec(step[:3]).as_matrix() @ r_m
        lever = lever + step[3:]
        if np.max(np.abs(step)) < tol:
            converged = True
            break
    res, jac, lab = _system(ctx, obs, r_m, lever)
    jf = jac[:, free]
    normal = jf.T @ (jf * weights[:, None])
    dof = max(1, len(res) - int(free.sum()))
    sigma0_sq = float(np.sum(weights * res**2) / dof)
    n_inv = np.linalg.inv(normal)
    factor = block_factors(ctx, obs, jf, res, weights, n_inv, block_s, r_m, lever)
    root = np.sqrt(factor)
    # Formal covariance σ0² N⁻¹, inflated by the block-sandwich factors, + reference planes.
    cov_f = sigma0_sq * n_inv * np.outer(root, root) + \
        _reference_cov(ctx, obs, r_m, lever, free, weights, n_inv) + \
        ins_covariance(ctx, obs, r_m, lever, jf, weights, n_inv, np.asarray(ins_sigma_rad),
                       ins_tau_s)
    cov_d = np.zeros((6, 6))
    cov_d[np.ix_(free, free)] = cov_f
    # Propagate δ -> Euler angles (roll, pitch, yaw).
    t = np.eye(6)
    t[:3, :3] = euler_jacobian(r_m)
    cov = t @ cov_d @ t.T
    rms = {str(n): float(np.sqrt(np.mean(res[lab == n] ** 2))) for n in obs}
    vf = np.ones(6)
    vf[free] = factor
    return JointFit(r_m, lever, cov, float(np.sqrt(sigma0_sq)), len(res), it, converged,
                    fixed, rms, vf)


def correlation(cov: np.ndarray) -> np.ndarray:
    """Correlation matrix of a covariance (zero rows stay zero)."""
    s = np.sqrt(np.clip(np.diag(cov), 0, None))
    denom = np.outer(s, s)
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.where(denom > 0, cov / denom, 0.0)
    return c
