"""Pockets fed through restrictors (bearingfe.bearings.hydrostatic) against the closed forms of the circular recess pad.

Reference (derived in the module docstring of tests/test_reynolds_closed_forms.py and in Rowe,
*Hydrostatic, Aerostatic and Hybrid Bearing Design*, 2012, ch. 4-5): a flat circular pad of radius R with a
central recess of radius r at pressure p_r, uniform film h, no motion:

    film flow  Q = pi h^3 p_r / (6 mu ln(R/r)) = K h^3 p_r,    load  W = pi p_r (R^2 - r^2) / (2 ln(R/r)).

Fed from a supply p_s: capillary ``Kc (p_s - p_r) = Q`` gives beta = p_r/p_s = Kc / (Kc + K h^3) and the
stiffness -dW/dh = 3 W (1 - beta) / h; orifice ``C sqrt(p_s - p_r) = Q`` gives beta from
``(K h^3 p_s)^2 beta^2 = C^2 p_s (1 - beta)`` and -dW/dh = 6 W (1 - beta) / ((2 - beta) h); constant flow gives
p_r = Q / (K h^3) and -dW/dh = 3 W / h. At fixed p_s and pad, the capillary stiffness 3 A p_s beta (1 - beta)/h
is largest at beta = 1/2, the orifice's 6 A p_s beta (1 - beta)/((2 - beta) h) at beta = 2 - sqrt(2).

Tolerances, from the mesh convergence measured on these meshes (pad R = 0.4, r = 0.1, size 0.05, recess edges
size/3): P2 on curved (order-2) meshes: load and flow errors 4e-6 at size 0.05 and 7e-7 at 0.025, hence 2e-5;
P1: 6e-4 (load) and 1.7e-3 (flow) at 0.05, 1.2e-4 and 7e-4 at 0.025, hence 3e-3. The stiffness is a central
difference with step 1e-3: its truncation error measured 4.2e-7 relative against the formula evaluated with
the computed load and beta, hence 2e-6 there; against the fully closed-form value the mesh error adds.
"""

import math

import numpy as np
import pytest

from bearingfe import (Circle, CosineFilm, Discretization, OperatingPoint, Scale, Surface, UniformFilm, load_mechanism,
                       mesh_surface, solve_reynolds)
from bearingfe.bearings.hydrostatic import (SUPPLIES, Capillary, ConstantFlow, Orifice, PrescribedPressure, Restrictor,
                                            SupplyError, solve_supplied, supply_stiffness)
from bearingfe.film.pockets import pocket_film, pocket_flows, pocket_names
from bearingfe.core.schema import SchemaError
from tests.helpers import ROOT

R, r = 0.4, 0.1
SCALE = Scale(radius=0.05, clearance=20e-6, viscosity=0.05, speed=100.0)  # pad 20 mm radius, film 20 um
PS = 5e6  # supply pressure [Pa]
LOG = math.log(R / r)
C = SCALE.clearance
#: the film's conductance at h = 1 [m^3/s per Pa]: Q = K h^3 p_r (closed form above, SI)
K = math.pi * C**3 / (6 * SCALE.viscosity * LOG)
#: the pad's effective area [m^2]: W = A p_r
AREA = math.pi * ((R * SCALE.radius) ** 2 - (r * SCALE.radius) ** 2) / (2 * LOG)
P2 = Discretization(element="P2", formulation="direct")
P1 = Discretization(element="P1", formulation="direct")
TOL = {"P1": 3e-3, "P2": 2e-5}
MU, RHO, CD = SCALE.viscosity, 860.0, 0.7


@pytest.fixture(scope="module")
def pads():
    surface = Surface(outer=Circle((0.0, 0.0), R), inlets=(Circle((0.0, 0.0), r),))
    return {"P2": mesh_surface(surface, 0.05, inlet_size=0.05 / 3, order=2),
            "P1": mesh_surface(surface, 0.05, inlet_size=0.05 / 3, order=1)}


def capillary_for(beta: float, h: float = 1.0) -> Capillary:
    """The capillary that puts the recess at beta p_s: Kc = K h^3 beta / (1 - beta), Kc = pi d^4 / (128 mu l)."""
    d = 0.4e-3
    kc = K * h**3 * beta / (1 - beta)
    return Capillary(diameter=d, length=math.pi * d**4 / (128 * MU * kc), supply_pressure=PS)


def orifice_for(beta: float, h: float = 1.0) -> Orifice:
    """The orifice that puts the recess at beta p_s: C sqrt(p_s (1 - beta)) = K h^3 beta p_s, C = Cd pi d^2/4 sqrt(2/rho)."""
    c = K * h**3 * beta * PS / math.sqrt(PS * (1 - beta))
    d = math.sqrt(4 * c / (CD * math.pi * math.sqrt(2 / RHO)))
    return Orifice(diameter=d, discharge_coefficient=CD, density=RHO, supply_pressure=PS)


# -- the supplies ----------------------------------------------------------------------------

def test_the_table_of_supplies():
    assert set(SUPPLIES) == {"pressure", "capillary", "orifice", "flow"}
    assert all(cls.kind == kind for kind, cls in SUPPLIES.items())


@pytest.mark.parametrize("make, name", [
    (lambda: Capillary(diameter=-1e-3, length=0.01, supply_pressure=1e6), "Capillary.diameter"),
    (lambda: Capillary(diameter=1e-3, length=5e-4, supply_pressure=1e6), "Capillary.length"),
    (lambda: Capillary(diameter=1e-3, length=0.01, supply_pressure=0.0), "Capillary.supply_pressure"),
    (lambda: Orifice(diameter=1e-3, discharge_coefficient=1.2, density=860, supply_pressure=1e6),
     "Orifice.discharge_coefficient"),
    (lambda: Orifice(diameter=1e-3, discharge_coefficient=0.6, density=0.0, supply_pressure=1e6), "Orifice.density"),
    (lambda: ConstantFlow(flow=math.nan), "ConstantFlow.flow"),
    (lambda: PrescribedPressure(pressure=math.inf), "PrescribedPressure.pressure"),
])
def test_a_bad_supply_is_named(make, name):
    with pytest.raises(ValueError, match=name):
        make()


def test_the_laws_in_the_solvers_currency():
    # Hagen-Poiseuille and the sharp orifice in SI, converted back from the non-dimensional law
    cap = Capillary(diameter=0.5e-3, length=0.02, supply_pressure=PS)
    law = cap.law(SCALE)
    dp = 0.3 * PS
    assert SCALE.to_flow(law.flow(SCALE.from_pressure(PS - dp))) == pytest.approx(
        math.pi * 0.5e-3**4 * dp / (128 * MU * 0.02), rel=1e-13)
    orf = Orifice(diameter=0.3e-3, discharge_coefficient=CD, density=RHO, supply_pressure=PS)
    law = orf.law(SCALE)
    assert SCALE.to_flow(law.flow(SCALE.from_pressure(PS - dp))) == pytest.approx(
        CD * math.pi * 0.3e-3**2 / 4 * math.sqrt(2 * dp / RHO), rel=1e-13)


