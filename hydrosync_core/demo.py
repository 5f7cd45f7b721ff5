"""The demo project: simulated data of every plugin, every plugin run, saved, reported.

Generic over the plugin registry: each spec with a ``demo`` simulator fills the project
(the latency plugin a survey day of 13 lines, the pool plugin a calibration pass), then
every plugin whose inputs are present runs headless with its default parameters. A
plugin that fails is recorded and the others go on; the caller decides the exit code.
"""

from __future__ import annotations

import logging
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from hydrosync_core.errors import Cancelled
from hydrosync_core.plugins import PluginSpec, discover, load_object
from hydrosync_core.progress import check_cancel
from hydrosync_core.project import Project, default_vessel

log = logging.getLogger(__name__)

DEMO_PROJECT = "demo.h5"
DEMO_REPORT = "demo-report.pdf"
DEMO_SEED = 20240917
DEMO_NAME = "HydroSync demo (simulated data)"
DEMO_VESSEL = "Simulated survey launch"


@dataclass(frozen=True)
class Stage:
    """One step of the demo and how it went."""

    label: str
    plugin_id: str | None
    ok: bool
    seconds: float
    message: str = ""


@dataclass
class DemoOutcome:
    """Everything the demo produced."""

    project_path: Path
    report_path: Path | None
    stages: list[Stage] = field(default_factory=list)
    results: dict[str, object] = field(default_factory=dict)
    truth: dict[str, object] = field(default_factory=dict)

    @property
    def failed(self) -> list[Stage]:
        return [s for s in self.stages if not s.ok]


class StageListener:
    """What :func:`build_demo` tells its caller; the CLI prints, tests stay quiet.

    ``start(index, total, label)`` returns a progress callback for that stage;
    ``finish(stage)`` is called with its outcome.
    """

    def start(self, index: int, total: int, label: str) -> Callable[[float, str], None] | None:
        return None

    def finish(self, stage: Stage) -> None:
        return None


def _timed(label: str, plugin_id: str | None, listener: StageListener, index: int,
           total: int, fn: Callable[[Callable | None], object]) -> tuple[Stage, object]:
    """Run ``fn(progress)``; turn any exception except a cancel into a failed stage."""
    progress = listener.start(index, total, label)
    t0 = time.perf_counter()
    try:
        value = fn(progress)
    except (Cancelled, KeyboardInterrupt):
        raise
    except Exception as exc:  # one failing plugin must not stop the others
        message = f"{type(exc).__name__}: {exc}"
        stage = Stage(label, plugin_id, False, time.perf_counter() - t0, message)
        log.info("%s failed:\n%s", label, traceback.format_exc())
        listener.finish(stage)
        return stage, None
    stage = Stage(label, plugin_id, True, time.perf_counter() - t0)
    listener.finish(stage)
    return stage, value


