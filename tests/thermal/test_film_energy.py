"""Level 2 (film energy equation coupled to Reynolds with mu(T)) against its references.

Sources of the expected values:
- energy balance: the discrete energy equation tested with v = 1 and Reynolds' consistent boundary flows
  give dissipated = convected + inflow share + conducted exactly (module docstring), so to round-off
  (1e-12 relative); the friction power U F equals the dissipation exactly for the discrete Reynolds
  solution (its weak form tested with the pressure itself).
- isoviscous limit: a Vogel law with b = 1e-30 K gives mu = a exp(b/T) = a in floating point, so the
  results must be bitwise those of ConstantViscosity(a); the load of the isoviscous infinitely wide
  inclined slider has the closed form W/B = 6 mu U L^2/(h_o^2 K^2) (ln(1 + K) - 2K/(2 + K)).
- the adiabatic infinitely wide slider with mu(T): film_energy.slider_reference, the 1-D coupled ODEs
  integrated by DOP853 to 1e-11 with the flux found by shooting (independent of the FEM).
- mesh convergence: errors against that reference on nx = 10, 20, 40 (observed order ~1.05 for the
  largest temperature error, measured).
- the isoviscous full journal bearing (unwrapped from its line of largest film, Swift-Stieber): the load and
  friction variable of bearingfe.bearings.journal.performance (the package's journal solver, its own mesh) to
  its discretization: measured 0.24 % and 0.23 % on 120 x 20 cells, bound 0.6 %.
- level 1 against level 2: the effective temperature T_in + dT/2 of the whole film's balance and the area
  mean of the level-2 field differ by 0.53 K on a 15 K rise on this pad (measured); a tenth of the rise
  is the bound of a one-temperature model.
"""

import math

import numpy as np
import pytest

from bearingfe.thermal import (ConstantViscosity, HeatBalance, Lubricant, ThermalError, VogelViscosity, iso_vg, kelvin,
                               mixed_inlet)
from bearingfe.thermal.film_energy import Pad, film_energy, journal_pad, pad_level1, pad_mesh, slider_reference

OIL = iso_vg("VG 32", 5.4e-6, specific_heat=2000.0)
L, B, H0, K, U = 0.05, 0.05, 20e-6, 1.0, 10.0
TS = kelvin(40.0)


def _thickness(x):
    return H0 * (1.0 + K * (1.0 - x / L))


@pytest.fixture(scope="module")
def reference():
    return slider_reference(L, _thickness, U, OIL, TS)


def test_energy_balance_closes_to_round_off_with_walls_and_sides():
    pad = Pad.inclined(L, B, H0, K, U)
    r = film_energy(pad, pad_mesh(pad, 16, 8), OIL, TS, wall_coefficient=2000.0)
    assert r.balance_residual < 1e-12
    assert r.conducted > 0.05 * r.power  # the walls take a real share here
    assert r.convected + r.inflow_heat + r.conducted == pytest.approx(r.power, rel=1e-12)
    assert r.friction_power == pytest.approx(r.power, rel=1e-12)
    assert abs(r.inflow_heat) < 1e-3 * r.power  # the weak inlet's share is small
    assert r.change <= 1e-9 and r.cavitated == 0


def test_zero_temperature_coefficient_is_bitwise_isoviscous():
    pad = Pad.inclined(L, B, H0, K, U)
    m = pad_mesh(pad, 12, 6)
    a = 0.03
    v = film_energy(pad, m, Lubricant(VogelViscosity(a, 1e-30, 0.0)), TS)
    c = film_energy(pad, m, Lubricant(ConstantViscosity(a)), TS)
    assert np.array_equal(v.pressure, c.pressure) and np.array_equal(v.temperature, c.temperature)
    assert c.iterations == 2  # the pressure does not depend on the temperature: one solve, one check


def test_isoviscous_wide_slider_load_matches_closed_form():
    mu = 0.03
    pad = Pad.inclined(L, 0.01, H0, K, U, sides="closed")
    r = film_energy(pad, pad_mesh(pad, 80, 1), Lubricant(ConstantViscosity(mu)), TS)
    exact = 6 * mu * U * L**2 / (H0**2 * K**2) * (math.log(1 + K) - 2 * K / (2 + K))
    assert r.load / 0.01 == pytest.approx(exact, rel=5e-4)  # P1 on 80 cells, measured 2.8e-4


