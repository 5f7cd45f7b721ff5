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

from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.methods.pool_calibration.block_sigma import block_factors
from hydrosync_core.methods.pool_calibration.georef import (
    GeorefContext,
    boresight_angles,
    boresight_matrix,
)
from hydrosync_core.methods.pool_calibration.ins_cov import ins_covariance
from hydrosync_core.methods.pool_calibration.planes import PlaneFit
from hydrosync_core.progress import check_cancel

NAMES = ("roll", "pitch", "yaw", "lever_x", "lever_y", "lever_z")


@dataclass(frozen=True)
class JointFit:
    """Joint solution: boresight matrix, lever (body FRD, m), covariance of NAMES order
    (Euler angles rad, lever m; rows/columns of undetermined parameters NaN)."""

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
    #: Parameters not determined by the data -> the reason (held at their start value).
    undetermined: dict[str, str] = field(default_factory=dict)


def _axes(theta: np.ndarray) -> np.ndarray:
    """Columns ω_roll, ω_pitch, ω_yaw (body FRD) with ∂R_m/∂θ_k = [ω_k]× R_m for
    R_m = Rz(yaw)·Ry(pitch)·Rx(roll)."""
    _, pitch, yaw = theta
    cy, sy, cp, sp = np.cos(yaw), np.sin(yaw), np.cos(pitch), np.sin(pitch)
    return np.array([[cy * cp, -sy, 0.0], [sy * cp, cy, 0.0], [-sp, 0.0, 1.0]])


def _system(ctx: GeorefContext, obs: dict[str, tuple[np.ndarray, PlaneFit]], r_m, lever,
            theta=None):
    """Residuals (m), Jacobian (n, 6) and face labels of all observations.

    Columns: Euler angles (roll, pitch, yaw) of R_m (rad) when *theta* is given, else small
    rotations about the body axes; then the lever arm (m).
    """
    w = np.eye(3) if theta is None else _axes(theta)
    res, jac, lab = [], [], []
    for name, (idx, plane) in obs.items():
        p = ctx.ping[idx]
        y = ctx.x_m[idx] @ r_m.T
        a = np.einsum("nji,j->ni", ctx.rot[p], plane.normal)      # A_iᵀ n
        pts = ctx.origin[p] + np.einsum("nij,nj->ni", ctx.rot[p], y + lever)
        res.append(pts @ plane.normal - plane.d)
        jac.append(np.hstack([np.cross(y, a) @ w, a]))
        lab.append(np.full(len(idx), name, dtype=object))
    return np.concatenate(res), np.vstack(jac), np.concatenate(lab)


def _points(ctx, idx, r_m, lever):
    p = ctx.ping[idx]
    return ctx.origin[p] + np.einsum("nij,nj->ni", ctx.rot[p], ctx.x_m[idx] @ r_m.T + lever)


def _reference_cov(ctx, obs, r_m, lever, theta, free, weights, n_inv, refs=None,
                   build_sigma=(0.0, 0.0)) -> np.ndarray:
    """Covariance added by the reference planes' own uncertainty (free parameters).

    Laser fit: a plane perturbed by tilts (α, β) about its in-plane axes and an offset γ
    changes the residuals by ``B = [a1·(p - c), a2·(p - c), -1]``; the solution moves by
    ``-N⁻¹ JᵀW B (α, β, γ)``. Faces whose reference is the same laser plane (a face crossing
    the water, the twins moved from it) share (α, β, γ): their ``M = N⁻¹ JᵀW B`` are summed
    per laser plane before ``M C_plane Mᵀ`` (c is the moved centroid: a translated copy keeps
    the tilt about its own centroid).

    Build: the faces of one below-water body share its rigid error relative to the twin
    body, translation δt and rotation δω about the body's centroid q; the residual changes
    by ``[-n, n × (p - q)] (δt, δω)``, summed per body pair, with
    ``C = diag(σ_t² I, σ_ω² I)`` (*build_sigma* = (σ_t m, σ_ω rad)).
    """
    k = int(free.sum())
    per_src: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    per_group: dict[tuple, np.ndarray] = {}
    start = 0
    for name, (idx, plane) in obs.items():
        _, jac, _ = _system(ctx, {name: (idx, plane)}, r_m, lever, theta)
        w = weights[start:start + len(idx)]
        start += len(idx)
        jw = jac[:, free] * w[:, None]
        pts = _points(ctx, idx, r_m, lever)
        ref = refs.get(name) if refs else None
        if plane.axes is not None:
            rel = pts - plane.centroid
            b = np.column_stack([rel @ plane.axes[:, 1], rel @ plane.axes[:, 2],
                                 -np.ones(len(idx))])
            src = ref.source if ref is not None else name
            m = n_inv @ (jw.T @ b)
            old = per_src.get(src)
            per_src[src] = (m if old is None else old[0] + m, plane.covariance())
        if ref is not None and ref.group is not None and any(build_sigma):
            n = plane.normal
            b6 = np.hstack([-np.tile(n, (len(idx), 1)), np.cross(n, pts - ref.pivot)])
            per_group[ref.group] = per_group.get(ref.group, 0.0) + n_inv @ (jw.T @ b6)
    out = np.zeros((k, k))
    for m, c in per_src.values():
        out += m @ c @ m.T
    c_build = np.diag([build_sigma[0] ** 2] * 3 + [build_sigma[1] ** 2] * 3)
    for m in per_group.values():
        out += m @ c_build @ m.T
    return out


