"""Speed and memory of ``hydrosync import`` of a survey day's CSV files, fast vs generic reader.

The day of :mod:`bench_latency_speed` (500 lines of 2 minutes, 100 Hz attitude, 10 Hz
GNSS: 8.0 M + 0.8 M rows, 335 MiB of CSV), simulated into a temporary folder, imported
with ``hydrosync import P.h5 --gnss --attitude --lines`` in a fresh process:

* with the fast reader (:mod:`hydrosync_core.importers.fastcsv`), twice: the first run may
  compile and cache the numba kernels;
* with the generic reader alone (``read_numeric_csv(fast=False)``: the import before the
  fast path) as the reference, unless ``--no-reference`` (it needs ~6.5 GiB and ~45 s;
  the figures measured before then stand, see ``docs/benchmarks.md``).

Each run: wall time, CPU time (all threads) and the process's peak resident memory. Then
the stored arrays are checked bit for bit: against the reference project (every dataset),
and — in any case — against the generic reader run on the CSV files cut into pieces of
``--piece`` rows (the generic reader's memory grows with the file; a piece needs a few
hundred MiB), concatenated.

Run: ``.venv/bin/python benchmarks/bench_import.py [--lines 500] [--dir DIR] [--no-reference]``.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from hydrosync_core import plausible
from hydrosync_core.importers.csv_table import read_numeric_csv
from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day, write_day_csv

sys.path.insert(0, str(Path(__file__).parent))
from bench_latency_speed import CFG  # noqa: E402 - the same survey day

# The import command in a new process; "generic" disables the fast path first.
_IMPORT = ("import sys; from hydrosync_core.importers import csv_table; "
           "csv_table.FAST_MIN_BYTES = 1 << 62 if sys.argv[1] == 'generic' else "
           "csv_table.FAST_MIN_BYTES; from hydrosync_core.cli import main; "
           "sys.exit(main(sys.argv[2:]))")
# Peak RSS and CPU of that child alone: a wrapper process reports its own child's.
_WRAPPER = ("import resource, subprocess, sys; subprocess.run(sys.argv[1:], check=True, "
            "stdout=subprocess.DEVNULL); r = resource.getrusage(resource.RUSAGE_CHILDREN); "
            "print(r.ru_maxrss, r.ru_utime + r.ru_stime)")

TABLES = {"gnss": (["time", "height"], ["lat", "lon", "quality"], plausible.GNSS),
          "attitude": (["time", "roll", "pitch", "heading", "heave"], [], plausible.ATTITUDE)}


def run_import(d: Path, project: Path, reader: str) -> tuple[float, float, float]:
    """Wall time (s), peak RSS (MiB) and CPU time (s) of ``hydrosync import``."""
    project.unlink(missing_ok=True)
    cmd = [sys.executable, "-c", _IMPORT, reader, "import", str(project),
           "--gnss", str(d / "gnss.csv"), "--attitude", str(d / "attitude.csv"),
           "--lines", str(d / "lines.csv")]
    t0 = time.perf_counter()
    res = subprocess.run([sys.executable, "-c", _WRAPPER, *cmd], check=True,
                         capture_output=True, text=True)
    wall = time.perf_counter() - t0
    rss, cpu = res.stdout.split()
    return wall, int(rss) / 1024, float(cpu)


def datasets(path: Path) -> dict[str, object]:
    import h5py

    found = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: found.__setitem__(name, obj.dtype)
                     if isinstance(obj, h5py.Dataset) else None)
    return found


def same_projects(a: Path, b: Path) -> tuple[bool, int]:
    """Every numeric dataset of *a* and *b* equal bit for bit (one at a time)."""
    import h5py

    names = datasets(a)
    if names.keys() != datasets(b).keys():
        return False, 0
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        for name, dtype in names.items():
            if dtype.kind == "f":
                x, y = fa[name][()], fb[name][()]
                if x.dtype != y.dtype or x.tobytes() != y.tobytes():
                    return False, len(names)
    return True, len(names)


def generic_in_pieces(path: Path, kind: str, piece: int, tmp: Path):
    """The generic reader's columns of *path*, read *piece* rows at a time (the file is in
    time order, so the pieces concatenate to the whole file's sorted columns)."""
    required, optional, limits = TABLES[kind]
    parts: dict[str, list[np.ndarray]] = {}
    with open(path, "rb") as fh:
        header = fh.readline()
        while True:
            rows = [fh.readline() for _ in range(piece)]
            rows = [r for r in rows if r]
            if not rows:
                break
            part = tmp / f"piece-{kind}.csv"
            part.write_bytes(header + b"".join(rows))
            table = read_numeric_csv(part, required, optional, min_rows=1, limits=limits,
                                     fast=False)
            for k, v in table.items():
                parts.setdefault(k, []).append(v)
            del rows, table
    part.unlink()
    return {k: np.concatenate(v) for k, v in parts.items()}


