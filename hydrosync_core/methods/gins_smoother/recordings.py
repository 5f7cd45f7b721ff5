"""Importers of real GNSS/INS recordings, read in place: comma2k19 and rtklibexplorer.

Each reader turns one recording folder into the smoother's inputs — IMU increments in the
body frame (x forward, y right, z down) on the GPS time-of-week scale, GNSS antenna
positions with N/E/D std, a :class:`~.config.SensorConfig` and the processing options that
suit the recording — plus the provider's reference trajectory when there is one. Nothing
is hand-edited: every choice below is made from the files or stated as an assumption.

**comma2k19** (``comma2k19-ex1``: one 60 s highway segment; ``.npy`` arrays without
extension; Schafer et al. 2018):

* IMU ``processed_log/IMU/{accelerometer,gyro}``: specific force (m/s²) and angular rate
  (rad/s, Android's bias estimate removed) at ≈104 Hz, axes [forward, right, down] —
  already the body frame. Boot-clock times ``t``.
* Clock: boot time → GPS time of week by the constant ``frame_gps_times − frame_times``
  of the reference (one clock for IMU, GNSS and frames).
* GNSS ``live_gnss_ublox`` (10 Hz): the epoch time is the fix's own UTC time stamp
  (milliseconds, + 18 leap seconds → GPS), not the logger's boot time (the message reaches
  the logger ≈0.2 s after its epoch); ``gnss_time_shift_s`` is added on top. Altitude is
  taken as ellipsoidal (the SOURCE notes show it is). No accuracy in the file: σ assumed
  (:data:`COMMA_GNSS_STD`, standalone u-blox M8 figures). Speed and bearing give the
  horizontal velocity used by the moving alignment.
* Reference ``global_pose`` (20 Hz): ECEF camera position, velocity and camera→ECEF
  quaternion ``[w, x, y, z]``, converted to the ``.nav`` quantities. It comes from the
  provider's optimiser over these same sensors (not independent) and describes the camera
  (≈ the IMU: same device), not the antenna.
* IMU grade: smartphone (no specification in the recording): :data:`PHONE_NOISE`. Lever
  arm unknown: zero, the GNSS σ covering it; mounting unknown: no NHC.

**rtklibexplorer** (``rtkexplorer-gnss-imu/drive_0708``; ``walk_0827`` reads the same way):

* IMU ``imu_*.csv``: 7 columns, accelerometer (g) and gyro (deg/s) in the **sensor**
  frame, then a millisecond counter. Rows whose six values repeat the previous row (the
  sensor read before it had a new sample) are dropped; truncated lines (fewer than 7
  fields) are skipped.
* Clock: the RTKLIB ``.tag`` file gives the GPST start; the counter is mapped linearly
  over the tag span as the author's converter does, then the author's logging delay
  (``imu_time_shift_s``; drive −0.125 s, walk 0) is added.
* Sensor → body: ``body = Cᵀ·sensor`` with ``C = Rz(ψ)·Ry(θ)·Rx(φ)`` of the author's
  mounting roll/pitch/yaw (drive [180, −6.79, 185.35]°, walk [180, 0, −90]°), so the body
  frame is the vehicle frame and the NHC needs no further mounting angles.
* GNSS ``gnss_*_sf.pos`` (RTKLIB layout, 4 Hz real-time RTK): heights are **above mean
  sea level** (NAV-PVT hMSL) — kept as they are (the trajectory heights are then MSL
  too; gravity changes by 5·10⁻⁶ of g over the ≈17 m geoid separation); σ from sdn, sde,
  sdu, doubled for float solutions and ×5 for single (the author's gains); velocity
  columns feed the alignment. Antenna lever arm from the author's offsets.
* IMU grade: the author's filter noise (gyro 0.0038 °/s/√Hz, accel 70 µg/√Hz; a TDK
  ICM-45686 according to the author's configuration), bias figures in
  :data:`RTK_DRIVE_NOISE`.
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.gins_smoother.config import D2R, ImuNoise, SensorConfig
from hydrosync_core.methods.gins_smoother.io import GnssData, ImuData, NavData

G0 = 9.80665  # m/s² per g
GPS_UNIX_OFFSET = 315964800.0  # s from 1970-01-01 to 1980-01-06
WEEK_S = 604800.0
LEAP_S = 18.0  # GPS − UTC since 2017

#: Smartphone IMU (KF-GINS units): ARW deg/√h, VRW m/s/√h, bias instability deg/h and
#: mGal, scale ppm, correlation time h. Datasheet noise of phone IMUs (≈0.01 °/s/√Hz,
#: ≈300 µg/√Hz) inflated ×1.5 for the vehicle's vibration; the Gauss–Markov bias figures
#: are the order of a phone's thermal bias wander.
PHONE_NOISE = {"arw": 0.9, "vrw": 0.3, "gb": 50.0, "ab": 3000.0, "scale": 5000.0, "T_h": 0.5}
#: Initial bias std of a phone IMU: gyro 0.1 °/s after Android's own calibration,
#: accelerometer 30 mg.
PHONE_INIT_BIAS = {"gb": 360.0, "ab": 30000.0}
#: rtklibexplorer drive IMU: the author's noise densities (0.0038 °/s/√Hz → 0.228 °/√h;
#: 70 µg/√Hz → 0.041 m/s/√h) ×2 for roof vibration; bias instability from the author's bias
#: random walks over one hour (3.8e-5 °/s/√Hz → ≈8 °/h, 7 µg/√Hz → ≈400 mGal).
RTK_DRIVE_NOISE = {"arw": 0.46, "vrw": 0.082, "gb": 10.0, "ab": 400.0, "scale": 1000.0,
                   "T_h": 1.0}
#: Initial bias std (the author's: 0.1 °/s, 0.1 m/s²).
RTK_INIT_BIAS = {"gb": 360.0, "ab": 10000.0}
#: Assumed σ N, E, D (m) of the comma2k19 u-blox fixes (standalone, no corrections).
COMMA_GNSS_STD = (1.0, 1.0, 2.0)
#: Author's sensor-to-body roll/pitch/yaw (deg) and offsets from the system origin
#: (forward, right, down, m) of the rtklibexplorer recordings (SOURCE.md).
RTK_SETUP = {
    "drive": {"rpy": (180.0, -6.79, 185.35), "imu": (0.0, 0.0, -0.65),
              "antenna": (0.0, -0.05, -0.65), "imu_time_shift_s": -0.125},
    "walk": {"rpy": (180.0, 0.0, -90.0), "imu": (0.0, 0.05, 0.0),
             "antenna": (0.0, 0.0, 0.0), "imu_time_shift_s": 0.0},
}


@dataclass
class Recording:
    """A real recording ready for :func:`.filter.run_gins`.

    ``params``: processing options suited to the recording (a :class:`GinsParams` dict);
    ``reference``: the provider's trajectory or None; ``notes``: what was assumed.
    """

    name: str
    imu: ImuData
    gnss: GnssData
    config: SensorConfig
    params: dict
    reference: NavData | None = None
    notes: list[str] = field(default_factory=list)
    #: False for a hand-held IMU: the walker turns the device before the track turns, so
    #: the turns do not time the clocks (:func:`estimate_time_shift` keeps the author's).
    clock_from_turns: bool = True

    def sliced(self, start: float, end: float) -> Recording:
        """The recording between GPS times *start* and *end* (s)."""
        mi = (self.imu.time >= start) & (self.imu.time <= end)
        mg = (self.gnss.time >= start) & (self.gnss.time <= end)
        g = GnssData(self.gnss.time[mg], self.gnss.llh[mg], self.gnss.std[mg],
                     self.gnss.source)
        if self.gnss.vel is not None:
            g.vel = self.gnss.vel[mg]
        ref = None
        if self.reference is not None:
            r = self.reference
            mr = (r.time >= start) & (r.time <= end)
            ref = NavData(r.time[mr], r.llh[mr], r.vel[mr], r.att[mr], r.source)
        return Recording(self.name, ImuData(self.imu.time[mi], self.imu.inc[mi],
                                            self.imu.source), g, self.config, self.params,
                         ref, self.notes, self.clock_from_turns)


def increments_from_rates(t: np.ndarray, gyro_rad_s: np.ndarray, acc_ms2: np.ndarray,
                          source: str) -> ImuData:
    """Angle and velocity increments over each interval ending at ``t[j]`` (trapezoid);
    the first interval uses the median step."""
    t = np.asarray(t, float)
    vals = np.column_stack([gyro_rad_s, acc_ms2]).astype(float)
    dt = np.diff(t)
    inc = np.empty_like(vals)
    inc[0] = vals[0] * float(np.median(dt))
    inc[1:] = 0.5 * (vals[1:] + vals[:-1]) * dt[:, None]
    return ImuData(np.ascontiguousarray(t), np.ascontiguousarray(inc), source)


def tow(gps_seconds_since_1970):
    """GPS time of week (s) of seconds since 1970-01-01 counted on the GPS scale."""
    return np.mod(np.asarray(gps_seconds_since_1970, float) - GPS_UNIX_OFFSET, WEEK_S)


def euler_dcm(roll_deg: float, pitch_deg: float, yaw_deg: float) -> np.ndarray:
    """``Rz(yaw)·Ry(pitch)·Rx(roll)`` (degrees in)."""
    r, p, y = (math.radians(a) for a in (roll_deg, pitch_deg, yaw_deg))
    cr, sr, cp, sp, cy, sy = (math.cos(r), math.sin(r), math.cos(p), math.sin(p),
                              math.cos(y), math.sin(y))
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def _config(noise: dict, init_bias: dict, lever, rate_hz: float, source: str) -> SensorConfig:
    n = ImuNoise.from_kfgins([noise["arw"]] * 3, [noise["vrw"]] * 3, [noise["gb"]] * 3,
                             [noise["ab"]] * 3, [noise["scale"]] * 3, [noise["scale"]] * 3,
                             noise["T_h"])
    return SensorConfig(noise=n, lever_arm_m=tuple(float(v) for v in lever),
                        init_bg_std=(init_bias["gb"] * D2R / 3600,) * 3,
                        init_ba_std=(init_bias["ab"] * 1e-5,) * 3,
                        imu_rate_hz=rate_hz, source=source)


# ------------------------------------------------------------------ comma2k19
def _npy(path: Path) -> np.ndarray:
    try:
        with open(path, "rb") as fh:
            arr = np.load(fh, allow_pickle=False)
    except FileNotFoundError:
        raise InputError(str(path), "file not found (a comma2k19 segment folder has "
                         "processed_log/ and global_pose/)") from None
    except (OSError, ValueError) as exc:
        raise InputError(str(path), f"not a NumPy array file: {exc}") from None
    if not np.issubdtype(arr.dtype, np.number):
        raise InputError(str(path), "not a numeric array")
    return np.asarray(arr, float)


def _log(folder: Path, name: str, cols: int) -> tuple[np.ndarray, np.ndarray]:
    t = _npy(folder / "processed_log" / name / "t")
    v = _npy(folder / "processed_log" / name / "value")
    if v.ndim != 2 or v.shape[0] != t.size or v.shape[1] < cols:
        raise InputError(str(folder / "processed_log" / name / "value"),
                         f"shape {v.shape}, expected ({t.size}, {cols})")
    good = np.isfinite(t) & np.isfinite(v[:, :cols]).all(axis=1)
    order = np.argsort(t[good], kind="stable")
    t, v = t[good][order], v[good][order]
    keep = np.concatenate([[True], np.diff(t) > 0])
    return t[keep], v[keep]


def comma_reference(folder: Path, boot_to_tow: float | None = None) -> tuple[NavData, float]:
    """The comma2k19 reference pose (camera) as a :class:`NavData` on GPS time of week,
    and the boot-clock → time-of-week offset (s)."""
    from scipy.spatial.transform import Rotation

    from hydrosync_core.geodesy import ecef_to_geodetic, ecef_to_ned_matrix

    g = folder / "global_pose"
    ft = _npy(g / "frame_times")
    gps = _npy(g / "frame_gps_times")
    pos = _npy(g / "frame_positions")
    vel = _npy(g / "frame_velocities")
    quat = _npy(g / "frame_orientations")
    n = ft.size
    for arr, name, k in ((gps, "frame_gps_times", 2), (pos, "frame_positions", 3),
                         (vel, "frame_velocities", 3), (quat, "frame_orientations", 4)):
        if arr.shape != (n, k):
            raise InputError(str(g / name), f"shape {arr.shape}, expected ({n}, {k})")
    off = float(np.median(gps[:, 1] - ft))
    lat, lon, h = ecef_to_geodetic(pos)
    c_en = ecef_to_ned_matrix(lat, lon)  # (n, 3, 3) ECEF → NED
    v_ned = np.einsum("nij,nj->ni", c_en, vel)
    c_be = Rotation.from_quat(quat[:, [1, 2, 3, 0]]).as_matrix()  # camera → ECEF
    c_bn = c_en @ c_be
    roll = np.degrees(np.arctan2(c_bn[:, 2, 1], c_bn[:, 2, 2]))
    pitch = np.degrees(np.arcsin(np.clip(-c_bn[:, 2, 0], -1, 1)))
    yaw = np.mod(np.degrees(np.arctan2(c_bn[:, 1, 0], c_bn[:, 0, 0])), 360.0)
    t = gps[:, 1] if boot_to_tow is None else ft + boot_to_tow
    nav = NavData(t, np.column_stack([lat, lon, h]), v_ned,
                  np.column_stack([roll, pitch, yaw]), str(g))
    return nav, off


def read_comma2k19(folder, gnss_time_shift_s: float = 0.0) -> Recording:
    """A comma2k19 segment folder (``processed_log/``, ``global_pose/``): module docstring."""
    folder = Path(folder)
    if not folder.is_dir():
        raise InputError(str(folder), "not a folder (a comma2k19 segment)")
    ref, boot_to_tow = comma_reference(folder)
    ta, acc = _log(folder, "IMU/accelerometer", 3)
    tg, gyr = _log(folder, "IMU/gyro", 3)
    common, ia, ig = np.intersect1d(ta, tg, return_indices=True)
    if common.size < 100:
        raise InputError(str(folder / "processed_log/IMU"), "accelerometer and gyro times "
                         "do not match")
    if np.median(np.linalg.norm(acc[ia], axis=1)) < 5.0:
        raise InputError(str(folder / "processed_log/IMU/accelerometer/value"),
                         "specific force far below 1 g: not m/s²")
    imu = increments_from_rates(common + boot_to_tow, gyr[ig], acc[ia],
                                str(folder / "processed_log/IMU"))
    tu, u = _log(folder, "GNSS/live_gnss_ublox", 6)
    ok = (np.abs(u[:, 0]) <= 90) & (np.abs(u[:, 1]) <= 180) & (u[:, 3] > 1e12)
    u = u[ok]
    t_fix = tow(u[:, 3] / 1000.0 + LEAP_S) + gnss_time_shift_s
    order = np.argsort(t_fix, kind="stable")
    u, t_fix = u[order], t_fix[order]
    keep = np.concatenate([[True], np.diff(t_fix) > 1e-6])
    u, t_fix = u[keep], t_fix[keep]
    # the UTC stamps and the boot clock must agree to within a second
    lag = np.median(tu[ok][order][keep] + boot_to_tow - t_fix)
    if not -1.0 < lag < 2.0:
        raise InputError(str(folder / "processed_log/GNSS/live_gnss_ublox/value"),
                         f"fix UTC time stamps are {lag:.1f} s from the logger clock",
                         field="utc_timestamp")
    brg = np.radians(u[:, 5])
    vel = np.column_stack([u[:, 2] * np.cos(brg), u[:, 2] * np.sin(brg),
                           np.full(u.shape[0], np.nan)])
    gnss = GnssData(t_fix, u[:, [0, 1, 4]].copy(), np.tile(COMMA_GNSS_STD, (u.shape[0], 1)),
                    str(folder / "processed_log/GNSS/live_gnss_ublox"))
    gnss.vel = vel
    cfg = _config(PHONE_NOISE, PHONE_INIT_BIAS, (0.0, 0.0, 0.0), round(imu.rate_hz, 1),
                  f"{folder} (assumed smartphone IMU)")
    notes = [
        f"boot clock + {boot_to_tow:.4f} s = GPS time of week (reference frame times)",
        f"u-blox fixes time-tagged by their own UTC stamp (+{LEAP_S:.0f} s), logged "
        f"{lag:.3f} s later (median); extra shift {gnss_time_shift_s:+.3f} s",
        f"GNSS σ N/E/D assumed {COMMA_GNSS_STD} m (no accuracy in the file)",
        "IMU noise: smartphone grade assumed (no specification); lever arm and mounting "
        "unknown: lever arm 0, no NHC",
        "reference: provider's optimiser output for the camera, not independent",
    ]
    params = {"nhc": False, "zupt": False, "scale_factors": False,
              "constraint_interval_s": 0.5, "align_speed": 3.0, "align_att_std_deg": 3.0}
    return Recording("comma2k19", imu, gnss, cfg, params, ref, notes)


# ------------------------------------------------------------------ rtklibexplorer
def read_tag(path) -> tuple[float, np.ndarray]:
    """An RTKLIB time-tag file: start time (GPS s since 1970) and records (n, 2) of
    ``ms since start``, ``byte offset``."""
    p = Path(path)
    try:
        raw = p.read_bytes()
    except FileNotFoundError:
        raise InputError(str(p), "file not found (the IMU needs its RTKLIB .tag file for "
                         "GPS time)") from None
    except OSError as exc:
        raise InputError(str(p), f"cannot read: {exc.strerror}") from None
    if len(raw) < 76 or not raw.startswith(b"TIMETAG"):
        raise InputError(str(p), "not an RTKLIB time-tag file (no TIMETAG header)")
    _tick, start_s = struct.unpack("<II", raw[60:68])
    frac = struct.unpack("<d", raw[68:76])[0]
    body = raw[76:]
    rec = np.frombuffer(body[: len(body) // 8 * 8], dtype="<u4").reshape(-1, 2)
    if rec.shape[0] == 0:
        raise InputError(str(p), "no time-tag records")
    return float(start_s) + float(frac), rec.astype(np.int64)


def read_rtk_imu(csv_path, rpy_deg, imu_time_shift_s: float = 0.0) -> ImuData:
    """rtklibexplorer raw IMU CSV + its ``.tag``: increments in the body frame (module
    docstring)."""
    p = Path(csv_path)
    try:
        text = p.read_text(encoding="ascii", errors="replace")
    except FileNotFoundError:
        raise InputError(str(p), "file not found") from None
    rows = []
    for line in text.splitlines():
        parts = line.split(",")
        if len(parts) != 7:
            continue  # truncated first/last line of a log
        try:
            rows.append([float(v) for v in parts])
        except ValueError:
            continue
    if len(rows) < 100:
        raise InputError(str(p), "fewer than 100 complete 7-column IMU rows")
    d = np.asarray(rows)
    d = d[np.isfinite(d).all(axis=1)]
    keep = np.concatenate([[True], np.any(np.diff(d[:, :6], axis=0) != 0, axis=1)])
    keep &= np.concatenate([[True], np.diff(d[:, 6]) > 0])
    d = d[keep]
    start, rec = read_tag(str(p) + ".tag")
    end = start + rec[-1, 0] / 1000.0
    cnt = d[:, 6] - d[0, 6]
    if cnt[-1] <= 0:
        raise InputError(str(p), "IMU counter does not increase", field="column 7")
    t_gps = start + cnt * (end - start) / cnt[-1] + imu_time_shift_s
    c = euler_dcm(*rpy_deg).T  # sensor → body
    acc = d[:, 0:3] @ c.T * G0
    gyr = np.radians(d[:, 3:6]) @ c.T
    return increments_from_rates(tow(t_gps), gyr, acc, str(p))


def read_rtk_pos(path) -> GnssData:
    """The receiver's RTK solution (``gnss_*_sf.pos``) as antenna positions with σ."""
    from hydrosync_core.importers.rtklib_pos import read_pos

    pos = read_pos(path)
    c = pos.columns
    for name in ("lat", "lon", "height", "sdn", "sde", "sdu"):
        if name not in c:
            raise InputError(str(path), "column missing", field=name)
    gain = np.where(c["q"] == 1, 1.0, np.where(c["q"] == 2, 2.0, 5.0))
    std = np.column_stack([c["sdn"], c["sde"], c["sdu"]]) * gain[:, None]
    std = np.maximum(std, 0.005)
    g = GnssData(np.asarray(c["time"], float), np.column_stack([c["lat"], c["lon"],
                                                                 c["height"]]),
                 std, str(path))
    if all(k in c for k in ("vn", "ve", "vu")):
        g.vel = np.column_stack([c["vn"], c["ve"], -np.asarray(c["vu"])])
    return g


