"""Tilt-pole alignment: the foreign swings and a Monte Carlo across IMU grades × conventions.

Part 1 — ``../shared/data/foreign/tilt/swing_*`` (made outside the team, with truth):
``hydrosync tilt``'s defaults (the joint method) per swing: horizontal and vertical tip
error, σ, the GNSS↔IMU offset it estimates (truth 0), the IMU noise it reports (truth
0.02°/s and 0.01 m/s² per sample), the warning, and the plain reference's tip error.

Part 2 — Monte Carlo: for each IMU grade (consumer / mems / industrial: the simulated
biases and noise drawn from the grade's documented numbers, the solver told the grade)
and each IMU convention (``instant`` and ``interval-end``, declared as the data set
would), ``--runs`` swings per tilt class (< 40°, 40–60°). Each run draws a swing
(amplitude, line or ellipse, 1 or 3 sweeps, twist, hand wobble), a pole of 1.2–2.5 m, an
IMU at 50/100/200 Hz with white or low-passed noise, GNSS at 5/10/20 Hz with 1–1.5 cm
horizontal and 2–3 cm vertical noise, a GNSS gap (up to 1 s) in half the runs and a
gravity off the standard value. Printed per cell: share of tips within 1 cm, the largest
error, σ coverage (east/north at 1.96σ: 95 % when honest; 2-D: the mean of the squared
Mahalanobis distance of the horizontal error over 2 — 1 when honest — and the share inside
the 95 % ellipse), the mean estimated GNSS offset
(truth 0), the warning rule of issue #30 (swings without the warning within 1 cm; share
of the swings within 1 cm warned about anyway, at most a fifth), the median IMU noise the
joint method reports over the simulated (gyro/accelerometer) and the plain reference's
share within 1 cm. ``--all-methods`` adds Li et al.'s heading-only methods.

Second opinion (``reference_tip``): a plain batch least squares written here, sharing no
code with the joint method but the attitude propagation: the same 12 unknowns (initial
attitude, tip, gyro and accelerometer biases with the grade's priors), GNSS positions
with their stated σ and the accelerometers as 0.2-s velocity increments against the
modelled antenna velocity, white weights, ``scipy.optimize.least_squares``.

Part 3 (``--demo-mc N``): the Monte Carlo the demo used to run by default (issue #23: it
took 116 s of a 173-s demo): the demo record solved with ``monte_carlo_runs = N``, which
fills the panel's and the report's Monte-Carlo figures, written to ``--demo-out``.

Run: ``.venv/bin/python benchmarks/bench_tilt.py`` (about 6 minutes on two loaded cores;
``--runs 4`` for a quick look).
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

from hydrosync_core.methods.tilt_alignment.geometry import propagate
from hydrosync_core.methods.tilt_alignment.imu_convention import to_model_grid
from hydrosync_core.methods.tilt_alignment.montecarlo import run_monte_carlo, statistics
from hydrosync_core.methods.tilt_alignment.params import IMU_GRADES, TiltParams
from hydrosync_core.methods.tilt_alignment.pipeline import solve_record

FOREIGN = Path(__file__).resolve().parents[1] / ".." / "shared" / "data" / "foreign" / "tilt"
CONVENTIONS = ("instant", "interval-end")


def _rotvec_matrix(v: np.ndarray) -> np.ndarray:
    from scipy.spatial.transform import Rotation

    return Rotation.from_rotvec(v).as_matrix()


def reference_tip(time, gyro, accel, gnss_t, gnss_ned, length, C0, tip0, grade: str,
                  convention: str, sigma_h=0.01, sigma_v=0.02, g=9.80665) -> np.ndarray:
    """Tip (NED, m) of the plain batch least squares (see the module)."""
    from scipy.optimize import least_squares

    t, w, f = to_model_grid(time, gyro, accel, convention)
    pri = IMU_GRADES[grade]
    sbg, sba = math.radians(pri.gyro_bias_deg_s), pri.accel_bias_m_s2
    dt = float(np.median(np.diff(t)))
    step = max(2, int(round(0.2 / dt)))
    edges = np.arange(1, t.size - 1, step)
    sf = float(np.std(np.diff(f, axis=0)) / math.sqrt(2))
    sw = float(np.std(np.diff(w, axis=0)) / math.sqrt(2))
    # velocity from central differences of the modelled antenna: its gyro noise is
    # l·σ_ω/√2 per edge; a block's increment adds the accelerometer noise σ_f·Δt·√n
    s_blk = math.hypot(length * sw, sf * dt * math.sqrt(step))
    e_down = np.array([0.0, 0.0, 1.0])

    def residuals(x):
        C = propagate(_rotvec_matrix(x[:3]) @ C0, t, w, x[6:9])
        p = x[3:6] - C[:, :, 2] * length
        k = np.clip(np.searchsorted(t, gnss_t) - 1, 0, t.size - 2)
        a = (gnss_t - t[k]) / (t[k + 1] - t[k])
        p_at = p[k] * (1 - a)[:, None] + p[k + 1] * a[:, None]
        rg = (gnss_ned - p_at) / np.array([sigma_h, sigma_h, sigma_v])
        v = (p[edges + 1] - p[edges - 1]) / (2 * dt)
        acc = np.einsum("kij,kj->ki", C, f - x[9:12]) + g * e_down
        cum = np.vstack([np.zeros(3), np.cumsum(0.5 * (acc[1:] + acc[:-1]) * dt, axis=0)])
        ra = ((cum[edges[1:]] - cum[edges[:-1]]) - (v[1:] - v[:-1])) / s_blk
        return np.concatenate([rg.ravel(), ra.ravel(), x[6:9] / sbg, x[9:12] / sba])

    x0 = np.concatenate([np.zeros(3), tip0, np.zeros(6)])
    sol = least_squares(residuals, x0, x_scale=np.r_[[1e-2] * 3, [1e-2] * 3, [1e-3] * 3,
                                                        [1e-2] * 3])
    return sol.x[3:6]


def _solve(time, gyro, accel, gnss_t, gnss_ned, length, params, g, convention):
    sol = solve_record(time, gyro, accel, gnss_t, gnss_ned, length, params, gravity=g,
                       imu_convention=convention)
    j = sol.methods["joint"]
    start = sol.methods["closed_form"] if sol.methods["closed_form"].ok else j
    ref = (reference_tip(time, gyro, accel, gnss_t, gnss_ned, length, start.C0, start.tip,
                         params.imu_grade, sol.imu_convention, params.sigma_h_m,
                         params.sigma_v_m, sol.gravity)
           if start.C0 is not None else np.full(3, np.nan))
    return sol, ref


def foreign_table() -> list[dict]:
    """Part 1: every foreign swing with the command's defaults."""
    from hydrosync_core.methods.tilt_alignment.io import (
        gnss_to_local,
        read_gnss_csv,
        read_imu_csv,
    )

    rows = []
    for d in sorted(FOREIGN.glob("swing_*")):
        imu, gnss = read_imu_csv(d / "imu.csv"), read_gnss_csv(d / "gnss.csv")
        length = json.loads((d / "pole.json").read_text())["pole_length_m"]
        truth = json.loads((d / "truth.json").read_text())
        ned, _ = gnss_to_local(gnss)
        tip_true = np.array([truth["tip_enu"][1], truth["tip_enu"][0], -truth["tip_enu"][2]])
        gyro = np.column_stack([imu[k] for k in ("gx", "gy", "gz")])
        accel = np.column_stack([imu[k] for k in ("ax", "ay", "az")])
        p = TiltParams()
        sol, ref = _solve(imu["time"], gyro, accel, gnss["time"], ned, length, p, None, None)
        j, jr = sol.methods["joint"], sol.joint
        err = j.tip - tip_true
        rows.append({"swing": d.name, "max_tilt": truth["max_tilt_deg"],
                     "h_mm": 1000 * math.hypot(*err[:2]), "v_mm": 1000 * err[2],
                     "sd_h_mm": 1000 * float(np.max(j.tip_std[:2])),
                     "tau_ms": 1000 * (jr.time_offset_s + jr.time_offset_applied_s),
                     "tau_sd_ms": 1000 * jr.time_offset_std_s,
                     "gyro_noise": math.degrees(jr.gyro_noise_rad_s),
                     "accel_noise": jr.accel_noise_m_s2, "warned": j.warning is not None,
                     "ref_h_mm": 1000 * math.hypot(*(ref - tip_true)[:2])})
    return rows


