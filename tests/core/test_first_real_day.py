"""A first real day (#11): provenance of imports, caveats, time spans, missing vessel sheet."""

from __future__ import annotations

import hashlib
import json

from hydrosync_core.cli import main
from hydrosync_core.project import Project
from tests.core._real_logs import REAL_LOGS, needs_real_logs

LOG = REAL_LOGS / "tagged" / "openrvdas_NBP1406_seap-2014-08-01.txt"
LINES = "name,start,end\nA,1406851200,1406851500\nB,1406851500,1406851910\n"


def _import(tmp_path, *extra) -> str:
    project = str(tmp_path / "seap.h5")
    (tmp_path / "lines.csv").write_text(LINES)
    assert main(["import", project, "--gnss-log", str(LOG), "--attitude-log", str(LOG),
                 "--heave-positive", "down", "--lines", str(tmp_path / "lines.csv"),
                 *extra]) == 0
    return project


@needs_real_logs
def test_missing_vessel_sheet_names_every_entry_and_the_fix(tmp_path, capsys):
    project = _import(tmp_path)
    capsys.readouterr()
    assert main(["latency", project]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err
    assert "no 'gnss' and no 'motion' sensor" in err
    assert "--set gnss X Y Z --set motion X Y Z" in err and "--lever-arm" in err
    assert "Vessel offsets" in err


@needs_real_logs
def test_import_provenance_caveat_and_time_spans(tmp_path, capsys):
    project = _import(tmp_path)
    with Project.open(project) as p:
        entry = json.loads(p.attrs("raw/gnss")["imports"])[0]
    assert entry["file"] == LOG.name and entry["size_bytes"] == LOG.stat().st_size
    assert entry["sha256"] == hashlib.sha256(LOG.read_bytes()).hexdigest()
    assert entry["kind"] == "gnss_log"
    assert main(["latency", project, "--lever-arm", "0", "0", "0"]) == 0
    out = capsys.readouterr().out
    assert "warning: /raw/gnss import: 715 GGA epochs have an empty geoid separation" in out
    assert main(["info", project]) == 0
    info = capsys.readouterr().out
    assert "time 2014-08-01 00:00:00 – 00:11:53 UTC" in info
    pdf = tmp_path / "r.pdf"
    assert main(["report", project, "-o", str(pdf)]) == 0
    from pypdf import PdfReader

    pages = [page.extract_text() for page in PdfReader(pdf).pages]
    assert "Caveat" in pages[1] and "geoid" in pages[1]  # on the summary page
    text = " ".join(pages)
    assert entry["sha256"] in text and "positive down (stored positive up)" in text
    assert "Survey lines" in text and "2014-08-01 00:05:00" in text


@needs_real_logs
def test_empty_geoid_skip_on_the_command_line(tmp_path, capsys):
    project = str(tmp_path / "g.h5")
    # Every GGA of this log lacks the separation: skipping them leaves no height at all.
    assert main(["import", project, "--gnss-log", str(LOG), "--empty-geoid", "skip"]) == 2
    assert "GGA: empty geoid separation 715" in capsys.readouterr().err


def test_no_overlap_names_the_spans(tmp_path, capsys):
    from hydrosync_core.methods.latency.demo import fill_demo
    from hydrosync_core.methods.latency.project_run import run

    p = Project.new("p")
    fill_demo(p, seed=1)
    lines = p.get_table("raw/lines")
    p.put_table("raw/lines", {"name": lines["name"][:2], "start": lines["start"][:2] + 1e9,
                              "end": lines["end"][:2] + 1e9})
    import pytest

    from hydrosync_core.errors import InputError

    with pytest.raises(InputError) as err:
        run(p, {"step_s": 0.02})
    message = err.value.message
    assert "lines span" in message and "GNSS raw" in message and "attitude raw" in message
