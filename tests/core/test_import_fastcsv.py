"""The fast CSV reader of ``hydrosync import`` against the generic reader it stands in for.

:func:`~hydrosync_core.importers.fastcsv.read_numeric_fast` must return exactly (float64
bit for bit, same column order, same sort) what ``read_numeric_csv(..., fast=False)``
returns, or None — and then ``read_numeric_csv`` falls back to the generic reading, so
every bad file gives the same one-line error whichever path reads it. Checked on varied
files (ENU and geodetic columns, CRLF, with and without a last newline, negative
numbers, many digits, exponents, unsorted, extra text columns), on each bad-input case,
on random files (hypothesis), on chunk and piece boundaries, and through
``hydrosync import`` (exit 2, one line, project untouched).
"""

from __future__ import annotations

import subprocess
import sys
import zlib

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hydrosync_core import plausible
from hydrosync_core.cli import main
from hydrosync_core.errors import InputError
from hydrosync_core.importers import csv_table, fastcsv, survey_csv
from hydrosync_core.project import Project

GNSS = dict(required=["time", "height"], optional=["lat", "lon", "quality"], min_rows=2,
            limits=plausible.GNSS)
ATT = dict(required=["time", "roll", "pitch", "heading", "heave"], min_rows=2,
           limits=plausible.ATTITUDE)
ENU = dict(required=["time", "e", "n", "u"], min_rows=2)  # tilt gnss.csv, ENU form
GEO = dict(required=["time", "lat", "lon", "height"], min_rows=2)  # tilt gnss.csv, geodetic
POINTS = dict(required=["x", "y", "z"], time_column=None, min_rows=3, limits=plausible.POINTS)


@pytest.fixture(autouse=True)
def _fast_for_every_size(monkeypatch):
    """The fast path for test-sized files too (by default it starts at 2 MiB)."""
    monkeypatch.setattr(csv_table, "FAST_MIN_BYTES", 0)


def generic(path, spec):
    return csv_table.read_numeric_csv(path, **spec, fast=False)


def routed(path, spec):
    return csv_table.read_numeric_csv(path, **spec)


def assert_same(fast: dict, slow: dict) -> None:
    assert list(fast) == list(slow)
    for key in slow:
        assert fast[key].dtype == slow[key].dtype == np.float64
        assert fast[key].tobytes() == slow[key].tobytes(), key  # bit for bit (-0.0 too)


def outcome(read, path, spec):
    try:
        return read(path, spec)
    except InputError as exc:
        return exc.one_line()


def assert_same_outcome(path, spec) -> str | None:
    """Both paths agree (equal columns or the same error line); the error line or None."""
    slow, fast = outcome(generic, path, spec), outcome(routed, path, spec)
    if isinstance(slow, str):
        assert fast == slow
        return slow
    assert not isinstance(fast, str), fast
    assert_same(fast, slow)
    return None


def _columns(rng, n, kinds):
    out = []
    for kind in kinds:
        if kind == "time":
            out.append(345600 + np.cumsum(rng.uniform(0.001, 0.02, n)))
        elif kind == "lat":
            out.append(rng.uniform(-89, 89, n))
        elif kind == "lon":
            out.append(rng.uniform(-179, 179, n))
        elif kind == "quality":
            out.append(rng.integers(0, 6, n).astype(float))
        elif kind in ("roll", "pitch"):
            out.append(rng.normal(0, 5, n))
        elif kind == "heading":
            out.append(rng.uniform(0, 360, n))
        elif kind == "heave":
            out.append(rng.normal(0, 2, n))
        else:
            out.append(rng.normal(0, 1e3, n))
    return out


FORMATS = {
    "plain": lambda v: f"{v:.4f}",
    "many digits": lambda v: f"{v:.15g}",            # 15 significant digits (compiled)
    "repr": lambda v: repr(float(v)),                # 17 digits, exponents (pyarrow)
    "exponent": lambda v: f"{v:.12e}",               # pyarrow
    "integers": lambda v: f"{round(v)}",
}


