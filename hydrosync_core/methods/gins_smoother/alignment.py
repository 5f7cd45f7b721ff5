"""Initial state of a GNSS/INS run: given, static levelling, or from the GNSS track.

:func:`initial_state` chooses by ``params.align_mode``:

* ``given`` — the attitude of ``initial_attitude_deg`` (roll, pitch, yaw) or the
  configuration's ``initatt``; position from the first GNSS fix (lever arm applied),
  velocity from the GNSS;
* ``static`` — the IMU at rest at the start (quiet over at least :data:`MIN_REST_S`):
  roll and pitch by levelling (mean specific force), the gyro bias from the rest (earth
  rate removed); heading by gyrocompassing for a gyro better than 1 °/h, else the given
  ``initial_heading_deg``, else the GNSS track once the antenna moves faster than
  ``track_speed`` carried back to the end of the rest by the gyro's rotation about the
  vertical. The filter starts at the end of the rest: a walk, a boat at a quay;
* ``moving`` — roll and pitch from the accelerometers minus the GNSS acceleration, heading
  from the GNSS course at the first epoch faster than ``align_speed`` (the body's heading
  by the mounting angles);
* ``auto`` (default) — the configuration's initial state if complete, the given attitude
  if any, gyrocompassing on a quiet start, a moving alignment if the track ever reaches
  ``align_speed``, else the static alignment with the track's heading.

Angles in radians inside, degrees in the options; body frame FRD, navigation frame NED.
"""

from __future__ import annotations

import math

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.gins_smoother import kernel as K  # noqa: N812
from hydrosync_core.methods.gins_smoother.config import D2R, SensorConfig
from hydrosync_core.methods.gins_smoother.io import GnssData, ImuData
from hydrosync_core.methods.gins_smoother.params import GinsParams
from hydrosync_core.rotations import euler_to_quat, euler_zyx_angles, euler_zyx_matrix

#: Shortest quiet start (s) that the static alignment levels from.
MIN_REST_S = 2.0
#: Heading std (rad) floor of the static alignment's track heading (a hand-held IMU is
#: not pointed exactly along the walk).
TRACK_HEADING_FLOOR = math.radians(5.0)


def euler_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """``C_b^n = Rz(yaw)·Ry(pitch)·Rx(roll)`` (radians)."""
    return euler_zyx_matrix(roll, pitch, yaw)


def _empty_state(cfg: SensorConfig) -> np.ndarray:
    x = np.zeros(K.NX)
    x[10:13] = cfg.init_gyro_bias
    x[13:16] = cfg.init_acc_bias
    x[16:19] = cfg.init_gyro_scale
    x[19:22] = cfg.init_acc_scale
    return x


def _place(x: np.ndarray, gnss: GnssData, k: int, t_imu: float, v: np.ndarray,
           att: tuple[float, float, float], lever) -> None:
    """Position of the IMU at *t_imu* from GNSS fix *k* (lever arm, velocity over the
    time difference), velocity *v* and attitude *att* (rad) into the total state *x*."""
    llh = gnss.llh
    la = euler_matrix(*att) @ np.asarray(lever, float)
    lat, lon = np.radians(llh[k, :2])
    rm, rn = K.radii(lat)
    dtg = t_imu - gnss.time[k]
    x[0:3] = (lat + (v[0] * dtg - la[0]) / (rm + llh[k, 2]),
              lon + (v[1] * dtg - la[1]) / ((rn + llh[k, 2]) * math.cos(lat)),
              llh[k, 2] - v[2] * dtg + la[2])
    x[3:6] = v
    x[6:10] = euler_to_quat(*att)


