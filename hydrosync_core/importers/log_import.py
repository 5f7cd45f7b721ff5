"""Import real NMEA device logs as the GNSS-height and attitude tables of a project.

:func:`read_gnss_log` -> columns ``time`` (s), ``height`` (m, ellipsoidal), ``lat``,
``lon`` (deg), ``quality`` (GGA code) and, when the log has GST, ``sigma_h`` (m, NaN
where no GST matched); :func:`read_attitude_log` -> ``time`` (s), ``roll``, ``pitch``,
``heading`` (deg, HydroSync conventions), ``heave`` (m, positive up). Both stream the file
block by block (:mod:`log_stream`) into chunked HDF5 datasets, so memory does not grow
with the file, and return an :class:`ImportReport` saying what was read, what was used and
what was skipped and why; they raise :class:`~hydrosync_core.errors.InputError` naming the
file and the reasons when nothing is usable. :func:`import_gnss_log` and
:func:`import_attitude_log` return the columns as arrays (small files, tests).

Time scale. ``time_source="logger"`` uses the logging computer's time tag (Unix
seconds); ``"sentence"`` uses the sentence's own UTC time of day dated by ZDA/RMC/GGK
(week-rollover corrected) or by the logger tag, also as Unix seconds — or seconds since
00:00 of the first day when the log holds no date at all (reported). ``"auto"`` (default)
takes the logger tag when most sentences carry one: the latency method needs the time
at which each record reached the logger.
"""

from __future__ import annotations

import os
from pathlib import Path

import h5py
import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.importers import log_stream as ls
from hydrosync_core.importers import nmea_gnss as ng
from hydrosync_core.importers import nmea_motion as nm
from hydrosync_core.importers.import_report import ImportReport
from hydrosync_core.importers.table_sink import READ_ROWS, memory_file, read_columns
from hydrosync_core.progress import CancelToken, ProgressCallback, report

__all__ = ["ImportReport", "import_attitude_log", "import_gnss_log", "read_attitude_log",
           "read_gnss_log"]

MAX_LOG_BYTES = ls.MAX_LOG_BYTES
MOTION_SOURCES = ("PASHR", "PSXN,23", "TSS1")


def _line_skips(state: ls.FileState, wanted: tuple[str, ...]) -> dict[str, int]:
    """Lines set aside while splitting, plus valid sentences of types not read here."""
    out = {k: v for k, v in ls.finish_counts(state).items()
           if k not in ("lines", "sentences", "no checksum (accepted)")}
    other = sum(n for k, n in state.kinds.items() if k not in wanted)
    if other:
        out["other sentence types"] = other
    return out


def _nothing_usable(path: Path, what: str, state: ls.FileState, skipped: dict) -> InputError:
    seen = ", ".join(f"{k} {n}" for k, n in sorted(state.kinds.items())) or "none"
    why = ", ".join(f"{k} {v}" for k, v in sorted(skipped.items())) or "nothing set aside"
    return InputError(
        str(path),
        f"no usable {what} in {state.counts.get('lines', 0)} lines "
        f"(sentences found: {seen}; set aside: {why})",
    )


def _start(path, time_source, progress, cancel) -> ls.FileState:
    path = Path(path)
    ls.check_file(path)
    census = ls.census(path, progress, cancel)
    return ls.FileState(path, census, ls.choose_time(census, time_source, path))


def _base_warnings(state: ls.FileState) -> list[str]:
    return ["no checksums in file: sentences accepted unchecked"] if (
        state.census.no_checksums and state.census.n_without) else []


def _report(state, kind, cand, date_source, used, skipped, warnings, **extra) -> ImportReport:
    return ImportReport(
        file=str(state.path), kind=kind, source=cand.source, time_source=state.time_source,
        date_source=date_source, lines=state.counts.get("lines", 0),
        sentences=state.counts.get("sentences", 0), used=used, skipped=skipped,
        sentence_counts=dict(sorted(state.kinds.items())), warnings=tuple(warnings),
        logger_minus_sentence_s=cand.lag(), **extra,
    )


