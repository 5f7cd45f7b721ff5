"""``hydrosync batch CAMPAIGN.toml``: run a campaign of projects × analyses on Dask.

The campaign file is described in ``docs/formats.md`` ("Campaign file"). The file is read
and checked completely before anything runs (bad file → exit 2, one line). ``--dry-run``
prints the plan and exits. Otherwise the steps run on a Dask cluster
(:mod:`hydrosync_core.campaign.engine`): a LocalCluster of ``--workers`` processes (default
one per core), or an existing scheduler given by ``--scheduler`` or
``DASK_SCHEDULER_ADDRESS``. Progress goes to stderr; the table of outcomes and the summary
files to stdout. Exit 0 when every step succeeded (or was up to date), 1 when some failed
(the others still ran; the summary says which), 2 when the campaign stalled (no step
finished or ran for ``--stall-timeout`` seconds), 3 when a step was done but its data did
not determine the result, 130 on Ctrl-C (steps not started are cancelled, running ones
waited for; those saved stay saved and are named: re-running redoes only the rest).
"""

from __future__ import annotations

import argparse
import sys

from hydrosync_core.errors import InputError


def _table(result) -> list[str]:
    steps = list(dict.fromkeys(o["step"] for o in result.outcomes))
    projects = list(dict.fromkeys(o["project"] for o in result.outcomes))
    by = {(o["project"], o["step"]): o for o in result.outcomes}
    width = max([7] + [len(p) for p in projects])
    cells = {}
    for key, o in by.items():
        cells[key] = f"{o['status']} {o.get('seconds', 0.0):.1f}s"
    col = {s: max([len(s)] + [len(cells.get((p, s), "")) for p in projects]) for s in steps}
    lines = ["  ".join([f"{'project':<{width}}"] + [f"{s:<{col[s]}}" for s in steps])]
    for p in projects:
        lines.append("  ".join([f"{p:<{width}}"]
                               + [f"{cells.get((p, s), ''):<{col[s]}}" for s in steps]))
    return lines


def cmd_batch(args: argparse.Namespace) -> int:
    from hydrosync_core import interrupts
    from hydrosync_core.campaign import load_campaign
    from hydrosync_core.campaign.steps import DONE, OK_STATES, UNDETERMINED

    if args.workers is not None and args.workers < 1:
        raise InputError("--workers", "must be at least 1")
    if not args.stall_timeout > 0:
        raise InputError("--stall-timeout", "must be a positive number of seconds")
    campaign = load_campaign(args.campaign)
    if args.dry_run:
        from hydrosync_core.campaign.steps import plan_status

        for line in campaign.plan_lines():
            print(line)
        print("  steps:")
        runs = 0
        for entry in campaign.projects:
            for analysis in campaign.analyses:
                state = plan_status(entry, analysis)
                runs += state.startswith("will run")
                print(f"    {entry.label} {analysis.id}: {state}")
        n = len(campaign.projects) * len(campaign.analyses)
        print(f"dry run: {runs} of {n} analysis task(s) would run; nothing was done")
        return 0

    from hydrosync_core.campaign.engine import Listener, run_campaign, status_counts
    from hydrosync_core.cli.terminal import TerminalProgress

    bar = TerminalProgress("batch")
    reported: set[tuple[str, str]] = set()

    class Printer(Listener):
        def started(self, result, total):
            print(f"campaign '{campaign.name}': {len(campaign.projects)} project(s) x "
                  f"{len(campaign.analyses)} analysis(es), {total} task(s) on {result.where}",
                  file=sys.stderr, flush=True)
            if result.dashboard:
                print(f"Dask dashboard: {result.dashboard}", file=sys.stderr, flush=True)

        def update(self, progress):
            last = progress.last
            if last is not None and (last["project"], last["step"]) not in reported:
                reported.add((last["project"], last["step"]))
                if last["status"] in (DONE, UNDETERMINED) and last["step"] != "report":
                    interrupts.note_completed(last["path"])
                if last["status"] not in OK_STATES or last["status"] == UNDETERMINED:
                    bar.done()
                    print(f"{last['status'].upper()}: {last['project']} {last['step']}: "
                          f"{last.get('message', '')}", file=sys.stderr, flush=True)
            bar(progress.finished / max(progress.total, 1), progress.text())

    if args.scheduler and args.workers is not None:
        print("note: --workers is ignored with --scheduler (the cluster has its own workers)",
              file=sys.stderr)
    result = run_campaign(campaign, scheduler=args.scheduler, workers=args.workers,
                          listener=Printer(), stall_s=args.stall_timeout)
    bar.done()
    for line in _table(result):
        print(line)
    for path in result.summary_files:
        print(f"summary: {path}")
    print(f"{campaign.name}: {status_counts(result)} in {result.wall_s:.1f} s")
    if result.failed:
        print(f"hydrosync batch: {len(result.failed)} step(s) failed (the others ran); see "
              "the table above" + (" and the summary" if result.summary_files else ""),
              file=sys.stderr)
        return 1
    undetermined = [o for o in result.outcomes if o["status"] == UNDETERMINED]
    if undetermined:
        print(f"hydrosync batch: {len(undetermined)} step(s) done but undetermined by their "
              "data: " + "; ".join(f"{o['project']} {o['step']} ({o['message']})"
                                   for o in undetermined), file=sys.stderr)
        return 3
    return 0


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "batch", help="run a campaign (many projects x analyses) on Dask",
        description="Run the analyses of a campaign file (TOML, docs/formats.md 'Campaign "
        "file') on every project it names, in parallel on dask.distributed: a local cluster "
        "of worker processes by default, or an existing cluster (--scheduler or "
        "DASK_SCHEDULER_ADDRESS). Results already up to date (same inputs, parameters and "
        "versions) are not computed again; a failing project never stops the others. "
        "Exit 0 all steps succeeded, 1 some failed, 2 bad campaign file or stalled, 3 some "
        "step done but undetermined (did not converge), 130 interrupted (running steps are "
        "waited for; the message names the projects saved).")
    p.add_argument("campaign", help="campaign file (.toml)")
    p.add_argument("--dry-run", action="store_true",
                   help="list the projects, analyses, parameters and outputs; run nothing")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="address of a running Dask scheduler, e.g. tcp://host:8786 (default: "
                   "DASK_SCHEDULER_ADDRESS, else a local cluster)")
    p.add_argument("--workers", type=int, metavar="N",
                   help="worker processes of the local cluster (default: one per core)")
    p.add_argument("--stall-timeout", type=float, default=120.0, metavar="S",
                   help="stop (exit 2) when no step finished or ran for S seconds, e.g. every "
                   "worker dead (default 120)")
    p.set_defaults(func=cmd_batch)
