r"""Level 1 thermal model of pad bearings: the effective temperature of thrust pads and of tilting-pad
journal bearings from their heat balance.

Thrust pads (:func:`thrust_temperature`): the balance of :mod:`bearingfe.thermal.heat_balance` (:func:`~bearingfe.thermal.heat_balance.film_temperatures`)
with the thrust pad's flows: ``Q`` the oil entering the film through the leading edges (and out of any
pockets), ``Q_s`` the oil leaving through the inner and outer rims (the pads' "side" flow, leaving on
average at ``T_in + dT/2``), ``Q_t = Q - Q_s`` the trailing-edge flow that meets the next pad (the
carry-over fraction ``lambda`` of it enters that pad unmixed). The pads are solved isoviscously at the
viscosity of the effective temperature (tilting pads in equilibrium, or fixed pads carrying the load), and
temperature and film are iterated to the fixed point by the same Brent bracket as the journal bearing's
(:func:`~bearingfe.thermal.heat_balance.fixed_point`), each solve warm-started from the previous trial with
its film scaled as ``mu^(1/2)`` (the isoviscous similarity at fixed load).

Tilting-pad journal bearings (:func:`tilting_pad_temperature`): the same balance over the loaded pads, ``Q``
into their leading edges, ``Q_s`` out of their axial edges, the trailing flow of one pad meeting the next
pad's leading edge with the supply between them (the carry-over fraction of it unmixed); the shaft and
pads in equilibrium (:func:`bearingfe.bearings.tilting_pad.tilting_pad_equilibrium`) at each trial
temperature, warm-started from the previous one on the same pad meshes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..bearings.thrust import ThrustPerformance, carry
from ..core.scales import Scale
from .heat_balance import FilmTemperatures, HeatBalance, film_temperatures, fixed_point
from .lubricant import Lubricant

__all__ = ["ThrustTemperature", "thrust_temperature", "TiltingPadTemperature", "tilting_pad_temperature"]


@dataclass(frozen=True)
class _PadFilm:
    temperature: float
    viscosity: float
    performance: ThrustPerformance
    heat: FilmTemperatures


@dataclass(frozen=True)
class ThrustTemperature:
    """A thrust bearing at the fixed point of its level-1 heat balance (SI).

    Attributes
    ----------
    temperature : float
        Effective temperature ``T_eff`` [K].
    supply_temperature : float
        ``T_s`` [K].
    heat : FilmTemperatures
        Inlet, outlet, side temperatures, rise, supply flow, convected and conducted heat at ``T_eff``.
    viscosity, supply_viscosity : float
        ``mu(T_eff)`` and ``mu(T_s)`` [Pa s].
    performance : ThrustPerformance
        The bearing at ``T_eff``.
    isothermal : ThrustPerformance
        The bearing at the supply temperature (the isothermal model's answer).
    evaluations : int
        Bearing solves of the fixed point.
    residual : float
        ``|T_eff(film at T_eff) - T_eff|`` [K].
    """

    temperature: float
    supply_temperature: float
    heat: FilmTemperatures
    viscosity: float
    supply_viscosity: float
    performance: ThrustPerformance = field(repr=False)
    isothermal: ThrustPerformance = field(repr=False)
    evaluations: int = 0
    residual: float = 0.0


def thrust_temperature(pad, mesh, load: float, speed: float, lubricant: Lubricant, balance: HeatBalance, *,
                       reference_film: float, pivot: str | None = "point", pitch: float = 0.0, roll: float = 0.0,
                       **solve_options: Any) -> ThrustTemperature:
    """The effective temperature of a thrust bearing carrying ``load`` [N] at ``speed`` [rad/s].

    Parameters
    ----------
    pad : ThrustPad
    mesh : SupportMesh
        The pad's mesh (:meth:`ThrustPad.mesh`).
    lubricant, balance
        The oil and how its heat is carried away (supply temperature, carry-over, conducted share).
    reference_film : float
        The film scale ``h_ref`` [m] of the non-dimensional solves.
    pivot, pitch, roll, solve_options
        As in :func:`bearingfe.bearings.thrust.carry`.
    """
    last: dict[str, Any] = {}

    def film(t: float) -> _PadFilm:
        mu = lubricant.viscosity(t)
        scale = Scale(pad.outer_radius, reference_film, mu, speed)
        start = None
        if last:
            k = math.sqrt(mu / last["mu"])
            p = last["perf"]
            start = (p.h_pivot * k, p.pitch * k, p.roll * k)
        perf = carry(pad, mesh, scale, load, pivot=pivot, pitch=pitch, roll=roll, start=start, **solve_options)
        last.update(mu=mu, perf=perf)
        side = perf.flows.get("inner", 0.0) + perf.flows.get("outer", 0.0)
        leading = perf.flows.get("leading", 0.0) + perf.flows.get("pocket", 0.0)
        heat = film_temperatures(perf.power, leading, side, lubricant.density_at(t), lubricant.specific_heat_at(t),
                                 balance)
        return _PadFilm(temperature=t, viscosity=mu, performance=perf, heat=heat)

    root, residual, films = fixed_point(film, balance)
    end = films[root] if root in films else film(root)
    start = films[balance.supply_temperature]
    return ThrustTemperature(temperature=root, supply_temperature=balance.supply_temperature, heat=end.heat,
                             viscosity=end.viscosity, supply_viscosity=start.viscosity,
                             performance=end.performance, isothermal=start.performance,
                             evaluations=len(films), residual=residual)


@dataclass(frozen=True)
class _JournalPads:
    temperature: float
    viscosity: float
    power: float
    leading: float
    side: float
    equilibrium: Any
    heat: FilmTemperatures


@dataclass(frozen=True)
class TiltingPadTemperature:
    """A tilting-pad journal bearing at the fixed point of its level-1 heat balance (SI).

    Attributes
    ----------
    temperature, supply_temperature : float
        ``T_eff`` and ``T_s`` [K].
    heat : FilmTemperatures
        Inlet, outlet, side temperatures, rise, supply flow, convected and conducted heat at ``T_eff``.
    viscosity, supply_viscosity : float
        ``mu(T_eff)``, ``mu(T_s)`` [Pa s].
    friction_power, isothermal_friction_power : float
        [W] at ``T_eff`` and at ``T_s``.
    leading_flow, side_flow : float
        Into the pads' leading edges and out of their axial edges [m^3/s] at ``T_eff``.
    eccentricity, isothermal_eccentricity : float
        Shaft eccentricity over the pad clearance [-].
    min_film, isothermal_min_film : float
        Smallest film over the pads [m].
    equilibrium : TiltingPadEquilibrium
        At ``T_eff`` (non-dimensional at ``viscosity``).
    evaluations : int
    residual : float
        [K].
    density, specific_heat : float
        Of the oil at ``T_eff`` [kg/m^3], [J/(kg K)].

    The journal's names (:class:`~bearingfe.thermal.heat_balance.EffectiveTemperature`) are properties:
    ``inlet_temperature``, ``outlet_temperature``, ``temperature_rise``, ``convected_power``,
    ``conducted_power``, ``supply_flow``.
    """

    temperature: float
    supply_temperature: float
    heat: FilmTemperatures
    viscosity: float
    supply_viscosity: float
    friction_power: float
    isothermal_friction_power: float
    leading_flow: float
    side_flow: float
    eccentricity: float
    isothermal_eccentricity: float
    min_film: float
    isothermal_min_film: float
    equilibrium: Any = field(repr=False)
    evaluations: int = 0
    residual: float = 0.0
    density: float = 0.0
    specific_heat: float = 0.0

    # the names of :class:`~bearingfe.thermal.heat_balance.EffectiveTemperature` (one summary for both)
    @property
    def inlet_temperature(self) -> float:
        return self.heat.inlet

    @property
    def outlet_temperature(self) -> float:
        return self.heat.outlet

    @property
    def temperature_rise(self) -> float:
        return self.heat.rise

    @property
    def convected_power(self) -> float:
        return self.heat.convected

    @property
    def conducted_power(self) -> float:
        return self.heat.conducted

    @property
    def supply_flow(self) -> float:
        return self.heat.supply_flow


def tilting_pad_temperature(bearing, load: float, speed: float, lubricant: Lubricant, balance: HeatBalance, *,
                            size: float = 0.1, cavitation: str = "reynolds", element: str = "P1",
                            meshes=None) -> TiltingPadTemperature:
    """The effective temperature of a tilting-pad journal bearing carrying ``load`` [N] (along ``-y``, on or
    between pads as its geometry says) at ``speed`` [rad/s].

    Parameters
    ----------
    bearing : TiltingPadBearing
    lubricant, balance
        The oil and how its heat is carried away.
    size, cavitation, element, meshes
        As in :func:`bearingfe.bearings.tilting_pad.tilting_pad_equilibrium`.
    """
    from ..bearings.tilting_pad import tilting_pad_equilibrium, tilting_pad_meshes
    from .heat_balance import ThermalError

    geometry = bearing.geometry
    meshes = tilting_pad_meshes(geometry, size) if meshes is None else meshes
    last: dict[str, Any] = {}

    def film(t: float) -> _JournalPads:
        mu = lubricant.viscosity(t)
        scale = Scale(bearing.radius, bearing.pad_clearance, mu, speed)
        try:
            eq = tilting_pad_equilibrium(geometry, (0.0, -load / bearing.force_scale(mu, speed)), meshes=meshes,
                                         cavitation=cavitation, element=element, start=last.get("eq"),
                                         pivot_stiffness=bearing.pivot_stiffness_parameter(mu, speed))
        except RuntimeError as exc:
            raise ThermalError(f"at {t:.6g} K (viscosity {mu:.4g} Pa s) the tilting-pad equilibrium failed: "
                               f"{exc}") from exc
        last["eq"] = eq
        results = [st.results[0] for st in eq.pads.states if st is not None]
        power = scale.to_moment(sum(r.friction for r in results)) * speed
        leading = scale.to_flow(sum(r.flows.get("inlet", 0.0) - r.flows.get("arc_start", 0.0) for r in results))
        side = scale.to_flow(sum(r.flows.get("side", 0.0) for r in results))
        heat = film_temperatures(power, leading, side, lubricant.density_at(t), lubricant.specific_heat_at(t),
                                 balance)
        return _JournalPads(temperature=t, viscosity=mu, power=power, leading=leading, side=side, equilibrium=eq,
                            heat=heat)

    def h_min(f: _JournalPads) -> float:
        return bearing.pad_clearance * min(st.results[0].h_min for st in f.equilibrium.pads.states if st is not None)

    root, residual, films = fixed_point(film, balance)
    end = films[root] if root in films else film(root)
    start = films[balance.supply_temperature]
    return TiltingPadTemperature(
        temperature=root, supply_temperature=balance.supply_temperature, heat=end.heat, viscosity=end.viscosity,
        supply_viscosity=start.viscosity, friction_power=end.power, isothermal_friction_power=start.power,
        leading_flow=end.leading, side_flow=end.side, eccentricity=end.equilibrium.eps,
        isothermal_eccentricity=start.equilibrium.eps, min_film=h_min(end), isothermal_min_film=h_min(start),
        equilibrium=end.equilibrium, evaluations=len(films), residual=residual,
        density=lubricant.density_at(root), specific_heat=lubricant.specific_heat_at(root))
