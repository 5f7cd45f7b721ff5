"""Errors of a trajectory against a reference, and drift across GNSS outages.

Errors are *solution minus reference* at the reference epochs inside the solution's span
(the solution interpolated linearly, the heading unwrapped first): position north, east,
down (m), velocity N/E/D (m/s), roll, pitch, yaw (deg, yaw difference wrapped to
[-180, 180)). Statistics per component: RMS, mean, maximum of the absolute value, 95th
percentile of the absolute value.
"""

from __future__ import annotations

import numpy as np

from hydrosync_core.methods.gins_smoother.filter import Trajectory
from hydrosync_core.methods.gins_smoother.io import NavData

A_WGS = 6378137.0
E2_WGS = 0.00669437999013
POS = ("north", "east", "down")
VEL = ("vn", "ve", "vd")
ATT = ("roll", "pitch", "yaw")


def error_series(sol: Trajectory, ref: NavData) -> dict[str, np.ndarray]:
    """Per-epoch errors at the reference epochs inside the solution's span.

    Returns ``time`` and the columns of :data:`POS` (m), :data:`VEL` (m/s), :data:`ATT`
    (deg) plus ``horizontal`` (m) and, when the solution carries standard deviations, the
    solution's 1σ of each component as ``sd_<name>`` (same units) for error/σ plots.
    """
    t = sol.time
    keep = (ref.time >= t[0]) & (ref.time <= t[-1])
    tr = ref.time[keep]
    if tr.size == 0:
        return {"time": tr}

    def at(values):
        return np.column_stack([np.interp(tr, t, values[:, c]) for c in range(values.shape[1])])

    llh = at(sol.llh)
    vel = at(sol.vel)
    att = sol.att.copy()
    att[:, 2] = np.degrees(np.unwrap(np.radians(att[:, 2])))
    att = at(att)
    r = ref.llh[keep]
    lat = np.radians(r[:, 0])
    s2 = np.sin(lat) ** 2
    rn = A_WGS / np.sqrt(1 - E2_WGS * s2)
    rm = rn * (1 - E2_WGS) / (1 - E2_WGS * s2)
    out = {"time": tr,
           "north": np.radians(llh[:, 0] - r[:, 0]) * (rm + r[:, 2]),
           "east": np.radians(llh[:, 1] - r[:, 1]) * (rn + r[:, 2]) * np.cos(lat),
           "down": -(llh[:, 2] - r[:, 2])}
    dv = vel - ref.vel[keep]
    da = att - ref.att[keep]
    da[:, 2] = (da[:, 2] + 180.0) % 360.0 - 180.0
    for c in range(3):
        out[VEL[c]] = dv[:, c]
        out[ATT[c]] = da[:, c]
    out["horizontal"] = np.hypot(out["north"], out["east"])
    for names, std in ((POS, sol.pos_std), (VEL, sol.vel_std), (ATT, sol.att_std)):
        if std is not None:
            for c, name in enumerate(names):
                out[f"sd_{name}"] = np.interp(tr, t, std[:, c])
    return out


def statistics(errors: dict[str, np.ndarray], mask: np.ndarray | None = None) -> dict:
    """RMS, mean, max |e| and 95 % of |e| per component (units of :func:`error_series`)."""
    out = {"epochs": int(errors["time"].size if mask is None else mask.sum())}
    for name in POS + VEL + ATT + ("horizontal",):
        e = errors[name] if mask is None else errors[name][mask]
        if e.size == 0:
            out[name] = None
            continue
        a = np.abs(e)
        out[name] = {"rms": float(np.sqrt(np.mean(e * e))), "mean": float(np.mean(e)),
                     "max": float(a.max()), "p95": float(np.percentile(a, 95))}
    return out


def coverage(errors: dict[str, np.ndarray], mask: np.ndarray | None = None) -> dict:
    """How honest the solution's σ are: per component the share of epochs with
    ``|e| ≤ 1.96 σ`` (``within_95``, 0.95 for honest Gaussian σ) and the RMS of ``e/σ``
    (``rms_z``, 1 for honest σ). Needs the ``sd_<name>`` columns of :func:`error_series`.
    Consecutive epochs are correlated: the share is a coverage, not an independent count.
    """
    out = {"epochs": int(errors["time"].size if mask is None else mask.sum())}
    for name in POS + VEL + ATT:
        sd = errors.get(f"sd_{name}")
        if sd is None:
            out[name] = None
            continue
        e, s = errors[name], sd
        if mask is not None:
            e, s = e[mask], s[mask]
        ok = s > 0
        if not ok.any():
            out[name] = None
            continue
        z = e[ok] / s[ok]
        out[name] = {"within_95": float(np.mean(np.abs(z) <= 1.96)),
                     "rms_z": float(np.sqrt(np.mean(z * z)))}
    return out


