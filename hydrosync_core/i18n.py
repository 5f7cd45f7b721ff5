"""Translations of user-visible text, keyed by the English source text (no Qt).

HydroSync's strings are written in English in the code. A translation catalogue is a Qt
Linguist ``.ts`` file under ``resources/i18n/`` (``hydrosync_<lang>.ts``), plus any an
installed plugin ships (``<package>/i18n/*_<lang>.ts``): the GUI loads their compiled
``.qm`` through ``QTranslator``; the PDF report, which must run without Qt, reads the same
``.ts`` here. One catalogue, two readers.

Entries:

* exact (context ``hydrosync``): ``<source>Pool Calibration</source>`` → ``水池检校``;
* patterns (context ``hydrosync-patterns``), for text assembled at run time: ``{0}``,
  ``{1}``… stand for any part of one line (``Table {0}.`` → ``表 {0}``). What a
  placeholder captured is translated in turn (a module name inside a sentence); numbers
  pass through unchanged;
* other contexts hold a second meaning of one English word, asked for by name
  (``tr("Name", context="signoff")`` → ``姓名``, a person's, not a file's ``名称``).

A text of several lines (``\\n`` or ``<br>``) without an entry of its own is translated
line by line. A trailing unit in brackets (``Roll [°]``) or a colon is kept and the label
in front of it translated. A text with no entry is returned as it is, so an untranslated
string shows in English rather than not at all.

Example
-------
>>> with using("zh_CN"):
...     tr("Pool Calibration")
'水池检校'
"""

from __future__ import annotations

import contextlib
import functools
import re
import xml.etree.ElementTree as ET
from collections.abc import Iterator
from contextvars import ContextVar
from dataclasses import dataclass, field
from pathlib import Path

#: Language codes HydroSync offers, with their names in their own language.
LANGUAGES: dict[str, str] = {"en": "English", "zh_CN": "简体中文"}
DEFAULT = "en"
#: The ``.ts`` context of HydroSync's texts (the one Qt's ``translate`` is asked in).
EXACT_CONTEXT = "hydrosync"
CATALOGUE_DIR = Path(__file__).resolve().parents[1] / "resources" / "i18n"

_language: ContextVar[str] = ContextVar("hydrosync_language", default=DEFAULT)
_collector: ContextVar[set | None] = ContextVar("hydrosync_i18n_collector", default=None)
_PLACEHOLDER = re.compile(r"\{(\d+)\}")
_UNIT_TAIL = re.compile(r"^(?P<head>.*\S)(?P<tail> \[[^\[\]]*\]|:)$", re.S)
_ONE_LINE = r"(?:(?!<br\s*/?>)[^\n])+?"
_LINE_BREAK = re.compile(r"(\n|<br\s*/?>)")
_NUMBERISH = re.compile(r"^[\s\d.,+\-−±%eE:/]*$")


def catalogue_path(lang: str) -> Path:
    """The ``.ts`` source of *lang* (it may not exist)."""
    return CATALOGUE_DIR / f"hydrosync_{lang}.ts"


def normalise(lang: str | None) -> str:
    """A supported language code from *lang* (``zh``, ``zh-CN``, ``zh_CN.UTF-8`` → ``zh_CN``).

    Raises
    ------
    ValueError
        *lang* names a language HydroSync has no catalogue for.
    """
    if not lang:
        return DEFAULT
    code = lang.split(".")[0].replace("-", "_")
    if code in LANGUAGES:
        return code
    if code.lower().startswith("zh") and "TW" not in code.upper() and "HK" not in code.upper():
        return "zh_CN"
    if code.lower().startswith("en") or code in ("C", "POSIX"):
        return DEFAULT
    raise ValueError(f"language '{lang}' is not available (choose one of "
                     f"{', '.join(LANGUAGES)})")


@dataclass
class Catalogue:
    """The entries of one ``.ts`` file: exact texts and run-time patterns."""

    exact: dict[str, str] = field(default_factory=dict)
    patterns: list[tuple[re.Pattern, str]] = field(default_factory=list)
    #: Entries of other ``.ts`` contexts: one English word, two meanings (``signoff``:
    #: "Name" of a person, not of a file).
    by_context: dict[str, dict[str, str]] = field(default_factory=dict)

    @classmethod
    def read(cls, path: Path) -> Catalogue:
        """Parse a Qt Linguist ``.ts`` file; unfinished or empty translations are skipped."""
        cat = cls()
        if not path.is_file():
            return cat
        root = ET.parse(path).getroot()
        pattern_entries = []
        for context in root.iter("context"):
            name = context.findtext("name") or ""
            for message in context.iter("message"):
                cat._add(name, message, pattern_entries)
        # Longest literal first: the most specific pattern wins.
        pattern_entries.sort(key=lambda e: -len(_PLACEHOLDER.sub("", e[0])))
        cat.patterns = [(_compile(src), dst) for src, dst in pattern_entries]
        return cat

    def _add(self, context: str, message: ET.Element, pattern_entries: list) -> None:
        source = message.findtext("source") or ""
        node = message.find("translation")
        if node is None or not (node.text or "") or node.get("type") in (
                "unfinished", "obsolete", "vanished"):
            return
        if _PLACEHOLDER.search(source):
            pattern_entries.append((source, node.text))
        elif context in (EXACT_CONTEXT, ""):
            self.exact[source] = node.text
        else:
            self.by_context.setdefault(context, {})[source] = node.text

    def sources(self) -> list[str]:
        return list(self.exact) + [p.pattern for p, _ in self.patterns]


