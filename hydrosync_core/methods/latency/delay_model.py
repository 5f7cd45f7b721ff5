"""Does one pure delay relate the heights and the heave? A check run with every estimate.

Qi et al. (2010) model the GNSS heights as the total heave shifted by one delay Δt. On real
motion sensors that fails when the heave has passed a high-pass heave filter (its phase
lead grows towards long periods) or when the heights come from an INS-blended solution: the
"delay" then depends on the frequency, and estimators that weight the frequencies
differently (qi2010, weighted) disagree by more than their σ.

The check: with the heave aligned at the estimate Δt, the cross-spectrum of heights and
heave, pooled over the used lines (Welch segments of SEGMENT_S), leaves a residual phase
φ(f). In each of BANDS frequency bands of the coherent range, the slope of φ through the
origin gives the band's delay ``Δt + τ_b`` with σ from the coherence (Bendat & Piersol:
var φ = (1 − γ²)/(2 n γ²)). One pure delay means the bands agree: χ² of the band delays
about their weighted mean, flagged at p < P_FLAG. Times in s, frequencies in Hz.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np
from scipy.signal import csd, welch
from scipy.stats import chi2

SEGMENT_S = 64.0
"""Length of the Welch segments (s): resolves the wave band (periods 3–20 s) in ~12 bins."""

BANDS = 3
"""Frequency bands compared (long, middle and short periods of the coherent range)."""

MIN_COHERENCE = 0.5
"""Bins with a pooled squared coherence below this carry no usable phase."""

MIN_BINS = 2
"""Coherent bins a band needs."""

P_FLAG = 0.01
"""χ² p-value below which the bands are said to disagree."""

NEIGHBOUR_FACTOR = np.sqrt(2.0)
"""σ inflation: neighbouring bins of Hann-windowed, half-overlapping segments share about
half their information, so the bins are not independent."""


@dataclasses.dataclass(frozen=True)
class BandDelay:
    """Delay (s) of one frequency band [low_hz, high_hz] and its standard uncertainty."""

    low_hz: float
    high_hz: float
    delay_s: float
    sigma_s: float

    def periods_text(self) -> str:
        """``"8–14 s"``: the band as wave periods."""
        return f"{1.0 / self.high_hz:.0f}\u2013{1.0 / self.low_hz:.0f} s"


@dataclasses.dataclass(frozen=True)
class ModelCheck:
    """Outcome of :func:`check_delay_model`; ``determined`` False when the data hold too
    few coherent frequencies to compare bands."""

    determined: bool
    bands: tuple[BandDelay, ...] = ()
    chi2: float = float("nan")
    p_value: float = float("nan")
    spread_s: float = float("nan")
    """Standard deviation of the band delays about their weighted mean (s)."""

    @property
    def pure_delay(self) -> bool:
        return not self.determined or self.p_value >= P_FLAG

    def to_dict(self) -> dict:
        return {"determined": self.determined, "pure_delay": self.pure_delay,
                "chi2": self.chi2, "p_value": self.p_value, "spread_s": self.spread_s,
                "bands": [dataclasses.asdict(b) for b in self.bands]}

    def bands_text(self) -> str:
        """``"+1.203 s at 14–32 s periods, …"``."""
        return ", ".join(f"{b.delay_s:+.3f} s at {b.periods_text()} periods" for b in self.bands)


def _pooled_spectra(pairs: Sequence[tuple[np.ndarray, np.ndarray]], interval: float):
    """(f, Pxy, Pxx, Pyy, segments) summed over the lines long enough for a segment."""
    nper = int(round(SEGMENT_S / interval))
    total = None
    segments = 0
    for heave, height in pairs:
        if heave.size < nper or nper < 8:
            continue
        f, pxy = csd(heave, height, fs=1.0 / interval, nperseg=nper, detrend="linear")
        _, pxx = welch(heave, fs=1.0 / interval, nperseg=nper, detrend="linear")
        _, pyy = welch(height, fs=1.0 / interval, nperseg=nper, detrend="linear")
        count = 1 + 2 * (heave.size - nper) // nper  # half-overlapping segments
        parts = (pxy * count, pxx * count, pyy * count)
        total = parts if total is None else tuple(a + b for a, b in zip(total, parts,
                                                                        strict=True))
        segments += count
    if total is None:
        return None
    return (f, *(part / segments for part in total), segments)


def _band(f, phase, weight, latency_s) -> BandDelay:
    """Least-squares slope through the origin of the residual phase of one band."""
    sxx = float(np.sum(weight * f * f))
    tau = -float(np.sum(weight * phase * f)) / sxx / (2 * np.pi)
    sigma = NEIGHBOUR_FACTOR / np.sqrt(sxx) / (2 * np.pi)
    return BandDelay(float(f[0]), float(f[-1]), latency_s + tau, sigma)


def check_delay_model(pairs: Sequence[tuple[np.ndarray, np.ndarray]], interval: float,
                      latency_s: float) -> ModelCheck:
    """The band check on the used lines.

    Parameters
    ----------
    pairs : sequence of (heave, height)
        Per used line: total heave at ``tag − latency_s`` and the detrended heights (m),
        both at the line's GNSS epochs (regular, every *interval* s).
    interval : float
        GNSS sampling interval (s).
    latency_s : float
        The estimate the heave is aligned at (s).
    """
    pooled = _pooled_spectra(pairs, interval)
    if pooled is None or not np.isfinite(latency_s):
        return ModelCheck(False)
    f, pxy, pxx, pyy, segments = pooled
    with np.errstate(invalid="ignore", divide="ignore"):
        coherence = np.abs(pxy) ** 2 / (pxx * pyy)
    keep = (f > 0) & (coherence >= MIN_COHERENCE) & (coherence < 1.0)
    idx = np.flatnonzero(keep)
    if idx.size < BANDS * MIN_BINS:
        return ModelCheck(False)
    # Half-overlapping Hann segments are nearly independent (Welch 1967: ~0.95 of the
    # variance reduction of as many disjoint ones); the neighbouring bins are not
    # (NEIGHBOUR_FACTOR).
    n_eff = float(segments)
    var_phase = (1.0 - coherence[idx]) / (2.0 * n_eff * coherence[idx])
    phase = np.angle(pxy[idx])
    bands = tuple(_band(f[part], phase[pos], 1.0 / var_phase[pos], latency_s)
                  for part, pos in zip(np.array_split(idx, BANDS),
                                       np.array_split(np.arange(idx.size), BANDS),
                                       strict=True))
    d = np.array([b.delay_s for b in bands])
    w = 1.0 / np.array([b.sigma_s for b in bands]) ** 2
    mean = float(np.sum(w * d) / np.sum(w))
    stat = float(np.sum(w * (d - mean) ** 2))
    return ModelCheck(True, bands, stat, float(chi2.sf(stat, BANDS - 1)),
                      float(np.sqrt(np.mean((d - mean) ** 2))))
