"""Cover page, contents and the summary table of all modules.

The summary asks each plugin's section module for an optional
``summary(project) -> list[tuple[str, str]]`` (quantity, formatted value); a module that
was not run is listed with the reason (which inputs are missing).
"""

from __future__ import annotations

import hashlib
import logging
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

from reportlab.lib.units import mm
from reportlab.platypus import Flowable, PageBreak, Paragraph, Spacer, Table, TableStyle
from reportlab.platypus.tableofcontents import TableOfContents

from hydrosync_core import __version__
from hydrosync_core.errors import InputError
from hydrosync_core.i18n import tr
from hydrosync_core.plugins.spec import PluginSpec, load_object
from hydrosync_core.project.vessel import vessel_config
from hydrosync_core.provenance import OUT_OF_DATE, stale_reasons
from hydrosync_core.report.context import ReportContext, esc, utc_text
from hydrosync_core.report.styles import ACCENT, FONT, FONT_BOLD, INK, RULE

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class ModuleStatus:
    """Whether one plugin's results are in the project, and its summary rows."""

    spec: PluginSpec
    has_results: bool
    reason: str
    run_utc: str
    software_version: str
    rows: tuple[tuple[str, str], ...]
    #: Why the stored result no longer matches its inputs (empty: up to date).
    stale: tuple[str, ...] = ()
    #: (quantity, reason) of the summary rows the analysis flags (its ``flags()``).
    flags: tuple[tuple[str, str], ...] = ()

    def flag(self, quantity: str) -> str:
        """Why *quantity* is flagged ("" if it is not)."""
        return dict(self.flags).get(quantity, "")


def results_path(spec: PluginSpec) -> str:
    return f"results/{spec.id}"


def module_status(project, spec: PluginSpec) -> ModuleStatus:
    """Collect the status line and key results of *spec*'s module."""
    path = results_path(spec)
    if not project.exists(path):
        missing = spec.missing_inputs(project)
        reason = ("not run: inputs missing (" + ", ".join("/" + m for m in missing) + ")"
                  if missing else "not run (inputs present)")
        return ModuleStatus(spec, False, reason, "", "", ())
    attrs = project.attrs(path)
    rows: tuple[tuple[str, str], ...] = ()
    if spec.report_section:
        module_name = spec.report_section.partition(":")[0]
        try:
            summary = load_object(f"{module_name}:summary")
            rows = tuple((str(k), str(v)) for k, v in summary(project))
        except AttributeError:
            rows = ()
        except Exception as exc:  # a plugin's summary must not sink the whole report
            log.error("summary of %s failed: %s", spec.id, exc)
            rows = (("summary unavailable", f"{type(exc).__name__}: {exc}"),)
    flags = _flags(project, spec)
    try:
        stale = tuple(stale_reasons(project, path))
    except InputError as exc:  # a damaged project: flag the results, the report goes on
        stale = (f"whether they are up to date cannot be checked ({exc.message})",)
    return ModuleStatus(spec, True, "run", str(attrs.get("run_utc", "")),
                        str(attrs.get("software_version", "")), rows, stale, flags)


def _flags(project, spec: PluginSpec) -> tuple[tuple[str, str], ...]:
    """The analysis's flagged summary quantities (its optional ``flags(project)``)."""
    if not spec.report_section:
        return ()
    try:
        found = load_object(f"{spec.report_section.partition(':')[0]}:flags")
    except AttributeError:
        return ()
    try:
        return tuple((str(k), str(v)) for k, v in dict(found(project)).items())
    except Exception as exc:  # a faulty flag check: say so in the summary, go on
        log.error("flags of %s failed: %s", spec.id, exc)
        return (("(flags)", f"could not be checked: {type(exc).__name__}: {exc}"),)


def file_sha256(path: Path | None) -> str:
    """SHA-256 of the saved project file (what the reader can check the report against)."""
    if path is None or not Path(path).exists():
        return "not saved"
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            digest.update(chunk)
    return digest.hexdigest()


def cover_page(project, ctx: ReportContext, statuses: list[ModuleStatus]) -> list[Flowable]:
    """Title block, project identification, and a sign-off box."""
    attrs = project.attrs_root
    try:
        vessel = vessel_config(project).get("name") or "(not set in the vessel sheet)"
    except InputError as exc:  # a damaged sheet: say so, the report goes on
        vessel = f"(the vessel sheet could not be read: {exc.message})"
    now = datetime.now(UTC).strftime("%Y-%m-%d %H:%M:%S UTC")
    path = project.path
    run = [tr(s.spec.name) for s in statuses if s.has_results]
    pairs = [
        ("Project", project.name or "(unnamed)"),
        ("Vessel", vessel),
        ("Report date", now),
        ("Software", f"HydroSync {__version__}"),
        ("Project file", str(path) if path else "(not saved)"),
        ("Project file SHA-256", file_sha256(path)
         + (" (the project has unsaved changes)" if project.dirty else "")),
        ("Project created", utc_text(attrs.get("created"))),
        ("Project last saved", utc_text(attrs.get("modified")) if path is not None
         and Path(path).exists() else "never (the project exists only in memory)"),
        ("Modules with results", ", ".join(run) if run else "none"),
    ]
    out: list[Flowable] = [
        Spacer(1, 30 * mm),
        Paragraph(tr("Sensor calibration report"), ctx.styles["Title"]),
        Paragraph(esc(project.name or tr("Untitled project")), ctx.styles["Subtitle"]),
    ]
    rows = [[Paragraph(f"<b>{esc(tr(k))}</b>", ctx.styles["Cell"]),
             Paragraph(esc(tr(v)), ctx.styles["Cell"])] for k, v in pairs]
    info = Table(rows, colWidths=[0.26 * ctx.width, 0.74 * ctx.width], hAlign="LEFT")
    info.setStyle(TableStyle([
        ("VALIGN", (0, 0), (-1, -1), "TOP"),
        ("LINEBELOW", (0, 0), (-1, -1), 0.4, RULE),
        ("LINEABOVE", (0, 0), (-1, 0), 0.8, ACCENT),
        ("TOPPADDING", (0, 0), (-1, -1), 4),
        ("BOTTOMPADDING", (0, 0), (-1, -1), 4),
    ]))
    out += [info, Spacer(1, 25 * mm), _signoff(ctx), PageBreak()]
    return out


