"""The fault table of issues #9 and #28: every fault case of ``tests/reliability``, more of
the random ones.

Runs the reliability tests with ``HYDROSYNC_FAULT_SCALE`` (default 5: five times the
random cases of the test suite — SIGINT/SIGKILL moments, fuzzed importer inputs) and prints
the table the tests keep: per kind of fault, cases tried, clean (every check held: exit code,
one line, nothing destroyed, nothing left behind, no hang) and failed, with the wall time.
The hostile-environment cases (symlinked and foreign locks, devices, FIFOs, /proc, another
pid namespace via ``unshare``, a full tmpfs in a private mount namespace) run where the
machine allows them and are skipped with the reason otherwise.

Run: ``.venv/bin/python benchmarks/bench_faults.py [--scale N]``; exit 1 if a case failed.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scale", type=int, default=5,
                        help="multiplier of the random fault cases (default 5)")
    args = parser.parse_args()
    env = dict(os.environ, HYDROSYNC_FAULT_SCALE=str(args.scale), QT_QPA_PLATFORM="offscreen")
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                           "-rs", "tests/reliability"], cwd=ROOT, env=env,
                          capture_output=True, text=True)
    wall = time.perf_counter() - start
    text = done.stdout
    table = text[text.find("fault cases ="):] if "fault cases =" in text else ""
    lines = [line for line in table.splitlines()[1:] if line.strip()
             and not line.startswith(("=", "SKIPPED", "FAILED", "ERROR"))]
    summary = [line for line in text.splitlines() if re.search(r"\d+ (passed|failed)", line)]
    skipped = [line for line in text.splitlines() if line.startswith("SKIPPED")]
    print(f"fault table (HYDROSYNC_FAULT_SCALE={args.scale}), {wall:.0f} s wall:")
    for line in lines:
        print("  " + line)
    for line in skipped:
        print("  " + line)
    print("pytest: " + (summary[-1].strip("= ") if summary else f"exit {done.returncode}"))
    if done.returncode:
        print(text[-3000:])
    return 1 if done.returncode else 0


if __name__ == "__main__":
    sys.exit(main())
