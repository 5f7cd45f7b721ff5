"""Exact correlation sums over a uniform grid of trial delays, without candidates × epochs work.

For one line, eq. 4 of Qi et al. (2010) needs, at every trial delay Δt_k,

    F_k = Σ_i w_i·H(t_i − Δt_k),   S1_k = Σ_i H(t_i − Δt_k),   S2_k = Σ_i H(t_i − Δt_k)²,

with H the first-order (linear) interpolant of the total heave between attitude samples
(eq. 3) and w the centred, normalised heights. Between two attitude samples t_j ≤ u ≤
t_{j+1}, H(u) = A − b·Δt with b the segment's slope and A = H_j + b·(t_i − t_j): linear in
Δt. So each (epoch, attitude segment) pair adds a polynomial in Δt of degree ≤ 2 to a
contiguous run of candidates, and difference arrays with one cumulative sum give every
F_k, S1_k, S2_k exactly (to rounding). The work is epochs × (segments the scan range
spans) instead of epochs × candidates: with 100 Hz attitude and a 1 ms step, 10× less,
and no interpolation at all. Compiled with numba when it is available; otherwise callers
fall back to the direct evaluation (:func:`.correlation.correlation_curve_direct`).

Values at the ends follow :func:`numpy.interp`: constant beyond the first and last sample.
"""

from __future__ import annotations

import numpy as np

try:  # numba is a dependency; the direct numpy evaluation remains if it cannot load
    from numba import njit
except ImportError:  # pragma: no cover
    njit = None


def _sums_py(tags, w, ta, ha, dts, step):  # pragma: no cover - compiled below
    """Kernel: (F, S1, S2) at every ``dts[k] = dts[0] + k·step`` (see the module doc)."""
    K = dts.size
    m = ta.size
    d0 = dts[0]
    inv = 1.0 / step
    slope = np.empty(max(m - 1, 0))
    for j in range(m - 1):
        slope[j] = (ha[j + 1] - ha[j]) / (ta[j + 1] - ta[j])
    # Changes of the running coefficients at each candidate: F = Aw − Bw·Δ, S1 = A − B·Δ,
    # S2 = A2 − 2·AB·Δ + B2·Δ² (one row of 7 per candidate: contiguous writes).
    acc = np.zeros((K + 1, 7))
    for i in range(tags.size):
        t = tags[i]
        wi = w[i]
        # First candidate: u = t − d0, the latest time; segment j with ta[j] <= u < ta[j+1].
        u0 = t - d0
        j = np.searchsorted(ta, u0, side="right") - 1
        k = 0
        pa = 0.0
        pb = 0.0
        while k < K:
            if j >= m - 1:
                a = ha[m - 1]  # at or beyond the last sample: constant (np.interp)
                b = 0.0
                kend = int(np.floor((u0 - ta[m - 1]) * inv)) + 1
            elif j < 0:
                a = ha[0]  # before the first sample: constant
                b = 0.0
                kend = K
            else:
                b = slope[j]
                a = ha[j] + b * (t - ta[j])
                kend = int(np.floor((u0 - ta[j]) * inv)) + 1
            if kend > K:
                kend = K
            if kend > k:
                da = a - pa
                db = b - pb
                row = acc[k]
                row[0] += wi * da
                row[1] += wi * db
                row[2] += da
                row[3] += db
                row[4] += a * a - pa * pa
                row[5] += a * b - pa * pb
                row[6] += b * b - pb * pb
                pa = a
                pb = b
                k = kend
            j -= 1
    F = np.empty(K)
    S1 = np.empty(K)
    S2 = np.empty(K)
    c0 = c1 = c2 = c3 = c4 = c5 = c6 = 0.0
    for k in range(K):
        row = acc[k]
        c0 += row[0]
        c1 += row[1]
        c2 += row[2]
        c3 += row[3]
        c4 += row[4]
        c5 += row[5]
        c6 += row[6]
        d = dts[k]
        F[k] = c0 - c1 * d
        S1[k] = c2 - c3 * d
        S2[k] = c4 - 2.0 * c5 * d + c6 * d * d
    return F, S1, S2


_sums = njit(cache=True, nogil=True)(_sums_py) if njit is not None else None


def available() -> bool:
    """True when the compiled kernel can be used."""
    return _sums is not None


def uniform_step(dts: np.ndarray) -> float | None:
    """The step of *dts* if it is an increasing uniform grid of ≥ 2 points, else None."""
    if dts.size < 2:
        return None
    step = (float(dts[-1]) - float(dts[0])) / (dts.size - 1)
    if not step > 0:
        return None
    if np.max(np.abs(np.diff(dts) - step)) > 1e-9 * max(step, 1e-300):
        return None
    return step


def correlation_sums(tags: np.ndarray, w: np.ndarray, t_att: np.ndarray, h_att: np.ndarray,
                     dts: np.ndarray, step: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(F, S1, S2) of the module doc for the uniform grid *dts* (s) of spacing *step*."""
    return _sums(np.ascontiguousarray(tags, dtype=float), np.ascontiguousarray(w, dtype=float),
                 np.ascontiguousarray(t_att, dtype=float),
                 np.ascontiguousarray(h_att, dtype=float),
                 np.ascontiguousarray(dts, dtype=float), float(step))
