"""Readers for the pool-calibration ``setup.json`` and ``target.json`` files."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

from hydrosync_core.errors import InputError


def read_json(path: str | os.PathLike) -> dict:
    """Parse a JSON object from *path*, with the line of a syntax error named."""
    path = Path(path)
    if not path.exists():
        raise InputError(str(path), "no such file")
    text = path.read_text(encoding="utf-8", errors="replace")
    if not text.strip():
        raise InputError(str(path), "file is empty")
    try:
        document = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(str(path), f"invalid JSON: {exc.msg}", line=exc.lineno) from None
    if not isinstance(document, dict):
        raise InputError(str(path), "expected a JSON object at the top level")
    return document


def finite_number(path: Path, value, field: str) -> float:
    """*value* as float if it is a finite JSON number, else an InputError naming *field*."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise InputError(str(path), f"expected a finite number, got {value!r}", field=field)
    return float(value)


def read_setup_json(path: str | os.PathLike) -> dict:
    """Coarse boresight (deg) and lever arm (m, body FRD) of the multibeam."""
    path = Path(path)
    document = read_json(path)
    out: dict[str, dict[str, float]] = {}
    for block, keys in (("boresight_deg", ("roll", "pitch", "yaw")), ("lever_arm_m", "xyz")):
        values = document.get(block)
        if not isinstance(values, dict):
            raise InputError(str(path), "missing object", field=block)
        out[block] = {}
        for key in keys:
            if key not in values:
                raise InputError(str(path), "missing value", field=f"{block}.{key}")
            out[block][key] = finite_number(path, values[key], f"{block}.{key}")
    return out


def read_target_json(path: str | os.PathLike) -> dict:
    """Target design: faces (name, corners in target ENU, m) and the water level (m)."""
    path = Path(path)
    document = read_json(path)
    faces = document.get("faces")
    if not isinstance(faces, list) or not faces:
        raise InputError(str(path), "expected a non-empty list of faces", field="faces")
    clean = []
    for i, face in enumerate(faces):
        where = f"faces[{i}]"
        if not isinstance(face, dict) or "corners" not in face:
            raise InputError(str(path), "expected an object with 'corners'", field=where)
        corners = face["corners"]
        if not isinstance(corners, list) or len(corners) < 3:
            raise InputError(str(path), "a face needs 3 or more corners", field=f"{where}.corners")
        points = []
        for j, corner in enumerate(corners):
            if not isinstance(corner, list) or len(corner) != 3:
                raise InputError(
                    str(path), "a corner is [e, n, u]", field=f"{where}.corners[{j}]"
                )
            points.append([finite_number(path, v, f"{where}.corners[{j}]") for v in corner])
        clean.append({"name": str(face.get("name", f"face{i}")), "corners": points})
    water = finite_number(path, document.get("water_level_m", 0.0), "water_level_m")
    return {"frame": document.get("frame", "ENU"), "water_level_m": water, "faces": clean}
