r"""Pockets fed through restrictors: hydrostatic and hybrid supports.

A pocket held at a prescribed pressure assumes a supply of infinite stiffness.
In a real machine each pocket is fed through a restrictor, and its pressure
``p_r`` is an unknown set by the balance of what the restrictor lets in and
what the film lets out::

    Q_restrictor(p_r) = Q_film(p_1, ..., p_n)     for every fed pocket.

The supply kinds (:data:`SUPPLIES`, SI at the door, one per pocket):

=================  =============================================  ========================================
kind               law (SI)                                       parameters
=================  =============================================  ========================================
``"pressure"``     ``p_r = p``  (today's pockets)                 pressure
``"capillary"``    ``Q = pi d^4 (p_s - p_r) / (128 mu l)``        diameter, length, supply pressure
``"orifice"``      ``Q = Cd pi d^2/4 sqrt(2 (p_s - p_r)/rho)``    diameter, Cd, density, supply pressure
``"flow"``         ``Q = Q_0``                                    flow
=================  =============================================  ========================================

The capillary is Hagen-Poiseuille's laminar law (viscosity ``mu`` of the
operating point, :class:`bearingfe.Scale`); the orifice is the sharp-edged
orifice (Bernoulli with a discharge coefficient). Each law is turned once into
the solver's non-dimensional currency (:mod:`bearingfe.core.scales`) by
:meth:`Supply.law`, written here and nowhere else.

The film is linear in the pocket pressures when its model is (no cavitation,
rigid surfaces): with one unit-pressure solution per pocket (the other pockets
and the outline at 0) and the motion's solution (all pockets at 0), the film
outflow of pocket ``j`` is ``Q_j = q0_j + sum_k G_jk p_k`` (``G`` the
conductance matrix of the film, symmetric positive definite). The fluxes are
the consistent nodal residuals of :mod:`bearingfe.film.flows`, summed over each
pocket's contour. Capillaries and constant flows then make a linear system;
orifices make it quadratic in ``s`` with ``p_r = p_s - s |s|``, solved by Newton
in that variable (the restrictor flow ``C s`` is linear in it, the Jacobian never
blows up at ``p_r = p_s``, and ``s < 0`` is the back-flow of a pocket the motion
pumps above its supply pressure). Where the balance has no solution with
``p_r >= 0`` (the motion draws more from a pocket than its restrictor can feed
at ``p_r = 0``) :class:`SupplyError` says so.

Under cavitation (``"reynolds"``, ``"gumbel"``) the film's outflow is no longer
linear in the pocket pressures: the same Newton iteration runs with the film's
linear conductance as its first Jacobian and Broyden updates, each evaluation
a cavitation solve on the film state whose pocket column carries the pockets
at their current pressures (one factorization per pocket for the whole
iteration). On the finite-volume scheme (``"jfo"``, recessed or periodic
surfaces, a cavity pressure) and the elastic support the pockets are balanced
by the same iteration on :func:`bearingfe.solve_reynolds`, each evaluation one
solve of that path with every pocket at its own pressure (``inlet_pressure``
one value per pocket; the result books each pocket's outflow under its name).
Under JFO the film is linear in the pocket pressures only within a fixed
cavitated set, so this is a Newton iteration on the ``n`` pocket pressures (the
starting Jacobian from ``n + 1`` solves, Broyden-updated) around complete JFO
solves, each finding its own cavitated set: no outer iteration on a frozen set.
On the elastic support each pocket loads the surface with its own pressure
(:func:`bearingfe.elastic.coupled.pocket_deflections`: the half-space's opening
under each pocket). The restrictor's flow then
equals the film's outflow to the iteration's tolerance, and the scheme carries
that flow out through the edges to round-off.

The support's stiffness :func:`supply_stiffness` is ``-dW/dh`` at fixed supply
along a one-parameter family of films (the pad lifting off: ``UniformFilm(h)``),
by a central finite difference of the balanced supports at ``h +- step``; its
truncation error is ``O(step^2)`` (``step = 1e-3 c``: below 4e-6 relative on the
closed forms of the tests).

The oil in a pocket is compressible: :func:`pocket_transient` integrates each
pocket's own rate equation ``V/K dp_r/dt = Q_restrictor - Q_film`` at a fixed
film (volume ``V``, bulk modulus ``K``) and gives the time constants of its
linearisation at the balance (``V / (K (Kc + G))`` for a capillary-fed pocket).
:func:`supply_dynamics` linearises the same rate equation with the pad in motion
(``UniformFilm(h)`` moving normal to itself, the pocket's own gap opening with it)
and gives the dynamic stiffness and damping at each frequency, in all and per
pocket; :func:`journal_dynamics` does the same for a journal's centre moving in
the plane (:class:`DisplacedJournal`: its 2x2 stiffness and damping, one
superposition column per pocket and per direction of the squeeze). The pump's shoe pocket may be fed from the chamber through a
:class:`Restrictor` in the plunger (``[shoe.supply]`` of the machine file;
:meth:`bearingfe.EccentricPump.pocket_supply`), carried by the pump transient's
``"fed"`` model (:mod:`bearingfe.transient.fed`).

Closed forms the tests check (circular pad of radius ``R`` with a central
recess of radius ``r``, uniform film ``h``: Rowe, *Hydrostatic, Aerostatic and
Hybrid Bearing Design* (2012), ch. 4-5; Hamrock, Schmid & Jacobson, ch. 6):
film flow ``Q = pi h^3 p_r / (6 mu ln(R/r))``, load ``W = pi p_r (R^2 - r^2) /
(2 ln(R/r))``; with ``beta = p_r/p_s`` the stiffness ``3 W (1 - beta)/h``
(capillary, largest at ``beta = 1/2`` for a given supply pressure and area) and
``6 W (1 - beta)/((2 - beta) h)`` (orifice, largest at ``beta = 2 - sqrt(2)``); at
constant flow ``p_r ~ h^-3`` and the stiffness is ``3 W/h``. Its squeeze-film damping
with the recess held at its pressure (a rigid supply) is ``B = 3 pi mu/(2 h^3) (R^4 -
r^4 - (R^2 - r^2)^2/ln(R/r))``; fed through a restrictor of slope ``k_r`` the slow
motion adds ``W_1^2/(k_r + G)`` (``W_1 = W/p_r`` the effective area, ``G = Q/p_r``), and
a pocket of volume ``V`` makes the dynamic stiffness ``Z = W_1 (3 G p_r/h + i omega
W_1)/(k_r + G + i omega V/K) + i omega B``.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from types import MappingProxyType
from typing import Callable, ClassVar, Mapping, Sequence

import numpy as np

from ..cavitation import MODELS, ModelOptions, solve_model
from ..core.checks import check_resolution
from ..core.parameters import Discretization, OperatingPoint
from ..core.scales import Scale
from ..core.schema import Range, finite, in_range, positive
from ..elastic import Compliance
from ..film import Film, ReynoldsResult, Superposition, film_outputs, superpose
from ..film.pockets import PocketFilm, pocket_film, pocket_flows, pocket_names, pocket_unknown
from ..geometry.meshing import SupportMesh
from ..reynolds import discretization_for, solve_reynolds

__all__ = ["SUPPLIES", "Supply", "Restrictor", "PrescribedPressure", "Capillary", "Orifice", "ConstantFlow", "Law", "SupplyError",
           "PocketState", "SuppliedResult", "SupportStiffness", "PocketTransient", "pocket_transient",
           "balance_pockets",
           "solve_supplied", "supply_stiffness", "SupportDynamics", "supply_dynamics", "DisplacedJournal",
           "JournalDynamics", "journal_dynamics"]


class SupplyError(RuntimeError):
    """The pocket pressures have no admissible solution, or the iteration did not find it."""


# -- the supply kinds -------------------------------------------------------------------------

@dataclass(frozen=True)
class Law:
    """A restrictor law in the solver's non-dimensional currency.

    ``Q(p) = conductance (supply - p)`` (``"capillary"``), ``conductance sqrt(supply - p)``
    (``"orifice"``) or ``conductance`` (``"flow"``); ``"pressure"`` fixes ``p = supply``.

    Attributes
    ----------
    kind : str
        A key of :data:`SUPPLIES`.
    supply : float
        Supply (or prescribed) pressure [mu omega R0^2 / c^2]; NaN for ``"flow"``.
    conductance : float
        Flow per unit pressure drop (capillary), per square root of the drop (orifice), or the
        flow itself (constant flow), flows in [omega R0^2 c] and pressures in [mu omega R0^2 / c^2].
    """

    kind: str
    supply: float
    conductance: float

    def flow(self, p: float) -> float:
        """Flow through the restrictor into the pocket at pocket pressure ``p`` [omega R0^2 c]."""
        if self.kind == "capillary":
            return self.conductance * (self.supply - p)
        if self.kind == "orifice":  # back-flow through the orifice when the pocket is above the supply
            drop = self.supply - p
            return math.copysign(self.conductance * math.sqrt(abs(drop)), drop)
        if self.kind == "flow":
            return self.conductance
        return math.nan

    def slope(self, p: float) -> float:
        """``dQ/dp`` of the restrictor at pocket pressure ``p`` (``-inf`` at an orifice's supply pressure)."""
        if self.kind == "capillary":
            return -self.conductance
        if self.kind == "orifice":
            drop = abs(self.supply - p)
            return -0.5 * self.conductance / math.sqrt(drop) if drop > 0 else -math.inf
        return 0.0


class Supply:
    """A pocket's supply (base of the kinds of :data:`SUPPLIES`): SI fields, checked when made."""

    kind: ClassVar[str] = ""

    def law(self, scale: Scale) -> Law:  # pragma: no cover - every kind defines it
        """The law in non-dimensional form for the scales of a support."""
        raise NotImplementedError


def _set(obj, name: str, value: float) -> None:
    object.__setattr__(obj, name, value)


@dataclass(frozen=True)
class PrescribedPressure(Supply):
    """A pocket held at a pressure (an infinitely stiff supply: the pockets of :func:`bearingfe.solve_reynolds`).

    Parameters
    ----------
    pressure : float
        Pocket pressure [Pa], finite.
    """

    pressure: float = 0.0
    kind: ClassVar[str] = "pressure"

    def __post_init__(self) -> None:
        _set(self, "pressure", finite("PrescribedPressure.pressure", self.pressure))

    def law(self, scale: Scale) -> Law:
        return Law("pressure", scale.from_pressure(self.pressure), 0.0)


@dataclass(frozen=True)
class Capillary(Supply):
    """A laminar capillary from a supply at ``supply_pressure``: ``Q = pi d^4 (p_s - p_r) / (128 mu l)``.

    The viscosity ``mu`` is the operating point's (:attr:`bearingfe.Scale.viscosity`).

    Parameters
    ----------
    diameter : float
        Bore ``d`` [m], > 0.
    length : float
        Length ``l`` [m], >= diameter (the Hagen-Poiseuille law needs a long bore).
    supply_pressure : float
        ``p_s`` [Pa], > 0.
    """

    diameter: float
    length: float
    supply_pressure: float
    kind: ClassVar[str] = "capillary"

    def __post_init__(self) -> None:
        _set(self, "diameter", positive("Capillary.diameter", self.diameter, "m"))
        _set(self, "length", in_range("Capillary.length", self.length, Range(self.diameter), "m"))
        _set(self, "supply_pressure", positive("Capillary.supply_pressure", self.supply_pressure, "Pa"))

    def law(self, scale: Scale) -> Law:
        si = math.pi * self.diameter**4 / (128.0 * scale.viscosity * self.length)  # m^3/s per Pa
        return Law("capillary", scale.from_pressure(self.supply_pressure), si * scale.pressure / scale.flow)


@dataclass(frozen=True)
class Orifice(Supply):
    """A sharp-edged orifice from a supply at ``supply_pressure``: ``Q = Cd pi d^2/4 sqrt(2 (p_s - p_r)/rho)``.

    Parameters
    ----------
    diameter : float
        Orifice diameter ``d`` [m], > 0.
    discharge_coefficient : float
        ``Cd`` [-], in (0, 1].
    density : float
        Oil density ``rho`` [kg/m^3], > 0.
    supply_pressure : float
        ``p_s`` [Pa], > 0.
    """

    diameter: float
    discharge_coefficient: float
    density: float
    supply_pressure: float
    kind: ClassVar[str] = "orifice"

    def __post_init__(self) -> None:
        _set(self, "diameter", positive("Orifice.diameter", self.diameter, "m"))
        _set(self, "discharge_coefficient", in_range("Orifice.discharge_coefficient", self.discharge_coefficient,
                                                     Range(0.0, 1.0, lo_open=True)))
        _set(self, "density", positive("Orifice.density", self.density, "kg/m^3"))
        _set(self, "supply_pressure", positive("Orifice.supply_pressure", self.supply_pressure, "Pa"))

    def law(self, scale: Scale) -> Law:
        area = math.pi * self.diameter**2 / 4.0
        si = self.discharge_coefficient * area * math.sqrt(2.0 / self.density)  # m^3/s per sqrt(Pa)
        return Law("orifice", scale.from_pressure(self.supply_pressure),
                   si * math.sqrt(scale.pressure) / scale.flow)


@dataclass(frozen=True)
class ConstantFlow(Supply):
    """A constant-flow supply (a pump per pocket): ``Q = flow`` whatever the pocket pressure.

    Parameters
    ----------
    flow : float
        Volume flow into the pocket [m^3/s], > 0.
    """

    flow: float
    kind: ClassVar[str] = "flow"

    def __post_init__(self) -> None:
        _set(self, "flow", positive("ConstantFlow.flow", self.flow, "m^3/s"))

    def law(self, scale: Scale) -> Law:
        return Law("flow", math.nan, self.flow / scale.flow)


#: The supply kinds by name (read-only): ``kind -> class``.
SUPPLIES: Mapping[str, type] = MappingProxyType({cls.kind: cls for cls in
                                                 (PrescribedPressure, Capillary, Orifice, ConstantFlow)})


@dataclass(frozen=True)
class Restrictor:
    """A restrictor whose supply pressure is set elsewhere: the plunger's bore from the pump chamber.

    :meth:`fed_from` makes the pocket's :class:`Supply` at a supply pressure (the chamber's at an
    instant of the cycle). Each kind takes its own fields and no others.

    Parameters
    ----------
    kind : str
        ``"capillary"`` (``diameter``, ``length``) or ``"orifice"`` (``diameter``,
        ``discharge_coefficient``, ``density``).
    diameter : float
        [m], > 0.
    length : float, optional
        Capillary length [m], >= diameter.
    discharge_coefficient : float, optional
        Orifice ``Cd`` [-], in (0, 1].
    density : float, optional
        Oil density for the orifice [kg/m^3], > 0.
    pocket_volume : float, optional
        Oil volume of the pocket it feeds [m^3], > 0: with it the pump transient carries the pocket
        pressure as a state (``V/K dp_r/dt = Q_restrictor - Q_film - dV/dt``); without it the pocket is
        balanced at each instant (no volume).
    bulk_modulus : float
        The oil's bulk modulus ``K`` [Pa], > 0 (used with ``pocket_volume``).

    Raises
    ------
    ValueError
        The kind is not a restrictor, a field the kind needs is missing or one it does not take is
        given, or a value is out of its range (the message of the :class:`Supply` it makes).
    """

    kind: str
    diameter: float
    length: float | None = None
    discharge_coefficient: float | None = None
    density: float | None = None
    pocket_volume: float | None = None
    bulk_modulus: float = 1.5e9

    #: The fields of each kind.
    FIELDS: ClassVar[Mapping[str, tuple[str, ...]]] = MappingProxyType({
        "capillary": ("diameter", "length"), "orifice": ("diameter", "discharge_coefficient", "density")})

    def __post_init__(self) -> None:
        if self.kind not in self.FIELDS:
            raise ValueError(f"Restrictor.kind must be one of {tuple(self.FIELDS)}, got {self.kind!r}")
        for name in ("length", "discharge_coefficient", "density"):  # the kinds' own fields
            needed = name in self.FIELDS[self.kind]
            if needed and getattr(self, name) is None:
                raise ValueError(f"Restrictor.{name} is required by kind = {self.kind!r}")
            if not needed and getattr(self, name) is not None:
                raise ValueError(f"Restrictor.{name} is not taken by kind = {self.kind!r} "
                                 f"(it takes {', '.join(self.FIELDS[self.kind])})")
        self.fed_from(1.0)  # the supply's own checks of the values
        if self.pocket_volume is not None:
            object.__setattr__(self, "pocket_volume", positive("Restrictor.pocket_volume", self.pocket_volume, "m^3"))
        object.__setattr__(self, "bulk_modulus", positive("Restrictor.bulk_modulus", self.bulk_modulus, "Pa"))

    def fed_from(self, supply_pressure: float) -> Supply:
        """The pocket's supply from a source at ``supply_pressure`` [Pa], > 0."""
        fields = {name: getattr(self, name) for name in self.FIELDS[self.kind]}
        return SUPPLIES[self.kind](supply_pressure=supply_pressure, **fields)

    def law_at(self, supply_pressure: float, scale: Scale) -> Law:
        """The non-dimensional law from a source at ``supply_pressure`` [Pa], any finite value (a chamber
        at 0 in suction: the flow runs back)."""
        return dataclasses.replace(self.fed_from(1.0).law(scale), supply=scale.from_pressure(supply_pressure))


# -- pockets of a mesh and their film flows ------------------------------------------------------

# -- the balance of the pockets ----------------------------------------------------------------

def balance_pockets(laws: Sequence[Law], film_flow: Callable[[np.ndarray], np.ndarray], conductance: np.ndarray,
                    *, tol: float = 1e-11, max_iterations: int = 60) -> np.ndarray:
    """Pocket pressures where every restrictor's flow equals the film's outflow [-].

    Newton in the variables ``x = p`` (capillary, constant flow) and ``s`` with ``p = p_s - s |s|``
    (orifice: its flow ``C s`` is linear in ``s``, negative when the pocket is above its supply and
    the oil runs back); prescribed pockets are fixed. The Jacobian starts from the film's linear
    conductance (exact for a linear film: one step for capillaries and constant flows) and is
    updated by Broyden's rule when the film is not linear (cavitation).

    Parameters
    ----------
    laws : sequence of Law
        One per pocket.
    film_flow : callable
        ``p (n,) -> Q (n,)``: the film outflow of each pocket [omega R0^2 c].
    conductance : ndarray, shape (n, n)
        ``dQ_film/dp`` of the linear film.

    Raises
    ------
    SupplyError
        No solution with ``p >= 0``, or no convergence.
    """
    laws = list(laws)
    n = len(laws)
    p_fixed = np.array([law.supply if law.kind == "pressure" else 0.0 for law in laws])
    free = np.array([law.kind != "pressure" for law in laws])
    orifice = np.array([law.kind == "orifice" for law in laws])
    if not free.any():
        return p_fixed
    G = np.asarray(conductance, float).reshape(n, n)

    def pressures(x: np.ndarray) -> np.ndarray:
        q = p_fixed.copy()
        for k in np.flatnonzero(free):
            q[k] = laws[k].supply - x[k] * abs(x[k]) if orifice[k] else x[k]
        return q

    def residual(x: np.ndarray, q_film: np.ndarray) -> np.ndarray:
        r = np.zeros(n)
        for k in np.flatnonzero(free):
            inflow = laws[k].conductance * x[k] if orifice[k] else laws[k].flow(x[k])
            r[k] = inflow - q_film[k]
        return r

    def dp_dx(x: np.ndarray) -> np.ndarray:
        return np.where(orifice, -2.0 * np.abs(x), 1.0)

    # start: each pocket at half its supply pressure (orifice s = sqrt(p_s / 2)), flows at a film estimate
    x = np.zeros(n)
    scale = 1e-300  # the largest restrictor flow: the residual's unit
    for k in np.flatnonzero(free):
        law = laws[k]
        if law.kind == "orifice":
            x[k] = math.sqrt(law.supply / 2.0)
        elif law.kind == "capillary":
            x[k] = law.supply / 2.0
        else:
            x[k] = max(law.conductance / max(G[k, k], 1e-300), 0.0)
        scale = max(scale, abs(law.flow(0.0)) if law.kind != "flow" else law.conductance)
    idx = np.flatnonzero(free)
    restrictor = np.array([laws[k].conductance if orifice[k] else
                           (-laws[k].conductance if laws[k].kind == "capillary" else 0.0) for k in range(n)])
    B = G.copy()  # dQ_film/dp: exact for a linear film, Broyden-updated otherwise
    p = pressures(x)
    q = film_flow(p)
    r = residual(x, q)
    for _ in range(max_iterations):
        if np.max(np.abs(r[idx])) <= tol * scale:
            break
        # Newton in x: d(inflow)/dx - B dp/dx (the chain rule through p(x) is exact for the orifice's s)
        J = np.diag(restrictor[idx]) - B[np.ix_(idx, idx)] * dp_dx(x)[idx][None, :]
        x_new = x.copy()
        x_new[idx] += np.linalg.solve(J, -r[idx])
        x_new = _admissible(x_new, laws, orifice, free)
        p_new = pressures(x_new)
        q_new = film_flow(p_new)
        r_new = residual(x_new, q_new)
        dp, dq = p_new - p, q_new - q
        if np.dot(dp, dp) > 0:  # Broyden: B dp = dq (no change for a linear film)
            B += np.outer(dq - B @ dp, dp) / np.dot(dp, dp)
        if np.array_equal(x_new, x) and np.max(np.abs(r_new[idx])) > tol * scale:
            raise _no_solution(laws, p_new, r_new, idx)
        x, p, q, r = x_new, p_new, q_new, r_new
    else:
        raise SupplyError(f"the pocket pressures did not converge in {max_iterations} iterations "
                          f"(largest flow imbalance {np.max(np.abs(r[idx])):.3g} [omega R0^2 c])")
    return p


def _admissible(x: np.ndarray, laws, orifice, free) -> np.ndarray:
    """Clip an iterate into ``p >= 0`` (orifice: ``s <= sqrt(p_s)``)."""
    out = x.copy()
    for k in np.flatnonzero(free):
        if orifice[k]:
            out[k] = min(out[k], math.sqrt(max(laws[k].supply, 0.0)))
        else:
            out[k] = max(out[k], 0.0)
    return out


def _no_solution(laws, p, r, idx) -> SupplyError:
    k = int(idx[np.argmax(np.abs(r[idx]))])
    law = laws[k]
    why = "the film draws more from it at p_r = 0 than the " + ("supply feeds" if law.kind == "flow" else
                                                                 "restrictor can feed")
    return SupplyError(f"pocket {k} ({law.kind}): no solution with p_r >= 0: {why} "
                       f"(flow imbalance {r[k]:.3g} [omega R0^2 c] at p_r = {p[k]:.4g} [-])")


# -- results -------------------------------------------------------------------------------------

@dataclass(frozen=True)
class PocketState:
    """One pocket of a balanced support [SI].

    Attributes
    ----------
    name : str
        Its boundary name (``inlet_0``, ...).
    kind : str
        Its supply kind (a key of :data:`SUPPLIES`).
    pressure : float
        Pocket pressure ``p_r`` [Pa].
    restrictor_flow : float
        Flow through the restrictor into the pocket [m^3/s] (the film's for a prescribed pocket).
    film_flow : float
        Flow out of the pocket into the film [m^3/s].
    supply_pressure : float
        ``p_s`` [Pa] (NaN at constant flow; the pocket pressure when prescribed).
    stiffness, damping : ndarray or None
        What this pocket's pressure response adds to the support's stiffness [N/m] and damping
        [N s/m] at each frequency of :func:`supply_dynamics` (None from :func:`solve_supplied`).
    """

    name: str
    kind: str
    pressure: float
    restrictor_flow: float
    film_flow: float
    supply_pressure: float
    stiffness: np.ndarray | None = None
    damping: np.ndarray | None = None

    @property
    def ratio(self) -> float:
        """``beta = p_r / p_s`` [-] (NaN at constant flow)."""
        return self.pressure / self.supply_pressure if self.supply_pressure else math.nan


@dataclass(frozen=True)
class SuppliedResult:
    """A support with its pockets balanced against their restrictors.

    Attributes
    ----------
    film : ReynoldsResult
        The film at the balanced pocket pressures (non-dimensional; its ``force`` and ``integral``
        count each pocket at its own pressure; ``inlet_pressure`` is the largest pocket pressure).
    pockets : tuple of PocketState
        Per pocket [SI].
    scale : Scale
    load : float
        ``int p dA`` over the surface, pockets included [N] (the load of a flat pad).
    force : ndarray, shape (2,)
        ``int p (cos phi, sin phi) dA`` [N].
    """

    film: ReynoldsResult
    pockets: tuple[PocketState, ...]
    scale: Scale
    load: float
    force: np.ndarray

    @property
    def pressures(self) -> np.ndarray:
        """Pocket pressures [Pa]."""
        return np.array([p.pressure for p in self.pockets])

    @property
    def total_flow(self) -> float:
        """Flow into all the pockets [m^3/s]."""
        return float(sum(p.film_flow for p in self.pockets))


# -- the front door --------------------------------------------------------------------------------

def solve_supplied(mesh: SupportMesh, film: Film, supplies: Sequence[Supply] | Supply, scale: Scale, *,
                   operating: OperatingPoint = OperatingPoint(wedge=0.0),
                   discretization: Discretization = Discretization(), cavitation: str = "none",
                   elastic: Compliance | None = None, on_indefinite: str = "fallback") -> SuppliedResult:
    """Solve a support whose pockets are fed through restrictors.

    Parameters
    ----------
    mesh : SupportMesh
        With its pockets (:func:`pocket_names` lists them in order).
    film : Film
    supplies : Supply or sequence of Supply
        One per pocket (a single one is given to every pocket, each through its own restrictor);
        the kinds of :data:`SUPPLIES`.
    scale : Scale
        The support's scales (radius, clearance, viscosity, speed): SI in, SI out.
    operating : OperatingPoint
        Wedge, squeeze rates and sliding [-]; its ``inlet_pressure`` must be 0 (the supplies set
        the pockets). Default: no motion (a purely hydrostatic support).
    discretization : Discretization
        Element, formulation and linear solver.
    cavitation : str
        A model of :data:`bearingfe.cavitation.MODELS`. ``"none"`` solves the pockets exactly by
        superposition; ``"reynolds"`` and ``"gumbel"`` iterate them with the film (Newton-Broyden);
        a model or surface that needs the finite-volume scheme is balanced on
        :func:`bearingfe.solve_reynolds` (see the module docstring).
    elastic : Compliance, optional
        An elastic support (:func:`bearingfe.half_space`; several pockets need the half-space's opening per
        pocket): the pockets are balanced on the coupled film of :func:`bearingfe.solve_reynolds`.

    Returns
    -------
    SuppliedResult

    Raises
    ------
    ValueError
        A bad argument (no pockets, the wrong number of supplies, a non-zero ``inlet_pressure``).
    SupplyError
        No admissible pocket pressures.
    """
    names = pocket_names(mesh)
    laws = _laws(names, supplies, scale)
    if operating.inlet_pressure != 0.0:
        raise ValueError("operating.inlet_pressure must be 0: the supplies set the pocket pressures")
    if cavitation not in MODELS:
        raise ValueError(f"cavitation must be one of {tuple(MODELS)}, got {cavitation!r}")
    path = discretization_for(mesh, cavitation)
    if path == "finite-element" and elastic is None:
        film_result, p, q = _solve_pockets_fe(mesh, film, laws, operating, discretization, cavitation, on_indefinite)
    else:
        film_result, p, q = _solve_pockets_front_door(mesh, film, laws, operating, discretization, cavitation,
                                                      elastic)
    pockets = tuple(PocketState(name=n, kind=law.kind, pressure=scale.to_pressure(pk),
                                restrictor_flow=scale.to_flow(law.flow(pk) if law.kind != "pressure" else qk),
                                film_flow=scale.to_flow(qk),
                                supply_pressure=scale.to_pressure(law.supply) if law.kind != "flow" else math.nan)
                    for n, law, pk, qk in zip(names, laws, p, q))
    return SuppliedResult(film=film_result, pockets=pockets, scale=scale,
                          load=scale.to_force(film_result.integral), force=scale.to_force(np.asarray(film_result.force)))


def _laws(names: Sequence[str], supplies, scale: Scale) -> list[Law]:
    if not names:
        raise ValueError("the mesh has no pockets ('inlet' boundaries): nothing to feed")
    if not isinstance(scale, Scale):
        raise ValueError(f"scale must be a bearingfe.Scale, got {type(scale).__name__}")
    given = [supplies] * len(names) if isinstance(supplies, Supply) else list(supplies)
    if len(given) != len(names):
        raise ValueError(f"supplies must give one supply per pocket ({len(names)}: {', '.join(names)}), "
                         f"got {len(given)}")
    for k, s in enumerate(given):
        if not isinstance(s, Supply):
            raise ValueError(f"supplies[{k}] must be one of {tuple(c.__name__ for c in SUPPLIES.values())}, "
                             f"got {type(s).__name__}")
    return [s.law(scale) for s in given]


def _solve_pockets_fe(mesh, film, laws, operating, discretization, cavitation, on_indefinite):
    """The finite-element film state with one unit field per pocket; the pockets balanced on it."""
    pf = pocket_film(mesh, film, discretization, on_indefinite)
    q0, G = _linear_film(pf, operating)
    weights = np.array([operating.wedge, *operating.squeeze, 1.0])
    last: dict = {}

    def solve_at(p: np.ndarray) -> ReynoldsResult:
        key = tuple(np.asarray(p, float))
        if last.get("key") != key:
            # each iterate warm-started from the previous one's rupture set
            warm = last["result"].cavitated if "result" in last else None
            options = ModelOptions(sliding=operating.sliding, warm_start=warm)
            last.update(key=key, result=solve_model(pf.state(p), weights, cavitation, options))
        return last["result"]

    if cavitation == "none":
        def film_flow(p):
            return q0 + G @ p
    else:
        def film_flow(p):
            res = solve_at(np.maximum(p, 0.0))
            u = pocket_unknown(pf.whole, res)
            return pocket_flows(pf, u[:, None], weights[:, None],
                                None if res.cavitated is None else res.cavitated[:, None])[:, 0]

    p = balance_pockets(laws, film_flow, G)
    res = solve_at(p)
    q = film_flow(p)
    if res.cavitated is not None:  # the model's loads count the pockets at the column's unit weight
        force, integral = pf.whole.loads(pocket_unknown(pf.whole, res), 0.0)
        moments = pf.pocket_moments(p)
        res = dataclasses.replace(res, force=force + moments[1:], integral=integral + moments[0])
    unresolved = check_resolution(mesh, film, stacklevel=4)  # as the front door's finite-element path does
    notes = res.notes + ((unresolved,) if unresolved else ()) + (f"pockets fed through restrictors at {_listed(p)} [-]",)
    res = dataclasses.replace(res, inlet_pressure=float(np.max(p)), notes=notes)
    return res, p, q


def _linear_film(pf: PocketFilm, operating: OperatingPoint) -> tuple[np.ndarray, np.ndarray]:
    """The film's outflow from each pocket as ``q0 + G p`` [omega R0^2 c]: ``q0`` of the motion (pockets
    at 0), ``G`` of the unit pocket pressures (no motion)."""
    n = len(pf.pockets)
    motion = np.array([operating.wedge, *operating.squeeze, 0.0])
    U = np.column_stack([pf.whole.fields @ motion] + [s.fields[:, 3] for s in pf.pockets])
    W = np.zeros((4, n + 1))
    W[:, 0] = motion
    W[3, 1:] = 1.0
    flows = pocket_flows(pf, U, W)
    return flows[:, 0], flows[:, 1:]


def _listed(p: np.ndarray) -> str:
    return "(" + ", ".join(f"{x:.6g}" for x in p) + ")"


def _solve_pockets_front_door(mesh, film, laws, operating, discretization, cavitation, elastic):
    """The pockets balanced on :func:`bearingfe.solve_reynolds` (the finite-volume scheme, the elastic support),
    each evaluation one solve with every pocket at its own pressure."""
    names = pocket_names(mesh)
    n = len(laws)
    last: dict = {}

    def solve_at(p: np.ndarray) -> ReynoldsResult:
        key = tuple(float(v) for v in p)
        if last.get("key") != key:
            warm = last.get("result")
            warm = warm if warm is not None and warm.cavitated is not None and elastic is None else None
            last.update(key=key, result=solve_reynolds(
                mesh, film, wedge=operating.wedge, squeeze=operating.squeeze,
                inlet_pressure=key[0] if n == 1 else key, sliding=operating.sliding, cavitation=cavitation,
                discretization=discretization, elastic=elastic, warm_start=warm))
        return last["result"]

    def flows_of(res: ReynoldsResult) -> np.ndarray:
        return np.array([res.flows["inlet"]]) if n == 1 else np.array([res.flows[name] for name in names])

    def film_flow(p):
        return flows_of(solve_at(np.maximum(p, 0.0)))

    # the Jacobian's start: n + 1 solves (the free pockets' columns; Broyden corrects them)
    base = np.array([law.supply if law.kind == "pressure" else 0.0 for law in laws])
    q_base = film_flow(base)
    G = np.eye(n)
    for k, law in enumerate(laws):
        if law.kind == "pressure":
            continue
        ref = law.supply if law.kind != "flow" and law.supply > 0 else 1.0
        p = base.copy()
        p[k] = ref
        G[:, k] = (film_flow(p) - q_base) / ref
        G[k, k] = max(G[k, k], 1e-300)
    p = balance_pockets(laws, film_flow, G)
    res = solve_at(p)
    return res, p, flows_of(res)


# -- the pockets' compressibility ------------------------------------------------------------------

@dataclass(frozen=True)
class PocketTransient:
    """Pocket pressures after a change, at a fixed film, with the oil in each pocket compressible [SI].

    Attributes
    ----------
    times : ndarray, shape (T,)
        [s].
    pressures : ndarray, shape (T, n)
        Pocket pressures [Pa] (prescribed pockets constant).
    balanced : SuppliedResult
        The steady balance the pressures tend to.
    time_constants : ndarray, shape (m,)
        ``-1/lambda`` of the eigenvalues of the rate equation linearised at the balance, over the
        fed pockets [s], largest first.
    """

    times: np.ndarray
    pressures: np.ndarray
    balanced: SuppliedResult
    time_constants: np.ndarray


def pocket_transient(mesh: SupportMesh, film: Film, supplies: Sequence[Supply] | Supply, scale: Scale, *,
                     volumes: Sequence[float] | float, bulk_modulus: float, times: Sequence[float],
                     initial: Sequence[float] | float = 0.0, operating: OperatingPoint = OperatingPoint(wedge=0.0),
                     discretization: Discretization = Discretization()) -> PocketTransient:
    """The pocket pressures' own rate equation at a fixed film: ``V/K dp_r/dt = Q_restrictor - Q_film``.

    Each fed pocket of volume ``V`` (oil of bulk modulus ``K``) fills and empties through its
    restrictor and the film; the film is the linear one of this state (no cavitation, rigid, fixed
    thickness: the pocket volume does not change), so ``Q_film = q0 + G p`` as in
    :func:`solve_supplied`, and the equation is integrated by scipy's Radau (relative tolerance 1e-10).
    A capillary-fed pocket relaxes as ``exp(-t/tau)`` with ``tau = V / (K (Kc + G))``.

    Parameters
    ----------
    mesh, film, supplies, scale, operating, discretization
        As :func:`solve_supplied` (``cavitation="none"``).
    volumes : float or sequence of float
        Each pocket's oil volume [m^3], > 0 (one for all, or one per pocket).
    bulk_modulus : float
        The oil's bulk modulus ``K`` [Pa], > 0.
    times : sequence of float
        Output times [s], increasing from 0.
    initial : float or sequence of float
        Pocket pressures at ``t = 0`` [Pa] (prescribed pockets keep their pressure).
    """
    from scipy.integrate import solve_ivp

    names = pocket_names(mesh)
    laws = _laws(names, supplies, scale)
    n = len(laws)
    vol = np.broadcast_to(np.asarray(volumes, float), (n,)).copy()
    for k, v in enumerate(vol):
        positive(f"volumes[{k}]", v, "m^3")
    bulk = positive("bulk_modulus", bulk_modulus, "Pa")
    t = np.asarray(times, float)
    if t.ndim != 1 or t.size < 2 or t[0] != 0.0 or np.any(np.diff(t) <= 0) or not np.all(np.isfinite(t)):
        raise ValueError(f"times must increase from 0 [s], got {times!r}")
    balanced = solve_supplied(mesh, film, supplies, scale, operating=operating, discretization=discretization)
    q0, G = _linear_film(pocket_film(mesh, film, discretization), operating)
    free = np.array([law.kind != "pressure" for law in laws])
    p_bal = np.array([scale.from_pressure(p) for p in balanced.pressures])
    p0 = np.broadcast_to(np.asarray(initial, float), (n,)).copy() / scale.pressure
    p0[~free] = p_bal[~free]
    rate = bulk * scale.flow / (vol * scale.pressure)  # dp [-]/dt [s] per unit flow imbalance [-]

    def rhs(_, x):
        p = p_bal.copy()
        p[free] = x
        imbalance = np.array([law.flow(pk) for law, pk in zip(laws, p)]) - (q0 + G @ p)
        return (rate * imbalance)[free]

    def jacobian(_, x):
        p = p_bal.copy()
        p[free] = x
        J = np.diag([law.slope(pk) for law, pk in zip(laws, p)]) - G
        return (rate[:, None] * J)[np.ix_(free, free)]

    sol = solve_ivp(rhs, (t[0], t[-1]), p0[free], method="Radau", t_eval=t, jac=jacobian, rtol=1e-10,
                    atol=1e-12 * max(1.0, float(np.max(np.abs(p_bal)))))
    if not sol.success:
        raise SupplyError(f"the pocket pressures' rate equation could not be integrated: {sol.message}")
    pressures = np.tile(p_bal, (t.size, 1))
    pressures[:, free] = sol.y.T
    lam = np.linalg.eigvals(jacobian(0.0, p_bal[free])) if free.any() else np.zeros(0)
    return PocketTransient(times=t, pressures=pressures * scale.pressure, balanced=balanced,
                           time_constants=np.sort(-1.0 / lam.real)[::-1])


# -- stiffness -------------------------------------------------------------------------------------

@dataclass(frozen=True)
class SupportStiffness:
    """Load and stiffness of a fed support at fixed supply [SI].

    Attributes
    ----------
    result : SuppliedResult
        The balanced support at ``h``.
    stiffness : float
        ``-dW/dh`` of the load ``W = int p dA`` [N/m].
    force_stiffness : ndarray, shape (2,)
        ``-dF/dh`` of the force ``int p (cos phi, sin phi) dA`` [N/m].
    pressure_rate : ndarray
        ``dp_r/dh`` of each pocket [Pa/m].
    """

    result: SuppliedResult
    stiffness: float
    force_stiffness: np.ndarray
    pressure_rate: np.ndarray


def supply_stiffness(mesh: SupportMesh, films: Callable[[float], Film], h: float,
                     supplies: Sequence[Supply] | Supply, scale: Scale, *, step: float = 1e-3,
                     **options) -> SupportStiffness:
    """Stiffness ``-dW/dh`` of a fed support at fixed supply, along a family of films.

    A central finite difference of balanced supports (:func:`solve_supplied`) at ``h +- step``:
    truncation error ``O(step^2)`` (for ``W ~ h^-n`` it is ``(n + 1)(n + 2)/6 (step/h)^2`` relative:
    4e-7 for a capillary recess at ``h = 1``, 3.3e-6 at constant flow, with the default step).

    Parameters
    ----------
    mesh : SupportMesh
    films : callable
        ``h -> Film``: the one-parameter family, e.g. :class:`bearingfe.UniformFilm` for a pad
        lifting off, ``lambda e: CosineFilm(e, phi0)`` for a journal displaced towards ``phi0``
        [h and e in units of the clearance].
    h : float
        Where [c], finite; ``films(h +- step)`` must be films.
    supplies, scale
        As :func:`solve_supplied`.
    step : float
        The difference step [c], in (0, 0.1].
    **options
        Passed to :func:`solve_supplied` (``operating``, ``discretization``, ``cavitation``, ``elastic``).
    """
    h = finite("h", h)
    step = in_range("step", step, Range(0.0, 0.1, lo_open=True))
    centre = solve_supplied(mesh, films(h), supplies, scale, **options)
    up = solve_supplied(mesh, films(h + step), supplies, scale, **options)
    down = solve_supplied(mesh, films(h - step), supplies, scale, **options)
    dh = 2 * step * scale.clearance  # [m]
    return SupportStiffness(result=centre, stiffness=-(up.load - down.load) / dh,
                            force_stiffness=-(up.force - down.force) / dh,
                            pressure_rate=(up.pressures - down.pressures) / dh)


# -- dynamics: the pad's motion linearised -------------------------------------------------------------

@dataclass(frozen=True)
class SupportDynamics:
    """Stiffness and damping of a fed pad moving normal to itself, linearised at its balance [SI].

    Attributes
    ----------
    result : SuppliedResult
        The balanced support at ``h``; each pocket's :class:`PocketState` carries its share of the
        stiffness and damping (``stiffness``, ``damping``, one value per frequency).
    frequencies : ndarray, shape (F,)
        Angular frequencies of the motion [rad/s] (0: the limit of slow motion).
    stiffness : ndarray, shape (F,)
        ``Re Z`` of the dynamic stiffness ``Z = -dW/dh`` [N/m].
    damping : ndarray, shape (F,)
        ``Im Z / omega`` [N s/m] (at ``omega = 0`` its limit, ``d Im Z/d omega``).
    squeeze_damping : float
        The film's own damping with every pocket held at its pressure (a rigid supply) [N s/m].
    film_stiffness : float
        ``-dW/dh`` with every pocket held at its pressure [N/m] (0 for a flat pad: its load is
        ``int p dA`` of pressures that do not depend on ``h``).
    pressure_response : ndarray, shape (F, n), complex
        ``dp_r / dh`` of each pocket at each frequency [Pa/m].
    """

    result: SuppliedResult
    frequencies: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    squeeze_damping: float
    film_stiffness: float
    pressure_response: np.ndarray


def _dynamics_inputs(mesh: SupportMesh, supplies, scale: Scale, frequencies, volumes, bulk_modulus):
    """The checked inputs of a linearised fed support: frequencies [rad/s], the pockets' laws, their volumes
    [m^3] (0: incompressible) and the bulk modulus [Pa]."""
    omega = np.asarray(frequencies, float).reshape(-1)
    if omega.size == 0 or not np.all(np.isfinite(omega)) or np.any(omega < 0):
        raise ValueError(f"frequencies must be finite numbers >= 0 [rad/s], got {frequencies!r}")
    laws = _laws(pocket_names(mesh), supplies, scale)
    bulk = positive("bulk_modulus", bulk_modulus, "Pa")
    if volumes is None:
        return omega, laws, np.zeros(len(laws)), bulk
    vol = np.broadcast_to(np.asarray(volumes, float), (len(laws),)).copy()
    for k, v in enumerate(vol):
        positive(f"volumes[{k}]", v, "m^3")
    return omega, laws, vol, bulk


def supply_dynamics(mesh: SupportMesh, h: float, supplies: Sequence[Supply] | Supply, scale: Scale, *,
                    frequencies: Sequence[float] = (0.0,), volumes: Sequence[float] | float | None = None,
                    bulk_modulus: float = 1.5e9, step: float = 1e-3,
                    discretization: Discretization = Discretization()) -> SupportDynamics:
    r"""Stiffness and damping of a fed pad moving normal to itself (``UniformFilm(h)``), linearised.

    The pockets' rate equations of the pad in motion, ``V/K dp_r/dt = Q_restrictor(p_r) - Q_film(h, p, dh/dt)
    - A_r dh/dt`` (``A_r dh/dt`` the pocket's own gap opening), with the load ``W(h, p, dh/dt)``, are
    linearised at the balance (:func:`solve_supplied`, no motion) for a small harmonic motion
    ``dh = h_hat exp(i omega t)``::

        (i omega V/K + k_r + G) dp = -(dQ/dh + i omega (q_s + A_r)) h_hat,
        Z = -dW/h_hat = -a . dp/h_hat - dW/dh + i omega B,

    with ``k_r = -dQ_restrictor/dp`` (:meth:`Law.slope`), ``G`` the film's conductance, ``q_s`` the pockets'
    outflow per unit squeeze, ``a`` the load per unit pocket pressure, ``B`` the film's squeeze damping at
    fixed pockets, and ``dQ/dh``, ``dW/dh`` at fixed pockets by a central difference of films at
    ``h +- step`` (as :func:`supply_stiffness`). The film is linear in ``p`` and ``dh/dt`` (no cavitation,
    rigid surfaces): each term is one superposition column. The stiffness is ``Re Z``, the damping
    ``Im Z / omega``; at ``omega = 0`` the limit ``d Im Z / d omega``. Prescribed pockets (a rigid supply)
    keep ``dp = 0``: the damping is then ``B``, for the circular recess pad the closed form
    ``3 pi mu/(2 h^3) (R^4 - R0^4 - (R^2 - R0^2)^2/ln(R/R0))``. A restrictor adds ``a (q_s + A_r)/(k_r + G)``
    to the slow-motion damping (``q_s + A_r = a`` on the recess pad: the squeeze draws from the pocket what
    its pressure carries), and the pocket's compressibility ``V/K`` takes some back at speed.

    Parameters
    ----------
    mesh : SupportMesh
        The pad with its pockets.
    h : float
        Film thickness [c], > step.
    supplies, scale, discretization
        As :func:`solve_supplied`.
    frequencies : sequence of float
        Angular frequencies of the motion [rad/s], >= 0.
    volumes : float or sequence of float, optional
        Each pocket's oil volume [m^3], > 0; default none (an incompressible pocket).
    bulk_modulus : float
        The oil's bulk modulus ``K`` [Pa], > 0.
    step : float
        The difference step [c], in (0, 0.1].

    Returns
    -------
    SupportDynamics
    """
    from ..film import UniformFilm

    h = positive("h", h, "c")
    step = in_range("step", step, Range(0.0, 0.1, lo_open=True))
    if h <= step:
        raise ValueError(f"h must be larger than step = {step:g} [c], got {h!r}")
    omega, laws, vol, bulk = _dynamics_inputs(mesh, supplies, scale, frequencies, volumes, bulk_modulus)
    n = len(laws)
    balanced = solve_supplied(mesh, UniformFilm(h), supplies, scale, discretization=discretization)
    p0 = np.array([scale.from_pressure(p) for p in balanced.pressures])

    def linear(hh: float):
        """Per pocket: outflow per unit pressure of each pocket (n, n) and per unit squeeze (n,); the load per unit
        pocket pressure (n,) and per unit squeeze; the pockets' areas (n,) [non-dimensional]."""
        pf = pocket_film(mesh, UniformFilm(hh), discretization)
        U = np.column_stack([pf.whole.fields[:, 1]] + [s.fields[:, 3] for s in pf.pockets])
        W = np.zeros((4, n + 1))
        W[1, 0] = 1.0
        W[3, 1:] = 1.0
        flows = pocket_flows(pf, U, W)
        loads = np.array([s.integrals[3] for s in pf.pockets])
        areas = np.array([s.operators.pocket_moments[0] for s in pf.pockets])
        return flows[:, 1:], flows[:, 0], loads, float(pf.whole.integrals[1]), areas

    G, q_s, a, w_s, areas = linear(h)
    G_up, _, a_up, _, _ = linear(h + step)
    G_down, _, a_down, _, _ = linear(h - step)
    # SI: pressures [Pa], flows [m^3/s], lengths [m], speeds dh/dt [m/s] (time scale 1/omega of the scale)
    P, Q, F = scale.pressure, scale.flow, scale.force
    c, t = scale.clearance, 1.0 / scale.speed
    G_si = G * Q / P
    dQ_dh = (G_up - G_down) @ p0 / (2 * step) * Q / c
    dW_dh = float((a_up - a_down) @ p0) / (2 * step) * F / c
    demand = (q_s + areas) * Q * t / c  # [m^3/s per m/s]: the film's and the pocket's own
    a_si = a * F / P  # [N/Pa]
    B = -w_s * F * t / c  # [N s/m]
    free = np.array([law.kind != "pressure" for law in laws])
    k_r = np.array([-law.slope(pk) if law.kind != "pressure" else 0.0 for law, pk in zip(laws, p0)]) * Q / P
    if not np.all(np.isfinite(k_r)):
        raise SupplyError("an orifice at its supply pressure (no pressure drop) has no linearisation: its flow's "
                          "slope is infinite")
    compliance = vol / bulk  # [m^3/Pa]
    idx = np.flatnonzero(free)
    S0 = np.diag(k_r[idx]) + G_si[np.ix_(idx, idx)]
    response = np.zeros((omega.size, n), complex)  # dp/h_hat [Pa/m]
    slope = np.zeros(n)  # d(Im dp / h_hat)/d omega at omega = 0
    if idx.size:
        D, M, Gam = dQ_dh[idx], demand[idx], np.diag(compliance[idx])
        s0_D = np.linalg.solve(S0, D)
        slope[idx] = -np.linalg.solve(S0, M) + np.linalg.solve(S0, Gam @ s0_D)
        for i, w in enumerate(omega):
            response[i, idx] = np.linalg.solve(S0 + 1j * w * Gam, -(D + 1j * w * M))
    Z = -(response @ a_si) - dW_dh + 1j * omega * B
    stiffness = Z.real
    share_k = -(response * a_si).real
    with np.errstate(invalid="ignore", divide="ignore"):
        damping = np.where(omega > 0, Z.imag / np.where(omega > 0, omega, 1.0), B - float(slope @ a_si))
        share_c = np.where(omega[:, None] > 0, -(response * a_si).imag / np.where(omega > 0, omega, 1.0)[:, None],
                           -(slope * a_si)[None, :])
    pockets = tuple(dataclasses.replace(ps, stiffness=share_k[:, j], damping=share_c[:, j])
                    for j, ps in enumerate(balanced.pockets))
    return SupportDynamics(result=dataclasses.replace(balanced, pockets=pockets), frequencies=omega,
                           stiffness=stiffness, damping=damping, squeeze_damping=float(B), film_stiffness=-dW_dh,
                           pressure_response=response)


# -- dynamics of a journal displaced in the plane: its pockets responding ------------------------------------

@dataclass(frozen=True)
class DisplacedJournal:
    """The film of a journal whose centre is displaced by ``(x, y)`` [c]: ``h = 1 - x cos phi - y sin phi``.

    The same film as ``CosineFilm(hypot(x, y), atan2(-y, -x))``; its squeeze shapes are those of the
    centre's velocity in the plane, ``dh/dx = -cos phi``, ``dh/dy = -sin phi`` (defined at the centred
    journal too, where ``CosineFilm``'s ``phi0`` is not).
    """

    x: float
    y: float
    smooth: ClassVar[bool] = True

    def thickness(self, phi, z):
        phi = np.asarray(phi, float)
        return 1.0 - self.x * np.cos(phi) - self.y * np.sin(phi) + 0.0 * np.asarray(z, float)

    def gradient(self, phi, z):
        phi = np.asarray(phi, float)
        dphi = self.x * np.sin(phi) - self.y * np.cos(phi) + 0.0 * np.asarray(z, float)
        return dphi, np.zeros_like(dphi)

    def laplacian(self, phi, z):
        phi = np.asarray(phi, float)
        return self.x * np.cos(phi) + self.y * np.sin(phi) + 0.0 * np.asarray(z, float)

    def rate_shapes(self, phi, z):
        phi = np.asarray(phi, float) + 0.0 * np.asarray(z, float)
        return -np.cos(phi), -np.sin(phi)

    def minimum(self, phi_range):
        return None


@dataclass(frozen=True)
class JournalDynamics:
    """Stiffness and damping of a journal on a fed support, its pockets responding, linearised [SI].

    The film's force on the journal is ``-force`` (``force = int p (cos phi, sin phi) dA``, from the journal's
    centre into the film); the coefficients are ``K_ij + i omega C_ij = d force_i / d x_j`` for a harmonic motion
    ``x = x_hat exp(i omega t)`` of the journal's centre, i.e. the film's force on the journal is
    ``-K x - C dx/dt`` for a slow motion.

    Attributes
    ----------
    result : SuppliedResult
        The balanced support at the displacement.
    frequencies : ndarray, shape (F,)
        Angular frequencies [rad/s] (0: the limit of slow motion).
    stiffness : ndarray, shape (F, 2, 2)
        ``Re Z`` [N/m], rows the force's ``(x, y)``, columns the displacement's.
    damping : ndarray, shape (F, 2, 2)
        ``Im Z / omega`` [N s/m] (at ``omega = 0`` the limit ``d Im Z / d omega``).
    squeeze_damping : ndarray, shape (2, 2)
        The film's own damping with every pocket held at its pressure (a rigid supply) [N s/m].
    film_stiffness : ndarray, shape (2, 2)
        The stiffness with every pocket held at its pressure [N/m].
    pressure_response : ndarray, shape (F, n, 2), complex
        ``dp_r / dx_j`` of each pocket [Pa/m].
    """

    result: SuppliedResult
    frequencies: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    squeeze_damping: np.ndarray
    film_stiffness: np.ndarray
    pressure_response: np.ndarray


def journal_dynamics(mesh: SupportMesh, displacement: Sequence[float], supplies: Sequence[Supply] | Supply,
                     scale: Scale, *, frequencies: Sequence[float] = (0.0,),
                     volumes: Sequence[float] | float | None = None, bulk_modulus: float = 1.5e9,
                     step: float = 1e-3, operating: OperatingPoint = OperatingPoint(wedge=0.0),
                     discretization: Discretization = Discretization()) -> JournalDynamics:
    r"""The 2x2 stiffness and damping of a journal on a fed support, each pocket responding through its restrictor.

    The linear film of a journal displaced by ``x = (x, y)`` [c] (:class:`DisplacedJournal`) moving at ``v``, with
    each pocket's rate equation ``V/K dp_r/dt = Q_restrictor(p_r) - Q_film(x, p, v) - dV_r/dt`` (``dV_r/dt =
    int_pocket dh/dt dA``, the pocket's own gap), linearised at the balance (:func:`solve_supplied`) for a
    harmonic motion ``x = x_hat exp(i omega t)`` as :func:`supply_dynamics` does for the pad::

        (i omega V/K + k_r + G) dp = -(dQ/dx + i omega (q_v + m)) x_hat,
        Z = d force/d x_hat = dF/dx + a dp/x_hat + i omega B,

    one superposition column per pocket and per direction of the squeeze (``q_v`` the pockets' outflow and ``B``
    the film's force per unit velocity of the centre, ``a`` the force per unit pocket pressure, ``m`` the pockets'
    gap rate per unit velocity), ``dQ/dx`` and ``dF/dx`` at fixed pockets by central differences of films at
    ``x +- step`` in each direction. Prescribed pockets keep ``dp = 0`` (the damping is then ``B``, the film's
    own); ``V -> inf`` holds every fed pocket at its balanced pressure at any ``omega > 0``; at ``omega -> 0`` the
    stiffness is the slope of the balanced force against the displacement at fixed supply.

    Parameters
    ----------
    mesh : SupportMesh
        The support surface with its pockets (a pad of a multi-pad journal: rotate and add the pads).
    displacement : (float, float)
        The journal centre's displacement ``(x, y)`` [c] in the surface's frame (``phi = 0`` along x).
    supplies, scale, discretization
        As :func:`solve_supplied` (no cavitation, rigid surfaces: the film is linear).
    frequencies : sequence of float
        Angular frequencies of the motion [rad/s], >= 0.
    volumes : float or sequence of float, optional
        Each pocket's oil volume [m^3], > 0; default none (incompressible pockets).
    bulk_modulus : float
        The oil's bulk modulus ``K`` [Pa], > 0.
    step : float
        The difference step [c], in (0, 0.1].
    operating : OperatingPoint
        Its wedge (a turning journal: a hybrid support); squeeze and inlet pressure must be 0.

    Returns
    -------
    JournalDynamics
    """
    try:
        x0, y0 = (float(v) for v in displacement)
    except (TypeError, ValueError):
        raise ValueError(f"displacement must be a pair (x, y) [c], got {displacement!r}") from None
    if not (math.isfinite(x0) and math.isfinite(y0)) or math.hypot(x0, y0) + step >= 1.0:
        raise ValueError(f"displacement must be finite with |(x, y)| + step < 1 [c], got {displacement!r}")
    step = in_range("step", step, Range(0.0, 0.1, lo_open=True))
    if any(operating.squeeze) or operating.inlet_pressure != 0.0:
        raise ValueError("operating: the squeeze and the inlet pressure must be 0 (the motion and the supplies "
                         "set them)")
    omega, laws, vol, bulk = _dynamics_inputs(mesh, supplies, scale, frequencies, volumes, bulk_modulus)
    n = len(laws)
    wedge = operating.wedge
    balanced = solve_supplied(mesh, DisplacedJournal(x0, y0), supplies, scale, operating=operating,
                              discretization=discretization)
    p0 = np.array([scale.from_pressure(p) for p in balanced.pressures])

    def linear(x: float, y: float):
        """Per pocket: outflow of the motion (n,), per unit velocity (n, 2), per unit pocket pressure (n, n); the
        force of the motion (2,), per unit velocity (2, 2), per unit pocket pressure (2, n); the pockets'
        moments (n, 3) [non-dimensional]."""
        pf = pocket_film(mesh, DisplacedJournal(x, y), discretization)
        whole = pf.whole
        U = np.column_stack([wedge * whole.fields[:, 0], whole.fields[:, 1], whole.fields[:, 2]]
                            + [s.fields[:, 3] for s in pf.pockets])
        W = np.zeros((4, n + 3))
        W[0, 0], W[1, 1], W[2, 2] = wedge, 1.0, 1.0
        W[3, 3:] = 1.0
        flows = pocket_flows(pf, U, W)
        forces = np.column_stack([s.forces[:, 3] for s in pf.pockets])
        moments = np.array([s.operators.pocket_moments for s in pf.pockets])
        return flows[:, 0], flows[:, 1:3], flows[:, 3:], wedge * whole.forces[:, 0], whole.forces[:, 1:3], forces, moments

    _, q_v, G, _, f_v, a, moments = linear(x0, y0)
    dQ, dF = np.zeros((n, 2)), np.zeros((2, 2))
    for j in range(2):
        e = np.eye(2)[j] * step
        q_u, _, G_u, f_u, _, a_u, _ = linear(x0 + e[0], y0 + e[1])
        q_d, _, G_d, f_d, _, a_d, _ = linear(x0 - e[0], y0 - e[1])
        dQ[:, j] = ((q_u + G_u @ p0) - (q_d + G_d @ p0)) / (2 * step)
        dF[:, j] = ((f_u + a_u @ p0) - (f_d + a_d @ p0)) / (2 * step)
    # SI: pressures [Pa], flows [m^3/s], displacements [m], velocities [m/s] (time scale 1/omega of the scale)
    P, Q, F = scale.pressure, scale.flow, scale.force
    c, t = scale.clearance, 1.0 / scale.speed
    G_si = G * Q / P
    dQ_si = dQ * Q / c
    dF_si = dF * F / c
    demand = (q_v - moments[:, 1:3]) * Q * t / c  # the film's outflow and the pocket's gap per unit velocity [m^3]
    a_si = a * F / P  # [N/Pa]
    B = f_v * F * t / c  # [N s/m]
    free = np.array([law.kind != "pressure" for law in laws])
    k_r = np.array([-law.slope(pk) if law.kind != "pressure" else 0.0 for law, pk in zip(laws, p0)]) * Q / P
    if not np.all(np.isfinite(k_r)):
        raise SupplyError("an orifice at its supply pressure (no pressure drop) has no linearisation: its flow's "
                          "slope is infinite")
    idx = np.flatnonzero(free)
    response = np.zeros((omega.size, n, 2), complex)  # dp/dx_hat [Pa/m]
    slope = np.zeros((n, 2))  # d(Im dp/x_hat)/d omega at omega = 0
    if idx.size:
        S0 = np.diag(k_r[idx]) + G_si[np.ix_(idx, idx)]
        D, M, Gam = dQ_si[idx], demand[idx], np.diag(vol[idx] / bulk)
        slope[idx] = -np.linalg.solve(S0, M) + np.linalg.solve(S0, Gam @ np.linalg.solve(S0, D))
        for i, w in enumerate(omega):
            response[i, idx] = np.linalg.solve(S0 + 1j * w * Gam, -(D + 1j * w * M))
    Z = dF_si[None] + np.einsum("in,fnj->fij", a_si, response) + 1j * omega[:, None, None] * B[None]
    with np.errstate(invalid="ignore", divide="ignore"):
        damping = np.where(omega[:, None, None] > 0, Z.imag / np.where(omega > 0, omega, 1.0)[:, None, None],
                           (B + a_si @ slope)[None])
    return JournalDynamics(result=balanced, frequencies=omega, stiffness=Z.real, damping=damping,
                           squeeze_damping=B, film_stiffness=dF_si, pressure_response=response)
