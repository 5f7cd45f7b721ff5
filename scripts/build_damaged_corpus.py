#!/usr/bin/env python3
"""Build the damaged-project corpus of issue #9 (and optionally run HydroSync on it).

A small but complete project (a 3-line latency day and a small pool pass, both run, so
``/results`` exists) is damaged in the ways a careless tool, an old version or a disk
can damage a file: a deleted column, a ``columns`` attribute naming a missing dataset, a
string time column, a short or 2-D column, bytes where floats belong, impossible
values, duplicated survey lines, a setup / target / vessel JSON that does not parse or
has the wrong shape, flipped bytes inside a compressed chunk, a damaged result table.

Every case names the command to run and what must happen: exit 2 with one line naming
the project file and the HDF5 path, or — for ``report`` — exit 0 with a warning and the
section shown as "could not be produced" (exit 2 with ``--strict``).

    python scripts/build_damaged_corpus.py OUT_DIR [--run]

The reliability tests (``tests/reliability/test_damaged_projects.py``) build the corpus in
a temporary folder and run every case.
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np


@dataclass(frozen=True)
class Case:
    """One damaged project and the command that must survive it."""

    name: str
    command: str  # "latency", "pool-calibrate", "vessel", "report"
    hdf5_path: str  # what the message must name ("" for report cases)
    damage: Callable[[h5py.File], None]


def build_base(path: Path) -> Path:
    """The undamaged project: latency day (3 lines) + small pool pass, both run."""
    from hydrosync_core.methods.latency.project_run import run as run_latency
    from hydrosync_core.methods.latency.simulate import DayConfig, simulate_day
    from hydrosync_core.methods.pool_calibration.demo import fill_demo as fill_pool
    from hydrosync_core.methods.pool_calibration.project_run import run as run_pool
    from hydrosync_core.methods.pool_calibration.simulate import PoolPassConfig
    from hydrosync_core.project import Project
    from hydrosync_core.project.vessel import set_sensor

    project = Project.new("damaged-corpus base")
    day = simulate_day(DayConfig(n_lines=3, line_s=100.0, turn_s=40.0), seed=4)
    for name in ("gnss", "attitude", "lines"):
        project.put_table(f"raw/{name}", day[name], source="simulated")
    set_sensor(project, "motion", [0.0, 0.0, 0.0])
    set_sensor(project, "gnss", day["truth"]["lever_arm_m"])
    fill_pool(project, seed=11, config=PoolPassConfig(beams=96, ping_rate_hz=6.0,
                                                      laser_density_per_m2=500.0))
    run_latency(project, {"step_s": 0.01})
    run_pool(project)
    project.save(path)
    project.close()
    return path


# ----------------------------------------------------------------- damage kinds
def _replace(f: h5py.File, path: str, data) -> None:
    attrs = dict(f[path].attrs)
    del f[path]
    f.create_dataset(path, data=data)
    for key, value in attrs.items():
        f[path].attrs[key] = value


def _drop_column(table: str, column: str, keep_listing: bool) -> Callable:
    def damage(f):
        del f[f"{table}/{column}"]
        if not keep_listing:
            names = [n for n in f[table].attrs["columns"] if n != column]
            f[table].attrs["columns"] = np.array(names, dtype=h5py.string_dtype())
    return damage


def _as_strings(path: str) -> Callable:
    def damage(f):
        values = f[path][()]
        _replace(f, path, np.array([f"{v:.3f}" for v in values], dtype=h5py.string_dtype()))
    return damage


def _as_bytes(path: str) -> Callable:
    def damage(f):
        values = f[path][()]
        _replace(f, path, np.array([str(v).encode() for v in values], dtype="S24"))
    return damage


def _short(path: str) -> Callable:
    return lambda f: _replace(f, path, f[path][()][:-7])


def _two_d(path: str) -> Callable:
    return lambda f: _replace(f, path, np.repeat(f[path][()][:, None], 2, axis=1))


def _value(path: str, index: int, value: float) -> Callable:
    def damage(f):
        data = f[path][()]
        data[index] = value
        _replace(f, path, data)
    return damage


def _json(path: str, text: str) -> Callable:
    def damage(f):
        f[path].attrs["json"] = text
    return damage


def _json_edit(path: str, edit: Callable[[dict], object]) -> Callable:
    def damage(f):
        f[path].attrs["json"] = json.dumps(edit(json.loads(f[path].attrs["json"])))
    return damage


def _flip_chunk(path: str) -> Callable:
    """Flip bytes in the middle of the first compressed chunk of *path* (on disk)."""
    def damage(f):
        info = f[path].id.get_chunk_info(0)
        f.attrs["_flip"] = np.array([info.byte_offset, info.size], dtype=np.int64)
    return damage


def _without_pool(damage: Callable) -> Callable:
    """*damage*, with the pool results removed (a shorter report to build)."""
    def both(f):
        damage(f)
        del f["results/pool_calibration"]
    return both


def _duplicate_line(f: h5py.File) -> None:
    table = "raw/lines"
    names = f[f"{table}/name"].asstr()[()]
    start, end = f[f"{table}/start"][()], f[f"{table}/end"][()]
    _replace(f, f"{table}/name", np.array(list(names) + [names[0] + "-again"],
                                          dtype=h5py.string_dtype()))
    _replace(f, f"{table}/start", np.append(start, start[0]))
    _replace(f, f"{table}/end", np.append(end, end[0]))


def _overlap_line(f: h5py.File) -> None:
    table = "raw/lines"
    start, end = f[f"{table}/start"][()], f[f"{table}/end"][()]
    end[0] = start[1] + 10.0
    _replace(f, f"{table}/end", end)


CASES: tuple[Case, ...] = (
    Case("deleted-column", "latency", "raw/gnss/height",
         _drop_column("raw/gnss", "height", keep_listing=True)),
    Case("deleted-column-unlisted", "latency", "raw/gnss",
         _drop_column("raw/gnss", "height", keep_listing=False)),
    Case("string-time-column", "latency", "raw/attitude/time", _as_strings("raw/attitude/time")),
    Case("bytes-for-floats", "latency", "raw/gnss/height", _as_bytes("raw/gnss/height")),
    Case("short-column", "latency", "raw/gnss/height", _short("raw/gnss/height")),
    Case("2d-column", "latency", "raw/attitude/roll", _two_d("raw/attitude/roll")),
    Case("nan-in-time", "latency", "raw/gnss/time", _value("raw/gnss/time", 5, np.nan)),
    Case("roll-1e308", "latency", "raw/attitude/roll", _value("raw/attitude/roll", 9, 1e308)),
    Case("duplicated-line", "latency", "raw/lines", _duplicate_line),
    Case("overlapping-lines", "latency", "raw/lines", _overlap_line),
    Case("vessel-json-invalid", "latency", "vessel@json", _json("vessel", "{'sensors': [")),
    Case("vessel-json-shape", "vessel", "vessel@json",
         _json_edit("vessel", lambda d: {**d, "sensors": {"gnss": {"offset_m": "1,2,3"}}})),
    Case("broken-chunk-attitude", "latency", "raw/attitude/", _flip_chunk("raw/attitude/heave")),
    Case("setup-json-invalid", "pool-calibrate", "raw/pool/setup@json",
         _json("raw/pool/setup", '{"boresight_deg": {"roll": -35,')),
    Case("setup-json-shape", "pool-calibrate", "raw/pool/setup@json",
         _json_edit("raw/pool/setup", lambda d: {**d, "boresight_deg": [-35, 0, 0]})),
    Case("setup-json-string-value", "pool-calibrate", "raw/pool/setup@json",
         _json_edit("raw/pool/setup", lambda d: {**d, "lever_arm_m": {"x": "1.2", "y": 2,
                                                                      "z": 1}})),
    Case("target-json-shape", "pool-calibrate", "raw/pool/target@json",
         _json_edit("raw/pool/target", lambda d: {**d, "faces": {"wall": 1}})),
    Case("lidar-wrong-shape", "pool-calibrate", "raw/pool/lidar",
         lambda f: _replace(f, "raw/pool/lidar", f["raw/pool/lidar"][()][:, :2])),
    Case("broken-chunk-lidar", "pool-calibrate", "raw/pool/", _flip_chunk("raw/pool/lidar")),
    Case("mbes-column-missing-dataset", "pool-calibrate", "raw/pool/mbes/x",
         _drop_column("raw/pool/mbes", "x", keep_listing=True)),
    Case("results-2d-column", "report", "", _without_pool(_two_d(
        "results/latency/lines/latency_s"))),
    Case("report-vessel-json-invalid", "report", "",
         _without_pool(_json("vessel", "{'sensors': ["))),
    Case("results-columns-name-missing", "report", "",
         _drop_column("results/pool_calibration/faces", "rms_mbes_m", keep_listing=True)),
)


def damage_copy(base: Path, folder: Path, case: Case) -> Path:
    """Copy *base* to ``folder/<case>.h5`` and damage it as *case* says."""
    path = folder / f"{case.name}.h5"
    shutil.copyfile(base, path)
    with h5py.File(path, "r+") as f:
        case.damage(f)
        flip = f.attrs.get("_flip")
        if flip is not None:
            del f.attrs["_flip"]
    if flip is not None:
        offset, size = (int(v) for v in flip)
        with open(path, "r+b") as fh:
            fh.seek(offset + size // 3)
            chunk = bytearray(fh.read(16))
            fh.seek(offset + size // 3)
            fh.write(bytes(b ^ 0xA5 for b in chunk))
    return path


def build_corpus(folder: Path, base: Path | None = None) -> list[tuple[Case, Path]]:
    """Build the base project and every damaged copy in *folder*."""
    folder.mkdir(parents=True, exist_ok=True)
    base = base or build_base(folder / "base.h5")
    return [(case, damage_copy(base, folder, case)) for case in CASES]


def argv_for(case: Case, path: Path, strict: bool = False) -> list[str]:
    if case.command == "report":
        return ["report", str(path), "-o", str(path.with_suffix(".pdf"))] + (
            ["--strict"] if strict else [])
    return [case.command, str(path)]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", type=Path, help="folder to build the corpus in")
    parser.add_argument("--run", action="store_true", help="run hydrosync on every case")
    args = parser.parse_args()
    corpus = build_corpus(args.out)
    print(f"{len(corpus)} damaged projects in {args.out}")
    if not args.run:
        return 0
    import subprocess

    failed = 0
    for case, path in corpus:
        done = subprocess.run([sys.executable, "-m", "hydrosync_core.cli", *argv_for(case, path)],
                              capture_output=True, text=True)
        lines = done.stderr.strip().splitlines()
        want = 0 if case.command == "report" else 2
        ok = done.returncode == want and (want == 0 or len(lines) == 1)
        failed += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {case.name:<30} exit {done.returncode}  "
              f"{lines[-1] if lines else ''}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
