r"""The Swift-Stieber (Reynolds) cavitation condition on a film state: ``p >= 0`` with a free boundary.

On the condensed unknowns ``u`` of a film state (``p`` for the direct form,
``Pi = h^(3/2) p`` for the pi form: ``Pi >= 0`` iff ``p >= 0`` since ``h > 0``)
the condition is the obstacle problem of :mod:`bearingfe.cavitation.obstacle`,
posed on the superposition's own condensed matrix and started with its
factorization of the full film. The multiplier is the nodal residual of the
Reynolds equation: zero where the film is full, non-negative where it ruptured.

On quadratic (P2) elements the condition is imposed on the Bernstein
coefficients of the unknown: its values at the vertices and, on each edge
between two free vertices, ``2 u_mid - (u_a + u_b) / 2``. A quadratic with
non-negative Bernstein coefficients is non-negative on the whole element,
and the coefficients of a refined mesh are convex combinations of the
coarse ones, so the discrete sets are nested under refinement: a
conforming discretization of the variational inequality (on the edges
that touch the Dirichlet outline the midside value is bounded as on P1,
which keeps the constraint's reaction off the outline's flows). Bounding
only the nodal values everywhere lets the quadratic dip below zero between
the nodes next to the free boundary, and the load then converged
irregularly at the 1e-5 level (a journal at eps 0.6 changed by +1e-5,
+5.5e-5, -7e-6 under three refinements), which an error estimate from one
refinement cannot follow. Cavitated dofs are those whose coefficient is
held at zero (on an edge next to the free boundary, the nodal pressure can
be positive there); ``u = S v`` maps the coefficients ``v`` back to the
nodal unknowns (:func:`bernstein_change`).

Warm starts: the rupture set of a previous solution on the same mesh (the
previous time step), or of a solution on another mesh of the same surface
(nested iteration: a new dof is ruptured if it lies in a ruptured element of the
previous mesh), which keeps the active-set count bounded under refinement.
"""

from __future__ import annotations

import time
import weakref
from dataclasses import dataclass, replace
from functools import cached_property
from types import MappingProxyType
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

from .coarse import NESTED_MIN, CoarseChain, nested_start
from .obstacle import MAX_ITERATIONS, TOLERANCE, CavitationError, ObstacleProblem
from ..core.compressed import compressed, csr_of, csr_product, csr_transposed, matvec, sorted_entries
from ..core.linalg import DEFAULT_SOLVER, SMALL_PANELS_UP_TO, Factorize, dense_threads, get_linear_solver
from ..film import ReynoldsResult, Superposition, build_result
from ..film.flows import bernstein_edges, ruptured_elements
from ..geometry.locate import containing_cells

if TYPE_CHECKING:
    from .models import ModelOptions

__all__ = ["FilmProblem", "bernstein_change", "cached_problem", "cold_mask", "obstacle_problem",
           "solve_swift_stieber", "warm_mask"]

