"""Correlation of detrended GNSS heights with total heave over candidate delays (seed eqs. 3–4).

All candidate delays of a line are evaluated at once: the corrected times
``T = CT1 − Δt`` (seed eq. 3) of every (candidate, epoch) pair form one array that is
interpolated in a single :func:`numpy.interp` call (first-order Lagrange, as the seed),
in chunks that bound the memory.
"""

from __future__ import annotations

import numpy as np

from hydrosync_core.methods.latency import fastscan

CHUNK_ELEMENTS = 2_000_000
"""Candidates x epochs interpolated per chunk (16 MB of float64)."""

MAX_LAG_S = 15.0
"""Newey–West lag window of :func:`peak_uncertainty` (s)."""
DELTA_S = 0.05
"""Half-step of its central difference of the heave (s)."""
WIDTH_S = 0.1
"""Half-width of its curvature fit (s)."""
SUBDIVISIONS = 40
"""Points per two grid steps of :func:`refine_peak`'s fine grid."""


def heave_at(tags: np.ndarray, dts: np.ndarray, t_att: np.ndarray, h_att: np.ndarray) -> np.ndarray:
    """Total heave (m) at corrected times ``tags − dt`` for every dt: shape (len(dts), len(tags)).

    Seed eq. 3: T_i = CT1_i − Δt, attitude data linearly interpolated at T_i.
    """
    corrected = tags[None, :] - np.asarray(dts, dtype=float)[:, None]
    return np.interp(corrected.ravel(), t_att, h_att).reshape(corrected.shape)


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    """Σ a·b without BLAS (a threaded BLAS wakes its threads for long vectors: slow when
    called per line from the scan threads on a busy machine)."""
    return float(np.multiply(a, b).sum())


def unit_centred(h: np.ndarray) -> np.ndarray:
    """*h* minus its mean, scaled to unit norm (the heights' side of eq. 4)."""
    hc = h - h.mean()
    return hc / max(float(np.linalg.norm(hc)), 1e-300)


def correlation_curve(
    tags: np.ndarray, h: np.ndarray, t_att: np.ndarray, h_att: np.ndarray, dts: np.ndarray,
    unit: np.ndarray | None = None,
) -> np.ndarray:
    """Pearson correlation R(Δt) of *h* with total heave at ``tags − Δt`` (seed eq. 4).

    Parameters
    ----------
    tags : ndarray (n,)
        GNSS time tags of the line, s.
    h : ndarray (n,)
        Detrended GNSS heights, m.
    t_att, h_att : ndarray (m,)
        Attitude times (s, increasing) and total heave there (m, up).
    dts : ndarray (k,)
        Candidate delays Δt, s.
    unit : ndarray (n,), optional
        ``unit_centred(h)``, when the caller has it (a line's scans share it).

    Returns
    -------
    ndarray (k,)
        R for every candidate (NaN where the heave is constant).

    On a uniform grid the sums are exact closed forms over the attitude segments
    (:mod:`.fastscan`); the result equals :func:`correlation_curve_direct` to rounding.
    """
    dts = np.asarray(dts, dtype=float)
    step = fastscan.uniform_step(dts) if fastscan.available() else None
    if step is None or tags.size < 2:
        return correlation_curve_direct(tags, h, t_att, h_att, dts)
    hn = unit_centred(h) if unit is None else unit
    F, S1, S2 = fastscan.correlation_sums(tags, hn, t_att, h_att, dts, step)
    # Seed eq. 4 from the sums: Σ hn·(H − H̄) / sqrt(Σ (H − H̄)²).
    return fastscan.pearson(F, S1, S2, tags.size, hn.sum() / tags.size)


