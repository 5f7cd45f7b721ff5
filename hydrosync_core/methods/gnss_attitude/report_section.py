"""Report section of the GNSS-array attitude (Liu et al.).

Reads ``/results/gnss_attitude`` as :mod:`.project_run` stores it: the screening counts,
the statistics table (scatter and predicted precision per method and angle, as in Liu et
al.'s table 3), the time series of heading, pitch and roll (direct method and least
squares overlaid, like their figs. 6–8), the baseline-length residuals and the predicted
precision versus baseline length (their fig. 15).
"""

from __future__ import annotations

import json

import numpy as np

from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams
from hydrosync_core.methods.gnss_attitude.project_run import RESULT
from hydrosync_core.params import stored
from hydrosync_core.report.context import fmt

HEADING = "Attitude from a GNSS antenna array"
LABELS = {"lsq": "least squares", "direct": "direct (3 antennas)", "wahba": "Wahba (closed form)"}
MAX_POINTS = 1500
ENVELOPE_BINS = 60  # slices of the record in a third-page-wide angle plot
#: Why the measured scatter is not given without a static interval (panel and PDF).
MOVING_REASON = ("the measured scatter of a moving platform is its motion, so only the "
                 "prediction is given; set a static interval (static_start_s/static_end_s) "
                 "on a period when it stood still")