def test_wide_slider_matches_the_ode_reference(reference):
    pad = Pad.inclined(L, 0.01, H0, K, U, sides="closed")
    r = film_energy(pad, pad_mesh(pad, 80, 1), OIL, TS)
    x = r.mesh.p[0]
    rise = reference.temperature(L) - TS
    assert rise > 10.0  # a strongly coupled case: mu falls by half over the film
    assert np.abs(r.temperature - reference.temperature(x)).max() < 2e-3 * rise  # measured 1.7e-3
    assert r.load / 0.01 == pytest.approx(reference.load, rel=5e-4)  # measured 1.4e-4
    assert r.power / 0.01 == pytest.approx(reference.power, rel=5e-4)  # measured 7e-5
    # no side flow: the field varies across the pad only by the triangulation's diagonals (measured 2.5e-3)
    y = r.mesh.p[1]
    assert np.abs(r.temperature[y == 0.0] - r.temperature[y == 0.01]).max() < 5e-3 * rise


def test_mesh_convergence_of_the_temperature(reference):
    pad = Pad.inclined(L, 0.01, H0, K, U, sides="closed")
    errors = []
    for nx in (10, 20, 40):
        r = film_energy(pad, pad_mesh(pad, nx, 1), OIL, TS)
        errors.append(np.abs(r.temperature - reference.temperature(r.mesh.p[0])).max())
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(orders > 0.9), orders  # SUPG P1 with a weak inlet: first order in the max norm


def test_level1_effective_temperature_near_the_level2_mean():
    pad = Pad.inclined(L, B, H0, K, U)
    m = pad_mesh(pad, 16, 8)
    l2 = film_energy(pad, m, OIL, TS)
    l1 = pad_level1(pad, m, OIL, HeatBalance(TS, tolerance=1e-4))
    assert abs(l1.temperature - l2.mean_temperature) < 0.1 * l1.rise
    assert TS < l2.mean_temperature < l2.max_temperature


def test_swift_stieber_holds_the_diverging_part_at_zero():
    pad = Pad(L, B, lambda x, y: H0 * (1 + 0.5 * np.cos(2 * np.pi * x / L)) + 0 * y, U)
    r = film_energy(pad, pad_mesh(pad, 16, 8), OIL, TS)
    assert r.cavitated > 0 and r.pressure.min() == 0.0
    assert r.balance_residual < 1e-12


@pytest.mark.parametrize("kwargs", [dict(wall_coefficient=-1.0), dict(relaxation=0.0), dict(tolerance=0.0),
                                    dict(max_iterations=0), dict(supply_temperature=-3.0)])
def test_bad_parameters_are_refused(kwargs):
    pad = Pad.inclined(L, B, H0, K, U)
    args = dict(supply_temperature=TS) | kwargs
    with pytest.raises(ValueError):
        film_energy(pad, pad_mesh(pad, 2, 2), OIL, **args)


def test_no_convergence_is_reported():
    pad = Pad.inclined(L, B, H0, K, U)
    with pytest.raises(ThermalError, match="did not converge"):
        film_energy(pad, pad_mesh(pad, 4, 2), OIL, TS, max_iterations=2)


def test_anderson_mixing_reaches_the_plain_iterations_fixed_point_in_fewer_iterations():
    pad = Pad.inclined(L, B, H0, K, U)
    m = pad_mesh(pad, 12, 6)
    plain = film_energy(pad, m, OIL, TS, memory=0)
    mixed = film_energy(pad, m, OIL, TS, memory=3)
    assert np.abs(plain.temperature - mixed.temperature).max() < 1e-8  # both to 1e-9 K per iteration
    assert mixed.iterations < plain.iterations  # measured 10 against 15
    with pytest.raises(ValueError, match="memory"):
        film_energy(pad, m, OIL, TS, memory=-1)


@pytest.mark.parametrize("make", [lambda: Pad(L, B, lambda x, y: 0 * x - 1e-6, U),
                                  lambda: Pad(L, B, lambda x, y: 0 * x + float("nan"), U)])
def test_a_film_that_is_not_positive_is_refused(make):
    pad = make()
    with pytest.raises(ValueError, match="thickness"):
        film_energy(pad, pad_mesh(pad, 2, 2), OIL, TS)


@pytest.mark.parametrize("make", [lambda: Pad(L, B, "h", U), lambda: Pad(L, B, _thickness, U, sides="open"),
                                  lambda: Pad(-L, B, _thickness, U), lambda: Pad(L, B, _thickness, 0.0),
                                  lambda: pad_mesh(Pad.inclined(L, B, H0, K, U), 0, 2)])
def test_bad_pads_are_refused(make):
    with pytest.raises(ValueError):
        make()


def test_isoviscous_journal_matches_the_packages_journal_solver():
    import skfem

    from bearingfe.bearings.journal import JournalBearing, performance

    R, length, c, eps, omega, mu = 0.025, 0.025, 25e-6, 0.6, 100 * math.pi, 0.02
    pad = journal_pad(R, length, c, eps, omega)
    r = film_energy(pad, pad_mesh(pad, 120, 20), Lubricant(ConstantViscosity(mu)), TS)
    basis = skfem.Basis(r.mesh, skfem.ElementTriP1())
    p, phi = np.asarray(basis.interpolate(r.pressure)), np.asarray(basis.global_coordinates()[0]) / R
    load = math.hypot(float((p * np.cos(phi) * basis.dx).sum()), float((p * np.sin(phi) * basis.dx).sum()))
    perf = performance(JournalBearing(length / (2 * R)), eps, size=0.05)
    assert load == pytest.approx(perf.load * mu * omega * R**4 / c**2, rel=6e-3)
    assert r.friction / load * R / c == pytest.approx(perf.friction_variable, rel=6e-3)
    assert r.cavitated > 0 and r.balance_residual < 1e-12


