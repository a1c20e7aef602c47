"""The JFO assembly and postprocess computed block by block: the same numbers, bit for bit, as the formulas over
all quadrature points at once (the previous path, written out here), whatever the block size."""

import numpy as np
import pytest

from bearingfe import Circle, CosineFilm, Recess, Surface, grid_mesh, mesh_surface
from bearingfe.film import finite_volume as fv
from bearingfe.film.mesh_operators import operators
from bearingfe.film.thickness import UniformFilm


def _dimpled(n_side=3, radius=0.1, depth=0.8):
    pitch = 1.0 / n_side
    dimples = [Recess(Circle((pitch * (i + 0.5), pitch * (j + 0.5) - 0.5), radius), depth)
               for i in range(n_side) for j in range(n_side)]
    return Surface(arc=(0.0, 1.0), half_width=0.5, recesses=dimples)


FILM = CosineFilm(0.3, 1.0)   # a film that varies over the cells and opens (a cavity), a uniform one would hide
# the order of the points


@pytest.mark.parametrize("kind", ["grid", "gmsh"])
def test_quadrature_points_and_weights_are_scikit_fems(kind):
    mesh = grid_mesh(_dimpled(), 1 / 40) if kind == "grid" else mesh_surface(_dimpled(), 0.08)
    basis = operators(mesh).basis
    mapping = basis.mapping
    assert np.array_equal(operators(mesh).x, np.array(mapping.F(basis.X)))
    reference = np.abs(mapping.detDF(basis.X)) * np.broadcast_to(basis.W, (basis.nelems, basis.W.size))
    dx = basis.dx
    assert np.array_equal(dx, reference) and dx.strides == reference.strides   # the layout the sums rely on


def _systems(monkeypatch, block):
    monkeypatch.setattr(fv, "BLOCK", block)
    monkeypatch.setattr(fv, "INTERPOLATE_BLOCK", block)
    mesh = grid_mesh(_dimpled(), 1 / 70)   # 5,041 nodes: a nested start
    ops = fv.operators(mesh)
    system = fv._assemble(ops, mesh, FILM, 1.0, (0.0, 0.0), None, None, "grid")
    result = fv.solve_jfo(mesh, FILM, cavitation_pressure=-0.05, couette="grid")
    return mesh, ops, system, result


def test_blocks_of_any_size_give_the_same_system_and_result(monkeypatch):
    *_, one, r_one = _systems(monkeypatch, 10**9)     # one block: the arrays of all points at once
    mesh, ops, small, r_small = _systems(monkeypatch, 37)   # blocks of 37 triangles or faces, the last one short
    for name in ("h_q", "inv_h_q", "hdot_q", "area", "storage", "face_film"):
        assert np.array_equal(getattr(one, name), getattr(small, name)), name
    for name in ("K", "C"):
        assert (getattr(one, name) != getattr(small, name)).nnz == 0, name
    assert r_one.cavitated.any() and r_one.cost["nested_levels"] >= 1
    assert (r_one.friction, r_one.integral, *r_one.force) == (r_small.friction, r_small.integral, *r_small.force)


def test_assembly_equals_the_formulas_over_all_points(monkeypatch):
    mesh, ops, system, result = _systems(monkeypatch, 37)
    x = ops.x
    cells = fv._cells(mesh, ops)
    # the previous path: h, 1/h and h^3 at every quadrature point, the cut cells' means put in, K from h^3/12
    h = np.asarray(FILM.thickness(x[0], x[1]), float) + 0.0 * x[0] + fv._quadrature_depth(mesh, x)
    inv, h3 = 1.0 / h, h**3
    cut, h_m, inv_m, h3_m = fv._cell_means(mesh, FILM, x)
    assert cut.size > 0
    h[cut], inv[cut], h3[cut] = h_m[:, None], inv_m[:, None], h3_m[:, None]
    assert np.array_equal(system.h_q, h) and np.array_equal(system.inv_h_q, inv)
    assert (system.K != fv._stiffness(cells, h3 / 12.0)).nnz == 0
    assert np.array_equal(system.area, fv._load(cells, np.ones_like(h)))
    # the postprocess's sums over the points: those of the whole arrays
    pq, dp = fv._interpolate(cells, result.pressure)
    ut = result.pressure[cells.t]
    assert np.array_equal(pq, ut[0][:, None] * cells.lam[0] + ut[1][:, None] * cells.lam[1]
                          + ut[2][:, None] * cells.lam[2])
    assert result.integral == float(np.sum(pq * cells.dx))
    assert result.force[0] == np.sum(pq * np.cos(x[0]) * cells.dx)
    assert result.force[1] == np.sum(pq * np.sin(x[0]) * cells.dx)


