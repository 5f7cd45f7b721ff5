"""Vessel sheet from the CLI, and the latency chain end to end on a real Seapath log."""

from __future__ import annotations

import json

import pytest

from hydrosync_core.cli import main
from hydrosync_core.project import Project
from hydrosync_core.project.vessel import lever_arm
from tests.core._real_logs import REAL_LOGS, needs_real_logs


def test_vessel_set_and_import(tmp_path, capsys):
    project = tmp_path / "p.h5"
    assert main(["new", str(project)]) == 0
    assert main(["vessel", str(project), "--set", "motion", "0.5", "0", "0",
                 "--set", "gnss", "-1", "2", "-6", "--name", "MV Test"]) == 0
    assert "MV Test" in capsys.readouterr().out
    with Project.open(project) as p:
        assert lever_arm(p, "gnss", "motion").tolist() == [-1.5, 2.0, -6.0]
    sheet = tmp_path / "vessel.json"
    sheet.write_text(json.dumps({"name": "Sheet", "sensors": {
        "motion": {"offset_m": [0, 0, 0]},
        "multibeam": {"offset_m": [1.2, 2.45, 1.8], "angles_deg": {"roll": -35}}}}))
    assert main(["import", str(project), "--vessel", str(sheet)]) == 0
    with Project.open(project) as p:
        sensors = p.get_json("vessel")["sensors"]
        assert sensors["multibeam"]["angles_deg"] == {"roll": -35.0}
        assert "gnss" not in sensors


@pytest.mark.parametrize(
    ("document", "field"),
    [({"sensors": {}}, "sensors"),
     ({"sensors": {"gnss": {"offset_m": [1, 2]}}}, "sensors.gnss.offset_m"),
     ({"sensors": {"gnss": {"offset_m": [1, 2, None]}}}, "sensors.gnss.offset_m"),
     ({"sensors": {"gnss": {"offset_m": [1, 2, 3], "angles_deg": {"tilt": 1}}}},
      "sensors.gnss.angles_deg")],
)
def test_bad_vessel_sheet(tmp_path, capsys, document, field):
    sheet = tmp_path / "vessel.json"
    sheet.write_text(json.dumps(document))
    assert main(["import", str(tmp_path / "p.h5"), "--vessel", str(sheet)]) == 2
    err = capsys.readouterr().err
    assert f"field '{field}'" in err and "vessel.json" in err
    assert not (tmp_path / "p.h5").exists()


@needs_real_logs
def test_latency_on_real_seapath_log(tmp_path, capsys):
    """RVIB Palmer Seapath 200: GGA heights and PSXN,23 heave from one logger file.

    No truth is known here; the check is that the real chain works and gives a sharp,
    plausible answer: both lines correlate strongly (heights and heave from one INS) and
    agree on a small relative delay of the order of the 0.12 s logger-vs-sentence delay
    the importer measures on the GGA lines.
    """
    log = REAL_LOGS / "tagged" / "openrvdas_NBP1406_seap-2014-08-01.txt"
    project = tmp_path / "seap.h5"
    lines = tmp_path / "lines.csv"
    lines.write_text("name,start,end\nA,1406851200,1406851500\nB,1406851500,1406851910\n")
    assert main(["import", str(project), "--gnss_log", str(log), "--attitude_log", str(log),
                 "--heave-positive", "down", "--lines", str(lines)]) == 0
    result_json = tmp_path / "r.json"
    assert main(["latency", str(project), "--lever-arm", "0", "0", "0",
                 "--json", str(result_json)]) == 0
    result = json.loads(result_json.read_text())
    assert [line["used"] for line in result["lines"]] == [True, True]
    assert min(line["r_max"] for line in result["lines"]) > 0.95
    assert -0.3 < result["latency_s"] < 0.0
    assert abs(result["lines"][0]["latency_s"] - result["lines"][1]["latency_s"]) < 0.05
