"""What a file holds, cheaply, before it is imported: the Import dialog's preview.

For a device log: the sentences found and how many of each, the time span (logger tags,
else the dates and times the sentences state) and the import kinds they feed. The same
scanner and checksum policy as the import (:func:`nmea_lines.scan_block`,
:func:`nmea_lines.apply_policy`, :func:`nmea_gnss.sentence_kinds`) run on at most
``HEAD_BYTES`` from the start and as much from the end of the file, whole lines only, so
a 10 GB log previews as fast as a small one; its counts are then those of the part read
(said so), its span still runs from the first to the last sentence.

Other files (CSV tables, RTKLIB ``.pos``, point clouds) get their kind guessed from the
extension and their first line shown.
"""

from __future__ import annotations

import datetime as _dt
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.importers import nmea_fields as nf
from hydrosync_core.importers import nmea_gnss as ng
from hydrosync_core.importers import nmea_lines as nl
from hydrosync_core.progress import check_cancel

HEAD_BYTES = 4 << 20
"""Bytes read from each end of a large file (whole lines): ~50 000 lines of a tagged log."""
GNSS_SENTENCES = ("GGA", "PTNL,GGK")
MOTION_SENTENCES = ("PSXN,23", "PASHR", "TSS1")
BY_EXTENSION = {".pos": "pos", ".geo": "geo", ".ply": "lidar", ".las": "lidar",
                ".laz": "lidar"}
"""Kinds a file's extension alone names."""


@dataclass
class FilePreview:
    """What :func:`preview_file` found in one file.

    Attributes
    ----------
    path : str
    size : int
        Bytes.
    sentences : dict of str to int
        NMEA sentences with a valid checksum (or, in a file without checksums, all) by
        kind, most frequent first; empty for a file that holds none.
    lines : int
        Lines read.
    first, last : float or None
        Unix seconds (UTC) of the first and last dated sentence; without any date in the
        file, seconds of the day (``dated`` False).
    dated : bool
    time_from : str
        ``"logger tags"``, ``"sentence dates"``, ``"sentence times (no date)"`` or ``""``.
    kinds : tuple of str
        Import kinds the content fits (``gnss_log``, ``attitude_log``, ``pos``…).
    partial : bool
        Only the first and last ``HEAD_BYTES`` were read: counts are of that part.
    first_line : str
        The first non-empty line (cut to 120 characters), for files that are no log.
    error : str or None
        Why the file cannot be previewed (one line); the rest is then empty.
    """

    path: str
    size: int = 0
    sentences: dict[str, int] = field(default_factory=dict)
    lines: int = 0
    first: float | None = None
    last: float | None = None
    dated: bool = False
    time_from: str = ""
    kinds: tuple[str, ...] = ()
    partial: bool = False
    first_line: str = ""
    error: str | None = None

    def span_text(self) -> str:
        """``2014-08-01 00:00:00.7 – 00:11:54.6 UTC (11 min 54 s)`` or ``""``."""
        if self.first is None or self.last is None:
            return ""
        a, b = (_dt.datetime.fromtimestamp(t, _dt.UTC) for t in (self.first, self.last))
        start = a.strftime("%Y-%m-%d %H:%M:%S" if self.dated else "%H:%M:%S")
        end = b.strftime("%H:%M:%S" if a.date() == b.date() or not self.dated
                         else "%Y-%m-%d %H:%M:%S")
        return f"{start} – {end} UTC ({duration_text(self.last - self.first)})"

    def sentences_text(self, most: int = 6) -> str:
        """``GGA 712, PSXN,23 712, HDT 712, … (+3 kinds)``; counts of the part read."""
        items = [f"{k} {n}" for k, n in list(self.sentences.items())[:most]]
        more = len(self.sentences) - most
        return ", ".join(items) + (f", … (+{more} kinds)" if more > 0 else "")


def duration_text(seconds: float) -> str:
    """``3 h 02 min``, ``11 min 54 s``, ``42 s``."""
    s = int(round(max(seconds, 0.0)))
    if s >= 3600:
        return f"{s // 3600} h {s % 3600 // 60:02d} min"
    if s >= 60:
        return f"{s // 60} min {s % 60:02d} s"
    return f"{s} s"