def initial_state(imu: ImuData, gnss: GnssData, cfg: SensorConfig, i0: int,
                  static: np.ndarray, p: GinsParams) -> tuple[int, np.ndarray, SensorConfig,
                                                              dict]:
    """Start index, total state and the config with the alignment's std (module
    docstring); ``info`` says which alignment ran and what it found.

    Raises
    ------
    InputError
        The chosen alignment is impossible (no rest, no motion, no attitude given), with
        the option that would help.
    """
    mode = p.align_mode
    if cfg.init_pos is not None and cfg.init_att is not None and \
            p.initial_attitude_deg is None and mode in ("auto", "given"):
        x = _empty_state(cfg)
        x[0:3] = cfg.init_pos
        x[3:6] = cfg.init_vel if cfg.init_vel is not None else (0.0, 0.0, 0.0)
        x[6:10] = euler_to_quat(*cfg.init_att)
        return i0, x, cfg, {"method": "given (configuration)"}
    t = imu.time
    if np.flatnonzero(gnss.time >= t[i0]).size < 3:
        raise InputError(gnss.source, "fewer than three GNSS epochs after the start: "
                         "cannot align (give initpos/initatt in the configuration)")
    if mode == "given" or (mode == "auto" and p.initial_attitude_deg is not None):
        return _given_alignment(imu, gnss, cfg, i0, static, p)
    if mode == "moving":
        return _moving_alignment(imu, gnss, cfg, i0, p)
    rest = _rest(static, i0, imu.rate_hz, p.align_time_s)
    gb_dph = max(cfg.noise.gb_std) * 3600 / D2R
    if mode == "static" or (mode == "auto" and rest is not None and gb_dph < 1.0):
        if rest is None:
            raise InputError(imu.source, f"no rest of {MIN_REST_S:g} s at the start for a "
                             "static alignment (check the standstill options or use "
                             "--align-mode moving)")
        return _static_alignment(imu, gnss, cfg, *rest, p)
    try:
        return _moving_alignment(imu, gnss, cfg, i0, p)
    except InputError:
        if rest is None:
            raise
        return _static_alignment(imu, gnss, cfg, *rest, p)


def _rest(static: np.ndarray, i0: int, rate_hz: float, max_s: float
          ) -> tuple[int, int] | None:
    """First and last index of the quiet run that begins within :data:`MIN_REST_S` of *i0*
    (the detector's window is cut at the very start), at most *max_s* long; None if
    shorter than :data:`MIN_REST_S`."""
    head = np.flatnonzero(static[i0:i0 + int(MIN_REST_S * rate_hz)])
    if head.size == 0:
        return None
    a = i0 + int(head[0])
    seg = static[a:a + int(max_s * rate_hz)]
    n = int(np.argmin(seg)) if not seg.all() else seg.size
    return (a, a + n - 1) if n >= MIN_REST_S * rate_hz else None


def _levelling(imu: ImuData, a: int, b: int) -> tuple[float, float, np.ndarray, float]:
    """Roll, pitch (rad) from the mean specific force over IMU epochs *a* … *b*, the mean
    angular rate (rad/s) and the span (s)."""
    T = imu.time[b] - imu.time[a] + 1.0 / imu.rate_hz
    f = imu.inc[a:b + 1, 3:6].sum(axis=0) / T
    w = imu.inc[a:b + 1, 0:3].sum(axis=0) / T
    return math.atan2(-f[1], -f[2]), math.atan2(f[0], math.hypot(f[1], f[2])), w, T


def _static_alignment(imu: ImuData, gnss: GnssData, cfg: SensorConfig, i0: int, i_end: int,
                      p: GinsParams):
    """Levelling over the rest ``i0 … i_end``, heading by gyrocompassing, given, or from
    the track (module docstring); the filter starts at ``i_end`` at rest."""
    t = imu.time
    roll, pitch, w, T = _levelling(imu, i0, i_end)
    lat = math.radians(float(np.median(gnss.llh[:, 0])))
    c_lb = euler_matrix(roll, pitch, 0.0)  # level frame ← body
    wl = c_lb @ w
    gb_dph = max(cfg.noise.gb_std) * 3600 / D2R
    info = {"rest_s": float(T)}
    if p.initial_heading_deg is not None:
        yaw, yaw_std = math.radians(p.initial_heading_deg), math.radians(p.align_att_std_deg)
        info["method"] = "static levelling + given heading"
    elif gb_dph < 1.0 and T >= 10.0:
        yaw = math.atan2(-wl[1], wl[0])
        yaw_std = max(cfg.noise.gb_std) / (K.WIE * math.cos(lat)) + 0.002
        info["method"] = "static levelling + gyrocompassing"
    else:
        yaw, yaw_std, track = _track_heading(imu, gnss, i_end, p)
        info["method"] = "static levelling + heading from the GNSS track"
        info.update(track)
    # the gyro bias from the rest: the earth rate's vertical part removed (its horizontal
    # part, of unknown direction without a heading, stays in the std)
    w_vert = c_lb.T @ np.array([0.0, 0.0, -K.WIE * math.sin(lat)])
    rate_sd = float(np.std(imu.inc[i0:i_end + 1, 0:3], axis=0).max()) * imu.rate_hz
    sd_b = math.hypot(K.WIE * math.cos(lat), rate_sd / math.sqrt(i_end - i0 + 1)) + 2e-5
    x = _empty_state(cfg)
    k = int(np.argmin(np.abs(gnss.time - t[i_end])))
    _place(x, gnss, k, t[i_end], np.zeros(3), (roll, pitch, yaw), cfg.lever_arm_m)
    acc_std = max(cfg.noise.ab_std) / 9.8
    changes = {"init_att_std": (acc_std + 1e-3, acc_std + 1e-3, yaw_std),
               "init_vel_std": (0.02, 0.02, 0.02),
               "init_pos_std": tuple(gnss.std[k] + 0.01)}
    prior = cfg.init_bg_std or cfg.noise.gb_std
    if not np.any(cfg.init_gyro_bias) and sd_b < min(prior):
        # a rest quieter than the prior knows the bias better; a shaky one (a hand) not
        x[10:13] = w - w_vert
        changes["init_bg_std"] = tuple(min(a, sd_b) for a in prior)
        info["static_gyro_bias_dph"] = [float(b) * 3600 / D2R for b in x[10:13]]
    info.update(roll_deg=math.degrees(roll), pitch_deg=math.degrees(pitch),
                yaw_deg=math.degrees(yaw) % 360, yaw_std_deg=math.degrees(yaw_std),
                start_time=float(t[i_end]))
    return i_end, x, cfg.with_(**changes), info


