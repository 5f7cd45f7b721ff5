"""Simulated IMU increments, GNSS fixes and truth for a land vehicle or a survey vessel.

The truth is built from a smooth motion profile (speed, heading, pitch, roll as functions
of time) on a fine grid (10 steps per IMU interval): velocity ``v^n`` from speed, heading
and pitch, position by integration on the WGS-84 ellipsoid, and the exact sensor outputs
``ω_ib^b = ω_nb^b + C_n^b (ω_ie^n + ω_en^n)`` and
``f^b = C_n^b (a^n − g^n + (2ω_ie^n + ω_en^n) × v^n)``, integrated over each IMU interval
into increments. The filter's own mechanisation code is not used. Injected errors:
constant biases and scale factors drawn from the IMU grade, white noise (ARW, VRW), GNSS
white noise with the given std and, optionally, a time-correlated GNSS error (first-order
Gauss–Markov / AR(1) with ``gnss_corr_std`` and ``gnss_corr_time_s``, as multipath and
atmosphere make it); the GNSS file then reports the total std ``√(white² + correlated²)``,
as a receiver's accuracy figure does.

Profiles: ``vehicle`` (standstill, accelerations, straight runs, 90° turns, stops; body x
along the velocity so the NHC holds) and ``vessel`` (slow survey turns at 2–3 m/s with
wave-induced roll and pitch; sway breaks the NHC).
"""

from __future__ import annotations

import math

import numpy as np

from hydrosync_core.methods.gins_smoother.config import D2R, ImuNoise, SensorConfig
from hydrosync_core.methods.gins_smoother.io import GnssData, ImuData, NavData
from hydrosync_core.rotations import euler_zyx_matrix

WIE = 7.2921151467e-5
A_WGS = 6378137.0
E2_WGS = 0.00669437999013


def _gravity(lat, h):
    s2 = np.sin(lat) ** 2
    return (9.7803267715 * (1.0 + 0.0052790414 * s2 + 0.0000232718 * s2 * s2)
            + h * (0.0000000043977311 * s2 - 0.0000030876910891) + 0.0000000000007211 * h * h)


def _smoothstep(x):
    x = np.clip(x, 0.0, 1.0)
    return x * x * (3 - 2 * x)


def _profile(kind: str, t: np.ndarray, rng: np.random.Generator):
    """Speed (m/s), heading, pitch, roll (rad) over *t* (s from start)."""
    if kind == "vehicle":
        # segments: (duration s, speed at end m/s, heading change deg)
        segs = [(20, 0, 0), (8, 10, 0), (15, 10, 0), (9, 10, 90), (12, 12, 0), (6, 0, 0),
                (8, 0, 0), (7, 8, 0), (10, 8, -90), (15, 14, 0), (8, 14, 45)]
        while sum(s[0] for s in segs) < t[-1] + 1:
            segs.append((float(rng.uniform(8, 20)), float(rng.choice([0, 6, 10, 14])),
                         float(rng.choice([0, 0, 90, -90, 45]))))
        speed = np.zeros_like(t)
        heading = np.full_like(t, math.radians(rng.uniform(0, 360)))
        t0, v0, h0 = 0.0, 0.0, heading[0]
        for dur, v1, dh in segs:
            w = _smoothstep((t - t0) / dur)
            m = t >= t0
            speed[m] = v0 + (v1 - v0) * w[m]
            heading[m] = h0 + math.radians(dh) * w[m]
            t0, v0, h0 = t0 + dur, v1, h0 + math.radians(dh)
        pitch = 0.02 * np.sin(2 * np.pi * t / 90.0)
        lat_acc = speed * np.gradient(heading, t)
        roll = 0.5 * D2R * lat_acc + 0.3 * D2R
    else:
        speed = 2.5 * _smoothstep(t / 20.0)
        heading = math.radians(rng.uniform(0, 360)) + 0.5 * np.pi * _smoothstep((t - 60) / 60)
        roll = 3 * D2R * np.sin(2 * np.pi * t / 7.0) + 1 * D2R * np.sin(2 * np.pi * t / 11.0)
        pitch = 1.5 * D2R * np.sin(2 * np.pi * t / 5.0 + 1.0)
    return speed, heading, pitch, roll


