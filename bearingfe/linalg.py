"""Pluggable sparse linear solvers for the condensed Reynolds systems.

A solver is a function ``factorize(A) -> solve`` where ``solve(b)`` returns
``A^-1 b`` for a vector or a matrix of right sides. The matrix is symmetric
(positive definite for the direct form; for the substituted form see
:mod:`bearingfe.reynolds`). Choose by name from :data:`LINEAR_SOLVERS` or
pass any callable with that signature.
"""

from __future__ import annotations

from typing import Callable

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

__all__ = ["LINEAR_SOLVERS", "get_linear_solver", "factorize_splu", "factorize_amg"]

Solve = Callable[[np.ndarray], np.ndarray]
Factorize = Callable[[sp.spmatrix], Solve]


def factorize_splu(A: sp.spmatrix) -> Solve:
    """SuperLU with COLAMD ordering (scipy; the measured best of its orderings)."""
    lu = spla.splu(sp.csc_matrix(A), permc_spec="COLAMD")
    return lu.solve


def factorize_amg(A: sp.spmatrix, tol: float = 1e-12) -> Solve:
    """Smoothed-aggregation AMG preconditioned CG (pyamg), to relative ``tol``."""
    import pyamg

    ml = pyamg.smoothed_aggregation_solver(sp.csr_matrix(A))

    def solve(b: np.ndarray) -> np.ndarray:
        b = np.asarray(b, dtype=float)
        cols = b.reshape(b.shape[0], -1)
        out = np.column_stack([ml.solve(c, tol=tol, accel="cg", maxiter=500) for c in cols.T])
        return out.reshape(b.shape)

    return solve


LINEAR_SOLVERS: dict[str, Factorize] = {
    "splu": factorize_splu,
    "amg": factorize_amg,
}


def get_linear_solver(solver: str | Factorize) -> Factorize:
    """Look a solver up by name, or pass a callable through."""
    if callable(solver):
        return solver
    try:
        return LINEAR_SOLVERS[solver]
    except KeyError:
        raise ValueError(f"solver must be one of {sorted(LINEAR_SOLVERS)} or a callable, got {solver!r}") from None
