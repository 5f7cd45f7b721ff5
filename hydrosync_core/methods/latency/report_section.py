"""Report section of the latency module (seed 000: correlative approximation).

Reads ``/results/latency`` as :mod:`hydrosync_core.methods.latency.project_run` stores it
(group attributes with the final values, table ``lines``, arrays ``dt_grid`` and
``r_curves``) and the raw ``raw/gnss`` / ``raw/attitude`` tables for the before/after
plots. Content: final value with uncertainty and 95 % interval, the per-line table in the
style of the seed's tables 1 and 2, the R–Δt curves, and the detrended GNSS height against
the total heave before and after synchronisation for the best and the worst used line.
"""

from __future__ import annotations

import json

import numpy as np
from reportlab.platypus import Flowable, Paragraph

from hydrosync_core.methods.latency.params import LatencyParams, estimator_label
from hydrosync_core.methods.latency.texts import (
    interval_text,
    latency_text,
    line_cells,
    lines_used_text,
)
from hydrosync_core.params import stored
from hydrosync_core.report.context import ReportContext, esc, fmt, utc_text
from hydrosync_core.report.styles import INK, MUTED, SERIES

RESULT = "results/latency"
HEADING = "Latency between GNSS heights and attitude"

# Decimals of each printed quantity (tests format the stored values the same way).
# Δt to the millisecond (sub-step refinement), R to 4 decimals (seed table 1), σ0 in
# metres to the millimetre (seed table 2).
DT_DECIMALS = 3
R_DECIMALS = 4
SIGMA0_DECIMALS = 3
EXCERPT_S = 60.0


def _json_attr(attrs: dict, key: str, default):
    value = attrs.get(key)
    if value is None:
        return default
    try:
        return json.loads(value) if isinstance(value, str) else value
    except ValueError:
        return default


def final_value_text(attrs: dict) -> str:
    """``"+288 ± 6.0 ms"`` — final Δt and its standard uncertainty (:mod:`.texts`)."""
    return latency_text(attrs.get("latency_s"), attrs.get("uncertainty_s"))


def ci_text(attrs: dict) -> str:
    """``"+276 … +300 ms"`` — the 95 % interval of the final Δt (:mod:`.texts`)."""
    return interval_text(attrs.get("ci95_low"), attrs.get("ci95_high"),
                         attrs.get("uncertainty_s"))


def estimator_text(attrs: dict) -> str:
    """Which estimator produced the final Δt (results before v1.2: the published one)."""
    return estimator_label(attrs.get("estimator", "qi2010"))


def line_row(table: dict, i: int) -> list[str]:
    """Formatted cells of line *i*: name, epochs, R_max, Δt, σΔt, σ0 before, σ0 after, used."""
    return [
        str(table["name"][i]),
        str(int(table["epochs"][i])),
        fmt(table["r_max"][i], R_DECIMALS),
        *line_cells(table["latency_s"][i], table["uncertainty_s"][i]),
        fmt(table["sigma0_before_m"][i], SIGMA0_DECIMALS),
        fmt(table["sigma0_after_m"][i], SIGMA0_DECIMALS),
        "yes" if bool(table["used"][i]) else "no",
    ]


def summary(project) -> list[tuple[str, str]]:
    """Rows of the report's summary table (and of ``hydrosync demo``'s printout)."""
    attrs = project.attrs(RESULT)
    table = project.get_table(f"{RESULT}/lines")
    params = stored(LatencyParams, project, RESULT)
    n = len(table["name"])
    rows = [("Latency \u0394t (GNSS tags late), 1\u03c3", final_value_text(attrs)),
            ("95 % interval of \u0394t", ci_text(attrs)),
            ("Latency estimator", estimator_text(attrs)),
            ("Lines used", lines_used_text(attrs.get("n_used", 0), n, params.min_r))]
    used = np.asarray(table["used"], bool)
    if used.any():
        before = np.nanmedian(np.asarray(table["sigma0_before_m"], float)[used])
        after = np.nanmedian(np.asarray(table["sigma0_after_m"], float)[used])
        rows.append(("\u03c3\u2080 before \u2192 after (median of used lines)",
                     f"{fmt(before, SIGMA0_DECIMALS)} \u2192 {fmt(after, SIGMA0_DECIMALS)} m"))
    # Import warnings change what the numbers mean: on the summary, not only in the section.
    for warning in _json_attr(attrs, "warnings", []):
        if str(warning).startswith("/raw/"):
            rows.append(("Caveat", str(warning)))
    return rows