def read_rtkexplorer(folder, imu_time_shift_s: float | None = None) -> Recording:
    """An rtklibexplorer recording folder (``drive_0708`` or ``walk_0827``; module
    docstring). *imu_time_shift_s* None takes the author's value."""
    folder = Path(folder)
    if not folder.is_dir():
        raise InputError(str(folder), "not a folder (an rtklibexplorer recording)")
    imus = sorted(p for p in folder.glob("imu_*.csv") if not p.stem.endswith("_sf"))
    poss = sorted(folder.glob("gnss_*_sf.pos"))
    if not imus or not poss:
        raise InputError(str(folder), "expected imu_NNNN.csv (+ .tag) and gnss_NNNN_sf.pos")
    kind = "walk" if folder.name.startswith("walk") else "drive"
    setup = RTK_SETUP[kind]
    shift = setup["imu_time_shift_s"] if imu_time_shift_s is None else imu_time_shift_s
    imu = read_rtk_imu(imus[0], setup["rpy"], shift)
    gnss = read_rtk_pos(poss[0])
    lever = np.subtract(setup["antenna"], setup["imu"])
    cfg = _config(RTK_DRIVE_NOISE, RTK_INIT_BIAS, lever, 100.0 if kind == "drive" else 150.0,
                  f"{folder} (author's IMU noise figures)")
    notes = [
        f"IMU counter mapped to GPST over the .tag span, {shift:+.3f} s logging delay "
        "(author's value)",
        f"sensor → body by the author's mounting roll/pitch/yaw {setup['rpy']} deg",
        f"antenna lever arm {tuple(round(float(v), 3) for v in lever)} m (author's "
        "offsets)",
        "GNSS heights are above mean sea level (receiver hMSL); the trajectory's too",
        "σ from the receiver (sdn, sde, sdu), ×2 float, ×5 single",
    ]
    params = {"nhc": kind == "drive", "zupt": True, "scale_factors": False,
              "zupt_acc_std": 0.5, "zupt_gyro_dps": 3.0, "zupt_speed": 0.2,
              "align_speed": 2.0}
    if kind == "walk":
        notes.append("hand-held: the clock offset is not estimated from the turns (the "
                     "walker turns the IMU before the track turns); the author's timing is "
                     "kept unless --clock-offset is given")
    return Recording(f"rtklibexplorer {folder.name}", imu, gnss, cfg, params, None, notes,
                     clock_from_turns=kind != "walk")


