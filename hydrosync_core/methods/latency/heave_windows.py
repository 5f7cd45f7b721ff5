"""Total heave (seed eq. 2) of the attitude records a line needs, computed on demand."""

from __future__ import annotations

import numpy as np

from hydrosync_core.methods.latency.heave import total_heave_at, total_heave_deg
from hydrosync_core.methods.latency.lines import attitude_window


class HeaveWindows:
    """Attitude records and lever arm: total heave (eq. 2) of line windows on demand.

    A day of 100 Hz attitude is ~10⁷ records: the whole-day total heave would be one more
    80 MB array; the windows the lines need are computed when a line needs them.
    """

    def __init__(self, att: dict, arm: np.ndarray):
        self.t, self.att, self.arm = att["time"], att, arm

    def windows(self, tags: np.ndarray, lo: float, hi: float, pad: int = 0
                ) -> tuple[slice, slice]:
        """(records needed for ``tags − Δt``, Δt in [lo, hi]; the same widened by *pad*
        records on each side, for filtering)."""
        inner = attitude_window(self.t, tags, lo, hi)
        return inner, slice(max(inner.start - pad, 0), min(inner.stop + pad, self.t.size))

    def heave(self, win: slice) -> np.ndarray:
        """Total heave (m, up) of the records *win*."""
        a = self.att
        return total_heave_deg(a["heave"][win], a["roll"][win], a["pitch"][win], self.arm)

    def at(self, times: np.ndarray) -> np.ndarray:
        """Total heave linearly interpolated at *times* (eq. 3), unfiltered.

        Only the two records around each time are evaluated: interpolating over that
        subset gives exactly what interpolating over the whole record gives.
        """
        a = self.att
        return total_heave_at(times, self.t, a["heave"], a["roll"], a["pitch"], self.arm)
