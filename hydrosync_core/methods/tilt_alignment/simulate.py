"""Simulated tilt-pole records: a person swings a pole whose tip rests on a point.

The record has four phases: the pole held near vertical for levelling (with the hand's
wobble — a hand-held pole is never still), a move to one end of the swing, the swing
(2-3 s, one or three sweeps, along a line or an ellipse, with a twist about the pole) and
the hold at the end of the swing (the shot). Attitude ``C = Rz(heading)·Ry(pitch)·
Rx(roll)`` (body x forward, y right, z down along the pole; NED). The IMU sits at the
antenna and reports in one of the conventions of :mod:`.imu_convention` (``imu_convention``):
the motion is computed on a grid eight times finer than the IMU's, and a sample is either
the rate and specific force ``Cᵀ(a − g·e_down)`` at its tag (``instant``) or their exact
means over its interval, tagged at the interval's start, middle or end; noise is white
(density × √rate) or, with ``imu_noise_taps``, through a sensor's moving-average low-pass
(same random walk), biases constant. GNSS antenna positions (NED, m) at 5-20 Hz with white
noise, optionally a gap. The IMU's own heading starts at 0, so the true heading at the
start is the misalignment to find.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from hydrosync_core.methods.tilt_alignment.geometry import E_DOWN
from hydrosync_core.methods.tilt_alignment.imu_convention import CONVENTIONS, TAG_FRACTION
from hydrosync_core.methods.tilt_alignment.params import IMU_GRADES
from hydrosync_core.rotations import euler_zyx_matrix, log_so3

#: IMU grades as simulated: gyro noise (°/s/√Hz), gyro bias 1σ (°/s), accel noise
#: (m/s²/√Hz), accel bias 1σ (m/s²) — the documented numbers of ``params.IMU_GRADES``.
GRADES = {name: (g.gyro_noise_deg_s_rthz, g.gyro_bias_deg_s, g.accel_noise_m_s2_rthz,
                 g.accel_bias_m_s2) for name, g in IMU_GRADES.items()}
#: IMU samples per interval of the simulator's fine motion grid (even: a middle tag falls
#: on it)
OVERSAMPLE = 8


@dataclass(frozen=True)
class SwingConfig:
    """One simulated record (SI units, degrees where named ``_deg``)."""

    pole_length_m: float = 1.865
    tilt_deg: float = 35.0             # swing amplitude = largest tilt
    shape_ratio: float = 0.0           # 0 = swing along a line, up to 1 = ellipse/cone
    sweeps: int = 1                    # 1 or 3 passes from end to end
    swing_s: float = 2.5
    level_s: float = 1.2
    move_s: float = 0.7
    hold_s: float = 1.2
    azimuth_deg: float = 30.0          # lean direction of the swing in the body frame
    heading_deg: float = 123.0         # true heading at the start = the misalignment
    twist_deg: float = 8.0             # rotation about the pole during the swing
    wobble_deg: float = 0.3            # hand wobble amplitude (3 sinusoids, ∝ 1/f above 0.7 Hz)
    imu_rate_hz: float = 100.0
    gnss_rate_hz: float = 10.0
    gnss_sigma_h_m: float = 0.01
    gnss_sigma_v_m: float = 0.02
    gap_s: float = 0.0                 # GNSS gap length inside the swing
    gnss_time_offset_s: float = 0.0    # GNSS time tags late (+) against the IMU clock
    gyro_noise_deg_s_rthz: float = 0.008
    accel_noise_m_s2_rthz: float = 0.0012
    gyro_bias_deg_s: tuple[float, float, float] = (0.0, 0.0, 0.0)
    accel_bias_m_s2: tuple[float, float, float] = (0.0, 0.0, 0.0)
    gravity_m_s2: float = 9.80665
    gnss_outliers: int = 0             # epochs with a 5-15 cm error (multipath, a bad fix)
    imu_noise_taps: int = 1            # IMU noise through a moving average of this many
                                       # samples (a sensor's digital low-pass), same ARW
    imu_convention: str = "instant"    # what a sample means (:mod:`.imu_convention`)
    wobble: tuple = field(default=(), compare=False)   # (freqs, phases) filled by random


def noise_free(config: SwingConfig) -> SwingConfig:
    """The same swing without any noise or bias."""
    return replace(config, gnss_sigma_h_m=0.0, gnss_sigma_v_m=0.0, gyro_noise_deg_s_rthz=0.0,
                   accel_noise_m_s2_rthz=0.0, gyro_bias_deg_s=(0.0, 0.0, 0.0),
                   accel_bias_m_s2=(0.0, 0.0, 0.0))


def random_config(rng: np.random.Generator, tilt_range=(15.0, 60.0), grade: str | None = None,
                  **overrides) -> SwingConfig:
    """A random realistic swing: amplitude, shape, pole, IMU grade (*grade* fixes it),
    rate, noise colour, biases and sample convention, GNSS rate, noise and gap (up to 1 s).
    """
    drawn = rng.choice(list(GRADES))
    grade = GRADES[grade or drawn]
    gn, gb, an, ab = grade
    cfg = SwingConfig(
        pole_length_m=float(rng.uniform(1.2, 2.5)),
        tilt_deg=float(rng.uniform(*tilt_range)),
        shape_ratio=float(rng.choice([0.0, rng.uniform(0.1, 0.8)])),
        sweeps=int(rng.choice([1, 1, 3])),
        swing_s=float(rng.uniform(2.0, 3.0)),
        level_s=float(rng.uniform(1.0, 1.6)),
        move_s=float(rng.uniform(0.5, 0.9)),
        hold_s=float(rng.uniform(1.0, 1.5)),
        azimuth_deg=float(rng.uniform(0, 360)),
        heading_deg=float(rng.uniform(-180, 180)),
        twist_deg=float(rng.uniform(-15, 15)),
        wobble_deg=float(rng.uniform(0.05, 0.4)),
        gnss_rate_hz=float(rng.choice([5.0, 10.0, 10.0, 20.0])),
        gnss_sigma_h_m=float(rng.choice([0.01, 0.01, 0.015])),
        gnss_sigma_v_m=float(rng.choice([0.02, 0.02, 0.03])),
        gap_s=float(rng.choice([0.0, rng.uniform(0.2, 1.0)])),
        gyro_noise_deg_s_rthz=gn,
        accel_noise_m_s2_rthz=an,
        gyro_bias_deg_s=tuple(float(v) for v in rng.normal(0, gb, 3)),
        accel_bias_m_s2=tuple(float(v) for v in rng.normal(0, ab, 3)),
        gravity_m_s2=float(9.80665 + rng.uniform(-0.025, 0.025)),
    )
    # harder cases added later (drawn after the others): the IMU at 50/100/200 Hz and its
    # noise through a sensor's digital low-pass in half the runs
    cfg = replace(cfg, imu_rate_hz=float(rng.choice([50.0, 100.0, 100.0, 200.0])),
                  imu_noise_taps=int(rng.choice([1, 1, 2, 4])),
                  imu_convention=str(rng.choice(CONVENTIONS)))
    return replace(cfg, **overrides)


def _smooth(u):
    """0 → 1 with zero rate, acceleration, jerk and snap at both ends (the ninth-degree
    smoothstep): a hand's motion is band-limited. The quintic step left a jump in jerk at
    each end of the move to the swing, a kink in the acceleration that instantaneous
    samples at 50 Hz cannot follow: 0.03 m/s² in the accelerometer window across it, read
    as 1.5-2× the accelerometer noise (issue #30)."""
    u = np.clip(u, 0.0, 1.0)
    return u ** 5 * (126.0 + u * (-420.0 + u * (540.0 + u * (-315.0 + 70.0 * u))))


def _ease(tau, ramp: float = 0.15):
    """Swing phase 0 → 1 whose rate rises from zero over the first *ramp* of the swing
    (and falls over the last) by the quintic smoothstep, steady between: zero rate and
    acceleration at both ends, the peak rate only 1/(1 − ramp) of a steady swing's."""
    tau = np.clip(np.asarray(tau, float), 0.0, 1.0)

    def rise(x):            # ∫₀ˣ smoothstep = ramp·F(x/ramp), F(1) = 1/2
        u = np.clip(x / ramp, 0.0, 1.0)
        return ramp * u ** 4 * (2.5 - 3.0 * u + u * u)

    inner = np.clip(tau, ramp, 1.0 - ramp) - ramp
    s = rise(tau) + inner + (0.5 * ramp - rise(1.0 - tau)) * (tau > 1.0 - ramp)
    return s / (1.0 - ramp)


def _angles(cfg: SwingConfig, t: np.ndarray, wob: tuple, scale: float) -> np.ndarray:
    """(roll, pitch, heading) rad at times *t* (s from the start)."""
    a = math.radians(cfg.tilt_deg) * scale
    az = math.radians(cfg.azimuth_deg)
    d1 = np.array([math.cos(az), math.sin(az)])
    d2 = np.array([-math.sin(az), math.cos(az)])
    lean0 = np.array([0.02, -0.015])
    t_move = cfg.level_s
    t_swing = t_move + cfg.move_s
    tau = _ease((t - t_swing) / cfg.swing_s)
    n = cfg.sweeps
    swing = (-np.cos(np.pi * n * tau))[:, None] * a * d1 \
        + (cfg.shape_ratio * a * np.sin(np.pi * n * tau) * np.sin(np.pi * tau))[:, None] * d2
    start = -a * d1
    m = _smooth((t - t_move) / cfg.move_s)[:, None]
    lean = np.where((t < t_swing)[:, None], lean0 + (start - lean0) * m, swing)
    heading = math.radians(cfg.heading_deg) + math.radians(cfg.twist_deg) * _smooth(
        (t - t_swing) / cfg.swing_s)
    out = np.column_stack([lean[:, 0], lean[:, 1], heading])
    freqs, phases, amps = wob
    w = math.radians(cfg.wobble_deg)
    for axis in range(3):
        for f, ph, am in zip(freqs[axis], phases[axis], amps[axis], strict=True):
            out[:, axis] += w * am * min(1.0, 0.7 / f) * np.sin(2 * np.pi * f * t + ph)
    return out


def _matrices(angles: np.ndarray) -> np.ndarray:
    return euler_zyx_matrix(angles[:, 0], angles[:, 1], angles[:, 2])


def _noise(rng: np.random.Generator, sigma: float, shape: tuple, taps: int) -> np.ndarray:
    """White noise of per-sample σ *sigma*, or (taps > 1) its moving average over *taps*
    samples: a sensor's digital low-pass, which keeps the low-frequency density (angle /
    velocity random walk, the grade's number) and lowers the per-sample σ to σ/√taps.
    (Scaled back up by √taps, as before, the random walk was √taps times the grade's:
    the solver rightly reported 1.4× and 2.0× the grade's noise on those records.)"""
    if taps <= 1:
        return rng.normal(0, sigma, shape)
    raw = rng.normal(0, sigma, (shape[0] + taps - 1, *shape[1:]))
    c = np.cumsum(np.vstack([np.zeros((1, *shape[1:])), raw]), axis=0)
    return (c[taps:] - c[:-taps]) / taps


def _imu_samples(cfg: SwingConfig, t: np.ndarray, wob: tuple, scale: float
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Noise-free gyro (rad/s) and accelerometer (m/s²) rows at the tags *t* in the
    record's convention, and the true attitudes (N, 3, 3) at the tags.

    The motion is sampled every ``Δt/OVERSAMPLE`` from one interval before the first tag to
    one after the last; the antenna acceleration is the second difference there. An
    interval sample's rate is the raw increment ``∫ω dt`` over its interval divided by
    ``Δt`` (the fine steps' rotation vectors summed), its specific force the trapezoid
    mean over the interval.
    """
    dt = 1.0 / cfg.imu_rate_hz
    m = OVERSAMPLE
    h = dt / m
    tf = t[0] - dt + h * np.arange((t.size + 1) * m + 1)
    Cf = _matrices(_angles(cfg, tf, wob, scale))
    pf = -Cf[:, :, 2] * cfg.pole_length_m
    acc = np.zeros_like(pf)
    acc[1:-1] = (pf[2:] - 2 * pf[1:-1] + pf[:-2]) / h ** 2
    acc[0], acc[-1] = acc[1], acc[-2]
    ff = np.einsum("kji,kj->ki", Cf, acc - cfg.gravity_m_s2 * E_DOWN)
    tags = m * (np.arange(t.size) + 1)               # fine index of each tag
    if cfg.imu_convention == "instant":
        rel = np.einsum("kji,kjl->kil", Cf[tags - 1], Cf[tags + 1])
        gyro = log_so3(rel) / (2 * h)
        f = ff[tags]
    else:
        start = tags - int(round(TAG_FRACTION[cfg.imu_convention] * m))
        # raw increment ∫ω dt / Δt (formats.md: the mean rate), summed over the fine
        # steps — not the interval's rotation, which differs by the coning term
        fine = log_so3(np.einsum("kji,kjl->kil", Cf[:-1], Cf[1:]))
        cum = np.vstack([np.zeros(3), np.cumsum(fine, axis=0)])
        gyro = (cum[start + m] - cum[start]) / dt
        idx = start[:, None] + np.arange(m + 1)[None, :]
        wts = np.full(m + 1, 1.0 / m)
        wts[[0, -1]] *= 0.5
        f = np.einsum("kjc,j->kc", ff[idx], wts)
    return gyro, f, Cf[tags]


def simulate_swing(config: SwingConfig | None = None, seed: int = 0) -> dict:
    """Simulate one record.

    Returns
    -------
    dict with ``time`` (N,) s, ``gyro`` (N, 3) rad/s, ``accel`` (N, 3) m/s² (body),
    ``gnss_time`` (M,) s, ``gnss_ned`` (M, 3) m, ``pole_length_m``, and ``truth``: ``C``
    (N, 3, 3) true attitudes, ``tip_ned`` (3,) m (the origin), ``heading_deg`` (initial
    true heading = misalignment), ``hold_tilt_deg`` (mean tilt in the hold), ``max_tilt_deg``,
    ``gyro_bias`` rad/s, ``accel_bias`` m/s², ``config``.
    """
    cfg = config or SwingConfig()
    rng = np.random.default_rng(seed)
    wob = (rng.uniform(0.3, 2.5, (3, 3)), rng.uniform(0, 2 * np.pi, (3, 3)),
           rng.uniform(0.3, 1.0, (3, 3)))
    duration = cfg.level_s + cfg.move_s + cfg.swing_s + cfg.hold_s
    dt = 1.0 / cfg.imu_rate_hz
    n = int(round(duration / dt)) + 1
    t = np.arange(n) * dt
    # scale the amplitude so that the largest tilt equals the configured one
    scale = 1.0
    for _ in range(3):
        C = _matrices(_angles(cfg, t, wob, scale))
        max_tilt = math.degrees(float(np.max(np.arccos(np.clip(C[:, 2, 2], -1, 1)))))
        scale *= cfg.tilt_deg / max(max_tilt, 1e-6)
    length = cfg.pole_length_m
    tip = np.zeros(3)
    gyro, f, C = _imu_samples(cfg, t, wob, scale)
    p = tip - C[:, :, 2] * length
    bg = np.radians(np.array(cfg.gyro_bias_deg_s))
    ba = np.array(cfg.accel_bias_m_s2)
    gyro = gyro + bg + _noise(rng, math.radians(cfg.gyro_noise_deg_s_rthz)
                              * math.sqrt(cfg.imu_rate_hz), gyro.shape, cfg.imu_noise_taps)
    f = f + ba + _noise(rng, cfg.accel_noise_m_s2_rthz * math.sqrt(cfg.imu_rate_hz), f.shape,
                        cfg.imu_noise_taps)
    # GNSS epochs on the IMU grid (every imu_rate/gnss_rate samples), a gap in the swing
    stride = max(1, int(round(cfg.imu_rate_hz / cfg.gnss_rate_hz)))
    idx = np.arange(int(rng.integers(0, stride)), n, stride)
    if cfg.gap_s > 0:
        t_gap = cfg.level_s + cfg.move_s + rng.uniform(0.2, 0.7) * cfg.swing_s
        idx = idx[(t[idx] < t_gap) | (t[idx] >= t_gap + cfg.gap_s)]
    sig = np.array([cfg.gnss_sigma_h_m, cfg.gnss_sigma_h_m, cfg.gnss_sigma_v_m])
    gnss = p[idx] + rng.normal(0, 1, (idx.size, 3)) * sig
    if cfg.gnss_outliers:
        bad = rng.choice(idx.size, size=min(cfg.gnss_outliers, idx.size), replace=False)
        jump = rng.normal(0, 1, (bad.size, 3))
        jump /= np.linalg.norm(jump, axis=1)[:, None]
        gnss[bad] += jump * rng.uniform(0.05, 0.15, (bad.size, 1))
    hold = t >= duration - cfg.hold_s
    tilt = np.degrees(np.arccos(np.clip(C[:, 2, 2], -1, 1)))
    return {
        "time": t, "gyro": gyro, "accel": f, "gnss_time": t[idx] - cfg.gnss_time_offset_s,
        "gnss_ned": gnss,
        "pole_length_m": length,
        "truth": {"C": C, "tip_ned": tip,
                  "heading_deg": math.degrees(math.atan2(C[0, 1, 0], C[0, 0, 0])),
                  "hold_tilt_deg": float(tilt[hold].mean()), "max_tilt_deg": float(tilt.max()),
                  "gyro_bias": bg, "accel_bias": ba, "config": cfg},
    }
