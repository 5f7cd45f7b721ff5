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

:func:`scan_core` runs a line's whole scan (the curve, its maximum, the sub-step refinement
and the uncertainty of :mod:`.correlation`) as one compiled call that releases the GIL;
:func:`.lines.scan_line` takes it where it applies and the Python steps otherwise (the
tests keep the two equal to rounding).
"""

from __future__ import annotations

import numpy as np
from numba import njit


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


_sums = njit(cache=True, nogil=True)(_sums_py)


def _row_py(acc, c0, c1, c2, c3, v0, v1, v2, v3, n):  # pragma: no cover - compiled below
    """``acc[:n] += c0·v0 + c1·v1 + c2·v2 + c3·v3``, element by element in that order."""
    for i in range(n):
        acc[i] += c0 * v0[i] + c1 * v1[i] + c2 * v2[i] + c3 * v3[i]


def _combine_py(tf, t1, t2, a, u, g, off, n):  # pragma: no cover - compiled below
    """One residue's share of F, S1, S2 at ``n`` candidates of one phase (see below)."""
    a0, a1, a2, a3, a4 = a[0], a[1], a[2], a[3], a[4]
    a5, a6, a7, a8, a9 = a[5], a[6], a[7], a[8], a[9]
    for kap in range(n):
        li = kap + off
        tf[kap] += u * a0[li] - a1[li] + g * a0[li - 1] + a1[li - 1]
        t1[kap] += u * a2[li] - a3[li] + g * a2[li - 1] + a3[li - 1]
        t2[kap] += (u * u * a4[li] - 2.0 * u * a5[li] + a6[li]
                    + 2.0 * (g * u * a7[li] + (1.0 - 2.0 * g) * a8[li] - a9[li])
                    + g * g * a4[li - 1] + 2.0 * g * a5[li - 1] + a6[li - 1])


# Inlined: a call per row would cost more than the row on short grids.
_row = njit(nogil=True, inline="always")(_row_py)
_combine = njit(nogil=True, inline="always")(_combine_py)


SPLIT_MIN_LAGS = 16
"""Lags from which :func:`_lattice_sums_py` updates each accumulator row in its own loop.

With the ten rows updated in one loop LLVM cannot show that they do not overlap the heave
arrays and emits scalar code; one row per loop it vectorises (with a run-time overlap
check), which halves a 2001-candidate scan. Short lag ranges (the refinement's grid) keep
the single loop, whose overhead is lower there. Both give the same sums to the last bit:
every element sees the same operations in the same order."""


