"""Pluggable sparse linear solvers for the condensed Reynolds systems.

A solver is a function ``factorize(A) -> solve`` where ``solve(b)`` returns
``A^-1 b`` for a vector or a matrix of right sides. The matrix is symmetric
(positive definite for the direct form; for the substituted form see
:mod:`bearingfe.reynolds`). Choose by name from :data:`LINEAR_SOLVERS` or
pass any callable with that signature.
"""

from __future__ import annotations

import contextlib
import threading
from typing import Callable

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .ordering import NESTED_DISSECTION_FROM, nested_dissection

__all__ = ["DEFAULT_SOLVER", "LINEAR_SOLVERS", "get_linear_solver", "available_solvers", "PatternFactorizer", "factorize_splu",
           "factorize_splu_sym", "factorize_splu_small", "SMALL_PANELS_UP_TO", "factorize_amg", "factorize_cholmod", "factorize_pardiso", "factorize_cholespy", "dense_threads"]

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


#: The default: SuperLU in symmetric mode needs nothing beyond scipy and
#: factored the condensed Reynolds systems about 2x faster than COLAMD
#: (docs/benchmarks.md); the systems it gets are symmetric positive definite
#: (the pi form is checked first, see bearingfe.reynolds). CHOLMOD and PARDISO
#: are faster still where installed: pass ``solver="cholmod"`` or ``"pardiso"``.
DEFAULT_SOLVER = "splu_sym"


def get_linear_solver(solver: str | Factorize) -> Factorize:
    """Look a solver up by name, or pass a callable through."""
    if callable(solver):
        return solver
    try:
        return LINEAR_SOLVERS[solver]
    except KeyError:
        raise ValueError(f"solver must be one of {sorted(LINEAR_SOLVERS)} or a callable, got {solver!r}") from None


# -- optional solvers (used only if their package is installed) -------------------

def _optional(module: str, package: str):
    """Import an optional solver backend or say which pip package provides it."""
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as exc:
        raise ImportError(f"this linear solver needs the optional package {package!r} "
                          f"(pip install {package}); the default 'splu' needs nothing extra") from exc


def _columns(b: np.ndarray) -> np.ndarray:
    return np.asarray(b, dtype=float).reshape(b.shape[0], -1)


def factorize_splu_sym(A: sp.spmatrix, coordinates: np.ndarray | None = None) -> Solve:
    """SuperLU in symmetric mode, no pivoting: minimum degree on ``A^T + A``, or nested dissection.

    Valid for the symmetric positive definite condensed systems (diagonal
    pivots are safe); on this project's meshes minimum degree fills ~30 % less
    than COLAMD and factors 1.3-1.5x faster (``docs/benchmarks.md``).

    Parameters
    ----------
    A : sparse matrix (n, n)
        Symmetric positive definite.
    coordinates : array (2, n), optional
        Positions of the unknowns (the dofs' coordinates, any unit). Given, and
        from :data:`~bearingfe.core.ordering.NESTED_DISSECTION_FROM` unknowns on,
        the order is :func:`~bearingfe.core.ordering.nested_dissection` by them,
        which fills less there (docs/benchmarks.md, part ``orderings``). Without
        coordinates minimum degree is kept: nested dissection from the graph
        alone fills less from ~1e5 P1 unknowns too, but finding it costs more
        than it saves in one factorization (measured up to 3e5 unknowns).
    """
    A = sp.csc_matrix(A)
    if coordinates is None or A.shape[0] < NESTED_DISSECTION_FROM:
        lu = spla.splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        return lu.solve
    return _splu_in_order(A, nested_dissection(A, coordinates))


def _splu_in_order(A: sp.csc_matrix, order: np.ndarray) -> Solve:
    """SuperLU (symmetric mode, no pivoting) of ``A[order][:, order]`` in that order, solving for ``A``."""
    lu = spla.splu(A[order][:, order].tocsc(), permc_spec="NATURAL", diag_pivot_thresh=0.0,
                   options={"SymmetricMode": True})
    inverse = np.argsort(order)

    def solve(b: np.ndarray) -> np.ndarray:
        return lu.solve(np.asarray(b, dtype=float)[order])[inverse]

    return solve


def factorize_splu_small(A: sp.spmatrix) -> Solve:
    """:func:`factorize_splu_sym` with panels of one column and no supernode relaxation.

    For matrices up to :data:`SMALL_PANELS_UP_TO` rows (the cavitation models'
    active-set and coarse-grid systems): SuperLU's dense kernels then stay out of
    threaded BLAS, whose threads wait for each other on a busy machine (a 300-row
    matrix took 2.8 ms with the default panels, 0.2 ms with these); the compiled
    path of :mod:`bearingfe.film.compiled` factors its small systems the same way.
    """
    lu = spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                   options={"SymmetricMode": True}, panel_size=1, relax=1)
    return lu.solve


