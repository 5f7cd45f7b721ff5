"""The vessel offset sheet stored in ``/vessel``: sensor positions and mounting angles.

Each sensor has ``offset_m`` ``[x, y, z]`` in the body frame (FRD, metres) relative to
the vessel reference point, and optionally ``angles_deg`` ``{roll, pitch, yaw}``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from hydrosync_core import plausible
from hydrosync_core.errors import InputError
from hydrosync_core.project.model import Project, default_vessel
from hydrosync_core.project.schema import VESSEL


def vessel_config(project: Project) -> dict:
    """Return the vessel sheet (the default empty sheet if none is stored)."""
    return project.get_json(VESSEL, default_vessel())


def set_sensor(
    project: Project, name: str, offset_m, angles_deg: dict | None = None, **info
) -> None:
    """Set sensor *name*'s offset (body FRD, m) and optional mounting angles (deg)."""
    where = str(project.path or "<project>")
    config = vessel_config(project)
    entry = {"offset_m": [_checked(where, name, "offset", v, plausible.OFFSET)
                          for v in offset_m]}
    if angles_deg is not None:
        entry["angles_deg"] = {k: _checked(where, name, k, v, plausible.ANGLE)
                               for k, v in angles_deg.items()}
    entry.update(info)
    config.setdefault("sensors", {})[name] = entry
    project.put_json(VESSEL, config)


def _checked(where: str, sensor: str, what: str, value, limits) -> float:
    """*value* as a finite float within *limits*, else InputError naming the sensor."""
    try:
        number = float(value)
    except (TypeError, ValueError, OverflowError):
        raise InputError(where, f"{sensor} {what}: expected a number", field="vessel") from None
    if not math.isfinite(number) or not limits[0] <= number <= limits[1]:
        raise InputError(where, f"{sensor} {what}: " + plausible.problem(number, limits),
                         field="vessel")
    return number


def sensor_offset(project: Project, name: str) -> np.ndarray:
    """Offset of sensor *name*, body frame FRD, metres, shape (3,)."""
    sensors = vessel_config(project).get("sensors", {})
    if name not in sensors:
        raise InputError(
            str(project.path or "<project>"), f"vessel sheet has no sensor '{name}'",
            field="vessel/sensors",
        )
    return np.asarray(sensors[name]["offset_m"], dtype=float)


def lever_arm(project: Project, to: str, origin: str) -> np.ndarray:
    """Vector from sensor *origin* to sensor *to*, body frame FRD, metres, shape (3,).

    A sheet lacking either sensor raises one error naming every missing entry and the
    ways to provide them.
    """
    sensors = vessel_config(project).get("sensors", {})
    missing = [name for name in (to, origin) if name not in sensors]
    if missing:
        where = str(project.path or "<project>")
        example = " ".join(f"--set {m} X Y Z" for m in missing)
        raise InputError(
            where, f"the vessel sheet has no {' and no '.join(repr(m) for m in missing)} "
            f"sensor: set {'them' if len(missing) > 1 else 'it'} with 'hydrosync vessel "
            f"{Path(where).name if project.path else 'P.h5'} {example}' (body frame, m), "
            "with Edit → Vessel offsets… in the application, or give the lever arm "
            "directly (--lever-arm X Y Z)",
            field="vessel/sensors")
    return sensor_offset(project, to) - sensor_offset(project, origin)
