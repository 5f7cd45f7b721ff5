"""Simulator of a pool calibration data set (seed 003): INS, side-looking multibeam, laser.

Frames: target ENU (m) for the INS positions and the laser points; multibeam soundings in
the multibeam frame (FRD, m). The vessel runs roughly north along the wall with its
starboard side to it, in ``len(ranges_m)`` passes at different distances (at the target
centre) and headings (``headings_deg``, the track turns with the heading), separated by
time gaps in which the INS logs nothing. Optionally one INS dropout inside a pass: the
multibeam keeps pinging there, and those pings must be dropped by the georeferencing.

Target: the design of ``target.json`` (:mod:`.simulate_target`, either kind), *as built*:
every body that lies wholly below water (a below-water twin block) is displaced from its
design by a rigid error drawn uniformly within ±``build_tol_m`` per axis and
±``build_tol_deg`` per axis (about the body's centroid), which is what the design
translation between twins is known to.

Multibeam: beams in the sensor y-z plane, angle ``a`` from the sensor z axis,
``x_m = r·(0, sin a, cos a)``, ray-cast (vectorised, first hit: blocks occlude each other)
against the as-built faces, the water surface (seen from below: a few multipath returns)
and the pool floor. Grazing returns fade out: a return whose incidence angle (ray to face
normal) exceeds ``grazing_start_deg`` is kept with a probability falling linearly to 0 at
``grazing_max_deg``. Range and angle noise, self-returns and strays. Laser: the trusted,
georeferenced scanner, sampled uniformly on the above-water parts of the faces facing the
vessel (occlusion ignored), with noise, water-surface returns, vessel self-returns and
strays. INS: exact by default; ``ins_attitude_noise_deg`` > 0 adds first-order
Gauss-Markov errors (correlation time ``ins_noise_tau_s``) to the logged roll, pitch and
heading only. :func:`random_config` draws every setting of a pass at random.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field, replace
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
from hydrosync_core.methods.pool_calibration.simulate_target import (
    KINDS,
    build_target,
    prism_target,
    random_target,
)
from hydrosync_core.methods.pool_calibration.twins import bodies, outward_normals


@dataclass(frozen=True)
class PoolPassConfig:
    """Simulation settings (units in the names; angles in degrees)."""

    coarse_boresight_deg: tuple[float, float, float] = (-45.0, 0.0, 0.0)
    coarse_lever_m: tuple[float, float, float] = (0.50, 1.20, 1.80)
    boresight_error_deg: tuple[float, float, float] = (0.8, -0.6, 0.7)
    lever_error_m: tuple[float, float, float] = (0.05, -0.04, 0.06)
    ranges_m: tuple[float, ...] = (4.0, 5.5, 7.0)
    headings_deg: tuple[float, ...] | None = None
    y_start_m: float | None = None
    y_end_m: float | None = None
    speed_m_s: float = 1.0
    gap_s: float = 30.0
    ins_rate_hz: float = 50.0
    ins_height_m: float = 0.5
    ins_dropout_s: float = 0.0
    ins_attitude_noise_deg: float = 0.0
    ins_noise_tau_s: float = 1.0
    roll_amp_deg: float = 1.5
    pitch_amp_deg: float = 0.7
    heading_amp_deg: float = 1.0
    roll_period_s: float = 6.0
    pitch_period_s: float = 4.5
    sway_m: float = 0.05
    heave_m: float = 0.03
    ping_rate_hz: float = 15.0
    beams: int = 256
    swath_deg: float = 130.0
    range_noise_m: float = 0.01
    angle_noise_deg: float = 0.03
    mbes_outlier_fraction: float = 0.01
    grazing_start_deg: float = 70.0
    grazing_max_deg: float = 85.0
    laser_density_per_m2: float = 5000.0
    laser_noise_m: float = 0.003
    laser_stray_fraction: float = 0.03
    floor_m: float | None = None
    build_tol_m: float = 0.002
    build_tol_deg: float = 0.01
    target_kind: str = "patent"
    target: dict | None = field(default=None)
    #: Seed of the as-built errors (None: from the pass's seed). Passes of one session
    #: share it: they see the same built target.
    build_seed: int | None = None


def random_config(rng: np.random.Generator, kind: str | None = None,
                  passes: int | None = None, **override) -> PoolPassConfig:
    """A pass drawn at random: target (kind, blocks, spacing, low side, wall, water level),
    pass ranges and headings, vessel speed and attitude dynamics, INS height above the
    water (hence the head's depth), beam count and opening, laser density/noise, stray
    returns, INS noise and the coarse errors (±2°, ±0.15 m)."""
    kind = kind or str(rng.choice(KINDS))
    target = random_target(rng, kind)
    n = int(passes or rng.integers(1, 4))
    ranges = np.sort(rng.uniform(3.5, 7.0, n))
    if n > 1:  # distinct ranges (what separates yaw from the along-track lever arm)
        ranges = np.linspace(rng.uniform(3.5, 4.5), rng.uniform(5.5, 7.0), n)
    cfg = PoolPassConfig(
        coarse_boresight_deg=(float(rng.uniform(-50, -35)), float(rng.uniform(-3, 3)),
                              float(rng.uniform(-3, 3))),
        coarse_lever_m=(float(rng.uniform(-1, 1)), float(rng.uniform(0.8, 1.5)),
                        float(rng.uniform(1.6, 2.0))),
        boresight_error_deg=tuple(float(v) for v in rng.uniform(-2.0, 2.0, 3)),
        lever_error_m=tuple(float(v) for v in rng.uniform(-0.15, 0.15, 3)),
        ranges_m=tuple(float(r) for r in ranges),
        headings_deg=tuple(float(h) for h in rng.uniform(-6.0, 6.0, n)),
        speed_m_s=float(rng.uniform(0.4, 1.0)),
        roll_amp_deg=float(rng.uniform(0.3, 3.0)), pitch_amp_deg=float(rng.uniform(0.2, 1.5)),
        heading_amp_deg=float(rng.uniform(0.2, 2.0)),
        roll_period_s=float(rng.uniform(3.0, 9.0)), pitch_period_s=float(rng.uniform(2.5, 7.0)),
        sway_m=float(rng.uniform(0.0, 0.15)), heave_m=float(rng.uniform(0.0, 0.08)),
        ping_rate_hz=float(rng.uniform(15.0, 40.0)), beams=int(rng.integers(256, 513)),
        swath_deg=float(rng.uniform(110.0, 160.0)),
        range_noise_m=float(rng.uniform(0.005, 0.015)),
        angle_noise_deg=float(rng.uniform(0.01, 0.05)),
        mbes_outlier_fraction=float(rng.uniform(0.0, 0.03)),
        laser_density_per_m2=float(rng.uniform(1000.0, 5000.0)),
        laser_noise_m=float(rng.uniform(0.002, 0.005)),
        laser_stray_fraction=float(rng.uniform(0.0, 0.06)),
        ins_attitude_noise_deg=float(rng.choice([0.0, rng.uniform(0.002, 0.01)])),
        ins_noise_tau_s=float(rng.uniform(0.5, 3.0)),
        ins_height_m=float(rng.uniform(0.5, 1.0)),
        target=target, target_kind=kind)
    return replace(cfg, **override) if override else cfg


def _attitude_deg(t: np.ndarray, phase: float, cfg: PoolPassConfig,
                  heading0: float = 0.0) -> np.ndarray:
    """Vessel motion (deg): roll, pitch, heading as sums of sines."""
    roll = cfg.roll_amp_deg * (np.sin(2 * np.pi * t / cfg.roll_period_s + phase)
                               + 0.27 * np.sin(2 * np.pi * t / (0.38 * cfg.roll_period_s)))
    pitch = cfg.pitch_amp_deg * (np.sin(2 * np.pi * t / cfg.pitch_period_s + 2 * phase)
                                 + 0.29 * np.sin(2 * np.pi * t / (0.38 * cfg.pitch_period_s)))
    heading = heading0 + cfg.heading_amp_deg * np.sin(2 * np.pi * t / 20.0 + phase)
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


def _trajectory(t: np.ndarray, t0: float, rng_x: float, heading: float, y0: float,
                cfg: PoolPassConfig, phase: float,
                water: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """INS position (ENU, m) and attitude (deg) of one pass at times *t* (s).

    The track has heading *heading* (deg from north) and passes at *rng_x* m west of the
    wall abeam of the target centre (y = 0); it starts at y = *y0*; the INS rides
    ``ins_height_m`` above the water level *water*.
    """
    s = t - t0
    h = np.deg2rad(heading)
    along = y0 / np.cos(h) + cfg.speed_m_s * s
    e = -rng_x + along * np.sin(h) + cfg.sway_m * np.sin(2 * np.pi * s / 15.0 + phase)
    n = along * np.cos(h)
    u = water + cfg.ins_height_m + cfg.heave_m * np.sin(2 * np.pi * s / 3.1 + phase)
    return np.column_stack([e, n, u]), _attitude_deg(t, phase, cfg, heading)


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


def as_built(faces: list[DesignFace], water: float, tol_m: float, tol_deg: float,
             rng: np.random.Generator) -> tuple[list[DesignFace], dict]:
    """The faces as built: bodies wholly below water displaced by a rigid error (uniform
    within ±tol_m per axis, ±tol_deg per axis about the body centroid). Returns the faces
    and the errors {body: (translation m, rotation vector rad)}."""
    body = bodies(faces)
    errors = {}
    out = []
    for f in faces:
        b = body[f.name]
        members = [g for g in faces if body[g.name] == b]
        if max(g.z_max for g in members) > water or (tol_m <= 0 and tol_deg <= 0):
            out.append(f)
            continue
        if b not in errors:
            errors[b] = (rng.uniform(-tol_m, tol_m, 3),
                         np.deg2rad(rng.uniform(-tol_deg, tol_deg, 3)),
                         np.unique(np.concatenate([g.corners for g in members]), axis=0)
                         .mean(axis=0))
        dt, rv, c = errors[b]
        rot = Rotation.from_rotvec(rv).as_matrix()
        out.append(make_face(f.name, c + (f.corners - c) @ rot.T + dt, "<sim>", 0))
    return out, {k: (v[0].tolist(), v[1].tolist()) for k, v in errors.items()}


def _laser(faces: list[DesignFace], water: float, traj: np.ndarray, cfg: PoolPassConfig,
           rng: np.random.Generator) -> np.ndarray:
    """Laser points (N, 3) ENU m on above-water faces facing the vessel, plus clutter."""
    chunks = []
    outward = outward_normals(faces)
    for face in faces:
        out = outward[face.name]
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
        lo, hi = traj.min(axis=0), traj.max(axis=0)
        # Water-surface returns near the vessel, vessel self-returns around the INS, strays.
        surf = np.column_stack([rng.uniform(lo[0] - 3, -0.2, k), rng.uniform(lo[1], hi[1], k),
                                water + rng.normal(0, 0.01, k)])
        at = traj[rng.integers(0, len(traj), k)]
        self_ret = at + rng.normal(0, 0.6, (k, 3))
        strays = np.column_stack([rng.uniform(lo[0] - 2, 2, n_clutter - 2 * k),
                                  rng.uniform(lo[1], hi[1], n_clutter - 2 * k),
                                  rng.uniform(water, water + 4, n_clutter - 2 * k)])
        pts = np.concatenate([pts, surf, self_ret, strays])
    return pts[rng.permutation(len(pts))]


def _environment(faces: list[DesignFace], water: float, floor: float) -> list[DesignFace]:
    """Design faces plus the water surface and the pool floor as large rectangles."""
    def rect(name, z, up):
        c = np.array([[-40, -60, z], [15, -60, z], [15, 60, z], [-40, 60, z]], float)
        return make_face(name, c if up else c[::-1], "<sim>", 0)
    return faces + [rect("__water__", water, True), rect("__floor__", floor, True)]


def _mbes(faces: list[DesignFace], water: float, floor: float, ping_t: np.ndarray,
          pos: np.ndarray, att: np.ndarray, cfg: PoolPassConfig,
          rng: np.random.Generator) -> dict:
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
    env = _environment(faces, water, floor)
    t, f = cast_rays(origins, dirs, env)
    n_rays = len(t)
    angle = np.tile(a, len(ping_t))
    time = np.repeat(ping_t, len(a))
    hit_water = f == len(faces)
    normals = np.array([g.normal for g in env])
    cos_inc = np.abs(np.einsum("ij,ij->i", dirs, normals[np.maximum(f, 0)]))
    inc = np.degrees(np.arccos(np.clip(cos_inc, 0.0, 1.0)))
    span = max(cfg.grazing_max_deg - cfg.grazing_start_deg, 1e-6)
    p_detect = np.clip((cfg.grazing_max_deg - inc) / span, 0.0, 1.0)
    keep = (f >= 0) & (~hit_water | (rng.random(n_rays) < 0.02)) & \
        (hit_water | (rng.random(n_rays) < p_detect))
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
    boresight_deg / lever_arm_m, and the as-built ``build_errors`` per body); ``target``
    (target.json dict, the design); ``dropout`` (start, end) of the INS dropout inside
    pass 2 or None; ``config`` (the settings).
    """
    cfg = config or PoolPassConfig()
    rng = np.random.default_rng(seed)
    target = cfg.target or (prism_target(rng) if cfg.target_kind == "prism"
                            else build_target(kind=cfg.target_kind))
    water = float(target["water_level_m"])
    design = design_faces(target)
    build_rng = rng if cfg.build_seed is None else np.random.default_rng(cfg.build_seed)
    faces, build_errors = as_built(design, water, cfg.build_tol_m, cfg.build_tol_deg,
                                   build_rng)
    corners = np.concatenate([f.corners for f in design])
    floor = float(corners[:, 2].min()) if cfg.floor_m is None else cfg.floor_m
    y0 = corners[:, 1].min() - 4.5 if cfg.y_start_m is None else cfg.y_start_m
    y1 = corners[:, 1].max() + 4.5 if cfg.y_end_m is None else cfg.y_end_m
    headings = cfg.headings_deg or (0.0,) * len(cfg.ranges_m)
    ins_t, ins_p, ins_a, ping_t, ping_p, ping_a = [], [], [], [], [], []
    t0 = 1000.0
    dropout = None
    for k, rx in enumerate(cfg.ranges_m):
        heading = float(headings[k % len(headings)])
        duration = (y1 - y0) / np.cos(np.deg2rad(heading)) / cfg.speed_m_s
        phase = 1.3 * k + rng.uniform(0, 2 * np.pi)
        t_i = t0 + np.arange(0.0, duration + 1e-9, 1.0 / cfg.ins_rate_hz)
        t_p = t0 + 0.5 + 0.0137 + np.arange(0.0, duration - 1.0, 1.0 / cfg.ping_rate_hz)
        if k == 1 and cfg.ins_dropout_s > 0:
            mid = t0 + duration / 2
            dropout = (mid, mid + cfg.ins_dropout_s)
            t_i = t_i[(t_i < dropout[0]) | (t_i > dropout[1])]
        for tt, pl, al in ((t_i, ins_p, ins_a), (t_p, ping_p, ping_a)):
            p, a = _trajectory(tt, t0, rx, heading, y0, cfg, phase, water)
            pl.append(p)
            al.append(a)
        ins_t.append(t_i)
        ping_t.append(t_p)
        t0 += duration + cfg.gap_s
    ins_t, ins_p, ins_a = np.concatenate(ins_t), np.concatenate(ins_p), np.concatenate(ins_a)
    ping_t, ping_p, ping_a = (np.concatenate(v) for v in (ping_t, ping_p, ping_a))
    mbes = _mbes(faces, water, floor, ping_t, ping_p, ping_a, cfg, rng)
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
                                                              cfg.lever_error_m)), strict=True)),
             "build_errors": build_errors}
    return {"lidar": lidar, "mbes": mbes, "ins": ins, "setup": setup, "truth": truth,
            "target": target, "dropout": dropout, "config": cfg}


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