def recording_kind(folder) -> str | None:
    """``"comma2k19"``, ``"rtklibexplorer"`` or None for a folder that is neither."""
    folder = Path(folder)
    if (folder / "processed_log").is_dir() and (folder / "global_pose").is_dir():
        return "comma2k19"
    if any(folder.glob("imu_*.csv")) and any(folder.glob("gnss_*_sf.pos")):
        return "rtklibexplorer"
    return None


def recordings_in(folder) -> list[Path]:
    """The recording folders directly inside *folder*, sorted by name."""
    folder = Path(folder)
    if not folder.is_dir():
        return []
    return sorted(p for p in folder.iterdir() if p.is_dir() and recording_kind(p))


def read_recording(folder) -> Recording:
    """Recognise a recording folder: comma2k19 segment or rtklibexplorer recording. A
    folder of recordings is refused with the list of the recordings in it."""
    folder = Path(folder)
    if not folder.is_dir():
        raise InputError(str(folder), "not a folder (give a recording folder)")
    kind = recording_kind(folder)
    if kind == "comma2k19":
        return read_comma2k19(folder)
    if kind == "rtklibexplorer":
        return read_rtkexplorer(folder)
    inside = recordings_in(folder)
    if inside:
        raise InputError(str(folder), f"a folder of {len(inside)} recordings, give one of "
                         "them: " + ", ".join(f"{p.name} ({recording_kind(p)})"
                                              for p in inside))
    raise InputError(str(folder), "not a known recording folder (comma2k19 segment with "
                     "processed_log/ and global_pose/, or rtklibexplorer imu_*.csv + "
                     "gnss_*_sf.pos)")


