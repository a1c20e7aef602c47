r"""A cold start for the obstacle problem from Galerkin problems on coarse grids (nested iteration).

From the default start (where the unconstrained solution is negative) the
primal-dual active-set method moves the free boundary by about one layer of
dofs per iteration: the multiplier of a ruptured dof not next to the full film
is ``-b >= 0`` whatever the solution is, so only the first layer can be
released. The count grows like ``1 / element size`` (measured 7, 11, 18, 29,
52 iterations at 1e3 .. 1e5 unknowns), each with a new factorization.

Nested iteration bounds it: solve the problem on a coarse space, carry its
rupture set up one level, correct it there in a few iterations, and so on up
to the given system. The coarse spaces here need no coarse mesh: they are the
bilinear functions of uniform grids laid over the dof coordinates (spacing
``2^k`` times the mean dof spacing, k from :data:`FIRST_LEVEL` up to about :data:`COARSEST` nodes),
interpolated to the dofs. Their problems are the Galerkin restrictions of the
given one, ``(P^T A P) u_c - P^T b = lam_c, u_c >= 0``: the interpolation has
no negative weight, so ``u_c >= 0`` makes ``P u_c >= 0``, and each coarse
solution is the obstacle problem on a subspace. A dof starts ruptured on the
next level where the interpolated signed field ``u - lam / diag`` of the coarse
solution is negative (within a fine spacing of the coarse free boundary), the
free set grown by a ring of neighbours where the next level's sets go by
conjugate gradients (:func:`_carried`); the start from a coarser mesh
(:func:`bearingfe.cavitation.swift_stieber.warm_mask`) ruptures a dof only
where every old element around it is ruptured. Nothing here knows about films:
it takes the matrix, the right side and the dof coordinates.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp

from .obstacle import DIRECT_UP_TO, CavitationError, ObstacleProblem
from ..core.linalg import SMALL_PANELS_UP_TO, Factorize, factorize_splu_small

__all__ = ["COARSEST", "CoarseChain", "NESTED_MIN", "grid_interpolation", "nested_start"]

#: Nodes of the coarsest grid (about): its cold solve is the cheap start of the chain.
COARSEST = 600
#: The finest coarse grid has ``2**FIRST_LEVEL`` times the mean dof spacing.
FIRST_LEVEL = 2  # measured: 12-15 % cheaper than 1 at 3e3 .. 3e4 unknowns (one coarse level less, one fine step more)
#: Below this many unknowns the cold start is used as is: there the coarse grids' setup (a dozen small sparse
#: products and factorizations, about 2 ms at 1e3 unknowns) costs more than the two or three active-set steps
#: it saves, each one banded factorization of a few hundred unknowns (measured at 1e3 unknowns, P1 and P2:
#: 20-25 % less time from the cold start with a factorization per set).
NESTED_MIN = 2000


def grid_interpolation(points: np.ndarray, origin: np.ndarray, spacing: np.ndarray,
                       shape: tuple[int, int]) -> sp.csr_matrix:
    """Bilinear interpolation from the nodes of a uniform grid to ``points``.

    Parameters
    ----------
    points : ndarray, shape (n, 2)
        Where to interpolate, inside the grid's box.
    origin, spacing : ndarray, shape (2,)
        Lower-left node and node spacing of the grid.
    shape : (int, int)
        Nodes along each axis; node ``(i, j)`` is column ``i * shape[1] + j``.

    Returns
    -------
    scipy.sparse.csr_matrix, shape (n, shape[0] * shape[1])
        Non-negative weights summing to one in each row.
    """
    s = (np.asarray(points, float) - origin) / spacing
    cell = np.floor(s).astype(np.int64)
    cell[:, 0] = np.clip(cell[:, 0], 0, shape[0] - 2)
    cell[:, 1] = np.clip(cell[:, 1], 0, shape[1] - 2)
    t = np.clip(s - cell, 0.0, 1.0)
    rows = np.repeat(np.arange(len(s)), 4)
    cols, vals = [], []
    for di, dj in ((0, 0), (1, 0), (0, 1), (1, 1)):
        cols.append((cell[:, 0] + di) * shape[1] + cell[:, 1] + dj)
        vals.append((t[:, 0] if di else 1 - t[:, 0]) * (t[:, 1] if dj else 1 - t[:, 1]))
    P = sp.csr_matrix((np.column_stack(vals).ravel(), (rows, np.column_stack(cols).ravel())),
                      shape=(len(s), shape[0] * shape[1]))
    P.eliminate_zeros()
    return P


def _levels(points: np.ndarray) -> list[tuple[np.ndarray, np.ndarray, tuple[int, int]]]:
    """Grids from the finest coarse one (``2**FIRST_LEVEL`` times the mean dof spacing) to about :data:`COARSEST` nodes."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    extent = np.maximum(hi - lo, 1e-12 * max(float((hi - lo).max()), 1.0))
    spacing = math.sqrt(float(extent[0] * extent[1]) / len(points))  # mean dof spacing
    grids = []
    for k in range(FIRST_LEVEL, 40):
        H = spacing * 2.0**k
        shape = tuple(int(max(2, math.ceil(e / H) + 1)) for e in extent)
        grids.append((lo, extent / (np.array(shape) - 1), shape))
        if shape[0] * shape[1] <= COARSEST:
            break
    return grids


