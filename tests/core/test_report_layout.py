"""PDF layout of the report framework: column widths that fit, sections that follow on
without half-empty pages, and the demo report checked page by page (#26)."""

from __future__ import annotations

import pytest
from reportlab.lib.pagesizes import A4
from reportlab.platypus import LongTable, Paragraph

from hydrosync_core.report.colwidths import cell_need, fit_widths, shrink_factor
from hydrosync_core.report.context import ReportContext
from hydrosync_core.report.styles import FONT, PAGE_MARGIN
from hydrosync_core.report.template import PageLayout

WIDTH = A4[0] - 2 * PAGE_MARGIN


def _table(flowables) -> LongTable:
    return next(f for f in flowables if isinstance(f, LongTable))


def test_fit_widths_gives_short_columns_their_need_from_the_slack():
    widths = fit_widths([100, 20, 80], [30, 50, 30])
    assert widths == pytest.approx([100 - 30 * 70 / 120, 50, 80 - 30 * 50 / 120])
    assert sum(widths) == pytest.approx(200)
    assert fit_widths([100, 100], [50, 60]) == [100, 100]  # all fit: unchanged
    assert fit_widths([50, 50], [150, 50]) == pytest.approx([75, 25])  # too much: shared
    assert shrink_factor(100, [60, 60]) == pytest.approx(100 / 120)
    assert shrink_factor(100, [200, 200]) == 0.75 and shrink_factor(100, [10]) == 1.0


def test_header_words_and_plain_cells_fit_their_columns():
    """"Patent method" broke into "Patent metho/d" in a 7 % column and
    "N1_up_perpendicular" ran into the next column (#26)."""
    ctx = ReportContext(width=WIDTH)
    rows = [["N1_up_perpendicular", "-44.193", "1.0"], ["wall", "0.605", "2.0"]]
    table = _table(ctx.table(["Face", "Patent method", "x"], rows,
                             col_widths=[0.07, 0.07, 0.86], font_size=8.5))
    widths = table._colWidths
    assert sum(widths) == pytest.approx(WIDTH)
    pad = 2 * 4
    assert widths[0] >= cell_need("N1_up_perpendicular", FONT, 8.5) + pad
    head = Paragraph("Patent method", ctx.styles["CellBold"])
    assert widths[1] >= head.minWidth() + pad
    # reportlab breaks a word only when it is wider than the cell: none is now
    for col, cell in enumerate(table._cellvalues[0]):
        assert cell.minWidth() <= widths[col] - pad, col


def test_a_table_too_wide_for_the_page_gets_a_smaller_font_not_overflow():
    ctx = ReportContext(width=300)
    rows = [["x" * 30] * 4]
    flow = ctx.table(["a", "b", "c", "d"], rows, font_size=8.5)
    table = _table(flow)
    assert sum(table._colWidths) == pytest.approx(300)
    # 4 × 30 "x" do not fit 300 pt at 8.5 pt: the font is reduced (not below 3/4)
    size = table._cellStyles[1][0].fontsize
    assert 8.5 * 0.75 - 0.25 <= size < 8.5


def test_sparse_pages_are_those_under_the_threshold_that_end_no_section():
    layout = PageLayout(fill=[0.6, 0.95, 0.3, 0.8, 0.2, 0.9, 0.1],
                        section_starts={1, 2, 4, 7})
    # page 3 ends a section (4 starts one), page 7 is the last: only page 5 is sparse
    assert layout.sparse_pages() == [5]


def test_demo_report_has_no_nearly_empty_page(hydrosync_demo, tmp_path):
    """The demo's PDF, laid out again from its project: every page at least 40 % full
    except one that ends a section, and fewer pages than the 22 a page break before every
    section gave."""
    from hydrosync_core.demo import DEMO_PROJECT
    from hydrosync_core.project import Project
    from hydrosync_core.report import build_report

    project_file = hydrosync_demo / DEMO_PROJECT
    if not project_file.exists():
        pytest.skip(f"the demo did not run: {(hydrosync_demo / 'stderr.txt').read_text()[-300:]}")
    layout = PageLayout()
    with Project.open(project_file, readonly=True) as project:
        build_report(project, tmp_path / "demo.pdf", layout=layout)
    assert layout.fill and layout.sparse_pages() == [], layout.fill
    assert len(layout.fill) <= 21


