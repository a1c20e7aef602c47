"""The cold start by coarse-grid nested iteration and the factorization reuse give the plain method's answer.

The plain primal-dual active-set method (a factorization per active set, from the Gumbel set) is the
reference: the fast path must find the same rupture set and the same unknown to the solver tolerance
(sign tests at 1e-10 relative; the conjugate-gradient solves stop at a relative step of 1e-12).
"""

import math

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.sparse.csgraph import reverse_cuthill_mckee

from bearingfe import CosineFilm, Surface, mesh_surface, superpose
from bearingfe.cavitation import ObstacleProblem, solve_cavitating
from bearingfe.cavitation import obstacle, swift_stieber
from bearingfe.core import banded as band_rule
from bearingfe.cavitation.coarse import NESTED_MIN, grid_interpolation
from bearingfe.cavitation.obstacle import CavitationError
from benchmarks.cavitation_cost import plain_solve


@pytest.fixture(scope="module")
def journal_mesh():
    # full 360-degree bearing, L/D = 1/2: about 3600 P1 unknowns (above NESTED_MIN), 14000 P2
    return mesh_surface(Surface(arc=(0.0, 2 * math.pi), half_width=0.5), 0.045)


def _plain(sup, weights, result=False):
    # the benchmark's reference (benchmarks/cavitation_cost.py, part cavitation): testing it here keeps the
    # benchmark's comparison on the same discrete problem (Bernstein coefficients on P2)
    fp, sol, res = plain_solve(sup, weights)
    return (fp, sol, res) if result else (fp, sol)


@pytest.mark.parametrize("formulation,element,weights", [
    ("direct", "P1", (1.0, 0.0, 0.0, 0.0)),
    ("pi", "P1", (1.0, 0.4, -0.3, 0.0)),
    ("direct", "P2", (1.0, 0.0, 0.2, 0.0)),
])
def test_fast_path_matches_the_plain_method(journal_mesh, formulation, element, weights):
    sup = superpose(journal_mesh, CosineFilm(0.6, 0.2), formulation=formulation, element=element)
    weights = np.array(weights)
    fp, ref, plain = _plain(sup, weights, result=True)
    assert fp.problem.n >= NESTED_MIN  # the nested cold start is taken
    res = solve_cavitating(sup, weights[0], tuple(weights[1:3]))
    assert "cavitation_coarse_iterations" in res.cost and "cavitation_fallback" not in res.cost
    np.testing.assert_array_equal(res.cavitated[fp.interior], ref.active)
    # the reference is a true solution (zero residual on its full-film set), and the pressures agree
    lam = fp.problem.A @ ref.u - fp.right_side(weights)
    assert np.abs(lam[~ref.active]).max() <= 1e-9 * np.abs(lam).max()
    np.testing.assert_array_equal(plain.cavitated, res.cavitated)
    np.testing.assert_allclose(res.pressure, plain.pressure, rtol=0, atol=1e-9 * np.abs(res.pressure).max())
    # fewer iterations than the plain method, which walks the free boundary one layer per step
    assert res.iterations < ref.iterations


def test_failed_fast_path_falls_back_and_says_so(journal_mesh, monkeypatch):
    sup = superpose(journal_mesh, CosineFilm(0.6, 0.0), formulation="direct")
    weights = np.array([1.0, 0.0, 0.0, 0.0])
    fp, ref = _plain(sup, weights)

    def failing(*args, **kwargs):
        raise CavitationError("coarse problem did not converge (forced by the test)")

    # a failed coarse start: the iteration starts from the linear solution instead, and says so
    monkeypatch.setattr(swift_stieber, "nested_start", failing)
    res = solve_cavitating(sup, 1.0)
    assert res.cost["cavitation_fallback"] == 1.0
    assert any("coarse-grid start failed" in note for note in res.notes)
    np.testing.assert_array_equal(res.cavitated[fp.interior], ref.active)
    # a failed iteration with reused factorizations: the plain method, which says so
    original = ObstacleProblem.solve

    def failing_reuse(self, b, active=None):
        if self.reuse:
            raise CavitationError("forced by the test")
        return original(self, b, active)

    monkeypatch.setattr(ObstacleProblem, "solve", failing_reuse)
    res = solve_cavitating(superpose(journal_mesh, CosineFilm(0.6, 0.0), formulation="direct"), 1.0)
    assert any("plain active-set method" in note for note in res.notes)
    np.testing.assert_array_equal(res.cavitated[fp.interior], ref.active)
    assert res.iterations == ref.iterations


