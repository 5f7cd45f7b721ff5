"""Figures of the pool calibration section: plan, elevation and face profiles.

Reads the decimated clouds stored under ``/results/pool_calibration/plan`` (target ENU, m;
face index per point) and the design outlines of ``raw/pool/target``. Point clouds are
thinned to :data:`PLOT_POINTS` per series so the vector PDF stays light.
"""

from __future__ import annotations

import numpy as np
from reportlab.platypus import Flowable

from hydrosync_core.report.context import ReportContext
from hydrosync_core.report.styles import INK, SERIES

RESULT = "results/pool_calibration"
PLOT_POINTS = 2500  # per cloud and panel: enough to see the faces, light in the PDF
ROLE_COLORS = {"wall": SERIES[0], "oblique": SERIES[1], "perpendicular": SERIES[2],
               "horizontal": SERIES[3], "parallel": SERIES[4], "other": SERIES[5]}


def _subsample(n: int, k: int) -> np.ndarray:
    """At most *k* evenly spread indices of *n* (deterministic)."""
    return np.arange(n) if n <= k else np.linspace(0, n - 1, k).astype(int)


def plan_figures(project, ctx: ReportContext) -> list[Flowable]:
    base = f"{RESULT}/plan"
    needed = ("laser_xyz", "laser_face", "mbes_before_xyz", "mbes_after_xyz", "mbes_face")
    if not all(project.exists(f"{base}/{k}") for k in needed):
        return []
    t = project.get_table(f"{RESULT}/faces")
    roles = np.asarray(t["role"]).astype(str)
    lx = np.asarray(project.get(f"{base}/laser_xyz"), float)
    lf = np.asarray(project.get(f"{base}/laser_face"), int)
    mb = np.asarray(project.get(f"{base}/mbes_before_xyz"), float)
    ma = np.asarray(project.get(f"{base}/mbes_after_xyz"), float)
    mf = np.asarray(project.get(f"{base}/mbes_face"), int)
    on = mf >= 0
    mb, ma, mf = mb[on], ma[on], mf[on]
    target = project.get_json("raw/pool/target", {}) or {}
    faces = target.get("faces", [])
    water = float(target.get("water_level_m", 0.0))
    out: list[Flowable] = [ctx.heading("Segmented point clouds", 2)]

    def outlines(chart, ix, iy):
        for face in faces:
            c = np.asarray(face["corners"], float)
            chart.polygon(c[:, ix], c[:, iy], color="#8a8a8a", width=0.4)

    def by_role(chart, xyz, face_idx, ix, iy, marker, label_suffix):
        for role, color in ROLE_COLORS.items():
            sel = np.flatnonzero(roles[face_idx] == role) if len(face_idx) else []
            if len(sel) == 0:
                continue
            sel = sel[_subsample(len(sel), PLOT_POINTS // 2)]
            chart.points(xyz[sel, ix], xyz[sel, iy], color=color, size=0.8, marker=marker,
                         label=f"{role}{label_suffix}")

    # Plan view: north along the page (the wall runs north), east across.
    plan = ctx.chart(height=250, xlabel="north [m]", ylabel="east [m]")
    outlines(plan, 1, 0)
    by_role(plan, lx, lf, 1, 0, "circle", " (laser)")
    sel = _subsample(len(ma), PLOT_POINTS)
    plan.points(ma[sel, 1], ma[sel, 0], color=INK, size=0.5, marker="square",
                label="multibeam, final values")
    out.append(ctx.figure(plan, (
        "Plan view of the segmented clouds in the target frame (ENU): laser points coloured "
        "by the role of their face, multibeam soundings on faces georeferenced with the final "
        "values (black), design face outlines in grey. The vertical scale is stretched "
        "(axes not to the same scale) to separate the faces.")))
    # Elevation seen from the vessel: the faces above water (laser) and below (multibeam).
    elev = ctx.chart(height=250, xlabel="north [m]", ylabel="up [m]")
    outlines(elev, 1, 2)
    elev.hline(water, color=SERIES[5], dash=(4, 2), width=0.8, label="water level")
    sel = _subsample(len(lx), PLOT_POINTS)
    elev.points(lx[sel, 1], lx[sel, 2], color="#9ec5e8", size=0.6, marker="square",
                label="laser")
    by_role(elev, ma, mf, 1, 2, "square", " (multibeam)")
    out.append(ctx.figure(elev, (
        "Elevation of the target seen from the vessel (north against up): laser points above "
        "the water line and multibeam soundings below it, georeferenced with the final values "
        "and coloured by the role of their face; design outlines in grey.")))
    panels = [chart for chart in (
        _profile(ctx, lx, lf, mb, ma, mf, t, roles, role) for role in ("wall", "oblique"))
        if chart is not None]
    if panels:
        for chart in panels:
            chart.width = ctx.width / len(panels)
        out.append(ctx.figure(panels, (
            "Profiles across faces: distance of each point from the laser plane of the face "
            "against height. Multibeam soundings with the coarse setup (grey) lean or sit off "
            "the plane; with the final values (colour) they continue the laser points (light "
            "blue) below the water line.")))
    return out


def _profile(ctx, lx, lf, mb, ma, mf, t, roles, role):
    """Distance to the laser plane of the best face of *role* vs height, before/after."""
    faces = [k for k in range(len(roles)) if roles[k] == role
             and np.sum(lf == k) >= 10 and np.sum(mf == k) >= 10]
    if not faces:
        return None
    k = max(faces, key=lambda j: int(np.sum(mf == j)))
    laser = lx[lf == k]
    # TLS plane of the laser points (seed eqs. [0051]-[0088]): smallest singular vector.
    centre = laser.mean(axis=0)
    normal = np.linalg.svd(laser - centre, full_matrices=False)[2][-1]
    if normal[np.argmax(np.abs(normal[:2]))] < 0:
        normal = -normal  # a fixed, readable orientation (east or north positive)

    def dist_cm(p):
        return 100.0 * (p - centre) @ normal

    name = str(t["face"][k])
    chart = ctx.chart(height=230, fraction=0.5,
                      xlabel=f"distance from the laser plane of {name} [cm]", ylabel="up [m]")
    sel = _subsample(len(laser), PLOT_POINTS // 2)
    chart.points(dist_cm(laser[sel]), laser[sel, 2], color="#9ec5e8", size=0.7,
                 marker="square", label="laser")
    on = np.flatnonzero(mf == k)
    on = on[_subsample(len(on), PLOT_POINTS // 2)]
    chart.points(dist_cm(mb[on]), mb[on, 2], color="#a0a0a0", size=0.7, marker="square",
                 label="coarse")
    chart.points(dist_cm(ma[on]), ma[on, 2], color=ROLE_COLORS.get(role, INK), size=0.7,
                 marker="square", label="final")
    return chart