def _print_foreign(rows: list[dict]) -> None:
    if not rows:
        print(f"foreign swings: none at {FOREIGN} (skipped)")
        return
    print("Foreign swings (../shared/data/foreign/tilt), hydrosync tilt defaults (joint, "
          "mems, instant):")
    print(f"{'swing':<18} {'tilt°':>5} {'H mm':>5} {'V mm':>5} {'σH mm':>5} "
          f"{'offset ms':>11} {'gyro °/s':>8} {'acc m/s²':>8} {'warn':>4} {'ref H mm':>8}")
    for r in rows:
        print(f"{r['swing']:<18} {r['max_tilt']:5.1f} {r['h_mm']:5.1f} {r['v_mm']:5.1f} "
              f"{r['sd_h_mm']:5.1f} {r['tau_ms']:+5.1f}±{r['tau_sd_ms']:3.1f} "
              f"{r['gyro_noise']:8.3f} {r['accel_noise']:8.3f} "
              f"{'yes' if r['warned'] else 'no':>4} {r['ref_h_mm']:8.1f}")


def _reference_column(grade: str):
    def extra(sim):
        cfg = sim["truth"]["config"]
        p = TiltParams(imu_grade=grade, sigma_h_m=cfg.gnss_sigma_h_m,
                       sigma_v_m=cfg.gnss_sigma_v_m)
        sol, ref = _solve(sim["time"], sim["gyro"], sim["accel"], sim["gnss_time"],
                          sim["gnss_ned"], sim["pole_length_m"], p, cfg.gravity_m_s2,
                          cfg.imu_convention)
        err = ref - sim["truth"]["tip_ned"]
        jr = sol.joint
        root = math.sqrt(cfg.imu_rate_hz)
        e2 = sol.methods["joint"].tip[:2] - sim["truth"]["tip_ned"][:2]
        d2 = (float(e2 @ np.linalg.solve(jr.cov[3:5, 3:5], e2))
              if jr is not None and sol.methods["joint"].ok else math.nan)
        return {"ref_h_err": float(math.hypot(*err[:2])),
                # squared Mahalanobis distance of the horizontal tip error (χ²₂ if honest)
                "joint_d2": d2,
                "joint_offset_ms": (1000 * (jr.time_offset_s + jr.time_offset_applied_s)
                                    if jr is not None else math.nan),
                # the IMU noise the joint method reports over the simulated (grade's
                # density × √rate: per sample for white noise, the random walk's
                # equivalent for low-passed noise)
                "gyro_noise_x": (jr.gyro_noise_rad_s
                                 / (math.radians(cfg.gyro_noise_deg_s_rthz) * root)
                                 if jr is not None else math.nan),
                "accel_noise_x": (jr.accel_noise_m_s2 / (cfg.accel_noise_m_s2_rthz * root)
                                  if jr is not None else math.nan)}
    return extra


