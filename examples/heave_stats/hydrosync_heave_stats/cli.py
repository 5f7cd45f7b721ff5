"""``hydrosync heave-stats PROJECT``: the analysis's command, found through its spec."""

from __future__ import annotations

import argparse

from hydrosync_core.params import add_cli_arguments, from_cli
from hydrosync_heave_stats.params import HeaveStatsParams


def cmd_heave_stats(args: argparse.Namespace) -> int:
    from hydrosync_core.project import Project
    from hydrosync_heave_stats.method import run

    params = from_cli(args, HeaveStatsParams)  # bad parameters fail before any work
    project = Project.open(args.project)
    table = run(project, params)
    project.save()
    for i, name in enumerate(table["name"]):
        print(f"{name:<10} RMS {table['rms_m'][i]:.3f} m  Hs {table['significant_m'][i]:.3f} m"
              f"  period {table['peak_period_s'][i]:.1f} s")
    return 0


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("heave-stats", help="heave statistics per survey line",
                       description="RMS heave, significant heave and dominant period of "
                       "each survey line; results stored under /results/heave_stats.")
    p.add_argument("project", help="project file (.h5) holding raw/attitude and raw/lines")
    add_cli_arguments(p, HeaveStatsParams)
    p.set_defaults(func=cmd_heave_stats)
