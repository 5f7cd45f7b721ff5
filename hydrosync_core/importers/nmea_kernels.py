"""Compiled byte scanners of the NMEA log reader: lines, sentences, tags and fields.

The reader sees a log as a ``uint8`` block of whole lines. :func:`scan_lines` classifies
every line in one compiled pass and, for the common *plain* line, does all the work the
regex splitter of :mod:`nmea_lines` would do: it finds the ``$`` sentence, verifies its
checksum and parses the logger's time tag. A line the kernel does not call plain (binary
bytes, two sentence starts, a ``!`` or ``#``, a TSS1 record, an odd prefix…) is handed to
the regex splitter, so every oddity is still set aside and counted by the same code as
before; the kernel only takes the lines on which both would agree.

Plain line (after stripping trailing ``\\r\\n\\t`` and spaces): printable ASCII only,
exactly one ``$`` and no ``!``, a valid address ``[A-Z][A-Z0-9]{2,6},``, then either a
first ``*`` followed by two hex digits (checksum) or no ``*`` at all (no checksum); the
text before ``$``, spaces stripped, is empty or one of the three logger tags of
:mod:`nmea_lines` with a valid date and time.

Numbers are parsed as mantissa / 10**k with an integer mantissa below 2**53, which is the
correctly rounded value, i.e. exactly what ``float()`` gives; anything else (exponents,
``inf``, more digits) is flagged for ``float()`` in Python.

The kernels are long loops on purpose: splitting them into helper functions costs numba a
call per byte. numba is a dependency; the kernels compile on first use (cached on disk).
"""

from __future__ import annotations

import numpy as np
from numba import njit

PLAIN, BLANK, FALLBACK = 1, 0, 2
"""Line status written by :func:`scan_lines`."""
CS_OK, CS_BAD, CS_NONE = 0, 1, 2
"""Checksum state of a plain sentence."""
STYLE_NONE, STYLE_ISO, STYLE_MDY, STYLE_EPOCH = 0, 1, 2, 3
STYLES = (None, "iso", "mdy", "epoch")

_POW10 = np.array([10.0 ** k for k in range(23)])
_MAX_MANTISSA = 9007199254740992  # 2**53


@njit(cache=True, nogil=True)
def _hex(c):
    if 48 <= c <= 57:
        return c - 48
    if 65 <= c <= 70:
        return c - 55
    if 97 <= c <= 102:
        return c - 87
    return -1


@njit(cache=True, nogil=True)
def _days_from_civil(y, m, d):
    """Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's algorithm)."""
    y2 = y - 1 if m <= 2 else y
    era = (y2 if y2 >= 0 else y2 - 399) // 400
    yoe = y2 - era * 400
    mp = m - 3 if m > 2 else m + 9
    doy = (153 * mp + 2) // 5 + d - 1
    doe = yoe * 365 + yoe // 4 - yoe // 100 + doy
    return era * 146097 + doe - 719468


@njit(cache=True, nogil=True)
def _month_days(y, m):
    if m == 2:
        leap = (y % 4 == 0 and y % 100 != 0) or y % 400 == 0
        return 29 if leap else 28
    if m == 4 or m == 6 or m == 9 or m == 11:
        return 30
    return 31


@njit(cache=True, nogil=True)
def _digits(buf, i, n, e):
    """Integer value of exactly *n* digits at buf[i:], or -1 (also past *e*)."""
    if i + n > e:
        return -1
    v = 0
    for j in range(i, i + n):
        c = buf[j]
        if c < 48 or c > 57:
            return -1
        v = v * 10 + (c - 48)
    return v


@njit(cache=True, nogil=True)
def _seconds(buf, i, e, pow10):
    """Parse ``\\d\\d(\\.\\d*)?`` then ``[ ,;]*`` to the end; (value, ok)."""
    whole = _digits(buf, i, 2, e)
    if whole < 0:
        return 0.0, False
    i += 2
    mant = whole
    frac = 0
    if i < e and buf[i] == 46:
        i += 1
        while i < e and 48 <= buf[i] <= 57:
            mant = mant * 10 + (buf[i] - 48)
            frac += 1
            i += 1
            if frac > 15:
                return 0.0, False
    while i < e:
        c = buf[i]
        if c != 32 and c != 44 and c != 59:
            return 0.0, False
        i += 1
    return mant / pow10[frac], True


