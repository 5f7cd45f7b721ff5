"""Running a campaign on ``dask.distributed``.

Where it runs: an explicit ``scheduler`` address (``--scheduler tcp://host:8786``), else
Dask's own ``scheduler-address`` setting (the ``DASK_SCHEDULER_ADDRESS`` environment
variable or a Dask config file), else a ``LocalCluster`` of worker *processes* with one
thread each (the numeric work holds the GIL), as many as the machine has cores unless
``workers`` says otherwise. A caller may also pass its own ``Client`` (tests).

The task graph: per project a chain ``[import] → analysis 1 → analysis 2 → … → [report]``,
one Dask task per project × analysis. Tasks of one project are chained — each takes the
outcome of the one before as an argument — because they all need the project's write lock
(:mod:`hydrosync_core.project.lock`): two of them at once would have the second refused.
Chains of different projects are independent, so the cluster runs as many projects at a
time as it has worker threads. Chaining (rather than one task per project running its
analyses in a loop) keeps a status, a duration and a retry per analysis: the dashboard and
the progress line count project × analysis tasks, and a worker killed during the third
analysis costs only that analysis — Dask reruns that one task elsewhere; the first two
are saved in the project already.

Steps never raise for a problem of their project (:mod:`hydrosync_core.campaign.steps`);
what can still fail at the Dask level (a task that killed ``allowed-failures`` workers in
a row, a lost connection) is recorded as a failed step of that project and the others go
on.
"""

from __future__ import annotations

import contextlib
import logging
import os
import time
import uuid
from dataclasses import dataclass, field

from hydrosync_core.campaign.config import Campaign
from hydrosync_core.campaign.steps import (
    DONE,
    FAILED,
    OK_STATES,
    UNDETERMINED,
    UP_TO_DATE,
    analysis_step,
    import_step,
    report_step,
)
from hydrosync_core.errors import Cancelled, InputError

log = logging.getLogger(__name__)

HEARTBEAT_S = 5.0
"""The progress line is repeated at least this often (s), also when nothing changes."""

STALL_S = 120.0
"""Default stall timeout (s): no step finished and none ran for this long."""


@dataclass
class Progress:
    """The state of a running campaign, handed to the listener after every change."""

    total: int
    done: int = 0
    failed: int = 0
    running: int = 0
    elapsed_s: float = 0.0
    eta_s: float | None = None
    last: dict | None = None
    """Outcome of the step that finished last."""
    workers: int | None = None
    """Workers alive at the last look (None: not asked)."""

    @property
    def finished(self) -> int:
        return self.done + self.failed

    def text(self) -> str:
        eta = f"ETA {_duration(self.eta_s)}" if self.eta_s is not None else "ETA --"
        line = (f"[{self.finished}/{self.total}] done {self.done}, failed {self.failed}, "
                f"running {self.running}; elapsed {_duration(self.elapsed_s)}, {eta}")
        if self.last is not None:
            line += f"; last: {self.last['project']} {self.last['step']} {self.last['status']}"
        if self.workers == 0:
            line += "; no worker alive (waiting for one)"
        return line


def _duration(seconds: float | None) -> str:
    if seconds is None:
        return "--"
    seconds = int(round(seconds))
    return f"{seconds // 60}m{seconds % 60:02d}s" if seconds >= 60 else f"{seconds}s"


@dataclass
class CampaignResult:
    """Every step's outcome, in campaign order, and where it ran."""

    campaign: Campaign
    outcomes: list[dict] = field(default_factory=list)
    where: str = ""
    dashboard: str | None = None
    workers: int = 0
    wall_s: float = 0.0
    summary_files: list[str] = field(default_factory=list)

    @property
    def failed(self) -> list[dict]:
        return [o for o in self.outcomes if o["status"] not in OK_STATES]

    def count(self, status: str) -> int:
        return sum(1 for o in self.outcomes if o["status"] == status)


class Listener:
    """What :func:`run_campaign` tells its caller (the CLI prints, the GUI shows)."""

    def started(self, result: CampaignResult, total: int) -> None:
        return None

    def update(self, progress: Progress) -> None:
        return None