def test_grid_interpolation_is_a_partition_of_unity():
    # bilinear weights: non-negative, sum to one, reproduce linear functions exactly
    rng = np.random.default_rng(0)
    pts = rng.uniform([0.0, -0.5], [2.0, 0.5], size=(200, 2))
    P = grid_interpolation(pts, np.array([0.0, -0.5]), np.array([0.25, 0.25]), (9, 5))
    assert P.data.min() >= 0.0
    np.testing.assert_allclose(np.asarray(P.sum(axis=1)).ravel(), 1.0, atol=1e-14)
    gx, gz = np.meshgrid(np.arange(9) * 0.25, -0.5 + np.arange(5) * 0.25, indexing="ij")
    f = 3 * gx.ravel() - 2 * gz.ravel() + 1
    np.testing.assert_allclose(P @ f, 3 * pts[:, 0] - 2 * pts[:, 1] + 1, atol=1e-12)


def test_no_memory_for_a_second_factorization_falls_back_to_cg_on_the_first(journal_mesh, monkeypatch):
    # at 1e6 unknowns SuperLU can fail to allocate the active set's factorization next to the full one
    # (SUPERLU_MALLOC fails: a RuntimeError); then CG preconditioned with the full factorization solves
    # every set, to the same answer. The sets here (about 1,750 unknowns) stand for large ones: factored
    # directly only up to DIRECT_UP_TO, set below them
    monkeypatch.setattr(obstacle, "DIRECT_UP_TO", 1000)
    sup = superpose(journal_mesh, CosineFilm(0.6, 0.0), formulation="direct")
    weights = np.array([1.0, 0.0, 0.0, 0.0])
    fp, ref = _plain(sup, weights)

    def no_memory(A):
        raise RuntimeError("SUPERLU_MALLOC fails for buf in intCalloc() (forced by the test)")

    problem = ObstacleProblem(fp.problem.A, no_memory)
    problem.add_factorization(np.ones(problem.n, bool), sup.system.solve)
    sol = problem.solve(fp.right_side(weights), (sup.fields @ weights)[fp.interior] < 0)
    assert sol.factorizations == 0 and problem.krylov_iterations > 0
    np.testing.assert_array_equal(sol.active, ref.active)
    np.testing.assert_allclose(sol.u, ref.u, rtol=0, atol=1e-9 * np.abs(ref.u).max())


def _laplacian(m):
    # the 5-point Laplacian on an m x m grid (SPD); its natural order has half-bandwidth m
    one = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(m, m))
    return (sp.kron(one, sp.eye(m)) + sp.kron(sp.eye(m), one)).tocsr()


def test_free_set_factorizations_solve_the_free_block():
    # the banded Cholesky and the SuperLU in a given order both solve A[free][:, free]: against spsolve
    # (round-off, 1e-10 relative); a band wider than the limit or an indefinite block is refused (None)
    rng = np.random.default_rng(1)
    A = _laplacian(24)
    free = rng.random(A.shape[0]) < 0.7
    idx = np.flatnonzero(free)
    b = rng.standard_normal(idx.size)
    reference = spla.spsolve(A[idx][:, idx].tocsc(), b)
    banded = obstacle._factor_banded(A[idx][:, idx])
    assert banded is not None
    np.testing.assert_allclose(banded(b), reference, rtol=0, atol=1e-10 * np.abs(reference).max())
    ordered = obstacle._factor_in_order(A, free, rng.permutation(A.shape[0]))
    np.testing.assert_allclose(ordered(b), reference, rtol=0, atol=1e-10 * np.abs(reference).max())
    widest = band_rule.band_limits("new_pattern").kd_max
    assert obstacle._factor_banded(_laplacian(2 * widest)) is None  # RCM band ~ twice the widest
    assert obstacle._factor_banded(-A) is None  # not positive definite
    with pytest.raises(ValueError, match="order must be a permutation"):
        ObstacleProblem(A, obstacle.factorize_splu_sym, order=np.zeros(A.shape[0], int))
    # the same two from the precomputed block entries (the path ObstacleProblem takes)
    block = obstacle._Blocks(A).coo(free)
    banded = obstacle._factor_banded(A[idx][:, idx], block)
    np.testing.assert_allclose(banded(b), reference, rtol=0, atol=1e-10 * np.abs(reference).max())
    ordered = obstacle._factor_in_order(A, free, rng.permutation(A.shape[0]), block)
    np.testing.assert_allclose(ordered(b), reference, rtol=0, atol=1e-10 * np.abs(reference).max())
    # banded in the whole matrix's reverse Cuthill-McKee order restricted to the set (ObstacleProblem's first try)
    whole = reverse_cuthill_mckee(A, symmetric_mode=True)
    banded = obstacle._factor_banded(None, block, obstacle._restricted(whole, free))
    np.testing.assert_allclose(banded(b), reference, rtol=0, atol=1e-10 * np.abs(reference).max())


