"""Hypothesis fuzzing of every importer (issue #9): whatever the bytes, an import either
succeeds or raises :class:`InputError` with one line of at most 400 characters — no other
exception, no warning (warnings are errors in this test suite), no hang.

Example counts are small to fit the suite's time budget; ``HYDROSYNC_FAULT_SCALE``
multiplies them. Runs are derandomized (reproducible in CI) and keep no database.
"""

from __future__ import annotations

import io
import json
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hydrosync_core.errors import LINE_LIMIT, InputError
from hydrosync_core.importers.kinds import import_file
from hydrosync_core.project import Project
from tests.reliability.conftest import SCALE

_FAULTS = None


@pytest.fixture(autouse=True)
def _table(faults):
    global _FAULTS
    _FAULTS = faults


def _settings(n: int):
    return settings(max_examples=n * SCALE, deadline=None, database=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                           HealthCheck.function_scoped_fixture])


def _reason(exc: InputError) -> str:
    """The part of a one-line message after its file location (which is never clipped)."""
    where = (exc.file or "") + ("" if exc.line is None else f":{exc.line}")
    return exc.one_line().removeprefix(where).removeprefix(": ")


def _import(kind: str, suffix: str, content: bytes, **options) -> None:
    """Import *content* as *kind*; only success or a one-line InputError is acceptable."""
    with tempfile.TemporaryDirectory(prefix="hydrosync-fuzz-") as folder:
        path = Path(folder) / f"fuzz{suffix}"
        path.write_bytes(content)
        scratch = Project.new("fuzz")
        try:
            import_file(scratch, kind, path, **options)
        except InputError as exc:
            line = exc.one_line()
            assert "\n" not in line and len(_reason(exc)) <= LINE_LIMIT, line
        finally:
            scratch.close()
    shown = "" if suffix in (".csv", ".json", ".log") else suffix
    _FAULTS.record(f"fuzzed importer: {kind}{shown}", True)


# ------------------------------------------------------------------ strategies
_SPECIAL = ["", " ", "nan", "NaN", "inf", "-inf", "1e308", "-1e308", "1e-320", "0x1A", "#",
            '"', '""', "1,5", "١٢", "\x00", "9" * 400, "-0", "+1", "1e", ".", "e5"]
cell = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(-10**6, 10**6).map(str),
    st.sampled_from(_SPECIAL),
    st.text(max_size=12),
)


def csv_text(columns: list[str]):
    header = st.lists(st.sampled_from(columns + ["x", "", "extra", "a b", '"q"']),
                      min_size=1, max_size=len(columns) + 2).map(",".join)
    row = st.lists(cell, min_size=0, max_size=len(columns) + 2).map(",".join)
    good_row = st.lists(st.floats(-1e6, 1e6, allow_nan=False).map(lambda v: f"{v:.3f}"),
                        min_size=len(columns), max_size=len(columns)).map(",".join)
    body = st.lists(st.one_of(row, good_row, good_row), max_size=25)
    sep = st.sampled_from(["\n", "\r\n"])
    return st.builds(lambda h, b, s, good: s.join(([",".join(columns)] if good else [h]) + b),
                     header, body, sep, st.booleans())


def _encode(text: str) -> bytes:
    return text.encode("utf-8", "surrogatepass")


json_values = st.recursive(
    st.one_of(st.none(), st.booleans(), st.floats(), st.integers(-10**30, 10**30),
              st.text(max_size=10)),
    lambda inner: st.one_of(st.lists(inner, max_size=4),
                            st.dictionaries(st.text(max_size=8), inner, max_size=4)),
    max_leaves=12)


def mutated(document: dict):
    """*document* with one of its leaves (at any depth) replaced by a random JSON value."""
    paths = []

    def walk(node, here):
        if isinstance(node, dict):
            for k, v in node.items():
                walk(v, here + [k])
        elif isinstance(node, list):
            for i, v in enumerate(node):
                walk(v, here + [i])
        paths.append(here)

    walk(document, [])

    def replace(path, value):
        doc = json.loads(json.dumps(document))
        if not path:
            return value
        node = doc
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
        return doc

    return st.builds(replace, st.sampled_from(paths), json_values)


SETUP = {"boresight_deg": {"roll": -35.0, "pitch": 0.0, "yaw": 0.0},
         "lever_arm_m": {"x": 1.2, "y": 2.45, "z": 1.8}}
