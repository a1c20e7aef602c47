"""Restarted GMRES for the elastic solves that never form their matrix.

One home for the Krylov solve of the matrix-free paths: the coupled film's inexact Newton steps
(:func:`bearingfe.elastic.coupled.newton` on a product compliance) and the transient's solves with the
compliance's stiffness and its integrator's Newton matrix (:mod:`bearingfe.transient.elastic`).
"""

from __future__ import annotations

from typing import Callable

import numpy as np
import scipy.sparse.linalg as spla

from .compliance import ElasticError

#: Largest Krylov dimension between restarts.
RESTART = 60


def gmres(matvec: Callable[[np.ndarray], np.ndarray], b: np.ndarray, *, rtol: float, what: str,
          preconditioner: Callable[[np.ndarray], np.ndarray] | None = None, x0: np.ndarray | None = None,
          max_iterations: int, must_converge: bool = True) -> tuple[np.ndarray, int]:
    """``x`` with ``|A x - b| <= rtol |b|`` by restarted GMRES (right-hand preconditioned), and its iterations.

    Parameters
    ----------
    matvec : callable
        ``v -> A v`` on vectors of ``b``'s size (non-dimensional, as the caller's unknowns).
    b : numpy.ndarray
        Right side.
    rtol : float
        Relative residual to reach (the absolute tolerance is zero).
    what : str
        The solve, as an error message names it.
    preconditioner : callable, optional
        ``v -> M^-1 v``; none by default.
    x0 : numpy.ndarray, optional
        Start; zero by default.
    max_iterations : int
        Largest number of GMRES iterations, restarts included (whole restart cycles of ``min(n, RESTART)``).
    must_converge : bool
        Raise when ``rtol`` is not met (default); ``False`` returns the last iterate (an inexact Newton step
        that a line search judges), and raises only on a breakdown or a non-finite iterate.

    Returns
    -------
    x : numpy.ndarray
        The solution.
    iterations : int
        GMRES iterations taken.

    Raises
    ------
    ElasticError
        Naming ``what``: breakdown, a non-finite iterate, or (``must_converge``) ``rtol`` not met.
    """
    n = b.size
    op = spla.LinearOperator((n, n), matvec=matvec, dtype=float)
    pre = None if preconditioner is None else spla.LinearOperator((n, n), matvec=preconditioner, dtype=float)
    count = [0]

    def counted(_):
        count[0] += 1

    restart = min(n, RESTART)
    x, info = spla.gmres(op, b, x0=x0, rtol=rtol, atol=0.0, restart=restart, maxiter=max(1, max_iterations // restart),
                         M=pre, callback=counted, callback_type="pr_norm")
    if info < 0 or not np.all(np.isfinite(x)):
        raise ElasticError(f"{what}: GMRES broke down (a non-finite or singular Krylov space)")
    if info != 0 and must_converge:
        size = float(np.linalg.norm(matvec(x) - b) / max(float(np.linalg.norm(b)), 1e-300))
        raise ElasticError(f"{what}: GMRES did not reach the relative residual {rtol:g} in {count[0]} iterations "
                           f"(reached {size:.3g})")
    return x, count[0]
