"""Physically plausible ranges of the quantities HydroSync reads.

A value outside its range cannot be a measurement (a roll of 1e308°, a coordinate of
1e300 m): importers and the project checks reject it with a message naming the value
and the range, instead of letting it poison a result. The ranges are deliberately wide:
they catch impossible values, not unusual ones.
"""

from __future__ import annotations

import numpy as np

Limits = tuple[float, float, str]
"""(lowest, highest, unit) of a plausible value."""

TIME: Limits = (-1e11, 1e11, "s")            # ±3000 years on any scale
ROLL: Limits = (-180.0, 180.0, "deg")
PITCH: Limits = (-90.0, 90.0, "deg")
HEADING: Limits = (-360.0, 720.0, "deg")     # 0..360 or -180..180, a little unwrapped
HEAVE: Limits = (-100.0, 100.0, "m")
HEIGHT: Limits = (-1e5, 1e5, "m")            # ellipsoidal height of an antenna
LATITUDE: Limits = (-90.0, 90.0, "deg")
LONGITUDE: Limits = (-360.0, 360.0, "deg")
COORDINATE: Limits = (-1e8, 1e8, "m")        # local ENU, projected, ECEF: all well inside
SENSOR_XYZ: Limits = (-2e4, 2e4, "m")        # a sounding in the multibeam's own frame
OFFSET: Limits = (-1000.0, 1000.0, "m")      # a lever arm / sensor offset on a vessel
ANGLE: Limits = (-360.0, 360.0, "deg")       # a mounting / boresight angle
QUALITY: Limits = (-1.0, 100.0, "")
SIGMA: Limits = (0.0, 1e6, "m")

GNSS = {"time": TIME, "height": HEIGHT, "lat": LATITUDE, "lon": LONGITUDE, "quality": QUALITY,
        "sigma_h": SIGMA}
ATTITUDE = {"time": TIME, "roll": ROLL, "pitch": PITCH, "heading": HEADING, "heave": HEAVE}
LINES = {"start": TIME, "end": TIME}
MBES = {"time": TIME, "x": SENSOR_XYZ, "y": SENSOR_XYZ, "z": SENSOR_XYZ}
INS = {"time": TIME, "e": COORDINATE, "n": COORDINATE, "u": HEIGHT, "roll": ROLL,
       "pitch": PITCH, "heading": HEADING}
POINTS = {"x": COORDINATE, "y": COORDINATE, "z": COORDINATE}


def describe(limits: Limits) -> str:
    lo, hi, unit = limits
    return f"{lo:g} … {hi:g}" + (f" {unit}" if unit else "")


def first_outside(values: np.ndarray, limits: Limits) -> int | None:
    """Index of the first finite value outside *limits* (NaN is not judged here)."""
    lo, hi, _ = limits
    values = np.asarray(values, dtype=float)
    bad = (values < lo) | (values > hi)
    if not bad.any():
        return None
    return int(np.flatnonzero(bad)[0])


def problem(value: float, limits: Limits) -> str:
    """The message for *value* outside *limits*."""
    return f"value {value:g} is outside the plausible range {describe(limits)}"
