"""``hydrosync demo``: end to end and failure isolation between plugins."""

from __future__ import annotations

import json
import re
from pathlib import Path

from pypdf import PdfReader

from hydrosync_core.cli import main
from hydrosync_core.demo import (
    DEMO_PROJECT,
    DEMO_REPORT,
    DEMO_SEED,
    Stage,
    StageListener,
    build_demo,
    key_results,
)
from hydrosync_core.methods.latency import report_section as lat
from hydrosync_core.methods.pool_calibration import report_section as pool
from hydrosync_core.plugins import Discovered, PluginSpec, get_spec, load_object, plugin_specs
from hydrosync_core.project import Project

# ``esc(text)`` called as ``esc(project, seed=…, progress=…)`` raises a TypeError: a
# stand-in for a plugin whose simulator or run function is broken.
BROKEN = "hydrosync_core.report.context:esc"


def pdf_text(path: Path) -> str:
    return re.sub(r"\s+", " ", " ".join(p.extract_text() for p in PdfReader(str(path)).pages))


def test_demo_end_to_end(hydrosync_demo):
    """The real command as ``make demo`` runs it: every plugin simulated, run, reported.

    The run is the session's shared one (``hydrosync_demo``); how long it takes is measured
    in ``benchmarks/bench_demo.py``, not asserted here.
    """
    out = hydrosync_demo
    stdout = (out / "stdout.txt").read_text()
    stderr = (out / "stderr.txt").read_text()
    assert (out / "returncode.txt").read_text() == "0", stdout + stderr
    project_path, report_path = out / DEMO_PROJECT, out / DEMO_REPORT
    assert project_path.is_file() and report_path.is_file()
    assert not list(out.glob("*.tmp"))
    specs = plugin_specs()
    # One line per stage (a non-tty log shows progress), then where the files are.
    for spec in specs:
        if spec.demo:
            assert f"] {spec.name}: simulate data ..." in stdout
        assert f"] {spec.name}: run ..." in stdout
    assert "FAILED" not in stdout
    assert f"project: {project_path}" in stdout and f"report:  {report_path}" in stdout
    # The key results printed are those stored in the project, formatted as in the report.
    rows = key_results(project_path)
    names = {get_spec(i).name for i in ("latency", "pool_calibration")}
    assert names <= {name for name, _, _ in rows}
    text = pdf_text(report_path)
    for _name, quantity, value in rows:
        assert re.search(rf"{re.escape(quantity)}\s+{re.escape(value)}", stdout)
        assert value in text
    assert "not run" not in text and "could not be produced" not in text
    assert lat.HEADING in text and pool.HEADING in text
    with Project.open(project_path) as project:
        for spec in specs:
            assert project.exists(f"results/{spec.id}"), spec.id
        # Latency: the simulated survey day has a 0.29 s delay (as the seed's table 1).
        attrs = project.attrs("results/latency")
        assert abs(attrs["latency_s"] - 0.29) < 0.03
        assert attrs["ci95_low"] < 0.29 < attrs["ci95_high"]
        assert lat.final_value_text(attrs) in text
        table = project.get_table("results/latency/lines")
        for i in range(len(table["name"])):
            assert " ".join(lat.line_row(table, i)) in text
        # Pool: final parameters near the simulator's truth, printed as stored.
        attrs = project.attrs("results/pool_calibration")
        truth = load_object(get_spec("pool_calibration").demo)(
            Project.new("truth"), seed=DEMO_SEED, progress=None)
        # The demo target is the patent's: below-water twins referenced to the laser planes
        # of their above-water blocks, moved by the design translation.
        faces = project.get_table("results/pool_calibration/faces")
        refs = {str(n): str(r) for n, r in zip(faces["face"], faces["reference"], strict=True)}
        assert refs["wall"] == "own" and refs["N1_dn_oblique"] == "N1_up_oblique"
        assert "Face pairing and reference planes" in text and "N1_up_oblique" in text
        assert json.loads(attrs["undetermined"]) == {}
        for key in ("roll", "pitch", "yaw"):
            # The published pool calibration reaches < 0.015°; so does the demo pass, and
            # the error stays within 4 reported σ.
            error = abs(attrs[f"{key}_deg"] - truth["boresight_deg"][key])
            assert error < min(0.015, 4 * attrs[f"sigma_{key}_deg"] + 1e-3), key
        for key in "xyz":
            error = abs(attrs[f"lever_{key}_m"] - truth["lever_arm_m"][key])
            assert error < min(0.002, 4 * attrs[f"sigma_lever_{key}_m"] + 2e-4), key
        for _label, value in pool.parameter_rows(attrs):
            assert value in text
        assert "Uncertainty model" in text and "variance factors" in text
        faces = project.get_table("results/pool_calibration/faces")
        for i, name in enumerate(faces["face"]):
            assert re.search(rf"{name} {faces['role'][i]} {faces['water'][i]} "
                             rf"{faces['points_laser'][i]} {faces['points_mbes'][i]} ", text)


