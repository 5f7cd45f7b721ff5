"""PDF report of a project (reportlab): cover, summary and one section per plugin.

``build_report(project, pdf_path, progress=None, cancel=None) -> Path`` is the entry point
used by ``hydrosync report`` and the GUI's File → Export report….

A plugin contributes through ``spec.report_section = "module:section"``:

* ``section(project, ctx: ReportContext) -> list[Flowable]`` — its pages, built with the
  helpers of :class:`~hydrosync_core.report.context.ReportContext` (headings, tables that
  split across pages with a repeated header, vector charts with captions);
* optionally ``summary(project) -> list[tuple[str, str]]`` in the same module — its rows
  (quantity, formatted value) in the report's summary table and in ``hydrosync demo``'s
  printout;
* optionally ``flags(project) -> dict[str, str]`` in the same module — the summary
  quantities the panel flags (a σ above its threshold, two estimates that disagree),
  each with its reason: the summary table marks them in red with the reason.

Modules without results under ``/results/<id>`` get no section; the summary says why.
"""

from hydrosync_core.report.build import build_report

__all__ = ["build_report"]
