"""Frozen result dataclasses of the latency module, serialisable to JSON.

``LatencyParams`` is declared in :mod:`.params` (re-exported here for convenience).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np

from hydrosync_core.jsonsafe import jsonable
from hydrosync_core.methods.latency.params import LatencyParams

__all__ = ["LatencyParams", "LatencyResult", "LineResult"]


@dataclass(frozen=True)
class LineResult:
    """One survey line: delay at the correlation peak and quality (s, m)."""

    name: str
    start: float
    end: float
    epochs: int
    r_max: float
    latency_s: float
    uncertainty_s: float
    sigma0_before_m: float
    sigma0_after_m: float
    used: bool
    at_edge: bool = False
    warnings: tuple[str, ...] = ()

    def to_dict(self) -> dict:
        return jsonable(asdict(self))


@dataclass(frozen=True, eq=False)
class LatencyResult:
    """Final delay of the GNSS time tags relative to the attitude time tags.

    ``latency_s`` follows ``formats.md``: a GNSS epoch tagged *t* was measured at
    attitude-time ``t − latency_s``. ``dt_grid`` (s, shape (k,)) and ``r_curves``
    (shape (lines, k)) hold the scanned correlation curves.
    """

    latency_s: float
    uncertainty_s: float
    ci95_low: float
    ci95_high: float
    n_used: int
    weighting: str
    joint_latency_s: float
    lines: tuple[LineResult, ...]
    dt_grid: np.ndarray
    r_curves: np.ndarray
    lever_arm_m: tuple[float, float, float]
    params: dict
    converged: bool
    message: str
    warnings: tuple[str, ...] = ()
    diagnostics: dict = field(default_factory=dict)
    estimator: str = "qi2010"
    """The estimator that produced ``latency_s`` (``params.ESTIMATORS``; "auto" resolved)."""

    def to_dict(self, curves: bool = False) -> dict:
        """JSON-ready dict (``formats.md`` result.json); *curves* adds the R curves."""
        d = {
            "latency_s": self.latency_s,
            "uncertainty_s": self.uncertainty_s,
            "ci95_s": [self.ci95_low, self.ci95_high],
            "n_used": self.n_used,
            "weighting": self.weighting,
            "estimator": self.estimator,
            "joint_latency_s": self.joint_latency_s,
            "converged": self.converged,
            "message": self.message,
            "warnings": list(self.warnings),
            "lever_arm_m": list(self.lever_arm_m),
            "params": self.params,
            "diagnostics": self.diagnostics,
            "lines": [line.to_dict() for line in self.lines],
        }
        if curves:
            d["dt_grid_s"] = self.dt_grid
            d["r_curves"] = self.r_curves
        return jsonable(d)
