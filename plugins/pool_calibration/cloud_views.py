"""Views of the laser and multibeam clouds coloured by face (target ENU, m).

Two interchangeable views with the same API (``draw(names, clouds)``, ``set_after(bool)``,
``clear()``): :class:`GLCloudView` (3-D, pyqtgraph.opengl) where an OpenGL context can be
created, and :class:`ProjectionView` (2-D plan E-N and section N-U) everywhere else,
e.g. under ``QT_QPA_PLATFORM=offscreen``. ``clouds`` is a dict of the stored plan arrays:
``laser_xyz`` (n, 3), ``laser_face`` (n,), ``mbes_before_xyz`` (m, 3), ``mbes_after_xyz``
(m, 3) or None, ``mbes_face`` (m,), face indices into *names* (-1 = on no face).
"""

from __future__ import annotations

import functools

import numpy as np
import pyqtgraph as pg
from PySide6.QtWidgets import QHBoxLayout, QVBoxLayout, QWidget

# Qualitative palette (tab20 order, strong colours first): neighbouring faces differ.
PALETTE = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
           "#17becf", "#bcbd22", "#7f7f7f", "#aec7e8", "#ffbb78", "#98df8a", "#ff9896",
           "#c5b0d5", "#c49c94", "#f7b6d2", "#9edae5", "#dbdb8d", "#393b79")
UNASSIGNED = "#c8c8c8"
#: Face kind -> shades of one hue (dark to light): a kind reads at a glance, neighbouring
#: faces of one kind still differ. The order is the legend's.
KIND_SHADES = {
    "wall": ("#1f77b4", "#4f9bd0", "#16527f"),
    "perpendicular side": ("#ff7f0e", "#ffa54f", "#c25f05"),
    "oblique side": ("#2ca02c", "#5cc45c", "#1d6d1d"),
    "top": ("#d62728", "#e8666a", "#9c1b1c"),
    "underside": ("#9467bd", "#b595d4", "#6a4690"),
    "floor": ("#8c564b", "#b07f74", "#5f3a33"),
    "other": ("#7f7f7f", "#a5a5a5", "#555555"),
}
_ROLE_KIND = {"wall": "wall", "perpendicular": "perpendicular side",
              "oblique": "oblique side"}


def face_kind(name: str, role: str | None = None) -> str:
    """The kind of face *name* (a key of :data:`KIND_SHADES`), from its role in the
    adjustment when known (``wall``, ``perpendicular``, ``oblique``, ``horizontal``),
    else from the words of its name (``N1_up_top``, ``floor``)."""
    low = name.lower()
    if role in _ROLE_KIND:
        return _ROLE_KIND[role]
    if role == "horizontal" or role is None:
        for word, kind in (("floor", "floor"), ("bottom", "underside"),
                           ("under", "underside"), ("top", "top")):
            if word in low:
                return kind
    if role is None:
        for word in ("wall", "perpendicular", "oblique"):
            if word in low:
                return _ROLE_KIND[word]
    return "top" if role == "horizontal" else "other"


class _FaceColours:
    """The colours of the faces on show, shared by the cloud views and the face table
    (one pool panel per window: :meth:`CloudBox.draw` sets them, the table's swatches
    read them with :func:`face_colour` when painted)."""

    def __init__(self) -> None:
        self.kinds: list[str] = []
        self.colours: list[str] = []

    def set(self, kinds: list[str]) -> None:
        seen: dict[str, int] = {}
        self.kinds, self.colours = list(kinds), []
        for kind in kinds:
            shades = KIND_SHADES[kind]
            self.colours.append(shades[seen.get(kind, 0) % len(shades)])
            seen[kind] = seen.get(kind, 0) + 1


FACE_COLOURS = _FaceColours()


def set_face_kinds(kinds: list[str]) -> None:
    """Colour face *k* by ``kinds[k]`` from now on (see :class:`_FaceColours`)."""
    FACE_COLOURS.set(kinds)


def face_colour(k: int) -> str:
    """Hex colour of face index *k*: a shade of its kind's hue once the kinds are set,
    else a colour of :data:`PALETTE` (-1 = soundings on no face: light grey)."""
    if k < 0:
        return UNASSIGNED
    if k < len(FACE_COLOURS.colours):
        return FACE_COLOURS.colours[k]
    return PALETTE[k % len(PALETTE)]


def gl_available() -> bool:
    """True if pyqtgraph.opengl imports and a real OpenGL context can be made current.

    The offscreen/minimal platforms never give one ("QOpenGLWidget: Failed to create
    context"), so they are refused without trying; elsewhere a context is created on an
    offscreen surface, which fails cleanly on machines without GL drivers. Needs the
    QApplication; the answer is then cached for the process.
    """
    from PySide6.QtGui import QGuiApplication

    return QGuiApplication.instance() is not None and _probe_gl()


