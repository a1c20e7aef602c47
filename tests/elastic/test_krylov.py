"""The one GMRES of the matrix-free elastic solves (bearingfe.elastic.krylov)."""

import numpy as np
import pytest
import scipy.sparse as sp

from bearingfe.elastic import ElasticError
from bearingfe.elastic.krylov import gmres


def _laplacian(n: int) -> sp.csr_matrix:
    return sp.diags([-np.ones(n - 1), 2.0 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1], format="csr")


def test_solves_to_its_relative_tolerance():
    # Reference: the direct solve of the same tridiagonal system.
    A = _laplacian(80)
    b = np.linspace(1.0, 2.0, 80)
    x, iterations = gmres(A.dot, b, rtol=1e-10, what="test", max_iterations=2000,
                          preconditioner=lambda v: v / 2.0)
    exact = np.linalg.solve(A.toarray(), b)
    assert np.abs(x - exact).max() <= 1e-7 * np.abs(exact).max()
    assert 1 <= iterations <= 2000


def test_short_budget_raises_naming_the_solve():
    # 400 unknowns of a 1-D Laplacian (condition number ~6.5e4) need far more than one unpreconditioned
    # restart cycle (60 iterations) for 1e-12.
    A = _laplacian(400)
    with pytest.raises(ElasticError, match="the test solve: GMRES did not reach the relative residual 1e-12 in 60"):
        gmres(A.dot, np.ones(400), rtol=1e-12, what="the test solve", max_iterations=60)


def test_inexact_step_returns_the_last_iterate():
    # must_converge=False (an inexact Newton step): the iterate after one restart cycle, short of 1e-12 (as
    # above) but better than the zero start.
    A = _laplacian(400)
    b = np.ones(400)
    x, iterations = gmres(A.dot, b, rtol=1e-12, what="test", max_iterations=60, must_converge=False)
    assert iterations == 60
    assert 1e-12 < np.linalg.norm(A @ x - b) / np.linalg.norm(b) < 0.9


def test_breakdown_on_non_finite_products_is_reported():
    with pytest.raises(ElasticError, match="test: GMRES broke down"):
        gmres(lambda v: np.full_like(v, np.nan), np.ones(10), rtol=1e-8, what="test", max_iterations=100)
