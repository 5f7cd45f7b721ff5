"""``hydrosync tilt``: heading alignment and tip of a tilt RTK pole (docs/formats.md).

File form::

    hydrosync tilt --imu imu.csv --gnss gnss.csv --pole pole.json --json result.json \
        [method parameters]

Project form: ``hydrosync tilt PROJECT.h5 [--json result.json]`` reads ``/raw/tilt/imu``,
``/raw/tilt/gnss`` and ``/raw/tilt/pole`` and stores ``/results/tilt_alignment``.

``result.json``: ``tip_enu`` ``[e, n, u]`` (or ``tip_llh`` ``[lat, lon, height]`` for
geodetic input), ``tip_std_enu_m``, ``heading_misalignment_deg`` (C = Rz(ψ)·C' with C' the
levelled IMU attitude, heading 0 at the first IMU sample), ``heading_std_deg``,
``method``, ``vectors_used``, ``vectors_rejected``, ``methods`` (every method's answer),
``undetermined``, ``warnings``, ``params``. Exit codes: 0 success; 2 bad input (one line
naming the file, line and field); 3 the reported method is not determined by the data
(named on stderr and in the JSON, which is still written); 130 interrupted; 1 otherwise.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from hydrosync_core.errors import InputError
from hydrosync_core.methods.tilt_alignment.params import TiltParams
from hydrosync_core.outputs import Outputs
from hydrosync_core.params import add_cli_arguments, from_cli

EXIT_UNDETERMINED = 3


def _print(doc: dict) -> None:
    from hydrosync_core.methods.tilt_alignment.present import (
        COLUMNS,
        imu_text,
        joint_text,
        method_rows,
        tip_header,
    )

    rows = method_rows(doc)
    heads = {**COLUMNS, "tip": tip_header(doc)}
    width = {k: max(len(heads[k]), *(len(r[k]) for r in rows)) for k in heads}
    print("  ".join(f"{heads[k]:<{width[k]}}" for k in heads).rstrip())
    for r in rows:
        print("  ".join(f"{r[k]:<{width[k]}}" for k in heads).rstrip())
    print(f"vectors used {doc['vectors_used']}, rejected {doc['vectors_rejected']}, "
          f"too short {doc['vectors_short']}; tilt max {doc['tilt_deg']['max']:.1f}°, "
          f"shot {doc['tilt_deg']['shot']:.1f}°")
    print(imu_text(doc))
    if doc.get("joint"):
        print(joint_text(doc))
    for w in doc["warnings"]:
        print(f"warning: {w}")


def _finish(doc: dict) -> int:
    _print(doc)
    if doc["undetermined"]:
        print(f"hydrosync tilt: undetermined: {'; '.join(doc['undetermined'])}",
              file=sys.stderr)
        return EXIT_UNDETERMINED
    return 0


def cmd_tilt(args: argparse.Namespace) -> int:
    from hydrosync_core.cli.terminal import TerminalProgress
    from hydrosync_core.jsonsafe import jsonable

    params = from_cli(args, TiltParams)  # bad parameters fail before any work
    out = Outputs({f"--{n}": getattr(args, n) for n in ("imu", "gnss", "pole", "project")})
    out.plan(args.json, "--json")
    progress = TerminalProgress("tilt")
    if args.project:
        if args.imu or args.gnss or args.pole:
            raise InputError(str(args.project), "give either a project file or "
                             "--imu/--gnss/--pole")
        from hydrosync_core.methods.tilt_alignment.project_run import run
        from hydrosync_core.project import Project

        with out, Project.open(args.project) as project:
            try:
                doc = run(project, params, progress, None)
            except InputError as exc:
                raise InputError(f"{args.project}{exc.file or ''}", exc.message,
                                 line=exc.line, field=exc.field) from None
            progress.done()
            if args.json:
                out.write_json(args.json, jsonable(doc))
            project.save()
            out.publish()
        print(f"results stored in {args.project} under /results/tilt_alignment")
        return _finish(doc)
    missing = [f"--{n}" for n in ("imu", "gnss", "pole", "json") if not getattr(args, n)]
    if missing:
        raise InputError(None, f"missing {', '.join(missing)} (or give a project file)")
    from hydrosync_core.methods.tilt_alignment.io import read_gnss_csv, read_imu_csv, read_pole_json
    from hydrosync_core.methods.tilt_alignment.solve_files import result_document, solve_columns

    imu = read_imu_csv(args.imu)
    gnss = read_gnss_csv(args.gnss)
    pole = read_pole_json(args.pole)
    length = pole["pole_length_m"]
    sol, frame = solve_columns(imu, gnss, length, params, (str(args.imu), str(args.gnss)),
                               progress, None, pole.get("imu_convention"))
    progress.done()
    doc = result_document(sol, frame, length, params)
    with out:
        out.write_json(args.json, jsonable(doc))
        out.publish()
    return _finish(doc)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "tilt", aliases=["tilt-alignment", "tilt_alignment"],
        help="heading alignment and tip of a tilt RTK pole (IMU + GNSS swing)",
        description="Initial heading of a tilt RTK pole's IMU and the tip coordinates from a "
        "2-3 s swing with the tip on the point: Li et al.'s gradient descent (BGD, SGD, "
        "MBGD) and SVD, the closed-form heading-only least squares, and a joint batch "
        "least squares over the whole swing (default). Give --imu, --gnss, --pole and "
        "--json, or a project file holding raw/tilt/*.")
    p.add_argument("project", nargs="?", type=Path, help="project file (.h5) holding raw/tilt/*")
    p.add_argument("--imu", type=Path, help="imu.csv: time, gx, gy, gz (rad/s), ax, ay, az "
                   "(m/s²), body frame x forward, y right, z down along the pole")
    p.add_argument("--gnss", type=Path, help="gnss.csv: time, e, n, u (local ENU, m) or "
                   "time, lat, lon, height (deg, m): the antenna phase centre")
    p.add_argument("--pole", type=Path, help='pole.json: {"pole_length_m": 1.865} '
                   "(antenna phase centre to tip)")
    p.add_argument("--json", type=Path, help="result.json to write (atomically)")
    add_cli_arguments(p, TiltParams)
    p.set_defaults(func=cmd_tilt)
