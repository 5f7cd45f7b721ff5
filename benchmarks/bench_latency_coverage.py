"""Coverage of the latency's 95 % interval over many simulated days (issue #15 part 2).

Each day draws a noise scenario (clean, paper-like, coloured), a sea state (calm,
moderate, rough), a GNSS rate (1, 5, 10, 20 Hz), a line length (30 s … 5 min) and a true
delay (−0.5 … 0.5 s), then every estimator runs with default parameters. Reported per
estimator: the fraction of days whose 95 % interval holds the truth (goal 0.92–0.98),
by scenario and rate, the widest interval, and the RMS of (error / σ).
Run: ``.venv/bin/python benchmarks/bench_latency_coverage.py [--days 240]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from hydrosync_core.methods.latency import estimate_latency
from hydrosync_core.methods.latency.params import ESTIMATORS
from hydrosync_core.methods.latency.simulate import SCENARIOS, SEA_STATES, scenario, simulate_day

RATES = (1.0, 5.0, 10.0, 20.0)
LINES_S = (30.0, 60.0, 120.0, 300.0)

REPORTED = (*ESTIMATORS, "auto")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--days", type=int, default=240)
    args = parser.parse_args()
    rng = np.random.default_rng(15)
    records = []
    t0 = time.perf_counter()
    for k in range(args.days):
        name = list(SCENARIOS)[k % 3]
        sea = list(SEA_STATES)[rng.integers(3)]
        hz = RATES[(k // 3) % 4]
        line_s = LINES_S[rng.integers(4)]
        truth = float(np.round(rng.uniform(-0.5, 0.5), 3))
        cfg = scenario(name, sea, latency_s=truth, gnss_hz=hz, line_s=line_s,
                       n_lines=int(rng.integers(6, 16)),
                       attitude_hz=50.0 if hz < 5 else 100.0)
        day = simulate_day(cfg, seed=5000 + k)
        results = {est: estimate_latency(day["gnss"], day["attitude"], day["lines"],
                                         cfg.lever_arm_m, {"estimator": est})
                   for est in ESTIMATORS}
        # estimator="auto" keeps the smaller-σ of qi2010 and weighted (same rule as estimate._auto)
        results["auto"] = min((results["qi2010"], results["weighted"]), key=lambda r: (
            r.uncertainty_s if r.converged and np.isfinite(r.uncertainty_s) else np.inf))
        for est, res in results.items():
            records.append((est, name, hz, res.converged,
                            res.ci95_low <= truth <= res.ci95_high,
                            (res.latency_s - truth) / res.uncertainty_s,
                            res.ci95_high - res.ci95_low))
    print(f"latency 95 % interval coverage over {args.days} simulated days "
          f"(scenarios x sea states x 1/5/10/20 Hz x 30-300 s lines), "
          f"{time.perf_counter() - t0:.0f} s")
    header = (f"{'estimator':>17} {'days':>5} {'cover':>6} {'RMS e/σ':>8} {'widest':>8} | "
              + " ".join(f"{n:>8}" for n in SCENARIOS) + " | "
              + " ".join(f"{r:>4.0f}Hz" for r in RATES))
    print(header)
    for est in REPORTED:
        rows = [r for r in records if r[0] == est]
        ok = [r for r in rows if r[3]]
        cover = np.mean([r[4] for r in ok])
        z = np.array([r[5] for r in ok])
        by_name = [np.mean([r[4] for r in ok if r[1] == n]) for n in SCENARIOS]
        by_rate = [np.mean([r[4] for r in ok if r[2] == hz]) for hz in RATES]
        print(f"{est:>17} {len(ok):>5} {cover:6.3f} {np.sqrt(np.mean(z**2)):8.2f} "
              f"{max(r[6] for r in ok) * 1e3:6.0f}ms | "
              + " ".join(f"{c:8.3f}" for c in by_name) + " | "
              + " ".join(f"{c:6.3f}" for c in by_rate))


if __name__ == "__main__":
    main()
