"""The pump transient with the shoe pocket fed through the plunger's orifice (bearingfe.transient.fed).

References are the model's exact limits, each computed by another model or path:

- an orifice so wide that it drops nothing (3 mm: its pressure drop at the film's 0.1 l/min is ~1e-6 of
  the chamber pressure) is the rigid model with the pocket at the chamber pressure (measured: smallest film
  4.4e-5, pocket pressure 2.7e-6 relative, the difference of the integrators' paths);
- a pocket volume V -> 0 is the pocket balanced at each instant (no volume): the difference shrinks like V
  (measured 0.21, 0.011, 1.1e-3 on the smallest film for V = 2.4e-7, 2.4e-8, 2.4e-9 m^3), so 10x less
  volume must give about 10x less difference.

Coarse P2 mesh (0.3 R0) and 36 samples a revolution: each run takes about a second.
"""

import dataclasses

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.bearings.hydrostatic import Restrictor
from tests.helpers import ROOT

ORIFICE = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump_orifice.toml")
RIGID = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")


@pytest.fixture(scope="module")
def mesh():
    return bf.transient.pump_mesh(ORIFICE, 0.3, order=2)


def run(pump, mesh):
    return bf.simulate(pump, mesh, start="steady", points_per_revolution=36)


def with_supply(**changes):
    return dataclasses.replace(ORIFICE, shoe_supply=dataclasses.replace(ORIFICE.shoe_supply, **changes))


def test_a_wide_orifice_is_the_prescribed_pocket(mesh):
    wide = dataclasses.replace(ORIFICE, shoe_supply=Restrictor("orifice", 3e-3, discharge_coefficient=0.7,
                                                               density=870.0))
    fed, rigid = run(wide, mesh), run(RIGID, mesh)
    assert fed.status == rigid.status == "completed"
    np.testing.assert_allclose(fed.h_min, rigid.h_min, rtol=5e-4)
    np.testing.assert_allclose(fed.inlet_pressure, rigid.inlet_pressure, rtol=5e-5)


@pytest.mark.slow
def test_the_pocket_volume_vanishing_is_the_balanced_pocket(mesh):
    balanced = run(with_supply(pocket_volume=None), mesh)
    diffs = []
    for volume in (2.4e-8, 2.4e-9):
        tr = run(with_supply(pocket_volume=volume), mesh)
        assert tr.status == "completed"
        diffs.append(np.max(np.abs(tr.h_min / balanced.h_min - 1)))
    assert 5 < diffs[0] / diffs[1] < 20  # first order in V
    assert diffs[1] < 3e-3


def test_the_orifice_drops_the_pocket_below_the_chamber(mesh):
    # the shipped orifice pump: during discharge the pocket sits below the chamber pressure (the orifice's
    # drop feeds the film), so the pocket lifts less and the film is thinner than with the prescribed pocket
    fed, rigid = run(ORIFICE, mesh), run(RIGID, mesh)
    chamber = fed.chamber_pressure / ORIFICE.scale.pressure
    discharge = chamber > 0.9 * chamber.max()
    assert np.all(fed.inlet_pressure[discharge] < chamber[discharge])
    assert np.min(fed.inlet_pressure[discharge] / chamber[discharge]) < 0.99
    assert fed.h_min.min() < rigid.h_min.min()


def test_a_cavitating_film_needs_the_pocket_volume(mesh):
    with pytest.raises(ValueError, match="pocket_volume"):
        bf.simulate(with_supply(pocket_volume=None), mesh, cavitation="reynolds")
    p1 = bf.transient.pump_mesh(ORIFICE, 0.15, order=1)
    with pytest.raises(ValueError, match="pocket_volume"):
        bf.simulate(with_supply(pocket_volume=None), p1, cavitation="jfo", element="P1")
    with pytest.raises(ValueError, match="P1"):
        bf.simulate(ORIFICE, mesh, cavitation="jfo", element="P2")


def test_the_pocket_outflow_is_the_films_inlet_flow(mesh):
    # the model's linear pocket outflow (one flux per unit field) against the film result's inlet flow
    # (bearingfe.film.result.build_result) at a state with wedge, squeeze and pocket pressure together
    from bearingfe.transient.fed import Fed
    model = Fed(ORIFICE, mesh, element="P2")
    sup = model.superposition(0.5, 3.5)
    weights = np.array([0.9, 0.03, -0.02, 0.8])
    res = sup.combine(0.9, (0.03, -0.02), 0.8)
    assert model.unit_flux(sup) @ weights == pytest.approx(res.flows["inlet"], rel=1e-12)