@pytest.mark.parametrize("newline", ["\n", "\r\n"])
@pytest.mark.parametrize("last_newline", [True, False])
@pytest.mark.parametrize("fmt", list(FORMATS))
@pytest.mark.parametrize("header, spec", [
    ("time,height,lat,lon,quality", GNSS),
    ("time,roll,pitch,heading,heave", ATT),
    ("time,e,n,u", ENU),
    ("time,lat,lon,height", GEO),
    ("x,y,z", POINTS),
    ("Quality, Lon,height,TIME ,lat", GNSS),                  # any order, case, spaces
])
def test_fast_path_returns_the_generic_readers_arrays(tmp_path, newline, last_newline, fmt,
                                                      header, spec):
    rng = np.random.default_rng(zlib.crc32(f"{header}{fmt}".encode()))
    names = [h.strip().lower() for h in header.split(",")]
    n = 500
    cols = _columns(rng, n, names)
    if fmt == "integers" and "time" in names:
        cols[names.index("time")] = 1000.0 + np.arange(n)
    text = newline.join(",".join(FORMATS[fmt](c[i]) if names[j] != "quality" else f"{c[i]:.0f}"
                                 for j, c in enumerate(cols)) for i in range(n))
    path = tmp_path / "t.csv"
    path.write_bytes((header + newline + text + (newline if last_newline else "")).encode())
    fast = fastcsv.read_numeric_fast(path, **spec)
    assert fast is not None  # the fast path took the file
    assert np.any(np.signbit(fast[list(fast)[1]]))  # negative numbers were in it
    assert_same(fast, generic(path, spec))


def test_compiled_parser_takes_plain_decimals_pyarrow_the_rest(tmp_path):
    plain = tmp_path / "plain.csv"
    plain.write_text("time,height\n1.5,-42.25\n2.5,-0.0\n3,7.\n")
    names, header = fastcsv._header(plain)
    assert fastcsv._read_compiled(plain, names, header, ["time", "height"],
                                  ["time", "height"], plausible.GNSS, 2) is not None
    for body in ("1.5,4.2e1\n2.5,1\n", "1.5,42.123456789012345678\n2.5,1\n", "1,2\n\n2,3\n",
                 "+1,2\n2,3\n", "1, 2\n2,3\n"):
        other = tmp_path / "other.csv"
        other.write_text("time,height\n" + body)
        names, header = fastcsv._header(other)
        assert fastcsv._read_compiled(other, names, header, ["time", "height"],
                                      ["time", "height"], plausible.GNSS, 2) is None
        assert_same_outcome(other, GNSS)


def test_unsorted_file_is_sorted_stably_on_both_paths(tmp_path):
    rng = np.random.default_rng(3)
    t = rng.permutation(np.arange(2000) * 0.01 + 100)
    path = tmp_path / "gnss.csv"
    path.write_text("time,height\n" + "".join(f"{a:.2f},{b:.4f}\n" for a, b in
                                              zip(t, rng.normal(40, 1, t.size), strict=True)))
    fast = fastcsv.read_numeric_fast(path, **GNSS)
    assert fast is not None and np.all(np.diff(fast["time"]) > 0)
    assert_same(fast, generic(path, GNSS))
    # Unsorted by a single row at a compiled chunk boundary and across the two halves.
    body = "".join(f"{i},{i % 7}\n" for i in range(3000)).splitlines(keepends=True)
    body[1500], body[1501] = body[1501], body[1500]
    body[10], body[11] = body[11], body[10]
    path.write_text("time,height\n" + "".join(body))
    assert_same(fastcsv.read_numeric_fast(path, **GNSS), generic(path, GNSS))


@pytest.mark.parametrize("chunk, piece", [(97, 64), (1 << 25, 1 << 22)])
def test_chunk_and_piece_boundaries(tmp_path, monkeypatch, chunk, piece):
    monkeypatch.setattr(fastcsv, "COMPILED_CHUNK", chunk)  # cut inside rows
    monkeypatch.setattr(fastcsv, "PIECE_BYTES", piece)
    rng = np.random.default_rng(5)
    cols = _columns(rng, 3000, ["time", "roll", "pitch", "heading", "heave"])
    for fmt in ("plain", "repr"):  # compiled, then pyarrow
        path = tmp_path / f"{fmt}.csv"
        path.write_text("time,roll,pitch,heading,heave\r\n" + "".join(
            ",".join(FORMATS[fmt](c[i]) for c in cols) + "\r\n" for i in range(3000)),
            newline="")
        assert_same(fastcsv.read_numeric_fast(path, **ATT), generic(path, ATT))


