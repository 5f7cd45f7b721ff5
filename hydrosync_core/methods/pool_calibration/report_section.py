"""Report section of the pool calibration (seed 003 and the joint adjustment).

Reads ``/results/pool_calibration`` as :mod:`hydrosync_core.methods.pool_calibration.project_run`
stores it: group attributes with the final values and their 1-σ, the JSON of
``PoolResult.to_dict()`` on ``result``, tables ``faces`` and ``iterations``, and the
decimated clouds under ``plan``; plus ``raw/pool/target`` for the design outlines.
Content: final parameters beside the coarse values and both solutions, the face table,
the joint adjustment's statistics and correlations, the seed iteration table with its
convergence, and plan and elevation views of the segmented clouds.
"""

from __future__ import annotations

import json

import numpy as np
from reportlab.lib.styles import ParagraphStyle
from reportlab.platypus import Flowable, Paragraph

from hydrosync_core.methods.pool_calibration.params import PoolParams
from hydrosync_core.methods.pool_calibration.report_figures import plan_figures
from hydrosync_core.methods.pool_calibration.result import (
    ANGLE_DECIMALS,
    LEVER_DECIMALS,
    parameter_text,
)
from hydrosync_core.numfmt import sigma_decimals
from hydrosync_core.params import stored
from hydrosync_core.report.context import ReportContext, esc, fmt, utc_text
from hydrosync_core.report.styles import BAD_TEXT, SERIES

RESULT = "results/pool_calibration"
HEADING = "Pool calibration of multibeam boresight and lever arm"


ANGLES = (("roll", "Boresight roll", "\u00b0"), ("pitch", "Boresight pitch", "\u00b0"),
          ("yaw", "Boresight yaw", "\u00b0"))
LEVERS = (("x", "Lever arm x (forward)", "m"), ("y", "Lever arm y (starboard)", "m"),
          ("z", "Lever arm z (down)", "m"))


def _result(project) -> dict:
    return project.get_json(f"{RESULT}/result", {}) or {}


def parameter_rows(attrs: dict) -> list[tuple[str, str]]:
    """``(name, "value ± σ unit")`` of the six final parameters, as printed everywhere."""
    rows = []
    for key, label, unit in ANGLES:
        rows.append((label, parameter_text(attrs.get(f"{key}_deg"),
                                           attrs.get(f"sigma_{key}_deg"), unit)))
    for key, label, unit in LEVERS:
        rows.append((label, parameter_text(attrs.get(f"lever_{key}_m"),
                                           attrs.get(f"sigma_lever_{key}_m"), unit)))
    return rows


def summary(project) -> list[tuple[str, str]]:
    """Rows of the report's summary table (and of ``hydrosync demo``'s printout)."""
    attrs = project.attrs(RESULT)
    method = {"joint": "joint adjustment", "seed": "patent iteration"}.get(
        str(attrs.get("method")), str(attrs.get("method")))
    state = "converged" if attrs.get("converged") else "NOT converged"
    rows = [(f"{label} (final, 1\u03c3)", value) for label, value in parameter_rows(attrs)] + [
        ("Final values from", f"{method}, {state}")]
    # Caveats that change what the σ mean: on the summary page, not only in the section.
    params = stored(PoolParams, project, RESULT)
    if params is not None and not any(params.ins_sigma_deg):
        rows.append(("Caveat", "INS attitude taken as exact (no INS accuracy given): the "
                               "\u03c3 are a lower bound"))
    undetermined = json.loads(attrs.get("undetermined") or "{}")
    if undetermined:
        rows.append(("Caveat", "not determined by the data (coarse values kept): "
                               + ", ".join(sorted(undetermined))))
    return rows


def flags(project) -> dict[str, str]:
    """Summary rows the panel flags, with why: a σ beyond its threshold (``flagged``) or a
    parameter the data do not determine (``undetermined``); the PDF marks them the same."""
    res = _result(project)
    flagged = res.get("flagged") or {}
    undetermined = res.get("undetermined") or {}
    out = {}
    names = [(key, label) for key, label, _ in ANGLES] + \
        [(f"lever_{key}", label) for key, label, _ in LEVERS]
    for name, label in names:
        reason = flagged.get(name) or (
            f"not determined by the data ({undetermined[name]}); the coarse value is kept"
            if name in undetermined else "")
        if reason:
            out[f"{label} (final, 1\u03c3)"] = str(reason)
    return out


