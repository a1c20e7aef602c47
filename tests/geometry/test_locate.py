"""Point location on triangle meshes (bearingfe.geometry.locate)."""

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.geometry.locate import barycentric, containing_cells, lattice_cells, probe_matrices

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
