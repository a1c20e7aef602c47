"""Pluggable sparse solvers and symbolic-factorization reuse.

Every solver that imports here must reproduce scipy's ``spsolve`` on a
condensed Reynolds matrix to near machine precision (it is a direct
solve of an SPD system with condition ~1e3; amg is iterative to 1e-12).
"""

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

import bearingfe as bf
from bearingfe.core.linalg import LINEAR_SOLVERS, PatternFactorizer, available_solvers, get_linear_solver
from bearingfe.film.forms import film_at
from bearingfe.film import operators
from bearingfe.film.reference import system_matrix


@pytest.fixture(scope="module")
def mesh():
    return bf.mesh_surface(bf.Surface(arc=(-0.8, 0.8), half_width=0.5,
                                      inlets=(bf.Circle((0.0, 0.0), 0.15),)), 0.08)


def _condensed(mesh, gamma, formulation="direct", element="P1"):
    ops = operators(mesh, element)
    A = system_matrix(ops, film_at(bf.CosineFilm(gamma, np.pi + 0.2), ops.x), formulation)
    return A[ops.interior][:, ops.interior].tocsc()


def _available_backends():
    have = set(available_solvers())
    return [b for b in PatternFactorizer.BACKENDS if b in have]


@pytest.mark.parametrize("name", available_solvers())
@pytest.mark.parametrize("formulation", ["direct", "pi"])
def test_each_available_solver_matches_spsolve(mesh, name, formulation):
    A = _condensed(mesh, 0.6, formulation)
    b = np.random.default_rng(0).standard_normal((A.shape[0], 4))
    x = get_linear_solver(name)(A)(b)
    ref = spla.spsolve(A, b)
    assert x.shape == b.shape
    # direct solvers: rounding only (1e-9 relative); amg: its 1e-12 residual tolerance times cond ~1e3
    assert np.max(np.abs(x - ref)) <= 1e-8 * np.max(np.abs(ref))
    x1 = get_linear_solver(name)(A)(b[:, 0])
    assert x1.shape == (A.shape[0],)
    assert np.allclose(x1, ref[:, 0], rtol=0, atol=1e-8 * np.max(np.abs(ref)))


def test_solve_reynolds_same_force_with_every_solver(mesh):
    film = bf.CosineFilm(0.5, np.pi)
    ref = bf.solve_reynolds(mesh, film, inlet_pressure=10.0, squeeze=(0.1, 0.2)).force
    for name in available_solvers():
        f = bf.solve_reynolds(mesh, film, inlet_pressure=10.0, squeeze=(0.1, 0.2), solver=name).force
        assert np.allclose(f, ref, rtol=1e-9, atol=1e-9 * np.abs(ref).max()), name


@pytest.mark.parametrize("backend", _available_backends())
def test_pattern_factorizer_reuses_analysis_and_stays_exact(mesh, backend):
    fac = PatternFactorizer(backend)
    b = np.ones(_condensed(mesh, 0.3).shape[0])
    for gamma in (0.3, 0.6, 0.9):  # same mesh: same pattern, new values
        A = _condensed(mesh, gamma)
        x = fac(A)(b)
        ref = spla.spsolve(A, b)
        assert np.max(np.abs(x - ref)) <= 1e-9 * np.max(np.abs(ref))
    assert fac.analyses == 1
    A2 = _condensed(mesh, 0.3, element="P2")  # new pattern: analysed again
    assert np.allclose(fac(A2)(np.ones(A2.shape[0])), spla.spsolve(A2, np.ones(A2.shape[0])), rtol=1e-9)
    assert fac.analyses == 2


def test_pattern_factorizer_works_through_superpose(mesh):
    fac = PatternFactorizer("splu_sym")
    for gamma in (0.2, 0.7):
        film = bf.CosineFilm(gamma, np.pi)
        a = bf.superpose(mesh, film, solver=fac).forces
        b = bf.superpose(mesh, film).forces
        assert np.allclose(a, b, rtol=1e-9, atol=1e-12)
    assert fac.analyses == 1


def test_unknown_solver_and_backend_are_value_errors():
    with pytest.raises(ValueError, match="solver must be one of"):
        get_linear_solver("umfpack")
    with pytest.raises(ValueError, match="backend must be one of"):
        PatternFactorizer("cholespy")


def test_missing_optional_package_names_the_pip_package(monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "pypardiso", None)  # makes `import pypardiso` raise ImportError
    with pytest.raises(ImportError, match="pip install pypardiso"):
        LINEAR_SOLVERS["pardiso"](sp.identity(3, format="csc"))
    assert "pardiso" not in available_solvers()


