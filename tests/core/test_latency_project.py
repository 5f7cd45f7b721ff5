"""``project_run.run`` layout in /results/latency, recombination by hand, demo data."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hydrosync_core.errors import InputError
from hydrosync_core.methods.latency.combine import combine
from hydrosync_core.methods.latency.demo import fill_demo
from hydrosync_core.methods.latency.project_run import recombine, run
from hydrosync_core.project import Project


@pytest.fixture(scope="module")
def demo_project():
    project = Project.new("demo")
    truth = fill_demo(project, seed=0)
    result = run(project, {"step_s": 0.01})
    return project, truth, result


def test_run_stores_documented_layout(demo_project):
    project, truth, result = demo_project
    attrs = project.attrs("results/latency")
    for key in ("software_version", "run_utc", "latency_s", "ci95_low", "ci95_high",
                "uncertainty_s", "n_used", "weighting", "warnings", "lever_arm_m"):
        assert key in attrs
    assert attrs["latency_s"] == pytest.approx(truth["latency_s"], abs=0.03)
    assert attrs["ci95_low"] < attrs["latency_s"] < attrs["ci95_high"]
    assert json.loads(attrs["lever_arm_m"]) == truth["lever_arm_m"]  # from the vessel sheet
    assert isinstance(json.loads(attrs["warnings"]), list)
    params = project.get_json("results/latency")
    assert params["step_s"] == 0.01 and params["lever_arm_m"] is None  # vessel sheet used
    table = project.get_table("results/latency/lines")
    assert list(table)[:10] == ["name", "start", "end", "epochs", "r_max", "latency_s",
                                "uncertainty_s", "sigma0_before_m", "sigma0_after_m", "used"]
    assert table["name"].size == 13 and table["epochs"].min() == 120
    grid = project.get("results/latency/dt_grid")
    curves = project.get("results/latency/r_curves")
    assert grid.shape == (201,) and curves.shape == (13, 201)
    np.testing.assert_allclose(np.nanmax(curves, axis=1), table["r_max"], atol=0.01)
    sync = project.get_table("results/latency/synchronised")
    assert list(sync) == ["time", "height", "roll", "pitch", "heading", "heave", "total_heave"]
    gnss = project.get_table("raw/gnss")
    np.testing.assert_allclose(sync["time"], gnss["time"][: sync["time"].size]
                               - result.latency_s)


def test_recombine_matches_combine_of_stored_values(demo_project):
    project, _, _ = demo_project
    table = project.get_table("results/latency/lines")
    used = table["used"].copy()
    used[[0, 4, 7]] = False
    values = recombine(project, used)
    expect = combine(table["latency_s"], table["r_max"], table["uncertainty_s"], used, "r")
    assert values["latency_s"] == pytest.approx(expect.latency_s)
    attrs = project.attrs("results/latency")
    assert attrs["latency_s"] == pytest.approx(expect.latency_s) and attrs["n_used"] == 10
    stored = project.get_table("results/latency/lines")
    assert stored["used"].tolist() == used.tolist()
    assert np.all(np.isfinite(stored["sigma0_after_m"]))


def test_run_needs_lever_arm(demo_project):
    project = Project.new("no vessel")
    demo, _, _ = demo_project
    for path in ("raw/gnss", "raw/attitude", "raw/lines"):
        project.put_table(path, demo.get_table(path))
    with pytest.raises(InputError, match="vessel sheet has no .gnss. and no .motion. sensor"):
        run(project, {})
    result = run(project, {"lever_arm_m": [-1.5, 2.0, -6.0], "step_s": 0.02})
    assert result.converged
