"""Project browser: rows, shapes, sizes, tables with columns, attributes, refresh."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hydrosync_core.project import Project
from hydrosync_gui.project_browser import ProjectBrowser, human_size, shape_text


@pytest.mark.parametrize(("nbytes", "text"), [
    (0, "0 B"), (1023, "1023 B"), (1024, "1.0 KiB"), (8000, "7.8 KiB"),
    (3 * 1024**2, "3.0 MiB"), (5 * 1024**3 + 1, "5.0 GiB"),
])
def test_human_size(nbytes, text):
    assert human_size(nbytes) == text


def test_shape_text():
    assert shape_text((1200, 3)) == "1200 × 3"
    assert shape_text(()) == "scalar"
    assert shape_text(None) == ""


@pytest.fixture
def browser(qtbot):
    widget = ProjectBrowser()
    qtbot.addWidget(widget)
    return widget


def test_tree_of_a_project(browser, make_project):
    browser.set_project(make_project())
    top = [browser.tree.topLevelItem(i).text(0) for i in range(browser.tree.topLevelItemCount())]
    assert top == ["vessel", "raw", "results"]
    assert browser.row_texts("vessel")[1] == "json"
    assert browser.row_texts("results") == ("results", "group", "", "0 B")
    gnss = browser.item("raw/gnss")
    assert [gnss.child(i).text(0) for i in range(gnss.childCount())] == ["time", "height"]
    assert browser.row_texts("raw/gnss/time") == ("time", "1000", "float64", "7.8 KiB")
    assert browser.row_texts("raw/pool") == ("pool", "group", "", "11.7 KiB")
    setup = json.dumps({"boresight_deg": {"roll": 0.0, "pitch": 0.0, "yaw": 0.0}})
    assert browser.row_texts("raw/pool/setup") == ("setup", "json", "", f"{len(setup)} B")
    # raw and its plain sub-groups are expanded, tables are not
    assert browser.item("raw").isExpanded() and browser.item("raw/pool").isExpanded()
    assert not browser.item("raw/gnss").isExpanded()


def test_string_and_integer_datasets(browser, tmp_path):
    project = Project.new("p")
    project.put_table("raw/lines", {"name": np.array(["L1", "L2"]), "start": np.array([0.0, 5.0]),
                                    "end": np.array([4.0, 9.0])})
    project.put("results/x/flags", np.arange(6, dtype=np.int32).reshape(2, 3))
    project.save(tmp_path / "p.h5")  # strings come back as objects from the file
    with Project.open(tmp_path / "p.h5") as reopened:
        browser.set_project(reopened)
        assert browser.row_texts("raw/lines/name")[1:3] == ("2", "str")
        assert browser.row_texts("results/x/flags") == ("flags", "2 × 3", "int32", "24 B")
        assert browser.row_texts("raw/lines")[1] == "table 2 × 3"


def test_attributes_in_detail_pane_and_tooltip(browser, qtbot, make_project):
    browser.set_project(make_project())
    selected = []
    browser.sig_selected.connect(selected.append)
    browser.tree.setCurrentItem(browser.item("raw/pool/lidar"))
    assert selected == ["raw/pool/lidar"]
    detail = browser.detail.toPlainText()
    assert detail.splitlines()[0] == "/raw/pool/lidar"
    assert "  frame: target ENU" in detail and "  units: m" in detail
    browser.tree.setCurrentItem(browser.item("raw/pool/setup"))
    text = browser.detail.toPlainText()
    document = json.loads("\n".join(line[4:] for line in text.splitlines()
                                    if line.startswith("    ")))
    assert document == {"boresight_deg": {"roll": 0.0, "pitch": 0.0, "yaw": 0.0}}
    assert "source: gnss.csv" in browser.item("raw/gnss").toolTip(0)


def test_refresh_keeps_expansion_and_selection_and_shows_new_nodes(browser, make_project):
    project = make_project()
    browser.set_project(project)
    browser.item("raw/gnss").setExpanded(True)
    browser.item("vessel").setExpanded(False)
    browser.tree.setCurrentItem(browser.item("raw/gnss/height"))
    project.put("results/latency/lag", np.array(0.25))
    project.put_json("results/latency", {"max_lag": 1.0})  # parameters of a result group
    browser.refresh()
    assert browser.row_texts("results/latency")[1] == "group"
    assert "max_lag" in browser.item("results/latency").toolTip(0)
    assert browser.item("raw/gnss").isExpanded()
    assert not browser.item("vessel").isExpanded()
    assert browser.tree.currentItem() is browser.item("raw/gnss/height")
    assert browser.row_texts("results/latency/lag") == ("lag", "scalar", "float64", "8 B")
    browser.set_project(None)
    assert browser.tree.topLevelItemCount() == 0 and browser.item("raw") is None