@njit(cache=True, nogil=True)
def _parse_tag(buf, s, e, pow10):
    """Logger tag in buf[s:e] (spaces stripped): (Unix seconds, style) or (nan, -1)."""
    # ISO 8601: YYYY-MM-DD[T ]hh:mm:ss(.s*)Z?[ ,;]*
    if e - s >= 19 and buf[s + 4] == 45 and buf[s + 7] == 45:
        y = _digits(buf, s, 4, e)
        mo = _digits(buf, s + 5, 2, e)
        d = _digits(buf, s + 8, 2, e)
        sep = buf[s + 10]
        hh = _digits(buf, s + 11, 2, e)
        mi = _digits(buf, s + 14, 2, e)
        if (y < 0 or mo < 0 or d < 0 or hh < 0 or mi < 0 or (sep != 84 and sep != 32)
                or buf[s + 13] != 58 or buf[s + 16] != 58):
            return np.nan, -1
        # optional Z right after the seconds: find where the seconds end
        j = s + 19
        if j < e and buf[j] == 46:
            j += 1
            while j < e and 48 <= buf[j] <= 57:
                j += 1
        stop = e
        if j < e and buf[j] == 90:  # 'Z'
            for q in range(j + 1, e):
                if buf[q] != 32 and buf[q] != 44 and buf[q] != 59:
                    return np.nan, -1
            stop = j
        sec, ok = _seconds(buf, s + 17, stop, pow10)
        style = 1
    elif e - s >= 19 and buf[s + 2] == 47 and buf[s + 5] == 47:
        mo = _digits(buf, s, 2, e)
        d = _digits(buf, s + 3, 2, e)
        y = _digits(buf, s + 6, 4, e)
        sep = buf[s + 10]
        hh = _digits(buf, s + 11, 2, e)
        mi = _digits(buf, s + 14, 2, e)
        if (y < 0 or mo < 0 or d < 0 or hh < 0 or mi < 0 or (sep != 44 and sep != 32)
                or buf[s + 13] != 58 or buf[s + 16] != 58):
            return np.nan, -1
        sec, ok = _seconds(buf, s + 17, e, pow10)
        style = 2
    else:
        # epoch seconds: \d{9,11}(\.\d*)?[ ,;]*
        j = s
        mant = 0
        while j < e and 48 <= buf[j] <= 57:
            mant = mant * 10 + (buf[j] - 48)
            j += 1
        n_int = j - s
        if n_int < 9 or n_int > 11:
            return np.nan, -1
        frac = 0
        if j < e and buf[j] == 46:
            j += 1
            while j < e and 48 <= buf[j] <= 57:
                mant = mant * 10 + (buf[j] - 48)
                frac += 1
                j += 1
                if mant > 9007199254740992:
                    return np.nan, -1
        for q in range(j, e):
            if buf[q] != 32 and buf[q] != 44 and buf[q] != 59:
                return np.nan, -1
        return mant / pow10[frac], 3
    if not ok or y < 1 or mo < 1 or mo > 12 or d < 1 or d > _month_days(y, mo):
        return np.nan, -1
    if hh > 23 or mi > 59 or sec >= 61.0:
        return np.nan, -1
    day = _days_from_civil(y, mo, d)
    return day * 86400.0 + hh * 3600.0 + mi * 60.0 + sec, style


