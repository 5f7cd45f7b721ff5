"""Streaming NMEA log import: block boundaries anywhere, several files per kind, cancel.

The reference is reading a file as one block: every block size must give the same
report and the same columns. The real-log corpus must give the counts, warnings and
values recorded from the importer before streaming (``data/real_log_imports.json``,
written by ``scripts/log_import_golden.py``).
"""

from __future__ import annotations

import json
import random
import threading
from functools import reduce
from pathlib import Path

import numpy as np
import pytest

from hydrosync_core.errors import Cancelled, InputError
from hydrosync_core.importers import log_stream
from hydrosync_core.importers.kinds import import_file
from hydrosync_core.importers.log_import import import_attitude_log, import_gnss_log
from hydrosync_core.project import Project
from hydrosync_core.project.table_files import read_window, table_length
from tests.core._real_logs import REAL, needs_real

GOLDEN = Path(__file__).parent / "data" / "real_log_imports.json"


def nmea(body: str, wrong: bool = False) -> str:
    return f"${body}*{reduce(lambda a, c: a ^ ord(c), body, 0) ^ int(wrong):02X}"


def hms(t: float) -> str:
    h, rem = divmod(t % 86400, 3600)
    m, s = divmod(rem, 60)
    return f"{int(h):02d}{int(m):02d}{s:06.3f}"


def tag(t: float) -> str:
    h, rem = divmod(t % 86400, 3600)
    m, s = divmod(rem, 60)
    return f"2024-05-01T{int(h):02d}:{int(m):02d}:{s:09.6f}Z "


def awkward_log(seconds: float, t0: float = 0.0, seed: int = 1) -> bytes:
    """A tagged log with everything a block boundary could cut: CRLF and LF endings,
    GGA + GST (σ matched across lines), ZDA dates, PSXN,23 with PSXN,20 quality going
    invalid, binary runs holding ``\\n``, ``\\r`` and ``$``, bad checksums, spliced
    fragments, comments, and a last sentence cut in the middle."""
    rng = random.Random(seed)
    out = []
    t = t0
    k = 0
    while t < t0 + seconds:
        end = "\r\n" if k % 3 else "\n"
        if k % 50 == 0:
            out.append(tag(t) + nmea(f"GPZDA,{hms(t)},01,05,2024,00,00") + end)
            out.append(tag(t) + nmea(f"PSXN,20,0,0,0,{2 if (k // 500) % 4 == 3 else 0}") + end)
        if k % 10 == 0:
            alt = f"{10 + 0.1 * np.sin(t):.3f}"
            out.append(tag(t) + nmea(f"GPGGA,{hms(t)},4530.0000,S,17030.0000,E,4,12,0.8,"
                                     f"{alt},M,-30.000,M,,") + end)
            if k % 20 == 0:
                out.append(tag(t) + nmea(f"GPGST,{hms(t)},0.5,0.1,0.1,0,0.02,0.02,0.0{k % 7 + 1}")
                           + end)
        out.append(tag(t) + nmea(f"PSXN,23,{rng.uniform(-5, 5):.2f},{rng.uniform(-2, 2):.2f},"
                                 f"{rng.uniform(0, 360):.2f},{rng.uniform(-1, 1):.3f}",
                                 wrong=k % 97 == 5) + end)
        if k % 131 == 7:
            blob = bytes(rng.randrange(256) for _ in range(40)) + b"\n$\r\n\xb5b"
            out.append(blob.decode("latin-1") + "\n")
        if k % 173 == 11:
            out.append(tag(t) + "$GPGGA,12345" + nmea(f"PSXN,23,0.1,0.2,3.0,{k * 1e-4:.4f}")
                       + end)
        if k % 211 == 0:
            out.append("# logger restarted\n")
        t = round(t + 0.02, 6)
        k += 1
    out.append(tag(t) + "$GPGGA,000000.00,4530.0")
    return "".join(out).encode("latin-1")


def _same(a, b) -> None:
    cols_a, rep_a = a
    cols_b, rep_b = b
    assert rep_a.to_dict() == rep_b.to_dict()
    assert list(cols_a) == list(cols_b)
    for name in cols_a:
        np.testing.assert_array_equal(cols_a[name], cols_b[name])


