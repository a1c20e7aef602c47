r"""Level 1 over the pump cycle: the plunger shoe's effective temperature from its cycle-mean heat balance.

The shoe's film is run over a revolution at the viscosity of a trial effective
temperature (:func:`bearingfe.transient.simulate`, isoviscous); its cycle means
enter the balance of :func:`bearingfe.thermal.heat_balance.film_temperatures`:

- the heat: the shear power on the sliding eccentric ``M omega (1 - dphi2/dbeta)``
  (``M`` the film's friction moment) plus the work of the pocket's pressure on
  the oil it feeds, ``p_pocket Q_pocket`` (the squeeze work of the shoe's orbit
  is left out);
- the flows: into the film through its leading edge (``psi`` start for the
  eccentric sliding towards ``+psi``) and out of the pocket, and out through
  the sides ``z = +-a``, from the re-solved film of every sample
  (:func:`bearingfe.transient.state_result`); the pocket's oil and the oil the
  eccentric drags in are both taken at the supply temperature.

The fixed point on ``T_eff`` is :func:`bearingfe.thermal.heat_balance.fixed_point`.
The cycle is short against the oil's passage only in part (the film is crossed
in a fraction of a revolution), so besides the cycle-mean rise the result has
the *quasi-steady peak*: the largest outlet temperature over the samples of the
balance of each instant, ``T_in + (1 - chi) P(beta) / (rho c_p (Q_s/2 + Q_t)(beta))``.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..bearings.pump import EccentricPump
from ..geometry.meshing import SupportMesh
from ..transient import Trajectory, simulate, state_result
from .heat_balance import HeatBalance, ThermalError, film_rise, film_temperatures, fixed_point
from .lubricant import Lubricant

__all__ = ["CycleHeat", "CycleTemperature", "cycle_heat", "cycle_temperature", "shoe_pad"]


@dataclass(frozen=True)
class CycleHeat:
    """Heat and flows of one pump run, per sample and as cycle means (SI).

    Attributes
    ----------
    power, leading_flow, side_flow : ndarray
        Heat into the film [W], flow in through the leading edge and the pockets and out through
        the sides [m^3/s], at the trajectory's samples.
    mean_power, mean_leading_flow, mean_side_flow : float
        Their time means over the run [W], [m^3/s].
    """

    power: np.ndarray
    leading_flow: np.ndarray
    side_flow: np.ndarray
    mean_power: float
    mean_leading_flow: float
    mean_side_flow: float


def _mean(values: np.ndarray, t: np.ndarray) -> float:
    return float(np.trapezoid(values, t) / (t[-1] - t[0]))


def cycle_heat(pump: EccentricPump, mesh: SupportMesh, traj: Trajectory, cavitation: str = "none") -> CycleHeat:
    """Heat and flows of a pump run (see the module docstring), from its samples re-solved.

    Raises
    ------
    ValueError
        The shoe's surface has no arc edges (``arc_start``/``arc_end``) to tell the leading edge by.
    """
    sc = pump.scale
    n = traj.beta.size
    leading, side = np.empty(n), np.empty(n)
    for k in range(n):
        flows = state_result(pump, mesh, traj, k, cavitation).flows
        if "arc_start" not in flows or "arc_end" not in flows:
            raise ValueError("the pump's level-1 balance needs a shoe surface with arc edges (a rectangle in "
                             "(psi, z)) to find the leading edge")
        edge = "arc_start" if traj.wedge[k] >= 0 else "arc_end"
        leading[k] = sc.to_flow(flows.get("inlet", 0.0) - flows[edge])
        side[k] = sc.to_flow(flows.get("side", 0.0))
    power = (traj.friction_moment * sc.speed * traj.wedge
             + np.where(traj.flow_inlet > 0, traj.chamber_pressure * traj.flow_inlet, 0.0))
    t = traj.t
    return CycleHeat(power=power, leading_flow=leading, side_flow=side, mean_power=_mean(power, t),
                     mean_leading_flow=_mean(leading, t), mean_side_flow=_mean(side, t))


@dataclass(frozen=True)
class _Run:
    temperature: float
    viscosity: float
    density: float
    specific_heat: float
    trajectory: Trajectory
    cycle: CycleHeat
    heat: Any


@dataclass(frozen=True)
class CycleTemperature:
    """The plunger shoe at the fixed point of its cycle-mean heat balance (SI).

    Attributes
    ----------
    temperature : float
        Effective film temperature ``T_eff`` [K].
    supply_temperature, inlet_temperature, outlet_temperature : float
        ``T_s``, ``T_in`` and the cycle-mean outlet ``T_in + dT`` [K].
    temperature_rise : float
        Cycle-mean rise ``dT`` across the film [K].
    peak_temperature : float
        Largest quasi-steady outlet temperature over the cycle [K].
    viscosity, supply_viscosity : float
        ``mu(T_eff)`` and ``mu(T_s)`` [Pa s].
    density, specific_heat : float
        At ``T_eff`` [kg/m^3], [J/(kg K)].
    friction_power, convected_power, conducted_power : float
        Cycle means: heat into the film, carried out by the oil, conducted away [W].
    leading_flow, side_flow : float
        Cycle-mean flows in (leading edge and pockets) and out of the sides [m^3/s].
    smallest_film, isothermal_smallest_film : float
        Smallest film over the cycle at ``T_eff`` and at ``T_s`` [m].
    isothermal_friction_power : float
        Cycle-mean heat at ``T_s`` [W].
    evaluations : int
        Pump runs solved.
    residual : float
        ``|T_eff(T) - T|`` at the answer [K].
    balance : HeatBalance
    trajectory, isothermal_trajectory : Trajectory
        The runs at ``T_eff`` and at ``T_s``.
    """

    temperature: float
    supply_temperature: float
    inlet_temperature: float
    outlet_temperature: float
    temperature_rise: float
    peak_temperature: float
    viscosity: float
    supply_viscosity: float
    density: float
    specific_heat: float
    friction_power: float
    convected_power: float
    conducted_power: float
    leading_flow: float
    side_flow: float
    smallest_film: float
    isothermal_smallest_film: float
    isothermal_friction_power: float
    evaluations: int
    residual: float
    balance: HeatBalance
    trajectory: Trajectory = field(repr=False, compare=False)
    isothermal_trajectory: Trajectory = field(repr=False, compare=False)


def cycle_temperature(pump: EccentricPump, mesh: SupportMesh, lubricant: Lubricant, balance: HeatBalance,
                      **simulate_options: Any) -> CycleTemperature:
    """The plunger shoe's effective temperature over the pump cycle (level 1).

    Parameters
    ----------
    pump : EccentricPump
        Its ``viscosity`` is replaced by the lubricant's at each trial temperature.
    mesh : SupportMesh
        The shoe's mesh (:func:`bearingfe.transient.pump_mesh`).
    lubricant : Lubricant
    balance : HeatBalance
    **simulate_options
        Keywords of :func:`bearingfe.transient.simulate` (``revolutions`` 1 by default, ``start``,
        ``rtol``, ``cavitation``, ``element``), the same for every run.

    Raises
    ------
    ThermalError
        A run did not complete (its film closed) at a trial temperature, or the fixed point failed
        (:func:`bearingfe.thermal.heat_balance.fixed_point`).
    """
    options = {"revolutions": 1.0, **simulate_options}
    revolutions = options.pop("revolutions")
    cavitation = options.get("cavitation", "none")

    def run(t: float) -> _Run:
        mu = lubricant.viscosity(t)
        at = dataclasses.replace(pump, viscosity=mu)
        traj = simulate(at, mesh, revolutions, **options)
        if traj.status != "completed":
            raise ThermalError(f"at {t:.6g} K (viscosity {mu:.4g} Pa s) the pump run ended {traj.status!r}: "
                               f"{traj.message}")
        cyc = cycle_heat(at, mesh, traj, cavitation)
        rho, cp = lubricant.density_at(t), lubricant.specific_heat_at(t)
        heat = film_temperatures(cyc.mean_power, cyc.mean_leading_flow, cyc.mean_side_flow, rho, cp, balance)
        return _Run(temperature=t, viscosity=mu, density=rho, specific_heat=cp, trajectory=traj, cycle=cyc, heat=heat)

    root, residual, runs = fixed_point(run, balance)
    end, start = runs[root], runs[balance.supply_temperature]
    h, cyc = end.heat, end.cycle
    peak = h.inlet + float(np.max(film_rise(cyc.power, cyc.leading_flow, cyc.side_flow,
                                            end.density * end.specific_heat, balance.conducted_fraction)))
    return CycleTemperature(
        temperature=root, supply_temperature=balance.supply_temperature, inlet_temperature=h.inlet,
        outlet_temperature=h.outlet, temperature_rise=h.rise, peak_temperature=peak, viscosity=end.viscosity,
        supply_viscosity=start.viscosity, density=end.density, specific_heat=end.specific_heat,
        friction_power=cyc.mean_power, convected_power=h.convected, conducted_power=h.conducted,
        leading_flow=cyc.mean_leading_flow, side_flow=cyc.mean_side_flow,
        smallest_film=end.trajectory.smallest_film, isothermal_smallest_film=start.trajectory.smallest_film,
        isothermal_friction_power=start.cycle.mean_power, evaluations=len(runs), residual=residual,
        balance=balance, trajectory=end.trajectory, isothermal_trajectory=start.trajectory)


def shoe_pad(pump: EccentricPump, trajectory: Trajectory, index: int):
    """The plunger shoe's film at one sample of a pump run as a :class:`~bearingfe.thermal.film_energy.Pad`
    (SI), for level 2 (:func:`bearingfe.thermal.film_energy.film_energy`) at that state.

    In the shoe frame the eccentric slides at ``wedge omega R0`` past the shoe and the film is
    ``h = c (1 + gamma cos(psi - delta))`` (:mod:`bearingfe.bearings.pump`); unrolled, ``x = R0 (psi -
    psi_start)`` along the arc (from ``psi_end`` backwards when the sliding runs towards ``-psi``, so that
    ``x = 0`` is always the leading edge) and ``y = R0 (z + a)`` across, ambient pressure on every edge.
    The state is frozen: its squeeze rates (``gamma'``, ``delta'``) are left out, as is the pocket (a
    shoe with pockets is refused: the pad has none).

    Parameters
    ----------
    pump : EccentricPump
        A shoe surface without pockets (the rectangle ``arc x [-a, a]``).
    trajectory : Trajectory
        A run of that pump (:func:`bearingfe.transient.simulate`).
    index : int
        The sample.

    Raises
    ------
    ValueError
        A shoe that is not a plain rectangle, a sample out of range, or a sample where the eccentric does not slide.
    """
    from .film_energy import Pad

    surface = pump.surface
    if surface.inlets or surface.recesses or surface.outer is not None or surface.periodic:
        raise ValueError("shoe_pad needs a plain rectangular shoe (no pockets, recesses, outline or periodic arc): "
                         "the pad has none")
    n = trajectory.beta.size
    if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not -n <= index < n:
        raise ValueError(f"index must be an integer sample of the run, in [-{n}, {n}), got {index!r}")
    R0, c = pump.radius, pump.clearance
    a0, a1 = pump.surface.arc
    g, d, w = (float(v[index]) for v in (trajectory.gamma, trajectory.delta, trajectory.wedge))
    if w == 0.0:
        raise ValueError(f"the eccentric does not slide past the shoe at sample {index} (wedge 0)")
    start, sign = (a0, 1.0) if w > 0 else (a1, -1.0)
    return Pad(R0 * (a1 - a0), 2.0 * pump.surface.half_width * R0,
               lambda x, y: c * (1.0 + g * np.cos(start + sign * np.asarray(x) / R0 - d)) + 0.0 * np.asarray(y),
               abs(w) * pump.scale.speed * R0, "ambient")
