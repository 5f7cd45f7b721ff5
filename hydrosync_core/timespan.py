"""Time spans of project data, as a person reads them (raw seconds and, when the scale
looks like Unix time, UTC)."""

from __future__ import annotations

from dataclasses import dataclass
from datetime import UTC, datetime

import numpy as np

#: Unix seconds of 2000-01-01 and 2100-01-01: a time column inside this range is taken
#: to be Unix time for display (GPS seconds of week never reach it).
UNIX_RANGE = (946_684_800.0, 4_102_444_800.0)


@dataclass(frozen=True)
class Span:
    """First and last time (s, raw scale) and the number of samples."""

    start: float
    end: float
    count: int

    @property
    def is_unix(self) -> bool:
        return UNIX_RANGE[0] <= self.start <= UNIX_RANGE[1]

    def text(self) -> str:
        """``"2024-05-01 10:00:00 – 10:59:59 UTC (3599.0 s; raw 1714557600.0 … )"``."""
        raw = f"raw {self.start:.3f} … {self.end:.3f} s"
        duration = f"{self.end - self.start:.1f} s"
        if not self.is_unix:
            return f"{raw} ({duration}; not Unix time)"
        a = datetime.fromtimestamp(self.start, UTC)
        b = datetime.fromtimestamp(self.end, UTC)
        end = b.strftime("%H:%M:%S" if a.date() == b.date() else "%Y-%m-%d %H:%M:%S")
        return f"{a:%Y-%m-%d %H:%M:%S} – {end} UTC ({duration}; {raw})"


def span_of(values) -> Span | None:
    """The span of a time column (None if it is empty or holds no finite value)."""
    t = np.asarray(values, dtype=float).ravel()
    t = t[np.isfinite(t)]
    if t.size == 0:
        return None
    return Span(float(t.min()), float(t.max()), int(t.size))


def table_span(project, path: str, column: str = "time") -> Span | None:
    """The span of the ``time`` column of table *path* (None if it has none)."""
    try:
        attrs = project.attrs(path)
        if column not in (attrs.get("columns") or project.children(path)):
            return None
        return span_of(project.get(f"{path}/{column}"))
    except Exception:  # a damaged or non-table node has no span to show
        return None
