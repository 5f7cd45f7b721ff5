"""Anti-alias low-pass and coherence weighting of the latency series (beyond Qi et al. 2010).

**Anti-alias.** The motion sensor reports heave at 50–200 Hz with its own white noise;
the GNSS heights come at 1–20 Hz. Interpolating the raw high-rate total heave at the GNSS
epochs (eq. 3 of Qi et al. 2010) keeps all of that noise, folded into the GNSS band. The
total heave is therefore low-passed first, zero-phase, with the response
``1 / (1 + (f/fc)^16)`` (the squared magnitude of an 8th-order Butterworth filter applied
forwards and backwards), ``fc`` = ANTIALIAS_FRACTION × the GNSS Nyquist frequency, on the
line's attitude window padded by PAD_S seconds of real records on each side so that the
window edges are not distorted.

**Coherence weighting.** With coloured errors (long-period heave-filter errors, correlated
RTK noise) the frequencies outside the wave band carry noise only, and the maximum-
likelihood delay estimator weights each frequency by ``γ²/((1 − γ²)·|G_hH|)`` (Hannan and
Thomson 1973; Knapp and Carter 1976), γ² the coherence and G_hH the cross-spectrum of
heights and heave. Both series are filtered, zero-phase, with the square root of that
weight, so their cross-spectrum becomes ``γ²/(1 − γ²)``, and the delay is the peak of the
correlation of the filtered series — the same scan, refinement and uncertainty as the
published method. γ² and G_hH are estimated jointly over all the day's lines (Welch, Hann
windows of WELCH_S seconds, pooled), aligned at the median delay of a first anti-aliased
pass; frequencies whose pooled coherence is not significant (COHERENCE_ALPHA) get no
weight. The Cramér–Rao bound of the delay for one line of duration T under this model is
``1 / (2T ∫ (2πf)² γ²/(1 − γ²) df)`` (:func:`crb_variance`).

Times in seconds, frequencies in Hz, heights and heave in metres (up).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache
from typing import NamedTuple

import numpy as np

from hydrosync_core.methods.latency import fastfilter

PAD_S = 30.0
"""Real records taken on each side of a window before filtering (edge effects stay there)."""

ANTIALIAS_FRACTION = 0.8
"""Anti-alias corner frequency as a fraction of the GNSS Nyquist frequency."""

WELCH_S = 64.0
"""Welch segment length for the pooled spectra (shorter if a line is shorter)."""

COHERENCE_ALPHA = 0.001
"""Significance level of the pooled coherence: a frequency whose estimate a coherence of
zero exceeds with probability ≥ this counts as noise only (weight zero). Without it the
noise-only band above the waves (0.5–8 Hz at 20 Hz GNSS) got the largest weights: 1.6x
the Cramér–Rao bound at 20 Hz, 1.2x with it (docs/benchmarks.md)."""

MIN_SEGMENTS = 6
"""Welch segments the pooled weighting needs. The weight is estimated from the very lines
it then weights: its noise is common to every line, so it biases them alike and never
shows in their scatter. Weighted estimator on simulated 5 Hz days, 40 per row (paper
noise): 3 segments 95 % coverage 0.83 and 0.95 on two draws (error/σ RMS 1.67, 1.2), 4
segments 0.875 (1.51), 6 segments 0.95 (1.15; coloured 0.975), 8 segments 0.975 (1.01).
Below 6 the anti-aliased correlation is used (the 3-segment draw: 0.97, RMS 0.95)."""

MAX_COHERENCE = 0.99
"""Upper clip of the estimated coherence (keeps the weight finite)."""


def antialias_response(f: np.ndarray, cutoff_hz: float) -> np.ndarray:
    """Zero-phase low-pass ``1 / (1 + (f/fc)^16)`` at frequencies *f* (Hz)."""
    return 1.0 / (1.0 + (np.abs(f) / cutoff_hz) ** 16)


@lru_cache(maxsize=256)
def next_fast_len(n: int) -> int:
    """Smallest 5-smooth integer (2^a·3^b·5^c) ≥ *n*: ``scipy.fft.next_fast_len(n,
    real=True)``, without importing scipy.fft (0.15 s of a command-line run). Cached: a
    day's line windows have a few lengths, asked for per line and pass."""
    n = max(int(n), 1)
    best = 1 << max(n - 1, 0).bit_length()  # the power of two ≥ n
    f5 = 1
    while f5 < best:
        f35 = f5
        while f35 < best:
            # Times the power of two that brings it to n or more.
            f = f35 << max((n - 1) // f35, 0).bit_length() if f35 < n else f35
            best = min(best, f)
            f35 *= 3
        f5 *= 5
    return best


@lru_cache(maxsize=16)
def _centred_index(n: int) -> np.ndarray:
    """``arange(n) − (n − 1)/2`` (read-only, cached: a day's windows have a few lengths)."""
    kc = np.arange(n, dtype=float) - 0.5 * (n - 1)
    kc.flags.writeable = False
    return kc


def _sum_of_squares(n: int) -> float:
    """``(kc·kc).sum()`` of :func:`_centred_index`: ``(n−1)·n·(n+1)/12``. Exactly, as the
    float sum is while every partial sum (multiples of 1/4) stays below 2^51."""
    if n < 1 << 18:
        return (n - 1) * n * (n + 1) / 12
    kc = _centred_index(n)
    return float((kc * kc).sum())


RESPONSE_CACHE_SIZE = 32
"""Responses kept per cache (one per FFT length; a day's line windows share a few)."""


@dataclass(frozen=True)
class Spectrum:
    """A series made ready for :func:`fft_filter`'s filtering: everything but the response.

    The linear trend ``intercept + slope·k_c`` (k_c the sample index centred on the
    series) is taken out, the rest mirrored on both sides to *size* samples (the series
    starts at *left*) and transformed. *bins* may hold the first bins only
    (:meth:`head`): enough for a response that is zero beyond them. A series of fewer
    than 4 samples is kept as it is (*raw*); filtering returns it unchanged.
    """

    n: int
    size: int
    left: int
    intercept: float
    slope: float
    bins: np.ndarray | None
    raw: np.ndarray | None = None

    def head(self, count: int, out: np.ndarray | None = None) -> Spectrum:
        """The same spectrum with only its first *count* bins, copied (to *out*, complex,
        at least *count* long, when given) so that the rest can be freed."""
        if self.bins is None:
            return self
        count = min(count, self.bins.size)
        if out is None:
            return replace(self, bins=self.bins[:count].copy())
        out[:count] = self.bins[:count]
        return replace(self, bins=out[:count])

    def covers(self, gains: Gains | np.ndarray) -> bool:
        """True when *gains* (:class:`Gains`, or one gain per bin of the full spectrum)
        are zero beyond *bins*."""
        if self.bins is None:
            return True
        if isinstance(gains, Gains):
            return gains.support <= self.bins.size
        return not np.any(gains[self.bins.size:])


def spectrum(x: np.ndarray) -> Spectrum:
    """:class:`Spectrum` of the regularly sampled series *x* (see :func:`fft_filter`)."""
    n = x.size
    if n < 4:
        return Spectrum(n, n, 0, 0.0, 0.0, None, x.copy())
    kc = _centred_index(n)
    # Least-squares line in closed form (kc is centred): polyfit's numbers without
    # lstsq, and no BLAS (a threaded BLAS dot wakes its threads for 10^4+ elements:
    # 10 ms per window on a busy machine).
    intercept = float(np.add.reduce(x)) / n  # x.mean()'s numbers without its Python layer
    slope = float(np.add.reduce(kc * x)) / _sum_of_squares(n)
    # Mirrored on both sides to a fast FFT length (about twice n): the wrap-around seam
    # lies half a window away from the data. numpy.fft is the pocketfft of scipy.fft (the
    # same numbers), without scipy.fft's import.
    size = next_fast_len(2 * n)
    left = (size - n) // 2
    right = size - n - left
    if left > n or right > n:  # reflections of reflections
        y = np.pad(x - (intercept + slope * kc), (left, right), mode="symmetric")
    else:  # np.pad(mode="symmetric")'s numbers without its Python overhead
        y = np.empty(size)
        fastfilter.mirror_detrended(np.ascontiguousarray(x, dtype=float), intercept, slope,
                                    left, y)
    return Spectrum(n, size, left, intercept, slope, np.fft.rfft(y))


class Gains(NamedTuple):
    """A zero-phase response at the ``rfft`` bins of one FFT length (:func:`response_gains`)."""

    values: np.ndarray
    """Gain per bin."""
    dc: float
    """Gain at 0 Hz (scales the trend put back)."""
    support: int
    """Bins up to the last non-zero gain: ``values[support:]`` are all zero."""


def _gains(values: np.ndarray, dc: float) -> Gains:
    nonzero = np.flatnonzero(values)
    return Gains(values, dc, int(nonzero[-1]) + 1 if nonzero.size else 0)


def response_gains(response, size: int, dt: float, cache: dict | None = None) -> Gains:
    """:class:`Gains` of *response* at the ``rfft`` bins of *size* samples every *dt* s.

    *cache* (a dict owned by the caller, for one *response* and *dt*) keeps them per
    *size*: the same numbers, computed once instead of once per line.
    """
    gains = cache.get(size) if cache is not None else None
    if gains is None:
        gains = _gains(response(np.fft.rfftfreq(size, dt)), float(response(np.zeros(1))[0]))
        if cache is not None and len(cache) < RESPONSE_CACHE_SIZE:
            cache[size] = gains
    return gains


def filtered(spec: Spectrum, gains: Gains | tuple[np.ndarray, float],
             crop: slice | None = None, out: np.ndarray | None = None) -> np.ndarray:
    """The series of *spec* filtered with *gains* (:func:`response_gains`, or a pair of
    the gain per bin and the gain at 0 Hz), samples *crop*.

    The same numbers as :func:`fft_filter` followed by ``[crop]``, written to *out* when
    given (its first ``len(crop)`` elements; returned). Raises ValueError when *spec*
    keeps too few bins for *gains* (:meth:`Spectrum.covers`).
    """
    if not isinstance(gains, Gains):
        gains = _gains(np.asarray(gains[0], dtype=float), float(gains[1]))
    crop = crop if crop is not None else slice(0, spec.n)
    lo, hi, _ = crop.indices(spec.n)
    if spec.bins is None:
        if out is None:
            return spec.raw[crop].copy()
        out[:hi - lo] = spec.raw[crop]
        return out[:hi - lo]
    if spec.bins.size < spec.size // 2 + 1 and not spec.covers(gains):
        raise ValueError("the response is not zero beyond the kept bins")
    # Beyond the kept bins the product is zero: irfft pads its input with zeros to
    # size // 2 + 1 bins, the same numbers as a full product with zero gains there.
    product = np.empty(spec.bins.size, dtype=complex)
    fastfilter.scaled(spec.bins, gains.values, product)
    full = np.fft.irfft(product, spec.size)
    out = np.empty(hi - lo) if out is None else out[:hi - lo]
    fastfilter.plus_trend(full, spec.left + lo, lo, spec.n, spec.intercept, spec.slope,
                          gains.dc, out)
    return out


def fft_filter(x: np.ndarray, dt: float, response, cache: dict | None = None) -> np.ndarray:
    """Apply the real, zero-phase frequency *response* (callable of f in Hz) to *x*.

    The series is sampled every *dt* seconds (regular sampling assumed). Its linear trend
    is taken out before and put back after (scaled by the response at 0 Hz), and the
    series is mirrored on both sides so that the FFT sees no jump next to the data.
    *cache*: see :func:`response_gains`. The steps are :func:`spectrum`,
    :func:`response_gains` and :func:`filtered`, which callers that filter one series
    with several responses use directly (one forward FFT for all of them).
    """
    if x.size < 4:
        return x.copy()
    spec = spectrum(x)
    return filtered(spec, response_gains(response, spec.size, dt, cache))


@dataclass(frozen=True)
class Weighting:
    """Pooled spectra of a day and the coherence weight derived from them."""

    f: np.ndarray          # Hz
    coherence: np.ndarray  # γ², clipped to [0, MAX_COHERENCE]
    gain: np.ndarray       # sqrt of the ML weight, normalised to a maximum of 1
    nyquist_hz: float

    def response(self, f: np.ndarray) -> np.ndarray:
        """Gain at frequencies *f* (zero beyond the GNSS Nyquist frequency)."""
        f = np.abs(f)
        g = np.interp(f, self.f, self.gain, right=0.0)
        return g * antialias_response(f, ANTIALIAS_FRACTION * self.nyquist_hz)


WELCH_BLOCK = 64
"""Lines whose Welch segments :func:`_pooled_spectra` transforms together: its temporary
arrays, ~7 MB at 10 Hz GNSS, add to the day's peak memory (the kept line windows are
alive then); 128 lines added 13 MB to the survey day's peak for no measurable speed."""


def _pooled_spectra(pairs: list[tuple[np.ndarray, np.ndarray]], fs: float, nper: int):
    """(f, Σ n·P_xx, Σ n·P_yy, Σ n·P_xy) over the lines' (x, y) *pairs* sampled at *fs*
    Hz, n a line's samples, summed in line order. P are a line's spectra as
    ``scipy.signal.welch``/``csd`` give them with ``nperseg=nper``, ``detrend="linear"``
    and the other defaults (periodic Hann window, half overlap, density scaling,
    one-sided, mean of the segments). Every line needs at least *nper* samples.

    The segments of WELCH_BLOCK lines are detrended and transformed as one array: the
    same numbers per segment as line by line, without ~20 numpy calls per line in the
    single thread that waits for this between the day's two parallel passes.
    """
    step = nper - nper // 2
    win = 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(nper) / nper)
    kc = np.arange(nper, dtype=float) - 0.5 * (nper - 1)
    kk = float(kc @ kc)
    scale = 1.0 / (fs * float(win @ win))
    last = -1 if nper % 2 == 0 else None

    def spectra(seg):
        seg = seg - seg.mean(axis=1, keepdims=True)
        seg -= np.outer(seg @ kc / kk, kc)  # linear detrend per segment
        return np.fft.rfft(seg * win, axis=1)

    s_xx = s_yy = 0.0
    s_xy = 0.0j
    for b in range(0, len(pairs), WELCH_BLOCK):
        block = pairs[b:b + WELCH_BLOCK]
        sizes = [x.size for x, _ in block]
        counts = np.array([(n - nper // 2) // step for n in sizes])
        firsts = np.cumsum(counts) - counts
        # Segment k of a line starts at its offset in the concatenated series + k·step.
        offsets = np.cumsum([0, *sizes[:-1]])
        starts = (np.repeat(offsets, counts)
                  + (np.arange(int(counts.sum())) - np.repeat(firsts, counts)) * step)
        idx = starts[:, None] + np.arange(nper)[None, :]
        X = spectra(np.concatenate([x for x, _ in block])[idx])
        Y = spectra(np.concatenate([y for _, y in block])[idx])
        per_line = []
        for values in (np.abs(X) ** 2, np.abs(Y) ** 2, np.conj(X) * Y):
            p = np.add.reduceat(values, firsts, axis=0) / counts[:, None] * scale
            p[:, 1:last] *= 2.0
            per_line.append(p)
        del X, Y, idx
        for i, n in enumerate(sizes):
            s_xx = s_xx + n * per_line[0][i]
            s_yy = s_yy + n * per_line[1][i]
            s_xy = s_xy + n * per_line[2][i]
    return np.fft.rfftfreq(nper, 1.0 / fs), s_xx, s_yy, s_xy


def pooled_weighting(pairs: list[tuple[np.ndarray, np.ndarray]], dt: float) -> Weighting | None:
    """Coherence weight from (heights, heave at the same epochs) pairs of the day's lines.

    Returns None with fewer than 16 epochs in the shortest line, or fewer than
    MIN_SEGMENTS Welch segments over the lines.
    """
    pairs = [(h, H) for h, H in pairs if h.size >= 16]
    if not pairs:
        return None
    nper = int(min(round(WELCH_S / dt), min(h.size for h, _ in pairs)))
    # Unbiased for K independent segments (the raw estimate is ~1/K even without signal).
    k = sum(max(1, 2 * h.size // nper - 1) for h, _ in pairs)
    if k < MIN_SEGMENTS:
        return None
    f, s_hh, s_HH, s_hH = _pooled_spectra(pairs, 1.0 / dt, nper)
    total = sum(h.size for h, _ in pairs)
    with np.errstate(invalid="ignore", divide="ignore"):
        coh = np.abs(s_hH) ** 2 / (s_hh * s_HH)
    raw = np.nan_to_num(coh, nan=0.0)
    coh = (k * raw - 1.0) / (k - 1.0) if k > 1 else coh
    if k > 1 and COHERENCE_ALPHA > 0:
        # Frequencies whose coherence is not significant carry noise only: their spurious
        # γ² over a tiny |G_hH| would get the largest weights of all (and the most delay
        # information, ∝ f²). Null distribution of K-segment coherence: P(γ̂² > x) =
        # (1 − x)^(K − 1).
        coh[raw < 1.0 - COHERENCE_ALPHA ** (1.0 / (k - 1.0))] = 0.0
    coh = np.clip(coh, 0.0, MAX_COHERENCE)
    coh[0] = 0.0  # the mean / trend carries no delay information
    with np.errstate(invalid="ignore", divide="ignore"):
        weight = coh / ((1.0 - coh) * (np.abs(s_hH) / total))
    weight = np.nan_to_num(weight, nan=0.0, posinf=0.0)
    gain = np.sqrt(weight)
    if not gain.max() > 0:
        return None
    return Weighting(f, coh, gain / gain.max(), 0.5 / dt)


def crb_variance(f: np.ndarray, coherence: np.ndarray, duration_s: float) -> float:
    """Cramér–Rao bound (s²) of the delay from one record of *duration_s* seconds.

    ``1 / (2T ∫ (2πf)² γ²/(1 − γ²) df)`` (Knapp and Carter 1976) for jointly Gaussian
    stationary heights and heave with coherence γ²(f) (one-sided frequencies, Hz).
    """
    coherence = np.clip(coherence, 0.0, 1.0 - 1e-12)
    integrand = (2 * np.pi * f) ** 2 * coherence / (1.0 - coherence)
    info = 2.0 * duration_s * float(np.trapezoid(integrand, f))
    return 1.0 / info if info > 0 else float("inf")
