"""The contract every plugin of the real registry must keep (Orange widget-test style).

For each entry point of ``hydrosync.plugins`` — and for the example third-party analysis
under ``examples/heave_stats`` (loaded from its folder, as an installed package would be
through its entry point) —: the spec loads (a broken *built-in* plugin
fails here; a broken third-party one is skipped with its error), its dotted paths import,
its panel opens on an empty project, on a demo project and on one holding the results of
a run, and its run can be cancelled, both
before it starts and after its first progress report, leaving no partial results.
"""

from __future__ import annotations

import inspect
import json
import threading

import pytest
from example_plugin import example_discovered

from hydrosync_core.errors import Cancelled
from hydrosync_core.plugins import discover, load_object
from hydrosync_core.plugins.registry import Discovered
from hydrosync_core.project import Project
from hydrosync_core.provenance import read_record, stale_reasons

BUILT_IN_PREFIXES = ("plugins.", "hydrosync_core.", "hydrosync_gui.", "hydrosync_heave_stats")
FOUND = discover() + [example_discovered()]


def _id(d: Discovered) -> str:
    return d.entry_point


def _spec(d: Discovered):
    """The loaded spec; fail for a broken built-in plugin, skip a broken third-party one."""
    if d.spec is None:
        if d.value.startswith(BUILT_IN_PREFIXES):
            pytest.fail(f"built-in plugin '{d.entry_point}' ({d.value}) does not load: {d.error}")
        pytest.skip(f"third-party plugin '{d.entry_point}' does not load: {d.error}")
    return d.spec


@pytest.fixture(scope="module")
def demo_files(tmp_path_factory):
    """Demo project file per plugin id, written once per module (demos may take a while)."""
    cache: dict[str, object] = {}

    def get(spec):
        if not spec.demo:
            pytest.skip(f"plugin '{spec.id}' declares no demo (spec.demo is empty)")
        if spec.id not in cache:
            project = Project.new(f"{spec.id} demo")
            load_object(spec.demo)(project, seed=0)
            path = tmp_path_factory.mktemp("demo") / f"{spec.id}.h5"
            project.save(path)
            project.close()
            cache[spec.id] = path
        return Project.open(cache[spec.id])

    return get


def test_registry_lists_the_built_in_plugins():
    names = {d.entry_point for d in FOUND}
    assert {"latency", "pool_calibration"} <= names


@pytest.mark.parametrize("found", FOUND, ids=_id)
def test_spec_loads_and_is_consistent(found):
    spec = _spec(found)
    assert spec.id.isidentifier(), f"id '{spec.id}' must be a Python identifier"
    assert spec.name.strip() and spec.run and spec.panel
    assert all(isinstance(p, str) and p and not p.startswith("/") for p in spec.requires)
    json.dumps(spec.default_params)  # parameters are stored with the results as JSON
    schema = spec.load_params()
    assert schema.from_dict(spec.default_params) == schema()  # defaults round-trip
    for info in schema.schema():
        assert info.meta.label and (info.meta.help or info.kind == "bool"), info.name
    ids = [d.spec.id for d in FOUND if d.spec is not None]
    assert ids.count(spec.id) == 1, f"plugin id '{spec.id}' is not unique"


@pytest.mark.parametrize("found", FOUND, ids=_id)
def test_dotted_paths_import(found):
    from hydrosync_gui.plugin_panel import PluginPanel

    spec = _spec(found)
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


@pytest.mark.parametrize("found", FOUND, ids=_id)
def test_command_registers_with_schema_flags(found):
    """The analysis command adds one flag per parameter, none of them with a default."""
    import argparse

    spec = _spec(found)
    if not spec.cli:
        pytest.skip("no command")
    sub = argparse.ArgumentParser(prog="hydrosync").add_subparsers()
    load_object(spec.cli)(sub)
    (parser,) = set(sub.choices.values())
    dests = {a.dest for a in parser._actions}
    for info in spec.load_params().schema():
        assert f"param_{info.name}" in dests, f"no flag for parameter {info.name}"


