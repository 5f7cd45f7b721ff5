"""The latency PDF's R-curve figures: a survey day's curves as a range and a median, a small
day's one curve per line (#26: 500 curves printed as a solid block)."""

import numpy as np

from hydrosync_core.methods.latency.report_section import MANY_CURVES, _draw_lines
from hydrosync_core.report.charts import Chart


def _curves(n: int) -> tuple[np.ndarray, np.ndarray]:
    x = np.linspace(-1.0, 1.0, 201)
    shift = np.linspace(-0.05, 0.05, n)[:, None]
    return x, np.exp(-((x[None, :] - 0.3 - shift) / 0.2) ** 2)


def test_many_lines_draw_their_range_and_median():
    x, curves = _curves(MANY_CURVES + 10)
    chart = Chart(width=400, height=200)
    assert _draw_lines(chart, x, curves, np.arange(len(curves)), color="#1f77b4",
                       label="line used")
    kinds = [s.kind for s in chart.series]
    assert kinds == ["band", "line"]
    band, median = chart.series
    np.testing.assert_allclose(band.y, curves.min(axis=0))
    np.testing.assert_allclose(band.y2, curves.max(axis=0))
    np.testing.assert_allclose(median.y, np.median(curves, axis=0))
    assert band.label == f"line used: range of {len(curves)}"


def test_few_lines_draw_one_curve_each_with_one_legend_entry():
    x, curves = _curves(5)
    chart = Chart(width=400, height=200)
    assert not _draw_lines(chart, x, curves, np.arange(5), color="#1f77b4", label="line used")
    assert [s.kind for s in chart.series] == ["line"] * 5
    assert [s.label for s in chart.series] == ["line used", None, None, None, None]
