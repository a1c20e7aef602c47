"""The elastic_fft section of the benchmark page is its stored run, and the run says what the part claims.

``docs/benchmarks_parts/elastic_fft.md`` and ``.json`` are written by ``benchmarks/run_all.py``
(part ``elastic_fft``, :mod:`benchmarks.elastic_fft`). Expected values: the page text is
re-derived here from the stored rows by the same report function (timings are never asserted);
the rows must show the two paths agreeing to the solver tolerance (1e-8 c) where both ran, the
FFT path converged up to 1e5 unknowns, and its answer settling under refinement; on gmsh meshes the
grid transfer's difference from the dense map shrinking with the mesh; the deflection squeeze's
transient running matrix-free above the dense cap and equal to the dense run on the same map.
"""

import json

from benchmarks import elastic_fft
from tests.helpers import ROOT

PART = ROOT / "docs" / "benchmarks_parts" / "elastic_fft"


def test_page_is_the_report_of_its_rows():
    facts = json.loads(PART.with_suffix(".json").read_text())
    text, again = elastic_fft.report(facts["rows"])
    page = PART.with_suffix(".md").read_text()
    assert page.split("\n", 2)[2] == text  # after the part's stamp line and a blank line
    assert again["fft_solve_slope"] == facts["fft_solve_slope"]


def test_rows_show_the_claims():
    stored = json.loads(PART.with_suffix(".json").read_text())["rows"]
    rows = [r for r in stored if r["mesh"] == "grid"]
    assert max(r["dofs"] for r in rows) > 9e4  # the goal: 1e5 film unknowns on the elastic support
    both = [r for r in rows if r["dense_solve"] is not None]
    assert both and all(r["dofs"] <= 4000 for r in both)  # dense only below its limit
    assert all(r["difference"] <= 1e-8 for r in both)  # converged to 1e-8 c each: the same answer
    assert all(r["residual"] <= 1e-8 for r in rows)
    # the largest opening converges under refinement: consecutive sizes move it by less each time
    w = [r["max_deflection"] for r in sorted(rows, key=lambda r: r["dofs"])]
    steps = [abs(b - a) for a, b in zip(w, w[1:])]
    assert all(b < a for a, b in zip(steps, steps[1:])) and steps[-1] < 1e-3 * w[-1]
    # gmsh meshes through the auxiliary grid: up to 1e5 unknowns; an approximation of the dense map whose
    # difference (relative to the largest opening) shrinks with the mesh and stays under 1 %, force under 1e-3
    gmsh = sorted((r for r in stored if r["mesh"] == "gmsh"), key=lambda r: r["dofs"])
    assert gmsh[-1]["dofs"] > 9e4 and all(r["residual"] <= 1e-8 for r in gmsh)
    compared = [r for r in gmsh if r["difference"] is not None]
    assert len(compared) >= 2
    relative = [r["difference"] / r["max_deflection"] for r in compared]
    assert all(b < a for a, b in zip(relative, relative[1:])) and relative[0] < 1e-2
    assert all(r["force_difference"] < 1e-3 for r in compared)


def test_transient_rows_show_the_claims():
    """The transient table (simulate_elastic, the deflection's squeeze): the matrix-free path completes above
    the dense limit; on the dense map held as its product it is the dense run to 1e-6 (its inner GMRES
    tolerances; the integrator's rtol is 1e-5); the grid half-space's film is the dense one's within 1e-3 c
    (the grid transfer's approximation, second order in its spacing) and takes nearly the dense steps."""
    stored = json.loads(PART.with_suffix(".json").read_text())["rows"]
    rows = sorted((r for r in stored if r["mesh"] == "transient"), key=lambda r: r["dofs"])
    assert rows and all(r["status"] == "completed" for r in rows)
    assert rows[-1]["dofs"] > 4000 and rows[-1]["dense"] is None  # above the dense cap: the product path only
    both = [r for r in rows if r["dense"] is not None]
    assert both and all(r["difference"] < 1e-3 for r in both)
    assert all(abs(r["steps"] - r["dense_steps"]) <= 0.1 * r["dense_steps"] for r in both)
    same = [r["same_map"] for r in rows if r["same_map"] is not None]
    assert same and max(same) < 1e-6
