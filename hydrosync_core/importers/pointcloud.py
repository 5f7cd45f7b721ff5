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

PLY is read by a small numpy reader (header parse + one ``frombuffer``/``loadtxt``):
``open3d.io.read_point_cloud`` silently returns an empty cloud on a bad file.
"""

from __future__ import annotations

import io
import os
import struct
from pathlib import Path

import numpy as np

from hydrosync_core.errors import InputError

_PLY_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "i2", "int16": "i2",
    "ushort": "u2", "uint16": "u2", "int": "i4", "int32": "i4", "uint": "u4",
    "uint32": "u4", "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
}
_VLR_HEADER = 54
_MAX_LAZ_RATIO = 60  # a LAZ point never compresses below ~1/60 of its record length


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
    if not all(np.isfinite(scale)) or any(s == 0 for s in scale):
        raise InputError(str(path), f"invalid coordinate scale factors {scale}")
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
    import laspy

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
    try:
        las = laspy.read(io.BytesIO(data))
    except Exception as exc:  # laspy raises many types on damaged files
        raise InputError(str(path), f"cannot read LAS/LAZ: {exc}") from None
    points = np.column_stack([np.asarray(las.x), np.asarray(las.y), np.asarray(las.z)])
    names = set(las.point_format.dimension_names)
    if "gps_time" in names:
        bad_time = int(np.count_nonzero(~np.isfinite(np.asarray(las.gps_time))))
        if bad_time:
            notes.append(f"{bad_time} points with non-finite GPS time (coordinates kept)")
    return points.astype(np.float64)


def _read_ply(path: Path) -> np.ndarray:
    data = path.read_bytes()
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise InputError(str(path), "not a PLY file (no 'ply' magic or no end_header)")
    body_start = data.index(b"\n", end) + 1
    header = data[:end].decode("ascii", errors="replace").splitlines()
    fmt, elements = None, []
    for number, line in enumerate(header, start=1):
        words = line.split()
        if not words or words[0] in ("ply", "comment", "obj_info"):
            continue
        if words[0] == "format" and len(words) >= 2:
            fmt = words[1]
        elif words[0] == "element" and len(words) == 3:
            elements.append([words[1], int(words[2]), []])
        elif words[0] == "property" and elements:
            if words[1] == "list":
                elements[-1][2].append(("list", None))
            elif len(words) == 3 and words[1] in _PLY_TYPES:
                elements[-1][2].append((words[2], _PLY_TYPES[words[1]]))
            else:
                raise InputError(str(path), f"bad PLY property '{line}'", line=number)
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise InputError(str(path), f"unknown PLY format '{fmt}'")
    if not elements or elements[0][0] != "vertex":
        raise InputError(str(path), "PLY has no vertex element first")
    _, count, props = elements[0]
    names = [p[0] for p in props]
    if "list" in names or not {"x", "y", "z"} <= set(names):
        raise InputError(str(path), f"PLY vertex needs scalar x, y, z (has {names})")
    if fmt == "ascii":
        try:
            table = np.loadtxt(io.BytesIO(data[body_start:]), max_rows=count, ndmin=2,
                               usecols=[names.index(c) for c in "xyz"], dtype=np.float64)
        except ValueError as exc:
            raise InputError(str(path), f"bad PLY vertex data: {exc}") from None
        if len(table) < count:
            raise InputError(str(path), f"PLY says {count} vertices, {len(table)} found")
        return table
    order = "<" if fmt == "binary_little_endian" else ">"
    dtype = np.dtype([(n, order + t) for n, t in props])
    if body_start + count * dtype.itemsize > len(data):
        raise InputError(str(path), f"PLY says {count} vertices but the file is truncated")
    verts = np.frombuffer(data, dtype=dtype, count=count, offset=body_start)
    return np.column_stack([verts[c].astype(np.float64) for c in "xyz"])
