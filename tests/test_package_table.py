"""The package docstring's module table lists every module of the package (issue 15).

Expected values come from the file system: every ``bearingfe/*.py`` module and every
subpackage must have a row in the table of ``bearingfe/__init__.py``, and every row must
name a module that exists, so the table cannot drift from the code.
"""

import re
from pathlib import Path

import bearingfe

PACKAGE = Path(bearingfe.__file__).parent


def _table_names() -> list[str]:
    rows = re.findall(r"^``([a-z_0-9]+)``\s", bearingfe.__doc__, flags=re.MULTILINE)
    assert rows, "the package docstring has no module table"
    return rows


def _modules() -> set[str]:
    names = {p.stem for p in PACKAGE.glob("*.py") if p.stem not in ("__init__", "__main__")}
    names |= {p.parent.name for p in PACKAGE.glob("*/__init__.py")}
    return names


def test_every_module_has_a_row():
    missing = sorted(_modules() - set(_table_names()))
    assert missing == [], f"modules missing from the table in bearingfe/__init__.py: {missing}"


def test_every_row_names_a_module_once():
    rows = _table_names()
    assert sorted(set(rows) - _modules()) == []
    assert len(rows) == len(set(rows))