def test_a_mesh_of_another_pad_is_refused():
    pad, other = Pad.inclined(L, B, H0, K, U), Pad.inclined(2 * L, B, H0, K, U)
    with pytest.raises(ValueError, match="mesh must cover the pad"):
        film_energy(pad, pad_mesh(other, 4, 2), OIL, TS)


# -- JFO cavitation: the liquid's heat share ------------------------------------------------------------------
# Sources: the discrete balance of the conserving cells (module docstring: exact to the JFO solver's
# tolerance, 1e-12 relative asked); in a cavity of a wide film with constant viscosity the liquid's flux
# U theta h/2 is constant along x and its dissipation theta mu U^2/h heats it at dT/dx = 2 mu U/(rho c_p h^2)
# whatever theta (closed form, quadrature by scipy); the wide slider's ODE reference (slider_reference) for
# the full film; the fill-fraction formulas with theta = 1 are the full film's bit for bit.

def _cosine_pad(width, sides):
    return Pad(L, width, lambda x, y: H0 * (1 + 0.5 * np.cos(2 * np.pi * x / L)) + 0 * y, U, sides)


@pytest.mark.parametrize("sides", ["ambient", "closed"])
def test_jfo_energy_balance_closes_on_a_cavitating_pad(sides):
    pad = _cosine_pad(B, sides)
    r = film_energy(pad, pad_mesh(pad, 32, 8), OIL, TS, cavitation="jfo", wall_coefficient=1000.0)
    assert r.cavitated > 50 and 0.3 < r.fill.min() < 0.6 and r.fill.max() == 1.0  # a real cavity
    assert r.pressure.min() == 0.0
    assert r.balance_residual < 1e-12  # measured 2e-15
    assert r.convected + r.inflow_heat + r.conducted == pytest.approx(r.power, rel=1e-12)
    assert r.temperature.min() >= TS - 1e-9  # the conserving cells' M-matrix: nothing colder than the inlet
    ss = film_energy(pad, pad_mesh(pad, 32, 8), OIL, TS, wall_coefficient=1000.0)
    assert r.power < ss.power  # the cavity's gas shears nothing: less heat than the full film's streamers


def test_jfo_cavity_heats_the_liquid_at_the_closed_form_rate():
    mu = 0.03
    oil = Lubricant(ConstantViscosity(mu))
    rc = oil.density_at(TS) * oil.specific_heat_at(TS)
    errors = []
    for nx in (80, 160):
        pad = _cosine_pad(0.005, "closed")
        r = film_energy(pad, pad_mesh(pad, nx, 1), oil, TS, cavitation="jfo")
        x, y = r.mesh.p
        o = np.argsort(x[y == 0])
        xs, T, th = x[y == 0][o], r.temperature[y == 0][o], r.fill[y == 0][o]
        k = np.flatnonzero(th < 1 - 1e-9)[0] - 1  # the last full-film node before the cavity
        h = pad.thickness(xs, 0 * xs)
        assert np.ptp((th * h)[k + 1:-1]) < 0.04 * (th * h)[k + 1]  # the liquid's flux U theta h/2: constant
        from scipy.integrate import quad
        exact = quad(lambda s: 2 * mu * U / (rc * float(pad.thickness(s, 0.0)) ** 2), xs[k], xs[-2])[0]
        errors.append(abs(T[-2] - T[k] - exact) / exact)
    assert errors[1] < 0.04 and errors[0] / errors[1] > 1.7  # first order: measured 6.1 % and 3.1 %


def test_jfo_full_film_converges_to_the_ode_reference(reference):
    pad = Pad.inclined(L, 0.01, H0, K, U, sides="closed")
    rise = reference.temperature(L) - TS
    errors = []
    for nx in (20, 40, 80):
        r = film_energy(pad, pad_mesh(pad, nx, 1), OIL, TS, cavitation="jfo")
        assert r.cavitated == 0 and np.all(r.fill == 1.0)  # no cavity: theta is exactly one
        assert r.balance_residual < 1e-12
        errors.append(np.abs(r.temperature - reference.temperature(r.mesh.p[0])).max() / rise)
    assert r.load / 0.01 == pytest.approx(reference.load, rel=5e-3)  # measured 2.9e-3
    assert errors[-1] < 0.012  # first-order upwind cells: measured 3.5 %, 1.8 %, 0.93 % of the rise
    assert np.all(np.log2(np.array(errors[:-1]) / np.array(errors[1:])) > 0.9)