def simulate(duration_s: float = 120.0, kind: str = "vehicle", grade: str = "tactical",
             imu_rate_hz: float = 100.0, gnss_rate_hz: float = 1.0,
             gnss_std=(0.01, 0.01, 0.02), lever_arm_m=(0.5, -0.3, -1.2),
             lat_deg: float = 52.0, lon_deg: float = 4.5, height_m: float = 40.0,
             t0: float = 345600.0, seed: int = 0, noise_free: bool = False,
             gnss_corr_std=(0.0, 0.0, 0.0), gnss_corr_time_s: float = 60.0,
             init_errors: bool = False) -> dict:
    """Simulate a drive or a vessel track.

    Returns ``imu`` (:class:`ImuData`), ``gnss`` (:class:`GnssData`), ``truth``
    (:class:`NavData` at IMU rate), ``config`` (:class:`SensorConfig` with the grade's
    noise, the lever arm and the true initial state) and ``errors`` (injected biases in
    deg/h and mGal, scale factors in ppm).

    The configuration's initial state is the truth with the std of ``init_*_std`` — unless
    *init_errors*, which draws the initial position, velocity and attitude errors from
    those std (independent generator), so that the σ a run reports can be checked against
    the truth from the first epoch (an exact start with a nonzero σ makes them look
    conservative).
    """
    rng = np.random.default_rng(seed)
    sub = 10
    dt = 1.0 / imu_rate_hz
    n_imu = int(round(duration_s * imu_rate_hz))
    tf = np.arange(n_imu * sub + 1) * (dt / sub)
    speed, psi, theta, phi = _profile(kind, tf, rng)
    vn = np.column_stack([speed * np.cos(theta) * np.cos(psi),
                          speed * np.cos(theta) * np.sin(psi), -speed * np.sin(theta)])
    if kind == "vessel":  # sway: a lateral velocity component
        sway = 0.15 * np.sin(2 * np.pi * tf / 7.0)
        vn[:, 0] += -sway * np.sin(psi)
        vn[:, 1] += sway * np.cos(psi)
        vn[:, 2] += 0.3 * np.cos(2 * np.pi * tf / 6.0) * _smoothstep(tf / 5)
    h_step = dt / sub
    lat = np.empty_like(tf)
    lon = np.empty_like(tf)
    h = np.empty_like(tf)
    lat[0], lon[0], h[0] = math.radians(lat_deg), math.radians(lon_deg), height_m
    for i in range(tf.size - 1):  # trapezoid on the ellipsoid (fine grid)
        vm = 0.5 * (vn[i] + vn[i + 1])
        s2 = math.sin(lat[i]) ** 2
        rn = A_WGS / math.sqrt(1 - E2_WGS * s2)
        rm = rn * (1 - E2_WGS) / (1 - E2_WGS * s2)
        h[i + 1] = h[i] - vm[2] * h_step
        lat[i + 1] = lat[i] + vm[0] * h_step / (rm + 0.5 * (h[i] + h[i + 1]))
        lon[i + 1] = lon[i] + vm[1] * h_step / ((rn + h[i]) * math.cos(lat[i]))
    s2 = np.sin(lat) ** 2
    rn = A_WGS / np.sqrt(1 - E2_WGS * s2)
    rm = rn * (1 - E2_WGS) / (1 - E2_WGS * s2)
    wie = np.column_stack([WIE * np.cos(lat), np.zeros_like(lat), -WIE * np.sin(lat)])
    wen = np.column_stack([vn[:, 1] / (rn + h), -vn[:, 0] / (rm + h),
                           -vn[:, 1] * np.tan(lat) / (rn + h)])
    an = np.gradient(vn, tf, axis=0)
    g = np.column_stack([np.zeros_like(h), np.zeros_like(h), _gravity(lat, h)])
    fn = an - g + np.cross(2 * wie + wen, vn)
    cr, sr, cp, sp = np.cos(phi), np.sin(phi), np.cos(theta), np.sin(theta)
    C = euler_zyx_matrix(phi, theta, psi)  # C_b^n
    dphi, dth, dpsi = (np.gradient(a, tf) for a in (phi, theta, psi))
    wnb = np.column_stack([dphi - dpsi * sp, dth * cr + dpsi * cp * sr,
                           -dth * sr + dpsi * cp * cr])
    wib = wnb + np.einsum("kji,kj->ki", C, wie + wen)
    fb = np.einsum("kji,kj->ki", C, fn)

    def increments(rate):
        c = np.concatenate([np.zeros((1, 3)), np.cumsum(0.5 * (rate[1:] + rate[:-1]) * h_step,
                                                         axis=0)])
        return np.diff(c[::sub], axis=0)

    dth_inc = increments(wib)
    dv_inc = increments(fb)
    noise = ImuNoise.grade(grade)
    errors = {"gyro_bias_dph": [0.0] * 3, "acc_bias_mgal": [0.0] * 3,
              "gyro_scale_ppm": [0.0] * 3, "acc_scale_ppm": [0.0] * 3}
    if not noise_free:
        bg = rng.normal(0, 1, 3) * np.asarray(noise.gb_std)
        ba = rng.normal(0, 1, 3) * np.asarray(noise.ab_std)
        sg = rng.normal(0, 1, 3) * np.asarray(noise.gs_std) * 0.5
        sa = rng.normal(0, 1, 3) * np.asarray(noise.as_std) * 0.5
        dth_inc = dth_inc * (1 + sg) + bg * dt + rng.normal(0, 1, dth_inc.shape) * \
            np.asarray(noise.arw) * math.sqrt(dt)
        dv_inc = dv_inc * (1 + sa) + ba * dt + rng.normal(0, 1, dv_inc.shape) * \
            np.asarray(noise.vrw) * math.sqrt(dt)
        errors = {"gyro_bias_dph": list(bg * 3600 / D2R), "acc_bias_mgal": list(ba / 1e-5),
                  "gyro_scale_ppm": list(sg * 1e6), "acc_scale_ppm": list(sa * 1e6)}
    ti = t0 + np.arange(1, n_imu + 1) * dt
    k = np.arange(sub, tf.size, sub)
    truth = NavData(np.concatenate([[t0], ti]),
                    np.column_stack([np.degrees(lat[::sub]), np.degrees(lon[::sub]), h[::sub]]),
                    vn[::sub].copy(),
                    np.column_stack([np.degrees(phi[::sub]), np.degrees(theta[::sub]),
                                     np.degrees(psi[::sub]) % 360]), "simulated truth")
    imu = ImuData(ti, np.column_stack([dth_inc, dv_inc]), "simulated IMU")
    # GNSS at whole multiples of the GNSS interval: antenna = IMU + C l
    gstep = int(round(imu_rate_hz / gnss_rate_hz)) * sub
    gi = np.arange(gstep, tf.size, gstep)
    la = np.einsum("kij,j->ki", C[gi], np.asarray(lever_arm_m, float))
    sw = np.asarray(gnss_std, float)
    sc = np.asarray(gnss_corr_std, float)
    std = np.tile(np.sqrt(sw ** 2 + sc ** 2), (gi.size, 1))
    e = np.zeros((gi.size, 3)) if noise_free else rng.normal(0, 1, (gi.size, 3)) * sw
    if not noise_free and np.any(sc > 0):
        rho = math.exp(-1.0 / (gnss_rate_hz * gnss_corr_time_s))
        c = np.empty((gi.size, 3))
        c[0] = rng.normal(0, 1, 3) * sc
        drive = rng.normal(0, 1, (gi.size, 3)) * sc * math.sqrt(1 - rho * rho)
        for i in range(1, gi.size):
            c[i] = rho * c[i - 1] + drive[i]
        e = e + c
    glat = lat[gi] + (la[:, 0] + e[:, 0]) / (rm[gi] + h[gi])
    glon = lon[gi] + (la[:, 1] + e[:, 1]) / ((rn[gi] + h[gi]) * np.cos(lat[gi]))
    gh = h[gi] - la[:, 2] - e[:, 2]
    gnss = GnssData(t0 + tf[gi], np.column_stack([np.degrees(glat), np.degrees(glon), gh]), std,
                    "simulated GNSS")
    del k
    pos_sd, vel_sd = np.array([0.02, 0.02, 0.04]), np.array([0.01, 0.01, 0.01])
    att_sd = np.array([0.05, 0.05, 0.5]) * D2R
    d_pos, d_vel, d_att = np.zeros(3), np.zeros(3), np.zeros(3)
    if init_errors:
        r2 = np.random.default_rng([seed, 1])
        d_pos, d_vel, d_att = (r2.normal(0, 1, 3) * sd for sd in (pos_sd, vel_sd, att_sd))
    cfg = SensorConfig(noise=noise, lever_arm_m=tuple(float(v) for v in lever_arm_m),
                       init_pos=(float(lat[0] + d_pos[0] / (rm[0] + h[0])),
                                 float(lon[0] + d_pos[1] / ((rn[0] + h[0]) * np.cos(lat[0]))),
                                 float(h[0] - d_pos[2])),
                       init_vel=tuple(float(v) for v in vn[0] + d_vel),
                       init_att=(float(phi[0] + d_att[0]), float(theta[0] + d_att[1]),
                                 float(psi[0] + d_att[2])),
                       init_pos_std=tuple(map(float, pos_sd)),
                       init_vel_std=tuple(map(float, vel_sd)),
                       init_att_std=tuple(map(float, att_sd)),
                       start_time=t0, imu_rate_hz=imu_rate_hz, source="simulation")
    return {"imu": imu, "gnss": gnss, "truth": truth, "config": cfg, "errors": errors}
