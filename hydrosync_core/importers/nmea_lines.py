"""Split raw device-log bytes into time-tagged NMEA 0183 sentences.

Real logs are not clean NMEA: a logging computer may prefix every line with its own time
tag, receivers interleave binary frames (UBX, RTCM) with text, serial-port collisions
splice a truncated sentence onto the next one, some loggers write no checksums at all and
others write lower-case hex. :func:`split_log` turns such a file into one record per
usable sentence — ``(line_no, logger time tag or NaN, sentence body)`` — and counts
everything it set aside, by reason, so the caller can report it.

Why a small regex splitter and not pynmeagps: pynmeagps parses a *stream* of well-formed
sentences and rejects (or raises on) exactly the oddities this module must survive and
count — logger prefixes, sentences without checksum, spliced fragments, a `$` inside
binary. Here each line is matched with two compiled regular expressions (C speed) and the
checksums of all sentences are verified at once with ``numpy.bitwise_xor.reduceat``.

Recognised logger time tags (the text before the sentence):

* ISO 8601 UTC ``2014-08-01T00:00:00.814000Z`` followed by a space, tab or comma
  (openrvdas);
* ``MM/DD/YYYY,hh:mm:ss.sss,`` (R2R / SCS loggers);
* epoch seconds ``1535243706.515`` followed by a space or tab (NCEI/UHDAS).

All three become float64 seconds since 1970-01-01 00:00:00 UTC (Unix time, leap seconds
ignored as Unix time does).

Checksum policy: a sentence with a ``*hh`` checksum (either case) must match it, else it
is dropped as ``bad checksum``. A sentence without checksum is accepted only when most
sentences of the file carry none (a logger or device that never writes them — reported
as ``no checksum``); in a file whose sentences normally carry checksums a sentence without
one is a truncated fragment and is dropped as ``missing checksum``.
"""

from __future__ import annotations

import datetime as _dt
import re
from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.progress import CancelToken, ProgressCallback, check_cancel, report

# A sentence start: `$` or `!`, an address of 3-7 upper-case letters/digits, a comma.
_START = re.compile(r"[$!][A-Z][A-Z0-9]{2,6},")
# A complete sentence from its start: printable body, then `*hh` (hh hex, any case).
_WITH_CS = re.compile(r"[$!]([\x20-\x7e]*?)\*([0-9A-Fa-f]{2})")
# A sentence without checksum: printable body to the end of the line.
_NO_CS = re.compile(r"[$!]([^$!*\x00-\x1f\x7f-\xff]*)\Z")
# TSS1 motion record (no `$`): ":XXAAAA MHHHHQMRRRR MPPPP".
_TSS1 = re.compile(r":[0-9A-Fa-f]{6} [ +-]\d{4}[A-Za-z ][ +-]\d{4} [ +-]\d{4}")
_ISO = re.compile(
    r"\A(\d{4})-(\d\d)-(\d\d)[T ](\d\d):(\d\d):(\d\d(?:\.\d*)?)Z?[ \t,;]*\Z"
)
_MDY = re.compile(r"\A(\d\d)/(\d\d)/(\d{4})[, ](\d\d):(\d\d):(\d\d(?:\.\d*)?)[ \t,;]*\Z")
_EPOCH = re.compile(r"\A(\d{9,11}(?:\.\d*)?)[ \t,;]*\Z")
_NONPRINT = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\xff]")

_DAY0 = _dt.date(1970, 1, 1).toordinal()


