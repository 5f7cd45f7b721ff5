"""Speed and memory of the latency estimate on a full survey day.

500 lines of 2 minutes, 100 Hz attitude, 10 Hz GNSS, scan −1..+1 s with a 1 ms step
(2001 candidates per line), end to end (trend removal, scan, refinement, uncertainty,
combination, σ0, synchronised output). Peak memory of the estimation is measured with
tracemalloc (numpy reports its allocations to it); the process's maxrss is shown too.
Run: ``.venv/bin/python benchmarks/bench_latency_speed.py``.
"""

from __future__ import annotations

import argparse
import resource
import time
import tracemalloc

from hydrosync_core.methods.latency import estimate_latency, synchronise
from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, default=500)
    parser.add_argument("--step", type=float, default=0.001)
    args = parser.parse_args()
    cfg = DayConfig(latency_s=0.123, n_lines=args.lines, line_s=120.0, run_in_s=10.0,
                    turn_s=30.0, gnss_hz=10.0, attitude_hz=100.0)
    t0 = time.perf_counter()
    day = simulate_day(cfg, seed=7)
    t_sim = time.perf_counter() - t0
    n_att, n_gnss = day["attitude"]["time"].size, day["gnss"]["time"].size

    tracemalloc.start()
    base = tracemalloc.get_traced_memory()[0]
    t0 = time.perf_counter()
    res = estimate_latency(day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m,
                           {"range_s": (-1.0, 1.0), "step_s": args.step})
    t_est = time.perf_counter() - t0
    peak_est = tracemalloc.get_traced_memory()[1] - base
    tracemalloc.reset_peak()
    base = tracemalloc.get_traced_memory()[0]
    t0 = time.perf_counter()
    sync = synchronise(day["gnss"], day["attitude"], cfg.lever_arm_m, res.latency_s)
    t_sync = time.perf_counter() - t0
    peak_sync = tracemalloc.get_traced_memory()[1] - base
    tracemalloc.stop()
    maxrss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024

    print("latency speed: one survey day")
    rows = [
        ("lines", f"{args.lines} x {cfg.line_s:.0f} s"),
        ("attitude samples (100 Hz)", f"{n_att:,}"),
        ("GNSS epochs (10 Hz)", f"{n_gnss:,}"),
        ("candidates per line", f"{res.dt_grid.size} (step {args.step * 1e3:g} ms)"),
        ("simulation time", f"{t_sim:.1f} s"),
        ("estimate time", f"{t_est:.1f} s ({1e3 * t_est / args.lines:.0f} ms per line)"),
        ("synchronise time", f"{t_sync:.2f} s ({sync['time'].size:,} epochs)"),
        ("peak memory, estimate", f"{peak_est / 2**20:.0f} MiB above the input (tracemalloc)"),
        ("peak memory, synchronise", f"{peak_sync / 2**20:.0f} MiB above the input"),
        ("process maxrss", f"{maxrss:.0f} MiB (incl. simulated data)"),
        ("result", f"{res.latency_s:.4f} s (truth {cfg.latency_s}), 95 % "
                   f"[{res.ci95_low:.4f}, {res.ci95_high:.4f}], {res.n_used} lines used"),
    ]
    width = max(len(k) for k, _ in rows)
    for key, value in rows:
        print(f"{key:<{width}}  {value}")


if __name__ == "__main__":
    main()
