"""The sensor configuration of a GNSS/INS run: initial state, IMU noise, antenna lever arm.

Read from a KF-GINS YAML file as it is (``kf-gins.yaml``; the keys and units of the
KF-GINS software, see ``docs/formats.md``) or from the same keys in a JSON file. Units at
this edge are those of KF-GINS: degrees, deg/h, deg/√h, m/s/√h, mGal, ppm, hours; the
:class:`SensorConfig` holds SI units and radians.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from hydrosync_core.errors import InputError

D2R = math.pi / 180.0
MGAL = 1e-5  # m/s²
PPM = 1e-6


@dataclass(frozen=True)
class ImuNoise:
    """IMU error model per axis (x, y, z of b), SI units.

    Attributes
    ----------
    arw : angle random walk, rad/√s
    vrw : velocity random walk, m/s/√s
    gb_std, ab_std : bias instability (1σ of the Gauss-Markov process), rad/s and m/s²
    gs_std, as_std : scale-factor instability (1σ), dimensionless
    corr_time : correlation time of the Gauss-Markov processes, s
    """

    arw: tuple[float, float, float]
    vrw: tuple[float, float, float]
    gb_std: tuple[float, float, float]
    ab_std: tuple[float, float, float]
    gs_std: tuple[float, float, float]
    as_std: tuple[float, float, float]
    corr_time: float

    @classmethod
    def grade(cls, name: str) -> ImuNoise:
        """Typical figures of an IMU grade: ``navigation``, ``tactical`` or ``mems``."""
        table = {  # arw deg/√h, vrw m/s/√h, gb deg/h, ab mGal, scale ppm, T h
            "navigation": (0.003, 0.03, 0.027, 15.0, 300.0, 4.0),
            "tactical": (0.1, 0.1, 1.0, 100.0, 500.0, 1.0),
            "mems": (0.3, 0.5, 20.0, 2000.0, 3000.0, 0.5),
        }
        arw, vrw, gb, ab, sc, th = table[name]
        return cls.from_kfgins([arw] * 3, [vrw] * 3, [gb] * 3, [ab] * 3, [sc] * 3, [sc] * 3,
                               th)

    @classmethod
    def from_kfgins(cls, arw, vrw, gbstd, abstd, gsstd, asstd, corrtime_h) -> ImuNoise:
        """From KF-GINS units (deg/√h, m/s/√h, deg/h, mGal, ppm, ppm, h)."""
        def t3(values, k):
            return tuple(float(v) * k for v in values)
        return cls(t3(arw, D2R / 60.0), t3(vrw, 1.0 / 60.0), t3(gbstd, D2R / 3600.0),
                   t3(abstd, MGAL), t3(gsstd, PPM), t3(asstd, PPM), float(corrtime_h) * 3600)


@dataclass(frozen=True)
class SensorConfig:
    """Everything about the sensors and the start of a run (SI units, radians).

    Attributes
    ----------
    noise : ImuNoise
    lever_arm_m : antenna phase centre in b (FRD), m
    init_pos : (lat rad, lon rad, h m) of the IMU centre, or None (from GNSS)
    init_vel : NED m/s or None
    init_att : (roll, pitch, yaw) rad or None (alignment)
    init_pos_std : N, E, D m; init_vel_std m/s; init_att_std rad
    init_gyro_bias rad/s, init_acc_bias m/s², init_gyro_scale, init_acc_scale (-)
    init_bg_std, init_ba_std, init_sg_std, init_sa_std : initial std of the IMU errors
    start_time, end_time : processing interval, s (None = whole IMU file)
    imu_rate_hz : nominal IMU rate (the step used across an irregular interval)
    source : where it was read
    """

    noise: ImuNoise
    lever_arm_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    init_pos: tuple[float, float, float] | None = None
    init_vel: tuple[float, float, float] | None = None
    init_att: tuple[float, float, float] | None = None
    init_pos_std: tuple[float, float, float] = (0.05, 0.05, 0.1)
    init_vel_std: tuple[float, float, float] = (0.05, 0.05, 0.05)
    init_att_std: tuple[float, float, float] = (0.5 * D2R, 0.5 * D2R, 2.0 * D2R)
    init_gyro_bias: tuple[float, float, float] = (0.0, 0.0, 0.0)
    init_acc_bias: tuple[float, float, float] = (0.0, 0.0, 0.0)
    init_gyro_scale: tuple[float, float, float] = (0.0, 0.0, 0.0)
    init_acc_scale: tuple[float, float, float] = (0.0, 0.0, 0.0)
    init_bg_std: tuple[float, float, float] | None = None
    init_ba_std: tuple[float, float, float] | None = None
    init_sg_std: tuple[float, float, float] | None = None
    init_sa_std: tuple[float, float, float] | None = None
    start_time: float | None = None
    end_time: float | None = None
    imu_rate_hz: float = 200.0
    source: str = ""
    extra: dict = field(default_factory=dict, compare=False)

    def with_(self, **changes) -> SensorConfig:
        return replace(self, **changes)

    def to_dict(self) -> dict:
        """JSON-able form in KF-GINS units (what :func:`read_config` reads back)."""
        n = self.noise
        d: dict = {
            "imudatarate": self.imu_rate_hz,
            "starttime": self.start_time if self.start_time is not None else -1,
            "endtime": self.end_time if self.end_time is not None else -1,
            "antlever": list(self.lever_arm_m),
            "imunoise": {"arw": [v * 60 / D2R for v in n.arw], "vrw": [v * 60 for v in n.vrw],
                         "gbstd": [v * 3600 / D2R for v in n.gb_std],
                         "abstd": [v / MGAL for v in n.ab_std],
                         "gsstd": [v / PPM for v in n.gs_std],
                         "asstd": [v / PPM for v in n.as_std],
                         "corrtime": n.corr_time / 3600},
            "initposstd": list(self.init_pos_std), "initvelstd": list(self.init_vel_std),
            "initattstd": [v / D2R for v in self.init_att_std],
            "initgyrbias": [v * 3600 / D2R for v in self.init_gyro_bias],
            "initaccbias": [v / MGAL for v in self.init_acc_bias],
            "initgyrscale": [v / PPM for v in self.init_gyro_scale],
            "initaccscale": [v / PPM for v in self.init_acc_scale],
        }
        for key, val, k in (("initbgstd", self.init_bg_std, 3600 / D2R),
                            ("initbastd", self.init_ba_std, 1 / MGAL),
                            ("initsgstd", self.init_sg_std, 1 / PPM),
                            ("initsastd", self.init_sa_std, 1 / PPM)):
            if val is not None:
                d[key] = [v * k for v in val]
        if self.init_pos is not None:
            d["initpos"] = [self.init_pos[0] / D2R, self.init_pos[1] / D2R, self.init_pos[2]]
        if self.init_vel is not None:
            d["initvel"] = list(self.init_vel)
        if self.init_att is not None:
            d["initatt"] = [v / D2R for v in self.init_att]
        return d


def _vec(doc: dict, key: str, source: str, n: int = 3, required: bool = False):
    if key not in doc or doc[key] is None:
        if required:
            raise InputError(source, "missing", field=key)
        return None
    value = doc[key]
    if not isinstance(value, list | tuple) or len(value) != n:
        raise InputError(source, f"expected a list of {n} numbers", field=key)
    try:
        out = tuple(float(v) for v in value)
    except (TypeError, ValueError):
        raise InputError(source, f"expected a list of {n} numbers", field=key) from None
    if not all(math.isfinite(v) for v in out):
        raise InputError(source, "not a finite number", field=key)
    return out


def _num(doc: dict, key: str, source: str, default=None):
    if key not in doc or doc[key] is None:
        if default is None:
            raise InputError(source, "missing", field=key)
        return default
    try:
        v = float(doc[key])
    except (TypeError, ValueError):
        raise InputError(source, "not a number", field=key) from None
    if not math.isfinite(v):
        raise InputError(source, "not a finite number", field=key)
    return v


def config_from_dict(doc: dict, source: str = "config") -> SensorConfig:
    """A :class:`SensorConfig` from KF-GINS keys and units (see the module docstring).

    ``imunoise`` and ``antlever`` are required; the initial state is optional (missing
    ``initpos``/``initatt`` make the run align from the data).
    """
    if not isinstance(doc, dict):
        raise InputError(source, "not a mapping of KF-GINS keys")
    noise = doc.get("imunoise")
    if not isinstance(noise, dict):
        raise InputError(source, "missing or not a mapping", field="imunoise")
    src = f"{source}"
    vals = {k: _vec(noise, k, src, required=True)
            for k in ("arw", "vrw", "gbstd", "abstd")}
    gs = _vec(noise, "gsstd", src) or (0.0, 0.0, 0.0)
    as_ = _vec(noise, "asstd", src) or (0.0, 0.0, 0.0)
    corr = _num(noise, "corrtime", src)
    if corr <= 0:
        raise InputError(source, "correlation time must be positive (hours)",
                         field="imunoise.corrtime")
    for k, v in vals.items():
        if min(v) < 0:
            raise InputError(source, "negative noise figure", field=f"imunoise.{k}")
    n = ImuNoise.from_kfgins(vals["arw"], vals["vrw"], vals["gbstd"], vals["abstd"], gs, as_,
                             corr)
    lever = _vec(doc, "antlever", source, required=True)
    pos = _vec(doc, "initpos", source)
    att = _vec(doc, "initatt", source)
    if pos is not None and not (-90 <= pos[0] <= 90 and -360 <= pos[1] <= 360):
        raise InputError(source, "latitude/longitude out of range (degrees)", field="initpos")

    def std(key, default, k=1.0):
        v = _vec(doc, key, source)
        if v is None:
            return default
        if min(v) <= 0:
            raise InputError(source, "standard deviations must be positive (KF-GINS "
                             "gives NaN with 0)", field=key)
        return tuple(x * k for x in v)

    start = _num(doc, "starttime", source, default=-1.0)
    end = _num(doc, "endtime", source, default=-1.0)
    rate = _num(doc, "imudatarate", source, default=200.0)
    if rate <= 0:
        raise InputError(source, "must be positive (Hz)", field="imudatarate")

    def init_err(key, k):
        v = _vec(doc, key, source)
        return (0.0, 0.0, 0.0) if v is None else tuple(x * k for x in v)

    cfg = SensorConfig(
        noise=n, lever_arm_m=lever,
        init_pos=None if pos is None else (pos[0] * D2R, pos[1] * D2R, pos[2]),
        init_vel=_vec(doc, "initvel", source),
        init_att=None if att is None else tuple(a * D2R for a in att),
        init_pos_std=std("initposstd", (0.05, 0.05, 0.1)),
        init_vel_std=std("initvelstd", (0.05, 0.05, 0.05)),
        init_att_std=std("initattstd", (0.5 * D2R, 0.5 * D2R, 2.0 * D2R), D2R),
        init_gyro_bias=init_err("initgyrbias", D2R / 3600),
        init_acc_bias=init_err("initaccbias", MGAL),
        init_gyro_scale=init_err("initgyrscale", PPM),
        init_acc_scale=init_err("initaccscale", PPM),
        init_bg_std=std("initbgstd", None, D2R / 3600),
        init_ba_std=std("initbastd", None, MGAL),
        init_sg_std=std("initsgstd", None, PPM),
        init_sa_std=std("initsastd", None, PPM),
        start_time=None if start < 0 else start,
        end_time=None if end < 0 else end,
        imu_rate_hz=rate, source=source,
        extra={k: doc[k] for k in ("imupath", "gnsspath", "outputpath") if k in doc},
    )
    return cfg


def read_config(path: str | os.PathLike) -> SensorConfig:
    """Read a KF-GINS YAML configuration (as it is) or a JSON file with the same keys."""
    from hydrosync_core.configfiles import parse_json, parse_yaml, read_config_text

    p = Path(path)
    text = read_config_text(p, "KF-GINS configuration")  # gated, bounded
    parse = parse_json if p.suffix.lower() == ".json" else parse_yaml
    return config_from_dict(parse(text, str(p)), str(p))


def initial_covariance(cfg: SensorConfig, ns: int) -> np.ndarray:
    """Diagonal initial error covariance (ns × ns), SI units (module :mod:`.kernel`)."""
    n = cfg.noise
    sd = list(cfg.init_pos_std) + list(cfg.init_vel_std) + list(cfg.init_att_std)
    sd += list(cfg.init_bg_std or n.gb_std) + list(cfg.init_ba_std or n.ab_std)
    if ns == 21:
        sd += list(cfg.init_sg_std or n.gs_std) + list(cfg.init_sa_std or n.as_std)
    return np.diag(np.square(np.asarray(sd, float)))


def noise_densities(cfg: SensorConfig, ns: int) -> np.ndarray:
    """Continuous white-noise densities q (ns,) of :func:`.kernel.forward`."""
    n = cfg.noise
    T = n.corr_time
    q = [0.0] * 3 + list(np.square(n.vrw)) + list(np.square(n.arw))
    q += list(2 * np.square(n.gb_std) / T) + list(2 * np.square(n.ab_std) / T)
    if ns == 21:
        q += list(2 * np.square(n.gs_std) / T) + list(2 * np.square(n.as_std) / T)
    return np.asarray(q, float)
