"""What ``hydrosync import`` and File → Import… can bring into a project.

Each kind maps a file to a project location through a reader. Modules add kinds with
:func:`register_kind` (the NMEA/real-log readers register theirs on import).
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from hydrosync_core.importers import pool_json, survey_csv, vessel_json
from hydrosync_core.project import Project, schema


@dataclass(frozen=True)
class ImportKind:
    """A kind of input file and how it lands in the project."""

    name: str
    description: str
    target: str
    store: Callable[[Project, str, Path], str]


KINDS: dict[str, ImportKind] = {}


def register_kind(kind: ImportKind) -> None:
    KINDS[kind.name] = kind


def _table(reader: Callable) -> Callable[[Project, str, Path], str]:
    def store(project: Project, target: str, path: Path) -> str:
        columns = reader(path)
        project.put_table(target, columns, source=str(path))
        rows = len(next(iter(columns.values())))
        return f"{rows} rows from {path.name} into /{target}"

    return store


def _points(project: Project, target: str, path: Path) -> str:
    from hydrosync_core.importers.pointcloud import read_point_cloud

    points = read_point_cloud(path)
    project.put(target, points, attrs={"source": str(path), "frame": "target ENU", "units": "m"})
    return f"{len(points)} points from {path.name} into /{target}"


def _json(reader: Callable) -> Callable[[Project, str, Path], str]:
    def store(project: Project, target: str, path: Path) -> str:
        project.put_json(target, reader(path))
        project.set_attrs(target, source=str(path))
        return f"{path.name} into /{target}"

    return store


for _kind in (
    ImportKind("gnss", "GNSS heights CSV (time, height[, lat, lon, quality])", schema.RAW_GNSS,
               _table(survey_csv.read_gnss_csv)),
    ImportKind("attitude", "attitude CSV (time, roll, pitch, heading, heave)", schema.RAW_ATTITUDE,
               _table(survey_csv.read_attitude_csv)),
    ImportKind("lines", "survey lines CSV (name, start, end)", schema.RAW_LINES,
               _table(survey_csv.read_lines_csv)),
    ImportKind("mbes", "multibeam soundings CSV (time, x, y, z; sensor frame)",
               f"{schema.RAW_POOL}/mbes", _table(survey_csv.read_mbes_csv)),
    ImportKind("ins", "INS trajectory CSV (time, e, n, u, roll, pitch, heading)",
               f"{schema.RAW_POOL}/ins", _table(survey_csv.read_ins_csv)),
    ImportKind("lidar", "laser points (CSV x,y,z / PLY / LAS / LAZ; target ENU)",
               f"{schema.RAW_POOL}/lidar", _points),
    ImportKind("setup", "pool setup.json (coarse boresight and lever arm)",
               f"{schema.RAW_POOL}/setup", _json(pool_json.read_setup_json)),
    ImportKind("target", "pool target.json (target design)", f"{schema.RAW_POOL}/target",
               _json(pool_json.read_target_json)),
    ImportKind("vessel", "vessel offset sheet vessel.json (sensor offsets, body FRD)",
               schema.VESSEL, _json(vessel_json.read_vessel_json)),
):
    register_kind(_kind)


def import_file(project: Project, kind: str, path: str | os.PathLike) -> str:
    """Read *path* as *kind* into *project*; return a one-line summary."""
    if kind not in KINDS:
        raise KeyError(f"unknown import kind '{kind}' (known: {', '.join(KINDS)})")
    spec = KINDS[kind]
    return spec.store(project, spec.target, Path(path))


# --- Real device logs (NMEA): stores live in log_import, imported lazily. -----------------
def _gnss_log(project: Project, target: str, path: Path) -> str:
    from hydrosync_core.importers.log_import import store_gnss_log

    return store_gnss_log(project, target, path)


def _attitude_log(project: Project, target: str, path: Path) -> str:
    from hydrosync_core.importers.log_import import store_attitude_log

    return store_attitude_log(project, target, path)


register_kind(ImportKind(
    "gnss_log", "NMEA GNSS log (GGA / PTNL,GGK [+GST, ZDA]; logger time tags allowed)",
    schema.RAW_GNSS, _gnss_log,
))
register_kind(ImportKind(
    "attitude_log", "NMEA motion log (PASHR / PSXN,23 / TSS1; see --heave-positive)",
    schema.RAW_ATTITUDE, _attitude_log,
))
