"""Issue #6/#7 of #9: hostile files and impossible values end with exit 2 and one line.

The corpus is built by ``scripts/build_hostile_corpus.py``: LAZ chunk tables that make
the LAZ decoder abort or panic, a 200 000-character CSV field, a 400-digit JSON integer,
JSON nested 100 000 deep, a PLY ``element vertex many``, roll 1e308, LAS scale 1e300, PLY
vertex 1e308, rows with extra fields, duplicated and overlapping survey lines, binary
garbage. Each import must exit 2 with exactly one line on stderr that quotes at most
~120 characters of the file, and leave no project behind.
"""

from __future__ import annotations

import pytest

from hydrosync_core.cli import main
from hydrosync_core.errors import InputError
from hydrosync_core.importers import pointcloud
from tests.reliability.conftest import load_script, run_cli, stderr_lines

hostile = load_script("build_hostile_corpus")
NAMES = [name for name, _, _ in hostile.cases()]


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    folder = tmp_path_factory.mktemp("hostile")
    return {path.name: (kind, path) for kind, path in hostile.build_corpus(folder)}


def _quotes_too_much(message: str, content: bytes) -> bool:
    """True if *message* contains a run of more than 120 characters of *content*."""
    text = content.decode("utf-8", "replace")
    return any(message[start:start + 121] in text
               for start in range(0, max(len(message) - 120, 0)))


@pytest.mark.parametrize("name", NAMES)
def test_hostile_file_is_exit_2_with_one_line(corpus, name, tmp_path, capsys, faults):
    kind, path = corpus[name]
    project = tmp_path / "p.h5"
    code = main(["import", str(project), f"--{kind}", str(path)])
    captured = capsys.readouterr()
    lines = stderr_lines(captured.err)
    ok = (code == 2 and len(lines) == 1 and len(lines[0]) <= 400 and path.name in lines[0]
          and not _quotes_too_much(lines[0], path.read_bytes()) and not project.exists())
    faults.record(f"hostile file: {kind}", ok, f"{name}: {code} {lines}")
    assert ok, (code, lines)


@pytest.mark.parametrize("name", ["laz-chunk-entries.laz", "laz-chunk-count.laz",
                                  "laz-truncated.laz", "csv-header-only.csv",
                                  "ply-no-vertices.ply"])
def test_one_line_in_a_real_process(corpus, name, tmp_path, faults):
    """No Rust backtrace, no traceback, no library warning: the real stderr holds one line."""
    kind, path = corpus[name]
    done = run_cli("import", tmp_path / "p.h5", f"--{kind}", path)
    lines = stderr_lines(done.stderr)
    ok = done.returncode == 2 and len(lines) == 1 and path.name in lines[0]
    faults.record("hostile file: in a real process", ok, done.stderr[-300:])
    assert ok, done.stderr


def test_decoder_abort_in_the_child_becomes_input_error(corpus, monkeypatch, faults):
    """Without the chunk-table check the decoder aborts (SIGABRT): the child absorbs it."""
    _, path = corpus["laz-chunk-count.laz"]
    monkeypatch.setattr(pointcloud, "_check_chunk_table", lambda *a: None)
    with pytest.raises(InputError) as caught:
        pointcloud.read_point_cloud(path)
    ok = "decoder crashed" in caught.value.message
    faults.record("hostile file: LAZ decoder abort in the child", ok, caught.value.message)
    assert ok, caught.value.message


def test_vessel_set_rejects_impossible_offsets(tmp_path, capsys, faults):
    from hydrosync_core.project import Project

    path = tmp_path / "p.h5"
    Project.new("v").save(path)
    code = main(["vessel", str(path), "--set", "gnss", "1e308", "0", "0"])
    lines = stderr_lines(capsys.readouterr().err)
    ok = code == 2 and len(lines) == 1 and "plausible range" in lines[0]
    faults.record("impossible value: vessel --set", ok, str(lines))
    assert ok, lines


def test_ins_and_mbes_ranges(tmp_path):
    from hydrosync_core.importers.survey_csv import read_ins_csv, read_mbes_csv

    ins = tmp_path / "ins.csv"
    ins.write_text("time,e,n,u,roll,pitch,heading\n0,1,2,3,0,0,0\n1,1,2,3,0,95,0\n")
    with pytest.raises(InputError, match="pitch.*outside the plausible range"):
        read_ins_csv(ins)
    mbes = tmp_path / "mbes.csv"
    mbes.write_text("time,x,y,z\n0,1,2,3\n0,1,2,3\n1,1,2,1e300\n")
    with pytest.raises(InputError, match="line 4|:4:"):
        read_mbes_csv(mbes)


def test_rtklib_pos_with_a_huge_token_quotes_little(tmp_path, faults):
    from hydrosync_core.importers.rtklib_pos import read_pos

    path = tmp_path / "A1.pos"
    big = "7" * 200_000
    path.write_text(f"% legend\n{big} x 1 2 3 4 5\n2000 1.0 {big}.5 1 2 3 4 5\n")
    with pytest.raises(InputError) as caught:
        read_pos(path)
    line = caught.value.one_line()
    ok = len(line) <= 400 and "7" * 121 not in line
    faults.record("hostile file: rtklib .pos", ok, line[:200])
    assert ok, line[:200]
