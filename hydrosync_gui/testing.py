"""pytest fixtures and the plugin contract, for HydroSync's own tests and for third parties.

Load it from a ``conftest.py`` (HydroSync's root ``conftest.py`` does)::

    pytest_plugins = ["hydrosync_gui.testing"]

and check a plugin against the contract every built-in analysis keeps::

    from hydrosync_gui.testing import PluginContract

    class TestHeaveStatsContract(PluginContract):
        SPEC = "hydrosync_heave_stats:SPEC"   # the entry point's value

The contract (Orange widget-test style): the spec loads and is consistent, its dotted paths
import, the command has one flag per parameter, the panel opens on an empty project, on a
demo project and on stored results, a run stores its provenance (the "out of date" banner
appears when an input changes), and a run can be cancelled before it starts and after its
first progress report without leaving partial results.

Fixtures:

``hydrosync_demo`` (session)
    The folder of one ``hydrosync demo --out …`` run (``demo.h5``, ``demo-report.pdf``, and
    ``stdout.txt``), built once per test session — once across pytest-xdist workers too —
    and never modified by tests: copy ``demo.h5`` before writing to it.
``demo_project_of``
    ``demo_project_of(spec)`` opens a project holding *spec*'s simulated data and no
    results; built once per spec and session, opened afresh (read-only) each call.

Importing this module loads neither Qt nor the methods: they are imported when used.
"""

from __future__ import annotations

import contextlib
import fcntl
import inspect
import json
import os
import shutil
import subprocess
import sys
import threading
from pathlib import Path

import pytest

DEMO_TIMEOUT_S = 900  # a guard against a hang, not a speed requirement


# --------------------------------------------------------------------------- demo
@contextlib.contextmanager
def _exclusive(lock_path: Path):
    """An inter-process lock, so that parallel workers build a shared fixture once."""
    with open(lock_path, "a") as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


def _shared_dir(tmp_path_factory) -> Path:
    """A folder shared by every xdist worker of this session (the plain base otherwise)."""
    base = tmp_path_factory.getbasetemp()
    return base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base


def run_demo_command(out: Path) -> subprocess.CompletedProcess:
    """``hydrosync demo --out OUT`` as ``make demo`` runs it (the installed console script
    when there is one)."""
    script = Path(sys.executable).with_name("hydrosync")
    command = [str(script)] if script.exists() else [sys.executable, "-m", "hydrosync_core.cli"]
    env = dict(os.environ, HYDROSYNC_DEBUG="1")
    return subprocess.run([*command, "demo", "--out", str(out)], capture_output=True,
                          text=True, timeout=DEMO_TIMEOUT_S, env=env)


@pytest.fixture(scope="session")
def hydrosync_demo(tmp_path_factory) -> Path:
    """Folder of one ``hydrosync demo`` run: ``demo.h5``, ``demo-report.pdf``, ``stdout.txt``
    and ``returncode.txt``. Shared: never write into it.

    ``HYDROSYNC_DEMO_DIR`` names the folder of an earlier run of the same code to reuse
    (while working on the GUI: the demo takes minutes); it is ignored unless it holds
    ``returncode.txt``.
    """
    reuse = os.environ.get("HYDROSYNC_DEMO_DIR")
    if reuse and (Path(reuse) / "returncode.txt").exists():
        return Path(reuse)
    shared = _shared_dir(tmp_path_factory)
    out = shared / "hydrosync-demo"
    with _exclusive(shared / "hydrosync-demo.lock"):
        if not (out / "returncode.txt").exists():
            shutil.rmtree(out, ignore_errors=True)
            proc = run_demo_command(out)
            out.mkdir(parents=True, exist_ok=True)
            (out / "stdout.txt").write_text(proc.stdout)
            (out / "stderr.txt").write_text(proc.stderr)
            (out / "returncode.txt").write_text(str(proc.returncode))
    return out


@pytest.fixture(scope="session")
def demo_project_of(tmp_path_factory):
    """``demo_project_of(spec)`` → a :class:`Project` with *spec*'s simulated data only.

    Each spec's simulator runs once per session (seed 0); every call opens the saved file
    read-only (no lock), so tests may change the project in memory but never save it back.
    """
    from hydrosync_core.plugins import load_object
    from hydrosync_core.project import Project

    shared = _shared_dir(tmp_path_factory)

    def get(spec):
        if not spec.demo:
            pytest.skip(f"plugin '{spec.id}' declares no demo (spec.demo is empty)")
        path = shared / f"demo-{spec.id}.h5"
        with _exclusive(shared / f"demo-{spec.id}.lock"):
            if not path.exists():
                project = Project.new(f"{spec.id} demo")
                load_object(spec.demo)(project, seed=0)
                project.save(path)
                project.close()
        return Project.open(path, readonly=True)

    return get


# ----------------------------------------------------------------------- contract
def _touch_content(project, path: str) -> None:
    """Change the content of the project node *path* (a table, dataset or JSON group)."""
    import numpy as np

    from hydrosync_core.project import schema

    if schema.JSON_ATTR in project.attrs(path):
        doc = project.get_json(path)
        project.put_json(path, {**doc, "edited": True} if isinstance(doc, dict) else [doc])
        return
    node = path
    while project.children(node):
        node = f"{node}/{sorted(project.children(node))[0]}"
    value = np.array(project.get(node), copy=True)
    if value.dtype.kind in "fiu" and value.size:
        value.flat[0] += 1
    else:
        value = value[:-1]
    project.put(node, value, attrs=dict(project.attrs(node)))


def open_panel(qtbot, spec, project):
    """The spec's panel, shown, bound to *project*, its first task finished."""
    panel = spec.load_panel()()
    qtbot.addWidget(panel)
    if panel.spec is None:
        panel.spec = spec
    panel.set_project(project)
    panel.show()
    qtbot.wait(20)
    assert panel.wait_idle(30.0)
    return panel


