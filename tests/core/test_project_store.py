"""Project file: round trip, atomic save, lazy loading, schema versions, migrations."""

from __future__ import annotations

import h5py
import numpy as np
import pytest

from hydrosync_core.errors import InputError, ProjectFormatError
from hydrosync_core.project import Project, schema, store
from hydrosync_core.project.vessel import lever_arm, set_sensor


def _sample_project() -> Project:
    project = Project.new(name="Round trip")
    rng = np.random.default_rng(1)
    project.put_table(
        "raw/gnss",
        {"time": np.arange(10.0), "height": rng.normal(size=10), "quality": np.full(10, 4.0)},
        source="gnss.csv",
    )
    project.put_table("raw/lines", {"name": np.array(["L01", "L02"]), "start": [0.0, 5.0],
                                    "end": [4.0, 9.0]})
    project.put("raw/pool/lidar", rng.normal(size=(20000, 3)), attrs={"frame": "target ENU"})
    project.put_json("results/latency", {"latency_s": 0.29, "lines": ["L01"]})
    project.set_attrs("results/latency", latency_s=0.29, converged=True)
    set_sensor(project, "gnss", [1.0, 2.0, -3.0])
    set_sensor(project, "motion", [0.5, 0.0, 0.0], angles_deg={"roll": 0, "pitch": 0, "yaw": 0})
    return project


def test_round_trip_identical_arrays_and_attributes(tmp_path):
    original = _sample_project()
    path = original.save(tmp_path / "p.h5")
    with Project.open(path) as again:
        assert again.name == "Round trip"
        assert again.attrs()["schema_version"] == schema.SCHEMA_VERSION
        gnss = again.get_table("raw/gnss")
        assert list(gnss) == ["time", "height", "quality"]
        for key, values in original.get_table("raw/gnss").items():
            np.testing.assert_array_equal(gnss[key], values)
        assert again.get_table("raw/lines")["name"].tolist() == ["L01", "L02"]
        np.testing.assert_array_equal(again.get("raw/pool/lidar"), original.get("raw/pool/lidar"))
        assert again.attrs("raw/pool/lidar")["frame"] == "target ENU"
        assert again.get_json("results/latency") == {"latency_s": 0.29, "lines": ["L01"]}
        assert again.attrs("results/latency")["latency_s"] == 0.29
        assert again.attrs("results/latency")["converged"]
        np.testing.assert_allclose(lever_arm(again, "gnss", "motion"), [0.5, 2.0, -3.0])
        assert not again.dirty


def test_large_datasets_are_chunked_and_compressed(tmp_path):
    path = _sample_project().save(tmp_path / "p.h5")
    with h5py.File(path, "r") as f:
        ds = f["raw/pool/lidar"]
        assert ds.chunks is not None
        assert ds.compression == "gzip"


@pytest.fixture
def h5_reads(monkeypatch) -> list:
    """The names of the HDF5 datasets read from here on, in order."""
    reads = []
    original_getitem = h5py.Dataset.__getitem__

    def spy(self, key):
        reads.append(self.name)
        return original_getitem(self, key)

    monkeypatch.setattr(h5py.Dataset, "__getitem__", spy)
    return reads


def test_open_reads_metadata_only(tmp_path, h5_reads):
    path = _sample_project().save(tmp_path / "p.h5")
    reads = h5_reads
    with Project.open(path) as project:
        infos = {i.path: i for i in project.walk()}
        assert infos["raw/pool/lidar"].shape == (20000, 3)
        assert reads == []
        project.get("raw/gnss/time")
        assert reads == ["/raw/gnss/time"]


def test_resave_in_place_keeps_lazy_data(tmp_path):
    path = _sample_project().save(tmp_path / "p.h5")
    with Project.open(path) as project:
        lidar = project.get("raw/pool/lidar")
        project.put("results/extra", np.ones(3))
        project.save()
        np.testing.assert_array_equal(project.get("raw/pool/lidar"), lidar)
    with Project.open(path) as project:
        np.testing.assert_array_equal(project.get("results/extra"), np.ones(3))
        np.testing.assert_array_equal(project.get("raw/pool/lidar"), lidar)


def test_crash_midway_through_save_leaves_previous_file_intact(tmp_path, monkeypatch):
    path = _sample_project().save(tmp_path / "p.h5")
    before = path.read_bytes()
    with Project.open(path) as project:
        project.put("raw/new", np.arange(100000.0))
        calls = {"n": 0}
        real = store._write_dataset

        def exploding(group, name, node):
            calls["n"] += 1
            if calls["n"] == 3:
                raise OSError("disk unplugged")
            real(group, name, node)

        monkeypatch.setattr(store, "_write_dataset", exploding)
        with pytest.raises(OSError, match="disk unplugged"):
            project.save()
        assert project.dirty
    assert path.read_bytes() == before
    assert not (tmp_path / "p.h5.tmp").exists()
    with Project.open(path) as again:
        assert not again.exists("raw/new")


