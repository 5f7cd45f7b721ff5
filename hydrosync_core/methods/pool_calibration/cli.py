"""``hydrosync pool-calibrate``: pool calibration from files (docs/formats.md) or a project."""

from __future__ import annotations

import argparse
from pathlib import Path

from hydrosync_core.errors import InputError
from hydrosync_core.methods.pool_calibration.params import PoolParams
from hydrosync_core.methods.pool_calibration.result import parameter_text
from hydrosync_core.outputs import Outputs
from hydrosync_core.params import add_cli_arguments, from_cli


def _read_lidar(path: str):
    try:
        from hydrosync_core.importers.pointcloud import read_point_cloud
    except ModuleNotFoundError as exc:
        if exc.name != "hydrosync_core.importers.pointcloud":
            raise
        if Path(path).suffix.lower() != ".csv":
            raise InputError(path, "only CSV laser files can be read in this build") from None
        from hydrosync_core.importers.survey_csv import read_lidar_csv
        return read_lidar_csv(path)
    return read_point_cloud(path)


LIDAR_NAMES = ("lidar.csv", "lidar.ply", "lidar.las", "lidar.laz")


def _same_json(path: Path, first: Path | None, reader):
    """The document at *path*, checked to equal the one at *first* (one session, one
    setup and one target)."""
    doc = reader(path)
    if first is not None and doc != reader(first):
        raise InputError(str(path), f"differs from {first}: the passes of one session share "
                         "one setup and one target")
    return doc


def read_passes(folders: list[str], lidar: str | None, setup: str | None,
                target: str | None) -> tuple[list, list, list, dict, dict]:
    """Read the ``--pass`` folders (each: mbes.csv, ins.csv, optionally lidar.*,
    setup.json, target.json) and the shared files; every problem is one InputError
    naming the file."""
    from hydrosync_core.importers.pool_json import read_setup_json, read_target_json
    from hydrosync_core.importers.survey_csv import read_ins_csv, read_mbes_csv

    clouds, mbes, ins = [], [], []
    docs: dict[str, Path | None] = {"setup.json": None, "target.json": None}
    for folder in folders:
        d = Path(folder)
        if not d.is_dir():
            raise InputError(str(d), "no such folder (--pass)")
        for name in ("mbes.csv", "ins.csv"):
            if not (d / name).is_file():
                raise InputError(str(d / name), "missing: a --pass folder holds mbes.csv and "
                                 "ins.csv (and a lidar.* unless --lidar gives a shared cloud)")
        own = next((d / n for n in LIDAR_NAMES if (d / n).is_file()), None)
        if own is None and lidar is None:
            raise InputError(str(d / "lidar.csv"), "missing: no laser cloud for this pass "
                             "(put one in the folder or give a shared --lidar)")
        if own is not None:
            clouds.append(_read_lidar(str(own)))
        mbes.append(read_mbes_csv(d / "mbes.csv"))
        ins.append(read_ins_csv(d / "ins.csv"))
        for name, reader in (("setup.json", read_setup_json),
                             ("target.json", read_target_json)):
            if (d / name).is_file():
                _same_json(d / name, docs[name], reader)
                docs[name] = docs[name] or d / name
    if lidar is not None:
        clouds.append(_read_lidar(lidar))
    setup_path = Path(setup) if setup else docs["setup.json"]
    target_path = Path(target) if target else docs["target.json"]
    for flag, path in (("--setup", setup_path), ("--target", target_path)):
        if path is None:
            raise InputError(str(Path(folders[0]) / f"{flag[2:]}.json"),
                             f"missing: give {flag} or put it in the --pass folders")
    return (clouds, mbes, ins, read_setup_json(setup_path), read_target_json(target_path))


def _summary(result, stored_in: str | None = None) -> str:
    """Final values with their 1σ (joint solution), one per line, and where they went."""
    b, la = result.boresight_deg, result.lever_arm_m
    joint = result.joint if result.method == "joint" else None
    sb = joint.sigma_boresight_deg if joint else {}
    sl = joint.sigma_lever_arm_m if joint else {}

    def pm(value, sigma, unit):
        if sigma is not None and sigma == sigma:  # NaN: not determined
            return parameter_text(value, sigma, unit)
        text = parameter_text(value, None, unit)
        return text + (" (not determined: coarse value kept)" if joint is not None else "")

    lines = [f"pool calibration, final values from the "
             f"{'joint adjustment' if result.method == 'joint' else 'patent method'} "
             f"({result.iterations} patent iterations, "
             f"{'converged' if result.converged else 'NOT converged'}), 1σ:"]
    for k in ("roll", "pitch", "yaw"):
        lines.append(f"  boresight {k:<5} {pm(b[k], sb.get(k), '°')}")
    for k, name in (("x", "forward"), ("y", "starboard"), ("z", "down")):
        lines.append(f"  lever arm {k} ({name:<9}) {pm(la[k], sl.get(k), 'm')}")
    if stored_in:
        lines.append(f"stored in {stored_in} under /results/pool_calibration")
    lines += [f"warning: {w}" for w in result.warnings]
    return "\n".join(lines)


