"""Accuracy of the latency estimate: Monte-Carlo over simulated survey days.

For each GNSS rate (1 Hz like the seed's RTK, 10 Hz) and true delay (+0.29 s, −0.15 s),
simulate N days of 13 two-minute lines (50 Hz attitude, R ≈ 0.85–0.95 as in the seed's
table 1), estimate the delay with default parameters and report the bias and RMSE of the
final Δt against the truth, the mean reported uncertainty, the coverage of the 95 %
interval, and the lines' R range. Run: ``.venv/bin/python benchmarks/bench_latency_accuracy.py``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from hydrosync_core.methods.latency import estimate_latency
from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day


def run_case(gnss_hz: float, latency: float, days: int, weighting: str) -> dict:
    errors, uncert, covered, r_all, line_err, line_unc = [], [], [], [], [], []
    for seed in range(days):
        cfg = DayConfig(latency_s=latency, gnss_hz=gnss_hz)
        day = simulate_day(cfg, seed=1000 + seed)
        res = estimate_latency(day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m,
                               {"weighting": weighting})
        errors.append(res.latency_s - latency)
        uncert.append(res.uncertainty_s)
        covered.append(res.ci95_low <= latency <= res.ci95_high)
        r_all += [ln.r_max for ln in res.lines]
        line_err += [ln.latency_s - latency for ln in res.lines if ln.used]
        line_unc += [ln.uncertainty_s for ln in res.lines if ln.used]
    e = np.array(errors)
    le = np.array(line_err)
    return {
        "bias_ms": 1e3 * e.mean(), "rmse_ms": 1e3 * np.sqrt(np.mean(e**2)),
        "unc_ms": 1e3 * np.mean(uncert), "cover": np.mean(covered),
        "r5": np.percentile(r_all, 5), "r50": np.median(r_all), "r95": np.percentile(r_all, 95),
        "line_rmse_ms": 1e3 * np.sqrt(np.mean(le**2)), "line_unc_ms": 1e3 * np.mean(line_unc),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--days", type=int, default=20)
    args = parser.parse_args()
    print(f"latency accuracy, {args.days} simulated days per row, 13 lines x 120 s, 50 Hz attitude")
    print(f"{'GNSS':>5} {'true':>6} {'weights':>8} {'bias':>7} {'RMSE':>7} {'unc':>7} {'cov95':>6} "
          f"{'line RMSE':>9} {'line unc':>8} {'R p5/p50/p95':>17} {'time':>6}")
    print(f"{'Hz':>5} {'s':>6} {'':>8} {'ms':>7} {'ms':>7} {'ms':>7} {'':>6} {'ms':>9} {'ms':>8}")
    for hz in (1.0, 10.0):
        for latency in (0.29, -0.15):
            for weighting in ("r", "inverse_variance"):
                t0 = time.perf_counter()
                s = run_case(hz, latency, args.days, weighting)
                print(f"{hz:5.0f} {latency:+6.2f} {weighting[:8]:>8} {s['bias_ms']:7.2f} "
                      f"{s['rmse_ms']:7.2f} {s['unc_ms']:7.2f} {s['cover']:6.2f} "
                      f"{s['line_rmse_ms']:9.1f} {s['line_unc_ms']:8.1f} "
                      f"{s['r5']:.3f}/{s['r50']:.3f}/{s['r95']:.3f} "
                      f"{time.perf_counter() - t0:5.1f}s", flush=True)


if __name__ == "__main__":
    main()
