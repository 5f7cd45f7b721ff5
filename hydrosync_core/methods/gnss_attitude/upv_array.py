"""The UPV four-antenna car-roof array (real data): layout, reference readers, comparison.

Data set ``shared/data/upv-gnss4ant`` (UPV MUIGG course *Georreferenciación de sensores y
navegación*, practical 2, 2022, via github.com/Jovilero/P2; internal test data only — its
licence is unclear). Four network-RTK receivers at the corners of a 0.8 m × 0.8 m square on
a car roof, 1 Hz, 2022-10-20 15:30–15:55; an SBG Ellipse2-N MEMS INS on the same platform;
the course software's own array attitude. See the data set's ``SOURCE.md``.

What this module knows about the recording (all from ``SOURCE.md``):

- layout (body x forward, y right, z down, m): REC2 front left (0.4, −0.4, 0), REC3 front
  right (0.4, 0.4, 0), REC4 back left (−0.4, −0.4, 0), REC5 back right (−0.4, 0.4, 0);
  antennas are named by their file stems (``VRS-TR8-REC2_0``…);
- INS time tags are 18.0 s behind the GNSS ones (``t_GNSS = t_INS + 18 s``, GPS−UTC in
  2022); :func:`compare_all` re-estimates the offset from the heading and reports it;
- seconds may read ``9.999``: every time is rounded to 0.01 s;
- the recording's attitude file (``GNSS/Unified/…_ses0.geo``) writes pitch 0 when only two
  receivers were used and all-zero rows with none: only rows with ≥ 3 receivers are used;
- session 2 (car standing) is 15:39:00–15:39:59 INS time.

Angles everywhere in degrees, heading (yaw) 0–360, convention of the project (body FRD →
NED, ``R = Rz(heading)·Ry(pitch)·Rx(roll)``, which is the ZYX Euler convention of both the
course software and the INS).
"""

from __future__ import annotations

from datetime import datetime
from pathlib import Path

import numpy as np

from hydrosync_core.errors import InputError
from hydrosync_core.methods.gnss_attitude import compare as cmp

GPS_EPOCH = datetime(1980, 1, 6)
RECEIVERS = ("REC2", "REC3", "REC4", "REC5")
LAYOUT = {"REC2": [0.4, -0.4, 0.0], "REC3": [0.4, 0.4, 0.0], "REC4": [-0.4, -0.4, 0.0],
          "REC5": [-0.4, 0.4, 0.0]}
#: ``t_GNSS = t_INS + INS_CLOCK_OFFSET_S`` (SOURCE.md: found 18.0 s, = GPS−UTC in 2022).
INS_CLOCK_OFFSET_S = 18.0
#: Session 2, car standing (INS clock, time of day).
STATIC_INS = ("15:39:00", "15:39:59")
DATE = (2022, 10, 20)


def stem(receiver: str) -> str:
    return f"VRS-TR8-{receiver}_0"


def antennas() -> dict[str, list[float]]:
    """``{file stem: [x, y, z]}`` for ``antennas.json``."""
    return {stem(r): LAYOUT[r] for r in RECEIVERS}


def position_files(folder: str | Path) -> list[Path]:
    return [Path(folder) / "GNSS" / "Receivers" / f"{stem(r)}.geo" for r in RECEIVERS]


def gps_seconds(hms: str) -> float:
    """Seconds since 1980-01-06 of ``hh:mm:ss`` on the recording day (no leap seconds)."""
    h, m, s = (float(v) for v in hms.split(":"))
    return (datetime(*DATE) - GPS_EPOCH).total_seconds() + h * 3600 + m * 60 + s


def _calendar_table(path: Path, columns: int) -> tuple[np.ndarray, np.ndarray]:
    """(gps_s rounded to 0.01 s, values (N, columns)) of a headerless calendar table."""
    if not path.is_file():
        raise InputError(str(path), "no such file")
    try:
        a = np.loadtxt(path, ndmin=2)
    except ValueError as exc:
        raise InputError(str(path), f"not a numeric table: {str(exc)[:80]}") from None
    if a.shape[1] != columns:
        raise InputError(str(path), f"expected {columns} columns, found {a.shape[1]}")
    days = np.array([(datetime(int(y), int(mo), int(d)) - GPS_EPOCH).total_seconds()
                     for y, mo, d in a[:, :3]])
    t = np.round((days + a[:, 3] * 3600 + a[:, 4] * 60 + a[:, 5]) * 100.0) / 100.0
    return t, a


