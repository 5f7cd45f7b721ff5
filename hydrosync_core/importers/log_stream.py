"""Read an NMEA device log block by block into growing HDF5 tables, in bounded memory.

Two passes over the file, each holding one block of whole lines (``BLOCK_BYTES``):

1. :func:`census` — what the file-wide rules need before any record is kept: how many
   sentences carry a checksum (the policy of :mod:`nmea_lines`), how many lines carry a
   logger tag (the ``"auto"`` time source), the tag style, and the first date sentence
   (the date of records logged before it).
2. :func:`stream_log` — every block is split (:func:`nmea_lines.scan_block`), its
   sentences parsed by the readers of :mod:`nmea_gnss` / :mod:`nmea_motion`, dated with
   the date carried over from the blocks before, and its records appended to one
   :class:`~.table_sink.TableSink` per candidate source (GGA and PTNL,GGK; PASHR,
   PSXN,23 and TSS1). At the end the source the whole-file reader would have chosen is
   kept and the others dropped.

What crosses a block boundary is carried explicitly: the last date event, the last
``$PSXN,20`` quality, the last GST and the GNSS epochs after it (their GST may open the
next block), the day counter of a log without dates, and the HDT headings of a TSS1 log.
The counts, warnings and values are those of reading the file whole (checked on the
real-log corpus by ``tests/core/test_log_stream.py``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

import h5py
import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.importers import nmea_fields as nf
from hydrosync_core.importers import nmea_gnss as ng
from hydrosync_core.importers import nmea_lines as nl
from hydrosync_core.importers import nmea_motion as nm
from hydrosync_core.importers.table_sink import TableSink
from hydrosync_core.inputs import input_ok
from hydrosync_core.progress import check_cancel, report

BLOCK_BYTES = 16 << 20
"""Bytes read at a time (whole lines): ~0.2 M lines of a tagged log."""
MAX_LOG_BYTES = 16_000_000_000
"""Streamed, a log's size no longer limits memory; this only stops a wrong pick (a disk
image) from running for an hour."""
GNSS_KINDS = ("GGA", "PTNL,GGK", "GST", "ZDA", "RMC")
MOTION_KINDS = ("PASHR", "PSXN,23", "PSXN,20", "TSS1", "HDT", "ZDA", "RMC", "PTNL,GGK")
GNSS_COLUMNS = ("time", "height", "lat", "lon", "quality", "sigma_h")
MOTION_COLUMNS = ("time", "roll", "pitch", "heading", "heave")


def check_file(path: Path) -> int:
    """Size of *path* in bytes, or the one-line reason it cannot be read as a log."""
    input_ok(path, "log", max_bytes=MAX_LOG_BYTES * 8)  # not a FIFO, device or sparse file
    if not path.exists():
        raise InputError(str(path), "no such file")
    if path.is_dir():
        raise InputError(str(path), "is a folder, not a file")
    size = path.stat().st_size
    if size == 0:
        raise InputError(str(path), "file is empty")
    if size > MAX_LOG_BYTES:
        raise InputError(str(path), f"file is {size} bytes; logs above 16 GB are not supported")
    return size


def blocks(path: Path, block_bytes: int | None = None):
    """Yield ``(buf, bytes_done)``: blocks of whole lines of *path* (uint8).

    A block ends after its last ``\n`` and the next read starts right after it (the file
    is read again from there, nothing is copied), so a sentence, a CRLF pair or a binary
    run cut by a read is whole in one block. A line longer than a block doubles the read.
    The last block may end without ``\n`` (a file cut mid-sentence). The caller numbers
    the lines (the scanner counts them).
    """
    size = block_bytes or BLOCK_BYTES
    pos = 0
    with open(path, "rb") as handle:
        while True:
            handle.seek(pos)
            chunk = handle.read(size)
            if not chunk:
                return
            cut = len(chunk) if len(chunk) < size else chunk.rfind(b"\n") + 1
            if cut == 0:
                size *= 2
                continue
            pos += cut
            yield np.frombuffer(chunk, np.uint8, count=cut), pos
            del chunk


# ----------------------------------------------------------------------------- census
@dataclass
class Census:
    """What pass 1 learnt about a whole file (see module docstring)."""

    lines: int = 0
    n_with: int = 0
    n_without: int = 0
    styles: dict[str, int] = field(default_factory=dict)
    kept_checked: int = 0
    tagged_checked: int = 0
    kept_unchecked: int = 0
    tagged_unchecked: int = 0
    first_event: dict[bool, tuple[float, float] | None] = field(
        default_factory=lambda: {True: None, False: None})

    @property
    def no_checksums(self) -> bool:
        return nl.checksum_policy(self.n_with, self.n_without)

    @property
    def has_tags(self) -> bool:
        """Most kept sentences carry a logger tag (what ``time_source="auto"`` asks)."""
        kept = self.kept_checked + (self.kept_unchecked if self.no_checksums else 0)
        tagged = self.tagged_checked + (self.tagged_unchecked if self.no_checksums else 0)
        return kept > 0 and tagged * 2 >= kept

    @property
    def any_tags(self) -> bool:
        return (self.tagged_checked + (self.tagged_unchecked if self.no_checksums else 0)) > 0

    def date_of_first(self) -> tuple[float, float] | None:
        """(day, time of day) of the file's first date sentence under its checksum policy."""
        return self.first_event[self.no_checksums]

    def add(self, raw: nl.RawBlock, path: str) -> None:
        self.lines += raw.counts["lines"]
        n_with, n_without = raw.checksum_census()
        self.n_with += n_with
        self.n_without += n_without
        for style, n in raw.styles.items():
            self.styles[style] = self.styles.get(style, 0) + n
        tagged = np.isfinite(raw.tag)
        checked = (raw.cs == nl.nk.CS_OK) | (raw.tss & (raw.cs != nl.nk.CS_BAD))
        unchecked = ~raw.tss & (raw.cs == nl.nk.CS_NONE)
        self.kept_checked += int(np.count_nonzero(checked))
        self.tagged_checked += int(np.count_nonzero(checked & tagged))
        self.kept_unchecked += int(np.count_nonzero(unchecked))
        self.tagged_unchecked += int(np.count_nonzero(unchecked & tagged))
        for policy in (True, False):
            if self.first_event[policy] is None:
                block = nl.apply_policy(raw, policy, path)
                events = ng.date_events(block, ng.sentence_kinds(block))
                if events.position.size:
                    self.first_event[policy] = (float(events.day[0]), float(events.tod[0]))


