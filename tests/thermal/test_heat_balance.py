"""Level-1 heat balance of a journal bearing: closed form, energy conservation, the isoviscous limit and
the Raimondi-Boyd effective-temperature procedure.

Sources of the expected values:
- Shigley's *Mechanical Engineering Design* (chapter on journal bearings): the temperature rise of a
  self-contained bearing ``dT = 4 pi P (R/c) f / (rho c_p (1 - Q_s/(2 Q)) Q/(R c N L))`` with the
  average film temperature ``T_s + dT/2`` (its SI constant 8.30 is ``4 pi 1e6/(rho c_p)`` with
  ``rho = 861 kg/m^3``, ``c_p = 1760 J/(kg K)``). With no carry-over, nothing conducted and ``k = 1/2``
  the balance must be this formula (to round-off).
- Energy conservation: the heat carried out of the bearing (outflows minus supply) plus the conducted
  share equals the friction power, to round-off (a separate count from the film balance that fixes dT).
- The Raimondi-Boyd design procedure (Shigley): the effective temperature found by iterating the
  chart variables ``(R/c) f``, ``Q/(R c N L)``, ``Q_s/Q`` against the Sommerfeld number at the
  trial viscosity. Here the published table (:data:`bearingfe.validation.RAIMONDI_BOYD`, Raimondi & Boyd
  1958 as reproduced in Shigley) replaces the chart, read by interpolation in log S between its rows;
  the package's own isoviscous solution replaces the table on the other side. That interpolation
  between rows 0.2 apart in eps costs about 1 % (a chart read by eye, a few %), so the two must agree
  to 2 % in the temperature rise and 0.02 in eps.
- Shigley's worked example (problem 12-12 of the 8th edition's solutions manual), by hand with the charts:
  the numbers and tolerances are stated above its test.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from bearingfe.bearings.journal import JournalBearing, equilibrium
from bearingfe.thermal import (ConstantViscosity, HeatBalance, JournalDuty, Lubricant, ThermalError,
                               WaltherViscosity, effective_temperature, film_temperatures, kelvin, mixed_inlet)
from bearingfe.validation import RAIMONDI_BOYD

FAST = dict(size=0.1, structured=True)
#: Shigley's oil properties for the temperature rise (861 kg/m^3, 1760 J/(kg K)), with an ISO VG 68
#: viscosity (68 and 8.7 mm^2/s at 40 and 100 degC) for the temperature dependence.
SHIGLEY_OIL = Lubricant(WaltherViscosity.through((kelvin(40.0), 68e-6), (kelvin(100.0), 8.7e-6)),
                        density=861.0, density_slope=0.0, specific_heat=1760.0)


def test_balance_is_shigleys_temperature_rise():
    # chart variables of the Raimondi-Boyd row L/D = 1, eps = 0.6: (R/c) f = 3.22, Q/(R c N L) = 4.33, Qs/Q = 0.680
    R, c, L, N, P_m = 0.025, 40e-6, 0.05, 30.0, 2.0e6
    W = P_m * 2 * R * L
    power = 2 * math.pi * N * 3.22 * c * W            # T omega with T = f W R = (R/c) f W c
    Q = 4.33 * R * c * N * L
    heat = film_temperatures(power, Q, 0.680 * Q, 861.0, 1760.0, HeatBalance(kelvin(40.0)))
    constant = 4 * math.pi * 1e6 / (861.0 * 1760.0)     # 8.2927, Shigley's 8.30
    shigley = constant * (P_m / 1e6) * 3.22 / ((1 - 0.5 * 0.680) * 4.33)
    assert heat.rise == pytest.approx(shigley, rel=1e-12)
    assert heat.effective == pytest.approx(kelvin(40.0) + shigley / 2, rel=1e-6)
    assert heat.inlet == kelvin(40.0) and heat.convected == pytest.approx(power, rel=1e-12)


@pytest.mark.parametrize("carry_over, conducted", [(0.0, 0.0), (0.6, 0.0), (0.3, 0.25), (1.0, 0.1)])
def test_balance_conserves_energy(carry_over, conducted):
    balance = HeatBalance(kelvin(45.0), carry_over=carry_over, conducted_fraction=conducted, effective_fraction=0.8)
    power, Q, Qs, rho, cp = 950.0, 3.1e-5, 1.9e-5, 850.0, 1950.0
    heat = film_temperatures(power, Q, Qs, rho, cp, balance)
    assert heat.convected + heat.conducted == pytest.approx(power, rel=1e-12)
    # the film's own balance and the mixing at the leading edge
    assert (1 - conducted) * power == pytest.approx(rho * cp * (Qs / 2 + (Q - Qs)) * heat.rise, rel=1e-12)
    mixed = ((Q - carry_over * (Q - Qs)) * kelvin(45.0) + carry_over * (Q - Qs) * heat.outlet) / Q
    assert heat.inlet == pytest.approx(mixed, rel=1e-12)
    assert heat.effective == pytest.approx(heat.inlet + 0.8 * heat.rise, rel=1e-12)


def test_no_fresh_oil_is_an_error():
    with pytest.raises(ThermalError, match="no fresh oil"):
        film_temperatures(100.0, 1e-5, 0.0, 850.0, 1900.0, HeatBalance(300.0, carry_over=1.0))


def _duty(ld=0.5, W=10e3):
    return JournalDuty(radius=0.05, clearance=75e-6, speed=2 * math.pi * 50.0, load=W)


def test_isoviscous_limit_reproduces_the_isothermal_equilibrium_exactly():
    mu = 0.018
    duty = _duty()
    r = effective_temperature(JournalBearing(0.5), duty, Lubricant(ConstantViscosity(mu), density=860.0),
                              HeatBalance(kelvin(50.0)), **FAST)
    scale = duty.scale(mu)
    eq = equilibrium(JournalBearing(0.5), scale.from_force(duty.load) * np.array([0.0, -1.0]), **FAST)
    assert r.viscosity == mu == r.supply_viscosity
    assert r.eccentricity == eq.eps == r.isothermal_eccentricity
    assert r.friction_power == scale.to_moment(eq.state.results[0].friction) * duty.speed
    assert r.friction_power == r.isothermal_friction_power and r.min_film == r.isothermal_min_film
    assert r.temperature_rise > 0 and r.residual <= 3 * r.balance.tolerance


def test_fixed_point_conserves_energy_and_is_consistent():
    oil = Lubricant(WaltherViscosity.through((kelvin(40.0), 32e-6), (kelvin(100.0), 5.4e-6)), density=860.0)
    balance = HeatBalance(kelvin(40.0), carry_over=0.5, conducted_fraction=0.2, tolerance=1e-4)
    r = effective_temperature(JournalBearing(0.5), _duty(), oil, balance, **FAST)
    assert r.convected_power + r.conducted_power == pytest.approx(r.friction_power, rel=1e-12)
    assert r.conducted_power == pytest.approx(0.2 * r.friction_power, rel=1e-12)
    assert r.viscosity == oil.viscosity(r.temperature)
    # Brent's tolerance is on T; the residual T_eff(T) - T is that times the slope of g (1 to 2 here)
    assert abs(r.inlet_temperature + 0.5 * r.temperature_rise - r.temperature) == pytest.approx(r.residual, abs=1e-9)
    assert r.residual <= 3 * balance.tolerance
    assert r.supply_flow == pytest.approx(r.side_flow + 0.5 * r.trailing_flow, rel=1e-12)
    # hotter and thinner than the isothermal answer at the supply temperature
    assert r.temperature > r.inlet_temperature > r.supply_temperature
    assert r.viscosity < r.supply_viscosity and r.eccentricity > r.isothermal_eccentricity
    assert r.min_film < r.isothermal_min_film and r.friction_power < r.isothermal_friction_power


def _raimondi_boyd_procedure(ld, R, c, L, N, W, oil, Ts):
    """Shigley's effective-temperature iteration with the Raimondi-Boyd table for the chart."""
    rows = RAIMONDI_BOYD[ld]
    eps = sorted(rows)[::-1]                                  # S increasing
    logS = np.log([rows[e][0] for e in eps])
    log_f = np.log([rows[e][2] for e in eps])
    flow = np.array([rows[e][3] for e in eps])
    ratio = np.array([rows[e][4] for e in eps])
    P_m = W / (2 * R * L)

    def state(T):
        s = math.log((R / c) ** 2 * oil.viscosity(T) * N / P_m)
        f, q, r = math.exp(np.interp(s, logS, log_f)), np.interp(s, logS, flow), np.interp(s, logS, ratio)
        rise = 4 * math.pi * P_m * f / (oil.density_at(T) * oil.specific_heat_at(T) * (1 - 0.5 * r) * q)
        return rise, float(np.interp(s, logS, eps))
    T = brentq(lambda t: Ts + state(t)[0] / 2 - t, Ts, Ts + 200.0, xtol=1e-9)
    return T, *state(T)


