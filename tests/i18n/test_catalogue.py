"""The zh_CN catalogue: every entry is live, well formed and follows the glossary.

An entry whose English source no longer occurs in the code is dead weight that hides a
missing translation (the text was reworded, the new wording shows in English); the check
reads every string literal and f-string fragment of the code with :mod:`ast`, so implicit
concatenation across lines is seen as the one string it is.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

from hydrosync_core import i18n

ROOT = Path(__file__).resolve().parents[2]
CODE = ("hydrosync_core", "hydrosync_gui", "plugins")
PLACEHOLDER = re.compile(r"\{\d+\}")
CJK = re.compile(r"[\u4e00-\u9fff]")


def _code_strings() -> list[str]:
    """String literals of HydroSync and of the pyqtgraph widgets it shows (whose plot
    context menus are translated too)."""
    import pyqtgraph

    pg_root = Path(pyqtgraph.__file__).parent
    folders = [ROOT / top for top in CODE] + [pg_root / "graphicsItems"]
    out: list[str] = []
    for folder in folders:
        for path in folder.rglob("*.py"):
            if "tests" in path.parts:
                continue
            for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
                if isinstance(node, ast.Constant) and isinstance(node.value, str):
                    out.append(node.value)
    return out


@pytest.fixture(scope="module")
def catalogue() -> i18n.Catalogue:
    i18n.reload()
    cat = i18n.catalogue("zh_CN")
    assert len(cat.exact) > 100, "the zh_CN catalogue did not load"
    return cat


def _pattern_sources() -> dict[str, str]:
    import xml.etree.ElementTree as ET

    root = ET.parse(i18n.catalogue_path("zh_CN")).getroot()
    return {m.findtext("source"): m.findtext("translation") for m in root.iter("message")
            if PLACEHOLDER.search(m.findtext("source") or "")}


def _assembled(source: str, fragments: list[str]) -> bool:
    """Whether *source* is made of code literals (f-string pieces, names joined in a loop)
    and run-time values (numbers, units, punctuation, one- or two-letter symbols)."""
    source = source.lower()  # a literal may be capitalised at run time
    covered = [False] * len(source)
    for fragment in fragments:
        start = source.find(fragment)
        while start >= 0:
            covered[start:start + len(fragment)] = [True] * len(fragment)
            start = source.find(fragment, start + 1)
    rest = "".join(" " if done else ch for ch, done in zip(source, covered, strict=True))
    return all(len(word) <= 2 for word in re.findall(r"[A-Za-z]+", rest))


def test_no_stale_entries(catalogue):
    """Every source is a literal of the code, or is assembled from literals and values."""
    strings = _code_strings()
    # A label is looked up without its unit: "H RMS [mm]" → "H RMS".
    # and the part before a colon ("an underside: no scanner sees it".split(":")[0]).
    literal = (set(strings) | {s.strip() for s in strings}
               | {re.sub(r" \[[^\[\]]*\]$", "", s) for s in strings}
               | {s.split(":")[0] for s in strings})
    fragments = sorted({s.lower() for s in literal if len(s.strip()) >= 3}, key=len,
                       reverse=True)
    stale = [source for source in [*catalogue.exact, *_pattern_sources()]
             if source not in literal
             and not _assembled(PLACEHOLDER.sub(" ", source), fragments)]
    assert not stale, f"{len(stale)} catalogue entries no longer in the code: {stale[:10]}"


def test_entries_are_chinese_and_keep_their_placeholders(catalogue):
    for source, target in {**catalogue.exact, **_pattern_sources()}.items():
        assert target.strip(), source
        assert sorted(PLACEHOLDER.findall(source)) == sorted(PLACEHOLDER.findall(target)), source
        words = re.sub(r"<[^>]+>", "", source)
        # target == source marks a name that stays as it is (Mahony Kp, lsq, R_max)
        if re.search(r"[a-z]{3}", words) and target != source:
            assert CJK.search(target), f"{source!r} → {target!r} has no Chinese"


# English term (as a word) → the glossary's Chinese (docs/glossary.md)
GLOSSARY = {
    r"\blever[ -]arm": "杆臂",
    r"\blatency\b": "延迟",
    r"\bheave\b": "升沉",
    r"\broll\b": "横摇",
    r"\bpitch\b": "纵摇",
    r"\bboresight\b": "安装偏角",
    r"\bsurvey lines?\b": "测线",
    r"\bmultibeam\b": "多波束",
    r"\bgradient descent\b": "梯度下降",
    r"\bzero[- ]velocity\b": "零速",
}


@pytest.mark.parametrize("term", sorted(GLOSSARY))
def test_translations_follow_the_glossary(catalogue, term):
    chinese = GLOSSARY[term]
    off = [(s, t) for s, t in {**catalogue.exact, **_pattern_sources()}.items()
           if re.search(term, s, re.I) and chinese not in t]
    assert not off, f"'{term}' not rendered as {chinese}: {off[:5]}"


def test_lookup_exact_pattern_unit_and_numbers():
    with i18n.using("zh_CN"):
        assert i18n.tr("Lever arm (antenna − motion sensor)").startswith("杆臂")
        assert i18n.tr("roll [°]") == "横摇 [°]"
        assert i18n.tr("page 3 of 12") == "第 3 页,共 12 页"
        # A placeholder's text is translated in turn; numbers pass through.
        assert i18n.tr("not run: inputs missing (/raw/gnss)") == "未运行:缺少输入(/raw/gnss)"
        assert i18n.tr("12.345 ± 0.002") == "12.345 ± 0.002"
        assert i18n.tr("no such text in any catalogue") == "no such text in any catalogue"
    assert i18n.tr("Lever arm (antenna − motion sensor)") == \
        "Lever arm (antenna − motion sensor)"  # English: the source itself


def test_language_names():
    assert i18n.normalise("zh_CN.UTF-8") == "zh_CN"
    assert i18n.normalise("zh-CN") == "zh_CN"
    assert i18n.normalise("C") == "en"
    with pytest.raises(ValueError, match="not available"):
        i18n.normalise("fr_FR")


def test_a_plugin_ships_its_own_catalogue(tmp_path, monkeypatch):
    """A third party's ``<package>/i18n/*_zh_CN.ts`` is read beside HydroSync's."""
    import sys
    from types import SimpleNamespace

    from hydrosync_core.plugins import registry

    package = tmp_path / "heave_stats_plugin"
    (package / "i18n").mkdir(parents=True)
    (package / "__init__.py").write_text("SPEC = None\n")
    (package / "i18n" / "heave_stats_zh_CN.ts").write_text(
        '<?xml version="1.0" encoding="utf-8"?><TS version="2.1" language="zh_CN">'
        "<context><name>hydrosync</name>"
        "<message><source>Heave statistics</source><translation>升沉统计</translation>"
        "</message><message><source>Pool Calibration</source><translation>不应覆盖</translation>"
        "</message></context><context><name>hydrosync-patterns</name>"
        "<message><source>{0} heave samples</source><translation>{0} 个升沉样本"
        "</translation></message></context></TS>", encoding="utf-8")
    monkeypatch.syspath_prepend(str(tmp_path))
    fake = SimpleNamespace(value="heave_stats_plugin:SPEC", name="heave_stats")
    monkeypatch.setattr(registry, "_entry_points", lambda group: (fake,))
    i18n.reload()
    try:
        with i18n.using("zh_CN"):
            assert i18n.tr("Heave statistics") == "升沉统计"
            assert i18n.tr("1200 heave samples") == "1200 个升沉样本"
            assert i18n.tr("Pool Calibration") == "水池检校"  # HydroSync's entry wins
    finally:
        monkeypatch.undo()
        sys.modules.pop("heave_stats_plugin", None)
        i18n.reload()


def test_no_pattern_matches_almost_anything(catalogue):
    """A pattern with placeholders at both ends needs a long literal in between: '{0} with
    {1}' would have turned any sentence containing 'with' into the pairing rule."""
    loose = [source for source in _pattern_sources()
             if source.startswith("{") and source.endswith("}")
             and len(PLACEHOLDER.sub("", source).strip()) < 12]
    assert not loose, loose