_CENSUS: dict[tuple, Census] = {}
"""The last files surveyed, by (path, size, modification time): the GNSS and the attitude
import of one logger file (one ``hydrosync import``) survey it once."""


def census(path: Path, progress=None, cancel=None, share: float = 0.3) -> Census:
    """Pass 1 over *path* (progress reported on 0..*share*)."""
    stat = path.stat()
    key = (str(path.resolve()), stat.st_size, stat.st_mtime_ns, BLOCK_BYTES)
    if key in _CENSUS:
        return _CENSUS[key]
    size = max(stat.st_size, 1)
    out = Census()
    first_line = 1
    for buf, done in blocks(path):
        check_cancel(cancel)
        raw = nl.scan_block(buf, first_line)
        first_line += raw.counts["lines"]
        out.add(raw, str(path))
        report(progress, share * done / size, f"{path.name}: surveying {done >> 20} MiB")
    if len(_CENSUS) >= 64:
        _CENSUS.clear()
    _CENSUS[key] = out
    return out


# ------------------------------------------------------------------------ the stream
@dataclass
class Candidate:
    """One candidate record source of a file: its sink and what it counted."""

    source: str
    sink: TableSink
    parsed: int = 0
    skipped: dict[str, int] = field(default_factory=dict)
    bad_time: int = 0
    lags: list[np.ndarray] = field(default_factory=list)
    notes: dict[str, int] = field(default_factory=dict)
    matched: int = 0
    carry: dict[str, np.ndarray] | None = None
    last_quality: float = np.nan

    lag_ref: float | None = None

    def add_lag(self, lag: np.ndarray) -> None:
        """Keep logger − sentence differences for the median, as float32 offsets from the
        first block's median (4 bytes a record; the offsets are small, so exact to 1e-10 s)."""
        if lag.size == 0:
            return
        if self.lag_ref is None:
            self.lag_ref = float(np.median(lag))
        self.lags.append((lag - self.lag_ref).astype(np.float32))

    def lag(self) -> float | None:
        """Median of logger − sentence (s), partitioning the offsets in place."""
        if not self.lags:
            return None
        v = np.concatenate(self.lags)
        self.lags = [v]
        n = v.size
        k = n // 2
        v.partition([k - 1, k] if n % 2 == 0 else k)
        middle = float(v[k]) if n % 2 else (float(v[k - 1]) + float(v[k])) / 2.0
        return self.lag_ref + middle


