"""GNSS/INS smoother on the shared KF-GINS synthetic set: accuracy, time and peak memory.

Runs ``../shared/data/kfgins/synthetic`` (682 400 IMU epochs at 200 Hz, 1 Hz GNSS, exact
truth at 50 Hz) from 456 300 s with its KF-GINS configuration, GNSS always on and with the
fifteen 60 s outages of ``outages_60s_every180s.txt``; 21 states (scale factors) and 15,
and with the non-holonomic constraint. Prints position (mm), velocity (mm/s) and attitude
(deg) RMS errors against the truth, forward and smoothed, and the RMS over outages of the
maximum horizontal / vertical drift, next to the figures of the open-source C++ KF-GINS on
the same set (forward only). Time is the run without file reading (the compiled kernel is
cached on disk; the first run of a fresh install compiles it once, ~30 s). Peak memory is
the process's maximum resident set size.

Then the honesty of the σ the smoother reports (``--coverage``, or alone with
``--coverage-only``): simulated drives and vessel tracks (``simulate.py``, several seeds,
tactical and MEMS IMUs, RTK-like white GNSS noise and time-correlated GNSS noise, GNSS
outages of 20 s every 80 s) — per component the share of epochs with |error| ≤ 1.96 σ
(honest: 95 %) and the RMS of error/σ (honest: 1), forward and smoothed, with GNSS and
inside the outages; and the same on the KF-GINS synthetic set (exact truth).

``--quick`` runs only the two 21-state cases.
"""

from __future__ import annotations

import argparse
import resource
import sys
import time
from pathlib import Path

import numpy as np

from hydrosync_core.methods.gins_smoother.config import read_config
from hydrosync_core.methods.gins_smoother.evaluate import (
    ATT,
    POS,
    VEL,
    coverage,
    error_series,
    evaluate,
    outage_windows,
)
from hydrosync_core.methods.gins_smoother.filter import run_gins
from hydrosync_core.methods.gins_smoother.io import read_gnss, read_imu, read_nav, read_outages
from hydrosync_core.methods.gins_smoother.params import GinsParams
from hydrosync_core.methods.gins_smoother.simulate import simulate

DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "kfgins" / "synthetic"
#: KF-GINS (C++, 21 states) on this set: pos N/E/D mm, vel mm/s, roll/pitch/yaw deg,
#: outage drift RMS of the per-outage maximum, horizontal / vertical m.
CPP = {"pos": (7.4, 6.6, 10.5), "vel": (1.5, 1.3, 1.7), "att": (0.0005, 0.00055, 0.0059),
       "drift": (0.32, 0.25)}
CPP15 = {"yaw": 0.020, "drift_h": 0.41}


def _row(label: str, s: dict, drift: dict | None) -> str:
    a = s["all"] if drift is None else s["gnss_on"]
    pos = [a[k]["rms"] * 1000 for k in ("north", "east", "down")]
    vel = [a[k]["rms"] * 1000 for k in ("vn", "ve", "vd")]
    att = [a[k]["rms"] for k in ("roll", "pitch", "yaw")]
    text = (f"{label:<26} {pos[0]:6.1f} {pos[1]:6.1f} {pos[2]:6.1f}  {vel[0]:5.2f} {vel[1]:5.2f} "
            f"{vel[2]:5.2f}  {att[0]:.5f} {att[1]:.5f} {att[2]:.5f}")
    if drift is not None and drift["rms_max_horizontal_m"] is not None:
        text += f"  {drift['rms_max_horizontal_m']:.3f} / {drift['rms_max_vertical_m']:.3f}"
    return text


