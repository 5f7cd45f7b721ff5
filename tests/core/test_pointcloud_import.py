"""Point-cloud readers: real LAS/LAZ files (including PDAL's broken ones) and synthetic
PLY / LAS / CSV files with known coordinates."""

from __future__ import annotations

import numpy as np
import pytest

from hydrosync_core.errors import InputError
from hydrosync_core.importers.pointcloud import read_point_cloud
from tests.core._real_logs import all_files, needs_real, real, run_with_timeout

PC = "pointcloud/"


@pytest.mark.parametrize(("name", "count"), [
    ("pdal_sample_c.las", 14408),
    ("laspy_file_with_both_wkt_and_geotiff_vlrs.las", 25408),
    ("laspy_autzen_trim.laz", 110000),
    ("pdal_las_with_several_extra_byte_bloc.laz", 697721),
    ("laspy_simple.las", 1065),
])
@needs_real
def test_real_las_counts(name, count):
    warnings: list[str] = []
    pts = read_point_cloud(real(PC + name), warnings=warnings)
    assert pts.shape == (count, 3) and pts.dtype == np.float64 and not warnings


@needs_real
def test_sample_c_extent_matches_readme():
    pts = read_point_cloud(real(PC + "pdal_sample_c.las"))
    extent = pts.max(axis=0) - pts.min(axis=0)
    assert extent[0] == pytest.approx(83, abs=1) and extent[1] == pytest.approx(75, abs=1)
    assert pts[:, 2].min() == pytest.approx(627.5, abs=0.5)
    assert pts[:, 2].max() == pytest.approx(656.2, abs=0.5)


@needs_real
def test_scaled_coordinates_equal_laspy():
    import laspy

    las = laspy.read(real(PC + "laspy_simple.las"))
    expected = las.X * las.header.scales[0] + las.header.offsets[0]
    assert np.array_equal(read_point_cloud(real(PC + "laspy_simple.las"))[:, 0], expected)


@needs_real
def test_garbage_vlr_count_is_repaired_without_walking_it():
    """1069128089 declared VLRs: the reader must not walk them (the timeout only guards a
    hang; the warning says the count was repaired from the data offset)."""
    warnings: list[str] = []
    pts = run_with_timeout(lambda: read_point_cloud(
        real(PC + "pdal_BAD_garbage_nVariableLength.las"), warnings=warnings), timeout=60)
    assert len(pts) == 718  # 719 declared, the last record is cut short
    assert any("1069128089 VLRs" in w for w in warnings)
    assert any("718 complete records" in w for w in warnings)


@needs_real
def test_bad_vlr_count_nan_time_and_no_points():
    warnings: list[str] = []
    assert len(read_point_cloud(real(PC + "pdal_BAD_bad_vlr_count.las"), warnings=warnings)) == 10
    assert warnings == ["header says 3 VLRs, 2 present: count repaired"]
    warnings = []
    assert len(read_point_cloud(real(PC + "pdal_BAD_gps-time-nan.las"), warnings=warnings)) == 1
    assert any("non-finite GPS time" in w for w in warnings)
    with pytest.raises(InputError, match="0 points"):
        read_point_cloud(real(PC + "pdal_BAD_no-points.las"))


@pytest.mark.parametrize("path", all_files("pointcloud"), ids=lambda p: p.name)
def test_every_real_cloud_reads_or_raises_input_error(path):
    try:
        pts = run_with_timeout(lambda: read_point_cloud(path), timeout=15)
    except InputError as exc:
        assert path.name in str(exc)
        return
    assert pts.ndim == 2 and pts.shape[1] == 3 and len(pts) >= 1
    assert np.isfinite(pts).all()


# ---------------------------------------------------------------- synthetic


def _cloud(n=50, seed=3):
    return np.random.default_rng(seed).uniform(-5, 5, size=(n, 3))


