"""Elastic support (EHD): half-space compliance and the coupled film.

Expected values: Love's closed form for a uniformly loaded rectangle on a
half-space (Johnson, Contact Mechanics, eq. 3.25), Gauss quadrature of a
smooth integrand for observation points off the surface, the rigid solution
for an infinitely stiff support, and the fixed point's own definition
(``w = C p`` at the answer). Tolerances: round-off for exact integrals;
measured discretization errors with margin for the mesh sequences.
"""

import math

import numpy as np
import pytest

from bearingfe import Circle, CosineFilm, Material, Scale, Surface, mesh_surface, solve_reynolds
from bearingfe.elastic import (Compliance, ElasticError, combined_modulus, half_space, influence_matrix,
                               rectangle_deflection, solve_elastic)
from bearingfe.cavitation import MODELS
from bearingfe.reynolds import operators
from tests.helpers import ROOT

SCALE = Scale(radius=0.05, clearance=20e-6, viscosity=0.03, speed=157.08)   # the shipped pump
STEEL = Material("steel", 210e9, poisson_ratio=0.3)
PLAIN = Surface(arc=(-0.6, 0.6), half_width=0.4)
POCKET = Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=[Circle((0.0, 0.0), 0.1748)])


@pytest.fixture(scope="module")
def plain_mesh():
    return mesh_surface(PLAIN, 0.1)


@pytest.fixture(scope="module")
def pocket_mesh():
    return mesh_surface(POCKET, 0.1)


def _node(basis, phi, z):
    d = basis.doflocs
    k = int(np.argmin((d[0] - phi) ** 2 + (d[1] - z) ** 2))
    assert math.hypot(d[0, k] - phi, d[1, k] - z) < 1e-12
    return k


def test_combined_modulus_steel_on_steel():
    # 1/E* = 2 (1 - 0.09)/210 GPa  ->  115.38 GPa
    assert combined_modulus(STEEL, STEEL) == pytest.approx(210e9 / 1.82, rel=1e-14)
    assert combined_modulus(STEEL) == pytest.approx(210e9 / 0.91, rel=1e-14)


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_uniform_pressure_on_rectangle_against_love(plain_mesh, element):
    # uniform 32 MPa on the 60 x 40 mm shoe: deflection at the centre and at a corner (Love 1929)
    C = half_space(plain_mesh, SCALE, (STEEL, STEEL), element)
    basis = operators(plain_mesh, element).basis
    e_star = combined_modulus(STEEL, STEEL)
    a, b = 0.6 * SCALE.radius, 0.4 * SCALE.radius
    love = lambda phi, z: 32e6 / (math.pi * e_star) * rectangle_deflection(  # noqa: E731
        phi * SCALE.radius, z * SCALE.radius, a, b)
    # corner: a dof of the mesh, through the Compliance (SI -> clearance units)
    w = C.deflection(np.full(basis.N, SCALE.from_pressure(32e6))) * SCALE.clearance
    assert w[_node(basis, 0.6, 0.4)] == pytest.approx(love(0.6, 0.4), rel=1e-11)
    # centre (not a dof on this mesh): the influence coefficients at that point, times P R0 / (pi E*)
    G, _ = influence_matrix(plain_mesh, element, np.array([[0.0], [0.0]]))
    centre = float(G.sum()) * 32e6 * SCALE.radius / (math.pi * e_star)
    assert centre == pytest.approx(love(0.0, 0.0), rel=1e-11)
    assert 5e-6 < centre < 20e-6  # "several micrometres": the order of the film
    # Love's closed form itself: the centre of a square 2a x 2a is 8 a asinh(1) (Johnson eq. 3.26,
    # ln(1 + sqrt 2) = asinh 1), twice the corner of the same square... of side 2a: 4 a asinh(1)
    assert rectangle_deflection(0.0, 0.0, 1.0, 1.0) == pytest.approx(8.0 * math.asinh(1.0), rel=1e-14)
    assert rectangle_deflection(1.0, 1.0, 1.0, 1.0) == pytest.approx(4.0 * math.asinh(1.0), rel=1e-14)


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_pocket_and_film_add_up_to_the_rectangle(pocket_mesh, element):
    # film tiles the rectangle minus the pocket polygon, whose contour integral is exact: the sum is Love's
    G, pocket = influence_matrix(pocket_mesh, element)
    basis = operators(pocket_mesh, element).basis
    w = G @ np.ones(basis.N) + pocket
    love = rectangle_deflection(basis.doflocs[0], basis.doflocs[1], 0.6, 0.4)
    assert np.max(np.abs(w - love) / love) < 1e-11