def _compile(source: str) -> re.Pattern:
    parts = _PLACEHOLDER.split(source)
    regex = ""
    for i, part in enumerate(parts):
        # A placeholder stays within one line: a status of several lines is matched
        # line by line, never by one pattern swallowing the lines before.
        regex += re.escape(part) if i % 2 == 0 else f"(?P<p{part}>{_ONE_LINE})"
    return re.compile(f"^{regex}$")


def plugin_catalogues(lang: str) -> list[Path]:
    """``<plugin package>/i18n/*_<lang>.ts`` of every installed plugin (third parties ship
    their translations beside their code; see docs/plugins.md)."""
    import importlib.util

    from hydrosync_core.plugins.registry import _entry_points
    from hydrosync_core.plugins.spec import ENTRY_POINT_GROUP

    found: list[Path] = []
    for ep in _entry_points(ENTRY_POINT_GROUP):
        module = ep.value.split(":")[0]
        try:
            origin = importlib.util.find_spec(module).origin
        except (ImportError, AttributeError, ValueError):
            continue  # a broken plugin: its load error is reported by the registry
        if origin:
            found += sorted((Path(origin).parent / "i18n").glob(f"*_{lang}.ts"))
    return found


@functools.lru_cache(maxsize=8)
def catalogue(lang: str) -> Catalogue:
    """The catalogue of *lang* (empty for English): HydroSync's, then the plugins' (which
    may add entries, not change HydroSync's), read once."""
    if lang == DEFAULT:
        return Catalogue()
    cat = Catalogue.read(catalogue_path(lang))
    for path in plugin_catalogues(lang):
        extra = Catalogue.read(path)
        cat.exact = {**extra.exact, **cat.exact}
        cat.patterns += extra.patterns
        for name, entries in extra.by_context.items():
            cat.by_context[name] = {**entries, **cat.by_context.get(name, {})}
    return cat


def language() -> str:
    """The language of text produced in the current context (``en`` unless set)."""
    return _language.get()


@contextlib.contextmanager
def using(lang: str | None) -> Iterator[str]:
    """Translate text produced inside the block into *lang* (thread/context local)."""
    token = _language.set(normalise(lang))
    try:
        yield _language.get()
    finally:
        _language.reset(token)


def tr(text: str, lang: str | None = None, context: str | None = None) -> str:
    """*text* in *lang* (default: the current language); unchanged where not translated.

    *context* names a ``.ts`` context whose entry, if any, wins (a word with two meanings).
    """
    lang = lang or _language.get()
    if lang == DEFAULT or not isinstance(text, str) or not text.strip():
        return text
    collector = _collector.get()
    if collector is not None:
        collector.add(text)
    if context:
        found = catalogue(lang).by_context.get(context, {}).get(text)
        if found is not None:
            return found
    return _lookup(text, lang, 0)


@functools.lru_cache(maxsize=20000)
def _lookup(text: str, lang: str, depth: int) -> str:
    cat = catalogue(lang)
    found = cat.exact.get(text)
    if found is not None:
        return found
    stripped = text.strip()
    if stripped != text and stripped in cat.exact:
        return text.replace(stripped, cat.exact[stripped])
    for pattern, target in cat.patterns:
        match = pattern.match(text)
        if match:
            values = {k[1:]: v for k, v in match.groupdict().items()}
            if depth < 3:
                values = {k: v if _NUMBERISH.match(v) else _lookup(v, lang, depth + 1)
                          for k, v in values.items()}
            return _fill(target, values)
    tail = _UNIT_TAIL.match(text)
    if tail and tail.group("head") in cat.exact:
        return cat.exact[tail.group("head")] + tail.group("tail")
    parts = _LINE_BREAK.split(text)
    if len(parts) > 1 and depth < 3:  # a status of several lines: line by line
        return "".join(part if i % 2 else _lookup(part, lang, depth + 1)
                       for i, part in enumerate(parts))
    return text


def _fill(target: str, values: dict[str, str]) -> str:
    return _PLACEHOLDER.sub(lambda m: values.get(m.group(1), m.group(0)), target)


def is_translated(text: str, lang: str) -> bool:
    """Whether *text* has an entry (exact, pattern, or label + unit) in *lang*; an entry
    that keeps the English (a name such as ``Mahony Kp``) counts."""
    lang = normalise(lang)
    return text.strip() in catalogue(lang).exact or _lookup(text, lang, 0) != text


@contextlib.contextmanager
def collecting() -> Iterator[set]:
    """Collect every text passed to :func:`tr` inside the block (to find missing entries)."""
    found: set = set()
    token = _collector.set(found)
    try:
        yield found
    finally:
        _collector.reset(token)


def reload() -> None:
    """Forget the catalogues read so far (after the ``.ts`` files changed)."""
    catalogue.cache_clear()
    _lookup.cache_clear()
