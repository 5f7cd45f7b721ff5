"""The workbench's language: Qt translators, the View → Language menu, live relabelling.

HydroSync's widgets are built with English text, much of it from the analyses' parameter
schemas and result tables. Rather than wrapping every ``setText`` in every panel, the
shell translates what the widgets show, at one place:

* :func:`set_language` installs ``QTranslator`` s — HydroSync's catalogue
  (``resources/i18n/hydrosync_<lang>.qm``, compiled from the ``.ts`` by
  ``pyside6-lrelease``; :func:`compiled_catalogue` builds it if the install did not),
  those a third-party plugin ships (``<package>/i18n/*_<lang>.ts``), and Qt's own
  ``qtbase_<lang>.qm`` (standard buttons and dialogs);
* :class:`Relabeler`, an application event filter active while the language is not
  English, puts each label, button, group box, tab, dock and window title, menu entry,
  tooltip, table header and plot axis/legend into the language just before it is painted
  (or its tooltip shown). It remembers the English source of each text, so a text the
  program changes later is translated afresh, and switching back restores English.

:func:`tr` is the lookup: the Qt catalogue first (``QCoreApplication.translate`` in the
``hydrosync`` context), then the patterns of :mod:`hydrosync_core.i18n` for text built
at run time (``Table {0}.``). The choice is kept in ``QSettings`` under
:data:`SETTINGS_KEY` (empty: follow the system locale) and applied live.
"""

from __future__ import annotations

import logging
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import pyqtgraph as pg
from PySide6.QtCore import (
    QCoreApplication,
    QEvent,
    QLibraryInfo,
    QLocale,
    QObject,
    QSettings,
    QTranslator,
)
from PySide6.QtGui import QAction, QActionGroup
from PySide6.QtWidgets import (
    QAbstractButton,
    QApplication,
    QComboBox,
    QDockWidget,
    QGroupBox,
    QLabel,
    QLineEdit,
    QMenu,
    QPlainTextEdit,
    QTabBar,
    QTableWidget,
    QTextEdit,
    QTreeWidget,
    QWidget,
)

from hydrosync_core import i18n as core

log = logging.getLogger(__name__)

SETTINGS_KEY = "ui/language"
CONTEXT = "hydrosync"

_state: dict = {"lang": core.DEFAULT, "translators": [], "relabeler": None}
_compiled: dict[Path, Path] = {}  # .ts → .qm compiled by this process


# --------------------------------------------------------------------------- lookup
def current() -> str:
    """The language the workbench shows (``en`` or ``zh_CN``)."""
    return _state["lang"]


def tr(text: str) -> str:
    """*text* in the workbench's language; unchanged where the catalogue has no entry."""
    lang = _state["lang"]
    if lang == core.DEFAULT or not isinstance(text, str) or not text.strip():
        return text
    out = QCoreApplication.translate(CONTEXT, text)
    return out if out != text else core.tr(text, lang)


# --------------------------------------------------------------------------- catalogues
def _lrelease() -> str | None:
    import PySide6

    exe = Path(PySide6.__file__).parent / "lrelease"
    return str(exe) if exe.is_file() else shutil.which("pyside6-lrelease")


def compiled_catalogue(ts: Path) -> Path | None:
    """The ``.qm`` of *ts*: next to it when up to date (``make install`` builds it), else
    compiled now into the temporary folder; None when ``lrelease`` is missing or fails."""
    if not ts.is_file():
        return None
    qm = ts.with_suffix(".qm")
    if qm.is_file() and qm.stat().st_mtime >= ts.stat().st_mtime:
        return qm
    tool = _lrelease()
    if tool is None:
        log.warning("pyside6-lrelease not found: %s is used through the Python catalogue", ts)
        return None
    if ts in _compiled:
        return _compiled[ts]
    handle, name = tempfile.mkstemp(prefix=f"hydrosync-{ts.stem}-", suffix=".qm")
    os.close(handle)  # a file of this process's own: no race with another HydroSync
    target = Path(name)
    result = subprocess.run([tool, "-silent", str(ts), "-qm", str(target)],
                            capture_output=True, text=True, check=False)
    if result.returncode != 0 or not target.is_file():
        log.warning("could not compile %s: %s", ts, result.stderr.strip()[:200])
        return None
    _compiled[ts] = target
    return target