# ------------------------------------------------------------------ processing
#: Which clock a recording's timing estimate moves: comma2k19's IMU and reference share the
#: logger clock, so the GNSS tags move; rtklibexplorer's GNSS is GPST, so the IMU moves.
SHIFTED_CLOCK = {"comma2k19": "gnss"}


def shifted(rec: Recording, seconds: float) -> Recording:
    """*rec* with the GNSS-minus-IMU clock offset changed by *seconds*: the GNSS epochs
    later by *seconds* (comma2k19) or the IMU epochs earlier (rtklibexplorer)."""
    if SHIFTED_CLOCK.get(rec.name) == "gnss":
        g = rec.gnss
        gnss = GnssData(g.time + seconds, g.llh, g.std, g.source, g.vel)
        return Recording(rec.name, rec.imu, gnss, rec.config, rec.params, rec.reference,
                         rec.notes, rec.clock_from_turns)
    imu = ImuData(rec.imu.time - seconds, rec.imu.inc, rec.imu.source)
    return Recording(rec.name, imu, rec.gnss, rec.config, rec.params, rec.reference,
                     rec.notes, rec.clock_from_turns)


def estimate_time_shift(rec: Recording, params: dict | None = None):
    """GNSS-minus-IMU clock offset of *rec* from its turns (:mod:`.clock`, no filter pass):
    ``(offset_s, ClockOffset)``; ``(0.0, None)`` — the recording's own timing — for a
    hand-held IMU (:attr:`Recording.clock_from_turns`). *params* (the options in force,
    the user's over the recording's) give the mounting, whose forward axis the speed
    signal uses."""
    from hydrosync_core.methods.gins_smoother.clock import estimate_clock_offset
    from hydrosync_core.methods.gins_smoother.params import GinsParams

    if not rec.clock_from_turns:
        return 0.0, None
    p = GinsParams.from_dict({**rec.params, **(params or {})})
    c_vb = euler_dcm(*p.mounting_deg)  # vehicle ← body
    est = estimate_clock_offset(rec.imu, rec.gnss, forward_b=c_vb[0, :],
                                lever_arm_m=rec.config.lever_arm_m)
    return est.offset_s, est


