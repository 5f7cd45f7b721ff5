"""Screenshots of the workbench in Simplified Chinese: ``docs/zh_CN-<panel>.png`` (1366×768).

Usage::

    QT_QPA_PLATFORM=offscreen .venv/bin/python docs/make_screenshots_zh.py [demo.h5]

With a project file (e.g. ``hydrosync demo``'s ``demo.h5``) every plugin panel is shown on
it; without, the demo project is built first (as ``docs/make_screenshots.py`` does).
Settings go to a temporary file, never to the user's. Prints, per panel, the texts still
shown in English (names, numbers and units excepted) — what a translator should add.
"""

from __future__ import annotations

import re
import sys
import tempfile
import time
from pathlib import Path

from PySide6.QtCore import QSettings
from PySide6.QtWidgets import QAbstractButton, QApplication, QGroupBox, QLabel

DOCS = Path(__file__).resolve().parent


def english_left(window) -> list[str]:
    """Visible label, button and group texts with an English word of 4+ letters."""
    out = []
    for widget in window.findChildren(QLabel) + window.findChildren(QAbstractButton) + \
            window.findChildren(QGroupBox):
        if not widget.isVisible():
            continue
        text = widget.title() if isinstance(widget, QGroupBox) else widget.text()
        plain = re.sub(r"<[^>]+>|&\w+;", " ", text)
        if re.search(r"[A-Za-z]{4,}", plain) and not re.search(r"[\u4e00-\u9fff]", plain):
            out.append(plain.strip()[:80])
    return out


def main() -> int:
    app = QApplication.instance() or QApplication(sys.argv[:1])
    from hydrosync_gui import i18n
    from hydrosync_gui.main_window import MainWindow

    with tempfile.TemporaryDirectory() as tmp:
        if len(sys.argv) > 1:
            path = Path(sys.argv[1])
        else:
            sys.path.insert(0, str(DOCS))
            from make_screenshots import demo_project

            path = demo_project(Path(tmp))
        settings = QSettings(str(Path(tmp) / "settings.ini"), QSettings.Format.IniFormat)
        i18n.set_language("zh_CN", settings)
        window = MainWindow(settings=settings)
        window.resize(1366, 768)
        window.show()
        window.open_project(str(path))
        for index in range(window.tabs.count()):
            window.tabs.setCurrentIndex(index)
            window.tabs.ensure_current()
            deadline = time.monotonic() + 60
            while window.busy and time.monotonic() < deadline:
                app.processEvents()
                time.sleep(0.05)
            app.processEvents()
            entry = window.tabs.entry_at(index)
            name = entry.spec.id if entry is not None else f"tab{index}"
            image = window.grab()
            out = DOCS / f"zh_CN-{name}.png"
            image.save(str(out))
            left = english_left(window)
            print(f"{out.name}: {len(left)} English texts left" + (
                ": " + " | ".join(left[:12]) if left else ""))
        window.close_without_prompt()
        window.deleteLater()
        app.processEvents()
    return 0


if __name__ == "__main__":
    sys.exit(main())
