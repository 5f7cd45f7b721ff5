"""NMEA GNSS log import: real receiver/logger files (counts from the corpus README) and
small synthetic logs with known answers (checksums, geoid, midnight, rollover, tags)."""

from __future__ import annotations

import calendar
from functools import reduce

import numpy as np
import pytest

from hydrosync_core.errors import InputError
from hydrosync_core.importers.log_import import import_attitude_log, import_gnss_log
from hydrosync_core.importers.nmea_lines import split_log
from tests.core._real_logs import all_files, needs_real, real, run_with_timeout


def utc(y, mo, d, h=0, mi=0, s=0.0) -> float:
    return calendar.timegm((y, mo, d, h, mi, 0)) + s


def nmea(body: str, *, lower: bool = False, wrong: bool = False) -> str:
    cs = reduce(lambda a, c: a ^ ord(c), body, 0) ^ (1 if wrong else 0)
    return f"${body}*{cs:02x}" if lower else f"${body}*{cs:02X}"


def gga(t: str, alt: str = "10.000", sep: str = "-30.000", q: int = 4) -> str:
    return f"GPGGA,{t},4530.0000,S,17030.0000,E,{q},12,0.8,{alt},M,{sep},M,,"


# ---------------------------------------------------------------- real logs


@needs_real
def test_rtk_log_counts_and_heights():
    cols, rep = import_gnss_log(real("nmea/gpsd_nmea-rtk.log"))
    assert rep.used == 122 and rep.sentence_counts["GGA"] == 122
    q, n = np.unique(cols["quality"], return_counts=True)
    assert dict(zip(q.tolist(), n.tolist(), strict=True)) == {2.0: 104, 4.0: 18}
    # First GGA of the file, worked by hand: h = altitude + geoid separation (-31.442).
    first = next(line for line in real("nmea/gpsd_nmea-rtk.log").read_text().splitlines()
                 if "GGA" in line)
    f = first.split(",")
    assert cols["height"][0] == pytest.approx(float(f[9]) + float(f[11]), abs=1e-9)
    assert float(f[11]) == -31.442
    assert rep.time_source == "sentence" and np.all(np.diff(cols["time"]) > 0)


@pytest.mark.parametrize(("name", "count", "quality"), [
    ("nmea/gpsd_ublox-zed-f9p-nmea.log", 29, None),
    ("nmea/gpsd_ublox-neo-m9n-nmea.log", 61, 2),
    ("nmea/gpsd_skytraq-dgps.log", 96, 2),
    ("nmea/gpsd_skytraq-PX1172RH_DS.log", 9, 5),
    ("nmea/gpsd_ublox-zed-f9r.log", 30, 5),
    ("nmea/gpsd_ublox-zed-f9p_hpg1.11.log", 655, 1),
    ("nmea/gpsd_isync.log", 12, None),
    ("nmea/gpsd_ac12_binary.log", 5, None),
    ("nmea/gpsd_nmea-fuzzy-cases.log", 14, None),
    ("nmea/pynmeagps_pygpsdata-mixed.log", 2, None),
    ("motion/gpsd_rst39_oxts_pashr.log", 40, 2),
    ("motion/gpsd_hemi.log", 215 - 194, 1),
    ("tagged/openrvdas_NBP1406_seap-2014-08-01.txt", 715, None),
    ("tagged/openrvdas_NBP1406_s330-2014-08-01.txt", 625, None),
    ("tagged/openrvdas_NBP1406_PCOD-2014-08-01.txt", 1000, None),
    ("tagged/r2r_nav03_NEMA-Serial_20101005-122347.Raw", 516, None),
])
@needs_real
def test_real_gga_counts(name, count, quality):
    cols, rep = import_gnss_log(real(name))
    assert rep.used == count
    assert np.all(np.isfinite(cols["height"])) and np.all(np.diff(cols["time"]) > 0)
    if quality is not None:
        assert np.all(cols["quality"] == quality)


@needs_real
def test_gst_sigma_attached():
    cols, _ = import_gnss_log(real("nmea/gpsd_skytraq-dgps.log"))
    assert "sigma_h" in cols and np.isfinite(cols["sigma_h"]).sum() == 96
    first_gst = next(line for line in real("nmea/gpsd_skytraq-dgps.log").read_text().splitlines()
                     if "GST" in line)
    assert cols["sigma_h"][0] == pytest.approx(float(first_gst.split("*")[0].split(",")[8]))


