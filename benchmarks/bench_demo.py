"""How long ``hydrosync demo`` takes, stage by stage (the timing ``test_demo`` no longer asserts).

Runs the demo as ``make demo`` does (a fresh process each time, into a temporary folder)
``--repeat`` times and prints each stage's time (the demo's own per-stage lines), the
wall time of the whole command and its peak resident memory, with the machine's load
average beside them: on a shared machine the same run takes twice as long under load, so
read the figures together with the load.

Run: ``.venv/bin/python benchmarks/bench_demo.py [--repeat 3]``.
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

STAGE = re.compile(r"^\[\d+/\d+\] (.+) \.\.\.\s*$")
DONE = re.compile(r"done in ([0-9.]+) s")


def run_once(out: Path) -> tuple[float, float, dict[str, float], int]:
    """(wall s, peak RSS MiB, {stage: s}, exit code) of one ``hydrosync demo`` run."""
    script = Path(sys.executable).with_name("hydrosync")
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    t0 = time.perf_counter()
    proc = subprocess.run([str(script), "demo", "--out", str(out)], capture_output=True,
                          text=True)
    wall = time.perf_counter() - t0
    peak = max(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, before) / 1024
    stages: dict[str, float] = {}
    label = None
    for line in proc.stdout.splitlines():
        if m := STAGE.match(line):
            label = m.group(1)
        elif label and (m := DONE.search(line)):
            stages[label] = float(m.group(1))
            label = None
    return wall, peak, stages, proc.returncode


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(args.repeat):
            load = os.getloadavg()[0]
            wall, peak, stages, code = run_once(Path(tmp) / f"run{i}")
            runs.append((wall, peak, stages, code, load))
            print(f"run {i + 1}: exit {code}, {wall:.1f} s, peak {peak:.0f} MiB, "
                  f"load average {load:.1f}", flush=True)
    labels = list(runs[0][2])
    print(f"\n| stage | {' | '.join(f'run {i + 1}' for i in range(len(runs)))} |")
    print(f"|---|{'---|' * len(runs)}")
    for label in labels:
        cells = " | ".join(f"{r[2].get(label, float('nan')):.1f} s" for r in runs)
        print(f"| {label} | {cells} |")
    print(f"| **whole command** | {' | '.join(f'**{r[0]:.1f} s**' for r in runs)} |")
    print(f"| load average (1 min) at start | {' | '.join(f'{r[4]:.1f}' for r in runs)} |")
    return 0 if all(r[3] == 0 for r in runs) else 1


if __name__ == "__main__":
    sys.exit(main())