def _lattice_sums_py(x, w, H, L, K, split_min):  # pragma: no cover - compiled below
    """Kernel of :func:`correlation_sums` on a uniform attitude grid (see LATTICE_TOLERANCE).

    *x*: epoch positions ``(tag − dts[0] − ta[0]) / step`` in steps; *H*: heave at the
    attitude samples, which lie every *L* steps. With ``x = L·q + r + ε`` (q, r integers,
    0 ≤ r < L, 0 ≤ ε < 1) and candidate ``k = L·κ + ρ``, the epoch sits at attitude sample
    ``J = q − κ − c`` plus the fraction ``f = g + ε/L``, where ``c = [r < ρ]`` and
    ``g = ((r − ρ) mod L)/L`` depend on (r, ρ) only. So per residue r the sums are
    correlations over the lag λ = κ + c of per-epoch weights (w, w·e, 1, e, e², e = ε/L)
    with H, H² and H_j·H_{j+1} — dense, contiguous loops — combined per candidate at the end.
    *split_min*: see SPLIT_MIN_LAGS. A residue without epochs adds +0 to each sum (its
    accumulators are +0 and u, g ≥ 0), which leaves every sum as it is: it is skipped.
    """
    m = H.size
    kk = (K - 1) // L
    nl = kk + 3  # λ = −1 … kk + 1, stored at λ + 1
    # Reversed so that the lags run forwards in memory: R[m − 1 − j] = H[j].
    Hr = np.empty(m)
    H2r = np.empty(m)
    Pr = np.zeros(m)
    for j in range(m):
        Hr[m - 1 - j] = H[j]
        H2r[m - 1 - j] = H[j] * H[j]
    for j in range(m - 1):
        Pr[m - 1 - j] = H[j] * H[j + 1]
    acc = np.zeros((L, 10, nl))
    # Epochs grouped by residue and taken four at a time: each pass over the lags then
    # loads and stores the ten accumulators once for four epochs.
    n_ep = x.size
    q_of = np.empty(n_ep, dtype=np.int64)
    r_of = np.empty(n_ep, dtype=np.int64)
    e_of = np.empty(n_ep)
    for i in range(n_ep):
        n = np.floor(x[i])
        e_of[i] = (x[i] - n) / L
        ni = int(n)
        q_of[i] = ni // L
        r_of[i] = ni - q_of[i] * L
    # Epochs by residue, in their order within a residue: a stable counting sort (the
    # order of np.argsort(r_of, kind="mergesort"), without its O(n log n)).
    first = np.zeros(L + 1, dtype=np.int64)
    for i in range(n_ep):
        first[r_of[i] + 1] += 1
    # Residues without epochs add exact zeros to every candidate: skipped below. Regular
    # GNSS tags on regular attitude all share one residue (9 in 10 empty at L = 10).
    filled = np.zeros(L, dtype=np.bool_)
    for r in range(L):
        filled[r] = first[r + 1] > 0
        first[r + 1] += first[r]
    order = np.empty(n_ep, dtype=np.int64)
    for i in range(n_ep):
        order[first[r_of[i]]] = i
        first[r_of[i]] += 1
    c = np.zeros((4, 10))
    b = np.zeros(4, dtype=np.int64)
    start = 0
    while start < n_ep:
        r = r_of[order[start]]
        stop = start
        while stop < n_ep and r_of[order[stop]] == r:
            stop += 1
        a = acc[r]
        for blk in range(start, stop, 4):
            for u in range(4):
                if blk + u < stop:
                    i = order[blk + u]
                    e = e_of[i]
                    wi = w[i]
                    c[u, 0] = wi
                    c[u, 1] = wi * e
                    c[u, 2] = 1.0
                    c[u, 3] = e
                    c[u, 4] = e * e
                    b[u] = m - 1 - q_of[i] - 1
                else:
                    for f in range(5):
                        c[u, f] = 0.0
                    b[u] = b[0]
            w0, w1, w2, w3 = c[0, 0], c[1, 0], c[2, 0], c[3, 0]
            x0, x1, x2, x3 = c[0, 1], c[1, 1], c[2, 1], c[3, 1]
            o0, o1, o2, o3 = c[0, 2], c[1, 2], c[2, 2], c[3, 2]
            e0, e1, e2, e3 = c[0, 3], c[1, 3], c[2, 3], c[3, 3]
            f0, f1, f2, f3 = c[0, 4], c[1, 4], c[2, 4], c[3, 4]
            b0, b1, b2, b3 = b[0], b[1], b[2], b[3]
            if nl >= split_min:
                hr0, hr1 = Hr[b0:b0 + nl], Hr[b1:b1 + nl]
                hr2, hr3 = Hr[b2:b2 + nl], Hr[b3:b3 + nl]
                gr0, gr1 = H2r[b0:b0 + nl], H2r[b1:b1 + nl]
                gr2, gr3 = H2r[b2:b2 + nl], H2r[b3:b3 + nl]
                pr0, pr1 = Pr[b0:b0 + nl], Pr[b1:b1 + nl]
                pr2, pr3 = Pr[b2:b2 + nl], Pr[b3:b3 + nl]
                _row(a[0], w0, w1, w2, w3, hr0, hr1, hr2, hr3, nl)
                _row(a[1], x0, x1, x2, x3, hr0, hr1, hr2, hr3, nl)
                _row(a[2], o0, o1, o2, o3, hr0, hr1, hr2, hr3, nl)
                _row(a[3], e0, e1, e2, e3, hr0, hr1, hr2, hr3, nl)
                _row(a[4], o0, o1, o2, o3, gr0, gr1, gr2, gr3, nl)
                _row(a[5], e0, e1, e2, e3, gr0, gr1, gr2, gr3, nl)
                _row(a[6], f0, f1, f2, f3, gr0, gr1, gr2, gr3, nl)
                _row(a[7], o0, o1, o2, o3, pr0, pr1, pr2, pr3, nl)
                _row(a[8], e0, e1, e2, e3, pr0, pr1, pr2, pr3, nl)
                _row(a[9], f0, f1, f2, f3, pr0, pr1, pr2, pr3, nl)
                continue
            for li in range(nl):
                h0 = Hr[b0 + li]
                h1 = Hr[b1 + li]
                h2 = Hr[b2 + li]
                h3 = Hr[b3 + li]
                g0 = H2r[b0 + li]
                g1 = H2r[b1 + li]
                g2 = H2r[b2 + li]
                g3 = H2r[b3 + li]
                p0 = Pr[b0 + li]
                p1 = Pr[b1 + li]
                p2 = Pr[b2 + li]
                p3 = Pr[b3 + li]
                a[0, li] += w0 * h0 + w1 * h1 + w2 * h2 + w3 * h3
                a[1, li] += x0 * h0 + x1 * h1 + x2 * h2 + x3 * h3
                a[2, li] += o0 * h0 + o1 * h1 + o2 * h2 + o3 * h3
                a[3, li] += e0 * h0 + e1 * h1 + e2 * h2 + e3 * h3
                a[4, li] += o0 * g0 + o1 * g1 + o2 * g2 + o3 * g3
                a[5, li] += e0 * g0 + e1 * g1 + e2 * g2 + e3 * g3
                a[6, li] += f0 * g0 + f1 * g1 + f2 * g2 + f3 * g3
                a[7, li] += o0 * p0 + o1 * p1 + o2 * p2 + o3 * p3
                a[8, li] += e0 * p0 + e1 * p1 + e2 * p2 + e3 * p3
                a[9, li] += f0 * p0 + f1 * p1 + f2 * p2 + f3 * p3
        start = stop
    if nl >= split_min:
        # Candidate by candidate below; here phase by phase (k = L·κ + ρ, ρ fixed): the
        # rows are read contiguously in κ. Each candidate still sums its residues in order.
        F = np.empty(K)
        S1 = np.empty(K)
        S2 = np.empty(K)
        tf = np.empty(kk + 1)
        t1 = np.empty(kk + 1)
        t2 = np.empty(kk + 1)
        for rho in range(min(L, K)):
            nk = (K - 1 - rho) // L + 1
            tf[:nk] = 0.0
            t1[:nk] = 0.0
            t2[:nk] = 0.0
            for r in range(L):
                if not filled[r]:
                    continue
                cr = 1 if r < rho else 0
                g = (r - rho + cr * L) / L
                _combine(tf, t1, t2, acc[r], 1.0 - g, g, cr + 1, nk)
            for kap in range(nk):
                F[kap * L + rho] = tf[kap]
                S1[kap * L + rho] = t1[kap]
                S2[kap * L + rho] = t2[kap]
        return F, S1, S2
    F = np.zeros(K)
    S1 = np.zeros(K)
    S2 = np.zeros(K)
    for k in range(K):
        kap = k // L
        rho = k - kap * L
        f = 0.0
        s1 = 0.0
        s2 = 0.0
        for r in range(L):
            if not filled[r]:
                continue
            c = 1 if r < rho else 0
            g = (r - rho + c * L) / L
            u = 1.0 - g
            li = kap + c + 1
            a = acc[r]
            # J = q − λ (weight 1 − f) and J + 1 = q − (λ − 1) (weight f), f = g + e.
            f += u * a[0, li] - a[1, li] + g * a[0, li - 1] + a[1, li - 1]
            s1 += u * a[2, li] - a[3, li] + g * a[2, li - 1] + a[3, li - 1]
            s2 += (u * u * a[4, li] - 2.0 * u * a[5, li] + a[6, li]
                   + 2.0 * (g * u * a[7, li] + (1.0 - 2.0 * g) * a[8, li] - a[9, li])
                   + g * g * a[4, li - 1] + 2.0 * g * a[5, li - 1] + a[6, li - 1])
        F[k] = f
        S1[k] = s1
        S2[k] = s2
    return F, S1, S2