#: Rows up to which :func:`factorize_splu_small` is used in place of the default.
SMALL_PANELS_UP_TO = 20000


def factorize_cholmod(A: sp.spmatrix) -> Solve:
    """Sparse Cholesky by CHOLMOD (optional ``scikit-sparse<0.5``, needs SuiteSparse)."""
    cholmod = _optional("sksparse.cholmod", "scikit-sparse<0.5")
    factor = cholmod.cholesky(sp.csc_matrix(A))
    return lambda b: factor(np.asarray(b, dtype=float))


def _pardiso_solver(A: sp.spmatrix):
    pypardiso = _optional("pypardiso", "pypardiso")
    solver = pypardiso.PyPardisoSolver(mtype=2)  # real symmetric positive definite
    upper = sp.triu(sp.csr_matrix(A), format="csr")
    upper.sort_indices()
    return solver, upper


def _pardiso_call(solver, upper: sp.csr_matrix, phase: int, b: np.ndarray) -> np.ndarray:
    solver.set_phase(phase)
    return solver._call_pardiso(upper, np.asfortranarray(b))  # documented escape hatch of pypardiso


def factorize_pardiso(A: sp.spmatrix) -> Solve:
    """MKL PARDISO in SPD mode (optional ``pypardiso``; upper triangle passed)."""
    solver, upper = _pardiso_solver(A)
    _pardiso_call(solver, upper, 12, np.zeros((upper.shape[0], 1)))

    def solve(b: np.ndarray) -> np.ndarray:
        b = np.asarray(b, dtype=float)
        return _pardiso_call(solver, upper, 33, _columns(b)).reshape(b.shape)

    return solve


def factorize_cholespy(A: sp.spmatrix) -> Solve:
    """Sparse Cholesky by cholespy (optional ``cholespy``; CPU, double precision)."""
    cholespy = _optional("cholespy", "cholespy")
    C = sp.csc_matrix(A)
    C.sort_indices()
    factor = cholespy.CholeskySolverD(C.shape[0], C.indptr.astype(np.int32), C.indices.astype(np.int32),
                                      C.data.astype(float), cholespy.MatrixType.CSC)

    def solve(b: np.ndarray) -> np.ndarray:
        b = np.asarray(b, dtype=float)
        rhs = np.ascontiguousarray(_columns(b))
        x = np.zeros_like(rhs)
        factor.solve(rhs, x)
        return x.reshape(b.shape)

    return solve


LINEAR_SOLVERS.update({
    "splu_sym": factorize_splu_sym,
    "cholmod": factorize_cholmod,
    "pardiso": factorize_pardiso,
    "cholespy": factorize_cholespy,
})


def available_solvers() -> tuple[str, ...]:
    """Names in :data:`LINEAR_SOLVERS` whose optional package imports here."""
    needs = {"amg": "pyamg", "cholmod": "sksparse.cholmod", "pardiso": "pypardiso", "cholespy": "cholespy"}
    out = []
    for name in LINEAR_SOLVERS:
        try:
            if name in needs:
                _optional(needs[name], name)
        except ImportError:
            continue
        out.append(name)
    return tuple(out)


# -- factorization reuse for a fixed sparsity pattern --------------------------------

def _pattern_key(A: sp.csc_matrix) -> tuple:
    return (A.shape, A.nnz, hash(A.indptr.tobytes()), hash(A.indices.tobytes()))