def test_quadratic_pressure_against_gauss_quadrature(pocket_mesh):
    # P2 on straight triangles reproduces p = phi^2 - phi z exactly; off the surface the kernel is smooth,
    # so 60-point Gauss-Legendre on the rectangle minus the same integrand on the pocket disc converges
    # to round-off. The pocket is a polygon in the mesh: compare against the rectangle with p = 0 there,
    # i.e. the film integral is checked on a plain mesh instead.
    mesh = mesh_surface(PLAIN, 0.15)
    basis = operators(mesh, "P2").basis
    x = np.array([[0.9, -0.2, 0.0], [0.1, 0.7, -0.55]])
    G, _ = influence_matrix(mesh, "P2", x)
    f = lambda s, z: s**2 - s * z + 0.3 * z  # noqa: E731
    w = G @ f(basis.doflocs[0], basis.doflocs[1])
    g, wt = np.polynomial.legendre.leggauss(60)
    S, Z = np.meshgrid(0.6 * g, 0.4 * g)
    W = np.outer(0.4 * wt, 0.6 * wt)
    ref = [np.sum(W * f(S, Z) / np.hypot(S - xi[0], Z - xi[1])) for xi in x.T]
    assert np.max(np.abs(w - ref)) < 1e-10 * np.max(np.abs(ref))


def test_infinitely_stiff_support_is_the_rigid_solution(pocket_mesh):
    C = half_space(pocket_mesh, SCALE, math.inf)
    film = CosineFilm(0.6, math.pi)
    rigid = solve_reynolds(pocket_mesh, film, inlet_pressure=1.0, formulation="direct")
    sol = solve_elastic(pocket_mesh, film, C, inlet_pressure=1.0)
    assert sol.iterations == 1 and sol.max_deflection == 0.0
    assert np.max(np.abs(sol.result.pressure - rigid.pressure)) < 1e-12
    assert np.allclose(sol.result.force, rigid.force, rtol=1e-12)
    # a very stiff support (E* = 1e6 x steel) moves the answer by about 1e-6 of the film
    stiff = solve_elastic(pocket_mesh, film, half_space(pocket_mesh, SCALE, 1.15e17))
    assert 0 < stiff.max_deflection < 1e-6
    assert stiff.result.h_min == pytest.approx(rigid.h_min, abs=2e-6)


@pytest.mark.parametrize("cavitation", list(MODELS))  # every model of the table, JFO included
def test_coupled_solve_satisfies_its_fixed_point(pocket_mesh, cavitation):
    # pump conditions: 32 MPa in the pocket, steel on steel; w = C p(h_rigid + w) at the answer
    C = half_space(pocket_mesh, SCALE, (STEEL, STEEL))
    ps = SCALE.from_pressure(32e6)
    film = CosineFilm(0.6, math.pi)
    sol = solve_elastic(pocket_mesh, film, C, inlet_pressure=ps, cavitation=cavitation, tol=1e-9)
    assert sol.iterations <= 12  # Newton: quadratic once close
    assert sol.history[-1] <= 1e-9 < sol.history[0]
    w = C.deflection(sol.result.pressure, ps)
    assert np.max(np.abs(w - sol.deflection)) <= 1e-9
    assert sol.result.cavitation == cavitation
    assert sol.max_deflection > 0.2  # several micrometres at 32 MPa: the film is opened
    h = sol.result.film.thickness(*operators(pocket_mesh, "P1").basis.doflocs)
    assert sol.result.h_min == pytest.approx(float(h.min()), abs=1e-12)
    assert sol.result.h_min > sol.rigid_h_min


# Converged reference of the pump-like EHD case below (steel on steel, 32 MPa pocket, gamma = 0.6,
# Swift-Stieber): film force along phi = 0 on curved P2 meshes 0.16 / 0.08 / 0.04 R0 (312 / 736 / 2728
# dofs) is 0.41745031 / 0.41761747 / 0.41767072, observed order log2(3.14) = 1.65, Richardson
# extrapolation 0.4176956. An independent iteration (Anderson-mixed fixed point instead of Newton)
# reproduced the three values to 8 digits.
REFERENCE_FORCE = 0.4176956


