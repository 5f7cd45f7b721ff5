"""PDF report of a project (reportlab): cover, summary and one section per plugin.

``build_report(project, pdf_path, progress=None, cancel=None) -> Path`` is the entry point
used by ``hydrosync report`` and the GUI's File → Export report….
"""

from hydrosync_core.report.build import build_report

__all__ = ["build_report"]