def test_keep_leaves_out_columns_but_checks_them(tmp_path):
    path = tmp_path / "attitude.csv"
    path.write_text("time,roll,pitch,heading,heave\n1,0,0,0,0.5\n2,0,0,0,-0.5\n")
    kept = fastcsv.read_numeric_fast(path, **ATT, keep=("heave",))
    assert list(kept) == ["time", "heave"]
    path.write_text("time,roll,pitch,heading,heave\n1,0,0,999,0.5\n2,0,0,0,-0.5\n")
    assert fastcsv.read_numeric_fast(path, **ATT, keep=("heave",)) is None  # heading range


@pytest.mark.parametrize("text, declined", [
    ('"time","height"\n1,2\n2,3\n', True),                 # quoted header
    ('time,height\n1,"2"\n2,3\n', True),                   # quoted value
    ("# exported by logger\ntime,height\n1,2\n2,3\n", True),  # comment before the header
    ("time,height\n1,2 # first\n2,3\n", True),             # comment after a value
    ("\ufefftime,height\n1,2\n2,3\n", True),               # byte-order mark
    ("time,height\n1,\t2\n2,3\n", True),                   # tab
    ("time,height,note\n1,2,a\x0cb\n2,3,c\n", True),       # form feed: a line break to splitlines
    ("time,height,note\n1,2,é\n2,3,c\n", True),            # non-ASCII text
    ("time,height\r1,2\r2,3\r", True),                     # old Mac line ends
    ("time,height,time\n1,2,3\n2,3,4\n", True),            # a column twice
    ("time,height,\n1,2,\n2,3,\n", True),                  # an empty column name
    ("time,height\n1,2\n\n2,3\n\n", False),                # blank lines (pyarrow skips them)
    ("time,height\n 1 , 2 \n2,3\n", False),                 # spaces around numbers (pyarrow)
    ("time,height\n1,2\n2,3", False),                       # no last newline (compiled)
])
def test_shapes_the_fast_parsers_refuse_go_to_the_generic_reader(tmp_path, text, declined):
    path = tmp_path / "gnss.csv"
    path.write_bytes(text.encode("utf-8"))
    assert (fastcsv.read_numeric_fast(path, **GNSS) is None) == declined
    assert_same_outcome(path, GNSS)  # declined: read_numeric_csv fell back to the generic


BAD = [
    ("", "file is empty"),
    ("   \n\n", "file is empty"),
    ('{"time": [1, 2], "height": [3, 4]}\n', "missing column"),  # a JSON given as CSV
    ("time,hgt\n1,42.0\n2,42.1\n", ":1: missing column(s) height"),
    ("time,height\n", "0 data row"),
    ("time,height\n1,42.0\n", "1 data row"),
    ("time,height\n1,42.0\n2,abc\n3,42.1\n", ":3: field 'height': 'abc' is not a number"),
    ("time,height\n1,42.0\n2,nan\n3,42.1\n", ":3: field 'height': value 'nan' is not finite"),
    ("time,height\n1,42.0\n2,-inf\n3,42.1\n", ":3: field 'height': value '-inf' is not fin"),
    ("time,height\n1,42.0\n2,1e400\n3,42.1\n", ":3: field 'height': value '1e400' is not fin"),
    ("time,height\n1,42.0\n2,\n3,42.1\n", ":3: field 'height': '' is not a number"),
    ("time,height\n1,42.0\n2,42.1,7\n3,42.1\n", ":3: expected 2 fields, found 3"),
    ("time,height\n1,42.0\n2\n3,42.1\n", ":3: expected 2 fields, found 1"),
    ("time,height\n1,42.0\n3,42.1\n1,42.2\n", ":4: field 'time': duplicate time 1.0 (also on "
                                              "line 2)"),
    ("time,height\n1,42.0\n2,42.1\n2,42.2\n", ":4: field 'time': duplicate time 2.0"),
    ("time,height\n1,42.0\n2,1e9\n3,42.1\n", ":3: field 'height': value 1e+09 is outside"),
    ("time,height\n1,42.0\n2,100001.5\n3,42.1\n", ":3: field 'height': value 100002 is out"),
    ("time,height,lat\n1,42.0,10\n2,42.1,91\n", ":3: field 'lat': value 91 is outside"),
    ("time,height\n1,42.0\n2,42.1\n3,42.1\n4,x\n5,1,2\n", ":6: expected 2 fields, found 3"),
    ("time,height\n1,42\n2,4.2e1\n1,42\n", ":4: field 'time': duplicate time 1.0"),
]


