"""List the user-visible texts a catalogue does not translate yet.

HydroSync's texts are plain English strings (many from the analyses' parameter schemas),
not ``tr()`` calls, so ``pyside6-lupdate`` finds few of them. This script finds them the
way a user meets them:

* every parameter schema's labels, help texts, "not set" notes and group names;
* every text the PDF report passes to :func:`hydrosync_core.i18n.tr`, on a project;
* every text the workbench shows (labels, buttons, tabs, menus, tooltips, table headers,
  plot axes) with each plugin panel opened on that project (offscreen).

Usage::

    QT_QPA_PLATFORM=offscreen .venv/bin/python resources/i18n/harvest.py demo.h5 \\
        [--lang zh_CN] [--out missing.tsv]

Writes one untranslated text per line (newlines as ``\\n``); add their translations to
``resources/i18n/hydrosync_<lang>.ts`` (Qt Linguist: ``pyside6-linguist``) and run
``pyside6-lrelease`` on it (``make install`` does).
"""

from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile
from pathlib import Path


def schema_texts() -> set[str]:
    """Labels, help, "not set" notes and groups of every plugin's parameter schema."""
    from hydrosync_core.plugins import plugin_specs

    out: set[str] = set()
    for spec in plugin_specs():
        out.add(spec.name)
        for info in spec.load_params().schema():
            out.update(t for t in (info.meta.label, info.meta.help, info.meta.none_label,
                                   info.meta.group) if t)
    return out


def report_texts(project_path: Path, lang: str) -> set[str]:
    """Texts the PDF report of *project_path* puts through the catalogue."""
    from hydrosync_core import i18n
    from hydrosync_core.project import Project
    from hydrosync_core.report import build_report

    with Project.open(project_path, readonly=True) as project, i18n.collecting() as found, \
            tempfile.TemporaryDirectory() as tmp:
        build_report(project, Path(tmp) / "r.pdf", lang=lang)
    return found


def gui_texts(project_path: Path, lang: str) -> set[str]:
    """Texts the workbench shows with every plugin panel open on *project_path*."""
    from PySide6.QtCore import QSettings
    from PySide6.QtWidgets import QApplication, QWidget

    from hydrosync_core import i18n
    from hydrosync_gui import i18n as gui_i18n

    app = QApplication.instance() or QApplication([])
    from hydrosync_gui.main_window import MainWindow

    settings = QSettings(str(Path(tempfile.mkdtemp()) / "s.ini"), QSettings.Format.IniFormat)
    with i18n.collecting() as found:
        window = MainWindow(settings=settings)
        window.resize(1366, 768)
        window.open_project(str(project_path))
        window.show()
        gui_i18n.set_language(lang)
        for index in range(window.tabs.count()):
            window.tabs.setCurrentIndex(index)
            window.tabs.ensure_current()
            app.processEvents()
            window.grab()
            for widget in window.findChildren(QWidget):
                if widget.toolTip():
                    gui_i18n.tr(widget.toolTip())
            gui_i18n.relabel_all()
        window.close_without_prompt()
    return found


def _wants_translation(text: str) -> bool:
    """Text with words in it: not a number, name, identifier or already translated text."""
    plain = re.sub(r"<[^>]+>", "", text).strip()
    if re.search(r"[\u4e00-\u9fff]", plain) or not re.search(r"[A-Za-z]{3}", plain):
        return False
    # identifiers, line and antenna names, paths, the version
    return not re.fullmatch(r"[\w.\-/ ,]*_[\w.\-/ ,]*|[A-Z]\d+|/[\w/.\-]+|HydroSync [\d.]+",
                            plain)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("project", type=Path)
    parser.add_argument("--lang", default="zh_CN")
    parser.add_argument("--out", type=Path)
    parser.add_argument("--no-gui", action="store_true")
    args = parser.parse_args(argv)
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from hydrosync_core import i18n

    texts = schema_texts() | report_texts(args.project, args.lang)
    if not args.no_gui:
        texts |= gui_texts(args.project, args.lang)
    missing = sorted(t for t in texts if _wants_translation(t)
                     and not i18n.is_translated(t, args.lang))
    lines = "\n".join(t.replace("\n", "\\n") for t in missing) + "\n"
    if args.out:
        args.out.write_text(lines, encoding="utf-8")
    else:
        sys.stdout.write(lines)
    print(f"{len(missing)} of {len(texts)} texts untranslated", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