def test_newer_schema_is_refused_with_clear_message(tmp_path):
    path = tmp_path / "future.h5"
    with h5py.File(path, "w") as f:
        f.attrs["format"] = schema.FORMAT_NAME
        f.attrs["schema_version"] = schema.SCHEMA_VERSION + 5
    with pytest.raises(ProjectFormatError, match="newer than this HydroSync"):
        Project.open(path)


def test_not_a_project(tmp_path):
    plain = tmp_path / "plain.h5"
    with h5py.File(plain, "w") as f:
        f["x"] = [1, 2]
    with pytest.raises(ProjectFormatError, match="not a HydroSync project"):
        Project.open(plain)
    text = tmp_path / "text.h5"
    text.write_text("hello")
    with pytest.raises(ProjectFormatError, match="not a readable HDF5 file"):
        Project.open(text)
    with pytest.raises(InputError, match="no such project file"):
        Project.open(tmp_path / "missing.h5")


def test_version0_file_is_migrated(tmp_path):
    """A pre-release (schema 0) project: /config and /analysis become /vessel and /results."""
    path = tmp_path / "old.h5"
    with h5py.File(path, "w") as f:
        f.attrs["format"] = schema.FORMAT_NAME
        f.attrs["schema_version"] = 0
        f.create_group("config").attrs["json"] = '{"name": "Old boat", "sensors": {}}'
        f.create_group("analysis/latency").attrs["latency_s"] = 0.31
        f.create_group("raw")
    with Project.open(path) as project:
        assert project.dirty
        assert project.get_json("vessel")["name"] == "Old boat"
        assert project.attrs("results/latency")["latency_s"] == 0.31
        project.save(tmp_path / "upgraded.h5")
    with Project.open(tmp_path / "upgraded.h5") as project:
        assert project.attrs()["schema_version"] == schema.SCHEMA_VERSION
        assert project.exists("results/latency") and not project.exists("analysis")


def test_fixture_v1_project_still_opens():
    from pathlib import Path

    fixture = Path(__file__).parents[1] / "data" / "project_v1.h5"
    with Project.open(fixture) as project:
        assert project.get_table("raw/gnss")["height"].shape == (5,)
        assert project.get_json("vessel")["name"] == "Fixture vessel"


def test_table_columns_must_match():
    project = Project.new()
    with pytest.raises(ValueError, match="different lengths"):
        project.put_table("raw/gnss", {"time": [1.0, 2.0], "height": [1.0]})


def test_cached_tables_are_read_once_frozen_and_follow_the_content(tmp_path, monkeypatch,
                                                                    h5_reads):
    """get_table(cached=True) reads a file-backed table once (also across a save), gives
    read-only arrays, reads again when the table is replaced, and never changes what the
    plain get_table gives."""
    from hydrosync_core.project import model

    path = _sample_project().save(tmp_path / "p.h5")
    reads = h5_reads
    with Project.open(path) as project:
        first = project.get_table("raw/gnss", cached=True)
        assert len(reads) == 3
        again = project.get_table("raw/gnss", cached=True)
        assert len(reads) == 3 and again["height"] is first["height"]
        with pytest.raises(ValueError):
            again["height"][0] = 1.0  # read-only: the cache cannot be changed through it
        plain = project.get_table("raw/gnss")
        assert len(reads) == 6 and plain["height"].flags.writeable
        np.testing.assert_array_equal(plain["height"], first["height"])
        project.save()  # nodes rebuilt from the new file, same content: still cached
        reads.clear()
        project.get_table("raw/gnss", cached=True)
        assert reads == []
        project.put_table("raw/gnss", {"time": np.arange(5.0), "height": np.ones(5)})
        fresh = project.get_table("raw/gnss", cached=True)  # in memory: not cached
        assert fresh["height"].size == 5 and fresh["height"].flags.writeable
        project.save()
        reads.clear()
        saved = project.get_table("raw/gnss", cached=True)
        assert len(reads) == 2 and saved["height"].size == 5  # new content, read once
    monkeypatch.setattr(model, "TABLE_CACHE_BYTES", 10)  # a budget below the table: no cache
    with Project.open(path) as project:
        reads.clear()
        project.get_table("raw/gnss", cached=True)
        project.get_table("raw/gnss", cached=True)
        assert len(reads) == 4
