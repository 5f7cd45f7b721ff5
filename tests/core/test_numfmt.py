"""The one number formatter: digits from σ, units, no "± 0.000", no "-0"."""

import pytest

from hydrosync_core import numfmt


@pytest.mark.parametrize("sigma, decimals", [
    (0.0005, 5), (0.00051, 5), (0.0123, 3), (0.0355, 3), (0.996, 1), (0.9996, 1),
    (1.4, 1), (12.0, 0), (350.0, -1), (0.0996, 2), (0.0994, 3),
])
def test_sigma_decimals_two_significant_digits(sigma, decimals):
    assert numfmt.sigma_decimals(sigma) == max(decimals, 0)


def test_value_sigma_reads_as_a_surveyor_expects():
    assert numfmt.value_sigma(0.12204, 0.0005, "s") == "0.12204 \u00b1 0.00050 s"
    assert numfmt.value_sigma(-0.2187, 0.0041, "s") == "-0.2187 \u00b1 0.0041 s"
    assert numfmt.value_sigma(1.23456, 0.0123, "\u00b0") == "1.235 \u00b1 0.012\u00b0"
    assert numfmt.value_sigma(0.5, 0.0, "m") == "0.500 \u00b1 0 m"
    assert numfmt.value_sigma(float("nan"), 0.1) == numfmt.MISSING
    assert numfmt.value_sigma(2.0, None, "m", decimals=2) == "2.00 m"
    assert not numfmt.value_sigma(0.122, 0.0005, "s").endswith("\u00b1 0.000 s")
    assert numfmt.value_sigma(0.815, 0.02, "\u00b0", sign=True) == "+0.815 \u00b1 0.020\u00b0"
    assert numfmt.value_sigma(0.1, 0.09996) == "0.10 \u00b1 0.10"


def test_quantity_switches_to_milli_units_when_sigma_is_small():
    assert numfmt.quantity(0.12204, 0.0005, "s") == "122.04 \u00b1 0.50 ms"
    assert numfmt.quantity(0.122, 0.0005, "s") == "122.00 \u00b1 0.50 ms"
    assert numfmt.quantity(-0.1291, 0.0051, "s") == "-129.1 \u00b1 5.1 ms"
    assert numfmt.quantity(0.29, 0.02, "s") == "0.290 \u00b1 0.020 s"
    assert numfmt.quantity(1.2503, 0.0008, "m") == "1250.30 \u00b1 0.80 mm"
    assert numfmt.quantity(1.0, 0.0008, "\u00b0") == "1.00000 \u00b1 0.00080\u00b0"


def test_fixed_and_missing():
    assert numfmt.fixed(-0.0001, 3) == "0.000"
    assert numfmt.fixed(None) == numfmt.MISSING
    assert numfmt.fixed("x") == numfmt.MISSING
    assert numfmt.fixed(0.8148, 4, "\u00b0") == "0.8148\u00b0"
    assert numfmt.fixed(0.8148, 2, "m", sign=True) == "+0.81 m"
    assert numfmt.sigma_text(0.00051, "s") == "0.00051 s"
    assert numfmt.sigma_text(None) == numfmt.MISSING
