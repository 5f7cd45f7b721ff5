"""What runs on a Dask worker: import a raw-file set, run one analysis, write a report.

Each step is a plain function of picklable arguments returning a plain dict (its
*outcome*); it never raises for a problem of its project — a damaged file, missing
inputs, a failing analysis, a project another process is writing — but reports it as
``status = "failed"`` with a one-line message, so the steps of the other projects (and
the later steps of this one) go on.

Each step opens the project with its write lock, works, saves atomically and closes. A
worker killed in the middle therefore leaves the project as it was before the step (the
kernel releases the lock; the next open removes the stale temporary file), and Dask runs
the step again on another worker. A step whose result is already up to date — stored,
:func:`~hydrosync_core.provenance.stale_reasons` empty, same parameters, same schema,
software and plugin versions — is skipped (``status = "up to date"``), checked first on a
read-only open that takes no lock.

Outcome keys: ``project`` (label), ``path``, ``step`` (``import``, an analysis id or
``report``), ``status`` (``done``, ``up to date``, ``not applicable``, ``skipped``,
``failed``), ``message``, ``warnings`` (list of str), ``seconds``, ``worker``
(``host:pid``), ``run_utc`` (of the stored result), ``rows`` (the analysis's summary rows
``[quantity, value]``), ``numbers`` (the result's numeric attributes), ``data_date``.
"""

from __future__ import annotations

import json
import os
import socket
import time
from datetime import UTC, datetime
from pathlib import Path

from hydrosync_core.campaign.config import AnalysisEntry, ProjectEntry

DONE, UP_TO_DATE, NOT_APPLICABLE, SKIPPED, FAILED = (
    "done", "up to date", "not applicable", "skipped", "failed")
UNDETERMINED = "done, undetermined"
"""Run and saved, but the data did not decide: not converged, or parameters left
undetermined (the ``converged``/``undetermined`` attributes of the result)."""
OK_STATES = (DONE, UNDETERMINED, UP_TO_DATE, NOT_APPLICABLE)
#: Numeric result attributes that are bookkeeping, not figures.
BOOKKEEPING = {"params_schema_version", "schema_version"}


def _outcome(entry: ProjectEntry, step: str) -> dict:
    return {"project": entry.label, "path": entry.path, "date": entry.date, "step": step,
            "status": FAILED, "message": "", "warnings": [], "seconds": 0.0,
            "worker": f"{socket.gethostname()}:{os.getpid()}", "run_utc": None, "rows": [],
            "numbers": {}, "data_date": None}


def undetermined_reason(attrs: dict) -> str:
    """Why a stored result is not determined by its data ("" when it is)."""
    reasons = []
    if "converged" in attrs and not bool(attrs["converged"]):
        reasons.append("did not converge")
    try:
        names = json.loads(attrs.get("undetermined") or "{}")
    except (TypeError, ValueError):
        names = {}
    if names:
        reasons.append("undetermined: " + ", ".join(sorted(names)))
    return "; ".join(reasons)


def _error_text(exc: BaseException) -> str:
    one_line = getattr(exc, "one_line", None)
    text = one_line() if callable(one_line) else f"{type(exc).__name__}: {exc}"
    return " ".join(text.split())[:400]


def _blocked(previous) -> str:
    """Why a step cannot run after *previous* (an import that failed), or ''."""
    items = previous if isinstance(previous, list) else [previous]
    for item in items:
        if isinstance(item, dict) and item.get("step") == "import" and \
                item.get("status") == FAILED:
            return "the project could not be imported"
    return ""


# ------------------------------------------------------------------------------ import
def import_step(entry: ProjectEntry) -> dict:
    """Create *entry*'s project from its raw-file set (nothing if it exists already)."""
    from hydrosync_core.importers.kinds import import_file, kinds
    from hydrosync_core.project import Project

    out = _outcome(entry, "import")
    t0 = time.perf_counter()
    try:
        source = entry.source
        if source is None or Path(entry.path).exists():
            out.update(status=UP_TO_DATE, message="project exists")
            return out
        if source.problem:
            out["message"] = f"{source.folder}: {source.problem}"
            return out
        Path(entry.path).parent.mkdir(parents=True, exist_ok=True)
        table = kinds()
        project = Project.create(entry.path, name=entry.label)
        try:
            messages = []
            for kind, file in source.files:
                options = {k: v for k, v in source.options.items()
                           if k in table[kind].options}
                messages.append(import_file(project, kind, file, **options))
            project.save()
        finally:
            project.close()
        out.update(status=DONE, message=f"{len(messages)} file(s) imported")
    except Exception as exc:  # reported, never raised: the other projects go on
        out["message"] = _error_text(exc)
    finally:
        out["seconds"] = time.perf_counter() - t0
    return out


# ---------------------------------------------------------------------------- analysis
def up_to_date(project, spec, params) -> bool:
    """Is ``results/<id>`` stored with these parameters, these versions, unchanged inputs?"""
    from hydrosync_core import __version__
    from hydrosync_core.provenance import read_record, stale_reasons

    path = f"results/{spec.id}"
    record = read_record(project, path)
    if record is None or stale_reasons(project, path):
        return False
    same_params = json.loads(json.dumps(params.to_dict())) == record.get("params")
    same_schema = record.get("params_schema_version") == type(params).SCHEMA_VERSION
    same_software = record.get("software_version") == __version__
    # Some analyses do not record their own version: then the software version decides.
    recorded_plugin = record.get("plugin_version")
    same_plugin = not recorded_plugin or recorded_plugin == spec.version
    return same_params and same_schema and same_software and same_plugin