@dataclass
class FileState:
    """Everything carried from one block to the next, and the file's totals."""

    path: Path
    census: Census
    time_source: str
    counts: dict[str, int] = field(default_factory=dict)
    kinds: dict[str, int] = field(default_factory=dict)
    odd_prefix: int = 0
    offset: int = 0
    event: tuple[float, float] | None = None
    rollover: list[int] = field(default_factory=lambda: [0, 0, 0])
    gst: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
    unwrap_state: list[float] = field(default_factory=lambda: [np.nan, 0.0])
    hdt: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)

    def add_counts(self, block: nl.SentenceBlock, kinds: dict[str, np.ndarray]) -> None:
        for key, n in block.counts.items():
            self.counts[key] = self.counts.get(key, 0) + n
        for key, idx in kinds.items():
            self.kinds[key] = self.kinds.get(key, 0) + int(idx.size)

    def events(self, block: nl.SentenceBlock, kinds) -> ng.DateEvents:
        """Date events of the block, led by the one in force when it starts."""
        ev = ng.date_events(block, kinds)
        self.rollover[0] += ev.rollover_fixed
        self.rollover[1] = max(self.rollover[1], ev.rollover_weeks)
        self.rollover[2] += ev.far
        lead = self.event or self.census.date_of_first()
        if ev.position.size:
            self.event = (float(ev.day[-1]), float(ev.tod[-1]))
        if lead is None:
            return ev
        return ng.DateEvents(np.concatenate([[0], ev.position]),
                             np.concatenate([[lead[0]], ev.day]),
                             np.concatenate([[lead[1]], ev.tod]))

    def unwrap(self, tod: np.ndarray) -> np.ndarray:
        """:func:`nmea_fields.unwrap_days` carried over blocks (a log without any date)."""
        last, wraps = self.unwrap_state
        finite = np.isfinite(tod)
        t = tod[finite]
        step = np.zeros(tod.shape)
        if t.size:
            prev = np.concatenate([[last], t[:-1]])
            back = np.cumsum(np.nan_to_num(t - prev, nan=0.0) < -nf.HALF_DAY)
            step[finite] = wraps + back
            self.unwrap_state = [float(t[-1]), float(wraps + back[-1])]
        return step * nf.DAY + tod

    def date_source(self) -> str:
        if self.census.date_of_first() is not None:
            return "date sentences"
        return "logger date" if self.census.any_tags else "none"


def record_times(state: FileState, block, events, index, tod, has_time: bool = True):
    """Unix times of records *index* by the file's time source, and logger − sentence."""
    tags = block.tag[index]
    if has_time:
        sent, _ = ng.sentence_times(block, index, tod, events, any_tags=state.census.any_tags,
                                    unwrap=state.unwrap)
    else:
        sent = np.full(index.size, np.nan)
    both = np.isfinite(tags) & np.isfinite(sent)
    lag = tags[both] - sent[both] if state.date_source() != "none" else np.zeros(0)
    return (tags if state.time_source == "logger" else sent), lag


def _emit(cand: Candidate, columns: dict[str, np.ndarray]) -> None:
    ok = np.isfinite(columns["time"])
    cand.bad_time += int(np.count_nonzero(~ok))
    cand.sink.append({k: v[ok] for k, v in columns.items()})


def _count(target: dict[str, int], source: dict[str, int]) -> None:
    for key, n in source.items():
        target[key] = target.get(key, 0) + n


def choose_time(census: Census, time_source: str, path: Path) -> str:
    if time_source not in ("auto", "logger", "sentence"):
        raise ValueError(f"time_source must be 'auto', 'logger' or 'sentence', not {time_source!r}")
    if time_source == "auto":
        return "logger" if census.has_tags else "sentence"
    if time_source == "logger" and not census.has_tags:
        raise InputError(str(path), "lines carry no logger time tag: use time_source='sentence'")
    return time_source


