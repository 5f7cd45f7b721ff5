"""Latency v2 (issue #15): estimators, σ sanity limits, coloured-noise simulator, CRB."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from hydrosync_core.methods.latency import estimate_latency, prefilter
from hydrosync_core.methods.latency.demo import fill_demo
from hydrosync_core.methods.latency.outcome import implausible_uncertainty
from hydrosync_core.methods.latency.params import ESTIMATOR_CHOICES, LatencyParams
from hydrosync_core.methods.latency.project_run import run, stored_params
from hydrosync_core.methods.latency.report_section import summary
from hydrosync_core.methods.latency.simulate import DayConfig, scenario, simulate_day
from hydrosync_core.project import Project

SHORT = dict(n_lines=8, line_s=90.0, turn_s=15.0, run_in_s=5.0)


def test_implausible_uncertainties_are_flagged():
    used = np.array([True, True, True, True, True, False])
    unc = np.array([0.01, 0.012, np.nan, 0.3, 0.011, 5.0])
    bad = implausible_uncertainty(unc, used, 0.2)
    assert bad.tolist() == [False, False, True, True, False, False]  # NaN, above the limit
    unc = np.array([0.01, 0.012, 0.011, 0.15, 0.013, 0.01])
    bad = implausible_uncertainty(unc, np.ones(6, bool), 0.2)
    assert bad.tolist() == [False, False, False, True, False, False]  # > 10x the median
    assert not implausible_uncertainty(np.array([0.01, 0.5]), np.ones(2, bool), 1.0).any()


def test_lines_with_incredible_sigma_are_not_used_with_a_warning():
    cfg = scenario("paper", gnss_hz=2.0, attitude_hz=20.0, **SHORT)
    day = simulate_day(cfg, seed=1)
    # The credibility rule is the extended screening (issue #29: the published method,
    # and qi2010 inside auto, apply the paper's rule only).
    res = estimate_latency(day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m,
                           {"max_line_sigma_s": 1e-5, "screening": "extended"})
    assert not res.converged and res.n_used == 0
    assert all("not credible" in " ".join(ln.warnings) for ln in res.lines)
    paper = estimate_latency(day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m,
                             {"max_line_sigma_s": 1e-5, "estimator": "qi2010"})
    assert paper.converged and not any("not credible" in w for w in paper.warnings)
    ok = estimate_latency(day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m)
    assert ok.converged and ok.ci95_high - ok.ci95_low < 0.1


def test_params_estimator_choices_and_migration():
    assert LatencyParams().estimator == "auto"
    assert set(ESTIMATOR_CHOICES) == {"qi2010", "qi2010_antialias", "weighted", "auto"}
    # Results stored before v2 have no estimator: they read as the published one (new
    # fields with defaults need no schema version of their own).
    old = LatencyParams.from_dict({"step_s": 0.01}, version=1)
    assert old.estimator == "qi2010"


def test_default_scenario_is_the_earlier_simulator():
    assert scenario("paper") == DayConfig()
    a = simulate_day(DayConfig(n_lines=2), seed=3)
    b = simulate_day(replace(DayConfig(n_lines=2), heave_white_m=0.0, attitude_noise_deg=0.0),
                     seed=3)
    np.testing.assert_array_equal(a["attitude"]["heave"], b["attitude"]["heave"])
    c = simulate_day(scenario("coloured", n_lines=2), seed=3)
    assert np.std(c["attitude"]["heave"] - a["attitude"]["heave"]) > 0.03  # extra noise


def test_coloured_noise_days_need_the_antialias_and_weighted_estimators():
    """1 Hz GNSS, 50 Hz heave with white + long-period errors: the published estimator's
    error is several times that of the anti-aliased and weighted ones (benchmark: ~4x)."""
    err = {e: [] for e in ("qi2010", "qi2010_antialias", "weighted", "auto")}
    for seed in range(3):
        cfg = scenario("coloured", latency_s=0.29, gnss_hz=1.0, attitude_hz=50.0)
        day = simulate_day(cfg, seed=40 + seed)
        for est in err:
            res = estimate_latency(day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m,
                                   {"estimator": est})
            assert res.estimator == (est if est != "auto" else res.estimator)
            err[est].append(res.latency_s - 0.29)
    rms = {e: float(np.sqrt(np.mean(np.square(v)))) for e, v in err.items()}
    assert rms["qi2010_antialias"] < 0.6 * rms["qi2010"], rms
    assert rms["weighted"] < 0.6 * rms["qi2010"], rms
    assert rms["auto"] < 0.6 * rms["qi2010"], rms


def test_auto_keeps_the_published_estimator_on_clean_days():
    cfg = scenario("clean", latency_s=-0.2, gnss_hz=1.0, attitude_hz=25.0, **SHORT)
    day = simulate_day(cfg, seed=2)
    res = estimate_latency(day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m,
                           {"estimator": "auto"})
    assert res.estimator == "qi2010" and "auto: qi2010" in res.message
    assert res.params["estimator"] == "auto"
    assert res.to_dict()["estimator"] == "qi2010"
    assert res.latency_s == pytest.approx(-0.2, abs=0.003)


def test_filter_keeps_band_and_removes_noise():
    dt = 0.02
    t = np.arange(0, 120, dt)
    wave = np.sin(2 * np.pi * 0.15 * t)
    noise = np.random.default_rng(0).standard_normal(t.size) * 0.05
    out = prefilter.fft_filter(wave + noise + 0.01 * t, dt,
                               lambda f: prefilter.antialias_response(f, 0.4))
    inner = slice(500, -500)
    # Band kept (zero phase: no shift), trend kept, noise above 0.4 Hz gone: what is
    # left is the white noise in 0–0.4 Hz of 25 Hz, 0.05·sqrt(0.4/25) = 0.0063.
    assert np.std((out - 0.01 * t - wave)[inner]) < 0.008


def test_crb_hand_case():
    # γ² = 0.5 on 0.1–0.2 Hz: ∫(2πf)² df = 4π²(0.2³ − 0.1³)/3; γ²/(1−γ²) = 1; T = 100 s.
    f = np.linspace(0, 0.5, 5001)
    coh = np.where((f >= 0.1) & (f <= 0.2), 0.5, 0.0)
    expect = 1 / (2 * 100 * 4 * np.pi**2 * (0.2**3 - 0.1**3) / 3)
    assert prefilter.crb_variance(f, coh, 100.0) == pytest.approx(expect, rel=2e-3)


def test_project_run_records_the_estimator_and_the_report_names_it():
    project = Project.new("demo")
    fill_demo(project, seed=0)
    run(project, {"step_s": 0.01, "estimator": "weighted"})
    attrs = project.attrs("results/latency")
    assert attrs["estimator"] == "weighted" and "weighted estimator" in attrs["message"]
    assert stored_params(project).estimator == "weighted"
    rows = dict(summary(project))
    assert rows["Latency estimator"].startswith("weighted")
    assert json.loads(attrs["warnings"]) is not None
