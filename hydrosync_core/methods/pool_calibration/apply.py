"""Apply a pool calibration to the vessel sheet (``hydrosync vessel P --apply
pool_calibration``, the panel's "Apply to vessel sheet").

The multibeam's entry becomes the calibrated values: mounting angles = the boresight
(roll, pitch, yaw of ``R_m = Rz·Ry·Rx``, degrees) and offset = the INS entry's offset plus
the calibrated lever arm (body frame x forward, y starboard, z down, metres; the lever arm
is the multibeam relative to the INS reference point). The change is recorded in the
project's history with the old and the new entry.
"""

from __future__ import annotations

import json

from hydrosync_core.errors import InputError
from hydrosync_core.project.history import add_event
from hydrosync_core.project.vessel import vessel_config
from hydrosync_core.provenance import stale_reasons

RESULT = "results/pool_calibration"
SENSOR, REFERENCE = "multibeam", "ins"


def apply_to_vessel(project, sensor: str = SENSOR, reference: str = REFERENCE) -> str:
    """Write the calibrated multibeam entry into the vessel sheet; return a summary line.

    Refuses (``InputError``) when there is no result, when it is out of date, when it did
    not converge or left a parameter undetermined, or when the sheet has no *reference*.
    """
    where = str(project.path or "<project>")
    if not project.exists(RESULT):
        raise InputError(where, "no pool calibration result to apply: run it first")
    stale = stale_reasons(project, RESULT)
    if stale:
        raise InputError(where, "the pool calibration is out of date (" + "; ".join(stale)
                         + "): run it again before applying it")
    attrs = project.attrs(RESULT)
    if not attrs.get("converged"):
        raise InputError(where, "the pool calibration did not converge: not applied")
    undetermined = json.loads(attrs.get("undetermined") or "{}")
    if undetermined:
        raise InputError(where, "the pool calibration left "
                         + ", ".join(sorted(undetermined)) + " undetermined: not applied")
    config = vessel_config(project)
    sensors = config.setdefault("sensors", {})
    if reference not in sensors:
        raise InputError(where, f"the vessel sheet has no '{reference}' sensor, which the lever "
                         f"arm is measured from: set it first (hydrosync vessel "
                         f"{project.path.name if project.path else 'P.h5'} --set {reference} "
                         "X Y Z, or Edit → Vessel offsets…)", field="vessel/sensors")
    base = sensors[reference]["offset_m"]
    lever = [float(attrs[f"lever_{k}_m"]) for k in "xyz"]
    old = sensors.get(sensor)
    new = dict(old or {})
    new["offset_m"] = [round(b + v, 6) for b, v in zip(base, lever, strict=True)]
    new["angles_deg"] = {k: round(float(attrs[f"{k}_deg"]), 6) for k in ("roll", "pitch", "yaw")}
    new["note"] = f"pool calibration of {attrs.get('run_utc', '?')} applied"
    sensors[sensor] = new
    project.put_json("vessel", config)
    add_event(project, "applied pool_calibration to the vessel sheet", sensor=sensor,
              old=old, new=new, result_run_utc=attrs.get("run_utc"),
              method=attrs.get("method"))
    a = new["angles_deg"]
    x, y, z = new["offset_m"]
    return (f"{sensor}: offset {x:+.4f} {y:+.4f} {z:+.4f} m, roll {a['roll']:+.4f} pitch "
            f"{a['pitch']:+.4f} yaw {a['yaw']:+.4f} deg (from the pool calibration of "
            f"{attrs.get('run_utc', '?')})")
