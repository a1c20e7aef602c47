"""docs/elastic.md is the page that benchmarks/elastic.py writes from docs/elastic.json, and its cheap
numbers (the half-space against Love's closed form) are recomputed here."""

import json
from pathlib import Path

import pytest

import bearingfe as bf
from benchmarks.elastic import love, page

DOCS = Path(__file__).resolve().parents[1] / "docs"


def test_page_is_generated_from_its_numbers():
    data = json.loads((DOCS / "elastic.json").read_text())
    assert (DOCS / "elastic.md").read_text() == page(data)


def test_love_numbers_recomputed():
    data = json.loads((DOCS / "elastic.json").read_text())["love"]
    now = love(bf.load_mechanism(DOCS.parent / "mechanisms" / "eccentric_pump.toml"))
    for point in ("centre", "corner"):
        assert now[point]["computed_um"] == pytest.approx(data[point]["computed_um"], rel=1e-12)
        assert now[point]["relative_error"] < 1e-10
