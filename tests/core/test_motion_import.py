"""Attitude log import: PASHR (OxTS), Seapath PSXN,23, TSS1 — real files with the
README's counts and hand-worked first records, plus synthetic sign/time cases."""

from __future__ import annotations

import calendar
from functools import reduce

import numpy as np
import pytest

from hydrosync_core.errors import InputError
from hydrosync_core.importers.log_import import import_attitude_log
from hydrosync_core.project import Project
from tests.core._real_logs import needs_real, real


def utc(y, mo, d, h=0, mi=0, s=0.0) -> float:
    return calendar.timegm((y, mo, d, h, mi, 0)) + s


def nmea(body: str) -> str:
    return f"${body}*{reduce(lambda a, c: a ^ ord(c), body, 0):02X}"


# ---------------------------------------------------------------- real logs


@needs_real
def test_oxts_pashr_records_and_heave_sign():
    path = real("motion/gpsd_rst39_oxts_pashr.log")
    cols, rep = import_attitude_log(path, heave_positive="up")
    assert rep.source == "PASHR" and rep.used == 100
    # $PASHR,204132.000,010.51,T,+00.39,-00.79,-00.84,... dated by the file's ZDA/RMC.
    assert cols["time"][0] == pytest.approx(utc(2014, 2, 19, 20, 41, 32.0))
    first = [cols[k][0] for k in ("heading", "roll", "pitch", "heave")]
    assert first == [10.51, 0.39, -0.79, -0.84]
    assert np.allclose(np.diff(cols["time"]), 0.04, atol=1e-6)  # 25 Hz
    down, rep_down = import_attitude_log(path, heave_positive="down")
    assert down["heave"][0] == 0.84 and rep_down.heave_positive == "down"
    assert any("against the PASHR specification" in w for w in rep_down.warnings)
    # PASHR's attitude form defines heave positive up: that is the default.
    default, rep_default = import_attitude_log(path)
    assert default["heave"][0] == -0.84 and rep_default.heave_positive == "up"


@needs_real
def test_seapath_psxn23_logger_time_and_sign():
    path = real("tagged/openrvdas_NBP1406_seap-2014-08-01.txt")
    cols, rep = import_attitude_log(path, heave_positive="down")
    assert rep.source == "PSXN,23" and rep.used == 714 and rep.time_source == "logger"
    # 2014-08-01T00:00:00.951000Z $PSXN,23,0.58,-1.09,218.83,0.78 (heave positive down)
    assert cols["time"][0] == pytest.approx(utc(2014, 8, 1, 0, 0, 0.951), abs=1e-6)
    assert [cols[k][0] for k in ("roll", "pitch", "heading")] == [0.58, -1.09, 218.83]
    assert cols["heave"][0] == -0.78
    with pytest.raises(InputError, match="down \\(Seapath manual\\)"):
        import_attitude_log(path)
    with pytest.raises(InputError, match="carries no time"):
        import_attitude_log(path, heave_positive="down", time_source="sentence")


@needs_real
def test_seapath_330_count():
    cols, rep = import_attitude_log(real("tagged/openrvdas_NBP1406_s330-2014-08-01.txt"),
                                    heave_positive="down")
    assert rep.used == 625 and cols["heave"][0] == -0.58


@needs_real
def test_healy_tss1_excerpt():
    cols, rep = import_attitude_log(real("motion/ncei_healy_mru_tss1_EXCERPT.txt"))
    # 3 lines, two share the epoch tag 1535243706.532: the later duplicate is dropped.
    assert rep.source == "TSS1" and rep.used == 2 and rep.skipped["duplicate time"] == 1
    assert cols["time"].tolist() == [1535243706.515, 1535243706.532]
    assert cols["heave"].tolist() == [-0.03, -0.03]
    assert cols["roll"].tolist() == [0.07, 0.06]
    assert cols["pitch"].tolist() == [-0.56, -0.56]
    assert np.isnan(cols["heading"]).all() and any("no heading" in w for w in rep.warnings)


@pytest.mark.parametrize(("name", "reason"), [
    ("nmea/gpsd_ac12_binary.log", "PASHR non-attitude \\(Ashtech\\) 13"),
    ("nmea/pynmeagps_trimble_nmea_MANUAL_EXAMPLES.log", "PASHR: empty heave 1"),
    ("motion/gpsd_hemi.log", "HDT 215"),
])
@needs_real
def test_logs_without_usable_attitude_raise(name, reason):
    with pytest.raises(InputError, match=reason):
        import_attitude_log(real(name), heave_positive="up")


# ---------------------------------------------------------------- synthetic


