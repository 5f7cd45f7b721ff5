"""The latency's numbers as the CLI, the panel and the PDF print them (one wording, one
rounding): digits from σ through :mod:`hydrosync_core.numfmt`, never ``"± 0.000"``.

A survey day of 500 lines has σ ≈ 0.5 ms: ``"0.122 ± 0.000 s"`` becomes
``"+122.0 ± 0.5 ms"``; a 1 Hz day with σ ≈ 6 ms reads ``"+288 ± 6.0 ms"``.
"""

from __future__ import annotations

from hydrosync_core import numfmt

LINE_MIN_DECIMALS = 3
"""Per-line Δt and σ (s) keep at least the millisecond (the scan's refinement)."""


def latency_text(latency_s, sigma_s) -> str:
    """Δt with its standard uncertainty, in s or ms as σ reads best (``"+122.0 ± 0.5 ms"``)."""
    return numfmt.quantity(latency_s, sigma_s, "s", sign=True)


def interval_text(low_s, high_s, sigma_s) -> str:
    """The 95 % interval in the unit and to the decimals of :func:`latency_text`."""
    unit, factor = numfmt.scaled(sigma_s, "s")
    s, low, high = numfmt.finite(sigma_s), numfmt.finite(low_s), numfmt.finite(high_s)
    decimals = numfmt.sigma_decimals(s * factor) if s is not None else None
    decimals = 3 if decimals is None else decimals
    if low is None or high is None:
        return numfmt.MISSING
    lo = numfmt.fixed(low * factor, decimals, sign=True)
    hi = numfmt.fixed(high * factor, decimals, sign=True)
    if numfmt.MISSING in (lo, hi):
        return numfmt.MISSING
    return numfmt.with_unit(f"{lo} \u2026 {hi}", unit)


def line_decimals(sigma_s) -> int:
    """Decimals (in s) of one line's Δt and σ: what its σ supports, at least 3."""
    decimals = numfmt.sigma_decimals(sigma_s, min_decimals=LINE_MIN_DECIMALS, max_decimals=6)
    return LINE_MIN_DECIMALS if decimals is None else decimals


def line_cells(latency_s, sigma_s) -> tuple[str, str]:
    """(Δt, σ) of one line in s, both to :func:`line_decimals` (``"—"`` when missing)."""
    d = line_decimals(sigma_s)
    return numfmt.fixed(latency_s, d), numfmt.fixed(sigma_s, d)


def lines_used_text(n_used: int, n_lines: int, min_r: float | None) -> str:
    """``"13 of 13 (R_max > 0.85)"``: the lines the estimate used and the screening
    threshold, as the panel and the PDF summary print them."""
    threshold = f" (R_max > {min_r:g})" if min_r is not None else ""
    return f"{int(n_used)} of {int(n_lines)}{threshold}"
