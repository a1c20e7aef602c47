"""Banded Cholesky and the one rule for when a band pays (bearingfe.core.banded).

Expected values: solutions against scipy's sparse direct solve (round-off, 1e-12 of the largest on these
well-conditioned matrices); bit for bit against scipy's ``cholesky_banded`` / ``cho_solve_banded`` (the same
LAPACK routines, ``pbtrf`` / ``pbtrs``, on the same band in the same order: the obstacle problem's path before
it used this module); the rule's answers from the limits of :data:`BAND_LIMITS` written out.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.sparse.csgraph import reverse_cuthill_mckee

from bearingfe.core import banded


def _laplacian(m: int, shift: float = 0.0) -> sp.csr_matrix:
    # the 5-point Laplacian on an m x m grid (SPD); its reverse Cuthill-McKee half-bandwidth is about m
    one = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(m, m))
    return (sp.kron(one, sp.eye(m)) + sp.kron(sp.eye(m), one) + shift * sp.eye(m * m)).tocsr()


def _scipy_banded(A: sp.csr_matrix, perm: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``A^-1 b`` by scipy's banded Cholesky in the order ``perm`` (the reference path)."""
    P = A[perm][:, perm].tocoo()
    kd = int(np.abs(P.row - P.col).max())
    lower = P.row >= P.col
    band = np.zeros((kd + 1, A.shape[0]))
    band[(P.row - P.col)[lower], P.col[lower]] = P.data[lower]
    factor = sla.cholesky_banded(band, lower=True, check_finite=False)
    inverse = np.argsort(perm)
    return sla.cho_solve_banded((factor, True), b[perm], check_finite=False)[inverse]


def test_csr_plan_solves_vectors_and_columns_as_scipy_does():
    A = _laplacian(12, shift=0.1)
    rng = np.random.default_rng(3)
    b, B = rng.standard_normal(A.shape[0]), rng.standard_normal((A.shape[0], 3))
    # the data are A's values read through a selection (as the film's pattern values are)
    data = np.concatenate([[7.0], A.data])
    plan = banded.band_plan(np.arange(A.nnz) + 1, A.indices, A.indptr, A.shape[0])
    assert plan is not None and plan.kd <= 13
    solve = banded.band_cholesky(plan, data)
    scale = np.abs(spla.spsolve(A.tocsc(), b)).max()
    np.testing.assert_allclose(solve(b), spla.spsolve(A.tocsc(), b), rtol=0, atol=1e-12 * scale)
    assert solve(B).shape == B.shape
    perm = reverse_cuthill_mckee(A, symmetric_mode=True)
    np.testing.assert_array_equal(solve(b), _scipy_banded(A, perm, b))
    for k in range(3):
        np.testing.assert_array_equal(solve(B)[:, k], _scipy_banded(A, perm, B[:, k]))


def test_plan_in_a_given_order_and_refusals():
    A = _laplacian(10, shift=0.05)
    C = A.tocoo()
    rng = np.random.default_rng(5)
    b = rng.standard_normal(A.shape[0])
    perm = rng.permutation(A.shape[0])  # a poor order (a wide band), with a widest half-bandwidth of its own
    plan = banded.band_plan_in_order(C.row, C.col, A.shape[0], perm, kd_max=10**6)
    assert plan is not None and plan.kd > 10
    np.testing.assert_array_equal(banded.band_cholesky(plan, C.data)(b), _scipy_banded(A, perm, b))
    # refused: a band wider than the caller's widest, an indefinite matrix, no unknowns, a wrong order
    assert banded.band_plan_in_order(C.row, C.col, A.shape[0], perm, kd_max=plan.kd - 1) is None
    assert banded.band_cholesky(plan, -C.data) is None
    assert banded.band_plan_in_order(C.row, C.col, 0, np.arange(0)) is None
    with pytest.raises(ValueError, match="perm must be an order"):
        banded.band_plan_in_order(C.row, C.col, A.shape[0], perm[:-1])


def test_one_rule_takes_the_matrix_kind():
    kept, new = banded.band_limits("kept_pattern"), banded.band_limits("new_pattern")
    assert (kept.kd_max, kept.work_max, kept.size_max) == (64, np.inf, np.inf)
    assert (new.kd_max, new.work_max, new.size_max) == (128, 2e7, 5000)
    assert banded.band_pays(10**5, 64, "kept_pattern") and not banded.band_pays(100, 65, "kept_pattern")
    assert banded.band_pays(1220, 128, "new_pattern") and not banded.band_pays(100, 129, "new_pattern")
    assert banded.band_pays(5000, 63, "new_pattern") and not banded.band_pays(5000, 64, "new_pattern")  # work
    assert banded.band_pays(100, 96, "kept_pattern", kd_max=96)  # a caller's own widest half-bandwidth
    assert banded.band_worth_trying(5000, "new_pattern") and not banded.band_worth_trying(5001, "new_pattern")
    assert not banded.band_worth_trying(0, "kept_pattern")
    with pytest.raises(ValueError, match="kind must be one of"):
        banded.band_pays(10, 1, "film")


def test_limits_are_read_at_the_call(monkeypatch):
    A = _laplacian(8)
    plan = banded.band_plan(np.arange(A.nnz), A.indices, A.indptr, A.shape[0])
    assert plan is not None
    monkeypatch.setitem(banded.BAND_LIMITS, "kept_pattern", banded.BandLimits(kd_max=plan.kd - 1))
    assert banded.band_plan(np.arange(A.nnz), A.indices, A.indptr, A.shape[0]) is None


def test_half_bandwidth_is_the_largest_distance_of_an_entry_from_the_diagonal_in_the_order():
    """half_bandwidth against its definition on a 1-D chain: tridiagonal in the natural order (1); in the order
    that visits every other unknown first, the neighbours 0-1 sit n/2 apart; and the same number as the band
    plan finds for that order."""
    import scipy.sparse as sp

    from bearingfe.core.banded import band_plan_in_order, half_bandwidth

    n = 10
    chain = sp.diags([np.ones(n - 1), 2 * np.ones(n), np.ones(n - 1)], [-1, 0, 1], format="csr")
    assert half_bandwidth(chain, np.arange(n)) == 1
    evens_first = np.concatenate([np.arange(0, n, 2), np.arange(1, n, 2)])
    assert half_bandwidth(chain, evens_first) == n // 2
    coo = chain.tocoo()
    plan = band_plan_in_order(coo.row, coo.col, n, evens_first, kd_max=n)
    assert plan.kd == half_bandwidth(chain, evens_first)