def read_gnss_log(
    path: str | os.PathLike,
    group: h5py.Group,
    time_source: str = "auto",
    *,
    empty_geoid: str = "zero",
    min_quality: int = 1,
    progress: ProgressCallback | None = None,
    cancel: CancelToken | None = None,
) -> tuple[dict[str, h5py.Dataset], ImportReport]:
    """Stream GNSS antenna heights from an NMEA log (GGA or ``$PTNL,GGK``, plus GST).

    Parameters
    ----------
    path : path-like
        The log file (any of the layouts of :mod:`nmea_lines`).
    group : h5py.Group
        Scratch group the columns are written into.
    time_source : {"auto", "logger", "sentence"}
        Which clock stamps the epochs (see module docstring).
    empty_geoid : {"zero", "skip"}
        GGA with an empty geoid separation: keep with N = 0 (warned) or drop.
    min_quality : int
        Lowest GGA fix quality kept (1 drops "no fix" only).

    Returns
    -------
    columns : dict of h5py.Dataset
        ``time`` (s), ``height`` (m, ellipsoidal), ``lat``, ``lon`` (deg), ``quality``
        and ``sigma_h`` (m) when the log has GST; sorted by time, unique times.
    report : ImportReport
    """
    if empty_geoid not in ("zero", "skip"):
        raise ValueError(f"empty_geoid must be 'zero' or 'skip', not {empty_geoid!r}")
    state = _start(path, time_source, progress, cancel)
    cands = ls.new_candidates(group, ("PTNL,GGK", "GGA"), ls.GNSS_COLUMNS)
    options = {"empty_geoid": empty_geoid, "min_quality": min_quality}
    on_block = ls.gnss_block(state, cands, options)
    motion = None
    if ls.wants_motion(state):  # the same file's attitude is imported next: one pass
        side = group.create_group("motion")
        side.attrs["intermediate"] = group.attrs.get("intermediate", False)
        motion = ls.new_candidates(side, MOTION_SOURCES, ls.MOTION_COLUMNS)
        on_block = ls.both(on_block, ls.motion_block(state, motion))
    ls.stream_blocks(state.path, state, on_block, progress, cancel)
    if motion is not None:
        ls.keep_motion(state, motion)
    skipped = _line_skips(state, ls.GNSS_KINDS)
    warnings = _base_warnings(state)
    chosen = None
    for key in ("PTNL,GGK", "GGA"):
        if key not in state.kinds:
            continue
        cand = cands[key]
        for reason, n in cand.skipped.items():
            skipped[f"{key}: {reason}"] = n
        if chosen is None and cand.parsed:
            chosen = cand
            if cand.notes.get("empty geoid"):
                warnings.append(ng.empty_geoid_warning(cand.notes["empty geoid"]))
        elif cand.parsed:
            warnings.append(f"{cand.parsed} {key} epochs ignored ({chosen.source} used)")
    if chosen is None:
        raise _nothing_usable(state.path, "GNSS height epochs (GGA / PTNL,GGK)", state,
                              skipped)
    report(progress, 0.96, "sorting epochs")
    warnings.extend(ng.date_warnings(*state.rollover))
    date_source = state.date_source()
    _time_skips(state, chosen, skipped)
    if state.time_source == "sentence" and date_source == "none":
        warnings.append("no date in file: time is seconds since 00:00 UTC of the first day")
    columns = _finish(chosen, cands, skipped)
    if chosen.sink.rows == 0:
        raise _nothing_usable(state.path, "time-stamped GNSS epochs", state, skipped)
    if not chosen.matched:
        del chosen.sink.group["sigma_h"]
        columns.pop("sigma_h")
    report(progress, 1.0, "done")
    return columns, _report(state, "gnss_log", chosen, date_source, chosen.sink.rows,
                            skipped, warnings)


def _time_skips(state: ls.FileState, cand: ls.Candidate, skipped: dict) -> None:
    if cand.bad_time:
        reason = "no logger time tag" if state.time_source == "logger" else "bad sentence time"
        skipped[reason] = skipped.get(reason, 0) + cand.bad_time


def _finish(chosen: ls.Candidate, cands: dict, skipped: dict) -> dict[str, h5py.Dataset]:
    """Sort the chosen source's rows, drop the other sources, count repeated times."""
    for cand in cands.values():
        if cand is not chosen:
            cand.sink.drop()
    columns = chosen.sink.finish()
    if chosen.sink.duplicates:
        skipped["duplicate time"] = skipped.get("duplicate time", 0) + chosen.sink.duplicates
    return columns


def _motion_choice(state, cands, source: str, skipped: dict) -> list[ls.Candidate]:
    """The candidate sources the whole-file reader would consider, most records first."""
    if cands["PASHR"].notes.get("ashtech"):
        skipped["PASHR non-attitude (Ashtech)"] = cands["PASHR"].notes["ashtech"]
    present = []
    for key in ("PASHR", "PSXN,23", "TSS1"):
        cand = cands[key]
        there = cand.notes.get("attitude", 0) if key == "PASHR" else state.kinds.get(key, 0)
        if there and source in ("auto", key):
            present.append(cand)
            for reason, n in cand.skipped.items():
                skipped[f"{key}: {reason}"] = n
    return sorted((c for c in present if c.parsed), key=lambda c: -c.parsed)


