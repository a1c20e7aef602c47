"""The plunger shoe over the pump cycle, plunger inertia neglected: :func:`simulate`, the door of every film model.

At every shaft angle the film force balances the applied load (paper 004
eq. 13-14, ``docs/formulations.md``); the film model (:data:`MODELS`) turns
that balance into the rates of the shoe's state, and the one stepping loop
(:mod:`bearingfe.transient.stepping`) integrates them:

================================  =========================================================  ==========================
key of :data:`MODELS`             model                                                      :func:`simulate` with
================================  =========================================================  ==========================
``"rigid"``                       rigid film, the pressure may go negative (the paper's)     ``cavitation="none"``
``"cavitating"``                  rigid film, Swift-Stieber or Gumbel rupture                ``"reynolds"``, ``"gumbel"``
``"jfo"``                         rigid film, mass-conserving rupture (history carried)      ``"jfo"`` (P1)
``"fed"``                         rigid film, pocket fed through the plunger's restrictor    ``pump.shoe_supply`` given
``"fed cavitating"``              the fed pocket on the film with Swift-Stieber or Gumbel    ``pump.shoe_supply``, ``"reynolds"``, ``"gumbel"``
``"fed jfo"``                     the fed pocket on the JFO film (pocket pressure stepped)   ``pump.shoe_supply``, ``"jfo"`` (P1)
``"quasi-static elastic"``        elastic support, deflection following the pressure         ``elastic=...``
``"fed quasi-static elastic"``    the fed pocket on the quasi-static elastic support         ``pump.shoe_supply``, ``elastic=...``
``"elastic"``                     elastic support with the squeeze of the deflection         :func:`~bearingfe.transient.elastic.simulate_elastic`
================================  =========================================================  ==========================
"""

from __future__ import annotations

import math
from types import MappingProxyType
from typing import Mapping

from ..bearings.pump import EccentricPump
from ..core import DEFAULT_SOLVER, Discretization
from ..core.parameters import takes
from ..elastic import Compliance
from ..geometry import SupportMesh
from ..reynolds import CAVITATION
from .base import Model
from .cavitating import Cavitating
from .driver import run_transient
from .elastic import ElasticSqueeze, FedQuasiStaticElastic, QuasiStaticElastic
from .fed import Fed, FedCavitating, FedJFO
from .jfo import JFO
from .rigid import Rigid, balance_ratio, pump_mesh, steady_state
from .settings import Integration
from .trajectory import LiftOffError, Trajectory

__all__ = ["simulate", "MODELS", "film_model", "pump_mesh", "steady_state", "balance_ratio"]

#: The film models of the pump transient by name (:class:`bearingfe.transient.base.Model`).
MODELS: Mapping[str, type[Model]] = MappingProxyType({"rigid": Rigid, "cavitating": Cavitating, "jfo": JFO,
                                                      "quasi-static elastic": QuasiStaticElastic,
                                                      "elastic": ElasticSqueeze, "fed": Fed,
                                                      "fed cavitating": FedCavitating, "fed jfo": FedJFO,
                                                      "fed quasi-static elastic": FedQuasiStaticElastic})


def _model_name(cavitation: str, elastic: Compliance | None, pump: EccentricPump | None = None) -> str:
    if pump is not None and pump.shoe_supply is not None:
        if cavitation == "jfo" and elastic is not None:
            raise ValueError("elastic: the JFO model runs on a rigid film; cavitation='jfo' does not take elastic=")
        if cavitation == "jfo":
            return "fed jfo"
        if elastic is not None:
            return "fed quasi-static elastic"
        return "fed" if cavitation == "none" else "fed cavitating"
    if elastic is not None:
        if cavitation == "jfo":
            raise ValueError("elastic: the JFO model runs on a rigid film; cavitation='jfo' does not take elastic=")
        return "quasi-static elastic"
    return {"none": "rigid", "jfo": "jfo"}.get(cavitation, "cavitating")