# -- the circular recess pad ----------------------------------------------------------------------

@pytest.mark.parametrize("element", ["P1", "P2"])
def test_capillary_recess_pad(pads, element):
    beta = 0.5
    st = supply_stiffness(pads[element], UniformFilm, 1.0, capillary_for(beta), SCALE,
                          discretization=P2 if element == "P2" else P1)
    pocket = st.result.pockets[0]
    tol = TOL[element]
    assert pocket.ratio == pytest.approx(beta, rel=tol)
    assert pocket.film_flow == pytest.approx(K * beta * PS, rel=tol)
    assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-10)  # the balance itself
    assert st.result.load == pytest.approx(AREA * beta * PS, rel=tol)
    # stiffness: the formula with the computed load and ratio (only the finite difference's error) ...
    assert st.stiffness == pytest.approx(3 * st.result.load * (1 - pocket.ratio) / C, rel=2e-6)
    # ... and the closed form outright
    assert st.stiffness == pytest.approx(3 * AREA * beta * PS * (1 - beta) / C, rel=tol)


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_orifice_recess_pad(pads, element):
    beta = 0.6
    st = supply_stiffness(pads[element], UniformFilm, 1.0, orifice_for(beta), SCALE,
                          discretization=P2 if element == "P2" else P1)
    pocket = st.result.pockets[0]
    tol = TOL[element]
    assert pocket.ratio == pytest.approx(beta, rel=tol)
    assert pocket.film_flow == pytest.approx(K * beta * PS, rel=tol)
    assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-10)
    assert st.result.load == pytest.approx(AREA * beta * PS, rel=tol)
    b = pocket.ratio
    assert st.stiffness == pytest.approx(6 * st.result.load * (1 - b) / ((2 - b) * C), rel=2e-6)
    assert st.stiffness == pytest.approx(6 * AREA * beta * PS * (1 - beta) / ((2 - beta) * C), rel=tol)


def test_constant_flow_recess_goes_as_h_cubed(pads):
    flow = 1e-6  # m^3/s
    mesh = pads["P2"]
    for h in (0.8, 1.0, 1.25):
        res = solve_supplied(mesh, UniformFilm(h), ConstantFlow(flow), SCALE, discretization=P2)
        assert res.pockets[0].pressure == pytest.approx(flow / (K * h**3), rel=TOL["P2"])
        assert res.pockets[0].film_flow == pytest.approx(flow, rel=1e-10)
    st = supply_stiffness(mesh, UniformFilm, 1.0, ConstantFlow(flow), SCALE, discretization=P2)
    # W ~ h^-3: the central difference's truncation error is (n + 1)(n + 2)/6 step^2 = 3.3e-6 for n = 3
    assert st.stiffness == pytest.approx(3 * st.result.load / C, rel=4e-6)


def _peak(beta: np.ndarray, k: np.ndarray) -> float:
    """The vertex of the parabola through three points."""
    a, b, _ = np.polyfit(beta, k, 2)
    return -b / (2 * a)


@pytest.mark.parametrize("kind, optimum, betas", [
    ("capillary", 0.5, (0.46, 0.5, 0.54)),
    ("orifice", 2 - math.sqrt(2), (0.55, 0.59, 0.63)),
])
def test_the_stiffest_recess_ratio(pads, kind, optimum, betas):
    # at fixed supply pressure and pad, the designs of three restrictors around the optimum: the vertex of
    # the parabola through their computed stiffnesses against the closed-form optimum (the parabola's
    # own error over +-0.04 is below 1e-3 for both laws: the cubic term of k(beta) is that small there)
    make = capillary_for if kind == "capillary" else orifice_for
    ratios, stiff = [], []
    for beta in betas:
        st = supply_stiffness(pads["P2"], UniformFilm, 1.0, make(beta), SCALE, discretization=P2)
        ratios.append(st.result.pockets[0].ratio)
        stiff.append(st.stiffness)
    assert _peak(np.array(ratios), np.array(stiff)) == pytest.approx(optimum, abs=2e-3)


# -- every cavitation model -------------------------------------------------------------------------

@pytest.mark.parametrize("element", ["P1", "P2"])
@pytest.mark.parametrize("cavitation", ["none", "reynolds", "gumbel"])
def test_every_finite_element_model_balances_the_pad(pads, cavitation, element):
    # no motion: the pressure is positive everywhere, so every model is the linear film
    res = solve_supplied(pads[element], UniformFilm(1.0), orifice_for(0.6), SCALE,
                         discretization=P2 if element == "P2" else P1, cavitation=cavitation)
    assert res.pockets[0].ratio == pytest.approx(0.6, rel=TOL[element])
    assert res.film.cavitation == cavitation


def test_jfo_balances_the_pad_through_the_front_door():
    # the finite-volume scheme (P1 on a straight-sided mesh) holds the one pocket at the balanced pressure;
    # without motion its film is the P1 Galerkin film (the same numbers: the ratio's error measured 3.0e-3,
    # 1.3e-3, 5.2e-4 at sizes 0.08, 0.04, 0.02 with either)
    surface = Surface(outer=Circle((0.0, 0.0), R), inlets=(Circle((0.0, 0.0), r),))
    mesh = mesh_surface(surface, 0.04, inlet_size=0.04 / 3, order=1)
    res = solve_supplied(mesh, UniformFilm(1.0), capillary_for(0.5), SCALE, discretization=P1, cavitation="jfo")
    pocket = res.pockets[0]
    assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-9)
    assert pocket.ratio == pytest.approx(0.5, rel=TOL["P1"])
    linear = solve_supplied(mesh, UniformFilm(1.0), capillary_for(0.5), SCALE, discretization=P1)
    assert pocket.pressure == pytest.approx(linear.pockets[0].pressure, rel=1e-9)
    assert res.film.cavitation == "jfo"


def test_jfo_balance_of_a_turning_pad_that_does_not_rupture_is_the_galerkin_one():
    # a tilted pad turning (wedge 1, gamma 0.15) over an orifice-fed pocket at 7.6 MPa: no node ruptures under
    # either model, so the JFO balance (finite-volume Couette fluxes) and the Swift-Stieber one (P1 Galerkin) differ
    # only by their discretizations, shrinking with the mesh: measured pocket pressure 1.3e-7, 3.7e-8 and load
    # 2.5e-6, 5.1e-7 relative at sizes 0.05, 0.025
    surface = Surface(arc=(-0.5, 0.5), half_width=0.3, inlets=(Circle((0.0, 0.0), 0.08),))
    orf = Orifice(diameter=0.2e-3, discharge_coefficient=CD, density=RHO, supply_pressure=8e6)
    op = OperatingPoint(wedge=1.0)
    diffs = []
    for size in (0.05, 0.025):
        mesh = mesh_surface(surface, size, inlet_size=size / 2.5, order=1)
        jfo = solve_supplied(mesh, CosineFilm(0.15, 0.3), orf, SCALE, operating=op, cavitation="jfo", discretization=P1)
        ss = solve_supplied(mesh, CosineFilm(0.15, 0.3), orf, SCALE, operating=op, cavitation="reynolds",
                            discretization=P1)
        assert jfo.film.cavitated_fraction == 0.0 and not ss.film.cavitated.any()
        assert jfo.pockets[0].restrictor_flow == pytest.approx(jfo.pockets[0].film_flow, rel=1e-9)
        diffs.append((abs(jfo.pockets[0].pressure / ss.pockets[0].pressure - 1), abs(jfo.load / ss.load - 1)))
    (p0, w0), (p1, w1) = diffs
    assert p1 < 1e-7 and w1 < 1e-6
    assert p0 / p1 > 2 and w0 / w1 > 2  # the difference shrinks with the mesh