def section(project, ctx: ReportContext) -> list[Flowable]:
    """The pool calibration section's flowables."""
    attrs = project.attrs(RESULT)
    res = _result(project)
    out: list[Flowable] = [
        ctx.heading(HEADING),
        ctx.para(
            "Method: pool calibration against a laser-scanned target (patent CN 105425246 B). "
            "Both point clouds are segmented into the design faces of the target; planes are "
            "fitted by total least squares. The patent method iterates the boresight angles from "
            "the angles between multibeam and laser plane normals (roll from the wall, pitch and "
            "yaw from the oblique faces), then derives the lever arm offsets (x from the wall, y "
            "from the oblique faces, z from the horizontal faces). The joint adjustment estimates"
            " all six parameters at once by minimising the point-to-plane distances of the "
            "multibeam soundings to the laser planes, with their covariance. Angles follow "
            "setup.json: R<sub>m</sub> = Rz(yaw)\u00b7Ry(pitch)\u00b7Rx(roll); "
            "the lever arm is in the body frame (x forward, y starboard, z down)."),
    ]
    out += _parameter_table(ctx, attrs, res)
    out += _budget_table(ctx, res)
    params = stored(PoolParams, project, RESULT)
    out += _run_info(ctx, attrs, res, params)
    for text in json.loads(attrs.get("warnings") or "[]"):
        out.append(ctx.warning(text))
    out += _face_table(project, ctx, res)
    out += _twin_table(project, ctx)
    out += _joint_tables(ctx, res)
    out += plan_figures(project, ctx)
    out += _iterations(project, ctx)
    out += ctx.params_table(params, "Pool calibration: processing parameters.")
    return out


def _parameter_table(ctx, attrs, res) -> list[Flowable]:
    coarse = res.get("coarse", {})
    seed = res.get("seed") or {}
    joint = res.get("joint") or {}
    undetermined = res.get("undetermined") or {}
    flagged = res.get("flagged") or {}
    rows, style = [], []
    for i, (key, label, unit) in enumerate(ANGLES + LEVERS):
        group, sig_group = (("boresight_deg", "sigma_boresight_deg") if unit == "\u00b0"
                            else ("lever_arm_m", "sigma_lever_arm_m"))
        final_key = f"{key}_deg" if unit == "\u00b0" else f"lever_{key}_m"
        name = key if unit == "\u00b0" else f"lever_{key}"
        # Every number of the row to the digits the final σ supports (as the panel, CLI).
        dec = sigma_decimals(attrs.get(f"sigma_{final_key}")) or (
            ANGLE_DECIMALS if unit == "\u00b0" else LEVER_DECIMALS)
        c = coarse.get(group, {}).get(key)
        final = attrs.get(final_key)
        status = ("undetermined (coarse kept)" if name in undetermined else
                  "contradicts the setup" if name in (res.get("contradicted") or {}) else
                  "\u03c3 above threshold" if name in flagged else "determined")
        if name in undetermined or name in flagged:
            style.append(("TEXTCOLOR", (6, i + 1), (6, i + 1), BAD_TEXT))
        rows.append([
            f"{label} [{unit}]", fmt(c, dec), fmt(seed.get(group, {}).get(key), dec),
            parameter_text(joint.get(group, {}).get(key), joint.get(sig_group, {}).get(key),
                           ""),
            fmt(final, dec),
            fmt(None if c is None or final is None else final - c, dec), status])
    method = str(attrs.get("method", "?"))
    out = ctx.table(
        ["Parameter", "Coarse (setup)", "Patent method", "Joint adjustment \u00b1 1\u03c3",
         f"Final ({method})", "Correction (final \u2212 coarse)", "Status"], rows,
        col_widths=[0.25, 0.1, 0.09, 0.18, 0.1, 0.12, 0.16], extra_style=style,
        caption="Boresight angles and lever arm: the coarse values of the installation "
        "drawing, the patent method's and the joint adjustment's solutions, and the final "
        "values to enter in the acquisition software. An undetermined parameter keeps its "
        "coarse value (no \u03c3); a parameter whose \u03c3 exceeds the warning threshold is "
        "flagged.")
    return out


