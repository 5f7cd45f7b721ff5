"""Find what a user would stumble on in a laid-out window: squashed, clipped or hidden.

:func:`check_layout` walks the visible widgets under a window and reports

* **squashed** — a control (button, box, label, table…) smaller than Qt says it needs
  (its ``minimumSizeHint``): the lever-arm row squashed to a strip, "Ru[n all]";
* **clipped text** — a label whose text does not fit: a wrapped label shorter than its
  text's height, or a one-line label narrower than its text;
* **outside** — a widget that reaches beyond its parent where no scroll area can bring
  it into view (the pool parameter column cut off on the right);
* **overlap** — two sibling widgets of one layout drawn over each other;
* **legend** — a plot legend cut by its plot or covering most of it ("forwa/smoo"),
  and plots too small to read.

It needs no screen of its own: run it offscreen on a window resized to 1366×768 (see
``tests/gui/test_layout_harness.py``). Every problem names the widget by its path of
object names or classes, so a failure points to the code that laid it out.
"""

from __future__ import annotations

from dataclasses import dataclass

from PySide6.QtCore import QRect
from PySide6.QtWidgets import (
    QAbstractButton,
    QAbstractScrollArea,
    QAbstractSpinBox,
    QComboBox,
    QGroupBox,
    QLabel,
    QLineEdit,
    QTabBar,
    QWidget,
)

#: Controls whose minimum size hint is what their content needs.
CONTROLS = (QAbstractButton, QAbstractSpinBox, QComboBox, QLineEdit, QGroupBox, QLabel)
#: Pixels of tolerance (rounding of fractional layouts).
SLACK = 1
#: A plot whose data area is smaller than this cannot be read (pixels).
MIN_PLOT = (150, 90)
#: A legend may cover at most this fraction of its plot's data area.
MAX_LEGEND_SHARE = 0.5


@dataclass(frozen=True)
class Problem:
    """One layout fault: its kind, the widget's path and what is wrong."""

    kind: str
    widget: str
    detail: str

    def __str__(self) -> str:
        return f"{self.kind}: {self.widget}: {self.detail}"


def widget_path(widget: QWidget, root: QWidget | None = None) -> str:
    """``Panel/QSplitter/QScrollArea/…/QPushButton'Run'`` — names or classes up to *root*."""
    parts = []
    w: QWidget | None = widget
    while w is not None and w is not root:
        name = w.objectName() or type(w).__name__
        text = w.text() if isinstance(w, QAbstractButton | QLabel) else ""
        parts.append(f"{name}'{text[:30]}'" if text else name)
        w = w.parentWidget()
    return "/".join(reversed(parts))


def _visible(widget: QWidget, root: QWidget) -> bool:
    return widget.isVisibleTo(root) and widget.width() > 0 and widget.height() > 0


def _internal(widget: QWidget) -> bool:
    """A part Qt builds inside a composite control (a spin box's line edit, a tab bar's
    scroll arrows): its parent's size is what counts."""
    return isinstance(widget.parentWidget(), QAbstractSpinBox | QComboBox | QTabBar)


def minimum_size(widget: QWidget) -> tuple[int, int]:
    """The smallest size a layout may give *widget* (pixels): its explicit minimum where
    set, its minimum size hint otherwise (Qt's own rule, ``qSmartMinSize``)."""
    hint = widget.minimumSizeHint()
    width = widget.minimumWidth() or max(hint.width(), 0)
    height = widget.minimumHeight() or max(hint.height(), 0)
    return width, height


def _squashed(widget: QWidget, root: QWidget) -> list[Problem]:
    if not isinstance(widget, CONTROLS) or _internal(widget):
        return []
    if isinstance(widget, QLabel) and (widget.wordWrap() or not widget.text()):
        return []  # a wrapped label's hint is arbitrary; its height is checked below
    width, height = minimum_size(widget)
    if widget.width() + SLACK >= width and widget.height() + SLACK >= height:
        return []
    return [Problem("squashed", widget_path(widget, root),
                    f"{widget.width()}×{widget.height()} px, needs at least "
                    f"{width}×{height}")]


