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
    scale = max(float(np.abs(tc).max()), 1e-9)
    # Seed eq. 1: h_i = h_M(CT1_i) − trend(CT1_i).
    coef = npoly.polyfit(tc / scale, height, degree)
    residual = height - npoly.polyval(tc / scale, coef)
    return residual, coef / scale ** np.arange(degree + 1)