@njit(cache=True, nogil=True)
def _scan(buf, n_lines, pow10):
    n = buf.size
    line_start = np.empty(n_lines, np.int64)
    line_end = np.empty(n_lines, np.int64)
    status = np.empty(n_lines, np.int8)
    body_start = np.zeros(n_lines, np.int64)
    body_end = np.zeros(n_lines, np.int64)
    cs = np.zeros(n_lines, np.int8)
    tag = np.full(n_lines, np.nan)
    style = np.zeros(n_lines, np.int8)
    i = 0
    k = 0
    while k < n_lines:
        s = i
        j = s
        # one pass to the newline: bytes outside printable ASCII, the '$' count and the
        # first '$', any '!', the first '*' after the '$'
        dollar = -1
        n_dollar = 0
        bang = False
        last_bad = -1
        first_ctl = -1  # \r or \t: allowed only in the stripped tail
        star = -1
        while j < n:
            c = buf[j]
            if c == 10:
                break
            if c == 13 or c == 9:
                if first_ctl < 0:
                    first_ctl = j
            elif c < 32 or c > 126:
                last_bad = j
            elif c == 36:
                n_dollar += 1
                if dollar < 0:
                    dollar = j
            elif c == 33:
                bang = True
            elif c == 42 and star < 0 and dollar >= 0:
                star = j
            j += 1
        line_start[k] = s
        line_end[k] = j
        i = j + 1
        e = j
        while e > s and (buf[e - 1] == 13 or buf[e - 1] == 9 or buf[e - 1] == 32):
            e -= 1
        if e == s:
            status[k] = 0
            k += 1
            continue
        status[k] = 2
        # printable only (the stripped tail aside); one '$', no '!'
        if last_bad >= 0 or 0 <= first_ctl < e or bang or n_dollar != 1:
            k += 1
            continue
        first = s
        while first < e and buf[first] == 32:
            first += 1
        if buf[first] == 35 or buf[first] == 123:  # '#' comment, '{' json
            k += 1
            continue
        # address [A-Z][A-Z0-9]{2,6},
        a = dollar + 1
        if a >= e or buf[a] < 65 or buf[a] > 90:
            k += 1
            continue
        m = a + 1
        while m < e and ((65 <= buf[m] <= 90) or (48 <= buf[m] <= 57)):
            m += 1
        if m >= e or buf[m] != 44 or m - a < 3 or m - a > 7:
            k += 1
            continue
        if star < 0:
            body_start[k] = a
            body_end[k] = e
            cs[k] = 2
        else:
            if star + 2 >= e:
                k += 1
                continue
            h1 = _hex(buf[star + 1])
            h2 = _hex(buf[star + 2])
            if h1 < 0 or h2 < 0:
                k += 1
                continue
            x = 0
            for q in range(a, star):
                x ^= buf[q]
            body_start[k] = a
            body_end[k] = star
            cs[k] = 0 if x == h1 * 16 + h2 else 1
        # prefix: the logger tag
        ps = s
        pe = dollar
        while ps < pe and buf[ps] == 32:
            ps += 1
        while pe > ps and buf[pe - 1] == 32:
            pe -= 1
        if pe > ps:
            t, st = _parse_tag(buf, ps, pe, pow10)
            if st < 0:
                k += 1
                continue
            tag[k] = t
            style[k] = st
        status[k] = 1
        k += 1
    return line_start, line_end, status, body_start, body_end, cs, tag, style


@njit(cache=True, nogil=True)
def _newlines(buf):
    n = 0
    for c in buf:
        if c == 10:
            n += 1
    return n


def count_lines(buf: np.ndarray) -> int:
    """Lines of a block as ``bytes.split(b"\\n")`` counts them, a final empty one dropped."""
    if buf.size == 0:
        return 0
    return int(_newlines(buf)) + (0 if buf[-1] == 10 else 1)


def scan_lines(buf: np.ndarray) -> tuple[np.ndarray, ...]:
    """Classify the lines of *buf* (uint8, whole lines).

    Returns
    -------
    line_start, line_end : ndarray of int64
        Byte span of each line without its ``\\n``.
    status : ndarray of int8
        ``BLANK``, ``PLAIN`` or ``FALLBACK`` (for the regex splitter).
    body_start, body_end : ndarray of int64
        Sentence body span (between ``$`` and ``*``) of plain lines.
    cs : ndarray of int8
        ``CS_OK``, ``CS_BAD`` or ``CS_NONE`` of plain lines.
    tag : ndarray of float64
        Logger time tag, Unix seconds (NaN when none).
    style : ndarray of int8
        Index into :data:`STYLES`.
    """
    return _scan(buf, count_lines(buf), _POW10)


