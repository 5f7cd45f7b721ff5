"""Accuracy of the pool calibration over simulated passes: seed method vs joint adjustment.

Each run simulates a full calibration data set (3 passes at 4, 5.5 and 7 m, 256 beams at
15 Hz, 1 cm range and 0.03° beam-angle noise, 1 % multibeam outliers, 3 mm laser noise
with clutter) with random boresight errors (uniform ±1°, both signs) and lever-arm errors
(uniform ±8 cm) on each of the six parameters, then runs segmentation, the seed (patent)
iteration + lever-arm steps, and the joint least-squares adjustment.
Rotation error = angle of R_est·R_trueᵀ (deg); lever error = |Δl| (mm).
Run: ``.venv/bin/python benchmarks/bench_pool_accuracy.py [--runs 12]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from scipy.spatial.transform import Rotation

from hydrosync_core.methods.pool import georef
from hydrosync_core.methods.pool.api import calibrate
from hydrosync_core.simulate.pool_pass import PoolPassConfig, simulate_pool_pass


def _errors(sol: dict, truth: dict) -> tuple[float, np.ndarray, float, np.ndarray]:
    b, t = sol["boresight_deg"], truth["boresight_deg"]
    r_est = georef.boresight_matrix(*np.deg2rad([b["roll"], b["pitch"], b["yaw"]]))
    r_tru = georef.boresight_matrix(*np.deg2rad([t["roll"], t["pitch"], t["yaw"]]))
    rot = float(np.degrees(Rotation.from_matrix(r_est @ r_tru.T).magnitude()))
    d_ang = np.array([b[k] - t[k] for k in ("roll", "pitch", "yaw")])
    d_lev = 1000 * np.array([sol["lever_arm_m"][k] - truth["lever_arm_m"][k] for k in "xyz"])
    return rot, d_ang, float(np.linalg.norm(d_lev)), d_lev


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=12)
    args = parser.parse_args()
    rng = np.random.default_rng(2026)
    rows = {"seed": [], "joint": []}
    print("pool calibration accuracy (per run: rotation error deg | max |Δangle| deg | "
          "|Δlever| mm | max |Δlever axis| mm)")
    print(f"{'run':>3} {'seed rot':>9} {'seed ang':>9} {'seed lev':>9} {'seed ax':>8} | "
          f"{'joint rot':>9} {'joint ang':>9} {'joint lev':>9} {'joint ax':>8} "
          f"{'σ max°':>7} {'σ max mm':>8} {'s':>5}")
    for run in range(args.runs):
        ang = rng.uniform(-1.0, 1.0, 3)
        lev = rng.uniform(-0.08, 0.08, 3)
        cfg = PoolPassConfig(boresight_error_deg=tuple(ang), lever_error_m=tuple(lev))
        sim = simulate_pool_pass(cfg, seed=100 + run)
        t0 = time.perf_counter()
        res = calibrate(sim["lidar"], sim["mbes"], sim["ins"], sim["setup"], sim["target"])
        dt = time.perf_counter() - t0
        d = res.to_dict()
        line = f"{run:>3}"
        for key in ("seed", "joint"):
            rot, da, ln, dl = _errors(d[key], sim["truth"])
            rows[key].append((rot, np.max(np.abs(da)), ln, np.max(np.abs(dl))))
            line += f" {rot:9.4f} {np.max(np.abs(da)):9.4f} {ln:9.2f} {np.max(np.abs(dl)):8.2f}"
            line += " |" if key == "seed" else ""
        sj = d["joint"]
        line += (f" {max(sj['sigma_boresight_deg'].values()):7.4f}"
                 f" {1000 * max(sj['sigma_lever_arm_m'].values()):8.2f} {dt:5.1f}")
        print(line, flush=True)
    print()
    print(f"{'summary':<24} {'rot mean':>9} {'rot max':>9} {'ang max':>9} "
          f"{'lev mean':>9} {'lev max':>9}")
    for key in ("seed", "joint"):
        a = np.array(rows[key])
        print(f"{key + ' (' + str(len(a)) + ' runs)':<24} {a[:, 0].mean():9.4f} "
              f"{a[:, 0].max():9.4f} {a[:, 1].max():9.4f} {a[:, 2].mean():9.2f} "
              f"{a[:, 2].max():9.2f}")
    print("units: rotation/angles in degrees, lever arm in millimetres")


if __name__ == "__main__":
    main()