def euler_jacobian(r_m: np.ndarray, h: float = 1e-7) -> np.ndarray:
    """d(roll, pitch, yaw)/dδ at δ = 0 for ``R = Rot(δ)·r_m`` (3, 3), numeric."""
    from scipy.spatial.transform import Rotation

    base = np.array(boresight_angles(r_m))
    out = np.zeros((3, 3))
    for k in range(3):
        step = np.zeros(3)
        step[k] = h
        moved = Rotation.from_rotvec(step).as_matrix() @ r_m
        out[:, k] = (np.array(boresight_angles(moved)) - base) / h
    return out


def _gauss_newton(ctx, obs, theta, free, huber_m, max_iter, tol, cancel):
    """IRLS Gauss-Newton on the free parameters; returns theta, weights, iterations, ok."""
    theta = theta.copy()
    weights, converged, it = None, False, 0
    for it in range(1, max_iter + 1):
        check_cancel(cancel)
        r_m = boresight_matrix(*theta[:3])
        res, jac, _ = _system(ctx, obs, r_m, theta[3:], theta[:3])
        scale_r = 1.4826 * np.median(np.abs(res - np.median(res)))
        k = max(huber_m, 2.0 * scale_r) if it > 1 else 10 * huber_m
        weights = np.minimum(1.0, k / np.maximum(np.abs(res), 1e-12))     # Huber weights
        if not free.any():
            converged = True
            break
        jf = jac[:, free]
        step_f = np.linalg.solve(jf.T @ (jf * weights[:, None]), -jf.T @ (weights * res))
        theta[free] += step_f
        if np.max(np.abs(step_f)) < tol:
            converged = True
            break
    return theta, weights, it, converged


