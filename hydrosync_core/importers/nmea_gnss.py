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
from hydrosync_core.importers.nmea_lines import LogLines

# Trimble GGK quality -> GGA quality: 0 none, 1 autonomous, 2 RTK float, 3 RTK fixed,
# 4 DGPS, 5 SBAS, 6 network RTK float, 7 network RTK fixed, 8 2D network float,
# 9 2D network fixed, 10 OmniSTAR HP/XP, 11 OmniSTAR VBS, 12 Location RTK, 13 beacon DGPS.
GGK_TO_GGA = np.array([0, 1, 5, 4, 2, 2, 5, 4, 5, 4, 5, 2, 5, 2], dtype=np.float64)


def sentence_kinds(log: LogLines) -> dict[str, np.ndarray]:
    """Sentence indices by kind: ``GGA``, ``ZDA``, ``PTNL,GGK``, ``PSXN,23``, ``TSS1``…

    Standard sentences are keyed by their 3-letter type (talker dropped, so a GP↔GN
    flip mid-file changes nothing); proprietary ones by address plus first field.
    """
    groups: dict[str, list[int]] = {}
    for i, body in enumerate(log.body):
        if body.startswith(":"):
            key = "TSS1"
        else:
            parts = body.split(",", 2)
            addr = parts[0]
            if addr.startswith("P") and addr in ("PTNL", "PSXN"):
                key = f"{addr},{parts[1] if len(parts) > 1 else ''}"
            elif addr.startswith("P"):
                key = addr
            else:
                key = addr[-3:]
        groups.setdefault(key, []).append(i)
    return {k: np.asarray(v, dtype=np.int64) for k, v in groups.items()}


@dataclass
class DateEvents:
    """Dates stated by sentences: position in the log, day (since 1970), time of day."""

    position: np.ndarray
    day: np.ndarray
    tod: np.ndarray
    rollover_fixed: int = 0
    rollover_weeks: int = 0
    warnings: list[str] = field(default_factory=list)


def date_events(log: LogLines, kinds: dict[str, np.ndarray]) -> DateEvents:
    """Collect dates from ZDA, RMC and GGK sentences, week-rollover corrected."""
    pos, day, tod = [], [], []
    if "ZDA" in kinds:
        rows = nf.rows_of(log.body, kinds["ZDA"])
        d, _, _ = nf.to_float(nf.column(rows, 2))
        m, _, _ = nf.to_float(nf.column(rows, 3))
        y, _, _ = nf.to_float(nf.column(rows, 4))
        pos.append(kinds["ZDA"])
        day.append(nf.day_numbers(d, m, y))
        tod.append(nf.time_of_day(nf.column(rows, 1)))
    for key, tcol, dcol, order in (("RMC", 1, 9, "dmy"), ("PTNL,GGK", 2, 3, "mdy")):
        if key not in kinds:
            continue
        rows = nf.rows_of(log.body, kinds[key])
        v, _, _ = nf.to_float(nf.column(rows, dcol))
        a, b, yy = np.floor(v / 10000.0), np.floor(v / 100.0) % 100, v % 100
        dd, mm = (a, b) if order == "dmy" else (b, a)
        # Two-digit years: 80-99 -> 19xx, 00-79 -> 20xx (NMEA convention).
        year = np.where(yy >= 80, 1900 + yy, 2000 + yy)
        pos.append(kinds[key])
        day.append(nf.day_numbers(dd, mm, year))
        tod.append(nf.time_of_day(nf.column(rows, tcol)))
    if not pos:
        return DateEvents(np.zeros(0, np.int64), np.zeros(0), np.zeros(0))
    position = np.concatenate(pos)
    days = np.concatenate(day)
    tods = np.concatenate(tod)
    ok = np.isfinite(days) & np.isfinite(tods)
    order = np.argsort(position[ok], kind="stable")
    ev = DateEvents(position[ok][order], days[ok][order], tods[ok][order])
    tags = log.tag[ev.position]
    if np.isfinite(tags).any():
        logger_day = np.floor(tags / nf.DAY)
        ev.day, ev.rollover_fixed, ev.rollover_weeks = nf.correct_rollover(ev.day, logger_day)
        if ev.rollover_fixed:
            ev.warnings.append(
                f"{ev.rollover_fixed} ZDA/RMC dates were {ev.rollover_weeks} weeks before "
                f"the logger date (GPS week-number rollover): corrected"
            )
        off = np.abs(ev.day - logger_day)
        far = np.count_nonzero(np.isfinite(off) & (off > 1))
        if far:
            ev.warnings.append(f"{far} sentence dates differ from the logger date by > 1 day")
    return ev


