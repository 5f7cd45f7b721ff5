"""What the CLI's garbage-collection setting saves: ``hydrosync latency`` on a survey day.

``hydrosync_core.cli`` runs every command with fewer full garbage collections and freezes
what is alive at exit (``cli._collect_less``). This benchmark keeps that choice honest: it
runs the same latency command in fresh processes with the setting and with Python's
default collector, alternating the two (the machine's speed wanders), and prints the
fastest and median wall time of each. Keep the setting only while the difference is
larger than the spread of the runs.

Run: ``python benchmarks/bench_cli_gc.py [--lines 500] [--repeat 5]``.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day, write_day_csv

CFG = dict(latency_s=0.123, line_s=120.0, run_in_s=10.0, turn_s=30.0, gnss_hz=10.0,
           attitude_hz=100.0)

RUN = ("import gc, sys\n"
       "from hydrosync_core import cli\n"
       "if sys.argv[1] == 'default':\n"
       "    cli._collect_less = gc.get_threshold\n"
       "sys.argv[0] = 'hydrosync'\n"
       "sys.exit(cli.main(sys.argv[2:]))\n")
"""A fresh ``hydrosync`` process; with ``default`` Python's own collector is kept."""


def run_once(mode: str, d: Path) -> float:
    """Wall time (s) of one ``hydrosync latency`` in a new process."""
    cmd = [sys.executable, "-c", RUN, mode, "latency", "--gnss", str(d / "gnss.csv"),
           "--attitude", str(d / "attitude.csv"), "--lines", str(d / "lines.csv"),
           "--lever-arm", "-1.5", "2.0", "-6.0", "--json", str(d / f"{mode}.json")]
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, default=500)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        write_day_csv(simulate_day(DayConfig(n_lines=args.lines, **CFG), seed=7), d)
        run_once("collect-less", d)  # numba's cache and the page cache warm
        times: dict[str, list[float]] = {"collect-less": [], "default": []}
        for _ in range(args.repeat):
            for mode in times:
                times[mode].append(run_once(mode, d))
    print(f"hydrosync latency, {args.lines} lines, {args.repeat} runs each (s):")
    print(f"{'collector':<14}{'fastest':>9}{'median':>9}{'slowest':>9}")
    for mode, t in times.items():
        print(f"{mode:<14}{min(t):9.2f}{statistics.median(t):9.2f}{max(t):9.2f}")
    gain = statistics.median(times["default"]) - statistics.median(times["collect-less"])
    print(f"median saving of the setting: {gain:+.2f} s per command")


if __name__ == "__main__":
    main()