def test_overlaps_sorted_by_x0_are_those_of_the_plain_test(monkeypatch):
    """The overlaps found on the rectangles sorted by ``x0`` (two binary searches per recess) are those of the
    plain test and of the formula written out, in the same (increasing) order: random rectangles, lines among
    them."""
    surface = _dimpled(n_side=4)
    rng = np.random.default_rng(3)
    n = 3 * fv.OVERLAPS_SORTED_FROM   # the sorted path (16 recesses)
    x0, z0 = rng.uniform(-0.1, 1.1, n), rng.uniform(-0.6, 0.6, n)
    x1, z1 = x0 + rng.uniform(0.0, 0.05, n), z0 + rng.uniform(0.0, 0.05, n)
    x0[:5] = x1[:5] = np.linspace(0.0, 1.0, 5)   # lines (no width)
    lo, hi = fv._recess_boxes(surface)[5]   # the widest rectangles ending on a box's lower phi end, and lines there
    x1[5:8], x0[5:8], z0[5:8], z1[5:8] = lo[0], lo[0] - 0.06, lo[1], hi[1]
    x0[8], x1[8], z0[8], z1[8] = lo[0], lo[0], lo[1], lo[1]
    sorted_ = fv._overlaps(surface, x0, x1, z0, z1)
    monkeypatch.setattr(fv, "OVERLAPS_SORTED_FROM", 10**12)
    plain = fv._overlaps(surface, x0, x1, z0, z1)
    assert len(sorted_) == len(plain) == 16 and sum(p.size for p in plain) > 1000
    assert {5, 6, 7, 8} <= set(sorted_[5].tolist())
    for (lo, hi), s, p in zip(fv._recess_boxes(surface), sorted_, plain):
        brute = np.flatnonzero((x1 >= lo[0]) & (x0 <= hi[0]) & (z1 >= lo[1]) & (z0 <= hi[1]))
        assert np.array_equal(s, brute) and np.array_equal(p, brute)


def test_barycentric_gradients_by_blocks_are_the_stacked_formula(monkeypatch):
    monkeypatch.setattr(fv, "BLOCK", 37)
    mesh = grid_mesh(_dimpled(), 1 / 30)
    p, t = mesh.mesh.p, mesh.mesh.t
    x, y = p[0][t], p[1][t]
    det = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0])
    grad = np.array([[y[1] - y[2], y[2] - y[0], y[0] - y[1]], [x[2] - x[1], x[0] - x[2], x[1] - x[0]]]) / det
    assert np.array_equal(fv._cells(mesh, fv.operators(mesh)).grad, grad)


@pytest.mark.parametrize("choice_up_to", [10**9, 0])
def test_set_matrix_by_column_choice_is_the_product_formula(monkeypatch, choice_up_to):
    """The active-set matrix picked entry by entry from the union pattern of K and G (built once per solver) is
    the previous path's ``K diag(~cav) + G diag(cav)``, bit for bit: same stored entries (explicit zeros
    dropped), same values, for several sets on one solver (the kept pattern is not consumed by a build)."""
    import scipy.sparse as sp

    monkeypatch.setattr(fv, "CHOICE_UP_TO", choice_up_to)   # the picked path, then the products above the limit
    rng = np.random.default_rng(3)
    n = 60
    K = sp.random(n, n, density=0.08, random_state=rng, format="csr") + sp.eye(n, format="csr")
    G = sp.random(n, n, density=0.05, random_state=rng, format="csr") - 2.0 * sp.eye(n, format="csr")
    G = G.tolil()
    G[5, 7] = 0.0   # a stored zero in one matrix only
    G = G.tocsr()
    K.data[::9] *= -1.0
    empty = sp.csr_matrix((n, n))   # a matrix without entries (a set solver's G without cavity terms)
    for solver in (fv._SetSolver(K, G, fv.factorize_splu), fv._SetSolver(K, empty, fv.factorize_splu)):
        for density in (0.0, 0.3, 0.7, 1.0):
            cav = rng.random(n) < density
            mine = solver.matrix(cav)
            plain = (solver.K @ sp.diags((~cav).astype(float)) + solver.G @ sp.diags(cav.astype(float))).tocsc()
            plain.sort_indices()
            assert mine.has_sorted_indices or not choice_up_to   # the picked matrix comes sorted
            mine.sort_indices()
            assert np.array_equal(mine.indptr, plain.indptr) and np.array_equal(mine.indices, plain.indices)
            assert np.array_equal(mine.data, plain.data)