def _translators(lang: str) -> list[QTranslator]:
    files: list[Path] = []
    ours = compiled_catalogue(core.catalogue_path(lang))
    if ours is not None:
        files.append(ours)
    files += [qm for ts in core.plugin_catalogues(lang)
              if (qm := compiled_catalogue(ts)) is not None]
    qt_dir = QLibraryInfo.path(QLibraryInfo.LibraryPath.TranslationsPath)
    files.append(Path(qt_dir) / f"qtbase_{lang}.qm")
    out = []
    for path in files:
        translator = QTranslator()
        if path.is_file() and translator.load(str(path)):
            out.append(translator)
    return out


# --------------------------------------------------------------------------- choosing
def chosen_language(settings: QSettings) -> str:
    """The language kept in *settings*, or the system locale's when none is chosen."""
    value = str(settings.value(SETTINGS_KEY, "") or "")
    try:
        return core.normalise(value or QLocale.system().name())
    except ValueError:
        return core.DEFAULT


def set_language(lang: str, settings: QSettings | None = None) -> str:
    """Show the workbench in *lang* from now on (live) and keep the choice in *settings*.

    Returns the language code applied. Open windows are relabelled at once.
    """
    lang = core.normalise(lang)
    app = QApplication.instance()
    for translator in _state["translators"]:
        app.removeTranslator(translator)
    _state["translators"] = _translators(lang) if lang != core.DEFAULT else []
    _state["lang"] = lang
    for translator in _state["translators"]:
        app.installTranslator(translator)
    if settings is not None:
        settings.setValue(SETTINGS_KEY, lang)
    if lang != core.DEFAULT and _state["relabeler"] is None:
        _state["relabeler"] = Relabeler(app)
        app.installEventFilter(_state["relabeler"])
    relabel_all()  # back to English: every remembered source is restored here
    if lang == core.DEFAULT and _state["relabeler"] is not None:
        app.removeEventFilter(_state["relabeler"])  # English needs no filter at all
        _state["relabeler"] = None
    return lang


def relabel_all() -> None:
    """Put every open window into the current language now."""
    relabeler = _state["relabeler"]
    if relabeler is None:
        return
    for window in QApplication.topLevelWidgets():
        relabeler.relabel_tree(window)


def add_language_menu(menu: QMenu, settings: QSettings) -> QMenu:
    """Add View → Language (English / 简体中文) to *menu*; the choice applies live."""
    sub = menu.addMenu("&Language")
    sub.setObjectName("language_menu")
    group = QActionGroup(sub)
    group.setExclusive(True)
    for code, name in core.LANGUAGES.items():
        action = QAction(name, sub)
        action.setCheckable(True)
        action.setChecked(code == current())
        action.setData(code)
        # The names stay in their own language: a reader finds their language either way.
        action.setProperty("i18n_fixed", True)
        action.triggered.connect(lambda _=False, c=code: set_language(c, settings))
        group.addAction(action)
        sub.addAction(action)
    sub.aboutToShow.connect(lambda: [a.setChecked(a.data() == current()) for a in sub.actions()])
    return sub


# --------------------------------------------------------------------------- relabelling
def _sync(obj: QObject, key: str, shown_now: str, setter) -> None:
    """Show *obj*'s text *key* in the current language, remembering its English source."""
    if not isinstance(shown_now, str) or obj.property("i18n_fixed"):
        return
    src_key, shown_key = f"i18n_src_{key}", f"i18n_shown_{key}"
    source = obj.property(src_key)
    if source is None or shown_now != obj.property(shown_key):
        source = shown_now  # new, or set again by the program since we last looked
        obj.setProperty(src_key, source)
    wanted = tr(source)
    obj.setProperty(shown_key, wanted)
    if wanted != shown_now:
        setter(wanted)


def _actions(widget: QWidget) -> None:
    for action in widget.actions():
        _sync(action, "text", action.text(), action.setText)
        _sync(action, "status", action.statusTip(), action.setStatusTip)


def _tabs(bar: QTabBar) -> None:
    for i in range(bar.count()):
        _sync(bar, f"tab{i}", bar.tabText(i), lambda t, i=i: bar.setTabText(i, t))
        _sync(bar, f"tabtip{i}", bar.tabToolTip(i), lambda t, i=i: bar.setTabToolTip(i, t))