@functools.cache
def _probe_gl() -> bool:
    from PySide6.QtGui import QGuiApplication, QOffscreenSurface, QOpenGLContext

    if QGuiApplication.platformName() in ("offscreen", "minimal", "vnc"):
        return False
    try:
        import pyqtgraph.opengl  # noqa: F401  (needs PyOpenGL)
    except Exception:
        return False
    surface = QOffscreenSurface()
    surface.create()
    context = QOpenGLContext()
    ok = surface.isValid() and context.create() and context.makeCurrent(surface)
    if ok:
        context.doneCurrent()
    surface.destroy()
    return bool(ok)


def _split(face: np.ndarray) -> dict[int, np.ndarray]:
    """Row indices per face index (sorted keys, -1 first)."""
    return {int(k): np.flatnonzero(face == k) for k in np.unique(face)}


def _tip(names: list[str], k: int, cloud: str) -> str | None:
    """Tool tip of a point of face *k*: its name, kind and cloud."""
    if k < 0 or k >= len(names):
        return None
    kind = FACE_COLOURS.kinds[k] if k < len(FACE_COLOURS.kinds) else ""
    return f"{names[k]}" + (f" ({kind})" if kind else "") + f", {cloud}"


class ProjectionView(QWidget):
    """Plan (E-N) and section (N-U) scatter plots, one item per face and cloud.

    ``laser_items[k]`` / ``mbes_items[k]`` are ``(plan_item, section_item)`` pairs of
    :class:`pyqtgraph.ScatterPlotItem` holding the points of face *k*.
    """

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.plan = pg.PlotWidget(title="Plan view (axes not to scale)")
        self.section = pg.PlotWidget(title="Section (looking along east)")
        for plot, (xl, yl) in ((self.plan, ("East", "North")),
                               (self.section, ("North", "Up"))):
            plot.setBackground("w")
            plot.setLabel("bottom", xl, units="m")
            plot.setLabel("left", yl, units="m")
            plot.showGrid(x=True, y=True, alpha=0.25)
        # The section keeps true shape; the plan stretches east so that a misfit of a few
        # centimetres across the wall and the blocks is visible at the scale of the target.
        self.section.setAspectLocked(True)
        # Fixed axis width: changing tick-label widths would resize the aspect-locked view
        # and change its range again, without end.
        self.section.getAxis("left").setWidth(52)
        lay = QHBoxLayout(self)
        lay.setContentsMargins(0, 0, 0, 0)
        lay.addWidget(self.plan, 1)
        lay.addWidget(self.section, 1)
        self.laser_items: dict[int, tuple] = {}
        self.mbes_items: dict[int, tuple] = {}
        self._mbes: dict[int, tuple[np.ndarray, np.ndarray | None]] = {}
        self.after = False

    def clear(self) -> None:
        self.plan.clear()
        self.section.clear()
        self.laser_items, self.mbes_items, self._mbes = {}, {}, {}

    def _pair(self, xyz: np.ndarray, colour: str, symbol: str, size: float,
              tip: str | None = None) -> tuple:
        pair = []
        for plot, (i, j) in ((self.plan, (0, 1)), (self.section, (1, 2))):
            # Hovering a point names its face (the legend names only the kinds).
            item = pg.ScatterPlotItem(x=xyz[:, i], y=xyz[:, j], symbol=symbol, size=size,
                                      pen=None, brush=pg.mkBrush(colour),
                                      hoverable=tip is not None,
                                      tip=None if tip is None else (lambda tip=tip, **_: tip))
            plot.addItem(item)
            pair.append(item)
        return tuple(pair)

    def draw(self, names: list[str], clouds: dict) -> None:
        """Draw *clouds* (see module doc); the multibeam as corrected if ``self.after``."""
        self.clear()
        for k, rows in _split(clouds["laser_face"]).items():
            # Laser: small, half-transparent discs under the soundings.
            colour = pg.mkColor(face_colour(k))
            colour.setAlpha(110)
            self.laser_items[k] = self._pair(clouds["laser_xyz"][rows], colour, "o", 3,
                                             _tip(names, k, "laser"))
        before, after = clouds["mbes_before_xyz"], clouds.get("mbes_after_xyz")
        for k, rows in _split(clouds["mbes_face"]).items():
            self._mbes[k] = (before[rows], None if after is None else after[rows])
            # Soundings on no face (floor, water column) are context only: small and grey.
            size, symbol = (2, "o") if k < 0 else (4, "t")
            colour = pg.mkColor(face_colour(k))
            colour.setAlpha(120 if k < 0 else 255)
            self.mbes_items[k] = self._pair(self._mbes_xyz(k), colour, symbol, size,
                                            _tip(names, k, "multibeam"))
            for item in self.mbes_items[k]:
                item.setZValue(-1 if k < 0 else 1)
        self._frame(clouds)

    def _mbes_xyz(self, k: int) -> np.ndarray:
        before, after = self._mbes[k]
        return after if self.after and after is not None else before

    def set_after(self, after: bool) -> None:
        """Show the multibeam georeferenced with the final (True) or coarse values."""
        self.after = after
        for k, (plan, section) in self.mbes_items.items():
            xyz = self._mbes_xyz(k)
            plan.setData(x=xyz[:, 0], y=xyz[:, 1])
            section.setData(x=xyz[:, 1], y=xyz[:, 2])

    def _frame(self, clouds: dict) -> None:
        # Zoom on the target (laser + face soundings), not on the whole pool floor.
        parts = [clouds["laser_xyz"], clouds["mbes_before_xyz"][clouds["mbes_face"] >= 0]]
        pts = np.concatenate([p for p in parts if len(p)] or [np.zeros((0, 3))])
        if len(pts) == 0:
            return
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        pad = 0.05 * (hi - lo) + 0.2
        self.plan.setRange(xRange=(lo[0] - pad[0], hi[0] + pad[0]),
                           yRange=(lo[1] - pad[1], hi[1] + pad[1]), padding=0)
        self.section.setRange(xRange=(lo[1] - pad[1], hi[1] + pad[1]),
                              yRange=(lo[2] - pad[2], hi[2] + pad[2]))