_lattice_sums = njit(cache=True, nogil=True)(_lattice_sums_py)


def _departure_py(ta, interval):  # pragma: no cover - compiled below
    """Largest |ta[j] − ta[0] − j·interval| (s)."""
    worst = 0.0
    for j in range(ta.size):
        d = abs(ta[j] - ta[0] - j * interval)
        if d > worst:
            worst = d
    return worst


_departure = njit(cache=True, nogil=True)(_departure_py)


def _departs_py(ta, interval, limit):  # pragma: no cover - compiled below
    """``_departure(ta, interval) > limit``: any departure above *limit* (NaNs never are).

    An OR over the samples rather than their maximum: LLVM vectorises it (a float
    maximum it may not reorder), and every line's scans ask it again.
    """
    t0 = ta[0]
    over = False
    for j in range(ta.size):
        over |= abs(ta[j] - t0 - j * interval) > limit
    return over

LATTICE_TOLERANCE = 1e-6
"""Largest departure of an attitude time from the uniform grid, as a fraction of the
sampling interval, for the lattice kernel (10 ns at 100 Hz: the interpolated heave then
differs from the exact one by less than 1e-7 m at 10 m/s)."""


def _lattice_py(tags, ta, d0, step, K, tolerance):  # pragma: no cover - compiled below
    """Kernel of :func:`_lattice`: (x, L), L = 0 when the grid does not fit."""
    none = (np.empty(0), 0)
    m = ta.size
    if m < 4 or tags.size == 0:
        return none
    interval = (ta[m - 1] - ta[0]) / (m - 1)
    ratio = interval / step
    L = int(np.rint(ratio))  # round(): halves to even, as np.rint
    if L < 1 or abs(ratio - L) > 1e-9 * ratio:
        return none
    if _departs(ta, interval, tolerance * interval):
        return none
    x = np.empty(tags.size)
    unit = interval / L
    lo = np.inf
    hi = -np.inf
    for i in range(tags.size):
        x[i] = (tags[i] - ta[0] - d0) / unit
        if x[i] < lo:
            lo = x[i]
        if x[i] > hi:
            hi = x[i]
        if x[i] != x[i]:  # NaN: every comparison below is False, the grid "fits"
            return x, L
    kk = (K - 1) // L
    if int(np.floor(lo)) // L - kk - 1 < 0 or int(np.floor(hi)) // L + 1 > m - 2:
        return none
    return x, L