def section(project, ctx: ReportContext) -> list[Flowable]:
    """The latency section's flowables."""
    attrs = project.attrs(RESULT)
    params = stored(LatencyParams, project, RESULT)
    table = project.get_table(f"{RESULT}/lines")
    warnings = _json_attr(attrs, "warnings", [])
    arm = _json_attr(attrs, "lever_arm_m", params.lever_arm_m or [np.nan] * 3)
    out: list[Flowable] = [
        ctx.heading(HEADING),
        ctx.para(
            "Method: correlative approximation (Qi et al. 2010). Per survey line the GNSS "
            "antenna heights are detrended (eq. 1), the total heave at the antenna is formed "
            "from heave, roll and pitch with the lever arm (eq. 2) and interpolated at the "
            "corrected GNSS times (eq. 3), and the correlation R (eq. 4) is scanned over "
            "\u0394t. Lines with R<sub>max</sub> above the threshold are combined by a "
            "weighted mean. \u0394t is how late the GNSS time tags are relative to the "
            "attitude time tags: synchronised heights use <i>tag \u2212 \u0394t</i>."
            + _estimator_note(attrs)),
    ]
    pairs = [
        ("Final latency \u0394t (1\u03c3)", final_value_text(attrs)),
        ("Estimator", estimator_text(attrs)),
        ("95 % interval", ci_text(attrs)),
        ("Joint estimate (all used lines at once)",
         fmt(attrs.get("joint_latency_s"), DT_DECIMALS, "s")),
        ("Lines used", f"{int(attrs.get('n_used', 0))} of {len(table['name'])}, weights: "
                       + {"r": "peak correlation R", "inverse_variance": "1/\u03c3\u00b2"}.get(
                           str(attrs.get("weighting")), str(attrs.get("weighting")))),
        ("Outcome", str(attrs.get("message", ""))),
        ("Lever arm GNSS antenna \u2212 motion sensor (x fwd, y stbd, z down)",
         " / ".join(fmt(v, 3) for v in arm) + " m"),
        ("Computed", f"{utc_text(attrs.get('run_utc'))} with HydroSync "
                     f"{attrs.get('software_version', '?')}"),
    ]
    out += ctx.key_values(pairs, caption="Latency: final result.", key_width=0.45)
    out += ctx.params_table(params, "Latency: processing parameters (lever arm "
                            "\u201cvessel sheet\u201d: the value above was taken from it).")
    for text in warnings:
        out.append(ctx.warning(text))
    out += _line_table(ctx, table, attrs)
    out += _curves_figure(project, ctx, table, attrs)
    out += _before_after_figures(project, ctx, table, attrs, params, arm)
    return out


def _estimator_note(attrs: dict) -> str:
    name = str(attrs.get("estimator", "qi2010"))
    if name == "qi2010":
        return " Estimator: the published one (raw series), as in Qi et al. (2010)."
    text = (" Estimator: <b>" + esc(name) + "</b>, beyond the publication: the high-rate "
            "total heave is low-passed to the GNSS band (zero-phase) before eq. 3")
    if name == "weighted":
        text += (", and both series are weighted per frequency by their coherence pooled "
                 "over the day's lines (maximum-likelihood generalised cross-correlation, "
                 "Knapp and Carter 1976); R<sub>max</sub> and the curves are the "
                 "anti-aliased correlation, \u0394t and \u03c3 come from the weighted one")
    return text + ". The published estimator stays available (parameter <i>estimator</i> = "\
        "qi2010)."


def _line_table(ctx: ReportContext, table: dict, attrs: dict) -> list[Flowable]:
    rows = [line_row(table, i) for i in range(len(table["name"]))]
    rows.append(["Weighted mean", "", "",
                 *line_cells(attrs.get("latency_s"), attrs.get("uncertainty_s")), "", "", ""])
    header = ["Line", "Epochs", "R<sub>max</sub>", "\u0394t [s]", "\u03c3<sub>\u0394t</sub> [s]",
              "\u03c3<sub>0</sub> before [m]", "\u03c3<sub>0</sub> after [m]", "Used"]
    not_used = [i + 1 for i in range(len(table["name"])) if not bool(table["used"][i])]
    style = [("TEXTCOLOR", (0, r), (-1, r), MUTED) for r in not_used]
    return ctx.table(
        header, rows, col_widths=[0.16, 0.1, 0.11, 0.11, 0.11, 0.15, 0.15, 0.11],
        highlight_rows=[len(rows) - 1], extra_style=style,
        caption="Per-line results (as tables 1 and 2 of Qi et al. 2010): maximum correlation "
        "R<sub>max</sub>, the "
        "latency at the peak \u0394t with its uncertainty \u03c3\u0394t (from the peak "
        "curvature), and the standard error \u03c3<sub>0</sub> of height minus total heave "
        "(eqs. 5\u20136) before (\u0394t = 0) and after synchronisation with the final "
        "\u0394t. Lines not used are greyed.")


