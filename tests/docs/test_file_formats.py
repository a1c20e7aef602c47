"""docs/file_formats.md is generated from the schema by scripts/make_file_formats.py: regenerate and compare.

The page lists every field the readers check, so a field added to a spec without regenerating the page
fails here (``PYTHONPATH=. python scripts/make_file_formats.py`` rewrites it).
"""

from __future__ import annotations

import difflib
import importlib.util

import pytest

from bearingfe.core import schema
from bearingfe.scenes import pump
from tests.helpers import ROOT


def _script():
    spec = importlib.util.spec_from_file_location("make_file_formats", ROOT / "scripts" / "make_file_formats.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_committed_file_format_page_is_the_generated_one():
    generated = _script().page()
    committed = (ROOT / "docs" / "file_formats.md").read_text(encoding="utf-8")
    diff = "".join(difflib.unified_diff(committed.splitlines(True), generated.splitlines(True)))
    assert generated == committed, "docs/file_formats.md is stale; run scripts/make_file_formats.py:\n" + diff[:4000]


def test_the_reference_rows_say_what_the_reader_accepts():
    rows = {(r.table, r.field): r for r in schema.reference_rows(pump.SPEC)}
    # the values of pump.SPEC: [run] revolutions is a positive number defaulting to 1.0, element a choice
    assert rows[("run", "revolutions")].accepts == "a number > 0"
    assert rows[("run", "revolutions")].default == "1.0"
    assert rows[("run", "element")].accepts == "one of 'P1', 'P2'"
    assert rows[("run", "element")].default == '"P2"'
    assert rows[("", "kind")].default == "required"
    assert rows[("pump", "compare_plain")].default == "true"


def test_a_field_check_without_a_description_is_refused():
    with pytest.raises(ValueError, match="has no description"):
        schema.reference_rows({"x": (lambda where, value: value, 1.0)})


def test_every_field_of_every_file_says_what_it_is():
    """Each field's spec entry carries its meaning with its unit (the page's ``meaning [unit]`` column)."""
    rows = [(kind, row) for kind, rows in _script().all_rows() for row in rows]
    assert len(rows) > 150
    assert [f"{kind}: [{row.table}] {row.field}" for kind, row in rows if not row.meaning.strip()] == []
