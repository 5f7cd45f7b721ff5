"""Accuracy of the pool calibration over simulated passes: seed method vs joint adjustment.

Each run simulates a full calibration data set (3 passes at 4, 5.5 and 7 m, 256 beams at
15 Hz, 1 cm range and 0.03° beam-angle noise, 1 % multibeam outliers, 3 mm laser noise
with clutter) with random boresight errors (uniform ±1°, both signs) and lever-arm errors
(uniform ±8 cm) on each of the six parameters, then runs segmentation, the seed (patent)
iteration + lever-arm steps, and the joint least-squares adjustment.

Per run: rotation error = angle of R_est·R_trueᵀ (deg), lever error = |Δl| (mm), and the
joint's normalised errors (estimate - truth) / σ. Summary per parameter (Monte-Carlo over
the runs): bias (mean error), scatter (sample SD), RMS error, mean reported 1-σ and the
RMS of error/σ, which must be ≈ 1 for an honest σ (with n runs its own spread is about
1/√(2n)). The seed method reports no σ. ``--ins-noise-deg`` adds Gauss-Markov INS
attitude errors (τ = 1 s) to roll, pitch and heading; ``--ins-sigma-deg`` is the INS
accuracy given to the adjustment (default: the simulated one; 0 to see the σ without it,
with only the ping-block inflation).
Run: ``.venv/bin/python benchmarks/bench_pool_accuracy.py [--runs 12] [--ins-noise-deg 0]
[--ins-sigma-deg X]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from scipy.spatial.transform import Rotation

from hydrosync_core.methods.pool_calibration import georef
from hydrosync_core.methods.pool_calibration.api import calibrate
from hydrosync_core.methods.pool_calibration.simulate import PoolPassConfig, simulate_pool_pass

PARAMS = ("roll", "pitch", "yaw", "lever_x", "lever_y", "lever_z")
UNITS = ("deg", "deg", "deg", "mm", "mm", "mm")


def _vector(sol: dict, key: str = "") -> np.ndarray:
    """(roll, pitch, yaw) deg and lever (x, y, z) mm of a solution (or its σ with key)."""
    b = sol["sigma_boresight_deg" if key else "boresight_deg"]
    la = sol["sigma_lever_arm_m" if key else "lever_arm_m"]
    return np.array([b["roll"], b["pitch"], b["yaw"]] + [1000 * la[k] for k in "xyz"])


def _rotation_error(sol: dict, truth: dict) -> float:
    b, t = sol["boresight_deg"], truth["boresight_deg"]
    r_est = georef.boresight_matrix(*np.deg2rad([b["roll"], b["pitch"], b["yaw"]]))
    r_tru = georef.boresight_matrix(*np.deg2rad([t["roll"], t["pitch"], t["yaw"]]))
    return float(np.degrees(Rotation.from_matrix(r_est @ r_tru.T).magnitude()))


def _summary(label: str, err: np.ndarray, sig: np.ndarray | None) -> None:
    print(f"{label}")
    print(f"  {'parameter':<10} {'unit':>4} {'bias':>9} {'SD':>9} {'RMS err':>9} "
          f"{'mean σ':>9} {'RMS e/σ':>8} {'max|e/σ|':>8}")
    for k, (name, unit) in enumerate(zip(PARAMS, UNITS, strict=True)):
        e = err[:, k]
        line = (f"  {name:<10} {unit:>4} {e.mean():+9.4f} {e.std(ddof=1):9.4f} "
                f"{np.sqrt(np.mean(e**2)):9.4f}")
        if sig is None:
            line += f" {'—':>9} {'—':>8} {'—':>8}"
        else:
            z = e / sig[:, k]
            line += (f" {sig[:, k].mean():9.4f} {np.sqrt(np.mean(z**2)):8.2f} "
                     f"{np.abs(z).max():8.2f}")
        print(line)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=12)
    parser.add_argument("--ins-noise-deg", type=float, default=0.0)
    parser.add_argument("--ins-sigma-deg", type=float, default=None)
    args = parser.parse_args()
    ins_sigma = args.ins_noise_deg if args.ins_sigma_deg is None else args.ins_sigma_deg
    params = {"ins_sigma_roll_deg": ins_sigma, "ins_sigma_pitch_deg": ins_sigma,
              "ins_sigma_heading_deg": ins_sigma, "ins_tau_s": 1.0}
    print(f"simulated INS attitude noise {args.ins_noise_deg}° (τ = 1 s); INS σ given to "
          f"the adjustment {ins_sigma}°")
    rng = np.random.default_rng(2026)
    err = {"seed": [], "joint": []}
    sig, rot = [], {"seed": [], "joint": []}
    print("pool calibration accuracy (per run: rotation error deg, |Δlever| mm; joint "
          "normalised errors (est - true)/σ for roll pitch yaw x y z)")
    print(f"{'run':>3} {'seed rot':>9} {'seed lev':>9} | {'joint rot':>9} {'joint lev':>9} | "
          f"{'normalised joint errors':<41} {'s':>5}")
    for run in range(args.runs):
        ang = rng.uniform(-1.0, 1.0, 3)
        lev = rng.uniform(-0.08, 0.08, 3)
        cfg = PoolPassConfig(boresight_error_deg=tuple(ang), lever_error_m=tuple(lev),
                             ins_attitude_noise_deg=args.ins_noise_deg)
        sim = simulate_pool_pass(cfg, seed=100 + run)
        t0 = time.perf_counter()
        res = calibrate(sim["lidar"], sim["mbes"], sim["ins"], sim["setup"], sim["target"],
                        params)
        dt = time.perf_counter() - t0
        d = res.to_dict()
        truth = _vector(sim["truth"])
        line = f"{run:>3}"
        for key in ("seed", "joint"):
            e = _vector(d[key]) - truth
            err[key].append(e)
            rot[key].append(_rotation_error(d[key], sim["truth"]))
            line += f" {rot[key][-1]:9.4f} {np.linalg.norm(e[3:]):9.2f} |"
        s = _vector(d["joint"], "sigma")
        sig.append(s)
        line += " " + " ".join(f"{v:+6.2f}" for v in err["joint"][-1] / s) + f" {dt:5.1f}"
        print(line, flush=True)
    print()
    _summary(f"seed method ({args.runs} runs; no σ reported)", np.array(err["seed"]), None)
    _summary(f"joint adjustment ({args.runs} runs)", np.array(err["joint"]), np.array(sig))
    for key in ("seed", "joint"):
        r = np.array(rot[key])
        print(f"{key:>5}: rotation error mean {r.mean():.4f}° max {r.max():.4f}°")


if __name__ == "__main__":
    main()
