"""Monte-Carlo runs: simulated swings solved by every method, errors against the truth.

Errors: heading error (deg) = heading of ``C_est(t0)·C_true(t0)ᵀ`` — the initial attitude
each method implies against the truth; tip error (m, ENU) = estimate − truth; the tilt of
the shot (deg, mean over the hold) classes the runs (< 40°, 40–60°, as Li et al.'s table 2).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from hydrosync_core.methods.tilt_alignment.geometry import yaw_of
from hydrosync_core.methods.tilt_alignment.imu_convention import CONVENTIONS
from hydrosync_core.methods.tilt_alignment.params import METHODS, TiltParams
from hydrosync_core.methods.tilt_alignment.pipeline import solve_record
from hydrosync_core.methods.tilt_alignment.simulate import GRADES, random_config, simulate_swing
from hydrosync_core.progress import check_cancel, report


def evaluate(sim: dict, params: TiltParams
             ) -> dict[str, tuple[float, np.ndarray, np.ndarray, bool]]:
    """Solve one simulated record (its IMU convention declared as the data set would,
    unless *params* sets one); per method (heading error deg, tip error ENU m, tip σ
    ENU m, whether the method warned that the tip is weaker than the tolerance).

    NaN for a method the data did not determine.
    """
    sol = solve_record(sim["time"], sim["gyro"], sim["accel"], sim["gnss_time"],
                       sim["gnss_ned"], sim["pole_length_m"], params,
                       gravity=sim["truth"]["config"].gravity_m_s2,
                       imu_convention=sim["truth"]["config"].imu_convention)
    C_true0 = sim["truth"]["C"][0]
    out = {}
    for name, m in sol.methods.items():
        if not m.ok or m.C0 is None:
            out[name] = (math.nan, np.full(3, np.nan), np.full(3, np.nan), False)
            continue
        err = m.tip - sim["truth"]["tip_ned"]
        out[name] = (math.degrees(yaw_of(m.C0 @ C_true0.T)),
                     np.array([err[1], err[0], -err[2]]), m.tip_std[[1, 0, 2]],
                     m.warning is not None)
    return out


def run_monte_carlo(n_runs: int, params: TiltParams, seed: int = 0,
                    tilt_range: tuple[float, float] = (15.0, 60.0), overrides=None,
                    progress=None, cancel=None, grade: str | None = None,
                    extra=None) -> dict[str, np.ndarray]:
    """*n_runs* random swings (:func:`.simulate.random_config`) solved by every method.

    *overrides* fixes configuration fields (e.g. ``pole_length_m``, ``gnss_rate_hz``);
    *grade* the simulated IMU grade (else drawn per run). *extra*: a callable
    ``(sim) -> dict[str, float]`` whose values are added as columns (a second opinion).

    Returns
    -------
    dict: ``run``, ``hold_tilt_deg``, ``max_tilt_deg``, ``pole_length_m``, ``imu_grade``
    (index into :data:`.simulate.GRADES`, −1 when the noise matches no grade),
    ``imu_convention`` (index into :data:`.imu_convention.CONVENTIONS`) and per method
    ``<m>_heading_err_deg``, ``<m>_tip_err_e``, ``_n``, ``_u`` (m) and the tip σ the method
    reported, ``<m>_tip_std_e``, ``_n``, ``_u`` (m), and ``<m>_warned`` (1 when the method
    warned that its tip is weaker than the tolerance).
    """
    rng = np.random.default_rng(seed)
    cols: dict[str, list] = {"run": [], "hold_tilt_deg": [], "max_tilt_deg": [],
                             "pole_length_m": [], "imu_grade": [], "imu_convention": []}
    for m in METHODS:
        for k in ("heading_err_deg", "tip_err_e", "tip_err_n", "tip_err_u", "tip_std_e",
                  "tip_std_n", "tip_std_u", "warned"):
            cols[f"{m}_{k}"] = []
    for r in range(n_runs):
        check_cancel(cancel)
        cfg = random_config(rng, tilt_range, grade=grade)
        if overrides:
            cfg = replace(cfg, **overrides)
        sim = simulate_swing(cfg, seed=int(rng.integers(0, 2**31)))
        res = evaluate(sim, params)
        cols["run"].append(r)
        cols["hold_tilt_deg"].append(sim["truth"]["hold_tilt_deg"])
        cols["max_tilt_deg"].append(sim["truth"]["max_tilt_deg"])
        cols["pole_length_m"].append(cfg.pole_length_m)
        cols["imu_grade"].append(_grade_index(cfg))
        cols["imu_convention"].append(CONVENTIONS.index(cfg.imu_convention))
        for m in METHODS:
            he, te, ts, warned = res[m]
            cols[f"{m}_heading_err_deg"].append(he)
            cols[f"{m}_warned"].append(float(warned))
            for i, a in enumerate("enu"):
                cols[f"{m}_tip_err_{a}"].append(te[i])
                cols[f"{m}_tip_std_{a}"].append(ts[i])
        for k, v in (extra(sim) if extra is not None else {}).items():
            cols.setdefault(k, []).append(v)
        report(progress, (r + 1) / max(n_runs, 1), f"Monte-Carlo run {r + 1}/{n_runs}")
    return {k: np.asarray(v, float) for k, v in cols.items()}


def _grade_index(cfg) -> int:
    """Which of :data:`.simulate.GRADES` the record's gyro and accelerometer noise is."""
    for k, (gn, _, an, _) in enumerate(GRADES.values()):
        if (gn, an) == (cfg.gyro_noise_deg_s_rthz, cfg.accel_noise_m_s2_rthz):
            return k
    return -1


