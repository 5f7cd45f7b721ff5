"""GNSS sentences of an NMEA log: GGA, Trimble PTNL,GGK, GST, and dates (ZDA, RMC).

Heights. GGA field 9 is the altitude above the geoid and field 11 the geoid separation
(geoid above ellipsoid), so the antenna's ellipsoidal height is h = altitude + N
(NMEA 0183 GGA definition; ``formats.md``). ``$PTNL,GGK`` carries the ellipsoidal height
directly (``EHT…`` field).

Empty geoid separation (Seapath 200 ``,M,,M,``, OxTS ``M,,,``): policy ``"zero"``
(default) keeps the epoch with N = 0 — for such receivers the altitude field is usually
already ellipsoidal, and the latency method removes a per-line trend anyway — and the
import report carries a warning with the count; policy ``"skip"`` drops those epochs,
counted as ``empty geoid separation``.

Quality. GGA fix quality is kept as is (0 invalid, 1 GPS, 2 DGPS, 4 RTK fixed, 5 RTK
float, …); GGK's Trimble codes are mapped onto GGA codes (``GGK_TO_GGA``) so one
``quality`` column means one thing. Epochs below ``min_quality`` (default 1, i.e. drop
"no fix") are counted as ``no fix``.

GST: field 8 is the 1-sigma error of the altitude (m); it is attached to the GGA/GGK
epoch with the same time of day nearest in the file as ``sigma_h`` (NaN when absent).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.importers import nmea_fields as nf
from hydrosync_core.importers import nmea_kernels as nk
from hydrosync_core.importers.nmea_lines import LogLines

# Trimble GGK quality -> GGA quality: 0 none, 1 autonomous, 2 RTK float, 3 RTK fixed,
# 4 DGPS, 5 SBAS, 6 network RTK float, 7 network RTK fixed, 8 2D network float,
# 9 2D network fixed, 10 OmniSTAR HP/XP, 11 OmniSTAR VBS, 12 Location RTK, 13 beacon DGPS.
EMPTY_GEOID_KEPT = "empty geoid separation (kept with N = 0)"
"""Counted while parsing; the import turns it into its warning (not a skip)."""

GGK_TO_GGA = np.array([0, 1, 5, 4, 2, 2, 5, 4, 5, 4, 5, 2, 5, 2], dtype=np.float64)


def sentence_kinds(log: LogLines) -> dict[str, np.ndarray]:
    """Sentence indices by kind: ``GGA``, ``ZDA``, ``PTNL,GGK``, ``PSXN,23``, ``TSS1``…

    Standard sentences are keyed by their 3-letter type (talker dropped, so a GP↔GN
    flip mid-file changes nothing); proprietary ones by address plus first field.
    """
    codes, names = nk.kind_codes(log.buf, log.start, log.end)
    if len(names) > 64:
        order = np.argsort(codes, kind="stable")
        bounds = np.searchsorted(codes[order], np.arange(len(names) + 1))
        return {name: order[bounds[j]:bounds[j + 1]] for j, name in enumerate(names)
                if bounds[j + 1] > bounds[j]}
    return {name: np.flatnonzero(codes == j) for j, name in enumerate(names)}


@dataclass
class DateEvents:
    """Dates stated by sentences: position (line number), day (since 1970), time of day."""

    position: np.ndarray
    day: np.ndarray
    tod: np.ndarray
    rollover_fixed: int = 0
    rollover_weeks: int = 0
    far: int = 0

    @property
    def warnings(self) -> list[str]:
        return date_warnings(self.rollover_fixed, self.rollover_weeks, self.far)


def date_events(log: LogLines, kinds: dict[str, np.ndarray]) -> DateEvents:
    """Collect dates from ZDA, RMC and GGK sentences, week-rollover corrected."""
    pos, day, tod = [], [], []
    if "ZDA" in kinds:
        idx = kinds["ZDA"]
        d, m, y = (nf.floats(log, idx, k)[0] for k in (2, 3, 4))
        pos.append(idx)
        day.append(nf.day_numbers(d, m, y))
        tod.append(nf.tod_field(log, idx, 1))
    for key, tcol, dcol, order in (("RMC", 1, 9, "dmy"), ("PTNL,GGK", 2, 3, "mdy")):
        if key not in kinds:
            continue
        idx = kinds[key]
        v = nf.floats(log, idx, dcol)[0]
        a, b, yy = np.floor(v / 10000.0), np.floor(v / 100.0) % 100, v % 100
        dd, mm = (a, b) if order == "dmy" else (b, a)
        # Two-digit years: 80-99 -> 19xx, 00-79 -> 20xx (NMEA convention).
        year = np.where(yy >= 80, 1900 + yy, 2000 + yy)
        pos.append(idx)
        day.append(nf.day_numbers(dd, mm, year))
        tod.append(nf.tod_field(log, idx, tcol))
    if not pos:
        return DateEvents(np.zeros(0, np.int64), np.zeros(0), np.zeros(0))
    position = np.concatenate(pos)
    days = np.concatenate(day)
    tods = np.concatenate(tod)
    ok = np.isfinite(days) & np.isfinite(tods)
    order = np.argsort(position[ok], kind="stable")
    index = position[ok][order]
    ev = DateEvents(log.line_no[index], days[ok][order], tods[ok][order])
    tags = log.tag[index]
    if np.isfinite(tags).any():
        logger_day = np.floor(tags / nf.DAY)
        ev.day, ev.rollover_fixed, ev.rollover_weeks = nf.correct_rollover(ev.day, logger_day)
        off = np.abs(ev.day - logger_day)
        ev.far = int(np.count_nonzero(np.isfinite(off) & (off > 1)))
    return ev


def date_warnings(fixed: int, weeks: int, far: int) -> list[str]:
    """Warnings about the sentence dates: week rollovers corrected, dates far off."""
    out = []
    if fixed:
        out.append(f"{fixed} ZDA/RMC dates were {weeks} weeks before the logger date "
                   "(GPS week-number rollover): corrected")
    if far:
        out.append(f"{far} sentence dates differ from the logger date by > 1 day")
    return out


def sentence_times(
    log: LogLines, index: np.ndarray, tod: np.ndarray, events: DateEvents, *,
    any_tags: bool | None = None, unwrap=None,
) -> tuple[np.ndarray, str]:
    """Unix seconds of sentences *index* whose UTC time of day is *tod*.

    The date comes from the nearest preceding date sentence (ZDA/RMC/GGK), else from the
    logger tag, else there is none and times count from 00:00 of the first day.
    Returns the times and a word saying which date source was used. *any_tags* (whether
    the file's records carry logger tags) and *unwrap* (a day counter carried over
    blocks) serve a file read block by block.
    """
    if events.position.size:
        k = nf.nearest_event(log.line_no[index], events.position)
        return nf.day_relative(tod, events.day[k], events.tod[k]), "date sentences"
    tags = log.tag[index]
    if any_tags if any_tags is not None else np.isfinite(tags).any():
        tag_day = np.floor(tags / nf.DAY)
        return nf.day_relative(tod, tag_day, tags - tag_day * nf.DAY), "logger date"
    return (unwrap(tod) if unwrap is not None else nf.unwrap_days(tod)), "none"


@dataclass
class GnssRecords:
    """Parsed GNSS epochs (before time assembly), one per usable GGA or GGK sentence.

    ``index`` are sentence indices into the LogLines; ``tod`` UTC seconds of day;
    ``height`` ellipsoidal (m); ``lat``/``lon`` degrees (WGS84 as output by the
    receiver); ``quality`` GGA fix quality; ``sigma_h`` GST altitude sigma (m, NaN if
    none).
    """

    source: str
    index: np.ndarray
    tod: np.ndarray
    height: np.ndarray
    lat: np.ndarray
    lon: np.ndarray
    quality: np.ndarray
    sigma_h: np.ndarray
    skipped: dict[str, int] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)


def parse_gga(
    log: LogLines, index: np.ndarray, *, empty_geoid: str = "zero", min_quality: int = 1
) -> GnssRecords:
    """Parse GGA sentences *index*: h = altitude (field 9) + geoid separation (field 11)."""
    q, q_empty, q_bad = nf.floats(log, index, 6)
    alt, alt_empty, alt_bad = nf.floats(log, index, 9)
    sep, sep_empty, sep_bad = nf.floats(log, index, 11)
    skipped: dict[str, int] = {}
    warnings: list[str] = []
    keep = np.ones(index.size, dtype=bool)
    nf.drop(skipped, "no fix", q_empty | q_bad | (q < min_quality), keep)
    nf.drop(skipped, "empty altitude", alt_empty, keep)
    nf.drop(skipped, "unparseable field", alt_bad | sep_bad, keep)
    if empty_geoid == "skip":
        nf.drop(skipped, "empty geoid separation", sep_empty, keep)
    else:
        n = int(np.count_nonzero(sep_empty & keep))
        if n:
            skipped[EMPTY_GEOID_KEPT] = n
        sep = np.where(sep_empty, 0.0, sep)
    # Ellipsoidal height h = H (altitude above geoid) + N (geoid separation).
    height = alt + sep
    lat = nf.latlon(log, index, 2, "S")
    lon = nf.latlon(log, index, 4, "W")
    return GnssRecords(
        "GGA", index[keep], nf.tod_field(log, index, 1)[keep], height[keep],
        lat[keep], lon[keep], q[keep], np.full(int(keep.sum()), np.nan), skipped, warnings,
    )


def parse_ggk(log: LogLines, index: np.ndarray, *, min_quality: int = 1) -> GnssRecords:
    """Parse ``$PTNL,GGK``: ellipsoidal height from the ``EHT…`` field (field 11)."""
    raw_q, q_empty, q_bad = nf.floats(log, index, 8)
    eht, eht_empty, eht_bad = nf.floats(log, index, 11, eht=True)
    in_table = np.isfinite(raw_q) & (raw_q >= 0) & (raw_q < len(GGK_TO_GGA))
    q = np.full(raw_q.shape, np.nan)
    q[in_table] = GGK_TO_GGA[raw_q[in_table].astype(int)]
    skipped: dict[str, int] = {}
    keep = np.ones(index.size, dtype=bool)
    nf.drop(skipped, "no fix", q_empty | q_bad | ~in_table | ~(q >= min_quality), keep)
    nf.drop(skipped, "empty altitude", eht_empty, keep)
    nf.drop(skipped, "unparseable field", eht_bad, keep)
    lat = nf.latlon(log, index, 4, "S")
    lon = nf.latlon(log, index, 6, "W")
    return GnssRecords(
        "PTNL,GGK", index[keep], nf.tod_field(log, index, 2)[keep], eht[keep],
        lat[keep], lon[keep], q[keep], np.full(int(keep.sum()), np.nan), skipped, [],
    )


def attach_gst(log: LogLines, rec: GnssRecords, gst_index: np.ndarray) -> int:
    """Fill ``rec.sigma_h`` from GST field 8 (altitude sigma, m); return epochs matched."""
    if gst_index.size == 0 or rec.index.size == 0:
        return 0
    rec.sigma_h[:] = match_gst(rec.index, rec.tod, gst_index, nf.tod_field(log, gst_index, 1),
                               nf.floats(log, gst_index, 8)[0])
    return int(np.count_nonzero(np.isfinite(rec.sigma_h)))


def match_gst(pos: np.ndarray, tod: np.ndarray, g_pos: np.ndarray, g_tod: np.ndarray,
              g_sig: np.ndarray) -> np.ndarray:
    """GST altitude σ (m) of epochs at sentence positions *pos* with times of day *tod*.

    A GST belongs to the epoch with the same time of day; of the candidates the nearest
    in the file (preceding or following GST) is taken. NaN where none matches.
    """
    out = np.full(pos.size, np.nan)
    if g_pos.size == 0:
        return out
    best = np.full(pos.size, -1)
    best_gap = np.full(pos.size, np.inf)
    k = np.searchsorted(g_pos, pos)
    for cand in (k - 1, k):
        c = np.clip(cand, 0, g_pos.size - 1)
        same = (np.abs(g_tod[c] - tod) < 1e-3) & (cand >= 0) & (cand < g_pos.size)
        gap = np.abs(g_pos[c] - pos).astype(float)
        better = same & (gap < best_gap)
        best[better] = c[better]
        best_gap[better] = gap[better]
    hit = best >= 0
    out[hit] = g_sig[best[hit]]
    return out


def empty_geoid_warning(n: int) -> str:
    """The warning for *n* GGA epochs kept with an empty geoid separation."""
    return (f"{n} GGA epochs have an empty geoid separation: height = altitude "
            "(separation taken as 0, so those heights are above the geoid, not "
            "ellipsoidal; import with --empty-geoid skip to drop them)")
