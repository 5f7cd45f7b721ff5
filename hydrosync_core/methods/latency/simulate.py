"""Simulated survey day for the latency module: GNSS heights and attitude with a known delay.

The vessel motion is a stationary random sea: heave, roll and pitch are synthesised by
inverse FFT with random phases from JONSWAP-shaped spectra (a sum of sinusoids on the FFT
frequency grid). The GNSS antenna sits at ``lever_arm_m`` (body FRD, metres) from the
motion sensor reference point, so its height is

    h(t) = tide(t) + heave(t) + H_R(t) + multipath(t) + white noise,

with H_R the rotation-induced heave (seed eq. 2). The motion sensor reports heave with a
slowly varying error (Gauss–Markov), the GNSS heights carry white noise plus a
time-correlated multipath-like error (first-order Gauss–Markov / AR(1)). GNSS epochs
measured at attitude-time ``t`` are tagged ``t + latency_s`` (``formats.md``).

Survey lines are time windows separated by turns; each line is preceded by a *run-in*
(``run_in_s``) in which the vessel is still settling (a decaying squat transient of a
few cm in the antenna height). The lines' ``start`` is the end of the run-in unless
``lines_include_run_in`` is set, in which case the run-in is inside the window and the
method's ``skip_s`` must remove it (the seed skips the first minute of each line).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from hydrosync_core.atomic import write_text_atomic
from hydrosync_core.methods.latency.heave import induced_heave


@dataclass(frozen=True)
class DayConfig:
    """Parameters of a simulated survey day (SI units, angles in degrees)."""

    latency_s: float = 0.29
    n_lines: int = 13
    line_s: float = 120.0
    turn_s: float = 60.0
    run_in_s: float = 20.0
    lines_include_run_in: bool = False
    gnss_hz: float = 1.0
    attitude_hz: float = 50.0
    lever_arm_m: tuple[float, float, float] = (-1.5, 2.0, -6.0)
    hs_m: float = 0.6
    tp_s: float = 6.0
    roll_amp_deg: float = 3.0
    roll_period_s: float = 8.0
    pitch_amp_deg: float = 1.2
    tide_rate_m_per_h: float = 0.4
    gnss_white_m: float = 0.05
    multipath_m: float = 0.05
    multipath_tau_s: float = 30.0
    heave_error_m: float = 0.05
    heave_error_tau_s: float = 5.0
    squat_m: float = 0.08
    t0: float = 345600.0
    heave_white_m: float = 0.0
    attitude_noise_deg: float = 0.0
    heave_filter_order: int = 0
    """Order of the motion sensor's causal Butterworth high-pass heave filter (0: none)."""
    heave_filter_period_s: float = 20.0
    """Its cut-off period (s); sensors use 10–30 s."""
    heave_filter_compensated: bool = False
    """The vendor's phase compensation: the same filter run forwards and backwards
    (zero phase), as a delayed heave output does."""
    gnss_blend_tau_s: float = 0.0
    """> 0: INS-blended heights: the GNSS errors pass a first-order low-pass of this time
    constant (the complementary filter's GNSS branch; the motion is the INS's), instead of
    raw RTK white noise."""
    attitude_out_hz: float = 0.0
    attitude_tag_delay_s: float = 0.0
    """The attitude's time-tag convention: records tagged this long after they were
    measured (e.g. half a sample for a tag at the end of the integration interval). The
    relative delay to find is then ``latency_s − attitude_tag_delay_s``."""
    """> 0: the attitude is reported at this rate (every k-th sample of the internal
    *attitude_hz* record), e.g. 1 Hz like the Seapath logs' PSXN records."""


SCENARIOS: dict[str, dict] = {
    # Almost noiseless: 1 cm white RTK noise, nothing else.
    "clean": dict(gnss_white_m=0.01, multipath_m=0.0, heave_error_m=0.0, squat_m=0.0),
    # The simulator's defaults: R 0.85–0.95 at 1 Hz as in table 1 of Qi et al. (2010).
    "paper": {},
    # Coloured errors (issue #15): the motion sensor's heave with 5 cm white noise at its
    # own rate and a long-period error (AR(1), τ 30 s: its high-pass heave filter settling),
    # RTK heights with white noise and a correlated part (τ 60 s: multipath, troposphere),
    # 0.03° roll/pitch noise.
    "coloured": dict(gnss_white_m=0.03, multipath_m=0.04, multipath_tau_s=60.0,
                     heave_error_m=0.06, heave_error_tau_s=30.0, heave_white_m=0.05,
                     attitude_noise_deg=0.03),
}
"""Noise scenarios of the benchmarks (overrides of :class:`DayConfig`)."""

SEA_STATES: dict[str, dict] = {
    "calm": dict(hs_m=0.3, tp_s=5.0, roll_amp_deg=1.5, pitch_amp_deg=0.6),
    "moderate": {},
    "rough": dict(hs_m=1.5, tp_s=8.0, roll_amp_deg=5.0, pitch_amp_deg=2.0),
}
"""Sea states of the benchmarks (overrides of :class:`DayConfig`)."""


