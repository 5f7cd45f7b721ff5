"""Several log files of one kind (a day in hourly files): names, time order, one table.

:func:`expand` turns the names and glob patterns a user gave into files;
:func:`merge` puts the per-file tables (each sorted, from :mod:`log_import`) in time
order into one. Files are ordered by their first epoch, whatever their names or the
order given. A gap between consecutive files longer than ten sampling intervals (and
1 s) is reported; files whose time spans overlap are reported and interleaved; an epoch
present in two files is an error naming both (the same data imported twice, or two
devices in one kind).
"""

from __future__ import annotations

import glob
import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.importers.import_report import ImportReport
from hydrosync_core.importers.table_sink import READ_ROWS, TableSink

_MAGIC = set("*?[")


def expand(paths: str | os.PathLike | Iterable[str | os.PathLike]) -> list[Path]:
    """Files named by *paths* (one name or pattern, or several), globs expanded and sorted,
    each file once. A pattern that matches nothing is an :class:`InputError`."""
    if isinstance(paths, str | os.PathLike):
        paths = [paths]
    out: list[Path] = []
    for item in paths:
        text = os.fspath(item)
        if _MAGIC & set(text) and not Path(text).exists():
            hits = sorted(p for p in glob.glob(os.path.expanduser(text)) if Path(p).is_file())
            if not hits:
                raise InputError(text, "matches no file")
            out.extend(Path(p) for p in hits)
        else:
            out.append(Path(text))
    seen: set = set()
    return [p for p in out if not (p.resolve() in seen or seen.add(p.resolve()))]


@dataclass
class Part:
    """One file's table (sorted by time, in *group* of the scratch file) and report.

    The columns are opened when asked for and closed when dropped: HDF5 keeps a chunk
    cache per open dataset, and a day of hourly files would otherwise hold 24 of them.
    """

    path: Path
    group: h5py.Group
    names: list[str]
    report: ImportReport

    @property
    def columns(self) -> dict[str, h5py.Dataset]:
        return {name: self.group[name] for name in self.names}

    @property
    def first(self) -> float:
        return float(self.group["time"][0])

    @property
    def last(self) -> float:
        return float(self.group["time"][-1])

    def interval(self) -> float:
        """Median sampling interval (s) over the first rows."""
        t = self.group["time"][:10_000]
        return float(np.median(np.diff(t))) if t.size > 1 else 0.0


def _repeated(a: Part, b: Part) -> np.ndarray:
    """Epochs of *b* that *a* also holds (each file's time column read once)."""
    lo, hi = max(a.first, b.first), min(a.last, b.last)
    ta, tb = a.group["time"][()], b.group["time"][()]
    return np.intersect1d(ta[(ta >= lo) & (ta <= hi)], tb[(tb >= lo) & (tb <= hi)])


def check_order(parts: Sequence[Part]) -> tuple[list[str], bool]:
    """Notes on gaps and overlaps between files in time order, and whether they are
    disjoint (so concatenating them keeps the time order). Raises on a repeated epoch."""
    notes: list[str] = []
    disjoint = True
    for j, b in enumerate(parts[1:], start=1):
        a = parts[j - 1]
        for earlier in parts[:j]:
            if earlier.last < b.first:
                continue
            common = _repeated(earlier, b)
            if common.size:
                raise InputError(
                    str(b.path),
                    f"{common.size} epochs (first at t = {common[0]:.3f} s) are also in "
                    f"{earlier.path}: the same records in two files; import each once")
            notes.append(f"{b.path.name} overlaps {earlier.path.name} by "
                         f"{min(earlier.last, b.last) - b.first:.1f} s: records interleaved")
            disjoint = False
        gap = b.first - a.last
        if gap > max(1.0, 10.0 * a.interval()):
            notes.append(f"gap of {gap:.1f} s between {a.path.name} and {b.path.name}")
    return notes, disjoint


def merge(group: h5py.Group, parts: list[Part]) -> tuple[dict[str, h5py.Dataset], list[str]]:
    """One table of *parts* in time order (in *group* when there are several)."""
    parts.sort(key=lambda p: p.first)
    notes, _ = check_order(parts)
    if len(parts) == 1:
        return parts[0].columns, notes
    names = list(dict.fromkeys(n for p in parts for n in p.names))
    sink = TableSink(group.create_group("merged"), names)
    for part in parts:
        columns = part.columns
        n = columns["time"].shape[0]
        for a in range(0, n, READ_ROWS):
            b = min(a + READ_ROWS, n)
            sink.append({k: columns[k][a:b] if k in columns else np.full(b - a, np.nan)
                         for k in names})
        del columns
    return sink.finish(), notes


def merged_report(parts: Sequence[Part], used: int, notes: list[str]) -> ImportReport:
    """The report of several files: counts summed, warnings named by file."""
    if len(parts) == 1:
        rep = parts[0].report
        return ImportReport(**{**rep.to_dict(), "warnings": tuple(rep.warnings) + tuple(notes)})
    reps = [p.report for p in parts]

    def distinct(name: str) -> str:
        return "+".join(dict.fromkeys(str(getattr(r, name)) for r in reps))

    def summed(name: str) -> dict[str, int]:
        out: dict[str, int] = {}
        for r in reps:
            for k, v in getattr(r, name).items():
                out[k] = out.get(k, 0) + v
        return out

    lags = [r.logger_minus_sentence_s for r in reps if r.logger_minus_sentence_s is not None]
    warnings = [f"{p.path.name}: {w}" for p in parts for w in p.report.warnings] + notes
    return ImportReport(
        file=f"{parts[0].path} … {parts[-1].path.name} ({len(parts)} files)",
        kind=reps[0].kind, source=distinct("source"), time_source=distinct("time_source"),
        date_source=distinct("date_source"), lines=sum(r.lines for r in reps),
        sentences=sum(r.sentences for r in reps), used=used, skipped=summed("skipped"),
        sentence_counts=summed("sentence_counts"), warnings=tuple(warnings),
        logger_minus_sentence_s=float(np.median(lags)) if lags else None,
        heave_positive=reps[0].heave_positive,
    )
