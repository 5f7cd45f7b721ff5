"""The parameters of the heave statistics: declared once, everything else derives."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hydrosync_core.errors import InputError
from hydrosync_core.params import Params, param


@dataclass(frozen=True)
class HeaveStatsParams(Params):
    """Heave statistics parameters (seconds)."""

    SCHEMA_VERSION: ClassVar[int] = 1

    skip_s: float = param(
        0.0, label="Skip at line start", unit="s", minimum=0.0, maximum=3600.0, decimals=1,
        help="seconds of run-in left out at the start of each line")
    min_period_s: float = param(
        2.0, label="Shortest period", unit="s", minimum=0.1, maximum=60.0, decimals=1,
        help="spectral peaks at shorter periods are ignored (vibration, sensor noise)")
    max_period_s: float = param(
        30.0, label="Longest period", unit="s", minimum=1.0, maximum=600.0, decimals=1,
        help="spectral peaks at longer periods are ignored (heave filter drift)")

    def validate(self) -> None:
        if not self.max_period_s > self.min_period_s:
            raise InputError(None, "longest period must exceed the shortest period",
                             field="max_period_s")
