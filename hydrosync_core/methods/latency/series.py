"""One line's heights and total heave before and after the latency correction (seed fig. 4),
for the panel and the report."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from hydrosync_core.methods.latency.correlation import heave_at
from hydrosync_core.methods.latency.detrend import detrend
from hydrosync_core.methods.latency.heave import total_heave_deg
from hydrosync_core.methods.latency.inputs import check_inputs
from hydrosync_core.methods.latency.lines import line_epochs
from hydrosync_core.methods.latency.params import LatencyParams


def line_series(
    gnss: Mapping, attitude: Mapping, lever_arm, start: float, end: float, latency_s: float,
    params: LatencyParams | Mapping | None = None,
) -> dict[str, np.ndarray]:
    """One line's detrended heights and total heave before (Δt = 0) and after (seed fig. 4).

    Returns ``time`` (s, tags), ``height`` (m, detrended), ``heave_before`` and
    ``heave_after`` (m, total heave at ``tag`` and at ``tag − latency_s``).
    """
    p = params if isinstance(params, LatencyParams) else LatencyParams.from_dict(params)
    dt = float(np.nan_to_num(latency_s))
    empty = np.empty(0)
    nothing = {"time": empty, "height": empty, "heave_before": empty, "heave_after": empty}
    # The records around the line only (with the one beyond each end, which the
    # interpolation may need across a gap): the same numbers as the whole day's, without
    # checking and transforming a day's 8 million attitude records for one line's plot.
    lo, hi = float(start) - abs(dt) - 1.0, float(end) + abs(dt) + 1.0
    gnss, attitude = _records_within(gnss, lo, hi), _records_within(attitude, lo, hi)
    if gnss is None or attitude is None:
        return nothing
    t_g, hgt, att, arm = check_inputs(gnss, attitude, lever_arm)
    sel = line_epochs(t_g, start, end, p.skip_s, att["time"], min(dt, 0.0), max(dt, 0.0))
    tags = t_g[sel]
    if tags.size < 3:
        return nothing
    h, _ = detrend(tags, hgt[sel], int(p.detrend_degree))
    h_att = total_heave_deg(att["heave"], att["roll"], att["pitch"], arm)
    H = heave_at(tags, np.array([0.0, dt]), att["time"], h_att)
    return {"time": tags, "height": h, "heave_before": H[0], "heave_after": H[1]}


def _records_within(table: Mapping, lo: float, hi: float) -> dict | None:
    """The rows of *table* (increasing ``time``, s) in [lo, hi] and the one beyond each
    end; None when fewer than 2 rows remain."""
    if "time" not in table:
        return dict(table)  # check_inputs names what is missing
    t = np.asarray(table["time"], dtype=float)
    i0 = max(int(np.searchsorted(t, lo, side="left")) - 1, 0)
    i1 = min(int(np.searchsorted(t, hi, side="right")) + 1, t.size)
    if i1 - i0 < 2:
        return None
    return {name: np.asarray(values)[i0:i1] for name, values in table.items()
            if np.ndim(values) == 1 and len(values) == t.size}
