r"""The plunger shoe with its pocket fed from the chamber through the plunger's restrictor.

The rigid film of :mod:`bearingfe.transient.rigid` (rates from the 2x2 superposition system),
with the pocket no longer at the chamber pressure ``p_ch(beta)`` but at its own pressure ``p_r``,
fed through :attr:`bearingfe.EccentricPump.shoe_supply` (a capillary or an orifice,
:class:`bearingfe.bearings.hydrostatic.Restrictor`). What enters the pocket through the restrictor
leaves it into the film, fills the pocket's growing gap, or compresses its oil::

    V/K dp_r/dt = Q_restrictor(p_ch - p_r) - Q_film - dV/dt,     dV/dt = int_pocket dh/dt dA,

with ``Q_film`` the film's outflow from the pocket (linear in the superposition's sources: one
flux per unit field, :func:`bearingfe.film.pockets.pocket_flows`) and ``dh/dt`` the
shoe's squeeze over the pocket (``dh/dgamma = cos(phi - delta)``, ``dh/ddelta = gamma sin(phi -
delta)``, integrated from the pocket's moments). With the restrictor's ``pocket_volume`` the
state is ``(gamma, delta, p_r)`` [-, rad, -] and ``p_r`` has this rate equation
(``dp_r/dbeta = K R0^2 c / (V P) (...)``, non-dimensional flows); without it the pocket holds no
oil of its own and ``p_r`` is balanced at each instant (the right side at zero), the state stays
``(gamma, delta)``. The trajectory's ``inlet_pressure`` is ``p_r``; its ``flow_restrictor`` and
``flow_pocket_gap`` are ``Q_restrictor`` and ``dV/dt`` [m^3/s] (``flow_inlet`` is ``Q_film``).

Starts: the rigid model's steady state at ``beta0`` (pocket at the chamber pressure) with the
pocket balanced on it, or the periodic state from there.

:class:`FedCavitating` is the same pocket on the film with Swift-Stieber or Gumbel rupture (the
rates of :class:`~bearingfe.transient.cavitating.Cavitating`): ``Q_film`` is then the cavitated
film's outflow from the pocket (its result's ``inlet`` flow), no longer linear in the pocket
pressure, so the pocket needs its ``pocket_volume`` (``p_r`` a state; a pocket balanced at each
instant would need the cavitated film solved inside its balance). Its start is the rigid model's,
the pocket balanced on the film without rupture (the first steps take it to the cavitated
balance; the periodic start converges it, but only to the integrator's accuracy: on the shipped
orifice pump Anderson's and the fixed-point start stall at a residual of 1.5e-5 to 1.3e-4 with
``rtol = 1e-5``, and reach ``periodic_tol = 1e-6`` with ``rtol = 1e-7``, measured; so the model is
``periodic_tied``: its search runs at ``rtol <= periodic_tol / 10`` by itself,
:func:`bearingfe.transient.periodic.search_settings`). Where the compressed pocket outlasts the chamber's
decompression it may press the shoe off harder than a film without tension can hold: the rates'
Newton finds no state and the run ends ``"no-equilibrium"``, its message giving the pocket's
force against the plunger load.

:class:`FedJFO` is the same pocket on the mass-conserving (JFO) film of
:class:`~bearingfe.transient.jfo.JFO`: the pocket pressure is stepped by the film's backward Euler with
the fill fraction, its rate equation solved at each step's end together with the load balance (the gap's
volume change over the step, so the pocket's oil is conserved from step to step as the film's is).
"""

from __future__ import annotations

import math

import numpy as np

from .base import NoEquilibrium, TrialRejected
from .cavitating import Cavitating
from .jfo import JFO, JFOState
from .rigid import Rigid
from ..bearings.hydrostatic import SupplyError, balance_pockets
from ..film.pockets import PocketFilm, pocket_flows
from ..bearings.pump import EccentricPump
from ..cavitation import CavitationError
from ..core.linalg import DEFAULT_SOLVER
from ..film import Superposition, source_weights
from ..film.mesh_operators import operators
from ..geometry.meshing import SupportMesh

__all__ = ["Fed", "FedCavitating", "FedJFO"]


