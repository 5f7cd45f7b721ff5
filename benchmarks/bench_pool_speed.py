"""Speed and memory of the pool calibration on a 10-million-point laser cloud plus
2 million multibeam soundings.

The laser cloud is cropped to the design's bounding box and voxel-downsampled (2 cm)
before the design-guided RANSAC/DBSCAN segmentation (per-face sets capped at 20 000
points); the multibeam soundings are georeferenced in chunks and segmented the same way.
Times per stage; peak traced memory (tracemalloc sees numpy allocations, not open3d's)
and the process maxrss. Run: ``.venv/bin/python benchmarks/bench_pool_speed.py``.
"""

from __future__ import annotations

import argparse
import resource
import time
import tracemalloc

from hydrosync_core.methods.pool_calibration.estimator import segment
from hydrosync_core.methods.pool_calibration.simulate import PoolPassConfig, simulate_pool_pass
from hydrosync_core.methods.pool_calibration.solve import solve


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--laser", type=float, default=10e6, help="laser points wanted")
    parser.add_argument("--mbes", type=float, default=2e6, help="soundings wanted")
    args = parser.parse_args()
    # Above-water area seen by the scanner is about 26 m²; about 87 % of the beams return.
    density = args.laser / 25.8
    passes = (3.5, 4.25, 5.0, 5.75, 6.5, 7.25)
    rays_per_ping = 512
    ping_hz = args.mbes / 0.87 / (len(passes) * 21.0 * rays_per_ping)
    cfg = PoolPassConfig(ranges_m=passes, beams=rays_per_ping, ping_rate_hz=ping_hz,
                         laser_density_per_m2=density)
    t0 = time.perf_counter()
    sim = simulate_pool_pass(cfg, seed=5)
    t_sim = time.perf_counter() - t0
    n_l, n_m = len(sim["lidar"]), len(sim["mbes"]["time"])

    tracemalloc.start()
    base = tracemalloc.get_traced_memory()[0]
    t0 = time.perf_counter()
    seg = segment(sim["lidar"], sim["mbes"], sim["ins"], sim["setup"], sim["target"])
    t_seg = time.perf_counter() - t0
    t0 = time.perf_counter()
    res = solve(seg)
    t_it = time.perf_counter() - t0
    peak = tracemalloc.get_traced_memory()[1] - base
    tracemalloc.stop()
    maxrss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    t = sim["truth"]
    d_ang = ", ".join(f"{k} {res.boresight_deg[k] - t['boresight_deg'][k]:+.4f}"
                      for k in ("roll", "pitch", "yaw"))
    d_lev = ", ".join(f"{k} {1000 * (res.lever_arm_m[k] - t['lever_arm_m'][k]):+.2f}"
                      for k in "xyz")
    rows = [
        ("laser points", f"{n_l:,}"),
        ("multibeam soundings", f"{n_m:,} ({len(passes)} passes, {rays_per_ping} beams, "
                                f"{ping_hz:.0f} Hz)"),
        ("INS epochs", f"{len(sim['ins']['time']):,}"),
        ("simulation", f"{t_sim:.1f} s"),
        ("segment (crop, voxel, RANSAC, DBSCAN)", f"{t_seg:.1f} s"),
        ("iterate (seed rounds, lever, joint)", f"{t_it:.1f} s ({res.iterations} seed "
                                                f"iterations)"),
        ("total calibration", f"{t_seg + t_it:.1f} s"),
        ("peak traced memory of calibration", f"{peak / 2**20:.0f} MiB"),
        ("process maxrss", f"{maxrss:.0f} MiB (incl. simulated data)"),
        ("joint error: angles (deg)", d_ang),
        ("joint error: lever arm (mm)", d_lev),
    ]
    width = max(len(k) for k, _ in rows)
    print("pool calibration speed: 10 M laser points + 2 M soundings")
    for k, v in rows:
        print(f"  {k:<{width}}  {v}")


if __name__ == "__main__":
    main()