@pytest.fixture(scope="module")
def dense(mesh):
    """The shipped orifice pump over one revolution from the steady start, sampled every 1 and 2 degrees."""
    return {n: bf.simulate(ORIFICE, mesh, start="steady", points_per_revolution=n) for n in (180, 360)}


def test_the_pocket_flows_balance_over_the_cycle(dense):
    # V/K dp_r/dt = Q_restrictor - Q_film - dV/dt (the model's rate equation), checked in its integral form on the
    # samples: the oil stored by compression, V/K (p_r(t) - p_r(0)), against the trapezoidal integral of the
    # flows. The trapezoid's error is second order in the sample spacing (measured 2.9e-3 and 7.2e-4 of the
    # stored range at 2 and 1 degree): it must shrink about 4x when the spacing halves and be < 1.5e-3 at 1 deg.
    from scipy.integrate import cumulative_trapezoid
    supply = ORIFICE.shoe_supply
    errors = []
    for n, tr in dense.items():
        assert tr.status == "completed"
        stored = supply.pocket_volume / supply.bulk_modulus * (tr.inlet_pressure - tr.inlet_pressure[0]) \
            * ORIFICE.scale.pressure
        net = cumulative_trapezoid(tr.flow_restrictor - tr.flow_inlet - tr.flow_pocket_gap, tr.t, initial=0.0)
        errors.append(np.max(np.abs(stored - net)) / np.ptp(stored))
    assert 3.0 < errors[0] / errors[1] < 5.0
    assert errors[1] < 1.5e-3


def test_the_power_split_sums_to_the_total_and_to_the_chambers_supply(dense):
    # total = friction + restrictor + film (by definition, at every sample and in the means); and the
    # chamber's hydraulic power Q_r p_ch is the restrictor's and the film's loss plus the pocket's own work
    # p_r (dV/dt + V/K dp_r/dt) (energy of the flow balance above; dp_r/dt by central differences:
    # measured 5e-4 relative at 1 degree)
    from bearingfe.transient.trajectory import cycle_losses, power_columns
    tr = dense[360]
    sc, supply = ORIFICE.scale, ORIFICE.shoe_supply
    cols = power_columns(tr, sc, ORIFICE.drive.omega)
    np.testing.assert_allclose(cols["total_power"], cols["friction_power"] + cols["restrictor_power"]
                               + cols["film_power"], rtol=1e-14, atol=0)
    losses = cycle_losses(tr, ORIFICE)
    assert losses.total_power == pytest.approx(losses.friction_power + losses.restrictor_power + losses.film_power,
                                               rel=1e-14)
    assert losses.friction_power == pytest.approx(np.mean(tr.friction_moment) * ORIFICE.drive.omega, rel=1e-14)
    p_r = tr.inlet_pressure * sc.pressure
    work = np.mean(p_r * (tr.flow_pocket_gap + supply.pocket_volume / supply.bulk_modulus * np.gradient(p_r, tr.t)))
    supplied = np.mean(tr.flow_restrictor * tr.chamber_pressure)
    assert losses.pumping_power + work == pytest.approx(supplied, rel=2e-3)
    # the orifice drops the pressure only while it feeds: its loss is a fraction of the film's (measured 0.24)
    assert 0 < losses.restrictor_power < losses.film_power
    # peaks are the largest samples; the pocket never exceeds the discharge pressure it is fed from
    assert losses.restrictor_flow_peak == pytest.approx(np.max(tr.flow_restrictor), rel=1e-14)
    assert losses.pocket_pressure_peak <= ORIFICE.cycle.discharge * (1 + 1e-9)



