"""Banded Cholesky of sparse symmetric positive definite matrices, and the rule for when a band pays.

A matrix is put in band storage in an elimination order (the reverse Cuthill-McKee order of its pattern,
or one the caller gives) and factored by LAPACK (``dpbtrf``, lower storage; solves by ``dpbtrs``). Two
steps, so that a caller that factors many matrices of one pattern finds the storage positions once:
:func:`band_plan` / :func:`band_plan_in_order` (the pattern: order, half-bandwidth, positions) and
:func:`band_cholesky` (the values: factorization and solve).

Whether a band is taken over SuperLU is decided by one rule, :func:`band_pays`, from the limits of
:data:`BAND_LIMITS` for the kind of matrix the caller factors:

``kept_pattern``
    A matrix whose pattern is factored again and again (a film's condensed ``A[I, I]``): SuperLU's
    alternative there is a numeric factorization in a fill-reducing order found once per pattern.
``new_pattern``
    A matrix factored once (the free block of one active set of an obstacle problem): SuperLU's
    alternative there builds the block's matrix and analyses it anew each time, so a band pays up to a
    wider bandwidth; in turn the band's own work ``n kd^2`` is capped, and larger blocks are not tried.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.sparse as sp
from scipy.linalg.lapack import dpbtrf, dpbtrs
from scipy.sparse.csgraph import reverse_cuthill_mckee

__all__ = ["BandLimits", "BAND_LIMITS", "band_limits", "band_pays", "band_worth_trying", "half_bandwidth", "BandPlan",
           "band_plan",
           "band_plan_in_order", "band_cholesky"]


@dataclass(frozen=True)
class BandLimits:
    """When banded Cholesky is taken over SuperLU for one kind of matrix.

    Attributes
    ----------
    kd_max : int
        Widest half-bandwidth (in the elimination order) factored banded.
    work_max : float
        Largest ``n kd^2`` (the band factorization's work, in multiply-adds up to a constant) factored banded.
    size_max : float
        Largest number of unknowns ``n`` for which a band is tried at all (a larger matrix is not even ordered).
    """

    kd_max: int
    work_max: float = math.inf
    size_max: float = math.inf


#: The limits of :func:`band_pays` per kind of matrix (read at each call, so tests may replace an entry).
#:
#: ``kept_pattern`` (a film's ``A[I, I]``, factored once per film state of a mesh): up to a half-bandwidth of 31
#: LAPACK runs its unblocked column algorithm (rank-one updates of unit-stride vectors, no threads); from 32 it
#: goes blocked with 32-wide blocks, whose BLAS-3 kernels are then too small to be threaded. Measured on the
#: pump's P2 shoe mesh of 0.2 R0 (214 unknowns, half-bandwidth 31): factorization and four solves 2x faster
#: than SuperLU's, one pump revolution 20-25 % faster; the main scene's pocket mesh has 34 (SuperLU 98 us a
#: factorization, banded 30 us). ``dpbtrf`` at 300 unknowns on a loaded machine (load 4, 2,000 factorizations
#: each): half-bandwidth 34 68 us median, 36 71 us, 40 82-84 us, with occasional scheduler stalls of 2-4 ms at
#: every width. Up to 64 the banded factorization and a four-column solve cost no more than SuperLU's numeric
#: factorization in the kept order and its solve (CPU, best of 100, P1 and P2 gmsh meshes of 288-3,570
#: unknowns; e.g. P2, 456 unknowns, half-bandwidth 47: 0.11 + 0.08 against 0.19 + 0.04 ms; P2, 779, 65: 0.43 +
#: 0.11 against 0.48 + 0.08 ms; P1, 3,570, 62: 1.3 + 0.7 against 4.0 + 0.4 ms), and a fresh mesh's first film
#: needs no factorization to find SuperLU's order (minimum degree, 1.5-2x the numeric one). From about 66
#: SuperLU is as fast or faster on repeated films (P2, 592 unknowns, 66: 0.32 + 0.09 against 0.27 + 0.05 ms)
#: and keeps them. No work or size cap: a pattern within the bandwidth is planned once per mesh.
#:
#: ``new_pattern`` (the free block of one obstacle-problem active set, factored once): against SuperLU,
#: ordering and extraction included, 0.21 ms against 0.68 ms at 509 unknowns, 0.66 against 2.1 ms at 1,572
#: (the solves cost the same). P2 free sets of 500 unknowns have a half-bandwidth of 42, of 1,600 have 68:
#: at 1e3 P2 unknowns (load 5) the Swift-Stieber solve took 15.7 ms with a limit of 40 (SuperLU took the
#: kd = 42 sets), 10.5 ms with 80. The work cap was first that of 5,000 unknowns with a half-bandwidth of 40
#: (8e6; raised below); blocks of more than 5,000 unknowns are not tried (a 2-D set that large has a wider
#: band). Measured again on the journal's free sets (360-degree bearing, L/D 1/2, P1 and P2; CPU, median of
#: 100, factorization and one solve): 1,973 unknowns, kd 38, 0.53 ms banded against 2.8 ms for SuperLU in
#: minimum degree; P2 sets of 1,990 unknowns with kd 74 (work 1.1e7, then refused by the work cap of 8e6) 1.56
#: against 2.8 ms. Raised to a half-bandwidth of 128 and a work of 2e7 from the journals' P2 free sets (part
#: ``journal_pads``'s two-groove pads and the full bearings, L/D 1/2 and 1, size 0.3, rupture_size 0.05; CPU,
#: median of 30, factorization and one solve, one BLAS thread as its callers run it): 1,012-1,257 unknowns
#: with kd 101-117 (work 1.1-1.4e7) 1.3-1.6 ms banded against 2.0-2.4 ms for SuperLU; 1,724-1,960 unknowns
#: with kd 173-189 (work 5.7-6.4e7) 4.2-4.7 against 3.7-4.4 ms, where SuperLU wins.
#:
#: ``full_film_guess`` (the mass-conserving solver's full-film system, the Poiseuille operator alone, factored
#: once per cold solve for its first cavity; Cholesky): measured (CPU time, 20 solves, the 5 x 5 dimple slider
#: on ``grid_mesh``) 2,401 unknowns, half-bandwidth 49: 1.2 against 3.5 ms for SuperLU in the active set's
#: order; 4,761 unknowns, 69: 2.4 against 6.9 ms. Not tried above ``96**2`` unknowns (a square grid's band is
#: then wider; larger systems start from a coarse level).
#:
#: ``active_set_lu`` (the mass-conserving solver's active-set matrices, nonsymmetric: banded LU with partial
#: pivoting, LAPACK ``dgbtrf``, in the reverse Cuthill-McKee order of ``|K| + |G|``; the rule is the same, the
#: factorization is :mod:`bearingfe.film.finite_volume`'s): measured (CPU time, 20 factorizations and a solve
#: of an active-set matrix of the 5 x 5 dimple slider on ``grid_mesh``) 2,401 unknowns, half-bandwidth 52:
#: 1.65 against 2.4 ms in the nested-dissection order; 3,481 unknowns, 92: 4.6-6.0 against 3.4 ms; whole
#: solves at 70 cells per side were slower with 72 than with 64 (the banded Woodbury solves cost more).
#: Not tried above ``64**2`` unknowns.
#:
#: ``front_band_lu`` (the same banded LU for the band subproblems around the cavity's fronts of the
#: mass-conserving solver's two-grid start: thin but long, 5e3-6e4 unknowns): in-process CPU A/B on the 5 x 5
#: dimple slider (median of 5 fresh meshes each): a whole cold solve 0.96x as costly with the band at 100 and
#: 200 cells per side (band work ``n kd^2`` 4.7e6 and 2.7e6), 1.02x at 280 (6.5e7), 0.99x at 400 (6.3e7) and
#: 1.03-1.05x at 600 (61,299 unknowns, half-bandwidth 38, 8.9e7): SuperLU in the nested-dissection order wins
#: on the long bands, so the work is capped between the two groups.
BAND_LIMITS: dict[str, BandLimits] = {
    "kept_pattern": BandLimits(kd_max=64),
    "new_pattern": BandLimits(kd_max=128, work_max=2e7, size_max=5000),
    "full_film_guess": BandLimits(kd_max=96, size_max=96**2),
    "active_set_lu": BandLimits(kd_max=64, size_max=64**2),
    "front_band_lu": BandLimits(kd_max=64, work_max=2e7),
}


def band_limits(kind: str) -> BandLimits:
    """The limits of :data:`BAND_LIMITS` for ``kind`` (one of its keys)."""
    try:
        return BAND_LIMITS[kind]
    except KeyError:
        raise ValueError(f"kind must be one of {sorted(BAND_LIMITS)}, got {kind!r}") from None


def band_worth_trying(n: int, kind: str) -> bool:
    """Whether an ``n``-unknown matrix of ``kind`` is small enough to order and test for a band."""
    return 0 < n <= band_limits(kind).size_max


def band_pays(n: int, kd: int, kind: str, kd_max: int | None = None) -> bool:
    """Whether banded Cholesky is taken over SuperLU for an ``n``-unknown matrix of ``kind`` whose
    half-bandwidth in the elimination order is ``kd``. ``kd_max``: a caller's own widest half-bandwidth
    instead of the kind's (its work and size limits still hold)."""
    limits = band_limits(kind)
    kd_max = limits.kd_max if kd_max is None else kd_max
    return kd <= kd_max and n * kd**2 <= limits.work_max and n <= limits.size_max


def half_bandwidth(pattern: sp.csr_matrix, perm: np.ndarray) -> int:
    """Half-bandwidth of the CSR ``pattern`` (square) in the elimination order ``perm`` (band position ->
    unknown): the largest ``|position(i) - position(j)|`` over its entries."""
    perm = np.asarray(perm, np.int64)
    inverse = np.empty_like(perm)
    inverse[perm] = np.arange(perm.size)
    rows = np.repeat(np.arange(pattern.shape[0]), np.diff(pattern.indptr))
    return int(np.abs(inverse[rows] - inverse[pattern.indices]).max(initial=0))


@dataclass(frozen=True, eq=False)
class BandPlan:
    """Where the values of a symmetric matrix go in LAPACK's lower band storage, in an elimination order.

    Attributes
    ----------
    perm : numpy.ndarray
        Band position -> unknown (the elimination order).
    inverse : numpy.ndarray
        Unknown -> band position.
    kd : int
        Half-bandwidth in that order.
    flat : numpy.ndarray
        Column-major positions in the ``(kd + 1, n)`` band array.
    take : numpy.ndarray
        Where the values that fill them are in the data passed to :func:`band_cholesky`.
    n : int
        Unknowns.
    """

    perm: np.ndarray
    inverse: np.ndarray
    kd: int
    flat: np.ndarray
    take: np.ndarray
    n: int


def band_plan_in_order(rows: np.ndarray, cols: np.ndarray, n: int, perm: np.ndarray, kind: str = "kept_pattern",
                       kd_max: int | None = None, values_at: np.ndarray | None = None) -> BandPlan | None:
    """Band storage of a symmetric ``n x n`` matrix with entries at ``(rows, cols)`` (both triangles) in the
    elimination order ``perm`` (band position -> unknown); None if :func:`band_pays` refuses the band
    (``kind``, ``kd_max``) or ``n`` is 0. ``values_at``: where the ``k``-th entry's value is in the data
    later passed to :func:`band_cholesky` (default ``k``)."""
    if n == 0:
        return None
    perm = np.asarray(perm, np.int64)
    if perm.shape != (n,):
        raise ValueError(f"perm must be an order of the {n} unknowns, got shape {perm.shape}")
    inverse = np.empty_like(perm)
    inverse[perm] = np.arange(n)
    i, j = inverse[rows], inverse[cols]          # positions in the band order
    offset = i - j
    kd = int(np.abs(offset).max(initial=0))
    if not band_pays(n, kd, kind, kd_max):
        return None
    lower = np.flatnonzero(offset >= 0)
    # LAPACK lower band storage, column-major: AB[i - j, j] = A[i, j]
    flat = offset[lower] + j[lower] * (kd + 1)
    take = lower if values_at is None else np.asarray(values_at)[lower]
    return BandPlan(perm=perm, inverse=inverse, kd=kd, flat=flat, take=take, n=n)


def band_plan(sel: np.ndarray, idx: np.ndarray, ptr: np.ndarray, n: int, kd_max: int | None = None,
              kind: str = "kept_pattern") -> BandPlan | None:
    """Band storage, in the reverse Cuthill-McKee order, of a symmetric ``n x n`` matrix given by its CSR
    pattern ``(idx, ptr)`` whose ``k``-th stored entry is ``data[sel[k]]`` of the values later passed to
    :func:`band_cholesky`; None if :func:`band_pays` refuses the band (``kind``; ``kd_max`` instead of the
    kind's widest half-bandwidth) or ``n`` is 0."""
    if n == 0:
        return None
    pattern = sp.csr_matrix((np.ones(idx.size), idx, ptr), shape=(n, n))
    perm = reverse_cuthill_mckee(pattern, symmetric_mode=True)
    rows = np.repeat(np.arange(n), np.diff(ptr))
    return band_plan_in_order(rows, idx, n, perm, kind, kd_max, values_at=sel)


def band_cholesky(plan: BandPlan, data: np.ndarray) -> Callable[[np.ndarray], np.ndarray] | None:
    """Banded Cholesky of the matrix of ``plan`` from its values ``data``; None if it is not positive definite
    in floating point. Returns ``solve(b)``: the solution for a vector or the columns of a matrix ``b``."""
    ab = np.zeros((plan.kd + 1, plan.n), order="F")
    ab.ravel(order="F")[plan.flat] = data[plan.take]
    factor, info = dpbtrf(ab, lower=1, overwrite_ab=1)
    if info != 0:
        return None
    perm, inverse, n = plan.perm, plan.inverse, plan.n

    def solve(b: np.ndarray) -> np.ndarray:
        b = np.asarray(b, dtype=float)
        x, _ = dpbtrs(factor, b[perm].reshape(n, -1), lower=1)
        return x[inverse].reshape(b.shape)

    return solve
