"""Streaming import of a field day of raw NMEA logs: time, peak memory, file size (#25).

The day: the latency simulator's survey day (:mod:`bench_latency_speed`'s settings: 100 Hz
attitude, 10 Hz GNSS, lines of 2 min with 10 s run-in and 30 s turns, i.e. 540 lines in
24 h) written as one logger's NMEA file: ISO 8601 logger tags, ``$PASHR`` at 100 Hz and
``$GPGGA`` at 10 Hz interleaved in logger-time order with real checksums, one ``$GPZDA``
a second and CRLF line ends. The GGA sentence carries the measurement time and the
logger tag comes ``latency_s`` later (the delay the latency run must recover). The same
day is also cut into 24 hourly files. Files are written once into ``--dir`` and reused.

Measured, each import in a fresh process (wall time, peak resident memory of that
process, project file size):

* ``hydrosync import P.h5 --gnss-log day.log --attitude-log day.log --heave-positive up
  --lines lines.csv`` for the first 1 h, 6 h and the whole 24 h;
* the same with the 24 hourly files (``--gnss-log 'hours/*.log'``);
* ``pynmeagps`` alone parsing one hour of the same sentences (``NMEAReader.parse`` per
  line, logger tag cut off), the reference the issue asks the import to beat 15×;
* reading the 24 h project's attitude table back, and ``hydrosync run P.h5 latency`` on
  it (delay recovered vs the simulated one).

Run: ``.venv/bin/python benchmarks/bench_import_stream.py [--dir DIR] [--hours 1 6 24]``
(the 24 h log is ~700 MB; writing it takes a few minutes the first time).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from bench_latency_speed import CFG  # noqa: E402 - the same survey day

T0 = 1714521600.0  # 2024-05-01 00:00:00 UTC
PERIOD = CFG["run_in_s"] + CFG["line_s"] + CFG["turn_s"]
HYDROSYNC = str(Path(sys.executable).with_name("hydrosync"))


def _checksums(bodies: list[str]) -> np.ndarray:
    data = np.frombuffer("".join(bodies).encode(), np.uint8)
    lengths = np.fromiter((len(b) for b in bodies), np.int64, len(bodies))
    starts = np.concatenate([[0], np.cumsum(lengths)[:-1]])
    return np.bitwise_xor.reduceat(data, starts)


def _iso(t: np.ndarray) -> np.ndarray:
    """``YYYY-MM-DDThh:mm:ss.sss`` of Unix seconds *t*."""
    return np.datetime_as_string((np.round(t * 1000)).astype("datetime64[ms]"), unit="ms")


def _hms(iso: str) -> str:
    return iso[11:13] + iso[14:16] + iso[17:23]


def _sentences(day: dict, a: int, b: int, g: np.ndarray) -> tuple[np.ndarray, list[str]]:
    """Logger tags and sentence bodies of attitude rows a:b and GNSS rows *g*."""
    att = day["attitude"]
    t = att["time"][a:b]
    iso_t = _iso(t)
    bodies = [f"PASHR,{_hms(s)},{h:.2f},T,{r:.3f},{p:.3f},{v:.3f},0.010,0.010,0.020,1,1"
              for s, h, r, p, v in zip(iso_t, att["heading"][a:b], att["roll"][a:b],
                                       att["pitch"][a:b], att["heave"][a:b], strict=True)]
    tags = [t]
    gt = day["truth"]["gnss_true_time"][g]
    iso_g = _iso(gt)
    # h = altitude + N with N = -30.000: altitude = h + 30
    bodies += [f"GPGGA,{_hms(s)[:9]},4530.1234,S,17030.5678,E,4,14,0.7,{h + 30.0:.3f},M,"
               f"-30.000,M,1.0,0001" for s, h in zip(iso_g, day["gnss"]["height"][g],
                                                     strict=True)]
    tags.append(day["gnss"]["time"][g])
    whole = np.flatnonzero(np.diff(np.floor(t)) > 0) + 1
    iso_z = _iso(t[whole])
    bodies += [f"GPZDA,{_hms(s)},{s[8:10]},{s[5:7]},{s[:4]},00,00" for s in iso_z]
    tags.append(t[whole])
    return np.concatenate(tags), bodies


def write_day(folder: Path, hours: int) -> dict[str, Path]:
    """Write the day log, the hourly files and lines.csv (once: reused when present)."""
    from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day

    folder.mkdir(parents=True, exist_ok=True)
    out = {"day": folder / f"day{hours}h.log", "lines": folder / f"lines{hours}h.csv",
           "hours": folder / f"hours{hours}h", "truth": folder / f"truth{hours}h.json"}
    if out["day"].exists() and out["truth"].exists():
        return out
    n_lines = int(hours * 3600 // PERIOD)
    cfg = DayConfig(**{**CFG, "n_lines": n_lines, "t0": T0})
    day = simulate_day(cfg, seed=25)
    out["hours"].mkdir(exist_ok=True)
    att_t = day["attitude"]["time"]
    g_t = day["gnss"]["time"]
    step = 60.0
    hour_files: dict[int, object] = {}
    with open(out["day"], "wb") as whole:
        for start in np.arange(att_t[0], att_t[-1] + step, step):
            a, b = np.searchsorted(att_t, [start, start + step])
            g = np.flatnonzero((g_t >= start) & (g_t < start + step))
            tags, bodies = _sentences(day, a, b, g)
            if not bodies:
                continue
            order = np.argsort(tags, kind="stable")
            iso = _iso(tags)
            cs = _checksums(bodies)
            text = "".join(f"{iso[i]}Z ${bodies[i]}*{cs[i]:02X}\r\n" for i in order).encode()
            whole.write(text)
            hour = int((start - T0) // 3600)
            if hour not in hour_files:
                hour_files[hour] = open(out["hours"] / f"h{hour:02d}.log", "wb")  # noqa: SIM115
            hour_files[hour].write(text)
    for handle in hour_files.values():
        handle.close()
    lines = day["lines"]
    out["lines"].write_text("name,start,end\n" + "".join(
        f"{n},{s:.3f},{e:.3f}\n" for n, s, e in zip(lines["name"], lines["start"], lines["end"],
                                                   strict=True)))
    out["truth"].write_text(json.dumps({"latency_s": cfg.latency_s,
                                        "lever_arm_m": list(cfg.lever_arm_m),
                                        "gga": int(g_t.size), "pashr": int(att_t.size)}))
    return out


def measured(args: list[str]) -> tuple[float, float, str]:
    """Wall time and peak memory of one command in a child python that reports its own
    peak resident memory, ``VmHWM`` of ``/proc/self/status``. Not ``ru_maxrss``: it keeps
    the peak of the process before ``exec``, i.e. of this benchmark when it forked (the
    simulated day), nor RUSAGE_CHILDREN, which keeps the largest child so far."""
    code = ("import os, runpy, sys, time\n"
            "sys.argv = sys.argv[1:]\n"
            "t = time.perf_counter()\n"
            "try:\n"
            "    runpy.run_path(sys.argv[0], run_name='__main__')\n"
            "except SystemExit as e:\n"
            "    if e.code: raise\n"
            "finally:\n"
            "    hwm = [ln for ln in open('/proc/self/status') if ln.startswith('VmHWM')]\n"
            "    cpu = sum(os.times()[:2])\n"
            "    print('@@', time.perf_counter() - t, hwm[0].split()[1], cpu, file=sys.stderr)\n")
    proc = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True,
                          env={**os.environ, "HYDROSYNC_PROGRESS": "off"})
    if proc.returncode:
        raise RuntimeError(f"{' '.join(args)} failed: {proc.stderr[-2000:]}")
    mark = [ln for ln in proc.stderr.splitlines() if ln.startswith("@@")][-1].split()
    print(f"    [{' '.join(a if len(a) < 40 else '…' + a[-30:] for a in args[1:])}: "
          f"wall {float(mark[1]):.1f} s, CPU {float(mark[3]):.1f} s, "
          f"peak {float(mark[2]) / 1024:.0f} MiB]", flush=True)
    return float(mark[1]), float(mark[2]) / 1024.0, proc.stdout


def pynmeagps_hour(path: Path, max_lines: int) -> tuple[float, int]:
    """Seconds for pynmeagps to parse the first *max_lines* sentences, and how many."""
    from pynmeagps import NMEAReader

    n = 0
    start = time.perf_counter()
    cpu = time.process_time()
    with open(path) as handle:
        for line in handle:
            NMEAReader.parse(line[line.index("$"):])
            n += 1
            if n >= max_lines:
                break
    print(f"    [pynmeagps: wall {time.perf_counter() - start:.1f} s, "
          f"CPU {time.process_time() - cpu:.1f} s for {n} sentences]", flush=True)
    return time.perf_counter() - start, n


def import_day(files: dict, project: Path, hourly: bool) -> tuple[float, float, str]:
    logs = str(files["hours"] / "*.log") if hourly else str(files["day"])
    project.unlink(missing_ok=True)
    return measured([HYDROSYNC, "import", str(project), "--gnss-log", logs, "--attitude-log",
                     logs, "--heave-positive", "up", "--lines", str(files["lines"])])


GUI_CODE = """
import os, sys, time
os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
from PySide6.QtWidgets import QApplication
from hydrosync_core.project import Project
from plugins.latency.panel import LatencyPanel
app = QApplication([])
panel = LatencyPanel()
panel.resize(1300, 850)
panel.show()
app.processEvents()
t0 = time.perf_counter()
project = Project.open(sys.argv[1], readonly=True)
t_open = time.perf_counter() - t0
t0 = time.perf_counter()
panel.set_project(project)
app.processEvents()
t_bind = time.perf_counter() - t0
title = panel.series_plot.plotItem.titleLabel
t1 = time.perf_counter()
while not title.text.startswith("line ") and time.perf_counter() - t1 < 300:
    app.processEvents()
    time.sleep(0.002)