def test_coupled_solve_converges_under_refinement():
    film = CosineFilm(0.6, math.pi)
    ps = SCALE.from_pressure(32e6)
    errors = []
    for size in (0.16, 0.08):
        mesh = mesh_surface(POCKET, size, order=2)
        C = half_space(mesh, SCALE, (STEEL, STEEL), "P2")
        sol = solve_elastic(mesh, film, C, inlet_pressure=ps, element="P2", cavitation="reynolds")
        errors.append(abs(sol.result.force[0] - REFERENCE_FORCE) / REFERENCE_FORCE)
    assert errors[1] < errors[0] / 2.5
    assert errors[1] < 3e-4
    # the elastic effect itself is large: the rigid force on the same mesh differs by 20 %
    rigid = solve_reynolds(mesh, film, inlet_pressure=ps, element="P2", formulation="direct",
                           cavitation="reynolds")
    assert abs(rigid.force[0] - REFERENCE_FORCE) / REFERENCE_FORCE > 0.1


def test_newton_converges_on_a_thin_cavitated_film():
    # h_min = 0.1 c (2 um) on the plain shoe: a plain fixed point w -> C p diverges here (the pressure
    # grows like h^-2 where the film is thin); Newton needs a handful of solves
    mesh = mesh_surface(PLAIN, 0.12)
    C = half_space(mesh, SCALE, (STEEL, STEEL))
    sol = solve_elastic(mesh, CosineFilm(0.9, math.pi - 0.3), C, cavitation="reynolds", tol=1e-10)
    assert sol.iterations <= 12
    assert np.max(np.abs(C.deflection(sol.result.pressure) - sol.deflection)) <= 1e-10
    assert sol.result.cavitated.any() and sol.result.pressure.min() >= 0.0


def test_bad_inputs_are_named(pocket_mesh, plain_mesh):
    with pytest.raises(ValueError, match="modulus"):
        half_space(pocket_mesh, SCALE, -1.0)
    with pytest.raises(ValueError, match="scale"):
        half_space(pocket_mesh, 1.0, 1e11)
    with pytest.raises(ValueError, match="poisson_ratio"):
        Material("rubber?", 1e9, poisson_ratio=0.5)
    C = half_space(pocket_mesh, SCALE, 1e11)
    assert isinstance(C, Compliance)
    with pytest.raises(ValueError, match="another mesh"):
        solve_elastic(plain_mesh, CosineFilm(0.5), C)
    with pytest.raises(ValueError, match="element"):
        solve_elastic(pocket_mesh, CosineFilm(0.5), C, element="P2")
    with pytest.raises(ElasticError, match="did not converge"):
        solve_elastic(pocket_mesh, CosineFilm(0.6, math.pi), C, inlet_pressure=1.0, max_iterations=1)
    with pytest.raises(ValueError, match="tol"):
        solve_elastic(pocket_mesh, CosineFilm(0.6, math.pi), C, tol=0.0)


def test_solve_reynolds_front_door_reports_the_deflection(pocket_mesh):
    C = half_space(pocket_mesh, SCALE, (STEEL, STEEL))
    ps = SCALE.from_pressure(32e6)
    res = solve_reynolds(pocket_mesh, CosineFilm(0.6, math.pi), inlet_pressure=ps, elastic=C)
    sol = solve_elastic(pocket_mesh, CosineFilm(0.6, math.pi), C, inlet_pressure=ps)
    assert np.array_equal(res.pressure, sol.result.pressure)
    assert res.elastic_iterations == sol.iterations > 1
    assert res.max_deflection == pytest.approx(sol.max_deflection, rel=1e-15)
    assert res.formulation == "direct" and any("elastic support" in n for n in res.notes)
    rigid = solve_reynolds(pocket_mesh, CosineFilm(0.6, math.pi), inlet_pressure=ps)
    assert rigid.deflection is None and rigid.max_deflection == 0.0 and rigid.elastic_iterations == 0