class CoarseChain:
    """The coarse grids and interpolations of :func:`nested_start` for one set of dof coordinates.

    They depend on the coordinates only, so every film state of a mesh can share them (made once: about a
    third of the nested start's time at 3e3 unknowns). :meth:`start` takes the matrix and the right side.

    Parameters
    ----------
    points : ndarray, shape (n, 2)
        Coordinates of the unknowns.
    """

    def __init__(self, points: np.ndarray) -> None:
        points = np.asarray(points, float)
        self.n = len(points)
        self.grids = _levels(points)
        # the chain of interpolations: dofs <- grid 1 <- grid 2 <- ...
        self.transfers, self.nodes = [], []
        P = grid_interpolation(points, *self.grids[0])
        for k in range(len(self.grids)):
            if k:
                lo, h, shape = self.grids[k - 1]
                fine_nodes = self.nodes[-1]
                xy = lo + h * np.column_stack([fine_nodes // shape[1], fine_nodes % shape[1]])
                P = grid_interpolation(xy, *self.grids[k])
            keep = np.flatnonzero(np.asarray(P.getnnz(axis=0)) > 0)
            self.transfers.append(P[:, keep].tocsr())
            self.nodes.append(keep)
        self.restrictions = [P.T.tocsr() for P in self.transfers]

    def start(self, A: sp.spmatrix, b: np.ndarray, factorize: Factorize, *, tol: float,
              max_iterations: int) -> tuple[np.ndarray, dict]:
        """:func:`nested_start` on these grids (``A`` and ``b`` of the :attr:`n` unknowns)."""
        if A.shape != (self.n, self.n):
            raise ValueError(f"A must be {self.n} x {self.n} (the chain's unknowns), got {A.shape}")
        matrices, rhs = [], []
        M, r = sp.csr_matrix(A), np.asarray(b, float)
        for P, R in zip(self.transfers, self.restrictions):  # coarse matrices by Galerkin products
            M, r = (R @ M @ P).tocsr(), R @ r
            matrices.append(M)
            rhs.append(r)
        active = None
        iterations = 0
        for k in range(len(self.grids) - 1, -1, -1):
            # a coarse node that reads only a few dofs (strongly graded meshes) can make the columns of the
            # interpolation dependent: a relative 1e-10 on the diagonal keeps the coarse matrix definite
            M = matrices[k] + sp.diags(1e-10 * matrices[k].diagonal())
            problem = ObstacleProblem(M, factorize_splu_small if M.shape[0] <= SMALL_PANELS_UP_TO else factorize,
                                      tol=tol, max_iterations=min(max_iterations, 25))
            sol = problem.solve(rhs[k], active)
            iterations += sol.iterations
            active = _carried(self.transfers[k], sol, M.diagonal(), matrices[k - 1] if k else A, finest=k == 0)
        info = {"levels": len(self.grids), "coarse_iterations": iterations,
                "coarse_nodes": int(self.nodes[0].size)}
        return active, info


def _carried(P: sp.csr_matrix, sol, diagonal: np.ndarray, fine: sp.spmatrix, finest: bool) -> np.ndarray:
    """The rupture set of a coarse solution carried to the next level's unknowns (interpolation ``P``, matrix
    ``fine``; ``finest``: that level is the given system).

    Ruptured where the interpolated signed coarse field ``u - lam / diag`` is negative (full film positive,
    rupture negative), which puts the free boundary within a fine spacing of the coarse one, and the free set
    grown by one ring of ``fine``'s neighbours, which puts it a layer outside (measured against the set
    ruptured only where every coarse node the interpolation reads is ruptured, the same answers; on the
    journal at 3e3 unknowns, where the free sets are factored: 4 -> 2 active-set steps P1, 5 -> 4 P2; at 1e4
    and 3e4, where they go by CG preconditioned with the first set's factorization, which then holds most
    later sets: CG steps in all 14 against 35 at 1e4 P2 unknowns, 19 against 41 P1, 25 against 33 at 3e4 P2,
    22 against 44 P1, with no more active-set steps; the signed set alone, a layer too small, took 64
    against 42 at 1e4 P2). On the coarse levels whose sets are factored (a start of at most
    :data:`~bearingfe.cavitation.obstacle.DIRECT_UP_TO` free unknowns) the signed set is kept as it is: the
    ring cost them a step more at 1e4 and 3e4 unknowns.
    """
    active = (P @ (sol.u - sol.multiplier / diagonal)) < 0.0
    if not finest and P.shape[0] - np.count_nonzero(active) <= DIRECT_UP_TO:
        return active
    fine = sp.csr_matrix(fine)
    pattern = sp.csr_matrix((np.ones(fine.indices.size), fine.indices, fine.indptr), shape=fine.shape)
    return (pattern @ (~active).astype(float)) == 0.0


def nested_start(A: sp.spmatrix, b: np.ndarray, points: np.ndarray, factorize: Factorize, *,
                 tol: float, max_iterations: int, chain: CoarseChain | None = None) -> tuple[np.ndarray, dict]:
    """Rupture set to start the active-set iteration on ``A`` from, by nested iteration on coarse grids.

    Parameters
    ----------
    A : sparse matrix, shape (n, n)
        The system (symmetric positive definite).
    b : ndarray, shape (n,)
    points : ndarray, shape (n, 2)
        Coordinates of the unknowns.
    factorize : callable
        Sparse solver of the coarse systems.
    tol, max_iterations : float, int
        As in :class:`ObstacleProblem` (per level).
    chain : CoarseChain, optional
        The grids of ``points`` made before (:class:`CoarseChain`); default: made here.

    Returns
    -------
    active : ndarray of bool, shape (n,)
        Where the finest coarse solution is zero around the unknown.
    info : dict
        ``levels`` (coarse grids used), ``coarse_iterations`` (their
        active-set iterations in total) and ``coarse_nodes``.

    Raises
    ------
    CavitationError
        If a coarse problem does not converge (the caller then starts cold).
    """
    chain = CoarseChain(points) if chain is None else chain
    return chain.start(A, b, factorize, tol=tol, max_iterations=max_iterations)
