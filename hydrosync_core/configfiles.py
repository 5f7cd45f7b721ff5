"""Reading small configuration documents (JSON, TOML, YAML) with bounds.

A settings file is small and shallow. Parsed without bounds, a hostile or broken one
ends in ``RecursionError`` (deep nesting), ``ValueError`` (an integer of 5001 digits)
or a long walk over shared YAML aliases. Here each is one :class:`InputError` naming the
file: at most :data:`MAX_CONFIG_BYTES`, :data:`MAX_DEPTH` levels of nesting,
:data:`MAX_VALUES` values and :data:`MAX_INT_DIGITS` digits per integer.
"""

from __future__ import annotations

import json
import os
import re
from pathlib import Path
from typing import Any

from hydrosync_core.errors import InputError
from hydrosync_core.inputs import input_ok

MAX_CONFIG_BYTES = 16 << 20
MAX_DEPTH = 64
MAX_VALUES = 1_000_000
MAX_INT_DIGITS = 40


def read_config_text(path: str | os.PathLike, what: str = "settings file") -> str:
    """The text of the configuration file *path* (UTF-8, BOM allowed), gated and bounded."""
    p = input_ok(path, what, max_bytes=MAX_CONFIG_BYTES)
    try:
        return p.read_bytes().decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(str(p), f"is not UTF-8 text (byte {exc.start})") from None
    except OSError as exc:
        raise InputError(str(p), f"cannot be read ({exc.strerror or exc})") from None


def check_shape(document: Any, where: str) -> Any:
    """Raise :class:`InputError` if *document* is nested too deeply or too big."""
    stack = [(document, 1)]
    seen = 0
    while stack:
        value, depth = stack.pop()
        seen += 1
        if seen > MAX_VALUES:
            raise InputError(where, f"holds more than {MAX_VALUES} values: not a settings "
                             "file")
        if depth > MAX_DEPTH:
            raise InputError(where, f"nested deeper than {MAX_DEPTH} levels")
        if isinstance(value, dict):
            stack.extend((v, depth + 1) for v in value.values())
            stack.extend((k, depth + 1) for k in value if not isinstance(k, str))
        elif isinstance(value, list | tuple):
            stack.extend((v, depth + 1) for v in value)
        elif isinstance(value, int) and not isinstance(value, bool) and \
                abs(value) >= 10 ** MAX_INT_DIGITS:
            raise InputError(where, f"holds an integer of more than {MAX_INT_DIGITS} digits")
    return document


def _too_deep(where: str) -> InputError:
    return InputError(where, f"nested deeper than {MAX_DEPTH} levels")


def _big_number(where: str, exc: ValueError) -> InputError:
    text = str(exc)
    if "digits" in text or "integer string conversion" in text:
        return InputError(where, f"holds an integer of more than {MAX_INT_DIGITS} digits")
    return InputError(where, f"invalid value ({text[:80]})")


def _long_digits(text: str, where: str) -> None:
    """Refuse runs of digits far beyond any number before a parser converts them
    (CPython's own limit, 4300 digits, would say so in a ValueError of its own)."""
    match = re.search(r"\d{" + str(MAX_INT_DIGITS * 8) + ",}", text)
    if match:
        line = text.count("\n", 0, match.start()) + 1
        raise InputError(where, f"holds a number of {len(match.group())} digits",
                         line=line)


def _bounded_parse(text: str, where: str, parse, syntax_error, syntax_message) -> Any:
    """*parse* (a library's ``loads``) of *text* from file *where*, bounded (see the module
    doc): *syntax_error* (an exception class) becomes ``syntax_message(exc)``, an
    ``(message, line)`` pair; too deep and too long numbers get their own one line."""
    _long_digits(text, where)
    try:
        document = parse(text)
    except syntax_error as exc:
        message, line = syntax_message(exc)
        raise InputError(where, message, line=line) from None
    except RecursionError:
        raise _too_deep(where) from None
    except ValueError as exc:
        raise _big_number(where, exc) from None
    return check_shape(document, where)


def parse_json(text: str, where: str) -> Any:
    """Parse JSON *text* from file *where*, bounded (see the module doc)."""
    return _bounded_parse(text, where, json.loads, json.JSONDecodeError,
                          lambda exc: (f"not valid JSON: {exc.msg}", exc.lineno))


def parse_toml(text: str, where: str) -> dict:
    """Parse TOML *text* from file *where*, bounded (see the module doc)."""
    import tomllib

    def message(exc):
        match = re.search(r"\(at line (\d+)", str(exc))
        return (f"not valid TOML: {str(exc).split(' (at line')[0]}",
                int(match.group(1)) if match else None)

    return _bounded_parse(text, where, tomllib.loads, tomllib.TOMLDecodeError, message)


def parse_yaml(text: str, where: str) -> Any:
    """Parse YAML *text* (safe loader) from file *where*, bounded (see the module doc)."""
    import yaml

    def message(exc):
        mark = getattr(exc, "problem_mark", None)
        return (f"not valid YAML: {getattr(exc, 'problem', None) or exc}",
                None if mark is None else mark.line + 1)

    return _bounded_parse(text, where, yaml.safe_load, yaml.YAMLError, message)


def load(path: str | os.PathLike, what: str = "settings file") -> Any:
    """Read and parse *path* by its suffix (``.toml``, ``.yaml``/``.yml``, else JSON)."""
    p = Path(path)
    text = read_config_text(p, what)
    suffix = p.suffix.lower()
    if suffix == ".toml":
        return parse_toml(text, str(p))
    if suffix in (".yaml", ".yml"):
        return parse_yaml(text, str(p))
    return parse_json(text, str(p))