#: σ-budget sources as the report names them, in column order.
BUDGET_SOURCES = (("data", "Soundings (data)"), ("build", "Build tolerance"),
                  ("reference", "Laser planes"), ("ins", "INS attitude"),
                  ("held", "Held parameters"))


def _budget_table(ctx, res) -> list[Flowable]:
    """Where each parameter's σ comes from: one column per source, and the total."""
    joint = res.get("joint") or {}
    budget = joint.get("sigma_budget") or {}
    if not budget:
        return []
    sources = [(k, label) for k, label in BUDGET_SOURCES if k in budget]
    rows, style = [], []
    for i, (key, label, unit) in enumerate(ANGLES + LEVERS):
        name = key if unit == "\u00b0" else f"lever_{key}"
        scale, dec, shown = (1.0, 4, "\u00b0") if unit == "\u00b0" else (1000.0, 2, "mm")
        values = [budget[k].get(name) for k, _ in sources]
        if all(v is None for v in values):
            rows.append([f"{label} [{shown}]"] + ["\u2014"] * (len(sources) + 1))
            continue
        total = float(np.sqrt(sum(v * v for v in values if v is not None)))
        rows.append([f"{label} [{shown}]"] + [fmt(None if v is None else v * scale, dec)
                                                for v in values] + [fmt(total * scale, dec)])
        top = int(np.nanargmax([np.nan if v is None else v for v in values]))
        style.append(("FONTNAME", (top + 1, i + 1), (top + 1, i + 1), "Helvetica-Bold"))
    return ctx.table(
        ["Parameter", *(label for _, label in sources), "Total \u03c3"], rows,
        col_widths=[0.22] + [0.65 / len(sources)] * len(sources) + [0.13], numeric_from=1,
        extra_style=style,
        caption="\u03c3 budget of the joint adjustment: the 1\u03c3 each source alone gives "
        "each parameter (their squares add up to the total; the largest in bold). Soundings: "
        "more passes, slower, at other ranges and on lines crossing the wall at about ±15°; "
        "build tolerance: survey the as-built "
        "below-water blocks; laser planes: a denser scan of the above-water faces; INS: a "
        "more accurate INS; held parameters: the coarse error of undetermined ones.")


def _twin_table(project, ctx) -> list[Flowable]:
    """Below-water faces compared with their above-water twin's laser plane, moved."""
    if not project.exists(f"{RESULT}/faces"):
        return []
    t = project.get_table(f"{RESULT}/faces")
    if "reference" not in t:
        return []
    rows = []
    small = ParagraphStyle("Pairing", parent=ctx.styles["Cell"], fontSize=7.5, leading=9)
    pairing = t.get("pairing")
    for i, name in enumerate(t["face"]):
        if str(t["water"][i]) == "above":
            continue
        ref = str(t["reference"][i])
        offs = [float(t[f"twin_d{a}_m"][i]) for a in "enu"]
        how = str(pairing[i]) if pairing is not None else (
            "own laser plane" if ref == "own" else ref or "\u2014")
        rows.append([Paragraph(esc(str(name)), small), Paragraph(esc(how), small),
                     *(fmt(v, 3) for v in offs), str(int(t["points_mbes"][i])),
                     Paragraph(esc(str(t["used_for"][i]).replace(",", ", ") or "\u2014"),
                               small)])
    if not rows:
        return []
    return [ctx.heading("Face pairing and reference planes", 2)] + ctx.table(
        ["Face (multibeam)", "Pairing (rule, twin) or why none", "\u0394E [m]", "\u0394N [m]",
         "\u0394U [m]", "MBES pts", "Carries"], rows,
        col_widths=[0.2, 0.3, 0.075, 0.075, 0.075, 0.075, 0.2], numeric_from=2,
        left_columns=[6], font_size=7.5,
        caption="Reference plane of each face the multibeam may see: a face that crosses the "
        "water is compared with its own laser plane; a below-water face with the laser plane "
        "of its above-water twin, found by plane (parallel outward normals, overlapping "
        "footprints in plan: coplanar, or a parallel offset such as the tops' design height "
        "difference) or declared in target.json, moved by the design translation \u0394 "
        "(known to the build tolerance, propagated into \u03c3). Undersides and faces turned "
        "away from the vessel are never references. 'Carries': parameters whose \u03c3 grows "
        "by more than 10 % without the face.")


