"""Speed and memory of the latency estimate on a full survey day, against a straightforward scan.

500 lines of 2 minutes, 100 Hz attitude, 10 Hz GNSS, scan −1..+1 s with a 1 ms step
(2001 candidates per line), issue #15 part 3. Measured in one run:

* ``hydrosync latency`` from the CSV files to the JSON result, in a fresh process (wall
  and CPU time and the process's peak resident memory), with ``--estimator qi2010`` (the
  paper's) and with the default ``auto`` (qi2010 and the weighted one), each ``--repeat``
  times (between the parts of the straightforward scan, below) after a first run that may
  compile and cache the numba kernels: the fastest run (a shared machine's other work
  only ever adds time) and the median;
* :func:`estimate_latency` alone on the arrays in memory, qi2010 and auto (the fastest of
  ``--repeat`` runs, 3 by default, and the median);
* a straightforward per-candidate scan written here: per line and trial delay, one
  ``numpy.interp`` of the total heave at ``tags − Δt`` and one Pearson correlation, the
  grid maximum refined by a parabola — what one writes from eqs. 3–4 of Qi et al. (2010).
  It runs in ``--repeat`` parts (a share of the lines each), and after each part comes
  one CLI run of each estimator: the ratio compares times taken in the same minutes of a
  shared machine whose speed wanders (the same scan took 60–77 s within one hour);
* the pre-v2 estimator (every candidate interpolated: ``correlation_curve_direct``) for the
  "identical to today's" check: final and per-line Δt must agree to 0.1 ms;
* auto with the weighted pass windowed (``passes.WINDOWED_SCAN = True``, opt-in) against the
  default auto, which scans every candidate of every pass;
* the CLI's qi2010 and auto results against *reference* (``--reference``; by default
  ``reference/latency_speed_day.json``: the default day's results before the auto
  speed-up of issue #15 part 3): final and per-line Δt and σ must agree to 0.01 ms.

Run: ``.venv/bin/python benchmarks/bench_latency_speed.py [--lines 500] [--dir DIR]
[--repeat 3] [--reference JSON]``.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from hydrosync_core.importers.survey_csv import read_lines_csv
from hydrosync_core.methods.latency import fastscan, passes
from hydrosync_core.methods.latency.estimate import estimate_latency
from hydrosync_core.methods.latency.heave import total_heave_deg
from hydrosync_core.methods.latency.readers import read_attitude_csv, read_gnss_csv
from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day, write_day_csv

CFG = dict(latency_s=0.123, line_s=120.0, run_in_s=10.0, turn_s=30.0, gnss_hz=10.0,
           attitude_hz=100.0)

REFERENCE = Path(__file__).with_name("reference") / "latency_speed_day.json"
"""Default day's CLI results before the auto speed-up (see the file's "about")."""


def reference_diff(doc: dict, ref: dict | None) -> str:
    """Largest |doc − ref| (ms) of the final (Δt, σ) and of the lines' (Δt, σ), as text.

    *doc*: a ``hydrosync latency`` JSON; *ref*: one run of the reference file (or None).
    """
    if ref is None or len(ref["lines"]) != len(doc["lines"]):
        return "n/a (no reference for this day)"

    def diff(a, b) -> float:
        a = np.nan if a is None else a
        b = np.nan if b is None else b
        if np.isnan(a) and np.isnan(b):
            return 0.0
        return abs(a - b)  # NaN against a number: NaN, reported as such

    final = max(diff(doc["latency_s"], ref["latency_s"]),
                diff(doc["uncertainty_s"], ref["uncertainty_s"]))
    lines = max(max(diff(ln["latency_s"], r[0]), diff(ln["uncertainty_s"], r[1]))
                for ln, r in zip(doc["lines"], ref["lines"], strict=True))
    same = "" if doc["estimator"] == ref["estimator"] else f" (estimator {ref['estimator']}!)"
    return f"final {final * 1e3:.2e} ms, lines {lines * 1e3:.2e} ms (goal <= 0.01 ms){same}"


def straightforward_scan(gnss, t_att, h_att, lines, dts, which=None
                         ) -> tuple[list[float], list[float]]:
    """Per line, per candidate: interpolate, correlate; parabola at the grid maximum.

    *h_att*: the total heave (m) at the attitude times *t_att* (s). Returns the peaks (s)
    and weights (R_max) of the lines *which* (indices; all by default) that pass
    R_max > 0.85; :func:`combined` gives the day's value.
    """
    t_g, hgt = gnss["time"], gnss["height"]
    lo, hi = float(dts[0]) - 0.15, float(dts[-1]) + 0.15
    peaks, weights = [], []
    starts, ends = np.asarray(lines["start"]), np.asarray(lines["end"])
    for i in range(starts.size) if which is None else which:
        start, end = starts[i], ends[i]
        sel = (t_g >= start) & (t_g <= end) & (t_g - hi >= t_att[0]) & (t_g - lo <= t_att[-1])
        tags, h = t_g[sel], hgt[sel]
        if tags.size < 30:
            continue
        h = h - np.polyval(np.polyfit(tags - tags.mean(), h, 1), tags - tags.mean())
        r = np.array([np.corrcoef(h, np.interp(tags - d, t_att, h_att))[0, 1] for d in dts])
        k = int(np.argmax(r))
        if 0 < k < dts.size - 1:
            a, b, c = r[k - 1:k + 2]
            peak = dts[k] + 0.5 * (a - c) / (a - 2 * b + c) * (dts[1] - dts[0])
        else:
            continue
        if r[k] > 0.85:
            peaks.append(float(peak))
            weights.append(float(r[k]))
    return peaks, weights


def combined(peaks: list[float], weights: list[float]) -> float:
    """The straightforward scan's day value: R-weighted mean of the line peaks (s)."""
    return float(np.average(peaks, weights=weights))