def _open_panel(qtbot, spec, project):
    panel = spec.load_panel()()
    qtbot.addWidget(panel)
    if panel.spec is None:
        panel.spec = spec
    panel.set_project(project)
    panel.show()
    qtbot.wait(20)
    assert panel.wait_idle(30.0)
    return panel


@pytest.mark.parametrize("found", FOUND, ids=_id)
def test_panel_opens_on_an_empty_project(qtbot, found):
    spec = _spec(found)
    project = Project.new("empty")
    assert spec.missing_inputs(project) == list(spec.requires)
    panel = _open_panel(qtbot, spec, project)
    assert panel.project is project
    panel.refresh()  # redrawing twice must work too


@pytest.mark.parametrize("found", FOUND, ids=_id)
def test_panel_opens_on_a_demo_project(qtbot, found, demo_files):
    spec = _spec(found)
    with demo_files(spec) as project:
        assert spec.missing_inputs(project) == [], "the demo must provide what the plugin needs"
        panel = _open_panel(qtbot, spec, project)
        assert panel.project is project


@pytest.mark.parametrize("found", FOUND, ids=_id)
def test_panel_shows_stored_results(qtbot, found, demo_files):
    """After a headless run the panel redraws from ``/results/<id>`` without error."""
    spec = _spec(found)
    with demo_files(spec) as project:
        spec.load_run()(project, spec.make_params())
        assert project.exists(f"results/{spec.id}"), "run stored nothing under /results/<id>"
        # the results contract: the params used (JSON, schema version), software version
        # and run time
        stored = project.get_json(f"results/{spec.id}")
        assert stored == spec.make_params().to_dict()
        attrs = project.attrs(f"results/{spec.id}")
        assert {"software_version", "run_utc", "params_schema_version"} <= set(attrs)
        assert attrs["params_schema_version"] == spec.load_params().SCHEMA_VERSION
        # ... all written by the one provenance.record(), which also lists the inputs read
        rec = read_record(project, f"results/{spec.id}")
        assert rec is not None, "run() must call hydrosync_core.provenance.record()"
        assert (rec["software_version"], rec["run_utc"], rec["params_schema_version"]) == (
            attrs["software_version"], attrs["run_utc"], attrs["params_schema_version"])
        assert rec["params"] == stored
        assert set(spec.requires) <= set(rec["inputs"]), "record() must name every input read"
        panel = _open_panel(qtbot, spec, project)
        assert not panel.stale_banner.isVisibleTo(panel)
        # Change one input: the panel's "out of date" banner appears.
        changed = spec.requires[0]
        _touch_content(project, changed)
        assert stale_reasons(project, f"results/{spec.id}")
        panel.update_stale_banner()
        assert panel.stale_banner.isVisibleTo(panel)
        assert "Out of date" in panel.stale_banner.text()


def _touch_content(project, path: str) -> None:
    """Change the content of the project node *path* (a table, dataset or JSON group)."""
    import numpy as np

    if schema_json_attr() in project.attrs(path):
        doc = project.get_json(path)
        project.put_json(path, {**doc, "edited": True} if isinstance(doc, dict) else doc)
        return
    node = path
    while project.children(node):
        node = f"{node}/{sorted(project.children(node))[0]}"
    value = np.array(project.get(node), copy=True)
    if value.dtype.kind in "fi" and value.size:
        value.flat[0] += 1
    else:
        value = value[:-1]
    project.put(node, value, attrs=dict(project.attrs(node)))


def schema_json_attr() -> str:
    from hydrosync_core.project import schema

    return schema.JSON_ATTR


@pytest.mark.parametrize("when", ["before start", "after first progress"])
@pytest.mark.parametrize("found", FOUND, ids=_id)
def test_run_can_be_cancelled(found, demo_files, when):
    spec = _spec(found)
    with demo_files(spec) as project:
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
        assert not project.exists(f"results/{spec.id}"), "a cancelled run left partial results"