@dataclass
class LogLines:
    """Usable sentences of one log file, in file order.

    Attributes
    ----------
    path : str
        File the sentences came from.
    line_no : ndarray of int64, shape (n,)
        1-based line number of each sentence.
    tag : ndarray of float64, shape (n,)
        Logger time tag, Unix seconds (UTC); NaN when the line has none.
    body : list of str
        Sentence text between ``$``/``!`` and ``*`` (no checksum), e.g.
        ``"GPGGA,000000.70,..."``; TSS1 records keep their leading ``:``.
    has_checksum : ndarray of bool, shape (n,)
        True when the sentence carried a (valid) checksum.
    counts : dict of str to int
        Lines set aside by reason, plus ``lines`` (all lines) and ``sentences``.
    tag_style : str or None
        ``"iso"``, ``"mdy"``, ``"epoch"`` or None (no logger tags).
    no_checksums : bool
        True when the file's sentences carry no checksums at all (accepted, flagged).
    """

    path: str
    line_no: np.ndarray
    tag: np.ndarray
    body: list[str]
    has_checksum: np.ndarray
    counts: dict[str, int] = field(default_factory=dict)
    tag_style: str | None = None
    no_checksums: bool = False

    def address(self) -> list[str]:
        """First field of every sentence (``GPGGA``, ``PSXN``, ``:`` for TSS1)."""
        return [":" if b.startswith(":") else b.split(",", 1)[0] for b in self.body]


def _day_number(cache: dict, y: int, m: int, d: int) -> int | None:
    key = (y, m, d)
    if key not in cache:
        try:
            cache[key] = _dt.date(y, m, d).toordinal() - _DAY0
        except ValueError:
            cache[key] = None
    return cache[key]


def parse_tag(prefix: str, cache: dict) -> tuple[float, str | None]:
    """Parse a logger time-tag prefix; return (Unix seconds or NaN, style or None)."""
    m = _ISO.match(prefix)
    if m:
        y, mo, d, hh, mi = (int(g) for g in m.groups()[:5])
        style = "iso"
    else:
        m = _MDY.match(prefix)
        if m:
            mo, d, y, hh, mi = (int(g) for g in m.groups()[:5])
            style = "mdy"
        else:
            m = _EPOCH.match(prefix)
            if m:
                return float(m.group(1)), "epoch"
            return float("nan"), None
    sec = float(m.group(6))
    day = _day_number(cache, y, mo, d)
    if day is None or hh > 23 or mi > 59 or sec >= 61.0:
        return float("nan"), None
    # Unix seconds = days since 1970-01-01 * 86400 + seconds of day.
    return day * 86400.0 + hh * 3600.0 + mi * 60.0 + sec, style


def _xor_checksums(bodies: list[str]) -> np.ndarray:
    """XOR of all bytes of every body (the NMEA checksum), vectorised with reduceat."""
    if not bodies:
        return np.zeros(0, dtype=np.uint8)
    lengths = np.fromiter((len(b) for b in bodies), dtype=np.int64, count=len(bodies))
    data = np.frombuffer("".join(bodies).encode("latin-1"), dtype=np.uint8)
    out = np.zeros(len(bodies), dtype=np.uint8)
    nonempty = lengths > 0
    if data.size:
        starts = np.concatenate([[0], np.cumsum(lengths)[:-1]])[nonempty]
        out[nonempty] = np.bitwise_xor.reduceat(data, starts)
    return out


def _find_sentence(text: str) -> tuple[int, str, str | None] | None:
    """Locate the usable sentence of a line: (start, body, checksum hex or None).

    The *last* sentence start whose remainder is well formed wins: a spliced line
    (truncated sentence + complete one) or binary noise containing `$` both put the
    real sentence last.
    """
    starts = [m.start() for m in _START.finditer(text)]
    for start in reversed(starts):
        m = _WITH_CS.match(text, start)
        if m and "$" not in m.group(1) and "!" not in m.group(1)[1:]:
            return start, m.group(1), m.group(2)
        m = _NO_CS.match(text, start)
        if m:
            return start, m.group(1), None
    return None


