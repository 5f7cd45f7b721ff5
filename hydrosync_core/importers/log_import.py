"""Import real NMEA device logs as the GNSS-height and attitude tables of a project.

:func:`import_gnss_log` -> columns ``time`` (s), ``height`` (m, ellipsoidal), ``lat``,
``lon`` (deg), ``quality`` (GGA code) and, when the log has GST, ``sigma_h`` (m, NaN
where no GST matched); :func:`import_attitude_log` -> ``time`` (s), ``roll``, ``pitch``,
``heading`` (deg, HydroSync conventions), ``heave`` (m, positive up). Both return an
:class:`ImportReport` saying what was read, what was used and what was skipped and why,
and raise :class:`~hydrosync_core.errors.InputError` naming the file and the reasons when
nothing is usable.

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

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.importers import nmea_gnss as ng
from hydrosync_core.importers import nmea_motion as nm
from hydrosync_core.importers.import_report import ImportReport
from hydrosync_core.importers.nmea_lines import LogLines, split_log
from hydrosync_core.inputs import input_ok
from hydrosync_core.progress import CancelToken, ProgressCallback, check_cancel, report

__all__ = ["ImportReport", "import_attitude_log", "import_gnss_log", "store_attitude_log",
           "store_gnss_log"]

MAX_LOG_BYTES = 2_000_000_000


def _read_log(path: Path, progress, cancel) -> LogLines:
    input_ok(path, "log", max_bytes=MAX_LOG_BYTES)  # not a FIFO, device or sparse file
    if not path.exists():
        raise InputError(str(path), "no such file")
    if path.is_dir():
        raise InputError(str(path), "is a folder, not a file")
    size = path.stat().st_size
    if size == 0:
        raise InputError(str(path), "file is empty")
    if size > MAX_LOG_BYTES:
        raise InputError(str(path), f"file is {size} bytes; logs above 2 GB are not supported")
    report(progress, 0.0, f"reading {path.name}")
    log = split_log(path.read_bytes(), str(path), progress=progress, cancel=cancel)
    check_cancel(cancel)
    return log


GNSS_KINDS = ("GGA", "PTNL,GGK", "GST", "ZDA", "RMC")
MOTION_KINDS = ("PASHR", "PSXN,23", "PSXN,20", "TSS1", "HDT", "ZDA", "RMC", "PTNL,GGK")


def _open_log(
    path: Path, wanted: tuple[str, ...], progress, cancel
) -> tuple[LogLines, dict, dict[str, int], list[str]]:
    """Read and split *path*; return the lines, sentence kinds, skip counts and warnings."""
    log = _read_log(path, progress, cancel)
    kinds = ng.sentence_kinds(log)
    skipped = _skipped_lines(log, kinds, wanted)
    warnings: list[str] = []
    if log.no_checksums:
        warnings.append("no checksums in file: sentences accepted unchecked")
    return log, kinds, skipped, warnings


def _skipped_lines(log: LogLines, kinds: dict, wanted: tuple[str, ...]) -> dict[str, int]:
    """Lines set aside while splitting, plus valid sentences of types not read here."""
    out = {k: v for k, v in log.counts.items()
           if k not in ("lines", "sentences", "no checksum (accepted)")}
    other = sum(len(v) for k, v in kinds.items() if k not in wanted)
    if other:
        out["other sentence types"] = other
    return out


def _nothing_usable(path: Path, what: str, log: LogLines, skipped: dict, kinds: dict) -> InputError:
    seen = ", ".join(f"{k} {len(v)}" for k, v in sorted(kinds.items())) or "none"
    why = ", ".join(f"{k} {v}" for k, v in sorted(skipped.items())) or "nothing set aside"
    return InputError(
        str(path),
        f"no usable {what} in {log.counts.get('lines', 0)} lines "
        f"(sentences found: {seen}; set aside: {why})",
    )


def _choose_time(log: LogLines, time_source: str, path: Path) -> str:
    if time_source not in ("auto", "logger", "sentence"):
        raise ValueError(f"time_source must be 'auto', 'logger' or 'sentence', not {time_source!r}")
    tagged = np.isfinite(log.tag)
    has_tags = tagged.size > 0 and np.count_nonzero(tagged) * 2 >= tagged.size
    if time_source == "auto":
        return "logger" if has_tags else "sentence"
    if time_source == "logger" and not has_tags:
        raise InputError(str(path), "lines carry no logger time tag: use time_source='sentence'")
    return time_source


def _assemble(log, rec_index, rec_tod, events, time_source, skipped, has_time=True):
    """Times of the records and the logger-minus-sentence median (s) when both exist."""
    tags = log.tag[rec_index]
    sent, date_source = (ng.sentence_times(log, rec_index, rec_tod, events) if has_time
                         else (np.full(rec_index.size, np.nan), "none"))
    both = np.isfinite(tags) & np.isfinite(sent)
    lag = None
    if both.any() and date_source != "none":
        lag = float(np.median(tags[both] - sent[both]))
    if time_source == "logger":
        time, reason = tags, "no logger time tag"
    else:
        time, reason = sent, "bad sentence time"
    bad = ~np.isfinite(time)
    if bad.any():
        skipped[reason] = skipped.get(reason, 0) + int(np.count_nonzero(bad))
    return time, ~bad, date_source, lag


def _sort_unique(time: np.ndarray, skipped: dict) -> np.ndarray:
    """Indices that sort *time* and drop later duplicates (counted)."""
    order = np.argsort(time, kind="stable")
    if order.size == 0:
        return order
    dup = np.concatenate([[False], np.diff(time[order]) == 0.0])
    if dup.any():
        skipped["duplicate time"] = skipped.get("duplicate time", 0) + int(np.count_nonzero(dup))
    return order[~dup]


def import_gnss_log(
    path: str | os.PathLike,
    time_source: str = "auto",
    *,
    empty_geoid: str = "zero",
    min_quality: int = 1,
    progress: ProgressCallback | None = None,
    cancel: CancelToken | None = None,
) -> tuple[dict[str, np.ndarray], ImportReport]:
    """Read GNSS antenna heights from an NMEA log (GGA or ``$PTNL,GGK``, plus GST).

    Parameters
    ----------
    path : path-like
        The log file (any of the layouts of :mod:`nmea_lines`).
    time_source : {"auto", "logger", "sentence"}
        Which clock stamps the epochs (see module docstring).
    empty_geoid : {"zero", "skip"}
        GGA with an empty geoid separation: keep with N = 0 (warned) or drop.
    min_quality : int
        Lowest GGA fix quality kept (1 drops "no fix" only).

    Returns
    -------
    columns : dict of ndarray
        ``time`` (s), ``height`` (m, ellipsoidal), ``lat``, ``lon`` (deg), ``quality``
        and ``sigma_h`` (m) when the log has GST; sorted by time, unique times.
    report : ImportReport
    """
    if empty_geoid not in ("zero", "skip"):
        raise ValueError(f"empty_geoid must be 'zero' or 'skip', not {empty_geoid!r}")
    path = Path(path)
    log, kinds, skipped, warnings = _open_log(path, GNSS_KINDS, progress, cancel)
    chosen: ng.GnssRecords | None = None
    for key in ("PTNL,GGK", "GGA"):
        if key not in kinds:
            continue
        rec = (ng.parse_ggk(log, kinds[key], min_quality=min_quality) if key == "PTNL,GGK"
               else ng.parse_gga(log, kinds[key], empty_geoid=empty_geoid,
                                min_quality=min_quality))
        for reason, n in rec.skipped.items():
            skipped[f"{key}: {reason}"] = n
        if chosen is None and rec.index.size:
            chosen = rec
            warnings.extend(rec.warnings)
        elif rec.index.size:
            warnings.append(f"{rec.index.size} {key} epochs ignored ({chosen.source} used)")
    if chosen is None:
        raise _nothing_usable(path, "GNSS height epochs (GGA / PTNL,GGK)", log, skipped, kinds)
    report(progress, 0.6, "assembling times")
    time_source = _choose_time(log, time_source, path)
    events = ng.date_events(log, kinds)
    warnings.extend(events.warnings)
    matched = ng.attach_gst(log, chosen, kinds.get("GST", np.zeros(0, np.int64)))
    time, ok, date_source, lag = _assemble(
        log, chosen.index, chosen.tod, events, time_source, skipped
    )
    if time_source == "sentence" and date_source == "none":
        warnings.append("no date in file: time is seconds since 00:00 UTC of the first day")
    sel = np.flatnonzero(ok)
    sel = sel[_sort_unique(time[sel], skipped)]
    if sel.size == 0:
        raise _nothing_usable(path, "time-stamped GNSS epochs", log, skipped, kinds)
    columns = {
        "time": time[sel], "height": chosen.height[sel], "lat": chosen.lat[sel],
        "lon": chosen.lon[sel], "quality": chosen.quality[sel],
    }
    if matched:
        columns["sigma_h"] = chosen.sigma_h[sel]
    report(progress, 1.0, "done")
    return columns, ImportReport(
        file=str(path), kind="gnss_log", source=chosen.source, time_source=time_source,
        date_source=date_source, lines=log.counts["lines"], sentences=log.counts["sentences"],
        used=int(sel.size), skipped=skipped,
        sentence_counts={k: int(v.size) for k, v in sorted(kinds.items())},
        warnings=tuple(warnings), logger_minus_sentence_s=lag,
    )


def _motion_records(log: LogLines, kinds: dict, source: str, skipped: dict) -> list:
    candidates = []
    if "PASHR" in kinds:
        att, ashtech = nm.split_pashr(log, kinds["PASHR"])
        if ashtech:
            skipped["PASHR non-attitude (Ashtech)"] = ashtech
        if att.size and source in ("auto", "PASHR"):
            candidates.append(nm.parse_pashr(log, att))
    if "PSXN,23" in kinds and source in ("auto", "PSXN,23"):
        candidates.append(nm.parse_psxn23(log, kinds["PSXN,23"], kinds.get("PSXN,20")))
    if "TSS1" in kinds and source in ("auto", "TSS1"):
        candidates.append(nm.parse_tss1(log, kinds["TSS1"]))
    for rec in candidates:
        for reason, n in rec.skipped.items():
            skipped[f"{rec.source}: {reason}"] = n
    return sorted(candidates, key=lambda r: -r.index.size)


def import_attitude_log(
    path: str | os.PathLike,
    heave_positive: str | None = None,
    time_source: str = "auto",
    *,
    source: str = "auto",
    progress: ProgressCallback | None = None,
    cancel: CancelToken | None = None,
) -> tuple[dict[str, np.ndarray], ImportReport]:
    """Read roll, pitch, heading and heave from a PASHR / PSXN,23 / TSS1 log.

    Parameters
    ----------
    heave_positive : {"up", "down", None}
        Direction in which the file's heave is positive. None is accepted only for
        TSS1, whose specification fixes it (up); PSXN,23 and PASHR need it stated.
    time_source : {"auto", "logger", "sentence"}
        PSXN,23 and TSS1 carry no time: they need logger tags.
    source : {"auto", "PASHR", "PSXN,23", "TSS1"}
        Which attitude sentence to read; "auto" takes the most numerous.

    Returns
    -------
    columns : dict of ndarray
        ``time`` (s), ``roll``, ``pitch``, ``heading`` (deg), ``heave`` (m, up).
    report : ImportReport
    """
    if heave_positive not in (None, "up", "down"):
        raise ValueError(f"heave_positive must be 'up', 'down' or None, not {heave_positive!r}")
    path = Path(path)
    log, kinds, skipped, warnings = _open_log(path, MOTION_KINDS, progress, cancel)
    candidates = _motion_records(log, kinds, source, skipped)
    usable = [r for r in candidates if r.index.size]
    if not usable:
        raise _nothing_usable(path, "attitude records (PASHR / PSXN,23 / TSS1)", log,
                              skipped, kinds)
    rec = usable[0]
    for other in usable[1:]:
        warnings.append(f"{other.index.size} {other.source} records ignored ({rec.source} used)")
    warnings.extend(rec.warnings)
    spec = nm.HEAVE_CONVENTION[rec.source]
    sign = heave_positive or spec
    if sign is None:
        raise InputError(
            str(path),
            f"heave sign of {rec.source} must be stated: heave_positive='up' or 'down' "
            f"(CLI --heave-positive; documented: {nm.DOCUMENTED_HEAVE[rec.source]})",
            field="heave",
        )
    if spec is not None and heave_positive is not None and heave_positive != spec:
        warnings.append(f"heave taken as positive {heave_positive}, against the "
                        f"{rec.source} specification ({spec})")
    has_time = rec.source == "PASHR"
    time_source = _choose_time(log, time_source, path)
    if not has_time and time_source == "sentence":
        raise InputError(str(path), f"{rec.source} carries no time: it needs logger time tags")
    events = ng.date_events(log, kinds)
    time, ok, date_source, lag = _assemble(
        log, rec.index, rec.tod, events, time_source, skipped, has_time=has_time
    )
    heading = rec.heading
    if rec.source == "TSS1":
        hdt = kinds.get("HDT", np.zeros(0, np.int64))
        heading = nm.heading_from_hdt(log, hdt, time, log.tag[hdt])
        if not np.isfinite(heading).any():
            warnings.append("TSS1 carries no heading and the log has no HDT: heading is NaN")
    sel = np.flatnonzero(ok)
    sel = sel[_sort_unique(time[sel], skipped)]
    if sel.size == 0:
        raise _nothing_usable(path, "time-stamped attitude records", log, skipped, kinds)
    # HydroSync heave is positive up: negate a positive-down file.
    heave = rec.heave if sign == "up" else -rec.heave
    columns = {"time": time[sel], "roll": rec.roll[sel], "pitch": rec.pitch[sel],
               "heading": heading[sel], "heave": heave[sel]}
    return columns, ImportReport(
        file=str(path), kind="attitude_log", source=rec.source, time_source=time_source,
        date_source=date_source, lines=log.counts["lines"], sentences=log.counts["sentences"],
        used=int(sel.size), skipped=skipped,
        sentence_counts={k: int(v.size) for k, v in sorted(kinds.items())},
        warnings=tuple(warnings), logger_minus_sentence_s=lag, heave_positive=sign,
    )


def store_gnss_log(project, target: str, path: Path, **options) -> str:
    """Import a GNSS log into table *target*, with the report's counts as attributes."""
    columns, rep = import_gnss_log(path, **options)
    project.put_table(target, columns, source=str(path), **rep.attrs())
    return f"{path.name} -> /{target}: {rep.summary()}"


def store_attitude_log(project, target: str, path: Path, **options) -> str:
    """Import an attitude log into table *target*, with the report's counts as attributes."""
    columns, rep = import_attitude_log(path, **options)
    project.put_table(target, columns, source=str(path), **rep.attrs())
    return f"{path.name} -> /{target}: {rep.summary()}"