def test_jfo_balances_a_cavitating_pad_and_conserves_its_mass():
    # a tilted pad turning over an orifice-fed pocket: JFO ruptures 46 % of the film. The pocket pressure is
    # found by the Newton-Broyden iteration on it (each evaluation one JFO solve): the orifice's flow equals
    # the film's outflow from the pocket to the iteration's tolerance (1e-11 of the flow), and the finite-volume
    # scheme conserves mass, so that flow leaves through the pad's edges to round-off (measured 1e-14 relative)
    surface = Surface(arc=(-0.5, 0.5), half_width=0.3, inlets=(Circle((0.0, 0.0), 0.08),))
    mesh = mesh_surface(surface, 0.05, inlet_size=0.02, order=1)
    orf = Orifice(diameter=0.1e-3, discharge_coefficient=CD, density=RHO, supply_pressure=2e6)
    res = solve_supplied(mesh, CosineFilm(0.8, 0.3), orf, SCALE, operating=OperatingPoint(wedge=1.0),
                         cavitation="jfo", discretization=P1)
    assert res.film.cavitation == "jfo"
    assert 0.3 < res.film.cavitated_fraction < 0.6
    pocket = res.pockets[0]
    assert 0 < pocket.pressure < 2e6
    assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-9)
    edges = sum(v for k, v in res.film.flows.items() if k in ("side", "arc_start", "arc_end"))
    assert SCALE.to_flow(edges) == pytest.approx(pocket.restrictor_flow, rel=1e-11)
    # mass conservation moves the balance: on the Swift-Stieber film the pocket sits 30 % higher
    ss = solve_supplied(mesh, CosineFilm(0.8, 0.3), orf, SCALE, operating=OperatingPoint(wedge=1.0),
                        cavitation="reynolds", discretization=P1)
    assert abs(ss.pockets[0].pressure - pocket.pressure) > 0.1 * pocket.pressure


@pytest.mark.parametrize("cavitation", ["reynolds", "gumbel"])
def test_a_wedge_under_cavitation_is_balanced_with_the_film(cavitation):
    # a tilted pad turning: the film ruptures where it diverges; the pocket pressure is iterated with the
    # cavitation solve until the orifice's flow equals the film's outflow from the pocket
    surface = Surface(arc=(-0.5, 0.5), half_width=0.3, inlets=(Circle((0.0, 0.0), 0.08),))
    mesh = mesh_surface(surface, 0.05, inlet_size=0.02, order=2)
    op = OperatingPoint(wedge=1.0)
    orf = Orifice(diameter=0.1e-3, discharge_coefficient=CD, density=RHO, supply_pressure=2e6)
    res = solve_supplied(mesh, CosineFilm(0.8, 0.3), orf, SCALE, operating=op, cavitation=cavitation,
                         discretization=P2)
    assert res.film.cavitated is not None and res.film.cavitated.any()
    pocket = res.pockets[0]
    assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-8)
    # the film at that pocket pressure through the front door: the same answer
    p_nd = SCALE.from_pressure(pocket.pressure)
    ref = solve_reynolds(mesh, CosineFilm(0.8, 0.3), wedge=1.0, inlet_pressure=p_nd, cavitation=cavitation,
                         discretization=P2)
    assert SCALE.to_flow(ref.flows["inlet"]) == pytest.approx(pocket.film_flow, rel=1e-9)
    assert res.film.integral == pytest.approx(ref.integral, rel=1e-9)
    np.testing.assert_allclose(res.film.force, ref.force, rtol=1e-9)


# -- several pockets -------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def twin():
    surface = Surface(outer=Circle((0.0, 0.0), R), inlets=(Circle((-0.18, 0.0), 0.07), Circle((0.18, 0.0), 0.07)))
    return mesh_surface(surface, 0.05, inlet_size=0.02, order=2)


def test_pocket_fields_are_reciprocal_and_conserve_mass(twin):
    # the film's conductance is symmetric (the Reynolds operator is self-adjoint), a pocket at pressure
    # draws from the other (G_01 < 0), and with both at unit pressure the pocket flows are the front door's
    assert pocket_names(twin) == ("inlet_0", "inlet_1")
    pf = pocket_film(twin, UniformFilm(1.0), P2)
    U = np.column_stack([s.fields[:, 3] for s in pf.pockets])
    G = pocket_flows(pf, U, np.array([[0, 0], [0, 0], [0, 0], [1.0, 1.0]]))
    assert G[0, 1] == pytest.approx(G[1, 0], rel=1e-8)
    assert G[0, 1] < 0 < G[0, 0]
    whole = solve_reynolds(twin, UniformFilm(1.0), wedge=0.0, inlet_pressure=1.0, discretization=P2)
    assert G.sum() == pytest.approx(whole.flows["inlet"], rel=1e-10)


@pytest.mark.parametrize("formulation", ["direct", "pi"])
def test_equal_prescribed_pockets_are_the_front_doors_film(twin, formulation):
    # every pocket prescribed at one pressure: the front door's problem, to round-off (both formulations:
    # the pi form's pocket data are h^(3/2) p)
    p = 3e6
    disc = Discretization(element="P2", formulation=formulation)
    res = solve_supplied(twin, CosineFilm(0.3), PrescribedPressure(p), SCALE, discretization=disc,
                         operating=OperatingPoint(wedge=1.0, squeeze=(0.1, 0.0)))
    ref = solve_reynolds(twin, CosineFilm(0.3), wedge=1.0, squeeze=(0.1, 0.0), inlet_pressure=SCALE.from_pressure(p),
                         discretization=disc)
    assert res.film.formulation == formulation
    assert res.film.integral == pytest.approx(ref.integral, rel=1e-10)
    np.testing.assert_allclose(res.film.force, ref.force, rtol=1e-10)
    assert res.total_flow == pytest.approx(SCALE.to_flow(ref.flows["inlet"]), rel=1e-10)


