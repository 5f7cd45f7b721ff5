"""Accuracy of the pool calibration over randomised passes: patent method vs joint adjustment.

Every run draws a whole data set at random (``simulate.random_config``): the target kind —
the patent's (above-water blocks seen only by the laser scanner, congruent below-water twins
seen only by the multibeam at design heights, only the wall crossing the water), faces
crossing the water, or both mixed — the number and size of the blocks, their spacing,
which side's first block is lower and by how much, wall height, water level, as-built
errors of the below-water blocks within the build tolerance (±2 mm, ±0.01°), pass ranges
and headings, vessel speed and attitude dynamics, beam count and opening angle, laser
density and noise, stray returns, INS attitude noise and the coarse errors (±2°, ±0.15 m).
The multibeam sees what the geometry lets it see (first hit, blocks occlude each other,
grazing returns fade out). The adjustment is given the simulated INS accuracy and the
build tolerance.

Per run: rotation error = angle of R_est·R_trueᵀ (deg), lever error = |Δl| (mm), and the
joint's normalised errors (estimate − truth)/σ. Summary per group (two-pass and one-pass,
both kinds): max and RMS of the rotation and lever-arm errors for the patent method and
the joint adjustment side by side, RMS and max of |error/σ| per parameter (joint; only
where determined), and how often each parameter was declared undetermined (coarse value
kept) or flagged (σ above the warning threshold).

Run: ``.venv/bin/python benchmarks/bench_pool_accuracy.py [--runs 60] [--seed 2026]
[--noise default]`` (about 4 min on 2 cores); ``--runs 8`` for a quick look.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

import numpy as np
from scipy.spatial.transform import Rotation

from hydrosync_core.methods.pool_calibration import georef
from hydrosync_core.methods.pool_calibration.estimator import calibrate
from hydrosync_core.methods.pool_calibration.params import PoolParams
from hydrosync_core.methods.pool_calibration.simulate import (
    PoolPassConfig,
    random_config,
    simulate_pool_pass,
)

PARAMS = ("roll", "pitch", "yaw", "lever_x", "lever_y", "lever_z")
ROT_MAX_DEG, LEVER_MAX_MM = 0.02, 2.0
#: (target kind, passes) of the runs, cycled: two-pass runs on every kind, one-pass runs.
PLAN = (("patent", 2), ("crossing", 2), ("patent", 1), ("mixed", 2), ("crossing", 1),
        ("patent", 2), ("crossing", 2), ("patent", 1), ("mixed", 1), ("patent", 2))


def _vector(sol: dict, key: str = "") -> np.ndarray:
    """(roll, pitch, yaw) deg and lever (x, y, z) mm of a solution (or its σ with key)."""
    b = sol["sigma_boresight_deg" if key else "boresight_deg"]
    la = sol["sigma_lever_arm_m" if key else "lever_arm_m"]
    v = [b[k] for k in ("roll", "pitch", "yaw")] + [None if la[k] is None else 1000 * la[k]
                                                    for k in "xyz"]
    return np.array([np.nan if x is None else x for x in v], dtype=float)


def _rotation_error(sol: dict, truth: dict) -> float:
    b, t = sol["boresight_deg"], truth["boresight_deg"]
    r_est = georef.boresight_matrix(*np.deg2rad([b["roll"], b["pitch"], b["yaw"]]))
    r_tru = georef.boresight_matrix(*np.deg2rad([t["roll"], t["pitch"], t["yaw"]]))
    return float(np.degrees(Rotation.from_matrix(r_est @ r_tru.T).magnitude()))


#: The noise settings of a pass; ``--noise default`` holds them at the simulator's defaults
#: (the issue's "default noise") while everything else stays random.
NOISE_FIELDS = ("range_noise_m", "angle_noise_deg", "mbes_outlier_fraction", "laser_noise_m",
                "laser_stray_fraction", "ins_attitude_noise_deg")


def _one(run: int, kind: str, passes: int, rng: np.random.Generator,
         build: tuple[float, float], noise: str = "random") -> dict:
    cfg = random_config(rng, kind, passes, build_tol_m=build[0], build_tol_deg=build[1])
    if noise == "default":
        default = PoolPassConfig()
        cfg = replace(cfg, **{k: getattr(default, k) for k in NOISE_FIELDS})
    params = PoolParams(ins_sigma_deg=(cfg.ins_attitude_noise_deg,) * 3,
                        ins_tau_s=cfg.ins_noise_tau_s, build_tol_m=cfg.build_tol_m,
                        build_tol_deg=cfg.build_tol_deg)
    sim = simulate_pool_pass(cfg, seed=1000 + run)
    t0 = time.perf_counter()
    res = calibrate(sim["lidar"], sim["mbes"], sim["ins"], sim["setup"], sim["target"], params)
    d = res.to_dict()
    truth = _vector(sim["truth"])
    out = {"run": run, "kind": kind, "passes": passes, "seconds": time.perf_counter() - t0,
           "soundings": len(sim["mbes"]["time"]), "undetermined": {}, "flagged": {}}
    for key in ("seed", "joint"):
        sol = d[key]
        if sol is None:
            continue
        e = _vector(sol) - truth
        out[key] = {"err": e, "rot": _rotation_error(sol, sim["truth"]),
                    "lever": float(np.linalg.norm(e[3:]))}
    out["sigma"] = _vector(d["joint"], "sigma")
    out["budget"] = {src: np.array([np.nan if v.get(n) is None else
                                    v[n] * (1.0 if k < 3 else 1000.0)
                                    for k, n in enumerate(PARAMS)])
                     for src, v in (d["joint"].get("sigma_budget") or {}).items()}
    out["undetermined"] = {"seed": set(res.seed.undetermined),
                           "joint": set(res.joint.undetermined if res.joint else PARAMS)}
    out["flagged"] = set(res.flagged)
    return out


def _fmt_set(names) -> str:
    return ",".join(sorted(names, key=PARAMS.index)) or "-"


def _group(label: str, runs: list[dict]) -> None:
    if not runs:
        return
    print(f"\n{label}: {len(runs)} runs")
    print(f"  {'':<28} {'patent method':>22} {'joint adjustment':>22}")
    for what, unit in (("rot", "deg"), ("lever", "mm")):
        for stat in ("max", "RMS"):
            cells = []
            for key in ("seed", "joint"):
                v = np.array([r[key][what] for r in runs if key in r])
                cells.append(v.max() if stat == "max" else np.sqrt(np.mean(v**2)))
            name = "rotation error" if what == "rot" else "lever-arm error"
            print(f"  {stat + ' ' + name + ' [' + unit + ']':<28} {cells[0]:>22.4f} "
                  f"{cells[1]:>22.4f}")
    print(f"  {'parameter':<10} {'RMS e/σ':>8} {'max|e/σ|':>9} {'RMS err':>10} "
          f"{'mean σ':>10} {'undet. patent':>12} {'undet. joint':>13} {'flagged':>8}")
    for k, name in enumerate(PARAMS):
        z = np.array([r["joint"]["err"][k] / r["sigma"][k] for r in runs
                      if name not in r["undetermined"]["joint"]])
        e = np.array([r["joint"]["err"][k] for r in runs
                      if name not in r["undetermined"]["joint"]])
        s = np.array([r["sigma"][k] for r in runs if name not in r["undetermined"]["joint"]])
        unit = "°" if k < 3 else "mm"
        u_seed = sum(name in r["undetermined"]["seed"] for r in runs)
        u_joint = sum(name in r["undetermined"]["joint"] for r in runs)
        flag = sum(name in r["flagged"] for r in runs)
        if len(z):
            stats = (f"{np.sqrt(np.mean(z**2)):8.2f} {np.abs(z).max():9.2f} "
                     f"{np.sqrt(np.mean(e**2)):8.4f}{unit:<2}{s.mean():8.4f}{unit:<2}")
        else:
            stats = f"{'—':>8} {'—':>9} {'—':>10} {'—':>10}"
        print(f"  {name:<10} {stats} {u_seed:>12d} {u_joint:>13d} {flag:>8d}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=60)
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--build-tol", type=float, nargs=2, default=(0.002, 0.01),
                        metavar=("M", "DEG"), help="build tolerance of the below-water "
                        "blocks, simulated (uniform within ±) and given to the adjustment")
    parser.add_argument("--noise", choices=("random", "default"), default="random",
                        help="random noise levels (default) or the simulator's default "
                        "levels (multibeam 10 mm / 0.03°, laser 3 mm, exact INS) with the "
                        "rest of each pass still random")
    parser.add_argument("--passes", type=int, default=2, metavar="N",
                        help="passes of the runs the plan makes multi-pass (default 2, the "
                        "issue's case; more shows what additional passes buy)")
    args = parser.parse_args()
    print(f"build tolerance ±{1000 * args.build_tol[0]:g} mm, ±{args.build_tol[1]:g}° "
          "(simulated as-built errors uniform within it; the same given to the adjustment); "
          f"noise levels: {args.noise}")
    rng = np.random.default_rng(args.seed)
    print("pool calibration accuracy over randomised passes (rotation error deg, |Δlever| "
          "mm; joint normalised errors (est − true)/σ for roll pitch yaw x y z)")
    print(f"{'run':>3} {'kind':<8} {'p':>1} {'patent rot':>10} {'lev':>7} | {'joint rot':>9} "
          f"{'lev':>6} | {'normalised joint errors':<41} | undetermined / flagged  {'s':>5}")
    runs = []
    for run in range(args.runs):
        kind, passes = PLAN[run % len(PLAN)]
        passes = args.passes if passes == 2 else passes
        r = _one(run, kind, passes, rng, tuple(args.build_tol), args.noise)
        runs.append(r)
        z = r["joint"]["err"] / r["sigma"]
        print(f"{run:>3} {kind:<8} {passes:>1} {r['seed']['rot']:10.4f} "
              f"{r['seed']['lever']:7.2f} | {r['joint']['rot']:9.4f} {r['joint']['lever']:6.2f} "
              f"| {' '.join('   nan' if not np.isfinite(v) else f'{v:+6.2f}' for v in z)} | "
              f"{_fmt_set(r['undetermined']['joint'])} / {_fmt_set(r['flagged'])} "
              f"{r['seconds']:5.1f}", flush=True)
    two = [r for r in runs if r["passes"] >= 2]
    mp = "two-pass" if args.passes == 2 else f"{args.passes}-pass"
    one = [r for r in runs if r["passes"] == 1]
    _budget(f"{mp} runs", two)
    _group(f"{mp} runs (all kinds)", two)
    for kind in ("patent", "crossing", "mixed"):
        _group(f"{mp} runs, {kind} target", [r for r in two if r["kind"] == kind])
    _group("one-pass runs (all kinds)", one)
    print("\ncriteria (issue #10):")
    ok_rot = all(r["joint"]["rot"] <= ROT_MAX_DEG for r in two)
    ok_lev = all(r["joint"]["lever"] <= LEVER_MAX_MM for r in two)
    print(f"  {mp}: joint rotation error <= {ROT_MAX_DEG}° in every run: {ok_rot} "
          f"({sum(r['joint']['rot'] <= ROT_MAX_DEG for r in two)}/{len(two)})")
    print(f"  {mp}: joint lever-arm error <= {LEVER_MAX_MM} mm in every run: {ok_lev} "
          f"({sum(r['joint']['lever'] <= LEVER_MAX_MM for r in two)}/{len(two)})")
    zs = np.array([r["joint"]["err"] / r["sigma"] for r in two])
    rms = np.sqrt(np.nanmean(zs**2, axis=0))
    print(f"  {mp}: RMS e/σ per parameter {np.round(rms, 2).tolist()} in [0.7, 1.3]: "
          f"{bool(np.all((rms >= 0.7) & (rms <= 1.3)))}; max |e/σ| "
          f"{np.nanmax(np.abs(zs)):.2f} <= 4: {bool(np.nanmax(np.abs(zs)) <= 4)}")
    for label, group in ((mp, two), ("one-pass", one)):
        ok = [_meets_or_declares(r) for r in group]
        print(f"  {label}: meets the targets, or declares (undetermined / flagged) every "
              f"parameter off by more than {ROT_MAX_DEG}°/√3 / {LEVER_MAX_MM}/√3 mm: "
              f"{sum(ok)}/{len(group)}" + ("" if all(ok) else " — not: runs " + ", ".join(
                  str(r["run"]) for r, good in zip(group, ok, strict=True) if not good)))
    if one:
        zs = np.array([r["joint"]["err"] / r["sigma"] for r in one])
        rms = np.sqrt(np.nanmean(zs**2, axis=0))
        print(f"  one-pass: RMS e/σ per parameter {np.round(rms, 2).tolist()}; max |e/σ| "
              f"{np.nanmax(np.abs(zs)):.2f}")


def _budget(label: str, runs: list[dict]) -> None:
    """Where the σ comes from: RMS over the runs of each source's σ, per parameter, and
    how many runs' own σ already exceed the target."""
    sources = [s for s in ("data", "build", "reference", "ins", "held")
               if any(s in r["budget"] for r in runs)]
    if not sources:
        return
    print(f"\nσ budget, {label}: RMS over the runs of the σ each source alone gives (° / mm; "
          "'held' over the runs that held a parameter)")
    print(f"  {'parameter':<10}" + "".join(f"{s:>11}" for s in sources) + f"{'total':>11}")
    for k, name in enumerate(PARAMS):
        cells = []
        for s in sources:
            v = np.array([r["budget"][s][k] for r in runs if s in r["budget"]])
            v = v[np.isfinite(v)]
            cells.append(np.sqrt(np.mean(v**2)) if len(v) else np.nan)
        v = np.array([r["sigma"][k] for r in runs])
        total = np.sqrt(np.mean(v[np.isfinite(v)] ** 2))
        fmt = "{:11.4f}" if k < 3 else "{:11.2f}"
        print(f"  {name:<10}" + "".join(fmt.format(c) for c in cells) + fmt.format(total))
    rot_sig = np.array([np.sqrt(np.nansum(r["sigma"][:3] ** 2)) for r in runs])
    lev_sig = np.array([np.sqrt(np.nansum(r["sigma"][3:] ** 2)) for r in runs])
    print(f"  runs whose own σ says the typical error exceeds the target (√Σσ² of the angles > "
          f"{ROT_MAX_DEG}° or of the lever arm > {LEVER_MAX_MM} mm): "
          f"{int(np.sum((rot_sig > ROT_MAX_DEG) | (lev_sig > LEVER_MAX_MM)))}/{len(runs)} "
          f"(angles {int(np.sum(rot_sig > ROT_MAX_DEG))}, "
          f"lever {int(np.sum(lev_sig > LEVER_MAX_MM))})")


def _meets_or_declares(r: dict) -> bool:
    """The run meets the targets, or every parameter off by more than its share of them
    (target/√3: all three within it keep the norm within the target) is declared."""
    e = r["joint"]["err"]
    bad = {n for k, n in enumerate(PARAMS)
           if abs(e[k]) > (ROT_MAX_DEG if k < 3 else LEVER_MAX_MM) / np.sqrt(3)}
    meets = r["joint"]["rot"] <= ROT_MAX_DEG and r["joint"]["lever"] <= LEVER_MAX_MM
    return bool(meets or bad <= (r["undetermined"]["joint"] | r["flagged"]))


if __name__ == "__main__":
    main()
