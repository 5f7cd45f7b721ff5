"""Bad input for every formats.md CSV reader: one clear line naming file, line, field."""

from __future__ import annotations

import numpy as np
import pytest

from hydrosync_core.errors import InputError
from hydrosync_core.importers import survey_csv


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_gnss_reads_sorts_and_keeps_optional_columns(tmp_path):
    path = _write(tmp_path, "gnss.csv",
                  "time,height,quality,extra\n2.0,10.5,4,x\n1.0,10.4,4,y\n3.0,10.6,5,z\n")
    table = survey_csv.read_gnss_csv(path)
    assert list(table) == ["time", "height", "quality"]
    np.testing.assert_array_equal(table["time"], [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(table["height"], [10.4, 10.5, 10.6])


@pytest.mark.parametrize(
    ("reader", "text", "pattern"),
    [
        (survey_csv.read_gnss_csv, "", "file is empty"),
        (survey_csv.read_gnss_csv, "time,lat\n1,2\n", r"gnss.csv:1: missing column\(s\) height"),
        (survey_csv.read_gnss_csv, "time,height\n1,2\n2,abc\n",
         r"gnss.csv:3: field 'height': 'abc' is not a number"),
        (survey_csv.read_gnss_csv, "time,height\n1,2\n2,nan\n",
         r"gnss.csv:3: field 'height': value 'nan' is not finite"),
        (survey_csv.read_gnss_csv, "time,height\n1,2\n2,3\n1,4\n",
         r"gnss.csv:4: field 'time': duplicate time 1.0 \(also on line 2\)"),
        (survey_csv.read_gnss_csv, "time,height\n1,2\n2\n",
         "gnss.csv:3: expected 2 fields, found 1"),
        (survey_csv.read_gnss_csv, "time,height\n1,2\n", "1 data row"),
        (survey_csv.read_attitude_csv, "time,roll,pitch,heading\n1,2,3,4\n",
         r"missing column\(s\) heave"),
        (survey_csv.read_attitude_csv, "time,roll,pitch,heading,heave\n1,2,3,4,5\n2,2,inf,4,5\n",
         "field 'pitch': value 'inf' is not finite"),
        (survey_csv.read_lines_csv, "name,start,end\nL1,10,5\n", "end 5.0 is not after start 10.0"),
        (survey_csv.read_lines_csv, "name,start,end\nL1,1,5\nL1,6,9\n",
         "line name 'L1' already used on line 2"),
        (survey_csv.read_lines_csv, "name,start\nL1,1\n", "missing column end"),
        (survey_csv.read_lines_csv, "name,start,end\n", "no survey lines"),
        (survey_csv.read_mbes_csv, "time,x,y\n1,2,3\n", r"missing column\(s\) z"),
        (survey_csv.read_ins_csv, "time,e,n,u,roll,pitch,heading\n1,0,0,0,0,0,0\n1,0,0,0,0,0,0\n",
         "duplicate time"),
        (survey_csv.read_lidar_csv, "x,y,z\n1,2,3\n", "1 data row"),
    ],
)
def test_bad_input_names_file_line_and_problem(tmp_path, reader, text, pattern):
    name = {
        survey_csv.read_gnss_csv: "gnss.csv", survey_csv.read_attitude_csv: "attitude.csv",
        survey_csv.read_lines_csv: "lines.csv", survey_csv.read_mbes_csv: "mbes.csv",
        survey_csv.read_ins_csv: "ins.csv", survey_csv.read_lidar_csv: "lidar.csv",
    }[reader]
    path = _write(tmp_path, name, text)
    with pytest.raises(InputError, match=pattern) as info:
        reader(path)
    message = info.value.one_line()
    assert "\n" not in message and str(path) in message


def test_missing_file_and_binary_file(tmp_path):
    with pytest.raises(InputError, match="no such file"):
        survey_csv.read_gnss_csv(tmp_path / "absent.csv")
    binary = tmp_path / "bin.csv"
    binary.write_bytes(b"time,height\n\xff\xfe\x00\x01")
    with pytest.raises(InputError, match="not a text file"):
        survey_csv.read_gnss_csv(binary)


def test_mbes_keeps_beams_of_one_ping_in_order(tmp_path):
    path = _write(tmp_path, "mbes.csv", "time,x,y,z\n2,0,1,5\n1,0,-1,5\n1,0,1,5\n2,0,-1,5\n")
    table = survey_csv.read_mbes_csv(path)
    np.testing.assert_array_equal(table["time"], [1, 1, 2, 2])
    np.testing.assert_array_equal(table["y"], [-1, 1, 1, -1])


def test_heave_sign_is_explicit(tmp_path):
    path = _write(tmp_path, "attitude.csv",
                  "time,roll,pitch,heading,heave\n1,0,0,0,0.25\n2,0,0,0,-0.5\n")
    np.testing.assert_array_equal(survey_csv.read_attitude_csv(path)["heave"], [0.25, -0.5])
    down = survey_csv.read_attitude_csv(path, heave_positive="down")
    np.testing.assert_array_equal(down["heave"], [-0.25, 0.5])
    with pytest.raises(InputError, match="heave sign must be 'up' or 'down'"):
        survey_csv.read_attitude_csv(path, heave_positive="sideways")