def correlation_curve_direct(
    tags: np.ndarray, h: np.ndarray, t_att: np.ndarray, h_att: np.ndarray, dts: np.ndarray
) -> np.ndarray:
    """R(Δt) by interpolating every (candidate, epoch) pair: the straightforward evaluation.

    The reference for :func:`correlation_curve` (same arguments and result); used when the
    compiled kernel is not available or the grid is not uniform.
    """
    hn = unit_centred(h)
    out = np.empty(len(dts))
    per = max(1, CHUNK_ELEMENTS // max(1, tags.size))
    for lo in range(0, len(dts), per):
        H = heave_at(tags, dts[lo:lo + per], t_att, h_att)
        H -= H.mean(axis=1, keepdims=True)
        norm = np.linalg.norm(H, axis=1)
        # Seed eq. 4: R = Σ(h−h̄)(H−H̄) / sqrt(Σ(h−h̄)² Σ(H−H̄)²).
        with np.errstate(invalid="ignore", divide="ignore"):
            out[lo:lo + per] = (H @ hn) / norm
    return out


def refine_peak(
    tags: np.ndarray, h: np.ndarray, t_att: np.ndarray, h_att: np.ndarray,
    dts: np.ndarray, r: np.ndarray, k: int, subdivisions: int = SUBDIVISIONS,
    unit: np.ndarray | None = None,
) -> tuple[float, float]:
    """Sub-step maximum of R around grid index *k* (bounded to one step either side).

    R is evaluated exactly on a fine grid (*subdivisions* points per two steps, one
    vectorised call), then a parabola through the best fine point and its neighbours
    gives the vertex. Returns ``(dt_peak, r_peak)``; staying within one step of the grid
    maximum keeps the search on the same lobe. *unit*: see :func:`correlation_curve`.
    """
    lo = dts[max(k - 1, 0)]
    hi = dts[min(k + 1, len(dts) - 1)]
    if hi <= lo:
        return float(dts[k]), float(r[k])
    fine = fastscan.grid(lo, hi, subdivisions + 1)
    rf = correlation_curve(tags, h, t_att, h_att, fine, unit)
    j = int(np.nanargmax(rf))
    if 0 < j < fine.size - 1:
        dt, rmax = fastscan.vertex(fine, rf, j)
        return float(dt), max(float(rmax), float(rf[j]))
    return float(fine[j]), float(rf[j])


def peak_uncertainty(
    tags: np.ndarray, h: np.ndarray, t_att: np.ndarray, h_att: np.ndarray, dt: float,
    max_lag_s: float = MAX_LAG_S, delta: float = DELTA_S, width: float = WIDTH_S,
    unit: np.ndarray | None = None,
) -> float:
    """Standard uncertainty (s) of a line's peak delay from the linearised model.

    The peak of R is the least-squares delay of ``h = a + b·H_T(T − Δt) + r``.
    Linearised in Δt: ``var(Δt) = JᵀΩJ / K²`` with ``J = b·∂H_T/∂Δt`` (a central
    difference over ±*delta*, made orthogonal to the fitted mean and scale), Ω the
    residual covariance — a Newey–West (Bartlett) sum of the autocovariance of
    ``u = r·J`` up to *max_lag_s*, by FFT, because multipath and heave-sensor errors are
    time-correlated — and K the curvature of the least-squares objective,
    ``K = −Σ(h−h̄)²·R·R''`` with R'' from a parabola fitted to R over ±*width*.

    *delta* and *width* are wide on purpose: the heave-sensor error is rough at short
    time scales, and a sample-scale derivative would overstate the information (the
    uncertainty came out 1.5–2x too small on simulated data with heave errors).
    *unit*: see :func:`correlation_curve`.
    """
    n = tags.size
    if n < 5:
        return float("nan")
    span = float(tags[-1] - tags[0]) / max(n - 1, 1)
    H = heave_at(tags, np.array([dt - delta, dt, dt + delta]), t_att, h_att)
    # Least squares h = a + b·H (closed form on centred series; no lstsq per line).
    Hc = H[1] - H[1].mean()
    hc = h - h.mean()
    hh = _dot(Hc, Hc)
    if not hh > 0:
        return float("nan")
    b = _dot(Hc, hc) / hh
    resid = hc - b * Hc
    g = b * (H[2] - H[0]) / (2 * delta)
    g = g - g.mean()
    g = g - (_dot(Hc, g) / hh) * Hc
    # Curvature of SSR(Δt)/2 = Σ(h−h̄)²(1 − R²)/2 at the peak: −Σ(h−h̄)²·R·R''. R'' from
    # the least-squares parabola over the symmetric grid (x and x² are orthogonal there).
    grid = fastscan.grid(dt - width, dt + width, 21)
    r = correlation_curve(tags, h, t_att, h_att, grid, unit)
    x2 = (grid - dt) ** 2
    x2 -= x2.mean()
    c2 = _dot(x2, r) / _dot(x2, x2)
    jj = float(-_dot(hc, hc) * r[10] * 2 * c2)
    if not jj > 0:
        return float("nan")
    u = resid * g
    lags = int(min(n // 3, max(1, round(max_lag_s / max(span, 1e-9)))))
    nfft = 1 << int(np.ceil(np.log2(2 * n)))
    spec = np.fft.rfft(u, nfft)
    acov = np.fft.irfft(spec * np.conj(spec), nfft)[: lags + 1]
    weights = 1.0 - np.arange(lags + 1) / (lags + 1)
    weights[1:] *= 2.0
    meat = float(weights @ acov) * n / max(n - 3, 1)
    return float(np.sqrt(max(meat, 0.0)) / jj)