def test_the_fed_pocket_on_a_swift_stieber_film(mesh):
    # the cavitated film's own outflow feeds the pocket's rate equation: the flows balance in the integral form
    # of test_the_pocket_flows_balance_over_the_cycle (measured 1.3e-2, 5.8e-3, 1.4e-3 of the stored range at 2,
    # 1 and 0.5 degree: the quadrature's error at the decompression's steep flows, converging); the film at a
    # sample, re-solved with rupture, carries the load (film force + load = 0) with no pressure below 0
    from scipy.integrate import cumulative_trapezoid
    # to 216 deg: past the decompression, where the cavitated pocket's flows change fastest
    tr = bf.simulate(ORIFICE, mesh, 0.6, start="steady", points_per_revolution=720, cavitation="reynolds")
    assert tr.status == "completed"
    supply = ORIFICE.shoe_supply
    stored = supply.pocket_volume / supply.bulk_modulus * (tr.inlet_pressure - tr.inlet_pressure[0]) \
        * ORIFICE.scale.pressure
    net = cumulative_trapezoid(tr.flow_restrictor - tr.flow_inlet - tr.flow_pocket_gap, tr.t, initial=0.0)
    assert np.max(np.abs(stored - net)) / np.ptp(stored) < 3e-3
    k = int(np.argmin(np.abs(tr.beta - np.radians(200.0))))  # decompression: the pocket above the chamber
    assert tr.inlet_pressure[k] > tr.chamber_pressure[k] / ORIFICE.scale.pressure
    res = bf.transient.state_result(ORIFICE, mesh, tr, k, "reynolds")
    np.testing.assert_allclose(res.force, -tr.load[k], atol=1e-6 * np.abs(tr.load[k, 0]))
    assert res.pressure.min() >= 0.0 and np.any(res.cavitated)


def test_a_gumbel_film_that_cannot_hold_the_compressed_pocket_ends_the_run_with_why(mesh):
    # after the inner dead centre the orifice vents the compressed pocket more slowly than the chamber falls: at
    # 195 deg the pocket's 17 MPa presses on its own area with 0.87 of the plunger load and through the film
    # with 3 times it; Gumbel's film (no tension) finds no rates there: the run stops as "no-equilibrium"
    tr = bf.simulate(ORIFICE, mesh, start="steady", points_per_revolution=36, cavitation="gumbel")
    assert tr.status == "no-equilibrium"
    assert "presses on its own area" in tr.message and "'gumbel'" in tr.message
    assert 180 < np.degrees(tr.rupture_beta) < 210


# -- the fed pocket on the JFO film (FedJFO: backward Euler on (gamma, delta, p_r)) ------------------------------

@pytest.fixture(scope="module")
def p1():
    """A coarse straight P1 mesh (0.15 R0, 88 nodes): the JFO film's."""
    return bf.transient.pump_mesh(ORIFICE, 0.15, order=1)


def test_the_fed_pocket_on_a_jfo_film_follows_the_fed_model_where_it_does_not_rupture(p1):
    # the first quarter turn (compression and discharge) does not rupture the film (cavitated fraction 0), so
    # the JFO model with the fed pocket must follow the fed model on the film without rupture ("none", LSODA at
    # rtol 1e-8) up to the backward-Euler error, first order in the step: measured max |d gamma| 0.038, 0.018,
    # 0.0099 and pocket pressure 5.9e-2, 3.7e-2, 2.1e-2 of its peak at 9, 18, 36 steps a quarter turn (the
    # finite-volume Couette flux against the Galerkin one adds a part that does not shrink with the step)
    ref = bf.simulate(ORIFICE, p1, 0.25, start="steady", points_per_revolution=144, element="P1", rtol=1e-8)
    errors = []
    for n in (36, 72):
        tr = bf.simulate(ORIFICE, p1, 0.25, start="steady", points_per_revolution=n, cavitation="jfo", element="P1")
        assert tr.status == "completed" and tr.stats["cavitated_fraction_max"] == 0.0
        errors.append(np.abs(tr.gamma - np.interp(tr.beta, ref.beta, ref.gamma)).max())
        p_err = np.abs(tr.inlet_pressure - np.interp(tr.beta, ref.beta, ref.inlet_pressure)).max()
        assert p_err < 0.08 * ref.inlet_pressure.max()
    assert 1.6 < errors[0] / errors[1] < 2.6 and errors[1] < 0.025


