"""Latency on every real log of the shared corpus that carries heights and heave (issue #29).

For each log in ``../shared/data/real-logs`` with GNSS heights (GGA) and heave (PSXN,23,
PASHR, TSS1) over at least two minutes: import it as the README walkthrough does (heave
positive down for Seapath, lever arm 0, two lines over the record), then estimate with the
default (``auto``) and the published method (``qi2010``), each with the delay-model band
check, and once more with a heave filter declared (2nd-order high-pass, 20 s, a typical
setting: the logs do not say theirs; scan range ±3 s, since such a filter moves the
peak beyond −1 s). Prints one Markdown table; no truth is known, the
point is whether the estimators agree within σ or say why not.

Run: ``.venv/bin/python benchmarks/bench_latency_real.py`` (about a minute).
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from hydrosync_core.cli import main as cli
from hydrosync_core.methods.latency import estimate_latency
from hydrosync_core.methods.latency.texts import latency_text
from hydrosync_core.project import Project

REAL = Path(__file__).resolve().parents[1] / ".." / "shared" / "data" / "real-logs"
LOGS = {  # file: (heave sign, why it is or is not in the table)
    "tagged/openrvdas_NBP1406_seap-2014-08-01.txt": "down",
    "tagged/openrvdas_NBP1406_s330-2014-08-01.txt": "down",
}
SKIPPED = {
    "motion/gpsd_rst39_oxts_pashr.log": "PASHR heave 4 s long (100 records at 25 Hz)",
    "motion/ncei_healy_mru_tss1_EXCERPT.txt": "3 TSS1 records, no heights",
    "motion/gpsd_hemi.log, gpsd_saab-r4.log": "no heave",
}


def _tables(log: Path, heave: str, folder: Path) -> tuple[dict, dict, dict]:
    """(gnss, attitude, lines) as the walkthrough imports them; two lines, halves."""
    project = folder / "log.h5"
    lines = folder / "lines.csv"
    lines.write_text("name,start,end\nA,0,1\n")
    assert cli(["import", str(project), "--gnss-log", str(log), "--attitude-log", str(log),
                "--heave-positive", heave]) == 0
    with Project.open(project) as p:
        gnss, att = p.get_table("raw/gnss"), p.get_table("raw/attitude")
    t0, t1 = float(gnss["time"][0]), float(gnss["time"][-1])
    mid = 0.5 * (t0 + t1)
    return gnss, att, {"name": np.array(["A", "B"]), "start": np.array([t0, mid]),
                       "end": np.array([mid, t1])}


def _row(name: str, label: str, res) -> str:
    model = res.diagnostics.get("delay_model", {})
    bands = ", ".join(f"{b['delay_s'] * 1e3:+.0f}" for b in model.get("bands", []))
    flags = "; ".join(w.split(":")[1].split("—")[0].split("(")[0].strip()
                      for w in res.warnings if w.startswith("delay model")) or "—"
    other = res.diagnostics.get("other_estimate")
    other_text = (f"{other['estimator']} {latency_text(other['latency_s'], other['uncertainty_s'])}"
                  if other else "—")
    return (f"| {name} | {label} | {res.estimator} {latency_text(res.latency_s, res.uncertainty_s)}"
            f" | {other_text} | {bands or '—'} | {model.get('p_value', float('nan')):.2g} "
            f"| {flags} |")


def main() -> None:
    print("| log | run | estimate (σ widened when flagged) | the other estimator | band "
          "delays [ms] (long → short periods) | band χ² p | flags |")
    print("|---|---|---|---|---|---|---|")
    for rel, heave in LOGS.items():
        log = REAL / rel
        if not log.exists():
            print(f"| {rel} | skipped: not in ../shared/data | | | | | |")
            continue
        with tempfile.TemporaryDirectory() as folder:
            gnss, att, lines = _tables(log, heave, Path(folder))
        name = Path(rel).name.replace("openrvdas_NBP1406_", "").replace("-2014-08-01.txt", "")
        for label, params in (
                ("auto", {}), ("qi2010", {"estimator": "qi2010"}),
                ("auto, HP2 20 s declared", {"heave_filter": "highpass",
                                             "range_s": (-3.0, 3.0)}),
                ("qi2010, HP2 20 s declared", {"estimator": "qi2010", "range_s": (-3.0, 3.0),
                                               "heave_filter": "highpass"})):
            res = estimate_latency(gnss, att, lines, (0.0, 0.0, 0.0), params)
            print(_row(name, label, res))
    for rel, why in SKIPPED.items():
        print(f"| {rel} | not in the table: {why} | | | | | |")


if __name__ == "__main__":
    main()