def offset_removed(errors: dict[str, np.ndarray]) -> tuple[dict, dict]:
    """The errors with each component's mean removed, and those means.

    A reference that is not independent of the sensors, or that describes another point
    or axes (comma2k19: the camera; its mounting on the IMU is not given), differs from the
    solution by a constant the σ cannot know about; :func:`coverage` of what is left
    tells whether the σ describe the varying part honestly.
    """
    out = dict(errors)
    means = {}
    for name in POS + VEL + ATT:
        if name in errors and errors[name].size:
            means[name] = float(np.mean(errors[name]))
            out[name] = errors[name] - means[name]
    return out, means


def outage_drift(errors: dict[str, np.ndarray], windows) -> dict:
    """Largest horizontal and vertical error inside each outage window (s).

    Returns ``outages`` (list of dicts: start, end, max_horizontal_m, max_vertical_m) and
    the RMS over the outages of those maxima (``rms_max_horizontal_m``,
    ``rms_max_vertical_m``), the figure KF-GINS users quote.
    """
    rows = []
    t = errors["time"]
    for a, b in windows:
        m = (t > a) & (t < b)
        if not m.any():
            continue
        rows.append({"start": float(a), "end": float(b),
                     "max_horizontal_m": float(np.max(errors["horizontal"][m])),
                     "max_vertical_m": float(np.max(np.abs(errors["down"][m])))})
    if not rows:
        return {"outages": [], "rms_max_horizontal_m": None, "rms_max_vertical_m": None}
    h = np.array([r["max_horizontal_m"] for r in rows])
    v = np.array([r["max_vertical_m"] for r in rows])
    return {"outages": rows, "rms_max_horizontal_m": float(np.sqrt(np.mean(h * h))),
            "rms_max_vertical_m": float(np.sqrt(np.mean(v * v))),
            "max_horizontal_m": float(h.max()), "max_vertical_m": float(v.max())}


def outage_windows(t0: float, t1: float, duration_s: float, every_s: float,
                   first_s: float | None = None) -> list[tuple[float, float]]:
    """Outages of *duration_s* every *every_s* from ``first_s`` (default t0 + every_s)."""
    start = t0 + every_s if first_s is None else first_s
    out = []
    while start + duration_s <= t1:
        out.append((start, start + duration_s))
        start += every_s
    return out


def evaluate(result, ref: NavData, windows=()) -> dict:
    """Statistics of the forward and smoothed solutions of a :class:`GinsResult`.

    ``{"forward": {...}, "smoothed": {...}}`` each with ``all`` (every reference epoch),
    ``gnss_on`` (outside the outage windows) and ``outage`` (:func:`outage_drift`), and
    ``coverage`` (:func:`coverage` of the solution's own σ) over ``all`` epochs, over all
    epochs with each component's constant offset removed (``offset_removed``; the offsets
    in ``constant_offset``, :func:`offset_removed`) and, with outage windows, ``gnss_on``
    and ``in_outage``.
    """
    out = {}
    for name in ("forward", "smoothed"):
        sol = getattr(result, name)
        if sol is None:
            continue
        e = error_series(sol, ref)
        entry = {"all": statistics(e), "coverage": {"all": coverage(e)}}
        if e["time"].size:
            e0, means = offset_removed(e)
            entry["constant_offset"] = means
            entry["coverage"]["offset_removed"] = coverage(e0)
        if windows:
            inside = np.zeros(e["time"].size, bool)
            for a, b in windows:
                inside |= (e["time"] > a) & (e["time"] < b)
            entry["gnss_on"] = statistics(e, ~inside)
            entry["outage"] = outage_drift(e, windows)
            entry["coverage"]["gnss_on"] = coverage(e, ~inside)
            entry["coverage"]["in_outage"] = coverage(e, inside)
        out[name] = entry
    return out