def statistics(mc: dict[str, np.ndarray], method: str, mask: np.ndarray | None = None
               ) -> dict[str, float]:
    """Heading RMS, share below 1°, horizontal tip shares within 1 and 2.5 cm, 3-D within 1 cm.

    Undetermined runs count as failures in the shares (and are counted). ``coverage_e``,
    ``_n``, ``_u``: share of the determined runs whose tip error is within 1.96 of the
    reported σ on that axis (95 % for an honest Gaussian σ); NaN when the table has no σ.
    ``warned``: share of the runs the method warned about (weak tip); ``h_within_1cm_quiet``:
    share within 1 cm horizontally of the runs it did not warn about (NaN if none);
    ``warned_within_1cm``: share of the runs within 1 cm that it warned about anyway.
    """
    mask = np.ones(mc["run"].size, bool) if mask is None else mask
    he = mc[f"{method}_heading_err_deg"][mask]
    e, n, u = (mc[f"{method}_tip_err_{a}"][mask] for a in "enu")
    h = np.hypot(e, n)
    d3 = np.sqrt(e ** 2 + n ** 2 + u ** 2)
    ok = np.isfinite(h)
    count = max(int(mask.sum()), 1)

    def share(x, lim):
        return float(np.sum(np.where(ok, x, np.inf) <= lim)) / count

    cover = {}
    for a, err in zip("enu", (e, n, u), strict=True):
        key = f"{method}_tip_std_{a}"
        if key in mc and ok.any():
            sd = mc[key][mask][ok]
            cover[f"coverage_{a}"] = float(np.mean(np.abs(err[ok]) < 1.96 * sd))
        else:
            cover[f"coverage_{a}"] = math.nan
    wkey = f"{method}_warned"
    warned = (mc[wkey][mask] > 0) if wkey in mc else np.zeros(h.size, bool)
    quiet = ok & ~warned
    cover["warned"] = float(np.sum(warned)) / count
    cover["h_within_1cm_quiet"] = (float(np.mean(h[quiet] <= 0.01)) if quiet.any()
                                   else math.nan)
    good = ok & (np.where(ok, h, np.inf) <= 0.01)
    cover["warned_within_1cm"] = (float(np.mean(warned[good])) if good.any() else math.nan)
    return {"runs": int(mask.sum()), "undetermined": int((~ok).sum()), **cover,
            "heading_rms_deg": float(np.sqrt(np.nanmean(he ** 2))) if ok.any() else math.nan,
            "heading_below_1deg": float(np.sum(np.abs(np.where(ok, he, 99)) < 1.0)) / count,
            "h_within_1cm": share(h, 0.01), "h_within_2_5cm": share(h, 0.025),
            "d3_within_1cm": share(d3, 0.01),
            "h_rms_m": float(np.sqrt(np.nanmean(h ** 2))) if ok.any() else math.nan,
            "h_max_m": float(np.nanmax(h)) if ok.any() else math.nan,
            "v_rms_m": float(np.sqrt(np.nanmean(u ** 2))) if ok.any() else math.nan}