@pytest.mark.parametrize("fmt", ["ascii", "binary_little_endian", "binary_big_endian"])
def test_ply_formats(tmp_path, fmt):
    pts = _cloud()
    header = (f"ply\nformat {fmt} 1.0\ncomment test\nelement vertex {len(pts)}\n"
              "property double x\nproperty double y\nproperty double z\n"
              "property uchar red\nelement face 0\nproperty list uchar int vertex_indices\n"
              "end_header\n").encode()
    if fmt == "ascii":
        body = "".join(f"{x!r} {y!r} {z!r} 7\n" for x, y, z in pts.tolist()).encode()
    else:
        order = "<" if fmt == "binary_little_endian" else ">"
        rec = np.zeros(len(pts), dtype=[("x", order + "f8"), ("y", order + "f8"),
                                         ("z", order + "f8"), ("r", "u1")])
        rec["x"], rec["y"], rec["z"] = pts.T
        body = rec.tobytes()
    path = tmp_path / "c.ply"
    path.write_bytes(header + body)
    assert np.array_equal(read_point_cloud(path), pts)


def test_ply_written_by_open3d(tmp_path):
    import open3d as o3d

    pts = _cloud(30)
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(pts))
    path = tmp_path / "o3d.ply"
    o3d.io.write_point_cloud(str(path), cloud)
    assert np.allclose(read_point_cloud(path), pts, atol=1e-6)


def test_bad_ply_files(tmp_path):
    trunc = tmp_path / "t.ply"
    trunc.write_bytes(b"ply\nformat binary_little_endian 1.0\nelement vertex 10\n"
                      b"property float x\nproperty float y\nproperty float z\nend_header\n"
                      + b"\x00" * 50)
    with pytest.raises(InputError, match="truncated"):
        read_point_cloud(trunc)
    noxyz = tmp_path / "n.ply"
    noxyz.write_bytes(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float a\n"
                      b"end_header\n1\n")
    with pytest.raises(InputError, match="x, y, z"):
        read_point_cloud(noxyz)
    junk = tmp_path / "j.ply"
    junk.write_bytes(b"\x00\x01 not a ply")
    with pytest.raises(InputError, match="not a PLY"):
        read_point_cloud(junk)


def test_las_scale_offset_and_truncation(tmp_path):
    import laspy

    pts = _cloud(100) + [1000.0, 2000.0, 30.0]
    header = laspy.LasHeader(point_format=3, version="1.2")
    header.scales = np.array([0.001, 0.001, 0.01])
    header.offsets = np.array([1000.0, 2000.0, 0.0])
    las = laspy.LasData(header)
    las.x, las.y, las.z = pts.T
    path = tmp_path / "s.las"
    las.write(path)
    got = read_point_cloud(path)
    assert np.allclose(got, pts, atol=[0.0005, 0.0005, 0.005])
    assert got[0, 0] == (round((pts[0, 0] - 1000.0) / 0.001)) * 0.001 + 1000.0
    cut = tmp_path / "cut.las"
    cut.write_bytes(path.read_bytes()[:-10])
    warnings: list[str] = []
    assert len(read_point_cloud(cut, warnings=warnings)) == 99
    assert "99 complete records" in warnings[0]
    notlas = tmp_path / "x.las"
    notlas.write_bytes(b"LASX" + b"\x00" * 400)
    with pytest.raises(InputError, match="not a LAS file"):
        read_point_cloud(notlas)


def test_csv_and_min_points(tmp_path):
    path = tmp_path / "lidar.csv"
    pts = _cloud(5)
    path.write_text("x,y,z\n" + "".join(f"{x!r},{y!r},{z!r}\n" for x, y, z in pts.tolist()))
    assert np.array_equal(read_point_cloud(path), pts)
    with pytest.raises(InputError, match="at least 10"):
        read_point_cloud(path, min_points=10)
    with pytest.raises(InputError, match="no such file"):
        read_point_cloud(tmp_path / "none.las")
