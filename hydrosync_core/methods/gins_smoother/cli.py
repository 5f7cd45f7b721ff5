"""``hydrosync gins``: post-processed trajectory from IMU increments and GNSS positions.

File form (docs/formats.md)::

    hydrosync gins --imu IMU --gnss GNSS --config CONFIG --out TRAJ.nav [--forward-only]
        [--truth TRUTH.nav --json RESULT] [--outages WINDOWS.txt] [method parameters]

``CONFIG`` may be a KF-GINS YAML file. ``TRAJ.nav`` is an 11-column KF-GINS ``.nav``
(smoothed unless ``--forward-only``) with the sibling ``TRAJ_std.nav`` of standard
deviations. Project form: ``hydrosync gins PROJECT.h5 [--out TRAJ.nav] [--json RESULT]``
reads ``/raw/gins`` and stores ``/results/gins_smoother``. Exit codes: 0 success, 2 bad
input (one line naming the file, line and field), 130 interrupted, 1 anything else.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from hydrosync_core.errors import InputError
from hydrosync_core.methods.gins_smoother.params import RAN, GinsParams
from hydrosync_core.params import add_cli_arguments, from_cli


def _check_out(path: Path | None, option: str) -> None:
    from hydrosync_core.atomic import check_writable

    if path is not None and not path.parent.resolve().is_dir():
        raise InputError(str(path), f"folder of {option} does not exist")
    if path is not None:
        check_writable(path, option)  # not a device, FIFO or /proc file; writable


def _write(res, out: Path, forward_only: bool) -> None:
    from hydrosync_core.methods.gins_smoother.io import write_nav

    tr = res.forward if forward_only or res.smoothed is None else res.smoothed
    write_nav(out, tr.time, tr.llh, tr.vel, tr.att, std=(tr.pos_std, tr.vel_std, tr.att_std))


def _summary(res, ev: dict) -> dict:
    import numpy as np

    from hydrosync_core.jsonsafe import jsonable

    doc = {"counts": res.counts, "alignment": res.alignment, "evaluation": ev,
           "gnss_model": res.gnss_model}
    for key in ("residual_forward", "residual"):
        if key in res.gnss:
            r = res.gnss[key]
            ok = np.isfinite(r).all(axis=1)
            doc[f"gnss_{key}_rms_m"] = (np.sqrt(np.mean(r[ok] ** 2, axis=0)).tolist()
                                        if ok.any() else None)
    return jsonable(doc)


def _print(doc: dict) -> None:
    c = doc["counts"]
    smoothed = c.get("ran", RAN[True]) == RAN[True]
    print(f"ran: {c.get('ran', RAN[True])}")
    print(f"{c['imu_epochs']} IMU epochs, {c['gnss_used']} of {c['gnss_epochs']} GNSS fixes "
          f"used, {c['states']} states, {c['nodes']} "
          f"{'smoother' if smoothed else 'filter'} nodes; alignment: "
          f"{doc['alignment'].get('method')}")
    if doc.get("gnss_model", {}).get("summary"):
        print(f"σ computed from: {doc['gnss_model']['summary']}")
    for name, ev in doc["evaluation"].items():
        a = ev.get("gnss_on", ev["all"])
        print(f"{name:<9} RMS pos N/E/D {a['north']['rms']:.4f} {a['east']['rms']:.4f} "
              f"{a['down']['rms']:.4f} m, vel {a['vn']['rms']:.4f} {a['ve']['rms']:.4f} "
              f"{a['vd']['rms']:.4f} m/s, roll/pitch/yaw {a['roll']['rms']:.5f} "
              f"{a['pitch']['rms']:.5f} {a['yaw']['rms']:.5f} deg")
        o = ev.get("outage")
        if o and o["rms_max_horizontal_m"] is not None:
            print(f"{'':<9} outage drift (RMS of per-outage max) horizontal "
                  f"{o['rms_max_horizontal_m']:.3f} m, vertical {o['rms_max_vertical_m']:.3f} m")
        c = ev.get("coverage", {}).get("all", {})
        if c.get("north"):
            print(f"{'':<9} within 1.96σ of the reference: pos N/E/D " + " ".join(
                f"{100 * c[k]['within_95']:.0f}" for k in ("north", "east", "down"))
                + " %, vel " + " ".join(f"{100 * c[k]['within_95']:.0f}" for k in
                                        ("vn", "ve", "vd"))
                + " %, roll/pitch/yaw " + " ".join(f"{100 * c[k]['within_95']:.0f}" for k in
                                                   ("roll", "pitch", "yaw")) + " %")
        off = ev.get("constant_offset")
        c0 = ev.get("coverage", {}).get("offset_removed", {})
        if off and c0.get("yaw"):
            print(f"{'':<9} constant offset from the reference roll/pitch/yaw "
                  + "/".join(f"{off[k]:+.2f}" for k in ("roll", "pitch", "yaw"))
                  + " deg, N/E/D " + "/".join(f"{off[k]:+.2f}" for k in ("north", "east",
                                                                        "down"))
                  + " m (the reference's own axes and point: not independent, mounting "
                  "unknown); within 1.96σ with it removed: roll/pitch/yaw "
                  + " ".join(f"{100 * c0[k]['within_95']:.0f}" for k in ("roll", "pitch",
                                                                        "yaw")) + " %")


def _run_files(args, params: GinsParams) -> int:
    from hydrosync_core.atomic import write_json_atomic
    from hydrosync_core.cli.terminal import TerminalProgress
    from hydrosync_core.methods.gins_smoother.config import read_config
    from hydrosync_core.methods.gins_smoother.evaluate import evaluate
    from hydrosync_core.methods.gins_smoother.filter import run_gins
    from hydrosync_core.methods.gins_smoother.io import (
        read_gnss,
        read_imu,
        read_nav,
        read_outages,
    )

    if args.recording is not None:
        if args.imu or args.gnss:
            raise InputError(str(args.recording), "give either --recording or --imu/--gnss")
        if not args.out:
            raise InputError(None, "missing option --out")
    else:
        if args.clock_offset is not None:
            raise InputError(None, "--clock-offset applies to --recording only")
        missing = [o for o, v in (("--imu", args.imu), ("--gnss", args.gnss),
                                  ("--config", args.config), ("--out", args.out)) if not v]
        if missing:
            raise InputError(None, f"missing option(s) {', '.join(missing)} (or give a "
                             "project or --recording)")
    _check_out(args.out, "--out")
    _check_out(args.json, "--json")
    truth = read_nav(args.truth) if args.truth else None
    if args.recording is not None:
        from hydrosync_core.methods.gins_smoother.recordings import (
            estimate_time_shift,
            read_recording,
            shifted,
        )

        rec = read_recording(args.recording)
        # the recording's options replace the options the user did not give (a value
        # given equal to the schema default still wins over the recording's), in every
        # step from the clock offset on
        params = GinsParams.from_dict({**rec.params, **_given(args, params)})
        if args.clock_offset is not None:
            shift = args.clock_offset
            print(f"{rec.name}: GNSS−IMU clock offset {shift:+.3f} s given and applied")
        else:
            shift, est = estimate_time_shift(rec, params.to_dict())
            print(f"{rec.name}: " + (f"{est.text()}; applied" if est is not None else
                                     "GNSS−IMU clock offset: the recording's own timing"))
        rec = shifted(rec, shift)
        for note in rec.notes:
            print(f"  {note}")
        cfg = read_config(args.config) if args.config else rec.config
        imu, gnss = rec.imu, rec.gnss
        truth = truth if truth is not None else rec.reference
    else:
        cfg = read_config(args.config)
        imu = read_imu(args.imu, cfg.imu_rate_hz)
        gnss = read_gnss(args.gnss)
    windows = read_outages(args.outages) if args.outages else []
    progress = TerminalProgress("gins")
    res = run_gins(imu, gnss.without(windows) if windows else gnss, cfg, params, progress)
    progress.done()
    ev = evaluate(res, truth, windows) if truth is not None else {}
    _write(res, args.out, args.forward_only)
    doc = _summary(res, ev)
    if args.json is not None:
        write_json_atomic(args.json, doc)
    _print(doc)
    print(f"{_which(res, args.forward_only)} trajectory written to {args.out} (standard "
          f"deviations in {args.out.stem}_std{args.out.suffix or '.nav'})")
    return 0


def _which(res, forward_only: bool) -> str:
    return "forward" if forward_only or res.smoothed is None else "smoothed"


def _given(args, params: GinsParams) -> dict:
    """The options given on the command line (validated values of *params*)."""
    from hydrosync_core.params import cli_values

    values = params.to_dict()
    return {k: values[k] for k in cli_values(args, GinsParams)}


def _run_project(args, params: GinsParams) -> int:
    from hydrosync_core.atomic import write_json_atomic
    from hydrosync_core.cli.terminal import TerminalProgress
    from hydrosync_core.methods.gins_smoother.project_run import run
    from hydrosync_core.project import Project

    if args.clock_offset is not None:
        raise InputError(str(args.project), "a project's recording takes its clock offset "
                         "at import: hydrosync import PROJECT --gins-recording DIR "
                         "--clock-offset S")
    if args.imu or args.gnss or args.config or args.recording:
        raise InputError(str(args.project), "give either a project file or --imu/--gnss/"
                         "--config/--recording")
    _check_out(args.out, "--out")
    _check_out(args.json, "--json")
    project = Project.open(args.project)
    progress = TerminalProgress("gins")
    try:
        # options the user did not give leave an imported recording's options in place
        res = run(project, _given(args, params), progress, None)
    except InputError as exc:
        raise InputError(f"{args.project}{exc.file or ''}", exc.message, line=exc.line,
                         field=exc.field) from None
    progress.done()
    import json

    ev = json.loads(project.attrs("results/gins_smoother")["evaluation"])
    doc = _summary(res, ev)
    if args.out is not None:
        _write(res, args.out, args.forward_only)
    if args.json is not None:
        write_json_atomic(args.json, doc)
    project.save()
    _print(doc)
    if args.out is not None:
        print(f"{_which(res, args.forward_only)} trajectory written to {args.out}")
    print(f"results stored in {args.project} under /results/gins_smoother")
    return 0


def cmd_gins(args: argparse.Namespace) -> int:
    params = from_cli(args, GinsParams)  # bad parameters fail before any work
    if args.forward_only:
        params = GinsParams.from_dict({**params.to_dict(), "smooth": False})
    return _run_project(args, params) if args.project else _run_files(args, params)


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "gins", aliases=["gins-smoother"],
        help="GNSS/INS trajectory: EKF with motion constraints and RTS smoothing",
        description="Loosely coupled GNSS/INS (Wang et al.): strapdown mechanisation, 15 or "
        "21-state EKF with GNSS lever arm, NHC and ZUPT, RTS smoother. From KF-GINS files "
        "(--imu, --gnss, --config, --out) or a project (results under "
        "/results/gins_smoother).")
    p.add_argument("project", nargs="?", type=Path, help="project file (.h5) instead of files")
    p.add_argument("--imu", type=Path, help="IMU increments: KF-GINS 7-column text or imu.csv "
                   "(body x forward, y right, z down)")
    p.add_argument("--gnss", type=Path, help="GNSS antenna positions with std: KF-GINS text "
                   "or gnss.csv")
    p.add_argument("--config", type=Path, help="KF-GINS YAML configuration (initial state, "
                   "IMU noise, lever arm) or JSON with the same keys")
    p.add_argument("--out", type=Path, help="trajectory to write, 11-column KF-GINS .nav "
                   "(+ NAME_std.nav)")
    p.add_argument("--recording", type=Path, help="a real recording folder instead of "
                   "--imu/--gnss: comma2k19 segment or rtklibexplorer drive/walk (its IMU "
                   "grade, lever arm, options and reference are used unless given)")
    p.add_argument("--clock-offset", type=float, metavar="S", help="with --recording: the "
                   "GNSS−IMU clock offset (s, the GNSS epoch tagged t happened at IMU time "
                   "t + S) instead of estimating it from the turns (for a project: give it "
                   "to 'hydrosync import --gins-recording')")
    p.add_argument("--forward-only", action="store_true", help="write the forward filter "
                   "solution, skip smoothing")
    p.add_argument("--truth", type=Path, help="reference .nav for error statistics")
    p.add_argument("--outages", type=Path, help="GNSS outages to simulate: 'start end' (s) "
                   "per line")
    p.add_argument("--json", type=Path, help="result JSON (counts, statistics, residuals)")
    add_cli_arguments(p, GinsParams)
    p.set_defaults(func=cmd_gins)
