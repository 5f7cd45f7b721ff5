"""GNSS-minus-IMU clock offset from the vehicle's manoeuvres, without a filter pass.

Two rates that the GNSS and the IMU both see, each compared as a difference over a span
``[t_{k−m}, t_{k+m}]`` of about :data:`SPAN_S` (long enough to average a standalone
receiver's course noise, short against a turn):

* **turns**: the change of the GNSS course (direction of the horizontal velocity) against
  the gyro's rotation about the local vertical — angle increments projected on the
  body-frame down direction (the mean specific force over :data:`DOWN_WINDOW_S`, so any
  mounting and a hand-held IMU work);
* **speed changes**: the change of the GNSS horizontal speed against the velocity
  increments along the vehicle's forward axis made horizontal (down direction over
  :data:`LONG_DOWN_WINDOW_S`; a fixed mounting, so not used for a hand-held IMU whose
  forward axis is not the walking direction — its fit is kept only when its gain is near
  one).

A span's GNSS change equals the IMU's integral over the same span moved by the offset
*s*: ``y_k = a·(Ψ(t_{k+m}+s) − Ψ(t_{k−m}+s)) / (t_{k+m} − t_{k−m}) + b`` with a gain *a*
and a bias *b* per signal, both series high-passed alike (:data:`HIGH_PASS_S`). *s*
minimises the squared residuals on a 2 ms grid refined by a parabola; its σ is the
Gauss–Newton one inflated by the residuals' autocorrelation (overlapping spans share
epochs): ``σ² = σ²_GN (1 + 2 Σ ρ_l)`` summed while ρ_l > 0. This costs no filter pass
(about a second).

The signal with the smaller σ gives the offset, the other is the second opinion. They are
not pooled: noise-free simulated drives show the speed signal 10–20 ms off (the road
grade and the lever arm leak into the along-track specific force), the turns within 2 ms
once the antenna's lever arm is taken out; on a highway (comma2k19) the speed changes
carry more timing than the few turns.

The GNSS velocity is differenced from the positions, never the receiver's own: a
receiver's velocity leaves its navigation filter late (rtklibexplorer drive: the course of
the receiver velocity lags that of the positions by ≈130 ms), and the smoother uses the
positions.

Convention: the offset is what :func:`.recordings.shifted` applies — the GNSS epoch
tagged *t* happened at IMU time *t + s*.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.gins_smoother.io import GnssData, ImuData

#: Horizontal speed (m/s) below which the GNSS course is too noisy to use.
MIN_SPEED = 0.5
#: Searched offsets (s) and grid step (s).
HALF_RANGE_S = 1.0
STEP_S = 0.002
#: Time (s) over which the GNSS course and speed are differenced.
SPAN_S = 1.0
#: Windows (s) of the mean specific force that gives the down direction in the body frame:
#: short for the rotation about the vertical (follows a hand-held IMU), long for the
#: horizontal forward axis (not tilted by the vehicle's own acceleration).
DOWN_WINDOW_S = 4.0
LONG_DOWN_WINDOW_S = 30.0
#: Slowly varying biases (gyro bias, road grade leaking into the along-track specific
#: force) are removed from both series by subtracting their running mean over this (s).
HIGH_PASS_S = 10.0
#: A signal's gain must lie in this range to count (the IMU and the GNSS see one motion).
GAIN_OK = (0.7, 1.4)


@dataclass
class _Signal:
    """One compared rate: GNSS differences ``y`` over spans ``(ta, tb)`` and the IMU's
    cumulative integral ``cum`` at ``t``."""

    name: str
    y: np.ndarray
    ta: np.ndarray
    tb: np.ndarray
    t: np.ndarray
    cum: np.ndarray

    def fit(self, s: float):
        """Residuals, gain, bias and the IMU mean rates at offset *s* (both series
        high-passed alike: slowly varying biases do not carry timing)."""
        r = _high_pass((np.interp(self.tb + s, self.t, self.cum)
                        - np.interp(self.ta + s, self.t, self.cum)) / (self.tb - self.ta),
                       self.ta)
        y = _high_pass(self.y, self.ta)
        A = np.column_stack([r, np.ones_like(r)])
        coef, *_ = np.linalg.lstsq(A, y, rcond=None)
        return y - A @ coef, float(coef[0]), float(coef[1]), r


def _high_pass(x: np.ndarray, t: np.ndarray) -> np.ndarray:
    """*x* minus its running mean over :data:`HIGH_PASS_S` (by epoch count)."""
    if x.size < 5:
        return x
    step = float(np.median(np.diff(t)))
    n = max(3, min(x.size, int(round(HIGH_PASS_S / step))) | 1)
    pad = np.pad(x, n // 2, mode="edge")
    return x - np.convolve(pad, np.ones(n) / n, mode="valid")


@dataclass(frozen=True)
class ClockOffset:
    """Estimated GNSS-minus-IMU clock offset.

    ``offset_s`` and its 1σ ``sigma_s``; ``epochs`` used; ``signals``: per signal used
    (``turns``, ``speed``) its own offset and σ (s), gain (≈1) and correlation of the GNSS
    and IMU rates at the common offset.
    """

    offset_s: float
    sigma_s: float
    epochs: int
    signals: dict = field(default_factory=dict)

    def text(self) -> str:
        from hydrosync_core.numfmt import value_sigma

        parts = []
        for name, v in self.signals.items():
            what = (f"from the {name} (r = {v['correlation']:.2f})" if v.get("used") else
                    f"{name} alone "
                    f"{value_sigma(v['offset_s'] * 1e3, v['sigma_s'] * 1e3, sign=True)} ms")
            parts.append(what)
        return (f"GNSS−IMU clock offset "
                f"{value_sigma(self.offset_s * 1e3, self.sigma_s * 1e3, sign=True)} ms "
                f"({'; '.join(parts)}; {self.epochs} GNSS spans, no filter pass)")


def _down(imu: ImuData, window_s: float) -> np.ndarray:
    """Unit down direction in the body frame at each IMU epoch (mean specific force over
    *window_s*, reversed)."""
    step = float(np.median(np.diff(imu.time)))
    n = max(3, min(imu.time.size, int(round(window_s / step))))
    kern = np.ones(n) / n
    f = np.column_stack([np.convolve(imu.inc[:, 3 + c], kern, mode="same") for c in range(3)])
    norm = np.linalg.norm(f, axis=1)
    return -f / np.where(norm > 0, norm, 1.0)[:, None]


def vertical_angle(imu: ImuData) -> np.ndarray:
    """Cumulative rotation about the local vertical (rad, clockwise seen from above)."""
    return np.cumsum(np.einsum("ij,ij->i", imu.inc[:, 0:3], _down(imu, DOWN_WINDOW_S)))


def forward_velocity(imu: ImuData, forward_b) -> np.ndarray:
    """Cumulative velocity increments (m/s) along the horizontal part of *forward_b* (the
    vehicle's forward axis in the body frame)."""
    d = _down(imu, LONG_DOWN_WINDOW_S)
    fwd = np.asarray(forward_b, float)[None, :] - np.einsum("j,ij->i", forward_b, d)[:, None] * d
    fwd /= np.linalg.norm(fwd, axis=1, keepdims=True)
    return np.cumsum(np.einsum("ij,ij->i", imu.inc[:, 3:6], fwd))


def _spans(gnss: GnssData, speed: np.ndarray, min_speed: float, span_s: float):
    """Epoch pairs ``(k−m, k+m)`` about *span_s* apart with every epoch between them faster
    than *min_speed*: index arrays ``a``, ``b``."""
    step = float(np.median(np.diff(gnss.time)))
    m = max(1, int(round(0.5 * span_s / step)))
    if gnss.time.size <= 2 * m:
        return np.zeros(0, int), np.zeros(0, int)
    a = np.arange(gnss.time.size - 2 * m)
    b = a + 2 * m
    fast = np.where(np.isfinite(speed), speed, 0.0) >= min_speed
    slow_run = np.convolve(~fast, np.ones(2 * m + 1), mode="valid")
    dt = gnss.time[b] - gnss.time[a]
    ok = (slow_run == 0) & (dt > 0) & (dt <= 2 * m * step * 1.5)
    return a[ok], b[ok]


def _imu_point_velocity(imu: ImuData, gnss: GnssData, v_ant: np.ndarray, lever) -> np.ndarray:
    """GNSS velocity moved from the antenna to the IMU: ``v − C(ω × l)`` with the yaw rate
    only and the heading taken as the course (a car without sideslip). An antenna *l_x*
    ahead of the IMU turns ahead of it: uncorrected, that reads as a clock offset of
    ``l_x / v`` (50 ms for 0.5 m at 10 m/s)."""
    lever = np.asarray(lever, float)
    if not np.any(lever[:2]):
        return v_ant
    psi = vertical_angle(imu)
    h = 0.25
    wz = (np.interp(gnss.time + h, imu.time, psi)
          - np.interp(gnss.time - h, imu.time, psi)) / (2 * h)
    course = np.arctan2(v_ant[:, 1], v_ant[:, 0])
    bx, by = -wz * lever[1], wz * lever[0]  # (ω × l) in b, horizontal part
    c, s_ = np.cos(course), np.sin(course)
    out = v_ant.copy()
    out[:, 0] -= c * bx - s_ * by
    out[:, 1] -= s_ * bx + c * by
    return out


def _signals(imu: ImuData, gnss: GnssData, min_speed: float, span_s: float, forward_b,
             half_range_s: float, lever) -> list[_Signal]:
    from hydrosync_core.methods.gins_smoother.alignment import gnss_velocity

    # positions only: a receiver's own velocity comes out of its navigation filter late
    # (rtklibexplorer drive: its course lags the positions' by 130 ms)
    positions = GnssData(gnss.time, gnss.llh, gnss.std, gnss.source)
    v = _imu_point_velocity(imu, gnss, gnss_velocity(positions), lever)
    speed = np.hypot(v[:, 0], v[:, 1])
    course = np.arctan2(v[:, 1], v[:, 0])
    a, b = _spans(gnss, speed, min_speed, span_s)
    ta, tb = gnss.time[a], gnss.time[b]
    inside = (ta - half_range_s > imu.time[0]) & (tb + half_range_s < imu.time[-1])
    a, b, ta, tb = a[inside], b[inside], ta[inside], tb[inside]
    turns = np.angle(np.exp(1j * (course[b] - course[a]))) / (tb - ta)
    accel = (speed[b] - speed[a]) / (tb - ta)
    out = [_Signal("turns", turns, ta, tb, imu.time, vertical_angle(imu))]
    if forward_b is not None:
        out.append(_Signal("speed", accel, ta, tb, imu.time, forward_velocity(imu, forward_b)))
    return out


def _sigma(sig: _Signal, s: float) -> tuple[float, float, float, float]:
    """Gauss–Newton σ of *s* from one signal (autocorrelation-inflated), its gain,
    correlation and residual std."""
    e, a, _b, r = sig.fit(s)
    h = 0.005
    dr = (sig.fit(s + h)[3] - sig.fit(s - h)[3]) / (2 * h)
    J = np.column_stack([a * dr, r, np.ones_like(r)])
    res_var = float(e @ e) / max(1, e.size - 3)
    try:
        cov = np.linalg.inv(J.T @ J) * res_var
    except np.linalg.LinAlgError:
        return math.inf, a, 0.0, math.sqrt(res_var)
    corr = float(np.corrcoef(_high_pass(sig.y, sig.ta), r)[0, 1]) if np.std(r) > 0 else 0.0
    return (math.sqrt(max(cov[0, 0], 0.0) * _autocorr_factor(e)), a, corr,
            math.sqrt(res_var))


def _autocorr_factor(e: np.ndarray, max_lag: int = 20) -> float:
    """``1 + 2 Σ ρ_l`` over the leading positive autocorrelations of *e* (≥ 1)."""
    e = e - e.mean()
    v = float(e @ e)
    total = 1.0
    for lag in range(1, min(max_lag, e.size // 4)):
        rho = float(e[:-lag] @ e[lag:]) / v
        if rho <= 0:
            break
        total += 2 * rho
    return total


def _grid_min(grid: np.ndarray, cost: np.ndarray) -> float:
    i = int(np.clip(np.argmin(cost), 1, grid.size - 2))
    c2, c1, _ = np.polyfit(grid[i - 1:i + 2] - grid[i], cost[i - 1:i + 2], 2)
    s = grid[i] + (float(-c1 / (2 * c2)) if c2 > 0 else 0.0)
    return float(np.clip(s, grid[0], grid[-1]))


def estimate_clock_offset(imu: ImuData, gnss: GnssData, min_speed: float = MIN_SPEED,
                          half_range_s: float = HALF_RANGE_S, span_s: float = SPAN_S,
                          forward_b=(1.0, 0.0, 0.0), lever_arm_m=(0.0, 0.0, 0.0)
                          ) -> ClockOffset:
    """GNSS-minus-IMU clock offset (module docstring).

    Parameters
    ----------
    imu : ImuData
        Angle and velocity increments, body frame.
    gnss : GnssData
        Positions (and the receiver's velocity where given).
    min_speed : float
        Horizontal speed (m/s) below which a span is not used.
    half_range_s : float
        The offset is searched in ±half_range_s.
    span_s : float
        Course and speed differences over about this time (s).
    forward_b : (3,) or None
        The vehicle's forward axis in the body frame (None: no speed signal).
    lever_arm_m : (3,)
        Antenna in the body frame (m): its velocity is moved to the IMU first.

    Raises
    ------
    InputError
        Too few moving spans, no manoeuvre to time, or the best offset at the search edge.
    """
    sigs = _signals(imu, gnss, min_speed, span_s, forward_b, half_range_s, lever_arm_m)
    n = sigs[0].y.size
    if n < 20:
        raise InputError(gnss.source, f"only {n} GNSS spans faster than {min_speed} m/s "
                         "inside the IMU span: cannot estimate the clock offset (give "
                         "--clock-offset)")
    grid = np.arange(-half_range_s, half_range_s + 1e-12, STEP_S)
    per = {}
    for sig in sigs:
        s_i = _grid_min(grid, np.array([float(np.sum(sig.fit(s)[0] ** 2)) for s in grid]))
        sd, gain, corr, _res_sd = _sigma(sig, s_i)
        if (GAIN_OK[0] <= gain <= GAIN_OK[1] and corr > 0.2 and math.isfinite(sd)
                and abs(s_i) < half_range_s - STEP_S):
            per[sig.name] = {"offset_s": s_i, "sigma_s": sd, "gain": gain, "correlation": corr}
    if not per:
        raise InputError(gnss.source, "the GNSS course and speed changes do not line up "
                         f"with the IMU within ±{half_range_s:g} s (too little "
                         "manoeuvring, or another motion): give --clock-offset")
    used = min(per, key=lambda k: per[k]["sigma_s"])
    best = per[used]
    per[used]["used"] = True
    return ClockOffset(best["offset_s"], best["sigma_s"], n, per)
