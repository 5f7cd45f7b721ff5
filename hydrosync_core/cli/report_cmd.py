"""``hydrosync report project.h5 -o report.pdf``: the PDF report of a project."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from hydrosync_core.errors import InputError


def cmd_report(args: argparse.Namespace) -> int:
    from hydrosync_core.cli.terminal import TerminalProgress
    from hydrosync_core.project import Project
    from hydrosync_core.report import build_report

    out = Path(args.output) if args.output else Path(args.project).with_suffix(".pdf")
    if out.suffix.lower() != ".pdf":
        raise InputError(str(out), "the report file name must end in .pdf")
    if out.resolve() == Path(args.project).resolve():
        raise InputError(str(out), "the report would overwrite the project file")
    if not out.parent.is_dir():
        raise InputError(str(out), "output folder does not exist")
    with Project.open(args.project) as project:
        from hydrosync_core.plugins import plugin_specs
        from hydrosync_core.provenance import stale_results

        stale = stale_results(project, plugin_specs())
        for plugin_id, reasons in stale.items():
            print(f"hydrosync report: warning: {plugin_id} results are out of date: "
                  + "; ".join(reasons), file=sys.stderr)
        if stale and args.strict:
            raise InputError(args.project, "results out of date ("
                             + ", ".join(stale) + "): run them again or drop --strict")
        progress = TerminalProgress("report")
        try:
            build_report(project, out, progress=progress)
        finally:
            progress.done()
    print(f"report written to {out}")
    return 0


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "report", help="write the PDF report of a project",
        description="Write a PDF report: cover, summary of all results, then one section "
        "per module that has results. The file is written atomically.",
    )
    p.add_argument("project", help="project file (.h5)")
    p.add_argument("-o", "--output", metavar="PDF",
                   help="report file to write (default: the project name with .pdf)")
    p.add_argument("--strict", action="store_true",
                   help="refuse (exit 2, no PDF) when a result is out of date, i.e. its "
                   "inputs, vessel-sheet entries changed since it was computed")
    p.set_defaults(func=cmd_report)