TARGET = {"frame": "ENU", "water_level_m": 0.0,
          "faces": [{"name": "wall", "corners": [[0, -3, -4], [0, 3, -4], [0, 3, 2]]}]}
VESSEL = {"name": "v", "sensors": {"gnss": {"offset_m": [1, 2, 3]},
                                   "motion": {"offset_m": [0, 0, 0],
                                              "angles_deg": {"roll": 0, "pitch": 0, "yaw": 0}}}}


def json_text(document: dict):
    return st.one_of(
        mutated(document).map(json.dumps),
        json_values.map(json.dumps),
        st.text(max_size=40),
        st.builds(lambda d, cut: json.dumps(d)[:cut], mutated(document), st.integers(0, 80)),
    )


# --------------------------------------------------------------------- tests
@pytest.mark.parametrize(("kind", "columns"), [
    ("gnss", ["time", "height", "lat", "lon", "quality"]),
    ("attitude", ["time", "roll", "pitch", "heading", "heave"]),
    ("lines", ["name", "start", "end"]),
    ("mbes", ["time", "x", "y", "z"]),
    ("ins", ["time", "e", "n", "u", "roll", "pitch", "heading"]),
    ("lidar", ["x", "y", "z"]),
])
def test_fuzz_csv_importers(kind, columns):
    @_settings(30)
    @given(csv_text(columns))
    def check(text):
        _import(kind, ".csv", _encode(text))

    check()


@pytest.mark.parametrize(("kind", "document"), [
    ("setup", SETUP), ("target", TARGET), ("vessel", VESSEL)])
def test_fuzz_json_importers(kind, document):
    @_settings(30)
    @given(json_text(document))
    def check(text):
        _import(kind, ".json", _encode(text))

    check()


def _nmea(body: str) -> str:
    checksum = 0
    for ch in body.encode("ascii", "replace"):
        checksum ^= ch
    return f"${body}*{checksum:02X}"


nmea_field = st.one_of(st.sampled_from(["", "0", "4", "12", "M", "N", "E", "1.5", "-3.2",
                                        "123519.00", "4807.038", "01131.000", "99.9"]),
                       st.text(alphabet="0123456789.-+ABCMNEW", max_size=10))
nmea_sentence = st.builds(
    lambda head, fields, good: (_nmea(head + "," + ",".join(fields)) if good
                                else "$" + head + "," + ",".join(fields)),
    st.sampled_from(["GPGGA", "GNGGA", "PTNL,GGK", "GPGST", "GPZDA", "GPRMC", "PASHR",
                     "PSXN,23", "GPHDT", "XXABC"]),
    st.lists(nmea_field, max_size=16), st.booleans())
nmea_line = st.one_of(
    nmea_sentence,
    st.builds(lambda t, s: f"{t} {s}", st.floats(0, 2e9).map(lambda v: f"{v:.3f}"),
              nmea_sentence),
    st.sampled_from([":\x00\x01\x02", "", "#comment", "TSS1 garbage"]),
)


@pytest.mark.parametrize(("kind", "options"), [
    ("gnss_log", {}), ("attitude_log", {}), ("attitude_log", {"heave_positive": "down"})])
def test_fuzz_nmea_importers(kind, options):
    @_settings(25)
    @given(st.lists(nmea_line, max_size=30).map("\r\n".join))
    def check(text):
        _import(kind, ".log", _encode(text), **options)

    check()


def _ply_text():
    prop = st.sampled_from(["property float x", "property float y", "property float z",
                            "property double x", "property uchar red", "property list uchar "
                            "int vertex_indices", "property foo x", "property float"])
    count = st.one_of(st.integers(0, 6).map(str), st.sampled_from(["many", "-1", "9" * 30]))
    fmt = st.sampled_from(["ascii 1.0", "binary_little_endian 1.0", "binary_big_endian 1.0",
                           "weird 2"])
    body = st.lists(st.lists(cell, max_size=4).map(" ".join), max_size=8).map("\n".join)
    return st.builds(
        lambda f, c, props, b, raw: (
            f"ply\nformat {f}\nelement vertex {c}\n" + "\n".join(props) + "\nend_header\n"
        ).encode() + (raw if f.startswith("binary") else b.encode("utf-8", "surrogatepass")),
        fmt, count, st.lists(prop, max_size=5), body, st.binary(max_size=80))


