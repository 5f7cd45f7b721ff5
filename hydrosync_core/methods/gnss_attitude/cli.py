"""``hydrosync attitude``: heading, pitch and roll from a GNSS antenna array.

File form (docs/formats.md)::

    hydrosync attitude --pos A1.pos A2.pos A3.pos [A4.pos …] --antennas antennas.json \
        --out attitude.csv [--json stats.json] [method parameters]
    hydrosync attitude --csv antenna_positions.csv --antennas antennas.json --out …

Each ``.pos`` (or ``.geo``) file is matched to an antenna of ``antennas.json`` by its stem;
the CSV names the antenna of each row. Project
form: ``hydrosync attitude PROJECT.h5 [--out attitude.csv] [--json stats.json]`` reads
``/raw/gnss_attitude`` and stores ``/results/gnss_attitude``. Exit codes: 0 success,
2 bad input (one line naming the file, line and field), 1 anything else.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from hydrosync_core.errors import InputError
from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams
from hydrosync_core.outputs import Outputs
from hydrosync_core.params import add_cli_arguments, from_cli


def _print(sol, stats: dict, method: str) -> None:
    c = sol.counts
    print(f"epochs {c['epochs']}, solved {c['solved']} (fewer than 3 antennas: "
          f"{c['too_few_antennas']}, with a dropped antenna: {c['with_dropped_antenna']}), "
          f"gaps {c['gaps']} (longest {c['longest_gap_s']:.1f} s), file covariance not "
          f"positive definite (a-priori sigma used) {c.get('cov_fallback', 0)}")
    for name, a in c["antennas"].items():
        print(f"  {name:<8} present {a['present']:>7}  not accepted (Q) "
              f"{a['not_accepted_quality']:>6}  length rejected {a['length_rejected']:>6}  "
              f"used {a['used']:>7}  cov fallback {a.get('cov_fallback', 0):>5}")
    print(f"{'method':<7} {'epochs':>7} {'sd heading':>11} {'sd pitch':>9} {'sd roll':>8}"
          f"   (scatter / predicted, deg)")
    for name, s in stats.items():
        cells = []
        for a in ("heading", "pitch", "roll"):
            v = s[a]
            cells.append("-" if v["std"] is None else f"{v['std']:.4f}/{v['predicted']:.4f}")
        mark = " *" if name == method else ""
        print(f"{name:<7} {s['epochs']:>7} " + " ".join(f"{x:>15}" for x in cells) + mark)


def read_positions(path) -> dict:
    """Columns of one antenna's position file: ``.geo`` (calendar lat/lon/h with σ, see
    :mod:`hydrosync_core.importers.geo_positions`) by suffix or content, else RTKLIB ``.pos``.
    """
    from hydrosync_core.importers.geo_positions import looks_like_geo, read_geo
    from hydrosync_core.importers.rtklib_pos import read_pos

    p = Path(path)
    if p.suffix.lower() == ".geo" or (p.suffix.lower() != ".pos" and looks_like_geo(p)):
        return read_geo(p)
    return read_pos(p).columns


def _run_files(args, params: GnssAttitudeParams) -> int:
    from hydrosync_core.methods.gnss_attitude.antennas import read_antennas_json
    from hydrosync_core.methods.gnss_attitude.output import (
        stats_document,
        write_attitude_csv,
        write_stats_json,
    )
    from hydrosync_core.methods.gnss_attitude.pipeline import solve_array, statistics
    from hydrosync_core.methods.gnss_attitude.precision import predict
    from hydrosync_core.methods.gnss_attitude.project_run import track_from_columns

    if args.pos and args.csv:
        raise InputError(None, "give either --pos files or one --csv file, not both")
    missing = [o for o, v in (("--pos or --csv", args.pos or args.csv),
                              ("--antennas", args.antennas), ("--out", args.out)) if not v]
    if missing:
        raise InputError(None, f"missing option(s) {', '.join(missing)} (or give a project)")
    inputs = {f"--pos {p}": p for p in args.pos or ()}
    if args.csv:
        inputs["--csv"] = args.csv
    out = Outputs(inputs | {"--antennas": args.antennas})
    out.plan(args.out, "--out")  # checked before any work
    out.plan(args.json, "--json")
    antennas = read_antennas_json(args.antennas)["antennas"]
    tracks = {}
    if args.csv:
        from hydrosync_core.importers.antenna_csv import read_antenna_csv

        for name, columns in read_antenna_csv(args.csv).items():
            if name not in antennas:
                raise InputError(str(args.csv), f"antenna '{name}' is not in {args.antennas} "
                                 f"(antennas: {', '.join(antennas)})", field="antenna")
            tracks[name] = track_from_columns(columns, str(args.csv))
        sources = str(args.csv)
    else:
        stems = [Path(p).stem for p in args.pos]
        if len(set(stems)) != len(stems):
            raise InputError("--pos", "two files have the same name stem (the stem names "
                             "the antenna)")
        for path, stem in zip(args.pos, stems, strict=True):
            if stem not in antennas:
                raise InputError(str(path), f"no antenna '{stem}' in {args.antennas} (files "
                                 f"are matched by stem; antennas: {', '.join(antennas)})")
            tracks[stem] = track_from_columns(read_positions(path), str(path))
        sources = ", ".join(map(str, args.pos))
    try:
        sol = solve_array(tracks, antennas, params)
    except InputError as exc:
        raise InputError(exc.file or sources, exc.message, line=exc.line,
                         field=exc.field) from None
    stats = statistics(sol, params.static_start_s, params.static_end_s)
    body = [antennas[n] for n in sol.names]
    predicted = {m: predict(body, params.sigma_horizontal_m, params.sigma_vertical_m,
                            method=m).tolist() for m in ("lsq", "direct")}
    with out:
        rows = write_attitude_csv(out.temp(args.out), sol, params.method)
        if args.json is not None:
            write_stats_json(out.temp(args.json), stats_document(sol, stats, predicted, params))
        out.publish()  # both outputs together, or none
    _print(sol, stats, params.method)
    print(f"{rows} epochs ({params.method}) written to {args.out}")
    return 0


def _run_project(args, params: GnssAttitudeParams) -> int:
    from hydrosync_core.cli.terminal import TerminalProgress
    from hydrosync_core.methods.gnss_attitude.output import (
        stats_document,
        write_attitude_csv,
        write_stats_json,
    )
    from hydrosync_core.methods.gnss_attitude.pipeline import statistics
    from hydrosync_core.methods.gnss_attitude.project_run import run
    from hydrosync_core.project import Project

    if args.pos or args.csv or args.antennas:
        raise InputError(str(args.project), "give either a project file or "
                         "--pos/--csv/--antennas")
    out = Outputs({"project": args.project})
    out.plan(args.out, "--out")  # checked before any work
    out.plan(args.json, "--json")
    project = Project.open(args.project)
    progress = TerminalProgress("attitude")
    try:
        sol = run(project, params, progress, None)
    except InputError as exc:
        raise InputError(f"{args.project}{exc.file or ''}", exc.message, line=exc.line,
                         field=exc.field) from None
    progress.done()
    stats = statistics(sol, params.static_start_s, params.static_end_s)
    _print(sol, stats, params.method)
    with out:
        if args.out is not None:
            write_attitude_csv(out.temp(args.out), sol, params.method)
        if args.json is not None:
            import json

            predicted = json.loads(project.attrs("results/gnss_attitude")["predicted_deg"])
            write_stats_json(out.temp(args.json), stats_document(sol, stats, predicted, params))
        project.save()
        out.publish()
    print(f"results stored in {args.project} under /results/gnss_attitude")
    return 0


def cmd_attitude(args: argparse.Namespace) -> int:
    params = from_cli(args, GnssAttitudeParams)  # bad parameters fail before any work
    return _run_project(args, params) if args.project else _run_files(args, params)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "attitude", aliases=["gnss-attitude"],
        help="heading, pitch and roll from a GNSS antenna array (RTKLIB .pos files)",
        description="Attitude from three or more GNSS antennas: Liu et al.'s direct method "
        "and iterative least squares, plus the closed-form Wahba solution; epochs screened "
        "by solution quality and baseline lengths. From .pos files (--pos, --antennas, "
        "--out) or a project (results under /results/gnss_attitude).")
    p.add_argument("project", nargs="?", type=Path, help="project file (.h5) instead of files")
    p.add_argument("--pos", nargs="+", type=Path, metavar="POS",
                   help="one position file per antenna, RTKLIB .pos or .geo (calendar time, "
                   "lat, lon, h, 3 sigma); the stem names the antenna")
    p.add_argument("--csv", type=Path, metavar="CSV",
                   help="instead of --pos: one antenna_positions.csv (time, antenna, x, y, z "
                   "ECEF, quality as GGA fix quality[, sdx, sdy, sdz])")
    p.add_argument("--antennas", type=Path,
                   help="antennas.json: body-frame coordinates (x forward, y starboard, "
                   "z down, m)")
    p.add_argument("--out", type=Path, help="attitude.csv to write (time, heading, pitch, "
                   "roll, their std in deg, method, n_antennas)")
    p.add_argument("--json", type=Path, help="stats.json to write (counts, statistics)")
    add_cli_arguments(p, GnssAttitudeParams)
    p.set_defaults(func=cmd_attitude)