def test_tss1_signs_and_heading_from_hdt(tmp_path):
    # NovAtel's documented example ':00FFCA -0003F-0325  0319' -> heave -0.03 m,
    # roll -3.25 deg, pitch +3.19 deg; heading from the logger-tagged HDT, interpolated.
    path = tmp_path / "tss1.log"
    path.write_text("\n".join([
        f"1600000100.0 {nmea('HEHDT,359.0,T')}",
        "1600000100.5\t:00FFCA -0003F-0325  0319",
        "1600000100.6\t:000064  0120f 0007 -0056",
        f"1600000101.0 {nmea('HEHDT,1.0,T')}",
    ]) + "\n")
    cols, rep = import_attitude_log(path)
    assert cols["time"].tolist() == [1600000100.5, 1600000100.6]
    assert cols["heave"].tolist() == pytest.approx([-0.03, 1.20])
    assert cols["roll"].tolist() == pytest.approx([-3.25, 0.07])
    assert cols["pitch"].tolist() == pytest.approx([3.19, -0.56])
    # 359 -> 1 deg through north: halfway is 0, 0.6 of the way is 0.2 deg.
    assert min(cols["heading"][0], 360.0 - cols["heading"][0]) == pytest.approx(0.0, abs=1e-6)
    assert cols["heading"][1] == pytest.approx(0.2, abs=1e-6)
    assert any("settling" in w for w in rep.warnings)
    down, rep = import_attitude_log(path, heave_positive="down")
    assert down["heave"].tolist() == pytest.approx([0.03, -1.20])
    assert any("against the TSS1 specification" in w for w in rep.warnings)


def test_pashr_midnight_with_zda_and_ashtech_forms(tmp_path):
    path = tmp_path / "pashr.nmea"
    path.write_text("\n".join([
        nmea("GPZDA,235959.90,31,12,2020,,"),
        nmea("PASHR,235959.960,090.00,T,+01.00,-02.00,+00.10,0.01,0.01,0.05,2,1"),
        nmea("PASHR,POS,0,05,235959.00,3723.00,N,12200.00,W,00010.0,,000.0,000.0,+000.0"),
        nmea("PASHR,000000.000,090.50,T,+01.10,-02.10,-00.20,0.01,0.01,0.05,2,1"),
    ]) + "\n")
    cols, rep = import_attitude_log(path, heave_positive="up")
    assert cols["time"].tolist() == pytest.approx([utc(2020, 12, 31, 23, 59, 59.96),
                                                   utc(2021, 1, 1)])
    assert cols["heave"].tolist() == [0.10, -0.20]
    assert rep.skipped["PASHR non-attitude (Ashtech)"] == 1


def test_psxn20_invalid_quality_dropped(tmp_path):
    path = tmp_path / "psxn.log"
    path.write_text("\n".join([
        f"1600001000.0 {nmea('PSXN,20,0,0,0,0')}",
        f"1600001000.1 {nmea('PSXN,23,1.0,2.0,3.0,0.5')}",
        f"1600001000.2 {nmea('PSXN,20,0,0,0,2')}",
        f"1600001000.3 {nmea('PSXN,23,9.0,9.0,9.0,9.0')}",
    ]) + "\n")
    cols, rep = import_attitude_log(path, heave_positive="down")
    assert cols["roll"].tolist() == [1.0] and cols["heave"].tolist() == [-0.5]
    assert rep.skipped["PSXN,23: roll/pitch quality invalid (PSXN,20)"] == 1


def test_store_puts_report_attrs(tmp_path):
    from hydrosync_core.importers.log_import import store_attitude_log

    path = tmp_path / "psxn.log"
    path.write_text("\n".join(f"{1600001000 + k}.0 {nmea(f'PSXN,23,0.{k},0.0,10.0,0.{k}')}"
                              for k in range(5)) + "\nnot a sentence\n")
    project = Project.new("t")
    message = store_attitude_log(project, "raw/attitude", path, heave_positive="up")
    assert "5 PSXN,23 records" in message
    attrs = project.attrs("raw/attitude")
    assert attrs["records_used"] == 5 and attrs["lines_read"] == 6
    assert attrs["skipped: unparseable"] == 1
    assert project.get_table("raw/attitude")["heave"].tolist() == [0.0, 0.1, 0.2, 0.3, 0.4]


def test_cli_import_logs_with_heave_option(tmp_path, capsys):
    from hydrosync_core.cli import main

    log = tmp_path / "seapath.log"
    gga = "GPGGA,00000{k}.40,2200.0,S,01756.0,W,1,10,0.9,1.{k},M,3.0,M,,"
    log.write_text("\n".join(
        f"2014-08-01T00:00:0{k}.500000Z {nmea(f'PSXN,23,0.{k},0.0,10.0,0.{k}')}\n"
        f"2014-08-01T00:00:0{k}.600000Z {nmea(gga.format(k=k))}"
        for k in range(4)) + "\n")
    project = tmp_path / "p.h5"
    assert main(["import", str(project), "--attitude_log", str(log)]) == 2
    assert "heave sign of PSXN,23 must be stated" in capsys.readouterr().err
    assert not project.exists()
    assert main(["import", str(project), "--gnss_log", str(log), "--attitude_log", str(log),
                 "--heave-positive", "down"]) == 0
    with Project.open(project) as p:
        assert p.get_table("raw/attitude")["heave"].tolist() == [0.0, -0.1, -0.2, -0.3]
        gnss = p.get_table("raw/gnss")
        assert gnss["height"].tolist() == pytest.approx([4.0, 4.1, 4.2, 4.3])
        assert p.attrs("raw/gnss")["records_used"] == 4
