"""Level-1 heat balance of a thrust bearing (bearingfe.thermal.thrust_balance).

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
