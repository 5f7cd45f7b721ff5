"""GNSS/INS integration: alignment, forward closed-loop EKF and RTS smoothing (Wang et al.).

:func:`run_gins` is the pure function over arrays that the command, the project run and the
benchmark call. The compiled loops are in :mod:`.kernel`; this module prepares their
inputs (alignment, stationary detection, noise), runs the forward pass in chunks (progress
and cancel between chunks), the backward RTS pass over the stored nodes, and turns the
result into IMU-rate trajectories with standard deviations.

Memory: the forward and smoothed trajectories at IMU rate (10 float64 each per epoch) plus,
per smoother node (GNSS and motion-constraint epochs, at least one per
``max_node_interval_s``), two total states and three ns × ns matrices — about 80 MB for an
hour at 200 Hz with 1 Hz GNSS and 2 Hz constraints.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.gins_smoother import kernel as K  # noqa: N812
from hydrosync_core.methods.gins_smoother.alignment import initial_state
from hydrosync_core.methods.gins_smoother.config import (
    SensorConfig,
    initial_covariance,
    noise_densities,
)
from hydrosync_core.methods.gins_smoother.io import GnssData, ImuData
from hydrosync_core.methods.gins_smoother.params import RAN, GinsParams
from hydrosync_core.progress import check_cancel, report
from hydrosync_core.rotations import euler_zyx_matrix

CHUNK_S = 60.0  # seconds of IMU data per compiled chunk (progress / cancel granularity)


@dataclass
class Trajectory:
    """A trajectory at IMU rate with 1σ.

    ``llh`` (n, 3): lat, lon (deg), h (m); ``vel`` (n, 3) NED m/s; ``att`` (n, 3) roll,
    pitch, yaw (deg, yaw in [0, 360)); ``pos_std`` N/E/D m, ``vel_std`` m/s, ``att_std``
    roll/pitch/yaw deg.
    """

    time: np.ndarray
    llh: np.ndarray
    vel: np.ndarray
    att: np.ndarray
    pos_std: np.ndarray
    vel_std: np.ndarray
    att_std: np.ndarray


@dataclass
class GinsResult:
    """Forward and smoothed solutions and the diagnostics of one run.

    ``imu_errors_*``: per node ``time`` and the estimated gyro bias (deg/h), accelerometer
    bias (mGal) and, with 21 states, scale factors (ppm), each (nodes, 3).
    ``gnss``: ``time``, ``innovation`` (forward, computed − measured antenna position,
    NED m, before the update), ``residual`` (smoothed trajectory minus measurement, NED m),
    ``used`` (1 if the forward filter applied it), ``innovation_cov`` (its predicted
    covariance, n × 3 × 3).
    ``gnss_model``: the GNSS noise model used and what it was computed from
    (:func:`run_gins`; ``summary`` is one line for the user).
    """

    forward: Trajectory
    smoothed: Trajectory | None
    imu_errors_forward: dict
    imu_errors_smoothed: dict | None
    gnss: dict
    alignment: dict
    counts: dict = field(default_factory=dict)
    gnss_model: dict = field(default_factory=dict)


def quat_to_euler(q: np.ndarray) -> np.ndarray:
    """Roll, pitch, yaw (deg; yaw in [0, 360)) of quaternions (n, 4) ``[w, x, y, z]``."""
    w, x, y, z = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    roll = np.arctan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = np.arcsin(np.clip(2 * (w * y - z * x), -1, 1))
    yaw = np.arctan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
    out = np.degrees(np.column_stack([roll, pitch, yaw]))
    out[:, 2] = np.mod(out[:, 2], 360.0)
    return out


def euler_to_quat(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Quaternion ``[w, x, y, z]`` of ``C_b^n = Rz(yaw)·Ry(pitch)·Rx(roll)`` (radians)."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return np.array([cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy,
                     cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy])


def euler_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    return K.qdcm(euler_to_quat(roll, pitch, yaw))


def detect_static(imu: ImuData, window_s: float, acc_std: float, gyro_dps: float
                  ) -> np.ndarray:
    """IMU epochs in a quiet window: specific-force std below *acc_std* (m/s², per axis)
    and mean angular-rate magnitude below *gyro_dps* (deg/s) over a centred window.

    Quiet is necessary, not sufficient, for standstill (a vehicle cruising straight at
    constant speed is quiet too): the filter applies a ZUPT only when its own speed is
    below ``zupt_speed`` as well.
    """
    t = imu.time
    dt = np.diff(t, prepend=t[0] - np.median(np.diff(t)))
    dt = np.where((dt > 0) & (dt < 0.1), dt, np.median(np.diff(t)))
    f = imu.inc[:, 3:6] / dt[:, None]
    w = np.linalg.norm(imu.inc[:, 0:3], axis=1) / dt
    n = max(3, int(round(window_s / float(np.median(dt)))))
    if t.size < n:
        return np.zeros(t.size, bool)
    kern = np.ones(n) / n
    var = np.zeros(t.size)
    for c in range(3):
        m = np.convolve(f[:, c], kern, mode="same")
        m2 = np.convolve(f[:, c] ** 2, kern, mode="same")
        var = np.maximum(var, m2 - m * m)
    wm = np.convolve(w, kern, mode="same")
    return (var < acc_std ** 2) & (wm < math.radians(gyro_dps))


def _std_from_diag(d: np.ndarray, yaw_deg: np.ndarray) -> tuple:
    pos = np.sqrt(np.maximum(d[:, 0:3], 0))
    vel = np.sqrt(np.maximum(d[:, 3:6], 0))
    psi = np.radians(yaw_deg)
    c2, s2 = np.cos(psi) ** 2, np.sin(psi) ** 2
    roll = np.sqrt(np.maximum(c2 * d[:, 6] + s2 * d[:, 7], 0))
    pitch = np.sqrt(np.maximum(s2 * d[:, 6] + c2 * d[:, 7], 0))
    yaw = np.sqrt(np.maximum(d[:, 8], 0))
    return pos, vel, np.degrees(np.column_stack([roll, pitch, yaw]))


def _interp_diag(t, node_t, start_d, end_d) -> np.ndarray:
    """Diagonal variance at IMU rate: linear between ``start_d[k]`` at node k and
    ``end_d[k+1]`` just before node k+1."""
    k = np.clip(np.searchsorted(node_t, t, side="right") - 1, 0, node_t.size - 1)
    k1 = np.minimum(k + 1, node_t.size - 1)
    span = node_t[k1] - node_t[k]
    w = np.where(span > 0, (t - node_t[k]) / np.where(span > 0, span, 1), 0.0)[:, None]
    at_node = np.isin(t, node_t)
    out = (1 - w) * start_d[k] + w * end_d[k1]
    out[at_node] = start_d[k[at_node]]
    return out


def _trajectory(t, traj, diag, node_t, diag_end) -> Trajectory:
    att = quat_to_euler(traj[:, 6:10])
    d = _interp_diag(t, node_t, diag, diag_end)
    ps, vs, as_ = _std_from_diag(d, att[:, 2])
    return Trajectory(t, np.column_stack([np.degrees(traj[:, 0:2]), traj[:, 2]]),
                      traj[:, 3:6].copy(), att, ps, vs, as_)


def _imu_errors(node_t, xs, ns) -> dict:
    out = {"time": node_t, "gyro_bias_dph": np.degrees(xs[:, 10:13]) * 3600,
           "acc_bias_mgal": xs[:, 13:16] / 1e-5}
    if ns in (18, 24):
        out["gnss_error_m"] = xs[:, K.GNSS_X:K.GNSS_X + 3].copy()
    if ns >= 21:
        out["gyro_scale_ppm"] = xs[:, 16:19] * 1e6
        out["acc_scale_ppm"] = xs[:, 19:22] * 1e6
    return out


def gnss_residuals(gnss: GnssData, traj: Trajectory, lever) -> np.ndarray:
    """Trajectory (interpolated, lever arm applied) minus measured antenna, NED m."""
    t = traj.time
    inside = (gnss.time >= t[0]) & (gnss.time <= t[-1])
    out = np.full((gnss.time.size, 3), np.nan)
    if not inside.any():
        return out
    tg = gnss.time[inside]
    j = np.clip(np.searchsorted(t, tg), 1, t.size - 1)
    w = ((tg - t[j - 1]) / (t[j] - t[j - 1]))[:, None]
    llh = (1 - w) * traj.llh[j - 1] + w * traj.llh[j]
    att = np.radians(traj.att[j])
    lat = np.radians(llh[:, 0])
    rm, rn = np.vectorize(K.radii)(lat)
    la = np.array([euler_matrix(*a) @ np.asarray(lever) for a in att]) if tg.size < 20000 \
        else _lever_vec(att, lever)
    g = gnss.llh[inside]
    dn = np.radians(llh[:, 0] - g[:, 0]) * (rm + llh[:, 2]) + la[:, 0]
    de = np.radians(llh[:, 1] - g[:, 1]) * (rn + llh[:, 2]) * np.cos(lat) + la[:, 1]
    dd = -(llh[:, 2] - g[:, 2]) + la[:, 2]
    out[inside] = np.column_stack([dn, de, dd])
    return out


def _lever_vec(att_rad: np.ndarray, lever) -> np.ndarray:
    C = euler_zyx_matrix(att_rad[:, 0], att_rad[:, 1], att_rad[:, 2])
    return C @ np.asarray(lever, float)


@dataclass
class NoiseModel:
    """The noise model of one pass beyond the configuration: the IMU white noise (ARW and
    VRW) × ``imu_scale``; GNSS white noise of std ``white_scale`` × the file's std (per
    N/E/D) plus, when ``corr_std`` is non-zero, a first-order Gauss–Markov GNSS error (std
    ``corr_std`` m N/E/D, correlation time ``corr_time_s``) estimated as 3 extra states,
    its driving noise ``2σ²/τ`` × ``corr_q_scale`` per N/E/D (None: × 1) — the steady σ
    is the absolute accuracy of a fix, which innovations cannot see; the driving noise is
    how fast that error wanders, which they can."""

    white_scale: np.ndarray
    corr_std: np.ndarray
    corr_time_s: float = 0.0
    imu_scale: float = 1.0
    corr_q_scale: np.ndarray | None = None

    @property
    def correlated(self) -> bool:
        return bool(np.any(self.corr_std > 0) and self.corr_time_s > 0)


#: The noise model is accepted when the RMS of the normalised GNSS innovations lies in
#: this range for every component and their autocorrelation at 1 s stays below RHO_MAX.
RMS_OK = (0.8, 1.25)
RHO_MAX = 0.3
#: Below this white scale the file's σ is not explained by the white scatter: the rest is
#: modelled as a time-correlated GNSS error.
K_WHITE_MIN = 0.9
#: Range of the factor on the IMU white noise (ARW, VRW) searched in factor-2 steps, and
#: GNSS correlation times (s) tried, by maximum likelihood of the innovations.
IMU_SCALE_RANGE = (1.0 / 16.0, 64.0)
TAU_GRID = (3.0, 10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0)
#: Lags (fix to fix) of the Ljung–Box whiteness test of the innovations, and the p-value
#: below which they are reported as still correlated.
LB_LAGS = 10
LB_ALPHA = 0.01
LB_RHO_MIN = 0.1
#: Factors on the Gauss–Markov driving noise searched per N/E/D by maximum likelihood:
#: a coarse decade grid, then steps of 10^0.5 and 10^0.25 around each axis's best.
Q_COARSE = (1e-3, 1e-2, 1e-1, 1.0, 10.0)
Q_REFINE = (10 ** 0.5, 10 ** 0.25)
#: When the innovations stay correlated fix to fix (a receiver whose fixes are its own
#: filter's output): every k-th fix for k in THIN_FACTORS, the first that leaves them white
#: with a mean square in MS_OK, at most THIN_MAX_INTERVAL_S between the fixes kept.
THIN_FACTORS = (2, 5, 10)
THIN_MAX_INTERVAL_S = 1.0
MS_OK = (0.8, 1.2)


def _lag_pairs(tt: np.ndarray, lag_s: float) -> tuple[np.ndarray, np.ndarray]:
    """Index pairs (i, j) of epochs *tt* whose separation is the epoch step nearest to
    *lag_s* (within half the median step)."""
    if tt.size < 3:
        return np.zeros(0, int), np.zeros(0, int)
    step = float(np.median(np.diff(tt)))
    k = max(1, int(round(lag_s / step)))
    i = np.arange(tt.size - k)
    j = i + k
    ok = np.abs((tt[j] - tt[i]) - k * step) <= 0.5 * step
    return i[ok], j[ok]


def innovation_check(gnss_out: dict, lag_s: float = 1.0) -> dict:
    """Normalised GNSS innovations ``ν / √S`` (each component by its own predicted std)
    of the forward filter: RMS per N/E/D (1 if the noise model is right), autocorrelation at
    *lag_s* (0 if right: a Kalman filter's innovations are white), count, and the mean
    negative log-likelihood per fix ``½(log det S + νᵀS⁻¹ν)`` (for comparing models)."""
    used = gnss_out["used"].astype(bool)
    nu = gnss_out["innovation"][used]
    S = gnss_out["innovation_cov"][used]
    tt = gnss_out["time"][used]
    if nu.shape[0] < 5:
        return {"fixes": int(nu.shape[0]), "rms": None, "rho_1s": None, "nll": None}
    sd = np.sqrt(np.einsum("kii->ki", S))
    u = nu / sd
    i, j = _lag_pairs(tt, lag_s)
    rho = [float(np.sum(u[i, c] * u[j, c]) / np.sqrt(np.sum(u[i, c] ** 2) *
                                                    np.sum(u[j, c] ** 2)))
           if i.size > 3 else None for c in range(3)]
    _sign, logdet = np.linalg.slogdet(S)
    m = np.einsum("ki,kij,kj->k", nu, np.linalg.inv(S), nu)
    lb = [ljung_box(u[:, c]) for c in range(3)]
    return {"fixes": int(nu.shape[0]), "rms": np.sqrt(np.mean(u * u, axis=0)).tolist(),
            "rho_1s": rho, "nll": float(np.mean(0.5 * (logdet + m))),
            "rho_lag1": [r[0] for r in lb], "ljung_box_p": [r[1] for r in lb],
            "ljung_box_lags": lb[0][2], "rho_max": [r[3] for r in lb]}


def still_correlated(check: dict) -> bool:
    """Innovations correlated fix to fix, significantly (Ljung–Box p < :data:`LB_ALPHA`)
    *and* materially (some |ρ_l| ≥ :data:`LB_RHO_MIN`; thousands of fixes make a ρ of
    0.03 significant, which changes no σ)."""
    return any(p == p and p < LB_ALPHA and r >= LB_RHO_MIN
               for p, r in zip(check.get("ljung_box_p", []), check.get("rho_max", []),
                               strict=False))


def ljung_box(u: np.ndarray, max_lags: int = LB_LAGS) -> tuple[float, float, int, float]:
    """Whiteness of a series of normalised innovations (consecutive fixes): the
    autocorrelation at lag 1, the Ljung–Box p-value over ``L = min(max_lags, n/5)`` lags,
    ``Q = n(n+2) Σ ρ_l²/(n−l)`` against χ²(L) (small p: correlated — a Kalman filter with
    the right model has white innovations), L, and the largest |ρ_l|."""
    from scipy.stats import chi2

    n = u.size
    L = int(min(max_lags, n // 5))
    if L < 1:
        return float("nan"), float("nan"), 0, float("nan")
    e = u - u.mean()
    v = float(e @ e)
    rho = np.array([float(e[:-k] @ e[k:]) / v for k in range(1, L + 1)])
    q = n * (n + 2) * float(np.sum(rho ** 2 / (n - np.arange(1, L + 1))))
    return float(rho[0]), float(chi2.sf(q, L)), L, float(np.max(np.abs(rho)))


def _consistent(check: dict) -> bool:
    if check["rms"] is None:
        return True
    rho = [r for r in check["rho_1s"] if r is not None]
    return (all(RMS_OK[0] <= r <= RMS_OK[1] for r in check["rms"])
            and (not rho or max(rho) < RHO_MAX))


def white_scale_from_innovations(gnss_out: dict, scale: np.ndarray) -> np.ndarray | None:
    """Scale of the file's GNSS σ (per N/E/D) that the forward innovations support: the
    pass ran with ``R = scale²·R_file`` and predicted the innovation covariance
    ``S = HPHᵀ + R``; the new scale is ``scale · √mean(ν²/S)``, the fixed point of which
    makes the normalised innovations' mean square 1 (an innovation-based adaptive
    estimate, Mohamed & Schwarz 1999, in multiplicative form so that it stays positive
    when ``HPHᵀ`` alone exceeds the scatter). Iterated by the caller (P depends on R);
    bounded to [10⁻³, 10³]. None with fewer than 10 fixes."""
    used = gnss_out["used"].astype(bool)
    if used.sum() < 10:
        return None
    nu = gnss_out["innovation"][used]
    S = np.einsum("kii->ki", gnss_out["innovation_cov"][used])
    return np.clip(scale * np.sqrt(np.mean(nu * nu / S, axis=0)), 1e-3, 1e3)


def run_gins(imu: ImuData, gnss: GnssData, cfg: SensorConfig, params: GinsParams | None = None,
             progress=None, cancel=None) -> GinsResult:
    """Forward closed-loop EKF and (unless ``params.smooth`` is off) RTS smoothing.

    With ``params.gnss_noise == "auto"`` (the default) the noise model is checked against
    the data after the first pass: the forward GNSS innovations normalised by their own
    predicted std must have an RMS in :data:`RMS_OK` and an autocorrelation at 1 s below
    :data:`RHO_MAX`. If not, the model is re-estimated from the innovations
    (:func:`_estimate_model`: a factor on the IMU white noise and the GNSS white σ scale,
    and, when the innovations stay time-correlated, a Gauss–Markov GNSS error with its
    driving noise per axis) and, if they are then still correlated fix to fix, the fixes
    are thinned to the first rate at which they are white (:func:`_thin_until_white`; only
    the fixes kept are used, ``counts["gnss_thinned_every"]``); the run is repeated. What
    was done is in ``result.gnss_model`` (and its ``summary`` line).

    Parameters
    ----------
    imu : ImuData
        Increments in the body frame (FRD), time-sorted.
    gnss : GnssData
        Antenna positions (deg, m) with N/E/D std (m).
    cfg : SensorConfig
        Initial state (or None parts for alignment), IMU noise, lever arm.
    params : GinsParams
        Processing options (scale-factor states, NHC, ZUPT, intervals, gate, GNSS noise).

    Returns
    -------
    GinsResult
    """
    p = params if params is not None else GinsParams()
    t = np.ascontiguousarray(imu.time, float)
    if t.size < 10:
        raise InputError(imu.source, "fewer than 10 IMU epochs")
    if gnss.time.size == 0:
        raise InputError(gnss.source, "no GNSS epochs")
    start = cfg.start_time if cfg.start_time is not None else t[0]
    end = cfg.end_time if cfg.end_time is not None else t[-1]
    i0 = int(np.searchsorted(t, start - 1e-9))
    i1 = int(np.searchsorted(t, end + 1e-9, side="right")) - 1
    if i0 >= t.size or i1 - i0 < 10:
        raise InputError(cfg.source or "config", f"processing interval {start} … {end} s holds "
                         "fewer than 10 IMU epochs", field="starttime")
    if gnss.time[-1] < t[i0] or gnss.time[0] > t[i1]:
        raise InputError(gnss.source, "no GNSS epoch inside the IMU time span (same time "
                         "scale, GPS seconds of week?)", field="time")
    quiet = detect_static(imu, p.zupt_window_s, p.zupt_acc_std, p.zupt_gyro_dps)
    i0, x0, cfg, align = initial_state(imu, gnss, cfg, i0, quiet, p)
    static = quiet if p.zupt else np.zeros(t.size, bool)
    base_std = np.asarray(gnss.std, float) * p.gnss_std_scale
    ctx = (imu, gnss, cfg, p, i0, i1, x0, static, align, base_std)
    model = NoiseModel(np.ones(3), np.zeros(3))
    adapt = p.gnss_noise == "auto"
    res = _pass(ctx, model, p.smooth, progress, cancel)
    first = check = innovation_check(res.gnss)
    estimated = False
    thin = 1
    if p.gnss_corr_time_s > 0 or (adapt and not _consistent(check)):
        model, check = _estimate_model(ctx, res, check, cancel)
        estimated = True
        if adapt and still_correlated(check):
            white = _thin_until_white(ctx, model, cancel)
            if white is not None:
                ctx, model, thin, check = white
        res = _pass(ctx, model, p.smooth, progress, cancel)
        check = innovation_check(res.gnss)
        if thin > 1:  # "used of in span" counts the fixes of the file, not those kept
            res.counts["gnss_epochs"] = int(((gnss.time > t[i0]) & (gnss.time <= t[i1])).sum())
            res.counts["gnss_thinned_every"] = thin
    info = {"mode": p.gnss_noise, "file_std_median_m": np.median(base_std, axis=0).tolist(),
            "gnss_std_scale": p.gnss_std_scale, "estimated": estimated,
            "model": "gauss-markov" if model.correlated else "white",
            "imu_noise_scale": model.imu_scale, "white_scale": model.white_scale.tolist(),
            "corr_std_m": model.corr_std.tolist() if model.correlated else None,
            "corr_time_s": model.corr_time_s if model.correlated else None,
            "corr_q_scale": (model.corr_q_scale.tolist() if model.correlated and
                             model.corr_q_scale is not None else None),
            "thinned_every": thin, "fixes_in_file": int(gnss.time.size),
            "tau_given": p.gnss_corr_time_s > 0, "first_check": first, "check": check}
    info["summary"] = _model_summary(info)
    res.gnss_model = info
    return res


def _model_summary(info: dict) -> str:
    """One line saying what the σ were computed from."""
    def f3(v):
        return "/".join(f"{x:.2g}" for x in v)

    def innov(chk):
        if chk.get("rms") is None:
            return "no GNSS innovations to check"
        rho = [r for r in chk["rho_1s"] if r is not None]
        text = (f"normalised GNSS innovations RMS N/E/D {f3(chk['rms'])}"
                + (f", autocorrelation at 1 s ≤ {max(rho):.2f}" if rho else ""))
        p = [x for x in chk.get("ljung_box_p", []) if x == x]
        if p and still_correlated(chk):
            text += (f", still correlated fix to fix (lag 1 {f3(chk['rho_lag1'])}, "
                     f"Ljung–Box p {'/'.join(f'{x:.0e}' for x in chk['ljung_box_p'])}: σ may "
                     "be optimistic)")
        elif p:
            text += (f", white (Ljung–Box p ≥ {min(p):.2g}, |ρ| ≤ "
                     f"{max(chk['rho_max']):.2f} over {chk['ljung_box_lags']} fixes)")
        return text
    if not info["estimated"]:
        return ("GNSS σ from the file" + (f" ×{info['gnss_std_scale']:g}"
                                          if info["gnss_std_scale"] != 1 else "")
                + " (white), IMU noise from the configuration; " + innov(info["check"]))
    text = "noise model estimated from the data (maximum likelihood of the GNSS innovations"
    text += (f", which were {innov(info['first_check'])[len('normalised GNSS innovations '):]}"
             " with the file's σ): ")
    if info["imu_noise_scale"] != 1:
        text += f"IMU white noise (ARW, VRW) ×{info['imu_noise_scale']:g}; "
    text += f"GNSS σ ×{f3(info['white_scale'])} (N/E/D, white)"
    if info["corr_std_m"] is not None:
        how = "given" if info["tau_given"] else "estimated"
        text += (f" plus a time-correlated GNSS error of σ {f3(info['corr_std_m'])} m, τ "
                 f"{info['corr_time_s']:g} s {how} (Gauss–Markov states"
                 + (f", driving noise ×{f3(info['corr_q_scale'])}"
                    if info.get("corr_q_scale") else "") + ")")
    if info.get("thinned_every", 1) > 1:
        text += (f"; every {info['thinned_every']}th GNSS fix used (consecutive fixes share "
                 "their error: the fewest thinned out that leaves the innovations white)")
    return text + "; now " + innov(info["check"])


def axis_nll(gnss_out: dict) -> np.ndarray | None:
    """Mean negative log-likelihood per fix of each innovation component on its own,
    ``½(log S_cc + ν_c²/S_cc)`` (N/E/D): the axes' GNSS errors are modelled apart, so
    each takes the driving noise its own innovations prefer. None with fewer than 10."""
    used = gnss_out["used"].astype(bool)
    if used.sum() < 10:
        return None
    nu = gnss_out["innovation"][used]
    S = np.einsum("kii->ki", gnss_out["innovation_cov"][used])
    return np.mean(0.5 * (np.log(S) + nu * nu / S), axis=0)


def _fit(ctx, m: NoiseModel, cancel, times: int = 2) -> tuple[dict, NoiseModel, dict]:
    """Settle the white GNSS scale of *m* on the innovations (:func:`white_scale_from_
    innovations`, *times* iterations; with a Gauss–Markov error its σ follows the part of
    the file's σ the white scale leaves, at least half). Returns the check, the model and
    the last pass's GNSS output."""
    med = np.median(ctx[9], axis=0)

    def run(model):
        check_cancel(cancel)
        return _pass(ctx, model, False, None, cancel).gnss

    r = run(m)
    for _ in range(times):
        k = white_scale_from_innovations(r, m.white_scale)
        if k is None:
            break
        corr = (med * np.sqrt(np.maximum(1.0 - np.minimum(k, 1.0) ** 2, 0.25))
                if m.correlated else np.zeros(3))
        m = NoiseModel(k, corr, m.corr_time_s, m.imu_scale, m.corr_q_scale)
        r = run(m)
    return innovation_check(r), m, r


def _driving_noise(ctx, m: NoiseModel, cancel) -> NoiseModel:
    """Per-axis factor on the Gauss–Markov driving noise by maximum likelihood of each
    axis's innovations (:func:`axis_nll`): the decade grid :data:`Q_COARSE` (every axis
    the same factor in a pass), then steps :data:`Q_REFINE` up and down from each axis's
    best. A horizontal and a vertical error of one receiver need not wander alike."""
    tried: list[tuple[np.ndarray, np.ndarray, NoiseModel]] = []

    def trial(q):
        _chk, fitted, r = _fit(ctx, NoiseModel(m.white_scale, m.corr_std, m.corr_time_s,
                                               m.imu_scale, np.asarray(q, float)), cancel)
        nll = axis_nll(r)
        if nll is not None:
            tried.append((np.asarray(q, float), nll, fitted))

    for q in Q_COARSE:
        trial(np.full(3, q))
    if not tried:
        return m
    for step in Q_REFINE:
        best = _best_per_axis(tried)
        trial(best * step)
        trial(best / step)
    return NoiseModel(m.white_scale, m.corr_std, m.corr_time_s, m.imu_scale,
                      _best_per_axis(tried))


def _best_per_axis(tried) -> np.ndarray:
    """The factor of each axis whose trial gave that axis the smallest likelihood cost."""
    nll = np.array([t[1] for t in tried])
    q = np.array([t[0] for t in tried])
    i = np.argmin(nll, axis=0)
    return q[i, np.arange(3)]


def _estimate_model(ctx, res: GinsResult, first_check: dict, cancel
                    ) -> tuple[NoiseModel, dict]:
    """Noise model by maximum likelihood of the GNSS innovations (:func:`run_gins`).

    1. IMU white-noise factor in factor-2 steps from 1 (up, then down, while the
       likelihood improves; within :data:`IMU_SCALE_RANGE`), with white GNSS noise whose
       scale is re-estimated from the innovations at each factor (:func:`_fit`);
    2. if the white scale leaves part of the file's σ unexplained (< :data:`K_WHITE_MIN`),
       the innovations of the best model are still correlated at 1 s (≥ RHO_MAX) or a
       correlation time is given: a Gauss–Markov GNSS error, its σ the part of the file's
       σ that the white scale leaves (at least half of it — the file's σ is taken as the
       accuracy of one fix, slowly varying errors included, which innovations cannot see),
       its correlation time over :data:`TAU_GRID` (or the given one), then the IMU factor
       again with it, and its driving noise per axis (:func:`_driving_noise`).

    Returns the model and the innovation check of a forward pass with it.
    """
    p = ctx[3]

    def best_of(models):
        best = None
        for m0 in models:
            chk, m, _r = _fit(ctx, m0, cancel)
            if chk["nll"] is not None and (best is None or chk["nll"] < best[0]["nll"]):
                best = (chk, m)
        return best

    def climb(make, start):
        """Best IMU factor by factor-2 steps up, then down, from *start* while the
        likelihood improves, within :data:`IMU_SCALE_RANGE`."""
        cache = {}

        def nll(q):
            if q not in cache:
                cache[q] = best_of([make(q)])
            return math.inf if cache[q] is None else cache[q][0]["nll"]
        q = start
        for step in (2.0, 0.5):
            while IMU_SCALE_RANGE[0] <= q * step <= IMU_SCALE_RANGE[1] and \
                    nll(q * step) < nll(q):
                q *= step
        nll(q)
        return cache[q]

    best = climb(lambda q: NoiseModel(np.ones(3), np.zeros(3), 0.0, q), 1.0)
    if best is None:
        m = NoiseModel(np.ones(3), np.zeros(3))
        return m, innovation_check(_pass(ctx, m, False, None, cancel).gnss)
    chk, m = best
    rho = [r for r in chk["rho_1s"] if r is not None]
    if p.gnss_corr_time_s > 0 or np.min(m.white_scale) < K_WHITE_MIN or \
            (rho and max(rho) >= RHO_MAX):
        taus = (p.gnss_corr_time_s,) if p.gnss_corr_time_s > 0 else TAU_GRID
        med = np.median(ctx[9], axis=0)
        corr = med * np.sqrt(np.maximum(1.0 - np.minimum(m.white_scale, 1.0) ** 2, 0.25))
        best = best_of(NoiseModel(m.white_scale, corr, float(tau), m.imu_scale)
                       for tau in taus) or best
        m = best[1]
        if m.correlated:  # the IMU factor again, with the Gauss-Markov GNSS error
            best = climb(lambda q: NoiseModel(m.white_scale, m.corr_std, m.corr_time_s, q),
                         m.imu_scale) or best
            best = (best[0], _driving_noise(ctx, best[1], cancel))
    chk, m, _r = _fit(ctx, best[1], cancel, 3)  # the white scale settled at the model
    return m, chk


def thinned(gnss: GnssData, every: int) -> GnssData:
    """Every *every*-th fix of *gnss* (from the first)."""
    k = slice(None, None, every)
    return GnssData(gnss.time[k], gnss.llh[k], gnss.std[k], gnss.source,
                    None if gnss.vel is None else gnss.vel[k])


def mean_square_ok(check: dict) -> bool:
    """Normalised innovations' mean square within :data:`MS_OK` on every axis."""
    return check.get("rms") is not None and all(
        MS_OK[0] <= r * r <= MS_OK[1] for r in check["rms"])


def _thin_until_white(ctx, model: NoiseModel, cancel):
    """The fixes thinned by the first factor of :data:`THIN_FACTORS` whose innovations,
    with the model's white scale and driving noise fitted again, are white (Ljung–Box,
    :func:`still_correlated`) with a mean square in :data:`MS_OK`; ``(ctx, model, factor,
    check)`` or None when no factor (keeping fixes at most :data:`THIN_MAX_INTERVAL_S`
    apart) does. Consecutive fixes of a receiver that filters its own solution share their
    error: used as independent, they make every σ optimistic; fewer fixes that are
    independent give σ that hold."""
    imu, gnss = ctx[0], ctx[1]
    step = float(np.median(np.diff(gnss.time))) if gnss.time.size > 1 else math.inf
    for k in THIN_FACTORS:
        if k * step > THIN_MAX_INTERVAL_S + 1e-9:
            break
        g = thinned(gnss, k)
        keep = np.arange(0, gnss.time.size, k)
        c = (imu, g) + ctx[2:9] + (ctx[9][keep],)
        m = _driving_noise(c, model, cancel) if model.correlated else model
        chk, m, _r = _fit(c, m, cancel, 3)
        if not still_correlated(chk) and mean_square_ok(chk):
            return c, m, k, chk
    return None


def _pass(ctx: tuple, model: NoiseModel, smooth: bool, progress, cancel) -> GinsResult:
    """One forward (and smoothed) pass with the noise *model*; *ctx* is ``(imu, gnss, cfg,
    params, i0, i1, x0, static, alignment, GNSS std)`` of :func:`run_gins`."""
    imu, gnss, cfg, p, i0, i1, x0, static, align, base_std = ctx
    ns_imu = 21 if p.scale_factors else 15
    ns = ns_imu + (3 if model.correlated else 0)
    t = np.ascontiguousarray(imu.time, float)
    inc = np.ascontiguousarray(imu.inc, float)
    P0 = np.zeros((ns, ns))
    P0[:ns_imu, :ns_imu] = initial_covariance(cfg, ns_imu)
    qc = np.zeros(ns)
    qc[:ns_imu] = noise_densities(cfg, ns_imu)
    qc[3:9] *= model.imu_scale ** 2  # VRW², ARW²
    tau_g = model.corr_time_s if model.correlated else 1.0
    if model.correlated:
        for c in range(3):
            P0[ns_imu + c, ns_imu + c] = model.corr_std[c] ** 2
            qc[ns_imu + c] = 2 * model.corr_std[c] ** 2 / tau_g * (
                1.0 if model.corr_q_scale is None else model.corr_q_scale[c])
    x0 = x0.copy()
    x0[K.GNSS_X:K.GNSS_X + 3] = 0.0
    n_traj = i1 - i0 + 1
    duration = t[i1] - t[i0]
    g_in = (gnss.time > t[i0]) & (gnss.time <= t[i1])
    con = p.constraint_interval_s if (p.nhc or p.zupt) else 1e9
    max_nodes = int(g_in.sum() + duration / min(con, p.max_node_interval_s) * 1.05 + 16)
    traj = np.zeros((n_traj, 10))
    node_idx = np.zeros(max_nodes, np.int64)
    xp_n = np.zeros((max_nodes, K.NX))
    xf_n = np.zeros((max_nodes, K.NX))
    Pp_n = np.zeros((max_nodes, ns, ns))
    Pf_n = np.zeros((max_nodes, ns, ns))
    Phi_n = np.zeros((max_nodes, ns, ns))
    tg = np.ascontiguousarray(gnss.time)
    llh_g = np.column_stack([np.radians(gnss.llh[:, :2]), gnss.llh[:, 2]])
    std_g = np.ascontiguousarray(base_std * model.white_scale)
    innov = np.full((tg.size, 3), np.nan)
    innov_cov = np.full((tg.size, 3, 3), np.nan)
    used = np.zeros(tg.size, np.int8)
    mount = np.radians(np.asarray(p.mounting_deg, float))
    # The mounting angles are the IMU's attitude in the vehicle frame, as the boresight
    # angles elsewhere: C(vehicle ← body) = Rz(yaw)·Ry(pitch)·Rx(roll).
    c_vb = euler_matrix(*mount)  # vehicle ← body
    nominal_dt = 1.0 / cfg.imu_rate_hz
    prop_n = max(1, int(round(p.propagation_interval_s * cfg.imu_rate_hz)))
    state = np.zeros(18)
    x = x0.copy()
    P = P0.copy()
    Phi = np.eye(ns)
    chunk = max(100, int(CHUNK_S * cfg.imu_rate_hz))
    ja = i0
    report(progress, 0.0, "forward filter")
    while ja <= i1:
        jb = min(i1, ja + chunk)
        check_cancel(cancel)
        K.forward(t, inc, i0, ja, jb, x, P, Phi, state, qc, ns, cfg.noise.corr_time, tau_g,
                  nominal_dt, prop_n, tg, llh_g, std_g, np.asarray(cfg.lever_arm_m, float),
                  p.gnss_gate, p.nhc, p.nhc_std, c_vb, con, static, p.zupt_std, p.zupt_speed,
                  p.max_node_interval_s, traj, node_idx, xp_n, xf_n, Pp_n, Pf_n, Phi_n, innov,
                  innov_cov, used)
        report(progress, 0.75 * (jb - i0 + 1) / n_traj if smooth else (jb - i0 + 1) / n_traj,
               f"forward filter {t[jb] - t[i0]:.0f} of {duration:.0f} s")
        ja = jb + 1
    nn = int(state[5])
    if not np.all(np.isfinite(traj)):
        raise InputError(imu.source, "the filter diverged (non-finite state): check units, "
                         "initial state and the IMU noise figures")
    tt = t[i0:i1 + 1]
    node_t = t[node_idx[:nn]]
    diag_f = np.einsum("kii->ki", Pf_n[:nn])
    diag_p = np.einsum("kii->ki", Pp_n[:nn])
    forward = _trajectory(tt, traj, diag_f, node_t, diag_p)
    err_f = _imu_errors(node_t, xf_n[:nn], ns)
    gnss_out = {"time": gnss.time, "innovation": innov, "innovation_cov": innov_cov,
                "used": used}
    counts = {"imu_epochs": int(n_traj), "nodes": nn, "states": ns,
              "ran": RAN[smooth],
              "gnss_epochs": int(g_in.sum()), "gnss_used": int(used.sum()),
              "static_epochs": int(static[i0:i1 + 1].sum())}
    smoothed = err_s = None
    if smooth:
        check_cancel(cancel)
        report(progress, 0.8, "RTS smoother")
        xs_n = np.zeros((nn, K.NX))
        es_n = np.zeros((nn, ns))
        ep_n = np.zeros((nn, ns))
        ps_diag = np.zeros((nn, ns))
        K.smooth(xp_n, xf_n, Pp_n, Pf_n, Phi_n, nn, ns, xs_n, es_n, ep_n, ps_diag)
        check_cancel(cancel)
        out = np.zeros_like(traj)
        rel = node_idx[:nn] - i0
        K.apply_corrections(traj, rel, es_n, ep_n, tt, nn, ns, out)
        smoothed = _trajectory(tt, out, ps_diag, node_t, ps_diag)
        err_s = _imu_errors(node_t, xs_n, ns)
        gnss_out["residual"] = gnss_residuals(gnss, smoothed, cfg.lever_arm_m)
    gnss_out["residual_forward"] = gnss_residuals(gnss, forward, cfg.lever_arm_m)
    report(progress, 1.0, "done")
    return GinsResult(forward, smoothed, err_f, err_s, gnss_out, align, counts)