def _heave_sign(path: Path, source: str, heave_positive: str | None, warnings) -> str:
    spec = nm.HEAVE_CONVENTION[source]
    sign = heave_positive or spec
    if sign is None:
        raise InputError(
            str(path),
            f"heave sign of {source} must be stated: heave_positive='up' or 'down' "
            f"(CLI --heave-positive; documented: {nm.DOCUMENTED_HEAVE[source]})",
            field="heave",
        )
    if spec is not None and heave_positive is not None and heave_positive != spec:
        warnings.append(f"heave taken as positive {heave_positive}, against the "
                        f"{source} specification ({spec})")
    return sign


def read_attitude_log(
    path: str | os.PathLike,
    group: h5py.Group,
    heave_positive: str | None = None,
    time_source: str = "auto",
    *,
    source: str = "auto",
    progress: ProgressCallback | None = None,
    cancel: CancelToken | None = None,
) -> tuple[dict[str, h5py.Dataset], ImportReport]:
    """Stream roll, pitch, heading and heave from a PASHR / PSXN,23 / TSS1 log.

    Parameters
    ----------
    group : h5py.Group
        Scratch group the columns are written into.
    heave_positive : {"up", "down", None}
        Direction in which the file's heave is positive. None is accepted only for
        TSS1, whose specification fixes it (up); PSXN,23 and PASHR need it stated.
    time_source : {"auto", "logger", "sentence"}
        PSXN,23 and TSS1 carry no time: they need logger tags.
    source : {"auto", "PASHR", "PSXN,23", "TSS1"}
        Which attitude sentence to read; "auto" takes the most numerous.

    Returns
    -------
    columns : dict of h5py.Dataset
        ``time`` (s), ``roll``, ``pitch``, ``heading`` (deg), ``heave`` (m, up).
    report : ImportReport
    """
    if heave_positive not in (None, "up", "down"):
        raise ValueError(f"heave_positive must be 'up', 'down' or None, not {heave_positive!r}")
    state = _start(path, time_source, progress, cancel)
    kept = ls.take_motion(state)
    if kept is not None:  # read in the GNSS import's pass over the same file
        state, cands = kept
    else:
        cands = ls.new_candidates(group, MOTION_SOURCES, ls.MOTION_COLUMNS)
        ls.stream_blocks(state.path, state, ls.motion_block(state, cands), progress, cancel)
    skipped = _line_skips(state, ls.MOTION_KINDS)
    warnings = _base_warnings(state)
    usable = _motion_choice(state, cands, source, skipped)
    if not usable:
        raise _nothing_usable(state.path, "attitude records (PASHR / PSXN,23 / TSS1)", state,
                              skipped)
    chosen = usable[0]
    for other in usable[1:]:
        warnings.append(f"{other.parsed} {other.source} records ignored "
                        f"({chosen.source} used)")
    if chosen.notes.get("settling"):
        warnings.append(f"{chosen.notes['settling']} TSS1 records flagged settling "
                        "(lower-case status)")
    sign = _heave_sign(state.path, chosen.source, heave_positive, warnings)
    has_time = chosen.source == "PASHR"
    if not has_time and state.time_source == "sentence":
        raise InputError(str(state.path),
                         f"{chosen.source} carries no time: it needs logger time tags")
    warnings.extend(ng.date_warnings(*state.rollover))
    date_source = state.date_source() if has_time else "none"
    _time_skips(state, chosen, skipped)
    report(progress, 0.96, "sorting records")
    columns = _finish(chosen, cands, skipped)
    if chosen.sink.rows == 0:
        raise _nothing_usable(state.path, "time-stamped attitude records", state, skipped)
    if chosen.source == "TSS1" and not _tss1_heading(state, columns):
        warnings.append("TSS1 carries no heading and the log has no HDT: heading is NaN")
    if sign == "down":
        # HydroSync heave is positive up: negate a positive-down file.
        _rewrite(columns["heave"], lambda a, b, v: -v)
    report(progress, 1.0, "done")
    return columns, _report(state, "attitude_log", chosen, date_source, chosen.sink.rows,
                            skipped, warnings, heave_positive=sign)


def _rewrite(ds: h5py.Dataset, func) -> None:
    """``ds[a:b] = func(a, b, ds[a:b])`` block by block."""
    for a in range(0, ds.shape[0], READ_ROWS):
        b = min(a + READ_ROWS, ds.shape[0])
        ds[a:b] = func(a, b, ds[a:b])