_departs = njit(nogil=True, inline="always")(_departs_py)
_lattice_nb = njit(cache=True, nogil=True)(_lattice_py)


def _lattice(tags, ta, dts, step):
    """(positions x, L) for :func:`_lattice_sums`, or None when the grid does not fit.

    Needs uniformly sampled attitude whose interval is a whole number L of steps, and
    every epoch at every candidate strictly inside the samples (one to spare each side).
    Positions ``(tag − ta[0] − dts[0]) / (interval / L)`` in steps.
    """
    x, L = _lattice_nb(np.ascontiguousarray(tags, dtype=float),
                       np.ascontiguousarray(ta, dtype=float), float(dts[0]), float(step),
                       int(dts.size), LATTICE_TOLERANCE)
    return (x, L) if L else None


COMPILED = True
"""False makes :func:`scan_core` and :func:`line_sigma` decline, so that the scan takes its
Python steps (the benchmark's reference evaluation; the tests keep the two equal)."""


def available() -> bool:
    """True when the compiled kernel is to be used (:data:`COMPILED`)."""
    return COMPILED


def _largest_step_py(t):  # pragma: no cover - compiled below
    """Kernel of :func:`largest_step`."""
    best = -np.inf
    for i in range(t.size - 1):
        d = t[i + 1] - t[i]
        if d > best:
            best = d
    return best


