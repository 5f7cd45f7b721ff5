"""One number formatter for the CLI, the panels and the PDF: units, and digits from σ.

A value printed beside its standard deviation carries the decimals that σ supports: σ is
rounded to two significant digits and the value to the same decimal place. A value without σ
keeps the decimals its caller states. Every text is plain: an ASCII minus (so that text
extracted from a PDF parses as a number), ``"—"`` for a missing or non-finite number,
never ``"-0.000"`` and never ``"± 0.000"``.

Units are written after a space, except ``°`` which is written closed up. :func:`scaled`
picks a display unit (s or ms, m or mm) in which σ reads with at most two leading zeros.
"""

from __future__ import annotations

import math

MISSING = "\u2014"
PM = "\u00b1"

#: Display scales: for each base unit, the units it may be shown in (factor from base).
SCALES = {"s": (("s", 1.0), ("ms", 1e3)), "m": (("m", 1.0), ("mm", 1e3)),
          "ms": (("ms", 1.0),), "mm": (("mm", 1.0),), "°": (("°", 1.0),),
          "deg": (("°", 1.0),)}


def finite(value) -> float | None:
    """*value* as a float, or None when it is missing, not a number or not finite."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        return None
    return number if math.isfinite(number) else None


def with_unit(text: str, unit: str = "") -> str:
    """Append *unit* after a space, except the degree sign, which is written closed up."""
    if not unit:
        return text
    return f"{text}{unit}" if unit == "\u00b0" else f"{text} {unit}"


def _clean(text: str) -> str:
    """No ``-0.000``: a zero keeps no sign."""
    return text.lstrip("-") if text.strip("-0.") == "" else text


def fixed(value, decimals: int = 3, unit: str = "", sign: bool = False) -> str:
    """*value* with *decimals* fixed decimals and an optional unit; ``"—"`` if missing.

    Parameters
    ----------
    value : float-like or None
    decimals : int
        Decimal places (≥ 0).
    unit : str
        Appended after a space (``°`` closed up).
    sign : bool
        Show ``+`` on positive values (corrections, differences).
    """
    number = finite(value)
    if number is None:
        return MISSING
    text = _clean(f"{number:{'+' if sign else ''}.{max(int(decimals), 0)}f}")
    if sign and text[0] not in "+-":
        text = "+" + text if number > 0 else text
    return with_unit(text, unit)


def sigma_decimals(sigma, min_decimals: int = 0, max_decimals: int = 12) -> int | None:
    """Decimal places that show *sigma* with two significant digits, so that a value
    rounded to them carries what σ supports.

    None when σ is missing, zero or not finite.
    """
    s = finite(sigma)
    if s is None or s <= 0:
        return None
    exponent = math.floor(math.log10(s))
    decimals = 1 - exponent
    # Rounding σ up may add a digit (0.0996 -> 0.10): one decimal fewer then.
    if round(s, decimals) >= 10.0 ** (exponent + 1):
        decimals -= 1
    return min(max(decimals, min_decimals), max_decimals)


def value_sigma(value, sigma, unit: str = "", decimals: int | None = None,
                sign: bool = False) -> str:
    """``"0.1220 ± 0.0005 s"``: value and σ to the decimals σ supports (or *decimals*).

    A missing σ gives the value alone with *decimals* (3 by default); a zero σ is written
    as ``"± 0"`` with the value's *decimals* (an exact, fixed quantity), never ``"± 0.000"``.
    """
    number = finite(value)
    if number is None:
        return MISSING
    s = finite(sigma)
    d = decimals if decimals is not None else sigma_decimals(sigma)
    if s is None:
        return fixed(number, 3 if d is None else d, unit, sign)
    if s == 0.0:
        return with_unit(f"{fixed(number, 3 if d is None else d, sign=sign)} {PM} 0", unit)
    return with_unit(f"{fixed(number, d, sign=sign)} {PM} {fixed(s, d)}", unit)


def sigma_text(sigma, unit: str = "", decimals: int | None = None) -> str:
    """σ alone, to two significant digits (``"0.00051 s"``), or ``"—"``."""
    s = finite(sigma)
    if s is None:
        return MISSING
    d = decimals if decimals is not None else (sigma_decimals(s) or 0)
    return fixed(s, d, unit)


def scaled(sigma, unit: str) -> tuple[str, float]:
    """Display unit and factor for a quantity in base *unit* whose σ is *sigma*.

    ``s`` and ``m`` switch to ``ms`` and ``mm`` when σ in the base unit would need three
    leading zeros or more (σ < 0.01), so that ``0.1220 ± 0.0005 s`` reads
    ``122.0 ± 0.5 ms``. Other units are kept.
    """
    options = SCALES.get(unit, ((unit, 1.0),))
    s = finite(sigma)
    if len(options) == 1 or s is None or s <= 0 or s >= 0.01:
        return options[0]
    return options[1]


def quantity(value, sigma, unit: str, sign: bool = False) -> str:
    """:func:`value_sigma` in the display unit :func:`scaled` picks for σ."""
    shown, factor = scaled(sigma, unit)
    v = finite(value)
    s = finite(sigma)
    return value_sigma(None if v is None else v * factor, None if s is None else s * factor,
                       shown, sign=sign)
