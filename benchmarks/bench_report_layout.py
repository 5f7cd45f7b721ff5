"""PDF layout of the report on the demo and on a long survey day (#26).

Two projects:

* the demo (``hydrosync demo``: all five analyses on simulated data; ``--demo DIR`` reuses
  an earlier run's folder);
* a survey day: 500 two-minute lines for the latency analysis (1 Hz RTK heights, 50 Hz
  attitude, as the demo's day but 500 lines) and a 10-hour 1 Hz record of a four-antenna
  GNSS array (36 000 epochs) — the long series that printed as solid blocks.

For each: pages, the fill of every page, the pages under 40 % that do not end a section
(there should be none), the PDF's size and the time to write it. ``--baseline`` writes
the same reports as before #26 for comparison: every series drawn sample by sample and a
page break before every section (the column-width fit stays).

Run: ``.venv/bin/python benchmarks/bench_report_layout.py [--demo DIR] [--lines 500]
[--hours 10] [--baseline]`` (about 5 min with a demo folder, 10 without).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np


def survey_day(folder: Path, lines: int, hours: float) -> Path:
    """A project with a *lines*-line latency day and an *hours*-long GNSS array record,
    both analysed; returns its file."""
    from hydrosync_core.methods.gnss_attitude.project_run import ANTENNAS, POS
    from hydrosync_core.methods.gnss_attitude.simulate import ArrayConfig, simulate_array
    from hydrosync_core.methods.latency.demo import DEMO_CONFIG
    from hydrosync_core.methods.latency.simulate import simulate_day
    from hydrosync_core.plugins import get_spec
    from hydrosync_core.project import Project
    from hydrosync_core.project.vessel import set_sensor

    project = Project.new("survey day (simulated)")
    day = simulate_day(replace(DEMO_CONFIG, n_lines=lines), seed=3)
    for name in ("gnss", "attitude", "lines"):
        project.put_table(f"raw/{name}", day[name], source="simulated survey day")
    set_sensor(project, "motion", [0.0, 0.0, 0.0], {"roll": 0, "pitch": 0, "yaw": 0})
    set_sensor(project, "gnss", day["truth"]["lever_arm_m"])
    # As the GNSS attitude demo writes its array, for a record of *hours*.
    sim = simulate_array(config=ArrayConfig(duration_s=3600.0 * hours, rate_hz=1.0), seed=3)
    for name, columns in sim["tracks"].items():
        project.put_table(f"{POS}/{name}", columns, source="simulated array", antenna=name,
                          form="llh", time_system="GPST", time_format="calendar",
                          frame="ECEF WGS84")
    project.put_json(ANTENNAS, {"frame": "FRD", "antennas": sim["antennas"]})
    for plugin in ("latency", "gnss_attitude"):
        t0 = time.perf_counter()
        spec = get_spec(plugin)
        spec.load_run()(project, spec.make_params())
        print(f"  {plugin} run in {time.perf_counter() - t0:.0f} s", flush=True)
    path = folder / "day.h5"
    project.save(path)
    project.close()
    return path


def demo_project(folder: Path | None, scratch: Path) -> Path:
    if folder is not None and (folder / "demo.h5").exists():
        return folder / "demo.h5"
    out = scratch / "demo"
    subprocess.run([sys.executable, "-m", "hydrosync_core.cli", "demo", "--out", str(out)],
                   check=True, stdout=subprocess.DEVNULL)
    return out / "demo.h5"


def as_before() -> None:
    """Draw every sample and break the page before every section (the pre-#26 layout)."""
    import hydrosync_core.report.build as build
    import hydrosync_core.report.charts as charts

    charts.line_indices = lambda x, y: np.arange(len(x))
    charts.cloud_indices = lambda x, y, cell: np.arange(len(x))
    build.SECTION_ROOM = 1.0


def measure(project_file: Path, pdf: Path) -> dict:
    from hydrosync_core.project import Project
    from hydrosync_core.report import build_report
    from hydrosync_core.report.template import PageLayout

    layout = PageLayout()
    with Project.open(project_file, readonly=True) as project:
        t0 = time.perf_counter()
        build_report(project, pdf, layout=layout)
        seconds = time.perf_counter() - t0
    return {"pages": len(layout.fill), "fill": layout.fill, "sparse": layout.sparse_pages(),
            "mb": pdf.stat().st_size / 1e6, "s": seconds}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--demo", type=Path, help="folder of an earlier `hydrosync demo`")
    parser.add_argument("--lines", type=int, default=500)
    parser.add_argument("--hours", type=float, default=10.0)
    parser.add_argument("--baseline", action="store_true", help="the pre-#26 layout")
    parser.add_argument("--keep", type=Path, help="write the PDFs into this folder")
    args = parser.parse_args()
    if args.baseline:
        as_before()
    with tempfile.TemporaryDirectory() as tmp:
        scratch = Path(tmp)
        out = args.keep or scratch
        out.mkdir(parents=True, exist_ok=True)
        print("building the projects …", flush=True)
        projects = {"demo": demo_project(args.demo, scratch),
                    f"survey day ({args.lines} lines, {args.hours:g} h array)":
                        survey_day(scratch, args.lines, args.hours)}
        label = "before #26 (--baseline)" if args.baseline else "now"
        print(f"\nreport layout, {label}")
        for i, (name, path) in enumerate(projects.items()):
            r = measure(path, out / f"report-{i}{'-baseline' if args.baseline else ''}.pdf")
            under = [f"{p}:{r['fill'][p - 1]:.0%}" for p in r["sparse"]]
            print(f"{name}: {r['pages']} pages, {r['mb']:.2f} MB, written in {r['s']:.1f} s; "
                  f"least-filled page {min(r['fill'][:-1], default=1):.0%}; pages under 40 % "
                  f"not ending a section: {', '.join(under) or 'none'}")
            print("  fill: " + " ".join(f"{f:.0%}" for f in r["fill"]))


if __name__ == "__main__":
    main()