def build_demo(out_dir: str | Path, *, seed: int = DEMO_SEED,
               listener: StageListener | None = None, cancel=None,
               specs: list[PluginSpec] | None = None) -> DemoOutcome:
    """Simulate, run every plugin, save ``demo.h5`` and write ``demo-report.pdf``.

    Parameters
    ----------
    out_dir : path-like
        Folder for the two files (created if missing).
    seed : int
        Seed of every simulator (the demo is reproducible).
    listener : StageListener, optional
        Receives stage start/finish events and hands out progress callbacks.
    cancel : object with ``is_set()``, optional
    specs : list of PluginSpec, optional
        The plugins to use (default: every registered plugin).
    """
    from hydrosync_core.report import build_report

    listener = listener or StageListener()
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    outcome = DemoOutcome(out_dir / DEMO_PROJECT, None)
    if specs is None:
        found = discover()
        specs = [d.spec for d in found if d.spec is not None]
        # A plugin that does not even load is a failure of the demo too.
        outcome.stages += [Stage(f"load plugin {d.entry_point}", d.entry_point, False, 0.0,
                                 d.error or "") for d in found if d.spec is None]
        for stage in outcome.stages:
            listener.finish(stage)
    project = Project.new(DEMO_NAME, vessel=dict(default_vessel(), name=DEMO_VESSEL))

    simulated = [s for s in specs if s.demo]
    # Stages: each simulation, each run (plugins with data: simulated or needing none),
    # the save and the report.
    total = len(simulated) + sum(1 for s in specs if s.demo or not s.requires) + 2
    index = 0
    failed_simulation: set[str] = set()
    for spec in simulated:
        check_cancel(cancel)
        index += 1
        fill = load_object_safe(spec.demo)
        stage, truth = _timed(f"{spec.name}: simulate data", spec.id, listener, index, total,
                              lambda progress, fill=fill: fill(project, seed=seed,
                                                               progress=progress))
        outcome.stages.append(stage)
        if not stage.ok:
            failed_simulation.add(spec.id)
        elif truth is not None:
            outcome.truth[spec.id] = truth  # what the simulator put in, to compare with

    for spec in specs:
        check_cancel(cancel)
        if spec.id in failed_simulation or spec.missing_inputs(project):
            continue  # nothing to run on (its simulation failed or it has none)
        index += 1
        run = spec.load_run

        def go(progress, spec=spec, run=run):
            return run()(project, dict(spec.default_params), progress, cancel)

        stage, result = _timed(f"{spec.name}: run", spec.id, listener, index, total, go)
        outcome.stages.append(stage)
        if stage.ok:
            outcome.results[spec.id] = result
        else:
            # Whatever a failed run left half-written must not reach the report.
            project.delete(f"results/{spec.id}")

    check_cancel(cancel)
    index += 1
    stage, _ = _timed("save project", None, listener, index, total,
                      lambda progress: project.save(outcome.project_path))
    outcome.stages.append(stage)
    index += 1
    report_path = out_dir / DEMO_REPORT
    stage, _ = _timed("write report", None, listener, index, total,
                      lambda progress: build_report(project, report_path, progress, cancel))
    outcome.stages.append(stage)
    if stage.ok:
        outcome.report_path = report_path
    project.close()
    return outcome


def truth_text(value, digits: int = 8) -> str:
    """Compact one-line text of a simulator's truth (nested dicts/lists of numbers).

    Up to *digits* significant digits, trailing zeros dropped: a round truth reads round
    (``-44.2``), a drawn one as many digits as any result printed beside it (results
    carry up to 8: ``512.3404``); at 4 digits the truth looked coarser than the estimate.
    """
    if isinstance(value, dict):
        # Arrays (e.g. true epoch times) are not one-line material: left out.
        return ", ".join(f"{k} {truth_text(v, digits)}" for k, v in value.items()
                         if not (hasattr(v, "shape") and getattr(v, "size", 0) > 6))
    if isinstance(value, list | tuple):
        return "[" + ", ".join(truth_text(v, digits) for v in value) + "]"
    if isinstance(value, float):
        return f"{value:.{digits}g}"
    return str(value)


def load_object_safe(dotted: str) -> Callable:
    """``load_object`` that defers an import error to the call (so it becomes a stage failure)."""
    try:
        return load_object(dotted)
    except Exception as exc:
        error = exc

        def broken(*_args, **_kwargs):
            raise error

        return broken


def key_results(project_path: str | Path, specs: list[PluginSpec] | None = None
                ) -> list[tuple[str, str, str]]:
    """``(module, quantity, value)`` rows of every module with results, as in the report."""
    from hydrosync_core.report.cover import module_status

    specs = [d.spec for d in discover() if d.spec is not None] if specs is None else specs
    rows: list[tuple[str, str, str]] = []
    with Project.open(project_path) as project:
        for spec in specs:
            status = module_status(project, spec)
            rows += [(spec.name, q, v) for q, v in status.rows]
    return rows
