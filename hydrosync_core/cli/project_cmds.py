"""``hydrosync new | import | info | run``: project management from the command line."""

from __future__ import annotations

import argparse
from pathlib import Path

from hydrosync_core.errors import InputError
from hydrosync_core.importers.kinds import import_file, kinds
from hydrosync_core.plugins.spec import DataKind
from hydrosync_core.project import Project
from hydrosync_core.timespan import table_span


def _open_project(path: str, readonly: bool = False) -> Project:
    """Open to change (write lock, writability checked first) unless *readonly*."""
    return Project.open(path, readonly=readonly)


def cmd_new(args: argparse.Namespace) -> int:
    path = Path(args.project)
    if path.exists() and not args.force:
        raise InputError(str(path), "file exists (use --force to overwrite)")
    project = Project.new(name=args.name or path.stem)
    project.save(path)
    print(f"created {path}")
    return 0


def cmd_import(args: argparse.Namespace) -> int:
    path = Path(args.project)
    project = _open_project(path) if path.exists() else Project.create(path)
    table = kinds()
    # Every file of a kind at once: device logs of one kind become one table in time order.
    chosen = [(kind, files) for kind in table if (files := getattr(args, kind, None))]
    if not chosen:
        raise InputError(None, "nothing to import: give at least one --KIND FILE")
    files_of = dict(chosen)
    if getattr(args, "clock_offset", None) is not None and "gins_recording" not in files_of:
        raise InputError(None, "--clock-offset applies to --gins-recording only")
    if files_of.get("gnss_log") and files_of.get("gnss_log") == files_of.get("attitude_log"):
        from hydrosync_core.importers.log_import import expect_gnss_then_attitude

        expect_gnss_then_attitude(files_of["gnss_log"])  # one pass over each logger file
    # Read everything first so one bad file leaves the project untouched.
    messages = [_import_one(project, table[kind], files, args) for kind, files in chosen]
    project.save(path)
    for message in messages:
        print(message)
    return 0


def _import_one(project: Project, kind: DataKind, files: list[str],
                args: argparse.Namespace) -> str:
    """Import the files of one kind with the options of the command line it accepts;
    streamed readers (device logs) show their progress on stderr."""
    from hydrosync_core.cli.terminal import TerminalProgress

    options = {name: getattr(args, name, None) for name in kind.options}
    progress = TerminalProgress(f"import --{kind.name.replace('_', '-')}")
    try:
        return import_file(project, kind.name, files if len(files) > 1 else files[0],
                           progress=progress, **options)
    finally:
        progress.done()


def _human(nbytes: int) -> str:
    size = float(nbytes)
    for unit in ("B", "KiB", "MiB", "GiB"):
        if size < 1024 or unit == "GiB":
            return f"{size:.0f} {unit}" if unit == "B" else f"{size:.1f} {unit}"
        size /= 1024
    return f"{size:.1f} GiB"


def cmd_info(args: argparse.Namespace) -> int:
    with _open_project(args.project, readonly=True) as project:
        attrs = project.attrs_root
        print(f"{args.project}: {attrs.get('name', '')}")
        for key in ("schema_version", "software_version", "created", "modified"):
            print(f"  {key}: {attrs.get(key)}")
        for info in project.walk():
            depth = info.path.count("/")
            label = info.path.rsplit("/", 1)[-1]
            if info.kind == "group":
                span = table_span(project, info.path) if info.path.startswith("raw/") else None
                print(f"  {'  ' * depth}{label}/  ({_human(info.nbytes)})"
                      + (f"  time {span.text()}" if span is not None else ""))
            else:
                shape = "x".join(str(n) for n in info.shape) or "scalar"
                print(f"  {'  ' * depth}{label}  {shape} {info.dtype}")
        damaged = _print_results_status(project, verify=not args.quick)
    if damaged:
        first = next(iter(damaged.items()))
        raise InputError(args.project, f"INPUT DAMAGED: {len(damaged)} stored data set(s) "
                         f"fail the read-back against their checksums, e.g. /{first[0]} "
                         f"{first[1]} (listed above)")
    return 0