def test_union_pattern_and_band_order_kept_per_pattern(monkeypatch):
    """A set solver with the unknowns keeps the union pattern's part of the column choice and the band order on
    them, per pattern of K and G: a second solver of new values on the same patterns picks the same matrices as
    one built afresh (bit for bit), and matrices of another pattern are not served the kept one. The reverse
    Cuthill-McKee band order (a grid's own line order, which needs no pattern, switched off)."""
    import scipy.sparse as sp

    monkeypatch.setattr(fv, "GRID_BAND_ORDER", False)
    mesh = grid_mesh(_dimpled(), 1 / 20)
    ops = fv.operators(mesh)
    unk = fv._unknowns(mesh, ops)
    system = fv._assemble(ops, mesh, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "grid")
    K, G, b = fv._reduced(system, unk, fv._pocket_values(mesh, ops, 0.0), -0.05)
    cav = np.zeros(b.size, bool)
    cav[::4] = True
    first = fv._SetSolver(K, G, fv.factorize_splu, unk)
    first.matrix(cav)
    kept = unk._order["choice"]
    band = unk._order["set_band"][2]
    second = fv._SetSolver(1.5 * K, 2.0 * G, fv.factorize_splu, unk)   # new values, the same patterns
    assert unk._order["choice"] is kept and unk._order["set_band"][2] is band
    fresh = fv._SetSolver(1.5 * K, 2.0 * G, fv.factorize_splu)          # no unknowns: nothing kept
    for c in (cav, ~cav):
        got, want = second.matrix(c), fresh.matrix(c)
        assert np.array_equal(got.indptr, want.indptr) and np.array_equal(got.indices, want.indices)
        assert np.array_equal(got.data, want.data)
    other = (K + sp.csr_matrix(([1e-3], ([0], [b.size - 1])), shape=K.shape)).tocsr()   # one entry more
    third = fv._SetSolver(other, G, fv.factorize_splu, unk)
    got = third.matrix(cav)
    want = (third.K @ sp.diags((~cav).astype(float)) + third.G @ sp.diags(cav.astype(float))).tocsc()
    want.eliminate_zeros()
    want.sort_indices()
    assert np.array_equal(got.indices, want.indices) and np.array_equal(got.data, want.data)
    assert unk._order["choice"] is not kept


def test_woodbury_columns_from_the_csc_arrays_are_the_sparse_difference():
    """The dense columns of a set change for the low-rank update, written from the CSC arrays of K and G, are
    the previous path's ``((G - K)[:, columns] @ diag(sign)).toarray()`` bit for bit (zeros as +0.0 too), with
    an explicit zero stored in G; non-canonical matrices take the sparse path."""
    import scipy.sparse as sp

    rng = np.random.default_rng(0)
    n = 400
    K = (sp.random(n, n, density=0.02, random_state=rng, format="csc") + sp.eye(n)).tocsc()
    G = (sp.random(n, n, density=0.01, random_state=rng, format="csc") - sp.eye(n)).tolil()
    G[3, 5] = 0.0   # a stored zero
    G = G.tocsc()
    K.data[::7] *= -1.0
    cols, sign = np.array([5, 17, 3, 0, 399]), np.array([1.0, -1.0, -1.0, 1.0, -1.0])
    want = ((G[:, cols] - K[:, cols]) @ sp.diags(sign)).toarray()
    got = fv._column_change(K, G, cols, sign)
    assert np.array_equal(got, want) and np.array_equal(np.signbit(got), np.signbit(want))
    # a duplicate (0, 0) entry put first in column 0 (which holds the diagonal already)
    doubled = sp.csc_matrix((np.r_[1.0, K.data], np.r_[0, K.indices], np.r_[0, K.indptr[1:] + 1]), shape=K.shape)
    assert not doubled.has_canonical_format
    assert np.array_equal(fv._column_change(doubled, G, cols, sign),
                          ((G[:, cols] - doubled[:, cols]) @ sp.diags(sign)).toarray())


@pytest.mark.parametrize("block", [7, 2048])
def test_interpolated_values_are_the_broadcast_sum_of_the_three_nodes(monkeypatch, block):
    """:func:`_interpolate`'s values (numpy's ``einsum`` over the triangles' three nodes, block by block) equal,
    bit for bit, the broadcast expression ``u_0 lambda_0 + u_1 lambda_1 + u_2 lambda_2`` (the previous path), and
    its gradient ``sum_k u_k grad lambda_k``, for a random field on a gmsh mesh (blocks of 7 triangles and one)."""
    monkeypatch.setattr(fv, "INTERPOLATE_BLOCK", block)
    mesh = mesh_surface(_dimpled(), 0.08)
    cells = fv._cells(mesh, operators(mesh))
    u = np.random.default_rng(5).standard_normal(cells.n)
    values, grad = fv._interpolate(cells, u)
    ut, lam, g = u[cells.t], cells.lam, cells.grad
    assert values.flags.c_contiguous and values.shape == (cells.t.shape[1], lam.shape[1])
    assert np.array_equal(values, ut[0][:, None] * lam[0] + ut[1][:, None] * lam[1] + ut[2][:, None] * lam[2])
    assert np.array_equal(grad, g[:, 0] * ut[0] + g[:, 1] * ut[1] + g[:, 2] * ut[2])
