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

``--quick`` runs only the two 21-state cases.
"""

from __future__ import annotations

import argparse
import resource
import sys
import time
from pathlib import Path

from hydrosync_core.methods.gins_smoother.config import read_config
from hydrosync_core.methods.gins_smoother.evaluate import evaluate
from hydrosync_core.methods.gins_smoother.filter import run_gins
from hydrosync_core.methods.gins_smoother.io import read_gnss, read_imu, read_nav, read_outages
from hydrosync_core.methods.gins_smoother.params import GinsParams

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


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="only the 21-state cases")
    args = ap.parse_args()
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
        res = run_gins(imu, g, cfg, params)
        dt = time.perf_counter() - t1
        ev = evaluate(res, truth, windows if outage else ())
        for name in ("forward", "smoothed"):
            s = ev[name]
            print(_row(f"{label} {name[:3]}", s, s.get("outage")))
        print(f"{'':<26} time {dt:.1f} s (forward + smoothing, {res.counts['nodes']} nodes), "
              f"peak RSS {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB",
              flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
