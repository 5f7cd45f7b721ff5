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

from hydrosync_core.importers import nmea_kernels as nk
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
class SentenceBlock:
    """Usable sentences of a block of log lines, in file order, as spans of one buffer.

    Attributes
    ----------
    path : str
        File the sentences came from.
    buf : ndarray of uint8
        The block's bytes (plus, after them, the bodies the regex splitter found).
    start, end : ndarray of int64, shape (n,)
        Byte span in *buf* of each sentence body: the text between ``$``/``!`` and
        ``*`` (no checksum), e.g. ``GPGGA,000000.70,...``; TSS1 records keep their ``:``.
    line_no : ndarray of int64, shape (n,)
        1-based line number of each sentence in its file.
    tag : ndarray of float64, shape (n,)
        Logger time tag, Unix seconds (UTC); NaN when the line has none.
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
    buf: np.ndarray
    start: np.ndarray
    end: np.ndarray
    line_no: np.ndarray
    tag: np.ndarray
    has_checksum: np.ndarray
    counts: dict[str, int] = field(default_factory=dict)
    tag_style: str | None = None
    no_checksums: bool = False

    @property
    def body(self) -> list[str]:
        """Sentence bodies as text (one Python string each: for tests and small logs)."""
        data = self.buf.tobytes()
        return [data[a:b].decode("latin-1") for a, b in zip(self.start, self.end, strict=True)]

    def address(self) -> list[str]:
        """First field of every sentence (``GPGGA``, ``PSXN``, ``:`` for TSS1)."""
        return [":" if b.startswith(":") else b.split(",", 1)[0] for b in self.body]


LogLines = SentenceBlock
"""The whole file as one block (what :func:`split_log` returns)."""


@dataclass
class RawBlock:
    """Sentences of a block before the file-wide checksum policy is applied.

    ``cs`` is ``CS_OK``/``CS_BAD``/``CS_NONE`` per sentence, ``tss`` marks TSS1 records
    (which never carry one); ``counts`` are the lines set aside whatever the policy,
    ``styles`` the logger tag styles seen and ``odd_prefix`` the sentences preceded by
    printable text that is no time tag.
    """

    buf: np.ndarray
    start: np.ndarray
    end: np.ndarray
    line_no: np.ndarray
    tag: np.ndarray
    cs: np.ndarray
    tss: np.ndarray
    counts: dict[str, int]
    styles: dict[str, int]
    odd_prefix: int

    def checksum_census(self) -> tuple[int, int]:
        """(NMEA sentences with a checksum, without one): what the policy is decided on."""
        nmea = ~self.tss
        given = self.cs != nk.CS_NONE
        return int(np.count_nonzero(nmea & given)), int(np.count_nonzero(nmea & ~given))


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


@dataclass
class _Found:
    """Sentences the regex splitter found in the lines the kernel handed over."""

    line: list[int] = field(default_factory=list)
    tag: list[float] = field(default_factory=list)
    body: list[str] = field(default_factory=list)
    cs: list[str | None] = field(default_factory=list)
    counts: dict[str, int] = field(default_factory=dict)
    styles: dict[str, int] = field(default_factory=dict)
    odd_prefix: int = 0

    def bump(self, key: str, n: int = 1) -> None:
        self.counts[key] = self.counts.get(key, 0) + n


def _regex_line(raw: str, number: int, found: _Found, cache: dict) -> None:
    """Split one line the kernel did not call plain (binary, spliced, TSS1, odd tag…)."""
    line = raw.rstrip("\r\n\t ")
    stripped = line.lstrip()
    if not stripped:
        found.bump("blank")
        return
    if stripped[0] in "#{" and not _NONPRINT.search(line):
        # Printable only: a binary fragment may begin with 0x23 '#' or 0x7B '{'.
        found.bump("comment" if stripped[0] == "#" else "json")
        return
    hit = _find_sentence(line)
    if hit is None:
        tss = _TSS1.search(line)
        if tss is None:
            found.bump("binary" if _NONPRINT.search(line) else "unparseable")
            return
        start, body, cs = tss.start(), tss.group(0), None
    else:
        start, body, cs = hit
    prefix = line[:start]
    tag = float("nan")
    fragment = _START.search(prefix)
    if fragment:
        # A truncated sentence spliced before this one: drop it, keep any tag.
        found.bump("spliced fragment")
        prefix = prefix[: fragment.start()]
    if prefix.strip():
        tag, style = parse_tag(prefix.strip(), cache)
        if style is not None:
            found.styles[style] = found.styles.get(style, 0) + 1
        elif _NONPRINT.search(prefix):
            found.bump("binary before sentence")
        else:
            found.odd_prefix += 1
    found.line.append(number)
    found.tag.append(tag)
    found.body.append(body)
    found.cs.append(cs)


def scan_block(buf: np.ndarray, first_line: int = 1) -> RawBlock:
    """Split a block of whole lines (uint8) into sentences, before the checksum policy.

    Plain lines are split by the compiled kernel (:mod:`nmea_kernels`), every other line
    by the regex splitter; *first_line* is the file's number of the block's first line.
    """
    line_start, line_end, status, b_start, b_end, cs, tag, style = nk.scan_lines(buf)
    plain = np.flatnonzero(status == nk.PLAIN)
    counts = {"lines": int(status.size)}
    blank = int(np.count_nonzero(status == nk.BLANK))
    found = _Found()
    if blank:
        found.bump("blank", blank)
    odd = np.flatnonzero(status == nk.FALLBACK)
    cache: dict = {}
    data = buf.tobytes() if odd.size else b""
    for i in odd:
        _regex_line(data[line_start[i]:line_end[i]].decode("latin-1"), int(first_line + i),
                    found, cache)
    counts.update(found.counts)
    styles = found.styles
    for code in np.unique(style[plain]) if plain.size else ():
        if code != nk.STYLE_NONE:
            styles[nk.STYLES[code]] = styles.get(nk.STYLES[code], 0) + int(
                np.count_nonzero(style[plain] == code))
    return _merge(buf, plain, first_line, (b_start, b_end, cs, tag), found, counts, styles)


def _merge(buf, plain, first_line, kernel, found: _Found, counts, styles) -> RawBlock:
    """Kernel and regex sentences together, in line order, bodies in one buffer."""
    b_start, b_end, cs, tag = kernel
    n_extra = len(found.body)
    starts = [b_start[plain]]
    ends = [b_end[plain]]
    states = [cs[plain]]
    if n_extra:
        extra = "".join(found.body).encode("latin-1")
        lengths = np.fromiter((len(b) for b in found.body), np.int64, n_extra)
        offs = buf.size + np.concatenate([[0], np.cumsum(lengths)[:-1]])
        buf = np.concatenate([buf, np.frombuffer(extra, np.uint8)])
        starts.append(offs)
        ends.append(offs + lengths)
        given = np.array([c is not None for c in found.cs], bool)
        state = np.full(n_extra, nk.CS_NONE, np.int8)
        with_cs = np.flatnonzero(given)
        if with_cs.size:
            computed = _xor_checksums([found.body[i] for i in with_cs])
            stated = np.array([int(found.cs[i], 16) for i in with_cs], dtype=np.uint8)
            state[with_cs] = np.where(computed == stated, nk.CS_OK, nk.CS_BAD)
        states.append(state)
    line_no = np.concatenate([plain + first_line, np.asarray(found.line, np.int64)])
    order = np.argsort(line_no, kind="stable") if n_extra else slice(None)
    tss = np.concatenate([np.zeros(plain.size, bool),
                          np.array([b.startswith(":") for b in found.body], bool)])
    return RawBlock(
        buf=buf, start=np.concatenate(starts)[order], end=np.concatenate(ends)[order],
        line_no=line_no[order],
        tag=np.concatenate([tag[plain], np.asarray(found.tag, np.float64)])[order],
        cs=np.concatenate(states)[order], tss=tss[order], counts=counts, styles=styles,
        odd_prefix=found.odd_prefix,
    )


def checksum_policy(n_with: int, n_without: int) -> bool:
    """True (accept sentences without checksum) when most of the file's carry none."""
    return n_without > 0 and n_without > n_with