# ------------------------------------------------------------------------ the cluster
def scheduler_address(explicit: str | None) -> str | None:
    """The address to connect to: *explicit*, else Dask's ``scheduler-address`` setting."""
    if explicit:
        return explicit
    import dask

    return dask.config.get("scheduler-address", None) or None


def dashboard_available() -> bool:
    try:
        import bokeh  # noqa: F401
    except ImportError:
        return False
    return True


def open_client(scheduler: str | None = None, workers: int | None = None,
                dashboard: bool = True):
    """``(client, cluster_or_None, where)``: connect, or start a LocalCluster."""
    from dask.distributed import Client, LocalCluster

    address = scheduler_address(scheduler)
    if address:
        try:
            client = Client(address, timeout="15s")
        except (OSError, TimeoutError) as exc:
            raise InputError(address, f"no Dask scheduler answers there ({exc})") from None
        return client, None, f"Dask scheduler {address}"
    n = int(workers or os.cpu_count() or 1)
    cluster = LocalCluster(
        n_workers=n, threads_per_worker=1, processes=True,
        # Any free port, also without a dashboard: Dask's HTTP server starts either way, and
        # its default 8787 taken by another campaign (or test worker) is a warning.
        dashboard_address=":0",
        silence_logs=logging.ERROR)
    client = Client(cluster)
    return client, cluster, f"LocalCluster of {n} worker process(es), 1 thread each"


# --------------------------------------------------------------------------- running
def stop_flag(token: str) -> str:
    """Name of the Dask ``Event`` that tells the steps of campaign *token* not to start."""
    return f"hydrosync-stop-{token}"


def _guarded(fn, token: str, step: str, entry, *args):
    """Run step *fn* on a worker unless the campaign was interrupted before it started
    (then a ``skipped`` outcome: exact, where cancelling a queued Dask task may lose the
    race with the worker starting it)."""
    from hydrosync_core.campaign.steps import SKIPPED, _outcome

    try:
        import distributed

        stopped = distributed.Event(stop_flag(token)).is_set()
    except Exception:  # no scheduler to ask: run, as before
        stopped = False
    if stopped:
        out = _outcome(entry, step)
        out.update(status=SKIPPED, message="not started: the campaign was interrupted")
        return out
    return fn(entry, *args)


def _submit(client, campaign: Campaign, token: str) -> list[tuple[object, dict]]:
    """Submit every step; return ``(future, placeholder outcome)`` in campaign order."""
    steps = []
    out_dir = campaign.outputs.dir
    for entry in campaign.projects:
        def add(fn, step, *args, entry=entry):
            future = client.submit(_guarded, fn, token, step, entry, *args,
                                   key=f"{step}-{entry.label}-{token}", pure=False)
            steps.append((future, {"project": entry.label, "path": entry.path,
                                   "date": entry.date, "step": step}))
            return future

        previous = add(import_step, "import") if entry.source is not None else None
        analysed = []
        for analysis in campaign.analyses:
            previous = add(analysis_step, analysis.id, analysis, previous)
            analysed.append(previous)
        if campaign.outputs.report:
            add(report_step, "report", out_dir, analysed)
    return steps


def _dask_failure(placeholder: dict, future) -> dict:
    if future.status == "cancelled":
        return dict(placeholder, status=FAILED, message="cancelled before it started "
                    "(interrupted): not run", warnings=[], seconds=0.0, worker="",
                    run_utc=None, rows=[], numbers={}, data_date=None)
    try:
        exc = future.exception(timeout=5)
        text = f"{type(exc).__name__}: {exc}"
    except Exception as exc:  # the future itself is gone
        text = f"{type(exc).__name__}: {exc}"
    if "KilledWorker" in text:
        text = ("the step killed the workers that ran it several times in a row "
                f"(Dask gave up): {text}")
    return dict(placeholder, status=FAILED, message=" ".join(text.split())[:400],
                warnings=[], seconds=0.0, worker="", run_utc=None, rows=[], numbers={},
                data_date=None)


