"""Merge ``source<TAB>translation`` lines into a Qt Linguist ``.ts`` catalogue.

For translators who prefer a spreadsheet to Qt Linguist::

    .venv/bin/python resources/i18n/merge_tsv.py new.tsv resources/i18n/hydrosync_zh_CN.ts

``\\n`` in a cell is a line break. A source with ``{0}``, ``{1}``… is a pattern for text
built at run time (see :mod:`hydrosync_core.i18n`) and goes to the ``hydrosync-patterns``
context, which Qt's own lookup never consults; ``context|source`` puts an entry into
that context (one English word, two meanings). Existing entries are replaced; the file is
written sorted, so diffs stay small.
"""

from __future__ import annotations

import re
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

EXACT, PATTERNS = "hydrosync", "hydrosync-patterns"


def read_ts(path: Path) -> dict[str, dict[str, str]]:
    """{context: {source: translation}} of an existing ``.ts`` (empty if absent)."""
    out: dict[str, dict[str, str]] = {EXACT: {}, PATTERNS: {}}
    if not path.is_file():
        return out
    for context in ET.parse(path).getroot().iter("context"):
        name = context.findtext("name") or EXACT
        for message in context.iter("message"):
            out.setdefault(name, {})[message.findtext("source") or ""] = (
                message.findtext("translation") or "")
    return out


def write_ts(path: Path, entries: dict[str, dict[str, str]], lang: str) -> None:
    root = ET.Element("TS", version="2.1", language=lang, sourcelanguage="en")
    for name in sorted(entries):
        context = ET.SubElement(root, "context")
        ET.SubElement(context, "name").text = name
        for source in sorted(entries[name]):
            message = ET.SubElement(context, "message")
            ET.SubElement(message, "source").text = source
            ET.SubElement(message, "translation").text = entries[name][source]
    ET.indent(root, space="    ")
    text = ET.tostring(root, encoding="unicode")
    tmp = path.with_suffix(".tmp")
    tmp.write_text('<?xml version="1.0" encoding="utf-8"?>\n<!DOCTYPE TS>\n' + text + "\n",
                   encoding="utf-8")
    tmp.replace(path)


def merge(tsv: Path, ts: Path) -> int:
    """Merge *tsv* into *ts*; return the number of entries merged."""
    entries = read_ts(ts)
    count = 0
    for number, line in enumerate(tsv.read_text(encoding="utf-8").splitlines(), 1):
        if not line.strip() or line.startswith("#"):
            continue
        if line.count("\t") != 1:
            raise SystemExit(f"{tsv}:{number}: expected 'source<TAB>translation'")
        source, target = (cell.replace("\\n", "\n") for cell in line.split("\t"))
        context = PATTERNS if re.search(r"\{\d+\}", source) else EXACT
        if "|" in source.split(" ")[0] and source.split("|", 1)[0].isidentifier():
            context, source = source.split("|", 1)  # "signoff|Name": a context's entry
        entries.setdefault(context, {})[source] = target
        count += 1
    lang = re.sub(r"^hydrosync_", "", ts.stem)
    write_ts(ts, entries, lang)
    return count


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    print(f"{merge(Path(sys.argv[1]), Path(sys.argv[2]))} entries merged into {sys.argv[2]}")