def _track_heading(imu: ImuData, gnss: GnssData, i_end: int, p: GinsParams):
    """Body heading (rad) at IMU epoch *i_end* from the GNSS course once faster than
    ``track_speed``, carried back by the gyro's rotation about the vertical; its std and
    what it used."""
    from hydrosync_core.methods.gins_smoother.clock import vertical_angle

    t = imu.time
    vg = gnss_velocity(gnss)
    speed = np.hypot(vg[:, 0], vg[:, 1])
    after = np.flatnonzero((gnss.time > t[i_end]) & np.isfinite(speed)
                           & (speed >= p.track_speed) & (gnss.time < t[-1]))
    if after.size == 0:
        raise InputError(gnss.source, f"never faster than {p.track_speed} m/s after the rest: "
                         "no heading from the track (give --initial-heading-deg)")
    k = int(after[0])
    v = vg[k]
    c_vb = euler_matrix(*np.radians(np.asarray(p.mounting_deg, float)))  # vehicle ← body
    _r, _p, body_yaw = euler_zyx_angles(euler_matrix(0.0, 0.0, math.atan2(v[1], v[0])) @ c_vb)
    psi = vertical_angle(imu)
    turned = float(np.interp(gnss.time[k], t, psi) - psi[i_end])
    sd = max(TRACK_HEADING_FLOOR, math.radians(p.align_att_std_deg),
             3 * float(np.hypot(gnss.std[k, 0], gnss.std[k, 1])) / speed[k])
    return body_yaw - turned, sd, {"track_time": float(gnss.time[k]),
                                   "track_speed_mps": float(speed[k]),
                                   "turned_since_rest_deg": math.degrees(turned)}


def _given_alignment(imu: ImuData, gnss: GnssData, cfg: SensorConfig, i0: int,
                     static: np.ndarray, p: GinsParams):
    """The attitude of ``initial_attitude_deg`` (or the configuration's) at the first GNSS
    epoch; velocity from the GNSS (zero when the IMU is quiet)."""
    att_deg = p.initial_attitude_deg
    if att_deg is None:
        if cfg.init_att is None:
            raise InputError(None, "--align-mode given needs --initial-attitude-deg ROLL "
                             "PITCH YAW (or initatt in the configuration)",
                             field="initial_attitude_deg")
        att = tuple(float(a) for a in cfg.init_att)
    else:
        att = tuple(math.radians(a) for a in att_deg)
    t = imu.time
    k = int(np.flatnonzero(gnss.time >= t[i0])[0])
    i_start = min(int(np.searchsorted(t, gnss.time[k])), t.size - 2)
    vg = gnss_velocity(gnss)
    v = np.zeros(3) if static[i_start] or not np.isfinite(vg[k]).all() else vg[k].copy()
    x = _empty_state(cfg)
    _place(x, gnss, k, t[i_start], v, att, cfg.lever_arm_m)
    sd = math.radians(p.align_att_std_deg)
    cfg = cfg.with_(init_att_std=(sd, sd, sd), init_vel_std=(0.1, 0.1, 0.1),
                    init_pos_std=tuple(gnss.std[k] + 0.05))
    return i_start, x, cfg, {"method": "given attitude", "roll_deg": math.degrees(att[0]),
                             "pitch_deg": math.degrees(att[1]),
                             "yaw_deg": math.degrees(att[2]) % 360,
                             "start_time": float(t[i_start])}


