"""Motion-sensor records of a log: ``$PASHR`` attitude, TSS1, Seapath ``$PSXN,23``.

Sign conventions (HydroSync: roll + starboard down, pitch + bow up, heave + up):

* TSS1 ``:XXAAAA MHHHHQMRRRR MPPPP`` — XX horizontal acceleration (hex, 3.83 cm/s²),
  AAAA vertical acceleration (hex, 0.0625 cm/s²), then sign + heave in cm, a status
  letter (U/u unaided, G/g GPS-aided, H/h heading-aided, F/f fully aided; lower case =
  settling), sign + roll and sign + pitch in 0.01°. Heave is positive up ("above
  datum"), roll positive port up (= starboard down), pitch positive bow up (TSS1 as
  documented by NovAtel SPAN, Norwegian Subsea MRU and UHDAS/MAHRS notes) — no sign
  change. TSS1 carries no time and no heading.
* ``$PSXN,23,roll,pitch,heading,heave`` (Kongsberg Seatex Seapath): roll positive port
  side up, pitch positive bow up, heading true (degrees). Seapath documentation gives
  heave positive *down*; ``formats.md`` forbids guessing a sign, so the caller must
  state it (``heave_positive="down"`` for a standard Seapath set-up).
* ``$PASHR,hhmmss.sss,HHH.HH,T,RRR.RR,PPP.PP,heave,σroll,σpitch,σheading,GPSq,INSq``
  (OxTS / Applanix / NovAtel / Trimble attitude form): roll and pitch taken as
  port-up and bow-up positive, as written (Applanix POS MV can be set to output
  Tait-Bryan or "TSS" angles — they differ at second order in roll·pitch; the file
  does not say which). Heave is vendor- and set-up-specific (Trimble marks the field
  "reserved", often empty: such epochs are skipped as ``empty heave``), so the caller
  must state its sign. Ashtech's unrelated ``$PASHR,POS|SAT|MCA|…`` sentences (alphabetic
  first field) are recognised and counted, never read as attitude.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.importers import nmea_fields as nf
from hydrosync_core.importers import nmea_kernels as nk
from hydrosync_core.importers.nmea_lines import LogLines
from hydrosync_core.inputs import input_ok

_TSS1 = re.compile(
    r":([0-9A-Fa-f]{2})([0-9A-Fa-f]{4}) ([ +-])(\d{4})([A-Za-z ])([ +-])(\d{4}) ([ +-])(\d{4})"
)
TSS1_SETTLING = "flagged settling (kept)"
"""Counted while parsing; the import turns it into its warning (not a skip)."""

HEAVE_CONVENTION = {"TSS1": "up", "PSXN,23": None, "PASHR": "up"}
"""Heave sign fixed by the format's specification (None: must be given by the user).