@pytest.mark.parametrize("text, where", BAD, ids=[w for _, w in BAD])
def test_bad_input_gives_the_same_one_line_error_on_both_paths(tmp_path, text, where):
    path = tmp_path / "gnss.csv"
    path.write_text(text)
    line = assert_same_outcome(path, GNSS)
    assert line is not None and where in line and line.startswith(str(path))
    assert "\n" not in line
    # The fast reader raises only the duplicate-time error it can word exactly (each row a
    # line on the compiled path); it leaves every other bad file to the generic reader.
    if "duplicate" in where and "e1" not in text:
        with pytest.raises(InputError) as exc:
            fastcsv.read_numeric_fast(path, **GNSS)
        assert exc.value.one_line() == line
    else:
        assert fastcsv.read_numeric_fast(path, **GNSS) is None


def test_binary_and_missing_files(tmp_path):
    path = tmp_path / "gnss.csv"
    path.write_bytes(b"time,height\n1,2\n2,\xff\n")
    assert "not UTF-8" in assert_same_outcome(path, GNSS)
    assert "no such file" in assert_same_outcome(tmp_path / "none.csv", GNSS)
    assert "is a folder" in assert_same_outcome(tmp_path, GNSS)


def test_readers_of_every_csv_kind_agree(tmp_path):
    """survey_csv readers (gnss, attitude, mbes, ins, lidar) through the routed path."""
    rng = np.random.default_rng(11)
    files = {
        "gnss": ("time,height,quality", [_columns(rng, 300, ["time", "height"]),
                                         [np.full(300, 4.0)]]),
        "attitude": ("time,roll,pitch,heading,heave",
                     [_columns(rng, 300, ["time", "roll", "pitch", "heading", "heave"])]),
        "mbes": ("time,x,y,z", [[np.repeat(np.arange(100.0), 3)[::-1]],
                                _columns(rng, 300, ["x", "y", "z"])]),
        "ins": ("time,e,n,u,roll,pitch,heading",
                [_columns(rng, 300, ["time", "e", "n", "u", "roll", "pitch", "heading"])]),
        "lidar": ("x,y,z", [_columns(rng, 300, ["x", "y", "z"])]),
    }
    for kind, (header, parts) in files.items():
        cols = [c for part in parts for c in part]
        path = tmp_path / f"{kind}.csv"
        path.write_text(header + "\n" + "".join(",".join(f"{c[i]:.5f}" for c in cols) + "\n"
                                                for i in range(300)))
        reader = getattr(survey_csv, f"read_{kind}_csv")
        fast = reader(path)
        with pytest.MonkeyPatch.context() as patch:
            patch.setattr(csv_table, "FAST_MIN_BYTES", 1 << 62)  # the generic reader
            slow = reader(path)
        if isinstance(slow, dict):
            assert_same(fast, slow)
        else:
            assert fast.tobytes() == slow.tobytes()


# Random files: every outcome (columns or error line) equal on both paths.
_CELLS = ["0", "-0", "1.5", "-12.25", "7.", "1e3", "4.2E-1", "nan", "inf", "", " 3", "x",
          "12345678901234567890", "0.000000000000000000001", "1e400", "91", "-1e9", "3.0",
          "2", "1"]
cell = st.one_of(st.sampled_from(_CELLS),
                 st.floats(-1e5, 1e5, allow_nan=False).map(lambda v: f"{v:.4f}"),
                 st.floats(-1e5, 1e5, allow_nan=False).map(lambda v: repr(float(v))))