def _moving_alignment(imu: ImuData, gnss: GnssData, cfg: SensorConfig, i0: int,
                      p: GinsParams):
    """Heading from the GNSS course at the first epoch faster than ``align_speed``; roll
    and pitch from the accelerometers minus the GNSS acceleration (module docstring)."""
    info: dict = {}
    x = _empty_state(cfg)
    t = imu.time
    lever = np.asarray(cfg.lever_arm_m)
    # moving alignment: heading from the GNSS course
    vg = gnss_velocity(gnss)
    gt, llh = gnss.time, gnss.llh
    c_vb = euler_matrix(*np.radians(np.asarray(p.mounting_deg, float)))  # vehicle ← body
    for k in range(1, gt.size - 1):
        if gt[k] < t[i0] or not np.isfinite(vg[k]).all():
            continue
        v = vg[k]
        speed = float(np.linalg.norm(v[:2]))
        if speed < p.align_speed:
            continue
        i_start = int(np.searchsorted(t, gt[k]))
        if i_start >= t.size - 1:
            break
        # vehicle attitude from the course (roll 0), then the body by the mounting
        c_vn = euler_matrix(0.0, math.atan2(-v[2], speed), math.atan2(v[1], v[0]))
        roll, pitch, yaw = euler_zyx_angles(c_vn @ c_vb)
        info["levelling"] = "GNSS course and mounting angles"
        lev = _moving_levelling(imu, gt, vg, i_start, yaw, gnss.llh[k])
        if lev is not None:
            roll, pitch = lev
            info["levelling"] = "accelerometers minus GNSS acceleration (±0.5 s)"
        C = euler_matrix(roll, pitch, yaw)
        la = C @ lever
        lat, lon = np.radians(llh[k, :2])
        rmk, rnk = K.radii(lat)
        dtg = t[i_start] - gt[k]
        x[0:3] = (lat + (v[0] * dtg - la[0]) / (rmk + llh[k, 2]),
                  lon + (v[1] * dtg - la[1]) / ((rnk + llh[k, 2]) * math.cos(lat)),
                  llh[k, 2] - v[2] * dtg + la[2])
        x[3:6] = v
        x[6:10] = euler_to_quat(roll, pitch, yaw)
        sd = math.radians(p.align_att_std_deg)
        cfg = cfg.with_(init_att_std=(sd, sd, max(sd, 3 * float(gnss.std[k, 0]) / speed)),
                        init_vel_std=(0.1, 0.1, 0.1),
                        init_pos_std=tuple(gnss.std[k] + 0.05 + float(np.linalg.norm(lever))))
        bias = None if np.any(cfg.init_gyro_bias) else _static_gyro_bias(imu, gt, vg, i0,
                                                                          i_start, llh[k])
        if bias is not None:
            x[10:13], sd_b = bias
            cfg = cfg.with_(init_bg_std=tuple(min(a, sd_b) for a in
                                              (cfg.init_bg_std or cfg.noise.gb_std)))
            info["static_gyro_bias_dph"] = [float(b) * 3600 / D2R for b in x[10:13]]
        info.update(method="GNSS course (moving)", roll_deg=math.degrees(roll),
                    pitch_deg=math.degrees(pitch), yaw_deg=math.degrees(yaw) % 360,
                    start_time=float(t[i_start]), speed_mps=speed)
        return i_start, x, cfg, info
    raise InputError(gnss.source, f"cannot align while moving: never faster than "
                     f"{p.align_speed} m/s (lower --align-speed, or give "
                     "--initial-attitude-deg)")




def gnss_velocity(gnss: GnssData) -> np.ndarray:
    """NED velocity (m/s) at each GNSS epoch: the receiver's where given (finite), else
    central differences of the positions (NaN across gaps over 3 s)."""
    gt, llh = gnss.time, gnss.llh
    out = np.full((gt.size, 3), np.nan)
    if gt.size >= 3:
        lat0 = math.radians(llh[0, 0])
        rm, rn = K.radii(lat0)
        ned = np.column_stack([np.radians(llh[:, 0] - llh[0, 0]) * (rm + llh[:, 2]),
                               np.radians(llh[:, 1] - llh[0, 1]) * (rn + llh[:, 2])
                               * math.cos(lat0), -(llh[:, 2] - llh[0, 2])])
        span = gt[2:] - gt[:-2]
        ok = (span > 0) & (span <= 3.0)
        out[1:-1][ok] = ((ned[2:] - ned[:-2]) / np.where(span > 0, span, 1)[:, None])[ok]
    if gnss.vel is not None:
        given = np.isfinite(gnss.vel)
        out[given] = gnss.vel[given]
    return out


