"""Latency with realistic motion sensors: heave filters, INS-blended heights, equal rates
(issue #29 items 1-3 and 8).

Each day is randomised over what varies in the field: latency uniform in ±0.4 s; the
motion sensor's heave filter (causal Butterworth high-pass of order 2 or 3, cut-off period
10-30 s, or the vendor's phase-compensated version); RTK or INS-blended heights
(τ 2-10 s); the rates (GNSS and attitude both at 1 Hz like the Seapath logs, GNSS 1 Hz with
20 Hz attitude, or both at 10 Hz); the attitude's time-tag convention (tagged at the start
or the end of its 0.05 s interval); sea state; coloured or paper-like noise. 8 two-minute
lines.

Rows: the filter declared as it is (causal, or compensated: what a user who knows the
sensor gets), a causal filter not declared (the delay-model check must flag every day it
biases), and no filter, not declared (how often a clean day is flagged). For each: the
default (``auto``), the published method (``qi2010``) and a plain reference estimator
written here (per line the argmax of ``np.corrcoef`` over the 5 ms grid, no refinement,
equal-weight mean of the lines with R > 0.85, given the declared filter's inputs when
there is one; no σ): bias, RMSE, mean σ, 95 % coverage and the share of days flagged by the
delay-model check, over the days with a result; days without one (no line above the R
threshold) are counted apart. Then ``auto`` on the declared days by filter, heights and
rates, and the undeclared days outside their interval without a flag (must be none).

Run: ``.venv/bin/python benchmarks/bench_latency_filters.py [--days 120]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from hydrosync_core.methods.latency import estimate_latency
from hydrosync_core.methods.latency.heave import total_heave_deg
from hydrosync_core.methods.latency.heave_filter import with_declared_filter
from hydrosync_core.methods.latency.simulate import scenario, simulate_day

GRID = np.arange(-1.0, 1.0 + 1e-9, 0.005)
KINDS = ("filter declared", "filter not declared", "no filter, not declared")
RATES = {"1 Hz / 1 Hz": (1.0, 20.0, 1.0), "1 Hz / 20 Hz": (1.0, 20.0, 0.0),
         "10 Hz / 10 Hz": (10.0, 50.0, 10.0)}
"""GNSS / attitude rates: (GNSS Hz, the simulator's internal attitude Hz, reported Hz)."""


def _day_config(rng, kind: str):
    """(DayConfig, declared params, labels) of one randomised day of row *kind*."""
    compensated = kind == "filter declared" and rng.random() < 0.4
    order = 0 if kind.startswith("no filter") else int(rng.choice([2, 3]))
    period = float(rng.uniform(10.0, 30.0))
    rate = str(rng.choice(list(RATES)))
    gnss_hz, internal_hz, out_hz = RATES[rate]
    blend = float(rng.uniform(2.0, 10.0)) if rng.random() < 0.5 else 0.0
    cfg = scenario(str(rng.choice(["paper", "coloured"])),
                   str(rng.choice(["calm", "moderate", "rough"])),
                   n_lines=8, line_s=120.0, turn_s=30.0, run_in_s=5.0, gnss_hz=gnss_hz,
                   attitude_hz=internal_hz, latency_s=float(rng.uniform(-0.4, 0.4)),
                   heave_filter_order=order, heave_filter_period_s=period,
                   heave_filter_compensated=compensated, gnss_blend_tau_s=blend,
                   attitude_out_hz=out_hz, attitude_tag_delay_s=float(rng.choice([0.0, 0.05])))
    if kind != "filter declared":
        declared = {}
    elif compensated:
        declared = {"heave_filter": "compensated"}
    else:
        declared = {"heave_filter": "highpass", "heave_filter_order": order,
                    "heave_filter_period_s": period}
    labels = ("compensated" if compensated else "causal", "INS-blended" if blend else "RTK",
              rate)
    return cfg, declared, labels


def plain_reference(day: dict, arm) -> float:
    """Equal-weight mean over the lines with R > 0.85 of each line's grid argmax of R."""
    g, att, lines = day["gnss"], day["attitude"], day["lines"]
    h_att = total_heave_deg(att["heave"], att["roll"], att["pitch"], arm)
    peaks = []
    for start, end in zip(lines["start"], lines["end"], strict=True):
        sel = (g["time"] >= start + 1.2) & (g["time"] <= end - 1.2)
        tags, hgt = g["time"][sel], g["height"][sel]
        if tags.size < 30:
            continue
        h = hgt - np.polyval(np.polyfit(tags - tags.mean(), hgt, 1), tags - tags.mean())
        r = np.array([np.corrcoef(h, np.interp(tags - dt, att["time"], h_att))[0, 1]
                      for dt in GRID])
        if np.nanmax(r) > 0.85:
            peaks.append(GRID[int(np.nanargmax(r))])
    return float(np.mean(peaks)) if peaks else float("nan")


def _stats(errors, sigmas, covered, flagged) -> str:
    """Bias, RMSE, mean σ, coverage and flags over the days with a result; the days
    without one (no line above the R threshold, e.g. a calm sea) are counted apart."""
    e = np.asarray(errors) * 1e3
    ok = np.isfinite(e)
    text = (f"{np.mean(e[ok]):+6.1f} | {np.sqrt(np.mean(e[ok] ** 2)):6.1f} | ")
    if sigmas is None:
        return text + f"— | — | — | {int((~ok).sum())} |"
    covered, flagged = np.asarray(covered)[ok], np.asarray(flagged)[ok]
    return (text + f"{np.nanmean(sigmas) * 1e3:5.1f} | {np.mean(covered):.3f} | "
            f"{np.mean(flagged):.2f} | {int((~ok).sum())} |")


def _flagged(res) -> bool:
    """A delay-model flag (not the note that the bands could not be compared)."""
    return any(w.startswith("delay model") and not w.startswith("delay model not checked")
               for w in res.warnings)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--days", type=int, default=120)
    args = ap.parse_args()
    rng = np.random.default_rng(2929)
    print(f"{args.days} days per row; errors in ms\n")
    print("| days | estimator | bias | RMSE | mean σ | 95 % coverage | flagged | no result |")
    print("|---|---|---|---|---|---|---|---|")
    started = time.perf_counter()
    groups: dict = {}
    unflagged_misses = 0
    for kind in KINDS:
        rows = {name: ([], [], [], []) for name in ("auto", "qi2010", "plain")}
        for _ in range(args.days):
            cfg, declared, labels = _day_config(rng, kind)
            day = simulate_day(cfg, seed=int(rng.integers(1 << 30)))
            truth = day["truth"]["latency_s"]
            for name in ("auto", "qi2010"):
                res = estimate_latency(day["gnss"], day["attitude"], day["lines"],
                                       cfg.lever_arm_m, {**declared, "estimator": name})
                err, sig, cov, flag = rows[name]
                err.append(res.latency_s - truth)
                sig.append(res.uncertainty_s)
                cov.append(bool(res.ci95_low <= truth <= res.ci95_high))
                flag.append(_flagged(res))
                if name == "auto" and kind == "filter declared":
                    for label in labels:
                        groups.setdefault(label, []).append((err[-1], sig[-1], cov[-1]))
                if (name == "auto" and kind == "filter not declared"
                        and np.isfinite(err[-1]) and not cov[-1] and not flag[-1]):
                    unflagged_misses += 1
            if declared.get("heave_filter") == "highpass":  # the reference sees it too
                day["gnss"], day["attitude"] = with_declared_filter(
                    day["gnss"], day["attitude"], cfg.lever_arm_m,
                    declared["heave_filter_order"], declared["heave_filter_period_s"])
            rows["plain"][0].append(plain_reference(day, cfg.lever_arm_m) - truth)
        for name, (err, sig, cov, flag) in rows.items():
            stats = _stats(err, sig if name != "plain" else None, cov, flag)
            print(f"| {kind} | {name} | {stats}", flush=True)
    print("\n`auto` on the declared days:\n")
    print("| days | n | bias | RMSE | mean σ | 95 % coverage |")
    print("|---|---|---|---|---|---|")
    order = ["causal", "compensated", "RTK", "INS-blended", *RATES]
    for label, values in sorted(groups.items(), key=lambda kv: order.index(kv[0])):
        e, s_, c = (np.array(v, dtype=float) for v in zip(*values, strict=True))
        ok = np.isfinite(e)
        print(f"| {label} | {ok.sum()} | {np.mean(e[ok]) * 1e3:+.1f} | "
              f"{np.sqrt(np.mean(e[ok] ** 2)) * 1e3:.1f} | {np.mean(s_[ok]) * 1e3:.1f} | "
              f"{np.mean(c[ok]):.3f} |")
    print(f"\nundeclared filter, outside the interval and not flagged: {unflagged_misses}")
    print(f"\n{time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    main()
