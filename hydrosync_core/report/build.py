"""Assemble the PDF report of a project: cover, contents, summary, one section per plugin.

Sections come from the plugins: ``spec.report_section`` is the dotted path of
``section(project, ctx) -> list[Flowable]``. A module without results gets no section
(the summary says it was not run). A section that cannot be produced — a damaged project
(:class:`~hydrosync_core.errors.ProjectDataError`) or a faulty plugin — is never silently
missing: the PDF shows its heading and "could not be produced: <reason>", and the reason
is added to the caller's *problems* list (``hydrosync report`` warns, and fails with
``--strict``).
"""

from __future__ import annotations

import logging
import os
import re
from pathlib import Path

from reportlab.platypus import CondPageBreak, Flowable

from hydrosync_core import __version__
from hydrosync_core.atomic import atomic_path
from hydrosync_core.errors import InputError, clip
from hydrosync_core.i18n import language, normalise, tr, using
from hydrosync_core.plugins import plugin_specs
from hydrosync_core.plugins.spec import PluginSpec, load_object
from hydrosync_core.progress import check_cancel, report
from hydrosync_core.report.context import ReportContext, esc
from hydrosync_core.report.cover import (
    ModuleStatus,
    contents_and_summary,
    cover_page,
    module_status,
    results_path,
)
from hydrosync_core.report.sources import section as sources_section
from hydrosync_core.report.styles import language_fonts
from hydrosync_core.report.template import NumberedCanvas, PageLayout, ReportDocTemplate

log = logging.getLogger(__name__)


def _generic_section(project, ctx: ReportContext, spec: PluginSpec) -> list[Flowable]:
    """Fallback for a plugin with results but no report section of its own."""
    path = results_path(spec)
    items = [f"/{info.path}" for info in project.walk(path)]
    return [ctx.heading(spec.name),
            ctx.para(f"This module provides no report section. Its results are stored in "
                     f"the project under <b>/{esc(path)}</b>: "
                     + esc(", ".join(items[:30]) or "(empty)") + ".")]


def failure_reason(exc: BaseException) -> str:
    """Why a section failed, in one line: the input problem, or the exception."""
    if isinstance(exc, InputError):
        return clip(exc.message, 300)
    # Not the raw library text ("TypeError: ufunc 'isfinite' …", issue #28): what it
    # means to the reader; the exception itself goes to the log (-v, HYDROSYNC_DEBUG).
    log.debug("section failure", exc_info=exc)
    kind = "damaged" if isinstance(exc, OSError | KeyError) else "not of the expected form"
    return (f"its stored data are {kind} (run the analysis again; "
            f"{type(exc).__name__} in the report code)")


def _section(project, ctx: ReportContext, status: ModuleStatus,
             problems: list[str]) -> list[Flowable]:
    spec = status.spec
    if not spec.report_section:
        return _generic_section(project, ctx, spec)
    try:
        flowables = list(load_object(spec.report_section)(project, ctx))
    except Exception as exc:  # a damaged project or faulty plugin must not sink the report
        reason = failure_reason(exc)
        log.error("report section of %s could not be produced: %s", spec.id, reason)
        problems.append(f"section '{spec.name}' could not be produced: {reason}")
        return [ctx.heading(spec.name),
                ctx.warning(f"The {spec.name} section could not be produced: {reason}. "
                            "The results stored in the project are unaffected; repair or "
                            "re-import the damaged data and run the module again.")]
    return flowables


def _status_problems(project, statuses: list[ModuleStatus]) -> list[str]:
    """Summary rows that failed, and a vessel sheet that cannot be read."""
    out = []
    for status in statuses:
        for quantity, value in status.rows:
            if quantity == "summary unavailable":
                value = re.sub(r"^\w+(Error|Exception): ", "", value)
                if project.path is not None:
                    value = value.replace(f"{project.path}: ", "")
                out.append(f"summary of '{status.spec.name}' could not be produced: {value}")
    try:
        from hydrosync_core.project.vessel import vessel_config

        vessel_config(project)
    except InputError as exc:
        out.append(f"vessel sheet could not be read: {failure_reason(exc)}")
    return out


#: A section starts on a new page unless at least this fraction of the page is still free:
#: a new page after every section left pages 60 % empty (#26).
SECTION_ROOM = 0.5


def section_break(doc) -> CondPageBreak:
    """Before a section: a page break only if less than :data:`SECTION_ROOM` is left."""
    return CondPageBreak(SECTION_ROOM * doc.height)