@njit(cache=True, nogil=True)
def _field_span(buf, bs, be, k):
    """Span of comma-separated field *k* of buf[bs:be], spaces stripped; (-1, -1) if absent."""
    q = bs
    for _ in range(k):
        while q < be and buf[q] != 44:
            q += 1
        if q >= be:
            return -1, -1
        q += 1
    fe = q
    while fe < be and buf[fe] != 44:
        fe += 1
    fs = q
    while fs < fe and buf[fs] == 32:
        fs += 1
    while fe > fs and buf[fe - 1] == 32:
        fe -= 1
    return fs, fe


@njit(cache=True, nogil=True)
def _floats(buf, starts, ends, index, k, skip, pow10):
    n = index.size
    out = np.full(n, np.nan)
    state = np.zeros(n, np.int8)  # 0 number, 1 empty, 2 for float() in Python
    spans = np.full((n, 2), -1, np.int64)
    for r in range(n):
        i = index[r]
        fs, fe = _field_span(buf, starts[i], ends[i], k)
        if fs < 0 or fs == fe:
            state[r] = 1
            continue
        # 'EHT' prefix of a PTNL,GGK height, any case
        if (skip > 0 and fe - fs >= skip and (buf[fs] | 32) == 101
                and (buf[fs + 1] | 32) == 104 and (buf[fs + 2] | 32) == 116):
            fs += 3
            if fs == fe:
                state[r] = 1
                continue
        spans[r, 0] = fs
        spans[r, 1] = fe
        q = fs
        neg = False
        if q < fe and (buf[q] == 45 or buf[q] == 43):
            neg = buf[q] == 45
            q += 1
        mant = 0
        nd = 0
        frac = 0
        while q < fe and 48 <= buf[q] <= 57:
            mant = mant * 10 + (buf[q] - 48)
            nd += 1
            q += 1
            if nd > 17:
                break
        if q < fe and buf[q] == 46:
            q += 1
            while q < fe and 48 <= buf[q] <= 57:
                mant = mant * 10 + (buf[q] - 48)
                nd += 1
                frac += 1
                q += 1
                if nd > 17:
                    break
        if q != fe or nd == 0 or mant > 9007199254740992 or frac > 22:
            state[r] = 2
            continue
        v = mant / pow10[frac]
        out[r] = -v if neg else v
    return out, state, spans


def field_floats(buf, starts, ends, index, k: int, eht: bool = False):
    """Field *k* of sentences *index* as float64: (values, state, spans).

    ``state`` 0 = parsed, 1 = empty or missing, 2 = not a plain decimal (``spans`` gives
    its bytes for ``float()``). *eht* drops a leading ``EHT`` (PTNL,GGK height).
    """
    return _floats(buf, starts, ends, np.asarray(index, np.int64), k, 3 if eht else 0, _POW10)


@njit(cache=True, nogil=True)
def _text(buf, starts, ends, index, k, width):
    n = index.size
    out = np.zeros((n, width), np.uint8)
    for r in range(n):
        i = index[r]
        fs, fe = _field_span(buf, starts[i], ends[i], k)
        if fs < 0:
            continue
        for q in range(min(fe - fs, width)):
            out[r, q] = buf[fs + q]
    return out


def field_text(buf, starts, ends, index, k: int, width: int = 4) -> np.ndarray:
    """Field *k* of sentences *index*, spaces stripped, as ``S<width>`` (truncated)."""
    index = np.asarray(index, np.int64)
    return _text(buf, starts, ends, index, k, width).view(f"S{width}").reshape(index.size)


