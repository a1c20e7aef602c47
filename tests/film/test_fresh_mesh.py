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


def test_boundary_facets_normals_point_out_of_the_film():
    """:func:`boundary_facets` of the outline of a rectangle: unit normals along -phi, +phi, -z, +z on the four
    sides (their centres on the sides), lengths summing to the perimeter 4, the facets' own triangles."""
    mesh = bf.mesh_surface(bf.Surface(arc=(0.0, 1.0), half_width=0.5), 0.2)
    m = mesh.mesh
    facets = np.asarray(mesh.boundaries["outer"])
    fr = film_operators.boundary_facets(m, facets)
    centre = 0.5 * (m.p[:, fr.a] + m.p[:, fr.b])
    np.testing.assert_allclose(np.hypot(*fr.normal), 1.0, rtol=1e-15)
    expected = np.zeros_like(fr.normal)
    expected[0, np.isclose(centre[0], 0.0)], expected[0, np.isclose(centre[0], 1.0)] = -1.0, 1.0
    expected[1, np.isclose(centre[1], -0.5)], expected[1, np.isclose(centre[1], 0.5)] = -1.0, 1.0
    np.testing.assert_allclose(fr.normal, expected, atol=1e-15)
    np.testing.assert_allclose(fr.length.sum(), 4.0, rtol=1e-14)
    assert np.array_equal(fr.elem, m.f2t[0, facets])


@pytest.mark.parametrize("surface, element", [(RECTANGLE, "P1"), (RECTANGLE, "P2"), (CIRCLE, "P2")])
def test_group_field_rows_are_the_nonzeros_of_the_dense_products(surface, element):
    # the flows' group maps evaluate each group's field on the cells it touches only; the reference is the
    # path they replace, the dense products over all cells made sparse: the same entries, bit for bit
    import scipy.sparse as sp

    ops = operators(_mesh(surface), element)
    co = ops.compiled
    U = np.zeros((co.n_dofs, len(co.groups)))
    for k, name in enumerate(co.groups):
        dofs, w = ops.flow_groups[name]
        U[dofs, k] = w
    m = co.maps
    dense = (m.gradient(U, 0), m.gradient(U, 1), m.values(U))
    for rows, full in zip(m.field_rows(U), dense):
        expected = sp.csr_matrix(np.asarray(full).T)
        assert rows.shape == expected.shape and rows.nnz == expected.nnz < full.size / 2
        np.testing.assert_array_equal(rows.indptr, expected.indptr)
        np.testing.assert_array_equal(rows.indices, expected.indices)
        np.testing.assert_array_equal(rows.data, expected.data)


@pytest.mark.parametrize("all_facets", [False, True])
@pytest.mark.parametrize("element", ["P1", "P2"])
def test_corner_facet_data_are_the_rows_of_the_facet_maps(monkeypatch, element, all_facets):
    # the corner dofs' facet data taken from the basis's tables on the kept facets; the reference is the
    # path they replace: the sparse maps of a facet basis on all corner facets, their corner-dof columns and
    # kept rows.
    # With all the groups' facets (not only those next to the corners) most are dropped as zero.
    from bearingfe.film.compiled import _interpolation

    if all_facets:
        monkeypatch.setattr(film_operators, "_corner_facets", lambda m, basis, bnd, groups: {n: bnd[n] for n in groups})
    ops = operators(_mesh(), element)
    co = ops.compiled
    E, Gx, Gz, normals, x, parts = co.corners
    slices = ops.corner_tables[1]
    fb = film_operators.facet_basis(ops.basis, np.concatenate([ops.facet_groups[n] for n in slices]),
                                    film_operators.quadrature_order(element))
    Ef, Gfx, Gfz = _interpolation(fb, co.n_dofs)
    cdofs = np.unique(np.concatenate([d[w < 1] for d, w in (ops.flow_groups[n] for n in slices)]))
    phi_ds = Ef[:, cdofs].toarray().T * np.asarray(fb.dx).ravel()
    n_points = np.shape(fb.dx)[1]
    keep = np.zeros(phi_ds.shape[1], dtype=bool)
    for name, facets in slices.items():
        rows = slice(facets.start * n_points, facets.stop * n_points)
        per_facet = np.abs(phi_ds[:, rows]).reshape(cdofs.size, -1, n_points).max(axis=(0, 2))
        keep[rows] = np.repeat(per_facet > 1e-14 * per_facet.max(), n_points)
        np.testing.assert_array_equal(parts[name][1], phi_ds[:, rows][:, keep[rows]])
    assert keep.any() and (keep.all() != all_facets)
    for mine, full in ((E, Ef), (Gx, Gfx), (Gz, Gfz)):
        assert (mine != full[keep]).nnz == 0
    np.testing.assert_array_equal(normals, np.asarray(fb.normals).reshape(2, -1)[:, keep])
    np.testing.assert_array_equal(x, np.asarray(fb.global_coordinates()).reshape(2, -1)[:, keep])