def test_two_pockets_each_its_own_restrictor(twin):
    # a capillary and a prescribed pocket: the capillary pocket sits where its restrictor's flow is the film's
    caps = [capillary_for(0.5), PrescribedPressure(2e6)]
    res = solve_supplied(twin, UniformFilm(1.0), caps, SCALE, discretization=P2)
    a, b = res.pockets
    assert (a.kind, b.kind) == ("capillary", "pressure")
    assert b.pressure == 2e6
    assert a.restrictor_flow == pytest.approx(a.film_flow, rel=1e-10)
    assert res.total_flow == pytest.approx(SCALE.to_flow(res.film.flows["inlet"]), rel=1e-9)
    # the pressure field holds each pocket at its own pressure
    assert res.film.interpolate(np.array([-0.18 + 0.07]), np.array([0.0]))[0] == pytest.approx(
        SCALE.from_pressure(a.pressure), rel=1e-6)
    assert res.film.interpolate(np.array([0.18 - 0.07]), np.array([0.0]))[0] == pytest.approx(
        SCALE.from_pressure(b.pressure), rel=1e-6)
    # symmetric twin capillaries sit at one pressure (to the mesh's asymmetry)
    sym = solve_supplied(twin, UniformFilm(1.0), capillary_for(0.5), SCALE, discretization=P2)
    assert sym.pockets[0].pressure == pytest.approx(sym.pockets[1].pressure, rel=1e-4)


def test_several_pockets_under_cavitation(twin):
    # a wedge over the twin pockets under Swift-Stieber, each pocket through its own orifice
    op = OperatingPoint(wedge=1.0)
    orfs = [Orifice(diameter=d, discharge_coefficient=CD, density=RHO, supply_pressure=2e6) for d in (0.1e-3, 0.2e-3)]
    film = CosineFilm(0.8, 1.5)
    res = solve_supplied(twin, film, orfs, SCALE, operating=op, cavitation="reynolds", discretization=P2)
    assert 0.2 < np.mean(res.film.cavitated) < 0.4  # a quarter of the film ruptured
    for pocket in res.pockets:
        assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-8)
        assert 0 < pocket.pressure < 2e6
    assert res.total_flow == pytest.approx(SCALE.to_flow(res.film.flows["inlet"]), rel=1e-9)
    # the pockets' film state under cavitation, both prescribed at one pressure: the front door's answer
    p = res.pockets[0].pressure
    for disc in (P2, Discretization(element="P2", formulation="pi")):
        same = solve_supplied(twin, film, PrescribedPressure(p), SCALE, operating=op, cavitation="reynolds",
                              discretization=disc)
        ref = solve_reynolds(twin, film, wedge=1.0, inlet_pressure=SCALE.from_pressure(p), cavitation="reynolds",
                             discretization=disc)
        assert same.film.formulation == ref.formulation == disc.formulation
        assert same.film.integral == pytest.approx(ref.integral, rel=1e-10)
        np.testing.assert_allclose(same.film.force, ref.force, rtol=1e-10)
        assert same.total_flow == pytest.approx(SCALE.to_flow(ref.flows["inlet"]), rel=1e-10)


# -- what is refused -----------------------------------------------------------------------------------

def test_an_orifice_that_cannot_feed_the_film_is_an_error(pads):
    # the surfaces separating fast: the film draws more from the recess at p_r = 0 than the orifice feeds
    op = OperatingPoint(wedge=0.0, squeeze=(50.0, 0.0))
    with pytest.raises(SupplyError, match="no solution with p_r >= 0"):
        solve_supplied(pads["P2"], UniformFilm(1.0), orifice_for(0.5), SCALE, discretization=P2, operating=op)


def test_the_wrong_number_of_supplies_is_named(twin):
    with pytest.raises(ValueError, match="one supply per pocket"):
        solve_supplied(twin, UniformFilm(1.0), [capillary_for(0.5)], SCALE)


def test_an_elastic_pad_is_balanced_on_the_coupled_film(pads):
    # rigid limit (E* = inf): the rigid answer to the coupled solver's tolerance; a soft pad opens the film
    # under the recess pressure, lets more oil out and so settles at a lower recess pressure
    from bearingfe import half_space
    mesh = pads["P1"]
    cap = capillary_for(0.5)
    rigid = solve_supplied(mesh, UniformFilm(1.0), cap, SCALE, discretization=P1)
    stiff = solve_supplied(mesh, UniformFilm(1.0), cap, SCALE, discretization=P1,
                           elastic=half_space(mesh, SCALE, math.inf, "P1"))
    assert stiff.pockets[0].pressure == pytest.approx(rigid.pockets[0].pressure, rel=1e-9)
    soft = solve_supplied(mesh, UniformFilm(1.0), cap, SCALE, discretization=P1,
                          elastic=half_space(mesh, SCALE, 2e9, "P1"))
    pocket = soft.pockets[0]
    assert soft.film.max_deflection > 0.05  # the film opens by more than 5 % of the clearance
    assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-8)
    assert pocket.pressure < 0.99 * rigid.pockets[0].pressure


# -- several pockets on the finite-volume scheme and on the elastic support ---------------------------

@pytest.fixture(scope="module")
def twin_p1():
    # a turning pad with two pockets side by side along phi (straight-sided: the finite-volume scheme's mesh)
    surface = Surface(arc=(-0.6, 0.6), half_width=0.3, inlets=(Circle((-0.25, 0.0), 0.07), Circle((0.25, 0.0), 0.07)))
    return mesh_surface(surface, 0.05, inlet_size=0.02, order=1)


def test_each_pocket_at_its_own_pressure_through_the_front_door(twin_p1):
    # one value per pocket (a sequence in pocket order or a mapping): the same film on the Galerkin and the
    # finite-volume paths; equal values are the scalar's film to round-off; each pocket's outflow is booked
    # under its name and they add up to the total
    film = CosineFilm(0.3, 0.3)
    for cavitation in ("none", "reynolds", "jfo"):
        seq = solve_reynolds(twin_p1, film, wedge=1.0, inlet_pressure=(2.0, 5.0), cavitation=cavitation,
                             discretization=P1)
        named = solve_reynolds(twin_p1, film, wedge=1.0, inlet_pressure={"inlet_1": 5.0, "inlet_0": 2.0},
                               cavitation=cavitation, discretization=P1)
        assert seq.integral == named.integral and seq.inlet_pressure == 5.0
        assert seq.flows["inlet_0"] + seq.flows["inlet_1"] == pytest.approx(seq.flows["inlet"], rel=1e-12)
        assert seq.flows["inlet_0"] < seq.flows["inlet_1"]
        same = solve_reynolds(twin_p1, film, wedge=1.0, inlet_pressure=(3.0, 3.0), cavitation=cavitation,
                              discretization=P1)
        ref = solve_reynolds(twin_p1, film, wedge=1.0, inlet_pressure=3.0, cavitation=cavitation, discretization=P1)
        assert same.integral == pytest.approx(ref.integral, rel=1e-12)
        np.testing.assert_allclose(same.force, ref.force, rtol=1e-12)
        assert same.flows["inlet"] == pytest.approx(ref.flows["inlet"], rel=1e-12)
    fe = solve_reynolds(twin_p1, film, wedge=1.0, inlet_pressure=(2.0, 5.0), discretization=P1)
    # the two schemes differ by their discretizations only (no rupture): 1e-7 on this mesh
    assert seq.integral == pytest.approx(fe.integral, rel=1e-6)


