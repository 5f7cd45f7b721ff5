"""GNSS heights with the attitude at their corrected times (seed eq. 3): the synchronised set."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.heave import total_heave
from hydrosync_core.methods.latency.inputs import check_inputs


def _attitude_at(attitude: Mapping, times: np.ndarray) -> dict[str, np.ndarray]:
    """Seed eq. 3: attitude linearly interpolated at *times* (deg; heading unwrapped)."""
    t = np.asarray(attitude["time"], dtype=float)
    out = {c: np.interp(times, t, np.asarray(attitude[c], dtype=float))
           for c in ("roll", "pitch", "heave")}
    # Heading wraps at 360 deg: interpolate along the shorter arc between the two
    # neighbouring samples (no unwrapping of the whole record: memory of the output only).
    heading = np.asarray(attitude["heading"], dtype=float)
    k = np.clip(np.searchsorted(t, times), 1, t.size - 1)
    h0, h1 = heading[k - 1], heading[k]
    w = (times - t[k - 1]) / (t[k] - t[k - 1])
    out["heading"] = (h0 + w * ((h1 - h0 + 180.0) % 360.0 - 180.0)) % 360.0
    return out


def synchronise(gnss: Mapping, attitude: Mapping, lever_arm, latency_s: float) -> dict:
    """GNSS heights with attitude at their corrected times ``tag − latency_s`` (seed eq. 3).

    Returns a dict of 1-D arrays: ``time`` (s, corrected), ``height`` (m), ``roll``,
    ``pitch``, ``heading`` (deg), ``heave`` and ``total_heave`` (m, up, seed eq. 2) —
    only the epochs whose corrected time lies inside the attitude record.
    """
    if not np.isfinite(latency_s):
        raise InputError(None, "cannot synchronise without a latency", field="latency_s")
    t_g, hgt, att, arm = check_inputs(gnss, attitude, lever_arm)
    corrected = t_g - latency_s
    keep = (corrected >= att["time"][0]) & (corrected <= att["time"][-1])
    out = {"time": corrected[keep], "height": hgt[keep]}
    out.update(_attitude_at(attitude, corrected[keep]))
    out["total_heave"] = total_heave(
        out["heave"], np.radians(out["roll"]), np.radians(out["pitch"]), arm)
    return {k: out[k] for k in ("time", "height", "roll", "pitch", "heading", "heave",
                                "total_heave")}
