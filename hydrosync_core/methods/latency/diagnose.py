"""Why does nothing correlate? Test a wrong heave sign and wrong lever-arm signs.

When the lines' correlation is low or negative, the scan is repeated on a coarse grid
with the heave negated and with the lever arm's y, z or whole vector flipped; a variant
that correlates much better names the likely set-up error.
"""

from __future__ import annotations

import numpy as np

from hydrosync_core.methods.latency.heave import induced_heave
from hydrosync_core.methods.latency.lines import LineData, scan_line

IMPROVEMENT = 0.1
"""A variant must raise the median R_max by this much to be reported."""

MESSAGES = {
    "heave_negated": "the heave sign is probably wrong (heave must be positive up; "
    "Kongsberg heave is positive down)",
    "lever_y_flipped": "the lever arm's y sign is probably wrong (y is positive to starboard)",
    "lever_z_flipped": "the lever arm's z sign is probably wrong (z is positive down)",
    "lever_negated": "the lever arm is probably reversed (it goes from the motion sensor "
    "to the antenna)",
}


def diagnose(
    lines: list[LineData], t_att: np.ndarray, heave: np.ndarray, roll: np.ndarray,
    pitch: np.ndarray, lever_arm: np.ndarray, dts: np.ndarray, max_lines: int = 8,
) -> tuple[dict, list[str]]:
    """Median R_max of the nominal set-up and of each variant, and warnings.

    Angles in radians, heave in m (up), lever arm body FRD in m, *dts* a coarse grid (s).
    """
    chosen = sorted((ln for ln in lines if ln.usable), key=lambda ln: -ln.tags.size)[:max_lines]
    # Copies, so the variants' scan warnings do not land on the real lines.
    usable = [LineData(ln.name, ln.start, ln.end, ln.tags, ln.h) for ln in chosen]
    if not usable:
        return {}, []
    x, y, z = lever_arm
    variants = {
        "nominal": (1.0, lever_arm),
        "heave_negated": (-1.0, lever_arm),
        "lever_y_flipped": (1.0, np.array([x, -y, z])),
        "lever_z_flipped": (1.0, np.array([x, y, -z])),
        "lever_negated": (1.0, -lever_arm),
    }
    medians = {}
    for name, (sign, arm) in variants.items():
        # Seed eq. 2 with the variant's heave sign and lever arm.
        h_att = sign * heave + induced_heave(roll, pitch, arm)
        r = [scan_line(ln, t_att, h_att, dts, refine=False, uncertainty=False).r_max
             for ln in usable]
        medians[name] = float(np.nanmedian(r)) if np.any(np.isfinite(r)) else float("nan")
    warnings = []
    nominal = medians["nominal"]
    best = max((k for k in medians if k != "nominal"),
               key=lambda k: np.nan_to_num(medians[k], nan=-2))
    if np.isfinite(medians[best]) and medians[best] > np.nan_to_num(nominal, nan=-1) + IMPROVEMENT:
        warnings.append(
            f"median R_max is {nominal:.2f} as set up but {medians[best]:.2f} with "
            f"{best.replace('_', ' ')}: {MESSAGES[best]}"
        )
    elif np.isfinite(nominal) and nominal < 0:
        warnings.append(
            f"median R_max is negative ({nominal:.2f}): check the heave sign and the lever arm"
        )
    return {"median_r_max": medians}, warnings