FIGURE_POINTS = 400
"""Points per R curve drawn in a figure (the stored curves keep every candidate): a survey
day's 500 curves of 2001 candidates made a 10.9 MB PDF that took 13 s to write, for lines
that are smooth at the figure's scale."""


def _drawn(count: int) -> np.ndarray:
    """Indices of the candidates drawn of a curve of *count*: evenly spread, with the last."""
    step = max(1, -(-count // FIGURE_POINTS))
    index = np.arange(0, count, step)
    return index if index.size == 0 or index[-1] == count - 1 else np.append(index, count - 1)


MANY_CURVES = 40
"""Above this many lines of one kind (used / not used) a figure draws their range and
median instead of one curve each: 500 curves printed as a solid block (#26)."""


def _draw_lines(chart, x, curves, rows, *, color, label: str, dash=None,
                width: float = 0.6) -> bool:
    """The R curves of *rows* on *chart*: one line each, or, above :data:`MANY_CURVES`,
    their min–max band and median. True when drawn as a band."""
    if rows.size == 0:
        return False
    if rows.size <= MANY_CURVES:
        for n, i in enumerate(rows):
            chart.line(x, curves[i], color=color, width=width, dash=dash,
                       label=label if n == 0 else None)
        return False
    block = curves[rows]
    with np.errstate(all="ignore"):
        chart.band(x, np.nanmin(block, axis=0), np.nanmax(block, axis=0), color=color,
                   label=f"{label}: range of {rows.size}")
        chart.line(x, np.nanmedian(block, axis=0), color=color, width=1.0, dash=dash,
                   label=f"{label}: median")
    return True


def _curves_figure(project, ctx: ReportContext, table: dict, attrs: dict) -> list[Flowable]:
    if not (project.exists(f"{RESULT}/dt_grid") and project.exists(f"{RESULT}/r_curves")):
        return []
    dts = np.asarray(project.get(f"{RESULT}/dt_grid"), float)
    curves = np.atleast_2d(np.asarray(project.get(f"{RESULT}/r_curves"), float))
    used = np.asarray(table["used"], bool)
    chart = ctx.chart(height=230, xlabel="\u0394t, GNSS tags late relative to attitude [s]",
                      ylabel="correlation R")
    lat = attrs.get("latency_s")
    lo, hi = attrs.get("ci95_low"), attrs.get("ci95_high")
    if lo is not None and hi is not None and np.isfinite(lo) and np.isfinite(hi):
        chart.vspan(lo, hi, color="#cfe0f0", label="95 % interval")
    k = _drawn(dts.size)
    banded = _draw_lines(chart, dts[k], curves[:, k], np.flatnonzero(~used), color="#b0b0b0",
                         label="line not used", dash=(2, 2))
    banded |= _draw_lines(chart, dts[k], curves[:, k], np.flatnonzero(used), color=SERIES[0],
                          label="line used")
    if lat is not None and np.isfinite(lat):
        chart.vline(lat, color=INK, dash=None, width=1.0,
                    label=f"final \u0394t = {fmt(lat, DT_DECIMALS)} s")
    chart.vline(0.0, color=MUTED, dash=(1, 2), width=0.6)
    per_line = ("the range over the lines (band) and their median (line)" if banded
                else "one curve per line")
    out = [ctx.figure(chart, "Correlation R between detrended GNSS height and total heave "
                      f"as a function of the trial latency \u0394t, {per_line} (eq. 4) "
                      "over the whole scan range.")]
    if lat is not None and np.isfinite(lat):
        out.append(_peak_zoom(ctx, dts, curves, table, attrs))
    return out


def _peak_zoom(ctx: ReportContext, dts, curves, table, attrs) -> Flowable:
    """The curves near the final Δt with every line's peak marked."""
    lat = float(attrs["latency_s"])
    peaks = np.asarray(table["latency_s"], float)
    r_max = np.asarray(table["r_max"], float)
    used = np.asarray(table["used"], bool)
    finite = np.isfinite(peaks)
    half = max(0.1, 1.3 * float(np.nanmax(np.abs(peaks[finite] - lat))) if finite.any() else 0.1)
    half = min(half, float(dts[-1] - dts[0]) / 2)
    window = (dts >= lat - half) & (dts <= lat + half)
    chart = ctx.chart(height=210, xlabel="\u0394t [s]", ylabel="correlation R",
                      xlim=(lat - half, lat + half))
    lo, hi = attrs.get("ci95_low"), attrs.get("ci95_high")
    if lo is not None and hi is not None and np.isfinite(lo) and np.isfinite(hi):
        chart.vspan(lo, hi, color="#cfe0f0", label="95 % interval")
    inside = np.flatnonzero(window)
    k = inside[_drawn(inside.size)]
    _draw_lines(chart, dts[k], curves[:, k], np.flatnonzero(~used), color="#b0b0b0",
                label="line not used", dash=(2, 2), width=0.5)
    _draw_lines(chart, dts[k], curves[:, k], np.flatnonzero(used), color=SERIES[0],
                label="line used", width=0.5)
    chart.points(peaks[used & finite], r_max[used & finite], color=SERIES[0], size=2.2,
                 label="peak of a used line")
    if np.any(~used & finite):
        chart.points(peaks[~used & finite], r_max[~used & finite], color="#909090", size=2.2,
                     label="peak of a line not used")
    chart.vline(lat, color=INK, dash=None, width=1.0, label=f"final \u0394t = {fmt(lat, 3)} s")
    return ctx.figure(chart, "Detail of the correlation peaks: each dot is one line's "
                      "(\u0394t, R<sub>max</sub>), the vertical line the weighted mean and the "
                      "band its 95 % interval.")


def _before_after_figures(project, ctx, table, attrs, params, arm) -> list[Flowable]:
    """Seed fig. 4 for the best and the worst used line (highest / lowest R_max)."""
    from hydrosync_core.methods.latency.series import line_series

    lat = attrs.get("latency_s")
    used = np.flatnonzero(np.asarray(table["used"], bool))
    if used.size == 0 or lat is None or not np.isfinite(lat):
        return []
    if not (project.exists("raw/gnss") and project.exists("raw/attitude")):
        return [ctx.para("The raw GNSS and attitude tables are no longer in the project; "
                         "the before/after plots are omitted.")]
    gnss, attitude = project.get_table("raw/gnss"), project.get_table("raw/attitude")
    r = np.asarray(table["r_max"], float)[used]
    picks = [("best", used[int(np.nanargmax(r))])]
    if used.size > 1:
        picks.append(("worst", used[int(np.nanargmin(r))]))
    out: list[Flowable] = [Paragraph("Before and after synchronisation", ctx.styles["H2"])]
    for label, i in picks:
        series = line_series(gnss, attitude, arm, float(table["start"][i]),
                             float(table["end"][i]), float(lat), params)
        if series["time"].size < 3:
            continue
        t = series["time"] - series["time"][0]
        # A 60-s excerpt from the middle of the line: a 0.3-s shift is invisible at the
        # scale of a whole line (the seed's fig. 4 also shows a local excerpt).
        mid = 0.5 * (t[0] + t[-1])
        keep = (t >= mid - EXCERPT_S / 2) & (t <= mid + EXCERPT_S / 2)
        t = t[keep]
        h, before, after = (series[k][keep] for k in ("height", "heave_before", "heave_after"))
        # Compare shapes as Qi et al. do (eq. 5): both curves about their means; heights
        # and heave are in metres throughout the report.
        hc, bc, ac = (v - np.mean(v) for v in (h, before, after))
        chart = ctx.chart(height=190, xlabel="time since line start [s]",
                          ylabel="height change [m]")
        chart.line(t, hc, color=INK, width=1.1, label="GNSS height, detrended")
        chart.line(t, bc, color=SERIES[1], width=0.8, dash=(3, 2),
                   label="total heave before (\u0394t = 0)")
        chart.line(t, ac, color=SERIES[0], width=0.9,
                   label=f"total heave after (\u0394t = {fmt(lat, DT_DECIMALS)} s)")
        name = esc(table["name"][i])
        out.append(ctx.figure(chart, (
            f"Line {name}, the {label} used line "
            f"(R<sub>max</sub> = {fmt(table['r_max'][i], R_DECIMALS)}): "
            f"\u03c3<sub>0</sub> {fmt(table['sigma0_before_m'][i], SIGMA0_DECIMALS)} m before, "
            f"{fmt(table['sigma0_after_m'][i], SIGMA0_DECIMALS)} m after synchronisation "
            f"over the whole line; a {EXCERPT_S:.0f}-s excerpt from its middle (as fig. 4 of "
            "Qi et al. 2010).")))
    return out
