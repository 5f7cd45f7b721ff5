"""Report section of the tilt-pole alignment (Li et al., plus HydroSync's joint solution).

Reads ``/results/tilt_alignment`` as :mod:`.project_run` stores it: the per-method table
(heading misalignment, tip and its σ, vectors, iterations), the antenna trajectory (plan
and side views), J(ψ) with the gradient-descent iterates (Li et al., fig. 11), the
Monte-Carlo heading-error histogram (their fig. 4) and tip-error scatter (figs. 6-9) on
simulated swings like the record, with the share of tips within 1 and 2.5 cm.
"""

from __future__ import annotations

import json

import numpy as np

from hydrosync_core.methods.tilt_alignment.params import METHODS, TiltParams
from hydrosync_core.methods.tilt_alignment.present import (
    COLUMNS,
    LABELS,
    heading_text,
    imu_text,
    joint_text,
    method_rows,
    sigma_enu_text,
    tip_header,
    tip_text,
)
from hydrosync_core.methods.tilt_alignment.project_run import RESULT
from hydrosync_core.params import stored
from hydrosync_core.report.context import fmt

HEADING = "Tilt-pole heading alignment and tip"


def _doc(project) -> dict:
    return json.loads(project.attrs(RESULT)["result"])


def summary(project) -> list[tuple[str, str]]:
    """Key results for the report summary and ``hydrosync demo``."""
    doc = _doc(project)
    m = doc["methods"][doc["method"]]
    key = "tip E, N, U [m]" if "tip_enu" in doc else "tip lat, lon, h"
    rows = [(f"Tilt pole {key} ({LABELS[doc['method']]})", tip_text(m))]
    if m["tip_std_enu_m"] is not None:
        rows.append(("Tilt pole tip σ E/N/U", sigma_enu_text(m) + " mm"))
    rows.append(("Tilt pole heading misalignment", heading_text(m)))
    return rows


