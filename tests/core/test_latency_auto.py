"""auto / weighted with the weighted pass scanned in windows (issue #15 part 3): the same
results as scanning every candidate of every pass."""

from __future__ import annotations

import numpy as np
import pytest

from hydrosync_core.methods.latency import estimate_latency, passes, weighted
from hydrosync_core.methods.latency.lines import FLAT_R_SPAN, LineData, scan_line, scan_line_window
from hydrosync_core.methods.latency.simulate import scenario, simulate_day

DAY = dict(n_lines=6, line_s=90.0, turn_s=15.0, run_in_s=5.0, gnss_hz=5.0, attitude_hz=50.0)
PARAMS = {"range_s": (-1.0, 1.0), "step_s": 0.002}
FIRST_PASSES, WEIGHTED_PASS = passes.first_passes, weighted.weighted_pass
SCAN_WINDOWS = passes.scan_windows


def _run(day, cfg, monkeypatch, windowed: bool, estimator: str = "auto", shift=None):
    """The estimate and the scan modes of every pass ("full", "window", "fallback"), in
    order: qi2010 (auto only), anti-aliased, weighted."""
    modes: list[list[str]] = []

    def spy_first(*args, **kwargs):
        out = FIRST_PASSES(*args, **kwargs)
        modes.extend([pk.scan for pk in peaks] for peaks in (out.raw_peaks, out.aa_peaks)
                     if peaks is not None)
        return out

    def spy_weighted(*args, **kwargs):
        peaks = WEIGHTED_PASS(*args, **kwargs)
        modes.append([pk.scan for pk in peaks])
        return peaks

    def shifted(first, hints, dts):
        # A line whose weighted peak lies far from where its first passes put it: the
        # window is moved 0.5 s away from them.
        out = SCAN_WINDOWS(first, hints, dts)
        k0, k1 = out[shift]
        move = int(round(0.5 / (dts[1] - dts[0])))
        move = move if k1 + move <= dts.size else -move
        out[shift] = (k0 + move, k1 + move)
        return out

    monkeypatch.setattr(passes, "WINDOWED_SCAN", windowed)
    monkeypatch.setattr(passes, "first_passes", spy_first)
    monkeypatch.setattr(weighted, "weighted_pass", spy_weighted)
    if shift is not None:
        monkeypatch.setattr(passes, "scan_windows", shifted)
    res = estimate_latency(day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m,
                           {**PARAMS, "estimator": estimator})
    return res, modes


def _assert_same(a, b, tol=1e-9):
    assert a.estimator == b.estimator and a.converged == b.converged
    assert a.n_used == b.n_used and a.message == b.message
    for name in ("latency_s", "uncertainty_s", "ci95_low", "ci95_high", "joint_latency_s"):
        assert getattr(a, name) == pytest.approx(getattr(b, name), abs=tol, nan_ok=True), name
    for la, lb in zip(a.lines, b.lines, strict=True):
        for name in ("latency_s", "uncertainty_s", "r_max", "sigma0_after_m"):
            assert getattr(la, name) == pytest.approx(getattr(lb, name), abs=tol,
                                                      nan_ok=True), (la.name, name)
        assert (la.used, la.at_edge, la.warnings) == (lb.used, lb.at_edge, lb.warnings)
    assert a.warnings == b.warnings
    np.testing.assert_allclose(a.r_curves, b.r_curves, atol=1e-12, equal_nan=True)


@pytest.mark.parametrize(("noise", "seed"), [("clean", 1), ("paper", 2), ("coloured", 3)])
def test_windowed_auto_equals_the_full_scan(noise, seed, monkeypatch):
    cfg = scenario(noise, **DAY)
    day = simulate_day(cfg, seed=seed)
    full, full_modes = _run(day, cfg, monkeypatch, windowed=False)
    fast, modes = _run(day, cfg, monkeypatch, windowed=True)
    _assert_same(fast, full)
    # qi2010, anti-aliased first pass: every candidate; the weighted pass in windows.
    assert all(m == "full" for pass_ in full_modes for m in pass_)
    assert modes[0] == modes[1] == ["full"] * cfg.n_lines
    assert modes[2] == ["window"] * cfg.n_lines


def test_windowed_weighted_equals_the_full_scan(monkeypatch):
    cfg = scenario("coloured", **DAY)
    day = simulate_day(cfg, seed=4)
    full, _ = _run(day, cfg, monkeypatch, windowed=False, estimator="weighted")
    fast, modes = _run(day, cfg, monkeypatch, windowed=True, estimator="weighted")
    _assert_same(fast, full)
    assert modes[1] == ["window"] * cfg.n_lines


def test_a_peak_outside_the_window_falls_back_to_the_full_scan(monkeypatch):
    cfg = scenario("coloured", **DAY)
    day = simulate_day(cfg, seed=5)
    full, _ = _run(day, cfg, monkeypatch, windowed=False)
    fast, modes = _run(day, cfg, monkeypatch, windowed=True, shift=2)
    _assert_same(fast, full)
    assert modes[2][2] == "fallback"
    assert modes[2][:2] + modes[2][3:] == ["window"] * (cfg.n_lines - 1)