@settings(max_examples=150, deadline=None, database=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(header=st.sampled_from(["time,height", "height,time,lat", "time,height,note",
                               "TIME,Height,quality"]),
       rows=st.lists(st.lists(cell, min_size=1, max_size=4), max_size=12),
       newline=st.sampled_from(["\n", "\r\n"]), last=st.booleans())
def test_random_files_same_outcome(tmp_path_factory, header, rows, newline, last):
    path = tmp_path_factory.mktemp("fuzz") / "gnss.csv"
    body = newline.join(",".join(r) for r in rows)
    path.write_bytes((header + newline + body + (newline if last else "")).encode())
    assert_same_outcome(path, GNSS)


def _day(tmp_path, rows: int):
    """An attitude file above the fast path's size floor (about 45 bytes a row)."""
    rng = np.random.default_rng(2)
    cols = _columns(rng, rows, ["time", "roll", "pitch", "heading", "heave"])
    lines = ["time,roll,pitch,heading,heave"] + [
        ",".join(f"{c[i]:.4f}" for c in cols) for i in range(rows)]
    return lines


@pytest.mark.parametrize("damage, message", [
    (lambda ls: ls.__setitem__(40000, ls[40000] + ",1"), ":40001: expected 5 fields, found 6"),
    (lambda ls: ls.__setitem__(50000, ",".join(ls[50000].split(",")[:2] + ["nan", "0", "0"])),
     ":50001: field 'pitch': value 'nan' is not finite"),
    (lambda ls: ls.__setitem__(50001, ls[20000]), ":50002: field 'time': duplicate time"),
    (lambda ls: ls.__setitem__(60000, ls[60000].split(",", 1)[0] + ",200,0,0,0"),
     ":60001: field 'roll': value 200 is outside"),
])
def test_import_command_bad_large_file_exit_2_project_untouched(tmp_path, monkeypatch,
                                                                capsys, damage, message):
    """Through ``hydrosync import`` at the default size floor: one line, exit 2, the
    project file byte for byte as before."""
    monkeypatch.setattr(csv_table, "FAST_MIN_BYTES", 1 << 21)
    lines = _day(tmp_path, 70000)
    project = tmp_path / "p.h5"
    assert main(["new", str(project)]) == 0
    before = project.read_bytes()
    damage(lines)
    path = tmp_path / "attitude.csv"
    path.write_text("\n".join(lines) + "\n")
    assert path.stat().st_size > csv_table.FAST_MIN_BYTES
    capsys.readouterr()
    assert main(["import", str(project), "--attitude", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "Traceback" not in err
    assert str(path) in err and message in err, err
    assert project.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["attitude.csv", "p.h5"]


def test_import_command_large_file_stores_the_generic_readers_arrays(tmp_path, monkeypatch):
    monkeypatch.setattr(csv_table, "FAST_MIN_BYTES", 1 << 21)
    lines = _day(tmp_path, 70000)
    lines[1:] = lines[:0:-1]  # reversed: the import sorts
    path = tmp_path / "attitude.csv"
    path.write_text("\r\n".join(lines))
    project = tmp_path / "p.h5"
    code = subprocess.run([sys.executable, "-m", "hydrosync_core.cli", "import", str(project),
                           "--attitude", str(path), "--heave-positive", "down"],
                          capture_output=True, text=True)
    assert code.returncode == 0, code.stderr
    reference = generic(path, ATT)
    reference["heave"] = -reference["heave"]
    with Project.open(project, readonly=True) as p:
        stored = p.get_table("raw/attitude")
    assert list(stored) == list(reference)
    for key in reference:
        assert np.asarray(stored[key]).tobytes() == reference[key].tobytes()


@pytest.mark.parametrize("block", [1, 2, 3])
def test_generic_field_count_in_blocks_of_lines(tmp_path, monkeypatch, block):
    """The generic reader counts commas a block of lines at a time (its memory on a large
    bad file): the same outcome whatever the block."""
    path = tmp_path / "gnss.csv"
    for text, _ in BAD + [("time,height\n1,2\n2,3\n\n4\n5,6", None),
                          ("time,height\r\n1,2\r\n2,3,4\r\n", None)]:
        path.write_text(text)
        expected = outcome(generic, path, GNSS)
        with pytest.MonkeyPatch.context() as patch:
            patch.setattr(csv_table, "COUNT_BLOCK", block)
            got = outcome(generic, path, GNSS)
        if isinstance(expected, str):
            assert got == expected
        else:
            assert_same(got, expected)


def _prescan(path, spec, keep=None):
    optional = spec.get("optional", ())
    return fastcsv.Prescan(path, spec["required"], optional,
                           time_column=spec.get("time_column", "time"), keep=keep)


@pytest.mark.parametrize("last", ["\n", ""])
def test_prescan_saves_the_count_and_changes_nothing(tmp_path, monkeypatch, last):
    monkeypatch.setattr(fastcsv, "PRESCAN_CHUNK", 61)  # many reads, cut inside rows
    rng = np.random.default_rng(11)
    cols = _columns(rng, 2500, ["time", "roll", "pitch", "heading", "heave"])
    path = tmp_path / "attitude.csv"
    path.write_text("time,roll,pitch,heading,heave\n" + "\n".join(
        ",".join(FORMATS["plain"](c[i]) for c in cols) for i in range(2500)) + last)
    keep = ("time", "heave")
    scan = _prescan(path, ATT, keep)
    kernels = fastcsv._compiled()
    counted = []
    monkeypatch.setattr(fastcsv, "_kernels",
                        [lambda *a: counted.append(1) or kernels[0](*a), kernels[1]])
    fast = fastcsv.read_numeric_fast(path, **ATT, keep=keep, prescan=scan)
    assert counted == []  # the prescan's count was used
    slow = generic(path, ATT)
    assert_same(fast, {k: slow[k] for k in ("time", "heave")})
    assert scan.take() is None  # used once


def test_prescan_of_other_columns_or_a_changed_file_is_not_used(tmp_path, monkeypatch):
    path = tmp_path / "gnss.csv"
    path.write_text("time,height\n" + "".join(f"{i}.5,{i % 9}.25\n" for i in range(400)))
    kernels = fastcsv._compiled()
    counted = []
    monkeypatch.setattr(fastcsv, "_kernels",
                        [lambda *a: counted.append(1) or kernels[0](*a), kernels[1]])
    scan = _prescan(path, GNSS, keep=("time",))  # other columns than read below
    assert_same(fastcsv.read_numeric_fast(path, **GNSS, prescan=scan), generic(path, GNSS))
    assert counted
    counted.clear()
    scan = _prescan(path, GNSS)
    scan._thread.join()
    with open(path, "a") as fh:  # one row more after the count
        fh.write("400.5,1.25\n")
    fast = fastcsv.read_numeric_fast(path, **GNSS, prescan=scan)
    assert counted and fast["time"].size == 401
    assert_same(fast, generic(path, GNSS))


def test_stale_counts_never_write_past_the_columns(tmp_path):
    """A file rewritten in place (same size and time stamp) after its rows were counted:
    the parser stops at the end of the columns and leaves the file to the other readers."""
    path = tmp_path / "gnss.csv"
    path.write_text("time,height\n" + "".join(f"{i}.5,{i % 9}.25\n" for i in range(400)))
    names, header = fastcsv._header(path)
    plan = fastcsv._plan(path, ["time", "height"], [], "time", None)
    short = fastcsv._Plan(plan.identity, plan.header_bytes, plan.keep, plan.mid,
                          (plan.counts[0] - 3, plan.counts[1] - 3), plan.rows_total - 6,
                          plan.out[:, :plan.rows_total - 6].copy())
    stale = type("StalePrescan", (), {"take": lambda self: short})()
    assert fastcsv._read_compiled(path, names, header, ["time", "height"], ["time", "height"],
                                  plausible.GNSS, 2, stale) is None
    data = np.frombuffer(path.read_bytes(), dtype=np.uint8)
    out = np.full((2, 5), 7.0)
    parse = fastcsv._compiled()[1]
    rows, status = parse(data, header, data.size, 2, np.array([0, 1]), out[:, :4], 0,
                         np.full(2, -np.inf), np.full(2, np.inf), fastcsv._POW10)
    assert (rows, status) == (4, 1) and np.all(out[:, 4] == 7.0)  # nothing past row 4


@pytest.mark.parametrize("text", ["", "time,height\n", "time;height\n1;2\n", None])
def test_prescan_of_a_bad_or_missing_file_is_harmless(tmp_path, text):
    path = tmp_path / "gnss.csv"
    if text is not None:
        path.write_text(text)
    scan = _prescan(path, GNSS)
    assert outcome(lambda p, s: fastcsv.read_numeric_fast(p, **s, prescan=scan) or
                   generic(p, s), path, GNSS) == outcome(generic, path, GNSS)


def test_columns_are_ordinary_writable_arrays(tmp_path):
    """The parsed columns live in an anonymous map (4 KiB pages, see _empty_columns): still
    plain writable, contiguous float64 arrays, like the generic reader's."""
    path = tmp_path / "gnss.csv"
    path.write_text("time,height\n" + "".join(f"{i}.5,{i % 9}.25\n" for i in range(50)))
    for column in fastcsv.read_numeric_fast(path, **GNSS).values():
        assert column.dtype == np.float64 and column.flags.c_contiguous
        assert column.flags.writeable
        column[0] = 1.0
    block = fastcsv._empty_columns(0, 0)
    assert block.shape == (0, 0) and block.dtype == np.float64