def test_precomputed_blocks_are_scipys_slices():
    # _Blocks gives exactly scipy's A[idx][:, idx] (same entries, same sorted CSR arrays), on a nonsymmetric
    # matrix with unsorted column indices, for random masks, the empty-row case and the full set
    rng = np.random.default_rng(4)
    A = (sp.random(60, 60, density=0.15, random_state=5) + sp.eye(60)).tocsr()
    A.indices = A.indices.copy()
    for i in range(60):  # shuffle the columns within each row: the extractor must sort them itself
        lo, hi = A.indptr[i], A.indptr[i + 1]
        order = lo + rng.permutation(hi - lo)
        A.indices[lo:hi], A.data[lo:hi] = A.indices[order], A.data[order]
    A.has_sorted_indices = False
    blocks = obstacle._Blocks(A)
    for free in (rng.random(60) < 0.5, rng.random(60) < 0.9, np.ones(60, bool)):
        idx = np.flatnonzero(free)
        expected = A[idx][:, idx].tocsr()
        expected.sort_indices()
        got = blocks.csr(blocks.coo(free))
        np.testing.assert_array_equal(got.indptr, expected.indptr)
        np.testing.assert_array_equal(got.indices, expected.indices)
        np.testing.assert_array_equal(got.data, expected.data)


def test_factorization_paths_give_the_same_answer(journal_mesh, monkeypatch):
    # the free sets factored by SuperLU in a given order (not banded), by minimum degree, or with no CG at
    # all: the same rupture set as the plain method and the unknown within the tolerance (1e-9 relative)
    sup = superpose(journal_mesh, CosineFilm(0.6, 0.0), formulation="direct")
    weights = np.array([1.0, 0.0, 0.0, 0.0])
    fp, ref = _plain(sup, weights)
    b, start = fp.right_side(weights), (sup.fields @ weights)[fp.interior] < 0
    monkeypatch.setitem(band_rule.BAND_LIMITS, "new_pattern", band_rule.BandLimits(kd_max=0, size_max=0))
    order = reverse_cuthill_mckee(fp.problem.A, symmetric_mode=True)
    for kwargs in ({"order": order}, {}):
        sol = ObstacleProblem(fp.problem.A, obstacle.factorize_splu_sym, **kwargs).solve(b, start)
        assert sol.factorizations >= 1
        np.testing.assert_array_equal(sol.active, ref.active)
        np.testing.assert_allclose(sol.u, ref.u, rtol=0, atol=1e-9 * np.abs(ref.u).max())
    monkeypatch.setattr(obstacle, "DIRECT_UP_TO", 10**9)
    problem = ObstacleProblem(fp.problem.A, obstacle.factorize_splu_sym)
    sol = problem.solve(b, start)
    assert problem.krylov_iterations == 0 and sol.factorizations == sol.iterations  # one per set
    np.testing.assert_array_equal(sol.active, ref.active)


def test_galerkin_product_is_scipys_triple_product():
    # the P2 problem's S^T A S from the per-pattern gather (GalerkinProduct) against scipy's two products:
    # the same pattern, values equal to round-off (1e-14 relative: the same terms summed in another order),
    # for two film states on one mesh (one pattern, other values); a matrix of another pattern is refused
    mesh = mesh_surface(Surface(arc=(0.0, 2 * math.pi), half_width=0.5), 0.3)
    sups = [superpose(mesh, CosineFilm(e, a), formulation="direct", element="P2") for e, a in ((0.6, 0.0), (0.3, 0.5))]
    S, _ = swift_stieber._change_of(sups[0].operators.basis, sups[0].system.interior)
    product = swift_stieber.GalerkinProduct(S, sups[0].system.matrix)
    for sup in sups:
        A = sup.system.matrix
        assert product.matches(A)
        expected = (S.T @ A @ S).tocsr()
        expected.sort_indices()
        got = product(A)
        np.testing.assert_array_equal(got.indptr, expected.indptr)
        np.testing.assert_array_equal(got.indices, expected.indices)
        np.testing.assert_allclose(got.data, expected.data, rtol=0, atol=1e-14 * np.abs(expected.data).max())
    assert not product.matches(sp.eye(S.shape[0], format="csr"))


