"""Campaign processing (``hydrosync batch``, issue #16) on a real ``dask.distributed`` cluster.

A small campaign — four simulated survey days with latency and GNSS-attitude data, plus a
damaged project — runs on a ``LocalCluster(n_workers=2, processes=True)``. A worker is
killed (SIGKILL) in the middle of saving one project; the damaged project fails without
stopping the others. The re-run, after the damaged project is replaced, runs only that
project's analyses: everything else is up to date and not computed again.
"""

from __future__ import annotations

import logging
import os
import shutil
import signal
import sys
from pathlib import Path

import pytest

from hydrosync_core.campaign import load_campaign
from hydrosync_core.campaign.simulate import make_campaign
from hydrosync_core.cli import main
from hydrosync_core.errors import InputError
from hydrosync_core.project import Project
from hydrosync_core.provenance import read_record, stale_reasons

ANALYSES = ("latency", "gnss_attitude")
KILLED = "2024-06-04.h5"
DAMAGED = "2024-06-07.h5"


def kill_during_save(project_name: str, marker: str) -> None:
    """In a worker: the first save of *project_name* SIGKILLs the worker mid-write."""
    from hydrosync_core.project import store

    original = store.write_tree

    def write_tree(group, node):
        if Path(group.file.filename).name.startswith(f".{project_name}.") and \
                not os.path.exists(marker):
            original(group, node)  # the temporary file is written, not yet published
            Path(marker).write_text(str(os.getpid()))
            os.kill(os.getpid(), signal.SIGKILL)
        return original(group, node)

    store.write_tree = write_tree


@pytest.fixture(scope="module")
def client():
    import cloudpickle
    from dask.distributed import Client, LocalCluster

    cloudpickle.register_pickle_by_value(sys.modules[__name__])
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=":0", silence_logs=logging.CRITICAL)
    client = Client(cluster)
    yield client
    client.close()
    cluster.close()


def by_step(result) -> dict:
    return {(o["project"], o["step"]): o for o in result.outcomes}


def test_campaign_survives_a_killed_worker_and_a_damaged_project(tmp_path, client):
    from hydrosync_core.campaign.engine import run_campaign

    toml = make_campaign(tmp_path, days=4, analyses=ANALYSES)
    days = tmp_path / "days"
    (days / DAMAGED).write_bytes(b"this is no HDF5 file" * 20)
    campaign = load_campaign(toml)
    assert len(campaign.projects) == 5
    marker = tmp_path / "killed-worker.pid"
    client.run(kill_during_save, KILLED, str(marker))

    first = run_campaign(campaign, client=client)

    assert marker.exists(), "the worker was not killed"
    steps = by_step(first)
    assert len(steps) == 10
    damaged = DAMAGED.removesuffix(".h5")
    for (project, _step), outcome in steps.items():
        if project == damaged:
            assert outcome["status"] == "failed"
            assert DAMAGED in outcome["message"] and "HDF5" in outcome["message"]
        else:
            assert outcome["status"] == "done", outcome
    # The first save of that day (its latency step) killed its worker: Dask ran the step
    # again in another process, which saved it; no temporary file is left behind.
    killed_pid = marker.read_text()
    assert steps[("2024-06-04", "latency")]["worker"].rsplit(":", 1)[1] != killed_pid
    assert not [p.name for p in days.iterdir() if p.name.endswith(".tmp")]
    runs = {}
    for path in sorted(days.glob("2024-06-0[3-6].h5")):
        with Project.open(path, readonly=True) as project:
            for analysis in ANALYSES:
                assert stale_reasons(project, f"results/{analysis}") == []
                runs[(path.stem, analysis)] = read_record(project, f"results/{analysis}")
    assert len(runs) == 8
    summary = (tmp_path / "output" / "summary.csv").read_text(encoding="utf-8")
    assert summary.count("\n") == 11 and "latency_s" in summary.splitlines()[0]
    page = (tmp_path / "output" / "summary.html").read_text(encoding="utf-8")
    assert "data:image/png;base64," in page and "Latency" in page and damaged in page

    # Repair the damaged day and run again: only its two analyses run.
    shutil.copy(days / "2024-06-03.h5", days / DAMAGED)
    with Project.open(days / DAMAGED) as project:
        for analysis in ANALYSES:
            project.delete(f"results/{analysis}")
        project.save()
    second = run_campaign(load_campaign(toml), client=client)
    steps = by_step(second)
    ran = sorted(key for key, o in steps.items() if o["status"] == "done")
    assert ran == [(damaged, "gnss_attitude"), (damaged, "latency")]
    assert all(o["status"] == "up to date" for key, o in steps.items() if key[0] != damaged)
    for path in sorted(days.glob("2024-06-0[3-6].h5")):
        with Project.open(path, readonly=True) as project:
            for analysis in ANALYSES:
                # Not computed again: the provenance record (with its run time) is unchanged.
                assert read_record(project, f"results/{analysis}") == runs[(path.stem,
                                                                             analysis)]
    assert not second.failed


def test_changed_parameters_run_again(tmp_path, client):
    from hydrosync_core.campaign.engine import run_campaign

    toml = make_campaign(tmp_path, days=1, analyses=("gnss_attitude",))
    campaign = load_campaign(toml)
    assert [o["status"] for o in run_campaign(campaign, client=client).outcomes] == ["done"]
    text = toml.read_text().replace("[analyses.gnss_attitude]",
                                    "[analyses.gnss_attitude]\nmethod = \"wahba\"")
    toml.write_text(text)
    again = run_campaign(load_campaign(toml), client=client, write_summary=False)
    assert [o["status"] for o in again.outcomes] == ["done"]