def stream_blocks(path: Path, state: FileState, on_block, progress, cancel,
                  span: tuple[float, float] = (0.3, 0.95)) -> None:
    """Pass 2: split every block under the file's checksum policy and hand it on."""
    size = max(path.stat().st_size, 1)
    start = time.monotonic()
    first_line = 1
    for buf, done in blocks(path):
        check_cancel(cancel)
        raw = nl.scan_block(buf, first_line)
        first_line += raw.counts["lines"]
        state.odd_prefix += raw.odd_prefix
        block = nl.apply_policy(raw, state.census.no_checksums, str(path))
        kinds = ng.sentence_kinds(block)
        state.add_counts(block, kinds)
        on_block(block, kinds, state.events(block, kinds))
        state.offset += block.start.size
        rate = done / max(time.monotonic() - start, 1e-3)
        report(progress, span[0] + (span[1] - span[0]) * done / size,
               f"{path.name}: {done / 1e6:.0f} of {size / 1e6:.0f} MB read, "
               f"{rate / 1e6:.0f} MB/s, {(size - done) / rate:.0f} s left")
    on_block(None, {}, None)


# ------------------------------------------------- one pass for GNSS and attitude
_BOTH: set[str] = set()
"""Files about to be imported both as GNSS and as attitude (one logger file for both)."""
_SIDE: dict[tuple, tuple] = {}
"""Motion records read beside the GNSS ones, waiting for the attitude import."""


def expect_both(paths) -> None:
    """Say that *paths* will be imported as GNSS and then as attitude: the GNSS import
    reads the attitude records in the same pass and the attitude import takes them."""
    _BOTH.update(str(Path(p).resolve()) for p in paths)


def side_key(state: FileState) -> tuple:
    stat = state.path.stat()
    return (str(state.path.resolve()), stat.st_size, stat.st_mtime_ns, BLOCK_BYTES,
            state.time_source)


def wants_motion(state: FileState) -> bool:
    return str(state.path.resolve()) in _BOTH


def keep_motion(state: FileState, cands: dict[str, Candidate]) -> None:
    """The attitude records read beside the GNSS ones, for :func:`take_motion`."""
    _BOTH.discard(str(state.path.resolve()))
    if len(_SIDE) >= 1000:
        _SIDE.clear()
    for cand in cands.values():
        cand.sink.close()  # a day of hourly files would hold a chunk cache per column
    _SIDE[side_key(state)] = (state, cands)


def take_motion(state: FileState) -> tuple | None:
    """(state, candidates) read with the GNSS of the same file and time source, or None
    (also when that import failed and closed its scratch file)."""
    kept = _SIDE.pop(side_key(state), None)
    if kept is None or not all(c.sink.group.id.valid for c in kept[1].values()):
        return None
    for cand in kept[1].values():
        cand.sink.reopen()
    return kept


def both(*handlers):
    """One per-block handler calling *handlers* in turn."""

    def on_block(block, kinds, events) -> None:
        for handler in handlers:
            handler(block, kinds, events)

    return on_block


# ----------------------------------------------------------------------------- GNSS
def gnss_block(state: FileState, cands: dict[str, Candidate], options: dict):
    """The per-block GNSS reader handed to :func:`stream_blocks` (None = end of file)."""

    def on_block(block, kinds, events) -> None:
        final = block is None
        if final:
            g_pos = g_tod = g_sig = np.zeros(0)
        else:
            gi = kinds.get("GST", np.zeros(0, np.int64))
            g_pos = (gi + state.offset).astype(np.float64)
            g_tod = nf.tod_field(block, gi, 1)
            g_sig = nf.floats(block, gi, 8)[0]
        if state.gst is not None:
            g_pos = np.concatenate([state.gst[0], g_pos])
            g_tod = np.concatenate([state.gst[1], g_tod])
            g_sig = np.concatenate([state.gst[2], g_sig])
        for key, cand in cands.items():
            new = None if final else _gnss_records(state, cand, block, kinds, events, key,
                                                   options)
            _gnss_emit(cand, new, (g_pos, g_tod, g_sig), final, has_gst=len(g_pos) > 0)
        if g_pos.size:
            state.gst = (g_pos[-1:], g_tod[-1:], g_sig[-1:])

    return on_block


def _gnss_records(state, cand, block, kinds, events, key, options):
    if key not in kinds:
        return None
    if key == "PTNL,GGK":
        rec = ng.parse_ggk(block, kinds[key], min_quality=options["min_quality"])
    else:
        rec = ng.parse_gga(block, kinds[key], empty_geoid=options["empty_geoid"],
                           min_quality=options["min_quality"])
    kept = rec.skipped.pop(ng.EMPTY_GEOID_KEPT, 0)
    if kept:
        cand.notes["empty geoid"] = cand.notes.get("empty geoid", 0) + kept
    _count(cand.skipped, rec.skipped)
    cand.parsed += rec.index.size
    time, lag = record_times(state, block, events, rec.index, rec.tod)
    cand.add_lag(lag)
    return {"pos": (rec.index + state.offset).astype(np.float64), "tod": rec.tod,
            "time": time, "height": rec.height, "lat": rec.lat, "lon": rec.lon,
            "quality": rec.quality}


