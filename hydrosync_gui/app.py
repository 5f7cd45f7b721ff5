"""``hydrosync-gui [project.h5]``: start the HydroSync desktop application.

Sets the organisation and application names (where :class:`QSettings` keeps window
geometry and recent files), routes :mod:`logging` into the window's log console, and
installs an exception hook that logs an unexpected error and shows it in a message box
instead of killing the application.
"""

from __future__ import annotations

import argparse
import logging
import sys
import traceback
from types import TracebackType

from PySide6.QtCore import QSettings
from PySide6.QtWidgets import QApplication, QMessageBox, QWidget

from hydrosync_core import __version__
from hydrosync_core.errors import InputError

log = logging.getLogger("hydrosync_gui.app")

ORGANISATION = "HydroSync"
APPLICATION = "HydroSync"


def excepthook_for(parent: QWidget | None = None):
    """An ``sys.excepthook`` that logs the traceback and shows a one-line error."""
    showing = False

    def hook(exc_type: type[BaseException], exc: BaseException,
             tb: TracebackType | None) -> None:
        nonlocal showing
        if issubclass(exc_type, KeyboardInterrupt):
            sys.__excepthook__(exc_type, exc, tb)
            return
        details = "".join(traceback.format_exception(exc_type, exc, tb))
        log.error("unexpected error:\n%s", details.rstrip())
        line = exc.one_line() if isinstance(exc, InputError) else f"{exc_type.__name__}: {exc}"
        if showing or QApplication.instance() is None:
            return  # an error while the box is up: the log has it
        showing = True
        try:
            box = QMessageBox(QMessageBox.Icon.Critical, "HydroSync — unexpected error",
                              line, QMessageBox.StandardButton.Ok, parent)
            box.setInformativeText("The application keeps running; save your work. "
                                   "The details are in the log.")
            box.setDetailedText(details)
            box.exec()
        finally:
            showing = False

    return hook


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="hydrosync-gui",
                                     description="HydroSync desktop workbench.")
    parser.add_argument("project", nargs="?", help="project file (.h5) to open")
    parser.add_argument("--version", action="version", version=f"hydrosync-gui {__version__}")
    parser.add_argument("-v", "--verbose", action="store_true", help="log debug messages")
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the application; return its exit code."""
    args = build_parser().parse_args(sys.argv[1:] if argv is None else argv)
    logging.basicConfig(level=logging.DEBUG if args.verbose else logging.INFO,
                        format="%(levelname)s %(name)s: %(message)s")
    app = QApplication.instance() or QApplication(sys.argv[:1])
    app.setOrganizationName(ORGANISATION)
    app.setOrganizationDomain("hydrosync.invalid")
    app.setApplicationName(APPLICATION)
    app.setApplicationVersion(__version__)

    from hydrosync_gui.main_window import MainWindow  # after the app exists (fonts, icons)
    from hydrosync_gui.resources import icon

    app.setWindowIcon(icon("app.svg"))
    from hydrosync_gui.i18n import apply_saved_language

    apply_saved_language(QSettings())  # the View → Language choice, else the system locale
    window = MainWindow()
    previous_hook = sys.excepthook
    sys.excepthook = excepthook_for(window)
    try:
        window.show()
        if args.project:
            window.open_project(args.project)
        return app.exec()
    finally:
        sys.excepthook = previous_hook


if __name__ == "__main__":
    sys.exit(main())
