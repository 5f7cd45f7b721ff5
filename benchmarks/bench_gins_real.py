"""GNSS/INS smoother on real recordings (read in place): residuals, reference, outages.

``../shared/data/comma2k19-ex1`` (60 s highway, phone IMU 104 Hz, u-blox 10 Hz, the
provider's fused pose at 20 Hz — not independent) and
``../shared/data/rtkexplorer-gnss-imu/drive_0708`` (9 min, MEMS IMU 100 Hz, real-time RTK
4 Hz, no reference) and ``walk_0827`` (2 min hand-held, the same sensors), each through
:mod:`hydrosync_core.methods.gins_smoother.recordings` with no hand edits: the recording's
assumed IMU grade and options, the GNSS−IMU clock offset estimated from the turns
(:mod:`.clock`, no filter pass; the walk keeps its own timing) beside the second opinion of
the smoothed-residual grid (13 smoother runs), the alignment chosen by ``auto``.

Prints per recording: the clock offset; GNSS residual RMS N/E/D (trajectory with lever arm
minus fix) forward and smoothed; for comma2k19 the error RMS / mean against the reference;
then the outage test — GNSS removed for 10, 20 and 30 s (comma2k19: one window 15 s into
the segment; drive: windows every 60 s while moving faster than 2 m/s) — as the largest
horizontal and vertical distance of the trajectory to the *removed* fixes, forward and
smoothed (median and maximum over the windows; comma2k19 also against the reference).

Honesty of the σ, with the GNSS noise model of the file (``gnss_noise=file``, white, the
file's σ) and the default (``auto``: checked against the residuals and re-estimated when
they disagree; the line printed says what the σ were computed from):

* GNSS innovations normalised by their own predicted std (``ν/√S`` per N/E/D): RMS (1 if
  the noise model is right), autocorrelation at 1 s and at one fix, and the Ljung–Box
  p-value over 10 fixes (white if right);
* drive (RTK fixes ≈ cm truth): at every fix removed by the outage test, the error of the
  forward and smoothed position (lever arm applied) over ``√(σ_trajectory² + σ_fix²)`` —
  share within 1.96 and RMS per N/E/D.
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
         R.read_rtkexplorer),
        ("rtkexplorer walk_0827", DATA / "rtkexplorer-gnss-imu" / "walk_0827",
         R.read_rtkexplorer))


def _rms(r: np.ndarray) -> str:
    ok = np.isfinite(r).all(axis=1)
    v = np.sqrt(np.mean(r[ok] ** 2, axis=0))
    return f"{v[0]:7.3f} {v[1]:7.3f} {v[2]:7.3f}"


def _innov(check: dict) -> str:
    if check["rms"] is None:
        return "—"
    rho = " ".join("  —  " if r is None else f"{r:+.2f}" for r in check["rho_1s"])
    lag1 = " ".join(f"{r:+.2f}" for r in check["rho_lag1"])
    lb = " ".join(f"{p:.0e}" for p in check["ljung_box_p"])
    return ("RMS N/E/D " + " ".join(f"{v:5.2f}" for v in check["rms"])
            + f"   autocorrelation 1 s {rho}, one fix {lag1}, Ljung–Box p {lb}   "
            f"({check['fixes']} fixes)")


def _z_cells(z: np.ndarray) -> str:
    if z.size == 0:
        return "—"
    cov = np.mean(np.abs(z) <= 1.96, axis=0) * 100
    rms = np.sqrt(np.mean(z * z, axis=0))
    return " ".join(f"{c:4.0f}/{r:5.2f}" for c, r in zip(cov, rms, strict=True))


def velocity_second_opinion(rec: R.Recording, res, half_s: float = 0.5) -> None:
    """Velocity against the reference beside a plain second opinion: the fixes differenced
    over ±*half_s* against the reference differenced over the same span (both means over
    one window, so neither's own smoothing favours it); and the smoothed velocity's σ."""
    from hydrosync_core.methods.gins_smoother.evaluate import error_series

    g, ref = rec.gnss, rec.reference
    t = g.time[(g.time - half_s >= max(g.time[0], ref.time[0]))
               & (g.time + half_s <= min(g.time[-1], ref.time[-1]))]

    def ned(time, llh):
        lat0 = np.radians(llh[0, 0])
        return np.column_stack([np.radians(llh[:, 0]) * 6378137.0,
                                np.radians(llh[:, 1]) * 6378137.0 * np.cos(lat0),
                                -llh[:, 2]])

    def diff(time, xyz):
        a = np.column_stack([np.interp(t - half_s, time, xyz[:, c]) for c in range(3)])
        b = np.column_stack([np.interp(t + half_s, time, xyz[:, c]) for c in range(3)])
        return (b - a) / (2 * half_s)

    d = diff(g.time, ned(g.time, g.llh)) - diff(ref.time, ned(ref.time, ref.llh))
    e = error_series(res.smoothed, ref)
    z = np.column_stack([e[k] / e[f"sd_{k}"] for k in ("vn", "ve", "vd")])
    err = np.column_stack([e[k] for k in ("vn", "ve", "vd")])
    sd = np.median(np.column_stack([e[f"sd_{k}"] for k in ("vn", "ve", "vd")]), axis=0)
    print("  velocity vN/vE/vD (m/s): smoothed − reference RMS "
          + " ".join(f"{v:.3f}" for v in np.sqrt(np.mean(err ** 2, axis=0)))
          + ", mean " + " ".join(f"{v:+.3f}" for v in err.mean(axis=0))
          + ", its σ (median) " + " ".join(f"{v:.3f}" for v in sd)
          + ", RMS(e/σ) " + " ".join(f"{v:.2f}" for v in np.sqrt(np.mean(z ** 2, axis=0))))
    print(f"  second opinion, fixes differenced over {2 * half_s:g} s − reference differenced "
          "alike: RMS " + " ".join(f"{v:.3f}" for v in np.sqrt(np.mean(d ** 2, axis=0)))
          + ", mean " + " ".join(f"{v:+.3f}" for v in d.mean(axis=0))
          + f" ({t.size} fixes)")


def sigma_honesty(rec: R.Recording, outage: bool) -> None:
    """Normalised innovations and (RTK drive) normalised outage errors, per GNSS model:
    the file's white σ (before), the estimated model without thinning the fixes, and the
    default (after)."""
    from hydrosync_core.methods.gins_smoother import filter as F  # noqa: N812

    print("σ honesty: GNSS innovations / their predicted std (honest: RMS 1, autocorrelation 0)")
    for mode, thin in (("file", True), ("auto", False), ("auto", True)):
        keep = F.THIN_FACTORS
        F.THIN_FACTORS = keep if thin else ()
        try:
            t0 = time.process_time()
            res = run_gins(rec.imu, rec.gnss, rec.config,
                           GinsParams.from_dict({**rec.params, "gnss_noise": mode}))
            cpu = time.process_time() - t0
        finally:
            F.THIN_FACTORS = keep
        label = mode if thin or mode == "file" else "auto, no thinning"
        print(f"  {label:<17} {_innov(res.gnss_model['check'])}   CPU {cpu:.1f} s")
        print(f"        {res.gnss_model['summary']}")
    if not outage:
        return
    print("  outage test, removed RTK fixes as truth: (trajectory − fix) / √(σ_traj² + σ_fix²),"
          " % within 1.96 / RMS, N E D (honest: 95 / 1)")
    for length in (10.0, 20.0, 30.0):
        windows = R.moving_windows(rec, length, 60.0)
        for mode in ("file", "auto"):
            out = R.outage_test(rec, windows, {"gnss_noise": mode})
            z = out["normalised"]
            print(f"  {length:4.0f}s {mode:<5} fixes {z['smoothed'].shape[0]:4d}  forward "
                  f"{_z_cells(z['forward'])}   smoothed {_z_cells(z['smoothed'])}")


def main() -> int:
    for label, folder, reader in SETS:
        if not folder.is_dir():
            print(f"{label}: {folder} absent, skipped")
            continue
        t0 = time.perf_counter()
        rec = reader(folder)
        t_read = time.perf_counter() - t0
        shift, est = R.estimate_time_shift(rec)
        t_clock = time.perf_counter() - t0 - t_read
        t2 = time.perf_counter()
        grid_shift, _grid = R.time_shift_by_residuals(rec, half_range_s=0.3 if est else 0.6,
                                                      step_s=0.05 if est else 0.1)
        t_grid = time.perf_counter() - t2
        rec = R.shifted(rec, shift)
        t1 = time.perf_counter()
        res = run_gins(rec.imu, rec.gnss, rec.config, GinsParams.from_dict(rec.params))
        t_run = time.perf_counter() - t1
        span = rec.imu.time[-1] - rec.imu.time[0]
        print(f"\n=== {label}: {rec.imu.time.size} IMU epochs ({rec.imu.rate_hz:.0f} Hz), "
              f"{rec.gnss.time.size} GNSS fixes, {span:.0f} s ===")
        print(f"read {t_read:.2f} s, clock offset {t_clock:.2f} s, one forward+smoothed "
              f"run {t_run:.2f} s (second opinion: residual grid {t_grid:.0f} s)")
        print("clock: " + (est.text() if est is not None else "the recording's own timing")
              + f"; residual-grid minimum {grid_shift * 1e3:+.0f} ms")
        print(f"alignment: {res.alignment.get('method')}, {res.alignment.get('levelling')}; "
              f"start {res.alignment['start_time'] - rec.imu.time[0]:.1f} s at "
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
            print("  within 1.96σ (%), as is / with the reference's constant offset removed")
            for name in ("forward", "smoothed"):
                c, c0 = ev[name]["coverage"]["all"], ev[name]["coverage"]["offset_removed"]
                print(f"  {name:9} " + " ".join(
                    f"{k} {100 * c[k]['within_95']:.0f}/{100 * c0[k]['within_95']:.0f}"
                    for k in ("north", "east", "down", "vn", "ve", "vd", "roll", "pitch",
                              "yaw")))
            velocity_second_opinion(rec, res)
        sigma_honesty(rec, rec.reference is None)
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