class Fed(Rigid):
    """The rigid film with the pocket fed through the plunger's restrictor (see the module docstring).

    Parameters
    ----------
    pump : EccentricPump
        With ``shoe_supply`` (a :class:`~bearingfe.bearings.hydrostatic.Restrictor`).
    mesh : SupportMesh
        Of ``pump.surface``; its pockets share the one restrictor (one pocket pressure).
    formulation, element, solver
        See :func:`bearingfe.superpose`.
    """

    name = "fed"
    # Newton shooting's monodromy is that of a (gamma, delta) state: not for the pocket-pressure state
    periodic_methods = ("fixed-point", "anderson", "one-revolution")
    periodic_default = "anderson"

    def __init__(self, pump: EccentricPump, mesh: SupportMesh, *, formulation: str = "pi", element: str = "P1",
                 solver: str = DEFAULT_SOLVER, **options) -> None:
        if pump.shoe_supply is None:
            raise ValueError(f"{pump.name!r} has no shoe_supply: its pocket is at the chamber pressure (the rigid "
                             "model)")
        if not mesh.has_inlet:
            raise ValueError("the fed model needs a shoe with a pocket (the mesh has no 'inlet' boundary)")
        super().__init__(pump, mesh, formulation=formulation, element=element, solver=solver, **options)
        self.restrictor = pump.shoe_supply
        sc = pump.scale
        volume = self.restrictor.pocket_volume
        #: dp_r/dbeta [-] per unit flow imbalance [omega R0^2 c]; None: no pocket volume (balanced pocket)
        self.compressibility = (None if volume is None else
                                self.restrictor.bulk_modulus * sc.radius**2 * sc.clearance / (volume * sc.pressure))
        self._flux: dict[int, tuple[Superposition, np.ndarray]] = {}

    # -- the pocket ------------------------------------------------------------------------------------

    def unit_flux(self, sup: Superposition) -> np.ndarray:
        """The film's outflow from the pockets of each unit field (4,) [omega R0^2 c]: linear in the sources."""
        got = self._flux.get(id(sup))
        if got is None or got[0] is not sup:
            flux = pocket_flows(PocketFilm(whole=sup, pockets=(sup,)), sup.fields, np.eye(4))[0]
            if len(self._flux) > 16:
                self._flux.clear()
            got = self._flux[id(sup)] = (sup, flux)
        return got[1]

    def _outflow(self, beta: float, y: np.ndarray, rates: np.ndarray, p: float, result=None) -> float:
        """``Q_film + dV/dt`` [omega R0^2 c] at pocket pressure ``p`` and squeeze rates ``rates``: the linear film's
        outflow, or that of the film ``result`` the rates were balanced on (a cavitated film)."""
        sup = self.superposition(y[0], y[1])
        if result is not None:
            q_film = float(result.flows["inlet"])
        else:
            q_film = float(self.unit_flux(sup) @ source_weights(float(self.pump.wedge(beta)), rates, p))
        return q_film + self._gap_rate(sup, y, rates)

    @staticmethod
    def _gap_rate(sup: Superposition, y: np.ndarray, rates: np.ndarray) -> float:
        """``dV/dbeta = int_pocket dh/dbeta dA`` [omega R0^2 c]: the shoe's motion opening the pocket's gap."""
        _, mc, ms = sup.operators.pocket_moments  # int_pocket (1, cos phi, sin phi)
        c, s = math.cos(y[1]), math.sin(y[1])
        return float(rates[0] * (c * mc + s * ms) + rates[1] * y[0] * (c * ms - s * mc))

    def _law(self, beta: float):
        return self.restrictor.law_at(float(self.pump.chamber_pressure(beta)), self.pump.scale)

    def pocket_pressure(self, beta: float, y: np.ndarray) -> float:
        """``p_r`` [-]: the state's third entry, or balanced at this instant (no pocket volume)."""
        if np.size(y) > 2:
            return float(y[2])
        return self._balanced(beta, y)

    def _balanced(self, beta: float, y: np.ndarray) -> float:
        """The pocket pressure at which the restrictor feeds exactly the film and the pocket's gap."""
        pump = self.pump
        sup = self.superposition(y[0], y[1])
        load, wedge = pump.load_vector(beta), float(pump.wedge(beta))
        r0 = np.asarray(sup.rates_for_load(load, wedge, 0.0))
        r1 = np.asarray(sup.rates_for_load(load, wedge, 1.0)) - r0  # the rates are linear in the pocket pressure
        f0 = self._outflow(beta, y, r0, 0.0)
        f1 = self._outflow(beta, y, r0 + r1, 1.0) - f0
        try:
            return float(balance_pockets([self._law(beta)], lambda p: np.array([f0 + f1 * p[0]]),
                                         np.array([[f1]]))[0])
        except SupplyError as exc:
            raise NoEquilibrium(f"beta = {beta:.4f} rad: the pocket fed through the restrictor has no balance ({exc})")

    def rates(self, beta: float, y: np.ndarray) -> np.ndarray:
        rates, result = self.balance(beta, y, full=False)
        if self.compressibility is None or np.size(y) == 2:
            return rates
        p = float(y[2])
        imbalance = self._law(beta).flow(p) - self._outflow(beta, y, rates, p, result)
        return np.array([rates[0], rates[1], self.compressibility * imbalance])

    # -- start and samples -----------------------------------------------------------------------------

    def initial_state(self, settings) -> tuple[float, np.ndarray]:
        beta0, y0 = super().initial_state(settings)
        y0 = np.asarray(y0, float)[:2]
        if self.compressibility is None:
            return beta0, y0
        return beta0, np.array([y0[0], y0[1], self._balanced(beta0, y0)])

    def sample_state(self, beta: float, y: np.ndarray):
        """The rigid sample with the pocket pressure [-], the restrictor's flow and the pocket's gap rate [m^3/s]."""
        rates, res, sup, more = super().sample_state(beta, y)
        p = self.pocket_pressure(beta, y)
        sc = self.pump.scale
        return rates, res, sup, dict(more, inlet_pressure=p, flow_restrictor=sc.to_flow(self._law(beta).flow(p)),
                                     flow_pocket_gap=sc.to_flow(self._gap_rate(sup, y, rates)))


