"""What a stored result was computed from, and whether that has changed since.

Every analysis records, with its result, the content hashes of the project data it read,
the vessel-sheet entries it used, its parameters, the software and plugin versions and
the time (:func:`record`). :func:`stale_reasons` compares that record with the project as
it is now: a result whose inputs changed is **out of date**, and the panel, the project
browser, ``hydrosync info``, ``hydrosync report`` and the PDF say so.

:func:`record` is the one place a result's bookkeeping is written: the JSON attribute
``provenance`` of the result group, plus the plain attributes ``software_version``,
``run_utc`` and ``params_schema_version`` that the report cover, the campaign's
up-to-date check and older readers use::

    {"inputs": {"raw/gnss": "<sha256>", ...},
     "vessel": {"gnss": {...sensor entry...} | null, ...},
     "params": {...}, "params_schema_version": 1,
     "software_version": "0.2.0", "plugin_version": "1.1.0", "run_utc": "..."}
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Iterable
from datetime import UTC, datetime

from hydrosync_core import __version__
from hydrosync_core.project import schema
from hydrosync_core.project.model import content_sha256
from hydrosync_core.project.vessel import vessel_config

ATTR = "provenance"
OUT_OF_DATE = "out of date"


def fingerprint(project, path: str) -> str | None:
    """Content hash of the node at *path* (dataset, table, JSON or any group); None if absent.

    Datasets carry their hash from the time they were written; older files without it are
    hashed from their values.
    """
    path = path.strip("/")
    if not project.exists(path):
        return None
    attrs = project.attrs(path)
    children = project.children(path)
    if not children and "sha256" in attrs:
        return str(attrs["sha256"])
    digest = hashlib.sha256()
    if schema.JSON_ATTR in attrs:
        digest.update(str(attrs[schema.JSON_ATTR]).encode())
    if not children and schema.JSON_ATTR not in attrs:
        try:
            return content_sha256(project.get(path))
        except Exception:  # an empty group
            return digest.hexdigest()
    for name in attrs.get("columns") or sorted(children):
        digest.update(f"{name}={fingerprint(project, f'{path}/{name}')};".encode())
    return digest.hexdigest()


def _sensors(project, names: Iterable[str]) -> dict:
    sensors = (vessel_config(project) or {}).get("sensors", {})
    return {name: sensors.get(name) for name in names}


def record(project, result_path: str, inputs: Iterable[str], params=None,
           vessel_sensors: Iterable[str] = (), plugin_version: str = "") -> dict:
    """Store on *result_path* what the result was computed from; return the record.

    Parameters
    ----------
    project : Project
    result_path : str
        The result group (``results/<id>``), already written.
    inputs : iterable of str
        Project paths the method read (``raw/gnss``, …).
    params : Params, optional
        The parameters used (stored as ``to_dict()`` with the schema version).
    vessel_sensors : iterable of str
        Vessel-sheet sensors whose entries the method used (empty when the parameters gave
        the values directly).
    plugin_version : str
        The analysis's own version (``PluginSpec.version``).
    """
    rec = {
        "inputs": {p.strip("/"): fingerprint(project, p) for p in inputs},
        "vessel": _sensors(project, vessel_sensors),
        "params": params.to_dict() if params is not None else None,
        "params_schema_version": type(params).SCHEMA_VERSION if params is not None else None,
        "software_version": __version__,
        "plugin_version": plugin_version,
        "run_utc": datetime.now(UTC).isoformat(timespec="seconds"),
    }
    plain = {k: rec[k] for k in ("software_version", "run_utc", "params_schema_version")
             if rec[k] is not None}
    project.set_attrs(result_path, **plain, **{ATTR: json.dumps(rec)})
    return rec


def read_record(project, result_path: str) -> dict | None:
    """The provenance record of *result_path*, None if it has none (older versions)."""
    if not project.exists(result_path):
        return None
    text = project.attrs(result_path).get(ATTR)
    try:
        return json.loads(text) if text else None
    except (TypeError, ValueError):
        return None


def stale_reasons(project, result_path: str) -> list[str]:
    """Why the result at *result_path* is out of date (empty: up to date or no result)."""
    if not project.exists(result_path):
        return []
    rec = read_record(project, result_path)
    if rec is None:
        return ["the result records no inputs (computed by an older HydroSync), so its "
                "inputs cannot be checked"]
    reasons = []
    for path, old in (rec.get("inputs") or {}).items():
        now = fingerprint(project, path)
        if now is None:
            reasons.append(f"/{path} was removed since the run")
        elif now != old:
            reasons.append(f"/{path} changed since the run")
    now_sensors = _sensors(project, (rec.get("vessel") or {}).keys())
    for name, old in (rec.get("vessel") or {}).items():
        if now_sensors.get(name) != old:
            reasons.append(f"vessel sheet entry '{name}' changed since the run")
    return reasons


def stale_results(project, specs) -> dict[str, list[str]]:
    """``{plugin id: reasons}`` of every stored result of *specs* that is out of date."""
    out = {}
    for spec in specs:
        reasons = stale_reasons(project, f"results/{spec.id}")
        if reasons:
            out[spec.id] = reasons
    return out