def test_the_fed_pocket_on_a_jfo_film_balances_its_flows_at_every_step(p1):
    # through the decompression (175 to 200 deg), where the pocket outlasts the chamber and the film ruptures:
    # at every accepted backward-Euler step the pocket's discrete rate equation
    #   V/K (p_{n+1} - p_n)/dt = Q_restrictor(p_{n+1}) - Q_film,{n+1} - (V_gap,{n+1} - V_gap,n)/dt
    # holds to the Newton tolerance (1e-9 of the orifice's flow at the discharge pressure), the film itself
    # conserving mass to round-off (its mass balance)
    import math
    from bearingfe.transient.driver import run_transient
    from bearingfe.transient.quasi_static import film_model
    from bearingfe.transient.settings import Integration
    model = film_model(ORIFICE, p1, cavitation="jfo", elastic=None, formulation="pi", element="P1", solver="splu")
    assert model.name == "fed jfo"
    settings = Integration(revolutions=0.07, start="steady", beta0=math.radians(175.0), points_per_revolution=360)
    tr = run_transient(model, settings, balance_ratio=0.87)
    assert tr.status == "completed" and tr.stats["cavitated_fraction_max"] > 0.3
    assert tr.mass_balance_relative < 1e-12
    sc, supply = ORIFICE.scale, ORIFICE.shoe_supply
    betas = sorted(model.states)
    assert len(betas) > 25
    stored, net = [], []
    for b0, b1 in zip(betas[:-1], betas[1:]):
        s0, s1 = model.states[b0], model.states[b1]
        dt = (b1 - b0) / ORIFICE.drive.omega
        stored.append(supply.pocket_volume / supply.bulk_modulus * (s1.y[2] - s0.y[2]) * sc.pressure / dt)
        q_r = sc.to_flow(model.rigid._law(b1).flow(s1.y[2]))
        gap = sc.to_flow((model._gap(s1.y) - model._gap(s0.y)) / (b1 - b0))
        net.append(q_r - sc.to_flow(s1.result.flows["inlet"]) - gap)
    unit = sc.to_flow(model.flow_unit)
    np.testing.assert_allclose(stored, net, rtol=0, atol=2e-9 * unit)
    assert np.ptp(stored) > 0.1 * unit  # the pocket's compression matters: a tenth of the orifice's flow and more
    # the samples' columns are those of the steps: restrictor, film and gap flows, and the pocket pressure
    k = int(np.argmin(np.abs(tr.beta - math.radians(190.0))))
    state = model.states[float(tr.beta[k])]
    assert tr.inlet_pressure[k] == state.y[2]
    assert tr.flow_restrictor[k] == pytest.approx(sc.to_flow(model.rigid._law(tr.beta[k]).flow(state.y[2])), rel=1e-14)


# -- the fed pocket on the quasi-static elastic support (FedQuasiStaticElastic) ----------------------------------

def test_the_fed_pocket_on_a_stiffening_support_tends_to_the_rigid_fed_model(mesh):
    # the compliance C ~ 1/E: the deflection and with it the difference to the rigid fed model shrink like 1/E
    # (measured over the first 0.15 turn: smallest film 0.099, 0.0103, 0.0011 and pocket pressure 0.065, 0.0069,
    # 0.0007 relative at E = 210, 2100, 21000 GPa; 2.4e-5 over a quarter turn with E = inf, the integrators'
    # difference)
    ref = bf.simulate(ORIFICE, mesh, 0.15, start="steady", points_per_revolution=72, rtol=1e-7)
    diffs = []
    for modulus in (210e10, 210e11):
        compliance = bf.elastic.half_space(mesh, ORIFICE.scale, modulus, "P2")
        tr = bf.simulate(ORIFICE, mesh, 0.15, start="steady", points_per_revolution=72, elastic=compliance, rtol=1e-7)
        assert tr.status == "completed" and tr.max_deflection.max() > 0
        diffs.append(max(np.abs(tr.h_min / ref.h_min - 1).max(),
                         np.abs(tr.inlet_pressure / ref.inlet_pressure - 1).max()))
    assert 7 < diffs[0] / diffs[1] < 13  # first order in the compliance
    assert diffs[1] < 2e-3


