"""``hydrosync demo [--out DIR]``: build, compute and report the demo project.

Prints one line per stage (so a log file shows progress) and, on a terminal, a live
progress line on stderr. Exit 0 when every stage worked, 1 if any plugin failed (the
others still ran and the files were still written).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from hydrosync_core.cli.terminal import TerminalProgress
from hydrosync_core.demo import (
    DEMO_PROJECT,
    DEMO_REPORT,
    DEMO_SEED,
    Stage,
    StageListener,
    build_demo,
    key_results,
    truth_text,
)


class _PrintingListener(StageListener):
    """Stage lines on stdout, a live progress line on stderr when it is a terminal."""

    def __init__(self) -> None:
        self._progress: TerminalProgress | None = None
        self._label = ""

    def start(self, index: int, total: int, label: str):
        print(f"[{index}/{total}] {label} ...", flush=True)
        self._label = label
        self._progress = TerminalProgress(label)
        return self._progress

    def finish(self, stage: Stage) -> None:
        if self._progress is not None:
            self._progress.done()
            self._progress = None
        if stage.label != self._label:  # a failure outside any stage (plugin not loading)
            print(f"{stage.label}: FAILED: {stage.message}", flush=True)
            return
        status = "done" if stage.ok else "FAILED"
        line = f"      {status} in {stage.seconds:.1f} s"
        if not stage.ok:
            line += f": {stage.message}"
        print(line, flush=True)


def cmd_demo(args: argparse.Namespace) -> int:
    from hydrosync_core.atomic import check_writable
    from hydrosync_core.errors import InputError

    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise InputError(str(out), "--out must be a folder")
    try:  # outputs checked before any work
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(str(out), f"--out folder cannot be created ({exc.strerror})") from None
    for name in (DEMO_PROJECT, DEMO_REPORT):
        check_writable(out / name, "--out")
    t0 = time.perf_counter()
    outcome = build_demo(out, seed=args.seed, listener=_PrintingListener())
    elapsed = time.perf_counter() - t0
    print()
    if outcome.project_path.exists():
        print(f"project: {outcome.project_path}")
    if outcome.report_path is not None:
        print(f"report:  {outcome.report_path}")
    if outcome.project_path.exists():
        rows = key_results(outcome.project_path)
        if rows:
            print("key results:")
            width = max(len(q) for _, q, _ in rows)
            module = None
            for name, quantity, value in rows:
                if name != module:
                    print(f"  {name}")
                    module = name
                print(f"    {quantity:<{width}}  {value}")
    names = {stage.plugin_id: stage.label.split(":")[0] for stage in outcome.stages}
    for plugin_id, truth in outcome.truth.items():
        if isinstance(truth, dict):
            print(f"simulated truth, {names.get(plugin_id, plugin_id)}: {truth_text(truth)}")
    print(f"finished in {elapsed:.1f} s")
    if outcome.failed:
        for stage in outcome.failed:
            print(f"hydrosync demo: {stage.label} failed: {stage.message}", file=sys.stderr)
        return 1
    return 0


def register(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "demo", help="build the demo project from simulated data, run every module, report",
        description="Simulate a data set for every installed module (latency: a survey day "
        "of 13 lines; pool calibration: a calibration pass), run every module, then write "
        "DIR/demo.h5 and DIR/demo-report.pdf.",
    )
    p.add_argument("--out", default=".", metavar="DIR",
                   help="output folder (default: the current folder; created if missing)")
    p.add_argument("--seed", type=int, default=DEMO_SEED,
                   help="random seed of the simulators (default: %(default)s)")
    p.set_defaults(func=cmd_demo)
