"""Where the main window opens: inside the screen's available geometry, never off it.

A window of 1280×800 on a 1366×768 laptop put the status bar (progress and Cancel) below
the screen, and a geometry saved on a large monitor restored the same way on a laptop.
:func:`fit_rect` is the pure rule (tested without a screen); :func:`fit_window` applies
it to a window after its saved geometry has been restored.
"""

from __future__ import annotations

from PySide6.QtCore import QRect, QSize
from PySide6.QtWidgets import QWidget

#: The size the window asks for on a screen with room to spare (pixels).
PREFERRED = QSize(1280, 800)
#: Below this available width the project dock starts narrow (pixels): on a 1366 px
#: laptop a 420 px dock left the panels 920 px, too little for a parameter column and
#: plots side by side.
NARROW_SCREEN = 1600
#: Width of the project dock on a narrow and on a wide screen (pixels).
DOCK_WIDTH_NARROW = 260
DOCK_WIDTH_WIDE = 420
#: Below this available height the log dock starts short (pixels).
SHORT_SCREEN = 900
LOG_HEIGHT_SHORT = 90
LOG_HEIGHT_TALL = 140
#: Room kept for the window manager's title bar and borders (pixels).
FRAME_ALLOWANCE = QSize(16, 40)


def fit_rect(available: QRect, wanted: QRect | None = None,
             preferred: QSize = PREFERRED) -> QRect:
    """The window's client rectangle inside *available* (screen pixels).

    Parameters
    ----------
    available : QRect
        The screen's available geometry (desktop minus task bars).
    wanted : QRect, optional
        A restored geometry; it keeps its size and position where they fit, and is
        shrunk and moved inside *available* where they do not. None: *preferred*
        centred.
    preferred : QSize
        The size wanted when nothing was restored.

    Returns
    -------
    QRect
        A rectangle whose frame (client plus :data:`FRAME_ALLOWANCE`) lies inside
        *available*.
    """
    border = FRAME_ALLOWANCE.width() // 2
    title = FRAME_ALLOWANCE.height() - border
    # The client area may lie inside this rectangle (the frame around it stays on screen).
    room = available.adjusted(border, title, -border, -border)
    if wanted is None or not wanted.isValid():
        size = preferred.boundedTo(room.size())
        left = room.left() + (room.width() - size.width()) // 2
        top = room.top() + (room.height() - size.height()) // 2
        return QRect(left, top, size.width(), size.height())
    size = wanted.size().boundedTo(room.size())
    left = min(max(wanted.left(), room.left()), room.right() + 1 - size.width())
    top = min(max(wanted.top(), room.top()), room.bottom() + 1 - size.height())
    return QRect(left, top, size.width(), size.height())


def log_height(available: QRect) -> int:
    """The log dock's starting height: 5 lines on a short screen (768 px), 7 otherwise."""
    return LOG_HEIGHT_SHORT if available.height() < SHORT_SCREEN else LOG_HEIGHT_TALL


def dock_width(available: QRect) -> int:
    """The project dock's starting width: narrower below :data:`NARROW_SCREEN` pixels."""
    return DOCK_WIDTH_NARROW if available.width() < NARROW_SCREEN else DOCK_WIDTH_WIDE


def fit_window(window: QWidget, restored: bool) -> QRect:
    """Move and resize *window* so it lies on its screen's available geometry.

    *restored*: a saved geometry was applied (it is kept where it fits). Returns the
    client rectangle set. A maximised or full-screen window is left to the window manager.
    """
    screen = window.screen()
    if screen is None or window.isMaximized() or window.isFullScreen():
        return window.geometry()
    rect = fit_rect(screen.availableGeometry(), window.geometry() if restored else None)
    window.setGeometry(rect)
    return rect
