"""Demo data: a simulated four-antenna survey launch turning through all headings."""

from __future__ import annotations

from hydrosync_core.methods.gnss_attitude.project_run import ANTENNAS, POS
from hydrosync_core.methods.gnss_attitude.simulate import ArrayConfig, simulate_array
from hydrosync_core.progress import report

#: Ten minutes at 1 Hz, 6 mm / 12 mm noise, float episodes, missing epochs, A4 out 60 s.
DEMO_CONFIG = ArrayConfig(duration_s=600.0, rate_hz=1.0)


def fill_demo(project, seed: int = 0, progress=None) -> dict:
    """Write ``raw/gnss_attitude/pos/A1…A4`` and ``raw/gnss_attitude/antennas``.

    Returns the simulation truth (``gps_s``, ``time``, ``heading``, ``pitch``, ``roll``;
    degrees).
    """
    report(progress, 0.0, "simulating a GNSS antenna array")
    sim = simulate_array(config=DEMO_CONFIG, seed=seed)
    src = f"simulated 4-antenna array (seed {seed})"
    for name, columns in sim["tracks"].items():
        project.put_table(f"{POS}/{name}", columns, source=src, antenna=name, form="llh",
                          time_system="GPST", time_format="calendar", frame="ECEF WGS84")
    project.put_json(ANTENNAS, {"frame": "FRD", "antennas": sim["antennas"]})
    project.set_attrs(ANTENNAS, source=src)
    report(progress, 1.0, "demo array written")
    truth = dict(sim["truth"])
    truth.update(antennas=len(sim["antennas"]), sigma_h_m=DEMO_CONFIG.sigma_h_m,
                 sigma_v_m=DEMO_CONFIG.sigma_v_m)
    return truth
