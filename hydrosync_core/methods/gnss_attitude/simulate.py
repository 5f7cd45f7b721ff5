"""Simulated GNSS antenna arrays: what real arrays see, with the truth kept.

A vessel (or car) moves at constant speed while its heading turns through all four
quadrants and it rolls and pitches; every antenna's position is the reference point plus
the rotated body-frame offset, plus noise: white noise and a multipath-like first-order
Gauss–Markov part (correlation time ``multipath_tau_s``), per antenna and axis. Solutions
flip between fixed (Q=1) and float (Q=2, larger noise and a bias) as a two-state Markov
chain; epochs go missing at random; one antenna can drop out for a while. The output is
what an RTKLIB ``.pos`` file holds (:func:`write_pos` writes one).

Frames: body FRD, local NED at the start point, ECEF WGS84. Angles in degrees at the
edges, times GPS seconds.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from datetime import datetime, timedelta

import numpy as np

from hydrosync_core.atomic import write_text_atomic
from hydrosync_core.geodesy import ecef_to_geodetic, ecef_to_ned_matrix, geodetic_to_ecef
from hydrosync_core.rotations import euler_zyx_matrix

#: Four antennas on a survey launch (m, FRD): bow, stern, port and starboard of the mast.
LAUNCH = {"A1": [0.0, 0.0, 0.0], "A2": [3.0, 0.2, 0.05], "A3": [0.6, 1.8, 0.0],
          "A4": [0.4, -1.7, 0.1]}
GPS_EPOCH = datetime(1980, 1, 6)


@dataclass(frozen=True)
class ArrayConfig:
    """What to simulate.

    Attributes
    ----------
    duration_s, rate_hz : float
        Length of the record and the output rate.
    start_gps_s : float
        Continuous GPS seconds of the first epoch.
    lat_deg, lon_deg, height_m : float
        Start point.
    speed_mps : float
        Speed over ground along the heading.
    turns : float
        Full heading turns over the record (1 → all quadrants).
    roll_amp_deg, pitch_amp_deg, roll_period_s, pitch_period_s : float
        Sinusoidal motion.
    sigma_h_m, sigma_v_m : float
        Per-antenna fixed-solution noise (1σ, horizontal and vertical).
    multipath_fraction : float
        Share of the variance in the correlated (Gauss–Markov) part.
    multipath_tau_s : float
        Its correlation time.
    float_rate_per_h, float_mean_s : float
        Float episodes per hour per antenna and their mean length.
    float_sigma_m : float
        Extra noise of float solutions (1σ per axis, plus a constant bias of that size).
    missing_prob : float
        Probability that an antenna's epoch is missing.
    dropout : tuple (antenna, start_s, end_s) or None
        One antenna absent from start_s to end_s after the first epoch.
    """

    duration_s: float = 600.0
    rate_hz: float = 1.0
    start_gps_s: float = 2137 * 604800.0 + 422922.0
    lat_deg: float = 30.5
    lon_deg: float = 114.0
    height_m: float = 20.0
    speed_mps: float = 3.0
    turns: float = 1.0
    roll_amp_deg: float = 6.0
    pitch_amp_deg: float = 2.5
    roll_period_s: float = 9.0
    pitch_period_s: float = 6.5
    sigma_h_m: float = 0.006
    sigma_v_m: float = 0.012
    multipath_fraction: float = 0.5
    multipath_tau_s: float = 60.0
    float_rate_per_h: float = 6.0
    float_mean_s: float = 20.0
    float_sigma_m: float = 0.05
    missing_prob: float = 0.01
    dropout: tuple[str, float, float] | None = ("A4", 200.0, 260.0)


def _gauss_markov(rng, n: int, dt: float, tau: float, sigma: np.ndarray) -> np.ndarray:
    """First-order Gauss–Markov noise, stationary std *sigma* (per column)."""
    from scipy.signal import lfilter

    phi = np.exp(-dt / tau)
    w = rng.standard_normal((n, sigma.size)) * sigma * np.sqrt(1 - phi**2)
    w[0] = rng.standard_normal(sigma.size) * sigma
    return lfilter([1.0], [1.0, -phi], w, axis=0)


def _two_state(rng, n: int, p_enter: float, p_leave: float) -> np.ndarray:
    """Two-state Markov chain (False = fixed, True = float) from geometric run lengths."""
    state = np.zeros(n, bool)
    i, floating = 0, False
    while i < n:
        p = p_leave if floating else p_enter
        run = int(rng.geometric(p)) if p > 0 else n
        state[i:i + run] = floating
        i += run
        floating = not floating
    return state


def simulate_array(antennas: dict[str, list[float]] | None = None,
                   config: ArrayConfig = ArrayConfig(), seed: int = 0) -> dict:
    """Simulate the antenna positions of an array.

    Returns
    -------
    dict
        ``"tracks"``: per antenna a dict of ``.pos``-like columns (``time`` TOW s, ``week``,
        ``gps_s``, ``x y z`` ECEF m, ``lat lon height``, ``q``, ``ns``, ``sdn sde sdu sdne
        sdeu sdun`` m, ``age``, ``ratio``), missing epochs removed; ``"truth"``: ``gps_s``,
        ``time``, ``heading``, ``pitch``, ``roll`` (deg) per epoch; ``"antennas"``: the
        body coordinates.
    """
    antennas = dict(LAUNCH if antennas is None else antennas)
    c = config
    rng = np.random.default_rng(seed)
    n = int(round(c.duration_s * c.rate_hz)) + 1
    t = np.arange(n) / c.rate_hz
    gps_s = c.start_gps_s + t
    heading = np.mod(37.0 + 360.0 * c.turns * t / max(c.duration_s, 1e-9), 360.0)
    roll = c.roll_amp_deg * np.sin(2 * np.pi * t / c.roll_period_s + 0.3)
    pitch = c.pitch_amp_deg * np.sin(2 * np.pi * t / c.pitch_period_s + 1.1)
    R = euler_zyx_matrix(np.radians(roll), np.radians(pitch), np.radians(heading))
    # reference point track in NED at the start point
    dt = 1.0 / c.rate_hz
    hd = np.radians(heading)
    vel = c.speed_mps * np.column_stack([np.cos(hd), np.sin(hd), np.zeros(n)])
    ref_ned = np.cumsum(vel, axis=0) * dt
    origin = geodetic_to_ecef(c.lat_deg, c.lon_deg, c.height_m)
    C = ecef_to_ned_matrix(c.lat_deg, c.lon_deg)
    sig = np.array([c.sigma_h_m, c.sigma_h_m, c.sigma_v_m])
    tracks = {}
    for name, xyz in antennas.items():
        ned = ref_ned + np.einsum("nij,j->ni", R, np.asarray(xyz, float))
        white = rng.standard_normal((n, 3)) * sig * np.sqrt(1 - c.multipath_fraction)
        mp = _gauss_markov(rng, n, dt, c.multipath_tau_s, sig * np.sqrt(c.multipath_fraction))
        noise = white + mp
        # fixed/float two-state Markov chain
        p_enter = c.float_rate_per_h * dt / 3600.0
        p_leave = dt / max(c.float_mean_s, dt)
        state = _two_state(rng, n, p_enter, p_leave)
        bias = rng.standard_normal(3) * c.float_sigma_m
        noise[state] += bias + rng.standard_normal((int(state.sum()), 3)) * c.float_sigma_m
        ecef = origin + (ned + noise) @ C
        keep = rng.random(n) >= c.missing_prob
        if c.dropout is not None and c.dropout[0] == name:
            keep &= ~((t >= c.dropout[1]) & (t < c.dropout[2]))
        lat, lon, h = ecef_to_geodetic(ecef)
        sd_scale = np.where(state, c.float_sigma_m * 1.5, 1.0)
        cols = {
            "gps_s": gps_s, "week": np.floor(gps_s / 604800.0).astype(np.int64),
            "time": gps_s - np.floor(gps_s / 604800.0) * 604800.0,
            "x": ecef[:, 0], "y": ecef[:, 1], "z": ecef[:, 2], "lat": lat, "lon": lon,
            "height": h, "q": np.where(state, 2, 1).astype(np.int8),
            "ns": np.full(n, 18, np.int16),
            "sdn": np.where(state, sd_scale, c.sigma_h_m), "sde": np.where(state, sd_scale,
                                                                             c.sigma_h_m),
            "sdu": np.where(state, sd_scale * 2, c.sigma_v_m), "sdne": np.zeros(n),
            "sdeu": np.zeros(n), "sdun": np.zeros(n), "age": np.zeros(n),
            "ratio": np.where(state, 0.0, 12.0),
        }
        tracks[name] = {key: v[keep] for key, v in cols.items()}
    truth = {"gps_s": gps_s, "time": gps_s - np.floor(gps_s / 604800.0) * 604800.0,
             "heading": heading, "pitch": pitch, "roll": roll}
    return {"tracks": tracks, "truth": truth, "antennas": antennas}


def random_attitudes(n: int, seed: int = 0, max_pitch_deg: float = 80.0) -> np.ndarray:
    """(heading, pitch, roll) degrees covering every quadrant: heading 0–360°, roll ±180°."""
    rng = np.random.default_rng(seed)
    return np.column_stack([rng.uniform(0, 360, n), rng.uniform(-max_pitch_deg,
                                                                max_pitch_deg, n),
                            rng.uniform(-180, 180, n)])


def write_pos(path: str | os.PathLike, track: dict, time_format: str = "calendar") -> None:
    """Write an antenna track as an RTKLIB llh ``.pos`` file (GPST)."""
    legend = ("%  GPST                  latitude(deg) longitude(deg)  height(m)   Q  ns   "
              "sdn(m)   sde(m)   sdu(m)  sdne(m)  sdeu(m)  sdun(m) age(s)  ratio")

    def writer(fh) -> None:
        fh.write("% program   : HydroSync simulator\n")
        fh.write("% (lat/lon/height=WGS84/ellipsoidal,Q=1:fix,2:float,3:sbas,4:dgps,"
                 "5:single,6:ppp,ns=# of satellites)\n")
        fh.write(legend + "\n")
        for i in range(track["gps_s"].size):
            g = float(track["gps_s"][i])
            if time_format == "calendar":
                stamp = (GPS_EPOCH + timedelta(seconds=round(g, 3))).strftime(
                    "%Y/%m/%d %H:%M:%S.%f")[:-3]
            else:
                week = int(g // 604800)
                stamp = f"{week} {g - week * 604800:.3f}"
            fh.write(f"{stamp} {track['lat'][i]:14.9f} {track['lon'][i]:14.9f} "
                     f"{track['height'][i]:10.4f} {int(track['q'][i]):3d} "
                     f"{int(track['ns'][i]):3d} {track['sdn'][i]:8.4f} {track['sde'][i]:8.4f} "
                     f"{track['sdu'][i]:8.4f} {track['sdne'][i]:8.4f} "
                     f"{track['sdeu'][i]:8.4f} {track['sdun'][i]:8.4f} "
                     f"{track['age'][i]:6.2f} {track['ratio'][i]:6.1f}\n")

    write_text_atomic(path, writer)