@needs_real
def test_tagged_seapath_logger_time_and_empty_geoid():
    cols, rep = import_gnss_log(real("tagged/openrvdas_NBP1406_seap-2014-08-01.txt"))
    assert rep.time_source == "logger"
    assert cols["time"][0] == pytest.approx(utc(2014, 8, 1, 0, 0, 0.814), abs=1e-6)
    assert cols["height"][0] == pytest.approx(1.04)  # empty geoid -> N = 0, warned
    assert any("empty geoid" in w and "715" in w for w in rep.warnings)
    assert rep.logger_minus_sentence_s == pytest.approx(0.117, abs=0.01)
    assert rep.skipped == {"other sentence types": 714 * 5}  # VTG, HDT, PSXN,20/22/23
    with pytest.raises(InputError, match="empty geoid separation 715"):
        import_gnss_log(real("tagged/openrvdas_NBP1406_seap-2014-08-01.txt"),
                        empty_geoid="skip")


@needs_real
def test_s330_geoid_and_negative_altitude():
    cols, _ = import_gnss_log(real("tagged/openrvdas_NBP1406_s330-2014-08-01.txt"))
    assert cols["height"][0] == pytest.approx(-2.76 + 4.67)
    assert cols["lat"][0] == pytest.approx(-(22 + 0.110899 / 60))
    assert cols["lon"][0] == pytest.approx(-(17 + 56.359432 / 60))


@needs_real
def test_pcod_week_rollover_and_midnight():
    path = real("tagged/openrvdas_NBP1406_PCOD-2014-08-01.txt")
    cols, rep = import_gnss_log(path, time_source="sentence")
    assert any("1024 weeks" in w for w in rep.warnings)
    # GGA 23:59:59.226 logged at 00:00:00.241 on 2014-08-01 belongs to 2014-07-31.
    assert cols["time"][0] == pytest.approx(utc(2014, 7, 31, 23, 59, 59.226), abs=1e-6)
    assert cols["height"][0] == pytest.approx(33.6 - 2.6)
    assert rep.logger_minus_sentence_s == pytest.approx(1.015, abs=0.05)


@needs_real
def test_r2r_no_checksums_flagged():
    cols, rep = import_gnss_log(real("tagged/r2r_nav03_NEMA-Serial_20101005-122347.Raw"))
    assert any("no checksums" in w for w in rep.warnings)
    assert cols["height"][0] == pytest.approx(196 - 32)
    assert cols["time"][0] == pytest.approx(utc(2010, 10, 5, 13, 2, 28.703), abs=1e-6)


@needs_real
def test_trimble_ggk_ellipsoidal_height():
    cols, rep = import_gnss_log(real("nmea/pynmeagps_trimble_nmea_MANUAL_EXAMPLES.log"))
    assert rep.source == "PTNL,GGK" and rep.used == 1
    assert cols["height"][0] == pytest.approx(150.790)
    assert cols["quality"][0] == 2  # GGK 5 (SBAS) -> GGA 2
    assert cols["time"][0] == pytest.approx(utc(2010, 5, 19, 10, 29, 39.0))


@pytest.mark.parametrize(("name", "reason"), [
    ("nmea/gpsd_polarx2.log", "empty altitude 5"),
    ("motion/gpsd_saab-r4.log", "empty altitude 12"),
    ("nmea/pynmeagps_pygpsdata-nmeabadck.log", "bad checksum 2"),
    ("nmea/gpsd_sounder.log", "sentences found: DBT 122, GLL 122"),
])
@needs_real
def test_real_files_without_heights_raise(name, reason):
    with pytest.raises(InputError, match=reason) as info:
        import_gnss_log(real(name))
    assert real(name).name in str(info.value)


@pytest.mark.parametrize("path", all_files("nmea", "motion", "tagged", "pos"),
                         ids=lambda p: p.name)
def test_every_real_log_imports_or_raises_input_error(path):
    for func, kwargs in ((import_gnss_log, {}), (import_attitude_log, {"heave_positive": "up"})):
        try:
            cols, rep = run_with_timeout(lambda f=func, k=kwargs: f(path, **k), timeout=10)
        except InputError as exc:
            assert path.name in str(exc)
            continue
        assert rep.used >= 1 and len(cols["time"]) == rep.used
        assert np.all(np.isfinite(cols["time"]))


