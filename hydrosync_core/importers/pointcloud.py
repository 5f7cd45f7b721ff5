"""Read laser point clouds: CSV ``x,y,z``, PLY (ascii / binary LE / BE), LAS and LAZ.

All readers return float64 ``(N, 3)`` coordinates in the file's frame (for the pool
calibration: target ENU, metres) and raise :class:`~hydrosync_core.errors.InputError` on
a file they cannot read.

LAS/LAZ safety. A LAS header states its VLR count, the offset of the point data and the
point count; a damaged header (PDAL's ``garbage_nVariableLength.las``) makes a naive
``laspy.open`` walk millions of phantom VLRs for many seconds. The header is therefore
parsed and checked here *before* laspy sees the file (LAS 1.0–1.4 header layout, ASPRS
R15 table 3/4): VLR count against the space between header and point data, point count
against the file size (uncompressed) or against an absurd ratio (LAZ), scale factors
non-zero and finite. A VLR count larger than the VLRs actually present is repaired in an
in-memory copy and reported as a warning; everything else that is wrong raises.
Coordinates are ``X·scale + offset`` (laspy's scaled ``x, y, z``), as float64.

LAZ is decoded in a child process (:func:`_decode_laz`): the LAZ decoder (lazrs) aborts
the whole process on some corrupt chunk tables (it tries to allocate tens of GB), which
no ``try`` can catch. The chunk table is checked against the point count and the file
size first; what still crashes the child becomes one InputError line.

Coordinates must be plausible (:data:`hydrosync_core.plausible.COORDINATE`): a LAS scale
of 1e300 or a PLY vertex at 1e308 is an error naming the point, not a point.

PLY is read by a small numpy reader (header parse + one ``frombuffer``/``loadtxt``):
``open3d.io.read_point_cloud`` silently returns an empty cloud on a bad file.
"""

from __future__ import annotations

import io
import math
import os
import struct
import subprocess
import sys
import tempfile
import warnings as _warnings
from pathlib import Path

import numpy as np

from hydrosync_core import plausible
from hydrosync_core.errors import InputError, clip, quote
from hydrosync_core.inputs import input_ok

_PLY_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
    "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4",
    "uint32": "u4", "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
}
_VLR_HEADER = 54
_MAX_LAZ_RATIO = 60  # a LAZ point never compresses below ~1/60 of its record length
_SCALE_RANGE = (1e-12, 1e3)  # |scale| of a LAS coordinate: 1 pm .. 1 km per unit
_OFFSET_MAX = 1e9
_LASZIP_RECORD = 22204


def read_point_cloud(
    path: str | os.PathLike, *, min_points: int = 1, warnings: list[str] | None = None
) -> np.ndarray:
    """Read a point cloud as float64 (N, 3) ``x, y, z``.

    Parameters
    ----------
    path : path-like
        ``.csv``/``.txt`` (header ``x,y,z``), ``.ply``, ``.las`` or ``.laz``.
    min_points : int
        Fewer valid points than this raise InputError.
    warnings : list of str, optional
        Receives a line per repaired or suspicious detail (bad VLR count, NaN GPS time).
    """
    input_ok(path, "point cloud", text=False)  # binary LAS/LAZ/PLY allowed
    path = Path(path)
    notes: list[str] = [] if warnings is None else warnings
    if not path.exists():
        raise InputError(str(path), "no such file")
    if path.is_dir():
        raise InputError(str(path), "is a folder, not a file")
    suffix = path.suffix.lower()
    if suffix in (".las", ".laz"):
        points = _read_las(path, notes)
    elif suffix == ".ply":
        points = _read_ply(path)
    else:
        from hydrosync_core.importers.survey_csv import read_lidar_csv

        points = read_lidar_csv(path)
    finite = np.isfinite(points).all(axis=1)
    if not finite.all():
        notes.append(f"{int(np.count_nonzero(~finite))} points with non-finite coordinates dropped")
        points = points[finite]
    lo, hi, unit = plausible.COORDINATE
    outside = (points < lo) | (points > hi)
    if outside.any():
        row, col = (int(v[0]) for v in np.nonzero(outside))
        raise InputError(str(path), f"point {row + 1}: {'xyz'[col]} = {points[row, col]:g} is "
                         f"outside the plausible range {plausible.describe(plausible.COORDINATE)}")
    if len(points) < min_points:
        raise InputError(str(path), f"{len(points)} valid points (at least {min_points} needed)")
    return np.ascontiguousarray(points, dtype=np.float64)


