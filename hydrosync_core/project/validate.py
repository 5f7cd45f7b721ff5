"""Checks of what the methods read from a project, as careful as an importer's.

A project file can be damaged after it was written (a tool deleted a column, an old
version wrote text where numbers belong, a disk flipped bytes). :class:`Project`'s
readers call these checks so that such a file gives one line naming the project file,
the HDF5 path and what is wrong (:class:`~hydrosync_core.errors.ProjectDataError`, exit
2) instead of a ``KeyError`` deep inside a method.

* every table: 1-D columns of one length (the ``columns`` attribute is checked by
  :meth:`Project.get_table`);
* the known input tables and datasets below: required columns present, numbers (not
  text or bytes), finite where the methods need it, and physically plausible
  (:mod:`hydrosync_core.plausible`); survey lines neither duplicated nor overlapping;
* the known JSON documents (vessel sheet, pool setup and target): the shape the
  importers accept.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hydrosync_core import plausible
from hydrosync_core.errors import InputError, ProjectDataError


@dataclass(frozen=True)
class Column:
    """What one column of a known table must be."""

    kind: str = "number"  # "number" or "text"
    limits: plausible.Limits | None = None
    finite: bool = True  # NaN/inf forbidden (else only judged where finite)
    required: bool = True


def _numbers(limits: dict, optional: tuple[str, ...] = (), nan_ok: tuple[str, ...] = ()):
    return {name: Column("number", lim, finite=name not in nan_ok + optional,
                         required=name not in optional) for name, lim in limits.items()}


TABLES: dict[str, dict[str, Column]] = {
    "raw/gnss": _numbers(plausible.GNSS, optional=("lat", "lon", "quality", "sigma_h")),
    "raw/attitude": _numbers(plausible.ATTITUDE, nan_ok=("heading",)),
    "raw/lines": {"name": Column("text"), **_numbers(plausible.LINES)},
    "raw/pool/mbes": _numbers(plausible.MBES),
    "raw/pool/ins": _numbers(plausible.INS),
}
"""Known input tables: column → requirement."""

DATASETS: dict[str, tuple[int, plausible.Limits]] = {
    "raw/pool/lidar": (3, plausible.COORDINATE),
}
"""Known input arrays: path → (number of columns of the (N, k) array, limits)."""


def _fail(project: str, path: str, message: str) -> ProjectDataError:
    return ProjectDataError(project, path, message)


def _as_numbers(project: str, path: str, values: np.ndarray) -> np.ndarray:
    if values.dtype.kind not in "biuf":
        kind = {"U": "text", "S": "bytes", "O": "text", "c": "complex numbers"}.get(
            values.dtype.kind, f"values of type {values.dtype}")
        raise _fail(project, path, f"holds {kind} where numbers belong")
    return values.astype(float, copy=False)


def _check_values(project: str, path: str, values: np.ndarray, column: Column) -> None:
    numbers = _as_numbers(project, path, values)
    finite = np.isfinite(numbers)
    if column.finite and not finite.all():
        i = int(np.flatnonzero(~finite)[0])
        raise _fail(project, path, f"row {i + 1}: value {numbers[i]} is not finite")
    if column.limits is not None:
        i = plausible.first_outside(np.where(finite, numbers, 0.0), column.limits)
        if i is not None:
            raise _fail(project, path, f"row {i + 1}: "
                        + plausible.problem(numbers[i], column.limits))


def check_table(project: str, path: str, table: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Check *table* read from *path* of *project*; return it (see the module doc)."""
    path = path.strip("/")
    lengths = {}
    for name, values in table.items():
        values = np.asarray(values)
        if values.ndim != 1:
            shape = "x".join(str(n) for n in values.shape) or "scalar"
            raise _fail(project, f"{path}/{name}", f"is {values.ndim}-D (shape {shape}); "
                        "a table column must be 1-D")
        lengths[name] = values.shape[0]
    if len(set(lengths.values())) > 1:
        first = next(iter(lengths))
        odd = next(n for n, k in lengths.items() if k != lengths[first])
        raise _fail(project, f"{path}/{odd}", f"has {lengths[odd]} rows but column "
                    f"'{first}' has {lengths[first]}: the table is damaged")
    spec = TABLES.get(path)
    if spec is None:
        return table
    for name, column in spec.items():
        if name not in table:
            if column.required:
                raise _fail(project, path, f"required column '{name}' is missing "
                            f"(table has: {', '.join(table) or 'no columns'})")
            continue
        if column.kind == "text":
            if table[name].dtype.kind not in "UO":
                raise _fail(project, f"{path}/{name}", f"holds {table[name].dtype} values "
                            "where text belongs")
            continue
        _check_values(project, f"{path}/{name}", table[name], column)
    if path == "raw/lines":
        check_lines(project, path, table)
    return table


