"""The log console: a read-only text view fed by :mod:`logging` from any thread.

:class:`QtLogHandler` formats each record in the thread that logged it and hands the
text to the GUI thread through a Qt signal (queued across threads), so core code running
in a worker may log freely. :class:`LogConsole` shows the lines, coloured by level.
"""

from __future__ import annotations

import logging

from PySide6.QtCore import QObject, Signal, Slot
from PySide6.QtGui import QColor, QFontDatabase, QTextCharFormat, QTextCursor
from PySide6.QtWidgets import QPlainTextEdit, QWidget

_COLOURS = {
    logging.DEBUG: "#808080",
    logging.INFO: "",
    logging.WARNING: "#b36b00",
    logging.ERROR: "#c00000",
    logging.CRITICAL: "#c00000",
}


class _Bridge(QObject):
    """Owns the signal; lives in the GUI thread so emission from workers is queued."""

    sig_record = Signal(str, int)  # formatted text, level number


#: Loggers whose INFO lines are the application's own; other libraries' (PyOpenGL's
#: "OpenGL_accelerate module loaded" at start-up) show from WARNING on, unless the
#: console shows debug lines (``-v``).
OWN_LOGGERS = ("hydrosync", "plugins", "root")


def _own_or_important(record: logging.LogRecord, level: int) -> bool:
    if record.levelno >= logging.WARNING or level < logging.INFO:
        return True
    return record.name.split(".")[0].startswith(OWN_LOGGERS)


class QtLogHandler(logging.Handler):
    """A :class:`logging.Handler` that emits ``bridge.sig_record(text, levelno)``."""

    def __init__(self, level: int = logging.INFO) -> None:
        super().__init__(level)
        self.addFilter(lambda record: _own_or_important(record, self.level))
        self.bridge = _Bridge()
        self.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s",
                                            "%H:%M:%S"))

    def emit(self, record: logging.LogRecord) -> None:
        try:
            text = self.format(record)
            self.bridge.sig_record.emit(text, record.levelno)
        except RuntimeError:  # the console was deleted before the handler was removed
            pass
        except Exception:
            self.handleError(record)


class LogConsole(QPlainTextEdit):
    """Read-only console showing log lines; keeps the last *max_lines*.

    Call :meth:`install` to attach it to a logger (the root logger by default) and
    :meth:`uninstall` before it is destroyed.
    """

    def __init__(self, parent: QWidget | None = None, max_lines: int = 5000) -> None:
        super().__init__(parent)
        self.setReadOnly(True)
        self.setMaximumBlockCount(max_lines)
        self.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont))
        self.setPlaceholderText("Log messages appear here.")
        self.handler = QtLogHandler()
        self.handler.bridge.sig_record.connect(self._on_record)
        self._logger: logging.Logger | None = None

    def install(self, logger: logging.Logger | None = None, level: int = logging.INFO) -> None:
        """Attach the handler to *logger* (root by default) at *level*."""
        self.uninstall()
        self._logger = logger or logging.getLogger()
        self.handler.setLevel(level)
        self._logger.addHandler(self.handler)

    def uninstall(self) -> None:
        if self._logger is not None:
            self._logger.removeHandler(self.handler)
            self._logger = None

    def lines(self) -> list[str]:
        """The plain text of the console, one entry per line (for tests and copying)."""
        return self.toPlainText().splitlines()

    @Slot(str, int)
    def _on_record(self, text: str, level: int) -> None:
        fmt = QTextCharFormat()
        colour = _COLOURS.get(level, "#c00000" if level > logging.ERROR else "")
        if colour:
            fmt.setForeground(QColor(colour))
        cursor = QTextCursor(self.document())
        cursor.movePosition(QTextCursor.MoveOperation.End)
        if not self.document().isEmpty():
            cursor.insertBlock()
        cursor.insertText(text, fmt)
        bar = self.verticalScrollBar()
        bar.setValue(bar.maximum())