def read_unified(path: str | Path) -> dict[str, np.ndarray]:
    """The recording's own array attitude (17 columns), rows with ≥ 3 receivers.

    Returns ``gps_s``, ``heading`` (0–360), ``pitch``, ``roll`` (deg), ``receivers``.
    """
    t, a = _calendar_table(Path(path), 17)
    keep = a[:, 16] >= 3
    return {"gps_s": t[keep], "heading": np.mod(a[keep, 14], 360.0), "pitch": a[keep, 13],
            "roll": a[keep, 12], "receivers": a[keep, 16].astype(int)}


def read_ins(path: str | Path) -> dict[str, np.ndarray]:
    """INS attitude: ``ses0.geo`` (22 columns, 1 Hz) or ``sesN.dat`` (18 columns, 50 Hz).

    Times stay on the INS clock (add :data:`INS_CLOCK_OFFSET_S` for the GNSS clock).
    """
    p = Path(path)
    columns = 22 if p.suffix == ".geo" else 18
    t, a = _calendar_table(p, columns)
    return {"gps_s": t, "heading": np.mod(a[:, 14], 360.0), "pitch": a[:, 13],
            "roll": a[:, 12]}


def reference_angles(ref: dict) -> np.ndarray:
    return np.column_stack([ref["heading"], ref["pitch"], ref["roll"]])


def static_interval_gps() -> tuple[float, float]:
    """Session 2 (car standing) on the GNSS clock (gps_s)."""
    return (gps_seconds(STATIC_INS[0]) + INS_CLOCK_OFFSET_S,
            gps_seconds(STATIC_INS[1]) + INS_CLOCK_OFFSET_S)


def solve(folder: str | Path, params=None):
    """Read the four receiver files and solve every epoch (:func:`.pipeline.solve_array`)."""
    from hydrosync_core.importers.geo_positions import read_geo
    from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams
    from hydrosync_core.methods.gnss_attitude.pipeline import solve_array
    from hydrosync_core.methods.gnss_attitude.project_run import track_from_columns

    params = params or GnssAttitudeParams()
    tracks = {p.stem: track_from_columns(read_geo(p), str(p)) for p in position_files(folder)}
    return solve_array(tracks, antennas(), params)


def compare_all(folder: str | Path, params=None) -> dict:
    """Solve the array and compare every method with the INS and the recording's attitude.

    Returns a JSON-able dict:

    - ``counts``: the screening counts of the solution;
    - ``clock``: estimated offsets (s) of the INS (1 Hz whole run, 50 Hz session 4) and of
      the recording's attitude file, with the heading spread at the optimum;
    - ``references``: ``{reference: {method: summary}}`` (:func:`.compare.summarize`: the
      constant offset = inlier mean, the scatter = inlier std, outliers) over all epochs
      with ≥ 3 antennas, the documented 18.0 s INS offset applied;
    - ``static``: session 2 (car standing, 60 s): per method the scatter of each angle,
      the predicted std from the files' σ (RMS of the formal std) and the a-priori
      prediction, and the INS's own scatter over the same interval.
    """
    from hydrosync_core.methods.gnss_attitude.params import GnssAttitudeParams
    from hydrosync_core.methods.gnss_attitude.pipeline import statistics
    from hydrosync_core.methods.gnss_attitude.precision import predict

    folder = Path(folder)
    params = params or GnssAttitudeParams()
    sol = solve(folder, params)
    t = sol.gps_s
    refs = {
        "recording": (read_unified(folder / "GNSS/Unified/VRS-20-10-2022_ses0.geo"), 0.0),
        "ins_1hz": (read_ins(folder / "INS/INS-20-10-2022_ses0.geo"), INS_CLOCK_OFFSET_S),
        "ins_50hz_ses4": (read_ins(folder / "INS/INS-20-10-2022_ses4.dat"),
                          INS_CLOCK_OFFSET_S),
        "ins_50hz_ses2": (read_ins(folder / "INS/INS-20-10-2022_ses2.dat"),
                          INS_CLOCK_OFFSET_S),
    }
    lsq_heading = sol.methods["lsq"].angles_deg[:, 0]
    clock = {}
    for name in ("recording", "ins_1hz", "ins_50hz_ses4"):
        ref, _ = refs[name]
        off, spread = cmp.estimate_time_offset(t, lsq_heading, ref["gps_s"], ref["heading"],
                                               search_s=(-30.0, 30.0))
        clock[name] = {"offset_s": off, "heading_spread_deg": spread}
    references: dict = {}
    for name, (ref, offset) in refs.items():
        if name == "ins_50hz_ses2":
            continue
        references[name] = {
            m: cmp.compare(t, s.angles_deg, ref["gps_s"], reference_angles(ref), offset,
                           max_gap_s=1.5)
            for m, s in sol.methods.items()}
    lo, hi = static_interval_gps()
    week = np.floor(t / 604800.0) * 604800.0
    tow_lo, tow_hi = lo - week[0], hi - week[0]
    stats = statistics(sol, tow_lo, tow_hi)
    body = [antennas()[n] for n in sol.names]
    apriori = {m: predict(body, params.sigma_horizontal_m, params.sigma_vertical_m,
                          method=m).tolist() for m in ("lsq", "direct")}
    ins2, _ = refs["ins_50hz_ses2"]
    ti = ins2["gps_s"] + INS_CLOCK_OFFSET_S
    sel = (ti >= lo) & (ti <= hi)
    ins_scatter = {a: float(np.std(cmp.wrap180(ins2[a][sel] - np.median(ins2[a][sel])),
                                   ddof=1)) for a in cmp.ANGLES}
    in_static = (t >= lo) & (t <= hi)
    static_vs_ins = {m: cmp.compare(t, s.angles_deg, ins2["gps_s"], reference_angles(ins2),
                                    INS_CLOCK_OFFSET_S, max_gap_s=0.1, select=in_static)
                     for m, s in sol.methods.items()}
    return {"counts": sol.counts, "clock": clock, "references": references,
            "static": {"interval_tow_s": [tow_lo, tow_hi], "statistics": stats,
                       "apriori_predicted": apriori, "sigma_apriori_m":
                       [params.sigma_horizontal_m, params.sigma_vertical_m],
                       "ins_scatter": ins_scatter, "vs_ins_50hz": static_vs_ins}}


