"""A motion sensor's heave filter, declared by the user and put into the delay model.

A motion sensor integrates vertical acceleration twice and high-passes the result so that it
does not drift: its heave is ``HP(heave)``, with a causal Butterworth high-pass of order 2–3
and a cut-off period of 10–30 s. At the wave periods (4–10 s) that filter *leads* by
hundreds of milliseconds, and by a different time at each period, so the GNSS heights
(which carry the true heave) and the reported heave are no longer one pure delay apart.
Vendors' "phase-compensated" heave (delayed output, zero-phase smoothing) removes that lead.

With a declared causal filter, HydroSync removes the filter's phase from the reported
heave and applies its gain alone to what the sensor's filter did not see: the GNSS heights
(at their own rate) and the rotation-induced heave of the lever arm (at the attitude rate;
seed eq. 2). Total heave and heights then carry the same (zero) phase and differ again by
the delay alone (:func:`with_declared_filter`). Times in s, heights and heave in m (up),
angles in degrees.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from scipy.fft import next_fast_len
from scipy.signal import butter, freqs

from hydrosync_core.methods.latency.heave import total_heave_deg

CHUNK = 100_000
"""Records per call of the serial total-heave kernel (:func:`.heave.total_heave_deg`)."""

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


def _per_stretch(times: np.ndarray, values: np.ndarray, gains_of,
                 keep_trend: bool = False) -> np.ndarray:
    """*values* (sampled at increasing *times*, s) times the response ``gains_of(f)`` (f
    in Hz), applied by FFT to each stretch without a gap: its linear trend removed first
    (added back with *keep_trend*), zero-padded to twice its length against
    wrap-around."""
    times = np.asarray(times, dtype=float)
    values = np.asarray(values, dtype=float)
    out = values.copy() if keep_trend else np.zeros_like(values)
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
        trend = intercept + slope * k
        spectrum = np.fft.rfft(x - trend, size)
        out[a:b] = np.fft.irfft(spectrum * gains_of(np.fft.rfftfreq(size, interval)),
                                size)[:x.size]
        if keep_trend:
            out[a:b] += trend
    return out


def causal_highpass(times: np.ndarray, values: np.ndarray, order: int,
                    cutoff_period_s: float) -> np.ndarray:
    """*values* (sampled at increasing *times*, s) through the analogue causal high-pass,
    per stretch without a gap (the filter passes no linear trend)."""
    return _per_stretch(times, values,
                        lambda f: highpass_response(f, order, cutoff_period_s))


def without_phase(times: np.ndarray, values: np.ndarray, order: int,
                  cutoff_period_s: float) -> np.ndarray:
    """*values* (a high-passed heave at increasing *times*, s) with the analogue
    high-pass's phase removed: the all-pass ``conj(H)/|H|`` (zero-phase, non-causal), per
    stretch without a gap; the linear trend is kept."""
    def unit_conjugate(f):
        h = highpass_response(f, order, cutoff_period_s)
        mag = np.abs(h)
        return np.where(mag > 1e-12, np.conj(h) / np.where(mag > 1e-12, mag, 1.0), 1.0)

    return _per_stretch(times, values, unit_conjugate, keep_trend=True)


def _induced_heave(attitude: Mapping, lever_arm) -> np.ndarray:
    """Rotation-induced heave H_R (m, seed eq. 2) at the attitude records."""
    roll = np.asarray(attitude["roll"], dtype=float)
    pitch = np.asarray(attitude["pitch"], dtype=float)
    induced = np.empty(roll.size)
    zeros = np.zeros(min(roll.size, CHUNK))
    # In chunks: the serial kernel, callable from any thread (the parallel one is not, and
    # warns on machines whose TBB is too old).
    for lo in range(0, roll.size, CHUNK):
        hi = min(lo + CHUNK, roll.size)
        induced[lo:hi] = total_heave_deg(zeros[:hi - lo], roll[lo:hi], pitch[lo:hi], lever_arm)
    return induced


def with_declared_filter(gnss: Mapping, attitude: Mapping, lever_arm, order: int,
                         cutoff_period_s: float) -> tuple[dict, dict]:
    """(gnss, attitude) with the declared causal heave filter put into the model.

    The filter's phase is removed from the reported heave, at the attitude rate; its gain
    |H| (zero phase) is applied to what the sensor's filter did not see, so that both sides
    keep the same long-period content: GNSS ``height`` becomes ``|H|(height)`` and the
    attitude's ``heave`` becomes ``dephased(heave) + |H|(H_R) − H_R``, whose total heave
    (eq. 2) is ``|H|(heave) + |H|(H_R)``. Other columns are shared, not copied.

    Why not the filter itself on the heights (HydroSync until 2026-12-04): heights at
    1 Hz are aliased samples of a motion with energy above 0.5 Hz, and a component at
    0.55 Hz, which the sensor's filter led by its phase at 0.55 Hz, reads at 0.45 Hz with
    that phase reversed; filtering the samples applies the phase of 0.45 Hz instead. On a
    simulated rough, noiseless 1 Hz day (filter order 2, cut-off 14 s) that left the
    shortest periods 20 ms late and Δt +3…+6 ms off (σ 0.3 ms); with the phase removed
    from the 20 Hz heave, −0.3…+0.1 ms. Zero-phase gains delay nothing, aliased or not.
    When the attitude is no faster than the heights the heave is aliased the same way
    and neither form is exact.
    """
    def gain(f):
        return np.abs(highpass_response(f, order, cutoff_period_s))

    gnss_out = dict(gnss)
    gnss_out["height"] = _per_stretch(gnss["time"], gnss["height"], gain)
    t = np.asarray(attitude["time"], dtype=float)
    induced = _induced_heave(attitude, lever_arm)
    att_out = dict(attitude)
    att_out["heave"] = (without_phase(t, attitude["heave"], order, cutoff_period_s)
                        + _per_stretch(t, induced, gain) - induced)
    return gnss_out, att_out