class _Recorder(StageListener):
    def __init__(self) -> None:
        self.started: list[str] = []
        self.finished: list[Stage] = []

    def start(self, index, total, label):
        self.started.append(label)
        return None

    def finish(self, stage):
        self.finished.append(stage)


def test_a_failing_plugin_does_not_stop_the_others(tmp_path):
    real = get_spec("latency")
    broken_demo = PluginSpec(id="broken_sim", name="Broken simulator", run=real.run,
                             panel=real.panel, requires=("raw/never",), demo=BROKEN, order=1)
    # Its simulator works (the latency one) but its run function is broken.
    broken_run = PluginSpec(id="broken_run", name="Broken run", run=BROKEN, panel=real.panel,
                            requires=real.requires, demo=real.demo, order=2)
    recorder = _Recorder()
    outcome = build_demo(tmp_path, seed=3, listener=recorder,
                         specs=[broken_demo, broken_run, real])
    failed = {s.label for s in outcome.failed}
    assert failed == {"Broken simulator: simulate data", "Broken run: run"}
    assert all("TypeError" in s.message for s in outcome.failed)
    assert [s.label for s in recorder.finished] == recorder.started
    assert "Latency: run" in recorder.started
    assert set(outcome.results) == {"latency"}
    assert outcome.report_path == tmp_path / DEMO_REPORT and outcome.report_path.is_file()
    with Project.open(tmp_path / DEMO_PROJECT) as project:
        assert project.exists("results/latency")
        assert not project.exists("results/broken_run")
        attrs = project.attrs("results/latency")
    text = pdf_text(outcome.report_path)
    assert lat.final_value_text(attrs) in text


def test_cli_exit_1_when_a_plugin_fails(tmp_path, monkeypatch, capsys):
    real = get_spec("latency")
    broken = PluginSpec(id="broken_run", name="Broken run", run=BROKEN, panel=real.panel,
                        requires=real.requires, demo=real.demo)
    found = [Discovered("latency", "x", real, None), Discovered("broken_run", "y", broken, None),
             Discovered("ghost", "plugins.ghost:SPEC", None, "ModuleNotFoundError: ghost")]
    monkeypatch.setattr("hydrosync_core.demo.discover", lambda: found)
    code = main(["demo", "--out", str(tmp_path / "out"), "--seed", "5"])
    captured = capsys.readouterr()
    assert code == 1
    assert "load plugin ghost: FAILED: ModuleNotFoundError: ghost" in captured.out
    assert "Broken run: run failed: TypeError" in captured.err
    assert "Latency between GNSS" in pdf_text(tmp_path / "out" / DEMO_REPORT)
    assert "Latency" in captured.out and "key results:" in captured.out


def test_demo_out_must_be_a_folder(tmp_path, capsys):
    target = tmp_path / "file.txt"
    target.write_text("x")
    assert main(["demo", "--out", str(target)]) == 2
    assert "--out must be a folder" in capsys.readouterr().err