def time_shift_by_residuals(rec: Recording, params: dict | None = None,
                            half_range_s: float = 0.3, step_s: float = 0.05
                            ) -> tuple[float, list[tuple[float, float]]]:
    """Second opinion on the clock offset (benchmarks only: 13 smoother runs): the offset
    that minimises the smoothed horizontal GNSS residuals over a grid of ±*half_range_s*,
    refined by a parabola through the best three. Returns the offset and the (offset,
    residual RMS m) grid. *params* are the user's options (over the recording's)."""
    from hydrosync_core.methods.gins_smoother.filter import run_gins
    from hydrosync_core.methods.gins_smoother.params import GinsParams

    p = GinsParams.from_dict({**rec.params, **(params or {}), "smooth": True,
                              "gnss_noise": "file", "gnss_corr_time_s": 0.0})
    grid = []
    for d in np.arange(-half_range_s, half_range_s + 1e-9, step_s):
        r = shifted(rec, float(d))
        res = run_gins(r.imu, r.gnss, r.config, p)
        e = res.gnss["residual"]
        ok = np.isfinite(e).all(axis=1)
        grid.append((float(d), float(np.sqrt(np.mean(np.sum(e[ok, :2] ** 2, axis=1))))))
    x = np.array([g[0] for g in grid])
    y = np.array([g[1] for g in grid])
    i = int(np.clip(np.argmin(y), 1, x.size - 2))
    a, b, _c = np.polyfit(x[i - 1:i + 2], y[i - 1:i + 2], 2)
    best = float(-b / (2 * a)) if a > 0 else float(x[np.argmin(y)])
    return float(np.clip(best, x[0], x[-1])), grid