def test_galerkin_plan_is_made_only_for_a_mesh_solved_many_times():
    # a basis' first GALERKIN_PLAN_AFTER film states take scipy's two products (no plan kept), the later ones the
    # GalerkinProduct made then; both give S^T A S with the same pattern and values equal to round-off
    # (1e-14 relative), and a new pattern on the basis starts the count again
    mesh = mesh_surface(Surface(arc=(0.0, 2 * math.pi), half_width=0.5), 0.3)
    sup = superpose(mesh, CosineFilm(0.6, 0.0), formulation="direct", element="P2")
    basis = sup.operators.basis
    S, _ = swift_stieber._change_of(basis, sup.system.interior)
    expected = (S.T @ sup.system.matrix @ S).tocsr()
    expected.sort_indices()
    swift_stieber._GALERKIN.pop(basis, None)
    for k in range(swift_stieber.GALERKIN_PLAN_AFTER + 2):
        got = swift_stieber._galerkin(basis, S, sp.csr_matrix(sup.system.matrix))
        planned = swift_stieber._GALERKIN[basis].product
        assert (planned is None) == (k < swift_stieber.GALERKIN_PLAN_AFTER)
        np.testing.assert_array_equal(got.indptr, expected.indptr)
        np.testing.assert_array_equal(got.indices, expected.indices)
        np.testing.assert_allclose(got.data, expected.data, rtol=0, atol=1e-14 * np.abs(expected.data).max())
    eye = sp.eye(S.shape[0], format="csr")
    swift_stieber._galerkin(basis, S, eye)
    assert swift_stieber._GALERKIN[basis].states == 1 and swift_stieber._GALERKIN[basis].product is None


def test_galerkin_with_the_kept_csc_change_is_scipys_product_digit_for_digit():
    # before the plan, _galerkin multiplies by the CSR form of S^T kept per basis (the arrays of the CSC S scipy
    # converts to itself), by scipy's kernels: the same products, so the same pattern and the same digits, on the first
    # and on a later film state of a mesh (the kept form reused); on this gmsh mesh no entry cancels, so the
    # whole pattern the result is placed on is scipy's
    mesh = mesh_surface(Surface(arc=(0.0, 2 * math.pi), half_width=0.5), 0.3)
    sups = [superpose(mesh, CosineFilm(e, a), formulation="direct", element="P2") for e, a in ((0.6, 0.0), (0.3, 0.5))]
    basis = sups[0].operators.basis
    S, _ = swift_stieber._change_of(basis, sups[0].system.interior)
    swift_stieber._GALERKIN.pop(basis, None)
    for sup in sups:
        expected = (S.T @ sup.system.matrix @ S).tocsr()
        expected.sort_indices()
        got = swift_stieber._galerkin(basis, S, sp.csr_matrix(sup.system.matrix))
        assert swift_stieber._GALERKIN[basis].product is None and swift_stieber._GALERKIN[basis].S_T is not None
        np.testing.assert_array_equal(got.indptr, expected.indptr)
        np.testing.assert_array_equal(got.indices, expected.indices)
        np.testing.assert_array_equal(got.data, expected.data)
    np.testing.assert_array_equal(swift_stieber._GALERKIN[basis].S_T.toarray(), S.T.toarray())


def test_film_states_of_one_mesh_share_one_p2_pattern_and_order():
    # on a structured journal mesh scipy's S^T A S drops entries that cancel exactly, different ones per film state
    # and some on one side of the diagonal only; the obstacle problems order by A's pattern instead (the mesh's
    # P2 couplings, symmetric; the product of the patterns with every value one gives it, so it holds every
    # entry of S^T A S): both states have that pattern and share one reverse Cuthill-McKee order (the per-pattern
    # cache hits); their matrices are scipy's products unchanged
    from bearingfe.bearings.journal import JournalBearing, structured_journal_mesh
    mesh = structured_journal_mesh(JournalBearing(1.0), 0.3)
    sups = [superpose(mesh, CosineFilm(e, a), formulation="direct", element="P2") for e, a in ((0.6, 0.0), (0.3, 0.5))]
    basis = sups[0].operators.basis
    S, _ = swift_stieber._change_of(basis, sups[0].system.interior)
    A0 = sp.csr_matrix(sups[0].system.matrix)
    structure = sp.csr_matrix((np.ones(A0.nnz), A0.indices, A0.indptr), shape=A0.shape)
    ones = sp.csr_matrix((np.ones(S.nnz), S.indices, S.indptr), shape=S.shape)
    products = (ones.T @ structure @ ones).tocsr()
    products.sort_indices()
    np.testing.assert_array_equal(products.indptr, A0.indptr)
    np.testing.assert_array_equal(products.indices, A0.indices)
    assert (structure != structure.T).nnz == 0
    swift_stieber._GALERKIN.pop(basis, None)
    scipys, problems = [], []
    for sup in sups:
        scipys.append((S.T @ sup.system.matrix @ S).tocsr())
        problems.append(swift_stieber.obstacle_problem(sup).problem)
    assert scipys[0].nnz < A0.nnz and scipys[1].nnz < A0.nnz  # the case this is about
    assert not np.array_equal(abs(scipys[0]).toarray() > 0, abs(scipys[1]).toarray() > 0)
    for problem, expected in zip(problems, scipys):
        np.testing.assert_array_equal(problem.pattern.indptr, A0.indptr)
        np.testing.assert_array_equal(problem.pattern.indices, A0.indices)
        np.testing.assert_array_equal(problem.A.toarray(), expected.toarray())
    obstacle._RCM_ORDERS.clear()
    assert problems[0]._rcm_order() is problems[1]._rcm_order()
    np.testing.assert_array_equal(problems[0]._rcm_order(), reverse_cuthill_mckee(structure, symmetric_mode=True))