@pytest.mark.parametrize("ld, D, c, N, W, expected", [
    # (L/D, D [m], c [m], N [rev/s], W [N]) and the procedure's (T_eff [degC], dT [K], eps)
    (1.0, 0.05, 40e-6, 30.0, 8000.0, (54.345, 28.689, 0.6142)),
    (0.5, 0.05, 40e-6, 30.0, 3000.0, (54.883, 29.766, 0.7249)),
])
def test_against_the_raimondi_boyd_effective_temperature_procedure(ld, D, c, N, W, expected):
    R, L, Ts = D / 2, ld * D, kelvin(40.0)
    T, rise, eps = _raimondi_boyd_procedure(ld, R, c, L, N, W, SHIGLEY_OIL, Ts)
    assert (T - kelvin(0.0), rise, eps) == pytest.approx(expected, abs=2e-3)   # the stated values
    r = effective_temperature(JournalBearing(ld), JournalDuty(R, c, 2 * math.pi * N, W), SHIGLEY_OIL,
                              HeatBalance(Ts, tolerance=1e-4), **FAST)
    assert r.temperature_rise == pytest.approx(rise, rel=0.02)   # measured 0.08 % and 0.6 %
    assert abs(r.eccentricity - eps) < 0.02                      # measured 0.004 and 0.013
    assert r.temperature == pytest.approx(r.supply_temperature + r.temperature_rise / 2, abs=1e-4)


