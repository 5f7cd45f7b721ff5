"""RTKLIB .pos reader: every real file of the corpus, every form, and bad input."""

from __future__ import annotations

import numpy as np
import pytest
from _real_logs import needs_real, real

from hydrosync_core.errors import InputError
from hydrosync_core.geodesy import ecef_to_geodetic, geodetic_to_ecef
from hydrosync_core.importers.rtklib_pos import ned_covariance, read_pos

#: file -> (epochs, {Q: count}, form, time format); counts from real-logs/README.md.
REAL_POS = {
    "rtklibpy_demo5_b34f_f.pos": (4521, {1: 4449, 2: 72}, "llh", "calendar"),
    "rtklibpy_py_0315f.pos": (4521, {1: 1649, 2: 2872}, "llh", "week_tow"),
    "rtklibexplorer_demo1_out_enu.pos": (4230, {1: 3063, 2: 1167}, "enu", "calendar"),
    "matrtklib_kinematic_rover_rtk.pos": (5395, {1: 1799, 2: 3596}, "llh", "week_tow"),
    "matrtklib_static_rover_rtk_withvel.pos": (301, {1: 301}, "llh", "calendar"),
}


@needs_real
@pytest.mark.parametrize("name", sorted(REAL_POS))
def test_real_pos_files(name):
    epochs, qs, form, tfmt = REAL_POS[name]
    data = read_pos(real(f"pos/{name}"))
    assert data.epochs == epochs
    assert data.q_counts() == qs
    assert (data.form, data.time_format, data.time_system) == (form, tfmt, "GPST")
    c = data.columns
    assert np.all(np.diff(c["gps_s"]) > 0)
    assert np.isfinite(c["x"]).all()
    cov = ned_covariance(c)
    assert cov.shape == (epochs, 3, 3)
    assert (np.diagonal(cov, axis1=1, axis2=2) > 0).all()
    np.testing.assert_allclose(cov, np.swapaxes(cov, 1, 2))


@needs_real
def test_real_pos_values():
    d = read_pos(real("pos/rtklibpy_demo5_b34f_f.pos")).columns
    # first row 2020/12/24 21:28:42.000 = GPS week 2137, TOW 422922 (header: same)
    assert (int(d["week"][0]), d["time"][0]) == (2137, 422922.0)
    assert d["lat"][0] == 40.097025378 and d["sdu"][0] == 2.9108
    lat, lon, h = ecef_to_geodetic(np.column_stack([d["x"], d["y"], d["z"]]))
    assert np.abs(h - d["height"]).max() < 1e-4
    v = read_pos(real("pos/matrtklib_static_rover_rtk_withvel.pos")).columns
    assert {"vn", "ve", "vu", "sdvn", "sdvun"} <= set(v)
    assert v["vn"][0] == 0.00141 and v["sdvun"][-1] == -0.05051
    assert v["time"][0] == 116400.0  # header: week2320 116400.0s
    wk = read_pos(real("pos/matrtklib_kinematic_rover_rtk.pos")).columns
    assert (int(wk["week"][0]), wk["time"][0]) == (2270, 194670.0)


@needs_real
def test_real_enu_file_uses_glued_ref_pos():
    d = read_pos(real("pos/rtklibexplorer_demo1_out_enu.pos"))
    assert d.ref_llh == (40.086179918, -105.206044414, 1575.6355)
    c = d.columns
    ref = geodetic_to_ecef(*d.ref_llh)
    dist = np.linalg.norm(np.column_stack([c["x"], c["y"], c["z"]]) - ref, axis=1)
    np.testing.assert_allclose(dist, np.sqrt(c["e"] ** 2 + c["n"] ** 2 + c["u"] ** 2),
                               atol=1e-6)


LEGEND_XYZ = ("%  GPST          x-ecef(m)      y-ecef(m)      z-ecef(m)   Q  ns   sdx(m)   "
              "sdy(m)   sdz(m)  sdxy(m)  sdyz(m)  sdzx(m) age(s)  ratio\n")
ROW_XYZ = "2137 422922.000  -1282014.1234  -4723163.5678  4078460.1111   1.0  12  0.0100  " \
          "0.0100  0.0200  0.0010 -0.0020  0.0030   0.00   10.0\n"


def test_xyz_form_with_float_q(tmp_path):
    p = tmp_path / "x.pos"
    p.write_text(LEGEND_XYZ + ROW_XYZ + ROW_XYZ.replace("422922.000", "422923.000"))
    d = read_pos(p)
    assert d.form == "xyz" and d.q_counts() == {1: 2}
    assert d.columns["x"][0] == -1282014.1234
    assert 39 < d.columns["lat"][0] < 41
    cov = ned_covariance(d.columns)
    assert np.trace(cov[0]) == pytest.approx(0.01**2 + 0.01**2 + 0.02**2)


@pytest.mark.parametrize("text, message, line, field", [
    ("", "empty", None, None),
    ("% only a header\n", "no solution rows", None, None),
    (LEGEND_XYZ + ROW_XYZ.replace("  12  ", "  12  7  "), "expected 15 fields, found 16", 2,
     None),
    (LEGEND_XYZ + ROW_XYZ.replace("4078460.1111", "40x8460"), "not a number", 2, "z"),
    (LEGEND_XYZ + ROW_XYZ.replace(" 1.0 ", " 9 "), "quality flag 9", 2, "Q"),
    (LEGEND_XYZ + ROW_XYZ.replace("0.0200", "nan"), "not finite", 2, "sdz"),
    (LEGEND_XYZ + ROW_XYZ + ROW_XYZ, "repeated", 3, "time"),
    (LEGEND_XYZ + ROW_XYZ.replace("2137 422922.000", "2020/13/01 00:00:00"),
     "not a yyyy/mm/dd", 2, "time"),
    (LEGEND_XYZ + ROW_XYZ.replace("4078460.1111", "4078460111.1"), "not near the Earth", 2,
     "x-ecef"),
])
def test_bad_pos_files_name_line_and_field(tmp_path, text, message, line, field):
    p = tmp_path / "bad.pos"
    p.write_text(text)
    with pytest.raises(InputError) as info:
        read_pos(p)
    err = info.value
    assert message in err.message and err.line == line and err.field == field
    assert "\n" not in err.one_line() and str(p) in err.one_line()


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="no such file"):
        read_pos(tmp_path / "nope.pos")