def _las_header(path: Path, data: bytes) -> dict:
    """Parse and validate the fixed LAS header fields used to guard laspy."""
    if len(data) < 227 or data[:4] != b"LASF":
        raise InputError(str(path), "not a LAS file (no 'LASF' signature or header too short)")
    major, minor = data[24], data[25]
    header_size, offset, n_vlr = struct.unpack_from("<HII", data, 94)
    fmt, rec_len, legacy_count = struct.unpack_from("<BHI", data, 104)
    scale = struct.unpack_from("<3d", data, 131)
    count = legacy_count
    if (major, minor) >= (1, 4) and len(data) >= 375:
        count = struct.unpack_from("<Q", data, 247)[0] or legacy_count
    if major != 1 or minor > 4:
        raise InputError(str(path), f"unsupported LAS version {major}.{minor}")
    if header_size < 227 or offset < header_size or offset > len(data):
        raise InputError(
            str(path), f"header size {header_size} / point data offset {offset} impossible "
            f"for a {len(data)}-byte file")
    offsets = struct.unpack_from("<3d", data, 155)
    lo, hi = _SCALE_RANGE
    if not all(math.isfinite(v) and lo <= abs(v) <= hi for v in scale):
        shown = ", ".join(f"{v:g}" for v in scale)
        raise InputError(str(path), f"invalid coordinate scale factors ({shown}): each must be "
                         f"between {lo:g} and {hi:g}")
    if not all(math.isfinite(v) and abs(v) <= _OFFSET_MAX for v in offsets):
        shown = ", ".join(f"{v:g}" for v in offsets)
        raise InputError(str(path), f"invalid coordinate offsets ({shown})")
    return {"version": (major, minor), "header_size": header_size, "offset": offset,
            "n_vlr": n_vlr, "format": fmt & 0x3F, "compressed": bool(fmt & 0xC0),
            "rec_len": rec_len, "count": count}


def _count_vlrs(data: bytes, start: int, end: int, limit: int) -> int:
    """Number of complete VLRs between *start* and *end* (at most *limit*)."""
    n, pos = 0, start
    while n < limit and pos + _VLR_HEADER <= end:
        length = struct.unpack_from("<H", data, pos + 20)[0]
        if pos + _VLR_HEADER + length > end:
            break
        pos += _VLR_HEADER + length
        n += 1
    return n


def _read_las(path: Path, notes: list[str]) -> np.ndarray:
    data = path.read_bytes()
    h = _las_header(path, data)
    present = _count_vlrs(data, h["header_size"], h["offset"], h["n_vlr"])
    if present != h["n_vlr"]:
        notes.append(f"header says {h['n_vlr']} VLRs, {present} present: count repaired")
        patched = bytearray(data)
        struct.pack_into("<I", patched, 100, present)
        data = bytes(patched)
    space = len(data) - h["offset"]
    compressed = h["compressed"] or path.suffix.lower() == ".laz"
    if h["count"] == 0:
        raise InputError(str(path), "LAS file holds 0 points")
    if not compressed and h["count"] * h["rec_len"] > space:
        whole = space // max(h["rec_len"], 1)
        if whole == 0:
            raise InputError(
                str(path), f"header says {h['count']} points of {h['rec_len']} bytes but "
                f"only {space} bytes of point data follow")
        # Truncated file: read the complete records only (count patched in a copy).
        notes.append(f"header says {h['count']} points, the file holds {whole} complete "
                     f"records: reading those")
        patched = bytearray(data)
        struct.pack_into("<I", patched, 107, min(whole, 0xFFFFFFFF))
        if h["version"] >= (1, 4) and len(patched) >= 375:
            struct.pack_into("<Q", patched, 247, whole)
        data = bytes(patched)
    if compressed and h["count"] * h["rec_len"] > _MAX_LAZ_RATIO * max(space, 1):
        raise InputError(str(path), f"header point count {h['count']} is absurd for "
                         f"{space} bytes of compressed data")
    if compressed:
        _check_chunk_table(path, data, h)
        points, bad_time = _decode_laz(path, data, h)
    else:
        points, bad_time = _decode_las(path, data)
    if bad_time:
        notes.append(f"{bad_time} points with non-finite GPS time (coordinates kept)")
    return points


def _decode_las(path: Path, data: bytes) -> tuple[np.ndarray, int]:
    """Uncompressed LAS in process: laspy reads it with numpy only."""
    import logging

    import laspy

    quiet = logging.getLogger("laspy")
    level = quiet.level
    quiet.setLevel(logging.CRITICAL)  # its log lines must not precede our one-line error
    try:
        with _warnings.catch_warnings():
            _warnings.simplefilter("ignore")
            las = laspy.read(io.BytesIO(data))
            return _xyz_and_bad_time(las)
    except Exception as exc:  # laspy raises many types on damaged files
        raise InputError(str(path), f"cannot read LAS: {clip(exc, 120)}") from None
    finally:
        quiet.setLevel(level)


