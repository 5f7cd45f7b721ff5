"""IMU sample conventions: what one row of ``imu.csv`` means, and the model grid.

An IMU either reports *instantaneous* samples (the rate and specific force at the time
tag) or *interval* samples (the mean rate and mean specific force — increments divided by
the interval — over one sample interval), and the tag of an interval sample sits at its
start, middle or end. Taking one for another shifts the attitude by half a sample (10 ms
samples: 5 ms), which the joint adjustment then reads as a GNSS time offset and as extra
IMU noise (issue #30).

:func:`to_model_grid` turns any convention into the one the solver integrates: on model
times ``τ_k``, gyro row *k* is the mean rate over ``[τ_k, τ_(k+1))`` and accelerometer row
*k* the specific force at ``τ_k``. Second-order interpolation (a midpoint average of two
neighbours) does it; its error is ``Δt²/8`` times the second derivative, 10⁻⁴ of a swing's
rate at 100 Hz.
"""

from __future__ import annotations

import numpy as np

#: The declared conventions (``--imu-convention``, ``pole.json`` key ``imu_convention``).
CONVENTIONS = ("instant", "interval-start", "interval-middle", "interval-end")
#: Where the tag sits in the sample's interval (fraction of the interval from its start).
TAG_FRACTION = {"interval-start": 0.0, "interval-middle": 0.5, "interval-end": 1.0}
#: The convention assumed when neither the options nor the data set declare one.
DEFAULT = "instant"


def _midpoints(x: np.ndarray, keep: str) -> np.ndarray:
    """Means of neighbouring rows; *keep* = ``"last"`` or ``"first"`` repeats that row so
    the length stays N."""
    mid = 0.5 * (x[:-1] + x[1:])
    return np.vstack([mid, x[-1:]]) if keep == "last" else np.vstack([x[:1], mid])


def to_model_grid(time: np.ndarray, gyro: np.ndarray, accel: np.ndarray, convention: str
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The record on the solver's grid.

    Parameters
    ----------
    time : (N,) time tags (s). gyro : (N, 3) rad/s. accel : (N, 3) m/s² (body frame).
    convention : one of :data:`CONVENTIONS`.

    Returns
    -------
    tau : (N,) model times (s). gyro : (N, 3) mean rate over ``[τ_k, τ_(k+1))`` (rad/s).
    accel : (N, 3) specific force at ``τ_k`` (m/s²).
    """
    time = np.asarray(time, float)
    if convention == "instant":
        return time, _midpoints(gyro, "last"), np.asarray(accel, float)
    if convention not in TAG_FRACTION:
        raise ValueError(f"unknown IMU convention {convention!r}")
    dt = float(np.median(np.diff(time)))
    tau = time - TAG_FRACTION[convention] * dt
    return tau, np.asarray(gyro, float), _midpoints(accel, "first")


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