def test_envelope_is_each_slices_range_and_median():
    """A long noisy angle: the band spans each slice's min..max and the line is its median
    (an epoch-by-epoch line printed as a solid block, #26); a short series stays a line."""
    import numpy as np

    from hydrosync_core.report.charts import Chart

    rng = np.random.default_rng(6)
    t = np.arange(6000) * 0.1
    y = np.sin(t / 60) + rng.normal(0, 0.4, t.size)
    chart = Chart(width=200, height=150).envelope(t, y, label="pitch", bins=60)
    band, line = chart.series
    assert (band.kind, line.kind, line.label) == ("band", "line", "pitch")
    slices = np.array_split(y, 60)  # 100 samples each, equal slices of t
    np.testing.assert_allclose(band.y, [s.min() for s in slices])
    np.testing.assert_allclose(band.y2, [s.max() for s in slices])
    np.testing.assert_allclose(line.y, [np.sort(s)[49] for s in slices])
    assert chart.drawing() is not None
    short = Chart(width=200, height=150).envelope(t[:100], y[:100], bins=60)
    assert [s.kind for s in short.series] == ["line"] and short.series[0].x.size == 100


def test_an_empty_text_parameter_is_never_a_blank_cell():
    """GNSS attitude printed "Direct-method antennas" with an empty value (#26)."""
    from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams

    ctx = ReportContext(width=WIDTH)
    table = _table(ctx.params_table(GnssAttitudeParams(), "p", blank={
        "direct_antennas": "automatic"}))
    values = {row[2].getPlainText(): row[1].getPlainText() for row in table._cellvalues[1:]}
    assert values["direct_antennas"] == "automatic"
    assert all(v.strip() for v in values.values())
    plain = _table(ctx.params_table(GnssAttitudeParams(), "p"))
    assert {row[2].getPlainText(): row[1].getPlainText()
            for row in plain._cellvalues[1:]}["direct_antennas"] == "(empty)"


def test_summary_table_marks_the_values_the_analysis_flags(tmp_path, monkeypatch):
    """The pool panel flags a pitch σ above its threshold and the PDF summary did not
    (#26): a section module's ``flags(project)`` marks its summary rows, with the reason;
    a flag without a summary row is still shown."""
    import subprocess
    import sys
    import types

    from hydrosync_core.plugins import PluginSpec, get_spec
    from hydrosync_core.project import Project
    from hydrosync_core.report import build_report
    from hydrosync_core.report.cover import module_status

    module = types.ModuleType("hydrosync_test_flagged_section")
    module.section = lambda project, ctx: [ctx.heading("Flagged analysis")]
    module.summary = lambda project: [("Boresight roll (final, 1σ)", "-44.193 ± 0.004°"),
                                      ("Boresight pitch (final, 1σ)", "-0.605 ± 0.016°")]
    module.flags = lambda project: {
        "Boresight pitch (final, 1σ)": "σ 0.016° above the 0.01° threshold",
        "Lever arm z (down)": "disagrees with the vessel sheet by 3σ"}
    monkeypatch.setitem(sys.modules, module.__name__, module)
    real = get_spec("latency")
    spec = PluginSpec(id="flagged", name="Flagged analysis", run=real.run, panel=real.panel,
                      report_section=f"{module.__name__}:section")
    project = Project.new("flags")
    project.put_json("results/flagged", {})
    status = module_status(project, spec)
    assert status.flag("Boresight pitch (final, 1σ)").startswith("σ 0.016°")
    assert status.flag("Boresight roll (final, 1σ)") == ""
    out = build_report(project, tmp_path / "f.pdf", specs=[spec])
    text = subprocess.run(["pdftotext", "-layout", str(out), "-"], capture_output=True,
                          text=True, check=True).stdout
    flat = " ".join(text.split())
    assert "\u2691 Boresight pitch" in flat and "\u2691 Boresight roll" not in flat
    assert "flagged: σ 0.016° above the 0.01° threshold" in flat
    assert "\u2691 Lever arm z (down)" in flat
    assert "marks a value the analysis flags" in flat


