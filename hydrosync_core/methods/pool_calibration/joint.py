"""Joint least-squares adjustment of the boresight angles and lever arm (beyond the seed).

Unknowns: the boresight Euler angles θ = (roll, pitch, yaw) of ``R_m = Rz·Ry·Rx`` (rad; an
undetermined angle is then held exactly at its coarse value) and the lever arm l (m, body
FRD); plus, for every below-water body whose faces are compared with their above-water
twin, its as-built displacement (δt m, δω rad about the body's centroid q) with the build
tolerance as prior. Observations: the signed distances of the multibeam points of each face
to that face's reference plane (:mod:`.twins`: its own laser plane, or its twin's moved by
the design translation)::

    r_i = n_k · p_i - d_k + [-n_k, n_k × (p_i - q)] (δt, δω),   p_i = o + A_i (R_m x_i + l)
    ∂r_i/∂l = a_i = A_iᵀ n_k,   ∂r_i/∂θ_j = ((R_m x_i) × a_i) · ω_j     (A_i = C·R_b)

with ω_roll = Rz·Ry·e_x, ω_pitch = Rz·e_y, ω_yaw = e_z (∂R_m/∂θ_j = [ω_j]× R_m), the
rotation columns taken at ``y* = R_m x_i - (r_i / (a_i·û_i)) û_i``, where the beam meets the
plane, not at the sounding: a range error moves ``R_m x_i`` with the residual and biased the
solution (errors in the variables, :mod:`.beams`). The
displacements' prior ``diag(σ_t² I, σ_ω² I)`` (σ = tol/√3, a rectangular tolerance) is a
stochastic constraint: ``σ0² C⁻¹`` added to their block of the normal matrix. So the
blocks' offsets weigh only as much as the build allows (block tops at different depths do
not pull roll and pitch) and ``σ0² [N_aug⁻¹]_θθ`` carries the build tolerance.

Gauss-Newton with Huber iteratively reweighted least squares (outliers left by the
segmentation get small weights). Covariance ``σ0² [N_aug⁻¹]_θθ``, plus the part propagated
from the laser reference planes' own fit uncertainty (faces sharing a laser plane — a
crossing face and the twins moved from it — share its error), plus the INS accuracy. Each
part is kept (``JointFit.budget``) so that a user told "pitch is poorly determined" also
learns what would help: more passes (data), a surveyed as-built target (build), a denser
laser scan (reference) or a better INS.

Undetermined parameters. A parameter whose column of the normal matrix is (nearly) in its
null space, that the caller names in ``fix`` (with a reason), or whose σ from the data
exceeds the accuracy of the coarse setup, is held at its coarse value and reported as
undetermined with the reason; the coarse error of every held parameter is propagated into
the σ of the free ones.

Honest σ under correlated errors. ``σ0² N⁻¹`` assumes independent soundings; real
errors are shared by the soundings of one ping and by neighbouring pings (INS attitude
and position noise, sound speed, refraction), and then it is optimistic. So the formal
covariance is checked against the block (cluster-robust) sandwich estimator
``N⁻¹ (B/(B-1) Σ_b g_b g_bᵀ) N⁻¹`` with ``N = JᵀWJ`` and ``g_b = Σ_{i∈b} w_i r̃_i J_i`` the
score summed over a block ``b`` of consecutive pings (``block_s`` seconds of ping time,
default 2 s; one ping when 0). r̃ are the residuals less, per face, their weighted fit by
a plane error (two tilts and an offset): that pattern is the reference plane's own error
(or its build displacement), already in the covariance, and would otherwise be counted
twice. Each free parameter's data variance is multiplied by
``F_k = max(1, [sandwich]_kk / [σ̃0² N⁻¹]_kk)`` (``JointFit.variance_factor``), never
reduced. The sandwich is itself a noisy estimate when few blocks see the faces that carry a
parameter (yaw, lever x on a short pass). The INS attitude accuracy is an input
(``ins_sigma_rad``, ``ins_tau_s``), propagated a priori by :mod:`.ins_cov` (zero by
default: exact INS), since the residuals cannot reveal the part of an INS error that the
boresight absorbs.

A former bias of up to ±0.017° in roll came from the segmentation (a RANSAC band cut
asymmetrically), not from this model: the final selection is a symmetric ±k·σ band around
the face's own least-squares plane (``segment.band_refit``, ``refine_band_sigma`` = 4).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.methods.pool_calibration.beams import beam_meets_plane, sounding_points
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
    #: σ budget: source -> (6,) 1-σ of each parameter from that source alone (NAMES order,
    #: rad / m; NaN for held parameters). Sources: ``data`` (soundings' noise, incl. the
    #: ping-block factor), ``build`` (twins' build tolerance), ``reference`` (laser planes'
    #: fit), ``ins`` (INS attitude accuracy), ``held`` (coarse error of held parameters).
    #: Their variances add up to the diagonal of ``covariance``; correlations between
    #: parameters are in ``covariance`` only.
    budget: dict[str, np.ndarray] = field(default_factory=dict)


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
        r = pts @ plane.normal - plane.d
        res.append(r)
        jac.append(np.hstack([np.cross(beam_meets_plane(y, a, r), a) @ w, a]))
        lab.append(np.full(len(idx), name, dtype=object))
    return np.concatenate(res), np.vstack(jac), np.concatenate(lab)


def _build_groups(obs, refs, build_sigma) -> tuple[dict, np.ndarray]:
    """Build-error groups (below-water body, twin body) -> index, and the prior σ (6,)."""
    sig = np.array([build_sigma[0]] * 3 + [build_sigma[1]] * 3, dtype=float)
    if refs is None or not np.any(sig > 0):
        return {}, sig
    groups: dict = {}
    for name in obs:
        ref = refs.get(name)
        if ref is not None and ref.group is not None and ref.group not in groups:
            groups[ref.group] = len(groups)
    return groups, sig


def _build_columns(ctx, obs, refs, groups, sig, r_m, lever) -> np.ndarray:
    """(n, 6G) derivatives of the residuals w.r.t. each group's as-built displacement.

    The faces of one below-water body share its rigid error relative to the twin body,
    translation δt and rotation δω about the body's centroid q: the residual of a point p of
    a face with normal n changes by ``[-n, n × (p - q)] (δt, δω)``. Columns whose prior σ is
    zero are left at zero.
    """
    n_obs = sum(len(i) for i, _ in obs.values())
    out = np.zeros((n_obs, 6 * len(groups)))
    start = 0
    for name, (idx, plane) in obs.items():
        ref = refs.get(name) if refs else None
        sl = slice(start, start + len(idx))
        start += len(idx)
        if ref is None or ref.group not in groups:
            continue
        g = groups[ref.group]
        pts = sounding_points(ctx, idx, r_m, lever, plane)
        n = plane.normal
        block = np.hstack([-np.tile(n, (len(idx), 1)), np.cross(n, pts - ref.pivot)])
        out[sl, 6 * g:6 * g + 6] = block * (sig > 0)
    return out


def _reference_cov(ctx, obs, r_m, lever, jac_aug, weights, g_theta, refs=None) -> np.ndarray:
    """Covariance of the free parameters added by the laser reference planes' own fit.

    A plane perturbed by tilts (α, β) about its in-plane axes and an offset γ changes the
    residuals by ``B = [a1·(p - c), a2·(p - c), -1]``; the solution moves by
    ``-G JᵀW B (α, β, γ)`` with ``G`` the parameters' rows of the inverse (augmented) normal
    matrix. Faces whose reference is the same laser plane (a face crossing the water, the
    twins moved from it) share (α, β, γ): their ``M = G JᵀW B`` are summed per laser plane
    before ``M C_plane Mᵀ`` (c is the moved centroid: a translated copy keeps the tilt about
    its own centroid).
    """
    k = g_theta.shape[0]
    per_src: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    start = 0
    for name, (idx, plane) in obs.items():
        sl = slice(start, start + len(idx))
        start += len(idx)
        if plane.axes is None:
            continue
        jw = jac_aug[sl] * weights[sl, None]
        rel = sounding_points(ctx, idx, r_m, lever, plane) - plane.centroid
        b = np.column_stack([rel @ plane.axes[:, 1], rel @ plane.axes[:, 2],
                             -np.ones(len(idx))])
        ref = refs.get(name) if refs else None
        src = ref.source if ref is not None else name
        m = g_theta @ (jw.T @ b)
        old = per_src.get(src)
        per_src[src] = (m if old is None else old[0] + m, plane.covariance())
    out = np.zeros((k, k))
    for m, c in per_src.values():
        out += m @ c @ m.T
    return out


def _augmented(jf, bcols, weights, sigma0_sq, prior_sig):
    """Normal matrix of (free parameters, build displacements) with the build prior."""
    a = np.hstack([jf, bcols])
    normal = a.T @ (a * weights[:, None])
    if bcols.shape[1]:
        k = jf.shape[1]
        prior = np.tile(prior_sig, bcols.shape[1] // 6)
        safe = np.where(prior > 0, prior, 1.0)
        diag = np.where(prior > 0, sigma0_sq / safe**2, 1.0)
        normal[k:, k:] += np.diag(diag)
    return a, normal


def _gauss_newton(ctx, obs, theta, free, huber_m, max_iter, tol, cancel, refs=None,
                  groups=None, prior_sig=None):
    """IRLS Gauss-Newton on the free parameters and the build displacements (with their
    prior); returns theta, weights, iterations, converged, the displacements and σ0²."""
    theta = theta.copy()
    groups = groups or {}
    nb = 6 * len(groups)
    disp = np.zeros(nb)
    weights, converged, it, sigma0_sq = None, False, 0, 1.0
    for it in range(1, max_iter + 1):
        check_cancel(cancel)
        r_m = boresight_matrix(*theta[:3])
        res, jac, _ = _system(ctx, obs, r_m, theta[3:], theta[:3])
        bcols = _build_columns(ctx, obs, refs, groups, prior_sig, r_m, theta[3:]) \
            if nb else np.zeros((len(res), 0))
        res = res + bcols @ disp
        scale_r = 1.4826 * np.median(np.abs(res - np.median(res)))
        k = max(huber_m, 2.0 * scale_r) if it > 1 else 10 * huber_m
        weights = np.minimum(1.0, k / np.maximum(np.abs(res), 1e-12))     # Huber weights
        sigma0_sq = max(float(np.sum(weights * res**2) / max(1, len(res) - free.sum())),
                        1e-12)
        if not free.any() and not nb:
            converged = True
            break
        a, normal = _augmented(jac[:, free], bcols, weights, sigma0_sq, prior_sig)
        rhs = -a.T @ (weights * res)
        if nb:
            # The prior pulls the displacements towards zero.
            prior = np.tile(prior_sig, len(groups))
            safe = np.where(prior > 0, prior, 1.0)
            rhs[-nb:] -= np.where(prior > 0, sigma0_sq / safe**2, 0.0) * disp
        step = np.linalg.solve(normal, rhs)
        theta[free] += step[:int(free.sum())]
        disp += step[int(free.sum()):]
        if np.max(np.abs(step)) < tol:
            converged = True
            break
    return theta, weights, it, converged, disp, sigma0_sq


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
    groups, prior_sig = _build_groups(obs, refs, build_sigma)
    while True:
        theta, weights, it, converged, disp, sigma0_sq = _gauss_newton(
            ctx, obs, theta, free, huber_m, max_iter, tol, cancel, refs, groups, prior_sig)
        r_m, lever = boresight_matrix(*theta[:3]), theta[3:].copy()
        res, jac, lab = _system(ctx, obs, r_m, lever, theta[:3])
        bcols = _build_columns(ctx, obs, refs, groups, prior_sig, r_m, lever) \
            if groups else np.zeros((len(res), 0))
        res = res + bcols @ disp
        if not covariance:
            cov = np.full((6, 6), np.nan)
            factor = np.ones(int(free.sum()))
            budget = {}
            break
        jf = jac[:, free]
        kf = int(free.sum())
        normal = jf.T @ (jf * weights[:, None])
        n_inv = np.linalg.inv(normal)
        # Augmented system (free parameters + as-built displacements with their prior):
        # σ0² [N_aug⁻¹]_θθ holds the data noise and the build tolerance.
        a_aug, n_aug = _augmented(jf, bcols, weights, sigma0_sq, prior_sig)
        n_aug_inv = np.linalg.inv(n_aug)
        g_theta = n_aug_inv[:kf]
        factor = block_factors(ctx, obs, jf, res, weights, n_inv, block_s, r_m, lever)
        root = np.sqrt(factor)
        # Formal σ0² N_aug⁻¹; its data part σ0² N⁻¹ inflated by the block-sandwich factors;
        # + laser reference planes and INS accuracy.
        parts = {
            "data": sigma0_sq * n_inv * np.outer(root, root),
            # Without build columns there is no build term: the difference of two inverses
            # of one matrix would only give round-off of order √(ε·cond N)·σ.
            "build": (sigma0_sq * (n_aug_inv[:kf, :kf] - n_inv) if bcols.shape[1]
                      else np.zeros((kf, kf))),
            "reference": _reference_cov(ctx, obs, r_m, lever, a_aug, weights, g_theta, refs),
            "ins": ins_covariance(ctx, obs, r_m, lever, a_aug, weights, n_aug_inv,
                                  np.asarray(ins_sigma_rad), ins_tau_s)[:kf, :kf],
        }
        held = ~free
        if c_sig is not None and held.any():
            # A held parameter keeps its coarse error e_c: the free ones move by
            # -[N_aug⁻¹ A_augᵀ W J_held]_θ e_c.
            jh = jac[:, held]
            k_mat = g_theta @ (a_aug.T @ (jh * weights[:, None]))
            parts["held"] = k_mat @ np.diag(c_sig[held] ** 2) @ k_mat.T
        cov_f = sum(parts.values())
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
        budget = {}
        for source, part in parts.items():
            budget[source] = np.full(6, np.nan)
            budget[source][free] = np.sqrt(np.clip(np.diag(part), 0, None))
        break
    rms = {str(n): float(np.sqrt(np.mean(res[lab == n] ** 2))) for n in obs}
    vf = np.full(6, np.nan)
    vf[free] = factor
    s0 = float(np.sqrt(np.sum(weights * res**2) / max(1, len(res) - int(free.sum()))))
    fixed = tuple(n for n, f in zip(NAMES, free, strict=True) if not f)
    return JointFit(r_m, lever, cov, s0, len(res), it, converged, fixed, rms, vf,
                    {n: undetermined[n] for n in fixed}, budget)


def correlation(cov: np.ndarray) -> np.ndarray:
    """Correlation matrix of a covariance (zero or NaN rows give 0; diagonal 1)."""
    d = np.diag(cov)
    s = np.sqrt(np.where(np.isfinite(d) & (d > 0), d, 0.0))
    denom = np.outer(s, s)
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.where(denom > 0, cov / denom, 0.0)
    return np.nan_to_num(c)
