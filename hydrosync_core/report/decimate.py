"""Thin long series to what a printed figure can show, without changing what it shows.

A survey day's series (tens of thousands of samples across a 480-point-wide plot) drew
as a solid block and made the PDF large and slow to lay out. In page coordinates:

* :func:`m4_indices` — for a series whose x only increases (a time series), the M4
  rule of Jugel et al. (2014, "M4: a visualization-oriented time series data
  aggregation", PVLDB 7(10)): in every column of the page keep the first, last,
  lowest and highest sample. The polyline drawn through them covers exactly the pixels
  the full series covers, at a resolution of one column.
* :func:`track_indices` — for a path that turns back on itself (a plan view), drop a
  sample that lands in the same cell of a fine grid as the one before it.
* :func:`cloud_indices` — for scattered points, keep one point per grid cell (the last
  drawn, which is the one on top).

All work on arrays (no Python loop per sample) and return sorted indices into the input.
"""

from __future__ import annotations

import numpy as np

#: Column width of the M4 rule and grid cell of the other two (points, 1/72 in): half a
#: point, so a reader zooming the PDF to 200 % still sees no steps.
RESOLUTION = 0.5


def m4_indices(x: np.ndarray, y: np.ndarray, column: float = RESOLUTION) -> np.ndarray:
    """Indices of the first, last, lowest and highest sample in each page column.

    Parameters
    ----------
    x, y : ndarray
        Page coordinates (points) of one unbroken polyline; *x* non-decreasing.
    column : float
        Column width (points).

    Returns
    -------
    ndarray of int
        Sorted unique indices; all of them when there are few samples per column.
    """
    n = len(x)
    if n <= 4:
        return np.arange(n)
    col = np.floor(x / column).astype(np.int64)
    starts = np.flatnonzero(np.r_[True, col[1:] != col[:-1]])
    if 4 * len(starts) >= n:
        return np.arange(n)
    ends = np.r_[starts[1:], n] - 1
    # Sorting by (column, y) puts each column's lowest sample at its start and the
    # highest at its end, because the columns are contiguous runs.
    order = np.lexsort((y, col))
    keep = np.concatenate([starts, ends, order[starts], order[ends]])
    return np.unique(keep)


def track_indices(x: np.ndarray, y: np.ndarray, cell: float = RESOLUTION) -> np.ndarray:
    """Indices of a path's samples that move to another grid cell than the one before.

    The first and last samples are always kept.
    """
    n = len(x)
    if n <= 2:
        return np.arange(n)
    gx = np.floor(x / cell).astype(np.int64)
    gy = np.floor(y / cell).astype(np.int64)
    moved = np.r_[True, (gx[1:] != gx[:-1]) | (gy[1:] != gy[:-1])]
    moved[-1] = True
    return np.flatnonzero(moved)


def cloud_indices(x: np.ndarray, y: np.ndarray, cell: float = RESOLUTION) -> np.ndarray:
    """Indices of one point per grid cell: the last in drawing order (the visible one)."""
    n = len(x)
    if n <= 1:
        return np.arange(n)
    gx = np.floor(x / cell).astype(np.int64)
    gy = np.floor(y / cell).astype(np.int64)
    key = (gx - gx.min()) * (int(gy.max() - gy.min()) + 1) + (gy - gy.min())
    _, first_from_end = np.unique(key[::-1], return_index=True)
    return np.sort(n - 1 - first_from_end)


def line_indices(x: np.ndarray, y: np.ndarray, column: float = RESOLUTION) -> np.ndarray:
    """The samples of one unbroken polyline worth drawing: M4 where x is monotonic (either
    way), the cell rule of :func:`track_indices` otherwise."""
    n = len(x)
    if n <= 4:
        return np.arange(n)
    dx = np.diff(x)
    if np.all(dx >= 0):
        return m4_indices(x, y, column)
    if np.all(dx <= 0):
        return n - 1 - m4_indices(x[::-1], y[::-1], column)[::-1]
    return track_indices(x, y, column)
