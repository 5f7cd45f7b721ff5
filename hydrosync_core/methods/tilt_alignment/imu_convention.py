"""IMU sample conventions: what one row of ``imu.csv`` means, and the model grid.

An IMU either reports *instantaneous* samples (the rate and specific force at the time
tag) or *interval* samples (the mean rate and mean specific force — increments divided by
the interval — over one sample interval), and the tag of an interval sample sits at its
start, middle or end. Taking one for another shifts the attitude by half a sample (10 ms
samples: 5 ms), which the joint adjustment then reads as a GNSS time offset and as extra
IMU noise (issue #30).

:func:`to_model_grid` turns any convention into the one the solver integrates: on model
times ``τ_k``, gyro row *k* is the mean rate over ``[τ_k, τ_(k+1))`` and accelerometer row
*k* the specific force at ``τ_k`` or its mean over the interval; the joint model's window
weights turn either into what its second differences of the antenna path see (the
acceleration plus ``Δt²/12`` of its second derivative), in NED. Fourth-order formulas do
it: midpoint averages of two neighbours (second order) left a systematic error that the
adjustment read as six times the gyro noise on a fast three-sweep swing at 50 Hz.
"""

from __future__ import annotations

import numpy as np

#: The declared conventions (``--imu-convention``, ``pole.json`` key ``imu_convention``).
CONVENTIONS = ("instant", "interval-start", "interval-middle", "interval-end")
#: Where the tag sits in the sample's interval (fraction of the interval from its start).
TAG_FRACTION = {"interval-start": 0.0, "interval-middle": 0.5, "interval-end": 1.0}
#: The convention assumed when neither the options nor the data set declare one.
DEFAULT = "instant"


def _interval_means(x: np.ndarray) -> np.ndarray:
    """Means over ``[t_k, t_(k+1))`` of instantaneous samples *x* (N, 3): the integral of
    the cubic through four neighbours, ``(−x_(k−1) + 13x_k + 13x_(k+1) − x_(k+2))/24``
    (fourth order); the trapezoid at the ends; the last row repeated."""
    x = np.asarray(x, float)
    out = np.vstack([0.5 * (x[:-1] + x[1:]), x[-1:]])
    if x.shape[0] >= 4:
        out[1:-2] = (-x[:-3] + 13 * x[1:-2] + 13 * x[2:-1] - x[3:]) / 24.0
    return out


def _interval_rotations(time: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Rotation vector over ``[t_k, t_(k+1))`` divided by its length (rad/s) from
    instantaneous body rates *x* (N, 3): the interval mean (:func:`_interval_means`) plus
    the coning term ``Δt/12·ω_k × ω_(k+1)`` (Bortz's equation for a rate linear across the
    interval). Without it a coning motion (an elliptic swing with a twist) turned the
    integrated attitude by 1.4 mrad over a fast three-sweep swing at 50 Hz, which the
    adjustment read as 1.9× the gyro noise (issue #30)."""
    x = np.asarray(x, float)
    out = _interval_means(x)
    if x.shape[0] >= 2:
        dt = np.diff(np.asarray(time, float))[:, None]
        out[:-1] += dt / 12.0 * np.cross(x[:-1], x[1:])
    return out


def _coned_increments(time: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Rotation over each interval divided by its length (rad/s) from interval-mean rates
    *x* (N, 3; increments ``Δθ_k = x_k·Δt``): ``Δθ_k`` plus the coning term, centred,
    ``(Δθ_(k−1)×Δθ_k + Δθ_k×Δθ_(k+1))/24`` (the classic two-sample correction
    ``Δθ_(k−1)×Δθ_k/12`` averaged with its forward form; one-sided at the ends). Exact
    for a rate linear across neighbouring intervals."""
    x = np.asarray(x, float)
    if x.shape[0] < 2:
        return x.copy()
    dt = float(np.median(np.diff(np.asarray(time, float))))
    c = np.cross(x[:-1], x[1:])                      # interval k with k+1, (N−1, 3)
    cone = np.zeros_like(x)
    cone[1:-1] = 0.5 * (c[:-1] + c[1:])
    cone[0], cone[-1] = c[0], c[-1]
    return x + dt / 12.0 * cone


def to_model_grid(time: np.ndarray, gyro: np.ndarray, accel: np.ndarray, convention: str
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The record on the solver's grid.

    Parameters
    ----------
    time : (N,) time tags (s). gyro : (N, 3) rad/s. accel : (N, 3) m/s² (body frame).
    convention : one of :data:`CONVENTIONS`.

    Returns
    -------
    tau : (N,) model times (s). gyro : (N, 3) rotation over ``[τ_k, τ_(k+1))`` divided by
    its length (rad/s): instantaneous rates integrated, interval means (raw increments
    ``∫ω dt / Δt``, as formats.md defines them) with the coning term added.
    accel : (N, 3) specific force (m/s²) as recorded: at ``τ_k`` (instant) or the mean
    over ``[τ_k, τ_(k+1))`` (interval); :func:`.joint.numerov_weights` and
    :func:`.joint.interval_weights` turn either into what the model's second differences
    of the antenna path see.
    """
    time = np.asarray(time, float)
    if convention == "instant":
        return time, _interval_rotations(time, gyro), np.asarray(accel, float)
    if convention not in TAG_FRACTION:
        raise ValueError(f"unknown IMU convention {convention!r}")
    dt = float(np.median(np.diff(time)))
    tau = time - TAG_FRACTION[convention] * dt
    return tau, _coned_increments(time, gyro), np.asarray(accel, float)


def mismatch_hint(offset_s: float, offset_std_s: float, dt: float, convention: str
                  ) -> str | None:
    """Name the likely convention mismatch when a GNSS offset looks like half a sample.

    A tag half an interval off moves the IMU attitude by ``±Δt/2`` against the GNSS. The
    hint is given when the offset is nearer ``±Δt/2`` than 0 or ``±Δt`` and more than 2σ
    from zero. Returns None otherwise.
    """
    half = 0.5 * dt
    if not (abs(offset_s) > 2 * offset_std_s and 0.5 * half <= abs(offset_s) <= 1.5 * half):
        return None
    # GNSS tags late (+τ) ⇔ the IMU attitude runs early: its tags sit later in the
    # interval than declared (an interval-end record declared as instant, and so on)
    shift = TAG_FRACTION.get(convention, 0.5) + (0.5 if offset_s > 0 else -0.5)
    likely = [c for c, f in TAG_FRACTION.items() if abs(f - shift) < 1e-9]
    if convention != "instant" and abs(shift - 0.5) < 1e-9:
        likely.append("instant")
    names = " or ".join(likely) if likely else "another convention"
    return (f"the GNSS↔IMU offset {1000 * offset_s:+.1f} ms (±{1000 * offset_std_s:.1f}) is "
            f"about half the {1000 * dt:.0f} ms IMU interval: the IMU samples are probably "
            f"'{names}', not '{convention}' as declared (--imu-convention)")