def _signoff(ctx: ReportContext) -> Table:
    head = ["", tr("Name", context="signoff"), tr("Signature"), tr("Date")]
    rows = [head] + [[tr(role), "", "", ""]
                     for role in ("Prepared by", "Checked by", "Approved by")]
    table = Table(rows, colWidths=[0.2 * ctx.width, 0.3 * ctx.width, 0.3 * ctx.width,
                                   0.2 * ctx.width], rowHeights=[14] + [26] * 3, hAlign="LEFT")
    table.setStyle(TableStyle([
        ("FONT", (0, 0), (-1, -1), FONT, 8.5),
        ("FONT", (0, 0), (-1, 0), FONT_BOLD, 8.5),
        ("TEXTCOLOR", (0, 0), (-1, -1), INK),
        ("GRID", (0, 0), (-1, -1), 0.5, RULE),
        ("VALIGN", (0, 0), (-1, -1), "MIDDLE"),
    ]))
    return table


def contents_and_summary(ctx: ReportContext, statuses: list[ModuleStatus]) -> list[Flowable]:
    """Table of contents, then one summary table over every registered module."""
    toc = TableOfContents()
    toc.levelStyles = [ctx.styles["TOC1"], ctx.styles["TOC2"]]
    toc.dotsMinLevel = 0
    out: list[Flowable] = [Paragraph(tr("Contents"), ctx.styles["ContentsTitle"]), toc,
                           Spacer(1, 10), ctx.heading("Summary of results")]
    if not statuses:
        out.append(ctx.para("No analysis module is installed."))
        return out
    rows = []
    separators = []
    flagged = 0
    for s in statuses:
        if rows:
            separators.append(("LINEABOVE", (0, len(rows) + 1), (-1, len(rows) + 1), 0.5, RULE))
        name = Paragraph(f"<b>{esc(tr(s.spec.name))}</b>"
                         + (f"<br/><font color='#b00000'><b>{tr(OUT_OF_DATE.upper())}</b></font>"
                            if s.stale else ""), ctx.styles["Cell"])
        if not s.has_results:
            rows.append([name, Paragraph(esc(tr(s.reason)), ctx.styles["Cell"]), "", ""])
            continue
        summary_rows = list(s.rows)
        # A flag whose quantity has no summary row still shows (never silently dropped).
        summary_rows += [(q, "\u2014") for q, _ in s.flags if q not in dict(s.rows)]
        if not summary_rows:
            rows.append([name, "results stored", "see section", ""])
        for i, (quantity, value) in enumerate(summary_rows):
            reason = s.flag(quantity)
            if reason:  # as the panel flags it: red, with why
                flagged += 1
                quantity_text = f"<font color='#a32020'><b>\u2691 {esc(tr(quantity))}</b></font>"
                value_text = (f"<font color='#a32020'><b>{esc(value)}</b></font><br/>"
                              f"<font size='7' color='#a32020'>{esc(tr('flagged'))}: "
                              f"{esc(tr(reason))}</font>")
            else:
                quantity_text, value_text = esc(tr(quantity)), esc(tr(value))
            rows.append([name if i == 0 else "", Paragraph(quantity_text, ctx.styles["Cell"]),
                         Paragraph(value_text, ctx.styles["Cell"]),
                         Paragraph(f"{esc(utc_text(s.run_utc))}<br/>HydroSync "
                                   f"{esc(s.software_version)}" if i == 0 else "",
                                   ctx.styles["Small"])])
    out += ctx.table(["Module", "Quantity", "Value", "Computed (UTC, version)"], rows,
                     col_widths=[0.17, 0.31, 0.28, 0.24], numeric_from=4, zebra=False,
                     extra_style=[("VALIGN", (0, 1), (-1, -1), "TOP"), *separators],
                     caption="Key results of every module. Values are the final, corrected "
                     "values; uncertainties are one standard deviation unless stated."
                     + (" \u2691 marks a value the analysis flags (in red, with why)."
                        if flagged else ""))
    for s in statuses:
        if s.stale:
            out.append(ctx.warning(f"{s.spec.name} results are {OUT_OF_DATE}: "
                                   + "; ".join(s.stale) + ". They were computed from other "
                                   "inputs than the project now holds; run the analysis again "
                                   "before signing."))
    not_run = [s.spec.name for s in statuses if not s.has_results]
    if not_run:
        out.append(ctx.para("Modules not run (their sections are omitted): "
                            + esc(", ".join(not_run)) + "."))
    return out