def _xyz_and_bad_time(las) -> tuple[np.ndarray, int]:
    points = np.column_stack([np.asarray(las.x), np.asarray(las.y), np.asarray(las.z)])
    bad_time = 0
    if "gps_time" in set(las.point_format.dimension_names):
        bad_time = int(np.count_nonzero(~np.isfinite(np.asarray(las.gps_time))))
    return points.astype(np.float64), bad_time


def _laszip_chunk_size(data: bytes, h: dict) -> int | None:
    """Chunk size from the LASzip VLR (None when the VLR is absent or short)."""
    pos, end = h["header_size"], h["offset"]
    for _ in range(h["n_vlr"]):
        if pos + _VLR_HEADER > end:
            return None
        user = data[pos + 2:pos + 18].split(b"\0", 1)[0]
        record, length = struct.unpack_from("<HH", data, pos + 18)
        body = pos + _VLR_HEADER
        if user == b"laszip encoder" and record == _LASZIP_RECORD and length >= 16:
            return struct.unpack_from("<I", data, body + 12)[0]
        pos = body + length
    return None


def _check_chunk_table(path: Path, data: bytes, h: dict) -> None:
    """Refuse a LAZ whose chunk table cannot belong to its point count and file size."""
    start, size = h["offset"], len(data)
    if start + 8 > size:
        raise InputError(str(path), "LAZ file ends before its point data")
    table = struct.unpack_from("<q", data, start)[0]
    if table == -1 and size >= 8:  # written while streaming: the offset is at the end
        table = struct.unpack_from("<q", data, size - 8)[0]
    if not start + 8 <= table <= size - 8:
        raise InputError(str(path), f"LAZ chunk table offset {table} lies outside the "
                         f"{size}-byte file: the file is damaged")
    version, chunks = struct.unpack_from("<II", data, table)
    chunk_size = _laszip_chunk_size(data, h)
    count = h["count"]
    expected = None
    if chunk_size not in (None, 0, 0xFFFFFFFF):
        expected = -(-count // chunk_size)
    if version != 0 or chunks == 0 or chunks > max(count, 1) or chunks > size - start or (
            expected is not None and chunks != expected):
        want = f" (expected {expected})" if expected is not None else ""
        raise InputError(str(path), f"LAZ chunk table is damaged: version {version}, {chunks} "
                         f"chunks for {count} points{want}")


_CHILD = r"""
import io, logging, sys, warnings
logging.disable(logging.CRITICAL)
warnings.simplefilter("ignore")
import numpy as np
import laspy
data = open(sys.argv[1], "rb").read()
las = laspy.read(io.BytesIO(data))
xyz = np.column_stack([np.asarray(las.x), np.asarray(las.y), np.asarray(las.z)])
bad = 0
if "gps_time" in set(las.point_format.dimension_names):
    bad = int(np.count_nonzero(~np.isfinite(np.asarray(las.gps_time))))
np.save(sys.argv[2], xyz.astype(np.float64))
sys.stdout.write(str(bad))
"""


def _limit_memory(limit: int):  # pragma: no cover - runs in the child
    def apply() -> None:
        try:
            import resource

            resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
        except (ImportError, ValueError, OSError):
            pass

    return apply


def _decode_laz(path: Path, data: bytes, h: dict) -> tuple[np.ndarray, int]:
    """Decode LAZ *data* in a child process; a crash of the decoder is an InputError."""
    count = int(h["count"])
    # Room for the decoded records, laspy's copies and the output, plus the interpreter.
    limit = 3 * 2**30 + 6 * count * (int(h["rec_len"]) + 24)
    timeout = 120.0 + count / 1e5
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1",
               RUST_BACKTRACE="0", PYTHONWARNINGS="ignore")
    with tempfile.TemporaryDirectory(prefix="hydrosync-laz-") as folder:
        source = Path(folder) / "in.laz"
        source.write_bytes(data)
        out = Path(folder) / "xyz.npy"
        try:
            done = subprocess.run(
                [sys.executable, "-I", "-c", _CHILD, str(source), str(out)],
                capture_output=True, timeout=timeout, env=env, stdin=subprocess.DEVNULL,
                preexec_fn=_limit_memory(limit) if os.name == "posix" else None,
            )
        except subprocess.TimeoutExpired:
            raise InputError(str(path), f"decoding the LAZ point data took more than "
                             f"{timeout:.0f} s: the file is probably damaged") from None
        if done.returncode != 0 or not out.exists():
            raise InputError(str(path), _laz_failure(done))
        points = np.load(out)
    try:
        bad_time = int(done.stdout.decode("ascii", "replace").strip() or 0)
    except ValueError:
        bad_time = 0
    return points, bad_time


