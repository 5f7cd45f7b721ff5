"""Accuracy of the latency estimators against the truth and the Cramér–Rao bound (issue #15 part 1).

For each noise scenario (``simulate.SCENARIOS``: clean, paper-like, coloured) and GNSS rate,
simulate N days of 13 two-minute lines (50 Hz attitude at 1 Hz GNSS, else 100 Hz),
estimate the delay with each estimator (``qi2010`` = Qi et al. 2010 as published,
``qi2010_antialias``, ``weighted``) and report the RMSE of the final Δt, the mean reported
σ, the 95 % coverage, and the Cramér–Rao bound of the day computed for the simulated
noise model: signal spectrum from the noise-free total heave, noise spectra of the
simulated errors (white + AR(1) in the GNSS heights, AR(1) + white heave error and
roll/pitch noise through the lever arm in the heave, in the GNSS band),
``1/(2T ∫ (2πf)² γ²/(1−γ²) df)`` per line, lines independent.
Run: ``.venv/bin/python benchmarks/bench_latency_accuracy.py [--days 50]``.
"""

from __future__ import annotations

import argparse
import dataclasses
import time

import numpy as np
from scipy.signal import welch

from hydrosync_core.methods.latency import estimate_latency
from hydrosync_core.methods.latency.heave import total_heave_deg
from hydrosync_core.methods.latency.params import ESTIMATORS
from hydrosync_core.methods.latency.prefilter import crb_variance
from hydrosync_core.methods.latency.simulate import scenario, simulate_day

ROWS = [("clean", 1.0), ("clean", 10.0), ("paper", 1.0), ("paper", 10.0),
        ("coloured", 1.0), ("coloured", 5.0), ("coloured", 10.0), ("coloured", 20.0)]
TRUE = 0.29

REPORTED = (*ESTIMATORS, "auto")


def _ar1_psd(f, fs, tau, std):
    """One-sided PSD (m²/Hz) of a sampled first-order Gauss–Markov series."""
    if std <= 0:
        return np.zeros_like(f)
    phi = np.exp(-1.0 / (fs * tau))
    return 2 * std**2 * (1 - phi**2) / np.abs(1 - phi * np.exp(-2j * np.pi * f / fs)) ** 2 / fs


def crb_day(cfg, seed: int) -> float:
    """Cramér–Rao bound (s) of the day's delay under the simulated noise model."""
    quiet = dataclasses.replace(cfg, gnss_white_m=0.0, multipath_m=0.0, heave_error_m=0.0,
                                heave_white_m=0.0, attitude_noise_deg=0.0, squat_m=0.0)
    day = simulate_day(quiet, seed=seed)
    att = day["attitude"]
    h_att = total_heave_deg(att["heave"], att["roll"], att["pitch"], cfg.lever_arm_m)
    fs = cfg.gnss_hz
    nper = int(64 * fs)
    spectra = []
    for start, end in zip(day["lines"]["start"], day["lines"]["end"], strict=True):
        t = np.arange(start, end, 1.0 / fs)
        f, s = welch(np.interp(t, att["time"], h_att), fs, nperseg=min(nper, t.size))
        spectra.append(s)
    signal = np.mean(spectra, axis=0)
    n_h = 2 * cfg.gnss_white_m**2 / fs + _ar1_psd(f, fs, cfg.multipath_tau_s, cfg.multipath_m)
    x, y, _ = cfg.lever_arm_m
    white_att = (cfg.heave_white_m**2 + (x**2 + y**2) * np.radians(cfg.attitude_noise_deg)**2)
    n_H = (2 * white_att / cfg.attitude_hz
           + _ar1_psd(f, cfg.attitude_hz, cfg.heave_error_tau_s, cfg.heave_error_m))
    coherence = signal**2 / ((signal + n_h) * (signal + n_H))
    info = sum(1.0 / crb_variance(f, coherence, cfg.line_s) for _ in range(cfg.n_lines))
    return float(np.sqrt(1.0 / info))


def _sigma(res) -> float:
    return res.uncertainty_s if res.converged and np.isfinite(res.uncertainty_s) else np.inf


def run_row(name: str, hz: float, days: int) -> dict:
    out = {e: [] for e in REPORTED}
    crb = []
    for k in range(days):
        cfg = scenario(name, latency_s=TRUE, gnss_hz=hz, attitude_hz=50.0 if hz < 5 else 100.0)
        seed = 2000 + k
        day = simulate_day(cfg, seed=seed)
        results = {}
        for est in ESTIMATORS:
            results[est] = estimate_latency(day["gnss"], day["attitude"], day["lines"],
                                            cfg.lever_arm_m, {"estimator": est})
        # The default itself: the smaller-σ of qi2010 and weighted, then the delay-model
        # check (σ widened when the bands or the two estimators disagree).
        results["auto"] = estimate_latency(day["gnss"], day["attitude"], day["lines"],
                                           cfg.lever_arm_m, {"estimator": "auto"})
        for est, res in results.items():
            out[est].append((res.latency_s - TRUE, res.uncertainty_s,
                             res.ci95_low <= TRUE <= res.ci95_high))
        if k < 5:  # the bound depends on the spectra, not on the noise draw
            crb.append(crb_day(cfg, seed))
    return {"crb": float(np.mean(crb)),
            **{e: np.array(v, dtype=float) for e, v in out.items()}}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--days", type=int, default=50)
    args = parser.parse_args()
    print(f"latency accuracy, {args.days} simulated days per row, 13 lines x 120 s, "
          f"true delay {TRUE} s; RMSE, mean σ and CRB in ms")
    print(f"{'noise':>9} {'GNSS':>4} {'CRB':>6} | " + " | ".join(
        f"{e:>16} RMSE    σ  cov /CRB" for e in REPORTED) + " | auto/qi2010   time")
    for name, hz in ROWS:
        t0 = time.perf_counter()
        row = run_row(name, hz, args.days)
        cells = []
        rmse = {}
        for est in REPORTED:
            v = row[est]
            rmse[est] = 1e3 * np.sqrt(np.nanmean(v[:, 0] ** 2))
            cells.append(f"{'':>16} {rmse[est]:5.2f} {1e3 * np.nanmean(v[:, 1]):5.2f} "
                         f"{np.mean(v[:, 2]):.2f} {rmse[est] / (1e3 * row['crb']):4.1f}")
        print(f"{name:>9} {hz:4.0f} {1e3 * row['crb']:6.2f} | " + " | ".join(cells)
              + f" | {rmse['auto'] / rmse['qi2010']:11.2f} {time.perf_counter() - t0:5.0f}s",
              flush=True)


if __name__ == "__main__":
    main()
