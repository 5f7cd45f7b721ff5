"""Demo data: a simulated two-minute drive (tactical-grade IMU at 100 Hz, 1 Hz RTK GNSS)."""

from __future__ import annotations

from hydrosync_core.methods.gins_smoother.project_run import (
    CONFIG,
    GNSS,
    IMU,
    OUTAGES,
    REFERENCE,
    nav_columns,
)
from hydrosync_core.methods.gins_smoother.simulate import simulate
from hydrosync_core.progress import report

DEMO_DURATION_S = 120.0


def fill_demo(project, seed: int = 0, progress=None) -> dict:
    """Write ``raw/gins/{imu,gnss,config,reference,outages}`` (one 20 s GNSS outage).

    Returns the simulation truth summary (injected IMU errors, outage window).
    """
    report(progress, 0.0, "simulating a drive")
    sim = simulate(DEMO_DURATION_S, "vehicle", "tactical", imu_rate_hz=100.0, seed=seed)
    imu, gnss, truth, cfg = sim["imu"], sim["gnss"], sim["truth"], sim["config"]
    src = f"simulated drive (seed {seed})"
    cols = {"time": imu.time}
    for i, c in enumerate(("dtheta_x", "dtheta_y", "dtheta_z", "dvel_x", "dvel_y", "dvel_z")):
        cols[c] = imu.inc[:, i]
    project.put_table(IMU, cols, source=src)
    project.put_table(GNSS, {"time": gnss.time, "lat": gnss.llh[:, 0], "lon": gnss.llh[:, 1],
                             "height": gnss.llh[:, 2], "sd_n": gnss.std[:, 0],
                             "sd_e": gnss.std[:, 1], "sd_d": gnss.std[:, 2]}, source=src)
    project.put_json(CONFIG, cfg.to_dict())
    project.put_table(REFERENCE, nav_columns(truth), source="simulation truth")
    t0 = float(imu.time[0])
    window = [t0 + 70.0, t0 + 90.0]
    project.put_json(OUTAGES, {"windows": [window]})
    report(progress, 1.0, "demo drive written")
    out = dict(sim["errors"])
    out["outage"] = window
    return out
