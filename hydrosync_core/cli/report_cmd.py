"""``hydrosync report project.h5 -o report.pdf``: the PDF report of a project.

The project is opened read-only (no lock: a report can be written while another process
works on the project). A section that cannot be produced from a damaged project is shown
in the PDF as "could not be produced: <reason>" and warned about on stderr; with
``--strict`` that is an error (exit 2) and no PDF is written.
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from hydrosync_core.errors import InputError
from hydrosync_core.outputs import Outputs


def cmd_report(args: argparse.Namespace) -> int:
    from hydrosync_core.cli.terminal import TerminalProgress
    from hydrosync_core.project import Project
    from hydrosync_core.report import build_report

    out = Path(args.output) if args.output else Path(args.project).with_suffix(".pdf")
    if out.suffix.lower() != ".pdf":
        raise InputError(str(out), "the report file name must end in .pdf")
    if os.path.realpath(out) == os.path.realpath(args.project):  # no raise on a loop
        raise InputError(str(out), "the report would overwrite the project file")
    problems: list[str] = []
    with Outputs() as outputs:
        outputs.plan(out, "-o")
        with Project.open(args.project, readonly=True) as project:
            from hydrosync_core.plugins import plugin_specs
            from hydrosync_core.provenance import stale_results

            try:
                stale = stale_results(project, plugin_specs())
            except InputError as exc:  # damaged project: the report says what it can
                stale = {}
                problems.append(f"whether the results are up to date could not be checked: "
                                f"{exc.message}")
            for plugin_id, reasons in stale.items():
                print(f"hydrosync report: warning: {plugin_id} results are out of date: "
                      + "; ".join(reasons), file=sys.stderr)
            if stale and args.strict:
                raise InputError(args.project, "results out of date ("
                                 + ", ".join(stale) + "): run them again or drop --strict")
            progress = TerminalProgress("report")
            try:
                build_report(project, outputs.temp(out), progress=progress, problems=problems,
                             lang=args.lang)
            finally:
                progress.done()
        if problems and args.strict:
            raise InputError(args.project, f"no report written (--strict): {len(problems)} "
                             f"part(s) could not be produced: {'; '.join(problems)}")
        outputs.publish()
    for problem in problems:
        print(f"hydrosync report: warning: {args.project}: {problem}", file=sys.stderr)
    print(f"report written to {out}" + (f" ({len(problems)} warning(s))" if problems else ""))
    return 0


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "report", help="write the PDF report of a project",
        description="Write a PDF report: cover, summary of all results, then one section "
        "per module that has results. The file is written atomically. A section that "
        "cannot be produced (damaged project) shows the reason in the PDF and a warning.",
    )
    p.add_argument("project", help="project file (.h5)")
    p.add_argument("-o", "--output", metavar="PDF",
                   help="report file to write (default: the project name with .pdf)")
    p.add_argument("--lang", choices=["en", "zh_CN"], default="en",
                   help="language of the report's text: en (default) or zh_CN (Simplified "
                   "Chinese; needs a CJK font, e.g. Debian fonts-wqy-zenhei). Numbers, units "
                   "and the command's own messages stay the same")
    p.add_argument("--strict", action="store_true",
                   help="refuse (exit 2, no PDF) when a result is out of date (its inputs or "
                   "vessel-sheet entries changed since it was computed) or a section cannot "
                   "be produced")
    p.set_defaults(func=cmd_report)
