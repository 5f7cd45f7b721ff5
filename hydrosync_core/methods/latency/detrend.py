"""Tide / trend removal from the GNSS heights of one line (seed eq. 1)."""

from __future__ import annotations

import numpy as np
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
