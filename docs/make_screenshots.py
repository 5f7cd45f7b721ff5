"""Regenerate ``docs/main-window.png``: the main window on the demo project.

Run ``xvfb-run -a .venv/bin/python docs/make_screenshots.py`` for a real X11 window (best
fonts), or with ``QT_QPA_PLATFORM=offscreen``. The demo project is built in a temporary
folder (``hydrosync_core.demo``-style: every plugin's simulator, then every plugin run);
settings go to a temporary file, never to the user's.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

from PySide6.QtCore import QSettings, QTimer
from PySide6.QtWidgets import QApplication

from hydrosync_core.plugins import discover, load_object
from hydrosync_core.project import Project

OUT = Path(__file__).with_name("main-window.png")


def demo_project(folder: Path) -> Path:
    """Fill and run every plugin that has a demo; return the saved project file."""
    project = Project.new("Survey launch — demo")
    for found in discover():
        spec = found.spec
        if spec is None or not spec.demo:
            continue
        load_object(spec.demo)(project, seed=1)
        if not spec.missing_inputs(project):
            spec.load_run()(project, dict(spec.default_params))
    path = folder / "demo.h5"
    project.save(path)
    project.close()
    return path


def main() -> int:
    app = QApplication(sys.argv[:1])
    from hydrosync_gui.main_window import MainWindow
    from hydrosync_gui.resources import icon

    app.setWindowIcon(icon("app.svg"))
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        path = demo_project(folder)
        settings = QSettings(str(folder / "settings.ini"), QSettings.Format.IniFormat)
        window = MainWindow(settings=settings)
        window.resize(1400, 860)
        window.show()
        window.open_project(str(path))

        def shoot() -> None:
            if window.busy:
                QTimer.singleShot(100, shoot)
                return
            item = window.browser.item("raw/gnss") or window.browser.item("raw")
            if item is not None:
                window.browser.tree.setCurrentItem(item)
            app.processEvents()
            window.grab().save(str(OUT))
            print(f"wrote {OUT}")
            window.close_without_prompt()

        QTimer.singleShot(300, shoot)
        app.exec()
        window.deleteLater()
    return 0


if __name__ == "__main__":
    sys.exit(main())
