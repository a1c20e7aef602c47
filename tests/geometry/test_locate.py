"""Point location on triangle meshes (bearingfe.geometry.locate)."""

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.geometry.locate import (barycentric, containing_cells, lattice_cells, probe_matrices, probes,
                                      values_in_cells)

POCKET = bf.Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=[bf.Circle((0.0, 0.0), 0.1748)])


def test_lattice_cells_hold_the_same_nodes_as_the_search():
    # Reference: containing_cells (k-d tree of centroids, barycentric tests) on the same lattice nodes of a
    # gmsh mesh with a pocket hole: the same nodes found (-1 in the hole and outside the curved outline of
    # the pocket), and every found cell holds its node (a node on a shared edge may get either triangle).
    m = bf.mesh_surface(POCKET, 0.05).mesh
    lo, hi = m.p.min(axis=1), m.p.max(axis=1)
    shape = (61, 41)
    step = ((hi[0] - lo[0]) / (shape[0] - 1), (hi[1] - lo[1]) / (shape[1] - 1))
    cells = lattice_cells(m.p, m.t, lo, step, shape).ravel()
    i, k = np.divmod(np.arange(shape[0] * shape[1]), shape[1])
    nodes = np.array([lo[0] + i * step[0], lo[1] + k * step[1]])
    searched = containing_cells(m.p, m.t, nodes)
    assert np.array_equal(cells >= 0, searched >= 0)
    assert 0 < (cells < 0).sum() < cells.size // 10
    found = cells >= 0
    l1, l2 = barycentric(m.p, m.t, cells[found], nodes[:, found])
    assert min(l1.min(), l2.min(), (1.0 - l1 - l2).min()) >= -1e-10


def test_probe_matrices_take_given_cells_and_check_them():
    # the same maps with the cells given as found by the search, and a clear error for a bad cell array
    mesh = bf.mesh_surface(POCKET, 0.1)
    basis = bf.reynolds.operators(mesh, "P2").basis
    x = np.array([[0.3, -0.4, 0.5], [0.1, 0.2, -0.3]])
    given = probe_matrices(basis, x, containing_cells(mesh.mesh.p, mesh.mesh.t, x))
    for a, b in zip(given, probe_matrices(basis, x)):
        assert np.abs((a - b).toarray()).max() <= 1e-12
    with pytest.raises(ValueError, match="cells must hold one cell"):
        probe_matrices(basis, x, np.array([0, -1, 2]))


def test_values_in_cells_are_the_fields_values():
    # a P2 field of a quadratic and a P1 field of a linear function (which the elements reproduce exactly): the
    # function's values at random points of given cells to 1e-12; scikit-fem's probes (element search and
    # reference mapping) give the same values for a field that is not polynomial; bad input names the parameter
    import skfem

    mesh = bf.mesh_surface(POCKET, 0.1)
    m = mesh.mesh
    rng = np.random.default_rng(5)
    cells = rng.integers(0, m.nelements, 400)
    w = rng.dirichlet(np.ones(3), cells.size).T
    points = np.einsum("ikn,kn->in", m.p[:, m.t[:, cells]], w)

    def quadratic(x):
        return 1.0 + 2.0 * x[0] - x[1] + 3.0 * x[0] ** 2 - 2.0 * x[0] * x[1] + 0.5 * x[1] ** 2
    for element, f in (("P2", quadratic), ("P1", lambda x: 1.0 + 2.0 * x[0] - 3.0 * x[1])):
        basis = bf.reynolds.operators(mesh, element).basis
        u = f(np.asarray(basis.doflocs))
        assert np.abs(values_in_cells(basis, u, points, cells) - f(points)).max() <= 1e-12
        u = np.sin(3.0 * np.asarray(basis.doflocs)[0]) * np.cos(2.0 * np.asarray(basis.doflocs)[1])
        assert np.abs(values_in_cells(basis, u, points, cells) - probes(basis, points) @ u).max() <= 1e-12
    with pytest.raises(ValueError, match="u must have shape"):
        values_in_cells(basis, u[:-1], points, cells)
    with pytest.raises(ValueError, match="points must have shape"):
        values_in_cells(basis, u, points, cells[:-1])
    with pytest.raises(ValueError, match="ElementTriP1 or ElementTriP2"):
        values_in_cells(skfem.Basis(m, skfem.ElementTriP3()), u, points, cells)