def _gnss_emit(cand: Candidate, new, gst, final: bool, has_gst: bool) -> None:
    """Match GST σ to the epochs so far and emit those whose following GST is known."""
    parts = [p for p in (cand.carry, new) if p is not None]
    if not parts:
        return
    recs = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
    g_pos, g_tod, g_sig = gst
    sigma = ng.match_gst(recs["pos"], recs["tod"], g_pos, g_tod, g_sig)
    cand.matched += int(np.count_nonzero(np.isfinite(sigma)))
    if final or not has_gst or new is None:
        cut = recs["pos"].size
    else:
        # epochs after this block's last GST wait: their GST may open the next block
        cut = int(np.searchsorted(recs["pos"], g_pos[-1]))
    columns = {k: recs[k][:cut] for k in GNSS_COLUMNS if k != "sigma_h"}
    columns["sigma_h"] = sigma[:cut]
    cand.matched -= int(np.count_nonzero(np.isfinite(sigma[cut:])))
    _emit(cand, columns)
    cand.carry = {k: v[cut:] for k, v in recs.items()} if cut < recs["pos"].size else None


# --------------------------------------------------------------------------- motion
def motion_block(state: FileState, cands: dict[str, Candidate]):
    """The per-block motion reader handed to :func:`stream_blocks`."""

    def on_block(block, kinds, events) -> None:
        if block is None:
            return
        if "HDT" in kinds and "TSS1" in cands:
            hdt = kinds["HDT"]
            state.hdt.append((block.tag[hdt], nm.hdt_headings(block, hdt)))
        for key, cand in cands.items():
            rec = _motion_records(cand, block, kinds, key)
            if rec is None:
                continue
            cand.parsed += rec.index.size
            time, lag = record_times(state, block, events, rec.index, rec.tod,
                                     has_time=key == "PASHR")
            cand.add_lag(lag)
            _emit(cand, {"time": time, "roll": rec.roll, "pitch": rec.pitch,
                         "heading": rec.heading, "heave": rec.heave})

    return on_block


def _motion_records(cand: Candidate, block, kinds, key: str):
    if key == "PASHR":
        if "PASHR" not in kinds:
            return None
        att, ashtech = nm.split_pashr(block, kinds["PASHR"])
        cand.notes["attitude"] = cand.notes.get("attitude", 0) + att.size
        if ashtech:
            cand.notes["ashtech"] = cand.notes.get("ashtech", 0) + ashtech
        rec = nm.parse_pashr(block, att)
    elif key == "PSXN,23":
        quality = kinds.get("PSXN,20", np.zeros(0, np.int64))
        if "PSXN,23" not in kinds:
            if quality.size:
                cand.last_quality = float(nf.floats(block, quality[-1:], 5)[0][0])
            return None
        rec = nm.parse_psxn23(block, kinds["PSXN,23"], quality, cand.last_quality)
        if quality.size:
            cand.last_quality = float(nf.floats(block, quality[-1:], 5)[0][0])
    else:
        if "TSS1" not in kinds:
            return None
        rec = nm.parse_tss1(block, kinds["TSS1"])
        settling = rec.skipped.pop(nm.TSS1_SETTLING, 0)
        if settling:
            cand.notes["settling"] = cand.notes.get("settling", 0) + settling
    _count(cand.skipped, rec.skipped)
    return rec


def new_candidates(group: h5py.Group, keys, columns) -> dict[str, Candidate]:
    """One sink per candidate source, in a subgroup of *group* each; compressed unless
    *group* says ``intermediate`` (one of several files, copied on when merged)."""
    compress = not group.attrs.get("intermediate", False)
    return {key: Candidate(key, TableSink(group.create_group(key.replace(",", "_")), columns,
                                          compress))
            for key in keys}


def finish_counts(state: FileState) -> dict[str, int]:
    """The file's lines set aside (the ``skipped`` of the report before record reasons)."""
    tag_style = nl.tag_style_of(state.census.styles)
    counts = dict(state.counts)
    if state.odd_prefix:
        reason = nl.odd_prefix_reason(tag_style)
        counts[reason] = counts.get(reason, 0) + state.odd_prefix
    return counts
