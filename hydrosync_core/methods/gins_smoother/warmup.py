"""Compile the GNSS/INS smoother's numba kernels once (``PluginSpec.warmup``)."""

from __future__ import annotations


def compile_kernels() -> None:
    """The GNSS/INS forward filter and smoother on a short simulated drive."""
    from hydrosync_core.methods.gins_smoother.filter import run_gins
    from hydrosync_core.methods.gins_smoother.simulate import simulate

    sim = simulate(30.0, "vehicle", "tactical", imu_rate_hz=100.0, seed=0)
    run_gins(sim["imu"], sim["gnss"], sim["config"])
