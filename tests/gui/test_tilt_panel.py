"""Tilt Alignment panel: human labels, and the same numbers as the CLI and the PDF."""

from __future__ import annotations

import json

import pytest

from hydrosync_core.methods.tilt_alignment import cli, demo, project_run
from hydrosync_core.methods.tilt_alignment.params import TiltParams
from hydrosync_core.methods.tilt_alignment.present import COLUMNS, method_rows
from hydrosync_core.project import Project


@pytest.fixture()
def solved_project():
    project = Project.new("tilt")
    demo.fill_demo(project, seed=0)
    project_run.run(project, TiltParams())
    return project


def test_table_reads_like_the_cli_and_the_pdf(qtbot, solved_project, capsys):
    from hydrosync_core.methods.tilt_alignment.report_section import summary
    from plugins.tilt_alignment.panel import TiltAlignmentPanel

    panel = TiltAlignmentPanel()
    qtbot.addWidget(panel)
    panel.set_project(solved_project)
    model = panel.table.table_model
    headers = [model.header(c) for c in range(model.columnCount())]
    # human labels with units, no raw keys
    assert headers[0] == "Method" and "Tip σ E/N/U [mm]" in headers
    assert not any(k in " ".join(headers) for k in ("sd_e_mm", "psi_deg", "_"))
    doc = json.loads(solved_project.attrs(project_run.RESULT)["result"])
    rows = method_rows(doc)
    cells = [[model.text(r, c) for c in range(model.columnCount())]
             for r in range(model.rowCount())]
    assert cells == [[row[k] for k in COLUMNS] for row in rows]
    joint = next(r for r in rows if r["method"].startswith("joint"))
    # digits from σ: "57.0 ± 0.12°"-like, σ with two significant digits
    value, sigma = joint["heading"].rstrip("°").split(" ± ")
    assert len(sigma.replace("0.", "").lstrip("0")) == 2
    assert len(value.split(".")[-1]) == len(sigma.split(".")[-1])
    cli._print(doc)
    printed = capsys.readouterr().out
    for row in rows:
        for key in ("method", "heading", "tip", "sigma"):
            assert row[key] in printed
    assert "IMU grade mems" in printed and "samples instant" in printed
    pdf = dict(summary(solved_project))
    assert joint["heading"] == pdf["Tilt pole heading misalignment"]
    assert joint["sigma"] + " mm" == pdf["Tilt pole tip σ E/N/U"]
    assert "IMU grade mems" in panel.summary.text()