@dataclass(frozen=True, eq=False)
class FilmProblem:
    """The complementarity problem of a film state on its condensed system.

    The constrained unknowns ``v`` are the nodal unknowns on P1 and the Bernstein coefficients on
    P2: ``u[I] = change @ v``.

    Attributes
    ----------
    problem : ObstacleProblem
        ``v >= 0`` on ``change^T A[I, I] change`` (on P1 ``sup.system.matrix`` itself, no
        reassembly); its cache starts with the superposition's own factorization of the full-film set.
    interior, boundary : ndarray of int
    rhs : ndarray, shape (n_interior, 4)
        Unit right sides of the condensed system (of the nodal unknowns).
    lift : ndarray, shape (n_dofs, 4)
        Dirichlet data of the unit sources.
    change : sparse matrix or None
        ``S[I, I]`` of :func:`bernstein_change` (None: ``v = u``).
    inverse : sparse matrix or None
        Its inverse ``T``: ``v = inverse @ u[I]`` (None with ``change``).
    """

    problem: ObstacleProblem
    interior: np.ndarray
    boundary: np.ndarray
    rhs: np.ndarray
    lift: np.ndarray
    change: sp.csr_matrix | None = None
    inverse: sp.csr_matrix | None = None

    @cached_property
    def change_transposed(self) -> sp.csc_matrix | None:
        """``change.T`` as scipy's transpose makes it (CSC on ``change``'s own arrays), made once per problem
        (scipy's ``change.T`` builds a new matrix each time)."""
        if self.change is None:
            return None
        S = self.change
        return compressed(S.data, S.indices, S.indptr, S.shape[::-1], fmt="csc")

    def unknowns(self, v: np.ndarray) -> np.ndarray:
        """The interior nodal unknowns from the constrained ones."""
        return v if self.change is None else matvec(self.change, v)

    def coefficients(self, u: np.ndarray) -> np.ndarray:
        """The constrained unknowns from the interior nodal ones (the inverse of :meth:`unknowns`)."""
        return u if self.change is None else matvec(self.inverse, u)

    def right_side(self, weights: np.ndarray) -> np.ndarray:
        """The right side of the problem in ``v`` at the operating point ``weights``."""
        b = self.rhs @ weights
        return b if self.change is None else matvec(self.change_transposed, b)

    def solve_fixed(self, rhs: np.ndarray, active: np.ndarray) -> np.ndarray:
        """Interior nodal unknowns of ``A[I, I] u = rhs`` with ``v = 0`` on ``active`` (a fixed rupture set:
        the linearization); ``rhs`` of the nodal equations, one or several columns."""
        if self.change is None:
            return self.problem.solve_fixed(rhs, active)
        return matvec(self.change, self.problem.solve_fixed(matvec(self.change_transposed, rhs), active))


def bernstein_change(basis, interior: np.ndarray) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """The interior nodal unknowns of a P2 basis from their constrained coefficients, ``u = S v``, and back.

    On an edge of :func:`bernstein_edges`, ``u_mid = v_mid / 2 + (v_a + v_b) / 4`` (a quadratic's value at
    the edge's middle from its Bernstein coefficients), so ``v_mid = 2 u_mid - (u_a + u_b) / 2``; every
    other dof keeps its nodal value. No coefficient reads a Dirichlet dof.

    Returns
    -------
    (S, T) : sparse matrices, shape (n_interior, n_interior)
        ``u[I] = S v`` and its inverse ``v = T u[I]``.
    """
    free = np.zeros(int(basis.N), bool)
    free[interior] = True
    middle, a, b = bernstein_edges(basis, free)
    position = np.full(int(basis.N), -1)
    position[interior] = np.arange(interior.size)
    m, a, b = position[middle], position[a], position[b]
    n, ones = interior.size, np.ones(middle.size)
    plain = np.setdiff1d(np.arange(n), m)
    rows = np.concatenate([plain, m, m, m])
    cols = np.concatenate([plain, m, a, b])

    def matrix(mid: float, ends: float) -> sp.csr_matrix:  # one entry per place: sorted_entries is scipy's CSR
        return sorted_entries(rows, cols, np.concatenate([np.ones(plain.size), mid * ones, ends * ones, ends * ones]),
                              n)

    return matrix(0.5, 0.25), matrix(2.0, -0.5)


