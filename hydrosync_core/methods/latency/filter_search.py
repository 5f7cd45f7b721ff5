"""An undeclared heave filter, searched for on every run whose filter is not declared.

For each candidate causal high-pass (orders 2–3, cut-off periods 8–40 s) the candidate's
phase is taken off the sensor's heave in the pooled spectra of the band check
(:class:`.delay_model.PooledSpectra`: what declaring it does, :mod:`.heave_filter`, without
filtering the record again) and the band check repeated at the result's Δt; the weighted
mean of its band delays is the delay that candidate implies. A candidate *fits* when its
bands agree (p ≥ P_FIT). Orders 2 and 3 with
neighbouring cut-offs have nearly the same phase at the wave periods, so the filter itself
is seldom determined; the delay is, when every fitting candidate implies the same one
within 2 σ. Otherwise HydroSync says the data do not determine it. The reported estimate is
not changed: the user declares the filter (the text names the best) and runs again.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from hydrosync_core.methods.latency.delay_model import (
    PooledSpectra,
    band_check,
    coherent_phase,
)
from hydrosync_core.methods.latency.heave_filter import highpass_response

ORDERS = (2, 3)
PERIODS_S = (8.0, 10.0, 12.5, 15.0, 20.0, 25.0, 30.0, 40.0)
P_FIT = 0.05
"""Band-check p-value from which a candidate filter fits the data."""


@dataclasses.dataclass(frozen=True)
class FilterSearch:
    """Outcome: the candidates' p-values, the best one and whether the data determine it."""

    p_values: dict
    best: tuple[int, float] | None
    determined: bool
    delays: dict = dataclasses.field(default_factory=dict)
    """Per candidate (order, cut-off): (implied Δt, its σ) in s."""
    none_delay_s: float = float("nan")
    """The Δt the bands imply without a filter (s): the limit of long cut-offs."""
    none_p: float = float("nan")
    """The band check's p-value without a filter."""

    def joint(self) -> tuple[float, float] | None:
        """(Δt, σ) in s of the joint estimate when the data determine the filter: the best
        candidate's implied Δt; σ from its bands, half the spread of the fitting
        candidates and half the largest step to a neighbouring candidate (the next
        cut-off either side — no filter beyond the longest —, the other order): the
        cut-off is only known to the grid's resolution (on 25 simulated days with an
        undeclared filter that the data determined, 22 within 1.96 σ of the truth; the
        the same σ without the grid term covered 12)."""
        if not self.determined or self.best is None:
            return None
        order, period = self.best
        dt, sigma = self.delays[self.best]
        fits = [self.delays[k][0] for k, v in self.p_values.items()
                if np.isfinite(v) and v >= P_FIT]
        i = PERIODS_S.index(period)
        steps = [self.delays.get((order, PERIODS_S[j]), (np.nan,))[0]
                 for j in (i - 1, i + 1) if 0 <= j < len(PERIODS_S)]
        steps.append(self.delays.get((5 - order, period), (np.nan,))[0])
        if i == len(PERIODS_S) - 1:
            steps.append(self.none_delay_s)
        grid = max((abs(x - dt) for x in steps if np.isfinite(x)), default=0.0) / 2.0
        return dt, float(np.sqrt(sigma**2 + ((max(fits) - min(fits)) / 2.0) ** 2 + grid**2))

    def text(self) -> str:
        if self.best is None:
            return ("no causal high-pass heave filter (order 2–3, cut-off 8–40 s) makes the "
                    "bands agree: the data do not determine a filter")
        order, period = self.best
        fits = [self.delays[k][0] for k, v in self.p_values.items()
                if np.isfinite(v) and v >= P_FIT]
        span = f"{min(fits) * 1e3:+.0f} … {max(fits) * 1e3:+.0f} ms"
        if not self.determined:
            return (f"heave filters that make the bands agree imply Δt {span} (best: order "
                    f"{order}, cut-off {period:g} s): the data do not determine the filter "
                    "nor the delay")
        dt, sigma = self.joint()
        return (f"with a heave filter the bands agree (best: order {order}, cut-off "
                f"{period:g} s, p = {self.p_values[self.best]:.2g}) and every fitting filter "
                f"implies Δt {span}: jointly with the filter Δt = {dt * 1e3:+.0f} ± "
                f"{sigma * 1e3:.0f} ms, which σ is widened to cover; declare the filter if "
                "the sensor's settings confirm it (heave_filter = highpass)")

    def far_fits(self, latency_s: float, tolerance_s: float) -> list:
        """Candidates (order, cut-off) that fit the bands as well as one pure delay does
        (p ≥ P_FIT, or ≥ the pure delay's own p when that is lower) and whose implied Δt
        lies further than *tolerance_s* from *latency_s* (s)."""
        level = min(P_FIT, self.none_p) if np.isfinite(self.none_p) else P_FIT
        return [k for k, v in self.p_values.items()
                if np.isfinite(v) and v >= level and k in self.delays
                and abs(self.delays[k][0] - latency_s) > tolerance_s]

    def not_excluded_text(self, far: list) -> str:
        """The flag of a run whose bands agree with one delay and with filters *far*."""
        implied = [self.delays[k][0] * 1e3 for k in far]
        periods = [k[1] for k in far]
        return (f"the bands agree with one delay, but as well with the lead of a causal "
                f"heave filter (order {min(k[0] for k in far)}–{max(k[0] for k in far)}, "
                f"cut-off {min(periods):g}–{max(periods):g} s), which would put Δt at "
                f"{min(implied):+.0f} … {max(implied):+.0f} ms: the data do not exclude an "
                "undeclared heave filter; declare it (heave_filter: none, compensated or "
                "highpass)")

    def to_dict(self) -> dict:
        return {"determined": self.determined, "best": list(self.best) if self.best else None,
                "p_values": {f"{o}/{t:g}": p for (o, t), p in self.p_values.items()},
                "implied_latency_s": {f"{o}/{t:g}": d[0] for (o, t), d in self.delays.items()},
                "implied_sigma_s": {f"{o}/{t:g}": d[1] for (o, t), d in self.delays.items()},
                "joint": list(self.joint()) if self.joint() else None}


