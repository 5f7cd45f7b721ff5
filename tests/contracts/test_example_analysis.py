"""The example third-party analysis works end to end once discovered: command, ``run``,
report section and import kinds come from its spec alone (no shared file lists it)."""

from __future__ import annotations

import pytest
from example_plugin import example_discovered

import hydrosync_core.plugins as plugins_pkg
from hydrosync_core.cli import build_parser, main
from hydrosync_core.methods.latency.demo import fill_demo
from hydrosync_core.plugins import registry
from hydrosync_core.project import Project


@pytest.fixture
def with_example(monkeypatch):
    real = registry.discover

    def discover(group=registry.ENTRY_POINT_GROUP):
        return real(group) + [example_discovered()]

    monkeypatch.setattr(registry, "discover", discover)
    monkeypatch.setattr(plugins_pkg, "discover", discover)


@pytest.fixture
def project_path(tmp_path):
    path = tmp_path / "P.h5"
    project = Project.new("p")
    fill_demo(project, seed=1)
    project.save(path)
    project.close()
    return path


def test_command_and_run_come_from_the_spec(with_example, project_path, capsys):
    assert "heave-stats" in build_parser().format_help()
    assert main(["heave-stats", str(project_path), "--min-period", "3"]) == 0
    out = capsys.readouterr().out
    assert out.count("RMS") == 13  # the demo day's 13 lines
    with Project.open(project_path) as p:
        assert p.get_json("results/heave_stats")["min_period_s"] == 3.0
        periods = p.get_table("results/heave_stats/lines")["peak_period_s"]
        assert ((periods >= 3.0) & (periods <= 30.0)).all()
    assert main(["run", "heave_stats", str(project_path), "--param", "skip_s=10"]) == 0
    with Project.open(project_path) as p:
        assert p.get_json("results/heave_stats")["skip_s"] == 10.0
    assert main(["heave-stats", str(project_path), "--min-period", "40"]) == 2
    assert "longest period must exceed" in capsys.readouterr().err


def test_report_includes_the_example_section(with_example, project_path, tmp_path):
    from pypdf import PdfReader

    assert main(["run", "heave_stats", str(project_path)]) == 0
    pdf = tmp_path / "r.pdf"
    assert main(["report", str(project_path), "--out", str(pdf)]) == 0
    text = "".join(page.extract_text() for page in PdfReader(pdf).pages)
    assert "Heave Statistics" in text and "Shortest period" in text


def test_example_panel_runs_in_a_worker_and_says_the_project_changed(qtbot, project_path):
    """Run from the panel: off the GUI thread, then ``sig_project_modified`` (the main
    window marks the project changed, the other panels redraw) and the table is shown
    with human labels."""
    example_discovered()  # puts the example on sys.path
    from hydrosync_heave_stats.panel import HeaveStatsPanel

    panel = HeaveStatsPanel()
    qtbot.addWidget(panel)
    with Project.open(project_path) as project:
        panel.set_project(project)
        assert panel.run_button.isEnabled()
        with qtbot.waitSignal(panel.sig_project_modified, timeout=60_000):
            panel.run_button.click()
        assert panel.wait_idle(30.0)
        assert project.exists("results/heave_stats/lines")
        model = panel.table.table_model
        assert model.rowCount() == 13
        assert model.header(2) == "RMS heave [m]"
