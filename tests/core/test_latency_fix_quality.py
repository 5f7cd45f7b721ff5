"""GNSS fix quality in the latency (issue #29 item 5): heights of mixed quality are never
mixed silently."""

from __future__ import annotations

import numpy as np
import pytest

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency import estimate_latency
from hydrosync_core.methods.latency.fix_quality import screen_fixes
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.simulate import scenario, simulate_day


def _gnss(quality):
    q = np.asarray(quality, dtype=float)
    return {"time": np.arange(q.size, dtype=float), "height": np.zeros(q.size), "quality": q}


def test_rtk_fixed_only_when_the_log_has_it():
    out, warnings = screen_fixes(_gnss([4, 4, 2, 5, 4, 1]))
    assert out["time"].tolist() == [0.0, 1.0, 4.0]
    assert len(warnings) == 1 and "3 GNSS epochs" in warnings[0]
    assert "DGPS" in warnings[0] and "RTK float" in warnings[0]


def test_no_rtk_all_used_with_their_quality_named():
    out, warnings = screen_fixes(_gnss([1, 1, 1]))
    assert out["time"].size == 3 and "3 autonomous (q 1)" in warnings[0]


def test_chosen_qualities_and_bad_choices():
    out, _ = screen_fixes(_gnss([4, 5, 2]), "4,5")
    assert out["time"].tolist() == [0.0, 1.0]
    with pytest.raises(InputError, match="no epoch of fix quality 4"):
        screen_fixes(_gnss([1, 2]), "4")
    with pytest.raises(InputError, match="fix_qualities"):
        LatencyParams(fix_qualities="rtk")
    assert screen_fixes({"time": np.zeros(2), "height": np.zeros(2)})[1] == []


def test_float_epochs_leave_the_estimate_with_a_warning():
    cfg = scenario("paper", n_lines=3, line_s=90.0, turn_s=15.0, run_in_s=5.0, gnss_hz=2.0,
                   attitude_hz=20.0)
    day = simulate_day(cfg, seed=2)
    g = dict(day["gnss"])
    q = np.full(g["time"].size, 4.0)
    q[::7] = 5.0
    g["quality"] = q
    res = estimate_latency(g, day["attitude"], day["lines"], cfg.lever_arm_m,
                           {"estimator": "qi2010"})
    assert any("RTK float" in w and "excluded" in w for w in res.warnings)
    assert res.lines[0].epochs < int(np.sum((g["time"] >= day["lines"]["start"][0])
                                            & (g["time"] <= day["lines"]["end"][0])))