_largest_step = njit(cache=True, nogil=True)(_largest_step_py)


def largest_step(t: np.ndarray) -> float:
    """``np.diff(t).max()`` of finite *t* (≥ 2 values), without the difference array
    (compiled: no interpreter lock held)."""
    if t.dtype != np.float64:
        return float(np.diff(t).max())
    return float(_largest_step(np.ascontiguousarray(t)))


def _uniform_step_py(dts):  # pragma: no cover - compiled below
    """Kernel of :func:`uniform_step`: the step, or 0.0 for None."""
    n = dts.size
    if n < 2:
        return 0.0
    step = (dts[n - 1] - dts[0]) / (n - 1)
    if not step > 0:
        return 0.0
    limit = 1e-9 * max(step, 1e-300)
    over = False
    for i in range(n - 1):
        d = abs((dts[i + 1] - dts[i]) - step)
        if d != d:
            return step  # np.max is NaN then, and NaN > limit is False
        if d > limit:
            over = True
    return 0.0 if over else step


_uniform_step = njit(cache=True, nogil=True)(_uniform_step_py)


def uniform_step(dts: np.ndarray) -> float | None:
    """The step of *dts* if it is an increasing uniform grid of ≥ 2 points, else None.

    Uniform: every difference within 1e-9 of the step (relative).
    """
    step = float(_uniform_step(np.ascontiguousarray(dts, dtype=float)))
    return step if step > 0 else None


def _grid_py(start, stop, num):  # pragma: no cover - compiled below
    """Kernel of :func:`grid`."""
    out = np.empty(num)
    div = num - 1
    delta = stop - start
    step = delta / div
    for i in range(num):
        # np.linspace's arithmetic, operation for operation (also for a zero step).
        out[i] = (i / div * delta if step == 0 else i * step) + start
    out[num - 1] = stop
    return out


_grid = njit(cache=True, nogil=True)(_grid_py)


def grid(start: float, stop: float, num: int) -> np.ndarray:
    """``np.linspace(start, stop, num)`` (num ≥ 2), the same numbers without its Python
    overhead (the refinement and uncertainty grids of every line and pass)."""
    if num < 2:
        return np.linspace(start, stop, num)
    return _grid(float(start), float(stop), int(num))


def _pearson_py(F, S1, S2, n, mean_w):  # pragma: no cover - compiled below
    """Kernel of :func:`pearson`."""
    r = np.empty(F.size)
    for k in range(F.size):
        var = S2[k] - S1[k] * S1[k] / n
        if var > 1e-12 * abs(S2[k]) + 1e-300:
            r[k] = (F[k] - S1[k] * mean_w) / np.sqrt(var)
        else:
            r[k] = np.nan
    return r


_pearson = njit(cache=True, nogil=True)(_pearson_py)


def pearson(F: np.ndarray, S1: np.ndarray, S2: np.ndarray, n: int, mean_w: float
            ) -> np.ndarray:
    """Seed eq. 4 from the sums: ``(F − S1·w̄) / sqrt(S2 − S1²/n)`` per candidate, NaN
    where the heave varies by less than 1e-12 of S2 (constant); *w* unit-normed heights
    of mean *mean_w*."""
    return _pearson(F, S1, S2, int(n), float(mean_w))


