r"""Level 1 thermal model of a thrust bearing: the pads' effective temperature from their heat balance.

The balance of :mod:`bearingfe.thermal.heat_balance` (:func:`~bearingfe.thermal.heat_balance.film_temperatures`)
with the thrust pad's flows: ``Q`` the oil entering the film through the leading edges (and out of any
pockets), ``Q_s`` the oil leaving through the inner and outer rims (the pads' "side" flow, leaving on
average at ``T_in + dT/2``), ``Q_t = Q - Q_s`` the trailing-edge flow that meets the next pad (the
carry-over fraction ``lambda`` of it enters that pad unmixed). The pads are solved isoviscously at the
viscosity of the effective temperature (tilting pads in equilibrium, or fixed pads carrying the load), and
temperature and film are iterated to the fixed point by the same Brent bracket as the journal bearing's
(:func:`~bearingfe.thermal.heat_balance.fixed_point`), each solve warm-started from the previous trial with
its film scaled as ``mu^(1/2)`` (the isoviscous similarity at fixed load).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..bearings.thrust import ThrustPerformance, carry
from ..core.scales import Scale
from .heat_balance import FilmTemperatures, HeatBalance, film_temperatures, fixed_point
from .lubricant import Lubricant

__all__ = ["ThrustTemperature", "thrust_temperature"]


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
