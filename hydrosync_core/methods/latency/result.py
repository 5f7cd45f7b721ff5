"""Frozen result and parameter dataclasses of the latency module, serialisable to JSON."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field, fields

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.combine import WEIGHTINGS


def _clean(value):
    """JSON-safe copy: NaN/inf become None, numpy scalars become Python ones."""
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_clean(v) for v in value]
    if isinstance(value, np.ndarray):
        return _clean(value.tolist())
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


@dataclass(frozen=True)
class LatencyParams:
    """Parameters of the latency estimation.

    Attributes
    ----------
    range_s : (float, float)
        Scan range of Δt, s (default symmetric −1..+1: the sign is not known).
    step_s : float
        Scan step, s (seed: 0.005).
    min_r : float
        Lines with R_max above this are used (seed: 0.85).
    detrend_degree : int
        Degree of the tide/trend polynomial (seed: 1).
    skip_s : float
        Seconds skipped at the start of each line (seed: ≥ 60 s of unsteady run-in).
        Default 0: the lines' start times are taken as the end of the run-in.
    weighting : str
        ``"r"`` (R as weight, default) or ``"inverse_variance"``.
    min_epochs : int
        Lines with fewer GNSS epochs are not used.
    gap_factor : float
        A GNSS/attitude interval longer than this many median intervals is a gap.
    outlier_k : float
        A line whose Δt departs from the median of the selected lines by more than
        *outlier_k* robust standard deviations (MAD of the lines combined with the line's
        own uncertainty) is not used; 0 disables the test. Needs 4 or more lines.
    """

    range_s: tuple[float, float] = (-1.0, 1.0)
    step_s: float = 0.005
    min_r: float = 0.85
    detrend_degree: int = 1
    skip_s: float = 0.0
    weighting: str = "r"
    min_epochs: int = 30
    gap_factor: float = 3.0
    outlier_k: float = 4.0

    def __post_init__(self) -> None:
        try:
            lo, hi = (float(v) for v in self.range_s)
        except (TypeError, ValueError):
            raise InputError(None, "range must be two numbers", field="range_s") from None
        object.__setattr__(self, "range_s", (lo, hi))
        def require(ok: bool, name: str, message: str) -> None:
            if not ok:
                raise InputError(None, message, field=name)

        try:
            step, min_r, skip = float(self.step_s), float(self.min_r), float(self.skip_s)
            degree, min_epochs = int(self.detrend_degree), int(self.min_epochs)
            gap, outlier_k = float(self.gap_factor), float(self.outlier_k)
        except (TypeError, ValueError) as exc:
            raise InputError(None, f"parameter is not a number ({exc})") from None
        require(math.isfinite(lo) and math.isfinite(hi) and hi > lo, "range_s",
                f"range maximum must be above minimum, got {lo}..{hi}")
        require(math.isfinite(step) and 0 < step <= hi - lo, "step_s",
                f"step must be positive and within the range, got {step}")
        require((hi - lo) / step <= 200_000, "step_s", "too many scan candidates (> 200000)")
        require(-1.0 <= min_r < 1.0, "min_r", f"R threshold must be in [-1, 1), got {min_r}")
        require(0 <= degree <= 5, "detrend_degree", f"detrend degree must be 0..5, got {degree}")
        require(math.isfinite(skip) and skip >= 0, "skip_s", f"skip must be >= 0 s, got {skip}")
        require(self.weighting in WEIGHTINGS, "weighting",
                f"weighting must be one of {', '.join(WEIGHTINGS)}, got '{self.weighting}'")
        require(min_epochs >= 5, "min_epochs", "min_epochs must be >= 5")
        require(gap > 1, "gap_factor", "gap_factor must be > 1")
        require(math.isfinite(outlier_k) and outlier_k >= 0, "outlier_k",
                f"outlier_k must be >= 0 (0 disables the test), got {outlier_k}")

    @classmethod
    def from_dict(cls, values: Mapping | None) -> LatencyParams:
        """Build from a dict, ignoring keys that are not parameters (e.g. ``lever_arm_m``)."""
        names = {f.name for f in fields(cls)}
        kwargs = {k: v for k, v in dict(values or {}).items() if k in names}
        if "range_s" in kwargs:
            kwargs["range_s"] = tuple(kwargs["range_s"])
        return cls(**kwargs)

    def to_dict(self) -> dict:
        d = asdict(self)
        d["range_s"] = list(self.range_s)
        return d


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
        return _clean(asdict(self))


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

    def to_dict(self, curves: bool = False) -> dict:
        """JSON-ready dict (``formats.md`` result.json); *curves* adds the R curves."""
        d = {
            "latency_s": self.latency_s,
            "uncertainty_s": self.uncertainty_s,
            "ci95_s": [self.ci95_low, self.ci95_high],
            "n_used": self.n_used,
            "weighting": self.weighting,
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
        return _clean(d)
