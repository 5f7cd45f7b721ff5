"""Issue #28: batch edge cases (no worker alive, Ctrl-C while a step runs, a step that
did not converge) and ``info`` reading stored inputs back against their checksums.

The batch tests run an in-process ``LocalCluster`` (threads, no worker processes) so the
steps can be replaced by module-level functions that wait on events: every condition
below is observed (the listener's records, marker files), no duration is asserted.
"""

from __future__ import annotations

import _thread
import logging
import threading
from pathlib import Path

import h5py
import numpy as np
import pytest

from hydrosync_core.project import Project
from tests.reliability.conftest import run_cli, stderr_lines

STARTED = threading.Event()
RELEASE = threading.Event()
MARKERS: dict[str, Path] = {}


def _campaign(tmp_path: Path, names=("a", "b")):
    from hydrosync_core.campaign import load_campaign

    for name in names:
        Project.new(name).save(tmp_path / f"{name}.h5")
    path = tmp_path / "c.toml"
    files = ", ".join(f'"{n}.h5"' for n in names)
    path.write_text(f'[campaign]\nname = "c"\n[projects]\nfiles = [{files}]\n'
                    '[analyses.latency]\n[outputs]\nreport = false\nsummary = false\n')
    return load_campaign(path)


class Recorder:
    def __init__(self) -> None:
        self.updates: list = []

    def started(self, result, total) -> None:
        pass

    def update(self, progress) -> None:
        self.updates.append((progress.text(), progress.workers, progress.last))


@pytest.fixture
def no_worker_client():
    from dask.distributed import Client, LocalCluster

    cluster = LocalCluster(n_workers=0, processes=False, dashboard_address=None,
                           silence_logs=logging.CRITICAL)
    client = Client(cluster)
    yield client
    client.close()
    cluster.close()


def test_no_worker_alive_heartbeats_then_stalls_with_one_line(tmp_path, no_worker_client,
                                                              faults):
    from hydrosync_core.campaign.engine import CampaignStalled, run_campaign

    campaign = _campaign(tmp_path)
    listener = Recorder()
    with pytest.raises(CampaignStalled) as caught:
        run_campaign(campaign, client=no_worker_client, listener=listener, poll_s=0.01,
                     heartbeat_s=0.05, stall_s=0.5, write_summary=False)
    message = caught.value.one_line()
    beats = [u for u in listener.updates if u[1] == 0]
    ok = (len(beats) >= 2 and all("no worker alive" in u[0] for u in beats)
          and "no worker is alive" in message and "nothing saved" in message
          and "\n" not in message)
    faults.record("batch: every worker dead (heartbeat, stall)", ok, message)
    assert ok, (listener.updates[:3], message)


FIRST: list[str] = []
_first_lock = threading.Lock()


def blocking_step(entry, analysis, previous=None):
    """Replaces the analysis step in-process: the first to start waits for RELEASE
    (Ctrl-C comes meanwhile), the others just mark."""
    from hydrosync_core.campaign.steps import DONE, _outcome

    with _first_lock:
        first = not FIRST
        if first:
            FIRST.append(entry.label)
    if first:
        STARTED.set()
        RELEASE.wait(120)
    MARKERS[entry.label].write_text("saved")
    out = _outcome(entry, analysis.id)
    out.update(status=DONE, message="")
    return out


class _ReleaseWhenWaitedFor(logging.Handler):
    def emit(self, record) -> None:
        if "waiting for" in record.getMessage():
            RELEASE.set()


def test_ctrl_c_cancels_pending_waits_for_running_and_reports_it(tmp_path, monkeypatch,
                                                                 faults):
    from dask.distributed import Client, LocalCluster

    from hydrosync_core.campaign import engine

    STARTED.clear()
    RELEASE.clear()
    FIRST.clear()
    MARKERS.update(a=tmp_path / "a.saved", b=tmp_path / "b.saved")
    monkeypatch.setattr(engine, "analysis_step", blocking_step)
    campaign = _campaign(tmp_path)
    handler = _ReleaseWhenWaitedFor()
    engine.log.addHandler(handler)
    cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                           dashboard_address=None, silence_logs=logging.CRITICAL)
    client = Client(cluster)
    listener = Recorder()

    def interrupt() -> None:
        if STARTED.wait(120):
            _thread.interrupt_main()  # Ctrl-C while step 'a' runs and 'b' waits

    helper = threading.Thread(target=interrupt, daemon=True)
    helper.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            engine.run_campaign(campaign, client=client, listener=listener, poll_s=0.01,
                                write_summary=False)
    finally:
        RELEASE.set()
        engine.log.removeHandler(handler)
        client.close()
        cluster.close()
    told = [u[2] for u in listener.updates if u[2] is not None]
    running, other = FIRST[0], {"a": "b", "b": "a"}[FIRST[0]]
    ok = (MARKERS[running].exists() and any(o["project"] == running and o["status"] == "done"
                                            for o in told)
          and not MARKERS[other].exists())
    faults.record("batch: Ctrl-C waits for the running step, cancels the rest", ok,
                  str(told))
    assert ok, (FIRST, told, MARKERS["a"].exists(), MARKERS["b"].exists())


def test_a_step_that_did_not_converge_is_done_undetermined():
    from hydrosync_core.campaign.steps import OK_STATES, UNDETERMINED, undetermined_reason

    assert undetermined_reason({"converged": True}) == ""
    assert undetermined_reason({"converged": False}) == "did not converge"
    assert undetermined_reason({"converged": True, "undetermined": '{"pitch": "flat"}'}) \
        == "undetermined: pitch"
    assert UNDETERMINED in OK_STATES and UNDETERMINED != "done"


# -------------------------------------------------------------------------- info
def _corrupt_first_chunk(path: Path, dataset: str) -> None:
    with h5py.File(path, "r") as f:
        info = f[dataset].id.get_chunk_info(0)
    with open(path, "r+b") as fh:
        fh.seek(info.byte_offset + info.size // 2)
        byte = fh.read(1)
        fh.seek(-1, 1)
        fh.write(bytes([byte[0] ^ 0xFF]))


def test_info_reads_inputs_back_and_says_input_damaged(tmp_path, faults):
    from hydrosync_core import provenance

    path = tmp_path / "P.h5"
    project = Project.new("P")
    project.put_table("raw/gnss", {"time": np.arange(20000.0), "height": np.zeros(20000)})
    project.put("results/latency/delay_s", np.array([0.1]))
    provenance.record(project, "results/latency", ["raw/gnss"])
    project.save(path)
    project.close()
    done = run_cli("info", path)
    assert done.returncode == 0 and "up to date" in done.stdout, done.stdout + done.stderr
    _corrupt_first_chunk(path, "raw/gnss/time")
    done = run_cli("info", path)
    lines = stderr_lines(done.stderr)
    ok = (done.returncode == 2 and len(lines) == 1 and "INPUT DAMAGED" in lines[0]
          and "latency: INPUT DAMAGED" in done.stdout and "up to date" not in done.stdout)
    faults.record("info: corrupt input chunk named", ok, done.stdout[-300:] + done.stderr)
    assert ok, (done.stdout, done.stderr)