def test_obstacle_pattern_orders_and_answers_as_before():
    # an ObstacleProblem given a pattern holding A's (A with one coupling cancelled, the full Laplacian's pattern)
    # orders by it and gives the answer of the problem without it to round-off (1e-12 relative: the same
    # equations, factored in another order); a pattern of another shape is refused
    n = 30
    A = sp.diags([-np.ones(n - 1), 2.5 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1], format="csr")
    b = np.sin(np.linspace(0.0, 6.0, n))
    cut = A.tolil()
    cut[3, 4] = cut[4, 3] = 0.0
    cut = cut.tocsr()
    cut.eliminate_zeros()
    plain = ObstacleProblem(cut, obstacle.factorize_splu_sym).solve(b)
    ordered_problem = ObstacleProblem(cut, obstacle.factorize_splu_sym, pattern=A)
    ordered = ordered_problem.solve(b)
    assert ordered_problem.pattern.nnz == A.nnz
    obstacle._RCM_ORDERS.clear()
    np.testing.assert_array_equal(ordered_problem._rcm_order(), reverse_cuthill_mckee(A, symmetric_mode=True))
    np.testing.assert_array_equal(ordered.active, plain.active)
    np.testing.assert_allclose(ordered.u, plain.u, rtol=0, atol=1e-12 * np.abs(plain.u).max())
    with pytest.raises(ValueError, match="pattern"):
        ObstacleProblem(cut, obstacle.factorize_splu_sym, pattern=sp.eye(n + 1, format="csr"))


def test_coarse_chain_kept_per_mesh_gives_the_fresh_start(journal_mesh):
    # the coarse grids depend on the dof coordinates only: the chain kept per basis (swift_stieber._chain_of)
    # gives the same start and coarse iterations as nested_start making its grids afresh, for two film states
    from bearingfe.cavitation.coarse import CoarseChain, nested_start
    for e, a in ((0.6, 0.0), (0.4, 0.7)):
        sup = superpose(journal_mesh, CosineFilm(e, a), formulation="direct")
        fp = swift_stieber.obstacle_problem(sup)
        b = fp.right_side(np.array([1.0, 0.0, 0.0, 0.0]))
        points = np.asarray(sup.operators.basis.doflocs)[:, fp.interior].T
        chain = swift_stieber._chain_of(sup.operators.basis, fp.interior)
        assert chain is swift_stieber._chain_of(sup.operators.basis, fp.interior)
        kept = nested_start(fp.problem.A, b, None, fp.problem.factorize, tol=1e-10, max_iterations=60, chain=chain)
        fresh = nested_start(fp.problem.A, b, points, fp.problem.factorize, tol=1e-10, max_iterations=60)
        np.testing.assert_array_equal(kept[0], fresh[0])
        assert kept[1] == fresh[1] and kept[0].any()
    with pytest.raises(ValueError, match="chain's unknowns"):
        CoarseChain(points).start(fp.problem.A[:10, :10], b[:10], fp.problem.factorize, tol=1e-10,
                                  max_iterations=60)


def test_blocks_by_scipy_slicing_above_the_limit_give_the_same_answer(journal_mesh, monkeypatch):
    # above BLOCKS_UP_TO unknowns the free blocks come from scipy's slicing (faster there): with the limit
    # set to zero the same problem takes that path for every set, and finds the plain method's set and unknown
    sup = superpose(journal_mesh, CosineFilm(0.6, 0.0), formulation="direct")
    weights = np.array([1.0, 0.0, 0.0, 0.0])
    fp, ref = _plain(sup, weights)
    monkeypatch.setattr(obstacle, "BLOCKS_UP_TO", 0)
    monkeypatch.setattr(obstacle, "DIRECT_UP_TO", 1000)  # CG on the sets too: its matrix is a sliced block
    problem = ObstacleProblem(fp.problem.A, fp.problem.factorize, order=fp.problem.order)
    problem.add_factorization(np.ones(problem.n, bool), sup.system.solve)  # P1: the full film's own
    sol = problem.solve(fp.right_side(weights), (sup.fields @ weights)[fp.interior] < 0)
    assert problem._block_plan is None and problem.krylov_iterations > 0
    np.testing.assert_array_equal(sol.active, ref.active)
    np.testing.assert_allclose(sol.u, ref.u, rtol=0, atol=1e-9 * np.abs(ref.u).max())


