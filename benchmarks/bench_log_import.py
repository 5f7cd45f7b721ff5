"""Speed of the real-log importers: the corpus files and a large synthetic tagged log.

Prints seconds per file (and MB/s) for the GNSS and attitude importers on every log of
``../shared/data/real-logs`` (when present) and on a synthetic 20 MB openrvdas-style
log (ISO tags, GGA 10 Hz + PSXN,23 50 Hz), and for the point-cloud reader on the LAS/LAZ
files. Run: ``.venv/bin/python benchmarks/bench_log_import.py``.
"""

from __future__ import annotations

import tempfile
import time
from functools import reduce
from pathlib import Path

from hydrosync_core.datasets import real_logs_dir
from hydrosync_core.errors import InputError
from hydrosync_core.importers.log_import import import_attitude_log, import_gnss_log
from hydrosync_core.importers.pointcloud import read_point_cloud

REAL = real_logs_dir()


def _nmea(body: str) -> str:
    return f"${body}*{reduce(lambda a, c: a ^ ord(c), body, 0):02X}"


def synthetic_log(path: Path, seconds: int) -> None:
    """Write a tagged Seapath-like log: GGA at 10 Hz, PSXN,23 at 50 Hz."""
    out = []
    for k in range(seconds * 50):
        t = k / 50.0
        hh, rem = divmod(t, 3600)
        mm, ss = divmod(rem, 60)
        tag = f"2014-08-01T{int(hh):02d}:{int(mm):02d}:{ss:09.6f}Z "
        out.append(tag + _nmea(f"PSXN,23,0.{k % 90:02d},-1.09,218.83,0.{k % 70:02d}"))
        if k % 5 == 0:
            out.append(tag + _nmea(
                f"GPGGA,{int(hh):02d}{int(mm):02d}{ss:05.2f},2200.112071,S,01756.360200,W,"
                f"4,10,0.9,1.{k % 97:02d},M,4.67,M,,"))
    path.write_text("\n".join(out) + "\n")


def timed(func, *args, **kwargs) -> tuple[float, str]:
    start = time.perf_counter()
    try:
        result = func(*args, **kwargs)
        rows = len(result[0]["time"]) if isinstance(result, tuple) else None
        what = f"{rows} rows" if rows is not None else f"{len(result)} pts"
    except InputError:
        what = "InputError"
    return time.perf_counter() - start, what


def main() -> None:
    print(f"{'file':48s} {'MB':>6s} {'gnss s':>8s} {'att s':>8s}  result")
    files = sorted(p for p in REAL.glob("*/*") if p.suffix not in (".md",)) if REAL.exists() else []
    with tempfile.TemporaryDirectory() as tmp:
        big = Path(tmp) / "synthetic_tagged.log"
        synthetic_log(big, 3000)
        for path in [*files, big]:
            mb = path.stat().st_size / 1e6
            if path.suffix in (".las", ".laz"):
                dt, what = timed(read_point_cloud, path)
                print(f"{path.name[:48]:48s} {mb:6.2f} {dt:8.3f} {'':8s}  {what}")
                continue
            g, gw = timed(import_gnss_log, path)
            a, aw = timed(import_attitude_log, path, heave_positive="down")
            print(f"{path.name[:48]:48s} {mb:6.2f} {g:8.3f} {a:8.3f}  {gw} / {aw}"
                  f"  ({mb / max(g, 1e-9):.1f} MB/s)")


if __name__ == "__main__":
    main()