@pytest.mark.parametrize("block", [997, 4096, 65536])
def test_any_block_size_gives_the_whole_file_answer(tmp_path, monkeypatch, block):
    """Blocks of 997 bytes cut inside sentences, CRLF pairs and binary runs many times
    (a cut every ~12 lines: ~1000 cuts in this 1 MB file)."""
    path = tmp_path / "day.log"
    path.write_bytes(awkward_log(150.0))
    whole = (import_gnss_log(path), import_attitude_log(path, "down"))
    monkeypatch.setattr(log_stream, "BLOCK_BYTES", block)
    _same(import_gnss_log(path), whole[0])
    _same(import_attitude_log(path, "down"), whole[1])
    gnss, rep = whole[0]
    # what the log holds: 5 Hz GGA, σ on every other epoch, one cut GGA at the end
    assert rep.used == 750 and np.isfinite(gnss["sigma_h"]).sum() == 375
    assert rep.skipped["missing checksum"] == 1 and rep.skipped["binary"] > 0
    att, arep = whole[1]
    # three 10 s stretches of invalid quality at 50 Hz, less the bad checksums in them
    assert 1490 <= arep.skipped["PSXN,23: roll/pitch quality invalid (PSXN,20)"] <= 1500
    assert arep.skipped["bad checksum"] == len(range(5, 7500, 97))


@needs_real
def test_real_corpus_counts_warnings_and_values_as_before(monkeypatch):
    """Every corpus log, read in 64 KiB blocks, as the whole-file importer read it."""
    monkeypatch.setattr(log_stream, "BLOCK_BYTES", 1 << 16)
    golden = json.loads(GOLDEN.read_text())
    for key, want in golden.items():
        rel, what, options = key.split("|")
        func = import_gnss_log if what == "gnss" else import_attitude_log
        try:
            cols, rep = func(REAL / rel, **json.loads(options))
        except InputError as exc:
            assert {"error": str(exc).replace(str(REAL), "<root>")} == want, key
            continue
        got = {**rep.to_dict(), "file": rel}
        got = json.loads(json.dumps(got))
        lag_want = want["report"].pop("logger_minus_sentence_s")
        lag_got = got.pop("logger_minus_sentence_s")
        assert got == want["report"], key
        assert lag_got == pytest.approx(lag_want, abs=1e-9), key
        assert sorted(cols) == sorted(want["columns"]), key
        for name, (n, finite, total, first, last) in want["columns"].items():
            v = cols[name][np.isfinite(cols[name])]
            assert (cols[name].size, v.size) == (n, finite), (key, name)
            assert v.sum() == pytest.approx(total, rel=1e-12, abs=1e-12), (key, name)
            if v.size:
                assert (v[0], v[-1]) == (first, last), (key, name)


def _split_hours(tmp_path: Path, n: int) -> tuple[Path, list[Path]]:
    whole = tmp_path / "whole.log"
    parts = [awkward_log(40.0, t0=40.0 * j, seed=j) for j in range(n)]
    # keep each part's cut last line off: the whole file is the parts joined
    parts = [p[: p.rfind(b"\n") + 1] for p in parts]
    whole.write_bytes(b"".join(parts))
    files = []
    for j, data in enumerate(parts):
        f = tmp_path / f"hour{j:02d}.log"
        f.write_bytes(data)
        files.append(f)
    return whole, files


def test_hourly_files_out_of_order_make_the_whole_day(tmp_path):
    whole, files = _split_hours(tmp_path, 4)
    shuffled = [files[2], files[0], files[3], files[1]]
    one, several = Project.new(), Project.new()
    import_file(one, "attitude_log", whole, heave_positive="down")
    import_file(several, "attitude_log", shuffled, heave_positive="down")
    a, b = one.get_table("raw/attitude"), several.get_table("raw/attitude")
    for name in a:
        np.testing.assert_array_equal(a[name], b[name])
    entries = json.loads(several.attrs("raw/attitude")["imports"])
    assert sorted(e["file"] for e in entries) == [f.name for f in files]
    # a glob gives the same table
    globbed = Project.new()
    import_file(globbed, "gnss_log", str(tmp_path / "hour*.log"))
    import_file(one, "gnss_log", whole)
    np.testing.assert_array_equal(globbed.get_table("raw/gnss")["time"],
                                  one.get_table("raw/gnss")["time"])


def test_overlapping_files_interleave_and_a_repeated_epoch_names_both(tmp_path):
    a = tmp_path / "a.log"
    b = tmp_path / "b.log"
    a.write_bytes(awkward_log(30.0, t0=0.0))
    b.write_bytes(awkward_log(30.0, t0=20.01, seed=2))  # 10 s overlap, other epochs
    project = Project.new()
    message = import_file(project, "attitude_log", [a, b], heave_positive="up")
    assert "b.log overlaps a.log by 10.0 s" in message
    t = project.get_table("raw/attitude")["time"]
    assert np.all(np.diff(t) > 0)
    c = tmp_path / "c.log"
    c.write_bytes(awkward_log(30.0, t0=20.0, seed=3))  # same epochs as a from 20 s
    with pytest.raises(InputError) as err:
        import_file(project, "attitude_log", [a, c], heave_positive="up")
    assert "a.log" in str(err.value) and "c.log" in str(err.value)
    assert np.array_equal(project.get_table("raw/attitude")["time"], t)  # unchanged


