"""The campaign summary's trend plots come from the analyses' specs (``PluginSpec.trends``)."""

from __future__ import annotations

import math
from types import SimpleNamespace

from hydrosync_core.campaign.summary import trend_series
from hydrosync_core.plugins import get_spec


def _outcome(project, step, date, numbers):
    return {"project": project, "step": step, "date": date, "numbers": numbers}


def test_trends_follow_the_specs_with_their_intervals():
    result = SimpleNamespace(outcomes=[
        _outcome("day2", "latency", "2026-05-02",
                 {"latency_s": 0.31, "ci95_low": 0.29, "ci95_high": 0.33}),
        _outcome("day1", "latency", "2026-05-01",
                 {"latency_s": 0.30, "ci95_low": 0.28, "ci95_high": 0.32}),
        _outcome("pool", "pool_calibration", "2026-05-03",
                 {"roll_deg": -35.0, "sigma_roll_deg": 0.01, "pitch_deg": 0.2,
                  "sigma_pitch_deg": 0.02, "yaw_deg": float("nan"), "sigma_yaw_deg": 0.1}),
        _outcome("att", "gnss_attitude", "2026-05-03", {"heading_deg": 1.0}),
    ])
    series = trend_series(result)
    titles = [t for t, _u, _lines in series]
    assert titles == [get_spec("latency").trends[0].title,
                      get_spec("pool_calibration").trends[0].title]
    (_, unit, [(label, points)]) = series[0]
    assert unit == "s" and label == "Δt"
    assert [p[0] for p in points] == ["2026-05-01", "2026-05-02"]  # sorted by day
    assert points[0][1:4] == (0.30, 0.28, 0.32)
    (_, unit, pool_lines) = series[1]
    assert unit == "°"
    # yaw is not finite: no point, no line; roll and pitch get ±1.96 σ.
    assert [label for label, _ in pool_lines] == ["roll", "pitch"]
    _, roll_points = pool_lines[0]
    _, value, low, high, _ = roll_points[0]
    assert math.isclose(low, -35.0 - 1.96 * 0.01) and math.isclose(high, -35.0 + 1.96 * 0.01)