def _read_ends(path: Path, size: int, head: int) -> list[bytes]:
    """The whole file, or its first and last *head* bytes cut to whole lines."""
    with open(path, "rb") as handle:
        if size <= 2 * head:
            return [handle.read()]
        first = handle.read(head)
        first = first[: first.rfind(b"\n") + 1] or first
        handle.seek(size - head)
        last = handle.read(head)
        cut = last.find(b"\n") + 1
        return [first, last[cut:] if 0 < cut < len(last) else last]


def _block_times(block: nl.SentenceBlock, kinds: dict[str, np.ndarray]):
    """(times, dated, source) of a block's sentences that carry a time."""
    tags = block.tag[np.isfinite(block.tag)]
    if tags.size:
        return tags, True, "logger tags"
    events = ng.date_events(block, kinds)
    if events.day.size:
        return events.day * nf.DAY + events.tod, True, "sentence dates"
    for key, column in (("GGA", 1), ("PTNL,GGK", 2), ("PASHR", 1)):
        if key in kinds:
            tod = nf.tod_field(block, kinds[key], column)
            tod = tod[np.isfinite(tod)]
            if tod.size:
                return tod, False, "sentence times (no date)"
    return np.zeros(0), False, ""


def _guess_kinds(sentences: dict[str, int], suffix: str) -> tuple[str, ...]:
    if suffix in BY_EXTENSION:
        return (BY_EXTENSION[suffix],)
    out = []
    if any(sentences.get(k) for k in GNSS_SENTENCES):
        out.append("gnss_log")
    if any(sentences.get(k) for k in MOTION_SENTENCES):
        out.append("attitude_log")
    return tuple(out)


def _folder_preview(folder: Path, out: FilePreview, most: int = 5) -> FilePreview:
    """A folder's files (names, total size): what a recording folder holds."""
    try:
        files = sorted(p for p in folder.rglob("*") if p.is_file())
        out.size = sum(p.stat().st_size for p in files)
    except OSError as exc:
        out.error = f"{folder}: cannot be read ({exc.strerror or exc})"
        return out
    names = [str(p.relative_to(folder)) for p in files[:most]]
    more = f", … (+{len(files) - most})" if len(files) > most else ""
    listed = f"{', '.join(names)}{more}"
    out.first_line = (f"folder of 1 file: {listed}" if len(files) == 1
                      else f"folder of {len(files)} files: {listed}")
    return out


def preview_file(path: str | Path, cancel=None, head: int = HEAD_BYTES) -> FilePreview:
    """What *path* holds (see :class:`FilePreview`); never raises for a bad file: its
    one-line reason is in ``error``. *cancel*: a token checked between the two ends.
    A folder (the input of a recording kind) is described by its files."""
    path = Path(path)
    out = FilePreview(str(path))
    if path.is_dir():  # a recording folder (an import kind whose input is a folder)
        return _folder_preview(path, out)
    try:
        # A regular file only: a FIFO or device would block the read.
        if not path.is_file():
            raise InputError(str(path), "is a folder" if path.is_dir() else
                             "no such file" if not path.exists() else "not a regular file")
        out.size = path.stat().st_size
        parts = _read_ends(path, out.size, head)
    except InputError as exc:
        out.error = str(exc)
        return out
    except OSError as exc:
        out.error = f"{path}: cannot be read ({exc.strerror or exc})"
        return out
    out.partial = len(parts) > 1
    counts: dict[str, int] = {}
    spans = []
    for data in parts:
        check_cancel(cancel)
        raw = nl.scan_block(np.frombuffer(data, np.uint8))
        out.lines += raw.counts["lines"]
        block = nl.apply_policy(raw, nl.checksum_policy(*raw.checksum_census()), str(path))
        kinds = ng.sentence_kinds(block)
        for kind, index in kinds.items():
            counts[kind] = counts.get(kind, 0) + int(index.size)
        spans.append(_block_times(block, kinds))
    out.sentences = dict(sorted(counts.items(), key=lambda kv: (-kv[1], kv[0])))
    times = [t for t, _, _ in spans if t.size]
    if times:
        out.first, out.last = float(times[0].min()), float(times[-1].max())
        out.dated, out.time_from = next((d, s) for t, d, s in spans if t.size)
    out.kinds = _guess_kinds(out.sentences, path.suffix.lower())
    if not out.sentences:
        start = parts[0][:4096]
        text = start.decode("utf-8", "replace")
        out.first_line = ("(binary)" if b"\0" in start else
                          next((ln.strip() for ln in text.splitlines() if ln.strip()), "")[:120])
    return out
