"""An undeclared heave filter, searched for when the delay-model check flags one.

For each candidate causal high-pass (orders 2–3, cut-off periods 8–40 s) the declared-filter
model (:mod:`.heave_filter`) is applied and the band check (:mod:`.delay_model`) repeated on
the used lines at the result's Δt; the weighted mean of its band delays is the delay that
candidate implies. A candidate *fits* when its bands agree (p ≥ P_FIT). Orders 2 and 3 with
neighbouring cut-offs have nearly the same phase at the wave periods, so the filter itself
is seldom determined; the delay is, when every fitting candidate implies the same one
within 2 σ. Otherwise HydroSync says the data do not determine it. The reported estimate is
not changed: the user declares the filter (the text names the best) and runs again.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

import numpy as np

from hydrosync_core.methods.latency.delay_model import check_delay_model
from hydrosync_core.methods.latency.heave_filter import with_declared_filter
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.result import LatencyResult

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
        dt, sigma = self.delays[self.best]
        return (f"with a heave filter the bands agree (best: order {order}, cut-off "
                f"{period:g} s, p = {self.p_values[self.best]:.2g}) and every fitting filter "
                f"implies Δt {span} (best {dt * 1e3:+.0f} ± {sigma * 1e3:.0f} ms): declare "
                "it if the sensor's settings confirm it (heave_filter = highpass)")

    def to_dict(self) -> dict:
        return {"determined": self.determined, "best": list(self.best) if self.best else None,
                "p_values": {f"{o}/{t:g}": p for (o, t), p in self.p_values.items()},
                "implied_latency_s": {f"{o}/{t:g}": d[0] for (o, t), d in self.delays.items()}}


def search_filter(result: LatencyResult, gnss: Mapping, attitude: Mapping,
                  p: LatencyParams, line_pairs) -> FilterSearch:
    """Try every candidate filter; *line_pairs(result, gnss, attitude, p)* gives the band
    check's inputs (:func:`.model_flags._line_pairs`)."""
    p_values, delays = {}, {}
    for order in ORDERS:
        for period in PERIODS_S:
            g, a = with_declared_filter(gnss, attitude, result.lever_arm_m, order, period)
            pairs, interval = line_pairs(result, g, a, p)
            check = check_delay_model(pairs, interval, result.latency_s)
            p_values[(order, period)] = check.p_value if check.determined else float("nan")
            if check.determined:
                d = np.array([b.delay_s for b in check.bands])
                w = 1.0 / np.array([b.sigma_s for b in check.bands]) ** 2
                delays[(order, period)] = (float(np.sum(w * d) / np.sum(w)),
                                           float(1.0 / np.sqrt(np.sum(w))))
    finite = {k: v for k, v in p_values.items() if np.isfinite(v)}
    if not finite or max(finite.values()) < P_FIT:
        return FilterSearch(p_values, None, False, delays)
    best = max(finite, key=finite.get)
    implied = [delays[k][0] for k, v in finite.items() if v >= P_FIT]
    determined = max(implied) - min(implied) <= 2.0 * delays[best][1]
    return FilterSearch(p_values, best, determined, delays)
