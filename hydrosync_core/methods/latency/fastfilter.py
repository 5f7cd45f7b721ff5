"""Compiled element-wise steps of :mod:`.prefilter`'s FFT filtering (numba).

A survey day filters ~1500 windows of 10⁴–10⁵ samples. Around each FFT, numpy spent
about as long again on element-wise steps (the trend taken out and the mirrored copy, the
spectrum times the gains with the gains cast to complex, the crop and the trend put
back: ~0.7 ms per attitude window), a dozen calls each holding the interpreter lock that
the two scan threads share. Here each step is one loop that releases it.

Every loop performs the same floating-point operations in the same order as the numpy
expressions it replaces, so the results are the same to the last bit (tests compare
them); the sums (mean, slope) stay with numpy, whose pairwise summation they would
otherwise change at the rounding level.
"""

from __future__ import annotations

from numba import njit


def _mirror_detrended_py(x, intercept, slope, left, y):  # pragma: no cover - compiled
    """``y[left:left+n] = x − (intercept + slope·kc)``, kc the index centred on the
    series, and the rest of *y* its mirror images (``np.pad(mode="symmetric")``; the
    caller ensures that neither side is longer than the series)."""
    n = x.size
    c = 0.5 * (n - 1)
    for i in range(n):
        y[left + i] = x[i] - (intercept + slope * (float(i) - c))
    for j in range(left):
        y[j] = y[2 * left - 1 - j]
    end = left + n
    for j in range(y.size - end):
        y[end + j] = y[end - 1 - j]


def _scaled_py(bins, gains, out):  # pragma: no cover - compiled below
    """``out[:bins.size] = bins · gains[:bins.size]`` (complex times real, as numpy's
    ``bins * gains``: the gain cast to complex)."""
    for k in range(bins.size):
        out[k] = bins[k] * complex(gains[k], 0.0)


def _plus_trend_py(series, start, lo, n, intercept, slope, g0, out):  # pragma: no cover
    """``out[j] = series[start + j] + (intercept + slope·kc)·g0``, kc = lo + j centred on
    a series of *n* samples, for every j of *out*."""
    c = 0.5 * (n - 1)
    for j in range(out.size):
        out[j] = series[start + j] + (intercept + slope * (float(lo + j) - c)) * g0


mirror_detrended = njit(cache=True, nogil=True)(_mirror_detrended_py)
scaled = njit(cache=True, nogil=True)(_scaled_py)
plus_trend = njit(cache=True, nogil=True)(_plus_trend_py)

