"""One schema for every input file: scene, mechanism and study files.

A file is read against a *spec*: a mapping ``{name: entry}`` where an entry is

- ``(check, default, meaning)``: a field; ``check(where, value) -> value`` raises
  :class:`SchemaError`, ``default`` is used when the field is absent
  (:data:`REQUIRED`: the field must be given), ``meaning`` says what the field is,
  with its unit in brackets (``"radial clearance c [m]"``), for the file-format
  reference (:func:`reference_rows`);
- :class:`Table`: a sub-table ``[section.name]`` read with its own spec;
- :class:`Tables`: an array of tables ``[[section.name]]``, optionally with one
  spec per value of a key (``shape = "circle"``).

:func:`read_table` reads a TOML table (or a whole file, ``section=""``)
against a spec; unknown names are errors. Every error has the same form::

    <file>: [<table>] <field>: <what is wrong>; got <value>
    <file>: <top-level field>: <what is wrong>; got <value>
    <file>: [<table>]: missing table (required)

The field checks (:func:`number`, :func:`choice`, ...) are built once here;
choice lists come from the modules that own them (pass a callable, e.g.
``choice(lambda: parameters.ELEMENTS)``, to read the list when a file is
checked). :func:`build` calls a parameter-object constructor and re-raises
its ``ValueError`` with the file and table. The value checks
:func:`finite`, :func:`positive`, :func:`nonnegative`, :func:`in_range` and
:func:`one_of` are those of the parameter objects' ``__post_init__``:
``"<name> must be <range> [unit], got <value>"``.

This module imports nothing from the package, so every module may use it.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from numbers import Real
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping

__all__ = [
    "FieldRow", "LIMITS", "LIMITS_TABLE", "Limit", "NONNEGATIVE", "POSITIVE", "REQUIRED", "Range", "SchemaError",
    "Table", "Tables", "anything", "build", "check_limits", "choice", "choices", "describe", "finite", "flag",
    "in_range", "integer", "nonnegative", "nonnegative_number", "number", "numbers", "one_of", "pair", "path_text",
    "points", "positive", "positive_number", "read_table", "read_toml", "reference_rows", "required_field", "text",
    "texts",
]


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


#: Default of a field that must be given.
REQUIRED: Any = _Required()


class SchemaError(ValueError):
    """An input file is malformed: the message names the file, the table, the field and what is allowed."""


# -- ranges and the value checks of parameter objects ----------------------------------

@dataclass(frozen=True)
class Range:
    """An interval of allowed numbers, open or closed at either end; ``None``: unbounded.

    ``str(Range(0, None, lo_open=True))`` is ``"> 0"``, ``str(Range(0, 1))`` is ``"in [0, 1]"``.
    """

    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False

    def __contains__(self, x: float) -> bool:
        if self.lo is not None and (x <= self.lo if self.lo_open else x < self.lo):
            return False
        return not (self.hi is not None and (x >= self.hi if self.hi_open else x > self.hi))

    def __str__(self) -> str:
        if self.lo is not None and self.hi is not None:
            return f"in {'(' if self.lo_open else '['}{self.lo:g}, {self.hi:g}{')' if self.hi_open else ']'}"
        if self.lo is not None:
            return f"{'>' if self.lo_open else '>='} {self.lo:g}"
        if self.hi is not None:
            return f"{'<' if self.hi_open else '<='} {self.hi:g}"
        return "a finite number"


POSITIVE = Range(0.0, lo_open=True)
NONNEGATIVE = Range(0.0)


def _is_number(value) -> bool:
    return not isinstance(value, bool) and isinstance(value, (int, float)) and math.isfinite(value)


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


def finite(name: str, value) -> float:
    """``float(value)``; ``ValueError`` naming ``name`` unless a finite real number (numpy scalars too)."""
    if isinstance(value, bool) or not isinstance(value, Real) or not math.isfinite(value):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    return float(value)


def in_range(name: str, value, allowed: Range, unit: str = "") -> float:
    """``float(value)`` checked to lie in ``allowed``; the error names ``name``, the range and the unit."""
    x = finite(name, value)
    if x not in allowed:
        raise ValueError(f"{name} must be {allowed}{_unit(unit)}, got {value!r}")
    return x


def positive(name: str, value, unit: str = "") -> float:
    """A finite number > 0 (``ValueError`` naming ``name`` otherwise)."""
    return in_range(name, value, POSITIVE, unit)


def nonnegative(name: str, value, unit: str = "") -> float:
    """A finite number >= 0 (``ValueError`` naming ``name`` otherwise)."""
    return in_range(name, value, NONNEGATIVE, unit)


def one_of(name: str, value, allowed: Iterable):
    """``value`` if it is one of ``allowed``; the error lists them."""
    allowed = tuple(allowed)
    if not _hashable_in(value, allowed):
        raise ValueError(f"{name} must be one of {_listed(allowed)}, got {value!r}")
    return value


def _hashable_in(value, allowed: tuple) -> bool:
    try:
        return value in allowed
    except TypeError:
        return False


def _listed(allowed: Iterable) -> str:
    return ", ".join(repr(a) for a in allowed)


# -- field checks: (where, value) -> value ------------------------------------------

Check = Callable[[str, Any], Any]


def _accepting(description: str | Callable[[], str]) -> Callable[[Check], Check]:
    """Attach ``description`` (what a field accepts, for the file-format reference) to a check."""
    def attach(check: Check) -> Check:
        check.accepts = description
        return check
    return attach


def describe(check: Check) -> str:
    """What a field check accepts, in words (``"a number > 0"``, ``"one of 'P1', 'P2'"``)."""
    description = getattr(check, "accepts", None)
    if description is None:
        raise ValueError(f"field check {getattr(check, '__name__', check)!r} has no description")
    return description() if callable(description) else description


def number(allowed: Range | None = None) -> Check:
    """A finite number (TOML integer or float), optionally in a range; returns a float."""
    @_accepting("a number" if allowed is None else f"a number {allowed}")
    def check(where: str, value):
        if not _is_number(value):
            raise SchemaError(f"{where}: expected a finite number; got {value!r}")
        if allowed is not None and value not in allowed:
            raise SchemaError(f"{where}: must be {allowed}; got {value!r}")
        return float(value)
    return check


def integer(allowed: Range | None = None) -> Check:
    """A TOML integer, optionally in a range."""
    @_accepting("an integer" if allowed is None else f"an integer {allowed}")
    def check(where: str, value):
        if isinstance(value, bool) or not isinstance(value, int):
            raise SchemaError(f"{where}: expected an integer; got {value!r}")
        if allowed is not None and value not in allowed:
            raise SchemaError(f"{where}: must be an integer {allowed}; got {value!r}")
        return value
    return check


def numbers(n: int, what: str) -> Check:
    """A list of ``n`` finite numbers; ``what`` describes it in the error (``"a pair [x, y]"``)."""
    @_accepting(what)
    def check(where: str, value):
        if not (isinstance(value, list) and len(value) == n and all(_is_number(v) for v in value)):
            raise SchemaError(f"{where}: expected {what}; got {value!r}")
        return tuple(float(v) for v in value)
    return check


@_accepting("a list of at least 3 points [[x, y], ...]")
def points(where: str, value) -> tuple:
    """At least 3 points ``[[x, y], ...]``."""
    if not (isinstance(value, list) and len(value) >= 3):
        raise SchemaError(f"{where}: expected a list of at least 3 points [[phi, z], ...]; got {value!r}")
    return tuple(pair(where, p) for p in value)


def _allowed(allowed) -> tuple:
    return tuple(allowed() if callable(allowed) else allowed)


def choice(allowed: Iterable | Callable[[], Iterable]) -> Check:
    """One of ``allowed`` (or of ``allowed()``, read when the file is checked)."""
    @_accepting(lambda: f"one of {_listed(_allowed(allowed))}")
    def check(where: str, value):
        names = _allowed(allowed)
        if not _hashable_in(value, names):
            raise SchemaError(f"{where}: must be one of {_listed(names)}; got {value!r}")
        return value
    return check


def choices(allowed: Iterable | Callable[[], Iterable], *, empty: bool = True) -> Check:
    """A list of values drawn from ``allowed`` (non-empty unless ``empty``); returns a tuple."""
    what = "a list" if empty else "a non-empty list"

    @_accepting(lambda: f"{what} drawn from {_listed(_allowed(allowed))}")
    def check(where: str, value):
        if not isinstance(value, list) or not (empty or value):
            raise SchemaError(f"{where}: expected {what} drawn from {_listed(_allowed(allowed))}; got {value!r}")
        return tuple(choice(allowed)(where, v) for v in value)
    return check


@_accepting("text")
def text(where: str, value) -> str:
    """A string."""
    if not isinstance(value, str):
        raise SchemaError(f"{where}: expected a string; got {value!r}")
    return value


@_accepting("a list of texts")
def texts(where: str, value) -> tuple[str, ...]:
    """A list of strings."""
    if not (isinstance(value, list) and all(isinstance(v, str) for v in value)):
        raise SchemaError(f"{where}: expected a list of strings; got {value!r}")
    return tuple(value)


@_accepting("a file path (text)")
def path_text(where: str, value) -> str:
    """A non-empty string naming a file."""
    if not isinstance(value, str) or not value:
        raise SchemaError(f"{where}: expected a file path (text); got {value!r}")
    return value


@_accepting("true or false")
def flag(where: str, value) -> bool:
    """``true`` or ``false``."""
    if not isinstance(value, bool):
        raise SchemaError(f"{where}: expected true or false; got {value!r}")
    return value


@_accepting("any value, checked by what reads it")
def anything(where: str, value):
    """Any value (checked later, e.g. by a parameter object's constructor)."""
    return value


pair = numbers(2, "a pair of numbers [x, y]")
positive_number = number(POSITIVE)
nonnegative_number = number(NONNEGATIVE)


# -- tables ------------------------------------------------------------------------------

def _where(label: str, section: str, name: str = "") -> str:
    if not section:
        return f"{label}: {name}" if name else label
    return f"{label}: [{section}] {name}" if name else f"{label}: [{section}]"


def _sub(section: str, name: str) -> str:
    return f"{section}.{name}" if section else name


@dataclass(frozen=True)
class Table:
    """A sub-table read with ``spec``; absent: an error if ``required``, else read as empty (defaults)."""

    spec: Mapping[str, Any]
    required: bool = False

    def read(self, value, label: str, section: str) -> dict:
        if value is REQUIRED:
            if self.required:
                raise SchemaError(f"{_where(label, section)}: missing table (required)")
            value = {}
        return read_table(value, label, section, self.spec)


@dataclass(frozen=True)
class Tables:
    """An array of tables ``[[section.name]]``: each read with ``spec``, or, with ``key``, with
    ``variants[table[key]]`` (the key's value kept under ``key`` in the result); ``key_meaning`` says
    what the key chooses, for the file-format reference."""

    spec: Mapping[str, Any] = field(default_factory=dict)
    key: str | None = None
    variants: Mapping[str, Mapping[str, Any]] | Callable[[], Mapping[str, Mapping[str, Any]]] = field(
        default_factory=dict)
    key_meaning: str = ""

    def read(self, value, label: str, section: str) -> tuple[dict, ...]:
        if value is REQUIRED:
            return ()
        if not isinstance(value, list):
            head, _, name = section.rpartition(".")
            raise SchemaError(f"{_where(label, head, name)}: expected an array of tables [[{section}]]; "
                              f"got {value!r}")
        return tuple(self._one(item, label, f"{section}.{k}") for k, item in enumerate(value))

    def _one(self, item, label: str, section: str) -> dict:
        if not isinstance(item, dict):
            raise SchemaError(f"{_where(label, section)}: expected a table; got {item!r}")
        if self.key is None:
            return read_table(item, label, section, self.spec)
        variants = self.variants() if callable(self.variants) else self.variants
        where = _where(label, section, self.key)
        if self.key not in item:
            raise SchemaError(f"{where}: missing (required); allowed: {_listed(variants)}")
        kind = choice(tuple(variants))(where, item[self.key])
        rest = {k: v for k, v in item.items() if k != self.key}
        return {self.key: kind, **read_table(rest, label, section, variants[kind])}


def read_table(table: Any, label: str, section: str, spec: Mapping[str, Any]) -> dict:
    """Check a TOML table against ``spec`` (see the module docstring); returns the values and defaults.

    Parameters
    ----------
    table : dict
        The parsed TOML table (the whole file when ``section`` is ``""``).
    label : str
        The file's name, first in every message.
    section : str
        Dotted name of the table (``"surface.inlets.0"``); ``""`` for the file itself.
    spec : mapping
        ``{name: (check, default) | Table | Tables}``.

    Raises
    ------
    SchemaError
        Not a table, an unknown name, a missing required field or table, or a field
        check's error; the message names the file, the table and the field.
    """
    if not isinstance(table, dict):
        raise SchemaError(f"{_where(label, section)}: expected a table; got {table!r}")
    unknown = sorted(set(table) - set(spec))
    if unknown:
        what = "unknown field" if section else "unknown table or field"
        message = f"{_where(label, section, unknown[0])}: {what}; allowed: {', '.join(spec)}"
        missing = [_missing(label, section, name, entry) for name, entry in spec.items() if name not in table]
        missing = [m for m in missing if m]
        raise SchemaError(message + (f" (and {missing[0]}: a misspelling?)" if missing else ""))
    out = {}
    for name, entry in spec.items():
        value = table.get(name, REQUIRED)
        if isinstance(entry, (Table, Tables)):
            out[name] = entry.read(value, label, _sub(section, name))
            continue
        check, default = entry[0], entry[1]
        if value is REQUIRED:
            if default is REQUIRED:
                raise SchemaError(_missing(label, section, name, entry))
            out[name] = default
        else:
            out[name] = check(_where(label, section, name), value)
    return out


def required_field(entry: tuple) -> tuple:
    """The field ``entry`` with no default (:data:`REQUIRED`), its check and meaning kept."""
    return (entry[0], REQUIRED, *entry[2:])


def _missing(label: str, section: str, name: str, entry) -> str:
    """The error text of a required entry that is absent ("" if it is not required)."""
    if isinstance(entry, Table):
        return f"{_where(label, _sub(section, name))}: missing table (required)" if entry.required else ""
    if isinstance(entry, Tables):
        return ""
    return f"{_where(label, section, name)}: missing (required)" if entry[1] is REQUIRED else ""


def build(label: str, section: str, factory: Callable, /, *args, **kwargs):
    """``factory(*args, **kwargs)``; its ``ValueError`` re-raised as :class:`SchemaError` naming the
    file and the table (``"<file>: [<section>] <the constructor's message>"``)."""
    try:
        return factory(*args, **kwargs)
    except SchemaError:
        raise
    except ValueError as exc:
        raise SchemaError(f"{_where(label, section)} {exc}" if section else f"{label}: {exc}") from None


#: Largest input (TOML) file read [bytes]: scene, mechanism and study files are a few kilobytes.
MAX_TOML_BYTES = 1 << 20


def read_toml(path: str | Path, what: str = "file") -> tuple[dict, str]:
    """Parse a TOML file; returns ``(data, label)`` with the file's name as label.

    Raises :class:`SchemaError` if the file is missing, unreadable or not valid TOML
    (``what`` names the kind of file in the message: ``"scene file"``).
    """
    path = Path(path)
    label = path.name
    if not path.is_file():
        raise SchemaError(f"{what} not found: {path}")
    try:
        if path.stat().st_size > MAX_TOML_BYTES:
            raise SchemaError(f"{label}: the {what} is {path.stat().st_size} bytes, more than the "
                              f"{MAX_TOML_BYTES} an input file of this package may have")
        return tomllib.loads(path.read_text(encoding="utf-8")), label
    except OSError as exc:
        raise SchemaError(f"cannot read {what} {path}: {exc}") from None
    except UnicodeDecodeError as exc:
        raise SchemaError(f"{label}: not valid TOML (not UTF-8 text): {exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise SchemaError(f"{label}: not valid TOML: {exc}") from None
    except RecursionError:
        raise SchemaError(f"{label}: arrays or tables nested too deeply to read (a {what} needs a few levels)") \
            from None


# -- design limits ([limits] of a scene) -----------------------------------------------

@dataclass(frozen=True)
class Limit:
    """A design limit a scene may set: the ``quantity`` it bounds, its SI ``unit``, the ``relation`` a
    design must satisfy (``">="``: at least the limit; ``"<="``: at most) and the ``allowed`` range."""

    quantity: str
    unit: str
    relation: str
    allowed: Range = POSITIVE


#: The ``[limits]`` table of the pump and journal scenes: every field optional (unset: not checked).
LIMITS = {
    "min_film": Limit("smallest film", "m", ">="),
    "max_pressure": Limit("peak pressure", "Pa", "<="),
    "max_friction_power": Limit("mean friction power", "W", "<="),
    "max_leakage": Limit("leakage (mean flow drawn from the supply)", "m^3/s", "<="),
}

#: The spec of the ``[limits]`` table (see :data:`LIMITS` for the units).
LIMITS_TABLE = Table({name: (number(limit.allowed), None, f"{limit.quantity} {limit.relation} this [{limit.unit}]")
                      for name, limit in LIMITS.items()})


def check_limits(values: Mapping[str, float], limits: Mapping[str, float | None]) -> dict[str, dict]:
    """Each set limit against the design's value of its quantity.

    Parameters
    ----------
    values : mapping
        ``{limit name: value [SI unit of the limit]}`` (names of :data:`LIMITS`).
    limits : mapping
        ``{limit name: limit or None}`` as read from ``[limits]`` (``None``: not set, not checked).

    Returns
    -------
    dict
        ``{name: {"quantity", "value", "limit", "unit", "relation", "ok"}}`` for every set limit.
    """
    out = {}
    for name, limit in limits.items():
        if limit is None:
            continue
        spec = LIMITS[name]
        value = float(values[name])
        ok = value >= limit if spec.relation == ">=" else value <= limit
        out[name] = {"quantity": spec.quantity, "value": value, "limit": float(limit), "unit": spec.unit,
                     "relation": spec.relation, "ok": bool(ok)}
    return out


# -- the file-format reference -------------------------------------------------------------

@dataclass(frozen=True)
class FieldRow:
    """One field of a spec as the file-format reference lists it.

    ``table`` is the dotted table name (``"run"``, ``"surface.inlets[shape = 'circle']"``; ``""`` for
    a top-level field), ``accepts`` what the field's check accepts, ``default`` the default's TOML text
    (``"required"`` for a field that must be given, ``"none"`` for an optional field without one).
    """

    table: str
    field: str
    accepts: str
    default: str
    meaning: str = ""


def _default_text(default: Any) -> str:
    if default is REQUIRED:
        return "required"
    if default is None:
        return "none"
    if isinstance(default, bool):
        return "true" if default else "false"
    if isinstance(default, str):
        return repr(default).replace("'", '"')
    if isinstance(default, (tuple, list)):
        return "[" + ", ".join(_default_text(d) for d in default) + "]"
    return repr(default)


def reference_rows(spec: Mapping[str, Any], section: str = "") -> list[FieldRow]:
    """Every field of ``spec`` and of its sub-tables, in file order: the rows of the file-format reference.

    A :class:`Table` contributes its fields under ``section.name``; a :class:`Tables` with a ``key``
    one group of fields per variant (``name[key = 'variant']``) after the key itself.
    """
    rows: list[FieldRow] = []
    for name, entry in spec.items():
        sub = _sub(section, name)
        if isinstance(entry, Table):
            rows += reference_rows(entry.spec, sub)
        elif isinstance(entry, Tables):
            rows += _tables_rows(entry, sub)
        else:
            meaning = entry[2] if len(entry) > 2 else ""
            rows.append(FieldRow(section, name, describe(entry[0]), _default_text(entry[1]), meaning))
    return rows


def _tables_rows(entry: Tables, section: str) -> list[FieldRow]:
    if entry.key is None:
        return reference_rows(entry.spec, f"{section}[]")
    variants = entry.variants() if callable(entry.variants) else entry.variants
    rows = [FieldRow(f"{section}[]", entry.key, f"one of {_listed(variants)}", "required",
                     entry.key_meaning)]
    for kind, spec in variants.items():
        rows += reference_rows(spec, f"{section}[{entry.key} = {kind!r}]".replace("'", '"'))
    return rows