@pytest.mark.parametrize("value, fragment", [((1.0,), "one value per pocket"), ((1.0, 2.0, 3.0), "one value per pocket"),
                                             ({"inlet_0": 1.0}, "missing"), ({"inlet_0": 1.0, "inlet_1": 1.0, "x": 1.0}, "unknown"),
                                             ((1.0, math.nan), "inlet_pressure")])
def test_a_bad_pressure_per_pocket_is_named(twin_p1, value, fragment):
    with pytest.raises(ValueError, match=fragment):
        solve_reynolds(twin_p1, UniformFilm(1.0), wedge=0.0, inlet_pressure=value, discretization=P1)


def test_two_pockets_under_jfo_without_rupture_are_the_galerkin_balance(twin_p1):
    # two orifices of different bores over a turning, tilted pad (8 MPa supply): no node ruptures, so the JFO
    # balance (finite-volume fluxes, the n-pocket Newton-Broyden iteration on solve_reynolds) and the Galerkin one
    # (superposition of the pockets' unit fields) differ by their discretizations only: measured 1.1e-7 and
    # 2.7e-8 in the pocket pressures and 9e-7 in the load on this mesh (the one-pocket test's order); the bounds
    # leave a factor 4
    op = OperatingPoint(wedge=1.0)
    orfs = [Orifice(diameter=d, discharge_coefficient=CD, density=RHO, supply_pressure=8e6) for d in (0.15e-3, 0.25e-3)]
    jfo = solve_supplied(twin_p1, CosineFilm(0.15, 0.3), orfs, SCALE, operating=op, cavitation="jfo", discretization=P1)
    fe = solve_supplied(twin_p1, CosineFilm(0.15, 0.3), orfs, SCALE, operating=op, discretization=P1)
    assert jfo.film.cavitation == "jfo" and jfo.film.cavitated_fraction == 0.0
    np.testing.assert_allclose(jfo.pressures, fe.pressures, rtol=5e-7)
    assert jfo.load == pytest.approx(fe.load, rel=4e-6)
    assert jfo.pressures[0] < jfo.pressures[1] < 8e6  # the smaller bore feeds less: its pocket sits lower
    for pocket in jfo.pockets:
        assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-9)


def test_two_pockets_under_jfo_with_rupture_each_balance_their_flow(twin_p1):
    # a strongly tilted pad at a 2 MPa supply: JFO ruptures part of the film. Each pocket's orifice flow equals its
    # own film outflow to the iteration's tolerance (1e-11 of the largest restrictor flow), and the scheme carries
    # all of it out through the pad's edges to round-off
    op = OperatingPoint(wedge=1.0)
    orfs = [Orifice(diameter=d, discharge_coefficient=CD, density=RHO, supply_pressure=2e6) for d in (0.1e-3, 0.15e-3)]
    res = solve_supplied(twin_p1, CosineFilm(0.8, 0.3), orfs, SCALE, operating=op, cavitation="jfo", discretization=P1)
    assert res.film.cavitated_fraction > 0.2
    for pocket in res.pockets:
        assert 0 < pocket.pressure < 2e6
        assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-9)
    edges = sum(v for k, v in res.film.flows.items() if k in ("side", "arc_start", "arc_end"))
    assert SCALE.to_flow(edges) == pytest.approx(sum(p.restrictor_flow for p in res.pockets), rel=1e-11)


def test_two_pockets_on_the_elastic_support_tend_to_the_rigid_balance(twin_p1):
    # each pocket's opening is the half-space's over its own contour (the two add up to the compliance's
    # opening under both); as E* grows the balance tends to the rigid one as 1/E* (the opening is C p, a
    # perturbation of the film of order 1/E*: measured 2.3e-2 and 2.3e-3 of the pocket pressures at 2e11 and 2e12 Pa)
    from bearingfe import half_space
    from bearingfe.elastic.coupled import pocket_deflections
    caps = [capillary_for(0.4), capillary_for(0.6)]
    film = CosineFilm(0.3, 0.3)
    op = OperatingPoint(wedge=1.0)
    rigid = solve_supplied(twin_p1, film, caps, SCALE, operating=op, discretization=P1)
    gaps = []
    for modulus in (2e11, 2e12):
        compliance = half_space(twin_p1, SCALE, modulus, "P1")
        columns = pocket_deflections(compliance, pocket_names(twin_p1))
        np.testing.assert_allclose(columns.sum(axis=1), compliance.pocket, rtol=1e-12, atol=1e-15)
        soft = solve_supplied(twin_p1, film, caps, SCALE, operating=op, discretization=P1, elastic=compliance)
        for pocket in soft.pockets:
            assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-8)
        gaps.append(np.max(np.abs(soft.pressures / rigid.pressures - 1)))
    assert 1e-3 < gaps[1] < 1e-2  # measured 2.3e-3 at E* = 2e12 Pa
    assert gaps[0] / gaps[1] == pytest.approx(10.0, rel=0.1)  # first order in 1/E*


# -- the pump's shoe fed from its chamber ([shoe.supply]) -----------------------------------------------

def test_the_shipped_pump_keeps_its_prescribed_pocket():
    pump = load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    assert pump.shoe_supply is None
    assert pump.pocket_supply(32e6) == PrescribedPressure(32e6)


def test_the_orifice_pump_feeds_its_pocket_through_the_plunger():
    pump = load_mechanism(ROOT / "mechanisms" / "eccentric_pump_orifice.toml")
    assert pump.shoe_supply == Restrictor("orifice", 0.1e-3, discharge_coefficient=0.7, density=870.0,
                                          pocket_volume=2.4e-7, bulk_modulus=1.5e9)
    assert pump.pocket_supply(32e6) == Orifice(diameter=0.1e-3, discharge_coefficient=0.7, density=870.0,
                                               supply_pressure=32e6)
    # at discharge, near the cycle's film state (gamma 0.54, delta 3.64 rad: the shoe's steady state at 90 deg,
    # thinnest film over the pocket): the pocket settles below the chamber pressure; where the film is thick over
    # the pocket (delta = 0) the orifice cannot keep up and the pocket drops far below it
    mesh = mesh_surface(pump.surface, 0.15, order=2)
    ratios = []
    for film in (CosineFilm(0.5, math.pi), CosineFilm(0.6, 0.0)):
        res = solve_supplied(mesh, film, pump.pocket_supply(pump.cycle.discharge), pump.scale,
                             operating=OperatingPoint(wedge=1.0), cavitation="reynolds", discretization=P2)
        pocket = res.pockets[0]
        assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-8)
        ratios.append(pocket.ratio)
    assert 0.8 < ratios[0] < 0.95 and 0.0 < ratios[1] < 0.2