def _sigma_model(joint: dict, params: PoolParams) -> str:
    """How the joint σ were obtained, so the reader knows what they cover."""
    factors = {k: v for k, v in (joint.get("variance_factor") or {}).items() if v is not None}
    text = ("point-to-plane fit incl. laser-plane errors; build tolerance of the twins "
            f"\u00b1{1000 * params.build_tol_m:g} mm / \u00b1{params.build_tol_deg:g}\u00b0 "
            "(rectangular, \u03c3 = tol/\u221a3); coarse error of undetermined parameters")
    if factors:
        largest = max(factors, key=lambda k: float(factors[k] or 1.0))
        text += (f"; ping-block variance factors 1.00–{float(factors[largest] or 1.0):.2f}"
                 f" (largest: {largest})")
    ins = list(params.ins_sigma_deg)
    if any(ins):
        text += (f"; INS accuracy roll/pitch/heading {ins[0]:g}/{ins[1]:g}/{ins[2]:g}° "
                 "(1σ) propagated")
    else:
        text += "; INS attitude taken as exact (no INS accuracy given): σ are a lower bound"
    return text


def _run_info(ctx, attrs, res, params: PoolParams) -> list[Flowable]:
    joint = res.get("joint") or {}
    seed = res.get("seed") or {}
    pairs = [
        ("Outcome", str(res.get("message", attrs.get("message", "")))),
        ("Patent method", f"{seed.get('iterations', '?')} angle iterations, "
                        + ("converged" if seed.get("converged") else "not converged")
                        + (f"; undetermined: {', '.join(seed['undetermined'])}"
                           if seed.get("undetermined") else "")),
    ]
    if joint:
        pairs += [("Joint adjustment",
                   f"{joint.get('iterations', '?')} iterations, "
                   + ("converged" if joint.get("converged") else "not converged")
                   + f", {joint.get('n_observations', '?')} soundings, \u03c3\u2080 = "
                   + fmt(1000 * float(joint.get("sigma0_m", np.nan)), 1, "mm")),
                  ("Uncertainty model", _sigma_model(joint, params))]
    passes = res.get("passes") or []
    if passes:
        pairs.append((f"Passes adjusted jointly ({len(passes)})", "; ".join(
            f"{q['pass']}: {q['pings']} pings, {q['soundings']} soundings, "
            f"{q['on_faces']} on referenced faces" for q in passes)))
    pairs += [("Multibeam pings dropped (INS gaps)", str(res.get("dropped_pings", 0))),
              ("Computed", f"{utc_text(attrs.get('run_utc'))} with HydroSync "
                           f"{attrs.get('software_version', '?')}")]
    return ctx.key_values(pairs, caption="Pool calibration: solution statistics.",
                          key_width=0.38)


def _face_table(project, ctx, res) -> list[Flowable]:
    if not project.exists(f"{RESULT}/faces"):
        return []
    t = project.get_table(f"{RESULT}/faces")
    resid = (res.get("joint") or {}).get("residual_rms_m", {})
    small = ParagraphStyle("UsedFor", parent=ctx.styles["Cell"], fontSize=7.5, leading=9)
    rows = []
    for i, name in enumerate(t["face"]):
        rows.append([
            str(name), str(t["role"][i]), str(t["water"][i]), str(int(t["points_laser"][i])),
            str(int(t["points_mbes"][i])), fmt(1000 * t["rms_laser_m"][i], 1),
            fmt(1000 * t["rms_mbes_m"][i], 1),
            fmt(1000 * resid[name], 1) if name in resid else "\u2014",
            fmt(t["normal_angle_deg"][i], 3),
            Paragraph(esc(str(t["used_for"][i]).replace(",", ", ") or "\u2014"), small)])
    return [ctx.heading("Target faces", 2)] + ctx.table(
        ["Face", "Role", "Water", "Laser pts", "MBES pts", "Laser RMS [mm]",
         "MBES RMS [mm]", "Joint resid. [mm]", "Normal angle [\u00b0]", "Used for"],
        rows, col_widths=[0.16, 0.125, 0.085, 0.07, 0.07, 0.07, 0.07, 0.075, 0.08, 0.175],
        numeric_from=3, left_columns=[9], font_size=7.5,
        caption="Faces of the target design, their role inferred from geometry, points "
        "segmented in each cloud, plane-fit RMS, the angle between the laser and the final "
        "multibeam plane normals, and the parameters each face determines.")