def split_log(
    data: bytes,
    path: str = "<bytes>",
    *,
    progress: ProgressCallback | None = None,
    cancel: CancelToken | None = None,
) -> LogLines:
    """Split raw log bytes into usable sentences and per-reason counts.

    Parameters
    ----------
    data : bytes
        The whole file. Decoded as Latin-1 so binary bytes never raise.
    path : str
        File name used in the result (for messages).
    progress, cancel
        Reported / checked every 50 000 lines.

    Returns
    -------
    LogLines
        Sentences with valid (or, in a checksum-free file, absent) checksums.
    """
    text_all = data.decode("latin-1")
    lines = text_all.split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    counts: dict[str, int] = {"lines": len(lines)}

    def bump(key: str, n: int = 1) -> None:
        counts[key] = counts.get(key, 0) + n

    cache: dict = {}
    rec_line: list[int] = []
    rec_tag: list[float] = []
    rec_body: list[str] = []
    rec_cs: list[str | None] = []
    styles: dict[str, int] = {}
    odd_prefix = 0  # printable text before a sentence that is not a time tag
    for number, raw in enumerate(lines, start=1):
        if number % 50_000 == 0:
            check_cancel(cancel)
            report(progress, 0.5 * number / len(lines), "splitting sentences")
        line = raw.rstrip("\r\n\t ")
        stripped = line.lstrip()
        if not stripped:
            bump("blank")
            continue
        if stripped[0] in "#{" and not _NONPRINT.search(line):
            # Printable only: a binary fragment may begin with 0x23 '#' or 0x7B '{'.
            bump("comment" if stripped[0] == "#" else "json")
            continue
        found = _find_sentence(line)
        if found is None:
            tss = _TSS1.search(line)
            if tss is None:
                bump("binary" if _NONPRINT.search(line) else "unparseable")
                continue
            start, body, cs = tss.start(), tss.group(0), None
        else:
            start, body, cs = found
        prefix = line[:start]
        tag = float("nan")
        fragment = _START.search(prefix)
        if fragment:
            # A truncated sentence spliced before this one: drop it, keep any tag.
            bump("spliced fragment")
            prefix = prefix[: fragment.start()]
        if prefix.strip():
            tag, style = parse_tag(prefix.strip(), cache)
            if style is not None:
                styles[style] = styles.get(style, 0) + 1
            elif _NONPRINT.search(prefix):
                bump("binary before sentence")
            else:
                odd_prefix += 1
        rec_line.append(number)
        rec_tag.append(tag)
        rec_body.append(body)
        rec_cs.append(cs)

    is_tss = np.array([b.startswith(":") for b in rec_body], dtype=bool)
    given = np.array([c is not None for c in rec_cs], dtype=bool)
    keep = np.ones(len(rec_body), dtype=bool)
    with_cs = np.flatnonzero(given)
    if with_cs.size:
        computed = _xor_checksums([rec_body[i] for i in with_cs])
        stated = np.array([int(rec_cs[i], 16) for i in with_cs], dtype=np.uint8)
        bad = with_cs[computed != stated]
        keep[bad] = False
        if bad.size:
            bump("bad checksum", int(bad.size))
    nmea = ~is_tss
    n_without = int(np.count_nonzero(nmea & ~given))
    n_with = int(np.count_nonzero(nmea & given))
    no_checksums = n_without > 0 and n_without > n_with
    if n_without and not no_checksums:
        # Most sentences carry a checksum: one without is a truncated fragment.
        keep[nmea & ~given] = False
        bump("missing checksum", n_without)
    elif no_checksums:
        bump("no checksum (accepted)", n_without)
    idx = np.flatnonzero(keep)
    counts["sentences"] = int(idx.size)
    tag_style = max(styles, key=styles.get) if styles else None
    if odd_prefix:
        # In a tagged file it is a damaged tag; otherwise stray bytes glued on.
        bump("bad time tag" if tag_style else "junk before sentence", odd_prefix)
    return LogLines(
        path=path,
        line_no=np.asarray(rec_line, dtype=np.int64)[idx] if rec_line else np.zeros(0, np.int64),
        tag=np.asarray(rec_tag, dtype=np.float64)[idx] if rec_tag else np.zeros(0),
        body=[rec_body[i] for i in idx],
        has_checksum=given[idx],
        counts=counts,
        tag_style=tag_style,
        no_checksums=no_checksums,
    )