class PatternFactorizer:
    """A ``factorize(A) -> solve`` callable that reuses the symbolic analysis
    (ordering and elimination tree) while the sparsity pattern does not change.

    The condensed Reynolds matrix of one mesh and element has a fixed
    pattern; only the values change with the film, so every step of a
    transient can skip the analysis. Pass an instance as ``solver=`` to
    :func:`bearingfe.superpose` and keep it for the whole run (one per mesh).

    Parameters
    ----------
    backend : {"splu_sym", "cholmod", "pardiso"}
        ``cholmod``: ``analyze`` once, numeric ``cholesky`` per call.
        ``pardiso``: phase 11 (analysis) once, phase 22 (numeric) per call.
        ``splu_sym``: SuperLU cannot keep its symbolic factorization between
        calls (scipy exposes no such handle); what can be reused is the
        fill-reducing ordering: the matrix is permuted once-found and factored
        with the natural order, which saves the ordering time only.

    Attributes
    ----------
    analyses : int
        How many symbolic analyses were done (1 while the pattern is fixed).
    """

    BACKENDS = ("splu_sym", "cholmod", "pardiso")

    def __init__(self, backend: str = "splu_sym") -> None:
        if backend not in self.BACKENDS:
            raise ValueError(f"backend must be one of {self.BACKENDS}, got {backend!r}")
        self.backend = backend
        self.analyses = 0
        self._key = None
        self._state = None

    def __call__(self, A: sp.spmatrix) -> Solve:
        A = sp.csc_matrix(A)
        A.sort_indices()
        key = _pattern_key(A)
        if key != self._key:
            self._state = self._analyze(A)
            self._key = key
            self.analyses += 1
        return self._numeric(A)

    def _analyze(self, A: sp.csc_matrix):
        if self.backend == "cholmod":
            return _optional("sksparse.cholmod", "scikit-sparse<0.5").analyze(A)
        if self.backend == "pardiso":
            solver, upper = _pardiso_solver(A)
            _pardiso_call(solver, upper, 11, np.zeros((upper.shape[0], 1)))
            return solver
        lu = spla.splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        return np.argsort(lu.perm_c)

    def _numeric(self, A: sp.csc_matrix) -> Solve:
        if self.backend == "cholmod":
            factor = self._state.cholesky(A)
            return lambda b: factor(np.asarray(b, dtype=float))
        if self.backend == "pardiso":
            solver = self._state
            upper = sp.triu(A.tocsr(), format="csr")
            upper.sort_indices()
            _pardiso_call(solver, upper, 22, np.zeros((upper.shape[0], 1)))

            def solve(b: np.ndarray) -> np.ndarray:
                b = np.asarray(b, dtype=float)
                return _pardiso_call(solver, upper, 33, _columns(b)).reshape(b.shape)

            return solve
        order = self._state
        lu = spla.splu(A[order][:, order].tocsc(), permc_spec="NATURAL", diag_pivot_thresh=0.0,
                       options={"SymmetricMode": True})
        inverse = np.argsort(order)

        def solve(b: np.ndarray) -> np.ndarray:
            b = np.asarray(b, dtype=float)
            return lu.solve(b[order])[inverse]

        return solve


# -- dense linear algebra on a shared machine ------------------------------------------

_THREADPOOLS: list = []


def dense_threads(limit: int = 1):
    """Context that caps the BLAS/LAPACK threads (OpenBLAS, MKL) at ``limit`` while it is open.

    The dense matrices of the elastic support (a few hundred to a few
    thousand rows: the compliance, the Jacobians of the coupled film) are too
    small for threaded BLAS to pay: on a machine whose cores are busy, its
    threads wait for each other, and one revolution of the pump on the elastic
    support took ten times longer with two threads than with one
    (``docs/elastic.md``). Uses ``threadpoolctl``; the thread counts are
    restored on exit. Opened inside another such context of this thread with
    the same ``limit``, it changes nothing and costs nothing
    (threadpoolctl's own cap and restore cost about 12 us CPU each time: the
    banded solves of one JFO solve open it a dozen times inside the solve's
    own).
    """
    if not (isinstance(limit, int) and limit >= 1):
        raise ValueError(f"limit must be an integer >= 1 (threads), got {limit!r}")
    if not _THREADPOOLS:
        from threadpoolctl import ThreadpoolController

        _THREADPOOLS.append(ThreadpoolController())
    caps = _open_caps()
    if caps and caps[-1] == limit:
        return contextlib.nullcontext()
    return _Capped(_THREADPOOLS[0].limit(limits=limit, user_api="blas"), limit)


_OPEN = threading.local()


def _open_caps() -> list[int]:
    """The caps of this thread's :func:`dense_threads` contexts open now, innermost last."""
    caps = getattr(_OPEN, "caps", None)
    if caps is None:
        caps = _OPEN.caps = []
    return caps


class _Capped:
    """A threadpoolctl limit (applied when made, as threadpoolctl's) that, while open as a context, is counted
    among this thread's open caps (:func:`_open_caps`)."""

    def __init__(self, limiter, cap: int):
        self.limiter, self.cap = limiter, cap

    def __enter__(self):
        _open_caps().append(self.cap)
        return self.limiter.__enter__()

    def __exit__(self, *exc):
        _open_caps().pop()
        return self.limiter.__exit__(*exc)