def _moving_levelling(imu: ImuData, gt, vg, j: int, yaw: float, llh_deg,
                      half_s: float = 0.5):
    """Roll and pitch (rad) from the mean specific force over ±*half_s* around IMU epoch
    *j*, the GNSS acceleration over the same span removed: ``C_b^n f^b = a^n − g^n``
    solved for roll and pitch at the given heading. None without the data."""
    t = imu.time
    a, b = np.searchsorted(t, [t[j] - half_s, t[j] + half_s])
    if b - a < 5 or b > t.size:
        return None
    fb = imu.inc[a:b, 3:6].sum(axis=0) / (t[b - 1] - t[a - 1] if a > 0 else
                                          (b - a) / imu.rate_hz)
    ok = np.isfinite(vg).all(axis=1)
    if ok.sum() < 3:
        return None
    t0, t1 = t[a], t[b - 1]
    if t0 < gt[ok][0] or t1 > gt[ok][-1]:
        return None
    v0 = np.array([np.interp(t0, gt[ok], vg[ok, c]) for c in range(3)])
    v1 = np.array([np.interp(t1, gt[ok], vg[ok, c]) for c in range(3)])
    an = (v1 - v0) / (t1 - t0)
    g = K.gravity(math.radians(float(llh_deg[0])), float(llh_deg[2]))
    cy, sy = math.cos(yaw), math.sin(yaw)
    fh = np.array([cy * an[0] + sy * an[1], -sy * an[0] + cy * an[1], an[2] - g])
    if not np.all(np.isfinite(fh)) or np.linalg.norm(an[:2]) > 5.0:
        return None
    roll = math.atan2(-fb[1], -fb[2])
    pitch = math.atan2(fb[0], math.hypot(fb[1], fb[2]))
    for _ in range(8):  # Gauss-Newton on Ry(pitch)·Rx(roll)·fb = fh
        def res(r, q):
            return euler_matrix(r, q, 0.0) @ fb - fh
        e = res(roll, pitch)
        h = 1e-6
        J = np.column_stack([(res(roll + h, pitch) - e) / h, (res(roll, pitch + h) - e) / h])
        step = np.linalg.lstsq(J, -e, rcond=None)[0]
        roll += step[0]
        pitch += step[1]
        if np.max(np.abs(step)) < 1e-9:
            break
    return roll, pitch


def _static_gyro_bias(imu: ImuData, gt, vg, i0: int, i_start: int, llh_deg):
    """Gyro bias (rad/s) and its std from a standstill before the moving alignment.

    The standstill is where the GNSS speed stays below 0.1 m/s (the IMU statistics are not
    trusted: a running engine shakes a car); its last second is left out. The earth rate is
    removed with roll and pitch from levelling; its horizontal part, of unknown direction
    before the heading is known, is left in the std (≤ 15 °/h). None if shorter than 5 s.
    """
    ok = np.isfinite(vg).all(axis=1)
    moving = gt[ok][np.linalg.norm(vg[ok], axis=1) > 0.1]
    t = imu.time
    end_t = min(t[i_start], moving[moving > t[i0]][0] if (moving > t[i0]).any() else t[i_start])
    first_g = gt[ok][0] if ok.any() else t[i0]
    start_t = max(t[i0], first_g)
    end_t -= 1.0
    if end_t - start_t < 5.0:
        return None
    a, b = np.searchsorted(t, [start_t, end_t])
    T = t[b - 1] - t[a - 1] if a > 0 else (b - a) / imu.rate_hz
    w = imu.inc[a:b, 0:3].sum(axis=0) / T
    f = imu.inc[a:b, 3:6].sum(axis=0) / T
    roll = math.atan2(-f[1], -f[2])
    pitch = math.atan2(f[0], math.hypot(f[1], f[2]))
    lat = math.radians(float(llh_deg[0]))
    c_nb = euler_matrix(roll, pitch, 0.0).T
    w_vert = c_nb @ np.array([0.0, 0.0, -K.WIE * math.sin(lat)])
    rate_sd = float(np.std(imu.inc[a:b, 0:3] / (T / (b - a)), axis=0).max())
    sd = math.hypot(K.WIE * math.cos(lat), rate_sd / math.sqrt(b - a)) + 2e-5
    return w - w_vert, sd


