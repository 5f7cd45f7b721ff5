"""Precision of the agreement between detrended heights and total heave (seed eqs. 5–6)."""

from __future__ import annotations

import numpy as np


def sigma0(h: np.ndarray, total_heave: np.ndarray) -> float:
    """Standard error σ0 (m) of the differences of the centred series.

    Parameters
    ----------
    h : ndarray (n,)
        Detrended GNSS heights of a line, m.
    total_heave : ndarray (n,)
        Total heave at the same (corrected) epochs, m.
    """
    n = h.size
    if n < 3:
        return float("nan")
    # Seed eq. 5: v_i = (h_i − h̄) − (H_Ti − H̄_T).
    v = (h - h.mean()) - (total_heave - total_heave.mean())
    # Seed eq. 6: σ0 = sqrt([vv] / (n − 2)).
    return float(np.sqrt(np.dot(v, v) / (n - 2)))