class GLCloudView(QWidget):
    """3-D view (pyqtgraph.opengl); only constructed when :func:`gl_available`."""

    def __init__(self, parent: QWidget | None = None) -> None:
        import pyqtgraph.opengl as gl

        super().__init__(parent)
        self._gl = gl
        self.view = gl.GLViewWidget()
        self.view.setBackgroundColor("w")
        QVBoxLayout(self).addWidget(self.view)
        self.laser_item = None
        self.mbes_item = None
        self._mbes: tuple[np.ndarray, np.ndarray | None] | None = None
        self.after = False

    def clear(self) -> None:
        for item in (self.laser_item, self.mbes_item):
            if item is not None:
                self.view.removeItem(item)
        self.laser_item = self.mbes_item = None
        self._mbes = None

    @staticmethod
    def _rgba(face: np.ndarray, alpha: float) -> np.ndarray:
        n = max(int(face.max(initial=-1)) + 1, 1)
        table = np.array([pg.mkColor(face_colour(k)).getRgbF() for k in range(n)])
        rgba = np.where((face >= 0)[:, None], table[np.maximum(face, 0)],
                        pg.mkColor(UNASSIGNED).getRgbF())
        rgba[:, 3] = alpha
        return rgba.astype(np.float32)

    def draw(self, names: list[str], clouds: dict) -> None:
        gl = self._gl
        self.clear()
        laser = np.asarray(clouds["laser_xyz"], np.float32)
        self._mbes = (np.asarray(clouds["mbes_before_xyz"], np.float32),
                      None if clouds.get("mbes_after_xyz") is None
                      else np.asarray(clouds["mbes_after_xyz"], np.float32))
        self.laser_item = gl.GLScatterPlotItem(
            pos=laser, color=self._rgba(clouds["laser_face"], 0.45), size=2, pxMode=True)
        self.mbes_item = gl.GLScatterPlotItem(
            pos=self._mbes_xyz(), color=self._rgba(clouds["mbes_face"], 1.0), size=3,
            pxMode=True)
        for item in (self.laser_item, self.mbes_item):
            item.setGLOptions("translucent")  # additive blending vanishes on white
            self.view.addItem(item)
        if len(laser):
            lo, hi = laser.min(axis=0), laser.max(axis=0)
            centre = (lo + hi) / 2
            self.view.opts["center"] = pg.Vector(*centre)
            # Close enough that the target fills the view (at 2x its size half was empty).
            self.view.setCameraPosition(distance=float(1.6 * (hi - lo).max() + 1.0),
                                        elevation=25, azimuth=200)

    def _mbes_xyz(self) -> np.ndarray:
        before, after = self._mbes
        return after if self.after and after is not None else before

    def set_after(self, after: bool) -> None:
        self.after = after
        if self.mbes_item is not None:
            self.mbes_item.setData(pos=self._mbes_xyz())
