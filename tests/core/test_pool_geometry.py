"""Pool calibration geometry: target builder, face roles, ray casting, georeferencing."""

from __future__ import annotations

import numpy as np
import pytest

from hydrosync_core.errors import InputError
from hydrosync_core.methods.pool_calibration import georef
from hydrosync_core.methods.pool_calibration.api import calibrate
from hydrosync_core.methods.pool_calibration.design import cast_rays, design_faces, inside_polygon
from hydrosync_core.methods.pool_calibration.roles import infer_roles
from hydrosync_core.methods.pool_calibration.seed_iteration import signed_angle
from hydrosync_core.methods.pool_calibration.simulate import PoolPassConfig, simulate_pool_pass
from hydrosync_core.methods.pool_calibration.simulate_target import build_target


def test_target_design_and_roles():
    target = build_target(blocks_per_side=3)
    faces = design_faces(target)
    roles = infer_roles(faces, target["water_level_m"])
    assert roles["wall"].role == "wall" and roles["wall"].water == "crossing"
    # The wall normal points to the vessel side (west, -x), where the blocks stand.
    assert roles["wall"].normal @ [-1, 0, 0] == pytest.approx(1.0)
    for side in "NS":
        for k in (1, 2, 3):
            assert roles[f"{side}{k}_oblique"].role == "oblique"
            assert roles[f"{side}{k}_perpendicular"].role == "perpendicular"
            assert roles[f"{side}{k}_top"].role == "horizontal"
    # First south block lower: its top below water, the first north one above.
    assert roles["S1_top"].water == "below" and roles["N1_top"].water == "above"
    assert roles["N1_oblique"].angle_to_wall_deg == pytest.approx(
        np.degrees(np.arctan2(1.0, 1.5)), abs=1e-6)
    with pytest.raises(ValueError):
        build_target(low_block_top=0.5)


def test_bad_design_faces():
    with pytest.raises(InputError, match="coplanar"):
        design_faces({"faces": [{"name": "w", "corners": [[0, 0, 0], [0, 1, 0], [0, 1, 1],
                                                            [0.5, 0, 1]]}]})
    with pytest.raises(InputError, match="zero area"):
        design_faces({"faces": [{"name": "w", "corners": [[0, 0, 0], [0, 1, 0], [0, 2, 0]]}]})
    flat = design_faces({"faces": [{"name": "t", "corners": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}]})
    with pytest.raises(InputError, match="no vertical face"):
        infer_roles(flat, 0.0)


def test_ray_cast_and_polygon():
    faces = design_faces(build_target())
    wall = faces[0]
    o = np.array([[-5.0, 0.0, -1.0], [-5.0, 0.0, -1.0], [-5.0, 10.0, -1.0]])
    d = np.array([[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    t, f = cast_rays(o, d, faces)
    assert t[0] == pytest.approx(5.0) and faces[f[0]].name == "wall"
    assert f[1] == -1 and np.isinf(t[1]) and f[2] == -1
    pts = np.array([[0, 0, 0], [0, 2.95, 0], [0, 3.5, 0]], float)
    assert inside_polygon(wall, pts).tolist() == [True, True, False]
    assert inside_polygon(wall, pts, margin=0.1).tolist() == [True, False, False]


def test_signed_angle_signs():
    axis = np.array([0.0, 1.0, 0.0])
    n = np.array([1.0, 0.0, 0.0])
    rot = georef.boresight_matrix(0.0, np.deg2rad(0.3), 0.0)  # +0.3° about +y
    assert np.degrees(signed_angle(n, rot @ n, axis)) == pytest.approx(0.3)
    assert np.degrees(signed_angle(rot @ n, n, axis)) == pytest.approx(-0.3)


def test_georeference_matches_equation():
    ins = {"time": np.array([0.0, 1.0]), "e": np.array([0.0, 2.0]), "n": np.array([0.0, 0.0]),
           "u": np.array([0.0, 0.0]), "roll": np.array([0.0, 0.0]),
           "pitch": np.array([0.0, 0.0]), "heading": np.array([90.0, 90.0])}
    mbes = {"time": np.array([0.5, 0.5, 5.0]), "x": np.array([0.0, 1.0, 0.0]),
            "y": np.array([1.0, 0.0, 0.0]), "z": np.array([2.0, 0.0, 0.0])}
    ctx = georef.prepare(mbes, ins)
    assert ctx.dropped_pings == 1 and ctx.dropped_soundings == 1
    p = georef.georeference(ctx, np.eye(3), np.array([0.0, 0.0, 0.0]))
    # Heading east: body x -> east, body y (starboard) -> south, body z (down) -> -up.
    assert p[0] == pytest.approx([1.0, -1.0, -2.0])
    assert p[1] == pytest.approx([2.0, 0.0, 0.0])


def test_single_pass_warns_naming_parameters():
    cfg = PoolPassConfig(ranges_m=(5.0,), beams=128, ping_rate_hz=8.0,
                         laser_density_per_m2=800.0)
    sim = simulate_pool_pass(cfg, seed=1)
    res = calibrate(sim["lidar"], sim["mbes"], sim["ins"], sim["setup"], sim["target"])
    text = " | ".join(res.warnings)
    assert "yaw and lever_x strongly correlated" in text
    assert "yaw poorly determined" in text
    # No horizontal face seen below water: the vertical offset is not guessed.
    assert "lever_z cannot be determined" in text
    # (only the mean-attitude projection of the other offsets touches body z: < 1 mm)
    assert res.lever_arm_m["z"] == pytest.approx(sim["setup"]["lever_arm_m"]["z"], abs=1e-3)
