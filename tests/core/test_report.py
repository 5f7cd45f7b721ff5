"""PDF report: numbers as text, section headings, page numbers, partial and empty projects.

The text of the PDF is extracted with pypdf and compared with the values stored in the
project, formatted by the same functions the sections use.
"""

from __future__ import annotations

import re
import threading

import h5py
import numpy as np
import pytest
from pypdf import PdfReader

from hydrosync_core.cli import main
from hydrosync_core.errors import Cancelled
from hydrosync_core.methods.latency import report_section as lat
from hydrosync_core.methods.pool_calibration import report_section as pool
from hydrosync_core.plugins import PluginSpec, get_spec, load_object, plugin_specs
from hydrosync_core.project import Project
from hydrosync_core.report import build_report
from hydrosync_core.report.charts import nice_ticks, tick_label
from hydrosync_core.report.context import fmt, fmt_pm, utc_text

LATENCY_HEADING = lat.HEADING


def pdf_pages(path) -> list[str]:
    """Text of every page (whitespace runs collapsed to one space)."""
    return [re.sub(r"\s+", " ", page.extract_text()) for page in PdfReader(str(path)).pages]


def run_plugin(project: Project, plugin_id: str, seed: int = 7) -> object:
    spec = get_spec(plugin_id)
    load_object(spec.demo)(project, seed=seed, progress=None)
    return spec.load_run()(project, dict(spec.default_params), None, None)


@pytest.fixture(scope="module")
def latency_project(tmp_path_factory):
    """A saved project in which only the latency module was run (demo data)."""
    path = tmp_path_factory.mktemp("latency") / "survey.h5"
    project = Project.new("Harbour survey")
    run_plugin(project, "latency")
    project.save(path)
    yield Project.open(path)


# ---------------------------------------------------------------------------- helpers
def test_fmt_and_ticks():
    assert fmt(0.28774, 3) == "0.288"
    assert fmt(-0.0001, 3) == "0.000"  # no "-0.000"
    assert fmt(float("nan")) == "\u2014" and fmt(None) == "\u2014"
    assert fmt_pm(0.2877, 0.0056, 3, "s") == "0.288 \u00b1 0.006 s"
    assert fmt_pm(0.2877, float("nan"), 3, "s") == "0.288 s"
    assert utc_text("2026-11-22T04:40:23+00:00") == "2026-11-22 04:40:23 UTC"
    ticks = nice_ticks(-1.0, 1.0)
    assert ticks[0] == -1.0 and ticks[-1] == 1.0 and np.allclose(np.diff(ticks), 0.5)
    assert np.allclose(np.diff(nice_ticks(0.21, 0.43)), 0.05)
    assert tick_label(0.25, 0.25) == "0.25" and tick_label(-0.5, 0.5) == "\u22120.5"


# ---------------------------------------------------------------------------- content
def test_empty_project_report(tmp_path):
    out = build_report(Project.new("Nothing yet"), tmp_path / "empty.pdf")
    pages = pdf_pages(out)
    text = " ".join(pages)
    assert "Sensor calibration report" in text and "Nothing yet" in text
    assert "Summary of results" in text
    for spec in plugin_specs():
        assert f"{spec.name} not run" in text
    assert LATENCY_HEADING not in text
    assert "Modules not run (their sections are omitted)" in text
    assert pages[-1].count(f"page {len(pages)} of {len(pages)}") == 1


def test_latency_only_report_numbers_and_pages(latency_project, tmp_path):
    progress: list[float] = []
    out = build_report(latency_project, tmp_path / "r.pdf",
                       progress=lambda f, m: progress.append(f))
    assert progress[0] == 0.0 and progress[-1] == 1.0 and progress == sorted(progress)
    pages = pdf_pages(out)
    n = len(pages)
    for i, page in enumerate(pages, start=1):
        assert f"page {i} of {n}" in page
    text = " ".join(pages)
    attrs = latency_project.attrs("results/latency")
    table = latency_project.get_table("results/latency/lines")
    assert len(table["name"]) == 13
    # Every line's row, in order, exactly as stored (formatted like the section does).
    for i in range(len(table["name"])):
        assert " ".join(lat.line_row(table, i)) in text, lat.line_row(table, i)
    assert lat.final_value_text(attrs) in text
    assert lat.ci_text(attrs) in text
    mean = " ".join(lat.line_cells(attrs["latency_s"], attrs["uncertainty_s"]))
    assert f"Weighted mean {mean}" in text
    # The demo latency is 0.29 s: the report must show a value close to it (s or ms, as
    # its σ reads best), never "± 0.000".
    value, _, _, unit = lat.final_value_text(attrs).split()
    assert abs(float(value) * (1e-3 if unit == "ms" else 1.0) - 0.29) < 0.03
    assert "0.000" not in lat.final_value_text(attrs)
    # Section headings and figures; the pool section is omitted, the summary says so.
    assert LATENCY_HEADING in text and "Before and after synchronisation" in text
    assert re.search(r"Figure 1\. Correlation R", text)
    assert "the best used line" in text and "the worst used line" in text
    spec = get_spec("pool_calibration")
    assert f"{spec.name} not run: inputs missing" in text
    assert pool.HEADING not in text
    # Summary rows come from the section module and are in the summary table.
    for _quantity, value in lat.summary(latency_project):
        assert value in text
    # The cover names the file and its checksum.
    assert str(latency_project.path.name) in text and "SHA-256" in text


