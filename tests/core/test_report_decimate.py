"""Plot decimation of the PDF report: long series drawn as what the page can show."""

from __future__ import annotations

import numpy as np
import pytest

from hydrosync_core.report.decimate import (
    RESOLUTION,
    cloud_indices,
    line_indices,
    m4_indices,
    track_indices,
)


def _columns(x, y, column=RESOLUTION):
    col = np.floor(x / column).astype(int)
    cols = np.unique(col)
    lo = np.array([y[col == c].min() for c in cols])
    hi = np.array([y[col == c].max() for c in cols])
    return cols, lo, hi


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_m4_keeps_every_columns_extremes_and_the_ends(seed):
    """A 100 000-sample random walk over a 480-point-wide box: in every page column the
    kept samples reach the same lowest and highest value (so the polyline covers the same
    pixels), the first and last samples are kept, and at most 4 per column remain."""
    rng = np.random.default_rng(seed)
    n = 100_000
    x = np.sort(rng.uniform(46, 526, n))
    y = 100 + np.cumsum(rng.normal(0, 0.3, n))
    keep = m4_indices(x, y)
    cols, lo, hi = _columns(x, y)
    kcols, klo, khi = _columns(x[keep], y[keep])
    np.testing.assert_array_equal(kcols, cols)
    np.testing.assert_array_equal(klo, lo)
    np.testing.assert_array_equal(khi, hi)
    assert keep[0] == 0 and keep[-1] == n - 1
    assert np.all(np.diff(keep) > 0)
    assert len(keep) <= 4 * len(cols) < n / 20


def test_few_samples_are_all_kept():
    x = np.linspace(0, 480, 300)
    y = np.sin(x)
    np.testing.assert_array_equal(line_indices(x, y), np.arange(300))
    np.testing.assert_array_equal(m4_indices(x[:3], y[:3]), np.arange(3))


def test_decreasing_x_uses_m4_in_reverse():
    rng = np.random.default_rng(3)
    x = np.sort(rng.uniform(0, 100, 20_000))[::-1]
    y = rng.normal(size=x.size)
    keep = line_indices(x, y)
    assert np.all(np.diff(keep) > 0) and keep[0] == 0 and keep[-1] == x.size - 1
    _, lo, hi = _columns(x, y)
    _, klo, khi = _columns(x[keep], y[keep])
    np.testing.assert_array_equal((klo, khi), (lo, hi))


def test_track_drops_only_samples_in_the_cell_of_the_one_before():
    """A dense survey-line track (turning back on itself): every dropped sample lies in the
    grid cell of the previous sample, so the drawn path is within one cell of the full one."""
    t = np.linspace(0, 4 * np.pi, 50_000)
    x, y = 200 + 150 * np.sin(t), 200 + 100 * np.sin(2 * t)
    keep = track_indices(x, y)
    assert keep[0] == 0 and keep[-1] == x.size - 1 and len(keep) < x.size / 5
    dropped = np.setdiff1d(np.arange(x.size), keep)
    same = (np.floor(x[dropped] / RESOLUTION) == np.floor(x[dropped - 1] / RESOLUTION)) \
        & (np.floor(y[dropped] / RESOLUTION) == np.floor(y[dropped - 1] / RESOLUTION))
    assert same.all()
    assert np.array_equal(line_indices(x, y), keep)


def test_cloud_keeps_one_point_per_occupied_cell_the_last_drawn():
    rng = np.random.default_rng(4)
    x, y = rng.normal(200, 20, 40_000), rng.normal(150, 10, 40_000)
    keep = cloud_indices(x, y, 1.0)
    cell = [tuple(c) for c in np.floor(np.column_stack([x, y])).astype(int).tolist()]
    assert len(keep) == len(set(cell))
    assert {cell[i] for i in keep.tolist()} == set(cell)
    # the last point drawn in each cell is the one kept (it is the one on top)
    last = {c: i for i, c in enumerate(cell)}
    assert sorted(last.values()) == keep.tolist()


def test_chart_of_a_long_series_draws_its_envelope(monkeypatch):
    """A survey day's 200 000-sample series in a full-width chart: at most four vertices
    per half-point column reach the PDF, and the drawn y range equals the data's."""
    from reportlab.graphics.shapes import PolyLine

    from hydrosync_core.report.charts import Chart

    rng = np.random.default_rng(5)
    t = np.linspace(0, 86_400, 200_000)
    y = np.sin(t / 50) + rng.normal(0, 0.1, t.size)
    chart = Chart(width=480, height=200).line(t, y, label="pitch")
    drawing = chart.drawing()
    lines = [s for g in drawing.contents for s in getattr(g, "contents", [])
             if isinstance(s, PolyLine)]
    assert len(lines) == 1
    points = np.asarray(lines[0].points, float).reshape(-1, 2)
    assert len(points) <= 4 * (480 - 54) / RESOLUTION
    # the same chart drawn from every sample reaches the same lowest and highest point
    import hydrosync_core.report.charts as charts

    monkeypatch.setattr(charts, "line_indices", lambda x, y: np.arange(len(x)))
    full = Chart(width=480, height=200).line(t, y, label="pitch").drawing()
    every = [s for g in full.contents for s in getattr(g, "contents", [])
             if isinstance(s, PolyLine)][0]
    every = np.asarray(every.points, float).reshape(-1, 2)
    assert len(every) == t.size
    assert (points[:, 1].min(), points[:, 1].max()) == (every[:, 1].min(), every[:, 1].max())
    assert (points[0] == every[0]).all() and (points[-1] == every[-1]).all()
