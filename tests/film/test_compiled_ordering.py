"""The compiled path's order of A[I, I]: nested dissection gives minimum degree's numbers, in one factorization.

From :data:`bearingfe.core.ordering.NESTED_DISSECTION_FROM` unknowns the compiled path orders by
nested dissection of the pattern (no factorization needed to find it); below, by SuperLU's
minimum degree read off a first factorization. Both factor the same symmetric positive definite
matrix without pivoting: a direct solve in either order gives the same film to round-off
(relative 1e-12, ~1000x the measured worst difference, 6.4e-16, on the mesh below). The crossover
is lowered or raised here so that the small test mesh takes either path, and the band limit of
banded Cholesky lowered so that it is factored by SuperLU.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse.linalg as spla

import bearingfe as bf
from bearingfe.core import banded
from bearingfe.film import compiled

RTOL = 1e-12
SURFACE = bf.Surface(arc=(-1.2, 1.2), half_width=0.6, inlets=(bf.Circle((0.1, 0.05), 0.2),))
FILM = bf.CosineFilm(0.55, 2.6)
SPLU = spla.splu


def _mesh():
    return bf.mesh_surface(SURFACE, 0.2, order=2)  # 382 interior P2 unknowns, half-bandwidth 49


def _solve(monkeypatch, crossover: int, films=(FILM,)):
    monkeypatch.setattr(compiled, "NESTED_DISSECTION_FROM", crossover)
    monkeypatch.setitem(banded.BAND_LIMITS, "kept_pattern", banded.BandLimits(kd_max=0))  # SuperLU, whatever the band
    calls = []

    def counting(A, *args, **kwargs):
        calls.append(kwargs.get("permc_spec"))
        return SPLU(A, *args, **kwargs)

    monkeypatch.setattr(compiled.spla, "splu", counting)
    mesh = _mesh()
    out = [bf.superpose(mesh, film, formulation="direct", element="P2") for film in films]
    assert not bf.film.operators(mesh, "P2").compiled.banded
    return out, calls


def test_nested_dissection_gives_minimum_degrees_film_with_one_factorization(monkeypatch):
    (nd,), nd_calls = _solve(monkeypatch, 0)
    (mmd,), mmd_calls = _solve(monkeypatch, 10**9)
    scale = np.abs(mmd.fields).max()
    assert np.abs(nd.fields - mmd.fields).max() <= RTOL * scale
    assert np.abs(nd.forces - mmd.forces).max() <= RTOL * np.abs(mmd.forces).max()
    # a fresh mesh's first film: one factorization in the found order, against two (the first finds it)
    assert nd_calls == ["NATURAL"]
    assert mmd_calls == ["MMD_AT_PLUS_A", "NATURAL"]


def test_in_nested_dissection_order_a_films_numbers_do_not_depend_on_the_films_before_it(monkeypatch):
    (first, _, again), calls = _solve(monkeypatch, 0, (FILM, bf.CosineFilm(0.3, 1.0), FILM))
    np.testing.assert_array_equal(first.fields, again.fields)
    assert calls == ["NATURAL"] * 3