def _clipped_text(widget: QWidget, root: QWidget) -> list[Problem]:
    if not isinstance(widget, QLabel) or not widget.text() or widget.pixmap() is not None \
            and not widget.pixmap().isNull():
        return []
    room = widget.contentsRect()
    margin = widget.margin() * 2 + widget.indent() if widget.indent() > 0 else widget.margin() * 2
    if widget.wordWrap():
        need = widget.heightForWidth(widget.width())
        if need > widget.height() + SLACK:
            return [Problem("clipped text", widget_path(widget, root),
                            f"wrapped text needs {need} px height, has {widget.height()}")]
        return []
    need = widget.sizeHint().width() - margin
    if need > room.width() + SLACK and widget.minimumWidth() < need:
        return [Problem("clipped text", widget_path(widget, root),
                        f"text needs {need} px width, has {room.width()}")]
    return []


def _outside(widget: QWidget, root: QWidget) -> list[Problem]:
    """The widget reaches beyond its parent (or the window) and cannot be scrolled to."""
    parent = widget.parentWidget()
    if parent is None or widget is root or widget.isWindow():
        return []
    grand = parent.parentWidget()
    if isinstance(parent, QAbstractScrollArea) or (
            isinstance(grand, QAbstractScrollArea) and grand.viewport() is parent):
        return []  # the content of a scroll area: scroll bars bring it into view
    inside = parent.rect().adjusted(-SLACK, -SLACK, SLACK, SLACK)
    if inside.contains(widget.geometry()):
        return []
    geo = widget.geometry()
    return [Problem("outside", widget_path(widget, root),
                    f"at {geo.x()},{geo.y()} {geo.width()}×{geo.height()} beyond its parent "
                    f"{parent.width()}×{parent.height()} with no scroll bar")]


def _overlaps(parent: QWidget, root: QWidget) -> list[Problem]:
    layout = parent.layout()
    if layout is None:
        return []
    managed = []
    for i in range(layout.count()):
        w = layout.itemAt(i).widget()
        if w is not None and _visible(w, root):
            managed.append(w)
    out = []
    for i, a in enumerate(managed):
        for b in managed[i + 1:]:
            common: QRect = a.geometry().intersected(b.geometry())
            if common.width() > SLACK and common.height() > SLACK:
                out.append(Problem("overlap", widget_path(a, root),
                                   f"covers {common.width()}×{common.height()} px of "
                                   f"{widget_path(b, root)}"))
    return out


def _plot_problems(root: QWidget) -> list[Problem]:
    """Legends cut by their plot or covering most of it; plots too small to read."""
    try:
        import pyqtgraph as pg
    except ImportError:  # pragma: no cover - pyqtgraph is a dependency
        return []
    out = []
    plots = [w for w in (root, *root.findChildren(pg.PlotWidget))
             if isinstance(w, pg.PlotWidget)]
    for plot in plots:
        if plot is not root and not _visible(plot, root):
            continue
        path = widget_path(plot, root)
        item = plot.getPlotItem()
        box = item.vb.sceneBoundingRect()
        if box.width() < MIN_PLOT[0] or box.height() < MIN_PLOT[1]:
            out.append(Problem("small plot", path, f"data area {box.width():.0f}×"
                               f"{box.height():.0f} px, less than {MIN_PLOT[0]}×{MIN_PLOT[1]}"))
        legend = item.legend
        if legend is None or not legend.isVisible() or not getattr(legend, "items", None):
            continue
        lrect = legend.sceneBoundingRect()
        if not box.adjusted(-SLACK, -SLACK, SLACK, SLACK).contains(lrect):
            out.append(Problem("legend", path, f"legend {lrect.width():.0f}×"
                               f"{lrect.height():.0f} px cut by the plot area "
                               f"{box.width():.0f}×{box.height():.0f}"))
        elif lrect.width() * lrect.height() > MAX_LEGEND_SHARE * box.width() * box.height():
            out.append(Problem("legend", path, f"legend {lrect.width():.0f}×"
                               f"{lrect.height():.0f} px covers more than "
                               f"{MAX_LEGEND_SHARE:.0%} of the plot"))
    return out


def check_layout(root: QWidget) -> list[Problem]:
    """Every layout problem of the visible widgets under *root* (see the module doc)."""
    problems: list[Problem] = []
    widgets = [root, *root.findChildren(QWidget)]
    for widget in widgets:
        if not _visible(widget, root) and widget is not root:
            continue
        if widget is not root:
            problems += _squashed(widget, root)
            problems += _clipped_text(widget, root)
            problems += _outside(widget, root)
        problems += _overlaps(widget, root)
    problems += _plot_problems(root)
    return problems