@njit(cache=True, nogil=True)
def _kinds(buf, starts, ends, width):
    n = starts.size
    out = np.zeros((n, width), np.uint8)
    for r in range(n):
        bs = starts[r]
        be = ends[r]
        if be > bs and buf[bs] == 58:  # ':' TSS1 record
            out[r, 0] = 84
            out[r, 1] = 83
            out[r, 2] = 83
            out[r, 3] = 49
            continue
        c = bs
        while c < be and buf[c] != 44:
            c += 1
        alen = c - bs
        two = alen == 4 and buf[bs] == 80 and (
            (buf[bs + 1] == 84 and buf[bs + 2] == 78 and buf[bs + 3] == 76)
            or (buf[bs + 1] == 83 and buf[bs + 2] == 88 and buf[bs + 3] == 78))
        if two:
            f2 = c + 1 if c < be else c
            while f2 < be and buf[f2] != 44:
                f2 += 1
            w = 0
            for q in range(bs, min(f2, be)):
                if w >= width:
                    break
                out[r, w] = buf[q]
                w += 1
            if c >= be and w < width:
                out[r, w] = 44  # "PTNL," with no second field
        elif alen > 0 and buf[bs] == 80:
            for q in range(min(alen, width)):
                out[r, q] = buf[bs + q]
        else:
            a0 = max(bs, c - 3)
            for q in range(a0, c):
                out[r, q - a0] = buf[q]
    return out


@njit(cache=True, nogil=True)
def _codes(keys, limit):
    """Number the distinct rows of *keys* in order of appearance (at most *limit*; -1
    beyond). The previous row's code is tried first: logs repeat kinds in runs."""
    n, width = keys.shape
    table = np.zeros((limit, width), np.uint8)
    codes = np.empty(n, np.int64)
    count = 0
    last = -1
    for r in range(n):
        found = -1
        if last >= 0:
            same = True
            for q in range(width):
                if keys[r, q] != table[last, q]:
                    same = False
                    break
            if same:
                found = last
        if found < 0:
            for c in range(count):
                same = True
                for q in range(width):
                    if keys[r, q] != table[c, q]:
                        same = False
                        break
                if same:
                    found = c
                    break
        if found < 0 and count < limit:
            table[count, :] = keys[r, :]
            found = count
            count += 1
        codes[r] = found
        last = found
    return codes, table[:count]


def kind_codes(buf, starts, ends, width: int = 16) -> tuple[np.ndarray, list[str]]:
    """Sentence kind of every body (``GGA``, ``PTNL,GGK``, ``PSXN,23``, ``TSS1``…).

    Standard sentences are keyed by their 3-letter type (talker dropped), proprietary
    ``PTNL``/``PSXN`` by address and first field, other proprietary ones by address.
    Returns a code per sentence and the kind names the codes index.
    """
    if starts.size == 0:
        return np.zeros(0, np.int64), []
    keys = _kinds(buf, starts, ends, width)
    codes, table = _codes(keys, 4096)
    if (codes < 0).any():  # more than 4096 kinds: binary noise read as addresses
        names, codes = np.unique(keys.view(f"S{width}").reshape(-1), return_inverse=True)
        return codes.reshape(-1), [v.decode("latin-1") for v in names]
    return codes, [bytes(row).rstrip(b"\0").decode("latin-1") for row in table]


@njit(cache=True, nogil=True)
def _pashr_attitude(buf, starts, ends, index):
    n = index.size
    out = np.zeros(n, np.bool_)
    for r in range(n):
        i = index[r]
        bs = starts[i]
        be = ends[i]
        commas = 0
        for q in range(bs, be):
            if buf[q] == 44:
                commas += 1
        if commas < 6:
            continue
        # field 1 raw: \d{6}(\.\d*)?
        q = bs
        while q < be and buf[q] != 44:
            q += 1
        q += 1
        f1 = q
        while q < be and 48 <= buf[q] <= 57:
            q += 1
        if q - f1 != 6:
            continue
        if q < be and buf[q] == 46:
            q += 1
            while q < be and 48 <= buf[q] <= 57:
                q += 1
        if q >= be or buf[q] != 44:
            continue
        q += 1
        while q < be and buf[q] != 44:  # field 2
            q += 1
        q += 1
        # field 3 raw == "T"
        out[r] = q + 1 < be and buf[q] == 84 and buf[q + 1] == 44
    return out


def pashr_attitude(buf, starts, ends, index) -> np.ndarray:
    """True for ``$PASHR`` bodies of the attitude form: ≥ 7 fields, field 1 a time
    ``\\d{6}(.\\d*)?`` and field 3 exactly ``T`` (not Ashtech's ``POS``/``SAT``…)."""
    return _pashr_attitude(buf, starts, ends, np.asarray(index, np.int64))
