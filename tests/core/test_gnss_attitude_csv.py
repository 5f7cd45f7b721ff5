"""antenna_positions.csv and .geo inputs of ``hydrosync attitude``; covariance fallback."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from hydrosync_core.cli import main
from hydrosync_core.errors import InputError
from hydrosync_core.importers.antenna_csv import read_antenna_csv
from hydrosync_core.importers.geo_positions import read_geo
from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams
from hydrosync_core.methods.gnss_attitude.pipeline import solve_array
from hydrosync_core.methods.gnss_attitude.project_run import track_from_columns
from hydrosync_core.methods.gnss_attitude.simulate import ArrayConfig, simulate_array

Q_TO_GGA = {1: 4, 2: 5}


@pytest.fixture(scope="module")
def sim():
    return simulate_array(config=ArrayConfig(duration_s=90.0), seed=7)


def write_csv(path, sim, with_sd=True, shuffle=True, extra_rows=()):
    rows = []
    for name, t in sim["tracks"].items():
        for i in range(t["time"].size):
            row = [f"{t['time'][i]:.3f}", name, f"{t['x'][i]:.4f}", f"{t['y'][i]:.4f}",
                   f"{t['z'][i]:.4f}", str(Q_TO_GGA[int(t["q"][i])])]
            if with_sd:
                row += ["0.006", "0.006", "0.012"]
            rows.append(row)
    if shuffle:
        np.random.default_rng(0).shuffle(rows)
    header = "time,Antenna,x,y,z,quality" + (",sdx,sdy,sdz" if with_sd else "")
    path.write_text(header + "\n" + "\n".join(",".join(r) for r in [*rows, *extra_rows])
                    + "\n")
    return path


def test_csv_reader_groups_sorts_and_maps_quality(sim, tmp_path):
    tables = read_antenna_csv(write_csv(tmp_path / "a.csv", sim,
                                        extra_rows=[["5.0", "A1", "1", "2", "3", "0",
                                                     "1", "1", "1"]]))
    assert set(tables) == set(sim["tracks"])
    for name, t in tables.items():
        src = sim["tracks"][name]
        assert np.all(np.diff(t["time"]) > 0)
        np.testing.assert_allclose(t["time"], src["time"], atol=1e-3)
        np.testing.assert_array_equal(t["q"], src["q"])  # GGA 4/5 -> RTKLIB 1/2
        np.testing.assert_allclose(t["lat"], src["lat"], atol=1e-8)
        assert "sdxy" in t and "week" not in t


def test_csv_command_matches_pos_solution(sim, tmp_path, capsys):
    path = write_csv(tmp_path / "a.csv", sim)
    ant = tmp_path / "antennas.json"
    ant.write_text(json.dumps({"antennas": sim["antennas"]}))
    out = tmp_path / "att.csv"
    rc = main(["attitude", "--csv", str(path), "--antennas", str(ant), "--out", str(out)])
    assert rc == 0, capsys.readouterr().err
    with out.open() as fh:
        rows = list(csv.DictReader(fh))
    truth = sim["truth"]
    t = np.array([float(r["time"]) for r in rows])
    idx = np.searchsorted(np.round(truth["time"], 3), np.round(t, 3))
    dh = (np.array([float(r["heading"]) for r in rows]) - truth["heading"][idx] + 180) % 360 \
        - 180
    assert len(rows) > 60 and np.sqrt(np.mean(dh**2)) < 0.3


def test_csv_times_are_kept_as_given_when_not_gps_seconds(sim):
    # Unix-like seconds: the output time is the input time, not a time of week
    tracks = {}
    for name, t in sim["tracks"].items():
        cols = {k: v for k, v in t.items() if k != "week"}
        cols["gps_s"] = cols["gps_s"] - sim["tracks"]["A1"]["gps_s"][0] + 1.7e9
        tracks[name] = track_from_columns(cols, name)
    sol = solve_array(tracks, sim["antennas"], GnssAttitudeParams(weights="apriori"))
    assert sol.time[0] == pytest.approx(1.7e9, abs=2)


@pytest.mark.parametrize("body, message, line, field", [
    ("time,antenna,x,y,z\n1,A1,1,2,3\n", "missing column(s) quality", 1, None),
    ("time,x,y,z,quality\n1,4.5e6,1e5,4.5e6,4\n", "missing column antenna", 1, None),
    ("time,antenna,x,y,z,quality\n1,A1,4.5e6,1e5,4.5e6,9\n", "not a GGA fix quality", 2,
     "quality"),
    ("time,antenna,x,y,z,quality\n1,A 1,4.5e6,1e5,4.5e6,4\n", "is not a name", 2, "antenna"),
    ("time,antenna,x,y,z,quality\n1,A1,1,2,3,4\n", "not near the Earth", 2, "x"),
    ("time,antenna,x,y,z,quality\n1,A1,4.5e6,1e5,4.5e6,4\n2,A2,4.5e6,1e5,4.5e6,4\n"
     "1,A1,4.5e6,1e5,4.5e6,4\n", "repeats time", 4, "time"),
    ("time,antenna,x,y,z,quality\n1,A1,4.5e6,abc,4.5e6,4\n", "", 2, "y"),
])
def test_bad_csv_names_line_and_field(tmp_path, body, message, line, field):
    p = tmp_path / "bad.csv"
    p.write_text(body)
    with pytest.raises(InputError) as exc:
        read_antenna_csv(p)
    assert message in exc.value.message
    assert exc.value.line == line and exc.value.field == field


def test_csv_and_pos_together_is_exit_2(sim, tmp_path, capsys):
    path = write_csv(tmp_path / "a.csv", sim)
    rc = main(["attitude", "--csv", str(path), "--pos", str(path), "--antennas", str(path),
               "--out", str(tmp_path / "o.csv")])
    assert rc == 2
    assert "either --pos files or one --csv" in capsys.readouterr().err


GEO = ("2022 10 20   15 30  8.000  39.4814020302  -0.3366088205    56.032   0.009   0.009"
       "   0.030\n"
       "2022 10 20   15 30  9.999  39.4814020218  -0.3366088441    56.036   0.009   0.009"
       "   0.030\n")


def test_geo_rounds_999_tags(tmp_path):
    p = tmp_path / "R.geo"
    p.write_text(GEO)
    c = read_geo(p)
    np.testing.assert_allclose(np.diff(c["gps_s"]), [2.0])
    assert c["time"][1] % 1.0 == pytest.approx(0.0)


@pytest.mark.parametrize("text, message, line, field", [
    (GEO + "2022 10 20 15 30 11 39.48 -0.33 56.0 0.01 0.01\n", "expected 12 fields", 3, None),
    (GEO + "2022 10 20 15 30 11 39.48 -0.33 56.0 0.01 0.01 -1\n", "positive", 3,
     "sigma_height"),
    (GEO + "2022 02 30 15 30 11 39.48 -0.33 56.0 0.01 0.01 0.1\n", "not a date", 3, "day"),
    (GEO + "2022 10 20 15 30 10.001 39.48 -0.33 56.0 0.01 0.01 0.1\n", "repeated", 3,
     "second"),
    (GEO + "2022 10 20 15 30 11 95 -0.33 56.0 0.01 0.01 0.1\n", "latitude", 3, "latitude"),
])
def test_bad_geo_names_line_and_field(tmp_path, text, message, line, field):
    p = tmp_path / "R.geo"
    p.write_text(text)
    with pytest.raises(InputError) as exc:
        read_geo(p)
    assert message in exc.value.message
    assert (exc.value.line, exc.value.field) == (line, field)


def test_covariance_not_positive_definite_falls_back_and_is_counted(sim):
    tracks = {n: track_from_columns(t, n) for n, t in sim["tracks"].items()}
    a1 = tracks["A1"]
    bad = np.arange(0, a1.cov_ned.shape[0], 10)
    a1.cov_ned[bad] = np.diag([1e-4, 1e-4, -1e-4])  # negative variance: not PD
    a1.cov_ned[bad[:2]] = np.nan
    sol = solve_array(tracks, sim["antennas"], GnssAttitudeParams())
    c = sol.counts
    assert c["antennas"]["A1"]["cov_fallback"] == bad.size
    assert 0 < c["cov_fallback"] <= bad.size
    assert all(c["antennas"][n]["cov_fallback"] == 0 for n in ("A2", "A3", "A4"))
    assert np.isfinite(sol.methods["lsq"].std_deg[sol.solved]).all()