def test_pattern_blocks_are_scipys_fancy_indexing():
    # the condensed blocks' positions and patterns by index arithmetic; the reference is the path they replace,
    # scipy's fancy indexing of a matrix holding each entry's position, indices then sorted: the same arrays
    import scipy.sparse as sp
    from bearingfe.film.compiled import _block

    co = operators(_mesh(), "P2").compiled
    n, rng = co.n_dofs, np.random.default_rng(5)
    carrier = sp.csr_matrix((np.arange(1, co.nnz + 1, dtype=float), co.indices, co.indptr), shape=(n, n))
    cases = [(co.interior, co.interior), (co.interior, co.inlet), (co.interior, rng.permutation(co.inlet)),
             (rng.permutation(n)[:40], rng.permutation(n)[:300]), (co.interior, np.zeros(0, np.int64))]
    for rows, cols in cases:
        expected = carrier[rows][:, cols].tocsr()
        expected.sort_indices()
        positions, indices, indptr = _block(co.indptr, co.indices, rows, cols, n)
        np.testing.assert_array_equal(positions, expected.data.astype(np.int64) - 1)
        np.testing.assert_array_equal(indices, expected.indices)
        np.testing.assert_array_equal(indptr, expected.indptr)


@pytest.mark.parametrize("surface, element", [(RECTANGLE, "P1"), (RECTANGLE, "P2"), (CIRCLE, "P2")])
def test_facet_geometry_is_the_facet_basis_geometry(surface, element):
    # the pocket contour's points, normals and weights without the basis functions; the reference is the
    # facet basis they were taken from before: the same numbers, bit for bit (straight and curved maps); first
    # on a straight map without scikit-fem's map of every facet (the facets' own, _facet_map), then with it
    ops = operators(_mesh(surface), element)
    facets = ops.mesh.boundaries["inlet"]
    straight = type(ops.basis.mapping).__name__ == "MappingAffine"
    assert not hasattr(ops.basis.mapping, "_B") or not straight
    x, n, dx = film_operators.facet_geometry(ops.basis, facets, 8)
    assert not hasattr(ops.basis.mapping, "_B") or not straight
    fb = film_operators.facet_basis(ops.basis, facets, 8)
    assert all(np.array_equal(u, v) for u, v in zip((x, n, dx), film_operators.facet_geometry(ops.basis, facets, 8)))
    np.testing.assert_array_equal(x, np.asarray(fb.global_coordinates()))
    np.testing.assert_array_equal(n, np.asarray(fb.normals))
    np.testing.assert_array_equal(dx, np.asarray(fb.dx))