def _summary_function(spec):
    if not spec.report_section:
        return None
    from hydrosync_core.plugins.spec import load_object

    try:
        return load_object(spec.report_section.partition(":")[0] + ":summary")
    except (AttributeError, ImportError):
        return None


def collect_figures(project, spec, out: dict) -> None:
    """Key figures of the stored result into *out*: rows, numbers, warnings, run time."""
    from hydrosync_core.provenance import read_record
    from hydrosync_core.timespan import table_span

    path = f"results/{spec.id}"
    attrs = project.attrs(path)
    numbers = {}
    for key, value in attrs.items():
        if key in BOOKKEEPING or isinstance(value, bool) or hasattr(value, "__len__"):
            continue
        try:
            numbers[key] = float(value)
        except (TypeError, ValueError):
            continue
    out["numbers"] = numbers
    warnings = []
    try:
        stored = json.loads(attrs.get("warnings") or "[]")
        warnings += [str(w) for w in stored] if isinstance(stored, list) else []
    except (TypeError, ValueError):
        pass
    if attrs.get("converged") is not None and not bool(attrs.get("converged")):
        warnings.append("not converged")
    out["warnings"] = warnings
    record = read_record(project, path) or {}
    out["run_utc"] = record.get("run_utc") or attrs.get("run_utc")
    summary = _summary_function(spec)
    if summary is not None:
        try:
            out["rows"] = [[str(q), str(v)] for q, v in summary(project)]
        except Exception as exc:  # the figures are a courtesy: the result is stored
            out["warnings"].append(f"summary rows unavailable ({_error_text(exc)})")
    for required in spec.requires:
        span = table_span(project, required)
        if span is not None and span.is_unix:
            out["data_date"] = datetime.fromtimestamp(span.start, UTC).date().isoformat()
            break


def analysis_step(entry: ProjectEntry, analysis: AnalysisEntry, previous=None) -> dict:
    """Run *analysis* on *entry*'s project unless its stored result is up to date.

    *previous* is the outcome of the step before on the same project (passed so that
    Dask runs the steps of one project one after the other: they all need its write lock).
    """
    from hydrosync_core.plugins import get_spec
    from hydrosync_core.project import Project

    out = _outcome(entry, analysis.id)
    t0 = time.perf_counter()
    try:
        blocked = _blocked(previous)
        if blocked:
            out.update(status=SKIPPED, message=blocked)
            return out
        spec = get_spec(analysis.id)
        params = spec.load_params().from_dict(analysis.params, strict=True)
        with Project.open(entry.path, readonly=True) as project:
            missing = spec.missing_inputs(project)
            if missing:
                out.update(status=NOT_APPLICABLE, message="no input " + ", ".join(
                    "/" + m for m in missing))
                return out
            if up_to_date(project, spec, params):
                collect_figures(project, spec, out)
                out.update(status=UP_TO_DATE, message="result up to date: not run again")
                return out
        project = Project.open(entry.path)  # the write lock, held until close
        try:
            if up_to_date(project, spec, params):  # done meanwhile by a retried step
                out.update(status=UP_TO_DATE, message="result up to date: not run again")
            else:
                spec.load_run()(project, params, None, None)
                project.save()
                out.update(status=DONE, message="")
                why = undetermined_reason(project.attrs(f"results/{spec.id}"))
                if why:
                    out.update(status=UNDETERMINED, message=why)
            collect_figures(project, spec, out)
        finally:
            project.close()
    except Exception as exc:  # reported, never raised: the other projects go on
        out.update(status=FAILED, message=_error_text(exc))
    finally:
        out["seconds"] = time.perf_counter() - t0
    return out


def plan_status(entry: ProjectEntry, analysis: AnalysisEntry) -> str:
    """What :func:`analysis_step` would do now (``--dry-run``), without taking the lock."""
    from hydrosync_core.plugins import get_spec
    from hydrosync_core.project import Project

    if not Path(entry.path).exists():
        return "will run after the import" if entry.source is not None else "project missing"
    try:
        spec = get_spec(analysis.id)
        params = spec.load_params().from_dict(analysis.params, strict=True)
        with Project.open(entry.path, readonly=True) as project:
            missing = spec.missing_inputs(project)
            if missing:
                return NOT_APPLICABLE + " (no input " + ", ".join("/" + m for m in missing) + ")"
            if up_to_date(project, spec, params):
                return UP_TO_DATE
            if project.exists(f"results/{spec.id}"):
                return "will run (stored result out of date or made with other parameters)"
            return "will run"
    except Exception as exc:
        return f"will fail: {_error_text(exc)}"


# ------------------------------------------------------------------------------ report
def report_step(entry: ProjectEntry, out_dir: str, previous=None) -> dict:
    """Write ``out_dir/reports/<label>.pdf`` unless it is newer than the project."""
    from hydrosync_core.project import Project
    from hydrosync_core.report import build_report

    out = _outcome(entry, "report")
    t0 = time.perf_counter()
    try:
        blocked = _blocked(previous)
        if blocked:
            out.update(status=SKIPPED, message=blocked)
            return out
        pdf = Path(out_dir) / "reports" / f"{entry.label}.pdf"
        out["message"] = str(pdf)
        project_file = Path(entry.path)
        if pdf.exists() and pdf.stat().st_mtime_ns >= project_file.stat().st_mtime_ns:
            out["status"] = UP_TO_DATE
            return out
        pdf.parent.mkdir(parents=True, exist_ok=True)
        problems: list[str] = []
        with Project.open(project_file, readonly=True) as project:
            build_report(project, pdf, problems=problems)
        out.update(status=DONE, warnings=problems)
    except Exception as exc:  # reported, never raised
        out.update(status=FAILED, message=_error_text(exc))
    finally:
        out["seconds"] = time.perf_counter() - t0
    return out
