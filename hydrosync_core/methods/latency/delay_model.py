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
from scipy.stats import chi2

SEGMENT_S = 64.0
"""Length of the Welch segments (s): resolves the wave band (periods 3–20 s) in ~12 bins."""

BANDS = 3
"""Frequency bands compared (long, middle and short periods of the coherent range)."""

MIN_COHERENCE = 0.5
"""Bins with a pooled squared coherence below this carry no usable phase."""

MIN_BINS = 2
"""Coherent bins a band needs."""

MIN_SEGMENTS = 8
"""Welch segments (about four two-minute lines) the pooled spectra need: with fewer the
squared coherence is biased high by ~1/segments and its phase variance is not known well
enough for a χ² test (on a simulated calm day whose one used line gave 2 segments, the
bands agreed at p = 0.14 while an undeclared filter put Δt 219 ms off)."""

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


def _segments(x: np.ndarray, nper: int) -> np.ndarray:
    """Half-overlapping segments of *x* (rows), each without its least-squares line and
    Hann-windowed: Welch's segments, for one rfft of both series."""
    starts = np.arange(0, x.size - nper + 1, nper // 2)
    seg = x[starts[:, None] + np.arange(nper)]
    k = np.arange(nper, dtype=float) - 0.5 * (nper - 1)
    seg = seg - seg.mean(axis=1, keepdims=True)
    seg -= np.outer(seg @ k / (k @ k), k)
    return seg * np.hanning(nper + 2)[1:-1]


@dataclasses.dataclass(frozen=True)
class PooledSpectra:
    """Auto- and cross-spectra summed over every Welch segment of the used lines, the
    total heave split into the sensor's heave (v) and the rotation-induced heave (r) so
    that a heave filter's phase can be taken off the first alone; y: the heights.
    Relative scale: only phases and coherences are used."""

    f: np.ndarray
    vy: np.ndarray
    ry: np.ndarray
    vv: np.ndarray
    rr: np.ndarray
    vr: np.ndarray
    yy: np.ndarray
    segments: int

    def cross_and_coherence(self, lead=None) -> tuple[np.ndarray, np.ndarray]:
        """(cross-spectrum of total heave and heights, squared coherence), with the phase
        ``lead(f)`` (rad) of a heave filter removed from the sensor's heave first:
        ``v → v·exp(−i·lead)``."""
        turn = 1.0 if lead is None else np.exp(1j * lead(self.f))
        cross = turn * self.vy + self.ry
        power = self.vv + self.rr + 2.0 * np.real(turn * self.vr)
        with np.errstate(invalid="ignore", divide="ignore"):
            return cross, np.abs(cross) ** 2 / (power * self.yy)


def pooled_spectra(series: Sequence[tuple], interval: float) -> PooledSpectra | None:
    """:class:`PooledSpectra` of *series*: per used line (sensor heave, induced heave,
    heights) or (total heave, heights), m, at the GNSS epochs (every *interval* s).
    None when no line is long enough for one segment of SEGMENT_S."""
    nper = int(round(SEGMENT_S / interval))
    if nper < 8:
        return None
    sums = None
    segments = 0
    for parts in series:
        v, r, y = parts if len(parts) == 3 else (parts[0], None, parts[1])
        if np.size(v) < nper:
            continue
        fv = np.fft.rfft(_segments(np.asarray(v, dtype=float), nper), axis=1)
        fy = np.fft.rfft(_segments(np.asarray(y, dtype=float), nper), axis=1)
        fr = np.zeros_like(fv) if r is None else np.fft.rfft(
            _segments(np.asarray(r, dtype=float), nper), axis=1)
        line = [(np.conj(fv) * fy).sum(axis=0), (np.conj(fr) * fy).sum(axis=0),
                (np.abs(fv) ** 2).sum(axis=0), (np.abs(fr) ** 2).sum(axis=0),
                (np.conj(fv) * fr).sum(axis=0), (np.abs(fy) ** 2).sum(axis=0)]
        sums = line if sums is None else [x + y for x, y in zip(sums, line, strict=True)]
        segments += fv.shape[0]
    if sums is None:
        return None
    return PooledSpectra(np.fft.rfftfreq(nper, interval), *sums, segments)


def _band(f, phase, weight, latency_s) -> BandDelay:
    """Least-squares slope through the origin of the residual phase of one band."""
    sxx = float(np.sum(weight * f * f))
    tau = -float(np.sum(weight * phase * f)) / sxx / (2 * np.pi)
    sigma = NEIGHBOUR_FACTOR / np.sqrt(sxx) / (2 * np.pi)
    return BandDelay(float(f[0]), float(f[-1]), latency_s + tau, sigma)


@dataclasses.dataclass(frozen=True)
class CoherentPhase:
    """The pooled residual cross-spectrum phase of the coherent bins: frequencies (Hz),
    phase (rad) and its variance (rad²), as :func:`check_delay_model` compares them."""

    f: np.ndarray
    phase: np.ndarray
    var_phase: np.ndarray


def coherent_phase(spectra: PooledSpectra | None, lead=None) -> CoherentPhase | None:
    """The coherent bins of *spectra* (a heave filter's phase ``lead(f)`` removed from the
    sensor's heave first, when given); None when there are too few to compare bands."""
    if spectra is None or spectra.segments < MIN_SEGMENTS:
        return None
    cross, coherence = spectra.cross_and_coherence(lead)
    f = spectra.f
    keep = (f > 0) & (coherence >= MIN_COHERENCE) & (coherence < 1.0)
    idx = np.flatnonzero(keep)
    if idx.size < BANDS * MIN_BINS:
        return None
    # Half-overlapping Hann segments are nearly independent (Welch 1967: ~0.95 of the
    # variance reduction of as many disjoint ones); the neighbouring bins are not
    # (NEIGHBOUR_FACTOR).
    var_phase = (1.0 - coherence[idx]) / (2.0 * float(spectra.segments) * coherence[idx])
    return CoherentPhase(f[idx], np.angle(cross[idx]), var_phase)


def band_check(spectrum: CoherentPhase | None, latency_s: float) -> ModelCheck:
    """Band delays of *spectrum* aligned at *latency_s* (s) and their χ² test."""
    if spectrum is None or not np.isfinite(latency_s):
        return ModelCheck(False)
    idx = np.arange(spectrum.f.size)
    bands = tuple(_band(spectrum.f[part], spectrum.phase[part],
                        1.0 / spectrum.var_phase[part], latency_s)
                  for part in np.array_split(idx, BANDS))
    d = np.array([b.delay_s for b in bands])
    w = 1.0 / np.array([b.sigma_s for b in bands]) ** 2
    mean = float(np.sum(w * d) / np.sum(w))
    stat = float(np.sum(w * (d - mean) ** 2))
    return ModelCheck(True, bands, stat, float(chi2.sf(stat, BANDS - 1)),
                      float(np.sqrt(np.mean((d - mean) ** 2))))


def check_delay_model(series: Sequence[tuple], interval: float,
                      latency_s: float) -> ModelCheck:
    """The band check on the used lines.

    Parameters
    ----------
    series : sequence of (heave, height) or (sensor heave, induced heave, height)
        Per used line: total heave at ``tag − latency_s`` (or its two parts) and the
        detrended heights (m), at the line's GNSS epochs (regular, every *interval* s).
    interval : float
        GNSS sampling interval (s).
    latency_s : float
        The estimate the heave is aligned at (s).
    """
    return band_check(coherent_phase(pooled_spectra(series, interval)), latency_s)
