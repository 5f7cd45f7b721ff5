"""A motion sensor's heave filter, declared by the user and put into the delay model.

A motion sensor integrates vertical acceleration twice and high-passes the result so that it
does not drift: its heave is ``HP(heave)``, with a causal Butterworth high-pass of order 2–3
and a cut-off period of 10–30 s. At the wave periods (4–10 s) that filter *leads* by
hundreds of milliseconds, and by a different time at each period, so the GNSS heights
(which carry the true heave) and the reported heave are no longer one pure delay apart.
Vendors' "phase-compensated" heave (delayed output, zero-phase smoothing) removes that lead.

With a declared causal filter, HydroSync applies the same filter to what the sensor's
filter did not see: the GNSS heights (at their own rate) and the rotation-induced heave of
the lever arm (at the attitude rate; seed eq. 2). Total heave and heights then carry the
same phase and differ again by the delay alone. Times in s, heights and heave in m (up),
angles in degrees.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from scipy.fft import next_fast_len
from scipy.signal import butter, freqs

from hydrosync_core.methods.latency.heave import total_heave_deg

GAP_FACTOR = 3.0
"""An interval above this many median intervals splits a record: the filter restarts."""


def highpass_sos(order: int, cutoff_period_s: float, rate_hz: float) -> np.ndarray:
    """Second-order sections of the digital Butterworth high-pass (bilinear, pre-warped)
    with cut-off period *cutoff_period_s* (s) at *rate_hz* (Hz): a sensor's filter at its
    internal rate (the simulator's)."""
    return butter(int(order), 1.0 / float(cutoff_period_s), btype="highpass", fs=float(rate_hz),
                  output="sos")


def highpass_response(freq_hz: np.ndarray, order: int, cutoff_period_s: float) -> np.ndarray:
    """Complex response of the analogue Butterworth high-pass at *freq_hz* (Hz).

    The sensor filters at its internal rate (100 Hz and more), where its digital filter is
    the analogue one; a digital copy at a 1 Hz GNSS rate would be warped by the bilinear
    transform (about 12 % in frequency at a 6 s wave) and leave tens of ms of bias.
    """
    b, a = butter(int(order), 2.0 * np.pi / float(cutoff_period_s), btype="highpass",
                  analog=True)
    _, h = freqs(b, a, worN=2.0 * np.pi * np.asarray(freq_hz, dtype=float))
    return h


def causal_highpass(times: np.ndarray, values: np.ndarray, order: int,
                    cutoff_period_s: float) -> np.ndarray:
    """*values* (sampled at increasing *times*, s) through the analogue causal high-pass,
    applied by FFT to each stretch without a gap: its linear trend removed (the filter
    passes none of it), zero-padded to twice its length against wrap-around."""
    times = np.asarray(times, dtype=float)
    values = np.asarray(values, dtype=float)
    out = np.zeros_like(values)
    if values.size < 4:
        return out
    steps = np.diff(times)
    interval = float(np.median(steps))
    cuts = np.r_[0, np.flatnonzero(steps > GAP_FACTOR * interval) + 1, values.size]
    for a, b in zip(cuts[:-1], cuts[1:], strict=True):
        if b - a < 4:
            continue
        x = values[a:b]
        k = np.arange(x.size, dtype=float)
        slope, intercept = np.polyfit(k, x, 1)
        size = next_fast_len(2 * x.size)
        spectrum = np.fft.rfft(x - (intercept + slope * k), size)
        gains = highpass_response(np.fft.rfftfreq(size, interval), order, cutoff_period_s)
        out[a:b] = np.fft.irfft(spectrum * gains, size)[:x.size]
    return out


def with_declared_filter(gnss: Mapping, attitude: Mapping, lever_arm, order: int,
                         cutoff_period_s: float) -> tuple[dict, dict]:
    """(gnss, attitude) with the declared causal heave filter put into the model.

    GNSS ``height`` becomes ``HP(height)``; the attitude's ``heave`` becomes
    ``heave + HP(H_R) − H_R`` so that the total heave (eq. 2) of the returned attitude is
    ``heave + HP(H_R)``: the sensor's filtered heave plus the filtered rotation-induced
    heave, the same filter as the heights'. Other columns are shared, not copied.
    """
    gnss_out = dict(gnss)
    gnss_out["height"] = causal_highpass(gnss["time"], gnss["height"], order, cutoff_period_s)
    t = np.asarray(attitude["time"], dtype=float)
    zeros = np.zeros(t.size)
    induced = total_heave_deg(zeros, np.asarray(attitude["roll"], dtype=float),
                              np.asarray(attitude["pitch"], dtype=float), lever_arm)
    att_out = dict(attitude)
    att_out["heave"] = (np.asarray(attitude["heave"], dtype=float)
                        + causal_highpass(t, induced, order, cutoff_period_s) - induced)
    return gnss_out, att_out