def test_the_fed_pocket_on_the_elastic_support_balances_its_flows(mesh):
    # steel (E = 210 GPa, the pad opening by 0.23 c at discharge): the integral form of the pocket's rate
    # equation as in test_the_pocket_flows_balance_over_the_cycle, Q_film the deflected film's own outflow;
    # the trapezoid's error is second order in the sampling (measured 2.1e-2, 5.5e-3, 1.4e-3 of the stored range
    # at 5, 2.5 and 1.25 degree over the first quarter turn)
    from scipy.integrate import cumulative_trapezoid
    compliance = bf.elastic.half_space(mesh, ORIFICE.scale, 210e9, "P2")
    supply = ORIFICE.shoe_supply
    errors = []
    for n in (72, 144):
        tr = bf.simulate(ORIFICE, mesh, 0.25, start="steady", points_per_revolution=n, elastic=compliance)
        assert tr.status == "completed"
        stored = supply.pocket_volume / supply.bulk_modulus * (tr.inlet_pressure - tr.inlet_pressure[0]) \
            * ORIFICE.scale.pressure
        net = cumulative_trapezoid(tr.flow_restrictor - tr.flow_inlet - tr.flow_pocket_gap, tr.t, initial=0.0)
        errors.append(np.max(np.abs(stored - net)) / np.ptp(stored))
    assert 3.0 < errors[0] / errors[1] < 5.0
    assert errors[1] < 7e-3
    assert tr.max_deflection.max() > 0.1 * ORIFICE.clearance


def test_the_deflection_squeeze_model_refuses_a_fed_pocket(mesh):
    # simulate_elastic holds the pocket at the chamber pressure: a fed pump is named, not silently run unfed
    compliance = bf.elastic.half_space(mesh, ORIFICE.scale, 210e9, "P2")
    with pytest.raises(ValueError, match="feeds its pocket through a restrictor"):
        bf.transient.simulate_elastic(ORIFICE, compliance, 0.1)


def test_a_trial_state_with_the_pocket_below_zero_is_rejected_on_a_film_without_tension(mesh):
    # a loose integrator's trial may overshoot the pocket pressure below 0: Swift-Stieber's film (p >= 0) has no
    # state there, so the trial is retaken shorter (TrialRejected), not an error out of the run
    from bearingfe.transient.base import TrialRejected
    from bearingfe.transient.fed import FedCavitating
    model = FedCavitating(ORIFICE, mesh, element="P2")
    sup = model.superposition(0.5, 3.5)
    with pytest.raises(TrialRejected, match="below 0"):
        model.balancing_rates(sup, ORIFICE.load_vector(0.5), float(ORIFICE.wedge(0.5)), -0.01)


def test_the_fed_pocket_on_steel_under_rupture_lifts_the_shoe_off_at_194_deg(mesh):
    # the Swift-Stieber run of the shipped orifice pump on steel reaches, at 194.6 deg, a state (recorded from that
    # run on this mesh) where the compressed pocket (21 MPa) outlasts the chamber's decompression: a film without
    # tension pushes at least with the pocket on its own area and the elements around its contour (every other dof
    # at 0), 1.027 times the plunger load there, so no rates balance it. The model says so (no-equilibrium: the shoe
    # lifts off) instead of retaking shorter steps down to the floor ("stalled")
    from bearingfe.cavitation.rates import solve_cavitating
    from bearingfe.transient.base import NoEquilibrium
    from bearingfe.transient.elastic import FedQuasiStaticElastic
    compliance = bf.elastic.half_space(mesh, ORIFICE.scale, 210e9, "P2")
    model = FedQuasiStaticElastic(ORIFICE, compliance, cavitation="reynolds")
    beta, y = 3.3960810184238923, np.array([0.7334991287102607, 3.0888931836744367, 0.7170774752901887])
    load = ORIFICE.load_vector(beta)
    # the least push is what the film gives when it separates fast: a rigid film at large separating rates, ruptured
    # everywhere outside the pocket, pushes with exactly that (round-off)
    sup = bf.superpose(mesh, bf.CosineFilm(y[0], y[1]), formulation="direct", element="P2")
    apart = solve_cavitating(sup, float(ORIFICE.wedge(beta)), np.array([-8.0, -8.0]), y[2], model="reynolds")
    np.testing.assert_allclose(apart.force, y[2] * model.least, rtol=1e-9, atol=1e-12)
    assert y[2] * model.least[0] / np.linalg.norm(load) == pytest.approx(1.027, abs=1e-3)
    assert y[2] * model.moments[1] < np.linalg.norm(load)  # the pocket alone would not lift it: its contour's elements do
    with pytest.raises(NoEquilibrium, match="pushes with 1.027 times the plunger load"):
        model.balance(beta, y)