def test_no_fixed_point_in_range_and_no_convergence_are_named_errors():
    oil = Lubricant(WaltherViscosity.through((kelvin(40.0), 32e-6), (kelvin(100.0), 5.4e-6)), density=860.0)
    with pytest.raises(ThermalError, match="no fixed point below max_temperature"):
        effective_temperature(JournalBearing(0.5), _duty(), oil,
                              HeatBalance(kelvin(40.0), max_temperature=kelvin(41.0)), **FAST)
    with pytest.raises(ThermalError, match="did not converge in 1 iterations"):
        effective_temperature(JournalBearing(0.5), _duty(), oil,
                              HeatBalance(kelvin(40.0), max_iterations=1, tolerance=1e-9), **FAST)


@pytest.mark.parametrize("make, words", [
    (lambda: HeatBalance(-3.0), "HeatBalance.supply_temperature must be > 0"),
    (lambda: HeatBalance(300.0, carry_over=1.5), "HeatBalance.carry_over must be in [0, 1]"),
    (lambda: HeatBalance(300.0, conducted_fraction=1.0), "HeatBalance.conducted_fraction must be in [0, 1)"),
    (lambda: HeatBalance(300.0, effective_fraction=0.0), "HeatBalance.effective_fraction must be in (0, 1]"),
    (lambda: HeatBalance(300.0, max_temperature=290.0), "HeatBalance.max_temperature must be > 300"),
    (lambda: HeatBalance(300.0, max_iterations=0), "HeatBalance.max_iterations must be an integer >= 1"),
    (lambda: JournalDuty(0.05, 0.06, 100.0, 1e3), "JournalDuty.clearance must be in (0, radius"),
    (lambda: JournalDuty(0.05, 1e-4, 100.0, -1e3), "JournalDuty.load must be > 0"),
])
def test_bad_values_are_named(make, words):
    with pytest.raises(ValueError) as info:
        make()
    assert words in str(info.value)