def test_scan_line_window_checks():
    rng = np.random.default_rng(0)
    ta = np.arange(0.0, 200.0, 0.02)
    ha = np.sin(2 * np.pi * ta / 7.0) + 0.3 * np.sin(2 * np.pi * ta / 3.1)
    tags = np.arange(20.0, 180.0, 0.2)
    h = np.interp(tags - 0.1, ta, ha) + 0.01 * rng.standard_normal(tags.size)
    dts = np.linspace(-1.0, 1.0, 1001)
    line = LineData("A", 20.0, 180.0, tags, h - h.mean())
    ref = scan_line(LineData("A", 20.0, 180.0, tags, h - h.mean()), ta, ha, dts)
    k = int(np.argmin(np.abs(dts - 0.1)))
    ok = scan_line_window(line, ta, ha, dts, k - 50, k + 51)
    assert ok is not None and ok.scan == "window"
    # The full scan is compiled (fastscan.scan_core), the window's refinement is not: a
    # rounding difference in R moves the fine parabola's vertex by picoseconds.
    assert ok.latency_s == pytest.approx(ref.latency_s, abs=1e-10)
    assert ok.r_max == pytest.approx(ref.r_max, abs=1e-12)
    assert ok.uncertainty_s == pytest.approx(ref.uncertainty_s, rel=1e-9)
    assert np.all(np.isnan(ok.curve[: k - 50])) and np.all(np.isnan(ok.curve[k + 51:]))
    np.testing.assert_allclose(ok.curve[k - 50:k + 51], ref.curve[k - 50:k + 51], atol=1e-12)
    # The maximum on the window's edge: not settled.
    assert scan_line_window(line, ta, ha, dts, k + 10, k + 200) is None
    assert scan_line_window(line, ta, ha, dts, k - 200, k - 10) is None
    # The window reaching the grid's end with the maximum there: not settled either.
    assert scan_line_window(line, ta, ha, dts, 0, 3) is None
    # No warning appended when it gives up.
    assert line.warnings == []
    # A flat R (heights unrelated to the heave): the full scan decides (its warning).
    flat = LineData("F", 20.0, 180.0, tags, 1e-3 * rng.standard_normal(tags.size))
    full = scan_line(LineData("F", 20.0, 180.0, tags, flat.h.copy()), ta, ha, dts)
    if np.nanmax(full.curve) - np.nanmin(full.curve) < FLAT_R_SPAN:
        assert scan_line_window(flat, ta, ha, dts, 400, 600) is None


@pytest.mark.parametrize(("noise", "seed"), [("clean", 1), ("coloured", 3)])
def test_auto_equals_the_estimator_it_keeps_run_alone(noise, seed):
    """auto shares the set-up, each line's total heave and the anti-aliased pass between
    its two estimators and computes σ0 for the one it keeps only: the same numbers as
    running that estimator alone; the note quotes the other one's."""
    cfg = scenario(noise, **DAY)
    day = simulate_day(cfg, seed=seed)
    alone = {e: estimate_latency(day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m,
                                 {**PARAMS, "estimator": e}) for e in ("qi2010", "weighted")}
    auto = estimate_latency(day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m,
                            {**PARAMS, "estimator": "auto"})
    kept = alone[auto.estimator]
    other = alone["weighted" if auto.estimator == "qi2010" else "qi2010"]
    assert auto.estimator == ("qi2010" if noise == "clean" else "weighted")
    assert auto.uncertainty_s <= other.uncertainty_s
    # The delay-model note (the check needs more lines than these) comes last in both.
    assert auto.message.startswith(kept.message.split("; delay model:")[0] + "; auto: ")
    assert f"Δt {other.latency_s:+.4f} s" in auto.message
    assert auto.params["estimator"] == "auto"
    a, b = auto.to_dict(curves=True), kept.to_dict(curves=True)
    for key in ("message", "params"):
        a.pop(key), b.pop(key)
    # auto also quotes the other estimate (the delay-model check compares the two).
    assert a["diagnostics"].pop("other_estimate")["latency_s"] == other.latency_s
    assert a == b


def test_weighted_pass_without_the_kept_bins_recomputes_the_spectrum(monkeypatch):
    """A weight beyond the bins kept from the first pass (not possible with the pooled
    weighting, which is zero above the GNSS Nyquist frequency) falls back to the whole
    spectrum of the line's window: the same numbers."""
    cfg = scenario("coloured", **DAY)
    day = simulate_day(cfg, seed=6)
    args = (day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m,
            {**PARAMS, "estimator": "weighted"})
    ref = estimate_latency(*args)
    monkeypatch.setattr(passes, "band_bins", lambda size, a_int, g_int: 3)
    _assert_same(estimate_latency(*args), ref, tol=0)


def test_weighted_without_a_weighting_is_the_antialiased_estimator(monkeypatch):
    """When the pooled weighting is not possible the anti-aliased first pass is the answer,
    its σ computed afterwards on the kept windows: qi2010_antialias's numbers."""
    cfg = scenario("coloured", **DAY)
    day = simulate_day(cfg, seed=7)
    args = (day["gnss"], day["attitude"], day["lines"], cfg.lever_arm_m)
    ref = estimate_latency(*args, {**PARAMS, "estimator": "qi2010_antialias"})
    monkeypatch.setattr(weighted, "pooled_weighting", lambda *a, **k: None)
    res = estimate_latency(*args, {**PARAMS, "estimator": "weighted"})
    assert res.estimator == "weighted"
    assert any("coherence weighting not possible" in w for w in res.warnings)
    assert res.latency_s == ref.latency_s and res.uncertainty_s == ref.uncertainty_s
    for a, b in zip(res.lines, ref.lines, strict=True):
        assert (a.latency_s, a.uncertainty_s, a.r_max, a.used, a.sigma0_after_m) == (
            b.latency_s, b.uncertainty_s, b.r_max, b.used, b.sigma0_after_m)
    np.testing.assert_array_equal(res.r_curves, ref.r_curves)