def sentence_times(
    log: LogLines, index: np.ndarray, tod: np.ndarray, events: DateEvents
) -> tuple[np.ndarray, str]:
    """Unix seconds of sentences *index* whose UTC time of day is *tod*.

    The date comes from the nearest preceding date sentence (ZDA/RMC/GGK), else from the
    logger tag, else there is none and times count from 00:00 of the first day.
    Returns the times and a word saying which date source was used.
    """
    if events.position.size:
        k = nf.nearest_event(index, events.position)
        return nf.day_relative(tod, events.day[k], events.tod[k]), "date sentences"
    tags = log.tag[index]
    if np.isfinite(tags).any():
        tag_day = np.floor(tags / nf.DAY)
        return nf.day_relative(tod, tag_day, tags - tag_day * nf.DAY), "logger date"
    return nf.unwrap_days(tod), "none"


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
    rows = nf.rows_of(log.body, index)
    q, q_empty, q_bad = nf.to_float(nf.column(rows, 6))
    alt, alt_empty, alt_bad = nf.to_float(nf.column(rows, 9))
    sep, sep_empty, sep_bad = nf.to_float(nf.column(rows, 11))
    skipped: dict[str, int] = {}
    warnings: list[str] = []
    keep = np.ones(len(rows), dtype=bool)
    nf.drop(skipped, "no fix", q_empty | q_bad | (q < min_quality), keep)
    nf.drop(skipped, "empty altitude", alt_empty, keep)
    nf.drop(skipped, "unparseable field", alt_bad | sep_bad, keep)
    if empty_geoid == "skip":
        nf.drop(skipped, "empty geoid separation", sep_empty, keep)
    else:
        n = int(np.count_nonzero(sep_empty & keep))
        if n:
            warnings.append(
                f"{n} GGA epochs have an empty geoid separation: height = altitude "
                "(separation taken as 0, so those heights are above the geoid, not "
                "ellipsoidal; import with --empty-geoid skip to drop them)"
            )
        sep = np.where(sep_empty, 0.0, sep)
    # Ellipsoidal height h = H (altitude above geoid) + N (geoid separation).
    height = alt + sep
    lat = nf.latlon(nf.column(rows, 2), nf.column(rows, 3), "S")
    lon = nf.latlon(nf.column(rows, 4), nf.column(rows, 5), "W")
    return GnssRecords(
        "GGA", index[keep], nf.time_of_day(nf.column(rows, 1))[keep], height[keep],
        lat[keep], lon[keep], q[keep], np.full(int(keep.sum()), np.nan), skipped, warnings,
    )


def parse_ggk(log: LogLines, index: np.ndarray, *, min_quality: int = 1) -> GnssRecords:
    """Parse ``$PTNL,GGK``: ellipsoidal height from the ``EHT…`` field (field 11)."""
    rows = nf.rows_of(log.body, index)
    raw_q, q_empty, q_bad = nf.to_float(nf.column(rows, 8))
    eht_text = nf.column(rows, 11)
    eht, eht_empty, eht_bad = nf.to_float(
        [t[3:] if t.upper().startswith("EHT") else t for t in eht_text]
    )
    in_table = np.isfinite(raw_q) & (raw_q >= 0) & (raw_q < len(GGK_TO_GGA))
    q = np.full(raw_q.shape, np.nan)
    q[in_table] = GGK_TO_GGA[raw_q[in_table].astype(int)]
    skipped: dict[str, int] = {}
    keep = np.ones(len(rows), dtype=bool)
    nf.drop(skipped, "no fix", q_empty | q_bad | ~in_table | ~(q >= min_quality), keep)
    nf.drop(skipped, "empty altitude", eht_empty, keep)
    nf.drop(skipped, "unparseable field", eht_bad, keep)
    lat = nf.latlon(nf.column(rows, 4), nf.column(rows, 5), "S")
    lon = nf.latlon(nf.column(rows, 6), nf.column(rows, 7), "W")
    return GnssRecords(
        "PTNL,GGK", index[keep], nf.time_of_day(nf.column(rows, 2))[keep], eht[keep],
        lat[keep], lon[keep], q[keep], np.full(int(keep.sum()), np.nan), skipped, [],
    )


def attach_gst(log: LogLines, rec: GnssRecords, gst_index: np.ndarray) -> int:
    """Fill ``rec.sigma_h`` from GST field 8 (altitude sigma, m); return epochs matched.

    A GST belongs to the epoch with the same time of day; of the candidates the nearest
    in the file (preceding or following GST) is taken.
    """
    if gst_index.size == 0 or rec.index.size == 0:
        return 0
    rows = nf.rows_of(log.body, gst_index)
    g_tod = nf.time_of_day(nf.column(rows, 1))
    g_sig, _, _ = nf.to_float(nf.column(rows, 8))
    best = np.full(rec.index.size, -1)
    best_gap = np.full(rec.index.size, np.inf)
    k = np.searchsorted(gst_index, rec.index)
    for cand in (k - 1, k):
        c = np.clip(cand, 0, gst_index.size - 1)
        same = (np.abs(g_tod[c] - rec.tod) < 1e-3) & (cand >= 0) & (cand < gst_index.size)
        gap = np.abs(gst_index[c] - rec.index).astype(float)
        better = same & (gap < best_gap)
        best[better] = c[better]
        best_gap[better] = gap[better]
    hit = best >= 0
    rec.sigma_h[hit] = g_sig[best[hit]]
    return int(np.count_nonzero(hit & np.isfinite(rec.sigma_h)))
