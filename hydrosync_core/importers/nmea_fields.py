"""Vectorised field conversion and time assembly shared by the NMEA readers.

Each wanted field is converted for all sentences at once by a compiled kernel reading
the sentence bytes (:mod:`nmea_kernels`), with ``float()`` only for a value that is not a
plain decimal, so a bad value costs a NaN and a count, not the file.

Time model. NMEA sentences carry the UTC *time of day*; the date comes from ZDA/RMC/GGK
sentences or, failing those, from the logger's time tag. All results are float64 Unix
seconds (UTC). A time of day more than 12 h away from its reference (a date sentence or
the logger tag) belongs to the neighbouring day — that is how a GGA stamped 23:59:59.2
logged at 00:00:00.2 (openrvdas PCOD) keeps its own, earlier, date.
"""

from __future__ import annotations

import numpy as np

from hydrosync_core.importers import nmea_kernels as nk

DAY = 86400.0
HALF_DAY = 43200.0
ROLLOVER_DAYS = 1024 * 7
"""GPS week-number rollover: 1024 weeks, the period of the 10-bit week counter."""


def floats(log, index: np.ndarray, k: int, *, eht: bool = False
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Field *k* of sentences *index* of a :class:`~.nmea_lines.SentenceBlock` as float64.

    Parsed by the compiled kernel; a field that is not a plain decimal (an exponent, a
    word) goes through ``float()``. *eht* drops a leading ``EHT`` (``$PTNL,GGK`` height).

    Returns
    -------
    numbers : ndarray of float64
        NaN where empty or not a number.
    empty : ndarray of bool
        The field was empty or missing.
    bad : ndarray of bool
        The field was present but not a finite number.
    """
    numbers, state, spans = nk.field_floats(log.buf, log.start, log.end, index, k, eht)
    empty = state == 1
    for r in np.flatnonzero(state == 2):
        text = log.buf[spans[r, 0]:spans[r, 1]].tobytes().decode("latin-1")
        numbers[r] = _float_or_nan(text)
    bad = ~empty & ~np.isfinite(numbers)
    numbers[bad] = np.nan
    return numbers, empty, bad


def texts(log, index: np.ndarray, k: int, width: int = 4) -> np.ndarray:
    """Field *k* of sentences *index*, spaces stripped, as bytes ``S<width>`` (truncated)."""
    return nk.field_text(log.buf, log.start, log.end, index, k, width)


def to_float(values: list[str]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Convert strings to float64: (numbers, empty, bad) as :func:`floats` returns them."""
    n = len(values)
    empty = np.fromiter((v == "" for v in values), dtype=bool, count=n)
    numbers = np.array([_float_or_nan(v) for v in values], dtype=np.float64)
    bad = ~empty & ~np.isfinite(numbers)
    numbers[bad] = np.nan
    return numbers, empty, bad


def _float_or_nan(value: str) -> float:
    try:
        return float(value) if value else float("nan")
    except ValueError:
        return float("nan")


def time_of_day(v: np.ndarray) -> np.ndarray:
    """``hhmmss[.sss]`` (as a number) -> seconds of the UTC day (float64); NaN when invalid."""
    hh = np.floor(v / 10000.0)
    mm = np.floor(v / 100.0) - 100.0 * hh
    ss = v - 10000.0 * hh - 100.0 * mm
    ok = (hh >= 0) & (hh < 24) & (mm >= 0) & (mm < 60) & (ss >= 0) & (ss < 61)
    return np.where(ok, hh * 3600.0 + mm * 60.0 + ss, np.nan)


def tod_field(log, index: np.ndarray, k: int) -> np.ndarray:
    """UTC seconds of day of the ``hhmmss.ss`` field *k* of sentences *index*."""
    return time_of_day(floats(log, index, k)[0])


def latlon(log, index: np.ndarray, k: int, negative: str) -> np.ndarray:
    """NMEA ``(d)ddmm.mmmm`` field *k* + hemisphere field *k+1* -> signed decimal degrees.

    *negative* is ``"S"`` or ``"W"``. A value written with its own minus sign and a
    hemisphere letter (seen in a Unicore GLL) is taken by magnitude, the letter decides.
    """
    v = np.abs(floats(log, index, k)[0])
    # ddmm.mmmm: degrees = floor(v/100), minutes = the rest.
    deg = np.floor(v / 100.0)
    minutes = v - 100.0 * deg
    out = deg + minutes / 60.0
    out[minutes >= 60.0] = np.nan
    hemi = np.char.upper(texts(log, index, k + 1, 2))
    sign = np.where(hemi == negative.encode(), -1.0, 1.0)
    return out * sign if out.size else out


def day_numbers(day: np.ndarray, month: np.ndarray, year: np.ndarray) -> np.ndarray:
    """Days since 1970-01-01 for float arrays of day, month, year (NaN if invalid)."""
    out = np.full(day.shape, np.nan)
    ok = (
        np.isfinite(day) & np.isfinite(month) & np.isfinite(year)
        & (month >= 1) & (month <= 12) & (day >= 1) & (day <= 31) & (year >= 1900)
        & (year <= 2200)
    )
    if not ok.any():
        return out
    y = year[ok].astype(np.int64)
    m = month[ok].astype(np.int64)
    d = day[ok].astype(np.int64)
    months = (y - 1970) * 12 + (m - 1)
    first = months.astype("datetime64[M]").astype("datetime64[D]").astype(np.int64)
    days = first + d - 1
    # A day beyond the month's end (31 April) is invalid, not the next month.
    next_first = (months + 1).astype("datetime64[M]").astype("datetime64[D]").astype(np.int64)
    days = np.where(days < next_first, days, np.nan)
    out[ok] = days
    return out


def correct_rollover(
    event_day: np.ndarray, logger_day: np.ndarray
) -> tuple[np.ndarray, int, int]:
    """Undo GPS week-number rollovers in sentence dates, using the logger's date.

    A receiver whose firmware predates a rollover reports dates exactly n·1024 weeks
    early (openrvdas PCOD: ZDA 1994-12-16 in a log written 2014-08-01). A date that sits
    n·1024 weeks (n ≥ 1) before the logger date, within 2 days, is moved forward.

    Returns the corrected days, the number corrected and the number of weeks added
    (0 when none).
    """
    delta = logger_day - event_day
    n = np.round(delta / ROLLOVER_DAYS)
    hit = np.isfinite(delta) & (n >= 1) & (np.abs(delta - n * ROLLOVER_DAYS) <= 2.0)
    fixed = np.where(hit, event_day + n * ROLLOVER_DAYS, event_day)
    weeks = int(n[hit].max()) * 1024 if hit.any() else 0
    return fixed, int(np.count_nonzero(hit)), weeks


def day_relative(tod: np.ndarray, ref_day: np.ndarray, ref_tod: np.ndarray) -> np.ndarray:
    """Unix seconds of a time of day *tod* nearest to the reference (day, time of day).

    A time of day more than 12 h after the reference belongs to the previous day
    (sentence 23:59:59 logged at 00:00:00), more than 12 h before it to the next.
    """
    diff = tod - ref_tod
    day = ref_day - (diff > HALF_DAY) + (diff < -HALF_DAY)
    return day * DAY + tod


def nearest_event(positions: np.ndarray, event_positions: np.ndarray) -> np.ndarray:
    """Index of the preceding event for each position (the following one if none)."""
    k = np.searchsorted(event_positions, positions, side="right") - 1
    return np.clip(k, 0, len(event_positions) - 1)


def unwrap_days(tod: np.ndarray) -> np.ndarray:
    """Seconds since 00:00 of the first day: add a day whenever the clock goes back >12 h."""
    finite = np.isfinite(tod)
    step = np.zeros(tod.shape)
    t = tod[finite]
    if t.size > 1:
        wraps = np.concatenate([[0.0], np.cumsum(np.diff(t) < -HALF_DAY)])
        step[finite] = wraps
    return step * DAY + tod


def drop(skipped: dict[str, int], reason: str, mask: np.ndarray, keep: np.ndarray) -> None:
    """Clear *mask* from the boolean *keep* (in place), counting newly dropped records
    under *reason* in *skipped*."""
    n = int(np.count_nonzero(mask & keep))
    if n:
        skipped[reason] = skipped.get(reason, 0) + n
    keep &= ~mask
