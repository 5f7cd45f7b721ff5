"""GNSS/INS smoother on real recordings (read in place): residuals, reference, outages.

``../shared/data/comma2k19-ex1`` (60 s highway, phone IMU 104 Hz, u-blox 10 Hz, the
provider's fused pose at 20 Hz — not independent) and
``../shared/data/rtkexplorer-gnss-imu/drive_0708`` (9 min, MEMS IMU 100 Hz, real-time RTK
4 Hz, no reference), each through :mod:`hydrosync_core.methods.gins_smoother.recordings`
with no hand edits: the recording's assumed IMU grade and options, the GNSS−IMU clock
offset estimated from the smoothed residuals, moving alignment from the GNSS course.

Prints per recording: the clock offset; GNSS residual RMS N/E/D (trajectory with lever arm
minus fix) forward and smoothed; for comma2k19 the error RMS / mean against the reference;
then the outage test — GNSS removed for 10, 20 and 30 s (comma2k19: one window 15 s into
the segment; drive: windows every 60 s while moving faster than 2 m/s) — as the largest
horizontal and vertical distance of the trajectory to the *removed* fixes, forward and
smoothed (median and maximum over the windows; comma2k19 also against the reference).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from hydrosync_core.methods.gins_smoother import recordings as R  # noqa: N812
from hydrosync_core.methods.gins_smoother.evaluate import evaluate
from hydrosync_core.methods.gins_smoother.filter import run_gins
from hydrosync_core.methods.gins_smoother.params import GinsParams

DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data"
SETS = (("comma2k19-ex1", DATA / "comma2k19-ex1", R.read_comma2k19),
        ("rtkexplorer drive_0708", DATA / "rtkexplorer-gnss-imu" / "drive_0708",
         R.read_rtkexplorer))


def _rms(r: np.ndarray) -> str:
    ok = np.isfinite(r).all(axis=1)
    v = np.sqrt(np.mean(r[ok] ** 2, axis=0))
    return f"{v[0]:7.3f} {v[1]:7.3f} {v[2]:7.3f}"


def main() -> int:
    for label, folder, reader in SETS:
        if not folder.is_dir():
            print(f"{label}: {folder} absent, skipped")
            continue
        t0 = time.perf_counter()
        rec = reader(folder)
        t_read = time.perf_counter() - t0
        shift, _grid = R.estimate_time_shift(rec)
        rec = R.shifted(rec, shift)
        t1 = time.perf_counter()
        res = run_gins(rec.imu, rec.gnss, rec.config, GinsParams.from_dict(rec.params))
        t_run = time.perf_counter() - t1
        span = rec.imu.time[-1] - rec.imu.time[0]
        print(f"\n=== {label}: {rec.imu.time.size} IMU epochs ({rec.imu.rate_hz:.0f} Hz), "
              f"{rec.gnss.time.size} GNSS fixes, {span:.0f} s ===")
        print(f"read {t_read:.2f} s, clock-offset search {t1 - t0 - t_read:.1f} s, "
              f"one forward+smoothed run {t_run:.2f} s")
        print(f"GNSS−IMU clock offset estimated: {shift:+.3f} s; alignment: "
              f"{res.alignment.get('method')}, {res.alignment.get('levelling')}; start "
              f"{res.alignment['start_time'] - rec.imu.time[0]:.1f} s at "
              f"{res.alignment.get('speed_mps', 0):.1f} m/s")
        print("GNSS residual RMS N/E/D (m)  forward " + _rms(res.gnss["residual_forward"])
              + "   smoothed " + _rms(res.gnss["residual"]))
        if rec.reference is not None:
            ev = evaluate(res, rec.reference)
            print("against the provider's reference (camera; not independent): RMS (mean)")
            print(f"  {'':9} {'N m':>13} {'E m':>13} {'D m':>13} {'vN m/s':>13} "
                  f"{'vE m/s':>13} {'vD m/s':>13} {'roll °':>13} {'pitch °':>13} "
                  f"{'yaw °':>13}")
            for name in ("forward", "smoothed"):
                a = ev[name]["all"]
                cells = [f"{a[k]['rms']:6.3f}({a[k]['mean']:+6.3f})" for k in
                         ("north", "east", "down", "vn", "ve", "vd", "roll", "pitch", "yaw")]
                print(f"  {name:9} " + " ".join(f"{c:>13}" for c in cells))
        print("outage test: largest distance to the removed fixes (m), median / max over "
              "windows")
        print(f"  {'length':>6} {'n':>3} {'fwd horiz':>15} {'smo horiz':>15} "
              f"{'fwd vert':>15} {'smo vert':>15}" + (f" {'fwd ref h':>11} {'smo ref h':>11}"
                                                     if rec.reference is not None else ""))
        for length in (10.0, 20.0, 30.0):
            if rec.reference is not None:
                a = rec.imu.time[0] + 15.0
                windows = [(a, a + length)]
            else:
                windows = R.moving_windows(rec, length, 60.0)
            rows = R.outage_test(rec, windows)["windows"]

            def col(key, rows=rows):
                v = np.array([r[key] for r in rows if r.get(key) is not None])
                return f"{np.median(v):7.3f}/{v.max():7.3f}" if v.size else "—"

            line = (f"  {length:5.0f}s {len(rows):3d} {col('forward_max_h_m'):>15} "
                    f"{col('smoothed_max_h_m'):>15} {col('forward_max_v_m'):>15} "
                    f"{col('smoothed_max_v_m'):>15}")
            if rec.reference is not None:
                line += (f" {col('forward_ref_max_h_m').split('/')[0]:>11} "
                         f"{col('smoothed_ref_max_h_m').split('/')[0]:>11}")
            print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
