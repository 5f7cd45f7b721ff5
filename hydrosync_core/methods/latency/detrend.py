"""Tide / trend removal from the GNSS heights of one line (seed eq. 1)."""

from __future__ import annotations

import numpy as np
from numba import njit
from numpy.polynomial import polynomial as npoly


def detrend(time: np.ndarray, height: np.ndarray, degree: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Subtract a least-squares polynomial in time from *height*.

    Parameters
    ----------
    time : ndarray (n,)
        Epoch times, s.
    height : ndarray (n,)
        Antenna ellipsoidal heights, m.
    degree : int
        Polynomial degree (seed: 1, tide is linear over a 2–3 min line).

    Returns
    -------
    residual : ndarray (n,)
        Detrended heights h_i, m.
    coefficients : ndarray (degree+1,)
        Polynomial coefficients in powers of ``time - time.mean()`` (m, m/s, ...).
    """
    if degree < 0:
        raise ValueError("detrend degree must be >= 0")
    if (degree <= 1 and time.size > degree
            and time.dtype == np.float64 and np.asarray(height).dtype == np.float64):
        residual = np.empty(time.size)
        coef = _linear_fit(np.ascontiguousarray(time), np.ascontiguousarray(height), degree,
                           residual)
        return residual, np.array(coef[:degree + 1])
    # Centre (and scale) time so the Vandermonde matrix is well conditioned.
    tc = time - time.mean()
    if degree <= 1 and time.size > degree:
        return _detrend_linear(tc, np.asarray(height, dtype=float), degree)
    scale = max(float(np.abs(tc).max()), 1e-9)
    # Seed eq. 1: h_i = h_M(CT1_i) − trend(CT1_i).
    coef = npoly.polyfit(tc / scale, height, degree)
    residual = height - npoly.polyval(tc / scale, coef)
    return residual, coef / scale ** np.arange(degree + 1)


def _detrend_linear(tc: np.ndarray, height: np.ndarray, degree: int
                    ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`detrend` for degree 0 or 1 in closed form (*tc*: centred times, s).

    The normal equations of a line in centred time are diagonal up to the times' mean
    left by rounding, so two sums give the fit: polyfit's numbers to rounding (1e-15 m),
    without its Vandermonde matrix and SVD — half the per-line cost of a survey day's
    latency scan, all of it holding the interpreter lock the scan threads share.
    """
    # Regress on tc − mean(tc): exactly centred in floating point as far as it matters.
    mean_h = float(height.mean())
    if degree == 0:
        return height - mean_h, np.array([mean_h])
    u = tc - tc.mean()
    uu = float(np.multiply(u, u).sum())
    slope = float(np.multiply(u, height).sum()) / uu if uu > 0 else 0.0
    intercept = mean_h - slope * float(tc.mean())  # the line at tc = 0
    residual = height - mean_h - slope * u
    return residual, np.array([intercept, slope])


# Compiled _detrend_linear (one call per line instead of a dozen numpy calls, each holding
# the interpreter lock that the scan threads share). Its sums are numpy's pairwise
# summation (numpy/_core/src/umath/loops_utils.h.src: 8 accumulators up to 128 values,
# halves at multiples of 8 above), so the numbers are numpy's to the last bit; a test
# holds it to that.


def _leaf_py(a, lo, n):  # pragma: no cover - compiled below
    """numpy's pairwise sum of ``a[lo:lo+n]`` for n <= 128 (no further halving)."""
    if n < 8:
        res = 0.0
        for i in range(n):
            res += a[lo + i]
        return res
    r0, r1, r2, r3 = a[lo], a[lo + 1], a[lo + 2], a[lo + 3]
    r4, r5, r6, r7 = a[lo + 4], a[lo + 5], a[lo + 6], a[lo + 7]
    i = 8
    whole = n - n % 8
    while i < whole:
        r0 += a[lo + i]
        r1 += a[lo + i + 1]
        r2 += a[lo + i + 2]
        r3 += a[lo + i + 3]
        r4 += a[lo + i + 4]
        r5 += a[lo + i + 5]
        r6 += a[lo + i + 6]
        r7 += a[lo + i + 7]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        res += a[lo + i]
        i += 1
    return res


def _pairwise_py(a, lo, n):  # pragma: no cover - compiled below
    """numpy's pairwise sum of ``a[lo:lo+n]``: above 128 values the sum of the two halves
    (split at a multiple of 8), each summed the same way. The recursion runs on an
    explicit stack: numba's cache does not reload recursive functions safely."""
    if n <= 128:
        return _leaf(a, lo, n)
    los = np.empty(64, dtype=np.int64)
    ns = np.empty(64, dtype=np.int64)
    stages = np.empty(64, dtype=np.int64)
    lefts = np.empty(64)
    top = 0
    los[0], ns[0], stages[0] = lo, n, 0
    ret = 0.0
    while top >= 0:
        m = ns[top]
        if m <= 128:
            ret = _leaf(a, los[top], m)
            top -= 1
            continue
        half = m // 2
        half -= half % 8
        if stages[top] == 0:  # sum the first half
            stages[top] = 1
            los[top + 1], ns[top + 1], stages[top + 1] = los[top], half, 0
            top += 1
        elif stages[top] == 1:  # the first half's sum is in ret: sum the second half
            lefts[top] = ret
            stages[top] = 2
            los[top + 1], ns[top + 1], stages[top + 1] = los[top] + half, m - half, 0
            top += 1
        else:  # both halves done
            ret = lefts[top] + ret
            top -= 1
    return ret


def _sum_py(a):  # pragma: no cover - compiled below
    """``numpy.add.reduce(a)`` of a contiguous float64 vector, the same number."""
    return 0.0 + _pairwise(a, 0, a.size)


def _linear_fit_py(time, height, degree, residual):  # pragma: no cover - compiled below
    """:func:`_detrend_linear` of ``time − mean(time)``: residual into *residual*;
    returns (intercept, slope) (slope 0 for degree 0)."""
    n = time.size
    t_mean = _sum(time) / n
    tc = np.empty(n)
    for i in range(n):
        tc[i] = time[i] - t_mean
    mean_h = _sum(height) / n
    if degree == 0:
        for i in range(n):
            residual[i] = height[i] - mean_h
        return mean_h, 0.0
    tc_mean = _sum(tc) / n
    u = np.empty(n)
    uu_terms = np.empty(n)
    uh_terms = np.empty(n)
    for i in range(n):
        u[i] = tc[i] - tc_mean
        uu_terms[i] = u[i] * u[i]
        uh_terms[i] = u[i] * height[i]
    uu = _sum(uu_terms)
    slope = _sum(uh_terms) / uu if uu > 0 else 0.0
    for i in range(n):
        residual[i] = (height[i] - mean_h) - slope * u[i]
    return mean_h - slope * tc_mean, slope


_leaf = njit(cache=True, nogil=True)(_leaf_py)
_pairwise = njit(cache=True, nogil=True)(_pairwise_py)
_sum = njit(cache=True, nogil=True)(_sum_py)
_linear_fit = njit(cache=True, nogil=True)(_linear_fit_py)