def monte_carlo(runs: int, seed: int, grades=tuple(IMU_GRADES), conventions=CONVENTIONS
                ) -> list[tuple]:
    """Part 2: one Monte Carlo per grade × convention × tilt class."""
    out = []
    for gi, grade in enumerate(IMU_GRADES):
        if grade not in grades:
            continue
        for ci, conv in enumerate(CONVENTIONS):
            if conv not in conventions:
                continue
            parts = []
            for ti, tilt in enumerate(((15.0, 40.0), (40.0, 60.0))):
                params = TiltParams(imu_grade=grade, monte_carlo_runs=0)
                parts.append(run_monte_carlo(
                    runs, params, seed=seed + 100 * gi + 10 * ci + ti, tilt_range=tilt,
                    overrides={"imu_convention": conv}, grade=grade,
                    extra=_reference_column(grade)))
            mc = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
            out.append((grade, conv, mc))
    return out


def _print_mc(cells, methods) -> None:
    print(f"{'grade':<10} {'convention':<12} {'method':<11} {'tilt':<6} {'runs':>4} "
          f"{'H≤1cm':>6} {'H max mm':>8} {'cov E/N':>7} {'2-D d²/2':>8} {'offset ms':>9} "
          f"{'quiet≤1cm':>9} {'warned|≤1cm':>11} {'noise× g/a':>10} {'ref H≤1cm':>9}")
    for grade, conv, mc in cells:
        tilt = mc["hold_tilt_deg"]
        for name in methods:
            for label, mask in (("<40°", tilt < 40.0), ("40-60°", tilt >= 40.0),
                                ("all", np.ones(tilt.size, bool))):
                s = statistics(mc, name, mask)
                ref = float(np.mean(mc["ref_h_err"][mask] <= 0.01))
                off = float(np.nanmean(mc["joint_offset_ms"][mask]))
                d2 = (f"{np.nanmean(mc['joint_d2'][mask]) / 2:.2f}/"
                      f"{_pct(np.nanmean(mc['joint_d2'][mask] < 5.991)).strip()}"
                      if name == "joint" else "")
                noise = (f"{np.nanmedian(mc['gyro_noise_x'][mask]):.2f}/"
                         f"{np.nanmedian(mc['accel_noise_x'][mask]):.2f}"
                         if name == "joint" else "")
                print(f"{grade:<10} {conv:<12} {name:<11} {label:<6} {s['runs']:>4} "
                      f"{100 * s['h_within_1cm']:5.0f}% {1000 * s['h_max_m']:8.1f} "
                      f"{_pct(s['coverage_e'])}/{_pct(s['coverage_n'])} {d2:>8} "
                      f"{(f'{off:+.2f}' if name == 'joint' else ''):>9} "
                      f"{_pct(s['h_within_1cm_quiet']):>8}% "
                      f"{_pct(s['warned_within_1cm']):>10}% {noise:>10} {100 * ref:8.0f}%")