def test_rcm_order_kept_per_pattern():
    # the reverse Cuthill-McKee order is found once per sparsity pattern: a matrix of the same pattern with other
    # values (the next film state of a mesh) gets the same order object, equal to scipy's order of the pattern;
    # another pattern gets its own
    A = _laplacian(20)
    first = obstacle._pattern_rcm(A)
    np.testing.assert_array_equal(first, reverse_cuthill_mckee(A, symmetric_mode=True))
    B = A.copy()
    B.data = B.data * np.linspace(1.0, 2.0, B.data.size)
    assert obstacle._pattern_rcm(B) is first
    C = _laplacian(21)
    other = obstacle._pattern_rcm(C)
    assert other is not first and other.size == C.shape[0]
    np.testing.assert_array_equal(other, reverse_cuthill_mckee(C, symmetric_mode=True))
    for k in range(obstacle.RCM_PATTERNS_KEPT):  # older patterns drop out: found again, equal
        obstacle._pattern_rcm(_laplacian(22 + k))
    again = obstacle._pattern_rcm(A)
    assert again is not first
    np.testing.assert_array_equal(again, first)


def test_both_carried_starts_give_the_plain_answer(journal_mesh, monkeypatch):
    # the coarse rupture set goes to the next level by the sign of the interpolated u - lam / diag, the free set
    # grown by one ring of the matrix's neighbours on the given system's level (and on coarse levels whose sets
    # go by CG); with the ring or without it the iteration ends on the plain method's set and unknown
    from bearingfe.cavitation import coarse

    sup = superpose(journal_mesh, CosineFilm(0.6, 0.0), formulation="direct")
    weights = np.array([1.0, 0.0, 0.0, 0.0])
    fp, ref = _plain(sup, weights)
    b, A = fp.right_side(weights), fp.problem.A
    chain = coarse.CoarseChain(np.asarray(sup.operators.basis.doflocs)[:, fp.interior].T)
    grown, _ = chain.start(A, b, fp.problem.factorize, tol=1e-10, max_iterations=60)
    carried = coarse._carried
    monkeypatch.setattr(coarse, "_carried", lambda *args, finest: carried(*args, finest=False))
    signed, _ = chain.start(A, b, fp.problem.factorize, tol=1e-10, max_iterations=60)
    # the same coarse solution (the coarse levels' sets are factored here): the grown free set is the signed
    # one grown by a ring of A's neighbours
    assert fp.problem.n - signed.sum() <= obstacle.DIRECT_UP_TO
    np.testing.assert_array_equal(~grown, (abs(A) @ (~signed).astype(float)) > 0)
    assert np.count_nonzero(~grown) > np.count_nonzero(~signed)
    for start in (signed, grown):
        sol = ObstacleProblem(A, fp.problem.factorize, reuse=False).solve(b, start)
        np.testing.assert_array_equal(sol.active, ref.active)
        np.testing.assert_allclose(sol.u, ref.u, rtol=0, atol=1e-9 * np.abs(ref.u).max())


def test_settled_sets_by_medium_steps_give_the_tight_answer(journal_mesh, monkeypatch):
    # once the active set nearly settles, its CG solves go to a medium step (MEDIUM * tol) and only the set that
    # no longer changes to tol / 100, which decides: the same rupture set and unknown (1e-9 relative) as every
    # settled set solved to tol / 100, and as the plain method; the free sets go by CG here (factored directly
    # only up to DIRECT_UP_TO, set below them). Fewer CG steps on the benchmark's journals (35 against 42 at 1e4
    # P2 unknowns, 34 against 43 at 3e5); about as many on this small one
    sup = superpose(journal_mesh, CosineFilm(0.6, 0.0), formulation="direct")
    weights = np.array([1.0, 0.0, 0.0, 0.0])
    fp, ref = _plain(sup, weights)
    b = fp.right_side(weights)
    start = (sup.fields @ weights)[fp.interior] < 0
    monkeypatch.setattr(obstacle, "DIRECT_UP_TO", 1000)
    steps, levels = {}, []
    solve_free = ObstacleProblem._solve_free

    def recorded(self, free, b_free, rtol=None, x0=None):
        levels.append(rtol)
        return solve_free(self, free, b_free, rtol, x0)

    monkeypatch.setattr(ObstacleProblem, "_solve_free", recorded)
    default = obstacle.MEDIUM
    for medium in (None, default):
        monkeypatch.setattr(obstacle, "MEDIUM", medium)
        problem = ObstacleProblem(fp.problem.A, obstacle.factorize_splu_sym)
        levels.clear()
        sol = problem.solve(b, start)
        # the medium path solves some sets to the medium step (the last one is exact: by CG to the tolerance, or
        # factored when CG would cost more)
        assert (default * problem.tol in levels) == (medium is not None)
        np.testing.assert_array_equal(sol.active, ref.active)
        np.testing.assert_allclose(sol.u, ref.u, rtol=0, atol=1e-9 * np.abs(ref.u).max())
        u_min, lam_min, product = sol.complementarity()
        scale = np.abs(ref.u).max() * np.abs(sol.multiplier).max()
        assert u_min >= -1e-10 * np.abs(ref.u).max() and product <= 1e-9 * scale
        steps[medium] = problem.krylov_iterations
    assert steps[default] > 0 and steps[None] > 0