def _running(client, keys: set, threads: int) -> int:
    """Steps being worked on: assigned to a worker, at most one per worker thread."""
    try:
        processing = client.processing()
    except Exception:
        return 0
    assigned = sum(1 for tasks in processing.values() for k in tasks if k in keys)
    return min(assigned, threads) if threads else assigned


def run_campaign(campaign: Campaign, *, scheduler: str | None = None,
                 workers: int | None = None, client=None,
                 listener: Listener | None = None, cancel=None,
                 poll_s: float = 0.25, write_summary: bool = True,
                 dashboard: bool = True, heartbeat_s: float = HEARTBEAT_S,
                 stall_s: float = STALL_S) -> CampaignResult:
    """Run *campaign* on Dask and return every step's outcome.

    Parameters
    ----------
    campaign : Campaign
    scheduler : str, optional
        Address of an existing scheduler (default: Dask's setting, else a LocalCluster).
    workers : int, optional
        Worker processes of the LocalCluster (default: one per core).
    client : distributed.Client, optional
        Use this client (left open) instead of making one.
    listener : Listener, optional
        Told of the start (where, dashboard) and of every change of progress.
    cancel : object with ``is_set()``, optional
        Set it to stop: pending steps are cancelled; steps already saved stay saved.
    write_summary : bool
        Write ``summary.csv`` / ``summary.html`` when the campaign asks for them.
    heartbeat_s : float
        The listener hears at least this often (s), even when nothing changes (no worker
        alive: formats.md promises a progress line every 5 s).
    stall_s : float
        Stop with :class:`CampaignStalled` when for this long (s) no step finished and
        none ran (every worker dead, a scheduler that schedules nothing).

    A Ctrl-C (``KeyboardInterrupt``) cancels the steps not started, waits for those
    running (their saves land, or not, before the message is written) and tells the
    listener of each, then raises again.
    """
    listener = listener or Listener()
    result = CampaignResult(campaign)
    t0 = time.perf_counter()
    own_cluster = None
    if client is None:
        client, own_cluster, result.where = open_client(scheduler, workers, dashboard)
        own_client = True
    else:
        own_client = False
        result.where = f"Dask client {client.scheduler.address}"
    steps = []
    try:
        try:
            result.dashboard = client.dashboard_link if dashboard and (
                own_cluster is None or own_cluster.scheduler.services.get("dashboard")) \
                else None
        except Exception:
            result.dashboard = None
        result.workers = len(client.scheduler_info().get("workers", {}))
        threads = sum(client.nthreads().values())
        outcomes: list[dict | None] = []
        progress, keys = Progress(total=0), set()
        token = uuid.uuid4().hex[:8]
        try:
            steps = _submit(client, campaign, token)
            outcomes[:] = [None] * len(steps)
            progress = Progress(total=len(steps))
            keys = {future.key for future, _ in steps}
            listener.started(result, len(steps))
            _watch(client, steps, outcomes, progress, keys, listener, threads, cancel,
                   (poll_s, heartbeat_s, stall_s), t0)
        except KeyboardInterrupt:
            if steps:
                _wind_down(client, steps, outcomes, progress, listener, keys, stall_s, token)
            raise
        result.outcomes = [o for o in outcomes if o is not None]
    finally:
        if steps and any(f.status == "pending" for f, _ in steps):
            with contextlib.suppress(Exception):
                client.cancel([f for f, _ in steps])
        if own_client:
            client.close()
            if own_cluster is not None:
                own_cluster.close()
    result.wall_s = time.perf_counter() - t0
    if write_summary and campaign.outputs.summary:
        from hydrosync_core.campaign.summary import write_summary as write

        result.summary_files = [str(p) for p in write(result)]
    return result


class CampaignStalled(InputError):
    """No step finished or ran for the stall timeout: exit 2 with one line."""


