"""The lean compiled maps: per-element data on affine cells gives the per-point maps' numbers to round-off,
the mesh's basis drops its per-point arrays after compiling, and what the compiled operator keeps per cell.

References: scikit-fem's own basis (``skfem.CellBasis``, the values and gradients at the quadrature points) and
the sparse per-point maps built from it (:func:`bearingfe.film.compiled.interpolation_maps`, the path of the
curved cells): the same sums in another order, so they agree to round-off (relative 1e-12 is ~1000x the
differences measured here, 1e-15 .. 1e-14).
"""

from __future__ import annotations

import numpy as np
import pytest
import skfem

import bearingfe as bf
from bearingfe.film import operators
from bearingfe.film.compiled import _AffineMaps, _affine_scatter, _scatter, _SparseMaps, interpolation_maps
from bearingfe.film.mesh_operators import LeanCellBasis, quadrature_order
from bearingfe.core.parameters import ELEMENTS

RTOL = 1e-12
SURFACE = bf.Surface(arc=(-1.2, 1.2), half_width=0.6, inlets=(bf.Circle((0.1, 0.05), 0.2),))
FILM = bf.CosineFilm(0.55, 2.6)


def _close(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert a.shape == b.shape
    assert np.max(np.abs(a - b)) <= RTOL * np.max(np.abs(b))


@pytest.fixture(scope="module")
def mesh():
    return bf.mesh_surface(SURFACE, 0.3)


def _reference_basis(mesh, element):
    m = mesh.mesh
    return skfem.Basis(m, ELEMENTS[element](), intorder=quadrature_order(element))


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_per_element_maps_equal_the_per_point_maps(mesh, element):
    basis = _reference_basis(mesh, element)
    assert _AffineMaps.applies(basis)
    maps = _AffineMaps(basis, np.ascontiguousarray(basis.dx))
    E, Gx, Gz = interpolation_maps(basis)
    rng = np.random.default_rng(1)
    u, w = rng.standard_normal((basis.N, 3)), rng.standard_normal((E.shape[0], 2))
    for k, G in enumerate((Gx, Gz)):
        _close(maps.gradient(u, k), G @ u)
        _close(maps.gradient(u[:, 0], k), G @ u[:, 0])
        _close(maps.integrate_gradient(w, k), G.T @ w)
    _close(maps.values(u), E @ u)
    _close(maps.values(u[:, :1]), E @ u[:, :1])
    _close(maps.integrate_value(w[:, 0]), E.T @ w[:, 0])
    for mine, ref in zip(maps.sparse(), (E, Gx, Gz)):  # the matrices the elastic and dynamic paths take
        _close(mine.toarray(), ref.toarray())


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_per_element_scatters_equal_the_per_point_scatters(mesh, element):
    co = operators(mesh, element).compiled
    assert isinstance(co.maps, _AffineMaps)
    basis = _reference_basis(mesh, element)
    c = 1.0 + 0.5 * np.cos(np.arange(co.dx.size))
    for kind in ("stiff", "mass"):
        lean = _affine_scatter(co.maps, co._rows, co.twins[1], kind)
        per_point = _scatter(basis, co._rows, co.twins[1], kind)
        _close(lean @ c, per_point @ c)


def test_curved_cells_keep_the_per_point_maps():
    # the isoparametric map of a curved P2 mesh is not affine: the sparse per-point maps (today's path)
    co = operators(bf.mesh_surface(SURFACE, 0.35, order=2), "P2").compiled
    assert isinstance(co.maps, _SparseMaps)


def test_the_lean_basis_is_scikit_fems_and_rebuilds_what_it_dropped(mesh):
    ref = _reference_basis(mesh, "P2")
    lean = LeanCellBasis(mesh.mesh, ELEMENTS["P2"](), intorder=quadrature_order("P2"))
    for _ in range(2):  # built on first use; released; rebuilt equal (bit for bit: the same expressions)
        np.testing.assert_array_equal(lean.dx, ref.dx)
        for a, b in zip(lean.basis, ref.basis):
            np.testing.assert_array_equal(a[0].grad, b[0].grad)
            np.testing.assert_array_equal(np.asarray(a[0]), np.asarray(b[0]))
        np.testing.assert_array_equal(lean.interpolate(np.arange(lean.N, dtype=float)).grad,
                                      ref.interpolate(np.arange(ref.N, dtype=float)).grad)
        lean.release()
        assert lean.__dict__["_values"] is None and lean.__dict__["_dx"] is None


def _array_bytes(obj, seen: set) -> int:
    """Bytes of the numpy arrays reachable from ``obj`` (each buffer once)."""
    if isinstance(obj, np.ndarray):
        base = obj
        while isinstance(base.base, np.ndarray):
            base = base.base
        if id(base) in seen:
            return 0
        seen.add(id(base))
        return base.nbytes
    plain = isinstance(obj, (str, bytes, int, float, type)) or callable(obj) and not hasattr(obj, "__dict__")
    if id(obj) in seen or plain:
        return 0
    seen.add(id(obj))
    if isinstance(obj, (tuple, list)):
        return sum(_array_bytes(x, seen) for x in obj)
    if isinstance(obj, dict):
        return sum(_array_bytes(x, seen) for x in obj.values())
    if hasattr(obj, "data") and hasattr(obj, "indices"):  # scipy sparse
        return sum(_array_bytes(getattr(obj, a), seen) for a in ("data", "indices", "indptr") if hasattr(obj, a))
    if hasattr(obj, "__dict__") and not isinstance(obj, (skfem.Mesh, skfem.CellBasis)):
        return sum(_array_bytes(x, seen) for x in vars(obj).values())
    return 0


def test_a_p1_solve_keeps_a_few_hundred_bytes_per_cell():
    # after a direct P1 solve the compiled operator holds per cell: the weights (6 points, 48 B), the angles of
    # the points (96 B), the element's dofs and inverse Jacobian (12 + 32 B), the pairs' upper rows (24 B), the
    # stiffness cell constants (24 B), the pattern, its blocks and the band plan (about 3.5 entries per cell, a
    # few int arrays each): 369 B measured. The per-point maps and scatters it replaced held 1467 B per cell on
    # this mesh (E, G_phi, G_z: 3 x 6 points x 3 x 12 B, the stiffness pair values 6 x 6 x 8 B, the loads
    # 144 B, the points 96 B, ...), and the basis another 316 B; 600 B is the bound.
    mesh = bf.grid_mesh(bf.Surface(arc=(-1.0, 1.0), half_width=0.5), 1 / 30)
    bf.solve_reynolds(mesh, FILM, formulation="direct", element="P1")
    ops = operators(mesh, "P1")
    co = ops.compiled
    n_cells = mesh.mesh.nelements
    per_cell = _array_bytes(co, set()) / n_cells
    assert 300 < per_cell < 600, per_cell
    # and the mesh's basis holds no per-point arrays (they would be 15 floats per point)
    assert ops.basis.__dict__["_values"] is None and ops.basis.__dict__["_dx"] is None