class FedCavitating(Fed, Cavitating):
    """The fed pocket (:class:`Fed`) on the film with Swift-Stieber or Gumbel rupture (:class:`Cavitating`).

    Parameters
    ----------
    pump : EccentricPump
        With ``shoe_supply`` and its ``pocket_volume`` (the pocket pressure a state).
    mesh, formulation, element, solver
        As :class:`Fed`.
    cavitation : {"reynolds", "gumbel"}
    """

    name = "fed cavitating"
    # its return map converges only to the integrator's accuracy: the periodic search ties rtol to periodic_tol
    periodic_tied = True

    def __init__(self, pump: EccentricPump, mesh: SupportMesh, *, cavitation: str = "reynolds",
                 formulation: str = "pi", element: str = "P1", solver: str = DEFAULT_SOLVER) -> None:
        if pump.shoe_supply is not None and pump.shoe_supply.pocket_volume is None:
            raise ValueError(f"{pump.name!r}: a pocket fed through a restrictor on a cavitating film "
                             f"(cavitation={cavitation!r}) needs [shoe.supply] pocket_volume: its pressure is then a "
                             "state; balanced at each instant it would need the cavitated film solved inside the "
                             "pocket's balance")
        super().__init__(pump, mesh, formulation=formulation, element=element, solver=solver, cavitation=cavitation)

    def balancing_rates(self, sup: Superposition, load: np.ndarray, wedge: float, inlet_pressure: float):
        """The cavitated film's rates (:meth:`Cavitating.balancing_rates`); where its Newton finds none, a
        :class:`~bearingfe.transient.base.NoEquilibrium` that gives the pocket's force against the load. A trial
        state whose pocket pressure is below 0 (the film holds no tension) is rejected: retaken shorter."""
        if inlet_pressure < 0:
            raise TrialRejected(f"the pocket pressure of a trial state is below 0 ({inlet_pressure:.3g} [-]): a film "
                                f"without tension ({self.cavitation!r}) cannot hold it")
        try:
            return super().balancing_rates(sup, load, wedge, inlet_pressure)
        except CavitationError:
            sc, load_norm = self.pump.scale, max(float(np.linalg.norm(load)), 1e-300)
            own = float(np.linalg.norm(sup.operators.pocket_moments[1:] * inlet_pressure)) / load_norm
            whole = float(np.linalg.norm(sup.forces[:, 3] * inlet_pressure)) / load_norm
            raise NoEquilibrium(
                f"no cavitated film carries the load: the pocket at {sc.to_pressure(inlet_pressure) / 1e6:.4g} MPa "
                f"presses on its own area with {own:.3g} and through the film around it with {whole:.3g} times the "
                f"plunger load; a film without tension ({self.cavitation!r}) takes the excess back only by "
                "separating fast (the shoe lifting off), and the rates' Newton found no such state") from None


