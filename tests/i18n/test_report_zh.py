"""``hydrosync report --lang zh_CN``: Chinese text, embedded fonts only, the same numbers.

Uses the session's demo project (``hydrosync demo``, every module run) and compares with
the English report the demo wrote from the same project (written afresh if absent).
"""

from __future__ import annotations

import collections
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(shutil.which("pdffonts") is None
                                or shutil.which("pdftotext") is None,
                                reason="poppler-utils (pdffonts, pdftotext) not installed")


def _cli(*args: str) -> subprocess.CompletedProcess:
    script = Path(sys.executable).with_name("hydrosync")
    command = [str(script)] if script.exists() else [sys.executable, "-m", "hydrosync_core.cli"]
    return subprocess.run([*command, *args], capture_output=True, text=True, timeout=600)


def _fonts(pdf: Path) -> list[list[str]]:
    lines = subprocess.run(["pdffonts", str(pdf)], capture_output=True, text=True,
                           check=True).stdout.splitlines()[2:]
    return [line.split() for line in lines if line.strip()]


def _text(pdf: Path) -> str:
    return subprocess.run(["pdftotext", str(pdf), "-"], capture_output=True, text=True,
                          check=True).stdout


def _decimals(text: str) -> collections.Counter:
    """Decimal numbers of *text*, without the version in each page's footer (the two
    languages need not break into the same number of pages)."""
    text = re.sub(r"HydroSync \d+(\.\d+)+", "", text)
    return collections.Counter(re.findall(r"[-+−]?\d+\.\d+", text))


@pytest.fixture(scope="module")
def reports(hydrosync_demo, tmp_path_factory):
    from hydrosync_core.errors import InputError
    from hydrosync_core.report.styles import cjk_font_file

    try:
        cjk_font_file()
    except InputError as exc:
        pytest.skip(f"no CJK font installed: {exc.one_line()}")
    project = hydrosync_demo / "demo.h5"
    if not project.exists():
        pytest.skip("the demo project was not built")
    out = tmp_path_factory.mktemp("zh-report")
    zh, en = out / "zh.pdf", out / "en.pdf"
    done = _cli("report", str(project), "--lang", "zh_CN", "-o", str(zh))
    assert done.returncode == 0, done.stderr
    if (hydrosync_demo / "demo-report.pdf").exists():  # the demo's own English report
        return zh, hydrosync_demo / "demo-report.pdf"
    done = _cli("report", str(project), "-o", str(en))
    assert done.returncode == 0, done.stderr
    return zh, en


def test_zh_report_embeds_every_font(reports):
    zh, _ = reports
    fonts = _fonts(zh)
    assert fonts
    # columns: name type encoding emb sub uni object-id generation
    not_embedded = [f[0] for f in fonts if f[-5] != "yes"]
    assert not not_embedded, f"fonts not embedded: {not_embedded}"
    assert any("WenQuanYi" in f[0] for f in fonts)


def test_zh_report_text_is_chinese_with_the_glossary_terms(reports):
    zh, _ = reports
    text = _text(zh)
    for term in ("延迟", "横摇", "纵摇", "杆臂", "升沉", "测线", "安装偏角", "水池检校",
                 "传感器检校报告", "结果汇总"):
        assert term in text, term
    assert "Summary of results" not in text and "Sensor calibration report" not in text


def test_zh_report_numbers_equal_the_english_report(reports):
    zh, en = reports
    zh_numbers, en_numbers = _decimals(_text(zh)), _decimals(_text(en))
    assert sum(en_numbers.values()) > 300  # the demo report is full of results
    assert zh_numbers == en_numbers


def test_english_report_stays_english(reports):
    _, en = reports
    text = _text(en)
    assert "Summary of results" in text
    assert not re.search(r"[\u4e00-\u9fff]", text)
    assert not any("WenQuanYi" in f[0] for f in _fonts(en))


def test_missing_cjk_font_is_one_clear_line(tmp_path, monkeypatch):
    from hydrosync_core.errors import InputError
    from hydrosync_core.project import Project
    from hydrosync_core.report import build_report

    monkeypatch.setenv("HYDROSYNC_CJK_FONT", str(tmp_path / "no-such-font.ttf"))
    out = tmp_path / "r.pdf"
    with pytest.raises(InputError, match="fonts-wqy-zenhei") as err:
        build_report(Project.new("p"), out, lang="zh_CN")
    assert "\n" not in err.value.one_line()
    assert not out.exists()


def test_unknown_language_is_refused(tmp_path):
    done = _cli("report", str(tmp_path / "p.h5"), "--lang", "fr")
    assert done.returncode == 2 and "invalid choice" in done.stderr