def test_fill_fraction_one_is_the_full_film_bit_for_bit():
    from bearingfe.film.forms import dissipation, film_flux, shear

    rng = np.random.default_rng(7)
    h, mu = H0 * (1 + rng.random(50)), 0.01 + 0.02 * rng.random(50)
    dp = (1e9 * rng.standard_normal(50), 1e9 * rng.standard_normal(50))
    one = np.ones(50)
    for a, b in zip(film_flux(h, dp, U, viscosity=mu, fill=one), film_flux(h, dp, U, viscosity=mu)):
        assert np.array_equal(a, b)
    assert np.array_equal(shear(h, dp, U, viscosity=mu, fill=one), shear(h, dp, U, viscosity=mu))
    assert np.array_equal(dissipation(h, dp, U, mu, fill=one), dissipation(h, dp, U, mu))
    half = 0.5 * one  # the liquid's share: Couette terms halved, Poiseuille terms unchanged
    assert np.allclose(dissipation(h, dp, U, mu, fill=half) - dissipation(h, dp, U, mu), -0.5 * mu * U**2 / h,
                       rtol=1e-12, atol=0)


def test_unknown_cavitation_model_is_refused():
    pad = Pad.inclined(L, B, H0, K, U)
    with pytest.raises(ValueError, match="cavitation must be one of"):
        film_energy(pad, pad_mesh(pad, 2, 2), OIL, TS, cavitation="gumbel")


# -- hot-oil carry-over -------------------------------------------------------------------------------------
# Source: the mix T_in = (Q_supply T_s + lambda Q_t T_t)/(Q_supply + lambda Q_t) (mixed_inlet, checked by hand
# in tests/thermal/test_heat_balance.py) of the film's own leading inflow and trailing outflow at the fixed point.

@pytest.mark.parametrize("cavitation", ["reynolds", "jfo"])
def test_carry_over_mixes_the_trailing_oil_into_the_inlet(cavitation):
    pad = journal_pad(0.025, 0.025, 25e-6, 0.6, 100 * math.pi)
    m = pad_mesh(pad, 40, 8)
    cold = film_energy(pad, m, OIL, TS, cavitation=cavitation)
    hot = film_energy(pad, m, OIL, TS, cavitation=cavitation, carry_over=0.5)
    assert cold.inlet_temperature == TS and cold.carried_flow == 0.0
    x = m.p[0]
    lead = np.abs(x) < 1e-12
    # the leading edge's inflow, from the same consistent nodal flows the solver mixes with
    T_in = hot.inlet_temperature
    assert T_in > TS + 1.0
    # T_in is the fixed point of the mix: rebuild it from the reported flows and trailing temperature
    q_lead = _leading_inflow(hot, pad, m, cavitation)
    assert T_in == pytest.approx(mixed_inlet(q_lead - hot.carried_flow, TS, hot.carried_flow / 0.5,
                                             hot.trailing_temperature, 0.5), abs=1e-6)
    assert hot.balance_residual < 1e-12 and hot.mean_temperature > cold.mean_temperature + 1.0
    assert np.all(hot.temperature[lead] > TS)


def _leading_inflow(r, pad, m, cavitation):
    """The leading edge's inflow [m^3/s] recomputed from the answer's fields, as the solver takes it."""
    from bearingfe.thermal.film_energy import _Film

    f = _Film(pad, m)
    mu_q = OIL.viscosity_field(np.asarray(f.basis.interpolate(r.temperature)))
    if cavitation == "jfo":
        flows = f.jfo(mu_q, None)[3]
    else:
        from bearingfe.film.forms import gradient_load

        (q0, q1), _ = f.flux(r.pressure, mu_q)
        flows = gradient_load.assemble(f.basis, f0=q0, f1=q1)
    return float(np.maximum(-flows[f.leading], 0.0).sum())


@pytest.mark.parametrize("carry_over", [1.5, -0.2])
def test_carry_over_outside_0_1_is_refused(carry_over):
    pad = Pad.inclined(L, B, H0, K, U)
    with pytest.raises(ValueError, match=r"carry_over must be in \[0, 1\]"):
        film_energy(pad, pad_mesh(pad, 2, 2), OIL, TS, carry_over=carry_over)


def test_carrying_over_all_the_outflow_of_a_closed_slider_is_an_error():
    # closed sides: all the oil that enters leaves at the trailing edge, so lambda = 1 leaves no fresh oil
    pad = Pad.inclined(L, 0.01, H0, K, U, sides="closed")
    with pytest.raises(ThermalError, match="no fresh oil"):
        film_energy(pad, pad_mesh(pad, 8, 1), OIL, TS, carry_over=1.0)