def scenario(name: str = "paper", sea: str = "moderate", **overrides) -> DayConfig:
    """A :class:`DayConfig` from a noise scenario, a sea state and further overrides."""
    return DayConfig(**{**SCENARIOS[name], **SEA_STATES[sea], **overrides})


def _jonswap(f: np.ndarray, tp: float, gamma: float = 3.3) -> np.ndarray:
    """Un-normalised JONSWAP spectral shape over frequencies *f* (Hz)."""
    fp = 1.0 / tp
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        sigma = np.where(f <= fp, 0.07, 0.09)
        pm = f ** -5.0 * np.exp(-1.25 * (fp / f) ** 4)
        peak = gamma ** np.exp(-((f - fp) ** 2) / (2 * sigma**2 * fp**2))
        s = pm * peak
    return np.nan_to_num(s, nan=0.0, posinf=0.0)


def _random_sea(rng, n: int, fs: float, tp: float, std: float, gamma: float = 3.3) -> np.ndarray:
    """Stationary series of *n* samples at *fs* Hz with a JONSWAP spectrum of peak period *tp*.

    Random-phase inverse FFT: a sum of sinusoids on the FFT frequency grid, scaled to *std*.
    """
    f = np.fft.rfftfreq(n, 1.0 / fs)
    amp = np.sqrt(_jonswap(f, tp, gamma))
    spec = amp * np.exp(2j * np.pi * rng.random(f.size))
    x = np.fft.irfft(spec, n)
    return x * (std / x.std())


def _gauss_markov(rng, n: int, dt: float, tau: float, std: float) -> np.ndarray:
    """First-order Gauss–Markov (AR(1)) series with correlation time *tau* (s), stationary *std*."""
    from scipy.signal import lfilter

    phi = np.exp(-dt / tau)
    e = rng.standard_normal(n) * std * np.sqrt(1 - phi**2)
    e[0] = rng.standard_normal() * std
    return lfilter([1.0], [1.0, -phi], e)


def _first_order_lowpass(x: np.ndarray, dt: float, tau: float) -> np.ndarray:
    """*x* (sampled every *dt* s) through a first-order low-pass of time constant *tau*
    (s), scaled back to the input's standard deviation (a blend moves errors in frequency,
    it does not remove them)."""
    from scipy.signal import lfilter

    a = np.exp(-dt / tau)
    y = lfilter([1.0 - a], [1.0, -a], x, zi=[a * x[0]])[0]
    return y * (x.std() / max(y.std(), 1e-300))


def _sensor_heave_filter(heave: np.ndarray, fs: float, cfg: DayConfig) -> np.ndarray:
    """The motion sensor's heave: causal high-pass (or zero-phase when compensated)."""
    from scipy.signal import sosfilt, sosfiltfilt

    from hydrosync_core.methods.latency.heave_filter import highpass_sos

    sos = highpass_sos(cfg.heave_filter_order, cfg.heave_filter_period_s, fs)
    if cfg.heave_filter_compensated:
        return sosfiltfilt(sos, heave)
    return sosfilt(sos, heave)