def _thin(n: int) -> np.ndarray:
    return np.arange(0, n, max(1, n // MAX_POINTS))


def summary(project) -> list[tuple[str, str]]:
    """Key results for the report summary and ``hydrosync demo``.

    The scatter is shown only over a static interval (parameters ``static_start_s`` /
    ``static_end_s``); otherwise the angles move and the formal 1σ is given.
    """
    attrs = project.attrs(RESULT)
    counts = json.loads(attrs["counts"])
    stats = json.loads(attrs["statistics"])
    params = stored(GnssAttitudeParams, project, RESULT)
    method = str(attrs.get("method", "lsq"))
    s = stats[method]
    static = params.static_start_s is not None or params.static_end_s is not None
    rows = [("Epochs solved", f"{counts['solved']} of {counts['epochs']}")]
    for a in ("heading", "pitch", "roll"):
        if static:
            rows.append((f"{a.capitalize()} static scatter / predicted ({LABELS[method]})",
                         f"{fmt(s[a]['std'], 4)} / {fmt(s[a]['predicted'], 4)}°"))
        else:
            rows.append((f"{a.capitalize()} formal 1σ, RMS ({LABELS[method]})",
                         f"{fmt(s[a]['predicted'], 4)}°"))
    return rows


def section(project, ctx) -> list:
    attrs = project.attrs(RESULT)
    counts = json.loads(attrs["counts"])
    stats = json.loads(attrs["statistics"])
    params = stored(GnssAttitudeParams, project, RESULT)
    out = [ctx.heading(HEADING)]
    out.append(ctx.para(
        "Heading, pitch and roll from the baselines between the antennas, rotated from ECEF "
        "to the local level frame at the array position: the three-antenna direct method "
        "and the iterative weighted least squares of Liu et al., and the optimal "
        "closed-form (Wahba) rotation as a cross-check. Angles in degrees; heading clockwise "
        "from north, pitch bow up, roll starboard down."))
    out += ctx.key_values(
        [("Antennas", ", ".join(json.loads(attrs["antennas"]))),
         ("Epochs matched / solved", f"{counts['epochs']} / {counts['solved']}"),
         ("Epochs with fewer than 3 usable antennas", str(counts["too_few_antennas"])),
         ("Epochs with an antenna dropped (length check)", str(counts["with_dropped_antenna"])),
         ("Gaps / longest", f"{counts['gaps']} / {fmt(counts['longest_gap_s'], 1)} s")]
        + [(f"Antenna {n}: present / not accepted (Q) / length rejected / used",
            f"{a['present']} / {a['not_accepted_quality']} / {a['length_rejected']} / "
            f"{a['used']}") for n, a in counts["antennas"].items()],
        caption="Epoch screening.")
    static = params.static_start_s is not None or params.static_end_s is not None
    rows = []
    for m, s in stats.items():
        row = [LABELS.get(m, m), str(s["epochs"])]
        for a in ("heading", "pitch", "roll"):
            # Without a static interval the spread is the platform's motion, not precision.
            row += [fmt(s[a]["std"], 4) if static else "\u2014", fmt(s[a]["predicted"], 4)]
        rows.append(row)
    interval = (f"{fmt(params.static_start_s, 1)} … {fmt(params.static_end_s, 1)} s" if static
                else f"no static interval ({MOVING_REASON})")
    out += ctx.table(["Method", "Epochs", "σ heading", "pred.", "σ pitch", "pred.", "σ roll",
                      "pred."], rows, col_widths=[0.22, 0.1] + [0.113] * 6,
                     caption=f"Standard deviation of the angles over {interval} and the "
                     "precision predicted from the position covariance (degrees). Liu et al. "
                     "report 0.066°/0.168°/0.268° (4 antennas, least squares) and "
                     "0.092°/0.216°/0.297° (3 antennas, direct) on a static car.")
    lsq = project.get_table(f"{RESULT}/lsq")
    direct = project.get_table(f"{RESULT}/direct")
    t0 = float(np.nanmin(lsq["time"])) if lsq["time"].size else 0.0
    charts = []
    for a in ("heading", "pitch", "roll"):
        ch = ctx.chart(height=150, fraction=1 / 3, xlabel="time [s]", ylabel=f"{a} [°]")
        # Every epoch, as the range and median of each 1/60 of the record: epoch by
        # epoch the noisy pitch and roll of a long record printed as solid blocks.
        ch.envelope(direct["time"] - t0, direct[a], label=LABELS["direct"],
                    bins=ENVELOPE_BINS)
        ch.envelope(lsq["time"] - t0, lsq[a], label=LABELS["lsq"], bins=ENVELOPE_BINS)
        charts.append(ch)
    out.append(ctx.figure(charts, "Heading, pitch and roll: direct method (three antennas) "
                          "and least squares overlaid (time from the first epoch). Where "
                          f"the record has more than {2 * ENVELOPE_BINS} epochs, each "
                          f"1/{ENVELOPE_BINS} of it is drawn as its median (line) and its "
                          "range (band)."))
    res = project.get_table(f"{RESULT}/baseline_residuals")
    ch = ctx.chart(height=170, xlabel="time [s]", ylabel="length residual [mm]")
    ri = _thin(res["time"].size)
    for pair in [k for k in res if k != "time"]:
        ch.points(res["time"][ri] - t0, 1000 * res[pair][ri], label=pair, size=0.8,
                  marker="square")
    out.append(ctx.figure(ch, "Measured minus known antenna distances; antennas beyond "
                          f"±{1000 * params.length_tolerance_m:g} mm are dropped."))
    curve = project.get_table(f"{RESULT}/precision")
    ch = ctx.chart(height=190, xlabel="longest baseline [m]", ylabel="1σ [°]")
    for a in ("heading", "pitch", "roll"):
        ch.line(curve["baseline_m"], curve[f"lsq_{a}_deg"], label=f"{a} predicted")
        if f"mc_lsq_{a}_deg" in curve:
            ch.points(curve["baseline_m"], curve[f"mc_lsq_{a}_deg"], label=f"{a} simulated")
    out.append(ctx.figure(ch, "Least-squares precision versus baseline length for this "
                          f"layout scaled, with σ = {1000 * params.sigma_horizontal_m:g} mm "
                          f"horizontal and {1000 * params.sigma_vertical_m:g} mm vertical per "
                          "antenna (cf. Liu et al., fig. 15)."))
    out += ctx.params_table(params, "GNSS attitude: processing parameters.", blank={
        "direct_antennas": "automatic: the largest triangle of the antennas present at "
                           "each epoch"})
    return out
