"""Readers for the pool-calibration ``setup.json`` and ``target.json`` files.

:func:`check_setup` / :func:`check_target` validate a parsed document (the readers, and
the project checks of ``raw/pool/setup`` / ``raw/pool/target``, use them). Hostile
documents — 400-digit numbers, nesting thousands deep, megabytes of text in one
string — end as one :class:`InputError` line like any other bad input.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

from hydrosync_core import plausible
from hydrosync_core.errors import InputError, quote
from hydrosync_core.inputs import input_ok

MAX_JSON_BYTES = 50_000_000
"""A setup, target or vessel file is a few kB; more is not one of them."""


def read_json(path: str | os.PathLike) -> dict:
    """Parse a JSON object from *path*, with the line of a syntax error named."""
    path = input_ok(path, "JSON settings file", max_bytes=MAX_JSON_BYTES)
    if path.stat().st_size > MAX_JSON_BYTES:
        raise InputError(str(path), f"file is {path.stat().st_size} bytes: too large for a "
                         "JSON settings file")
    text = path.read_text(encoding="utf-8", errors="replace")
    if not text.strip():
        raise InputError(str(path), "file is empty")
    from hydrosync_core.configfiles import parse_json

    document = parse_json(text, str(path))  # bounded depth, size and integer digits
    if not isinstance(document, dict):
        raise InputError(str(path), "expected a JSON object at the top level")
    return document


def finite_number(path, value, field: str, limits: plausible.Limits | None = None) -> float:
    """*value* as float if it is a finite JSON number (within *limits*), else InputError."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        shown = quote(value) if isinstance(value, str) else type(value).__name__
        raise InputError(str(path), f"expected a finite number, got {shown}", field=field)
    try:
        number = float(value)
    except OverflowError:
        raise InputError(str(path), f"number with {len(str(abs(value)))} digits is far too "
                         "large", field=field) from None
    if not math.isfinite(number):
        raise InputError(str(path), f"expected a finite number, got {value!r}", field=field)
    if limits is not None and not limits[0] <= number <= limits[1]:
        raise InputError(str(path), plausible.problem(number, limits), field=field)
    return number


def check_setup(document, source="setup.json") -> dict:
    """Coarse boresight (deg) and lever arm (m, body FRD) from a parsed setup document."""
    if not isinstance(document, dict):
        raise InputError(str(source), "expected a JSON object")
    out: dict[str, dict[str, float]] = {}
    for block, keys, limits in (("boresight_deg", ("roll", "pitch", "yaw"), plausible.ANGLE),
                                ("lever_arm_m", "xyz", plausible.OFFSET)):
        values = document.get(block)
        if not isinstance(values, dict):
            raise InputError(str(source), "missing object", field=block)
        out[block] = {}
        for key in keys:
            if key not in values:
                raise InputError(str(source), "missing value", field=f"{block}.{key}")
            out[block][key] = finite_number(source, values[key], f"{block}.{key}", limits)
    return out


def read_setup_json(path: str | os.PathLike) -> dict:
    """Coarse boresight (deg) and lever arm (m, body FRD) of the multibeam."""
    path = Path(path)
    return check_setup(read_json(path), path)


def check_target(document, source="target.json") -> dict:
    """Target design (faces with corners in target ENU, m; water level) from a document."""
    if not isinstance(document, dict):
        raise InputError(str(source), "expected a JSON object")
    faces = document.get("faces")
    if not isinstance(faces, list) or not faces:
        raise InputError(str(source), "expected a non-empty list of faces", field="faces")
    clean = []
    for i, face in enumerate(faces):
        where = f"faces[{i}]"
        if not isinstance(face, dict) or "corners" not in face:
            raise InputError(str(source), "expected an object with 'corners'", field=where)
        corners = face["corners"]
        if not isinstance(corners, list) or len(corners) < 3:
            raise InputError(str(source), "a face needs 3 or more corners",
                             field=f"{where}.corners")
        points = []
        for j, corner in enumerate(corners):
            if not isinstance(corner, list) or len(corner) != 3:
                raise InputError(
                    str(source), "a corner is [e, n, u]", field=f"{where}.corners[{j}]"
                )
            points.append([finite_number(source, v, f"{where}.corners[{j}]",
                                         plausible.COORDINATE) for v in corner])
        name = face.get("name", f"face{i}")
        if not isinstance(name, str | int | float) or len(str(name)) > 200:
            raise InputError(str(source), "a face name is a short text", field=f"{where}.name")
        item = {"name": str(name), "corners": points}
        if "twin" in face:  # an explicit twin declaration (formats.md), checked below
            if not isinstance(face["twin"], str):
                raise InputError(str(source), "a twin is the name of another face",
                                 field=f"{where}.twin")
            item["twin"] = face["twin"]
        if "offset_m" in face:
            item["offset_m"] = finite_number(source, face["offset_m"], f"{where}.offset_m",
                                             plausible.HEIGHT)
        clean.append(item)
    names = {c["name"] for c in clean}
    for i, item in enumerate(clean):
        if "offset_m" in item and "twin" not in item:
            raise InputError(str(source), "offset_m needs a twin", field=f"faces[{i}].offset_m")
        if item.get("twin") is not None and (item["twin"] not in names
                                             or item["twin"] == item["name"]):
            raise InputError(str(source), f"twin '{item['twin']}' is not another face of the "
                             "target", field=f"faces[{i}].twin")
    water = finite_number(source, document.get("water_level_m", 0.0), "water_level_m",
                          plausible.HEIGHT)
    frame = document.get("frame", "ENU")
    if not isinstance(frame, str) or len(frame) > 50:
        raise InputError(str(source), "expected a short text such as \"ENU\"", field="frame")
    return {"frame": frame, "water_level_m": water, "faces": clean}


def read_target_json(path: str | os.PathLike) -> dict:
    """Target design: faces (name, corners in target ENU, m) and the water level (m)."""
    path = Path(path)
    return check_target(read_json(path), path)