EPILOG = ("exit codes: 0 success; 2 bad input (one line on stderr naming the file and what "
          "is wrong); 3 finished, but some parameters are not determined by the data (one "
          "line on stderr naming them; in the JSON under 'undetermined' with the reason; "
          "their coarse values are kept) or their correction exceeds the coarse accuracy "
          "(the data contradict the setup; under 'contradicted'); 130 interrupted (one line "
          "saying what was saved); 1 anything else.")


def _exit_code(result) -> int:
    """3 with one line on stderr naming the undetermined parameters, else 0."""
    import sys

    if not result.undetermined and not result.contradicted:
        return 0
    if result.undetermined:
        names = ", ".join(result.undetermined)
        print(f"pool-calibrate: not determined by the data (coarse values kept): {names}",
              file=sys.stderr)
    if result.contradicted:
        names = ", ".join(result.contradicted)
        print(f"pool-calibrate: correction beyond the coarse accuracy, the data contradict "
              f"the setup (not a calibration): {names}", file=sys.stderr)
    return 3


def cmd_pool(args: argparse.Namespace) -> int:
    from hydrosync_core.cli.terminal import TerminalProgress

    params = from_cli(args, PoolParams)
    progress = TerminalProgress("pool-calibrate")
    out = Outputs({f"--{n}": getattr(args, n) for n in ("lidar", "mbes", "ins", "setup",
                                                         "target", "project")})
    out.plan(args.json, "--json")  # checked before any work
    if args.project and args.passes:
        raise InputError(args.project, "give either a project (its passes are stored under "
                         "raw/pool/passes) or --pass folders, not both")
    if args.project:
        from hydrosync_core.methods.pool_calibration.project_run import run
        from hydrosync_core.project import Project

        with out, Project.open(args.project) as project:
            for need in ("raw/pool/lidar", "raw/pool/mbes", "raw/pool/ins", "raw/pool/setup",
                         "raw/pool/target"):
                if not project.exists(need):
                    raise InputError(args.project, f"pool calibration needs /{need}")
            result = run(project, params, progress, None)
            progress.done()
            if args.json:
                out.write_json(args.json, result.to_dict())
            project.save()
            out.publish()
        print(_summary(result, str(args.project)))
        return _exit_code(result)
    if args.passes:
        if args.mbes or args.ins:
            raise InputError(None, "give either --pass folders or --mbes/--ins, not both")
        if not args.json:
            raise InputError(None, "missing --json")
        from hydrosync_core.methods.pool_calibration.estimator import calibrate

        inputs = read_passes(args.passes, args.lidar, args.setup, args.target)
        result = calibrate(*inputs, params, progress, None)
        progress.done()
        with out:
            out.write_json(args.json, result.to_dict())
            out.publish()
        print(_summary(result) + f"\n{len(args.passes)} passes; written to {args.json}")
        return _exit_code(result)
    missing = [f"--{n}" for n in ("lidar", "mbes", "ins", "setup", "target", "json")
               if not getattr(args, n)]
    if missing:
        raise InputError(None, f"missing {', '.join(missing)} (or give a project file)")
    from hydrosync_core.importers.pool_json import read_setup_json, read_target_json
    from hydrosync_core.importers.survey_csv import read_ins_csv, read_mbes_csv
    from hydrosync_core.methods.pool_calibration.estimator import calibrate

    # Read and check everything before computing, so bad input fails fast.
    lidar = _read_lidar(args.lidar)
    mbes = read_mbes_csv(args.mbes)
    ins = read_ins_csv(args.ins)
    setup = read_setup_json(args.setup)
    target = read_target_json(args.target)
    result = calibrate(lidar, mbes, ins, setup, target, params, progress, None)
    progress.done()
    with out:
        out.write_json(args.json, result.to_dict())
        out.publish()
    print(_summary(result) + f"\nwritten to {args.json}")
    return _exit_code(result)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "pool-calibrate", aliases=["pool_calibration", "pool-calibration"],
        help="multibeam boresight and lever arm from a pool target",
        description="Pool calibration (patent CN 105425246 B): the multibeam boresight and "
        "lever arm relative to the INS, against laser-scanned target faces. Give the five files "
        "and --json, or a project file holding raw/pool/*.", epilog=EPILOG)
    p.add_argument("project", nargs="?", help="project file (.h5) holding raw/pool/*")
    p.add_argument("--lidar", help="laser points x,y,z (CSV/PLY/LAS/LAZ, target ENU)")
    p.add_argument("--mbes", help="multibeam soundings CSV time,x,y,z (sensor frame)")
    p.add_argument("--ins", help="INS CSV time,e,n,u,roll,pitch,heading")
    p.add_argument("--setup", help="setup.json (coarse boresight and lever arm)")
    p.add_argument("--target", help="target.json (target design)")
    p.add_argument("--pass", dest="passes", action="append", metavar="DIR",
                   help="a folder holding one pass: mbes.csv, ins.csv and optionally "
                   "lidar.csv/.ply/.las/.laz, setup.json, target.json; repeat it for a "
                   "session of several passes adjusted jointly (--lidar, --setup, --target "
                   "then give shared files)")
    p.add_argument("--json", help="result.json to write (atomically)")
    add_cli_arguments(p, PoolParams)
    p.set_defaults(func=cmd_pool)