#: Simulated coverage cases: label, profile, IMU grade, white GNSS σ N/E/D (m),
#: correlated GNSS σ N/E/D (m) and its correlation time (s), processing options.
SIM_CASES = (
    ("vehicle tactical RTK", "vehicle", "tactical", (0.02, 0.02, 0.04), (0, 0, 0), 60.0,
     {"nhc": True}),
    ("vehicle MEMS RTK", "vehicle", "mems", (0.02, 0.02, 0.04), (0, 0, 0), 60.0,
     {"nhc": True}),
    ("vessel tactical RTK", "vessel", "tactical", (0.02, 0.02, 0.04), (0, 0, 0), 60.0,
     {"nhc": False}),
    ("vessel MEMS RTK", "vessel", "mems", (0.02, 0.02, 0.04), (0, 0, 0), 60.0,
     {"nhc": False}),
    ("vehicle tactical coloured", "vehicle", "tactical", (0.05, 0.05, 0.1), (0.3, 0.3, 0.6),
     60.0, {"nhc": True}),
    ("vessel MEMS coloured", "vessel", "mems", (0.05, 0.05, 0.1), (0.3, 0.3, 0.6), 60.0,
     {"nhc": False}),
)
COMPONENTS = POS + VEL + ATT


def _pooled(series: list[dict], key: str) -> dict:
    """Coverage over the epochs of several runs pooled (mask column *key*)."""
    e = {"time": np.concatenate([s["time"][s[key]] for s in series])}
    for name in COMPONENTS:
        e[name] = np.concatenate([s[name][s[key]] for s in series])
        e[f"sd_{name}"] = np.concatenate([s[f"sd_{name}"][s[key]] for s in series])
    return coverage(e)


def simulation_coverage(seeds=range(4), duration_s: float = 240.0, cases=SIM_CASES,
                        params: dict | None = None) -> list[dict]:
    """Coverage of the σ on simulated runs, pooled over *seeds* per case and solution."""
    rows = []
    for label, kind, grade, sw, sc, tau, opts in cases:
        pooled = {"forward": [], "smoothed": []}
        t_run = 0.0
        for seed in seeds:
            sim = simulate(duration_s, kind, grade, imu_rate_hz=100.0, gnss_std=sw,
                           gnss_corr_std=sc, gnss_corr_time_s=tau, seed=seed,
                           init_errors=True)
            t0 = sim["imu"].time[0]
            windows = outage_windows(t0, sim["imu"].time[-1] - 10.0, 20.0, 80.0, t0 + 60.0)
            t1 = time.perf_counter()
            res = run_gins(sim["imu"], sim["gnss"].without(windows), sim["config"],
                           GinsParams.from_dict({**opts, **(params or {})}))
            t_run += time.perf_counter() - t1
            for name in pooled:
                e = error_series(getattr(res, name), sim["truth"])
                inside = np.zeros(e["time"].size, bool)
                for a, b in windows:
                    inside |= (e["time"] > a) & (e["time"] < b)
                e["on"], e["out"], e["all"] = ~inside, inside, np.ones_like(inside)
                pooled[name].append(e)
        for name, series in pooled.items():
            rows.append({"case": label, "solution": name, "runs": len(series),
                         "time_s": t_run, "gnss_on": _pooled(series, "on"),
                         "in_outage": _pooled(series, "out"), "all": _pooled(series, "all")})
    return rows


def _cov_cells(c: dict) -> str:
    return " ".join(f"{100 * c[k]['within_95']:4.0f}/{c[k]['rms_z']:4.2f}" if c.get(k)
                    else f"{'—':>9}" for k in COMPONENTS)


