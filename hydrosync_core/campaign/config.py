"""Reading a campaign file (TOML) and planning its steps.

The format is documented in ``docs/formats.md`` ("Campaign file"). Everything is checked
here, before any work: the TOML syntax, unknown tables and keys, the analyses (known ids,
parameters validated by each analysis's own schema with ``strict=True``), the import
recipe (known data kinds, the options those kinds accept, the vessel sheet) and that at
least one project results. A problem is an :class:`~hydrosync_core.errors.InputError`
naming the campaign file and the key (``analyses.latency.step_s``): the command prints one
line and exits with 2.

Relative paths in the file are relative to the file's folder. This module imports
neither dask nor any analysis's method (only the parameter schemas).
"""

from __future__ import annotations

import datetime as _dt
import glob
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hydrosync_core.errors import InputError

TOP_KEYS = {"campaign", "projects", "import", "analyses", "outputs"}
CAMPAIGN_KEYS = {"name"}
PROJECTS_KEYS = {"files", "glob"}
PROJECT_ENTRY_KEYS = {"path", "date", "label"}
IMPORT_KEYS = {"sets", "project", "vessel", "files", "options"}
OUTPUT_KEYS = {"dir", "report", "summary"}

_DATE = re.compile(r"(?<!\d)(\d{4})-?(\d{2})-?(\d{2})(?!\d)")


@dataclass(frozen=True)
class AnalysisEntry:
    """One analysis of the campaign: its id, name and validated parameters."""

    id: str
    name: str
    params: dict[str, Any]
    """``Params.to_dict()`` of the validated parameters (every field, JSON-ready)."""
    given: dict[str, Any] = field(default_factory=dict)
    """What the campaign file set (for ``--dry-run``)."""


@dataclass(frozen=True)
class ImportSet:
    """A folder of raw files to import into a new project."""

    folder: str
    files: tuple[tuple[str, str], ...]
    """``(kind, file)`` pairs, in import order (the vessel sheet first)."""
    options: dict[str, Any]
    problem: str = ""
    """Why this set cannot be imported (found while planning; the import step fails)."""


@dataclass(frozen=True)
class ProjectEntry:
    """One project of the campaign."""

    label: str
    path: str
    date: str | None = None
    """ISO date of the survey day (for the trends), if known."""
    source: ImportSet | None = None
    """Raw files to import when the project does not exist yet."""


@dataclass(frozen=True)
class Outputs:
    dir: str
    report: bool = True
    summary: bool = True


@dataclass(frozen=True)
class Campaign:
    """A checked campaign file."""

    path: str
    name: str
    projects: tuple[ProjectEntry, ...]
    analyses: tuple[AnalysisEntry, ...]
    outputs: Outputs
    notes: tuple[str, ...] = ()
    """Things worth telling (a glob that matched nothing, a duplicate project dropped)."""

    def plan_lines(self) -> list[str]:
        """What would run, one line each (``hydrosync batch --dry-run``)."""
        out = [f"campaign '{self.name}' ({self.path}): {len(self.projects)} project(s) x "
               f"{len(self.analyses)} analysis(es); outputs in {self.outputs.dir}"]
        for a in self.analyses:
            given = ", ".join(f"{k}={v}" for k, v in a.given.items()) or "defaults"
            out.append(f"  analysis {a.id} ({a.name}): {given}")
        for p in self.projects:
            date = f" [{p.date}]" if p.date else ""
            if p.source is not None and not Path(p.path).exists():
                what = (f"import from {p.source.folder}: "
                        + ", ".join(f"{k}={Path(f).name}" for k, f in p.source.files))
                if p.source.problem:
                    what += f" -- WILL FAIL: {p.source.problem}"
            elif Path(p.path).exists():
                what = "existing project"
            else:
                what = "MISSING (will fail)"
            out.append(f"  project {p.label}{date}: {p.path} ({what})")
        outputs = []
        if self.outputs.report:
            outputs.append(f"PDF per project in {Path(self.outputs.dir) / 'reports'}")
        if self.outputs.summary:
            outputs.append("summary.csv and summary.html")
        out.append("  outputs: " + ("; ".join(outputs) or "none"))
        out += [f"  note: {n}" for n in self.notes]
        return out


# ----------------------------------------------------------------------------- reading
def load_campaign(path: str | Path, specs=None) -> Campaign:
    """Read and check the campaign file *path*; raise :class:`InputError` on any problem."""
    from hydrosync_core.configfiles import parse_toml, read_config_text

    path = Path(path)
    doc = parse_toml(read_config_text(path, "campaign file"), str(path))
    return parse_campaign(doc, path, specs)


def _table(doc: dict, key: str, where: str, allowed: set[str] | None) -> dict:
    value = doc.get(key, {})
    if not isinstance(value, dict):
        raise InputError(where, f"'{key}' must be a table ([{key}])", field=key)
    if allowed is not None:
        unknown = sorted(set(value) - allowed)
        if unknown:
            raise InputError(where, f"unknown key '{unknown[0]}' in [{key}] (known: "
                             f"{', '.join(sorted(allowed))})", field=f"{key}.{unknown[0]}")
    return value


