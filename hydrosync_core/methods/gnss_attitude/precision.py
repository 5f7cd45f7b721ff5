"""Predicted attitude precision from the array geometry and the antennas' position noise.

The least-squares prediction is the inverse normal matrix of Liu et al.'s adjustment
(their eq. 24) at a given attitude, with the full covariance of the baselines (they share
the reference antenna). The direct method's prediction propagates the same position
covariance through its closed formulas (numerical Jacobian). Scaling the layout gives the
accuracy-versus-baseline-length curve of Liu et al.'s fig. 15; :func:`monte_carlo` checks
it by simulation. Angles in degrees (heading, pitch, roll), lengths in metres.
"""

from __future__ import annotations

from itertools import combinations

import numpy as np

from hydrosync_core.methods.gnss_attitude import solve
from hydrosync_core.methods.gnss_attitude.pipeline import _direct_with_std, _triplet
from hydrosync_core.rotations import euler_zyx_matrix, wrap_pi


def _cov(sigma_h: float, sigma_v: float) -> np.ndarray:
    return np.diag([sigma_h**2, sigma_h**2, sigma_v**2])


def longest_baseline(body: np.ndarray) -> float:
    """Largest distance between two antennas (m)."""
    return max(np.linalg.norm(body[i] - body[j]) for i, j in combinations(range(len(body)), 2))


def predict(body, sigma_h: float, sigma_v: float, attitude_deg=(0.0, 0.0, 0.0),
            method: str = "lsq", triplet: tuple[int, int, int] | None = None) -> np.ndarray:
    """Predicted 1σ of (heading, pitch, roll) in degrees.

    Parameters
    ----------
    body : array_like (K, 3)
        Antenna coordinates in the body frame (FRD, m).
    sigma_h, sigma_v : float
        Per-antenna horizontal and vertical position noise (1σ, m), independent antennas.
    attitude_deg : (heading, pitch, roll)
        Attitude at which to predict (deg); level by default.
    method : ``"lsq"`` (all antennas) or ``"direct"`` (three antennas)
    triplet : indices of the direct method's antennas 1, 2, 3 (default: largest triangle)
    """
    body = np.asarray(body, float)
    h, p, r = np.radians(attitude_deg)
    R = euler_zyx_matrix(r, p, h)[None]
    K = body.shape[0]
    cov = np.broadcast_to(_cov(sigma_h, sigma_v), (1, K, 3, 3))
    if method == "lsq":
        W = solve.baseline_weight(cov, 0)
        c = solve.formal_covariance(R, body[1:] - body[0], W)[0]
    else:
        names = [str(i) for i in range(K)]
        tri = triplet or _triplet(names, body, np.ones(K, bool), None)
        ned = np.einsum("ij,kj->ki", R[0], body)[None]
        _, _, c = _direct_with_std(ned, cov, body, tri)
        c = c[0]
    return np.degrees(np.sqrt(np.diag(c)))[[2, 1, 0]]


def monte_carlo(body, sigma_h: float, sigma_v: float, n: int = 2000, seed: int = 0,
                attitude_deg=(0.0, 0.0, 0.0), triplet=None) -> dict[str, np.ndarray]:
    """Simulated std of (heading, pitch, roll) (deg) of LSQ and direct, *n* noisy epochs."""
    body = np.asarray(body, float)
    rng = np.random.default_rng(seed)
    h, p, r = np.radians(attitude_deg)
    R = euler_zyx_matrix(r, p, h)
    K = body.shape[0]
    ned = np.einsum("ij,kj->ki", R, body)[None] + rng.standard_normal((n, K, 3)) * np.array(
        [sigma_h, sigma_h, sigma_v])
    base = ned[:, 1:] - ned[:, :1]
    bb = body[1:] - body[0]
    cov = np.broadcast_to(_cov(sigma_h, sigma_v), (n, K, 3, 3))
    W = solve.baseline_weight(cov, 0)
    res = solve.lsq(base, bb, W, solve.wahba(base, bb), 1e-10, 20)
    names = [str(i) for i in range(K)]
    tri = triplet or _triplet(names, body, np.ones(K, bool), None)
    ad, _, _ = _direct_with_std(ned, cov, body, tri)
    truth = np.array([r, p, h])

    def spread(a):
        d = wrap_pi(a - truth)
        return np.degrees(np.sqrt(np.mean(d**2, axis=0)))[[2, 1, 0]]

    return {"lsq": spread(res.angles), "direct": spread(ad)}


def accuracy_vs_baseline(body, lengths_m, sigma_h: float, sigma_v: float, n_mc: int = 0,
                         seed: int = 0) -> dict[str, np.ndarray]:
    """Predicted (and optionally simulated) precision when the layout is scaled.

    The layout is scaled so that its longest antenna distance equals each length.
    Returns columns ``baseline_m`` and ``{lsq,direct}_{heading,pitch,roll}_deg`` (predicted)
    and, with *n_mc* > 0, ``mc_{lsq,direct}_{…}_deg`` (simulated RMS error).
    """
    body = np.asarray(body, float)
    scale0 = longest_baseline(body)
    lengths = np.asarray(lengths_m, float)
    out: dict[str, np.ndarray] = {"baseline_m": lengths}
    for method in ("lsq", "direct"):
        pred = np.array([predict(body * L / scale0, sigma_h, sigma_v, method=method)
                         for L in lengths])
        for c, a in enumerate(("heading", "pitch", "roll")):
            out[f"{method}_{a}_deg"] = pred[:, c]
    if n_mc > 0:
        sims = [monte_carlo(body * L / scale0, sigma_h, sigma_v, n_mc, seed + i)
                for i, L in enumerate(lengths)]
        for method in ("lsq", "direct"):
            arr = np.array([s[method] for s in sims])
            for c, a in enumerate(("heading", "pitch", "roll")):
                out[f"mc_{method}_{a}_deg"] = arr[:, c]
    return out