REFERENCE_LABELS = {"recording": "recording's attitude file (course software)",
                    "ins_1hz": "INS 1 Hz (ses0.geo, whole run)",
                    "ins_50hz_ses4": "INS 50 Hz (ses4.dat, driving)"}


def format_report(res: dict) -> str:
    """Plain-text tables of :func:`compare_all` (the benchmark prints this)."""
    lines = []
    c = res["counts"]
    lines.append(f"epochs {c['epochs']}, solved {c['solved']} (fewer than 3 antennas "
                 f"{c['too_few_antennas']}, with a dropped antenna "
                 f"{c['with_dropped_antenna']}, covariance fallback "
                 f"{c.get('cov_fallback', 0)})")
    lines.append("clock offsets from the heading (t_array = t_ref + offset): " + ", ".join(
        f"{k} {v['offset_s']:+.1f} s (spread {v['heading_spread_deg']:.2f} deg)"
        for k, v in res["clock"].items()))
    head = (f"{'reference':<16}{'method':<8}{'n':>6}{'out':>5}"
            + "".join(f"{a + ' mean/std (all)':>26}" for a in cmp.ANGLES))
    lines.append("\narray minus reference (deg): constant offset (inlier mean) / scatter "
                 "(inlier std) (std of all epochs); 'out' = gross outliers left out "
                 "(> max(5 robust sigma, 2 deg) from the median)")
    lines.append(head)
    for ref, per in res["references"].items():
        for m, s in per.items():
            cells = "".join(
                f"{s[a]['mean']:>+10.3f}/{s[a]['std']:.3f} ({s[a]['std_all']:6.3f})"
                if s[a]["mean"] is not None else f"{'-':>26}" for a in cmp.ANGLES)
            out = max((s[a]["outliers"] or 0) for a in cmp.ANGLES)
            lines.append(f"{ref:<16}{m:<8}{s['epochs']:>6}{out:>5}{cells}")
    st = res["static"]
    lines.append(f"\nstatic interval (session 2, car standing) TOW {st['interval_tow_s'][0]:.0f}"
                 f"-{st['interval_tow_s'][1]:.0f} s: scatter / predicted from the files' "
                 f"sigma / predicted a priori ({st['sigma_apriori_m'][0] * 100:.1f} cm h, "
                 f"{st['sigma_apriori_m'][1] * 100:.1f} cm v) (deg)")
    lines.append(f"{'method':<8}{'n':>5}" + "".join(f"{a:>26}" for a in cmp.ANGLES))
    for m, s in st["statistics"].items():
        ap = st["apriori_predicted"].get(m, st["apriori_predicted"]["lsq"])
        cells = "".join(f"{s[a]['std']:>10.3f}/{s[a]['predicted']:.3f}/{ap[i]:.3f}   "
                        if s[a]["std"] is not None else f"{'-':>26}"
                        for i, a in enumerate(cmp.ANGLES))
        lines.append(f"{m:<8}{s['epochs']:>5}{cells}")
    ins = st["ins_scatter"]
    lines.append("INS 50 Hz scatter over the same interval: " + ", ".join(
        f"{a} {ins[a]:.3f}" for a in cmp.ANGLES))
    return "\n".join(lines)