def demo_monte_carlo(runs: int, out: Path | None) -> None:
    """Part 3: the demo record with its own Monte Carlo (the panel's figures)."""
    from hydrosync_core.methods.tilt_alignment import demo, project_run
    from hydrosync_core.project import Project

    project = Project.new("tilt demo with Monte Carlo")
    demo.fill_demo(project, seed=0)
    t0 = time.perf_counter()
    project_run.run(project, TiltParams(monte_carlo_runs=runs))
    dt = time.perf_counter() - t0
    mc = project.get_table(f"{project_run.RESULT}/montecarlo")
    s = statistics(mc, "joint")
    print(f"demo record with {runs} Monte-Carlo runs: {dt:.1f} s; joint H≤1cm "
          f"{100 * s['h_within_1cm']:.0f}%, H max {1000 * s['h_max_m']:.1f} mm")
    if out is not None:
        project.save(out)
        print(f"written to {out}")


def _pct(x: float) -> str:
    return " --" if not np.isfinite(x) else f"{100 * x:3.0f}"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=12,
                    help="runs per grade × convention × tilt class (default 12: 144 in all)")
    ap.add_argument("--seed", type=int, default=2024)
    ap.add_argument("--all-methods", action="store_true",
                    help="also Li et al.'s heading-only methods")
    ap.add_argument("--no-foreign", action="store_true")
    ap.add_argument("--grades", default=",".join(IMU_GRADES), help="grades to simulate")
    ap.add_argument("--conventions", default=",".join(CONVENTIONS),
                    help="IMU conventions to simulate")
    ap.add_argument("--demo-mc", type=int, default=0, metavar="N",
                    help="also run the demo record with N Monte-Carlo runs (part 3)")
    ap.add_argument("--demo-out", type=Path, help="project file for --demo-mc")
    args = ap.parse_args()
    if args.demo_mc:
        demo_monte_carlo(args.demo_mc, args.demo_out)
    t0 = time.perf_counter()
    if not args.no_foreign:
        _print_foreign(foreign_table())
        print(f"({time.perf_counter() - t0:.1f} s)\n")
    if args.runs <= 0:
        return
    t1 = time.perf_counter()
    cells = monte_carlo(args.runs, args.seed, tuple(args.grades.split(",")),
                        tuple(args.conventions.split(",")))
    n = sum(c[2]["run"].size for c in cells)
    dt = time.perf_counter() - t1
    print(f"Monte Carlo: {n} simulated swings ({dt:.0f} s, {1000 * dt / max(n, 1):.0f} ms "
          "per run with the reference)")
    methods = (("joint", "mbgd", "bgd", "sgd", "svd", "closed_form") if args.all_methods
               else ("joint",))
    _print_mc(cells, methods)


if __name__ == "__main__":
    main()