class GalerkinProduct:
    """``S^T A S`` for every matrix ``A`` of one sparsity pattern, from the pattern's products made once.

    The product is linear in ``A``'s stored values: ``C.data = G @ A.data`` with ``G`` sparse (nine
    entries at most per entry of ``A`` on the Bernstein change, whose rows have one or three entries).
    Two sparse products per film state (1.5 ms at 1e3 P2 unknowns, a fifth of the cavitating solve) become
    one sparse matrix-vector product; the result's pattern is that of all products of the pattern's entries
    (scipy's ``(S.T @ A @ S).tocsr()`` has the same entries, summed in another order: equal to round-off).
    """

    def __init__(self, S: sp.csr_matrix, pattern: sp.csr_matrix) -> None:
        S = sp.csr_matrix(S)
        S.sort_indices()
        pattern = sp.csr_matrix(pattern)
        self.indptr_a, self.indices_a = pattern.indptr.copy(), pattern.indices.copy()
        n_a, nnz = pattern.shape[0], pattern.indptr[-1]
        rows = np.repeat(np.arange(n_a), np.diff(pattern.indptr))
        # each entry k = (i, j) of A contributes S[i, p] A[i, j] S[j, q] to C[p, q]: expand k over the entries
        # of S's row i, then each of those over the entries of row j
        first = _expand(S.indptr, rows)                       # positions in S of the (i, p)
        k = np.repeat(np.arange(nnz), np.diff(S.indptr)[rows])
        second = _expand(S.indptr, pattern.indices[k])        # positions in S of the (j, q)
        copies = np.diff(S.indptr)[pattern.indices[k]]
        k, first = np.repeat(k, copies), np.repeat(first, copies)
        p, q, w = S.indices[first], S.indices[second], S.data[first] * S.data[second]
        m = S.shape[1]
        # the result's pattern from scipy's products of the patterns (all values one: no entry cancels), and
        # each product's place in it by a binary search of its sorted (row, column) keys (np.unique's sort of
        # all products took twice as long: 9 against 5 ms at 2e3 P2 unknowns)
        one = sp.csr_matrix((np.ones(S.indptr[-1]), S.indices, S.indptr), shape=S.shape)
        C = (one.T.tocsr() @ sp.csr_matrix((np.ones(nnz), pattern.indices, pattern.indptr),
                                           shape=pattern.shape) @ one).tocsr()
        C.sort_indices()
        self.shape = (m, m)
        self.indices = C.indices.astype(np.int64)
        self.indptr = C.indptr.astype(np.int64)
        keys = np.repeat(np.arange(m, dtype=np.int64), np.diff(self.indptr)) * m + self.indices
        target = np.searchsorted(keys, p.astype(np.int64) * m + q)
        self.gather = sp.csr_matrix((w, (target, k)), shape=(keys.size, nnz))

    def matches(self, A: sp.csr_matrix) -> bool:
        """Whether ``A`` has the pattern this product was made for."""
        return (A.shape[0] + 1 == self.indptr_a.size and np.array_equal(A.indptr, self.indptr_a)
                and np.array_equal(A.indices, self.indices_a))

    def __call__(self, A: sp.csr_matrix) -> sp.csr_matrix:
        """``S^T A S`` (CSR, sorted indices) of an ``A`` with the pattern (:meth:`matches`)."""
        return sp.csr_matrix((self.gather @ A.data, self.indices, self.indptr), shape=self.shape)