def check_lines(source: str, path: str | None, table: dict[str, np.ndarray],
                line_numbers=None) -> None:
    """Survey lines must not repeat or overlap in time: each epoch belongs to one line.

    A duplicated line would be counted twice and narrow the 95 % interval falsely.
    Raises :class:`InputError` naming both lines (and their file lines, if given).
    """
    names = [str(n) for n in np.asarray(table["name"]).ravel()]
    start = np.asarray(table["start"], dtype=float).ravel()
    end = np.asarray(table["end"], dtype=float).ravel()
    backwards = np.flatnonzero(~(end > start))
    if backwards.size:  # else reported later as "no line has 30 epochs" (issue #28)
        i = int(backwards[0])
        message = (f"line '{names[i]}' ends ({end[i]:g} s) before or when it starts "
                   f"({start[i]:g} s)")
        if path is None:
            raise InputError(source, message, line=None if line_numbers is None
                             else int(line_numbers[i]))
        raise _fail(source, path, message)
    order = np.argsort(start, kind="stable")
    for a, b in zip(order[:-1], order[1:], strict=True):
        if start[b] < end[a]:
            same = start[a] == start[b] and end[a] == end[b]
            what = "repeats" if same else "overlaps"
            message = (f"line '{names[b]}' ({start[b]:g} … {end[b]:g} s) {what} line "
                       f"'{names[a]}' ({start[a]:g} … {end[a]:g} s): every epoch must belong "
                       "to one line (remove or split the duplicate)")
            if path is None:
                line = None if line_numbers is None else int(line_numbers[b])
                if line_numbers is not None:
                    message += f"; see also line {int(line_numbers[a])}"
                raise InputError(source, message, line=line)
            raise _fail(source, path, message)
    if len(set(names)) != len(names):
        dup = next(n for n in names if names.count(n) > 1)
        message = f"line name '{dup}' is used twice"
        raise (_fail(source, path, message) if path is not None
               else InputError(source, message, field="name"))


def check_dataset(project: str, path: str, values: np.ndarray) -> np.ndarray:
    """Check a known input array (``raw/pool/lidar``: (N, 3) finite plausible numbers)."""
    path = path.strip("/")
    spec = DATASETS.get(path)
    if spec is None:
        return values
    width, limits = spec
    values = np.asarray(values)
    if values.ndim != 2 or values.shape[1] != width:
        shape = "x".join(str(n) for n in values.shape) or "scalar"
        raise _fail(project, path, f"has shape {shape}; expected (N, {width})")
    _check_values(project, path, values.reshape(-1), Column("number", limits))
    return values


def check_json(project: str, path: str, document):
    """Check a known JSON document (vessel sheet, pool setup, pool target); return it."""
    path = path.strip("/")
    from hydrosync_core.importers import pool_json, vessel_json

    checks = {"vessel": vessel_json.check_vessel, "raw/pool/setup": pool_json.check_setup,
              "raw/pool/target": pool_json.check_target}
    check = checks.get(path)
    if check is None:
        return document
    try:
        return check(document, source=project)
    except InputError as exc:
        where = f"{path}@json" + (f" {exc.field}" if exc.field else "")
        raise _fail(project, where, exc.message) from None
