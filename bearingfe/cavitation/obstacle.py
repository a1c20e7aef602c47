r"""The obstacle problem on a condensed system: ``A u - b = lam, u >= 0, lam >= 0, u lam = 0``.

Solved by the primal-dual active-set method (Hintermueller, Ito & Kunisch, SIAM
J. Optim. 13 (2003) 865), a semismooth Newton method for ``min(u, lam) = 0``:
each iteration solves the equation on the current free set with ``u = 0`` on the
active set, then moves nodes with ``u < 0`` to the active set and nodes with
``lam < 0`` back. It stops when the set no longer changes (complementarity then
holds to round-off) and raises :class:`CavitationError` at the iteration cap or on
a cycle. Factorizations are cached per active set, so a warm start from a
previous solution with the same set costs one back-substitution. Nothing here
knows about films: :mod:`bearingfe.cavitation.swift_stieber` poses the problem.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..core.linalg import Factorize

__all__ = ["CavitationError", "ObstacleSolution", "ObstacleProblem", "TOLERANCE", "MAX_ITERATIONS"]

#: Default relative tolerance on the sign tests of the active-set iteration.
TOLERANCE = 1e-10
#: Default cap on active-set iterations.
MAX_ITERATIONS = 60


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
    """

    def __init__(self, A: sp.spmatrix, factorize: Factorize, *, tol: float = TOLERANCE,
                 max_iterations: int = MAX_ITERATIONS, cache_size: int = 4) -> None:
        if not (0 < tol < 1e-2):
            raise ValueError(f"tol must be in (0, 1e-2), got {tol!r}")
        if not (isinstance(max_iterations, int) and max_iterations >= 1):
            raise ValueError(f"max_iterations must be an integer >= 1, got {max_iterations!r}")
        self.A = sp.csr_matrix(A)
        self.n = self.A.shape[0]
        self.factorize = factorize
        self.tol = float(tol)
        self.max_iterations = max_iterations
        self._cache: dict[bytes, object] = {}
        self._cache_size = int(cache_size)

    def _solver(self, free: np.ndarray):
        key = np.packbits(free).tobytes()
        if key in self._cache:
            return self._cache[key], 0
        idx = np.flatnonzero(free)
        solve = self.factorize(self.A[idx][:, idx]) if idx.size else (lambda b: np.zeros_like(b))
        if len(self._cache) >= self._cache_size:
            self._cache.pop(next(iter(self._cache)))
        self._cache[key] = solve
        return solve, 1

    def add_factorization(self, free: np.ndarray, solve) -> None:
        """Put a factorization of ``A[free][:, free]`` made elsewhere in the cache."""
        free = np.asarray(free, bool)
        if free.shape != (self.n,):
            raise ValueError(f"free must be a boolean mask of length {self.n}")
        if len(self._cache) >= self._cache_size:
            self._cache.pop(next(iter(self._cache)))
        self._cache[np.packbits(free).tobytes()] = solve

    def solve_fixed(self, b: np.ndarray, active: np.ndarray) -> np.ndarray:
        """Solve with ``u = 0`` on a given active set (the linearization on a
        fixed rupture set); ``b`` may have several columns."""
        free = ~np.asarray(active, bool)
        solve, _ = self._solver(free)
        b = np.asarray(b, float)
        u = np.zeros_like(b)
        if free.any():
            u[free] = np.asarray(solve(b[free])).reshape(b[free].shape)
        return u

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
        active = np.zeros(self.n, bool) if active is None else np.asarray(active, bool).copy()
        if active.shape != (self.n,):
            raise ValueError(f"active must be a boolean mask of length {self.n}")
        seen: set[bytes] = set()
        factorizations = 0
        scale_b = float(np.abs(b).max(initial=0.0))
        for it in range(1, self.max_iterations + 1):
            free = ~active
            solve, new = self._solver(free)
            factorizations += new
            u = np.zeros(self.n)
            if free.any():
                u[free] = solve(b[free])
            if not np.all(np.isfinite(u)):
                raise CavitationError("the linear solve on the full-film set returned non-finite values "
                                      "(singular operator: is the film region connected to a p = 0 edge?)")
            lam = self.A @ u - b
            lam[free] = 0.0
            tol_u = self.tol * float(np.abs(u).max(initial=0.0))
            tol_l = self.tol * max(scale_b, float(np.abs(lam).max(initial=0.0)))
            new_active = np.where(active, lam > -tol_l, u < -tol_u)
            if np.array_equal(new_active, active):
                return ObstacleSolution(u=u, multiplier=lam, active=active, iterations=it,
                                        factorizations=factorizations)
            seen.add(np.packbits(active).tobytes())
            key = np.packbits(new_active).tobytes()
            if key in seen:
                raise CavitationError(
                    f"cavitation active-set iteration cycles after {it} iterations "
                    f"({int(new_active.sum())} ruptured dofs): the discrete operator is far from an "
                    "M-matrix (try element='P1', formulation='direct' or a finer mesh)")
            active = new_active
        raise CavitationError(
            f"cavitation active-set iteration did not converge in {self.max_iterations} iterations "
            f"({int(active.sum())} ruptured dofs); raise max_iterations or check the mesh")