def _strings(value, where: str, key: str) -> list[str]:
    if isinstance(value, str):
        return [value]
    if isinstance(value, list) and all(isinstance(v, str) for v in value):
        return list(value)
    raise InputError(where, "must be a string or a list of strings", field=key)


def _resolve(base: Path, text: str) -> Path:
    p = Path(text).expanduser()
    return p if p.is_absolute() else base / p


def _date_text(value, where: str, key: str) -> str:
    if isinstance(value, _dt.datetime):
        return value.date().isoformat()
    if isinstance(value, _dt.date):
        return value.isoformat()
    if isinstance(value, str):
        try:
            return _dt.date.fromisoformat(value).isoformat()
        except ValueError:
            pass
    raise InputError(where, f"'{value}' is not a date (YYYY-MM-DD)", field=key)


def date_from_name(name: str) -> str | None:
    """The first plausible ``YYYY-MM-DD`` / ``YYYYMMDD`` in *name*, as ISO text."""
    for match in _DATE.finditer(name):
        try:
            return _dt.date(*(int(g) for g in match.groups())).isoformat()
        except ValueError:
            continue
    return None


def _specs_by_id(specs) -> dict:
    if specs is None:
        from hydrosync_core.plugins import plugin_specs

        specs = plugin_specs()
    return {s.id: s for s in specs}


def _analyses(doc: dict, where: str, specs: dict) -> tuple[AnalysisEntry, ...]:
    table = _table(doc, "analyses", where, None)
    if not table:
        raise InputError(where, "no analyses: add at least one [analyses.<id>] table "
                         f"(known: {', '.join(specs)})", field="analyses")
    out = []
    for analysis_id, given in table.items():
        key = f"analyses.{analysis_id}"
        if analysis_id not in specs:
            raise InputError(where, f"unknown analysis '{analysis_id}' (known: "
                             f"{', '.join(specs)})", field=key)
        if not isinstance(given, dict):
            raise InputError(where, f"'{key}' must be a table of parameters", field=key)
        spec = specs[analysis_id]
        schema = spec.load_params()
        try:
            params = schema.from_dict(given, strict=True)
        except InputError as exc:
            name = f"{key}.{exc.field}" if exc.field else key
            raise InputError(where, exc.message, field=name) from None
        except (TypeError, ValueError) as exc:
            raise InputError(where, str(exc), field=key) from None
        out.append(AnalysisEntry(analysis_id, spec.name, params.to_dict(), dict(given)))
    return tuple(out)


def _explicit_projects(projects: dict, base: Path, where: str) -> list[ProjectEntry]:
    out = []
    for i, item in enumerate(projects.get("files", []) or []):
        key = f"projects.files[{i}]"
        if isinstance(item, str):
            item = {"path": item}
        if not isinstance(item, dict) or not isinstance(item.get("path"), str):
            raise InputError(where, "a project is a path or a table with 'path'", field=key)
        unknown = sorted(set(item) - PROJECT_ENTRY_KEYS)
        if unknown:
            raise InputError(where, f"unknown key '{unknown[0]}' (known: "
                             f"{', '.join(sorted(PROJECT_ENTRY_KEYS))})", field=key)
        path = _resolve(base, item["path"])
        date = (_date_text(item["date"], where, f"{key}.date") if "date" in item
                else date_from_name(path.stem))
        out.append(ProjectEntry(str(item.get("label") or path.stem), str(path), date))
    if "files" in projects and not isinstance(projects["files"], list):
        raise InputError(where, "must be a list", field="projects.files")
    return out


def _globbed_projects(projects: dict, base: Path, where: str,
                      notes: list[str]) -> list[ProjectEntry]:
    out = []
    for pattern in _strings(projects.get("glob", []), where, "projects.glob"):
        matches = sorted(glob.glob(str(_resolve(base, pattern)), recursive=True))
        matches = [m for m in matches if Path(m).is_file()]
        if not matches:
            notes.append(f"projects.glob '{pattern}' matched no file")
        out += [ProjectEntry(Path(m).stem, m, date_from_name(Path(m).stem)) for m in matches]
    return out