def _print_results_status(project: Project, verify: bool = True) -> dict[str, str]:
    """One line per stored result: up to date, out of date and why, or INPUT DAMAGED
    (its stored inputs, read back, fail their checksums). Returns the damaged data sets
    (all of ``raw/`` and every result's inputs are read back)."""
    from hydrosync_core.plugins import plugin_specs
    from hydrosync_core.project.verify import damaged
    from hydrosync_core.provenance import OUT_OF_DATE, read_record, stale_reasons

    specs = [s for s in plugin_specs() if project.exists(f"results/{s.id}")]
    records = {s.id: read_record(project, f"results/{s.id}") or {} for s in specs}
    inputs = ["raw"] + [p for rec in records.values() for p in (rec.get("inputs") or {})]
    bad = damaged(project, inputs) if verify else {}
    if not specs:
        _print_damaged(bad)
        return bad
    print("results:")
    for spec in specs:
        path = f"results/{spec.id}"
        hit = [p for p in bad if any(p == i or p.startswith(i.rstrip("/") + "/")
                                     for i in records[spec.id].get("inputs") or {})]
        try:
            reasons = stale_reasons(project, path)
            when = records[spec.id].get("run_utc") or project.attrs(path).get("run_utc", "?")
        except InputError as exc:  # a damaged project: info still lists what it holds
            print(f"  {spec.id}: status cannot be checked: {exc.message}")
            continue
        if hit:
            state = "INPUT DAMAGED: " + "; ".join(f"/{p} {bad[p]}" for p in hit)
        else:
            state = (f"{OUT_OF_DATE.upper()}: " + "; ".join(reasons) if reasons
                     else "up to date")
        print(f"  {spec.id}: {state} (computed {when})")
    _print_damaged(bad)
    return bad


def _print_damaged(bad: dict[str, str]) -> None:
    if bad:
        print("damaged data (read back against their checksums):")
        for path, what in bad.items():
            print(f"  /{path}: {what}")


def cmd_vessel(args: argparse.Namespace) -> int:
    from hydrosync_core.project.vessel import set_sensor, vessel_config

    project = _open_project(args.project, readonly=not args.set and args.name is None
                            and not args.apply)
    if args.apply:
        from hydrosync_core.plugins import plugin_specs
        from hydrosync_core.plugins.spec import load_object

        specs = {s.id: s for s in plugin_specs() if s.apply}
        if args.apply not in specs:
            raise InputError("--apply", f"'{args.apply}' has no calibration to apply (can "
                             f"apply: {', '.join(specs) or 'none'})")
        print("applied " + load_object(specs[args.apply].apply)(project))
    for name, *xyz in args.set or []:
        try:
            offset = [float(v) for v in xyz]
        except ValueError:
            raise InputError(None, f"--set {name}: offsets must be numbers, got {xyz}") from None
        set_sensor(project, name, offset)
    if args.name is not None:
        config = vessel_config(project)
        config["name"] = args.name
        project.put_json("vessel", config)
    if project.dirty:
        project.save()
    config = vessel_config(project)
    print(f"vessel: {config.get('name') or '(unnamed)'}  [{config.get('frame', '')}]")
    for name, sensor in config.get("sensors", {}).items():
        x, y, z = sensor["offset_m"]
        angles = sensor.get("angles_deg")
        extra = (f"  roll {angles.get('roll', 0):+.3f} pitch {angles.get('pitch', 0):+.3f} "
                 f"yaw {angles.get('yaw', 0):+.3f} deg") if angles else ""
        print(f"  {name:<12} x {x:+8.3f}  y {y:+8.3f}  z {z:+8.3f} m{extra}")
    return 0


def cmd_run(args: argparse.Namespace) -> int:
    from hydrosync_core.cli.terminal import TerminalProgress
    from hydrosync_core.params import parse_assignment
    from hydrosync_core.plugins import plugin_specs

    specs = {s.id: s for s in plugin_specs()}
    if args.plugin not in specs:
        raise InputError(None, f"unknown analysis '{args.plugin}' (known: {', '.join(specs)})")
    spec = specs[args.plugin]
    schema = spec.load_params()
    given = dict(parse_assignment(schema, text) for text in args.param or [])
    try:
        params = schema.from_dict(given, strict=True)
    except InputError as exc:
        raise InputError("--param", exc.message, field=exc.field) from None
    project = _open_project(args.project)
    missing = spec.missing_inputs(project)
    if missing:
        raise InputError(args.project, f"{spec.name} needs {', '.join('/' + m for m in missing)}")
    progress = TerminalProgress(spec.name)
    spec.load_run()(project, params, progress, None)
    progress.done()
    project.save()
    changed = ", ".join(f"{k}={v}" for k, v in given.items()) or "defaults"
    for quantity, value in _key_numbers(spec, project):
        print(f"  {quantity:<45} {value}")
    print(f"{spec.name}: parameters {changed}; results stored in {args.project} under "
          f"/results/{spec.id}")
    return 0