def test_dense_threads_inside_a_cap_as_tight_changes_nothing():
    """Inside an open ``dense_threads(1)`` a nested one with the same cap changes nothing (no threadpoolctl call:
    a null context) and the BLAS threads stay at 1 after it closes; another cap inside it is still passed to
    threadpoolctl (it sets the count while open, as before), and on leaving the outer one the counts are
    restored."""
    import contextlib

    from threadpoolctl import threadpool_info

    from bearingfe.core import linalg
    from bearingfe.core.linalg import dense_threads

    def blas():
        return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]

    before = blas()
    with dense_threads(1):
        inner = dense_threads(1)
        assert isinstance(inner, contextlib.nullcontext)
        with inner:
            assert all(n == 1 for n in blas())
        assert all(n == 1 for n in blas()) and linalg._open_caps() == [1]
        wider = dense_threads(2)
        assert not isinstance(wider, contextlib.nullcontext)
        with wider:
            assert linalg._open_caps() == [1, 2]
        assert all(n == 1 for n in blas())
    assert blas() == before and linalg._open_caps() == []


@pytest.mark.parametrize("fmt", ["csr", "csc"])
def test_compressed_is_scipys_matrix_of_the_same_arrays(fmt):
    """compressed() holds the given int32 arrays themselves and gives the matrix scipy's constructor gives (the
    same class, shape, arrays and products); other index dtypes go through scipy's constructor (int64 indices
    of a small matrix come back as scipy's int32)."""
    from bearingfe.core.linalg import compressed

    cls = sp.csr_matrix if fmt == "csr" else sp.csc_matrix
    A = cls(sp.random(40, 30, density=0.2, random_state=3))
    A.sum_duplicates()
    data, indices, indptr = A.data, A.indices.astype(np.int32), A.indptr.astype(np.int32)
    B = compressed(data, indices, indptr, A.shape, fmt=fmt, canonical=True)
    ref = cls((data, indices, indptr), shape=A.shape)
    assert type(B) is type(ref) and B.shape == ref.shape and B.format == fmt
    assert B.data is data and B.indices is indices and B.indptr is indptr
    assert B.has_canonical_format and B.has_sorted_indices
    x = np.arange(30.0)
    assert np.array_equal(B @ x, ref @ x) and np.array_equal((B + ref).toarray(), 2 * ref.toarray())
    assert repr(B) == repr(ref)
    wide = compressed(data, indices.astype(np.int64), indptr.astype(np.int64), A.shape, fmt=fmt)
    assert wide.indices.dtype == ref.indices.dtype and np.array_equal(wide.toarray(), ref.toarray())
    with pytest.raises(ValueError, match="index pointer"):   # inconsistent arrays: scipy's checks see them
        compressed(data[:-1], indices[:-1], indptr, A.shape, fmt=fmt)


def test_compressed_refuses_an_unknown_format():
    from bearingfe.core.linalg import compressed

    with pytest.raises(ValueError, match="fmt"):
        compressed(np.ones(1), np.zeros(1, np.int32), np.array([0, 1], np.int32), (1, 1), fmt="coo")


@pytest.mark.parametrize("fmt", ["csr", "csc"])
def test_matvec_is_scipys_product(fmt):
    """matvec() calls scipy's kernel of A @ x directly: the same vector bit for bit on random matrices (int32 and
    int64 indices, a strided vector); other inputs (a coo matrix, a 2-D right side, integer values) go through
    A @ x and give its answer."""
    from bearingfe.core.linalg import matvec

    rng = np.random.default_rng(2)
    for k in range(6):
        n, m = (int(v) for v in rng.integers(1, 50, size=2))
        A = sp.random(n, m, density=0.3, random_state=k, format=fmt)
        x = rng.normal(size=2 * m)[::2]   # strided
        assert np.array_equal(matvec(A, x), A @ x)
        wide = A.copy()
        wide.indices, wide.indptr = wide.indices.astype(np.int64), wide.indptr.astype(np.int64)
        assert np.array_equal(matvec(wide, x), A @ x)
    X = rng.normal(size=(m, 3))
    assert np.array_equal(matvec(A, X), A @ X)
    assert np.array_equal(matvec(A.tocoo(), x), A @ x)
    ints = np.arange(m)
    assert np.array_equal(matvec(A, ints), A @ ints)