@pytest.mark.parametrize("make, fragment", [
    (lambda: Restrictor("nozzle", 1e-3), "Restrictor.kind must be one of ('capillary', 'orifice')"),
    (lambda: Restrictor("orifice", 1e-3, discharge_coefficient=0.7), "Restrictor.density is required"),
    (lambda: Restrictor("capillary", 1e-3, length=0.02, density=870.0), "Restrictor.density is not taken"),
    (lambda: Restrictor("capillary", -1e-3, length=0.02), "Capillary.diameter must be > 0 m"),
    (lambda: Restrictor("capillary", 1e-3, length=0.02, pocket_volume=0.0), "Restrictor.pocket_volume must be > 0"),
    (lambda: Restrictor("capillary", 1e-3, length=0.02, bulk_modulus=-1.0), "Restrictor.bulk_modulus must be > 0"),
])
def test_a_bad_restrictor_is_named(make, fragment):
    with pytest.raises(ValueError, match=fragment.replace("(", r"\(").replace(")", r"\)")):
        make()


@pytest.mark.parametrize("new, fragment", [
    ('kind = "nozzle"', '[shoe.supply] kind: must be one of'),
    ('kind = "orifice"\ndiameter = 0.4e-3\ndensity = 870.0', "[shoe.supply] Restrictor.discharge_coefficient is required"),
    ('kind = "capillary"\nlength = 0.02', "[shoe.supply] diameter: missing (required by kind = 'capillary')"),
    ('diameter = 0.4e-3', "[shoe.supply] diameter: not taken by kind = 'pressure'"),
    ('kind = "orifice"\ndiameter = 0.4e-3\ndischarge_coefficient = 1.5\ndensity = 870.0',
     "[shoe.supply] Orifice.discharge_coefficient must be in (0, 1]"),
    ('kind = "capillary"\ndiameter = 0.4e-3\nlength = 0.02\nbore = 1', "[shoe.supply] bore: unknown field"),
])
def test_shoe_supply_errors_name_the_table(tmp_path, new, fragment):
    text = (ROOT / "mechanisms" / "eccentric_pump.toml").read_text(encoding="utf-8")
    old = "[shoe.seat]"
    path = tmp_path / "bad.toml"
    path.write_text(text.replace(old, "[shoe.supply]\n" + new + "\n\n" + old), encoding="utf-8")
    with pytest.raises(SchemaError) as info:
        load_mechanism(path)
    assert "bad.toml" in str(info.value) and fragment in str(info.value)


# -- the pockets' compressibility --------------------------------------------------------------------------

def test_a_capillary_recess_fills_with_its_closed_form_time_constant(pads):
    # V/K dp/dt = Kc (p_s - p) - K h^3 p: p = p_inf (1 - exp(-t/tau)), tau = V / (K_oil (Kc + K h^3)),
    # p_inf = beta p_s; with the capillary sized for beta = 0.5, Kc = K: tau = V / (2 K_oil K)
    from bearingfe.bearings.hydrostatic import pocket_transient
    volume, bulk = 2e-7, 1.5e9  # [m^3], [Pa]
    tau = volume / (bulk * 2 * K)
    times = np.linspace(0.0, 4 * tau, 9)
    tr = pocket_transient(pads["P2"], UniformFilm(1.0), capillary_for(0.5), SCALE, volumes=volume,
                          bulk_modulus=bulk, times=times, discretization=P2)
    assert tr.time_constants[0] == pytest.approx(tau, rel=TOL["P2"])
    # against the exponential with the computed balance and time constant: the integrator's error only
    p_inf, tau_h = tr.balanced.pockets[0].pressure, tr.time_constants[0]
    np.testing.assert_allclose(tr.pressures[:, 0], p_inf * (1 - np.exp(-times / tau_h)), rtol=1e-7, atol=1e-3)
    # and against the closed form outright (the mesh's error of beta and of K)
    np.testing.assert_allclose(tr.pressures[:, 0], 0.5 * PS * (1 - np.exp(-times / tau)), rtol=TOL["P2"],
                               atol=1e-3)


def test_an_orifice_recess_settles_at_its_balance(pads):
    # nonlinear: no closed form of the path, but the end is the balance and the small-signal time constant is
    # V / (K_oil (C/(2 sqrt(p_s - p_r)) + K h^3)) at the balance (linearised orifice law)
    from bearingfe.bearings.hydrostatic import pocket_transient
    volume, bulk = 2e-7, 1.5e9
    orf = orifice_for(0.6)
    c_si = CD * math.pi * orf.diameter**2 / 4 * math.sqrt(2 / RHO)
    tau = volume / (bulk * (c_si / (2 * math.sqrt(0.4 * PS)) + K))
    tr = pocket_transient(pads["P2"], UniformFilm(1.0), orf, SCALE, volumes=volume, bulk_modulus=bulk,
                          times=np.linspace(0.0, 20 * tau, 5), initial=0.9 * PS, discretization=P2)
    assert tr.time_constants[0] == pytest.approx(tau, rel=TOL["P2"])
    assert tr.pressures[-1, 0] == pytest.approx(tr.balanced.pockets[0].pressure, rel=1e-7)
    assert tr.pressures[0, 0] == 0.9 * PS


# -- dynamics: the pad's normal motion linearised ------------------------------------------------------------
#
# Squeeze of the annulus r < rho < R with both edges at 0 (the recess held: a rigid supply) from
# d/drho (rho h^3/(12 mu) dp/drho) = rho dh/dt: the load -B dh/dt with
#     B = 3 pi mu / (2 h^3) (R^4 - r^4 - (R^2 - r^2)^2 / ln(R/r)),
# and the squeeze's outflow from the recess plus the recess's own gap opening pi r^2 dh/dt adds up to
# AREA dh/dt (AREA = W/p_r, the effective area). Fed through a restrictor of slope k_r
# (V/K dp/dt = Q_r(p) - K h^3 p - AREA dh/dt), a small motion h_hat exp(i w t) gives
#     Z = -dW/h_hat = AREA (3 K h^2 p_r / c + i w AREA) / (k_r + K h^3 + i w V/K) + i w B
# (h in units of c; capillary k_r = Kc, orifice k_r = K h^3 beta / (2 (1 - beta))). Mesh errors measured at
# size 0.05: P2 1.6e-5 on B, 3e-6 on the fed damping, 8e-6 on the stiffness; P1 1.6e-2 on B (hence 2e-2 there).

B_SQUEEZE = 3 * math.pi * MU / (2 * C**3) * ((R * SCALE.radius) ** 4 - (r * SCALE.radius) ** 4
                                            - ((R * SCALE.radius) ** 2 - (r * SCALE.radius) ** 2) ** 2 / LOG)
DYN_TOL = {"P1": 2e-2, "P2": 5e-5}


