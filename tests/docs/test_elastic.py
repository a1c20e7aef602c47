"""docs/elastic.md is the page that benchmarks/elastic.py writes from docs/elastic.json, and its cheap
numbers (the half-space against Love's closed form) are recomputed here."""

import json

import pytest

import bearingfe as bf
from benchmarks.elastic import love, page
from tests.helpers import ROOT

DOCS = ROOT / "docs"


def test_page_is_generated_from_its_numbers():
    data = json.loads((DOCS / "elastic.json").read_text())
    assert (DOCS / "elastic.md").read_text() == page(data)


def test_love_numbers_recomputed():
    data = json.loads((DOCS / "elastic.json").read_text())["love"]
    now = love(bf.load_mechanism(DOCS.parent / "mechanisms" / "eccentric_pump.toml"))
    for point in ("centre", "corner"):
        assert now[point]["computed_um"] == pytest.approx(data[point]["computed_um"], rel=1e-12)
        assert now[point]["relative_error"] < 1e-10


def test_real_shoe_part_describes_the_shipped_shoe():
    # the real-shoe numbers were computed for the shoe body the machine file describes now
    data = json.loads((DOCS / "elastic.json").read_text())["shoe"]
    body = bf.load_mechanism(DOCS.parent / "mechanisms" / "eccentric_pump.toml").shoe_body
    assert data["body"] == {"thickness_mm": pytest.approx(body.thickness * 1e3), "back": body.back,
                            "seat": body.seat, "seat_radius_mm": pytest.approx(body.seat_radius * 1e3)}
    assert data["shoe_ratio"] == pytest.approx(data["pocket"]["shoe_um"] / data["plain"]["shoe_um"], rel=1e-12)
