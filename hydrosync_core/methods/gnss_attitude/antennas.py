"""``antennas.json``: the antennas' phase-centre coordinates in the body frame.

```json
{"frame": "FRD", "antennas": {"A1": [0, 0, 0], "A2": [2.5, 0.0, 0.0], "A3": [0.3, 1.6, 0.0]}}
```

Body frame x forward, y starboard, z down (FRD), metres. ``frame`` may be omitted; any
other value than ``FRD`` is refused (the sign of y and z would be guessed otherwise).
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from hydrosync_core.errors import InputError


def check_antennas(document, source: str | None = None) -> dict[str, list[float]]:
    """Validated ``{name: [x, y, z]}`` (m, body FRD) from a parsed ``antennas.json``.

    Raises
    ------
    InputError
        Not an object, wrong frame, fewer than three antennas, a coordinate that is not a
        finite number, two antennas at the same place, all antennas on one line.
    """
    if not isinstance(document, dict):
        raise InputError(source, "expected a JSON object with an 'antennas' object")
    frame = str(document.get("frame", "FRD"))
    if frame.upper() != "FRD":
        raise InputError(source, f"frame '{frame[:20]}' is not FRD (x forward, y starboard, "
                         "z down)", field="frame")
    antennas = document.get("antennas")
    if not isinstance(antennas, dict):
        raise InputError(source, "'antennas' must be an object {name: [x, y, z]}",
                         field="antennas")
    out: dict[str, list[float]] = {}
    for name, xyz in antennas.items():
        if (not isinstance(xyz, list | tuple) or len(xyz) != 3
                or not all(isinstance(v, int | float) and not isinstance(v, bool)
                           and math.isfinite(v) for v in xyz)):
            raise InputError(source, "expected three finite numbers [x, y, z] in metres",
                             field=f"antennas.{name}")
        out[str(name)] = [float(v) for v in xyz]
    if len(out) < 3:
        raise InputError(source, f"{len(out)} antenna(s): attitude needs at least three",
                         field="antennas")
    pts = np.array(list(out.values()))
    names = list(out)
    for i in range(len(pts)):
        for j in range(i + 1, len(pts)):
            if np.linalg.norm(pts[i] - pts[j]) < 0.05:
                raise InputError(source, f"antennas {names[i]} and {names[j]} are less than "
                                 "5 cm apart", field="antennas")
    centred = pts - pts.mean(axis=0)
    s = np.linalg.svd(centred, compute_uv=False)
    if s[1] < 1e-3 * s[0]:
        raise InputError(source, "all antennas lie on one line: roll (or pitch) is not "
                         "observable", field="antennas")
    return out


def read_antennas_json(path: str | os.PathLike) -> dict:
    """Read and check ``antennas.json``; returns ``{"frame": "FRD", "antennas": {…}}``."""
    from hydrosync_core.configfiles import parse_json, read_config_text

    p = Path(path)
    document = parse_json(read_config_text(p, "antennas.json"), str(p))
    return {"frame": "FRD", "antennas": check_antennas(document, str(p))}