def test_gap_between_files_is_reported(tmp_path):
    a = tmp_path / "a.log"
    b = tmp_path / "b.log"
    a.write_bytes(awkward_log(20.0, t0=0.0))
    b.write_bytes(awkward_log(20.0, t0=80.0, seed=2))
    message = import_file(Project.new(), "gnss_log", [b, a])
    assert "gap of 60.2 s between a.log and b.log" in message


def test_cancel_mid_import_leaves_the_saved_project_as_it_was(tmp_path, monkeypatch):
    """Cancel (the GUI button; Ctrl-C raises in the same place) after the first blocks."""
    monkeypatch.setattr(log_stream, "BLOCK_BYTES", 4096)
    log = tmp_path / "day.log"
    log.write_bytes(awkward_log(60.0))
    path = tmp_path / "P.h5"
    project = Project.create(path)
    import_file(project, "gnss_log", log)
    project.save()
    before = path.read_bytes()
    cancel = threading.Event()
    calls = []

    def progress(fraction, message=""):
        calls.append(fraction)
        if len(calls) == 5:
            cancel.set()

    gnss = project.get_table("raw/gnss")
    with pytest.raises(Cancelled):
        import_file(project, "attitude_log", log, heave_positive="up", progress=progress,
                    cancel=cancel)
    assert not project.exists("raw/attitude")
    np.testing.assert_array_equal(project.get_table("raw/gnss")["time"], gnss["time"])
    project.close()
    assert path.read_bytes() == before
    assert not list(tmp_path.glob(".hydrosync-import-*"))


def test_streamed_table_saves_compressed_and_reads_by_window(tmp_path):
    log = tmp_path / "day.log"
    log.write_bytes(awkward_log(60.0))
    path = tmp_path / "P.h5"
    project = Project.create(path)
    import_file(project, "attitude_log", log, heave_positive="up")
    memory = project.get_table("raw/attitude")
    project.save()
    again = Project.open(path, readonly=True)
    table = again.get_table("raw/attitude")
    for name in memory:
        np.testing.assert_array_equal(memory[name], table[name])
    n = table_length(again, "raw/attitude")
    assert n == table["time"].size
    t = table["time"]
    window = read_window(again, "raw/attitude", t[100], t[200], columns=["time", "heave"])
    np.testing.assert_array_equal(window["time"], t[100:201])
    np.testing.assert_array_equal(window["heave"], table["heave"][100:201])
    again.close()
    project.close()


TRICKY = [
    "$GPGGA,1,2*5A", "$GPGGA,1,2", "  $GPGGA,1,2*5a  \r", "$GPGGA,1\r,2*00", "$GPGGA,1\t,2*00",
    "$GPGGA,a*b*12", "$GPGGA,1*4", "$GPGGA,1*", "$GP,1*00", "$GPGGAXXX,1*00", "$gpgga,1*00",
    "$GPGGA,1*00$GPZDA,2*00", "!AIVDM,1*00", "#$GPGGA,1*00", "{\"a\":1}", "   ", "\r",
    "2014-08-01T00:00:00.814000Z $GPGGA,1*00", "2014-08-01 00:00:00Z, $GPGGA,1*00",
    "2014-02-30T00:00:00Z $GPGGA,1*00", "2014-08-01T24:00:00Z $GPGGA,1*00",
    "08/01/2014,12:34:56.789, $GPGGA,1*00", "08/01/2014 12:34:56 $GPGGA,1*00",
    "1535243706.515 $GPGGA,1*00", "1535243706. $GPGGA,1*00", "15352437 $GPGGA,1*00",
    "1535243706.5x $GPGGA,1*00", "junk $GPGGA,1*00", "\x01\x02$GPGGA,1*00",
    ":000064 -0003U 0007 -0056", "12345.6 :000064 -0003U 0007 -0056",
    "$PTNL,GGK,1,2*00", "$PTNL*00", "$GPGGA,1,2*5A\xff", "\x01$GPGGA,1*00\r",
    "$GPGGA,1\r,2*00\r", "$GPGGA,\x85,2*00 \t\r",
]