def simulate_day(config: DayConfig | None = None, seed: int = 0) -> dict:
    """Simulate a survey day.

    Returns
    -------
    dict
        ``gnss``: {time (s, GNSS time tags incl. latency), height (m)};
        ``attitude``: {time (s), roll, pitch, heading (deg), heave (m, up)};
        ``lines``: {name, start, end} (s, attitude time scale);
        ``truth``: {latency_s, lever_arm_m, gnss_true_time, ...}.
    """
    cfg = config or DayConfig()
    rng = np.random.default_rng(seed)
    period = cfg.run_in_s + cfg.line_s + cfg.turn_s
    duration = cfg.n_lines * period + 2 * abs(cfg.latency_s) + 10.0
    fs = cfg.attitude_hz
    n = int(np.ceil(duration * fs)) + 1
    t = cfg.t0 + np.arange(n) / fs

    # Vessel motion at the motion sensor reference point (heave up, m; angles rad).
    heave = _random_sea(rng, n, fs, cfg.tp_s, cfg.hs_m / 4.0)
    roll = _random_sea(rng, n, fs, cfg.roll_period_s, np.radians(cfg.roll_amp_deg), gamma=7.0)
    pitch = _random_sea(rng, n, fs, cfg.tp_s * 0.9, np.radians(cfg.pitch_amp_deg))
    # Heading: line courses alternating 0/180 deg with small yaw oscillations; turns linear.
    phase = (t - cfg.t0) % period
    k = ((t - cfg.t0) // period).astype(int)
    course = np.where(k % 2 == 0, 10.0, 190.0)
    turning = phase >= cfg.run_in_s + cfg.line_s
    frac = (phase - cfg.run_in_s - cfg.line_s) / cfg.turn_s
    heading = np.where(turning, course + 180.0 * frac, course)
    heading = (heading + np.degrees(_random_sea(rng, n, fs, 12.0, np.radians(1.0)))) % 360.0

    lever = np.asarray(cfg.lever_arm_m, dtype=float)
    # Seed eq. 2: true height change of the antenna = heave + rotation-induced heave.
    h_true = heave + induced_heave(roll, pitch, lever)
    tide = cfg.tide_rate_m_per_h * (t - cfg.t0) / 3600.0 + 0.3 * np.sin(
        2 * np.pi * (t - cfg.t0) / 44712.0
    )
    # Run-in transient: squat settling after each turn.
    squat = -cfg.squat_m * np.exp(-phase / (cfg.run_in_s / 3.0)) * (phase < cfg.run_in_s + 1)
    height_att_rate = 42.0 + tide + h_true + squat

    # GNSS epochs on the attitude-time scale, measured then tagged late by latency_s.
    g_dt = 1.0 / cfg.gnss_hz
    t_meas = np.arange(t[0] + abs(cfg.latency_s) + 1.0, t[-1] - abs(cfg.latency_s) - 1.0, g_dt)
    height = np.interp(t_meas, t, height_att_rate)
    m = t_meas.size
    errors = rng.standard_normal(m) * cfg.gnss_white_m
    errors += _gauss_markov(rng, m, g_dt, cfg.multipath_tau_s, cfg.multipath_m)
    if cfg.gnss_blend_tau_s > 0:
        errors = _first_order_lowpass(errors, g_dt, cfg.gnss_blend_tau_s)
    height += errors
    tags = t_meas + cfg.latency_s

    heave_meas = heave + _gauss_markov(rng, n, 1.0 / fs, cfg.heave_error_tau_s, cfg.heave_error_m)
    # Coloured-noise additions (drawn last, so the defaults reproduce earlier days exactly).
    if cfg.heave_white_m > 0:
        heave_meas += rng.standard_normal(n) * cfg.heave_white_m
    roll_meas, pitch_meas = roll, pitch
    if cfg.attitude_noise_deg > 0:
        noise = np.radians(cfg.attitude_noise_deg)
        roll_meas = roll + rng.standard_normal(n) * noise
        pitch_meas = pitch + rng.standard_normal(n) * noise
    if cfg.heave_filter_order > 0:
        heave_meas = _sensor_heave_filter(heave_meas, fs, cfg)
    t_out = t + cfg.attitude_tag_delay_s
    if cfg.attitude_out_hz > 0:
        keep = slice(None, None, max(int(round(fs / cfg.attitude_out_hz)), 1))
        t_out, heading = t_out[keep], heading[keep]
        roll_meas, pitch_meas, heave_meas = roll_meas[keep], pitch_meas[keep], heave_meas[keep]

    starts = cfg.t0 + np.arange(cfg.n_lines) * period
    if not cfg.lines_include_run_in:
        starts = starts + cfg.run_in_s
    ends = cfg.t0 + np.arange(cfg.n_lines) * period + cfg.run_in_s + cfg.line_s
    width = max(2, len(str(cfg.n_lines)))
    names = np.array([f"L{i + 1:0{width}d}" for i in range(cfg.n_lines)])
    return {
        "gnss": {"time": tags, "height": height},
        "attitude": {
            "time": t_out, "roll": np.degrees(roll_meas), "pitch": np.degrees(pitch_meas),
            "heading": heading, "heave": heave_meas,
        },
        "lines": {"name": names, "start": starts, "end": ends},
        "truth": {
            "latency_s": cfg.latency_s - cfg.attitude_tag_delay_s,
            "lever_arm_m": lever.tolist(),
            "gnss_true_time": t_meas,
        },
    }


def write_day_csv(day: dict, directory: str | os.PathLike) -> dict[str, Path]:
    """Write ``gnss.csv``, ``attitude.csv`` and ``lines.csv`` (``formats.md``) into *directory*."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    paths = {}
    for name, columns, fmt in (
        ("gnss", ("time", "height"), ("%.4f", "%.4f")),
        ("attitude", ("time", "roll", "pitch", "heading", "heave"),
         ("%.4f", "%.4f", "%.4f", "%.3f", "%.4f")),
    ):
        table = np.column_stack([day[name][c] for c in columns])
        path = directory / f"{name}.csv"

        def writer(fh, table=table, columns=columns, fmt=fmt):
            np.savetxt(fh, table, fmt=fmt, delimiter=",", header=",".join(columns), comments="")

        write_text_atomic(path, writer)
        paths[name] = path
    lines = day["lines"]
    path = directory / "lines.csv"
    write_text_atomic(path, lambda fh: fh.write("name,start,end\n" + "".join(
        f"{n},{s:.3f},{e:.3f}\n" for n, s, e in zip(lines["name"], lines["start"], lines["end"],
                                                   strict=True))))
    paths["lines"] = path
    return paths