def test_groove_supply_pressure_is_made_non_dimensional_at_the_effective_viscosity():
    # a 360-degree pad cut at 0 deg with a groove at the top fed at 1 bar: with a constant viscosity the
    # answer is the isothermal equilibrium of the bearing whose supply pressure is 1e5 Pa / (mu omega R^2/c^2)
    from bearingfe.bearings.journal import Groove
    mu, duty = 0.02, JournalDuty(radius=0.05, clearance=75e-6, speed=2 * math.pi * 50.0, load=5e3,
                                 supply_pressure=1e5)
    bearing = JournalBearing(0.5, pads=((0.0, 2 * math.pi),), grooves=(Groove(math.pi / 2, math.radians(10.0)),))
    r = effective_temperature(bearing, duty, Lubricant(ConstantViscosity(mu), density=860.0),
                              HeatBalance(kelvin(40.0)), size=0.2)
    scale = duty.scale(mu)
    fed = JournalBearing(0.5, pads=bearing.pads, grooves=bearing.grooves,
                         supply_pressure=1e5 / scale.pressure)
    # the load along duty.load_direction exactly as the balance takes it (cos(-pi/2) = 6e-17, not 0): on this
    # coarse grooved mesh a load direction 1e-16 off moved eps by 4e-5 (an equilibrium of the rupture set's
    # discrete jumps), so the two sides must get the same bits
    direction = np.array([math.cos(duty.load_direction), math.sin(duty.load_direction)])
    eq = equilibrium(fed, scale.from_force(5e3) * direction, size=0.2)
    assert r.eccentricity == pytest.approx(eq.eps, rel=1e-12)   # measured: equal to the last bit or one ulp
    assert r.leading_flow == pytest.approx(scale.to_flow(eq.state.results[0].flows["inlet"]
                                                         - eq.state.results[0].flows["arc_start"]), rel=1e-12)
    assert r.convected_power + r.conducted_power == pytest.approx(r.friction_power, rel=1e-12)


# Shigley's worked example: Budynas & Nisbett, Shigley's Mechanical Engineering Design, 8th ed., Instructor's
# Solutions Manual, problem 12-12: d = 2.5 in, c = 0.002 in, l = 2.5 in, W = 1200 lbf, N = 1120 rev/min,
# SAE 20 oil supplied at T_s = 110 degF. Its trial-and-error iteration (charts of Raimondi & Boyd, the SAE
# curve fit of Seireg & Dandage, Shigley's Table 12-1: mu = 0.0136 exp(1271.6/(T_F + 95)) ureyn) ends at
# T_f = 123.9 degF with mu = 4.53 ureyn, dT = 27.8 degF, h0/c = 0.482 and H = 0.124 Btu/s. Oil: Shigley's
# rho = 0.0311 lbm/in^3, c_p = 0.42 Btu/(lbm degF). Tolerances: the solution stops its iteration at
# +-0.2 degF and reads (R/c) f, Q/(R c N L), Qs/Q and h0/c off charts to two or three digits (a few %): 0.5 degF
# on T_f, 1 % on mu, 3 % on dT, h0/c and H. Measured: 124.06 degF, 4.514 ureyn, 28.11 degF, 0.488, 0.1252 Btu/s.
IN, LBF, REYN, BTU = 0.0254, 4.4482216152605, 6894.757293168, 1055.05585262


