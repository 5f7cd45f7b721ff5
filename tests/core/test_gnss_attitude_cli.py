"""``hydrosync attitude``: the command-line contract, file and project forms."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from hydrosync_core.cli import main
from hydrosync_core.methods.gnss_attitude.simulate import ArrayConfig, simulate_array, write_pos


@pytest.fixture(scope="module")
def array_files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("array")
    sim = simulate_array(config=ArrayConfig(duration_s=120.0), seed=4)
    for name, track in sim["tracks"].items():
        write_pos(folder / f"{name}.pos", track, "week_tow" if name == "A3" else "calendar")
    (folder / "antennas.json").write_text(json.dumps({"frame": "FRD",
                                                      "antennas": sim["antennas"]}))
    return folder, sim


def test_file_form_writes_csv_and_json(array_files, tmp_path, capsys):
    folder, sim = array_files
    out, js = tmp_path / "attitude.csv", tmp_path / "stats.json"
    pos = [str(folder / f"A{i}.pos") for i in (1, 2, 3, 4)]
    rc = main(["attitude", "--pos", *pos, "--antennas", str(folder / "antennas.json"),
               "--out", str(out), "--json", str(js)])
    assert rc == 0
    with out.open() as fh:
        rows = list(csv.DictReader(fh))
    assert list(rows[0]) == ["time", "heading", "pitch", "roll", "sd_heading", "sd_pitch",
                             "sd_roll", "method", "n_antennas"]
    assert {r["method"] for r in rows} == {"lsq"}
    truth = sim["truth"]
    t = np.array([float(r["time"]) for r in rows])
    idx = np.searchsorted(np.round(truth["time"], 3), t)
    dh = (np.array([float(r["heading"]) for r in rows]) - truth["heading"][idx] + 180) % 360 \
        - 180
    assert np.sqrt(np.mean(dh**2)) < 0.3
    stats = json.loads(js.read_text())
    assert stats["solved"] == len(rows) and set(stats["statistics"]) == {"lsq", "wahba",
                                                                          "direct"}
    assert "lsq" in capsys.readouterr().out


def test_three_antennas_direct_method(array_files, tmp_path):
    folder, _ = array_files
    out = tmp_path / "a.csv"
    rc = main(["attitude", "--pos", *(str(folder / f"A{i}.pos") for i in (1, 2, 3)),
               "--antennas", str(folder / "antennas.json"), "--out", str(out),
               "--method", "direct", "--min-quality", "float"])
    assert rc == 0
    with out.open() as fh:
        rows = list(csv.DictReader(fh))
    assert rows and {r["method"] for r in rows} == {"direct"}
    assert {r["n_antennas"] for r in rows} == {"3"}


def _err(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert "\n" not in err
    return err


def test_bad_input_exits_2_with_one_line(array_files, tmp_path, capsys):
    folder, _ = array_files
    ants = str(folder / "antennas.json")
    out = tmp_path / "a.csv"
    stray = tmp_path / "B9.pos"
    stray.write_text((folder / "A1.pos").read_text())
    rc = main(["attitude", "--pos", str(folder / "A1.pos"), str(folder / "A2.pos"),
               str(stray), "--antennas", ants, "--out", str(out)])
    assert rc == 2 and "no antenna 'B9'" in _err(capsys)
    broken = tmp_path / "A3.pos"
    lines = (folder / "A3.pos").read_text().splitlines()
    lines[10] = lines[10].replace(" 1  18", " 1  x8")
    broken.write_text("\n".join(lines) + "\n")
    rc = main(["attitude", "--pos", str(folder / "A1.pos"), str(folder / "A2.pos"),
               str(broken), "--antennas", ants, "--out", str(out)])
    err = _err(capsys)
    assert rc == 2 and f"{broken}:11: field 'ns'" in err
    rc = main(["attitude", "--pos", str(folder / "A1.pos"), str(folder / "A2.pos"),
               "--antennas", ants, "--out", str(out)])
    assert rc == 2 and "at least three" in _err(capsys)
    bad_json = tmp_path / "ants.json"
    bad_json.write_text('{"antennas": {"A1": [0, 0, 0], "A2": [1, 0, "x"], "A3": [0, 1, 0]}}')
    rc = main(["attitude", "--pos", str(folder / "A1.pos"), "--antennas", str(bad_json),
               "--out", str(out)])
    assert rc == 2 and "field 'antennas.A2'" in _err(capsys)
    rc = main(["attitude", "--pos", str(folder / "A1.pos"), "--antennas", ants, "--out",
               str(out), "--length-tolerance-m", "-1"])
    assert rc == 2 and "--length-tolerance-m" in _err(capsys)
    assert not out.exists()


def test_project_form_import_and_run(array_files, tmp_path, capsys):
    from hydrosync_core.project import Project

    folder, _ = array_files
    h5 = tmp_path / "p.h5"
    for i in (1, 2, 3, 4):  # `hydrosync import` takes one file per kind and call
        rc = main(["import", str(h5), "--pos", str(folder / f"A{i}.pos")])
        assert rc == 0, capsys.readouterr().err
    rc = main(["import", str(h5), "--antennas", str(folder / "antennas.json")])
    assert rc == 0, capsys.readouterr().err
    out = tmp_path / "p.csv"
    rc = main(["attitude", str(h5), "--out", str(out), "--static-start-s", "422930",
               "--static-end-s", "422990"])
    assert rc == 0, capsys.readouterr().err
    with Project.open(h5) as project:
        attrs = project.attrs("results/gnss_attitude")
        assert {"software_version", "run_utc", "params_schema_version"} <= set(attrs)
        stats = json.loads(attrs["statistics"])
        assert 50 <= stats["lsq"]["epochs"] <= 61
        assert project.get_table("results/gnss_attitude/lsq")["heading"].size > 100
    rc = main(["run", "gnss_attitude", str(h5), "--param", "method=wahba"])
    assert rc == 0
