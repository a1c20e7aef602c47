"""docs/hydrostatic.md is the page that benchmarks/hydrostatic.py writes from docs/hydrostatic.json, and its
coarsest rows (the recess pad against its closed forms) are recomputed here."""

import json

import pytest

from benchmarks.hydrostatic import errors, page
from tests.helpers import ROOT

DOCS = ROOT / "docs"


def test_page_is_generated_from_its_numbers():
    data = json.loads((DOCS / "hydrostatic.json").read_text())
    assert (DOCS / "hydrostatic.md").read_text() == page(data)


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_coarsest_errors_recomputed(element):
    data = json.loads((DOCS / "hydrostatic.json").read_text())
    stored = next(r for r in data["rows"] if r["element"] == element and r["size"] == 0.1)
    now = errors(0.1, element)
    assert now["dofs"] == stored["dofs"]
    for kind in ("capillary", "orifice", "flow"):
        for name in ("pressure", "flow", "load", "stiffness"):
            # the errors themselves (1e-2 to 1e-7) recomputed to 1e-9 absolute: the page's numbers are this code's
            assert now[kind][name] == pytest.approx(stored[kind][name], abs=1e-9), (kind, name)
    for name in ("squeeze", "fed", "dynamic"):  # the pad in motion against its closed forms
        assert now["dynamics"][name] == pytest.approx(stored["dynamics"][name], abs=1e-9), name