def _expand(indptr: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """Positions of the stored entries of ``rows`` (repeated rows included) in a CSR ``indptr``, row after row."""
    count = np.diff(indptr)[rows]
    return np.repeat(indptr[rows] - np.cumsum(count) + count, count) + np.arange(int(count.sum()))


_PROBLEMS: "weakref.WeakKeyDictionary[Superposition, FilmProblem]" = weakref.WeakKeyDictionary()
_GALERKIN: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


#: Systems up to this many unknowns take ``S^T A S`` from a :class:`GalerkinProduct` kept per basis; its
#: gather matrix holds about six entries per entry of ``A`` (some 100 MB at 1e5 unknowns), and above this size
#: the two sparse products are a small part of the solve.
GALERKIN_UP_TO = 20000

#: A basis' ``S^T A S`` comes from scipy's two sparse products for its first this many film states (of one
#: pattern), from a :class:`GalerkinProduct` made then for the later ones: making the gather costs 12 (1.7e3 P2
#: unknowns: 4.8 ms) to 22 (1.3e4) times the two products (0.41 ms; the gather applied 0.09 ms), so it pays off
#: only on a mesh solved many times (the steps of a transient), not on the refined meshes of a journal
#: equilibrium, each solved one to three times (CPU time, best of 50).
GALERKIN_PLAN_AFTER = 12


def _triple_product(S: sp.csr_matrix, A: sp.csr_matrix, S_T: sp.csr_matrix | None = None) -> sp.csr_matrix:
    """``S^T A S`` as scipy's ``(S.T @ A @ S).tocsr()`` makes it (CSR, sorted indices), by the kernels of
    :mod:`bearingfe.core.compressed` on the arrays scipy's products use: ``A^T S`` (``A`` converted to CSC, whose
    arrays are ``A^T``'s CSR arrays, times ``S``), ``S^T (A^T S)`` (``S`` in CSC, ``S^T``'s CSR arrays, times it)
    and that product's transpose: the same kernels on the same arrays, the same digits, without scipy's objects
    between them. ``S_T``: ``S^T`` in CSR (:func:`~bearingfe.core.compressed.csr_transposed` of ``S``), kept by
    the caller."""
    S_T = csr_transposed(S) if S_T is None else S_T
    C = csr_transposed(csr_product(S_T, csr_product(csr_transposed(A), S)))
    C.sort_indices()
    return C


@dataclass(eq=False)
class _KeptGalerkin:
    """What :func:`_galerkin` keeps per basis: ``S``, the pattern of ``A`` it was counted for, the film states
    of that pattern so far and, once they exceed :data:`GALERKIN_PLAN_AFTER`, the :class:`GalerkinProduct`."""

    S: sp.csr_matrix
    indptr: np.ndarray
    indices: np.ndarray
    states: int = 0
    product: "GalerkinProduct | None" = None
    S_T: sp.csr_matrix | None = None  # S^T in CSR, for the second product (made on the first state)

    def matches(self, S: sp.csr_matrix, A: sp.csr_matrix) -> bool:
        return self.S is S and np.array_equal(A.indptr, self.indptr) and np.array_equal(A.indices, self.indices)


def _galerkin(basis, S: sp.csr_matrix, A: sp.csr_matrix) -> sp.csr_matrix:
    """``S^T A S``: up to :data:`GALERKIN_UP_TO` unknowns, after :data:`GALERKIN_PLAN_AFTER` film states of one
    pattern on a basis by the :class:`GalerkinProduct` kept for it (remade when ``S`` or ``A``'s pattern change),
    else by scipy's products."""
    if A.shape[0] > GALERKIN_UP_TO:
        return _triple_product(S, A)
    kept = _GALERKIN.get(basis)
    if kept is None or not kept.matches(S, A):
        kept = _GALERKIN[basis] = _KeptGalerkin(S, A.indptr.copy(), A.indices.copy())
    kept.states += 1
    if kept.product is None and kept.states > GALERKIN_PLAN_AFTER:
        kept.product = GalerkinProduct(S, A)
    if kept.product is not None:
        return kept.product(A)
    if kept.S_T is None:
        kept.S_T = csr_transposed(S)
    return _triple_product(S, A, kept.S_T)
_CHANGES: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


def _change_of(basis, interior: np.ndarray) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """:func:`bernstein_change`, kept per basis: it depends on the mesh and its Dirichlet dofs, not on the
    film, so every film state of a mesh shares it (0.5 ms of 1e3 unknowns' 8 ms cavitating solve)."""
    key = np.asarray(interior).tobytes()
    cached = _CHANGES.get(basis)
    if cached is None or cached[0] != key:
        cached = (key, *bernstein_change(basis, interior))
        _CHANGES[basis] = cached
    return cached[1], cached[2]


_CHAINS: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


def _chain_of(basis, interior: np.ndarray) -> CoarseChain:
    """The :class:`~bearingfe.cavitation.coarse.CoarseChain` of the interior dofs, kept per basis (it depends
    on the dof coordinates only, so every film state of a mesh shares it)."""
    key = np.asarray(interior).tobytes()
    cached = _CHAINS.get(basis)
    if cached is None or cached[0] != key:
        cached = (key, CoarseChain(np.asarray(basis.doflocs)[:, interior].T))
        _CHAINS[basis] = cached
    return cached[1]


def cached_problem(sup: Superposition) -> FilmProblem | None:
    """The :class:`FilmProblem` of a film state if one was made (by :func:`obstacle_problem`), else None."""
    return _PROBLEMS.get(sup)


def obstacle_problem(sup: Superposition, solver: str | Factorize = DEFAULT_SOLVER, *,
                     tol: float = TOLERANCE, max_iterations: int = MAX_ITERATIONS) -> FilmProblem:
    """The condensed complementarity problem of a film state (cached per superposition)."""
    cached = _PROBLEMS.get(sup)
    if cached is not None and cached.problem.tol == tol and cached.problem.max_iterations == max_iterations:
        return cached
    system = sup.system
    factorize = get_linear_solver(solver)
    S, T = _change_of(sup.operators.basis, system.interior) if sup.operators.element == "P2" else (None, None)
    nodal = system.matrix
    # on P2, S^T A S has its entries in A's pattern (a Bernstein coefficient reads only the dofs of the elements
    # around its edge, so it couples only dofs that share an element), less those that cancel: A's pattern, the
    # mesh's, orders the sets (every film state of the mesh the same order)
    A, pattern = (nodal, None) if S is None else (_galerkin(sup.operators.basis, S, csr_of(nodal)), nodal)
    # the full film's fill-reducing order, restricted to each free set, orders the sets' factorizations
    order = getattr(sup.operators.assembly(sup.assembly), "condensed_order", None)
    problem = ObstacleProblem(A, factorize, tol=tol, max_iterations=max_iterations,
                              order=order if order is not None and len(order) == A.shape[0] else None,
                              pattern=pattern)
    if factorize is system.factorize:
        # the full film's factorization starts the cache; on P2 (S^T A S)^-1 = T A^-1 T^T
        solve = system.solve if S is None else (lambda r, solve=system.solve: T @ solve(T.T @ r))
        problem.add_factorization(np.ones(problem.n, bool), solve)
    fp = FilmProblem(problem=problem, interior=system.interior, boundary=system.boundary, rhs=system.rhs,
                     lift=system.lift, change=S, inverse=T)
    _PROBLEMS[sup] = fp
    return fp


def warm_mask(fp: FilmProblem, sup: Superposition, wts: np.ndarray, warm_start) -> np.ndarray:
    if warm_start is None:
        return (sup.fields @ wts)[fp.interior] < 0.0
    basis = sup.operators.basis
    if isinstance(warm_start, ReynoldsResult) and warm_start.cavitated is not None \
            and warm_start.basis is not basis and warm_start.basis.mesh is not basis.mesh:
        return _transferred_mask(warm_start, basis)[fp.interior]
    mask = warm_start.cavitated if isinstance(warm_start, ReynoldsResult) else warm_start
    mask = np.asarray(mask, bool) if mask is not None else None
    if mask is None or mask.shape != (sup.operators.n_dofs,):
        raise ValueError("warm_start must be a cavitated ReynoldsResult (on any mesh of the same surface) "
                         f"or a boolean mask of length {sup.operators.n_dofs}")
    return mask[fp.interior]


def _transferred_mask(previous: ReynoldsResult, basis) -> np.ndarray:
    """Rupture set of ``previous`` carried to the dofs of ``basis`` (another mesh of the same surface).

    A new dof is ruptured if it lies in an element of the previous mesh
    whose pressure is zero throughout (a ruptured element). This is the
    nested-iteration start that keeps the active-set count bounded under
    refinement: the free boundary is then wrong by about one coarse element
    instead of by the whole difference between the Gumbel and the
    Swift-Stieber rupture sets. Dofs outside the previous mesh start full.
    """
    old = previous.basis
    ruptured = ruptured_elements(old.element_dofs, np.asarray(previous.pressure), previous.cavitated)
    cells = containing_cells(old.mesh.p, old.mesh.t, np.asarray(basis.doflocs))
    return np.where(cells >= 0, ruptured[np.maximum(cells, 0)], False)


#: Rings of neighbours the cold start's free set (where the linear solution is positive) is grown by below
#: :data:`~bearingfe.cavitation.coarse.NESTED_MIN` unknowns: the Swift-Stieber film reaches past the linear
#: solution's zero, and the active-set method frees one layer a step (measured on the journal at 1e3 unknowns,
#: the same sets: P1 5 -> 3 steps with two rings, 4.78 -> 4.43 ms; P2 5 -> 4 with one, 5.82 -> 5.53 ms, whose
#: Bernstein matrix's ring spans an element; interleaved best of 30, load 0.7).
COLD_RINGS = MappingProxyType({"P1": 2, "P2": 1})


def cold_mask(fp: FilmProblem, sup: Superposition, wts: np.ndarray) -> np.ndarray:
    """The start of a system below :data:`~bearingfe.cavitation.coarse.NESTED_MIN` unknowns without a warm
    start: where the linear solution is negative, less :data:`COLD_RINGS` rings along its edge."""
    return _grown(warm_mask(fp, sup, wts, None), fp.problem.pattern, COLD_RINGS.get(sup.operators.element, 0))


def _grown(active: np.ndarray, A: sp.spmatrix, rings: int) -> np.ndarray:
    """``active`` with its complement (the free set) grown by ``rings`` rings of ``A``'s neighbours."""
    A = sp.csr_matrix(A)
    pattern = sp.csr_matrix((np.ones(A.indices.size), A.indices, A.indptr), shape=A.shape)
    free = ~np.asarray(active, bool)
    for _ in range(rings):
        free = (pattern @ free.astype(float)) > 0
    return ~free


def solve_swift_stieber(sup: Superposition, weights: np.ndarray, options: "ModelOptions") -> ReynoldsResult:
    """``"reynolds"``: ``p >= 0`` with a free boundary, by the primal-dual active-set method.

    Without a warm start, a system of :data:`~bearingfe.cavitation.coarse.NESTED_MIN`
    unknowns or more starts from the rupture set of nested coarse-grid problems
    (:func:`~bearingfe.cavitation.coarse.nested_start`), a smaller one from where the
    linear solution is negative less :data:`COLD_RINGS` rings along its edge, and the active-set steps
    reuse the last factorization as a preconditioner (:class:`ObstacleProblem`).
    Should that path fail (a coarse problem or the iteration from its start not
    converging), the plain method is run from the default start and the result's
    ``notes`` say so.
    """
    if sup.system.interior.size > SMALL_PANELS_UP_TO:
        return _solve(sup, weights, options)
    # the small systems' triangular solves and dense kernels out of threaded BLAS, as their factorizations
    # (factorize_splu_small): on a busy machine its threads waited for each other for a millisecond per CG
    # step (measured at 1e3 unknowns, load 5: 8 ms a solve with one thread, 18 ms with two)
    with dense_threads(1):
        return _solve(sup, weights, options)


def _solve(sup: Superposition, weights: np.ndarray, options: "ModelOptions") -> ReynoldsResult:
    t0 = time.perf_counter()
    fp = obstacle_problem(sup, options.solver, tol=options.tol, max_iterations=options.max_iterations)
    b = fp.right_side(weights)
    start = (cold_mask(fp, sup, weights) if options.warm_start is None and fp.problem.n < NESTED_MIN
             else warm_mask(fp, sup, weights, options.warm_start))
    cost = {}
    notes = ()
    krylov = fp.problem.krylov_iterations
    if options.warm_start is None and fp.problem.n >= NESTED_MIN:
        try:
            start, info = nested_start(fp.problem.A, b, None, fp.problem.factorize, tol=options.tol,
                                       max_iterations=options.max_iterations,
                                       chain=_chain_of(sup.operators.basis, fp.interior))
            cost["cavitation_coarse_iterations"] = float(info["coarse_iterations"])
        except (CavitationError, RuntimeError, ValueError, np.linalg.LinAlgError) as exc:
            # a coarse problem failed (e.g. a singular coarse matrix): start from the default set
            notes += (f"cavitation: the coarse-grid start failed ({exc}); started from the linear solution",)
            cost["cavitation_fallback"] = 1.0
        cost["cavitation_coarse"] = time.perf_counter() - t0
    try:
        sol = fp.problem.solve(b, start)
    except CavitationError as exc:
        if not fp.problem.reuse and options.warm_start is not None:
            raise
        # the plain method: a factorization per active set, from the default start
        plain = ObstacleProblem(fp.problem.A, fp.problem.factorize, tol=options.tol,
                                max_iterations=options.max_iterations, reuse=False, pattern=fp.problem.pattern)
        sol = plain.solve(b, warm_mask(fp, sup, weights, options.warm_start))
        notes += (f"cavitation: the nested/reused-factorization path failed ({exc}); solved by the plain "
                  "active-set method",)
        cost["cavitation_fallback"] = 1.0
    cavitated = np.zeros(sup.operators.n_dofs, bool)
    cavitated[fp.interior] = sol.active
    cost.update({"cavitation": time.perf_counter() - t0, "cavitation_factorizations": float(sol.factorizations),
                 "cavitation_krylov_iterations": float(fp.problem.krylov_iterations - krylov)})
    res = build_result(sup, sup.system.full(fp.unknowns(sol.u), weights), weights,
                       options.sliding, cavitation="reynolds",
                       iterations=sol.iterations, cavitated=cavitated, extra_cost=cost)
    return replace(res, notes=res.notes + notes) if notes else res
