"""Compile the latency estimate's numba kernels once (``PluginSpec.warmup``)."""

from __future__ import annotations

import tempfile
from pathlib import Path


def compile_kernels() -> None:
    """The latency estimate (auto: both estimators, the fallback σ) and its CSV readers
    on a tiny simulated day, written to CSV and read back as ``hydrosync latency`` does."""
    import numpy as np

    from hydrosync_core.importers.survey_csv import read_lines_csv
    from hydrosync_core.methods.latency import lines
    from hydrosync_core.methods.latency.estimate import estimate_latency
    from hydrosync_core.methods.latency.heave import total_heave_deg
    from hydrosync_core.methods.latency.readers import read_attitude_csv, read_gnss_csv
    from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day, write_day_csv

    cfg = DayConfig(n_lines=2, line_s=60.0, turn_s=10.0, run_in_s=5.0, gnss_hz=10.0,
                    attitude_hz=100.0)
    with tempfile.TemporaryDirectory() as folder:
        write_day_csv(simulate_day(cfg, seed=0), Path(folder))
        gnss = read_gnss_csv(Path(folder) / "gnss.csv")
        attitude = read_attitude_csv(Path(folder) / "attitude.csv",
                                     columns=("time", "roll", "pitch", "heave"))
        day_lines = read_lines_csv(Path(folder) / "lines.csv")
    estimate_latency(gnss, attitude, day_lines, cfg.lever_arm_m,
                     {"estimator": "auto", "step_s": 0.001})
    tags = gnss["time"][50:400]
    line = lines.LineData("warm-up", float(tags[0]), float(tags[-1]), tags, np.sin(tags))
    lines.line_uncertainty(line, attitude["time"], np.sin(attitude["time"]),
                           np.linspace(-1.0, 1.0, 2001), 0.0)
    # The whole-record total heave (the panel's plots, the synchronised data set) takes
    # the parallel kernel above 100 000 records.
    many = np.zeros(100_001)
    total_heave_deg(many, many, many, cfg.lever_arm_m)