def test_balance_load_balances_and_is_rigid_when_stiff(pocket_mesh):
    from bearingfe import superpose
    from bearingfe.elastic import balance_load

    film, load, ps = CosineFilm(0.6, math.pi), np.array([-0.42, 0.0]), 1.08
    rigid = superpose(pocket_mesh, film, formulation="direct").rates_for_load(load, 0.98, ps)
    stiff = balance_load(pocket_mesh, film, half_space(pocket_mesh, SCALE, math.inf), load, wedge=0.98,
                         inlet_pressure=ps)
    np.testing.assert_allclose(stiff.rates, rigid, rtol=1e-12)
    C = half_space(pocket_mesh, SCALE, (STEEL, STEEL))
    for cavitation in ("none", "reynolds"):
        b = balance_load(pocket_mesh, film, C, load, wedge=0.98, inlet_pressure=ps, cavitation=cavitation)
        np.testing.assert_allclose(b.result.force, -load, atol=1e-10)   # force + load = 0
        assert np.max(np.abs(C.deflection(b.result.pressure, ps) - b.deflection)) <= 1e-8
        assert np.max(np.abs(b.rates - rigid)) > 0.1   # the deflection changes the motion


def test_pump_transient_on_a_stiff_support_is_the_rigid_one():
    import bearingfe as bf

    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    mesh = bf.transient.pump_mesh(pump, 0.3)
    opts = dict(start="steady", formulation="direct", points_per_revolution=24, beta0=0.3)
    rigid = bf.simulate(pump, mesh, 0.1, **opts)
    stiff = bf.simulate(pump, mesh, 0.1, elastic=half_space(mesh, pump.scale, math.inf), **opts)
    # same right side to round-off, so the same integrator path
    np.testing.assert_allclose(stiff.gamma, rigid.gamma, rtol=1e-8)
    np.testing.assert_allclose(stiff.delta, rigid.delta, rtol=1e-8)
    # the elastic film's minimum is over dofs and quadrature points, the rigid cosine film's is exact
    np.testing.assert_allclose(stiff.h_min, rigid.h_min, rtol=1e-5)
    assert np.all(stiff.max_deflection == 0.0) and rigid.max_deflection is None
    steel = bf.simulate(pump, mesh, 0.1, elastic=half_space(mesh, pump.scale, (STEEL, STEEL)), **opts)
    assert steel.status == "completed" and np.max(steel.max_deflection) > 5e-6   # several micrometres
    assert steel.stats["jacobians"] < steel.stats["factorizations"] / 2   # Jacobian factors reused
    with pytest.raises(ValueError, match="another mesh"):
        bf.simulate(pump, bf.transient.pump_mesh(pump, 0.3), 0.1,
                    elastic=half_space(mesh, pump.scale, math.inf), **opts)


def test_shoe_body_approaches_the_half_space_as_it_grows(plain_mesh):
    # uniform pressure on the 60 x 40 mm shoe; a steel block clamped at its back, growing in depth and
    # width: the opening at the centre grows towards the single-body half-space value (Love) from below,
    # the gap shrinking with every doubling (measured 0.23 -> 0.15 -> 0.075 -> 0.035 of the half-space
    # value for depths 20 / 40 / 80 / 160 mm; the two shallow ones here keep the test fast)
    from bearingfe.elastic import block_compliance

    basis = operators(plain_mesh, "P1").basis
    k = int(np.argmin(basis.doflocs[0] ** 2 + basis.doflocs[1] ** 2))
    ones = np.ones(basis.N)
    half = half_space(plain_mesh, SCALE, STEEL).deflection(ones)[k]
    gaps = []
    for depth, margin in ((0.01, 0.0), (0.02, 0.0), (0.04, 0.02)):
        body = block_compliance(plain_mesh, SCALE, STEEL, depth, margin=margin, size=0.1)
        assert body.model == "body" and body.matrix.shape == (basis.N, basis.N)
        gaps.append((half - body.deflection(ones)[k]) / half)
    assert 0 < gaps[2] < gaps[1] < gaps[0] < 1
    assert gaps[2] < 0.8 * gaps[1]
    # the eccentric as a half-space on top: the two compliances add
    both = block_compliance(plain_mesh, SCALE, STEEL, 0.01, counterpart=STEEL, size=0.1)
    alone = block_compliance(plain_mesh, SCALE, STEEL, 0.01, size=0.1)
    np.testing.assert_allclose(both.matrix, alone.matrix + half_space(plain_mesh, SCALE, STEEL).matrix,
                               rtol=1e-12, atol=1e-15)
    with pytest.raises(ValueError, match="thickness"):
        block_compliance(plain_mesh, SCALE, STEEL, 0.0)
