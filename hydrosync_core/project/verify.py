"""Reading stored data back against the checksums written with it.

Each dataset of a project carries the SHA-256 of its values (``sha256`` attribute,
written when it was stored). The provenance check of results compares those attributes
without reading the data, so a chunk damaged on disk since (a bad sector, a copy cut
short) would still read "up to date". :func:`damaged` reads the datasets back and names
every one that cannot be read or whose values no longer match their checksum.
"""

from __future__ import annotations

from collections.abc import Iterable

from hydrosync_core.errors import clip
from hydrosync_core.project.model import Project, content_sha256
from hydrosync_core.project.nodes import GroupNode


def damaged(project: Project, paths: Iterable[str]) -> dict[str, str]:
    """``{dataset path: what is wrong}`` for the datasets under *paths* (groups or
    datasets); datasets without a stored checksum are read but not compared."""
    problems: dict[str, str] = {}
    for top in dict.fromkeys(p.strip("/") for p in paths):
        if not project.exists(top):
            continue
        if isinstance(project._find(top), GroupNode):
            infos = [i for i in project.walk(top) if i.kind == "dataset"]
            for info in infos:
                problems.update(_check(project, info.path, info.attrs.get("sha256")))
        else:
            problems.update(_check(project, top, project.attrs(top).get("sha256")))
    return problems


def _check(project: Project, path: str, expected) -> dict[str, str]:
    try:
        data = project.get(path)
    except Exception as exc:  # HDF5 raises many kinds on a damaged chunk
        return {path: f"cannot be read ({clip(exc, 100)})"}
    if expected is not None and content_sha256(data) != str(expected):
        return {path: "its values no longer match the checksum stored with them"}
    return {}