def test_kernel_splits_every_line_as_the_regex_splitter_does():
    """The compiled scanner and the regex splitter on lines built to sit on each of the
    kernel's rules (and the awkward log): same sentences, tags, checksum states, counts."""
    import numpy as np

    from hydrosync_core.importers import nmea_lines as nl

    rng = random.Random(5)
    lines = [line.replace("*00", "*" + format(
        reduce(lambda a, c: a ^ ord(c), line[line.find("$") + 1:line.find("*")], 0), "02X"))
        if rng.random() < 0.5 else line for line in TRICKY]
    data = ("\n".join(lines) + "\n").encode("latin-1") + awkward_log(20.0)
    raw = nl.scan_block(np.frombuffer(data, np.uint8))
    found = nl._Found()
    cache: dict = {}
    texts = data.decode("latin-1").split("\n")  # the last line has no newline
    for number, text in enumerate(texts, start=1):
        nl._regex_line(text, number, found, cache)
    body = raw.buf.tobytes()
    assert [body[a:b].decode("latin-1") for a, b in zip(raw.start, raw.end, strict=True)] \
        == found.body
    assert raw.line_no.tolist() == found.line
    np.testing.assert_array_equal(raw.tag, np.array(found.tag))
    given = raw.cs != 2
    assert given.tolist() == [c is not None for c in found.cs]
    counts = {k: v for k, v in raw.counts.items() if k != "lines"}
    assert counts == found.counts and raw.styles == found.styles
    assert raw.odd_prefix == found.odd_prefix


def test_ctrl_c_mid_import_leaves_the_project_and_no_scratch(tmp_path, monkeypatch):
    """Ctrl-C raises KeyboardInterrupt wherever the import is: here from inside the
    progress report of the fourth block of the attitude pass."""
    monkeypatch.setattr(log_stream, "BLOCK_BYTES", 8192)
    log = tmp_path / "day.log"
    log.write_bytes(awkward_log(40.0))
    path = tmp_path / "P.h5"
    project = Project.create(path)
    import_file(project, "gnss_log", log)
    project.save()
    before = path.read_bytes()
    calls = []

    def progress(fraction, message=""):
        calls.append(message)
        if sum("MB read" in m for m in calls) == 4:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        import_file(project, "attitude_log", log, heave_positive="up", progress=progress)
    assert not project.exists("raw/attitude") and not project.dirty
    project.close()
    assert path.read_bytes() == before
    assert not list(tmp_path.glob(".hydrosync-import-*"))


def test_bad_file_names_are_one_line_errors_naming_them(tmp_path):
    empty = tmp_path / "empty.log"
    empty.write_bytes(b"")
    good = tmp_path / "good.log"
    good.write_bytes(awkward_log(10.0))
    cases = {
        str(tmp_path / "nothing-*.log"): "matches no file",
        str(empty): "file is empty",
        str(tmp_path / "missing.log"): "no such file",
        str(tmp_path): "is a folder",
    }
    project = Project.new()
    for name, why in cases.items():
        with pytest.raises(InputError) as err:
            import_file(project, "gnss_log", [str(good), name])
        text = str(err.value)
        assert why in text and Path(name).name in text and "\n" not in text
    assert not project.exists("raw/gnss")


@pytest.mark.parametrize("hourly", [False, True])
def test_one_pass_for_gnss_and_attitude_of_the_same_files(tmp_path, monkeypatch, hourly):
    """``hydrosync import --gnss-log F --attitude-log F`` reads F once for both tables:
    the same tables and reports as two separate imports."""
    from hydrosync_core.importers.log_import import expect_gnss_then_attitude

    if hourly:
        _, files = _split_hours(tmp_path, 3)
        files = [str(f) for f in files]
    else:
        one = tmp_path / "day.log"
        one.write_bytes(awkward_log(60.0))
        files = [str(one)]
    separate, together = Project.new(), Project.new()
    m1 = import_file(separate, "gnss_log", files)
    m2 = import_file(separate, "attitude_log", files, heave_positive="down")
    passes = []
    real = log_stream.stream_blocks
    monkeypatch.setattr(log_stream, "stream_blocks",
                        lambda *a, **k: passes.append(a[0]) or real(*a, **k))
    expect_gnss_then_attitude(files)
    assert import_file(together, "gnss_log", files) == m1
    assert import_file(together, "attitude_log", files, heave_positive="down") == m2
    assert len(passes) == len(files)  # the GNSS import's passes only
    for target in ("raw/gnss", "raw/attitude"):
        a, b = separate.get_table(target), together.get_table(target)
        assert list(a) == list(b)
        for name in a:
            np.testing.assert_array_equal(a[name], b[name])
        ra, rb = (json.loads(p.attrs(target)["import_report"]) for p in (separate, together))
        assert ra == rb