def correlation_sums(tags: np.ndarray, w: np.ndarray, t_att: np.ndarray, h_att: np.ndarray,
                     dts: np.ndarray, step: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(F, S1, S2) of the module doc for the uniform grid *dts* (s) of spacing *step*.

    Regularly sampled attitude (an interval of a whole number of steps) takes the lattice
    kernel, which gives the same sums (to rounding) with dense, vectorisable loops.
    """
    tags = np.ascontiguousarray(tags, dtype=float)
    w = np.ascontiguousarray(w, dtype=float)
    t_att = np.ascontiguousarray(t_att, dtype=float)
    lattice = _lattice(tags, t_att, dts, step)
    if lattice is not None:
        x, L = lattice
        return _lattice_sums(x, w, np.ascontiguousarray(h_att, dtype=float), L, dts.size,
                             SPLIT_MIN_LAGS)
    return _sums(np.ascontiguousarray(tags, dtype=float), np.ascontiguousarray(w, dtype=float),
                 np.ascontiguousarray(t_att, dtype=float),
                 np.ascontiguousarray(h_att, dtype=float),
                 np.ascontiguousarray(dts, dtype=float), float(step))


# --- One line's whole scan in one compiled call -------------------------------------
# scan_line's steps (correlation curve, its maximum, sub-step refinement, uncertainty)
# as one kernel: per line and pass these were ~40 small numpy calls holding the
# interpreter lock, which the two scan threads then took turns for (a survey day's
# `auto` ran only 1.3x faster on two cores than on one). The kernels live in this
# module because numba's cache does not notice changes in another module's kernels.

def _sums_any_py(tags, w, ta, ha, dts, step):  # pragma: no cover - compiled below
    """:func:`correlation_sums` (lattice kernel where it fits, else the general one)."""
    x, L = _lattice_nb(tags, ta, dts[0], step, dts.size, LATTICE_TOLERANCE)
    if L:
        return _lattice_sums(x, w, ha, L, dts.size, SPLIT_MIN_LAGS)
    return _sums(tags, w, ta, ha, dts, step)


def _curve_py(tags, unit, ta, ha, dts, step):  # pragma: no cover - compiled below
    """:func:`.correlation.correlation_curve` on a uniform grid of spacing *step*."""
    F, S1, S2 = _sums_any(tags, unit, ta, ha, dts, step)
    return _pearson(F, S1, S2, tags.size, _mean(unit))


def _argmax_min_py(curve):  # pragma: no cover - compiled below
    """(first index of the maximum ignoring NaN, minimum ignoring NaN); index −1 when
    nothing is finite (:func:`.lines._argmax_min`)."""
    k = -1
    high = low = np.nan
    finite = False
    for i in range(curve.size):
        v = curve[i]
        if v != v:
            continue
        finite |= np.isfinite(v)
        if k < 0 or v > high:  # the first of equal maxima, as np.nanargmax
            k = i
            high = v
        if not v >= low:  # also the first value (low NaN)
            low = v
    return (k if finite else -1), low


def _mean_py(x):  # pragma: no cover - compiled below
    total = 0.0
    for i in range(x.size):
        total += x[i]
    return total / x.size


def vertex(x, y, k):
    """Vertex ``(x, y)`` of the parabola through ``(x, y)[k-1:k+2]`` (equally spaced x);
    the point ``k`` itself when they do not curve down. Plain Python, also compiled for
    :func:`scan_core`."""
    a, b, c = y[k - 1], y[k], y[k + 1]
    denom = a - 2 * b + c
    if not np.isfinite(denom) or denom >= 0:
        return x[k], y[k]
    shift = 0.5 * (a - c) / denom
    return x[k] + shift * (x[1] - x[0]), b - 0.25 * (a - c) * shift


def _sigma_py(tags, h, ta, ha, dt, unit, max_lag_s, delta, width
              ):  # pragma: no cover - compiled below
    """:func:`.correlation.peak_uncertainty` (s); NaN as there; −1.0 when its
    curvature grid is not uniform (the caller then takes the Python path).

    The Newey–West autocovariances are summed directly (a few hundred lags of a
    line's epochs) rather than by FFT: the same sums to rounding.
    """
    n = tags.size
    if n < 5:
        return np.nan
    span = (tags[n - 1] - tags[0]) / max(n - 1, 1)
    H0 = np.interp(tags - (dt - delta), ta, ha)
    H1 = np.interp(tags - dt, ta, ha)
    H2 = np.interp(tags - (dt + delta), ta, ha)
    Hc = H1 - _mean(H1)
    hc = h - _mean(h)
    hh = np.sum(Hc * Hc)
    if not hh > 0:
        return np.nan
    b = np.sum(Hc * hc) / hh
    resid = hc - b * Hc
    g = b * (H2 - H0) / (2 * delta)
    g = g - _mean(g)
    g = g - (np.sum(Hc * g) / hh) * Hc
    grid = _grid(dt - width, dt + width, 21)
    step = _uniform_step(grid)
    if not step > 0:
        return -1.0
    r = _curve(tags, unit, ta, ha, grid, step)
    x2 = (grid - dt) ** 2
    x2 = x2 - _mean(x2)
    c2 = np.sum(x2 * r) / np.sum(x2 * x2)
    jj = -np.sum(hc * hc) * r[10] * 2 * c2
    if not jj > 0:
        return np.nan
    u = resid * g
    lags = int(min(n // 3, max(1, np.rint(max_lag_s / max(span, 1e-9)))))
    # Every lag's sum at once, epoch by epoch: the inner loop over lags vectorises (one
    # running sum per lag would wait on its own additions).
    acov = np.zeros(lags + 1)
    for i in range(n):
        ui = u[i]
        top = min(lags, n - 1 - i)
        for lag in range(top + 1):
            acov[lag] += ui * u[i + lag]
    meat = 0.0
    for lag in range(lags + 1):
        weight = 1.0 - lag / (lags + 1)
        meat += (2.0 * weight if lag else weight) * acov[lag]
    meat *= n / max(n - 3, 1)
    return np.sqrt(max(meat, 0.0)) / jj


def _window_py(tags, h, t_att, h_att, lo, hi, margin):  # pragma: no cover - compiled below
    """(attitude times and heave of :func:`.lines.attitude_window` for Δt in [lo, hi],
    unit-normed centred heights :func:`.correlation.unit_centred`)."""
    i0 = max(np.searchsorted(t_att, tags[0] - hi - margin) - 1, 0)
    i1 = min(np.searchsorted(t_att, tags[tags.size - 1] - lo + margin) + 1, t_att.size)
    hc = h - _mean(h)
    norm = np.sqrt(np.sum(hc * hc))
    return t_att[i0:i1], h_att[i0:i1], hc / max(norm, 1e-300)


def _line_sigma_py(tags, h, t_att, h_att, lo, hi, dt, margin, max_lag_s, delta, width
                   ):  # pragma: no cover - compiled below
    """Kernel of :func:`line_sigma`."""
    ta, ha, unit = _window(tags, h, t_att, h_att, lo, hi, margin)
    return _sigma(tags, h, ta, ha, dt, unit, max_lag_s, delta, width)


def _scan_core_py(tags, h, t_att, h_att, dts, step, refine, uncertainty, subdivisions,
                  margin, max_lag_s, delta, width):  # pragma: no cover - compiled below
    """Kernel of :func:`scan_core`."""
    K = dts.size
    ta, ha, unit = _window(tags, h, t_att, h_att, dts[0], dts[K - 1], margin)
    curve = _curve(tags, unit, ta, ha, dts, step)
    k, low = _argmax_min(curve)
    status = 0
    lat = rmax = sigma = np.nan
    if k < 0 or k == 0 or k == K - 1:
        return curve, k, low, lat, rmax, sigma, status
    lat, rmax = dts[k], curve[k]
    if refine:
        lo, hi = dts[k - 1], dts[k + 1]
        if hi > lo:
            fine = _grid(lo, hi, subdivisions + 1)
            fstep = _uniform_step(fine)
            if not fstep > 0:
                return curve, k, low, lat, rmax, sigma, 1
            rf = _curve(tags, unit, ta, ha, fine, fstep)
            j, _ = _argmax_min(rf)
            if j < 0:
                return curve, k, low, lat, rmax, sigma, 1
            if 0 < j < fine.size - 1:
                lat, rv = _vertex(fine, rf, j)
                rmax = max(rv, rf[j])
            else:
                lat, rmax = fine[j], rf[j]
    if uncertainty:
        sigma = _sigma(tags, h, ta, ha, lat, unit, max_lag_s, delta, width)
        if sigma == -1.0:
            status = 1
    return curve, k, low, lat, rmax, sigma, status


_sums_any = njit(nogil=True)(_sums_any_py)
_curve = njit(nogil=True)(_curve_py)
_argmax_min = njit(cache=True, nogil=True)(_argmax_min_py)
_mean = njit(nogil=True, inline="always")(_mean_py)
_vertex = njit(nogil=True)(vertex)
_sigma = njit(nogil=True)(_sigma_py)
_window = njit(nogil=True)(_window_py)
_scan_core = njit(cache=True, nogil=True)(_scan_core_py)
_line_sigma = njit(cache=True, nogil=True)(_line_sigma_py)



def scan_core(tags: np.ndarray, h: np.ndarray, t_att: np.ndarray, h_att: np.ndarray,
              dts: np.ndarray, refine: bool, uncertainty: bool, subdivisions: int,
              margin_s: float, max_lag_s: float, delta_s: float, width_s: float):
    """One line's scan (:func:`.lines.scan_line`) in one compiled call, or None.

    *tags* (s) and detrended heights *h* (m) of the line's epochs; attitude times *t_att*
    (s, increasing) and total heave *h_att* (m, up); the candidate delays *dts* (s).
    Returns ``(curve, k, low, latency_s, r_max, uncertainty_s)``: R at every candidate,
    the index of its maximum (−1: none finite) and its minimum, then — when the maximum
    is inside the grid — the refined peak (*refine*; else the grid's) and its σ
    (*uncertainty*; else NaN), all as the Python steps compute them, to rounding.
    None when the compiled path does not apply (no numba, a grid that is not uniform,
    fewer than two epochs); the caller then takes the Python steps.
    """
    if not available() or tags.size < 2:
        return None
    step = uniform_step(dts)
    if step is None:
        return None
    out = _scan_core(np.ascontiguousarray(tags, dtype=float),
                     np.ascontiguousarray(h, dtype=float),
                     np.ascontiguousarray(t_att, dtype=float),
                     np.ascontiguousarray(h_att, dtype=float),
                     np.ascontiguousarray(dts, dtype=float), step, bool(refine),
                     bool(uncertainty), int(subdivisions), float(margin_s),
                     float(max_lag_s), float(delta_s), float(width_s))
    curve, k, low, lat, r_max, sigma, status = out
    if status:
        return None
    return curve, int(k), float(low), float(lat), float(r_max), float(sigma)


def line_sigma(tags: np.ndarray, h: np.ndarray, t_att: np.ndarray, h_att: np.ndarray,
               dts: np.ndarray, latency_s: float, margin_s: float, max_lag_s: float,
               delta_s: float, width_s: float) -> float | None:
    """The σ (s) :func:`scan_core` gives a line whose peak is at *latency_s*, for a peak
    found without it (same window, same numbers); None where :func:`scan_core` would be
    None or its curvature grid is not uniform. Arguments as :func:`scan_core`'s."""
    if not available() or tags.size < 2 or uniform_step(dts) is None:
        return None
    sigma = float(_line_sigma(np.ascontiguousarray(tags, dtype=float),
                              np.ascontiguousarray(h, dtype=float),
                              np.ascontiguousarray(t_att, dtype=float),
                              np.ascontiguousarray(h_att, dtype=float), float(dts[0]),
                              float(dts[-1]), float(latency_s), float(margin_s),
                              float(max_lag_s), float(delta_s), float(width_s)))
    return None if sigma == -1.0 else sigma
