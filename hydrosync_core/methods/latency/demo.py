"""Demo data for the latency plugin: a simulated 13-line survey day and its vessel sheet."""

from __future__ import annotations

from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day
from hydrosync_core.progress import report
from hydrosync_core.project import Project
from hydrosync_core.project.vessel import set_sensor

DEMO_CONFIG = DayConfig(latency_s=0.29, n_lines=13, gnss_hz=1.0, attitude_hz=50.0)
"""Like the seed's day: 13 two-minute lines, 1 Hz RTK heights, 0.29 s delay."""


def fill_demo(project: Project, seed: int = 0, progress=None) -> dict:
    """Write raw/gnss, raw/attitude, raw/lines and the vessel's gnss/motion sensors.

    Returns the simulation truth (``latency_s``, ``lever_arm_m``).
    """
    report(progress, 0.0, "simulating a survey day")
    day = simulate_day(DEMO_CONFIG, seed=seed)
    src = f"simulated survey day (seed {seed}, latency {DEMO_CONFIG.latency_s} s)"
    project.put_table("raw/gnss", day["gnss"], source=src)
    project.put_table("raw/attitude", day["attitude"], source=src)
    project.put_table("raw/lines", day["lines"], source=src)
    # Motion sensor at the reference point; the antenna at the simulated lever arm.
    set_sensor(project, "motion", [0.0, 0.0, 0.0], {"roll": 0, "pitch": 0, "yaw": 0})
    set_sensor(project, "gnss", day["truth"]["lever_arm_m"])
    report(progress, 1.0, "demo data written")
    return day["truth"]