def search_filter(spectra: PooledSpectra, latency_s: float) -> FilterSearch:
    """Try every candidate filter on the band check's pooled *spectra*, the heave aligned
    at *latency_s* (s)."""
    p_values, delays = {}, {}
    plain = band_check(coherent_phase(spectra), latency_s)
    none_delay = _implied(plain)[0] if plain.determined else float("nan")
    none_p = plain.p_value if plain.determined else float("nan")
    for order in ORDERS:
        for period in PERIODS_S:
            def lead(f, order=order, period=period):
                return np.angle(highpass_response(f, order, period))

            check = band_check(coherent_phase(spectra, lead), latency_s)
            p_values[(order, period)] = check.p_value if check.determined else float("nan")
            if check.determined:
                delays[(order, period)] = _implied(check)
    finite = {k: v for k, v in p_values.items() if np.isfinite(v)}
    if not finite or max(finite.values()) < P_FIT:
        return FilterSearch(p_values, None, False, delays, none_delay, none_p)
    best = max(finite, key=finite.get)
    implied = [delays[k][0] for k, v in finite.items() if v >= P_FIT]
    determined = max(implied) - min(implied) <= 2.0 * delays[best][1]
    return FilterSearch(p_values, best, determined, delays, none_delay, none_p)


def _implied(check) -> tuple[float, float]:
    """(weighted mean of the band delays, its σ) in s."""
    d = np.array([b.delay_s for b in check.bands])
    w = 1.0 / np.array([b.sigma_s for b in check.bands]) ** 2
    return float(np.sum(w * d) / np.sum(w)), float(1.0 / np.sqrt(np.sum(w)))