def build_report(project, pdf_path: str | os.PathLike, progress=None, cancel=None, *,
                 specs: list[PluginSpec] | None = None,
                 problems: list[str] | None = None,
                 layout: PageLayout | None = None, lang: str | None = None) -> Path:
    """Write the PDF report of *project* to *pdf_path* atomically and return the path.

    Parameters
    ----------
    project : hydrosync_core.project.Project
        The project; read only.
    pdf_path : path-like
        Output file. Written through a temporary file and renamed, so a failure or a
        cancel leaves any previous file untouched.
    progress : callable(fraction, message), optional
    cancel : object with ``is_set()``, optional
    specs : list of PluginSpec, optional
        The modules to report on (default: every registered plugin).
    problems : list of str, optional
        Receives one line per part of the report that could not be produced (a damaged
        project); those parts show "could not be produced: <reason>" in the PDF.
    layout : PageLayout, optional
        Receives how full each page is and where each section starts (benchmarks and
        tests check that no page is left nearly empty).
    lang : str, optional
        Language of the text (``en``, ``zh_CN``; default: the current
        :func:`hydrosync_core.i18n.language`). Numbers, units and symbols are the same in
        every language; Chinese embeds a CJK TrueType font (``fonts-wqy-zenhei``).

    Returns
    -------
    pathlib.Path
        *pdf_path*.
    """
    try:
        lang = normalise(lang or language())
    except ValueError as exc:
        raise InputError("--lang", str(exc)) from None
    with using(lang), language_fonts(lang):
        return _build(project, Path(pdf_path), progress, cancel, specs, problems, layout)


def _build(project, pdf_path: Path, progress, cancel, specs: list[PluginSpec] | None,
           problems: list[str] | None, layout: PageLayout | None) -> Path:
    """:func:`build_report` in the current language."""
    if not pdf_path.parent.is_dir():
        raise InputError(str(pdf_path), "output folder does not exist")
    report(progress, 0.0, "collecting results")
    specs = plugin_specs() if specs is None else specs
    statuses = [module_status(project, spec) for spec in specs]
    problems = [] if problems is None else problems
    problems += _status_problems(project, statuses)
    check_cancel(cancel)

    doc_title = tr(f"HydroSync report \u2014 {project.name or 'Untitled project'}")
    with atomic_path(pdf_path) as tmp:
        doc = ReportDocTemplate(str(tmp), title=doc_title, author="HydroSync",
                                subject=tr("Sensor calibration report"), progress=progress,
                                cancel=cancel)
        ctx = ReportContext(width=doc.width)
        story: list[Flowable] = cover_page(project, ctx, statuses)
        story += contents_and_summary(ctx, statuses)
        with_results = [s for s in statuses if s.has_results]
        for i, status in enumerate(with_results):
            check_cancel(cancel)
            report(progress, 0.1 + 0.6 * i / max(len(with_results), 1),
                   f"section {status.spec.name}")
            story.append(section_break(doc))
            section = _section(project, ctx, status, problems)
            if status.stale:
                # Right under the heading, before any number of the section.
                section[1:1] = [ctx.warning(
                    "OUT OF DATE: these results no longer match the project \u2014 "
                    + "; ".join(status.stale) + ". Run the analysis again before signing.")]
            story += section
        story.append(section_break(doc))
        try:
            story += sources_section(project, ctx)
        except Exception as exc:  # a damaged raw group must not sink the report
            reason = failure_reason(exc)
            problems.append(f"data-sources appendix could not be produced: {reason}")
            story += [ctx.heading("Appendix: data sources"),
                      ctx.warning(f"The data-sources appendix could not be produced: {reason}.")]
        for status in with_results:
            if not status.spec.report_appendix:
                continue
            try:
                story += list(load_object(status.spec.report_appendix)(project, ctx))
            except Exception as exc:  # an appendix must not sink the report
                reason = failure_reason(exc)
                problems.append(f"appendix of '{status.spec.name}' could not be produced: "
                                f"{reason}")
        check_cancel(cancel)
        report(progress, 0.75, "laying out pages")
        canvas = type("ReportCanvas", (NumberedCanvas,), {
            "footer_left": f"HydroSync {__version__} \u2014 {project.name or 'Untitled'}"
                           + (f" \u2014 {project.path.name}" if project.path else ""),
            "header_text": doc_title,
        })
        # Two passes at most: the contents needs the page numbers of the headings.
        doc.multiBuild(story, canvasmaker=canvas, maxPasses=4)
    if layout is not None:
        layout.fill[:] = doc.layout.fill
        layout.section_starts.clear()
        layout.section_starts.update(doc.layout.section_starts)
    report(progress, 1.0, f"report written to {pdf_path}")
    return pdf_path