def _item_headers(view) -> None:
    if isinstance(view, QTableWidget):
        for i in range(view.columnCount()):
            item = view.horizontalHeaderItem(i)
            if item is not None:
                _sync(view, f"head{i}", item.text(), item.setText)
    elif isinstance(view, QTreeWidget):
        item = view.headerItem()
        for i in range(view.columnCount()):
            _sync(view, f"head{i}", item.text(i), lambda t, i=i: item.setText(i, t))


def _combo_labels(box: QComboBox) -> None:
    """Choice labels ("least squares"); a choice shown as its key ("lsq", "auto") is a
    value the user may type or script, and stays."""
    for i in range(box.count()):
        data = box.itemData(i)
        source = box.property(f"i18n_src_item{i}") or box.itemText(i)
        if isinstance(data, str) and data != source:
            _sync(box, f"item{i}", box.itemText(i), lambda t, i=i: box.setItemText(i, t))


def _plot_texts(widget: QWidget) -> None:
    """Axis titles, plot titles and legend entries of a pyqtgraph view."""
    scene = widget.scene() if isinstance(widget, pg.GraphicsView) else None
    if scene is None:
        return
    for item in scene.items():
        if isinstance(item, pg.AxisItem) and item.labelText:
            _sync(item, "axis", item.labelText,
                  lambda t, a=item: a.setLabel(text=t, units=a.labelUnits, **a.labelStyle))
        elif isinstance(item, pg.LabelItem) and item.text:
            _sync(item, "label", item.text, item.setText)


def relabel_widget(widget: QWidget) -> None:
    """Put *widget*'s own texts into the current language (not its children)."""
    if widget.isWindow() or isinstance(widget, QDockWidget):
        _sync(widget, "title", widget.windowTitle(), widget.setWindowTitle)
    if isinstance(widget, QLabel | QAbstractButton):
        _sync(widget, "text", widget.text(), widget.setText)
    elif isinstance(widget, QGroupBox):
        _sync(widget, "text", widget.title(), widget.setTitle)
    elif isinstance(widget, QTabBar):
        _tabs(widget)
    elif isinstance(widget, QLineEdit | QTextEdit | QPlainTextEdit):
        _sync(widget, "placeholder", widget.placeholderText(), widget.setPlaceholderText)
    elif isinstance(widget, QTableWidget | QTreeWidget):
        _item_headers(widget)
    elif isinstance(widget, QComboBox):
        _combo_labels(widget)
    if isinstance(widget, QMenu):
        _sync(widget.menuAction(), "text", widget.title(), widget.setTitle)
    if widget.actions():
        _actions(widget)
    if isinstance(widget, pg.GraphicsView):
        _plot_texts(widget)


class Relabeler(QObject):
    """Application event filter: texts are put into the language before they are seen."""

    _PAINTED = (QEvent.Type.Paint, QEvent.Type.Show, QEvent.Type.Polish)

    def relabel_tree(self, root: QWidget) -> None:
        """*root* and every widget under it."""
        for widget in [root, *root.findChildren(QWidget)]:
            relabel_widget(widget)

    def eventFilter(self, obj, event) -> bool:  # noqa: N802 (Qt API)
        kind = event.type()
        if kind in self._PAINTED and isinstance(obj, QWidget):
            if kind == QEvent.Type.Show and obj.isWindow():
                self.relabel_tree(obj)
            else:
                relabel_widget(obj)
                parent = obj.parentWidget()
                if isinstance(parent, pg.GraphicsView):
                    _plot_texts(parent)  # the plot's viewport is painted, not the plot
        elif kind == QEvent.Type.ToolTip and isinstance(obj, QWidget) and obj.toolTip():
            _sync(obj, "tooltip", obj.toolTip(), obj.setToolTip)
        return False


def apply_saved_language(settings: QSettings) -> str:
    """At start-up: the saved choice or the system locale's language (English otherwise)."""
    lang = chosen_language(settings)
    if lang != core.DEFAULT:
        set_language(lang)
    return lang


__all__ = ["SETTINGS_KEY", "add_language_menu", "apply_saved_language",
           "chosen_language", "compiled_catalogue", "current", "relabel_all", "set_language",
           "tr"]