def _laz_failure(done: subprocess.CompletedProcess) -> str:
    """One line on why the LAZ child failed (its last error line, clipped)."""
    lines = [ln.strip() for ln in done.stderr.decode("utf-8", "replace").splitlines()
             if ln.strip()]
    if (done.returncode < 0 or any("panicked" in ln or "memory allocation" in ln
                                   for ln in lines)):
        return ("cannot decode the LAZ point data: the decoder crashed on damaged compressed "
                "data" + (f" (signal {-done.returncode})" if done.returncode < 0 else ""))
    if any("MemoryError" in ln for ln in lines):
        return "cannot decode the LAZ point data: it would need more memory than it can hold"
    errors = [ln for ln in lines if "Error" in ln or "error" in ln]
    reason = errors[-1] if errors else (lines[-1] if lines else f"exit {done.returncode}")
    reason = reason.rsplit("Error: ", 1)[-1]
    if "failed to fill whole buffer" in reason:
        reason = "the compressed data end early (truncated or damaged file)"
    return f"cannot decode the LAZ point data: {clip(reason, 120)}"


def _read_ply(path: Path) -> np.ndarray:
    data = path.read_bytes()
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise InputError(str(path), "not a PLY file (no 'ply' magic or no end_header)")
    newline = data.find(b"\n", end)
    if newline < 0:
        raise InputError(str(path), "PLY header has no line end after end_header")
    body_start = newline + 1
    header = data[:end].decode("ascii", errors="replace").splitlines()
    fmt, elements = None, []
    for number, line in enumerate(header, start=1):
        words = line.split()
        if not words or words[0] in ("ply", "comment", "obj_info"):
            continue
        if words[0] == "format" and len(words) >= 2:
            fmt = words[1]
        elif words[0] == "element" and len(words) == 3:
            if not words[2].isdigit() or len(words[2]) > 12:
                raise InputError(str(path), f"PLY element {quote(words[1], 30)} count "
                                 f"{quote(words[2], 30)} is not a number of elements",
                                 line=number)
            elements.append([words[1], int(words[2]), []])
        elif words[0] == "property" and elements:
            if words[1] == "list":
                elements[-1][2].append(("list", None))
            elif len(words) == 3 and words[1] in _PLY_TYPES:
                elements[-1][2].append((words[2], _PLY_TYPES[words[1]]))
            else:
                raise InputError(str(path), f"bad PLY property {quote(line)}", line=number)
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise InputError(str(path), f"unknown PLY format {quote(fmt or '')}")
    if not elements or elements[0][0] != "vertex":
        raise InputError(str(path), "PLY has no vertex element first")
    _, count, props = elements[0]
    names = [p[0] for p in props]
    twice = sorted({n for n in names if n != "list" and names.count(n) > 1})
    if twice:
        raise InputError(str(path), f"PLY vertex property {quote(twice[0], 30)} is declared "
                         "more than once")
    if "list" in names or not {"x", "y", "z"} <= set(names):
        raise InputError(str(path), f"PLY vertex needs scalar x, y, z (has "
                         f"{quote(', '.join(names), 80)})")
    if fmt == "ascii":
        if count == 0:
            raise InputError(str(path), "PLY says 0 vertices")
        try:
            with _warnings.catch_warnings():
                _warnings.simplefilter("ignore")  # "input contained no data": we say it below
                table = np.loadtxt(io.BytesIO(data[body_start:]), max_rows=count, ndmin=2,
                                   usecols=[names.index(c) for c in "xyz"], dtype=np.float64)
        except (ValueError, IndexError) as exc:
            raise InputError(str(path), f"bad PLY vertex data: {clip(exc, 120)}") from None
        if len(table) < count:
            raise InputError(str(path), f"PLY says {count} vertices, {len(table)} found")
        return table
    order = "<" if fmt == "binary_little_endian" else ">"
    dtype = np.dtype([(n, order + t) for n, t in props])
    if body_start + count * dtype.itemsize > len(data):
        raise InputError(str(path), f"PLY says {count} vertices but the file is truncated")
    verts = np.frombuffer(data, dtype=dtype, count=count, offset=body_start)
    return np.column_stack([verts[c].astype(np.float64) for c in "xyz"])