TSS1 and the attitude form of $PASHR (Applanix/OxTS) define heave positive up; Seapath's
$PSXN,23 is documented positive down but is not a published standard, so the user
states it."""
DOCUMENTED_HEAVE = {"PSXN,23": "down (Seapath manual)", "PASHR": "up", "TSS1": "up"}


@dataclass
class MotionRecords:
    """Attitude epochs of one source, before time assembly.

    ``index`` sentence indices; ``tod`` UTC seconds of day (NaN when the format has no
    time); roll, pitch, heading in degrees (HydroSync conventions); heave in metres *as
    written in the file* (sign applied later); ``sigma`` optional dict of σ arrays (deg;
    not read: no analysis uses the sensor's stated σ).
    """

    source: str
    index: np.ndarray
    tod: np.ndarray
    roll: np.ndarray
    pitch: np.ndarray
    heading: np.ndarray
    heave: np.ndarray
    sigma: dict[str, np.ndarray] = field(default_factory=dict)
    skipped: dict[str, int] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)


def split_pashr(log: LogLines, index: np.ndarray) -> tuple[np.ndarray, int]:
    """Keep the attitude form of ``$PASHR`` (numeric time, ``T`` in field 3).

    Returns the attitude sentence indices and how many Ashtech (non-attitude) ones
    were set aside.
    """
    attitude = nk.pashr_attitude(log.buf, log.start, log.end, index)
    return index[attitude], int(np.count_nonzero(~attitude))


def parse_pashr(log: LogLines, index: np.ndarray) -> MotionRecords:
    """Parse attitude-form ``$PASHR`` sentences (already filtered by :func:`split_pashr`)."""
    heading, h_empty, h_bad = nf.floats(log, index, 2)
    roll, r_empty, r_bad = nf.floats(log, index, 4)
    pitch, p_empty, p_bad = nf.floats(log, index, 5)
    heave, v_empty, v_bad = nf.floats(log, index, 6)
    keep = np.ones(index.size, dtype=bool)
    skipped: dict[str, int] = {}
    nf.drop(skipped, "empty attitude field", h_empty | r_empty | p_empty, keep)
    nf.drop(skipped, "empty heave", v_empty, keep)
    nf.drop(skipped, "unparseable field", h_bad | r_bad | p_bad | v_bad, keep)
    tod = nf.tod_field(log, index, 1)
    return MotionRecords(
        "PASHR", index[keep], tod[keep], roll[keep], pitch[keep], heading[keep],
        heave[keep], {}, skipped,
    )


def parse_psxn23(
    log: LogLines, index: np.ndarray, quality_index: np.ndarray | None = None,
    carried_quality: float = np.nan,
) -> MotionRecords:
    """Parse ``$PSXN,23,roll,pitch,heading,heave``.

    When ``$PSXN,20`` quality sentences are present, epochs whose latest preceding
    roll/pitch quality (field 5) is 2 = invalid are dropped; *carried_quality* is the
    last one of the blocks before (file read block by block).
    """
    roll, r_empty, r_bad = nf.floats(log, index, 2)
    pitch, p_empty, p_bad = nf.floats(log, index, 3)
    heading, h_empty, h_bad = nf.floats(log, index, 4)
    heave, v_empty, v_bad = nf.floats(log, index, 5)
    keep = np.ones(index.size, dtype=bool)
    skipped: dict[str, int] = {}
    nf.drop(skipped, "empty attitude field", r_empty | p_empty | h_empty, keep)
    nf.drop(skipped, "empty heave", v_empty, keep)
    nf.drop(skipped, "unparseable field", r_bad | p_bad | h_bad | v_bad, keep)
    if quality_index is None:
        quality_index = np.zeros(0, np.int64)
    if quality_index.size or np.isfinite(carried_quality):
        rp_quality = nf.floats(log, quality_index, 5)[0]
        k = np.searchsorted(quality_index, index, side="right") - 1
        latest = np.where(k >= 0, rp_quality[np.maximum(k, 0)] if rp_quality.size else np.nan,
                          carried_quality)
        nf.drop(skipped, "roll/pitch quality invalid (PSXN,20)", latest == 2, keep)
    return MotionRecords(
        "PSXN,23", index[keep], np.full(int(keep.sum()), np.nan), roll[keep], pitch[keep],
        heading[keep], heave[keep], {}, skipped,
    )


def parse_tss1(log: LogLines, index: np.ndarray) -> MotionRecords:
    """Parse TSS1 records: heave (cm -> m, positive up), roll and pitch (0.01° -> °)."""
    heave, roll, pitch = (np.full(index.size, np.nan) for _ in range(3))
    status = []
    data = log.buf.tobytes()
    for j, i in enumerate(index):
        m = _TSS1.fullmatch(data[log.start[i]:log.end[i]].decode("latin-1"))
        if m is None:
            status.append("")
            continue
        g = m.groups()
        # Sign character is a space (positive) or '-'; magnitudes are 4-digit integers.
        heave[j] = (-1.0 if g[2] == "-" else 1.0) * int(g[3]) * 0.01
        roll[j] = (-1.0 if g[5] == "-" else 1.0) * int(g[6]) * 0.01
        pitch[j] = (-1.0 if g[7] == "-" else 1.0) * int(g[8]) * 0.01
        status.append(g[4])
    keep = np.isfinite(heave)
    skipped: dict[str, int] = {}
    if (~keep).any():
        skipped["unparseable field"] = int(np.count_nonzero(~keep))
    settling = sum(1 for s in status if s.islower())
    if settling:
        skipped[TSS1_SETTLING] = settling
    return MotionRecords(
        "TSS1", index[keep], np.full(int(keep.sum()), np.nan), roll[keep], pitch[keep],
        np.full(int(keep.sum()), np.nan), heave[keep], {}, skipped,
    )


def hdt_headings(log: LogLines, hdt_index: np.ndarray) -> np.ndarray:
    """True heading (deg) of ``$--HDT`` sentences *hdt_index* (NaN where unreadable)."""
    return nf.floats(log, hdt_index, 1)[0]


def heading_from_hdt(hdg: np.ndarray, times: np.ndarray, hdt_times: np.ndarray) -> np.ndarray:
    """True heading (deg) from ``$--HDT`` headings *hdg* at *hdt_times*, interpolated at
    *times*.

    Headings are unwrapped before linear interpolation so 359° -> 1° does not sweep
    through 180°; outside the HDT time span the result is NaN.
    """
    ok = np.isfinite(hdg) & np.isfinite(hdt_times)
    if np.count_nonzero(ok) < 2:
        return np.full(times.shape, np.nan)
    t, h = hdt_times[ok], hdg[ok]
    order = np.argsort(t, kind="stable")
    t, h = t[order], np.unwrap(np.radians(h[order]))
    out = np.degrees(np.interp(times, t, h, left=np.nan, right=np.nan)) % 360.0
    return out


def sniff_motion_source(path, max_bytes: int = 262_144) -> str | None:
    """The motion sentence a log mostly holds (``PSXN,23``, ``PASHR``, ``TSS1``), from its
    first *max_bytes*; None when none is recognised or the file cannot be read.

    Cheap enough to call while the user picks a file, so the Import dialog can preselect
    the sentence's documented heave sign for confirmation.
    """
    try:
        input_ok(path, "motion log")  # a FIFO would block the sniffing read
    except InputError:
        return None
    import re

    try:
        with open(path, "rb") as handle:
            text = handle.read(max_bytes).decode("ascii", "replace")
    except OSError:
        return None
    counts = {"PSXN,23": len(re.findall(r"\$[A-Z]{0,2}PSXN,23,", text)),
              "PASHR": len(re.findall(r"\$[A-Z]{0,2}PASHR,", text)),
              "TSS1": len(re.findall(r":[0-9A-Fa-f]{6} [ +-]\d{4}[A-Za-z ][ +-]\d{4} [ +-]\d{4}",
                                     text))}
    best = max(counts, key=counts.get)
    return best if counts[best] else None


def documented_heave_sign(source: str | None) -> str | None:
    """``"up"``/``"down"`` as the sentence's documentation states it (None if unknown)."""
    text = DOCUMENTED_HEAVE.get(source or "", "")
    return text.split()[0] if text else None
