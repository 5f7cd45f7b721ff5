"""``hydrosync latency``: GNSS-versus-attitude delay from CSV files or a project (formats.md)."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.outputs import Outputs
from hydrosync_core.params import add_cli_arguments, cli_values


def _params(args: argparse.Namespace) -> LatencyParams:
    """The parameters given on the command line, the rest at their schema defaults."""
    return LatencyParams.from_dict(cli_values(args, LatencyParams))


def _print_table(result) -> None:
    from hydrosync_core.methods.latency.texts import interval_text, latency_text, line_cells

    print(f"{'line':<10} {'epochs':>6} {'R max':>7} {'dt [s]':>9} {'+-[s]':>8} "
          f"{'s0 bef[m]':>9} {'s0 aft[m]':>9}  used")
    for ln in result.lines:
        dt, sigma = line_cells(ln.latency_s, ln.uncertainty_s)
        print(f"{ln.name:<10} {ln.epochs:>6d} {ln.r_max:>7.4f} {dt:>9} {sigma:>8} "
              f"{ln.sigma0_before_m:>9.3f} {ln.sigma0_after_m:>9.3f}  "
              f"{'yes' if ln.used else 'no'}")
    sigma = result.uncertainty_s
    print(f"latency {latency_text(result.latency_s, sigma)}  (95 % interval "
          f"{interval_text(result.ci95_low, result.ci95_high, sigma)}; {result.message})")
    for warning in result.warnings:
        print(f"warning: {warning}")


def _rename(exc: InputError, files: dict) -> InputError:
    """Name the real file/option instead of the core's generic labels."""
    file = files.get(exc.file, exc.file)
    if file is None:
        file = LatencyParams.flag_of(exc.field)
    return InputError(file, exc.message, line=exc.line, field=exc.field)


def _import_in_background(name: str):
    """A started daemon thread importing module *name*, or None when it is loaded."""
    if name in sys.modules:
        return None
    import contextlib
    import importlib
    import threading

    def load() -> None:
        with contextlib.suppress(Exception):  # the caller's own import reports a failure
            importlib.import_module(name)

    thread = threading.Thread(target=load, name="hydrosync-preload", daemon=True)
    thread.start()
    return thread


def _run_csv(args: argparse.Namespace) -> int:
    from hydrosync_core.importers.survey_csv import read_lines_csv
    from hydrosync_core.methods.latency.readers import (
        prescan_attitude,
        prescan_gnss,
        read_attitude_csv,
        read_gnss_csv,
    )

    missing = [o for o, v in (("--gnss", args.gnss), ("--attitude", args.attitude),
                              ("--lines", args.lines), ("--lever-arm", args.param_lever_arm_m),
                              ("--json", args.json)) if v is None]
    if missing:
        raise InputError(None, f"missing option(s) {', '.join(missing)} (or give a project file)")
    files = {"gnss": args.gnss, "attitude": args.attitude, "lines": args.lines}
    with Outputs({"--gnss": args.gnss, "--attitude": args.attitude,
                  "--lines": args.lines}) as out:
        out.plan(args.json, "--json")  # checked before any work
        out.plan(args.sync_csv, "--sync-csv")
        try:
            params = _params(args)
            # The heading is only needed for the synchronised data set.
            columns = None if args.sync_csv is not None else ("time", "roll", "pitch", "heave")
            # The first pass over each file runs while the first read loads numba (numba
            # and the estimate are not imported before: that would leave the other core
            # idle while they load).
            scans = (prescan_gnss(args.gnss), prescan_attitude(args.attitude, columns))
            gnss = read_gnss_csv(args.gnss, scans[0])
            attitude = read_attitude_csv(args.attitude, args.heave_positive, columns, scans[1])
            lines = read_lines_csv(args.lines)
            from hydrosync_core.methods.latency.estimate import estimate_latency

            # The line combination needs scipy.special (t quantile): 0.13 s of import that
            # would otherwise run alone after the scans; during them the compiled scan
            # threads leave the interpreter to it.
            preload = _import_in_background("scipy.special")
            try:
                result = estimate_latency(gnss, attitude, lines, params.lever_arm_m, params)
            finally:
                if preload is not None:
                    preload.join()  # never left importing while the interpreter exits
        except InputError as exc:
            raise _rename(exc, files) from None
        _print_table(result)
        if not result.converged:
            raise InputError(args.lines, f"{result.message}; " + "; ".join(result.warnings[-2:]))
        out.write_json(args.json, result.to_dict())
        if args.sync_csv is not None:
            from hydrosync_core.methods.latency.synchronised import synchronise

            _write_sync(out, args.sync_csv, synchronise(gnss, attitude, params.lever_arm_m,
                                                        result.latency_s))
        out.publish()  # all outputs together, or none
    return 0


