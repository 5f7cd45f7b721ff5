"""Campaign processing on Dask: 16 simulated survey days with 1 and 2 worker processes.

Each day is one project holding the demo data of the latency (13 two-minute lines, 1 Hz RTK
heights, 50 Hz attitude), GNSS-attitude (four antennas, 10 min at 1 Hz) and tilt-alignment
(one pole swing) simulators; the campaign runs those three analyses on every day (48
project × analysis tasks, chained per project) and writes the summary (CSV + HTML with the
latency trend), no PDFs. Each worker count starts from fresh copies of the same projects.

Printed per worker count: the LocalCluster start-up, the campaign's wall time (submission
to last result, summary included), the speed-up against one worker, the summed task time
(work done inside the steps) and the peak resident memory of each worker process
(``ru_maxrss``); the header gives the machine's load average at the end: other processes
competing for the cores eat the speed-up (compare "sum of task s" between the rows: it
stays constant when the workers each have a core). The GNSS/INS smoother is left out:
about a minute per day on this machine, it would make the benchmark 30 minutes long
without saying more about the scheduling.
"""

from __future__ import annotations

import argparse
import logging
import os
import shutil
import tempfile
import time
from pathlib import Path

from hydrosync_core.campaign import load_campaign
from hydrosync_core.campaign.engine import run_campaign
from hydrosync_core.campaign.simulate import make_campaign

ANALYSES = ("latency", "gnss_attitude", "tilt_alignment")


def peak_rss_mib() -> float:
    import resource
    import sys

    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return rss / (1024 * 1024) if sys.platform == "darwin" else rss / 1024


def run(template: Path, workers: int) -> dict:
    from dask.distributed import Client, LocalCluster

    folder = template.parent / f"run-{workers}"
    shutil.copytree(template, folder)
    campaign = load_campaign(folder / "campaign.toml")
    t0 = time.perf_counter()
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                           dashboard_address=None, silence_logs=logging.ERROR)
    client = Client(cluster)
    start_s = time.perf_counter() - t0
    try:
        result = run_campaign(campaign, client=client)
        rss = sorted(client.run(peak_rss_mib).values())
    finally:
        client.close()
        cluster.close()
    bad = result.failed
    if bad:
        raise SystemExit(f"{len(bad)} step(s) failed: {bad[0]['message']}")
    return {"workers": workers, "start_s": start_s, "wall_s": result.wall_s,
            "task_s": sum(o["seconds"] for o in result.outcomes), "rss": rss,
            "tasks": len(result.outcomes)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--days", type=int, default=16)
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="bench-campaign-") as tmp:
        t0 = time.perf_counter()
        template = Path(tmp) / "template"
        make_campaign(template, days=args.days, analyses=ANALYSES)
        made = time.perf_counter() - t0
        rows = [run(template, n) for n in args.workers]
    load = ", ".join(f"{v:.1f}" for v in os.getloadavg())
    print(f"Campaign of {args.days} simulated survey days x {len(ANALYSES)} analyses "
          f"({', '.join(ANALYSES)}): {rows[0]['tasks']} tasks; projects simulated in "
          f"{made:.1f} s (not timed below); {os.cpu_count()} cores, load average {load}")
    head = (f"{'workers':>7} {'cluster start s':>15} {'campaign wall s':>15} {'speed-up':>8} "
            f"{'sum of task s':>13} {'peak RSS per worker MiB':>24}")
    print(head)
    print("-" * len(head))
    base = rows[0]["wall_s"]
    for r in rows:
        rss = ", ".join(f"{v:.0f}" for v in r["rss"])
        print(f"{r['workers']:>7} {r['start_s']:>15.1f} {r['wall_s']:>15.1f} "
              f"{base / r['wall_s']:>8.2f} {r['task_s']:>13.1f} {rss:>24}")


if __name__ == "__main__":
    main()