def same_as_generic(project: Path, d: Path, piece: int, tmp: Path) -> tuple[bool, float]:
    import h5py

    t0 = time.perf_counter()
    ok = True
    for kind in TABLES:
        ref = generic_in_pieces(d / f"{kind}.csv", kind, piece, tmp)
        ok &= bool(np.all(np.diff(ref["time"]) > 0))  # pieces in order: the whole file's sort
        with h5py.File(project, "r") as f:
            group = f[f"raw/{kind}"]
            ok &= sorted(group) == sorted(ref)
            for k, v in ref.items():
                ok &= group[k][()].tobytes() == v.tobytes()
        del ref
    return ok, time.perf_counter() - t0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lines", type=int, default=500)
    parser.add_argument("--dir", type=Path, help="keep/reuse the CSV files here")
    parser.add_argument("--no-reference", action="store_true",
                        help="skip the import with the generic reader (~6.5 GiB, ~45 s)")
    parser.add_argument("--piece", type=int, default=500_000,
                        help="rows per piece for the generic reader's check")
    args = parser.parse_args()
    tmp = tempfile.TemporaryDirectory(prefix="hydrosync-bench-import-")
    work = Path(tmp.name)
    d = args.dir or work
    d.mkdir(parents=True, exist_ok=True)
    load_start = os.getloadavg()[0]
    t0 = time.perf_counter()
    if not (d / "attitude.csv").exists():
        write_day_csv(simulate_day(DayConfig(n_lines=args.lines, **CFG), seed=7), d)
    t_sim = time.perf_counter() - t0
    sizes = {n: os.path.getsize(d / f"{n}.csv") for n in ("gnss", "attitude", "lines")}

    fast_p, ref_p = work / "fast.h5", work / "generic.h5"
    first = run_import(d, fast_p, "fast")
    fast = run_import(d, fast_p, "fast")
    ref = None if args.no_reference else run_import(d, ref_p, "generic")
    same_ref = None if ref is None else same_projects(fast_p, ref_p)
    same_gen, t_check = same_as_generic(fast_p, d, args.piece, work)
    load_end = os.getloadavg()[0]

    def fmt(r):
        return f"{r[0]:.1f} s wall, {r[2]:.1f} s CPU, peak RSS {r[1]:.0f} MiB"

    print("hydrosync import: one survey day (gnss.csv + attitude.csv + lines.csv)")
    rows = [
        ("lines", f"{args.lines} x {CFG['line_s']:.0f} s"),
        ("CSV files", ", ".join(f"{k} {v / 2**20:.0f} MiB" for k, v in sizes.items())),
        ("simulation + CSV writing", f"{t_sim:.1f} s" if t_sim > 0.5 else "reused"),
        ("fast reader, first run", fmt(first) + " (may compile the kernels)"),
        ("fast reader", fmt(fast)),
        ("generic reader (reference)", fmt(ref) if ref else "not run (--no-reference); "
         "measured before: 43.3 s wall, 20.9 s CPU, peak RSS 6599 MiB"),
        ("speed-up, memory", f"{ref[0] / fast[0]:.1f}x wall, {ref[1] / fast[1]:.1f}x less "
                             "memory" if ref else "-"),
        ("stored arrays == reference project", "not run" if same_ref is None else
         f"{'yes' if same_ref[0] else 'NO'} ({same_ref[1]} datasets, bit for bit)"),
        ("stored arrays == generic reader", f"{'yes' if same_gen else 'NO'} (read in pieces of "
                                            f"{args.piece:,} rows, {t_check:.0f} s)"),
        ("machine", f"{os.cpu_count()} cores, load {load_start:.1f} at the start, "
                    f"{load_end:.1f} at the end"),
        ("this process maxrss",
         f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MiB"),
    ]
    width = max(len(k) for k, _ in rows)
    for key, value in rows:
        print(f"{key:<{width}}  {value}")
    tmp.cleanup()
    if not same_gen or (same_ref is not None and not same_ref[0]):
        sys.exit(1)


if __name__ == "__main__":
    main()