@pytest.mark.parametrize("unused", [0, 2**16])  # dofs beyond the cells' (empty rows): the sort of > 2^16 columns
@pytest.mark.parametrize("element", ["P1", "P2"])
def test_pattern_from_the_upper_pairs_is_the_element_matrices_union(element, unused):
    # the pattern, twins and upper rows found from the local pairs i <= j; the references: scipy's sum of
    # the element matrices' patterns, _twins (searches each entry's twin in the pattern), and for every
    # local pair the rank of its (min, max) dof pair among the upper entries: the same integers
    import scipy.sparse as sp
    from bearingfe.film.compiled import _pattern, _twins

    ops = operators(_mesh(), element)
    dofs, n = np.asarray(ops.basis.element_dofs), ops.n_dofs + unused
    indptr, indices, (twins, n_upper), upper_rows = _pattern(dofs, n)
    nb = dofs.shape[0]
    rows, cols = np.repeat(dofs, nb, axis=0).ravel(), np.tile(dofs, (nb, 1)).ravel()
    union = sp.csr_matrix((np.ones(rows.size), (rows, cols)), shape=(n, n))
    union.sum_duplicates()
    np.testing.assert_array_equal(indptr, union.indptr)
    np.testing.assert_array_equal(indices, union.indices)
    expected_twins, expected_upper = _twins(union.indptr, union.indices, n)
    np.testing.assert_array_equal(twins, expected_twins)
    assert n_upper == expected_upper
    entry_rows = np.repeat(np.arange(n), np.diff(indptr))
    upper_keys = (entry_rows.astype(np.int64) * n + indices)[entry_rows <= indices]
    i, j = np.triu_indices(nb)
    pair_keys = np.minimum(dofs[i], dofs[j]).astype(np.int64) * n + np.maximum(dofs[i], dofs[j])
    np.testing.assert_array_equal(upper_rows, np.searchsorted(upper_keys, pair_keys))


@pytest.mark.parametrize("surface, element", [(RECTANGLE, "P1"), (RECTANGLE, "P2"), (CIRCLE, "P2")])
def test_facet_tables_are_the_facet_basis_numbers(surface, element):
    # the basis functions, points, normals and weights on facets from the facet basis's own calls without the
    # facet basis; the reference is scikit-fem's facet basis: the same numbers, bit for bit (straight and curved)
    ops = operators(_mesh(surface), element)
    facets = np.concatenate([ops.mesh.boundaries["inlet"], ops.mesh.boundaries["side"]])
    mine = film_operators.facet_tables(ops.basis, facets, 6)   # (before the facet basis builds every facet's map)
    fb = film_operators.facet_basis(ops.basis, facets, 6)
    np.testing.assert_array_equal(mine.dofs, fb.element_dofs)
    for j, phi in enumerate(fb.basis):
        np.testing.assert_array_equal(mine.tables[0, j], np.asarray(phi[0]))
        np.testing.assert_array_equal(mine.tables[1, j], phi[0].grad[0])
        np.testing.assert_array_equal(mine.tables[2, j], phi[0].grad[1])
    np.testing.assert_array_equal(mine.x, np.asarray(fb.global_coordinates()))
    np.testing.assert_array_equal(mine.normals, np.asarray(fb.normals))
    np.testing.assert_array_equal(mine.dx, np.asarray(fb.dx))


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_facet_dofs_are_scikit_fems(element):
    # the dofs on boundary facets by a mask; the reference is scikit-fem's get_dofs(...).all(): the same array
    ops = operators(_mesh(CIRCLE), element)
    for name, facets in ops.mesh.boundaries.items():
        expected = ops.basis.get_dofs(facets).all()
        mine = film_operators.facet_dofs(ops.basis, facets)
        np.testing.assert_array_equal(mine, expected)
        assert mine.dtype == expected.dtype and mine.size > 0


@pytest.mark.parametrize("surface, order", [(RECTANGLE, 1), (RECTANGLE, 2), (CIRCLE, 2)])
def test_boundary_facet_triangles_without_the_inverse_map(surface, order):
    # the triangles of boundary facets found among the triangles with two nodes on them are scikit-fem's
    # facet-to-triangle map's (built afterwards, on a copy); facets of two triangles take the map; the
    # pockets' moments of a fresh mesh, which no longer builds the map, are the same numbers bit for bit
    import copy

    from bearingfe.geometry.meshing import give_facet_triangles

    mesh = bf.mesh_surface(surface, 0.25, corner_size=0.05, order=order)
    m = copy.deepcopy(mesh.mesh)
    assert not hasattr(m, "_f2t")
    outer, inlet = np.asarray(mesh.boundaries["outer"]), np.asarray(mesh.boundaries["inlet"])
    every = np.concatenate([inlet, outer[::-1]])
    interior = np.flatnonzero(mesh.mesh.f2t[1] >= 0)[:7]
    got = film_operators.boundary_facet_triangles(m, every)
    assert not hasattr(m, "_f2t")
    assert np.array_equal(got, mesh.mesh.f2t[0, every])
    assert np.array_equal(film_operators.boundary_facet_triangles(m, np.concatenate([every[:3], interior])),
                          mesh.mesh.f2t[0, np.concatenate([every[:3], interior])])
    element = "P1" if order == 1 else "P2"
    fresh = copy.deepcopy(mesh)
    fresh.mesh.__dict__.pop("_f2t", None)
    moments = operators(fresh, element).pocket_moments
    assert not hasattr(fresh.mesh, "_f2t")
    mapped = copy.deepcopy(fresh)
    mapped._cache.clear()
    give_facet_triangles(mapped.mesh)
    assert np.array_equal(moments, operators(mapped, element).pocket_moments)


