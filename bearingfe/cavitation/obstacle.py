r"""The obstacle problem on a condensed system: ``A u - b = lam, u >= 0, lam >= 0, u lam = 0``.

Solved by the primal-dual active-set method (Hintermueller, Ito & Kunisch, SIAM
J. Optim. 13 (2003) 865), a semismooth Newton method for ``min(u, lam) = 0``:
each iteration solves the equation on the current free set with ``u = 0`` on the
active set, then moves nodes with ``u < 0`` to the active set and nodes with
``lam < 0`` back. It stops when the set no longer changes (complementarity then
holds to round-off) and raises :class:`CavitationError` at the iteration cap or on
a cycle. Factorizations are cached per active set, so a warm start from a
previous solution with the same set costs one back-substitution.

Consecutive active sets differ by a layer or two of dofs along the free
boundary, so a new set is solved by conjugate gradients preconditioned with the
last factorization (exact on the common dofs, diagonal on the newly freed ones),
started from the last iterate: to a loose step on intermediate sets, to a
medium one once the sets have nearly settled, and to ``tol / 100`` on the set
that then no longer changes, which decides; a set far
from the last factorization (a tenth of the dofs) or whose iteration would cost
more than a factorization is factorized instead (``reuse=False``: a
factorization per set, the plain method). Free sets of up to
:data:`DIRECT_UP_TO` unknowns are always factorized. A factorized set is factored by banded
Cholesky when its band pays (:func:`bearingfe.core.banded.band_pays` for a matrix factored once), else
in the caller's fill-reducing ``order`` (the full film's) restricted to the set.
Nothing here knows about films: :mod:`bearingfe.cavitation.swift_stieber` poses
the problem.
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.sparse.csgraph import reverse_cuthill_mckee

from ..core.banded import band_cholesky, band_plan_in_order, band_worth_trying
from ..core.compressed import csr_of, matvec
from ..core.linalg import SMALL_PANELS_UP_TO, Factorize, factorize_splu_small, factorize_splu_sym

__all__ = ["CavitationError", "ObstacleSolution", "ObstacleProblem", "TOLERANCE", "MAX_ITERATIONS"]

#: Default relative tolerance on the sign tests of the active-set iteration.
TOLERANCE = 1e-10
#: Default cap on active-set iterations.
MAX_ITERATIONS = 60
#: Relative step (in units of the tolerance) of the CG solves on the intermediate active sets. 1e6 rather than 1e5:
#: the same sets, active-set iterations and answers (pressures within 3.2e-13 relative) on full journals (eps 0.62,
#: cold and warm-started from eps 0.6; P1 and P2 at 1e4, 3e4, 1e5 unknowns), with fewer CG steps on the warm starts
#: (P1 85 -> 83, 67 -> 56, 105 -> 80; P2 57 -> 56, 92 -> 86, 81 -> 69; cold starts 20-26 steps, within one), and
#: 4 % fewer instructions for the supply groove of part ``journal_pads``; 1e7 took an active-set iteration more there.
LOOSE = 1e6
#: Relative step (in units of the tolerance) of the CG solves on the sets after the iteration has nearly settled
#: (a few dofs changing a step); the set that then no longer changes is solved to ``tol / 100`` and decided on.
#: None: every settled set to ``tol / 100``.
MEDIUM: float | None = 1e2


class CavitationError(RuntimeError):
    """The complementarity (cavitation) iteration did not converge."""


@dataclass(frozen=True, eq=False)
class ObstacleSolution:
    """Solution of ``A u - b = lam, u >= 0, lam >= 0, u lam = 0``.

    Attributes
    ----------
    u : ndarray
        Unknowns on the condensed (interior) dofs.
    multiplier : ndarray
        ``lam = A u - b`` (zero on the full-film set).
    active : ndarray of bool
        Ruptured (cavitated) dofs, where ``u = 0``.
    iterations : int
        Active-set iterations (linear solves) used.
    factorizations : int
        New factorizations among them (the rest came from the cache).
    """

    u: np.ndarray
    multiplier: np.ndarray
    active: np.ndarray
    iterations: int
    factorizations: int

    def complementarity(self) -> tuple[float, float, float]:
        """``(min u, min lam, max |u lam|)``: the three conditions to check."""
        return (float(self.u.min(initial=0.0)), float(self.multiplier.min(initial=0.0)),
                float(np.abs(self.u * self.multiplier).max(initial=0.0)))


class ObstacleProblem:
    """The condensed obstacle problem ``A u >= b`` type LCP with factorization reuse.

    Parameters
    ----------
    A : sparse matrix, shape (n, n)
        Condensed system matrix (interior dofs).
    factorize : callable
        ``factorize(A_FF) -> solve`` (see :mod:`bearingfe.core.linalg`).
    tol : float
        Relative tolerance of the sign tests (scaled by ``max |u|`` and
        ``max |b|``), guards against flipping nodes on round-off.
    max_iterations : int
        Cap on active-set iterations; beyond it :class:`CavitationError`.
    cache_size : int
        Number of factorizations (one per active set) kept.
    order : ndarray of int, optional
        A fill-reducing elimination order of ``A`` (e.g. the one its full-film factorization used):
        with the default solver a free set is then factored in this order restricted to it, which
        skips finding an order and fills less than minimum degree on the set (measured at 1e5 P1
        unknowns: 0.19 s against 0.49 s, and 30 % faster solves). Default: the solver's own order.
    pattern : sparse matrix, shape (n, n), optional
        A symmetric matrix whose sparsity pattern holds ``A``'s, from which the reverse Cuthill-McKee order of
        the whole matrix is found (and kept per pattern, see :func:`_pattern_rcm`): a condensed matrix made by
        sparse products (the P2 films' ``S^T A S``) drops the entries that cancel exactly, which ones depending
        on the rounding of the film state and some on one side of the diagonal only, and the order found from
        it then swings with the rounding; the mesh's pattern gives every film state of the mesh one order.
        Default: ``A``.
    reuse : bool
        Solve on a new free set by conjugate gradients preconditioned with
        the last factorization (of a nearby free set) instead of factorizing
        it (see :meth:`solve`); a new factorization is made only when the
        iteration has not converged within the cost of about half a
        factorization. False: one factorization per new set (the plain method).
    factor_settled : bool
        The caller will ask for a factorization of the set the iteration ends on (:meth:`factorization`,
        :meth:`solve_fixed`: a linearization on the rupture set, as every Newton step of a journal takes):
        the sets solved once the iteration has nearly settled (the last of them is the answer's) are then
        factored instead of solved by conjugate gradients, so that request finds the factorization made. On
        the supply-groove journal of part ``journal_pads`` (a refined pad of 9,654 P2 unknowns, free sets of
        about 6,000) it spares the CG steps on the last two sets (7 and 8 steps, half a factorization each)
        and the factorization made after them.
    """

    def __init__(self, A: sp.spmatrix, factorize: Factorize, *, tol: float = TOLERANCE,
                 max_iterations: int = MAX_ITERATIONS, cache_size: int = 4, reuse: bool = True,
                 order: np.ndarray | None = None, factor_settled: bool = False,
                 pattern: sp.spmatrix | None = None) -> None:
        if not (0 < tol < 1e-2):
            raise ValueError(f"tol must be in (0, 1e-2), got {tol!r}")
        if not (isinstance(max_iterations, int) and max_iterations >= 1):
            raise ValueError(f"max_iterations must be an integer >= 1, got {max_iterations!r}")
        self.A = csr_of(A)
        self.n = self.A.shape[0]
        self.factorize = factorize
        self.tol = float(tol)
        self.max_iterations = max_iterations
        self.reuse = bool(reuse)
        self.factor_settled = bool(factor_settled)
        if order is not None:
            order = np.asarray(order, np.int64)
            if order.shape != (self.n,) or not np.array_equal(np.sort(order), np.arange(self.n)):
                raise ValueError(f"order must be a permutation of the {self.n} unknowns")
        self.order = order
        self._cache: dict[bytes, object] = {}
        self._cache_size = int(cache_size)
        self._diag = self.A.diagonal()
        self._block_plan = None  # _Blocks of A, made on the first block taken
        if pattern is not None and pattern.shape != self.A.shape:
            raise ValueError(f"pattern must have A's shape {self.A.shape}, got {pattern.shape}")
        #: the matrix whose sparsity pattern orders the factorizations (see the parameter)
        self.pattern = self.A if pattern is None else csr_of(pattern)
        self._rcm = None  # reverse Cuthill-McKee order of the pattern, made on the first banded factorization
        self._band_refused_from = math.inf  # free sets this large or larger are not tried banded (see _factor)
        self._own_order_first = False  # a set's own order took a band the whole matrix's refused (see _factor)
        self._reference = None  # (free mask, solve) of the last factorization: the preconditioner
        self._low_memory = False  # a factorization failed for memory: CG with the reference only, no time cap
        #: conjugate-gradient iterations done on new free sets (instead of factorizations), in total
        self.krylov_iterations = 0
        #: factorizations made, in total
        self.factorization_count = 0

    @property
    def _blocks(self) -> "_Blocks":
        if self._block_plan is None:
            self._block_plan = _Blocks(self.A)
        return self._block_plan

    def _block_matrix(self, free: np.ndarray, block: tuple | None = None) -> sp.csr_matrix:
        """``A[free][:, free]``: from the block's entries of :class:`_Blocks` (given, or taken here up to
        :data:`BLOCKS_UP_TO` unknowns), by scipy's slicing above."""
        if block is None and self.n <= BLOCKS_UP_TO:
            block = self._blocks.coo(free)
        if block is not None:
            return self._blocks.csr(block)
        idx = np.flatnonzero(free)
        return self.A[idx][:, idx].tocsr()

    def _rcm_order(self) -> np.ndarray:
        """The reverse Cuthill-McKee order of the whole matrix's pattern (``pattern``; made once, and kept per
        sparsity pattern up to :data:`BLOCKS_UP_TO` unknowns: every film state of a mesh, and every coarse grid
        of its nested start, has the same pattern)."""
        if self._rcm is None:
            self._rcm = _pattern_rcm(self.pattern)
        return self._rcm

    def _store(self, key: bytes, solve) -> None:
        if key in self._cache:
            del self._cache[key]
        elif len(self._cache) >= self._cache_size:
            self._cache.pop(next(iter(self._cache)))
        self._cache[key] = solve

    def _factor(self, free: np.ndarray):
        factorize = self.factorize
        default = factorize is factorize_splu_sym or factorize is factorize_splu_small
        size = int(np.count_nonzero(free))
        block = self._blocks.coo(free) if size and self.n <= BLOCKS_UP_TO else None
        solve = None
        if default and band_worth_trying(size, "new_pattern") and size < self._band_refused_from:
            # in the reverse Cuthill-McKee order of the whole matrix restricted to the set (its band is no wider
            # than the whole's: measured the same as the set's own order on the journal's sets, P1 and P2), else
            # in the set's own. Once the set's own order took a band the whole matrix's refused, the whole
            # matrix's order is a poor one (scipy's starts at its node of least degree, which on a rupture-refined
            # mesh may lie inside it) and the next sets of this problem, a layer or two of dofs apart, are tried
            # in their own order first: on the two-groove journal's refined pads (journal_pads, level 1 of the
            # rupture refinement) the next three sets' bands 124-126 -> 58-69, their factorizations about half
            whole = block is not None  # (a whole-matrix order for a small set of a large matrix: not made)
            if whole and not self._own_order_first:
                solve = _factor_banded(None, block, _restricted(self._rcm_order(), free))
            if solve is None:
                solve = _factor_banded(self._block_matrix(free, block), block)
                self._own_order_first = self._own_order_first or (solve is not None and whole)
            if solve is None and whole and self._own_order_first:
                solve = _factor_banded(None, block, _restricted(self._rcm_order(), free))
            if solve is None:
                # refused in every order: the next sets of this problem (a layer or two of dofs apart, their bands
                # alike) as large or larger go to SuperLU at once (on the L/D 1 two-groove journal's level-3 sets,
                # 1,724-1,970 unknowns, bands 173-518 in either order, each try cost an order and a plan for nothing)
                self._band_refused_from = size
        if solve is None and not size:
            solve = lambda b: np.zeros_like(b)  # noqa: E731
        elif solve is None and factorize is factorize_splu_sym and self.order is not None:
            solve = _factor_in_order(self.A, free, self.order, block)
        elif solve is None:
            if factorize is factorize_splu_sym and size <= SMALL_PANELS_UP_TO:
                factorize = factorize_splu_small  # the same factorization, out of threaded BLAS
            solve = factorize(self._block_matrix(free, block))
        self._reference = (free.copy(), solve)
        self._store(np.packbits(free).tobytes(), solve)
        self.factorization_count += 1
        return solve

    def _solver(self, free: np.ndarray):
        """A factorization of ``A[free][:, free]`` (cached); ``(solve, 1 if new else 0)``."""
        key = np.packbits(free).tobytes()
        solve = self._cache.get(key)
        if solve is not None and not isinstance(solve, _Krylov):
            return solve, 0
        return self._factor(free), 1

    def _mask(self, mask: np.ndarray, name: str) -> np.ndarray:
        """``mask`` as a boolean array of the unknowns; ValueError naming ``name`` if it has another shape."""
        mask = np.asarray(mask, bool)
        if mask.shape != (self.n,):
            raise ValueError(f"{name} must be a boolean mask of length {self.n}")
        return mask

    def add_factorization(self, free: np.ndarray, solve) -> None:
        """Put a factorization of ``A[free][:, free]`` made elsewhere in the cache: the
        preconditioner of the next sets' conjugate-gradient solves."""
        free = self._mask(free, "free")
        self._store(np.packbits(free).tobytes(), solve)
        self._reference = (free.copy(), solve)

    def precondition(self, free: np.ndarray, solve) -> None:
        """Take a factorization of a nearby matrix's ``A'[free][:, free]`` (the same unknowns, e.g. the previous
        state of a film being iterated on) as the preconditioner of the next sets' conjugate-gradient solves;
        unlike :meth:`add_factorization` it is not taken as a solve of this matrix."""
        free = self._mask(free, "free")
        self._reference = (free.copy(), solve)

    def _solve_free(self, free: np.ndarray, b_free: np.ndarray, rtol: float | None = None,
                    x0: np.ndarray | None = None) -> tuple[np.ndarray, int, bool]:
        """``A[free][:, free]^-1 b_free``: cached, by preconditioned CG, or by a new factorization.

        Returns the solution, 1 if a factorization was made (else 0), and
        whether it is exact (a factorization) or a conjugate-gradient iterate
        to the relative step ``rtol`` (default ``tol / 100``).
        """
        key = np.packbits(free).tobytes()
        solve = self._cache.get(key)
        if solve is None and self.reuse and np.count_nonzero(free) > DIRECT_UP_TO:
            if not self._low_memory and (self._reference is None
                                         or np.count_nonzero(self._reference[0] != free) > 0.1 * self.n):
                # far from the last factorization: factorize this set, the reference of the next ones
                # (measured: factorizing it grown by 1-3 rings of neighbours, so that the next sets are
                # subsets of it, cost more outer and CG iterations than it saved)
                try:
                    return self._factor(free)(b_free), 1, True
                except (MemoryError, RuntimeError, SystemError):  # SuperLU out of memory: "SUPERLU_MALLOC fails",
                    # or "gstrf was called with invalid arguments" (measured at 1e6 unknowns, 16 GB address space)
                    if self._reference is None:
                        raise
                    self._low_memory = True
            solve = _Krylov(self, free)
            self._store(key, solve)
        if isinstance(solve, _Krylov):
            try:
                u = solve(b_free, rtol=rtol, x0=x0)
                self.krylov_iterations += solve.last_iterations
                return u, 0, False
            except _NotConverged as exc:
                self.krylov_iterations += exc.iterations
                if self._low_memory:
                    raise CavitationError(
                        "no memory for a factorization of the active set and the conjugate gradients "
                        f"preconditioned with the last one did not converge in {exc.iterations} iterations "
                        f"({self.n} unknowns)") from None
                return self._factor(free)(b_free), 1, True
        if solve is None:
            return self._factor(free)(b_free), 1, True
        return solve(b_free), 0, True

    def _solve_settled(self, free: np.ndarray, b_free: np.ndarray, rtol: float | None,
                       x0: np.ndarray | None) -> tuple[np.ndarray, int, bool]:
        """:meth:`_solve_free` of a set solved once the iteration has nearly settled: by a factorization (cached,
        or made now) if ``factor_settled`` and there is memory for it, else as :meth:`_solve_free` solves it."""
        if self.factor_settled and self.reuse and not self._low_memory:
            solve = self._cache.get(np.packbits(free).tobytes())
            if solve is not None and not isinstance(solve, _Krylov):
                return solve(b_free), 0, True
            try:
                return self._factor(free)(b_free), 1, True
            except (MemoryError, RuntimeError, SystemError):  # as in _solve_free: CG with the reference from here on
                if self._reference is None:
                    raise
                self._low_memory = True
        return self._solve_free(free, b_free, rtol, x0)

    def factorization(self, free: np.ndarray):
        """The solve ``b -> A[free][:, free]^-1 b`` by a factorization: the cached one of that set (the
        active-set iteration's, when it ended on a factored set), else a new one, kept in the cache."""
        free = self._mask(free, "free")
        return self._solver(free)[0]

    def solve_fixed(self, b: np.ndarray, active: np.ndarray) -> np.ndarray:
        """Solve with ``u = 0`` on a given active set (the linearization on a
        fixed rupture set) with a factorization; ``b`` may have several columns."""
        free = ~np.asarray(active, bool)
        solve = self.factorization(free)
        b = np.asarray(b, float)
        u = np.zeros_like(b)
        if free.any():
            u[free] = np.asarray(solve(b[free])).reshape(b[free].shape)
        return u

    def _next_set(self, u: np.ndarray, b: np.ndarray, active: np.ndarray, free: np.ndarray,
                  scale_b: float) -> tuple[np.ndarray, np.ndarray]:
        """The multiplier of ``u`` and the active set it asks for (primal-dual rule, sign tolerances)."""
        lam = matvec(self.A, u) - b
        lam[free] = 0.0
        tol_u = self.tol * float(np.abs(u).max(initial=0.0))
        tol_l = self.tol * max(scale_b, float(np.abs(lam).max(initial=0.0)))
        return lam, np.where(active, lam > -tol_l, u < -tol_u)

    def solve(self, b: np.ndarray, active: np.ndarray | None = None) -> ObstacleSolution:
        """Primal-dual active-set iteration from an initial rupture set.

        Parameters
        ----------
        b : ndarray, shape (n,)
        active : ndarray of bool, optional
            Warm start (e.g. the rupture set of a previous solution, or
            where the unconstrained solution is negative); default empty.
        """
        b = np.asarray(b, float)
        if b.shape != (self.n,) or not np.all(np.isfinite(b)):
            raise ValueError(f"b must be a finite vector of length {self.n}")
        active = np.zeros(self.n, bool) if active is None else self._mask(active, "active").copy()
        seen: set[bytes] = set()
        made = self.factorization_count
        scale_b = float(np.abs(b).max(initial=0.0))
        loose = LOOSE * self.tol  # intermediate sets need only the signs of the clear cases
        # settled sets: their signs to within a few dofs (None: to the tolerance at once)
        medium = MEDIUM * self.tol if self.reuse and MEDIUM is not None else None
        exact = True
        settled = False  # a set nearly settled: from then on every set is solved to the medium step, and to the
        # tolerance when it no longer changes (or comes back), which decides
        u = np.zeros(self.n)
        for it in range(1, self.max_iterations + 1):
            free = ~active
            u_previous = u
            u = np.zeros(self.n)
            if free.any():
                # from the last iterate (zero on the newly freed dofs); once settled, to the medium step, then
                # to the tolerance on the set that no longer changes (measured on the journal, the same sets:
                # 35 CG steps against 42 at 1e4 P2 unknowns, 41 against 55 P1, 33 against 44 at 3e4 P2, 44
                # against 55 P1, for every settled set solved to the tolerance; that had measured 333 CG steps
                # in all on eight cases from 1e3 to 1e5 unknowns against 453 for a loose solve and a restarted
                # tight one on each set)
                x0 = u_previous[free] if it > 1 else None
                u[free], _, exact = (self._solve_settled(free, b[free], medium, x0) if settled
                                     else self._solve_free(free, b[free], loose, x0))
                exact = exact or (settled and medium is None)
            if not np.all(np.isfinite(u)):
                raise CavitationError("the linear solve on the full-film set returned non-finite values "
                                      "(singular operator: is the film region connected to a p = 0 edge?)")
            lam, new_active = self._next_set(u, b, active, free, scale_b)
            key = np.packbits(new_active).tobytes()
            changes = int(np.count_nonzero(new_active != active))
            if not exact and not settled and (changes <= max(SETTLING_CHANGES, SETTLING_FRACTION * self.n)
                                              or key in seen):
                # settled, nearly (a few dofs flipping on the rounding of an inexact solve), or back to a
                # set seen, on an inexact solve: solve this set to the medium step (the tolerance if None) and
                # go on from that
                u[free], _, exact = self._solve_settled(free, b[free], medium, u[free])
                lam, new_active = self._next_set(u, b, active, free, scale_b)
                key = np.packbits(new_active).tobytes()
                changes = int(np.count_nonzero(new_active != active))
                exact = exact or medium is None
                settled = True
            if not exact and settled and (changes == 0 or key in seen):
                # a medium solve that keeps its set (or goes back to one seen): to the tolerance, and decide on that
                u[free], _, exact = self._solve_free(free, b[free], None, u[free])
                lam, new_active = self._next_set(u, b, active, free, scale_b)
                key = np.packbits(new_active).tobytes()
                exact = True
            if np.array_equal(new_active, active):
                return ObstacleSolution(u=u, multiplier=lam, active=active, iterations=it,
                                        factorizations=self.factorization_count - made)
            seen.add(np.packbits(active).tobytes())
            if key in seen:
                raise CavitationError(
                    f"cavitation active-set iteration cycles after {it} iterations "
                    f"({int(new_active.sum())} ruptured dofs): the discrete operator is far from an "
                    "M-matrix (try element='P1', formulation='direct' or a finer mesh)")
            active = new_active
        raise CavitationError(
            f"cavitation active-set iteration did not converge in {self.max_iterations} iterations "
            f"({int(active.sum())} ruptured dofs); raise max_iterations or check the mesh")


#: Free sets up to this many unknowns are factored, not solved by CG: a (banded) factorization costs less than
#: the ten or twenty CG steps of a set there (each mostly interpreter time). Measured at 3e3 unknowns (free sets
#: of 1,600-2,000, banded factorizations; CPU time, best of 30): P2 18.4 ms against 19.3 ms with 1,500 (a
#: factorization and 38 CG steps), P1 16.4 against 18.8 ms.
DIRECT_UP_TO = 3000


#: Matrices up to this many unknowns take their free blocks from :class:`_Blocks`; above, scipy's slicing (in C,
#: without the fixed costs that weigh at small sizes) is faster: 5.2 against 12 ms at 3e5 unknowns and 1.5e6
#: entries, 14 against 36 ms with 3.9e6 entries.
BLOCKS_UP_TO = 20000


class _Blocks:
    """Principal blocks ``A[idx][:, idx]`` of a fixed CSR matrix from index arrays made once per matrix.

    scipy's slicing builds two new sparse matrices per block (their index checks and dtype searches cost
    about 0.5 ms at 1e3 unknowns, a tenth of an active-set step there); here a block is one mask over the
    stored entries and three gathers. The block's entries come in the order of the stored ones (rows in
    order, columns sorted within a row if ``A``'s are), so :meth:`csr` is scipy's ``A[idx][:, idx]``.
    """

    def __init__(self, A: sp.csr_matrix) -> None:
        A = sp.csr_matrix(A)
        if not A.has_sorted_indices:
            A = A.sorted_indices()
        self.n = A.shape[0]
        index = np.int32 if self.n < 2**31 else np.int64  # two index arrays of nnz: half the memory in int32
        self.lengths = np.diff(A.indptr)  # entries per row
        self.row = np.repeat(np.arange(self.n, dtype=index), self.lengths)
        self.col = A.indices.astype(index, copy=False)
        self.data = A.data

    def coo(self, free: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
        """``(rows, cols, values, m)`` of the block on the ``free`` mask, numbered among the free dofs."""
        keep = np.repeat(free, self.lengths)  # free[self.row] without its gather (0.03 against 0.23 ms at 1e5 entries)
        keep &= free[self.col]
        position = np.cumsum(free) - 1
        return position[self.row[keep]], position[self.col[keep]], self.data[keep], int(position[-1]) + 1

    def csr(self, block: tuple[np.ndarray, np.ndarray, np.ndarray, int]) -> sp.csr_matrix:
        """The block of :meth:`coo` as a CSR matrix (sorted indices)."""
        rows, cols, values, m = block
        indptr = np.zeros(m + 1, np.int64)
        np.cumsum(np.bincount(rows, minlength=m), out=indptr[1:])
        return sp.csr_matrix((values, cols, indptr), shape=(m, m))


#: Reverse Cuthill-McKee orders of the last few sparsity patterns: ``(indptr, indices, order)``, newest last.
_RCM_ORDERS: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []
#: Patterns kept in :data:`_RCM_ORDERS` (a mesh's film states share one, its coarse grids one each).
RCM_PATTERNS_KEPT = 8
_RCM_LOCK = threading.Lock()


def _pattern_rcm(A: sp.csr_matrix) -> np.ndarray:
    """The reverse Cuthill-McKee order of ``A``'s pattern, found once per pattern up to :data:`BLOCKS_UP_TO`
    unknowns (0.4 ms at 3e3 unknowns, a third of a banded factorization there; the look-up compares the
    pattern's index arrays, some 20 us)."""
    if A.shape[0] > BLOCKS_UP_TO:
        return reverse_cuthill_mckee(A, symmetric_mode=True).astype(np.int64)
    with _RCM_LOCK:  # film states solved in threads share the list
        for k, (indptr, indices, order) in enumerate(_RCM_ORDERS):
            if indptr.size == A.indptr.size and indices.size == A.indices.size \
                    and np.array_equal(indptr, A.indptr) and np.array_equal(indices, A.indices):
                _RCM_ORDERS.append(_RCM_ORDERS.pop(k))
                return order
    order = reverse_cuthill_mckee(A, symmetric_mode=True).astype(np.int64)
    with _RCM_LOCK:
        _RCM_ORDERS.append((A.indptr.copy(), A.indices.copy(), order))
        del _RCM_ORDERS[:-RCM_PATTERNS_KEPT]
    return order


def _restricted(order: np.ndarray, free: np.ndarray) -> np.ndarray:
    """An elimination ``order`` of all dofs restricted to the ``free`` ones (positions among the free dofs)."""
    return (np.cumsum(free) - 1)[order[free[order]]]


def _factor_banded(M: sp.spmatrix | None, block: tuple | None = None, perm: np.ndarray | None = None):
    """Banded Cholesky (:func:`~bearingfe.core.banded.band_cholesky`) of a symmetric positive definite ``M`` in
    the reverse Cuthill-McKee order, or None if the band does not pay for a matrix factored once
    (:func:`~bearingfe.core.banded.band_pays`, ``"new_pattern"``) or ``M`` is not positive definite in floating
    point (the caller then uses SuperLU). ``block``: ``M``'s entries as ``(rows, cols, values, m)`` (from
    :class:`_Blocks`), which spares converting ``M``; ``perm``: the order to factor in instead of ``M``'s
    reverse Cuthill-McKee order (``M`` is then not read, ``block`` is needed)."""
    if perm is None:
        M = sp.csr_matrix(M)
        perm = reverse_cuthill_mckee(M, symmetric_mode=True)
    if block is None:
        C = M.tocoo()
        block = (C.row, C.col, C.data, M.shape[0])
    rows, cols, values, m = block
    plan = band_plan_in_order(rows, cols, m, perm, kind="new_pattern")
    return None if plan is None else band_cholesky(plan, values)


def _factor_in_order(A: sp.csr_matrix, free: np.ndarray, order: np.ndarray, block: tuple | None = None):
    """SuperLU (symmetric mode, no pivoting, as :func:`factorize_splu_sym`) of ``A[free][:, free]`` in
    ``order`` restricted to the free set; returns the solve of ``A[free][:, free]``. ``block``: the free
    block's entries as ``(rows, cols, values, m)`` (from :class:`_Blocks`)."""
    sub = _restricted(order, free)  # the free block's order (positions among the free dofs)
    inverse = np.empty_like(sub)
    inverse[sub] = np.arange(sub.size)
    if block is None:
        chosen = np.flatnonzero(free)[sub]
        matrix = A[chosen][:, chosen].tocsc()
    else:
        rows, cols, values, m = block
        # the CSR arrays of the permuted block's transpose are its CSC arrays (rows sorted within a column): by
        # scipy's conversion in C, 0.9 ms against 3.5 ms for a lexsort of the 1.1e5 entries of a 5,400-unknown
        # P2 set (the same matrix, entry for entry)
        csr = sp.coo_matrix((values, (inverse[cols], inverse[rows])), shape=(m, m)).tocsr()
        csr.sort_indices()
        matrix = sp.csc_matrix((csr.data, csr.indices, csr.indptr), shape=(m, m))
    lu = spla.splu(matrix, permc_spec="NATURAL", diag_pivot_thresh=0.0,
                   options={"SymmetricMode": True},
                   **({"panel_size": 1, "relax": 1} if sub.size <= SMALL_PANELS_UP_TO else {}))

    def solve(b: np.ndarray) -> np.ndarray:
        return lu.solve(np.asarray(b, dtype=float)[sub])[inverse]

    return solve


#: An inexact (conjugate-gradient) solve whose next set differs in at most this many dofs, or this fraction
#: of them, is redone to the tolerance before the set moves: near the answer the rounding of a loose solve
#: flips dofs on the free boundary back and forth (measured: 2-4 dofs of 1.8e5 chattering for five steps,
#: then a cycle) where the exact solve settles.
SETTLING_CHANGES = 16
SETTLING_FRACTION = 1e-4


def krylov_cap(unknowns: int, low_memory: bool = False) -> int:
    """A factorization's worth of preconditioned CG iterations on ``unknowns`` (the reference's size).

    A count, not a timing, so that the same problem always takes the same path and gives the same
    digits: ``3.5 n^0.24`` within [8, 200], fitted to the measured ratio of a factorization's time to
    one iteration's (about 14 at 226 unknowns, 25 at 2,694, 37 at 53,593, 70 at 160,928; P1 journal,
    cold start). Without memory for another factorization CG is the only way on: 1000.
    """
    if low_memory:
        return 1000
    return int(min(200, max(8, 3.5 * max(int(unknowns), 1) ** 0.24)))


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    # not BLAS: its threads wait for each other on a busy machine, which made a CG step cost ms
    return float(np.multiply(a, b).sum())


class _NotConverged(Exception):
    def __init__(self, iterations: int) -> None:
        super().__init__(iterations)
        self.iterations = iterations


class _Krylov:
    """``A[free][:, free]^-1 b`` by conjugate gradients preconditioned with the
    factorization of a nearby free set ``F0``.

    The preconditioner is the factorization on the dofs free in both sets and
    the diagonal on the dofs only ``free`` has: symmetric positive definite,
    and equal to the exact inverse but for the rows next to the dofs where
    the two sets differ, so the iteration converges in a few steps when the
    sets differ by a few layers of dofs along the free boundary. It stops when
    the last update is below ``rtol`` of the solution (max norm; at most
    ``tol / 100``) and raises :class:`_NotConverged` when the rate of the last
    steps says it would need more than a factorization's cost in iterations
    (:func:`krylov_cap`, a count, so that the path and its digits are reproducible) to get there.
    """

    def __init__(self, problem: ObstacleProblem, free: np.ndarray) -> None:
        ref_free, self.ref_solve = problem._reference
        self.problem = problem
        self.idx = np.flatnonzero(free)
        self.free = free.copy()
        pos = np.full(problem.n, -1)
        pos[self.idx] = np.arange(self.idx.size)
        ref_idx = np.flatnonzero(ref_free)
        common = free[ref_idx]
        self.ref_n = ref_idx.size
        self.ref_common = np.flatnonzero(common)        # positions in F0 of the common dofs
        self.common = pos[ref_idx[common]]              # their positions in F
        new = free & ~ref_free
        self.new = pos[np.flatnonzero(new)]
        self.new_diag = problem._diag[np.flatnonzero(new)]
        self._t = np.zeros(self.ref_n)  # the preconditioner's right side, zero off the common dofs
        self._matrix = None  # A[free][:, free], extracted on the first product
        self.rtol = 1e-2 * problem.tol
        self.last_iterations = 0
        self.cap = None
        self._last = None

    def _precondition(self, r: np.ndarray) -> np.ndarray:
        t = self._t
        t[self.ref_common] = r[self.common]
        s = np.asarray(self.ref_solve(t)).reshape(-1)
        z = np.empty_like(r)
        z[self.common] = s[self.ref_common]
        z[self.new] = r[self.new] / self.new_diag
        return z

    def _matvec(self, x: np.ndarray) -> np.ndarray:
        # the free rows and columns once, not a product with the whole matrix per step (the same sums in the
        # same order: the left-out columns multiply zeros)
        if self._matrix is None:
            self._matrix = self.problem._block_matrix(self.free)
        return self._matrix @ x

    def __call__(self, b: np.ndarray, rtol: float | None = None, x0: np.ndarray | None = None) -> np.ndarray:
        b = np.asarray(b, float)
        if b.ndim == 2:
            return np.column_stack([self(c, rtol) for c in b.T])
        rtol = self.rtol if rtol is None else max(float(rtol), self.rtol)
        if x0 is None and self._last is not None and np.array_equal(self._last[0], b):
            x0 = self._last[1]  # the same right side again (a warm start on this set): start from its answer
        x = np.zeros_like(b) if x0 is None else np.array(x0, float)
        r = b - self._matvec(x) if x0 is not None else b.copy()
        z = self._precondition(r)
        p = z.copy()
        rz = _dot(r, z)
        if self.cap is None:
            self.cap = krylov_cap(self.ref_n, self.problem._low_memory)
        cap = self.cap
        if float(np.abs(b).max(initial=0.0)) == 0.0:
            self.last_iterations = 0
            return np.zeros_like(b)
        steps = []
        for it in range(1, cap + 1):
            q = self._matvec(p)
            pq = _dot(p, q)
            if not pq > 0.0:
                raise _NotConverged(it)
            alpha = rz / pq
            x += alpha * p
            r -= alpha * q
            size = float(np.abs(x).max())
            steps.append(abs(alpha) * float(np.abs(p).max()) / size if size > 0 else 1.0)
            if steps[-1] <= rtol:
                self.last_iterations = it
                if rtol <= self.rtol:
                    self._last = (b.copy(), x.copy())
                return x
            if it >= 6:  # projected from the rate of the last four steps: give up early if it would not pay
                rate = (steps[-1] / max(steps[-5], 1e-300)) ** 0.25
                if rate >= 1.0 or it + math.log(rtol / steps[-1]) / math.log(rate) > cap:
                    raise _NotConverged(it)
            z = self._precondition(r)
            rz_new = _dot(r, z)
            p = z + (rz_new / rz) * p
            rz = rz_new
        raise _NotConverged(cap)
