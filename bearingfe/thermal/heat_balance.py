r"""Level 1 thermal model: the effective temperature of a journal bearing from its heat balance.

The film is solved isoviscously at the viscosity of one *effective temperature*
``T_eff``; the temperature comes from the balance of the friction power with
the heat the oil carries away, and the two are iterated to a fixed point.

The balance (:func:`film_temperatures`), with the flows of the isoviscous film
at ``T_eff``: ``Q`` into the leading edges of the pads (and the grooves),
``Q_s`` out of the axial edges, ``Q_t = Q - Q_s`` out of the trailing edges
(the mass-conserving closure: with Swift-Stieber cavitation the ruptured film's
Couette flow is not the flow that reaches the trailing edge); ``rho`` and
``c_p`` of the oil at ``T_eff``:

- a share ``chi`` (``conducted_fraction``) of the friction power ``P`` is
  conducted away through the shaft and housing; the rest heats the film oil
  from the inlet temperature ``T_in`` by ``dT`` at the trailing edge, the side
  flow leaving on average at ``T_in + dT/2``:
  ``(1 - chi) P = rho c_p (Q_s/2 + Q_t) dT``;
- hot-oil carry-over: a fraction ``lambda`` (``carry_over``) of the trailing
  flow re-enters the leading edge with the fresh oil at the supply temperature
  ``T_s``: the mix of :func:`mixed_inlet`,
  ``T_in = (Q_supply T_s + lambda Q_t T_out)/(Q_supply + lambda Q_t)`` with
  ``Q_supply = Q - lambda Q_t`` and ``T_out = T_in + dT``, solved for ``T_in``:
  ``T_in = T_s + lambda Q_t dT / Q_supply``;
- the effective temperature is ``T_eff = T_in + k dT``
  (``effective_fraction``, 1/2: the mean of inlet and outlet, as in the
  Raimondi-Boyd design procedure).

With ``chi = lambda = 0``, ``k = 1/2`` this is the balance of Shigley's
*Mechanical Engineering Design* (chapter on journal bearings),
``dT = 4 pi P_m (R/c) f / (rho c_p (1 - Q_s/(2Q)) Q/(R c N L))``.

The fixed point ``g(T) = T_eff(T) - T = 0`` is solved by Brent's method on a
bracket: ``g(T_s) > 0`` (the film heats), and ``g`` at ``T_s`` plus the rise
of the isothermal film at ``T_s`` is negative when the viscosity falls with
the temperature (the bracket is widened, up to ``max_temperature``, when it is
not). :class:`ThermalError` names what failed: no bracket, no convergence, a
load the bearing cannot carry at some temperature of the search.

Level 2 (:mod:`bearingfe.thermal.film_energy`): the film's mean temperature as a
2-D field from the energy equation (convection by the mean film flux, viscous
heating, adiabatic or with a heat-transfer coefficient to the walls), stabilised
by SUPG and coupled to a Reynolds equation whose viscosity varies over the film;
on a plane pad, a full journal unwrapped from its groove (with Swift-Stieber or
JFO cavitation, hot-oil carry-over at the groove) and the plain pump shoe at one
frozen state of its cycle (:func:`bearingfe.thermal.pump_cycle.shoe_pad`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np
from scipy.optimize import brentq

from ..bearings.journal import Equilibrium, JournalBearing, equilibrium
from ..core.scales import Scale
from ..core.schema import Range, finite, in_range, nonnegative, positive
from .lubricant import Lubricant

__all__ = ["HeatBalance", "JournalDuty", "FilmTemperatures", "EffectiveTemperature", "ThermalError",
           "film_rise", "film_temperatures", "effective_temperature", "fixed_point", "mixed_inlet"]

_FRACTION = Range(0.0, 1.0)


class ThermalError(RuntimeError):
    """The heat balance has no fixed point in the searched range, or its iteration did not converge."""


@dataclass(frozen=True)
class HeatBalance:
    """How the oil carries the friction heat away (level 1).

    Parameters
    ----------
    supply_temperature : float
        Temperature of the fresh oil ``T_s`` [K], > 0.
    carry_over : float
        Hot-oil carry-over ``lambda`` [-], in [0, 1]: the fraction of the trailing-edge flow that
        re-enters the leading edge unmixed with the supply.
    conducted_fraction : float
        Share ``chi`` of the friction power conducted away by the shaft and housing [-], in [0, 1).
    effective_fraction : float
        ``k`` in ``T_eff = T_in + k dT`` [-], in (0, 1].
    tolerance : float
        Tolerance of the fixed point on ``T_eff`` [K], > 0.
    max_temperature : float
        Largest effective temperature searched [K], > ``supply_temperature``.
    max_iterations : int
        Largest number of Brent iterations, >= 1.
    """

    supply_temperature: float
    carry_over: float = 0.0
    conducted_fraction: float = 0.0
    effective_fraction: float = 0.5
    tolerance: float = 1e-3
    max_temperature: float = 473.15
    max_iterations: int = 50

    def __post_init__(self) -> None:
        own = type(self).__name__
        object.__setattr__(self, "supply_temperature",
                           positive(f"{own}.supply_temperature", self.supply_temperature, "K"))
        object.__setattr__(self, "carry_over", in_range(f"{own}.carry_over", self.carry_over, _FRACTION))
        object.__setattr__(self, "conducted_fraction", in_range(f"{own}.conducted_fraction",
                                                                self.conducted_fraction, Range(0.0, 1.0, hi_open=True)))
        object.__setattr__(self, "effective_fraction", in_range(f"{own}.effective_fraction", self.effective_fraction,
                                                                Range(0.0, 1.0, lo_open=True)))
        object.__setattr__(self, "tolerance", positive(f"{own}.tolerance", self.tolerance, "K"))
        top = in_range(f"{own}.max_temperature", self.max_temperature,
                       Range(self.supply_temperature, lo_open=True), "K")
        object.__setattr__(self, "max_temperature", top)
        if isinstance(self.max_iterations, bool) or not isinstance(self.max_iterations, int) or self.max_iterations < 1:
            raise ValueError(f"{own}.max_iterations must be an integer >= 1, got {self.max_iterations!r}")


@dataclass(frozen=True)
class JournalDuty:
    """What a journal bearing is asked to carry, in SI.

    Parameters
    ----------
    radius : float
        Journal radius ``R`` [m], > 0.
    clearance : float
        Radial clearance ``c`` [m], in (0, R).
    speed : float
        Shaft speed ``omega`` [rad/s], > 0.
    load : float
        Load on the journal ``W`` [N], > 0.
    load_direction : float
        Direction of the load in the bearing frame [rad]; ``-pi/2`` (gravity) by default.
    supply_pressure : float
        Groove pressure [Pa], >= 0 (made non-dimensional at each viscosity; it replaces the
        bearing's own ``supply_pressure``).
    """

    radius: float
    clearance: float
    speed: float
    load: float
    load_direction: float = -math.pi / 2
    supply_pressure: float = 0.0

    def __post_init__(self) -> None:
        own = type(self).__name__
        for name, unit in (("radius", "m"), ("clearance", "m"), ("speed", "rad/s"), ("load", "N")):
            object.__setattr__(self, name, positive(f"{own}.{name}", getattr(self, name), unit))
        if not self.clearance < self.radius:
            raise ValueError(f"{own}.clearance must be in (0, radius = {self.radius:g}) m, got {self.clearance!r}")
        object.__setattr__(self, "load_direction", finite(f"{own}.load_direction", self.load_direction))
        object.__setattr__(self, "supply_pressure", nonnegative(f"{own}.supply_pressure", self.supply_pressure, "Pa"))

    def scale(self, viscosity: float) -> Scale:
        """The package's scales at a viscosity [Pa s]."""
        return Scale(radius=self.radius, clearance=self.clearance, viscosity=viscosity, speed=self.speed)


@dataclass(frozen=True)
class FilmTemperatures:
    """Temperatures and heat flows of the level-1 balance of one film (SI).

    Attributes
    ----------
    inlet, outlet, side, effective : float
        ``T_in``, ``T_in + dT``, ``T_in + dT/2``, ``T_in + k dT`` [K].
    rise : float
        ``dT`` across the film [K].
    supply_flow : float
        Fresh oil ``Q - lambda Q_t`` [m^3/s] (what the supply delivers).
    convected : float
        Heat carried out of the bearing by the oil, from the outflows and the supply [W].
    conducted : float
        ``chi P`` [W].
    """

    inlet: float
    outlet: float
    side: float
    effective: float
    rise: float
    supply_flow: float
    convected: float
    conducted: float


def mixed_inlet(supply_flow: float, supply_temperature: float, carried_flow: float, outlet_temperature: float,
                carry_over: float) -> float:
    """Inlet temperature of a pad or groove with hot-oil carry-over [K]: the mix
    ``T_in = (Q_supply T_s + lambda Q_carry T_out) / (Q_supply + lambda Q_carry)``.

    Parameters
    ----------
    supply_flow : float
        Fresh oil ``Q_supply`` [m^3/s], > 0.
    supply_temperature : float
        Its temperature ``T_s`` [K], > 0.
    carried_flow : float
        The outflow ``Q_carry`` [m^3/s], >= 0, a fraction of which is carried over.
    outlet_temperature : float
        Its temperature ``T_out`` [K], > 0.
    carry_over : float
        ``lambda`` [-] in [0, 1].

    Raises
    ------
    ValueError
        A parameter out of its range (named in the message).
    """
    qs = positive("supply_flow", supply_flow, "m^3/s")
    Ts = positive("supply_temperature", supply_temperature, "K")
    qc = nonnegative("carried_flow", carried_flow, "m^3/s")
    To = positive("outlet_temperature", outlet_temperature, "K")
    lam = in_range("carry_over", carry_over, _FRACTION)
    if lam * qc == 0.0:
        return Ts
    return (qs * Ts + lam * qc * To) / (qs + lam * qc)


def film_rise(power, leading_flow, side_flow, heat_capacity: float, conducted_fraction: float):
    """Temperature rise across the film ``dT = (1 - chi) P / (rho c_p (Q_s/2 + Q_t))`` [K].

    ``P`` [W], ``Q`` and ``Q_s`` [m^3/s] (numbers or arrays; ``Q_t = max(Q - Q_s, 0)``), the
    volumetric heat capacity ``rho c_p`` [J/(m^3 K)] and the conducted share ``chi`` [-].
    """
    trailing = np.maximum(np.asarray(leading_flow, float) - side_flow, 0.0)
    return (1.0 - conducted_fraction) * np.asarray(power, float) / (heat_capacity * (0.5 * np.asarray(side_flow, float)
                                                                                     + trailing))


def film_temperatures(power: float, leading_flow: float, side_flow: float, density: float, specific_heat: float,
                      balance: HeatBalance) -> FilmTemperatures:
    """The level-1 balance of a film of friction power ``P`` [W] and flows ``Q``, ``Q_s`` [m^3/s].

    ``rho`` [kg/m^3] and ``c_p`` [J/(kg K)] of the oil; see the module docstring for the balance.
    ``convected`` is counted on the bearing as a whole (oil out through the sides and the trailing
    edges not carried over, fresh oil in), independently of the film's balance that fixes ``dT``,
    so ``convected + conducted = P`` checks the algebra.

    Raises
    ------
    ThermalError
        No oil leaves the film, or no fresh oil enters it (``Q_s = 0`` and ``lambda = 1``).
    """
    P = nonnegative("power", power, "W")
    Q = positive("leading_flow", leading_flow, "m^3/s")
    Qs = nonnegative("side_flow", side_flow, "m^3/s")
    rc = positive("density", density, "kg/m^3") * positive("specific_heat", specific_heat, "J/(kg K)")
    Qt = max(Q - Qs, 0.0)
    lam, chi, k = balance.carry_over, balance.conducted_fraction, balance.effective_fraction
    fresh = Qs + (1.0 - lam) * Qt
    if not fresh > 0:
        raise ThermalError("no fresh oil enters the film (no side flow and carry_over = 1): no heat balance")
    rise = float(film_rise(P, Q, Qs, rc, chi))
    Ts = balance.supply_temperature
    inlet = Ts + lam * Qt * rise / fresh
    outlet, side = inlet + rise, inlet + 0.5 * rise
    convected = rc * (Qs * (side - Ts) + (1.0 - lam) * Qt * (outlet - Ts))
    return FilmTemperatures(inlet=inlet, outlet=outlet, side=side, effective=inlet + k * rise, rise=rise,
                            supply_flow=fresh, convected=convected, conducted=chi * P)


@dataclass(frozen=True)
class _Film:
    """The isoviscous film at one trial temperature."""

    temperature: float
    viscosity: float
    power: float
    leading_flow: float
    side_flow: float
    density: float
    specific_heat: float
    heat: FilmTemperatures
    equilibrium: Equilibrium


@dataclass(frozen=True)
class EffectiveTemperature:
    """A journal bearing at the fixed point of its level-1 heat balance (SI).

    Attributes
    ----------
    temperature : float
        Effective film temperature ``T_eff`` [K].
    supply_temperature, inlet_temperature, outlet_temperature, side_temperature : float
        ``T_s``, ``T_in``, ``T_in + dT``, ``T_in + dT/2`` [K].
    temperature_rise : float
        ``dT`` across the film [K].
    viscosity : float
        Effective viscosity ``mu(T_eff)`` [Pa s].
    supply_viscosity : float
        ``mu(T_s)`` [Pa s] (the isothermal model's viscosity).
    density, specific_heat : float
        ``rho`` [kg/m^3] and ``c_p`` [J/(kg K)] at ``T_eff``.
    friction_power, convected_power, conducted_power : float
        Friction power ``P`` and the heat the oil carries out of the bearing and the share
        conducted away [W]; ``convected + conducted = P`` to round-off.
    leading_flow, side_flow, trailing_flow, supply_flow : float
        ``Q``, ``Q_s``, ``Q_t = Q - Q_s`` and the fresh oil ``Q - lambda Q_t`` [m^3/s].
    eccentricity, min_film : float
        At ``T_eff``: eccentricity ratio [-] and smallest film [m].
    isothermal_eccentricity, isothermal_min_film, isothermal_friction_power : float
        The same at the supply temperature (the isothermal answer) [-], [m], [W].
    evaluations : int
        Isoviscous equilibria solved.
    residual : float
        ``|T_eff(T) - T|`` at the answer [K].
    balance : HeatBalance
    equilibrium : Equilibrium
        The isoviscous equilibrium at ``T_eff`` (non-dimensional at ``viscosity``).
    """

    temperature: float
    supply_temperature: float
    inlet_temperature: float
    outlet_temperature: float
    side_temperature: float
    temperature_rise: float
    viscosity: float
    supply_viscosity: float
    density: float
    specific_heat: float
    friction_power: float
    convected_power: float
    conducted_power: float
    leading_flow: float
    side_flow: float
    trailing_flow: float
    supply_flow: float
    eccentricity: float
    min_film: float
    isothermal_eccentricity: float
    isothermal_min_film: float
    isothermal_friction_power: float
    evaluations: int
    residual: float
    balance: HeatBalance
    equilibrium: Equilibrium = field(repr=False, compare=False)


def _solve_film(bearing: JournalBearing, duty: JournalDuty, lubricant: Lubricant, balance: HeatBalance,
                temperature: float, options: dict) -> _Film:
    mu = lubricant.viscosity(temperature)
    scale = duty.scale(mu)
    fed = dataclasses.replace(bearing, supply_pressure=scale.from_pressure(duty.supply_pressure))
    direction = np.array([math.cos(duty.load_direction), math.sin(duty.load_direction)])
    try:
        eq = equilibrium(fed, scale.from_force(duty.load) * direction, **options)
    except RuntimeError as exc:
        raise ThermalError(f"at {temperature:.6g} K (viscosity {mu:.4g} Pa s) the isoviscous equilibrium "
                           f"failed: {exc}") from exc
    results = eq.state.results
    power = scale.to_moment(sum(r.friction for r in results)) * duty.speed
    leading = scale.to_flow(sum(r.flows.get("inlet", 0.0) - r.flows.get("arc_start", 0.0) for r in results))
    side = scale.to_flow(sum(r.flows.get("side", 0.0) for r in results))
    rho, cp = lubricant.density_at(temperature), lubricant.specific_heat_at(temperature)
    heat = film_temperatures(power, leading, side, rho, cp, balance)
    return _Film(temperature=temperature, viscosity=mu, power=power, leading_flow=leading, side_flow=side,
                 density=rho, specific_heat=cp, heat=heat, equilibrium=eq)


def effective_temperature(bearing: JournalBearing, duty: JournalDuty, lubricant: Lubricant,
                          balance: HeatBalance, **equilibrium_options: Any) -> EffectiveTemperature:
    """The effective temperature of a journal bearing: its level-1 heat balance at a fixed point.

    Parameters
    ----------
    bearing : JournalBearing
        Geometry (non-dimensional); its ``supply_pressure`` is replaced by ``duty.supply_pressure``.
    duty : JournalDuty
        Size, speed and load in SI.
    lubricant : Lubricant
        The oil (viscosity law, density, specific heat).
    balance : HeatBalance
        Supply temperature, carry-over, conducted share, effective fraction, tolerance.
    **equilibrium_options
        Keywords of :func:`bearingfe.bearings.journal.equilibrium` (``size``, ``cavitation``,
        ``structured``, ``discretization``, ...), used at every trial temperature.

    Returns
    -------
    EffectiveTemperature

    Raises
    ------
    ThermalError
        No fixed point below ``balance.max_temperature``, Brent's iteration did not converge in
        ``balance.max_iterations``, or an isoviscous equilibrium of the search failed.
    """
    def film(t: float) -> _Film:
        return _solve_film(bearing, duty, lubricant, balance, t, equilibrium_options)

    root, residual, films = fixed_point(film, balance)
    return _result(films[root], films[balance.supply_temperature], balance, len(films), residual, duty)


def fixed_point(film: Callable[[float], Any], balance: HeatBalance) -> tuple[float, float, dict]:
    """The effective temperature where ``film(T).heat.effective = T``, by Brent's method on a bracket.

    Parameters
    ----------
    film : callable
        ``T [K] -> state`` with ``state.heat`` a :class:`FilmTemperatures` (an isoviscous solve at the
        viscosity of ``T``); called once per trial temperature.
    balance : HeatBalance
        Supply temperature (the bracket's lower end), tolerance, largest temperature and iterations.

    Returns
    -------
    root : float
        ``T_eff`` [K].
    residual : float
        ``|film(T_eff).heat.effective - T_eff|`` [K].
    films : dict
        Every state solved, by trial temperature (the supply temperature and the root among them).

    Raises
    ------
    ThermalError
        No sign change of ``g(T) = film(T).heat.effective - T`` up to ``max_temperature``, or no
        convergence in ``max_iterations``.
    """
    films: dict[float, Any] = {}

    def g(t: float) -> float:
        if t not in films:
            films[t] = film(t)
        return films[t].heat.effective - t

    Ts = balance.supply_temperature
    if g(Ts) <= balance.tolerance:
        root = Ts
    else:
        hi = min(Ts + g(Ts), balance.max_temperature)
        while g(hi) > 0:
            if hi >= balance.max_temperature:
                raise ThermalError(f"the heat balance has no fixed point below max_temperature = "
                                   f"{balance.max_temperature:g} K (effective temperature still rising at {hi:.6g} K)")
            hi = min(Ts + 2.0 * (hi - Ts), balance.max_temperature)
        if g(hi) == 0:
            root = hi
        else:
            root, report = brentq(g, Ts, hi, xtol=balance.tolerance, maxiter=balance.max_iterations,
                                  full_output=True, disp=False)
            if not report.converged:
                raise ThermalError(f"Brent's iteration on the effective temperature did not converge in "
                                   f"{balance.max_iterations} iterations ({report.flag})")
    residual = abs(g(root))
    return root, residual, films


def _result(end: _Film, start: _Film, balance: HeatBalance, evaluations: int, residual: float,
            duty: JournalDuty) -> EffectiveTemperature:
    h = end.heat
    c = duty.clearance

    def h_min(f: _Film) -> float:
        return c * min(r.h_min for r in f.equilibrium.state.results)
    return EffectiveTemperature(
        temperature=end.temperature, supply_temperature=balance.supply_temperature, inlet_temperature=h.inlet,
        outlet_temperature=h.outlet, side_temperature=h.side, temperature_rise=h.rise, viscosity=end.viscosity,
        supply_viscosity=start.viscosity, density=end.density, specific_heat=end.specific_heat,
        friction_power=end.power, convected_power=h.convected, conducted_power=h.conducted,
        leading_flow=end.leading_flow, side_flow=end.side_flow,
        trailing_flow=max(end.leading_flow - end.side_flow, 0.0), supply_flow=h.supply_flow,
        eccentricity=end.equilibrium.eps, min_film=h_min(end), isothermal_eccentricity=start.equilibrium.eps,
        isothermal_min_film=h_min(start), isothermal_friction_power=start.power, evaluations=evaluations,
        residual=residual, balance=balance, equilibrium=end.equilibrium)
