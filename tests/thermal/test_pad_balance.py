"""Level-1 heat balance of pad bearings: thrust pads and tilting-pad journals (bearingfe.thermal.pad_balance).

References: the balance's own algebra (the heat carried by the oil plus the heat conducted equals the
friction power); the isoviscous limit (a temperature-independent oil: the film is the isothermal one and
T_eff = T_s + k (1 - chi) P / (rho c_p (Q_s/2 + Q_t)) in closed form); monotonicity (carry-over of hot oil
heats the film).
"""

import math

import pytest

from bearingfe.bearings.thrust import ThrustPad
from bearingfe.thermal import (ConstantViscosity, HeatBalance, Lubricant, iso_vg, kelvin, thrust_temperature)

PAD = ThrustPad(0.05, 0.1, math.radians(40), n_pads=6, pivot_offset=0.6)
SPEED = 2 * math.pi * 3000 / 60


@pytest.fixture(scope="module")
def mesh():
    return PAD.mesh(0.05)


def test_energy_closes_and_the_film_runs_hotter_and_thinner(mesh):
    oil = iso_vg("VG 32", 5.4e-6)
    r = thrust_temperature(PAD, mesh, 2e4, SPEED, oil, HeatBalance(kelvin(40.0)), reference_film=20e-6)
    P = r.performance.power
    assert r.heat.convected + r.heat.conducted == pytest.approx(P, rel=1e-10)
    assert r.residual < 1e-3
    assert r.temperature > kelvin(40.0) and r.viscosity < r.supply_viscosity
    assert r.performance.h_min < r.isothermal.h_min
    assert r.performance.load == pytest.approx(2e4, rel=1e-8)


def test_isoviscous_oil_gives_the_closed_form_rise(mesh):
    oil = Lubricant(ConstantViscosity(0.03), specific_heat=2000.0)
    balance = HeatBalance(kelvin(40.0), conducted_fraction=0.2)
    r = thrust_temperature(PAD, mesh, 2e4, SPEED, oil, balance, reference_film=20e-6)
    perf = r.performance
    assert perf.h_pivot == pytest.approx(r.isothermal.h_pivot, rel=1e-9)
    Q = perf.flows["leading"]
    Qs = perf.flows["inner"] + perf.flows["outer"]
    rho_cp = oil.density_at(r.temperature) * oil.specific_heat_at(r.temperature)
    rise = 0.8 * perf.power / (rho_cp * (0.5 * Qs + (Q - Qs)))
    assert r.heat.rise == pytest.approx(rise, rel=1e-12)
    assert r.temperature - kelvin(40.0) == pytest.approx(0.5 * rise, abs=balance.tolerance)  # Brent's tolerance


def test_carry_over_heats_the_film(mesh):
    oil = iso_vg("VG 32", 5.4e-6)
    cold = thrust_temperature(PAD, mesh, 2e4, SPEED, oil, HeatBalance(kelvin(40.0)), reference_film=20e-6)
    hot = thrust_temperature(PAD, mesh, 2e4, SPEED, oil, HeatBalance(kelvin(40.0), carry_over=0.6),
                             reference_film=20e-6)
    assert hot.temperature > cold.temperature + 1.0
    assert hot.heat.inlet > kelvin(40.0)


def _five_pads():
    import bearingfe as bf

    return bf.TiltingPadBearing(radius=0.05, length=0.05, pad_clearance=80e-6, n_pads=5, arc=math.radians(60),
                                offset=0.6, preload=0.25)


def test_tilting_pad_journal_heats_and_closes_its_energy():
    """A five-pad journal bearing (the shipped tilting scene's) at its effective temperature: the oil carries
    the friction power away (algebra closes), the film is hotter, thinner and loses less than at supply."""
    from bearingfe.thermal import tilting_pad_temperature

    r = tilting_pad_temperature(_five_pads(), 3924.0, 2 * math.pi * 100, iso_vg("VG 32", 5.4e-6),
                                HeatBalance(kelvin(40.0)))
    assert r.heat.convected + r.heat.conducted == pytest.approx(r.friction_power, rel=1e-10)
    assert r.residual < 1e-3 and r.temperature > kelvin(40.0)
    assert r.min_film < r.isothermal_min_film and r.friction_power < r.isothermal_friction_power
    assert r.eccentricity > r.isothermal_eccentricity


def test_tilting_pad_journal_isoviscous_closed_form():
    """A temperature-independent oil: the equilibrium is the isothermal one and the rise the closed form."""
    from bearingfe.thermal import tilting_pad_temperature

    oil = Lubricant(ConstantViscosity(0.02), specific_heat=2000.0)
    balance = HeatBalance(kelvin(40.0))
    r = tilting_pad_temperature(_five_pads(), 3924.0, 2 * math.pi * 100, oil, balance)
    assert r.eccentricity == pytest.approx(r.isothermal_eccentricity, rel=1e-9)
    Q, Qs = r.leading_flow, r.side_flow
    rho_cp = oil.density_at(r.temperature) * oil.specific_heat_at(r.temperature)
    assert r.heat.rise == pytest.approx(r.friction_power / (rho_cp * (0.5 * Qs + Q - Qs)), rel=1e-12)
    assert r.temperature - kelvin(40.0) == pytest.approx(0.5 * r.heat.rise, abs=balance.tolerance)