def _key_numbers(spec, project) -> list[tuple[str, str]]:
    """The summary rows the analysis's report section offers (its key results)."""
    if not spec.report_section:
        return []
    from hydrosync_core.plugins.spec import load_object

    try:
        summary = load_object(spec.report_section.partition(":")[0] + ":summary")
    except (AttributeError, ImportError):
        return []
    return [(str(k), str(v)) for k, v in summary(project)]


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("new", help="create an empty project file",
                       description="Create an empty project file (HDF5) with an empty vessel "
                       "sheet; import data into it with 'hydrosync import'.")
    p.add_argument("project", help="project file to create (.h5)")
    p.add_argument("--name", help="project name (default: file stem)")
    p.add_argument("--force", action="store_true", help="overwrite an existing file")
    p.set_defaults(func=cmd_new)

    p = sub.add_parser(
        "import", help="import data files into a project (created if missing)",
        description="Import files into a project. Every file is read and checked before "
        "the project is saved, so a bad file leaves the project unchanged.",
    )
    p.add_argument("project", help="project file (.h5)")
    for name, kind in kinds().items():
        # The hyphenated spelling first, so that usage and help show it; the underscore
        # spelling of older scripts keeps working.
        flags = list(dict.fromkeys([f"--{name.replace('_', '-')}", f"--{name}"]))
        more = "".join(f"; see --{option.replace('_', '-')}" for option in kind.options)
        more += f" (repeatable: {kind.repeatable})" if kind.repeatable else ""
        p.add_argument(*flags, dest=name, metavar="FILE", action="append",
                       help=kind.description + more)
    p.add_argument(
        "--heave-positive", choices=("up", "down"), default=None,
        help="direction of positive heave in the --attitude CSV (formats.md: up) or the "
        "--attitude-log file (required for PSXN,23; TSS1 and PASHR are up; Seapath PSXN,23 is "
        "documented positive down); stored heave is always positive up",
    )
    p.add_argument(
        "--empty-geoid", choices=("zero", "skip"), default=None, dest="empty_geoid",
        help="GGA sentences of a --gnss-log with an empty geoid separation: 'zero' keeps them "
        "with the separation taken as 0 (heights then above the geoid, not ellipsoidal; the "
        "import warns), 'skip' drops them (default zero)",
    )
    p.add_argument(
        "--clock-offset", type=float, default=None, dest="clock_offset", metavar="S",
        help="--gins-recording: the GNSS−IMU clock offset (s; the GNSS epoch tagged t "
        "happened at IMU time t + S), applied and stored instead of estimating it from the "
        "turns; later runs use it",
    )
    p.set_defaults(func=cmd_import)

    p = sub.add_parser("info", help="list a project's contents",
                       description="List a project's contents: every group and dataset with "
                       "its shape, the time span of each raw data set (UTC and raw), and "
                       "whether each stored result is up to date with its inputs, which are "
                       "read back against their checksums.")
    p.add_argument("project", help="project file (.h5)")
    p.add_argument("--quick", action="store_true",
                   help="do not read the stored data back against their checksums (by "
                   "default every data set of /raw and every result's inputs is read: a "
                   "damaged one is listed as INPUT DAMAGED and the exit code is 2)")
    p.set_defaults(func=cmd_info)

    p = sub.add_parser(
        "vessel", help="show or edit the vessel offset sheet of a project",
        description="Show the vessel offset sheet; --set changes one sensor's offset "
        "(body frame: x forward, y starboard, z down; metres from the reference point). "
        "A whole sheet is imported with 'hydrosync import P --vessel vessel.json'.",
    )
    p.add_argument("project", help="project file (.h5)")
    p.add_argument("--set", nargs=4, action="append", metavar=("SENSOR", "X", "Y", "Z"),
                   help="set a sensor's offset, m (repeatable); e.g. --set gnss -1.5 2 -6")
    p.add_argument("--name", help="vessel name")
    p.add_argument("--apply", metavar="ANALYSIS",
                   help="write an analysis's calibrated values into the sheet, e.g. "
                   "--apply pool_calibration (multibeam offset = ins offset + lever arm, "
                   "angles = boresight); recorded in the project's history")
    p.set_defaults(func=cmd_vessel)

    p = sub.add_parser(
        "run", help="run one analysis headless on a project and save the results",
        description="Run one analysis on a project with its parameters (defaults from the "
        "analysis's parameter schema; change any with --param NAME=VALUE, repeatable; "
        "tuples as comma-separated numbers, e.g. --param range_s=-0.5,0.5) and store the "
        "results in the project.")
    p.add_argument("plugin", metavar="ANALYSIS", help="analysis id (e.g. latency, "
                   "pool_calibration)")
    p.add_argument("project", help="project file (.h5)")
    p.add_argument("--param", action="append", metavar="NAME=VALUE",
                   help="set one parameter (repeatable); see the analysis command's --help "
                   "for names, units and defaults")
    p.set_defaults(func=cmd_run)
