"""``superpose(..., lazy=True)``: the factorization and the four unit solutions deferred to their first use.

The same arrays as the eager call (bit for bit: the same factorization of the same matrix and the same
solves), and no factorization until a caller asks for the fields or the system's solve, which a cavitating
solve from a warm rupture set does not (the journal's Newton steps).
"""

from __future__ import annotations

import numpy as np

import bearingfe as bf
from bearingfe.cavitation import solve_cavitating

SURFACE = bf.Surface(arc=(-0.6, 0.6), half_width=0.5, inlets=(bf.Rectangle((0.05, 0.0), (0.48, 0.4)),))
FILM = bf.CosineFilm(0.7, 3.0)


def test_lazy_superposition_defers_and_matches():
    mesh = bf.mesh_surface(SURFACE, 0.2, order=2)
    eager = bf.superpose(mesh, FILM, formulation="direct", element="P2")
    lazy = bf.superpose(mesh, FILM, formulation="direct", element="P2", lazy=True)
    assert "factorization" in eager.cost and "factorization" not in lazy.cost
    np.testing.assert_array_equal(lazy.system.rhs, eager.system.rhs)
    # a cavitating solve from a warm rupture set needs only the system: still no full-film factorization
    cold = solve_cavitating(eager, 1.0, (0.0, 0.0), 2.0)
    assert cold.cavitated.any() and not cold.cavitated.all()  # a free boundary to find
    warm = solve_cavitating(lazy, 1.0, (0.0, 0.0), 2.0, warm_start=cold)
    assert "factorization" not in lazy.cost
    # same discrete problem, same active set: the pressures agree to the solver's round-off
    np.testing.assert_array_equal(warm.cavitated, cold.cavitated)
    np.testing.assert_allclose(warm.pressure, cold.pressure, rtol=0, atol=1e-12 * np.abs(cold.pressure).max())
    # the unit fields on first use: those of the eager call, bit for bit
    np.testing.assert_array_equal(lazy.fields, eager.fields)
    np.testing.assert_array_equal(lazy.forces, eager.forces)
    np.testing.assert_array_equal(lazy.integrals, eager.integrals)
    assert "factorization" in lazy.cost and "solve" in lazy.cost
    np.testing.assert_array_equal(lazy.system.solve(lazy.system.rhs), eager.system.solve(eager.system.rhs))
