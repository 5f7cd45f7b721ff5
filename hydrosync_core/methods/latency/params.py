"""Parameters of the latency estimation: the one place they are declared.

The panel form, the ``hydrosync latency`` flags, ``hydrosync run latency --param``, the
stored parameters and the report's parameter table all derive from
:class:`LatencyParams` (``hydrosync_core.params``). Imports only the standard library.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from hydrosync_core.errors import InputError
from hydrosync_core.params import Params, param

#: How the per-line delays are combined (Qi et al. 2010 weight by R).
WEIGHTINGS = ("r", "inverse_variance")

#: How each line's delay is estimated (docs/methods.md section 1):
#: ``qi2010`` — the published method: Pearson R of the detrended heights and the total heave
#: interpolated from the raw high-rate records (Qi et al. 2010, eqs. 1–4);
#: ``qi2010_antialias`` — the same with the high-rate total heave first low-passed to the
#: GNSS band (zero-phase), so its sensor noise is not aliased into the comparison;
#: ``weighted`` — anti-aliased, then both series weighted per frequency by the coherence of
#: heights and heave pooled over the day's lines (maximum-likelihood generalised
#: cross-correlation; near the Cramér–Rao bound when the errors are coloured).
#: ``auto`` (default) — runs ``qi2010`` and ``weighted`` and keeps the one with the smaller
#: combined uncertainty (the weighted one wins with coloured sensor noise, the published
#: one on clean data; never worse than ``qi2010`` in docs/benchmarks.md).
ESTIMATORS = ("qi2010", "qi2010_antialias", "weighted")
ESTIMATOR_CHOICES = ESTIMATORS + ("auto",)

#: Which lines enter the mean: ``paper`` — the rule of Qi et al. (2010) alone (R_max above
#: the threshold, for every line with data and a peak inside the scan range); ``extended``
#: — also not the lines whose σ is not credible or that are outliers; ``auto`` — paper
#: for ``qi2010`` (the published method stays exact), extended for the others.
SCREENINGS = ("auto", "paper", "extended")

#: The motion sensor's heave filter (:mod:`.heave_filter`): ``unknown`` (not declared: the
#: delay-model check says when the data show one), ``none`` or ``compensated`` (no phase
#: at the wave periods: nothing to model), ``highpass`` (causal Butterworth high-pass of
#: ``heave_filter_order`` and ``heave_filter_period_s``: its phase is removed from the
#: heave, its gain applied to the heights).
HEAVE_FILTERS = ("unknown", "none", "compensated", "highpass")

ESTIMATOR_NAMES = {
    "qi2010": "correlation of raw series (Qi et al. 2010)",
    "qi2010_antialias": "correlation after anti-alias low-pass (Qi et al. 2010 + filter)",
    "weighted": "coherence-weighted cross-correlation (maximum likelihood)",
    "auto": "the estimator with the smaller uncertainty of qi2010 and weighted",
}


def parse_qualities(text: str) -> tuple[int, ...] | None:
    """``"auto"`` -> None; ``"4,5"`` -> (4, 5). Raises InputError naming the field."""
    text = str(text).strip().lower()
    if text in ("", "auto"):
        return None
    try:
        values = tuple(sorted({int(v) for v in text.replace(" ", "").split(",") if v}))
    except ValueError:
        raise InputError(None, f"fix qualities must be 'auto' or numbers like '4,5', got "
                         f"'{text}'", field="fix_qualities") from None
    if not values or any(v < 0 or v > 9 for v in values):
        raise InputError(None, f"fix qualities must be GGA indicators 0-9, got '{text}'",
                         field="fix_qualities")
    return values


def estimator_label(name: str | None) -> str:
    """``"qi2010 — correlation of raw series (Qi et al. 2010)"`` for the panel and the PDF."""
    name = str(name or "qi2010")
    return f"{name} \u2014 {ESTIMATOR_NAMES.get(name, name)}"


@dataclass(frozen=True)
class LatencyParams(Params):
    """Parameters of the latency estimation (Qi et al. 2010 and HydroSync's additions).

    Times in seconds, lengths in metres, the lever arm in the body frame (x forward,
    y starboard, z down).
    """

    SCHEMA_VERSION: ClassVar[int] = 1

    estimator: str = param(
        "auto", label="Estimator", choices=ESTIMATOR_CHOICES,
        help="qi2010 = the published method (correlation of the raw series); "
             "qi2010_antialias = the same after low-passing the high-rate heave to the GNSS "
             "band; weighted = coherence-weighted cross-correlation (lower error with "
             "coloured sensor noise); auto = qi2010 or weighted, whichever has the smaller "
             "uncertainty (see docs/benchmarks.md)")
    range_s: tuple[float, float] = param(
        (-1.0, 1.0), label="Scan range", unit="s", minimum=-10.0, maximum=10.0,
        cli="--range", metavar=("MIN", "MAX"),
        help="range of delays tried; symmetric by default since the sign is not known")
    step_s: float = param(
        0.005, label="Step", unit="s", minimum=0.0, min_exclusive=True, maximum=0.5,
        cli="--step", decimals=4, step=0.001,
        help="scan step of the delay (Qi et al. 2010: 0.005 s); refined below the step")
    min_r: float = param(
        0.85, label="R threshold", minimum=-1.0, maximum=1.0, max_exclusive=True,
        help="lines whose best correlation R_max is above this are used "
             "(Qi et al. 2010: 0.85)")
    detrend_degree: int = param(
        1, label="Detrend degree", minimum=0, maximum=5,
        help="degree of the polynomial (tide, squat) removed from each line's heights")
    skip_s: float = param(
        0.0, label="Skip at line start", unit="s", minimum=0.0, maximum=3600.0,
        cli="--skip", decimals=1, step=1.0,
        help="seconds of unsteady run-in skipped at each line start "
             "(Qi et al. 2010 skip ≥ 60 s; 0 when the line times already exclude it)")
    weighting: str = param(
        "r", label="Weights", choices=WEIGHTINGS,
        help="weights of the line mean: r = R_max of each line (Qi et al. 2010), "
             "inverse_variance = 1/uncertainty²")
    outlier_k: float = param(
        4.0, label="Outlier limit", unit="σ", minimum=0.0, maximum=100.0, decimals=1,
        step=0.5, metavar=("K",),
        help="lines whose delay departs from the median by more than K robust σ are not "
             "used (0 disables; needs 4 or more lines)")
    lever_arm_m: tuple[float, float, float] | None = param(
        None, label="Lever arm (antenna − motion sensor)", unit="m", minimum=-200.0,
        maximum=200.0, cli="--lever-arm", metavar=("X", "Y", "Z"),
        none_label="vessel sheet (gnss − motion)",
        help="GNSS antenna phase centre relative to the motion sensor, body frame "
             "x forward, y starboard, z down; default: from the vessel sheet")
    screening: str = param(
        "auto", label="Line screening", choices=SCREENINGS, advanced=True,
        help="paper = only Qi et al. 2010's rule (R_max above the threshold); extended = "
             "also drop lines whose σ is not credible or that are outliers; auto = paper "
             "for qi2010, extended for the other estimators (a peak on the scan's edge is "
             "never used)")
    fix_qualities: str = param(
        "auto", label="GNSS fix qualities", advanced=True,
        help="GGA fix qualities used: auto = only RTK fixed (4) when the log has any, else "
             "all with a warning naming them; or a list such as '4,5'")
    heave_filter: str = param(
        "unknown", label="Heave filter", choices=HEAVE_FILTERS,
        help="the motion sensor's heave filter: highpass = a causal high-pass (order and "
             "cut-off period below), whose phase is removed from the heave and whose gain "
             "is applied to the GNSS heights; compensated/none = no phase at wave "
             "periods; unknown = not declared (the delay-model check flags a filter's "
             "phase or says when it cannot exclude one)")
    heave_filter_order: int = param(
        2, label="Heave filter order", minimum=1, maximum=4, advanced=True,
        help="order of the declared high-pass heave filter")
    heave_filter_period_s: float = param(
        20.0, label="Heave filter cut-off period", unit="s", minimum=1.0, maximum=1000.0,
        decimals=1, step=1.0, advanced=True,
        help="cut-off period of the declared high-pass heave filter (sensors: 10-30 s)")
    max_line_sigma_s: float = param(
        0.2, label="Largest credible line σ", unit="s", minimum=0.0, min_exclusive=True,
        maximum=100.0, decimals=3, step=0.05, advanced=True,
        help="a line whose own uncertainty exceeds this, or 10x the median of the selected "
             "lines, is not used (its R peak is too flat to locate); a warning names it")
    min_epochs: int = param(
        30, label="Minimum epochs per line", minimum=5, maximum=1_000_000, advanced=True,
        help="lines with fewer GNSS epochs are not used")
    gap_factor: float = param(
        3.0, label="Gap factor", minimum=1.0, min_exclusive=True, maximum=1000.0,
        advanced=True, decimals=1,
        help="an interval longer than this many median intervals is a data gap")

    @classmethod
    def from_dict(cls, values=None, *, version: int | None = None, strict: bool = True):
        """As :meth:`Params.from_dict`; a *stored* dict (``version`` given) without an
        ``estimator`` comes from a result computed before v1.2: the published one."""
        if version is not None and "estimator" not in (values or {}):
            values = {**(values or {}), "estimator": "qi2010"}
        return super().from_dict(values, version=version, strict=strict)

    def paper_screening(self) -> bool:
        """True when only the paper's line rule applies (:data:`SCREENINGS`)."""
        if self.screening == "auto":
            return self.estimator == "qi2010"
        return self.screening == "paper"

    def validate(self) -> None:
        lo, hi = self.range_s
        if not hi > lo:
            raise InputError(None, f"range maximum must be above minimum, got {lo:g}..{hi:g}",
                             field="range_s")
        parse_qualities(self.fix_qualities)
        if self.step_s > hi - lo:
            raise InputError(None, f"step must be within the range, got {self.step_s:g} s",
                             field="step_s")
        if (hi - lo) / self.step_s > 200_000:
            raise InputError(None, "too many scan candidates (> 200000): use a larger step",
                             field="step_s")