def apply_policy(raw: RawBlock, no_checksums: bool, path: str = "<bytes>") -> SentenceBlock:
    """Drop bad checksums and (unless *no_checksums*) NMEA sentences without one.

    The returned block's ``counts`` hold this block's lines set aside, the checksum
    counts and ``sentences``; ``tag_style`` is left for the caller (file-wide).
    """
    counts = dict(raw.counts)
    keep = raw.cs != nk.CS_BAD
    bad = int(np.count_nonzero(~keep))
    if bad:
        counts["bad checksum"] = counts.get("bad checksum", 0) + bad
    without = ~raw.tss & (raw.cs == nk.CS_NONE)
    n_without = int(np.count_nonzero(without))
    if n_without and not no_checksums:
        # Most sentences carry a checksum: one without is a truncated fragment.
        keep &= ~without
        counts["missing checksum"] = counts.get("missing checksum", 0) + n_without
    elif n_without:
        counts["no checksum (accepted)"] = counts.get("no checksum (accepted)", 0) + n_without
    idx = np.flatnonzero(keep)
    counts["sentences"] = int(idx.size)
    return SentenceBlock(
        path=path, buf=raw.buf, start=raw.start[idx], end=raw.end[idx],
        line_no=raw.line_no[idx], tag=raw.tag[idx],
        has_checksum=(raw.cs[idx] != nk.CS_NONE) & ~raw.tss[idx], counts=counts,
        no_checksums=no_checksums,
    )


def tag_style_of(styles: dict[str, int]) -> str | None:
    """The file's logger tag style: the most frequent one (None without tags)."""
    return max(styles, key=styles.get) if styles else None


def odd_prefix_reason(tag_style: str | None) -> str:
    """Printable non-tag text before a sentence: a damaged tag in a tagged file,
    otherwise stray bytes glued on."""
    return "bad time tag" if tag_style else "junk before sentence"


def split_log(
    data: bytes,
    path: str = "<bytes>",
    *,
    progress: ProgressCallback | None = None,
    cancel: CancelToken | None = None,
) -> SentenceBlock:
    """Split raw log bytes (a whole, small file) into usable sentences and counts.

    Large files are read block by block by :mod:`log_stream`; this is the same split on
    one block.

    Returns
    -------
    SentenceBlock
        Sentences with valid (or, in a checksum-free file, absent) checksums.
    """
    check_cancel(cancel)
    report(progress, 0.0, "splitting sentences")
    raw = scan_block(np.frombuffer(data, np.uint8))
    no_checksums = checksum_policy(*raw.checksum_census())
    block = apply_policy(raw, no_checksums, path)
    block.tag_style = tag_style_of(raw.styles)
    if raw.odd_prefix:
        reason = odd_prefix_reason(block.tag_style)
        block.counts[reason] = block.counts.get(reason, 0) + raw.odd_prefix
    return block
