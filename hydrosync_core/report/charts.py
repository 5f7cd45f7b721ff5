"""Small vector charts drawn with ``reportlab.graphics`` (lines, points, spans, legend).

Why not matplotlib? The figures must be *vector* in the PDF (a QA reader zooms on a
correlation peak) and the core must stay headless. reportlab cannot place a matplotlib
PDF/SVG page without an extra package (svglib or pdfrw, not dependencies of HydroSync),
and a raster (Agg) image is blurry when zoomed and hides its numbers from text search.
``reportlab.graphics`` shapes are vector, need nothing beyond reportlab, and their tick
labels and legends stay selectable text. reportlab's own ``LinePlot`` is awkward to style
(axis titles, legends outside the plot, equal aspect for plan views), so this module
draws axes, ticks and series itself on a :class:`~reportlab.graphics.shapes.Drawing`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from reportlab.graphics.shapes import (
    Circle,
    Drawing,
    Group,
    Line,
    Polygon,
    PolyLine,
    Rect,
    String,
)
from reportlab.lib import colors

from hydrosync_core.i18n import tr
from hydrosync_core.report.decimate import RESOLUTION, cloud_indices, line_indices
from hydrosync_core.report.styles import FONT, GRID, INK, MUTED, SERIES

FONT_SIZE = 7.5


def _text_width(text: str) -> float:
    """Width of *text* in Latin-letter units: a Chinese character is about two."""
    return sum(2.0 if ord(ch) > 0x2E80 else 1.0 for ch in text)


def nice_ticks(lo: float, hi: float, target: int = 6) -> np.ndarray:
    """Round tick values covering ``[lo, hi]`` with a 1-2-2.5-5 step, about *target* ticks."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return np.array([0.0, 1.0])
    if hi <= lo:
        hi = lo + (abs(lo) * 0.1 or 1.0)
    raw = (hi - lo) / max(target - 1, 1)
    mag = 10.0 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 2.5, 5, 10) if m * mag >= raw)
    first = math.ceil(lo / step - 1e-9) * step
    ticks = np.arange(first, hi + step * 1e-6, step)
    return np.round(ticks, 12)


def tick_label(value: float, step: float) -> str:
    """Format a tick with just enough decimals for *step*."""
    decimals = max(0, -math.floor(math.log10(step) + 1e-9)) if step > 0 else 0
    if step > 0 and abs(step * 10**decimals - round(step * 10**decimals)) > 1e-6:
        decimals += 1  # steps like 0.25
    text = f"{value:.{decimals}f}"
    return "0" if text.strip("-0.") == "" else text.replace("-", "\u2212")


@dataclass
class _Series:
    kind: str  # "line", "points", "vline", "hline", "vspan", "band"
    x: np.ndarray
    y: np.ndarray
    color: colors.Color
    label: str | None
    width: float = 1.0
    size: float = 1.5
    dash: tuple | None = None
    marker: str = "circle"
    y2: np.ndarray | None = None  # upper edge of a "band" (y is the lower)