@pytest.mark.parametrize("surface, order", [(RECTANGLE, 1), (CIRCLE, 1), (CIRCLE, 2)])
def test_boundary_facet_triangles_from_t2f_are_the_node_pair_searchs(surface, order):
    # where the mesh has scikit-fem's triangle-to-facet map t2f (gmsh meshes keep it), the triangles of boundary
    # facets are read off it: the same as the node-pair search (the mesh without t2f) and scikit-fem's
    # facet-to-triangle map, without building the latter; repeated, interior or unknown facets take the map
    import copy

    mesh = bf.mesh_surface(surface, 0.25, corner_size=0.05, order=order)
    m = copy.deepcopy(mesh.mesh)
    assert hasattr(m, "_t2f") and not hasattr(m, "_f2t")
    bare = copy.deepcopy(m)
    del bare.__dict__["_t2f"]
    outer, inlet = np.asarray(mesh.boundaries["outer"]), np.asarray(mesh.boundaries["inlet"])
    every = np.concatenate([inlet, outer[::-1]])
    for facets in (inlet, outer[::-1], every, every[::7]):
        got = film_operators.boundary_facet_triangles(m, facets)
        assert np.array_equal(got, film_operators.boundary_facet_triangles(bare, facets))
        assert np.array_equal(got, mesh.mesh.f2t[0, facets]) and got.dtype == np.int64
    assert not hasattr(m, "_f2t") and not hasattr(bare, "_t2f")
    interior = np.flatnonzero(mesh.mesh.f2t[1] >= 0)[:7]
    n_facets = m.facets.shape[1]
    assert film_operators._facet_owners(m.t2f, np.concatenate([every[:3], interior]), n_facets) is None
    assert film_operators._facet_owners(m.t2f, np.concatenate([inlet, inlet[:2]]), n_facets) is None
    assert film_operators._facet_owners(m.t2f, np.concatenate([interior[:1], every[:1]]), n_facets) is None
    for facets in (np.concatenate([every[:3], interior]), np.concatenate([inlet, inlet[:2]])):
        assert np.array_equal(film_operators.boundary_facet_triangles(copy.deepcopy(m), facets),
                              mesh.mesh.f2t[0, facets])


@pytest.mark.parametrize("surface, element", [(RECTANGLE, "P1"), (RECTANGLE, "P2"), (CIRCLE, "P2")])
def test_interior_dofs_and_corner_facets_are_their_definitions(surface, element):
    # the interior dofs by a mask of the outline's and the pockets' dofs, and each outflow group's facets at the
    # dofs it shares with another; the references are the set operations they replace (np.setdiff1d of
    # np.union1d; the shared dofs by np.unique, each a vertex dof by np.isin): the same arrays
    ops = operators(_mesh(surface), element)
    basis, m = ops.basis, ops.mesh.mesh
    assert np.array_equal(ops.interior, np.setdiff1d(np.arange(basis.N), np.union1d(ops.outer, ops.inlet)))
    groups = {k: v for k, v in ops.flow_groups.items() if k != "inlet"}
    shared = np.unique(np.concatenate([d[w < 1] for d, w in groups.values()]))
    vertex = np.asarray(basis.nodal_dofs)[0]
    assert shared.size and np.isin(shared, vertex).all()
    owner = np.full(basis.N, -1)
    owner[vertex] = np.arange(vertex.size)
    for name in groups:
        f = np.asarray(ops.mesh.boundaries[name])
        near = f[np.isin(m.facets[:, f], owner[shared]).any(axis=0)]
        assert np.array_equal(ops.facet_groups.get(name, np.zeros(0, f.dtype)), near), name
