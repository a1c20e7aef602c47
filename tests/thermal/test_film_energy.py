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

from bearingfe.thermal import ConstantViscosity, HeatBalance, Lubricant, ThermalError, VogelViscosity, iso_vg, kelvin
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