def film_model(pump: EccentricPump, mesh: SupportMesh, *, cavitation: str, elastic: Compliance | None,
               formulation: str, element: str, solver: str) -> Model:
    """The model of :data:`MODELS` that :func:`simulate`'s ``cavitation`` and ``elastic`` choose."""
    name = _model_name(cavitation, elastic, pump)
    if name in ("quasi-static elastic", "fed quasi-static elastic"):
        return MODELS[name](pump, elastic, cavitation=cavitation, formulation=formulation, solver=solver)
    if name in ("cavitating", "fed cavitating"):
        return MODELS[name](pump, mesh, cavitation=cavitation, formulation=formulation, element=element,
                            solver=solver)
    return MODELS[name](pump, mesh, formulation=formulation, element=element, solver=solver)


def _film_fraction(min_film: float | None, pump: EccentricPump) -> float:
    """``min_film`` [m] (default 2 % of the clearance) in clearances."""
    film = 0.02 * pump.clearance if min_film is None else min_film
    if not (isinstance(film, (int, float)) and 0 < film < pump.clearance):
        raise ValueError(f"min_film must be in (0, clearance = {pump.clearance} m), got {min_film!r}")
    return float(film) / pump.clearance


def _mesh_and_element(pump: EccentricPump, mesh: SupportMesh | None, mesh_size: float | None,
                      element: str | None, elastic: Compliance | None) -> tuple[SupportMesh, str]:
    """The run's mesh and element: the compliance's, the given ones, or the defaults (P2 on a curved mesh)."""
    if element is None:
        if isinstance(elastic, Compliance):
            element = elastic.element
        else:
            element = "P2" if mesh is None or getattr(mesh, "geometry_order", 1) == 2 else "P1"
    if elastic is not None:
        if not isinstance(elastic, Compliance):
            raise ValueError(f"elastic must be a bearingfe.elastic.Compliance, got {type(elastic).__name__}")
        if mesh is not None and elastic.mesh is not mesh:
            raise ValueError("elastic: the compliance was built on another mesh than `mesh`")
        if elastic.element != element:
            raise ValueError(f"elastic: the compliance is for element {elastic.element!r}, the run uses {element!r}")
        mesh = elastic.mesh
    if mesh is None:
        size = (0.2 if element == "P2" else 0.08) if mesh_size is None else mesh_size
        mesh = pump_mesh(pump, size, order=2 if element == "P2" else 1)
    if not isinstance(mesh, SupportMesh):
        raise ValueError(f"mesh must be a bearingfe.SupportMesh, got {type(mesh).__name__}")
    return mesh, element


