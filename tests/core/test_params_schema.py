"""One parameter schema per analysis: defaults declared once, everything derived from it.

Changing a default in the schema must change the panel form, the analysis command's
default, ``hydrosync run … --param`` and the stored parameters — checked by changing the
declared default of one parameter of each built-in analysis in place.
"""

from __future__ import annotations

import dataclasses
import json

import pytest

from hydrosync_core.cli import build_parser, main
from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.demo import fill_demo
from hydrosync_core.methods.latency.params import LatencyParams
from hydrosync_core.methods.pool_calibration.params import PoolParams
from hydrosync_core.params import cli_values, from_cli, parse_assignment
from hydrosync_core.plugins import get_spec
from hydrosync_core.project import Project


def _set_default(monkeypatch, schema, name: str, value) -> None:
    """Change the declared default of *name* (the dataclass field and its __init__)."""
    field = schema.__dataclass_fields__[name]
    monkeypatch.setattr(field, "default", value)
    names = [f.name for f in dataclasses.fields(schema)]
    defaults = list(schema.__init__.__defaults__)
    defaults[names.index(name) - (len(names) - len(defaults))] = value
    monkeypatch.setattr(schema.__init__, "__defaults__", tuple(defaults))
    monkeypatch.setattr(schema, "_schema_cache", None, raising=False)


@pytest.mark.parametrize(("analysis", "schema", "name", "value", "command"), [
    ("latency", LatencyParams, "step_s", 0.0125, ["latency", "P.h5"]),
    ("pool_calibration", PoolParams, "max_iter", 17, ["pool-calibrate", "P.h5"]),
])
def test_a_default_changed_in_the_schema_changes_every_view(monkeypatch, qtbot, analysis,
                                                           schema, name, value, command):
    from hydrosync_gui.widgets import ParamForm

    _set_default(monkeypatch, schema, name, value)
    spec = get_spec(analysis)
    assert spec.default_params[name] == value                      # the spec's defaults
    assert getattr(spec.make_params(), name) == value
    form = ParamForm(spec.load_params())                          # the panel's form
    qtbot.addWidget(form)
    assert form.values()[name] == value
    args = build_parser().parse_args(command)                     # the command's default
    assert name not in cli_values(args, schema)
    assert getattr(from_cli(args, schema), name) == value
    assert str(value) in build_parser()._subparsers._group_actions[0].choices[
        command[0]].format_help()                                  # … and its --help


def test_run_param_and_stored_parameters_follow_the_schema(monkeypatch, tmp_path, capsys):
    _set_default(monkeypatch, LatencyParams, "detrend_degree", 2)
    path = tmp_path / "P.h5"
    project = Project.new("p")
    fill_demo(project, seed=3)
    project.save(path)
    project.close()
    assert main(["run", "latency", str(path), "--param", "step_s=0.002",
                 "--param", "range_s=-0.6,0.6"]) == 0
    assert "step_s=0.002" in capsys.readouterr().out
    with Project.open(path) as p:
        stored = p.get_json("results/latency")
        assert stored["step_s"] == 0.002 and stored["range_s"] == [-0.6, 0.6]
        assert stored["detrend_degree"] == 2          # the changed default, stored
        assert stored == LatencyParams(step_s=0.002, range_s=(-0.6, 0.6)).to_dict()
        assert p.attrs("results/latency")["params_schema_version"] == 1


@pytest.mark.parametrize(("args", "message"), [
    (["--param", "step=0.002"], "unknown parameter 'step'"),
    (["--param", "step_s"], "expected NAME=VALUE"),
    (["--param", "step_s=fast"], "step_s must be a number"),
    (["--param", "step_s=-1"], "step_s must be > 0"),
    (["--param", "range_s=1,-1"], "range maximum must be above minimum"),
    (["--param", "weighting=median"], "weighting must be one of r, inverse_variance"),
])
def test_run_param_errors_are_one_line_and_exit_2(tmp_path, capsys, args, message):
    path = tmp_path / "P.h5"
    Project.new("p").save(path)
    assert main(["run", "latency", str(path), *args]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and message in err and "--param" in err


def test_validation_lives_in_the_core_with_the_field_named():
    with pytest.raises(InputError) as err:
        PoolParams(ins_sigma_deg=(0.1, -0.1, 0.0))
    assert err.value.field == "ins_sigma_deg" and ">= 0" in err.value.message
    with pytest.raises(InputError, match="unknown parameter 'ins_sigma_roll_deg'"):
        PoolParams.from_dict({"ins_sigma_roll_deg": 0.1})
    with pytest.raises(InputError) as err:
        LatencyParams(min_epochs=2)
    assert err.value.field == "min_epochs"
    assert parse_assignment(LatencyParams, "lever_arm_m=none") == ("lever_arm_m", None)
    assert parse_assignment(PoolParams, "final=seed") == ("final", "seed")


def test_parameters_stored_by_an_older_schema_are_migrated():
    old = {"final": "joint", "ins_sigma_roll_deg": 0.02, "ins_sigma_pitch_deg": 0.03,
           "ins_sigma_heading_deg": 0.05, "max_iter": 12}
    p = PoolParams.from_dict(old, version=1)
    assert p.ins_sigma_deg == (0.02, 0.03, 0.05) and p.max_iter == 12
    assert json.loads(json.dumps(p.to_dict()))["ins_sigma_deg"] == [0.02, 0.03, 0.05]