def test_a_long_survey_line_list_is_printed_two_lines_to_a_row(tmp_path):
    """A 500-line day's appendix took 11 mostly white pages of one narrow column (#26)."""
    import numpy as np

    from hydrosync_core.project import Project
    from hydrosync_core.report import build_report

    project = Project.new("lines")
    start = 345_600 + np.arange(500) * 170.0
    project.put_table("raw/lines", {"name": np.array([f"L{i:03d}" for i in range(1, 501)]),
                                    "start": start, "end": start + 120})
    layout = PageLayout()
    out = build_report(project, tmp_path / "lines.pdf", layout=layout)
    assert len(layout.fill) <= 7 and layout.sparse_pages() == []
    import subprocess

    text = subprocess.run(["pdftotext", "-layout", str(out), "-"], capture_output=True,
                          text=True, check=True).stdout
    assert re_search(r"L001 +raw 345600\.000 … 345720\.000 s .*L002 +raw 345770\.000", text)
    assert "L500" in text


def re_search(pattern: str, text: str) -> bool:
    import re

    return re.search(pattern, text) is not None


def test_band_of_many_curves_is_one_shaded_polygon_with_a_legend_entry():
    import numpy as np
    from reportlab.graphics.shapes import Polygon

    from hydrosync_core.report.charts import Chart

    x = np.linspace(-1, 1, 201)
    curves = np.array([0.9 - 0.3 * (x - s) ** 2 for s in np.linspace(0.2, 0.4, 500)])
    chart = Chart(width=400, height=200).band(x, curves.min(0), curves.max(0),
                                              label="500 lines: range")
    chart.line(x, np.median(curves, 0), label="median")
    drawing = chart.drawing()
    shapes = [s for g in drawing.contents for s in getattr(g, "contents", [])]
    assert sum(isinstance(s, Polygon) for s in shapes) == 1
    strings = [s.text for s in drawing.contents if hasattr(s, "text")]
    assert "500 lines: range" in strings and "median" in strings


def test_running_header_and_footer_cut_long_names_at_a_word():
    """The running header cut a long project name mid-word at a fixed character count."""
    from reportlab.pdfbase.pdfmetrics import stringWidth

    from hydrosync_core.report.template import fit_text

    name = ("HydroSync report \u2014 Harbour approaches multibeam patch test with the "
            "launch Sounder II and the Seapath 380 motion sensor, November 2026")
    text = fit_text(name, 300, FONT, 8)
    assert stringWidth(text, FONT, 8) <= 300 and text.endswith(" \u2026")
    assert name.startswith(text[:-2]) and name[len(text) - 2] == " "  # ends on a word
    assert fit_text("short", 300, FONT, 8) == "short"
    long_word = fit_text("x" * 200, 100, FONT, 8)
    assert stringWidth(long_word, FONT, 8) <= 100 and long_word.endswith("\u2026")


def test_a_split_table_never_leaves_one_row_alone_on_the_next_page():
    """The correlation table's last row went over to the next page alone (#26)."""
    ctx = ReportContext(width=WIDTH)
    rows = [[f"row {i}", f"{i:.2f}"] for i in range(10)]
    table = _table(ctx.table(["Name", "Value"], rows))
    table.wrap(WIDTH, 10_000)
    total = sum(table._rowHeights)
    seen = set()
    for room in range(60, int(total) + 1, 3):  # every page break position
        parts = table.split(WIDTH, float(room))
        if len(parts) != 2:
            continue
        first, rest = (len(p._cellvalues) - 1 for p in parts)
        assert first + rest == 10 and rest != 1, (room, first, rest)
        head = parts[1]._cellvalues[0][0]
        head = head[0] if isinstance(head, tuple | list) else head
        assert head.getPlainText() == "Name"  # the header is repeated
        seen.add(rest)
    assert 2 in seen and max(seen) >= 5  # splits happen, and the last row is never alone