def _fahrenheit(t_kelvin):
    return (t_kelvin - 273.15) * 1.8 + 32.0


def test_against_shigleys_worked_example_12_12():
    from bearingfe.thermal import VogelViscosity
    sae20 = VogelViscosity(a=0.0136e-6 * REYN, b=1271.6 / 1.8, c=273.15 - 127.0 / 1.8)   # T_F + 95 = 1.8 (T - c)
    oil = Lubricant(sae20, density=0.0311 * 0.45359237 / IN**3, density_slope=0.0, specific_heat=0.42 * 4186.8)
    duty = JournalDuty(radius=1.25 * IN, clearance=0.002 * IN, speed=2 * math.pi * 1120 / 60, load=1200 * LBF)
    r = effective_temperature(JournalBearing(1.0), duty, oil, HeatBalance(kelvin((110.0 - 32) / 1.8), tolerance=1e-4),
                              **FAST)
    assert _fahrenheit(r.temperature) == pytest.approx(123.9, abs=0.5)
    assert r.viscosity / REYN * 1e6 == pytest.approx(4.53, rel=0.01)
    assert r.temperature_rise * 1.8 == pytest.approx(27.8, rel=0.03)
    assert r.min_film / duty.clearance == pytest.approx(0.482, rel=0.03)
    assert r.friction_power / BTU == pytest.approx(0.124, rel=0.03)


def test_mixed_inlet_is_the_hand_computed_mix():
    # by hand: (2e-6 * 313.15 + 0.5 * 1e-6 * 343.15) / (2e-6 + 0.5e-6) = 313.15 + 0.5e-6 * 30 / 2.5e-6 = 319.15 K
    assert mixed_inlet(2e-6, 313.15, 1e-6, 343.15, 0.5) == pytest.approx(319.15, rel=1e-14)
    assert mixed_inlet(2e-6, 313.15, 1e-6, 343.15, 0.0) == 313.15  # no carry-over: the supply, exactly
    assert mixed_inlet(2e-6, 313.15, 1e-6, 343.15, 1.0) == pytest.approx(313.15 + 30.0 / 3.0, rel=1e-14)


@pytest.mark.parametrize("carry_over", [1.2, -0.1, float("nan")])
def test_mixed_inlet_refuses_a_fraction_outside_0_1(carry_over):
    with pytest.raises(ValueError, match="carry_over must be"):  # "in [0, 1]" or "a finite number"
        mixed_inlet(2e-6, 313.15, 1e-6, 343.15, carry_over)


@pytest.mark.parametrize("args, name", [((0.0, 313.15, 1e-6, 343.15, 0.5), "supply_flow"),
                                        ((2e-6, 313.15, -1e-6, 343.15, 0.5), "carried_flow"),
                                        ((2e-6, -1.0, 1e-6, 343.15, 0.5), "supply_temperature")])
def test_mixed_inlet_refuses_bad_flows_and_temperatures(args, name):
    with pytest.raises(ValueError, match=name):
        mixed_inlet(*args)


@pytest.mark.parametrize("carry_over", [0.0, 0.4, 1.0])
def test_level1_inlet_is_the_mix_of_its_own_outlet(carry_over):
    # the level-1 balance solves the mix for T_in in closed form: fed back its own outlet it must reproduce it
    balance = HeatBalance(kelvin(45.0), carry_over=carry_over)
    Q, Qs = 3.1e-5, 1.9e-5
    heat = film_temperatures(950.0, Q, Qs, 850.0, 1950.0, balance)
    assert heat.inlet == pytest.approx(mixed_inlet(heat.supply_flow, kelvin(45.0), Q - Qs, heat.outlet, carry_over),
                                       rel=1e-13)