class PluginContract:
    """The contract of a HydroSync analysis plugin, as pytest tests.

    Subclass it with ``SPEC = "package:SPEC"`` (or override the ``contract_spec`` fixture
    to return a loaded :class:`~hydrosync_core.plugins.spec.PluginSpec`).
    """

    SPEC: str = ""

    @pytest.fixture
    def contract_spec(self):
        from hydrosync_core.plugins.registry import check_spec
        from hydrosync_core.plugins.spec import load_object

        return check_spec(load_object(self.SPEC), self.SPEC)

    def test_spec_loads_and_is_consistent(self, contract_spec):
        spec = contract_spec
        assert spec.id.isidentifier(), f"id '{spec.id}' must be a Python identifier"
        assert spec.name.strip() and spec.run and spec.panel
        assert all(isinstance(p, str) and p and not p.startswith("/") for p in spec.requires)
        json.dumps(spec.default_params)  # parameters are stored with the results as JSON
        schema = spec.load_params()
        assert schema.from_dict(spec.default_params) == schema()  # defaults round-trip
        for info in schema.schema():
            assert info.meta.label and (info.meta.help or info.kind == "bool"), info.name

    def test_dotted_paths_import(self, contract_spec):
        from hydrosync_core.plugins import load_object
        from hydrosync_gui.plugin_panel import PluginPanel

        spec = contract_spec
        run = spec.load_run()
        params = list(inspect.signature(run).parameters)
        assert params[:2] == ["project", "params"] and {"progress", "cancel"} <= set(params)
        panel = spec.load_panel()
        assert isinstance(panel, type) and issubclass(panel, PluginPanel)
        for extra in (spec.demo, spec.report_section, spec.cli):
            if extra:
                assert callable(load_object(extra))
        for kind in spec.data_kinds:
            assert kind.store in ("table", "points", "json", "custom")
            assert callable(load_object(kind.reader)), kind.name

    def test_command_registers_with_schema_flags(self, contract_spec):
        """The analysis command adds one flag per parameter, none of them with a default."""
        import argparse

        from hydrosync_core.plugins import load_object

        spec = contract_spec
        if not spec.cli:
            pytest.skip("no command")
        sub = argparse.ArgumentParser(prog="hydrosync").add_subparsers()
        load_object(spec.cli)(sub)
        (parser,) = set(sub.choices.values())
        dests = {a.dest for a in parser._actions}
        for info in spec.load_params().schema():
            assert f"param_{info.name}" in dests, f"no flag for parameter {info.name}"

    def test_panel_opens_on_an_empty_project(self, qtbot, contract_spec):
        from hydrosync_core.project import Project

        spec = contract_spec
        project = Project.new("empty")
        assert spec.missing_inputs(project) == list(spec.requires)
        panel = open_panel(qtbot, spec, project)
        assert panel.project is project
        panel.refresh()  # redrawing twice must work too

    def test_panel_opens_on_a_demo_project(self, qtbot, contract_spec, demo_project_of):
        spec = contract_spec
        with demo_project_of(spec) as project:
            assert spec.missing_inputs(project) == [], \
                "the demo must provide what the plugin needs"
            panel = open_panel(qtbot, spec, project)
            assert panel.project is project

    def test_panel_shows_stored_results(self, qtbot, contract_spec, demo_project_of):
        """After a headless run the panel redraws from ``/results/<id>``; the run's
        provenance record is complete, and an input changed afterwards shows the panel's
        "out of date" banner."""
        from hydrosync_core.provenance import read_record, stale_reasons

        spec = contract_spec
        result = f"results/{spec.id}"
        with demo_project_of(spec) as project:
            spec.load_run()(project, spec.make_params())
            assert project.exists(result), "run stored nothing under /results/<id>"
            stored = project.get_json(result)
            assert stored == spec.make_params().to_dict()
            attrs = project.attrs(result)
            assert {"software_version", "run_utc", "params_schema_version"} <= set(attrs)
            assert attrs["params_schema_version"] == spec.load_params().SCHEMA_VERSION
            # ... all written by the one provenance.record(), with the inputs read
            rec = read_record(project, result)
            assert rec is not None, "run() must call hydrosync_core.provenance.record()"
            assert (rec["software_version"], rec["run_utc"], rec["params_schema_version"]) \
                == (attrs["software_version"], attrs["run_utc"],
                    attrs["params_schema_version"])
            assert rec["params"] == stored
            assert set(spec.requires) <= set(rec["inputs"]), \
                "record() must name every input the run read"
            panel = open_panel(qtbot, spec, project)
            assert not panel.stale_banner.isVisibleTo(panel)
            _touch_content(project, spec.requires[0])
            assert stale_reasons(project, result)
            panel.update_stale_banner()
            assert panel.stale_banner.isVisibleTo(panel)
            assert "Out of date" in panel.stale_banner.text()

    @pytest.mark.parametrize("when", ["before start", "after first progress"])
    def test_run_can_be_cancelled(self, contract_spec, demo_project_of, when):
        from hydrosync_core.errors import Cancelled

        spec = contract_spec
        with demo_project_of(spec) as project:
            cancel = threading.Event()
            calls = []

            def progress(fraction: float, message: str = "") -> None:
                calls.append(fraction)
                cancel.set()

            if when == "before start":
                cancel.set()
            with pytest.raises(Cancelled):
                spec.load_run()(project, spec.make_params(), progress, cancel)
            if when == "after first progress":
                assert calls, "run never reported progress"
            assert not project.exists(f"results/{spec.id}"), \
                "a cancelled run left partial results"
