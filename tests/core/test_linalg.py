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