def _joint_tables(ctx, res) -> list[Flowable]:
    joint = res.get("joint")
    if not joint or not joint.get("correlation"):
        return []
    names = list(joint.get("parameters", []))
    corr = np.asarray(joint["correlation"], float)
    rows = [[n] + [fmt(v, 2) for v in corr[i]] for i, n in enumerate(names)]
    strong = [("TEXTCOLOR", (j + 1, i + 1), (j + 1, i + 1), BAD_TEXT)
              for i in range(len(names)) for j in range(len(names))
              if i != j and abs(corr[i, j]) > 0.9]
    n = len(names)
    return [ctx.heading("Joint adjustment: correlations", 2)] + ctx.table(
        ["", *names], rows, col_widths=[0.16] + [0.84 / n] * n, extra_style=strong,
        caption="Correlation matrix of the joint adjustment's parameters. Values above 0.9 "
        "in magnitude (red) mean the pass geometry barely separates the two parameters.")


def _iterations(project, ctx) -> list[Flowable]:
    if not project.exists(f"{RESULT}/iterations"):
        return []
    t = project.get_table(f"{RESULT}/iterations")
    n = len(t["iteration"])
    if n == 0:
        return []
    out: list[Flowable] = [ctx.heading("Patent method: angle iterations", 2)]
    chart = ctx.chart(height=180, xlabel="iteration", ylabel="max. normal angle [\u00b0]")
    it = np.asarray(t["iteration"], float)
    chart.line(it, t["max_normal_angle_deg"], color=SERIES[0], width=1.0,
               label="largest angle between multibeam and laser normals")
    chart.points(it, t["max_normal_angle_deg"], color=SERIES[0], size=1.4)
    out.append(ctx.figure(chart, "Convergence of the patent's iteration (steps 3.1\u20133.6): the "
                          "largest angle between corresponding plane normals after each "
                          "boresight update."))
    # The last iteration of each round here; every iteration in the appendix.
    rounds = np.asarray(t["round"])
    last = [i for i in range(n) if i == n - 1 or rounds[i + 1] != rounds[i]]
    out += _iteration_table(ctx, t, last, "Patent iteration, last iteration of each round: "
                            "the accumulated angles and the largest remaining normal angle. "
                            "A new round starts after the lever arm has been re-estimated; "
                            f"all {n} iterations are listed in the appendix.")
    return out


def _iteration_table(ctx, t: dict, rows_idx: list[int], caption: str) -> list[Flowable]:
    rows = [[str(int(t["iteration"][i])), str(int(t["round"][i])),
             *(fmt(t[c][i], 5) for c in ("d_roll_deg", "d_pitch_deg", "d_yaw_deg")),
             *(fmt(t[c][i], ANGLE_DECIMALS) for c in ("roll_deg", "pitch_deg", "yaw_deg")),
             fmt(t["max_normal_angle_deg"][i], 4)] for i in rows_idx]
    return ctx.table(
        ["Iteration", "Round", "\u03b4roll [\u00b0]", "\u03b4pitch [\u00b0]",
         "\u03b4yaw [\u00b0]", "Roll [\u00b0]", "Pitch [\u00b0]", "Yaw [\u00b0]",
         "Max normal angle [\u00b0]"], rows,
        col_widths=[0.11, 0.08, 0.11, 0.11, 0.11, 0.11, 0.11, 0.11, 0.15], numeric_from=0,
        caption=caption)


def appendix(project, ctx) -> list[Flowable]:
    """Every iteration of the patent method (the section shows one row per round)."""
    if not project.exists(f"{RESULT}/iterations"):
        return []
    t = project.get_table(f"{RESULT}/iterations")
    n = len(t["iteration"])
    if n == 0:
        return []
    return [ctx.heading("Appendix: pool calibration, every patent iteration", 2)] + \
        _iteration_table(ctx, t, list(range(n)), "Boresight corrections of each iteration "
                         "(about the body axes), the accumulated angles and the largest "
                         "remaining normal angle.")
