"""Ping-block (cluster-robust) check of the joint adjustment's formal covariance.

See the module docstring of :mod:`.joint` ("Honest σ under correlated errors"): the
sandwich ``N⁻¹ (B/(B-1) Σ_b g_b g_bᵀ) N⁻¹`` over blocks of consecutive pings is compared
with ``σ̃0² N⁻¹`` and each parameter's variance is inflated by the ratio when above 1.
Units: residuals in m, δ in rad, Δl in m; ping times in s.
"""

from __future__ import annotations

import numpy as np

from hydrosync_core.methods.pool_calibration.beams import sounding_points
from hydrosync_core.methods.pool_calibration.georef import GeorefContext
from hydrosync_core.methods.pool_calibration.planes import PlaneFit


def _plane_pattern_removed(ctx: GeorefContext, obs: dict[str, tuple[np.ndarray, PlaneFit]],
                           res: np.ndarray, weights: np.ndarray, r_m, lever) -> np.ndarray:
    """Residuals (m) minus, per face, their weighted fit by a plane error (tilts + offset).

    An error of a face's reference plane leaves the residual pattern
    ``B (α, β, γ)``, ``B = [e1·(p - c), e2·(p - c), 1]`` (e1, e2 in-plane axes), shared by
    every sounding of the face; ``joint._reference_cov`` already propagates it, so it is taken
    out here lest the block check count it a second time.
    """
    out = res.copy()
    start = 0
    for idx, plane in obs.values():
        sl = slice(start, start + len(idx))
        start += len(idx)
        if len(idx) < 4:
            continue
        pts = sounding_points(ctx, idx, r_m, lever, plane)
        e1 = np.cross(plane.normal, [0.0, 0.0, 1.0])
        if np.linalg.norm(e1) < 0.5:
            e1 = np.cross(plane.normal, [1.0, 0.0, 0.0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(plane.normal, e1)
        rel = pts - pts.mean(axis=0)
        b = np.column_stack([rel @ e1, rel @ e2, np.ones(len(idx))])
        w = weights[sl]
        coef = np.linalg.lstsq(b * np.sqrt(w)[:, None], np.sqrt(w) * res[sl], rcond=None)[0]
        out[sl] = res[sl] - b @ coef
    return out


def block_factors(ctx: GeorefContext, obs: dict[str, tuple[np.ndarray, PlaneFit]],
                  jac_f: np.ndarray, res: np.ndarray, weights: np.ndarray,
                  n_inv: np.ndarray, block_s: float, r_m: np.ndarray,
                  lever: np.ndarray) -> np.ndarray:
    """Variance factors F_k >= 1 (free parameters) of the ping-block sandwich estimator.

    ``cov_c = N⁻¹ (B/(B-1) Σ_b g_b g_bᵀ) N⁻¹``, ``g_b = Σ_{i∈b} w_i r̃_i J_i`` summed over
    blocks of *block_s* seconds of ping time (single pings when 0 or without ping times),
    with r̃ the residuals less their per-face plane-error pattern
    (:func:`_plane_pattern_removed`); ``F_k = max(1, cov_c[k, k] / (σ̃0² N⁻¹)[k, k])`` with
    σ̃0² the weighted variance of r̃.
    """
    ping = np.concatenate([ctx.ping[idx] for idx, _ in obs.values()])
    if ctx.ping_time is not None and block_s > 0:
        t = ctx.ping_time[ping]
        block = np.floor((t - t.min()) / block_s).astype(np.int64)
    else:
        block = ping
    _, inv = np.unique(block, return_inverse=True)
    n_blocks = int(inv.max()) + 1
    if n_blocks < 2:
        return np.ones(jac_f.shape[1])
    r_t = _plane_pattern_removed(ctx, obs, res, weights, r_m, lever)
    dof = max(1, len(res) - jac_f.shape[1] - 3 * len(obs))
    sigma_sq = float(np.sum(weights * r_t**2) / dof)
    # Score of each observation, summed per block (clusters of correlated soundings).
    g = np.zeros((n_blocks, jac_f.shape[1]))
    np.add.at(g, inv, jac_f * (weights * r_t)[:, None])
    meat = n_blocks / (n_blocks - 1) * (g.T @ g)
    cov_c = n_inv @ meat @ n_inv
    formal = sigma_sq * np.diag(n_inv)
    return np.maximum(1.0, np.diag(cov_c) / np.maximum(formal, 1e-300))
