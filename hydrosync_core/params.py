"""Typed parameter schemas: one declaration per analysis, everything else derived from it.

An analysis declares its parameters once, as a frozen dataclass deriving from
:class:`Params` whose fields are made with :func:`param`::

    @dataclass(frozen=True)
    class LatencyParams(Params):
        SCHEMA_VERSION: ClassVar[int] = 1
        step_s: float = param(0.005, label="Step", unit="s", minimum=0.0, min_exclusive=True,
                              help="scan step of Δt")

From that one declaration HydroSync derives the panel's form (``ParamForm.from_schema``),
the flags of the analysis command (:func:`add_cli_arguments`), ``hydrosync run … --param
name=value`` (:func:`parse_assignment`), the spec's defaults (:meth:`Params.defaults`),
validation (``__post_init__`` raises :class:`~hydrosync_core.errors.InputError` with
``field=<name>``), what is stored in the project (:meth:`Params.to_dict` plus
:attr:`Params.SCHEMA_VERSION`) and the parameter table of the report (:func:`describe`).

Supported field types: ``float``, ``int``, ``bool``, ``str`` (usually with ``choices``),
fixed-length tuples of floats (``tuple[float, float]``) and any of these ``| None`` (None
means "not given": the method then takes the value from elsewhere, e.g. the vessel sheet).
This module imports only the standard library, so loading a schema is cheap.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import types
import typing
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from typing import Any, ClassVar

from hydrosync_core.errors import InputError

META_KEY = "hydrosync"


@dataclass(frozen=True)
class ParamMeta:
    """What the user sees of one parameter and the limits it must respect.

    Attributes
    ----------
    label : str
        Short label for forms and report tables.
    unit : str
        Unit shown to the user (``"s"``, ``"m"``, ``"°"``); values are stored in it.
    minimum, maximum : float or None
        Inclusive limits (exclusive with *min_exclusive*/*max_exclusive*); for tuples they
        apply to every element.
    choices : tuple of str
        Allowed values of a ``str`` field.
    help : str
        One or two sentences: what the parameter does and when to change it.
    cli : str
        The analysis command's flag (``"--step"``); default ``--name-with-hyphens``.
    metavar : tuple of str
        Names of the elements of a tuple field on the command line.
    decimals, step : int, float or None
        Editor hints for the panel (displayed decimals, spin-box step).
    group : str
        Panel group ("" = main); ``advanced`` groups are collapsed.
    advanced : bool
        Shown in a collapsed "Advanced" group of the panel.
    none_label : str
        For ``| None`` fields: what None means (e.g. "from the vessel sheet").
    """

    label: str
    unit: str = ""
    minimum: float | None = None
    maximum: float | None = None
    min_exclusive: bool = False
    max_exclusive: bool = False
    choices: tuple[str, ...] = ()
    help: str = ""
    cli: str = ""
    metavar: tuple[str, ...] = ()
    decimals: int = 3
    step: float | None = None
    group: str = ""
    advanced: bool = False
    none_label: str = ""


def param(default: Any, *, label: str, **meta: Any) -> Any:
    """A dataclass field with its :class:`ParamMeta` (keyword arguments as there)."""
    return field(default=default, metadata={META_KEY: ParamMeta(label=label, **meta)})


@dataclass(frozen=True)
class FieldInfo:
    """A parameter as the derived views need it: name, type, default and metadata."""

    name: str
    kind: str  # "float", "int", "bool", "str" or "tuple"
    length: int  # tuple length (0 for scalars)
    optional: bool
    default: Any
    meta: ParamMeta

    @property
    def flag(self) -> str:
        return self.meta.cli or "--" + self.name.replace("_", "-")

    def describe_value(self, value: Any) -> str:
        """The value as a person reads it, with its unit."""
        if value is None:
            return self.meta.none_label or "not set"
        if self.kind == "tuple":
            text = ", ".join(f"{v:g}" for v in value)
        elif self.kind == "float":
            text = f"{value:g}"
        elif self.kind == "bool":
            text = "yes" if value else "no"
        else:
            text = str(value)
        return f"{text} {self.meta.unit}".strip()


def _resolve(annotation: Any, owner: type) -> Any:
    if isinstance(annotation, str):
        module = __import__(owner.__module__, fromlist=["_"])
        annotation = eval(annotation, vars(typing) | vars(module))  # noqa: S307 - own source
    return annotation


def _kind_of(annotation: Any) -> tuple[str, int, bool]:
    optional = False
    origin = typing.get_origin(annotation)
    if origin in (typing.Union, types.UnionType):
        args = [a for a in typing.get_args(annotation) if a is not type(None)]
        optional = len(args) < len(typing.get_args(annotation))
        if len(args) != 1:
            raise TypeError(f"unsupported parameter type {annotation}")
        annotation = args[0]
        origin = typing.get_origin(annotation)
    if origin is tuple:
        return "tuple", len(typing.get_args(annotation)), optional
    for kind in (bool, int, float, str):
        if annotation is kind:
            return kind.__name__, 0, optional
    raise TypeError(f"unsupported parameter type {annotation}")


def _to_float(value: Any, name: str) -> float:
    if isinstance(value, bool) or value is None:
        raise InputError(None, f"{name} must be a number, got {value!r}", field=name)
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise InputError(None, f"{name} must be a number, got {str(value)[:40]!r}",
                         field=name) from None
    if not math.isfinite(out):
        raise InputError(None, f"{name} must be finite, got {out}", field=name)
    return out


def _coerce(info: FieldInfo, value: Any) -> Any:
    name = info.name
    if value is None:
        if info.optional:
            return None
        raise InputError(None, f"{name} must be given", field=name)
    if info.kind == "float":
        return _to_float(value, name)
    if info.kind == "int":
        number = _to_float(value, name)
        if number != int(number):
            raise InputError(None, f"{name} must be a whole number, got {value!r}", field=name)
        return int(number)
    if info.kind == "bool":
        if isinstance(value, bool):
            return value
        text = str(value).strip().lower()
        if text in ("1", "true", "yes", "on"):
            return True
        if text in ("0", "false", "no", "off"):
            return False
        raise InputError(None, f"{name} must be true or false, got {str(value)[:40]!r}",
                         field=name)
    if info.kind == "str":
        return str(value)
    if isinstance(value, str):
        value = value.replace(",", " ").split()
    try:
        items = list(value)
    except TypeError:
        raise InputError(None, f"{name} must be {info.length} numbers", field=name) from None
    if len(items) != info.length:
        raise InputError(None, f"{name} must be {info.length} numbers, got {len(items)}",
                         field=name)
    return tuple(_to_float(v, name) for v in items)


def _check_limits(info: FieldInfo, value: Any) -> None:
    if value is None:
        return
    m, name = info.meta, info.name
    if m.choices and value not in m.choices:
        raise InputError(None, f"{name} must be one of {', '.join(m.choices)}, got "
                         f"{str(value)[:40]!r}", field=name)
    if info.kind not in ("float", "int", "tuple"):
        return
    for v in value if info.kind == "tuple" else (value,):
        low_bad = m.minimum is not None and (v <= m.minimum if m.min_exclusive
                                             else v < m.minimum)
        high_bad = m.maximum is not None and (v >= m.maximum if m.max_exclusive
                                              else v > m.maximum)
        if low_bad or high_bad:
            lo = "" if m.minimum is None else f"{'>' if m.min_exclusive else '>='} {m.minimum:g}"
            hi = "" if m.maximum is None else f"{'<' if m.max_exclusive else '<='} {m.maximum:g}"
            limits = " and ".join(s for s in (lo, hi) if s)
            raise InputError(None, f"{name} must be {limits}{' ' + m.unit if m.unit else ''}, "
                             f"got {v:g}", field=name)


@dataclass(frozen=True)
class Params:
    """Base of every analysis's parameter dataclass (frozen, validated on creation).

    Subclasses set :attr:`SCHEMA_VERSION` (bumped when a stored parameter changes name
    or meaning, with :meth:`migrate` converting older dicts) and may override
    :meth:`validate` for checks between fields.
    """

    SCHEMA_VERSION: ClassVar[int] = 1

    def __post_init__(self) -> None:
        for info in self.schema():
            value = _coerce(info, getattr(self, info.name))
            _check_limits(info, value)
            object.__setattr__(self, info.name, value)
        self.validate()

    def validate(self) -> None:
        """Checks between fields; raise ``InputError(None, message, field=name)``."""

    # ------------------------------------------------------------------ schema
    @classmethod
    def schema(cls) -> list[FieldInfo]:
        """The parameters in declaration order."""
        cached = cls.__dict__.get("_schema_cache")
        if cached is not None:
            return cached
        hints = typing.get_type_hints(cls)
        out = []
        for f in fields(cls):
            meta = f.metadata.get(META_KEY)
            if meta is None:
                raise TypeError(f"{cls.__name__}.{f.name} is not declared with param()")
            kind, length, optional = _kind_of(_resolve(hints.get(f.name, f.type), cls))
            out.append(FieldInfo(f.name, kind, length, optional, f.default, meta))
        cls._schema_cache = out
        return out

    @classmethod
    def field_info(cls, name: str) -> FieldInfo:
        for info in cls.schema():
            if info.name == name:
                return info
        raise KeyError(name)

    @classmethod
    def flag_of(cls, name: str | None) -> str | None:
        """The command-line flag of parameter *name*, None if it is not a parameter."""
        names = {info.name: info for info in cls.schema()}
        return names[name].flag if name in names else None

    @classmethod
    def defaults(cls) -> dict[str, Any]:
        """The default parameters as a JSON-ready dict (tuples as lists)."""
        return cls().to_dict()

    # ------------------------------------------------------------- conversion
    @classmethod
    def migrate(cls, values: dict, version: int) -> dict:
        """Convert a dict stored by schema *version* (< :attr:`SCHEMA_VERSION`)."""
        return values

    @classmethod
    def from_dict(cls, values: Mapping | None, *, version: int | None = None,
                  strict: bool = True):
        """Build from a (stored or user-given) dict.

        Parameters
        ----------
        values : mapping or None
            Parameter values; missing ones keep their defaults.
        version : int, optional
            Schema version the dict was stored with; older dicts go through
            :meth:`migrate` first.
        strict : bool
            Raise for keys that are not parameters (default: a misspelt parameter must
            not be silently ignored); ``False`` ignores them (stored dicts written by
            other versions).
        """
        values = dict(values or {})
        if version is not None and version < cls.SCHEMA_VERSION:
            values = cls.migrate(values, version)
        names = {info.name for info in cls.schema()}
        unknown = sorted(set(values) - names)
        if strict and unknown:
            raise InputError(None, f"unknown parameter '{unknown[0]}' (known: "
                             f"{', '.join(sorted(names))})", field=unknown[0])
        return cls(**{k: v for k, v in values.items() if k in names})

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict of every parameter (tuples as lists)."""
        return {info.name: list(v) if isinstance(v := getattr(self, info.name), tuple) else v
                for info in self.schema()}

    def replace(self, **changes: Any):
        return dataclasses.replace(self, **changes)


def stored(schema: type[Params], project, path: str):
    """The parameters stored with the result at *path* of *project*, or None.

    Results keep ``schema.to_dict()`` as the group's JSON and the schema version as its
    ``params_schema_version`` attribute; older dicts are migrated on reading.
    """
    if not project.exists(path):
        return None
    version = int(project.attrs(path).get("params_schema_version", 1))
    return schema.from_dict(project.get_json(path, {}) or {}, version=version, strict=False)


# --------------------------------------------------------------------------- CLI
def add_cli_arguments(parser: argparse.ArgumentParser, schema: type[Params],
                      skip: tuple[str, ...] = ()) -> None:
    """One option per parameter of *schema*; defaults stay unset (the schema has them)."""
    group = parser.add_argument_group(f"{schema.__name__} (method parameters)")
    for info in schema.schema():
        if info.name in skip:
            continue
        m = info.meta
        default = info.describe_value(info.default)
        text = f"{m.help or m.label} (default {default})".replace("%", "%%")
        kwargs: dict[str, Any] = {"dest": f"param_{info.name}", "default": None, "help": text}
        if info.kind == "tuple":
            kwargs.update(nargs=info.length, type=float,
                          metavar=m.metavar or tuple(f"V{i + 1}" for i in range(info.length)))
        elif info.kind == "bool":
            kwargs.update(action=argparse.BooleanOptionalAction)
        elif m.choices:
            kwargs.update(choices=m.choices)
        else:
            kwargs.update(type={"float": float, "int": int, "str": str}[info.kind],
                          metavar=m.unit.upper().replace("°", "DEG") or "VALUE")
        flags = [info.flag]
        alias = "--" + info.name.replace("_", "-")
        if alias != info.flag:
            flags.append(alias)
        group.add_argument(*flags, **kwargs)


def cli_values(args: argparse.Namespace, schema: type[Params]) -> dict[str, Any]:
    """The parameters given on the command line (by :func:`add_cli_arguments`)."""
    out = {}
    for info in schema.schema():
        value = getattr(args, f"param_{info.name}", None)
        if value is not None:
            out[info.name] = value
    return out


def from_cli(args: argparse.Namespace, schema: type[Params]):
    """A validated *schema* instance from the command line; errors name the flag."""
    try:
        return schema.from_dict(cli_values(args, schema))
    except InputError as exc:
        raise InputError(exc.file or schema.flag_of(exc.field), exc.message,
                         field=exc.field) from None


def parse_assignment(schema: type[Params], text: str) -> tuple[str, Any]:
    """``"name=value"`` → (name, typed value) for ``hydrosync run … --param``."""
    name, sep, raw = text.partition("=")
    name = name.strip().replace("-", "_")
    if not sep:
        raise InputError("--param", f"expected NAME=VALUE, got {text[:60]!r}")
    try:
        info = schema.field_info(name)
    except KeyError:
        known = ", ".join(i.name for i in schema.schema())
        raise InputError("--param", f"unknown parameter '{name[:40]}' (known: {known})",
                         field=name) from None
    raw = raw.strip()
    if info.optional and raw.lower() in ("none", "null", ""):
        return name, None
    try:
        return name, _coerce(info, raw)
    except InputError as exc:
        raise InputError("--param", exc.message, field=name) from None


def describe(schema: type[Params], values: Mapping) -> list[tuple[str, str, str]]:
    """(label, value with unit, name) rows of a stored parameter dict, for reports."""
    rows = []
    for info in schema.schema():
        if info.name in values:
            value = values[info.name]
            if info.kind == "tuple" and value is not None:
                value = tuple(value)
            rows.append((info.meta.label, info.describe_value(value), info.name))
    return rows
