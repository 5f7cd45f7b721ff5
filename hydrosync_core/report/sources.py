"""The report's appendix: where the data came from, the vessel sheet and the survey lines.

For every imported data set: the file (name, size, SHA-256), the time span (UTC and raw),
the record counts (by sentence type for device logs), the import options (heave sign,
time-tag handling, …) and every import warning; then the full vessel offset table and the
survey lines with their start and end times — what a QA lead needs to trace a number back
to the files it came from.
"""

from __future__ import annotations

import json

from reportlab.platypus import Flowable, Paragraph

from hydrosync_core.project import schema
from hydrosync_core.project.vessel import vessel_config
from hydrosync_core.report.context import ReportContext, esc
from hydrosync_core.report.styles import RULE
from hydrosync_core.timespan import span_of, table_span

HEADING = "Appendix: data sources, vessel offsets and survey lines"


def _imported(project) -> list[tuple[str, dict]]:
    """(project path, attributes) of every node that records an import."""
    return [(info.path, info.attrs) for info in project.walk(schema.RAW)
            if "imports" in info.attrs or "import_report" in info.attrs] + (
        [(schema.VESSEL, project.attrs(schema.VESSEL))]
        if project.exists(schema.VESSEL) and "imports" in project.attrs(schema.VESSEL) else [])


def _size(n: int | None) -> str:
    if n is None:
        return "size unknown"
    return f"{n / 1048576:.1f} MiB" if n >= 1048576 else f"{n / 1024:.1f} KiB"


def _dataset_rows(project, path: str, attrs: dict) -> list[tuple[str, str]]:
    rows: list[tuple[str, str]] = []
    try:
        imports = json.loads(attrs.get("imports") or "[]")
    except (TypeError, ValueError):
        imports = []
    for entry in imports:
        options = ", ".join(f"{k} = {v}" for k, v in (entry.get("options") or {}).items())
        rows.append(("File", f"{entry.get('file')} ({_size(entry.get('size_bytes'))}, "
                             f"imported {entry.get('imported_utc', '?')} as "
                             f"{entry.get('kind')}{'; ' + options if options else ''})"))
        rows.append(("SHA-256", str(entry.get("sha256"))))
    if not imports and attrs.get("source"):
        rows.append(("Source", str(attrs["source"])))
    span = table_span(project, path)
    if span is not None:
        rows.append(("Time span", span.text()))
        rows.append(("Records", f"{span.count}"))
    try:
        report = json.loads(attrs.get("import_report") or "{}")
    except (TypeError, ValueError):
        report = {}
    if report:
        counts = ", ".join(f"{k} {v}" for k, v in (report.get("sentence_counts") or {}).items())
        rows.append(("Log records", f"{report.get('used')} {report.get('source')} records used "
                                    f"of {report.get('lines')} lines" + (f" ({counts})"
                                                                         if counts else "")))
        rows.append(("Time tags", f"time from {report.get('time_source')}, date from "
                                  f"{report.get('date_source')}"
                     + (f"; logger − sentence {report['logger_minus_sentence_s']:+.3f} s"
                        if report.get("logger_minus_sentence_s") is not None else "")))
        if report.get("heave_positive"):
            rows.append(("Heave sign in file", f"positive {report['heave_positive']} "
                                               "(stored positive up)"))
        skipped = ", ".join(f"{k} {v}" for k, v in (report.get("skipped") or {}).items())
        if skipped:
            rows.append(("Set aside", skipped))
        for warning in report.get("warnings") or ():
            rows.append(("Import warning", str(warning)))
    for key, value in attrs.items():
        if key.endswith("_in_file") and not report:
            rows.append((key.replace("_in_file", "").replace("_", " ").capitalize()
                         + " in file", str(value)))
    return rows


def _vessel_table(project, ctx: ReportContext) -> list[Flowable]:
    sensors = (vessel_config(project) or {}).get("sensors", {})
    if not sensors:
        return [ctx.para("The project holds no vessel offset sheet.")]
    rows = []
    for name, entry in sensors.items():
        x, y, z = entry.get("offset_m", [float("nan")] * 3)
        angles = entry.get("angles_deg") or {}
        notes = "; ".join(f"{k}: {v}" for k, v in entry.items()
                          if k not in ("offset_m", "angles_deg"))
        rows.append([name, f"{x:+.4f}", f"{y:+.4f}", f"{z:+.4f}",
                     *(f"{angles[a]:+.4f}" if a in angles else "\u2014"
                       for a in ("roll", "pitch", "yaw")),
                     Paragraph(esc(notes), ctx.styles["Small"])])
    return ctx.table(["Sensor", "x fwd [m]", "y stbd [m]", "z down [m]", "roll [\u00b0]",
                      "pitch [\u00b0]", "yaw [\u00b0]", "Notes"], rows,
                     col_widths=[0.13, 0.1, 0.1, 0.1, 0.09, 0.09, 0.09, 0.3],
                     numeric_from=1, left_columns=[7], font_size=7.5,
                     caption="Vessel offset sheet as stored in the project (body frame, "
                     "relative to the reference point).")


#: Survey lines are listed in two column pairs (Line, Start – end) from this many on:
#: one narrow pair per row left a 500-line day's appendix 11 pages of white.
TWO_UP_LINES = 30


def _lines_table(project, ctx: ReportContext) -> list[Flowable]:
    if not project.exists("raw/lines"):
        return []
    table = project.get_table("raw/lines")
    entries = []
    for i, name in enumerate(table["name"]):
        span = span_of([table["start"][i], table["end"][i]])
        entries.append([str(name), span.text() if span else "\u2014"])
    caption = "Survey lines (raw/lines) with their start and end times."
    if len(entries) < TWO_UP_LINES:
        return ctx.table(["Line", "Start \u2013 end"], entries, col_widths=[0.15, 0.85],
                         numeric_from=2, left_columns=[1], font_size=7.5, caption=caption)
    # Row by row, two lines per row (read left to right): L001 L002 / L003 L004 / …
    if len(entries) % 2:
        entries.append(["", ""])
    rows = [entries[i] + entries[i + 1] for i in range(0, len(entries), 2)]
    return ctx.table(["Line", "Start \u2013 end"] * 2, rows,
                     col_widths=[0.08, 0.42, 0.08, 0.42], numeric_from=4, font_size=7,
                     extra_style=[("LINEBEFORE", (2, 0), (2, -1), 0.5, RULE)],
                     caption=caption + " Two lines to a row, read left to right.")


def section(project, ctx: ReportContext) -> list[Flowable]:
    """The appendix flowables."""
    out: list[Flowable] = [ctx.heading(HEADING)]
    imported = _imported(project)
    if not imported:
        out.append(ctx.para("No imported file is recorded in the project (its raw data were "
                            "written by a simulator or an older HydroSync)."))
    for path, attrs in imported:
        rows = _dataset_rows(project, path, attrs)
        if rows:
            out += ctx.key_values(rows, caption=f"/{path}", key_width=0.22)
    out.append(ctx.heading("Vessel offsets", 2))
    out += _vessel_table(project, ctx)
    lines = _lines_table(project, ctx)
    if lines:
        out.append(ctx.heading("Survey lines", 2))
        out += lines
    return out