def test_settled_sets_factored_for_a_caller_that_linearizes_give_the_same_answer(journal_mesh, monkeypatch):
    # factor_settled: the sets solved once the iteration has nearly settled are factored, not solved by CG (the
    # caller will factor the answer's set anyway): the plain method's rupture set and unknown (1e-9 relative, the
    # CG path's tolerance), fewer CG steps (here 50 against 78), and the answer's factorization is then in the
    # cache (no new one on request); the free sets go by CG before settling (factored directly only up to
    # DIRECT_UP_TO, set below them)
    sup = superpose(journal_mesh, CosineFilm(0.6, 0.0), formulation="direct")
    weights = np.array([1.0, 0.0, 0.0, 0.0])
    fp, ref = _plain(sup, weights)
    b, start = fp.right_side(weights), (sup.fields @ weights)[fp.interior] < 0
    monkeypatch.setattr(obstacle, "DIRECT_UP_TO", 1000)
    made, steps = {}, {}
    for factor_settled in (False, True):
        problem = ObstacleProblem(fp.problem.A, obstacle.factorize_splu_sym, factor_settled=factor_settled)
        sol = problem.solve(b, start)
        assert problem.krylov_iterations > 0
        np.testing.assert_array_equal(sol.active, ref.active)
        np.testing.assert_allclose(sol.u, ref.u, rtol=0, atol=1e-9 * np.abs(ref.u).max())
        count = problem.factorization_count
        problem.factorization(~sol.active)
        made[factor_settled] = problem.factorization_count - count
        steps[factor_settled] = problem.krylov_iterations
    assert made[True] == 0 and steps[True] < steps[False]


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_small_cold_start_grown_gives_the_plain_answer(element):
    # below NESTED_MIN unknowns the cold start is where the linear solution is negative, its free set grown by
    # COLD_RINGS rings of neighbours (the Swift-Stieber film reaches past the linear zero): the plain method's
    # set and unknown (1e-9 relative), in fewer active-set steps than from the linear set (5 -> 3 P1, 5 -> 4 P2 on
    # the benchmark's 1e3-unknown journal)
    mesh = mesh_surface(Surface(arc=(0.0, 2 * math.pi), half_width=0.5), 0.09 if element == "P1" else 0.18)
    sup = superpose(mesh, CosineFilm(0.6, 0.0), formulation="direct", element=element)
    weights = np.array([1.0, 0.0, 0.0, 0.0])
    fp, ref, plain = _plain(sup, weights, result=True)
    assert fp.problem.n < NESTED_MIN and swift_stieber.COLD_RINGS[element] >= 1
    res = solve_cavitating(sup, 1.0)
    assert "cavitation_coarse_iterations" not in res.cost
    np.testing.assert_array_equal(res.cavitated, plain.cavitated)
    np.testing.assert_allclose(res.pressure, plain.pressure, rtol=0, atol=1e-9 * np.abs(plain.pressure).max())
    assert res.iterations < ref.iterations


def test_a_nearby_matrix_preconditions_to_the_same_answer(journal_mesh, monkeypatch):
    # precondition(): the factorization of the same set of another film (5 % thicker: A scaled by 1.05^3) as
    # the CG preconditioner, not as a solve: the same rupture set as the plain method and the unknown within
    # the tolerance (1e-9 relative), with no factorization of this matrix's sets
    sup = superpose(journal_mesh, CosineFilm(0.6, 0.0), formulation="direct")
    weights = np.array([1.0, 0.0, 0.0, 0.0])
    fp, ref = _plain(sup, weights)
    free = ~ref.active
    monkeypatch.setattr(obstacle, "DIRECT_UP_TO", 1000)  # the set (1,864 unknowns) by CG, not factored
    assert np.count_nonzero(free) > obstacle.DIRECT_UP_TO
    other = sp.csr_matrix(fp.problem.A * 1.05**3)
    nearby = spla.splu(sp.csc_matrix(other[free][:, free])).solve
    problem = ObstacleProblem(fp.problem.A, fp.problem.factorize, order=fp.problem.order)
    problem.precondition(free, nearby)
    sol = problem.solve(fp.right_side(weights), ref.active)
    assert sol.factorizations == 0 and problem.krylov_iterations > 0
    np.testing.assert_array_equal(sol.active, ref.active)
    np.testing.assert_allclose(sol.u, ref.u, rtol=0, atol=1e-9 * np.abs(ref.u).max())
    with pytest.raises(ValueError, match="free"):
        problem.precondition(free[:-1], nearby)


