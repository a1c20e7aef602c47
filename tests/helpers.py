"""What the tests share besides fixtures: the repository root, the shipped scenes and a small TOML writer.

``ROOT``            the repository root (``Path``): the one place a test finds the repository's files
``SHIPPED_SCENES``  scene kind -> the shipped scene file it starts from (``scenes/*.toml``)
``scene_data``      ``scene_data(kind, *layers, **overrides)``: a shipped scene as a dict, its relative
                    paths made absolute, the layers and then the overrides applied (:func:`apply_overrides`)
``toml_text``       a dict -> TOML text (the value types the input files use); ``tomllib`` reads it back

Module-level code (parametrize lists, constants) imports ``ROOT`` from here; inside a test the ``root``
fixture of ``tests/conftest.py`` gives the same path. Its ``scene_file`` fixture writes
``toml_text(scene_data(...))`` into a test's ``tmp_path``.
"""

from __future__ import annotations

import math
import re
import tomllib
from collections.abc import Mapping
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: The shipped scene file of each scene kind: ``scene_file(kind, ...)`` starts from it.
SHIPPED_SCENES = {
    "reynolds": ROOT / "scenes" / "default.toml",
    "pump": ROOT / "scenes" / "pump.toml",
    "journal": ROOT / "scenes" / "journal.toml",
}

#: ``(table, field)`` of the scene fields that name a file relative to the scene file.
SCENE_PATHS = (("pump", "mechanism"),)


def scene_data(kind: str, *layers: Mapping, **overrides) -> dict:
    """The shipped scene of ``kind`` as a dict, file paths absolute, with ``layers`` and ``overrides`` applied.

    Each layer is a dict of overrides (a test file's small scene, then one row's change), applied in
    order, the keyword ``overrides`` last. A relative path in the shipped file (the pump's
    ``mechanism = "../mechanisms/..."``) is made absolute first, so the scene can be written anywhere;
    a path given in an override is kept as given (relative to wherever the test writes the file).
    """
    if kind not in SHIPPED_SCENES:
        raise KeyError(f"scene kind {kind!r}: one of {', '.join(SHIPPED_SCENES)}")
    shipped = SHIPPED_SCENES[kind]
    data = tomllib.loads(shipped.read_text(encoding="utf-8"))
    for table, field in SCENE_PATHS:
        value = data.get(table, {}).get(field)
        if isinstance(value, str) and not Path(value).is_absolute():
            data[table][field] = (shipped.parent / value).resolve().as_posix()
    for layer in (*layers, overrides):
        data = apply_overrides(data, layer)
    return data


def apply_overrides(data: Mapping, overrides: Mapping, where: str = "") -> dict:
    """A copy of ``data`` with ``overrides`` applied, key by key.

    * a table (dict) given for a table merges into it, recursively;
    * a dict with integer keys given for an array of tables edits its items by position
      (``{"inlets": {0: {"radius": 0.16}}}``); ``None`` for an item removes it;
    * ``None`` removes the key (which must be there: an override edits something that exists);
    * any other value (numbers, strings, arrays, a new table) replaces the value or adds the key.
    """
    out = dict(data)
    for key, value in overrides.items():
        path = f"{where}.{key}" if where else str(key)
        old = out.get(key)
        if value is None:
            if key not in out:
                raise KeyError(f"override removes {path}, which is not there")
            del out[key]
        elif isinstance(value, Mapping) and isinstance(old, Mapping):
            out[key] = apply_overrides(old, value, path)
        elif isinstance(value, Mapping) and isinstance(old, list) and all(isinstance(k, int) for k in value):
            out[key] = _edit_items(old, value, path)
        elif isinstance(value, Mapping):
            out[key] = apply_overrides({}, value, path)
        else:
            out[key] = value
    return out


def _edit_items(items: list, edits: Mapping, where: str) -> list:
    out = list(items)
    for index, change in edits.items():
        if not -len(items) <= index < len(items):
            raise KeyError(f"override edits {where}[{index}]; there are {len(items)} items")
        if change is None:
            out[index] = None
        elif isinstance(change, Mapping) and isinstance(items[index], Mapping):
            out[index] = apply_overrides(items[index], change, f"{where}.{index}")
        else:
            out[index] = change
    return [item for item in out if item is not None]


# -- a small TOML writer --------------------------------------------------------------------------

_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def toml_text(data: Mapping) -> str:
    """``data`` as TOML: strings, integers, floats (also ``inf`` and ``nan``), booleans, arrays,
    tables and arrays of tables (a non-empty list of dicts). Each table lists its plain values
    first, then its sub-tables, then its arrays of tables."""
    lines: list[str] = []
    _write_table(lines, (), data)
    return "\n".join(lines).lstrip("\n") + "\n"


def _is_table_array(value) -> bool:
    return isinstance(value, list) and bool(value) and all(isinstance(item, Mapping) for item in value)


def _write_table(lines: list[str], path: tuple, table: Mapping) -> None:
    tables = [(k, v) for k, v in table.items() if isinstance(v, Mapping)]
    arrays = [(k, v) for k, v in table.items() if _is_table_array(v)]
    for key, value in table.items():
        if not isinstance(value, Mapping) and not _is_table_array(value):
            lines.append(f"{_key(key)} = {_value(value)}")
    for key, value in tables:
        lines += ["", f"[{_dotted(path + (key,))}]"]
        _write_table(lines, path + (key,), value)
    for key, items in arrays:
        for item in items:
            lines += ["", f"[[{_dotted(path + (key,))}]]"]
            _write_table(lines, path + (key,), item)


def _dotted(path: tuple) -> str:
    return ".".join(_key(k) for k in path)


def _key(key) -> str:
    if not isinstance(key, str):
        raise TypeError(f"TOML keys are strings; got {key!r}")
    return key if _BARE_KEY.fullmatch(key) else _string(key)


def _string(text: str) -> str:
    out = []
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        return _string(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_value(item) for item in value) + "]"
    if isinstance(value, Mapping):
        return "{" + ", ".join(f"{_key(k)} = {_value(v)}" for k, v in value.items()) + "}"
    raise TypeError(f"no TOML form for {value!r} ({type(value).__name__})")


def markdown_table(text: str, header_start: str, *, after: str | None = None) -> tuple[list[str], list[list[str]]]:
    """The header cells and the rows of cells of the first Markdown table whose header line starts with
    ``header_start`` (a generated page's table, read back by the tests that check its sentences); with
    ``after``, of the first table below the first line that starts with ``after`` (a heading)."""
    lines = text.splitlines()
    begin = 0 if after is None else next(i for i, line in enumerate(lines) if line.startswith(after))
    start = next(i for i in range(begin, len(lines)) if lines[i].startswith(header_start))
    head = [c.strip() for c in lines[start].strip("|").split("|")]
    rows = []
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        rows.append([c.strip() for c in line.strip("|").split("|")])
    return head, rows
