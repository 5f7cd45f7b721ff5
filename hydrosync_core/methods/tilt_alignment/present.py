"""How a tilt result reads: one set of labels and texts for the CLI, the panel and the PDF.

Every number beside its σ carries the digits σ supports (:mod:`hydrosync_core.numfmt`);
the tip coordinates get the decimals of their smallest σ.
"""

from __future__ import annotations

import math

from hydrosync_core.numfmt import MISSING, sigma_decimals, sigma_text, value_sigma

#: Human names of the methods.
LABELS = {"joint": "joint batch LSQ", "mbgd": "MBGD (Li et al.)", "bgd": "BGD",
          "sgd": "SGD", "svd": "SVD (Wahba)", "closed_form": "closed form"}

#: The per-method table: column key → header (unit in the header).
COLUMNS = {"method": "Method", "heading": "Heading misalignment ψ", "tip": "Tip",
           "sigma": "Tip σ E/N/U [mm]", "vectors": "Vectors", "iterations": "Iterations"}


def tip_header(doc: dict) -> str:
    return "Tip E, N, U [m]" if "tip_enu" in doc else "Tip lat, lon [°], h [m]"


def tip_text(m: dict) -> str:
    """The tip with the decimals its smallest σ supports (lat/lon: 9 decimals, 0.1 mm)."""
    sd = [s for s in (m.get("tip_std_enu_m") or []) if s is not None and s > 0]
    d = sigma_decimals(min(sd)) if sd else None
    d = 4 if d is None else d
    if m.get("tip_enu") is not None:
        return ", ".join(f"{v:.{d}f}" for v in m["tip_enu"])
    if m.get("tip_llh") is not None:
        lat, lon, h = m["tip_llh"]
        return f"{lat:.9f}, {lon:.9f}, {h:.{d}f}"
    return MISSING


def heading_text(m: dict) -> str:
    """``"57.03 ± 0.12°"``: the heading misalignment with its σ."""
    return value_sigma(m.get("heading_misalignment_deg"), m.get("heading_std_deg"), "°")


def sigma_enu_text(m: dict) -> str:
    """``"2.1/1.9/3.4"``: the tip's σ east, north, up in mm, two significant digits."""
    sd = m.get("tip_std_enu_m")
    if sd is None:
        return MISSING
    return "/".join(sigma_text(None if s is None else 1000 * s) for s in sd)


def method_row(name: str, m: dict, reported: bool = False) -> dict[str, str]:
    """One method's row: texts keyed like :data:`COLUMNS`."""
    label = LABELS.get(name, name) + (" *" if reported else "")
    if m.get("undetermined"):
        return {"method": label, "heading": "undetermined", "tip": m["undetermined"],
                "sigma": MISSING, "vectors": str(m.get("vectors", "")),
                "iterations": str(m.get("iterations", ""))}
    return {"method": label, "heading": heading_text(m), "tip": tip_text(m),
            "sigma": sigma_enu_text(m), "vectors": str(m.get("vectors", "")),
            "iterations": str(m.get("iterations", ""))}


def method_rows(doc: dict) -> list[dict[str, str]]:
    """Every method's row of a ``result.json`` document, the reported one marked ``*``."""
    return [method_row(name, m, name == doc["method"]) for name, m in doc["methods"].items()]


def imu_text(doc: dict) -> str:
    """The IMU grade, its priors and the sample convention the result was computed with."""
    pri = doc.get("priors") or {}
    grade = doc.get("imu_grade", "?")
    g, a = pri.get("gyro_bias_deg_s"), pri.get("accel_bias_m_s2")
    prior = (f" (bias priors: gyro {g:g}°/s, accelerometer {a:g} m/s²)"
             if g is not None and a is not None else "")
    return f"IMU grade {grade}{prior}; samples {doc.get('imu_convention', 'instant')}"


def joint_text(doc: dict) -> str:
    """The joint method's time offset and the IMU noise it measured."""
    j = doc.get("joint")
    if not j:
        return ""
    off = value_sigma(j.get("time_offset_ms"), j.get("time_offset_std_ms"), "ms", sign=True)
    gn, an = j.get("gyro_noise_deg_s_per_sample"), j.get("accel_noise_m_s2_per_sample")
    noise = ""
    if gn is not None and an is not None and math.isfinite(gn) and math.isfinite(an):
        noise = (f"; IMU noise per sample: gyro {gn:.2g}°/s, accelerometer "
                 f"{an:.2g} m/s²")
    return f"GNSS↔IMU time offset {off}{noise}"