def test_fuzz_ply():
    @_settings(40)
    @given(_ply_text())
    def check(content):
        _import("lidar", ".ply", content)

    check()


def _las_bytes(compressed: bool) -> bytes:
    import laspy

    header = laspy.LasHeader(point_format=1, version="1.2")
    header.scales, header.offsets = [0.001] * 3, [0.0] * 3
    las = laspy.LasData(header)
    rng = np.random.default_rng(1)
    n = 400
    las.x, las.y, las.z = (rng.uniform(-5, 5, n) for _ in range(3))
    las.gps_time = np.arange(n) * 0.01
    out = io.BytesIO()
    las.write(out, do_compress=compressed)
    return out.getvalue()


def _flipped(base: bytes, header_bias: int):
    """*base* with up to 6 bytes replaced, mostly in the first *header_bias* bytes."""
    where = st.one_of(st.integers(0, header_bias - 1), st.integers(0, len(base) - 1))
    edits = st.lists(st.tuples(where, st.integers(0, 255)), min_size=1, max_size=6)
    cut = st.one_of(st.none(), st.integers(0, len(base)))

    def apply(changes, length):
        data = bytearray(base)
        for pos, value in changes:
            data[pos] = value
        return bytes(data[:length] if length is not None else data)

    return st.builds(apply, edits, cut)


LAS = _las_bytes(False)
LAZ = _las_bytes(True)


def test_fuzz_las():
    @_settings(40)
    @given(_flipped(LAS, 400))
    def check(content):
        _import("lidar", ".las", content)

    check()


def test_fuzz_laz():
    """LAZ decoding runs in a child process (0.2–0.3 s each): few examples."""
    @_settings(6)
    @given(_flipped(LAZ, 420))
    def check(content):
        _import("lidar", ".laz", content)

    check()


# ------------------------------------------------------------ RTKLIB .pos (gnss_attitude)
POS_HEADER = ["% program   : RTKLIB ver.2.4.3",
              "% ref pos   : 35.0 139.0 50.0",
              "%  GPST                  latitude(deg) longitude(deg)  height(m)   Q  ns   "
              "sdn(m)   sde(m)   sdu(m)  sdne(m)  sdeu(m)  sdun(m) age(s)  ratio",
              "%  GPST          e-baseline(m)  n-baseline(m)  u-baseline(m)   Q  ns   sde(m)   "
              "sdn(m)   sdu(m)  sden(m)  sdnu(m)  sdue(m) age(s)  ratio",
              "%  GPST       x-ecef(m)      y-ecef(m)      z-ecef(m)   Q  ns   sdx(m)   "
              "sdy(m)   sdz(m)  sdxy(m)  sdyz(m)  sdzx(m) age(s)  ratio",
              "% garbage legend (deg)"]
pos_time = st.one_of(
    st.builds(lambda w, t: f"{w} {t:.3f}", st.integers(-5, 5000), st.floats(-10, 7e5)),
    st.builds(lambda d, s: f"2023/01/{d:02d} 10:00:{s:06.3f}", st.integers(0, 40),
              st.floats(0, 70)),
    st.sampled_from(["2023/13/45 99:99:99", "x y", "1e308 1e308", "2100 604799.999"]))
pos_value = st.one_of(st.floats(-1e7, 1e7).map(lambda v: f"{v:.4f}"), cell,
                      st.sampled_from(["35 10 5.5", "-139 0 0", "1", "5", "7", "9"]))
pos_row = st.builds(lambda t, vals: t + " " + " ".join(vals), pos_time,
                    st.lists(pos_value, min_size=0, max_size=17))


def test_fuzz_rtklib_pos():
    from hydrosync_core.importers.rtklib_pos import read_pos

    @_settings(40)
    @given(st.lists(st.sampled_from(POS_HEADER), max_size=3), st.lists(pos_row, max_size=12))
    def check(header, rows):
        with tempfile.TemporaryDirectory(prefix="hydrosync-fuzz-") as folder:
            path = Path(folder) / "A1.pos"
            path.write_bytes(_encode("\n".join(header + rows)))
            try:
                read_pos(path)
            except InputError as exc:
                line = exc.one_line()
                assert "\n" not in line and len(_reason(exc)) <= LINE_LIMIT, line
        _FAULTS.record("fuzzed importer: rtklib .pos", True)

    check()
