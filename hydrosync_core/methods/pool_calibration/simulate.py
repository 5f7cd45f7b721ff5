"""Simulator of a pool calibration data set (seed 003): INS, side-looking multibeam, laser.

Frames: target ENU (m) for the INS positions and the laser points; multibeam soundings in
the multibeam frame (FRD, m). The vessel runs north (heading ~0) along the wall with its
starboard side to it, in ``len(ranges)`` passes at different distances, separated by
time gaps in which the INS logs nothing. Optionally one INS dropout inside a pass: the
multibeam keeps pinging there, and those pings must be dropped by the georeferencing.

Multibeam: beams in the sensor y-z plane, angle ``a`` from the sensor z axis,
``x_m = r·(0, sin a, cos a)``, ray-cast (vectorised) against the design faces, the water
surface (seen from below: a few multipath returns) and the pool floor, with range and
angle noise, plus self-returns and strays. Laser: the trusted, georeferenced scanner,
sampled uniformly on the above-water parts of the faces facing the vessel (occlusion
ignored), with noise, water-surface returns, vessel self-returns and strays. INS: exact
by default; ``ins_attitude_noise_deg`` > 0 adds first-order Gauss-Markov errors
(correlation time ``ins_noise_tau_s``) to the logged roll, pitch and heading only.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from hydrosync_core.atomic import write_json_atomic, write_text_atomic
from hydrosync_core.methods.pool_calibration.design import (
    DesignFace,
    cast_rays,
    design_faces,
    make_face,
)
from hydrosync_core.methods.pool_calibration.georef import C_NED_TO_ENU, boresight_matrix
from hydrosync_core.methods.pool_calibration.simulate_target import build_target


@dataclass(frozen=True)
class PoolPassConfig:
    """Simulation settings (units in the names; angles in degrees)."""

    coarse_boresight_deg: tuple[float, float, float] = (-45.0, 0.0, 0.0)
    coarse_lever_m: tuple[float, float, float] = (0.50, 1.20, 1.80)
    boresight_error_deg: tuple[float, float, float] = (0.8, -0.6, 0.7)
    lever_error_m: tuple[float, float, float] = (0.05, -0.04, 0.06)
    ranges_m: tuple[float, ...] = (4.0, 5.5, 7.0)
    y_start_m: float = -11.0
    y_end_m: float = 11.0
    speed_m_s: float = 1.0
    gap_s: float = 30.0
    ins_rate_hz: float = 50.0
    ins_height_m: float = 0.5
    ins_dropout_s: float = 0.0
    ins_attitude_noise_deg: float = 0.0
    ins_noise_tau_s: float = 1.0
    ping_rate_hz: float = 15.0
    beams: int = 256
    swath_deg: float = 130.0
    range_noise_m: float = 0.01
    angle_noise_deg: float = 0.03
    mbes_outlier_fraction: float = 0.01
    laser_density_per_m2: float = 5000.0
    laser_noise_m: float = 0.003
    laser_stray_fraction: float = 0.03
    floor_m: float = -4.5
    target: dict | None = field(default=None)


def _attitude_deg(t: np.ndarray, phase: float) -> np.ndarray:
    """Gentle vessel motion (deg): roll, pitch, heading as sums of sines."""
    roll = 1.5 * np.sin(2 * np.pi * t / 6.0 + phase) + 0.4 * np.sin(2 * np.pi * t / 2.3)
    pitch = 0.7 * np.sin(2 * np.pi * t / 4.5 + 2 * phase) + 0.2 * np.sin(2 * np.pi * t / 1.7)
    heading = 1.0 * np.sin(2 * np.pi * t / 20.0 + phase)
    return np.column_stack([roll, pitch, heading])


def _gauss_markov(n: int, cfg: PoolPassConfig, rng: np.random.Generator) -> np.ndarray:
    """(n, 3) first-order Gauss-Markov attitude errors (deg), σ and τ from *cfg*.

    ``e_k+1 = φ e_k + √(1-φ²) σ w_k`` with ``φ = exp(-Δt/τ)`` at the INS rate (across the
    gaps between passes too: a single error process).
    """
    from scipy.signal import lfilter

    phi = np.exp(-1.0 / (cfg.ins_rate_hz * cfg.ins_noise_tau_s))
    w = rng.normal(0.0, cfg.ins_attitude_noise_deg * np.sqrt(1 - phi**2), (n, 3))
    w[0] = rng.normal(0.0, cfg.ins_attitude_noise_deg, 3)   # stationary start
    return lfilter([1.0], [1.0, -phi], w, axis=0)


def _trajectory(t: np.ndarray, t0: float, rng_x: float, cfg: PoolPassConfig,
                phase: float) -> tuple[np.ndarray, np.ndarray]:
    """INS position (ENU, m) and attitude (deg) of one pass at times *t* (s)."""
    s = t - t0
    e = -rng_x + 0.05 * np.sin(2 * np.pi * s / 15.0 + phase)
    n = cfg.y_start_m + cfg.speed_m_s * s
    u = cfg.ins_height_m + 0.03 * np.sin(2 * np.pi * s / 3.1 + phase)
    return np.column_stack([e, n, u]), _attitude_deg(t, phase)


def _body_to_enu(att_deg: np.ndarray) -> np.ndarray:
    r_b = Rotation.from_euler("ZYX", np.deg2rad(att_deg[:, [2, 1, 0]])).as_matrix()
    return np.einsum("ij,pjk->pik", C_NED_TO_ENU, r_b)


def _clip_above(corners: np.ndarray, level: float) -> np.ndarray:
    """Part of a convex polygon with z >= level (Sutherland-Hodgman, one plane)."""
    out = []
    for a, b in zip(corners, np.roll(corners, -1, axis=0), strict=True):
        ina, inb = a[2] >= level, b[2] >= level
        if ina:
            out.append(a)
        if ina != inb:
            out.append(a + (level - a[2]) / (b[2] - a[2]) * (b - a))
    return np.array(out)


def _sample_polygon(corners: np.ndarray, n: int, rng: np.random.Generator) -> np.ndarray:
    """*n* points uniform on a convex polygon (fan triangulation, area-weighted)."""
    a = corners[0]
    b, c = corners[1:-1], corners[2:]
    areas = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    tri = rng.choice(len(areas), size=n, p=areas / areas.sum())
    r1, r2 = rng.random(n), rng.random(n)
    flip = r1 + r2 > 1
    r1[flip], r2[flip] = 1 - r1[flip], 1 - r2[flip]
    return a + r1[:, None] * (b[tri] - a) + r2[:, None] * (c[tri] - a)


def _outward(face: DesignFace, faces: list[DesignFace]) -> np.ndarray:
    """Outward normal: away from the solid the face belongs to (its block or the wall)."""
    prefix = face.name.split("_")[0]
    group = [f.centroid for f in faces if f.name.split("_")[0] == prefix]
    solid = np.mean(group, axis=0) if len(group) > 1 else face.centroid + np.array([0.5, 0, 0])
    return face.normal if face.normal @ (face.centroid - solid) > 0 else -face.normal


def _laser(faces: list[DesignFace], water: float, traj: np.ndarray, cfg: PoolPassConfig,
           rng: np.random.Generator) -> np.ndarray:
    """Laser points (N, 3) ENU m on above-water faces facing the vessel, plus clutter."""
    chunks = []
    for face in faces:
        out = _outward(face, faces)
        if face.z_max <= water + 1e-6 or out[0] > 0.5 or out[2] < -0.5:
            continue  # under water, facing away from the vessel, or facing down
        poly = _clip_above(face.corners, water)
        if len(poly) < 3:
            continue
        area = 0.5 * np.linalg.norm(np.cross(poly - poly[0], np.roll(poly, -1, 0) - poly[0]).sum(0))
        n = int(rng.poisson(cfg.laser_density_per_m2 * area))
        if n:
            chunks.append(_sample_polygon(poly, n, rng))
    pts = np.concatenate(chunks)
    pts += rng.normal(0.0, cfg.laser_noise_m, pts.shape)
    n_clutter = int(cfg.laser_stray_fraction * len(pts))
    if n_clutter:
        k = n_clutter // 3
        # Water-surface returns near the vessel, vessel self-returns around the INS, strays.
        surf = np.column_stack([rng.uniform(-8, -0.2, k), rng.uniform(-10, 10, k),
                                water + rng.normal(0, 0.01, k)])
        at = traj[rng.integers(0, len(traj), k)]
        self_ret = at + rng.normal(0, 0.6, (k, 3))
        strays = np.column_stack([rng.uniform(-10, 2, n_clutter - 2 * k),
                                  rng.uniform(-12, 12, n_clutter - 2 * k),
                                  rng.uniform(water, 4, n_clutter - 2 * k)])
        pts = np.concatenate([pts, surf, self_ret, strays])
    return pts[rng.permutation(len(pts))]


def _environment(faces: list[DesignFace], water: float, floor: float) -> list[DesignFace]:
    """Design faces plus the water surface and the pool floor as large rectangles."""
    def rect(name, z, up):
        c = np.array([[-30, -40, z], [10, -40, z], [10, 40, z], [-30, 40, z]], float)
        return make_face(name, c if up else c[::-1], "<sim>", 0)
    return faces + [rect("__water__", water, True), rect("__floor__", floor, True)]


def _mbes(faces: list[DesignFace], water: float, ping_t: np.ndarray, pos: np.ndarray,
          att: np.ndarray, cfg: PoolPassConfig, rng: np.random.Generator) -> dict:
    """Ray-cast soundings; returns ``time`` (s) and x, y, z (sensor FRD, m)."""
    r_true = boresight_matrix(*np.deg2rad(np.add(cfg.coarse_boresight_deg,
                                                 cfg.boresight_error_deg)))
    lever_true = np.add(cfg.coarse_lever_m, cfg.lever_error_m)
    a = np.deg2rad(np.linspace(-cfg.swath_deg / 2, cfg.swath_deg / 2, cfg.beams))
    rot = _body_to_enu(att)                                   # (P, 3, 3) body -> ENU
    head = pos + rot @ lever_true                             # sensor origin, ENU
    beam_s = np.column_stack([np.zeros_like(a), np.sin(a), np.cos(a)])   # sensor frame
    dirs = np.einsum("pij,bj->pbi", rot, beam_s @ r_true.T).reshape(-1, 3)
    origins = np.repeat(head, len(a), axis=0)
    env = _environment(faces, water, cfg.floor_m)
    t, f = cast_rays(origins, dirs, env)
    n_rays = len(t)
    angle = np.tile(a, len(ping_t))
    time = np.repeat(ping_t, len(a))
    hit_water = f == len(faces)
    keep = (f >= 0) & (~hit_water | (rng.random(n_rays) < 0.02))
    t, angle, time = t[keep], angle[keep], time[keep]
    # Range and beam-angle noise of the sounding.
    r = t + rng.normal(0.0, cfg.range_noise_m, len(t))
    ang = angle + np.deg2rad(rng.normal(0.0, cfg.angle_noise_deg, len(t)))
    n_out = int(cfg.mbes_outlier_fraction * len(r))
    if n_out:
        pick = rng.choice(len(r), n_out, replace=False)
        half = n_out // 2
        r[pick[:half]] = rng.uniform(0.2, 0.8, half)            # self-returns at the head
        r[pick[half:]] *= rng.uniform(0.3, 1.5, n_out - half)   # strays along the beam
    xyz = r[:, None] * np.column_stack([np.zeros_like(ang), np.sin(ang), np.cos(ang)])
    return {"time": time, "x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2]}


def simulate_pool_pass(config: PoolPassConfig | None = None, seed: int = 0) -> dict:
    """Simulate one calibration data set.

    Returns
    -------
    dict with ``lidar`` (N, 3) ENU m; ``mbes`` {time, x, y, z}; ``ins`` {time, e, n, u,
    roll, pitch, heading}; ``setup`` (coarse, setup.json convention); ``truth`` (true
    boresight_deg / lever_arm_m); ``target`` (target.json dict); ``dropout`` (start, end)
    of the INS dropout inside pass 2 or None.
    """
    cfg = config or PoolPassConfig()
    rng = np.random.default_rng(seed)
    target = cfg.target or build_target()
    water = float(target["water_level_m"])
    faces = design_faces(target)
    duration = (cfg.y_end_m - cfg.y_start_m) / cfg.speed_m_s
    ins_t, ins_p, ins_a, ping_t, ping_p, ping_a = [], [], [], [], [], []
    t0 = 1000.0
    dropout = None
    for k, rx in enumerate(cfg.ranges_m):
        phase = 1.3 * k + rng.uniform(0, 2 * np.pi)
        t_i = t0 + np.arange(0.0, duration + 1e-9, 1.0 / cfg.ins_rate_hz)
        t_p = t0 + 0.5 + 0.0137 + np.arange(0.0, duration - 1.0, 1.0 / cfg.ping_rate_hz)
        if k == 1 and cfg.ins_dropout_s > 0:
            mid = t0 + duration / 2
            dropout = (mid, mid + cfg.ins_dropout_s)
            t_i = t_i[(t_i < dropout[0]) | (t_i > dropout[1])]
        for tt, pl, al in ((t_i, ins_p, ins_a), (t_p, ping_p, ping_a)):
            p, a = _trajectory(tt, t0, rx, cfg, phase)
            pl.append(p)
            al.append(a)
        ins_t.append(t_i)
        ping_t.append(t_p)
        t0 += duration + cfg.gap_s
    ins_t, ins_p, ins_a = np.concatenate(ins_t), np.concatenate(ins_p), np.concatenate(ins_a)
    ping_t, ping_p, ping_a = (np.concatenate(v) for v in (ping_t, ping_p, ping_a))
    mbes = _mbes(faces, water, ping_t, ping_p, ping_a, cfg, rng)
    lidar = _laser(faces, water, ins_p, cfg, rng)
    if cfg.ins_attitude_noise_deg > 0:
        # Logged attitude only (the soundings were cast with the true one): errors shared
        # by all soundings of a ping and by neighbouring pings, as a real INS has.
        ins_a = ins_a + _gauss_markov(len(ins_t), cfg, rng)
    ins = {"time": ins_t, "e": ins_p[:, 0], "n": ins_p[:, 1], "u": ins_p[:, 2],
           "roll": ins_a[:, 0], "pitch": ins_a[:, 1], "heading": ins_a[:, 2]}
    keys = ("roll", "pitch", "yaw")
    setup = {"boresight_deg": dict(zip(keys, map(float, cfg.coarse_boresight_deg), strict=True)),
             "lever_arm_m": dict(zip("xyz", map(float, cfg.coarse_lever_m), strict=True))}
    truth = {"boresight_deg": dict(zip(keys, map(float, np.add(cfg.coarse_boresight_deg,
                                                              cfg.boresight_error_deg)),
                                       strict=True)),
             "lever_arm_m": dict(zip("xyz", map(float, np.add(cfg.coarse_lever_m,
                                                              cfg.lever_error_m)), strict=True))}
    return {"lidar": lidar, "mbes": mbes, "ins": ins, "setup": setup, "truth": truth,
            "target": target, "dropout": dropout}


def _write_csv(path: Path, columns: dict) -> None:
    names = list(columns)
    data = np.column_stack([np.asarray(columns[n], float) for n in names])

    def writer(fh):
        fh.write(",".join(names) + "\n")
        np.savetxt(fh, data, delimiter=",", fmt="%.6f")
    write_text_atomic(path, writer)


def write_pool_files(sim: dict, directory: str | Path) -> dict[str, Path]:
    """Write lidar.csv, mbes.csv, ins.csv, setup.json, target.json, truth.json (formats.md)."""
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    paths = {k: d / f"{k}.csv" for k in ("lidar", "mbes", "ins")}
    lid = sim["lidar"]
    _write_csv(paths["lidar"], {"x": lid[:, 0], "y": lid[:, 1], "z": lid[:, 2]})
    _write_csv(paths["mbes"], sim["mbes"])
    _write_csv(paths["ins"], sim["ins"])
    for key in ("setup", "target", "truth"):
        paths[key] = d / f"{key}.json"
        write_json_atomic(paths[key], json.loads(json.dumps(sim[key])))
    return paths
