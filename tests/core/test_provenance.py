"""Results record what they were computed from and are marked out of date when it changes."""

from __future__ import annotations

import numpy as np
import pytest

from hydrosync_core.cli import main
from hydrosync_core.methods.latency.demo import fill_demo
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.latency.project_run import run
from hydrosync_core.project import Project
from hydrosync_core.project.vessel import set_sensor
from hydrosync_core.provenance import fingerprint, read_record, stale_reasons

RESULT = "results/latency"


@pytest.fixture
def project_path(tmp_path):
    path = tmp_path / "P.h5"
    project = Project.new("p")
    fill_demo(project, seed=4)
    run(project, LatencyParams(step_s=0.01))
    project.save(path)
    project.close()
    return path


def _replace_lines_and_move_antenna(path) -> None:
    with Project.open(path) as project:
        lines = project.get_table("raw/lines")
        project.put_table("raw/lines", {k: v[:1] for k, v in lines.items()})
        set_sensor(project, "gnss", [0.0, 2.0, -6.0])
        project.save()


def test_record_holds_inputs_vessel_params_and_versions(project_path):
    with Project.open(project_path) as project:
        rec = read_record(project, RESULT)
        assert set(rec["inputs"]) == {"raw/gnss", "raw/attitude", "raw/lines"}
        assert rec["inputs"]["raw/lines"] == fingerprint(project, "raw/lines")
        assert set(rec["vessel"]) == {"gnss", "motion"}  # lever arm from the sheet
        assert rec["params"]["step_s"] == 0.01 and rec["params_schema_version"] == 1
        assert rec["software_version"] and rec["plugin_version"] and rec["run_utc"]
        assert stale_reasons(project, RESULT) == []


def test_fingerprint_follows_content_not_storage(project_path):
    with Project.open(project_path) as project:
        before = fingerprint(project, "raw/attitude")
        table = project.get_table("raw/attitude")
        project.put_table("raw/attitude", table)  # same values rewritten
        assert fingerprint(project, "raw/attitude") == before
        table["heave"] = table["heave"] + np.where(np.arange(table["heave"].size) == 7, 1e-6, 0)
        project.put_table("raw/attitude", table)
        assert fingerprint(project, "raw/attitude") != before


def test_changed_lines_and_lever_arm_make_the_result_out_of_date(project_path, capsys, tmp_path):
    _replace_lines_and_move_antenna(project_path)
    with Project.open(project_path) as project:
        reasons = stale_reasons(project, RESULT)
    assert "/raw/lines changed since the run" in reasons
    assert "vessel sheet entry 'gnss' changed since the run" in reasons

    assert main(["info", str(project_path)]) == 0
    out = capsys.readouterr().out
    assert "latency: OUT OF DATE: /raw/lines changed" in out

    pdf = tmp_path / "r.pdf"
    assert main(["report", str(project_path), "-o", str(pdf), "--strict"]) == 2
    assert "out of date" in capsys.readouterr().err and not pdf.exists()
    assert main(["report", str(project_path), "-o", str(pdf)]) == 0
    assert "warning: latency results are out of date" in capsys.readouterr().err
    from pypdf import PdfReader

    text = " ".join(p.extract_text() for p in PdfReader(pdf).pages)
    assert text.count("OUT OF DATE") >= 2  # summary and the section itself

    # Running again brings it up to date.
    assert main(["run", "latency", str(project_path), "--param", "step_s=0.01",
                 "--param", "min_epochs=5"]) == 0
    with Project.open(project_path) as project:
        assert stale_reasons(project, RESULT) == []


def test_given_lever_arm_does_not_depend_on_the_vessel_sheet(tmp_path):
    project = Project.new("p")
    fill_demo(project, seed=4)
    run(project, LatencyParams(step_s=0.01, lever_arm_m=(-1.5, 2.0, -6.0)))
    assert read_record(project, RESULT)["vessel"] == {}
    set_sensor(project, "gnss", [9.0, 9.0, 9.0])
    assert stale_reasons(project, RESULT) == []
