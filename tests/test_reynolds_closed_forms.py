"""The FEM Reynolds solver against closed forms.

1. Flat circular pad with a central circular recess (h = 1, no wedge, no
   squeeze): div(grad p) = 0 on the annulus r0 < r < R with p(r0) = p_s,
   p(R) = 0, so (derived here)

       p = p_s ln(R/r) / ln(R/r0),
       int_annulus p dA = pi p_s (R^2 - r0^2) / (2 ln(R/r0)) - pi r0^2 p_s,
       so with the recess at p_s: W = pi p_s (R^2 - r0^2) / (2 ln(R/r0)),
       inlet flow Q = 2 pi r (-h^3/12 dp/dr) = 2 pi p_s / (12 ln(R/r0)).

2. Short bearing (Ocvirk): for a -> 0 the phi-flow is negligible and
   h^3 d2p/dz2 = 6 dh/dphi = -6 gamma sin(phi - phi0) gives
   p = 3 gamma sin(phi - phi0) (a^2 - z^2) / h^3, force from 1-D quadrature.
   The neglected term is O(a^2) relative.

3. Long bearing (full Sommerfeld 1904): d/dphi(h^3 dp/dphi) = 6 dh/dphi with
   p(0) = p(2 pi) = 0 gives
   p = 6 gamma sin(phi)(2 + gamma cos phi) / ((2 + gamma^2)(1 + gamma cos phi)^2),
   W per unit length = 12 pi gamma / ((2 + gamma^2) sqrt(1 - gamma^2)),
   normal to the line of centres. The FEM solves the full 2-D problem with
   p = 0 at z = +-a; the end effect decays like exp(-(a - |z|)).
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from bearingfe import Circle, CosineFilm, Surface, mesh_surface, solve_reynolds

# -- flat annular pad ----------------------------------------------------------

R, R0, PS = 0.5, 0.15, 2.0
LOG = math.log(R / R0)
W_ANNULUS = math.pi * PS * (R**2 - R0**2) / (2 * LOG)
Q_ANNULUS = 2 * math.pi * PS / (12 * LOG)


def annulus_probe_points():
    r = np.linspace(R0 + 0.02, R - 0.02, 7)
    t = np.linspace(0.0, 2 * np.pi, 9)[:-1]
    rr, tt = np.meshgrid(r, t)
    return rr * np.cos(tt), rr * np.sin(tt), PS * np.log(R / rr) / LOG


@pytest.fixture(scope="module")
def annulus():
    return Surface(outer=Circle((0.0, 0.0), R), inlets=(Circle((0.0, 0.0), R0),))


def test_annulus_closed_form_self_check():
    # the closed forms above, checked by quadrature of p over the annulus and by the flux
    integral = quad(lambda r: PS * math.log(R / r) / LOG * 2 * math.pi * r, R0, R)[0]
    assert integral + math.pi * R0**2 * PS == pytest.approx(W_ANNULUS, rel=1e-12)
    dpdr = -PS / (LOG * 0.3)
    assert 2 * math.pi * 0.3 * (-dpdr / 12) == pytest.approx(Q_ANNULUS, rel=1e-14)


@pytest.mark.parametrize("element, order, size, tol_w, tol_q, tol_p", [
    # measured: P2/curved 2.0e-5, 1.8e-5, 9e-4 (abs, p_s = 2) at size 0.05
    ("P2", 2, 0.05, 6e-5, 6e-5, 3e-3),
    # measured: P1/straight 1.4e-4, 2.2e-4, 1.9e-2
    ("P1", 1, 0.05, 5e-4, 6e-4, 4e-2),
])
@pytest.mark.parametrize("formulation", ["pi", "direct"])
def test_annulus_pressure_load_and_inlet_flow(annulus, element, order, size, tol_w, tol_q, tol_p, formulation):
    mesh = mesh_surface(annulus, size, order=order)
    res = solve_reynolds(mesh, CosineFilm(0.0), wedge=0.0, inlet_pressure=PS,
                         element=element, formulation=formulation)
    assert res.integral == pytest.approx(W_ANNULUS, rel=tol_w)
    assert res.flows["inlet"] == pytest.approx(Q_ANNULUS, rel=tol_q)
    assert res.flows["outer"] == pytest.approx(res.flows["inlet"], rel=1e-12)
    assert res.flows["squeeze"] == 0.0
    assert abs(res.mass_balance) < 1e-12
    x, y, p = annulus_probe_points()
    assert np.abs(res.interpolate(x, y) - p).max() < tol_p
    assert res.max_pressure == pytest.approx(PS)
    assert res.h_min == 1.0


def test_annulus_curved_p2_converges_fast(annulus):
    # the curved-geometry P2 load error falls by > 8 per halving of the size (measured 1.1e-4,
    # 2.0e-5, 1.5e-6 at 0.1, 0.05, 0.025: slopes 2.5 and 3.7; a straight boundary would
    # stall at second order)
    errors = []
    for size in (0.1, 0.05, 0.025):
        res = solve_reynolds(mesh_surface(annulus, size, order=2), CosineFilm(0.0), wedge=0.0,
                             inlet_pressure=PS, element="P2", formulation="direct")
        errors.append(abs(res.integral / W_ANNULUS - 1))
    assert errors[2] < 4e-6
    assert errors[0] / errors[2] > 30


# -- short bearing (Ocvirk) -------------------------------------------------------

GAMMA = 0.5


def ocvirk_force(a: float) -> float:
    """int p sin(phi) over [0, 2 pi] x [-a, a] with the Ocvirk pressure (phi0 = 0)."""
    # int_{-a}^{a} (a^2 - z^2) dz = 4 a^3 / 3
    return 4 * GAMMA * a**3 * quad(lambda f: math.sin(f) ** 2 / (1 + GAMMA * math.cos(f)) ** 3, 0, 2 * math.pi)[0]


def ocvirk_error(a: float, size: float) -> tuple[float, float, float]:
    mesh = mesh_surface(Surface(arc=(0.0, 2 * math.pi), half_width=a), size)
    res = solve_reynolds(mesh, CosineFilm(GAMMA, 0.0), element="P2", formulation="direct")
    exact = ocvirk_force(a)
    phi = np.linspace(0.3, 2 * math.pi - 0.3, 11)
    p_mid = 3 * GAMMA * np.sin(phi) * a**2 / (1 + GAMMA * np.cos(phi)) ** 3
    p_err = np.abs(res.interpolate(phi, 0 * phi) - p_mid).max() / p_mid.max()
    return res.force[1] / exact - 1, res.force[0] / exact, p_err


def test_ocvirk_sign_of_the_closed_form():
    # p = 3 gamma sin(phi)(a^2 - z^2)/h^3 satisfies h^3 p_zz = -6 gamma sin(phi) = 6 dh/dphi
    phi, a, z, dz = 1.1, 0.1, 0.03, 1e-4
    p = lambda zz: 3 * GAMMA * math.sin(phi) * (a**2 - zz**2) / (1 + GAMMA * math.cos(phi)) ** 3  # noqa: E731
    pzz = (p(z + dz) - 2 * p(z) + p(z - dz)) / dz**2
    assert (1 + GAMMA * math.cos(phi)) ** 3 * pzz == pytest.approx(-6 * GAMMA * math.sin(phi), rel=1e-6)


def test_short_bearing_limit_error_falls_like_a_squared():
    # P2 meshes fine enough that the discretisation error (< 1e-5) is far below the
    # model error (~0.9 a^2 measured: -8.86e-3 at a = 0.1, -2.24e-3 at a = 0.05)
    e1, fx1, p1 = ocvirk_error(0.1, 0.05)
    e2, fx2, p2 = ocvirk_error(0.05, 0.025)
    assert abs(e1) < 1.2 * 0.1**2 and abs(e2) < 1.2 * 0.05**2
    assert e1 < 0 and e2 < 0  # the phi-flow the short-bearing theory neglects lowers the load
    assert 3.5 < e1 / e2 < 4.5  # a^2 law
    assert p1 < 0.03 and p2 < 0.008  # mid-plane pressure too (measured 1.6e-2, 4.0e-3)
    # full Sommerfeld: no force along the line of centres (antisymmetric p about phi = pi)
    assert abs(fx1) < 1e-6 and abs(fx2) < 1e-6


# -- long bearing (Sommerfeld) ---------------------------------------------------

def sommerfeld_pressure(phi):
    g = GAMMA
    return 6 * g * np.sin(phi) * (2 + g * np.cos(phi)) / ((2 + g * g) * (1 + g * np.cos(phi)) ** 2)


W_SOMMERFELD = 12 * math.pi * GAMMA / ((2 + GAMMA**2) * math.sqrt(1 - GAMMA**2))


def test_sommerfeld_closed_form_self_check():
    # the pressure satisfies the 1-D equation (finite differences) and integrates to W
    phi, d = np.linspace(0.2, 6.0, 7), 1e-3
    h = lambda f: 1 + GAMMA * np.cos(f)  # noqa: E731
    flux = lambda f: h(f) ** 3 * (sommerfeld_pressure(f + d / 2) - sommerfeld_pressure(f - d / 2)) / d  # noqa: E731
    lhs = (flux(phi + d / 2) - flux(phi - d / 2)) / d
    assert lhs == pytest.approx(-6 * GAMMA * np.sin(phi), rel=1e-4, abs=1e-5)
    w = quad(lambda f: sommerfeld_pressure(f) * math.sin(f), 0, 2 * math.pi)[0]
    assert w == pytest.approx(W_SOMMERFELD, rel=1e-10)
    assert quad(lambda f: sommerfeld_pressure(f) * math.cos(f), 0, 2 * math.pi)[0] == pytest.approx(0, abs=1e-12)


def test_long_bearing_limit():
    phi = np.linspace(0.1, 2 * math.pi - 0.1, 60)
    exact = sommerfeld_pressure(phi)
    force, p_err = {}, {}
    for a in (4.0, 6.0):
        mesh = mesh_surface(Surface(arc=(0.0, 2 * math.pi), half_width=a), 0.2)
        res = solve_reynolds(mesh, CosineFilm(GAMMA, 0.0), element="P2", formulation="direct")
        force[a] = res.force
        p_err[a] = np.abs(res.interpolate(phi, 0 * phi) - exact).max() / exact.max()
        assert abs(res.force[0]) < 1e-5 * res.force[1]  # attitude angle 90 degrees
    # mid-plane pressure: end effect ~ exp(-a); measured 2.0e-2 (a = 4) and 2.4e-3 (a = 6)
    assert p_err[6.0] < 4e-3
    assert p_err[4.0] / p_err[6.0] > math.exp(2.0 * 0.8)
    # the extra width 2 x 2 between a = 4 and a = 6 carries the Sommerfeld load per unit
    # length (end losses cancel up to exp(-4)); measured 0.99986
    assert (force[6.0][1] - force[4.0][1]) / (4.0 * W_SOMMERFELD) == pytest.approx(1.0, abs=5e-4)