def run_cli(d: Path, step: float, estimator: str = "qi2010"
            ) -> tuple[float, float, float, dict]:
    """Wall time (s), peak RSS (MiB), CPU time (s, all threads) and JSON of
    ``hydrosync latency`` in a new process."""
    out = d / "result.json"
    cmd = [sys.executable, "-c", "import sys; from hydrosync_core.cli import main; "
           "sys.exit(main(sys.argv[1:]))", "latency", "--gnss", str(d / "gnss.csv"),
           "--attitude", str(d / "attitude.csv"), "--lines", str(d / "lines.csv"),
           "--lever-arm", "-1.5", "2.0", "-6.0", "--step", str(step), "--estimator", estimator,
           "--json", str(out)]
    # Peak RSS of this child alone: a wrapper process reports its own child's.
    wrapper = ("import resource, subprocess, sys; subprocess.run(sys.argv[1:], check=True, "
               "stdout=subprocess.DEVNULL); r = resource.getrusage(resource.RUSAGE_CHILDREN); "
               "print(r.ru_maxrss, r.ru_utime + r.ru_stime)")
    t0 = time.perf_counter()
    res = subprocess.run([sys.executable, "-c", wrapper, *cmd], check=True,
                         capture_output=True, text=True)
    wall = time.perf_counter() - t0
    rss, cpu = res.stdout.split()
    return wall, int(rss) / 1024, float(cpu), json.loads(out.read_text())


def summary(runs: list) -> tuple[float, float, float, dict, float]:
    """Of :func:`run_cli` results: the fastest run's wall and CPU time (s), the largest
    peak RSS (MiB), the fastest run's JSON and the median wall time (s)."""
    wall, _, cpu, doc = min(runs, key=lambda r: r[0])
    return (wall, max(r[1] for r in runs), cpu, doc,
            float(np.median([r[0] for r in runs])))


