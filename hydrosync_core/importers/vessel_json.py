"""Reader of a vessel offset sheet (``vessel.json``) for ``/vessel``.

Format (body frame FRD: x forward, y starboard, z down; metres; degrees)::

    {"name": "MV Example",
     "sensors": {"motion": {"offset_m": [0, 0, 0]},
                 "gnss": {"offset_m": [-1.5, 2.0, -6.0]},
                 "multibeam": {"offset_m": [1.2, 2.45, 1.8],
                               "angles_deg": {"roll": -35, "pitch": 0, "yaw": 0}}}}

Offsets must lie within ±1000 m and angles within ±360° (:mod:`hydrosync_core.plausible`).
"""

from __future__ import annotations

import os
from pathlib import Path

from hydrosync_core import plausible
from hydrosync_core.errors import InputError
from hydrosync_core.importers.pool_json import finite_number, read_json
from hydrosync_core.project.model import default_vessel


def _sensor(source, name, sensor) -> dict:
    where = f"sensors.{name}"
    offset = sensor.get("offset_m") if isinstance(sensor, dict) else None
    if not isinstance(offset, list) or len(offset) != 3:
        raise InputError(str(source), "offset_m must be [x, y, z]", field=f"{where}.offset_m")
    entry: dict = {"offset_m": [finite_number(source, v, f"{where}.offset_m", plausible.OFFSET)
                                for v in offset]}
    angles = sensor.get("angles_deg")
    if angles is not None:
        if not isinstance(angles, dict) or set(angles) - {"roll", "pitch", "yaw"}:
            raise InputError(
                str(source), "angles_deg takes roll, pitch, yaw", field=f"{where}.angles_deg"
            )
        entry["angles_deg"] = {
            k: finite_number(source, v, f"{where}.angles_deg.{k}", plausible.ANGLE)
            for k, v in angles.items()
        }
    entry.update({k: v for k, v in sensor.items() if k not in ("offset_m", "angles_deg")})
    return entry


def check_vessel(document, source="vessel.json", *, allow_empty: bool = True):
    """Validate a vessel sheet document (as stored in a project); return it unchanged."""
    if not isinstance(document, dict):
        raise InputError(str(source), "expected a JSON object")
    sensors = document.get("sensors", {})
    if not isinstance(sensors, dict) or (not sensors and not allow_empty):
        raise InputError(str(source), "expected an object of sensors", field="sensors")
    for name, sensor in sensors.items():
        _sensor(source, name, sensor)
    return document


def read_vessel_json(path: str | os.PathLike) -> dict:
    """Validate and return the vessel sheet (offsets in m, body FRD; angles in deg)."""
    path = Path(path)
    document = read_json(path)
    check_vessel(document, path, allow_empty=False)
    sheet = default_vessel()
    sheet["name"] = str(document.get("name", ""))
    for name, sensor in document["sensors"].items():
        sheet["sensors"][str(name)] = _sensor(path, name, sensor)
    return sheet
