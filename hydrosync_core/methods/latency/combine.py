"""Line selection and the weighted mean of the per-line delays (seed section 2.4).

The seed keeps lines whose maximum correlation exceeds 0.85 and takes a weighted mean
without naming the weights. HydroSync uses R as the weight by default (reproduces the
seed's table 1: 0.29 s) and offers inverse-variance weights from the per-line
uncertainties.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from hydrosync_core.methods.latency.params import WEIGHTINGS  # noqa: E402

Z975 = 1.959963984540054
"""Normal 97.5 % quantile (``scipy.special.ndtri(0.975)``; scipy.special is imported only
for Student's t: its import costs a command-line run 0.1–0.2 s)."""


def _t975(dof: int) -> float:
    from scipy import special

    return float(special.stdtrit(dof, 0.975))


@dataclass(frozen=True)
class Combined:
    """The final delay from the selected lines (seconds)."""

    latency_s: float
    uncertainty_s: float
    ci95_low: float
    ci95_high: float
    n_used: int
    weighting: str

    def to_dict(self) -> dict:
        return asdict(self)


def select_lines(r_max: np.ndarray, min_r: float, usable: np.ndarray | None = None) -> np.ndarray:
    """Boolean mask of lines with ``R_max > min_r`` (strictly, as the seed) and *usable*."""
    r_max = np.asarray(r_max, dtype=float)
    mask = np.nan_to_num(r_max, nan=-np.inf) > min_r
    if usable is not None:
        mask &= np.asarray(usable, dtype=bool)
    return mask


def find_outliers(
    latencies: np.ndarray, uncertainties: np.ndarray, used: np.ndarray, k: float,
    min_lines: int = 4,
) -> np.ndarray:
    """Boolean mask of used lines whose Δt is an outlier among the used lines.

    Beyond the seed: a line is an outlier when ``|Δt_i − median| > k·s_i`` with
    ``s_i = sqrt(MAD_σ² + u_i²)``, MAD_σ = 1.4826·median|Δt − median| of the used lines
    and u_i the line's own standard uncertainty (so a line is not rejected for a spread
    its own noise explains). Needs *min_lines* used lines; ``k = 0`` disables the test.
    """
    used = np.asarray(used, dtype=bool)
    out = np.zeros(used.shape, dtype=bool)
    if k <= 0 or used.sum() < min_lines:
        return out
    x = np.asarray(latencies, dtype=float)
    u = np.nan_to_num(np.asarray(uncertainties, dtype=float), nan=0.0)
    med = float(np.median(x[used]))
    mad = 1.4826 * float(np.median(np.abs(x[used] - med)))
    scale = np.sqrt(mad**2 + u**2)
    with np.errstate(invalid="ignore", divide="ignore"):
        out[used] = np.abs(x[used] - med) > k * scale[used]
    return out


def weighted_mean(values: np.ndarray, weights: np.ndarray) -> float:
    """Σ w·x / Σ w."""
    values = np.asarray(values, dtype=float)
    weights = np.asarray(weights, dtype=float)
    return float(np.sum(weights * values) / np.sum(weights))


def combine(
    latencies: np.ndarray, r_max: np.ndarray, uncertainties: np.ndarray, used: np.ndarray,
    weighting: str = "r",
) -> Combined:
    """Weighted mean of the used lines' delays with its uncertainty and 95 % interval.

    The standard uncertainty is the larger of the *internal* one (propagated from the
    per-line uncertainties) and the *external* one (from the scatter of the lines about
    the mean, a weighted sandwich estimate). The 95 % interval uses the normal factor
    when the internal figure is the larger (it rests on all the lines' residuals) and
    Student's t with n − 1 degrees of freedom when the scatter of the n lines is (until
    v1.2 always Student's t, which over-covered: 0.986 over 240 simulated days).
    """
    if weighting not in WEIGHTINGS:
        raise ValueError(f"weighting must be one of {WEIGHTINGS}, not '{weighting}'")
    used = np.asarray(used, dtype=bool)
    x = np.asarray(latencies, dtype=float)[used]
    s = np.asarray(uncertainties, dtype=float)[used]
    n = int(x.size)
    nan = float("nan")
    if n == 0:
        return Combined(nan, nan, nan, nan, 0, weighting)
    if weighting == "r":
        w = np.asarray(r_max, dtype=float)[used]
    else:
        if not np.all(np.isfinite(s) & (s > 0)):
            # Without usable per-line uncertainties fall back to equal weights.
            s = np.full(n, 1.0)
        w = 1.0 / s**2
    # Weighted mean of the selected lines (seed section 2.4).
    mean = weighted_mean(x, w)
    internal = float(np.sqrt(np.nansum((w * s) ** 2)) / w.sum()) if np.any(np.isfinite(s)) else nan
    if n >= 2:
        external = float(np.sqrt(np.sum((w * (x - mean)) ** 2) * n / (n - 1)) / w.sum())
        if np.isfinite(internal) and internal >= external:
            # The lines agree within their own uncertainties: the internal figure, built
            # from every line's residuals (many degrees of freedom), with the normal factor.
            sigma, factor = internal, Z975
        else:
            # The scatter of n lines says more: Student's t with n − 1 degrees of freedom.
            sigma, factor = external, _t975(n - 1)
    else:
        sigma, factor = internal, Z975  # normal quantile
    return Combined(mean, sigma, mean - factor * sigma, mean + factor * sigma, n, weighting)