def _write_sync(out: Outputs, path: Path, columns: dict) -> None:
    rows = out.write_csv(path, columns)
    print(f"synchronised data set: {rows} epochs written to {path}")


def _run_project(args: argparse.Namespace) -> int:
    from hydrosync_core.cli.terminal import TerminalProgress
    from hydrosync_core.methods.latency.project_run import run
    from hydrosync_core.project import Project

    if any(v is not None for v in (args.gnss, args.attitude, args.lines)):
        raise InputError(args.project, "give either a project file or --gnss/--attitude/--lines")
    out = Outputs({"project": args.project})
    out.plan(args.json, "--json")  # checked before any work
    out.plan(args.sync_csv, "--sync-csv")
    with out, Project.open(args.project) as project:
        for path in ("raw/gnss", "raw/attitude", "raw/lines"):
            if not project.exists(path):
                raise InputError(args.project, f"project has no /{path} (import it first)")
        progress = TerminalProgress("latency")
        try:
            result = run(project, _params(args), progress, None)
        except InputError as exc:
            raise _rename(exc, {"gnss": args.project, "attitude": args.project,
                                "lines": args.project}) from None
        progress.done()
        _print_table(result)
        if args.json is not None and result.converged:
            out.write_json(args.json, result.to_dict())
        if args.sync_csv is not None and project.exists("results/latency/synchronised"):
            _write_sync(out, args.sync_csv, project.get_table("results/latency/synchronised"))
        project.save()
        out.publish()
    print(f"results stored in {args.project} under /results/latency")
    if not result.converged:
        print(f"hydrosync latency: {args.project}: {result.message}", file=sys.stderr)
        return 2
    return 0


def _one_blas_thread() -> None:
    """One OpenBLAS thread in a process where numpy is not loaded yet, unless the user
    chose a number.

    The estimate calls no BLAS on large arrays (:mod:`.prefilter` avoids it on purpose),
    but OpenBLAS starts a thread per core when numpy loads and again when scipy does, and
    each spins ~0.1 s waiting for work: on 2 cores that took the second core from the
    start-up's background count of the CSV rows (survey day: -0.15 s wall, -0.3 s CPU).
    Nothing changes in a process that already has numpy (tests, the GUI).
    """
    if "numpy" not in sys.modules:
        os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def cmd_latency(args: argparse.Namespace) -> int:
    _one_blas_thread()
    return _run_project(args) if args.project else _run_csv(args)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "latency", help="delay of GNSS heights relative to attitude/heave (correlation)",
        description="Estimate how late the GNSS time tags are relative to the attitude "
        "time tags, from CSV files (--gnss/--attitude/--lines/--lever-arm/--json) or from "
        "a project file (results stored in it under /results/latency).",
    )
    p.add_argument("project", nargs="?", type=Path, help="project file (.h5) instead of CSVs")
    p.add_argument("--gnss", type=Path, help="gnss.csv (time, height)")
    p.add_argument("--attitude", type=Path, help="attitude.csv (time, roll, pitch, heading, heave)")
    p.add_argument("--heave-positive", choices=("up", "down"), default="up",
                   help="heave sign convention of attitude.csv (formats.md: up; default up)")
    p.add_argument("--lines", type=Path, help="lines.csv (name, start, end)")
    p.add_argument("--json", type=Path, help="result.json to write")
    p.add_argument("--sync-csv", type=Path, metavar="CSV",
                   help="also write the synchronised data set: GNSS epochs at corrected time "
                   "(tag - latency) with height, roll, pitch, heading, heave, total_heave")
    add_cli_arguments(p, LatencyParams)
    p.set_defaults(func=cmd_latency)