def _collect(steps, outcomes: list, progress: Progress, keys: set,
             listener: Listener) -> bool:
    """Record the steps that ended since the last look, telling the listener of each
    (``progress.last``); True if any did."""
    changed = False
    for i, (future, placeholder) in enumerate(steps):
        if outcomes[i] is not None or future.status == "pending":
            continue
        if future.status == "finished":
            outcomes[i] = future.result()
        else:  # error, cancelled, lost
            outcomes[i] = _dask_failure(placeholder, future)
        keys.discard(future.key)
        progress.last = outcomes[i]
        if outcomes[i]["status"] in OK_STATES:
            progress.done += 1
        else:
            progress.failed += 1
        changed = True
        listener.update(progress)
    return changed


def _alive_workers(client) -> int | None:
    try:
        return len(client.scheduler_info().get("workers", {}))
    except Exception:
        return None


def _watch(client, steps, outcomes: list, progress: Progress, keys: set,
           listener: Listener, threads: int, cancel, timing: tuple[float, float, float],
           t0: float) -> None:
    """Poll the futures until every step ended, filling *outcomes* (submission order).

    *timing* is ``(poll_s, heartbeat_s, stall_s)`` (see :func:`run_campaign`).
    """
    poll_s, heartbeat_s, stall_s = timing
    last_running, last_told = -1, time.monotonic()
    last_activity = last_told
    while True:
        if cancel is not None and cancel.is_set():
            raise Cancelled("campaign cancelled")
        changed = _collect(steps, outcomes, progress, keys, listener)
        now = time.monotonic()
        progress.elapsed_s = time.perf_counter() - t0
        if progress.finished == progress.total:
            progress.running, progress.eta_s = 0, 0.0
            listener.update(progress)
            return
        progress.running = _running(client, keys, threads)
        if changed or progress.running:
            last_activity = now
        if progress.finished:
            progress.eta_s = (progress.elapsed_s / progress.finished
                              * (progress.total - progress.finished))
        beat = now - last_told >= heartbeat_s
        if changed or progress.running != last_running or beat:
            if beat or progress.running == 0:
                progress.workers = _alive_workers(client)
            last_running, last_told = progress.running, now
            listener.update(progress)
        if now - last_activity >= stall_s:
            raise _stalled(progress, stall_s, outcomes)
        time.sleep(poll_s)


def _stalled(progress: Progress, stall_s: float, outcomes) -> CampaignStalled:
    saved = sorted({o["project"] for o in outcomes if o is not None and o["status"] in
                    (DONE, UNDETERMINED)})
    why = ("no worker is alive" if progress.workers == 0 else
           f"{progress.workers} worker(s) connected but none took a step")
    return CampaignStalled(
        None, f"campaign stalled: no step finished or ran for {stall_s:.0f} s ({why}); "
        f"{progress.finished} of {progress.total} step(s) ended"
        + (f", saved: {', '.join(saved)}" if saved else ", nothing saved")
        + "; running it again redoes only the rest (--stall-timeout S to wait longer)")


def _wind_down(client, steps, outcomes, progress: Progress, listener: Listener,
               keys: set, limit_s: float, token: str) -> None:
    """After Ctrl-C: tell the steps not yet started to skip (the stop flag) and wait for
    every step to end — a running one cannot be stopped mid-step, and its save must not
    land after we said it did not — so each outcome is known before the message. Without
    a live worker nothing can end: nothing is waited for."""
    import distributed

    with contextlib.suppress(Exception):
        distributed.Event(stop_flag(token), client=client).set()
    unfinished = [f for f, _ in steps if f.status == "pending"]
    if unfinished and _alive_workers(client):
        log.warning("interrupted: waiting for %d step(s) to finish or skip (Ctrl-C again to "
                    "stop at once)", len(unfinished))
        with contextlib.suppress(distributed.TimeoutError, Exception):
            distributed.wait(unfinished, timeout=limit_s)
    _collect(steps, outcomes, progress, keys, listener)


def status_counts(result: CampaignResult) -> str:
    """``"12 done, 4 up to date, 1 failed"``."""
    order = (DONE, UNDETERMINED, UP_TO_DATE, "not applicable", "skipped", FAILED)
    parts = [f"{result.count(s)} {s}" for s in order if result.count(s)]
    return ", ".join(parts) or "nothing to do"