def _imported_projects(recipe: dict, base: Path, where: str,
                       notes: list[str]) -> list[ProjectEntry]:
    if not recipe:
        return []
    from hydrosync_core.importers.kinds import kinds

    known = kinds()
    if "sets" not in recipe:
        raise InputError(where, "the import recipe needs 'sets' (folders of raw files)",
                         field="import.sets")
    files = recipe.get("files", {})
    if not isinstance(files, dict) or not files:
        raise InputError(where, "the import recipe needs a [import.files] table: data kind "
                         "= file name or pattern in each set folder", field="import.files")
    for kind, pattern in files.items():
        if kind not in known or kind == "vessel":
            raise InputError(where, f"unknown data kind '{kind}' (known: "
                             f"{', '.join(k for k in known if k != 'vessel')})",
                             field=f"import.files.{kind}")
        if not isinstance(pattern, str):
            raise InputError(where, "must be a file name or pattern", field=f"import.files.{kind}")
    options = recipe.get("options", {})
    if not isinstance(options, dict):
        raise InputError(where, "must be a table", field="import.options")
    accepted = {o for kind in files for o in known[kind].options}
    for name in options:
        if name not in accepted:
            raise InputError(where, f"no data kind of the recipe takes the option '{name}' "
                             f"(accepted: {', '.join(sorted(accepted)) or 'none'})",
                             field=f"import.options.{name}")
    vessel = recipe.get("vessel")
    if vessel is not None:
        if not isinstance(vessel, str):
            raise InputError(where, "must be a file name", field="import.vessel")
        vessel = _resolve(base, vessel)
        if not vessel.is_file():
            raise InputError(str(vessel), "no such vessel sheet", field="import.vessel")
    template = recipe.get("project", "{set}.h5")
    if not isinstance(template, str) or "{set}" not in template:
        raise InputError(where, "must be a path containing '{set}' (the set folder's name)",
                         field="import.project")
    out = []
    for pattern in _strings(recipe["sets"], where, "import.sets"):
        folders = [Path(m) for m in sorted(glob.glob(str(_resolve(base, pattern))))
                   if Path(m).is_dir()]
        if not folders:
            notes.append(f"import.sets '{pattern}' matched no folder")
        for folder in folders:
            pairs: list[tuple[str, str]] = [("vessel", str(vessel))] if vessel else []
            problems = []
            for kind, file_pattern in files.items():
                found = sorted(glob.glob(str(folder / file_pattern)))
                if not found:
                    problems.append(f"no {file_pattern} for {kind}")
                elif len(found) > 1 and known[kind].store != "custom":
                    problems.append(f"{len(found)} files match {file_pattern} for {kind} "
                                    "(one expected)")
                pairs += [(kind, f) for f in found]
            target = _resolve(base, template.replace("{set}", folder.name))
            out.append(ProjectEntry(
                folder.name, str(target), date_from_name(folder.name),
                ImportSet(str(folder), tuple(pairs), dict(options), "; ".join(problems))))
    return out


def parse_campaign(doc: dict, path: Path, specs=None) -> Campaign:
    """Check a parsed campaign document (see :func:`load_campaign`)."""
    where = str(path)
    base = path.parent
    unknown = sorted(set(doc) - TOP_KEYS)
    if unknown:
        raise InputError(where, f"unknown table '{unknown[0]}' (known: "
                         f"{', '.join(sorted(TOP_KEYS))})", field=unknown[0])
    head = _table(doc, "campaign", where, CAMPAIGN_KEYS)
    name = head.get("name", path.stem)
    if not isinstance(name, str):
        raise InputError(where, "must be a string", field="campaign.name")
    analyses = _analyses(doc, where, _specs_by_id(specs))

    notes: list[str] = []
    projects = _table(doc, "projects", where, PROJECTS_KEYS)
    entries = _explicit_projects(projects, base, where)
    entries += _globbed_projects(projects, base, where, notes)
    entries += _imported_projects(_table(doc, "import", where, IMPORT_KEYS), base, where,
                                  notes)
    unique: dict[str, ProjectEntry] = {}
    for entry in entries:
        key = str(Path(entry.path).resolve())
        if key in unique:
            notes.append(f"{entry.path} is listed twice: run once")
            continue
        unique[key] = entry
    if not unique:
        raise InputError(where, "no projects: [projects] files/glob and [import] sets give "
                         "none" + (f" ({'; '.join(notes)})" if notes else ""), field="projects")
    labels: dict[str, int] = {}
    final = []
    for entry in unique.values():  # labels name rows of the summary: keep them unique
        n = labels.get(entry.label, 0)
        labels[entry.label] = n + 1
        final.append(entry if n == 0 else ProjectEntry(f"{entry.label}~{n + 1}", entry.path,
                                                       entry.date, entry.source))

    out = _table(doc, "outputs", where, OUTPUT_KEYS)
    out_dir = out.get("dir", f"{path.stem}-output")
    if not isinstance(out_dir, str):
        raise InputError(where, "must be a folder name", field="outputs.dir")
    flags = {}
    for key in ("report", "summary"):
        value = out.get(key, True)
        if not isinstance(value, bool):
            raise InputError(where, "must be true or false", field=f"outputs.{key}")
        flags[key] = value
    outputs = Outputs(str(_resolve(base, out_dir)), **flags)
    if (flags.get("report", True) or flags.get("summary", True)) and \
            Path(outputs.dir).exists() and not Path(outputs.dir).is_dir():
        raise InputError(where, f"{outputs.dir} exists and is not a folder",
                         field="outputs.dir")
    return Campaign(where, name, tuple(final), analyses, outputs, tuple(notes))
