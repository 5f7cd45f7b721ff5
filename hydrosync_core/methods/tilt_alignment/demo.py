"""Demo data: one simulated tilt-pole record (35° swing, MEMS IMU with biases, 10 Hz RTK)."""

from __future__ import annotations

import numpy as np

from hydrosync_core.methods.tilt_alignment.project_run import GNSS, IMU, POLE
from hydrosync_core.methods.tilt_alignment.simulate import SwingConfig, simulate_swing
from hydrosync_core.progress import report

#: A realistic swing: 35° along an ellipse, MEMS biases of the issue's size, 1 cm / 2 cm GNSS.
DEMO_CONFIG = SwingConfig(tilt_deg=35.0, shape_ratio=0.4, heading_deg=57.0,
                          gyro_bias_deg_s=(0.04, -0.05, 0.03),
                          accel_bias_m_s2=(0.015, -0.02, 0.01), gap_s=0.3)
#: The tip's ENU coordinates in the demo (m): a benchmark on a quay.
DEMO_TIP_ENU = (512.340, 1023.870, 3.215)


def fill_demo(project, seed: int = 0, progress=None) -> dict:
    """Write ``raw/tilt/imu``, ``raw/tilt/gnss`` (ENU) and ``raw/tilt/pole``.

    Returns the simulation truth: ``tip_enu`` (m), ``heading_misalignment_deg``.
    """
    report(progress, 0.0, "simulating a tilt-pole swing")
    sim = simulate_swing(DEMO_CONFIG, seed=seed)
    src = f"simulated tilt-pole swing (seed {seed})"
    g, f = sim["gyro"], sim["accel"]
    project.put_table(IMU, {"time": sim["time"], "gx": g[:, 0], "gy": g[:, 1], "gz": g[:, 2],
                            "ax": f[:, 0], "ay": f[:, 1], "az": f[:, 2]}, source=src)
    ned = sim["gnss_ned"]
    e0, n0, u0 = DEMO_TIP_ENU
    project.put_table(GNSS, {"time": sim["gnss_time"], "e": ned[:, 1] + e0,
                             "n": ned[:, 0] + n0, "u": -ned[:, 2] + u0}, source=src)
    project.put_json(POLE, {"pole_length_m": sim["pole_length_m"]})
    project.set_attrs(POLE, source=src)
    report(progress, 1.0, "demo tilt-pole record written")
    return {"tip_enu": [float(v) for v in np.asarray(DEMO_TIP_ENU)],
            "heading_misalignment_deg": round(sim["truth"]["heading_deg"], 4)}