def timed(repeat: int, func):
    """(result, wall s, CPU s) of the fastest of *repeat* calls of *func* (a shared
    machine's other work only ever adds time), and the median wall time."""
    runs = []
    for _ in range(max(repeat, 1)):
        t0, c0 = time.perf_counter(), time.process_time()
        out = func()
        runs.append((time.perf_counter() - t0, time.process_time() - c0))
    best = min(runs)
    return out, best[0], best[1], float(np.median([w for w, _ in runs]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, default=500)
    parser.add_argument("--step", type=float, default=0.001)
    parser.add_argument("--dir", type=Path, help="keep/reuse the CSV files here")
    parser.add_argument("--repeat", type=int, default=3,
                        help="times each estimation and each CLI run is repeated (the "
                        "fastest is reported, and the median)")
    parser.add_argument("--reference", type=Path, default=REFERENCE,
                        help="results to compare with (see reference_diff)")
    args = parser.parse_args()
    refs = (json.loads(args.reference.read_text())["runs"]
            if args.reference is not None and args.reference.exists() else {})
    if args.reference == REFERENCE and (args.lines, args.step) != (500, 0.001):
        refs = {}  # the stored results are the default day's
    cfg = DayConfig(n_lines=args.lines, **CFG)
    tmp = None
    if args.dir is None:
        tmp = tempfile.TemporaryDirectory()
        d = Path(tmp.name)
    else:
        d = args.dir
    t0 = time.perf_counter()
    if not (d / "attitude.csv").exists():
        write_day_csv(simulate_day(cfg, seed=7), d)
    t_sim = time.perf_counter() - t0
    size = sum(os.path.getsize(d / f"{n}.csv") for n in ("gnss", "attitude", "lines"))

    gnss = read_gnss_csv(d / "gnss.csv")
    att = read_attitude_csv(d / "attitude.csv")
    lines = read_lines_csv(d / "lines.csv")
    arm = cfg.lever_arm_m
    dts = np.linspace(-1.0, 1.0, int(round(2.0 / args.step)) + 1)

    cli_first, rss_first, _, _ = run_cli(d, args.step)
    # The straightforward scan in --repeat parts, each followed by one CLI run of each
    # estimator: the ratio compares times taken in the same minutes of a shared machine
    # whose speed wanders (the same scan took 60-77 s within an hour).
    parts = np.array_split(np.arange(len(lines["name"])), max(args.repeat, 1))
    qi_runs, auto_runs, peaks, weights = [], [], [], []
    t0, c0 = time.perf_counter(), time.process_time()
    h_att = total_heave_deg(att["heave"], att["roll"], att["pitch"], arm)
    t_plain, c_plain = time.perf_counter() - t0, time.process_time() - c0
    for part in parts:
        t0, c0 = time.perf_counter(), time.process_time()
        got = straightforward_scan(gnss, att["time"], h_att, lines, dts, part)
        t_plain += time.perf_counter() - t0
        c_plain += time.process_time() - c0
        peaks += got[0]
        weights += got[1]
        qi_runs.append(run_cli(d, args.step, "qi2010"))
        auto_runs.append(run_cli(d, args.step, "auto"))
    plain = combined(peaks, weights)
    cli_wall, cli_rss, cli_cpu, doc, cli_med = summary(qi_runs)
    auto_wall, auto_rss, auto_cpu, auto_doc, auto_med = summary(auto_runs)

    params = {"range_s": (-1.0, 1.0), "step_s": args.step, "estimator": "qi2010"}
    res, t_est, c_est, m_est = timed(args.repeat, lambda: estimate_latency(
        gnss, att, lines, arm, params))
    auto, t_auto, c_auto, m_auto = timed(args.repeat, lambda: estimate_latency(
        gnss, att, lines, arm, {**params, "estimator": "auto"}))
    passes.WINDOWED_SCAN = True  # the opt-in windowed pass, against the default full scans
    try:
        auto_full, t_auto_full, c_auto_full, _ = timed(1, lambda: estimate_latency(
            gnss, att, lines, arm, {**params, "estimator": "auto"}))
    finally:
        passes.WINDOWED_SCAN = False
    auto_line_diff = max(max(abs(a.latency_s - b.latency_s), abs(a.uncertainty_s
                                                                  - b.uncertainty_s))
                         for a, b in zip(auto.lines, auto_full.lines, strict=True)
                         if np.isfinite(a.latency_s))
    auto_final_diff = max(abs(auto_doc["latency_s"] - auto_full.latency_s),
                          abs(auto_doc["uncertainty_s"] - auto_full.uncertainty_s))
    assert np.array_equal(res.dt_grid, dts), "the benchmark's grid is not the estimate's"

    available = fastscan.available
    fastscan.available = lambda: False  # the pre-v2 evaluation: every candidate interpolated
    try:
        t0 = time.perf_counter()
        old = estimate_latency(gnss, att, lines, arm, params)
        t_old = time.perf_counter() - t0
    finally:
        fastscan.available = available
    line_diff = max(abs(a.latency_s - b.latency_s) for a, b in zip(res.lines, old.lines,
                                                                  strict=True)
                    if np.isfinite(a.latency_s))
    final_diff = abs(doc["latency_s"] - old.latency_s)

    print("latency speed: one survey day (issue #15 part 3)")
    rows = [
        ("lines", f"{args.lines} x {cfg.line_s:.0f} s, CSV files {size / 2**20:.0f} MiB"),
        ("attitude records (100 Hz)", f"{att['time'].size:,}"),
        ("GNSS epochs (10 Hz)", f"{gnss['time'].size:,}"),
        ("candidates per line", f"{dts.size} (step {args.step * 1e3:g} ms)"),
        ("simulation + CSV writing", f"{t_sim:.1f} s"),
        ("straightforward scan (reference)", f"{t_plain:.1f} s (CPU {c_plain:.1f} s; in "
                                             f"{len(parts)} parts between the CLI runs)"),
        ("pre-v2 estimator (all candidates)", f"{t_old:.1f} s"),
        ("CSV -> JSON, first run", f"{cli_first:.1f} s, peak RSS {rss_first:.0f} MiB "
                                   "(may compile the kernels)"),
        ("CSV -> JSON", f"{cli_wall:.2f} s (CPU {cli_cpu:.1f} s, all threads; fastest of "
                        f"{args.repeat}, median {cli_med:.2f} s), peak RSS {cli_rss:.0f} MiB"),
        ("ratio CSV -> JSON / straightforward", f"1/{t_plain / cli_wall:.1f} wall (median "
                                                f"1/{t_plain / cli_med:.1f}), "
                                                f"1/{c_plain / cli_cpu:.0f} CPU (goal <= 1/30)"),
        ("CSV -> JSON, auto (default)", f"{auto_wall:.2f} s (CPU {auto_cpu:.1f} s; median "
                                        f"{auto_med:.2f} s), peak RSS {auto_rss:.0f} MiB"),
        ("ratio auto CSV -> JSON / straightfwd", f"1/{t_plain / auto_wall:.1f} wall (median "
                                                 f"1/{t_plain / auto_med:.1f}), "
                                                 f"1/{c_plain / auto_cpu:.0f} CPU (goal <= 1/30)"),
        ("estimation alone (qi2010)", f"{t_est:.2f} s, CPU {c_est:.2f} s (goal <= 1 s; "
                                      f"fastest of {args.repeat}, median {m_est:.2f} s)"),
        ("estimation, auto (default)", f"{t_auto:.2f} s, CPU {c_auto:.2f} s (goal <= 1 s; "
                                       f"median {m_auto:.2f} s; chose {auto.estimator}, "
                                       f"{auto.latency_s:.5f} s)"),
        ("estimation, auto, windowed (opt-in)", f"{t_auto_full:.2f} s, CPU {c_auto_full:.2f} s"),
        ("result", f"{res.latency_s:.5f} s (truth {cfg.latency_s}), 95 % "
                   f"[{res.ci95_low:.4f}, {res.ci95_high:.4f}], {res.n_used} lines used"),
        ("straightforward scan result", f"{plain:.5f} s"),
        ("|CLI - pre-v2| final", f"{final_diff * 1e3:.2e} ms (goal <= 0.1 ms)"),
        ("max |new - pre-v2| per line", f"{line_diff * 1e3:.2e} ms"),
        ("auto: |CLI - windowed| Δt, σ", f"{auto_final_diff * 1e3:.2e} ms (goal <= 0.1 ms)"),
        ("auto: max |full - windowed| line", f"{auto_line_diff * 1e3:.2e} ms"),
        ("qi2010 CLI vs reference", reference_diff(doc, refs.get("qi2010"))),
        ("auto CLI vs reference", reference_diff(auto_doc, refs.get("auto"))),
        ("machine", f"{os.cpu_count()} cores, load {os.getloadavg()[0]:.1f} at the end"),
        ("this process maxrss", f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f}"
                                " MiB (incl. benchmark data)"),
    ]
    width = max(len(k) for k, _ in rows)
    for key, value in rows:
        print(f"{key:<{width}}  {value}")
    if tmp is not None:
        tmp.cleanup()


if __name__ == "__main__":
    main()