@dataclass
class Chart:
    """A single x-y panel.

    Parameters
    ----------
    width, height : float
        Size of the whole drawing in points (1/72 in), axis labels and legend included.
    xlabel, ylabel : str
        Axis titles; put the unit in brackets, e.g. ``"latency Δt [s]"``.
    equal_aspect : bool
        Same scale on both axes (plan views); the data box is centred.
    """

    width: float
    height: float
    xlabel: str = ""
    ylabel: str = ""
    equal_aspect: bool = False
    xlim: tuple[float, float] | None = None
    ylim: tuple[float, float] | None = None
    series: list[_Series] = field(default_factory=list)

    # ------------------------------------------------------------------ adding data
    def _color(self, color) -> colors.Color:
        if color is None:
            used = sum(1 for s in self.series if s.kind in ("line", "points"))
            return SERIES[used % len(SERIES)]
        return color if isinstance(color, colors.Color) else colors.HexColor(color)

    def line(self, x, y, *, color=None, label=None, width=1.0, dash=None) -> Chart:
        """A polyline; NaN values break the line."""
        self.series.append(_Series("line", np.asarray(x, float), np.asarray(y, float),
                                   self._color(color), label, width=width, dash=dash))
        return self

    def points(self, x, y, *, color=None, label=None, size=1.5, marker="circle") -> Chart:
        """Filled markers of radius (half side) *size* points: ``"circle"`` or ``"square"``.

        Squares are cheaper in the PDF: use them for clouds of thousands of points.
        """
        self.series.append(_Series("points", np.asarray(x, float), np.asarray(y, float),
                                   self._color(color), label, size=size, marker=marker))
        return self

    def envelope(self, x, y, *, color=None, label=None, bins: int = 150,
                 width: float = 0.8) -> Chart:
        """A long, noisy series as what a printed page can show: the range (min to max)
        of each of *bins* equal slices of x as a light band, and their median as a line.

        Drawn sample by sample, a day of a ±0.4° noisy angle is a solid block of ink
        that hides its trend and the series drawn under it. Empty slices break both.
        """
        x, y = np.asarray(x, float), np.asarray(y, float)
        ok = np.isfinite(x) & np.isfinite(y)
        x, y = x[ok], y[ok]
        colour = self._color(color)
        if x.size < 2 * bins:  # few samples: each one can be seen
            return self.line(x, y, color=colour, label=label, width=width)
        edges = np.linspace(x.min(), x.max(), bins + 1)
        which = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, bins - 1)
        order = np.lexsort((y, which))
        which, ys = which[order], y[order]
        starts = np.searchsorted(which, np.arange(bins), side="left")
        ends = np.searchsorted(which, np.arange(bins), side="right")
        filled = ends > starts
        lo = np.full(bins, np.nan)
        hi = np.full(bins, np.nan)
        mid = np.full(bins, np.nan)
        lo[filled] = ys[starts[filled]]
        hi[filled] = ys[ends[filled] - 1]
        mid[filled] = ys[(starts[filled] + ends[filled] - 1) // 2]  # sorted: the median
        centre = (edges[:-1] + edges[1:]) / 2
        self.band(centre, lo, hi, color=colour)
        return self.line(centre, mid, color=colour, label=label, width=width)

    def band(self, x, lo, hi, *, color=None, label=None, alpha: float = 0.28) -> Chart:
        """A shaded band from *lo* to *hi* over *x* (NaN breaks it), e.g. the spread of
        many curves: 500 R curves drawn one by one printed as a solid block; their
        min–max band and a median curve show the same at a glance."""
        colour = self._color(color)
        light = colors.Color(colour.red, colour.green, colour.blue, alpha=alpha)
        self.series.append(_Series("band", np.asarray(x, float), np.asarray(lo, float), light,
                                   label, y2=np.asarray(hi, float)))
        return self

    def polygon(self, x, y, *, color=MUTED, width=0.5, label=None) -> Chart:
        """A closed outline (e.g. a design face)."""
        x, y = np.asarray(x, float), np.asarray(y, float)
        return self.line(np.append(x, x[:1]), np.append(y, y[:1]), color=color, width=width,
                         label=label)

    def vline(self, x: float, *, color=INK, label=None, dash=(3, 2), width=0.8) -> Chart:
        self.series.append(_Series("vline", np.array([x], float), np.array([]),
                                   self._color(color), label, width=width, dash=dash))
        return self

    def hline(self, y: float, *, color=INK, label=None, dash=(3, 2), width=0.8) -> Chart:
        self.series.append(_Series("hline", np.array([]), np.array([y], float),
                                   self._color(color), label, width=width, dash=dash))
        return self

    def vspan(self, x0: float, x1: float, *, color="#cfe0f0", label=None) -> Chart:
        """A shaded vertical band (e.g. a confidence interval)."""
        self.series.append(_Series("vspan", np.array([x0, x1], float), np.array([]),
                                   self._color(color), label))
        return self

    # ------------------------------------------------------------------ layout
    def _data_limits(self) -> tuple[float, float, float, float]:
        xs = [s.x for s in self.series
              if s.kind in ("line", "points", "vline", "vspan", "band")]
        ys = [s.y for s in self.series if s.kind in ("line", "points", "hline", "band")]
        ys += [s.y2 for s in self.series if s.kind == "band"]
        x = np.concatenate(xs) if xs else np.array([0.0, 1.0])
        y = np.concatenate(ys) if ys else np.array([0.0, 1.0])
        x, y = x[np.isfinite(x)], y[np.isfinite(y)]
        x0, x1 = (float(x.min()), float(x.max())) if x.size else (0.0, 1.0)
        y0, y1 = (float(y.min()), float(y.max())) if y.size else (0.0, 1.0)
        if self.xlim:
            x0, x1 = self.xlim
        if self.ylim:
            y0, y1 = self.ylim
        return x0, x1, y0, y1

    def _legend_items(self) -> list[_Series]:
        return [s for s in self.series if s.label]

    def drawing(self) -> Drawing:
        """Render to a reportlab :class:`Drawing` (a flowable)."""
        d = Drawing(self.width, self.height)
        legend = self._legend_items()
        legend_rows = self._legend_rows(legend)
        left, right = 46.0, 8.0
        bottom = 30.0 + 11.0 * len(legend_rows)
        top = 6.0
        box_w, box_h = self.width - left - right, self.height - bottom - top

        x0, x1, y0, y1 = self._data_limits()
        xt = nice_ticks(x0, x1) if not self.xlim else nice_ticks(*self.xlim)
        yt = nice_ticks(y0, y1) if not self.ylim else nice_ticks(*self.ylim)
        # Pad to whole ticks unless fixed limits were asked for.
        if not self.xlim:
            step = xt[1] - xt[0] if len(xt) > 1 else 1.0
            x0, x1 = min(x0, xt[0]), max(x1, xt[-1])
            if x1 - x0 < step:
                x1 = x0 + step
        if not self.ylim:
            step = yt[1] - yt[0] if len(yt) > 1 else 1.0
            y0 = min(y0, math.floor(y0 / step + 1e-9) * step)
            y1 = max(y1, math.ceil(y1 / step - 1e-9) * step)
            yt = nice_ticks(y0, y1)
        if self.equal_aspect:
            scale = min(box_w / (x1 - x0), box_h / (y1 - y0))
            cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
            x0, x1 = cx - box_w / scale / 2, cx + box_w / scale / 2
            y0, y1 = cy - box_h / scale / 2, cy + box_h / scale / 2
            xt, yt = nice_ticks(x0, x1), nice_ticks(y0, y1)
        xt = xt[(xt >= x0 - 1e-9) & (xt <= x1 + 1e-9)]
        yt = yt[(yt >= y0 - 1e-9) & (yt <= y1 + 1e-9)]

        def px(v):
            return left + (np.asarray(v, float) - x0) / (x1 - x0) * box_w

        def py(v):
            return bottom + (np.asarray(v, float) - y0) / (y1 - y0) * box_h

        self._draw_axes(d, left, bottom, box_w, box_h, xt, yt, px, py)
        plot = Group()
        for s in self.series:
            self._draw_series(plot, s, px, py, left, bottom, box_w, box_h)
        d.add(plot)
        d.add(Rect(left, bottom, box_w, box_h, fillColor=None, strokeColor=INK,
                   strokeWidth=0.6))
        self._draw_legend(d, legend_rows, left)
        return d

    # ------------------------------------------------------------------ drawing
    def _draw_axes(self, d, left, bottom, box_w, box_h, xt, yt, px, py) -> None:
        xstep = float(xt[1] - xt[0]) if len(xt) > 1 else 1.0
        ystep = float(yt[1] - yt[0]) if len(yt) > 1 else 1.0
        for v in xt:
            x = float(px(v))
            d.add(Line(x, bottom, x, bottom + box_h, strokeColor=GRID, strokeWidth=0.3))
            d.add(Line(x, bottom, x, bottom - 3, strokeColor=INK, strokeWidth=0.6))
            d.add(String(x, bottom - 11, tick_label(v, xstep), fontName=FONT,
                         fontSize=FONT_SIZE, fillColor=INK, textAnchor="middle"))
        for v in yt:
            y = float(py(v))
            d.add(Line(left, y, left + box_w, y, strokeColor=GRID, strokeWidth=0.3))
            d.add(Line(left - 3, y, left, y, strokeColor=INK, strokeWidth=0.6))
            d.add(String(left - 5, y - 2.5, tick_label(v, ystep), fontName=FONT,
                         fontSize=FONT_SIZE, fillColor=INK, textAnchor="end"))
        d.add(String(left + box_w / 2, bottom - 23, tr(self.xlabel), fontName=FONT,
                     fontSize=FONT_SIZE + 0.5, fillColor=INK, textAnchor="middle"))
        ylabel = String(0, 0, tr(self.ylabel), fontName=FONT, fontSize=FONT_SIZE + 0.5,
                        fillColor=INK, textAnchor="middle")
        g = Group(ylabel)
        g.translate(9, bottom + box_h / 2)
        g.rotate(90)
        d.add(g)

    @staticmethod
    def _draw_series(g, s: _Series, px, py, left, bottom, box_w, box_h) -> None:
        def inside(xv, yv):
            return ((xv >= left - 0.5) & (xv <= left + box_w + 0.5)
                    & (yv >= bottom - 0.5) & (yv <= bottom + box_h + 0.5))

        if s.kind == "band":
            xv = np.clip(px(s.x), left, left + box_w)
            lo = np.clip(py(s.y), bottom, bottom + box_h)
            hi = np.clip(py(s.y2), bottom, bottom + box_h)
            ok = np.isfinite(lo) & np.isfinite(hi)
            breaks = np.flatnonzero(np.diff(ok.astype(int)) != 0) + 1
            for seg in np.split(np.arange(len(xv)), breaks):
                if len(seg) < 2 or not ok[seg[0]]:
                    continue
                ring = np.concatenate([np.column_stack([xv[seg], hi[seg]]),
                                       np.column_stack([xv[seg], lo[seg]])[::-1]])
                g.add(Polygon(ring.ravel().tolist(), fillColor=s.color, strokeColor=None))
        elif s.kind == "vspan":
            a, b = sorted(np.clip(px(s.x), left, left + box_w))
            g.add(Rect(a, bottom, b - a, box_h, fillColor=s.color, strokeColor=None))
        elif s.kind == "vline":
            x = float(px(s.x[0]))
            if left <= x <= left + box_w:
                g.add(Line(x, bottom, x, bottom + box_h, strokeColor=s.color,
                           strokeWidth=s.width, strokeDashArray=s.dash))
        elif s.kind == "hline":
            y = float(py(s.y[0]))
            if bottom <= y <= bottom + box_h:
                g.add(Line(left, y, left + box_w, y, strokeColor=s.color,
                           strokeWidth=s.width, strokeDashArray=s.dash))
        elif s.kind == "points":
            xv, yv = px(s.x), py(s.y)
            keep = np.isfinite(xv) & np.isfinite(yv) & inside(xv, yv)
            r = s.size
            xv, yv = xv[keep], yv[keep]
            # Markers hidden under others add bytes and layout time, nothing to see.
            shown = cloud_indices(xv, yv, max(RESOLUTION, r / 2))
            for a, b in zip(xv[shown].tolist(), yv[shown].tolist(), strict=True):
                if s.marker == "square":
                    g.add(Rect(a - r, b - r, 2 * r, 2 * r, fillColor=s.color, strokeColor=None))
                else:
                    g.add(Circle(a, b, r, fillColor=s.color, strokeColor=None))
        elif s.kind == "line":
            xv, yv = px(s.x), py(s.y)
            ok = np.isfinite(xv) & np.isfinite(yv)
            # Clip to the box vertically by limiting values (lines stay continuous).
            yv = np.clip(yv, bottom, bottom + box_h)
            xv = np.clip(xv, left, left + box_w)
            breaks = np.flatnonzero(np.diff(ok.astype(int)) != 0) + 1
            for seg in np.split(np.arange(len(xv)), breaks):
                seg = seg[ok[seg]] if len(seg) else seg
                if len(seg) < 2:
                    continue
                # A long series as its per-column envelope: the same ink, a fraction of
                # the vertices (a survey day drew as a solid block of 10⁵ segments).
                seg = seg[line_indices(xv[seg], yv[seg])]
                pts = np.column_stack([xv[seg], yv[seg]]).ravel().tolist()
                g.add(PolyLine(pts, strokeColor=s.color, strokeWidth=s.width,
                               strokeDashArray=s.dash, strokeLineJoin=1))

    def _legend_rows(self, legend: list[_Series]) -> list[list[tuple[_Series, float]]]:
        """Pack legend entries into rows that fit the drawing width."""
        rows: list[list[tuple[_Series, float]]] = [[]]
        used = 46.0
        for s in legend:
            w = 22 + 4.2 * _text_width(tr(s.label or ""))
            if rows[-1] and used + w > self.width - 8:
                rows.append([])
                used = 46.0
            rows[-1].append((s, w))
            used += w
        return [r for r in rows if r]

    def _draw_legend(self, d, rows, left) -> None:
        for i, row in enumerate(rows):
            y = 4 + 11.0 * (len(rows) - 1 - i)
            x = left
            for s, w in row:
                if s.kind == "points" and s.marker == "square":
                    r = max(s.size, 2.0)
                    d.add(Rect(x + 7 - r, y + 3 - r, 2 * r, 2 * r, fillColor=s.color,
                               strokeColor=None))
                elif s.kind == "points":
                    d.add(Circle(x + 7, y + 3, max(s.size, 2.0), fillColor=s.color,
                                 strokeColor=None))
                elif s.kind in ("vspan", "band"):
                    d.add(Rect(x + 1, y - 1, 12, 8, fillColor=s.color, strokeColor=None))
                else:
                    d.add(Line(x, y + 3, x + 14, y + 3, strokeColor=s.color,
                               strokeWidth=max(s.width, 1.0), strokeDashArray=s.dash))
                d.add(String(x + 18, y, tr(s.label), fontName=FONT, fontSize=FONT_SIZE,
                             fillColor=MUTED if s.kind == "vspan" else INK))
                x += w