def test_a_set_refused_in_every_order_spares_the_tries_of_larger_sets(monkeypatch):
    # with the obstacle sets' band limit at 5, a 20 x 20 Laplacian's free sets (bands about 20) are refused in every
    # order; after the first refusal, sets as large or larger are not ordered and planned again (the tries are
    # counted), a smaller one is; every solve against scipy's sparse direct solve (round-off: 1e-10 of the largest)
    monkeypatch.setitem(band_rule.BAND_LIMITS, "new_pattern", band_rule.BandLimits(kd_max=5, size_max=5000))
    tries = []
    real = obstacle._factor_banded
    monkeypatch.setattr(obstacle, "_factor_banded", lambda *a, **k: tries.append(1) or real(*a, **k))
    A = _laplacian(20)
    problem = ObstacleProblem(A, obstacle.factorize_splu_sym)
    rng = np.random.default_rng(3)
    counts = []
    for ruptured in (40, 30, 60):  # free sets of 360, 370 and 340 unknowns
        free = np.ones(A.shape[0], bool)
        free[rng.choice(A.shape[0], ruptured, replace=False)] = False
        before = len(tries)
        solve = problem._factor(free)
        counts.append(len(tries) - before)
        b = np.linspace(1.0, 2.0, int(free.sum()))
        reference = spla.spsolve(A[free][:, free].tocsc(), b)
        np.testing.assert_allclose(solve(b), reference, rtol=0, atol=1e-10 * np.abs(reference).max())
    assert counts[0] >= 2 and counts[1] == 0 and counts[2] >= 2
    assert problem._band_refused_from == 340


def test_a_set_banded_in_its_own_order_sends_the_next_sets_to_their_own_order_first(monkeypatch):
    # a 40 x 6 grid Laplacian (shifted: SPD) with a node hung on the middle of a long side: scipy's reverse
    # Cuthill-McKee order of the whole matrix starts there (least degree), half-bandwidth 13. With the hung node
    # ruptured, a free set's own order starts at a corner (half-bandwidth 6 to 7, measured below). With the
    # obstacle sets' band limit at 10, the first set's band in the whole matrix's order is refused and its own
    # order taken; the next set of the problem is tried in its own order first (one try, no whole-matrix order
    # passed), and a new problem starts from the whole matrix's order again. Every solve against scipy's sparse
    # direct solve (round-off: 1e-10 of the largest).
    monkeypatch.setitem(band_rule.BAND_LIMITS, "new_pattern", band_rule.BandLimits(kd_max=10, size_max=5000))
    nx, ny = 40, 6
    one = lambda m: sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(m, m))  # noqa: E731
    n = nx * ny
    A = sp.lil_matrix((n + 1, n + 1))
    A[:n, :n] = sp.kron(one(nx), sp.eye(ny)) + sp.kron(sp.eye(nx), one(ny))
    A[n, (nx // 2) * ny] = A[(nx // 2) * ny, n] = -1.0
    A[n, n] = 2.0
    A = (A + 0.1 * sp.eye(n + 1)).tocsr()
    assert band_rule.half_bandwidth(A, reverse_cuthill_mckee(A, symmetric_mode=True)) == 13
    tries = []
    real = obstacle._factor_banded
    monkeypatch.setattr(obstacle, "_factor_banded", lambda M, block=None, perm=None:
                        tries.append(perm is None) or real(M, block, perm))
    problem = ObstacleProblem(A, obstacle.factorize_splu_sym)
    for ruptured, expected in ((0, [False, True]), (n - 1, [True]), (ny - 1, [True])):
        free = np.ones(n + 1, bool)
        free[[n, ruptured]] = False  # the hung node and a corner ruptured
        sub = A[free][:, free]
        assert band_rule.half_bandwidth(sub, reverse_cuthill_mckee(sub, symmetric_mode=True)) <= 7
        del tries[:]
        solve = problem._factor(free)
        assert tries == expected  # (perm is None: the set's own order)
        b = np.linspace(1.0, 2.0, int(free.sum()))
        reference = spla.spsolve(sub.tocsc(), b)
        np.testing.assert_allclose(solve(b), reference, rtol=0, atol=1e-10 * np.abs(reference).max())
    del tries[:]
    ObstacleProblem(A, obstacle.factorize_splu_sym)._factor(free)
    assert tries == [False, True]

