"""How the Latency panel responds on a survey day's project (GUI thread stalls, offscreen Qt).

The day of ``bench_latency_speed.py`` (500 lines of 2 min, 10 Hz GNSS, 100 Hz attitude:
8 million attitude rows) is imported into a project with the command line
(``hydrosync new``/``import``/``latency``), as a user would, and opened in the panel:

* binding the panel to the opened project (the GUI thread: results table, 500 R curves),
  then how long the selected line's series takes to appear while the raw tables are read
  on a thread, and the longest stall of the GUI thread meanwhile;
* a click in the line table (highlight + that line's series);
* a re-run after a changed lever arm (``project_run.run``, as the panel's worker does):
  the first reads the raw tables from the file, the next ones take them from memory.

Run: ``.venv/bin/python benchmarks/bench_latency_panel.py [--lines 500] [--dir DIR]``
(``--dir``: where the CSV files are kept or reused).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")

from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day, write_day_csv  # noqa: E402

CFG = dict(latency_s=0.123, line_s=120.0, run_in_s=10.0, turn_s=30.0, gnss_hz=10.0,
           attitude_hz=100.0)
ARM = ("-1.5", "2.0", "-6.0")


def hydrosync(*args: str) -> float:
    """Run ``hydrosync *args`` in a new process; its wall time (s)."""
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", "import sys; from hydrosync_core.cli import main; "
                    "sys.exit(main(sys.argv[1:]))", *args], check=True,
                   stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, default=500)
    parser.add_argument("--dir", type=Path, help="keep/reuse the CSV files here")
    args = parser.parse_args()
    tmp = tempfile.TemporaryDirectory()
    d = args.dir or Path(tmp.name)
    if not (d / "attitude.csv").exists():
        write_day_csv(simulate_day(DayConfig(n_lines=args.lines, **CFG), seed=7), d)
    project_file = Path(tmp.name) / "day.h5"
    t_new = hydrosync("new", str(project_file))
    t_import = hydrosync("import", str(project_file), "--gnss", str(d / "gnss.csv"),
                         "--attitude", str(d / "attitude.csv"), "--lines", str(d / "lines.csv"))
    t_run_cli = hydrosync("latency", str(project_file), "--lever-arm", *ARM, "--step", "0.001")

    from PySide6.QtWidgets import QApplication

    from hydrosync_core.methods.latency.project_run import run
    from hydrosync_core.project import Project
    from plugins.latency.panel import LatencyPanel

    app = QApplication([])
    panel = LatencyPanel()
    panel.resize(1300, 850)
    panel.show()
    app.processEvents()
    project = Project.open(project_file, readonly=True)
    t0 = time.perf_counter()
    panel.set_project(project)
    app.processEvents()
    t_bind = time.perf_counter() - t0
    title = panel.series_plot.plotItem.titleLabel
    longest, last, t1 = 0.0, time.perf_counter(), time.perf_counter()
    while not title.text.startswith("line ") and time.perf_counter() - t1 < 60:
        app.processEvents()
        now = time.perf_counter()
        longest, last = max(longest, now - last), now
        time.sleep(0.002)
    t_series = time.perf_counter() - t1
    clicks = []
    for row in (10, 200, 400, 3):
        t0 = time.perf_counter()
        panel.table.selectRow(row % panel.table.rowCount())
        app.processEvents()
        clicks.append(time.perf_counter() - t0)
    runs = []
    fresh = Project.open(project_file, readonly=True)  # nothing read from it yet
    for arm in ((-1.5, 2.0, -6.0), (-1.4, 2.0, -6.0), (-1.5, 2.1, -6.0)):
        t0 = time.perf_counter()
        run(fresh, {"lever_arm_m": arm, "step_s": 0.001})
        runs.append(time.perf_counter() - t0)
    panel.close()
    fresh.close()

    print("latency panel on a survey day (offscreen Qt)")
    rows = [
        ("lines", f"{panel.table.rowCount()} ({project_file.stat().st_size / 2**20:.0f} MiB "
                  "project)"),
        ("hydrosync new / import / latency", f"{t_new:.1f} / {t_import:.1f} / {t_run_cli:.1f} s"),
        ("bind panel to project (GUI thread)", f"{t_bind:.2f} s"),
        ("selected line's series shown after", f"{t_series:.2f} s more (read on a thread); "
                                               f"longest GUI stall meanwhile "
                                               f"{longest * 1e3:.0f} ms"),
        ("click in the line table", " / ".join(f"{c * 1e3:.0f}" for c in clicks) + " ms"),
        ("re-run, new lever arm (worker)", f"first {runs[0]:.2f} s (reads the file), then "
                                           + " / ".join(f"{r:.2f}" for r in runs[1:]) + " s"),
    ]
    width = max(len(k) for k, _ in rows)
    for key, value in rows:
        print(f"{key:<{width}}  {value}")
    project.close()
    tmp.cleanup()


if __name__ == "__main__":
    main()