class FedJFO(JFO):
    """The fed pocket (:class:`Fed`) on the film with mass-conserving (JFO) rupture (:class:`~bearingfe.transient.jfo.JFO`).

    The pocket pressure is the third entry of the state ``(gamma, delta, p_r)``, stepped by the same backward
    Euler as the film's fill fraction: at each step the rates ``(gamma', delta', p_r')`` solve together the load
    balance and the pocket's rate equation at the step's end,

        V/K p_r' = Q_restrictor(p_r) - Q_film - (V_gap(y_{n+1}) - V_gap(y_n)) / dbeta,

    with ``Q_film`` the JFO film's outflow from the pocket (its ``inlet`` flow) and the gap's volume change over
    the step (the pocket's own mass, conserved from step to step as the film's is). Newton with a
    forward-difference Jacobian on the three rates (the flow residual in units of the orifice's flow at the
    discharge pressure and an empty pocket). The start is :class:`Fed`'s (the pocket balanced on the film
    without rupture); the periodic start runs one revolution (film history and pocket pressure carried).

    Parameters
    ----------
    pump : EccentricPump
        With ``shoe_supply`` and its ``pocket_volume`` (the pocket pressure a state).
    mesh : SupportMesh
        Straight-sided P1 mesh of ``pump.surface``.
    formulation, element, solver, cavitation_pressure, tol, max_newton
        As :class:`~bearingfe.transient.jfo.JFO`.
    """

    name = "fed jfo"
    residual_note = " with the pocket's flow imbalance"

    def __init__(self, pump: EccentricPump, mesh: SupportMesh, *, formulation: str = "pi", element: str = "P1",
                 solver: str = DEFAULT_SOLVER, **options) -> None:
        if pump.shoe_supply is not None and pump.shoe_supply.pocket_volume is None:
            raise ValueError(f"{pump.name!r}: a pocket fed through a restrictor on the JFO film needs [shoe.supply] "
                             "pocket_volume: its pressure is then a state of the backward-Euler steps, as the "
                             "film's fill fraction is")
        super().__init__(pump, mesh, formulation=formulation, element=element, solver=solver, **options)
        self.rigid = Fed(pump, mesh, formulation=formulation, element=element, solver=solver)
        self.restrictor = self.rigid.restrictor
        self.compressibility = self.rigid.compressibility
        #: int_pocket (1, cos phi, sin phi) dA [-]: the pocket's gap volume is gamma (cos delta, sin delta) . (mc, ms)
        self.moments = np.asarray(operators(mesh, element).pocket_moments, float)
        #: the residual's unit of flow: the restrictor's at the discharge pressure into an empty pocket [omega R0^2 c]
        self.flow_unit = max(abs(self.rigid._law(0.0).flow(0.0)),
                             abs(self.restrictor.law_at(pump.cycle.discharge, pump.scale).flow(0.0)), 1e-300)

    def pocket_pressure(self, beta: float, y: np.ndarray) -> float:
        return float(y[2])

    def _gap(self, y: np.ndarray) -> float:
        """The pocket's gap volume beyond its concentric one [R0^2 c]."""
        return float(y[0] * (math.cos(y[1]) * self.moments[1] + math.sin(y[1]) * self.moments[2]))

    def gap_rate(self, dbeta: float, y: np.ndarray, rates: np.ndarray) -> float:
        """``(V_gap(y) - V_gap(y - dbeta r)) / dbeta`` [omega R0^2 c]: the gap's change over the step ending at ``y``."""
        return (self._gap(y) - self._gap(y - dbeta * np.asarray(rates, float))) / dbeta

    def step_residual(self, beta, dbeta, state, r, warm_start, load, scale):
        y = state.y + dbeta * r
        p = float(y[2])
        if p < self.cavitation_pressure:
            raise TrialRejected(f"JFO step to beta = {beta:.4f} rad: a Newton iterate put the pocket below the cavity "
                                f"pressure ({p:.3g} [-])")
        res, R = super().step_residual(beta, dbeta, state, r, warm_start, load, scale)
        imbalance = self.rigid._law(beta).flow(p) - float(res.flows["inlet"]) - self.gap_rate(dbeta, y, r)
        return res, np.append(R, (r[2] / self.compressibility - imbalance) / self.flow_unit)

    def sample_extra(self, beta: float, state: JFOState) -> dict[str, float]:
        """The pocket pressure [-], the restrictor's flow and the pocket gap's rate over the step [m^3/s]."""
        before = [b for b in self.states if b < beta]
        dbeta = beta - max(before) if before else 0.0
        gap = self.gap_rate(dbeta, state.y, state.rates) if dbeta > 0 else float(
            state.rates[0] * (math.cos(state.y[1]) * self.moments[1] + math.sin(state.y[1]) * self.moments[2])
            + state.rates[1] * state.y[0] * (math.cos(state.y[1]) * self.moments[2]
                                             - math.sin(state.y[1]) * self.moments[1]))
        p, sc = float(state.y[2]), self.pump.scale
        return {"inlet_pressure": p, "flow_restrictor": sc.to_flow(self.rigid._law(beta).flow(p)),
                "flow_pocket_gap": sc.to_flow(gap)}