@takes(Discretization)
def simulate(pump: EccentricPump, mesh: SupportMesh | None = None, revolutions: float = 1.0, *,
             start: str | tuple[float, float] = "steady", beta0: float = 0.0, cavitation: str = "none",
             method: str = "LSODA", rtol: float = 1e-5, atol: float | None = None, max_step: float = math.pi / 8,
             min_film: float | None = None, points_per_revolution: int = 180, mesh_size: float | None = None,
             formulation: str = "pi", element: str | None = None, solver: str = DEFAULT_SOLVER,
             periodic_tol: float = 1e-6, periodic_max_iter: int = 30,
             periodic_method: str | None = None, max_revolutions: float | None = None,
             elastic: Compliance | None = None) -> Trajectory:
    """Integrate the quasi-static equilibrium of the plunger shoe over the pump cycle.

    Parameters
    ----------
    pump : EccentricPump
    mesh : SupportMesh, optional
        Mesh of ``pump.surface`` (reused for the whole run). Default:
        :func:`pump_mesh` with ``mesh_size``, curved (order 2) for P2.
    revolutions : float
        Length of the run in shaft turns, > 0.
    start : {"steady", "periodic"} or (gamma, delta)
        Initial state: the steady state at ``beta0``; the periodic state
        (from the steady state, by ``periodic_method`` over one revolution
        at a time, at most ``periodic_max_iter`` turns, until ``max |y(2pi)
        - y(0)| < periodic_tol`` with the attitude difference wrapped); or
        given values.
    beta0 : float
        Shaft angle at the start [rad].
    cavitation : {"none", "reynolds", "gumbel", "jfo"}
        ``"none"`` keeps the paper's model (p may go negative, rates from the
        2x2 superposition system); ``"reynolds"`` (Swift-Stieber) and
        ``"gumbel"`` find the rates by a small Newton on the cavitated film
        force, warm-started from the previous rupture set
        (:func:`bearingfe.cavitation.rates_for_load`); ``"jfo"``
        (mass-conserving) carries the fill fraction over the cycle: backward
        Euler steps, one to each of the ``points_per_revolution`` samples per
        turn (:mod:`bearingfe.transient.jfo`; ``method``, ``rtol``, ``atol``
        and ``max_step`` do not apply; P1 only); its periodic start runs one
        revolution first and starts from its end (film history included).
        A pump whose shoe pocket is fed through the plunger's restrictor
        (``pump.shoe_supply``, ``[shoe.supply]``) runs the ``"fed"`` model
        (:mod:`bearingfe.transient.fed`) with ``"none"``; with ``"reynolds"``,
        ``"gumbel"`` (``"fed cavitating"``) or ``"jfo"`` (``"fed jfo"``, the pocket
        pressure stepped with the fill fraction) its ``pocket_volume`` is needed.
    method : {"LSODA", "Radau", "BDF", "RK23", "RK45"}
        scipy integrator, stepped with its own error control. LSODA (default)
        switches between Adams and BDF as the stiffness changes; on the
        shipped pump it needed a third to a half of Radau's right-side
        evaluations (one factorization each) for the same accuracy. The
        explicit Runge-Kutta pairs RK23 and RK45 suit films that are not
        stiff (there they need fewer evaluations still, and their error
        follows ``rtol`` more closely); where the film is stiff their error
        control shortens the steps, which stays correct but costs
        evaluations.
    rtol, atol : float
        Integrator tolerances on ``(gamma, delta)``; ``0 < rtol < 1``;
        ``atol`` defaults to ``1e-3 rtol``.
    max_step : float
        Largest step in shaft angle [rad].
    min_film : float, optional
        Smallest film thickness [m] that ends the run as ruptured. Default
        2 % of the clearance.
    points_per_revolution : int
        Output samples per turn (from the integrator's dense output), >= 8.
    mesh_size : float, optional
        Element size of the default mesh [R0]: 0.2 for P2, 0.08 for P1.
    formulation, solver
        See :func:`bearingfe.superpose`.
    element : {"P1", "P2"}, optional
        Finite element. Default: P2 on the default mesh and on a curved
        (order-2) mesh; P1 on a straight mesh passed in (P2 keeps its
        convergence rate only with curved pocket edges, and a mesh made for
        P1 would cost four times the unknowns).
    periodic_tol, periodic_max_iter
        Periodic start: tolerance on ``(gamma [-], delta [rad])`` and the
        largest number of revolutions. A fed pocket on a cavitating film
        (``"fed cavitating"``) integrates the search's revolutions at
        ``rtol <= periodic_tol / 10`` by itself (its return map converges
        only to its integrator's accuracy).
    periodic_method : {"newton", "fixed-point", "anderson", "one-revolution"}, optional
        :data:`bearingfe.transient.PERIODIC_METHODS`; default the model's
        own: ``"newton"`` (Newton shooting on the return map with the
        monodromy matrix of the second revolution, Broyden-updated; three
        revolutions on the shipped pump, plus the output revolution, which
        verifies the residual), ``"one-revolution"`` under JFO. ``"fixed-point"``
        iterates the return map (five to six revolutions there, plus the
        output revolution).
    max_revolutions : float, optional
        Largest ``revolutions`` accepted (a guard against runaway work);
        default the ``revolutions`` limit of :mod:`bearingfe.core.limits` (100).
    elastic : Compliance, optional
        Compliance of the support on ``mesh`` (:func:`bearingfe.elastic.half_space`;
        with a fed pocket the ``"fed quasi-static elastic"`` model, ``pocket_volume`` needed):
        at every shaft angle the film ``h_rigid + w`` and the rates are found
        together (:func:`bearingfe.elastic.balance_load`, the direct form):
        without cavitation by a chord Newton from the last answer whose dense
        Jacobian is kept over the right sides (:class:`bearingfe.elastic.ChordBalance`;
        ``stats["factorizations"]`` then counts its residuals), else by the damped
        Newton on the deflection. Quasi-static deflection (``dw/dt`` not in the
        squeeze term; :func:`bearingfe.transient.elastic.simulate_elastic` has it);
        the run starts from the rigid steady (or periodic-iteration) state.
    discretization : Discretization, optional
        ``element``, ``formulation``, ``solver`` and ``mesh_size`` in one
        object (:class:`bearingfe.core.parameters.Discretization`) instead of the
        keywords.

    Returns
    -------
    Trajectory

    Raises
    ------
    LiftOffError
        The pockets' hydrostatic lift reaches the plunger force (checked
        before integrating; see :func:`balance_ratio`).
    ValueError
        Bad argument (message names it); :class:`bearingfe.core.limits.LimitError`
        if ``revolutions`` is above its limit.

    Notes
    -----
    A trial step of the integrator whose state closes the film is rejected
    and retaken from the last accepted state, shorter
    (:mod:`bearingfe.transient.stepping`); the run ends as ``"ruptured"`` only
    where an accepted state's film reaches ``min_film`` (located on the
    integrator's dense output).

    The defaults (P2 on a curved 0.2 R0 mesh, LSODA, ``rtol = 1e-5``) are
    the cheapest setting measured within 0.1 % of the converged smallest
    film on the shipped pump, periodic start included, that stays there on
    other designs (``benchmarks/pump_revolution.py``,
    docs/benchmarks_pump.md): P1 needs far finer meshes for that (P1 on
    0.08 R0 is 1.4 % off); at ``rtol = 1e-4`` the periodic start needs five
    revolutions and lands 4e-4 off; ``method="RK23"`` at ``rtol = 1e-3``
    is the cheapest revolution within 0.1 % on the shipped pump from its
    periodic state, but its error reaches a few 1e-3 on thinner films
    (the page's table across designs), where LSODA at the default ``rtol``
    stays below 1e-4.
    Before these defaults the call was P1, ``mesh_size = 0.08``, ``rtol =
    1e-6``, ``atol = 1e-9``: pass them to reproduce old runs (a straight
    mesh passed in still gets P1).
    """
    if not isinstance(pump, EccentricPump):
        raise ValueError(f"pump must be a bearingfe.EccentricPump, got {type(pump).__name__}")
    settings = Integration(revolutions=revolutions, start=start, beta0=beta0, method=method, rtol=rtol, atol=atol,
                           max_step=max_step, min_film=_film_fraction(min_film, pump),
                           points_per_revolution=points_per_revolution, periodic_method=periodic_method,
                           periodic_tol=periodic_tol, periodic_max_iter=periodic_max_iter,
                           max_revolutions=max_revolutions)
    if cavitation not in CAVITATION:
        raise ValueError(f"cavitation must be one of {CAVITATION}, got {cavitation!r}")
    mesh, element = _mesh_and_element(pump, mesh, mesh_size, element, elastic)
    MODELS[_model_name(cavitation, elastic, pump)].check(settings)
    ratio = balance_ratio(pump, mesh, formulation=formulation, element=element)
    if ratio >= 1.0:
        raise LiftOffError(f"{pump.name!r}: the pockets' hydrostatic lift is {ratio:.3f} x the plunger force "
                           f"(balance ratio >= 1): the shoe lifts off, there is no equilibrium with a closed "
                           f"film; make the pockets smaller or the plunger larger")
    model = film_model(pump, mesh, cavitation=cavitation, elastic=elastic, formulation=formulation, element=element,
                       solver=solver)
    return run_transient(model, settings, balance_ratio=ratio)