def _hist(values: np.ndarray, edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    counts, _ = np.histogram(values[np.isfinite(values)], bins=edges)
    x = np.repeat(edges, 2)[1:-1]
    y = np.repeat(counts, 2).astype(float)
    return np.concatenate([[edges[0]], x, [edges[-1]]]), np.concatenate([[0], y, [0]])


def section(project, ctx) -> list:
    from hydrosync_core.methods.tilt_alignment.montecarlo import statistics

    doc = _doc(project)
    params = stored(TiltParams, project, RESULT)
    out = [ctx.heading(HEADING)]
    out.append(ctx.para(
        "The pole is swung for a few seconds with its tip on the point. Li et al. level the "
        "IMU (Mahony filter), form observation vectors between GNSS epochs and solve the "
        "heading misalignment by gradient descent (mini-batch after screening the vectors by "
        "their own heading; batch; stochastic with the longest vector) or SVD; the tip is "
        "the antenna corrected by the rotated pole (eq. 18). HydroSync adds the closed-form "
        "heading-only least squares and a joint batch least squares over the whole swing "
        "(initial attitude, tip, gyro and accelerometer biases from accelerometers, gyros "
        "and GNSS), the reported method by default. Tips in ENU (m); σ 1σ."))
    heads = {**COLUMNS, "tip": tip_header(doc)}
    rows = [[r[k] for k in heads] for r in method_rows(doc)]
    out += ctx.table(list(heads.values()), rows,
                     col_widths=[0.17, 0.16, 0.3, 0.15, 0.1, 0.12],
                     caption=f"Every method on this record (* reported). Vectors used "
                     f"{doc['vectors_used']}, rejected {doc['vectors_rejected']}; tilt up to "
                     f"{doc['tilt_deg']['max']:.1f}°, {doc['tilt_deg']['shot']:.1f}° at the "
                     f"shot. {imu_text(doc)}. {joint_text(doc)}.")
    for w in doc.get("warnings", []):
        out.append(ctx.warning(w))
    ep = project.get_table(f"{RESULT}/epochs")
    e0, n0, u0 = (float(np.mean(ep[k])) for k in ("e", "n", "u"))
    plan = ctx.chart(height=200, fraction=0.5, xlabel="east [m]", ylabel="north [m]",
                     equal_aspect=True)
    plan.line(ep["e"] - e0, ep["n"] - n0, label="antenna")
    side = ctx.chart(height=200, fraction=0.5, xlabel="east [m]", ylabel="up [m]",
                     equal_aspect=True)
    side.line(ep["e"] - e0, ep["u"] - u0, label="antenna")
    if "tip_e" in ep:
        plan.points(ep["tip_e"] - e0, ep["tip_n"] - n0, label="tip per epoch", size=1.0)
        side.points(ep["tip_e"] - e0, ep["tip_u"] - u0, label="tip per epoch", size=1.0)
    out.append(ctx.figure([plan, side], "The swing: antenna path on its sphere about the tip "
                          "(plan and side views, from the mean antenna position)."))
    jc = project.get_table(f"{RESULT}/j_curve")
    if np.isfinite(jc["J"]).any():
        ch = ctx.chart(height=190, xlabel="ψ [°]", ylabel="J(ψ)")
        ch.line(jc["psi_deg"], jc["J"], label="J(ψ)")
        for name in ("bgd", "sgd", "mbgd"):
            d = project.get_table(f"{RESULT}/descent_{name}")
            if d["psi_deg"].size:
                ch.points(d["psi_deg"], d["J"], label=f"{name.upper()} iterates", size=1.6)
        out.append(ctx.figure(ch, "Objective J(ψ) (normalised) over the screened vectors and "
                              f"the gradient-descent iterates (learning rate "
                              f"{params.learning_rate:g}, ε {params.stop_deg:g}°; cf. Li et "
                              "al., fig. 11)."))
    if project.exists(f"{RESULT}/montecarlo"):
        mc = project.get_table(f"{RESULT}/montecarlo")
        n = mc["run"].size
        rows = []
        tilt = mc["hold_tilt_deg"]
        for name in METHODS:
            for label, mask in (("< 40°", tilt < 40), ("40–60°", (tilt >= 40) & (tilt <= 60))):
                if not mask.any():
                    continue
                s = statistics(mc, name, mask)
                rows.append([LABELS[name], label, str(s["runs"]), fmt(s["heading_rms_deg"], 3),
                             f"{100 * s['heading_below_1deg']:.0f}",
                             f"{100 * s['h_within_1cm']:.0f}",
                             f"{100 * s['h_within_2_5cm']:.0f}",
                             fmt(1000 * s["h_rms_m"], 1)])
        out += ctx.table(["Method", "tilt", "runs", "ψ RMS [°]", "< 1° [%]", "H ≤ 1 cm [%]",
                          "H ≤ 2.5 cm [%]", "H RMS [mm]"], rows,
                         col_widths=[0.2, 0.09, 0.07, 0.12, 0.1, 0.14, 0.15, 0.13],
                         caption=f"{n} simulated swings like this record (same pole, GNSS rate "
                         "and σ; random shape, IMU grade and biases, hand wobble, GNSS gap): "
                         "heading error and horizontal tip error (Li et al.'s table 2 form).")
        edges = np.linspace(-2.0, 2.0, 33)
        ch = ctx.chart(height=180, xlabel="heading error [°]", ylabel="runs")
        for name in ("joint", "mbgd", "svd"):
            x, y = _hist(mc[f"{name}_heading_err_deg"], edges)
            ch.line(x, y, label=LABELS[name])
        out.append(ctx.figure(ch, "Heading-error histogram of the simulated swings (cf. Li et "
                              "al., fig. 4)."))
        sc = ctx.chart(height=220, xlabel="tip error east [mm]", ylabel="tip error north [mm]",
                       equal_aspect=True)
        for name in ("mbgd", "svd", "joint"):
            sc.points(1000 * mc[f"{name}_tip_err_e"], 1000 * mc[f"{name}_tip_err_n"],
                      label=LABELS[name], size=1.6)
        circle = np.linspace(0, 2 * np.pi, 90)
        sc.line(10 * np.cos(circle), 10 * np.sin(circle), color="#888888", label="1 cm")
        sc.line(25 * np.cos(circle), 25 * np.sin(circle), color="#bbbbbb", label="2.5 cm")
        out.append(ctx.figure(sc, "Horizontal tip errors of the simulated swings (cf. Li et "
                              "al., figs. 6-9)."))
    out += ctx.params_table(params, "Tilt alignment: processing parameters.")
    return out