def test_faulty_section_does_not_sink_the_report(latency_project, tmp_path):
    real = get_spec("latency")
    # A section whose callable has the wrong signature raises inside the build.
    broken = PluginSpec(id="latency", name="Latency", run=real.run, panel=real.panel,
                        report_section="hydrosync_core.report.context:esc")
    problems: list[str] = []
    out = build_report(latency_project, tmp_path / "b.pdf", specs=[broken], problems=problems)
    text = " ".join(pdf_pages(out))
    # in words for the reader (issue #28), the exception's class only as a hint
    assert "The Latency section could not be produced: its stored data are not of the " \
        "expected form" in " ".join(text.split())
    assert "TypeError in the report code" in " ".join(text.split())
    assert problems and problems[0].startswith("section 'Latency' could not be produced")
    assert "Summary of results" in text


def test_cancel_leaves_previous_file(latency_project, tmp_path):
    target = tmp_path / "r.pdf"
    target.write_bytes(b"previous")
    stop = threading.Event()
    stop.set()
    with pytest.raises(Cancelled):
        build_report(latency_project, target, cancel=stop)
    assert target.read_bytes() == b"previous"
    # Cancelled in the middle of the page layout (after the first page).
    stop.clear()

    def progress(_fraction, message):
        if message.startswith("laying out page"):
            stop.set()

    with pytest.raises(Cancelled):
        build_report(latency_project, target, progress=progress, cancel=stop)
    assert target.read_bytes() == b"previous"
    assert list(tmp_path.iterdir()) == [target]


# ---------------------------------------------------------------------------- CLI
def test_cli_report(latency_project, tmp_path, capsys):
    out = tmp_path / "cli.pdf"
    assert main(["report", str(latency_project.path), "-o", str(out)]) == 0
    assert f"report written to {out}" in capsys.readouterr().out
    assert out.read_bytes().startswith(b"%PDF")


@pytest.mark.parametrize("kind", ["missing", "text", "hdf5", "no-folder", "not-pdf"])
def test_cli_report_bad_input(kind, tmp_path, capsys):
    project = tmp_path / "p.h5"
    out = tmp_path / "r.pdf"
    if kind == "text":
        project.write_text("time,height\n1,2\n")
    elif kind == "hdf5":
        with h5py.File(project, "w") as f:
            f["x"] = np.arange(3)
    elif kind in ("no-folder", "not-pdf"):
        Project.new("p").save(project)
        out = tmp_path / "nowhere" / "r.pdf" if kind == "no-folder" else tmp_path / "r.txt"
    code = main(["report", str(project), "-o", str(out)])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert err.startswith("hydrosync report: ") and "\n" not in err
    assert not out.exists()
    assert not any(p.suffix in (".pdf", ".tmp", ".txt") for p in tmp_path.rglob("*"))


def test_report_when_no_line_passes_the_threshold(tmp_path):
    """A latency run without a final value still reports its lines and says why."""
    project = Project.new("Rough sea")
    spec = get_spec("latency")
    load_object(spec.demo)(project, seed=2, progress=None)
    result = spec.load_run()(project, dict(spec.default_params, min_r=0.999), None, None)
    assert not result.converged
    text = " ".join(pdf_pages(build_report(project, tmp_path / "r.pdf")))
    assert LATENCY_HEADING in text
    assert "Latency \u0394t (GNSS tags late), 1\u03c3 \u2014" in text
    assert result.message in text
    assert "Before and after synchronisation" not in text
    table = project.get_table("results/latency/lines")
    for i in range(len(table["name"])):
        assert " ".join(lat.line_row(table, i)) in text


def test_unsaved_project_report_says_never_saved_and_pool_appendix(tmp_path):
    """An unsaved project's cover says "never" saved (not a date); the pool iteration table
    is one row per round in the section and complete in the appendix (#11 item 10)."""
    from pypdf import PdfReader

    from hydrosync_core.methods.pool_calibration.demo import fill_demo as fill_pool
    from hydrosync_core.methods.pool_calibration.project_run import run as run_pool
    from tests.core.test_pool_cli_project import SMALL

    project = Project.new("unsaved")
    fill_pool(project, seed=3, config=SMALL)
    run_pool(project)
    pdf = tmp_path / "r.pdf"
    build_report(project, pdf)
    text = " ".join(page.extract_text() for page in PdfReader(pdf).pages)
    assert "never (the project exists only in memory)" in text
    assert "last iteration of each round" in text
    assert "every patent iteration" in text
