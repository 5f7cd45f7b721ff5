"""Report section of the GNSS/INS smoother (Wang et al.).

Reads ``/results/gins_smoother`` as :mod:`.project_run` stores it: a trajectory map (GNSS
fixes, forward, smoothed), the forward-versus-smoothed error table and the outage drift
table when a reference is stored, position/attitude σ plots and the parameters.
"""

from __future__ import annotations

import json

import numpy as np

from hydrosync_core.methods.gins_smoother.params import RAN, GinsParams
from hydrosync_core.methods.gins_smoother.project_run import GNSS, RESULT
from hydrosync_core.params import stored
from hydrosync_core.report.context import fmt

#: The section heading by whether the run smoothed (``counts["ran"]``): it says what ran.
HEADINGS = {True: "GNSS/INS trajectory with RTS smoothing",
            False: "GNSS/INS trajectory, forward filter only (no smoothing)"}
HEADING = HEADINGS[True]
MAX_POINTS = 1500


def _thin(n: int) -> np.ndarray:
    return np.arange(0, n, max(1, n // MAX_POINTS))


def summary(project) -> list[tuple[str, str]]:
    """Key results for the report summary and ``hydrosync demo``."""
    attrs = project.attrs(RESULT)
    counts = json.loads(attrs["counts"])
    ev = json.loads(attrs["evaluation"])
    rows = [("IMU epochs / GNSS fixes used",
             f"{counts['imu_epochs']} / {counts['gnss_used']} of {counts['gnss_epochs']}")]
    for name in ("forward", "smoothed"):
        if name in ev:
            a = ev[name].get("gnss_on", ev[name]["all"])
            rows.append((f"{name.capitalize()} horizontal RMS / yaw RMS vs reference",
                         f"{fmt(a['horizontal']['rms'] * 100, 2)} cm / "
                         f"{fmt(a['yaw']['rms'], 4)}°"))
            o = ev[name].get("outage")
            if o and o["rms_max_horizontal_m"] is not None:
                rows.append((f"{name.capitalize()} outage drift (max horizontal)",
                             f"{fmt(o['max_horizontal_m'], 3)} m"))
    return rows


#: (components, unit label, scale) of the three error figures.
ERROR_GROUPS = ((("north", "east", "down"), "position", "m", 1.0),
                (("vn", "ve", "vd"), "velocity", "m/s", 1.0),
                (("roll", "pitch", "yaw"), "attitude", "°", 1.0))
COLOR = {"forward": "#c83c28", "smoothed": "#1e5ac8"}


def error_figures(project, ctx, t0: float) -> list:
    """Per-component error against the reference, forward and smoothed, with the ±1σ
    envelope of each solution; simulated outages shaded. Empty without a reference."""
    from hydrosync_core.methods.gins_smoother.project_run import stored_errors

    errs = stored_errors(project)
    if not errs:
        return []
    windows = json.loads(project.attrs(RESULT).get("outages", "[]"))
    out = []
    sols = "forward and smoothed" if "smoothed" in errs else "forward only (no smoothing)"
    for comps, what, unit, scale in ERROR_GROUPS:
        charts = []
        for comp in comps:
            c = ctx.chart(height=130, fraction=1 / 3, xlabel="time [s]",
                          ylabel=f"{comp} error [{unit}]")
            for a, b in windows:
                c.vspan(a - t0, b - t0)
            for name, e in errs.items():
                i = _thin(e["time"].size)
                x = e["time"][i] - t0
                c.line(x, scale * e[comp][i], color=COLOR[name], label=name, width=0.7)
                sd = e.get(f"sd_{comp}")
                if sd is not None:
                    c.line(x, scale * sd[i], color=COLOR[name], width=0.5, dash=(2, 2))
                    c.line(x, -scale * sd[i], color=COLOR[name], width=0.5, dash=(2, 2))
            charts.append(c)
        out.append(ctx.figure(charts, f"{what.capitalize()} error against the reference "
                              f"(solution − reference, {unit}), {sols}; "
                              "dashed: ±1σ of each solution"
                              + ("; shaded: simulated GNSS outages." if windows else ".")))
    return out


#: (component, scale, decimals) of the constant-offset table: m, m/s, degrees.
OFFSET_COLUMNS = (("north", 1, 2), ("east", 1, 2), ("down", 1, 2), ("vn", 1, 3), ("ve", 1, 3),
                  ("vd", 1, 3), ("roll", 1, 2), ("pitch", 1, 2), ("yaw", 1, 2))


def reference_note(project) -> str | None:
    """What the imported recording says its reference is (``raw/gins`` notes), if any."""
    try:
        notes = json.loads(project.attrs("raw/gins").get("notes", "[]"))
    except (TypeError, ValueError, KeyError):
        return None
    return next((n.split(":", 1)[1].strip() for n in notes
                 if isinstance(n, str) and n.startswith("reference:")), None)


def reference_limits(project, ctx, ev: dict) -> list:
    """The reference's own limits and each solution's constant offset from it, with the
    share within 1.96σ as is and with that offset removed."""
    out = [ctx.para("The reference is compared as it is: its own accuracy is not known to "
                    "this analysis, and a reference computed from the same sensors is not "
                    "an independent truth. A constant offset (below) is the reference's own "
                    "axes or point — e.g. a camera whose mounting on the IMU is not given — "
                    "which no σ of this solution can know about.")]
    note = reference_note(project)
    if note:
        out.append(ctx.para(f"Reference: {note}."))
    rows = []
    for name in ("forward", "smoothed"):
        off = ev.get(name, {}).get("constant_offset")
        cov = ev.get(name, {}).get("coverage", {})
        c, c0 = cov.get("all", {}), cov.get("offset_removed", {})
        if not off or not c0:
            continue
        rows.append([f"{name} offset"] + [fmt(off[k] * f, d) for k, f, d in OFFSET_COLUMNS])
        rows.append([f"{name} within 1.96σ %"] + [
            f"{100 * c[k]['within_95']:.0f}/{100 * c0[k]['within_95']:.0f}"
            if c.get(k) and c0.get(k) else "—" for k, _f, _d in OFFSET_COLUMNS])
    if rows:
        out += ctx.table(["Solution", "N m", "E m", "D m", "vN m/s", "vE", "vD", "roll °",
                          "pitch °", "yaw °"], rows,
                         col_widths=[0.19] + [0.09] * 9,
                         caption="Constant offset from the reference (mean of solution − "
                         "reference) and the share of epochs within 1.96σ, as is / with "
                         "that offset removed.")
    return out


def section(project, ctx) -> list:
    attrs = project.attrs(RESULT)
    counts = json.loads(attrs["counts"])
    smoothed = counts.get("ran", RAN[True]) == RAN[True]
    ev = json.loads(attrs["evaluation"])
    align = json.loads(attrs["alignment"])
    params = stored(GinsParams, project, RESULT)
    out = [ctx.heading(HEADINGS[smoothed])]
    out.append(ctx.para(
        "Loosely coupled GNSS/INS integration after Wang et al.: strapdown mechanisation in "
        "the local-level frame (earth rate, transport rate, normal gravity, coning and "
        "sculling), an error-state Kalman filter with "
        f"{counts['states']} states, GNSS position updates with the antenna lever arm, "
        "optional non-holonomic and zero-velocity constraints, closed-loop feedback"
        + (", and a Rauch-Tung-Striebel smoother on the total state" if smoothed else
           " (no smoothing in this run)") + ". Angles in degrees, NED metres."))
    out += ctx.key_values(
        [("IMU epochs", str(counts["imu_epochs"])),
         ("GNSS fixes in span / used", f"{counts['gnss_epochs']} / {counts['gnss_used']}"),
         ("What ran", counts.get("ran", RAN[True])),
         ("Smoother nodes" if smoothed else "Filter nodes", str(counts["nodes"])),
         ("Alignment", str(align.get("method"))),
         ("Noise model (what the σ are computed from)",
          json.loads(attrs.get("gnss_model", "{}")).get("summary", "not recorded"))],
        caption="Processing summary.")
    fwd = project.get_table(f"{RESULT}/forward")
    smo = project.get_table(f"{RESULT}/smoothed") if project.exists(f"{RESULT}/smoothed") \
        else None
    g = project.get_table(GNSS)
    lat0, lon0 = float(fwd["lat"][0]), float(fwd["lon"][0])
    k_e = 111320.0 * np.cos(np.radians(lat0))

    def en(tab):
        return (np.asarray(tab["lon"]) - lon0) * k_e, (np.asarray(tab["lat"]) - lat0) * 110540.0

    ch = ctx.chart(height=220, xlabel="east [m]", ylabel="north [m]")
    e, n = en(g)
    gi = _thin(e.size)
    ch.points(e[gi], n[gi], label="GNSS", size=1.0)
    idx = _thin(fwd["time"].size)
    e, n = en(fwd)
    ch.line(e[idx], n[idx], label="forward")
    if smo is not None:
        e, n = en(smo)
        ch.line(e[idx], n[idx], label="smoothed")
    sols = "forward and smoothed" if smo is not None else "forward (no smoothing)"
    out.append(ctx.figure(ch, f"Trajectory: GNSS antenna fixes, {sols} IMU positions (local "
                          "east/north from the start)."))
    t0 = float(fwd["time"][0])
    charts = []
    for key, label, scale in (("sd_n", "σ north [cm]", 100), ("sd_d", "σ down [cm]", 100),
                              ("sd_yaw", "σ yaw [°]", 1)):
        c = ctx.chart(height=140, fraction=1 / 3, xlabel="time [s]", ylabel=label)
        c.line(fwd["time"][idx] - t0, scale * fwd[key][idx], label="forward")
        if smo is not None:
            c.line(smo["time"][idx] - t0, scale * smo[key][idx], label="smoothed")
        charts.append(c)
    out.append(ctx.figure(charts, "Standard deviations, forward and smoothed (the smoother "
                          "reduces them everywhere, most across GNSS outages)."
                          if smo is not None else "Standard deviations of the forward "
                          "filter (no smoothing in this run)."))
    out += error_figures(project, ctx, t0)
    if ev:
        rows = []
        for name in ("forward", "smoothed"):
            if name not in ev:
                continue
            a = ev[name].get("gnss_on", ev[name]["all"])
            rows.append([name] + [fmt(a[k]["rms"] * 1000, 1) for k in ("north", "east", "down")]
                        + [fmt(a[k]["rms"] * 1000, 2) for k in ("vn", "ve", "vd")]
                        + [fmt(a[k]["rms"], 4) for k in ("roll", "pitch", "yaw")])
        out += ctx.table(["Solution", "N mm", "E mm", "D mm", "vN mm/s", "vE", "vD", "roll °",
                          "pitch °", "yaw °"], rows,
                         col_widths=[0.14] + [0.086] * 3 + [0.09] * 3 + [0.1] * 3,
                         caption="RMS error against the reference (epochs with GNSS).")
        out += reference_limits(project, ctx, ev)
        orow = []
        for name in ("forward", "smoothed"):
            o = ev.get(name, {}).get("outage")
            if not o:
                continue
            for i, w in enumerate(o["outages"]):
                if len(orow) < 40:
                    orow.append([name, str(i + 1), f"{w['end'] - w['start']:.0f} s",
                                 fmt(w["max_horizontal_m"], 3), fmt(w["max_vertical_m"], 3)])
        if orow:
            out += ctx.table(["Solution", "Outage", "Length", "max horizontal m",
                              "max vertical m"], orow, col_widths=[0.2, 0.15, 0.15, 0.25, 0.25],
                             caption="Drift across simulated GNSS outages.")
    else:
        out.append(ctx.para("No reference trajectory stored: no error statistics."))
    out += ctx.params_table(params, "GNSS/INS smoother: processing parameters.")
    return out