def outage_test(rec: Recording, windows, params: dict | None = None) -> dict:
    """Remove the GNSS epochs inside *windows* and measure the drift against the removed
    fixes themselves (the antenna, lever arm applied) and against the reference if any.

    Returns ``windows`` (per window: length, and for forward and smoothed the largest
    horizontal and vertical distance to the removed fixes, m), ``normalised`` (per
    solution, the errors at every removed fix N/E/D divided by ``√(σ_trajectory² +
    σ_fix²)`` — the removed fix taken as the truth minus its own σ; (k, 3)) and the run's
    result.
    """
    from hydrosync_core.methods.gins_smoother.evaluate import error_series
    from hydrosync_core.methods.gins_smoother.filter import gnss_residuals, run_gins
    from hydrosync_core.methods.gins_smoother.params import GinsParams

    p = GinsParams.from_dict({**rec.params, **(params or {}), "smooth": True})
    res = run_gins(rec.imu, rec.gnss.without(windows), rec.config, p)
    rows = []
    ref_err = {}
    if rec.reference is not None:
        for name in ("forward", "smoothed"):
            ref_err[name] = error_series(getattr(res, name), rec.reference)
    resid = {name: gnss_residuals(rec.gnss, getattr(res, name), rec.config.lever_arm_m)
             for name in ("forward", "smoothed")}
    removed = np.zeros(rec.gnss.time.size, bool)
    for a, b in windows:
        removed |= (rec.gnss.time > a) & (rec.gnss.time < b)
    normalised = {}
    for name, r in resid.items():
        tr = getattr(res, name)
        sd = np.column_stack([np.interp(rec.gnss.time[removed], tr.time, tr.pos_std[:, c])
                              for c in range(3)])
        z = r[removed] / np.sqrt(sd ** 2 + rec.gnss.std[removed] ** 2)
        normalised[name] = z[np.isfinite(z).all(axis=1)]
    for a, b in windows:
        m = (rec.gnss.time > a) & (rec.gnss.time < b)
        row = {"start": float(a), "end": float(b), "length_s": float(b - a)}
        for name, r in resid.items():
            rr = r[m]
            ok = np.isfinite(rr).all(axis=1)
            row[f"{name}_max_h_m"] = float(np.max(np.hypot(rr[ok, 0], rr[ok, 1]))) \
                if ok.any() else None
            row[f"{name}_max_v_m"] = float(np.max(np.abs(rr[ok, 2]))) if ok.any() else None
            if name in ref_err:
                e = ref_err[name]
                mr = (e["time"] > a) & (e["time"] < b)
                row[f"{name}_ref_max_h_m"] = float(np.max(e["horizontal"][mr])) \
                    if mr.any() else None
        rows.append(row)
    return {"windows": rows, "normalised": normalised, "result": res}


def moving_windows(rec: Recording, length_s: float, every_s: float, min_speed: float = 2.0,
                   margin_s: float = 10.0) -> list[tuple[float, float]]:
    """Outage windows of *length_s* every *every_s* where the GNSS says the vehicle moves
    faster than *min_speed* throughout, *margin_s* clear of the ends."""
    from hydrosync_core.methods.gins_smoother.alignment import gnss_velocity

    g = rec.gnss
    v = gnss_velocity(g)
    speed = np.hypot(v[:, 0], v[:, 1])
    t0 = max(g.time[0], rec.imu.time[0]) + margin_s
    t1 = min(g.time[-1], rec.imu.time[-1]) - margin_s
    out = []
    a = t0
    while a + length_s <= t1:
        m = (g.time >= a) & (g.time <= a + length_s)
        if m.any() and np.nanmin(speed[m]) >= min_speed:
            out.append((float(a), float(a + length_s)))
            a += every_s
        else:
            a += 1.0
    return out