@needs_real
def test_one_megabyte_log_counts_every_sentence():
    """The 1 MB tagged logger file: every GGA and GLL sentence is counted (independent count
    by a regular expression over the raw bytes); its speed is in benchmarks/bench_log_import.py."""
    import re

    path = real("tagged/r2r_nav03_NEMA-Serial_20101005-122347.Raw")
    raw = path.read_bytes()
    assert len(raw) > 1_000_000
    cols, rep = run_with_timeout(lambda: import_gnss_log(path), timeout=60)
    assert rep.sentence_counts["GGA"] == len(re.findall(rb"\$..GGA,", raw)) == 516
    assert rep.sentence_counts["GLL"] == len(re.findall(rb"\$..GLL,", raw)) == 10387
    assert rep.used == len(cols["time"]) == 516


# ---------------------------------------------------------------- synthetic


def test_checksums_upper_lower_bad_and_missing(tmp_path):
    lines = [
        nmea(gga("120000.00", "10.0")),
        nmea(gga("120001.00", "11.0"), lower=True),
        nmea(gga("120002.00", "12.0"), wrong=True),
        "$" + gga("120003.00", "13.0"),  # no checksum in a checksummed file: truncated
        nmea(gga("120004.00", "14.0")),
    ]
    path = tmp_path / "cs.nmea"
    path.write_text("\r\n".join(lines) + "\r\n")
    cols, rep = import_gnss_log(path)
    assert cols["height"].tolist() == pytest.approx([-20.0, -19.0, -16.0])
    assert rep.skipped["bad checksum"] == 1 and rep.skipped["missing checksum"] == 1


def test_file_without_any_checksum_is_accepted_and_flagged(tmp_path):
    path = tmp_path / "nocs.nmea"
    path.write_text("\n".join("$" + gga(f"1200{s:02d}.00") for s in range(5)) + "\n")
    cols, rep = import_gnss_log(path)
    assert rep.used == 5 and any("no checksums" in w for w in rep.warnings)
    assert split_log(path.read_bytes()).no_checksums


def test_missing_geoid_zero_or_skip(tmp_path):
    path = tmp_path / "geoid.nmea"
    path.write_text("\n".join([nmea(gga("000001.0", "5.0", "")),
                               nmea(gga("000002.0", "6.0", "2.5"))]) + "\n")
    cols, rep = import_gnss_log(path)
    assert cols["height"].tolist() == [5.0, 8.5]
    assert any("1 GGA epochs have an empty geoid" in w for w in rep.warnings)
    cols, rep = import_gnss_log(path, empty_geoid="skip")
    assert cols["height"].tolist() == [8.5]
    assert rep.skipped["GGA: empty geoid separation"] == 1


def test_logger_tag_layouts_and_noise(tmp_path):
    base = utc(2021, 3, 4, 23, 59, 59.5)
    path = tmp_path / "mixed.log"
    path.write_bytes(b"\r\n".join([
        b"# comment header",
        b'{"class":"VERSION"}',
        b"2021-03-04T23:59:59.500000Z " + nmea(gga("235959.40")).encode(),
        b"\x00\xb5b\x01\x07$\xff\xfe binary junk",
        b"03/05/2021,00:00:00.500," + nmea(gga("000000.40")).encode(),
        b"1614902401.5\t" + nmea(gga("000001.40")).encode(),
        b"2021-03-05T00:00:02.500Z $GPGSV,3,1,12,0" + nmea(gga("000002.40")).encode(),
    ]) + b"\n")
    cols, rep = import_gnss_log(path, time_source="logger")
    assert cols["time"].tolist() == pytest.approx([base, base + 1, base + 2, base + 3])
    assert rep.skipped["comment"] == 1 and rep.skipped["json"] == 1
    assert rep.skipped["binary"] == 1 and rep.skipped["spliced fragment"] == 1
    # Sentence time across midnight, dated by the logger: 23:59:59.4 stays on 4 March.
    cols, rep = import_gnss_log(path, time_source="sentence")
    assert cols["time"].tolist() == pytest.approx([base - 0.1 + k for k in range(4)])
    assert rep.logger_minus_sentence_s == pytest.approx(0.1)


def test_zda_dates_midnight_and_rollover(tmp_path):
    zda = nmea("GPZDA,235959.00,15,12,1994,00,00")  # 2014-07-31 minus 1024 weeks
    lines = [f"2014-07-31T23:59:59.100Z {zda}",
             f"2014-07-31T23:59:59.200Z {nmea(gga('235959.00'))}",
             f"2014-08-01T00:00:00.200Z {nmea(gga('000000.00'))}"]
    path = tmp_path / "zda.log"
    path.write_text("\n".join(lines) + "\n")
    cols, rep = import_gnss_log(path, time_source="sentence")
    assert cols["time"].tolist() == pytest.approx([utc(2014, 7, 31, 23, 59, 59.0),
                                                   utc(2014, 8, 1)])
    assert any("1024 weeks" in w for w in rep.warnings)