def _tss1_heading(state: ls.FileState, columns: dict[str, h5py.Dataset]) -> bool:
    """Heading of TSS1 records from the log's HDT; False when none is finite."""
    if state.hdt:
        hdt_time = np.concatenate([t for t, _ in state.hdt])
        hdt_heading = np.concatenate([h for _, h in state.hdt])
    else:
        hdt_time = hdt_heading = np.zeros(0)
    time = columns["time"]
    finite = [False]

    def heading(a, b, _):
        out = nm.heading_from_hdt(hdt_heading, time[a:b], hdt_time)
        finite[0] = finite[0] or bool(np.isfinite(out).any())
        return out

    _rewrite(columns["heading"], heading)
    return finite[0]


def _in_memory(reader, path, **options) -> tuple[dict[str, np.ndarray], ImportReport]:
    with memory_file() as handle:
        datasets, rep = reader(path, handle.create_group("import"), **options)
        return read_columns(datasets), rep


def import_gnss_log(path: str | os.PathLike, time_source: str = "auto", **options
                    ) -> tuple[dict[str, np.ndarray], ImportReport]:
    """:func:`read_gnss_log` with the columns returned as arrays (for small files)."""
    return _in_memory(read_gnss_log, path, time_source=time_source, **options)


def import_attitude_log(path: str | os.PathLike, heave_positive: str | None = None,
                        time_source: str = "auto", **options
                        ) -> tuple[dict[str, np.ndarray], ImportReport]:
    """:func:`read_attitude_log` with the columns returned as arrays (for small files)."""
    return _in_memory(read_attitude_log, path, heave_positive=heave_positive,
                      time_source=time_source, **options)


def expect_gnss_then_attitude(paths) -> None:
    """*paths* (names or globs) are about to be imported as GNSS and then as attitude:
    read each file once for both (``hydrosync import --gnss-log F --attitude-log F``)."""
    from hydrosync_core.importers import log_files

    ls.expect_both(log_files.expand(paths))


def _store(project, target: str, paths, reader, options, progress=None, cancel=None) -> str:
    """Read every file of *paths* into a scratch file next to the project, put them in
    time order and make them table *target*; the project changes only at the end."""
    from hydrosync_core.importers import log_files
    from hydrosync_core.importers.table_sink import content_sha256, scratch_file
    from hydrosync_core.progress import sub_progress
    from hydrosync_core.project.table_files import put_file_table

    files = log_files.expand(paths)
    sizes = [ls.check_file(f) for f in files]
    total = max(sum(sizes), 1)
    handle = scratch_file(near=getattr(project, "path", None))
    try:
        parts, done = [], 0
        for j, (path, size) in enumerate(zip(files, sizes, strict=True)):
            sub = sub_progress(progress, 0.95 * done / total, 0.95 * (done + size) / total)
            group = handle.create_group(f"file{j}")
            group.attrs["intermediate"] = len(files) > 1
            columns, rep = reader(path, group, progress=sub, cancel=cancel, **options)
            # the datasets are closed here, reopened by name when merged (one chunk cache
            # at a time, not one per file)
            # (an attitude table read in the GNSS pass lives in that import's file)
            parts.append(log_files.Part(path, columns["time"].parent, list(columns), rep))
            del columns
            done += size
        columns, notes = log_files.merge(handle.create_group("all"), parts)
        rep = log_files.merged_report(parts, int(columns["time"].shape[0]), notes)
        report(progress, 0.97, "checking the table")
        hashes = {name: content_sha256(ds) for name, ds in columns.items()}
    except BaseException:
        handle.close()
        raise
    put_file_table(project, target, columns, hashes=hashes, source=", ".join(map(str, files)),
                   **rep.attrs())
    report(progress, 1.0, "done")
    name = files[0].name if len(files) == 1 else f"{len(files)} files"
    return f"{name} -> /{target}: {rep.summary()}"


def store_gnss_log(project, target: str, path, *, progress=None, cancel=None,
                   **options) -> str:
    """Import one or several GNSS logs (names or globs) into table *target*, with the
    report's counts as attributes."""
    return _store(project, target, path, read_gnss_log, options, progress, cancel)


def store_attitude_log(project, target: str, path, *, progress=None, cancel=None,
                       **options) -> str:
    """Import one or several attitude logs (names or globs) into table *target*."""
    return _store(project, target, path, read_attitude_log, options, progress, cancel)


def _expand(paths) -> list[Path]:
    from hydrosync_core.importers.log_files import expand

    return expand(paths)


store_gnss_log.several_files = _expand
store_attitude_log.several_files = _expand