def closed_form_z(w: np.ndarray, k_r: float, beta: float, compliance: float = 0.0) -> np.ndarray:
    """The recess pad's dynamic stiffness Z(w) [N/m] at h = 1 (the derivation above)."""
    return AREA * (3 * K * beta * PS / C + 1j * w * AREA) / (k_r + K + 1j * w * compliance) + 1j * w * B_SQUEEZE


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_a_rigid_supply_damps_as_the_squeeze_film_closed_form(pads, element):
    from bearingfe.bearings.hydrostatic import supply_dynamics
    disc = P2 if element == "P2" else P1
    dyn = supply_dynamics(pads[element], 1.0, PrescribedPressure(0.5 * PS), SCALE, frequencies=(0.0, 100.0, 1e4),
                          discretization=disc)
    np.testing.assert_allclose(dyn.damping, B_SQUEEZE, rtol=DYN_TOL[element])
    assert dyn.squeeze_damping == pytest.approx(B_SQUEEZE, rel=DYN_TOL[element])
    # the held recess does not move and the flat pad's load does not depend on h at fixed pressures: no stiffness
    # (the central difference of equal loads: round-off, below 1e-9 of the fed recess's 3 W (1 - beta)/h)
    assert np.all(np.abs(dyn.stiffness) < 1e-9 * 3 * AREA * 0.5 * PS / C)
    assert np.all(dyn.pressure_response == 0) and np.all(dyn.result.pockets[0].damping == 0)


def test_a_capillary_fed_compressible_recess_against_its_closed_form(pads):
    from bearingfe.bearings.hydrostatic import supply_dynamics
    volume, bulk = 1e-7, 1.5e9
    w = np.array([0.0, 10.0, 1e3, 1e5])  # [rad/s]: up to past the pocket's corner (k_r + G) K/V = 1.6e4 rad/s
    supply = capillary_for(0.5)
    dyn = supply_dynamics(pads["P2"], 1.0, supply, SCALE, frequencies=w, volumes=volume, bulk_modulus=bulk,
                          discretization=P2)
    z = closed_form_z(w, K, 0.5, volume / bulk)
    slow = B_SQUEEZE + AREA**2 / (2 * K) - AREA * volume / bulk * 3 * K * 0.5 * PS / C / (2 * K) ** 2  # d Im Z/dw
    np.testing.assert_allclose(dyn.stiffness, z.real, rtol=1e-4)
    np.testing.assert_allclose(dyn.damping, np.r_[slow, z.imag[1:] / w[1:]], rtol=1e-4)
    # the restrictor's slow damping (A^2/(Kc + G)) is 0.85 of the squeeze film's; the oil's compressibility takes
    # it back towards B at speed
    assert dyn.damping[0] > 1.8 * B_SQUEEZE and dyn.damping[-1] < 1.01 * B_SQUEEZE
    # per pocket: its share and the film's add up to the whole; its state is the balance (beta = 0.5)
    pocket = dyn.result.pockets[0]
    np.testing.assert_allclose(pocket.stiffness + dyn.film_stiffness, dyn.stiffness, rtol=1e-12)
    np.testing.assert_allclose(pocket.damping + dyn.squeeze_damping, dyn.damping, rtol=1e-12)
    assert pocket.pressure == pytest.approx(0.5 * PS, rel=TOL["P2"])
    assert pocket.restrictor_flow == pytest.approx(pocket.film_flow, rel=1e-10)
    # incompressible: the slow stiffness is the static one of supply_stiffness's closed form 3 W (1 - beta)/h
    rigid = supply_dynamics(pads["P2"], 1.0, supply, SCALE, discretization=P2)
    assert rigid.stiffness[0] == pytest.approx(3 * AREA * 0.5 * PS * 0.5 / C, rel=1e-4)
    assert rigid.damping[0] == pytest.approx(B_SQUEEZE + AREA**2 / (2 * K), rel=1e-4)


@pytest.mark.parametrize("element", ["P1", "P2"])
def test_an_orifice_fed_recess_slow_stiffness_and_damping(pads, element):
    from bearingfe.bearings.hydrostatic import supply_dynamics
    beta = 0.6
    disc = P2 if element == "P2" else P1
    dyn = supply_dynamics(pads[element], 1.0, orifice_for(beta), SCALE, discretization=disc)
    k_r = K * beta / (2 * (1 - beta))
    assert dyn.stiffness[0] == pytest.approx(6 * AREA * beta * PS * (1 - beta) / ((2 - beta) * C),
                                             rel=max(TOL[element], 1e-4))
    assert dyn.damping[0] == pytest.approx(B_SQUEEZE + AREA**2 / (k_r + K), rel=DYN_TOL[element])


def test_the_linearisation_is_the_small_harmonic_motion_of_the_transient(pads):
    # the nonlinear rate equation of the capillary-fed recess (closed-form film: Q = K h^3 p, W = AREA p - B/h^3
    # dh/dt, the pocket's demand AREA dh/dt) driven by h = 1 + eps sin(w t): the first harmonic of the load over a
    # settled period is -Z eps (linear response; the quadratic terms are O(eps) relative: eps = 1e-4)
    from scipy.integrate import solve_ivp

    from bearingfe.bearings.hydrostatic import supply_dynamics
    volume, bulk, eps, w = 1e-7, 1.5e9, 1e-4, 2e3
    kc = K  # beta = 0.5

    def hdot(t):
        return C * eps * w * math.cos(w * t)

    def rhs(t, y):
        h = 1 + eps * math.sin(w * t)
        return [bulk / volume * (kc * (PS - y[0]) - K * h**3 * y[0] - AREA * hdot(t))]

    tau = volume / (bulk * 2 * K)
    period = 2 * math.pi / w
    t0 = max(30 * tau, 3 * period)
    t = t0 + np.linspace(0.0, period, 257)[:-1]
    sol = solve_ivp(rhs, (0.0, t[-1]), [0.5 * PS], t_eval=t, method="Radau", rtol=1e-11, atol=1e-6)
    h = 1 + eps * np.sin(w * t)
    load = AREA * sol.y[0] - B_SQUEEZE / h**3 * np.array([hdot(tt) for tt in t])
    phase = np.exp(-1j * w * t)
    # the motion eps c sin(w t) = Re(-i eps c exp(i w t)) [m], so the load's harmonic 2 mean(W exp(-i w t)) is
    # -Z (-i eps c)
    z_transient = -1j * 2 * np.mean(load * phase) / (eps * C)
    dyn = supply_dynamics(pads["P2"], 1.0, capillary_for(0.5), SCALE, frequencies=(w,), volumes=volume,
                          bulk_modulus=bulk, discretization=P2)
    z = dyn.stiffness[0] + 1j * w * dyn.damping[0]
    assert z_transient == pytest.approx(z, rel=1e-4)  # measured 7.5e-6 (the mesh's error and O(eps))
    assert z == pytest.approx(closed_form_z(np.array([w]), K, 0.5, volume / bulk)[0], rel=1e-4)


def test_bad_dynamics_arguments_are_named(pads):
    from bearingfe.bearings.hydrostatic import supply_dynamics
    with pytest.raises(ValueError, match="frequencies"):
        supply_dynamics(pads["P1"], 1.0, capillary_for(0.5), SCALE, frequencies=(-1.0,))
    with pytest.raises(ValueError, match="h must be larger than step"):
        supply_dynamics(pads["P1"], 1e-3, capillary_for(0.5), SCALE)
    with pytest.raises(ValueError, match="volumes"):
        supply_dynamics(pads["P1"], 1.0, capillary_for(0.5), SCALE, volumes=-1.0)