def test_no_date_unwraps_midnight(tmp_path):
    path = tmp_path / "nodate.nmea"
    path.write_text("\n".join(nmea(gga(t)) for t in ("235959.0", "000000.0", "000001.0")))
    cols, rep = import_gnss_log(path)
    assert cols["time"].tolist() == [86399.0, 86400.0, 86401.0]
    assert any("no date" in w for w in rep.warnings)


def test_duplicates_and_no_fix(tmp_path):
    path = tmp_path / "dup.nmea"
    path.write_text("\n".join([nmea(gga("010000.0")), nmea(gga("010000.0", "99")),
                               nmea(gga("010001.0", q=0))]) + "\n")
    cols, rep = import_gnss_log(path)
    assert cols["height"].tolist() == [-20.0]
    assert rep.skipped["duplicate time"] == 1 and rep.skipped["GGA: no fix"] == 1


def test_bad_inputs(tmp_path):
    with pytest.raises(InputError, match="no such file"):
        import_gnss_log(tmp_path / "missing.log")
    empty = tmp_path / "empty.log"
    empty.write_bytes(b"")
    with pytest.raises(InputError, match="empty"):
        import_gnss_log(empty)
    junk = tmp_path / "junk.bin"
    junk.write_bytes(bytes(range(256)) * 40)
    with pytest.raises(InputError, match="no usable GNSS"):
        import_gnss_log(junk)
    plain = tmp_path / "plain.nmea"
    plain.write_text(nmea(gga("010000.0")) + "\n")
    with pytest.raises(InputError, match="no logger time tag"):
        import_gnss_log(plain, time_source="logger")


@needs_real
def test_damaged_copies_never_crash(tmp_path):
    """Truncated / byte-flipped copies (in tmp_path) import or raise InputError only."""
    rng = np.random.default_rng(5)
    sources = [real("nmea/gpsd_ublox-zed-f9r.log"), real("nmea/pynmeagps_pygpsdata-um981.log"),
               real("tagged/openrvdas_NBP1406_PCOD-2014-08-01.txt"),
               real("motion/gpsd_rst39_oxts_pashr.log")]
    for k in range(24):
        data = bytearray(sources[k % len(sources)].read_bytes()[:60_000])
        data = data[: int(rng.integers(0, len(data) + 1))]
        for pos in rng.integers(0, max(len(data), 1), size=int(rng.integers(0, 30))):
            if pos < len(data):
                data[pos] = int(rng.integers(0, 256))
        path = tmp_path / f"damaged{k}.log"
        path.write_bytes(bytes(data))
        for func in (import_gnss_log, import_attitude_log):
            kwargs = {"heave_positive": "up"} if func is import_attitude_log else {}
            try:
                cols, rep = func(path, **kwargs)
            except InputError:
                continue
            assert rep.used == len(cols["time"]) >= 1


@needs_real
def test_line_splitter_on_real_oddities():
    def split(name):
        return split_log(real(name).read_bytes(), name)

    mbdp = split("tagged/openrvdas_NBP1406_mbdp-2014-08-01.txt")  # 1845 lower-case hex
    lower = sum(1 for line in real("tagged/openrvdas_NBP1406_mbdp-2014-08-01.txt")
                .read_text().splitlines() if any(c in "abcdef" for c in line[-2:]))
    assert lower == 1845 and mbdp.counts["sentences"] == 5000
    assert "bad checksum" not in mbdp.counts and mbdp.tag_style == "iso"
    gp02 = split("tagged/openrvdas_NBP1406_gp02-2014-08-01.txt")
    assert gp02.no_checksums and gp02.counts["sentences"] == 5000
    r2r = split("tagged/r2r_nav03_NEMA-Serial_20101005-122347.Raw")
    assert r2r.tag_style == "mdy" and r2r.has_checksum.sum() == 1  # the single RMC
    isync = split("nmea/gpsd_isync.log")
    assert isync.counts["spliced fragment"] == 1
    hpg = split("nmea/gpsd_ublox-zed-f9p_hpg1.11.log")
    assert sum(b.startswith("GNRMC") for b in hpg.body) == 655  # incl. RMC glued to binary
    healy = split("motion/ncei_healy_mru_tss1_EXCERPT.txt")
    assert healy.tag_style == "epoch" and healy.body[0] == ":000064 -0003U 0007 -0056"