print(f"open {t_open:.2f} s, panel bound {t_bind:.2f} s, first line's series plotted "
      f"{time.perf_counter() - t1:.2f} s later")
"""


def _gui_script(folder: Path) -> Path:
    """The Latency panel opening the imported day: open, bind, first series plot."""
    path = folder / "gui.py"
    path.write_text(GUI_CODE)
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dir", type=Path, default=Path(tempfile.gettempdir()) / "hs-stream")
    parser.add_argument("--hours", type=int, nargs="+", default=[1, 6, 24])
    parser.add_argument("--no-latency", action="store_true")
    parser.add_argument("--no-pynmeagps", action="store_true",
                        help="skip the reference (use the figure measured before)")
    args = parser.parse_args()
    rows = []
    for hours in args.hours:
        files = write_day(args.dir, hours)
        truth = json.loads(files["truth"].read_text())
        size_mb = files["day"].stat().st_size / 1e6
        project = args.dir / f"P{hours}h.h5"
        # warm the page cache, as a second import of the day would find it
        subprocess.run(["cat", str(files["day"])], stdout=subprocess.DEVNULL, check=True)
        wall, peak, out = import_day(files, project, hourly=False)
        counts = out.split("\n")
        rows.append((f"{hours} h, one file", size_mb, wall, peak,
                     project.stat().st_size / 1e6, counts[0][:90]))
        print(rows[-1], flush=True)
        got = [int(s.split()[3]) for s in counts if "records" in s]
        print(f"  records {got}, simulated GGA {truth['gga']}, PASHR {truth['pashr']}")
        if hours == max(args.hours):
            wall, peak, out = import_day(files, project, hourly=True)
            rows.append((f"{hours} h, {hours} hourly files", size_mb, wall, peak,
                         project.stat().st_size / 1e6, out.split("\n")[0][:90]))
            print(rows[-1], flush=True)
            if not args.no_pynmeagps:
                n = 360_000 + 36_000 + 3600
                t_ref, n_ref = pynmeagps_hour(files["day"], n)
                print(f"pynmeagps: {n_ref} sentences (one hour) in {t_ref:.1f} s -> "
                      f"{t_ref * hours:.0f} s for {hours} h; import {wall:.1f} s = "
                      f"{t_ref * hours / wall:.1f}x faster")
            code = ("import sys, time; from hydrosync_core.project import Project\n"
                    "t = time.perf_counter(); p = Project.open(sys.argv[1], readonly=True)\n"
                    "a = p.get_table('raw/attitude'); g = p.get_table('raw/gnss')\n"
                    "print(time.perf_counter() - t, a['time'].size, g['time'].size)\n")
            script = args.dir / "read.py"
            script.write_text(code)
            wall_r, peak_r, out = measured([str(script), str(project)])
            print(f"read back: {out.strip()} ({wall_r:.1f} s, {peak_r:.0f} MiB)")
            if not args.no_latency:
                lever = [str(v) for v in truth["lever_arm_m"]]
                subprocess.run([HYDROSYNC, "vessel", str(project), "--set", "gnss", *lever,
                                "--set", "motion", "0", "0", "0"], check=True,
                               stdout=subprocess.DEVNULL)
                wall_l, peak_l, out = measured([HYDROSYNC, "run", "latency", str(project)])
                print(f"latency run: {wall_l:.1f} s, {peak_l:.0f} MiB; true "
                      f"{truth['latency_s']} s\n{out}")
                wall_g, peak_g, out = measured([str(_gui_script(args.dir)), str(project)])
                print(f"GUI (offscreen): {out.strip()}; peak {peak_g:.0f} MiB")
    print(f"{'case':28s} {'log MB':>7s} {'s':>7s} {'peak MiB':>9s} {'project MB':>10s}")
    for name, size, wall, peak, psize, _ in rows:
        print(f"{name:28s} {size:7.0f} {wall:7.1f} {peak:9.0f} {psize:10.0f}")


if __name__ == "__main__":
    main()
