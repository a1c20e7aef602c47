"""Level 1 over the pump cycle: the plunger shoe's cycle-mean heat balance.

The balance itself is validated in test_heat_balance.py (Shigley's formula, energy conservation, the
Raimondi-Boyd procedure); here the cycle's side of it: the isoviscous limit reproduces the isothermal
run exactly, energy is conserved at the fixed point to round-off, the cycle-mean flows obey the mass
balance of a periodic run (the squeeze of the film volume averages out over a revolution: the flow in
minus the side flow is the trailing-edge outflow to the periodicity of the run, 1e-3 here), and the
heat is the friction moment's power plus the pocket's pressure work. Coarse P1 meshes keep it fast.
"""

import dataclasses

import numpy as np
import pytest

from bearingfe.mechanisms.files import load_mechanism
from bearingfe.thermal import ConstantViscosity, HeatBalance, Lubricant, iso_vg, kelvin
from bearingfe.thermal.pump_cycle import cycle_heat, cycle_temperature
from bearingfe.transient import pump_mesh, simulate, state_result
from tests.helpers import ROOT

RUN = dict(start="periodic", rtol=1e-5, element="P1")


@pytest.fixture(scope="module")
def pump():
    return load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")


@pytest.fixture(scope="module")
def mesh(pump):
    return pump_mesh(pump, 0.3, order=1)


@pytest.mark.slow
def test_isoviscous_limit_is_the_isothermal_run(pump, mesh):
    oil = Lubricant(ConstantViscosity(pump.viscosity), density=870.0)
    r = cycle_temperature(pump, mesh, oil, HeatBalance(kelvin(50.0), tolerance=0.1), **RUN)
    traj = simulate(pump, mesh, 1.0, **RUN)
    assert r.viscosity == pump.viscosity == r.supply_viscosity
    assert r.smallest_film == traj.smallest_film == r.isothermal_smallest_film
    assert np.array_equal(r.trajectory.h_min, traj.h_min)


def test_cycle_heat_is_friction_power_plus_pocket_work_and_conserves_mass(pump, mesh):
    traj = simulate(pump, mesh, 1.0, **RUN)
    cyc = cycle_heat(pump, mesh, traj)
    omega = pump.drive.omega
    k = int(np.argmax(traj.chamber_pressure))
    assert cyc.power[k] == pytest.approx(traj.friction_moment[k] * omega * traj.wedge[k]
                                         + traj.chamber_pressure[k] * traj.flow_inlet[k], rel=1e-12)
    trailing = np.array([pump.scale.to_flow(state_result(pump, mesh, traj, j).flows["arc_end"])
                         for j in range(traj.beta.size)])
    mean_trailing = np.trapezoid(trailing, traj.t) / (traj.t[-1] - traj.t[0])
    assert cyc.mean_leading_flow - cyc.mean_side_flow == pytest.approx(mean_trailing, rel=1e-3)


@pytest.mark.slow
def test_fixed_point_conserves_energy_and_thins_the_film(pump, mesh):
    oil = iso_vg("VG 46", 6.8e-6, density=870.0)
    balance = HeatBalance(kelvin(46.0), conducted_fraction=0.5, carry_over=0.2, tolerance=0.1)
    r = cycle_temperature(pump, mesh, oil, balance, **RUN)
    assert r.convected_power + r.conducted_power == pytest.approx(r.friction_power, rel=1e-12)
    assert r.viscosity == oil.viscosity(r.temperature) < r.supply_viscosity
    assert r.residual <= 3 * balance.tolerance
    assert r.smallest_film < r.isothermal_smallest_film
    assert r.peak_temperature >= r.outlet_temperature > r.temperature > r.inlet_temperature > r.supply_temperature


def test_shoe_pad_is_the_runs_film_at_its_thinnest_sample(pump):
    # the pad must be the transient's film at that state: its thinnest film is the run's h_min there (the
    # closed form c (1 - gamma) when the thinnest line lies on the shoe), its size R0 x arc by 2 a R0 and its
    # speed the eccentric's sliding speed wedge omega R0 (module docstring of bearingfe.bearings.pump)
    from bearingfe.geometry.surface import Surface
    from bearingfe.thermal import shoe_pad

    plain = dataclasses.replace(pump, surface=Surface(arc=pump.surface.arc, half_width=pump.surface.half_width))
    traj = simulate(plain, pump_mesh(plain, 0.3, order=1), 1.0, **RUN)
    k = int(np.argmin(traj.h_min))
    pad = shoe_pad(plain, traj, k)
    a0, a1 = plain.surface.arc
    assert pad.length == pytest.approx(plain.radius * (a1 - a0), rel=1e-14)
    assert pad.width == pytest.approx(2 * plain.surface.half_width * plain.radius, rel=1e-14)
    assert pad.speed == pytest.approx(abs(traj.wedge[k]) * plain.drive.omega * plain.radius, rel=1e-14)
    x = np.linspace(0.0, pad.length, 20001)
    assert pad.thickness(x, 0 * x).min() == pytest.approx(traj.h_min[k], rel=1e-6)
    with pytest.raises(ValueError, match="plain rectangular shoe"):
        shoe_pad(pump, traj, k)
    with pytest.raises(ValueError, match="index"):
        shoe_pad(plain, traj, traj.beta.size)