def test_two_fed_pockets_share_the_dynamics(twin):
    # two equal pockets symmetric about z: each through an equal capillary they respond alike (to the mesh's
    # asymmetry), their shares and the film's add up to the whole; a pocket held at its pressure takes no share
    from bearingfe.bearings.hydrostatic import supply_dynamics
    cap = Capillary(diameter=0.4e-3, length=0.05, supply_pressure=PS)
    dyn = supply_dynamics(twin, 1.0, cap, SCALE, frequencies=(0.0, 1e3), volumes=1e-7, discretization=P2)
    a, b = dyn.result.pockets
    np.testing.assert_allclose(a.damping, b.damping, rtol=1e-2)
    np.testing.assert_allclose(a.stiffness, b.stiffness, rtol=1e-2)
    np.testing.assert_allclose(a.damping + b.damping + dyn.squeeze_damping, dyn.damping, rtol=1e-12)
    np.testing.assert_allclose(a.stiffness + b.stiffness + dyn.film_stiffness, dyn.stiffness, rtol=1e-12)
    assert np.all(dyn.stiffness > 0) and np.all(dyn.damping > dyn.squeeze_damping) and dyn.squeeze_damping > 0
    mixed = supply_dynamics(twin, 1.0, [PrescribedPressure(0.5 * PS), cap], SCALE, discretization=P2)
    held, fed = mixed.result.pockets
    assert held.damping[0] == 0.0 and held.stiffness[0] == 0.0 and fed.damping[0] > 0


# -- a journal's stiffness and damping with its pockets responding (journal_dynamics) ---------------------------

JOURNAL_AT = (0.2, -0.1)  # the journal centre's displacement [c] over the twin-pocket pad


def journal_caps():
    return [Capillary(diameter=0.3e-3, length=20e-3, supply_pressure=5e6),
            Capillary(diameter=0.3e-3, length=30e-3, supply_pressure=5e6)]


def test_journal_stiffness_of_slow_motion_is_the_slope_of_the_balanced_force(twin_p1):
    # omega -> 0: the linearised support's stiffness is d(force)/d(x, y) of the balanced support at fixed supply;
    # the reference is a central difference of solve_supplied at x +- 1e-3 c in each direction, whose truncation
    # error is O(1e-6) relative (the force's curvature over 1e-3 c; measured 1.8e-6 against the linearisation)
    from bearingfe.bearings.hydrostatic import DisplacedJournal, journal_dynamics
    caps = journal_caps()
    dyn = journal_dynamics(twin_p1, JOURNAL_AT, caps, SCALE, frequencies=(0.0,), volumes=1e-7, discretization=P1)
    de, x0 = 1e-3, np.array(JOURNAL_AT)
    slope = np.zeros((2, 2))
    for j in range(2):
        e = np.eye(2)[j] * de
        up = solve_supplied(twin_p1, DisplacedJournal(*(x0 + e)), caps, SCALE, discretization=P1)
        down = solve_supplied(twin_p1, DisplacedJournal(*(x0 - e)), caps, SCALE, discretization=P1)
        slope[:, j] = (up.force - down.force) / (2 * de * SCALE.clearance)
    np.testing.assert_allclose(dyn.stiffness[0], slope, rtol=2e-5, atol=2e-5 * np.abs(slope).max())
    # the restrictors make the support stiff: the pockets' response is most of it (the held film alone is softer)
    assert dyn.stiffness[0][0, 0] > 5 * abs(dyn.film_stiffness[0, 0])


def test_journal_damping_with_held_pockets_is_the_films_squeeze(twin_p1):
    # prescribed pockets (a rigid supply): no pocket responds, the stiffness is the held film's and the damping the
    # film's own squeeze at every frequency; the reference is the front door's journal film (CosineFilm) with each
    # pocket held at its pressure and a unit squeeze rate: its force per unit gamma_rate and phi0_rate is the damping
    # applied to the centre's velocity -(cos phi0, sin phi0) and gamma (sin phi0, -cos phi0) (round-off)
    from bearingfe.bearings.hydrostatic import journal_dynamics
    held = journal_dynamics(twin_p1, JOURNAL_AT, journal_caps(), SCALE, discretization=P1)
    pres = [PrescribedPressure(p) for p in held.result.pressures]
    rigid = journal_dynamics(twin_p1, JOURNAL_AT, pres, SCALE, frequencies=(0.0, 100.0, 1e4), discretization=P1)
    for k in range(3):
        np.testing.assert_allclose(rigid.damping[k], rigid.squeeze_damping, rtol=1e-12)
        np.testing.assert_allclose(rigid.stiffness[k], rigid.film_stiffness, rtol=1e-12)
    gamma, phi0 = math.hypot(*JOURNAL_AT), math.atan2(-JOURNAL_AT[1], -JOURNAL_AT[0])
    pockets = tuple(SCALE.from_pressure(p) for p in held.result.pressures)
    film = CosineFilm(gamma, phi0)
    at_rest = solve_reynolds(twin_p1, film, wedge=0.0, inlet_pressure=pockets, discretization=P1).force
    per_time = SCALE.force / SCALE.speed / SCALE.clearance  # damping unit [N s/m]
    for rates, velocity in (((1.0, 0.0), -np.array([math.cos(phi0), math.sin(phi0)])),
                            ((0.0, 1.0), gamma * np.array([math.sin(phi0), -math.cos(phi0)]))):
        moved = solve_reynolds(twin_p1, film, wedge=0.0, squeeze=rates, inlet_pressure=pockets, discretization=P1)
        np.testing.assert_allclose(rigid.squeeze_damping / per_time @ velocity, moved.force - at_rest, rtol=1e-9)


def test_journal_pockets_of_infinite_volume_are_held(twin_p1):
    # V -> inf: the compressible pockets cannot change their pressure at omega > 0, the rigid-pocket limit; the
    # difference is of order (k_r + G) K / (omega V) (1e-9 here: V = 1000 m^3)
    from bearingfe.bearings.hydrostatic import journal_dynamics
    caps = journal_caps()
    big = journal_dynamics(twin_p1, JOURNAL_AT, caps, SCALE, frequencies=(100.0, 1000.0), volumes=1e3,
                           discretization=P1)
    for k in range(2):
        np.testing.assert_allclose(big.stiffness[k], big.film_stiffness, rtol=1e-6,
                                   atol=1e-6 * np.abs(big.film_stiffness).max())
        np.testing.assert_allclose(big.damping[k], big.squeeze_damping, rtol=1e-6,
                                   atol=1e-6 * np.abs(big.squeeze_damping).max())
    # a small pocket responds: slow motion draws on it, adding damping (the restrictor's share)
    small = journal_dynamics(twin_p1, JOURNAL_AT, caps, SCALE, frequencies=(0.0,), volumes=1e-9, discretization=P1)
    assert small.damping[0][0, 0] > 1.1 * small.squeeze_damping[0, 0]
    assert np.abs(small.pressure_response[0]).max() > 0