def adjust(ctx: GeorefContext, obs: dict[str, tuple[np.ndarray, PlaneFit]], r_m0: np.ndarray,
           lever0: np.ndarray, *, huber_m: float = 0.03, max_iter: int = 30,
           tol: float = 1e-9, cond_max: float = 1e10, fix: dict | tuple = (),
           cancel=None, block_s: float = 2.0,
           ins_sigma_rad: tuple[float, float, float] = (0.0, 0.0, 0.0),
           ins_tau_s: float = 1.0, refs: dict | None = None,
           build_sigma: tuple[float, float] = (0.0, 0.0),
           coarse: np.ndarray | None = None,
           coarse_sigma: tuple[float, float] | None = None,
           covariance: bool = True) -> JointFit:
    """Gauss-Newton / IRLS solution from the start values (r_m0, lever0).

    *fix* names parameters (of NAMES; a dict maps them to the reason) held at their start
    values. A parameter whose column of the scaled normal matrix is (nearly) in its null
    space is held too. *block_s* (s) is the ping-time block of the cluster-robust variance
    factor (module docstring). *ins_sigma_rad* (roll, pitch, heading 1-σ, rad) and
    *ins_tau_s* (s) describe the INS attitude accuracy propagated by
    :func:`~.ins_cov.ins_covariance` (zero: not added). *refs* (face -> ``twins.Reference``)
    and *build_sigma* (σ_t m, σ_ω rad) propagate the build tolerance of the twins.
    *coarse* (6: Euler rad, lever m) and *coarse_sigma* (σ rad, σ m: the accuracy of the
    coarse setup): a free parameter whose σ from the data exceeds its coarse σ is not
    determined by the data; it is reset to its coarse value and held, and the coarse error
    of every held parameter is propagated into the σ of the others. With
    ``covariance=False`` only the solution is computed.
    """
    theta = np.array([*boresight_angles(r_m0), *np.asarray(lever0, float)])
    n_obs = sum(len(i) for i, _ in obs.values())
    if n_obs < 6:
        raise ValueError("fewer than 6 multibeam points on reference planes")
    undetermined = dict(fix) if isinstance(fix, dict) else \
        {n: "held by the caller" for n in fix}
    free = np.array([n not in undetermined for n in NAMES])
    # Observability: scaled normal matrix at the start; null directions are held.
    _, jac, _ = _system(ctx, obs, r_m0, theta[3:], theta[:3])
    while free.any():
        js = jac[:, free] / np.maximum(np.linalg.norm(jac[:, free], axis=0), 1e-300)
        w, v = np.linalg.eigh(js.T @ js)
        if w[0] >= w[-1] / cond_max:
            break
        k = np.flatnonzero(free)[np.argmax(np.abs(v[:, 0]))]
        free[k] = False
        undetermined[NAMES[k]] = ("the pass geometry does not change any point-to-plane "
                                  "distance with it (singular normal matrix)")
    c_sig = None if coarse_sigma is None else np.array([coarse_sigma[0]] * 3 +
                                                       [coarse_sigma[1]] * 3)
    if coarse is not None:
        for k in np.flatnonzero(~free):
            theta[k] = coarse[k]
    while True:
        theta, weights, it, converged = _gauss_newton(ctx, obs, theta, free, huber_m,
                                                      max_iter, tol, cancel)
        r_m, lever = boresight_matrix(*theta[:3]), theta[3:].copy()
        res, jac, lab = _system(ctx, obs, r_m, lever, theta[:3])
        if not covariance:
            cov = np.full((6, 6), np.nan)
            factor = np.ones(int(free.sum()))
            break
        jf = jac[:, free]
        normal = jf.T @ (jf * weights[:, None])
        dof = max(1, len(res) - int(free.sum()))
        sigma0_sq = float(np.sum(weights * res**2) / dof)
        n_inv = np.linalg.inv(normal)
        factor = block_factors(ctx, obs, jf, res, weights, n_inv, block_s, r_m, lever)
        root = np.sqrt(factor)
        # Formal σ0² N⁻¹, inflated by the block-sandwich factors, + reference planes, build
        # tolerance and INS accuracy.
        cov_f = sigma0_sq * n_inv * np.outer(root, root) + \
            _reference_cov(ctx, obs, r_m, lever, theta[:3], free, weights, n_inv, refs,
                           build_sigma) + \
            ins_covariance(ctx, obs, r_m, lever, jf, weights, n_inv,
                           np.asarray(ins_sigma_rad), ins_tau_s)
        held = ~free
        if c_sig is not None and held.any():
            # A held parameter keeps its coarse error e_c: the free ones move by
            # -N_ff⁻¹ N_fc e_c.
            jh = jac[:, held]
            k_mat = n_inv @ (jf.T @ (jh * weights[:, None]))
            cov_f = cov_f + k_mat @ np.diag(c_sig[held] ** 2) @ k_mat.T
        sig = np.sqrt(np.clip(np.diag(cov_f), 0, None))
        if c_sig is not None and coarse is not None:
            ratio = sig / c_sig[free]
            if ratio.max() > 1.0 and free.sum() > 1:
                k = np.flatnonzero(free)[int(np.argmax(ratio))]
                unit, scale = ("°", np.degrees(1.0)) if k < 3 else (" m", 1.0)
                undetermined[NAMES[k]] = (
                    f"σ from the data ({sig[np.argmax(ratio)] * scale:.3g}{unit}) exceeds the "
                    f"accuracy of the coarse value ({c_sig[k] * scale:.3g}{unit})")
                free[k] = False
                theta[k] = coarse[k]
                continue
        cov = np.full((6, 6), np.nan)
        cov[np.ix_(free, free)] = cov_f
        break
    rms = {str(n): float(np.sqrt(np.mean(res[lab == n] ** 2))) for n in obs}
    vf = np.full(6, np.nan)
    vf[free] = factor
    s0 = float(np.sqrt(np.sum(weights * res**2) / max(1, len(res) - int(free.sum()))))
    fixed = tuple(n for n, f in zip(NAMES, free, strict=True) if not f)
    return JointFit(r_m, lever, cov, s0, len(res), it, converged, fixed, rms, vf,
                    {n: undetermined[n] for n in fixed})


def correlation(cov: np.ndarray) -> np.ndarray:
    """Correlation matrix of a covariance (zero or NaN rows give 0; diagonal 1)."""
    d = np.diag(cov)
    s = np.sqrt(np.where(np.isfinite(d) & (d > 0), d, 0.0))
    denom = np.outer(s, s)
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.where(denom > 0, cov / denom, 0.0)
    return np.nan_to_num(c)