def print_coverage(rows: list[dict]) -> None:
    """Coverage table: share within 1.96 σ (%) / RMS of error/σ per component."""
    print("σ coverage: % of epochs with |error| ≤ 1.96 σ / RMS(error/σ); honest = 95 / 1.00")
    print(f"{'case':<27}{'solution':<9}{'epochs':<10}" + " ".join(f"{k:>9}" for k in COMPONENTS))
    for r in rows:
        for part in ("gnss_on", "in_outage"):
            c = r[part]
            label = r["case"] if part == "gnss_on" and r["solution"] == "forward" else ""
            print(f"{label:<27}{r['solution'][:3] + (' on' if part == 'gnss_on' else ' out'):<9}"
                  f"{c['epochs']:<10}" + _cov_cells(c))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="only the 21-state cases")
    ap.add_argument("--coverage-only", action="store_true",
                    help="only the simulated σ coverage table")
    ap.add_argument("--seeds", type=int, default=4, help="simulated runs per coverage case")
    ap.add_argument("--gnss-noise", default="auto", choices=("auto", "file"),
                    help="GNSS noise model of every run (file = as before the check)")
    args = ap.parse_args()
    extra = {"gnss_noise": args.gnss_noise}
    if args.coverage_only:
        t0 = time.perf_counter()
        print_coverage(simulation_coverage(range(args.seeds), params=extra))
        print(f"({time.perf_counter() - t0:.0f} s)")
        return 0
    if not (DATA / "IMU-synthetic.txt").exists():
        print(f"shared data not found: {DATA}")
        return 1
    t0 = time.perf_counter()
    imu = read_imu(DATA / "IMU-synthetic.txt")
    gnss = read_gnss(DATA / "GNSS-RTK-synthetic.txt")
    truth = read_nav(DATA / "truth-synthetic-50Hz.nav")
    windows = read_outages(DATA / "outages_60s_every180s.txt")
    cfg = read_config(DATA / "kf-gins-synthetic.yaml")
    print(f"read {imu.time.size} IMU epochs, {gnss.time.size} GNSS fixes, {truth.time.size} "
          f"truth rows in {time.perf_counter() - t0:.1f} s")
    cases = [("21 states", GinsParams(), False), ("21 states, outages", GinsParams(), True)]
    if not args.quick:
        cases += [("15 states", GinsParams(scale_factors=False), False),
                  ("15 states, outages", GinsParams(scale_factors=False), True),
                  ("21 states + NHC, outages", GinsParams(nhc=True), True)]
    print(f"{'case':<26} {'pos N/E/D mm':>20}  {'vel N/E/D mm/s':>17}  "
          f"{'roll/pitch/yaw deg':>25}  {'drift h / v m':>13}  (GNSS-on epochs)")
    print(f"{'KF-GINS C++ fwd, 21 states':<26} {CPP['pos'][0]:6.1f} {CPP['pos'][1]:6.1f} "
          f"{CPP['pos'][2]:6.1f}  {CPP['vel'][0]:5.2f} {CPP['vel'][1]:5.2f} {CPP['vel'][2]:5.2f}"
          f"  {CPP['att'][0]:.5f} {CPP['att'][1]:.5f} {CPP['att'][2]:.5f}  "
          f"{CPP['drift'][0]:.3f} / {CPP['drift'][1]:.3f}")
    print(f"{'KF-GINS C++ fwd, 15 states':<26} {'':>52}yaw {CPP15['yaw']:.3f}  "
          f"{CPP15['drift_h']:.3f} h")
    for label, params, outage in cases:
        g = gnss.without(windows) if outage else gnss
        t1 = time.perf_counter()
        res = run_gins(imu, g, cfg, GinsParams.from_dict({**params.to_dict(), **extra}))
        dt = time.perf_counter() - t1
        ev = evaluate(res, truth, windows if outage else ())
        for name in ("forward", "smoothed"):
            s = ev[name]
            print(_row(f"{label} {name[:3]}", s, s.get("outage")))
        for name in ("forward", "smoothed"):
            for part, c in ev[name]["coverage"].items():
                if part != "all" or not outage:
                    print(f"{'':<4}σ coverage {name[:3]} {part:<9} {_cov_cells(c)}")
        print(f"{'':<26} time {dt:.1f} s (forward + smoothing, {res.counts['nodes']} nodes), "
              f"peak RSS {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB",
              flush=True)
        print(f"{'':<26} {res.gnss_model['summary']}")
    print(f"{'':<4}(σ coverage: % within 1.96 σ / RMS(error/σ) for "
          + " ".join(COMPONENTS) + ")")
    print()
    print_coverage(simulation_coverage(range(args.seeds), params=extra))
    return 0


if __name__ == "__main__":
    sys.exit(main())
