"""What ``hydrosync import`` and File → Import… can bring into a project.

The kinds come from the plugin specs (``PluginSpec.data_kinds``) plus the project's own
(the vessel sheet); adding an analysis adds its kinds without touching this file. Each
:class:`~hydrosync_core.plugins.spec.DataKind` maps a file to a project location
through a reader named by dotted path, imported only when a file is read.
"""

from __future__ import annotations

import hashlib
import json
import logging
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

from hydrosync_core.inputs import input_ok
from hydrosync_core.plugins.spec import DataKind, load_object
from hydrosync_core.project import Project, schema

log = logging.getLogger(__name__)

#: Kept for code written against the earlier name.
ImportKind = DataKind

CORE_KINDS = (
    DataKind("vessel", "vessel offset sheet vessel.json (sensor offsets, body FRD)",
             schema.VESSEL, "hydrosync_core.importers.vessel_json:read_vessel_json", "json"),
)


def collect_kinds(specs=None) -> dict[str, DataKind]:
    """Every data kind: the core's and those of *specs* (default: the registry).

    Two plugins may declare the same kind only with the same target; a clash is logged
    and the first declaration kept.
    """
    if specs is None:
        from hydrosync_core.plugins import plugin_specs

        specs = plugin_specs()
    kinds: dict[str, DataKind] = {k.name: k for k in CORE_KINDS}
    for spec in specs:
        for kind in spec.data_kinds:
            known = kinds.get(kind.name)
            if known is not None and known.target != kind.target:
                log.error("plugin %s declares data kind '%s' -> /%s, already -> /%s: ignored",
                          spec.id, kind.name, kind.target, known.target)
                continue
            kinds.setdefault(kind.name, kind)
    return kinds


def kinds() -> dict[str, DataKind]:
    """The kinds of the registry as it is now (discovery takes milliseconds; not cached, so
    an analysis installed or a registry replaced in a test is seen at once)."""
    return collect_kinds()


def __getattr__(name: str) -> Any:
    if name == "KINDS":
        return kinds()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _summary(path: Path, target: str, count: int | None, what: str) -> str:
    return (f"{count} {what} from {path.name} into /{target}" if count is not None
            else f"{path.name} into /{target}")


def import_file(project: Project, kind: str, path, *, progress=None, cancel=None,
                **options: Any) -> str:
    """Read *path* as *kind* into *project*; return a one-line summary.

    *path* may be a list of files (or glob patterns): a kind whose reader takes several
    files (``several_files``, the device logs) makes one table of them in time order;
    other kinds import them one after the other. *options* are passed to the reader
    when the kind declares them (others are an error); those given are recorded as
    attributes of the imported data. *progress* and *cancel* reach the readers that
    stream (the device logs).
    """
    table = kinds()
    if kind not in table:
        raise KeyError(f"unknown import kind '{kind}' (known: {', '.join(table)})")
    spec = table[kind]
    given = {k: v for k, v in options.items() if v is not None}
    unknown = sorted(set(given) - set(spec.options))
    if unknown:
        raise ValueError(f"import kind '{kind}' takes no option {', '.join(unknown)}")
    reader = load_object(spec.reader)
    several = getattr(reader, "several_files", None)
    if spec.store == "custom" and several is not None:
        # One table from several files (a day of hourly logs): names and globs expanded.
        files = several(path)
        message = reader(project, spec.target, files, progress=progress, cancel=cancel,
                         **given)
        for file in files:
            record_import(project, spec.target, file, kind, given)
        return message
    if isinstance(path, list | tuple):
        return "\n".join(import_file(project, kind, p, **options) for p in path)
    path = Path(path)
    if not path.is_dir():  # a recording kind takes a folder; its reader checks it
        input_ok(path, f"--{kind.replace('_', '-')} file", text=spec.store != "points")
    if spec.store == "custom":
        message = reader(project, spec.target, path, **given)
        record_import(project, spec.target, path, kind, given)
        return message
    data = reader(path, **given)
    message = _store(project, spec, path, data, given)
    record_import(project, spec.target, path, kind, given)
    return message


def _store(project: Project, spec: DataKind, path: Path, data, given: dict) -> str:
    recorded = {f"{k}_in_file": v for k, v in given.items()}
    if spec.store == "table":
        project.put_table(spec.target, data, source=str(path), **recorded)
        return _summary(path, spec.target, len(next(iter(data.values()))), "rows")
    if spec.store == "points":
        project.put(spec.target, data, attrs={"source": str(path), "frame": "target ENU",
                                              "units": "m", **recorded})
        return _summary(path, spec.target, len(data), "points")
    if spec.store == "json":
        project.put_json(spec.target, data)
        project.set_attrs(spec.target, source=str(path), **recorded)
        return _summary(path, spec.target, None, "")
    raise ValueError(f"import kind '{spec.name}' has an unknown store '{spec.store}'")


def file_sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for block in iter(lambda: handle.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def record_import(project: Project, target: str, path: Path, kind: str, options: dict) -> None:
    """Add the imported file to the ``imports`` list (JSON) of *target*.

    Each entry: ``file`` (name), ``path``, ``size_bytes``, ``sha256``, ``kind``,
    ``options`` and ``imported_utc`` — what the report's data-sources table shows. A
    target replaced by the import starts a new list; one that collects several files (an
    antenna per file) keeps one entry per file name.
    """
    try:
        size, sha = path.stat().st_size, file_sha256(path)
    except OSError:  # a reader given a stream or a file gone since: record what is known
        size, sha = None, None
    entry = {"file": path.name, "path": str(path), "size_bytes": size,
             "sha256": sha, "kind": kind, "options": dict(options),
             "imported_utc": datetime.now(UTC).isoformat(timespec="seconds")}
    try:
        entries = json.loads(project.attrs(target).get("imports", "[]"))
    except (TypeError, ValueError):
        entries = []
    entries = [e for e in entries if e.get("file") != path.name] + [entry]
    project.set_attrs(target, imports=json.dumps(entries))