def test_dry_run_lists_the_plan(tmp_path, capsys):
    toml = make_campaign(tmp_path, days=2, analyses=("gnss_attitude",))
    assert main(["batch", str(toml), "--dry-run"]) == 0
    out = capsys.readouterr().out
    assert "2 project(s) x 1 analysis(es)" in out
    assert "2024-06-03 gnss_attitude: will run" in out
    assert "dry run: 2 of 2 analysis task(s) would run; nothing was done" in out
    assert not (tmp_path / "output").exists()


@pytest.mark.parametrize("text, expected", [
    ("[analyses.latency\n", "not valid TOML"),
    ("[analyses.nope]\n[projects]\nglob='*.h5'\n", "unknown analysis 'nope'"),
    ("[analyses.latency]\nstep_s = -1\n[projects]\nglob='*.h5'\n",
     "field 'analyses.latency.step_s'"),
    ("[analyses.latency]\nstepp = 1\n[projects]\nglob='*.h5'\n", "unknown parameter 'stepp'"),
    ("[analyses.latency]\n[projects]\nglob='nothing/*.h5'\n", "no projects"),
    ("[analyses.latency]\n[projects]\nfiles=['a.h5']\n[outputs]\nformat='x'\n",
     "unknown key 'format' in [outputs]"),
    ("[analyses.latency]\n[import]\nsets='raw/*'\n[import.files]\nnope='x'\n",
     "unknown data kind 'nope'"),
])
def test_bad_campaign_file_is_exit_2_one_line(tmp_path, capsys, text, expected):
    toml = tmp_path / "bad.toml"
    toml.write_text(text, encoding="utf-8")
    assert main(["batch", str(toml)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert err.startswith("hydrosync batch: ") and str(toml) in err and expected in err, err


def test_import_recipe_plans_new_projects(tmp_path):
    raw = tmp_path / "raw" / "2024-07-01"
    raw.mkdir(parents=True)
    for name in ("gnss.csv", "attitude.csv", "lines.csv"):
        (raw / name).write_text("x\n")
    (tmp_path / "raw" / "2024-07-02").mkdir()
    toml = tmp_path / "c.toml"
    toml.write_text(
        "[analyses.latency]\n[import]\nsets = 'raw/*'\nproject = 'projects/{set}.h5'\n"
        "[import.files]\ngnss='gnss.csv'\nattitude='attitude.csv'\nlines='lines.csv'\n"
        "[import.options]\nheave_positive='down'\n")
    campaign = load_campaign(toml)
    first, second = campaign.projects
    assert first.label == "2024-07-01" and first.date == "2024-07-01"
    assert first.path == str(tmp_path / "projects" / "2024-07-01.h5")
    assert [k for k, _ in first.source.files] == ["gnss", "attitude", "lines"]
    assert first.source.options == {"heave_positive": "down"} and not first.source.problem
    assert "no gnss.csv for gnss" in second.source.problem
    with pytest.raises(InputError, match="takes the option 'heave_sign'"):
        toml.write_text(toml.read_text().replace("heave_positive", "heave_sign"))
        load_campaign(toml)


def _write_csv(path: Path, table: dict) -> None:
    names = list(table)
    rows = zip(*(table[n] for n in names), strict=True)
    path.write_text(",".join(names) + "\n" + "".join(",".join(str(v) for v in row) + "\n"
                                                   for row in rows), encoding="utf-8")


def test_cli_imports_raw_sets_on_an_existing_scheduler(tmp_path, client, capsys, monkeypatch):
    """Raw files → new projects by the import recipe, run through ``DASK_SCHEDULER_ADDRESS``."""
    from hydrosync_core.methods.latency.demo import fill_demo

    day = Project.new("sim")
    truth = fill_demo(day, seed=3)
    folder = tmp_path / "raw" / "2024-08-01"
    folder.mkdir(parents=True)
    for name in ("gnss", "attitude", "lines"):
        _write_csv(folder / f"{name}.csv", day.get_table(f"raw/{name}"))
    x, y, z = truth["lever_arm_m"]
    (tmp_path / "vessel.json").write_text(
        '{"name": "launch", "sensors": {"motion": {"offset_m": [0, 0, 0]}, '
        f'"gnss": {{"offset_m": [{x}, {y}, {z}]}}}}}}')
    toml = tmp_path / "c.toml"
    toml.write_text(
        "[campaign]\nname = 'imported'\n[analyses.latency]\nstep_s = 0.01\n"
        "[import]\nsets = 'raw/*'\nproject = 'projects/{set}.h5'\nvessel = 'vessel.json'\n"
        "[import.files]\ngnss='gnss.csv'\nattitude='attitude.csv'\nlines='lines.csv'\n"
        "[import.options]\nheave_positive='up'\n[outputs]\nreport = false\n")
    monkeypatch.setenv("DASK_SCHEDULER_ADDRESS", client.scheduler.address)
    import dask

    dask.config.refresh()
    try:
        assert main(["batch", str(toml)]) == 0
    finally:
        monkeypatch.delenv("DASK_SCHEDULER_ADDRESS")
        dask.config.refresh()
    captured = capsys.readouterr()
    assert f"on Dask scheduler {client.scheduler.address}" in captured.err
    assert "imported: 2 done in" in captured.out
    with Project.open(tmp_path / "projects" / "2024-08-01.h5", readonly=True) as project:
        latency = project.attrs("results/latency")["latency_s"]
        assert abs(latency - truth["latency_s"]) < 0.03
    assert (tmp_path / "c-output" / "summary.csv").exists()
