"""The project's history: changes a user made on purpose (e.g. a calibration applied to
the vessel sheet), kept as a JSON list in ``/history`` so a report can show them."""

from __future__ import annotations

from datetime import UTC, datetime

from hydrosync_core import __version__

HISTORY = "history"


def add_event(project, action: str, **details) -> dict:
    """Append one event (UTC time, action, details, software version) and return it."""
    events = list(project.get_json(HISTORY, []) or [])
    event = {"utc": datetime.now(UTC).isoformat(timespec="seconds"), "action": action,
             "software_version": __version__, **details}
    events.append(event)
    project.put_json(HISTORY, events)
    return event


def events(project) -> list[dict]:
    """Every recorded event, oldest first."""
    return list(project.get_json(HISTORY, []) or [])
