"""A viscosity varying over the film in the shared forms and the compiled operator (level 2 of the thermal models).

Expected values: the compiled direct-form matrix with ``viscosity`` must equal the scikit-fem assembly of
``int (h^3/mu) grad u . grad v`` (bearingfe.film.forms.weighted_laplace) entry by entry, to round-off (1e-10 of the
largest entry, the tolerance of tests/film/test_compiled.py); without a viscosity every path is the isoviscous one,
bitwise (the same expression); a uniform relative viscosity of 1 gives the isoviscous matrix to round-off.
The flux, shear and dissipation with a viscosity follow their definitions (Poiseuille part over mu, Couette
shear times mu), and the dissipation of a 1-D isoviscous film equals the friction power: for Couette flow
alone (dp = 0) mu U^2/h exactly.
"""

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.film import operators
from bearingfe.film.forms import dissipation, film_at, film_flux, shear, weighted_laplace

SURFACE = bf.Surface(arc=(-1.2, 1.2), half_width=0.6)
FILM = bf.CosineFilm(0.55, 2.6)


@pytest.fixture(scope="module")
def ops():
    return operators(bf.mesh_surface(SURFACE, 0.35), "P2")


def test_compiled_matrix_with_a_viscosity_field_matches_the_assembly(ops):
    co = ops.compiled
    at = film_at(FILM, ops.x)
    mu = 1.0 + 0.5 * np.sin(ops.x[0]) * np.cos(2 * ops.x[1])  # relative viscosity at the quadrature points
    ref = weighted_laplace.assemble(ops.basis, c=at.h**3 / mu).toarray()
    mine = co.matrix(co.matrix_data("direct", at.h.ravel(), at.D.ravel(), viscosity=mu.ravel())).toarray()
    assert np.max(np.abs(mine - ref)) <= 1e-10 * np.max(np.abs(ref))


def test_without_a_viscosity_the_isoviscous_path_is_unchanged(ops):
    co = ops.compiled
    at = film_at(FILM, ops.x)
    h, D = at.h.ravel(), at.D.ravel()
    iso = co.matrix_data("direct", h, D)
    assert np.array_equal(iso, (co.stiffness_scatter @ h**3)[co.twins[0]])  # the former expression, bitwise
    one = co.matrix_data("direct", h, D, viscosity=np.ones_like(h))
    assert np.allclose(one, iso, rtol=1e-14, atol=0)
    with pytest.raises(ValueError, match="direct"):
        co.matrix_data("pi", h, D, viscosity=np.ones_like(h))


def test_flux_shear_dissipation_with_a_viscosity():
    h = np.array([1.0, 1.5, 2.0])
    dp = (np.array([0.3, -0.2, 0.1]), np.array([0.05, 0.0, -0.4]))
    mu = np.array([0.5, 1.0, 2.0])
    q0, q1 = film_flux(h, dp, 1.0, viscosity=mu)
    assert np.allclose(q0, -h**3 / (12 * mu) * dp[0] + h / 2, rtol=1e-15)
    assert np.allclose(q1, -h**3 / (12 * mu) * dp[1], rtol=1e-15)
    iso = film_flux(h, dp, 1.0)
    assert np.array_equal(iso[0], -h**3 / 12.0 * dp[0] + 0.5 * 1.0 * h)  # isoviscous formula, bitwise
    assert np.allclose(shear(h, dp, 1.0, viscosity=mu), mu / h + h / 2 * dp[0], rtol=1e-15)
    assert np.array_equal(shear(h, dp, 1.0), 1.0 / h + 0.5 * h * dp[0])
    zero = (np.zeros(3), np.zeros(3))
    assert np.allclose(dissipation(h, zero, 2.0, mu), mu * 4.0 / h, rtol=1e-15)
    assert np.allclose(dissipation(h, dp, 1.0, mu), mu / h + h**3 / (12 * mu) * (dp[0] ** 2 + dp[1] ** 2), rtol=1e-15)
