"""A first solve on a fresh mesh takes shortcuts that must not change its numbers.

The shortcuts (what FEM against FD at equal error on a fresh mesh measures,
docs/benchmarks.md): an affine map on quadratic meshes whose edges are all
straight, the facet fluxes of the outline corners on the facets next to the
corners only, and the matrix values as per-point pair products scattered
onto the pattern. Each is
compared with the path it replaces: relative 1e-12, ~300x the worst
difference measured on these cases (3.7e-15; round-off only: the same
discrete equations, summed in another order).
"""

from __future__ import annotations

import numpy as np
import pytest
import skfem
from skfem.mapping import MappingAffine

import bearingfe as bf
from bearingfe.film import forms
from bearingfe.film import mesh_operators as film_operators
from bearingfe.film.forms import TolerantMapping, mapping, straight_edges
from bearingfe.film import operators

RTOL = 1e-12
RECTANGLE = bf.Surface(arc=(-0.6, 0.6), half_width=0.5,
                       inlets=(bf.Rectangle((0.05, 0.0), (0.48, 0.4)),))  # the benchmark's case (b), off centre
CIRCLE = bf.Surface(arc=(-0.6, 0.6), half_width=0.5, inlets=(bf.Circle((0.05, 0.0), 0.2),))
FILM = bf.CosineFilm(0.5, 3.0)
POINT = dict(wedge=1.0, squeeze=(0.3, -0.2), inlet_pressure=50.0)


def _mesh(surface=RECTANGLE):
    return bf.mesh_surface(surface, 0.25, corner_size=0.05, order=2)


def _close(a, b, scale=None):
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = np.max(np.abs(b)) if scale is None else scale
    assert np.max(np.abs(a - b)) <= RTOL * scale


def test_quadratic_meshes_with_straight_edges_get_an_affine_map():
    straight, curved = _mesh().mesh, _mesh(CIRCLE).mesh
    assert isinstance(straight, skfem.MeshTri2) and isinstance(curved, skfem.MeshTri2)
    assert straight_edges(straight) and isinstance(mapping(straight), MappingAffine)
    assert not straight_edges(curved) and isinstance(mapping(curved), TolerantMapping)
    # one edge node moved off its midpoint by 1e-6 of the extent makes the mesh curved
    nodes = straight.doflocs.copy()
    nodes[1, int(straight.t.max()) + 1 + 7] += 1e-6
    assert not straight_edges(skfem.MeshTri2(nodes, straight.t))
    assert mapping(bf.mesh_surface(RECTANGLE, 0.25).mesh) is None  # order 1: scikit-fem's own


@pytest.mark.parametrize("formulation", ["pi", "direct"])
def test_the_affine_map_gives_the_isoparametric_numbers(monkeypatch, formulation, results_agree):
    fast = bf.solve_reynolds(_mesh(), FILM, formulation=formulation, element="P2", **POINT)
    monkeypatch.setattr(forms, "straight_edges", lambda m: False)
    iso_mesh = _mesh()  # a new mesh object: the map is chosen once per mesh
    assert isinstance(mapping(iso_mesh.mesh), TolerantMapping)
    iso = bf.solve_reynolds(iso_mesh, FILM, formulation=formulation, element="P2", **POINT)
    results_agree(fast, iso, RTOL)


@pytest.mark.parametrize("assembly", ["compiled", "reference"])
@pytest.mark.parametrize("element", ["P1", "P2"])
def test_corner_fluxes_on_the_corner_facets_equal_those_on_all_facets(monkeypatch, element, assembly, results_agree):
    mesh = _mesh()
    ops = operators(mesh, element)
    corners = {n: len(f) for n, f in ops.facet_groups.items()}
    assert set(corners) == {"side", "arc_start", "arc_end"}
    assert sum(corners.values()) <= 8  # two facets at each of the outline's four corners
    near = bf.superpose(mesh, FILM, element=element, assembly=assembly).combine(**POINT)
    monkeypatch.setattr(film_operators, "_corner_facets", lambda m, basis, bnd, groups: {n: bnd[n] for n in groups})
    everywhere_mesh = _mesh()
    assert sum(len(f) for f in operators(everywhere_mesh, element).facet_groups.values()) > 8
    everywhere = bf.superpose(everywhere_mesh, FILM, element=element, assembly=assembly).combine(**POINT)
    results_agree(near, everywhere, RTOL)


def test_a_films_numbers_do_not_depend_on_the_films_solved_before_it():
    # every film, a fresh mesh's first included, is factored in the ordering found on the first: the
    # same film gives bit-identical fields before and after another film was solved on the mesh
    mesh = _mesh()
    first = bf.superpose(mesh, FILM, formulation="direct", element="P2")
    bf.superpose(mesh, bf.CosineFilm(0.3, 1.0), formulation="direct", element="P2")
    again = bf.superpose(mesh, FILM, formulation="direct", element="P2")
    np.testing.assert_array_equal(first.fields, again.fields)
    _close(first.system.matrix @ first.system.solve(first.system.rhs), first.system.rhs)


def test_scatter_equals_its_sparse_matrix():
    co = operators(_mesh(), "P2").compiled
    c = np.cos(np.arange(co.dx.size))
    for scatter in (co.stiffness_scatter, co.mass_scatter):
        _close(scatter @ c, scatter.tocsr() @ c)


def test_pocket_moments_of_a_rectangle_are_its_area_and_cosine_moments():
    # closed form for the pocket (0.05, 0) +- (0.24, 0.2): area, int cos(phi) and int sin(phi) over it;
    # the straight contour is integrated with the tabulated 5-point Gauss rule (exact to ~1e-13 here)
    a, b, width = 0.05 - 0.24, 0.05 + 0.24, 0.4
    exact = [width * (b - a), width * (np.sin(b) - np.sin(a)), width * (np.cos(a) - np.cos(b))]
    for element in ("P1", "P2"):
        np.testing.assert_allclose(operators(_mesh(), element).pocket_moments, exact, rtol=1e-12, atol=1e-14)
