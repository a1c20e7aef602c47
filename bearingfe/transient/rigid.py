r"""The rigid film of the plunger shoe: quasi-static equilibrium as an ODE in the shaft angle.

Model (paper 004 eq. 13-14, ``docs/formulations.md``; frames in :mod:`bearingfe.bearings.pump`)
--------------------------------------------------------------------------------------
The plunger's inertia is neglected, so at every shaft angle the film force
balances the applied load. In the shoe frame the film is
``h = 1 + gamma cos(psi - delta)`` and the Reynolds right side is
``6 w dh/dpsi + 12 (gamma' cos(psi - delta) + gamma delta' sin(psi - delta))``
with ``w = 1 - dphi2/dbeta`` and primes ``d/dbeta``. By superposition the
film force is ``A(gamma, delta) (gamma', delta') + w F_w + p_s F_s`` and the
balance ``film force + (-f, 0) = 0`` is a 2x2 linear system for the rates:
the ODE

    d(gamma, delta)/dbeta = A^-1 ((f, 0) - w F_w - p_s F_s).

One :func:`bearingfe.superpose` (one factorization, four unit right sides)
per state gives ``A``, ``F_w``, ``F_s``; the same factorization serves the
post-processing (flows, friction) of that state. The mesh is built once.

The ODE is stiff where the film is thin (the squeeze resistance grows like
``h^-3``): LSODA (adaptive, switching to BDF where stiff) is the default of
:func:`bearingfe.simulate`. Also here: the steady state of an angle
(:func:`steady_state`), the hydrostatic balance ratio (:func:`balance_ratio`)
and the pump's default mesh (:func:`pump_mesh`).
"""

from __future__ import annotations

import math
import time
from typing import Mapping, Sequence

import numpy as np
from scipy.optimize import root

from ..bearings.pump import EccentricPump
from ..core import DEFAULT_SOLVER, Discretization
from ..core.checks import MAX_GAMMA
from ..core.parameters import takes
from ..film import CosineFilm, Superposition, film_outputs, source_weights, superpose
from ..geometry import SupportMesh, mesh_surface
from .base import FilmClosed, Model
from .settings import INTEGRATORS, STARTS

__all__ = ["Rigid", "pump_mesh", "balance_ratio", "steady_state", "scipy_stepper"]

#: Film states whose superpositions one run keeps (the integrator revisits the last few).
CACHE_SIZE = 8
#: Output samples whose flows and friction are computed as one batch: blocks of point fields of a few hundred
#: kB that the allocator reuses, where all samples at once (181 a revolution) made some thirty fields of a few MB
#: each, fresh pages from the system every time (a fifth of a pump design's CPU went to the page faults).
SAMPLE_BLOCK = 16


def pump_mesh(pump: EccentricPump, size: float = 0.08, **kwargs) -> SupportMesh:
    """Mesh of the pump's shoe surface (see :func:`bearingfe.mesh_surface`).

    Parameters
    ----------
    size : float
        Element size in units of ``R0`` [-].
    """
    return mesh_surface(pump.surface, size, **kwargs)


@takes(Discretization)
def balance_ratio(pump: EccentricPump, mesh: SupportMesh | None = None, *, formulation: str = "pi",
                  element: str = "P1") -> float:
    """Hydrostatic lift of the pockets over the plunger force, worst over the cycle [-].

    The lift is the film force of the pockets at chamber pressure with the
    shoe concentric (``h = 1``): for a uniform film the Laplace problem does
    not depend on the thickness, so this is the film-independent part the
    pocket contributes. The plunger force includes the preload, so the ratio
    is evaluated at suction and at discharge pressure and the larger is
    returned. ``>= 1`` means lift-off (no equilibrium with a closed film);
    ``0`` for a plain shoe.
    """
    if not pump.surface.inlets:
        return 0.0
    mesh = pump_mesh(pump) if mesh is None else mesh
    sup = superpose(mesh, CosineFilm(0.0, 0.0), formulation=formulation, element=element)
    lift = float(sup.forces[0, 3])  # along psi = 0, away from O2, per unit pocket pressure
    ratios = []
    for p in (pump.cycle.suction, pump.cycle.discharge):
        force = (p * pump.plunger_area + pump.preload) / pump.scale.force
        ratios.append(lift * p / pump.scale.pressure / force)
    return float(max(ratios))


@takes(Discretization)
def steady_state(pump: EccentricPump, mesh: SupportMesh | None = None, beta: float = 0.0, *,
                 formulation: str = "pi", element: str = "P1", solver: str = DEFAULT_SOLVER,
                 guess: tuple[float, float] = (0.5, math.pi - 0.5)) -> tuple[float, float]:
    """Shoe state ``(gamma, delta)`` at which the film carries the load of angle ``beta`` without squeeze.

    Solved for the Cartesian eccentricity ``gamma (cos delta, sin delta)``
    (regular through ``gamma = 0``) by Powell's hybrid method; if that stalls
    from ``guess``, by continuation in the chamber pressure (load and pocket
    pressure scaled together from a light load).

    Raises
    ------
    RuntimeError
        If no steady state is found (message with the residual).
    """
    model = Rigid(pump, pump_mesh(pump) if mesh is None else mesh, formulation=formulation, element=element,
                  solver=solver)
    return model.steady(beta, guess)


def scipy_stepper(fun, beta0: float, y0: np.ndarray, beta1: float, settings, first_step: float | None,
                  max_step: float, atol=None, **options):
    """The settings' scipy integrator from ``(beta0, y0)`` to ``beta1`` (``first_step`` kept inside the span,
    ``max_step`` None: the settings')."""
    max_step = settings.max_step if max_step is None else max_step
    if first_step is not None:
        first_step = min(float(first_step), beta1 - beta0)
    return INTEGRATORS[settings.method](fun, beta0, np.asarray(y0, float), beta1, rtol=settings.rtol,
                                        atol=settings.absolute_tolerance if atol is None else atol,
                                        max_step=max_step, first_step=first_step, **options)


class Rigid(Model):
    """The rigid film without cavitation (the source paper's model; the pressure may go negative).

    Film states of one run: the superpositions of the last few states are
    kept (:data:`CACHE_SIZE`); counters ``nfev`` (balances), ``factorizations``,
    ``jacobians`` and ``seconds`` (in film solves) describe the integration,
    start and periodic start included, post-processing not.

    Parameters
    ----------
    pump : EccentricPump
    mesh : SupportMesh
        Of ``pump.surface``, reused for the whole run.
    formulation, element, solver
        See :func:`bearingfe.superpose`.
    """

    name = "rigid"
    periodic_methods = ("newton", "fixed-point", "anderson", "one-revolution")
    periodic_default = "newton"

    def __init__(self, pump: EccentricPump, mesh: SupportMesh, *, formulation: str = "pi", element: str = "P1",
                 solver: str = DEFAULT_SOLVER) -> None:
        self.pump, self.mesh = pump, mesh
        self.formulation, self.element, self.solver = formulation, element, solver
        self.dofs = float(mesh.n_nodes)
        self.nfev = self.factorizations = self.jacobians = 0
        self.seconds = 0.0
        self._cache: dict[tuple[float, float], Superposition] = {}
        phi = mesh.mesh.p[0]
        self.phi_range = (float(phi.min()), float(phi.max()))

    # -- film states -------------------------------------------------------------------------------

    def smallest_film(self, beta: float, y: np.ndarray) -> float:
        """Smallest rigid film over the arc [c] (``gamma < 0`` read as 0; ``-inf`` beyond the thin-film
        model, ``gamma > MAX_GAMMA``: a trial state a root finder strays to is not admissible, rather than
        an error about the film object)."""
        if not y[0] <= MAX_GAMMA:
            return -math.inf
        return CosineFilm(max(y[0], 0.0), y[1]).minimum(self.phi_range)

    def superposition(self, gamma: float, delta: float) -> Superposition:
        """The film state ``(gamma, delta)`` (cached); :class:`FilmClosed` if it is not admissible."""
        key = (float(gamma), float(delta))
        sup = self._cache.get(key)
        if sup is None:
            if not (math.isfinite(gamma) and math.isfinite(delta)) or gamma < 0 or \
                    self.smallest_film(0.0, key) <= 0:
                raise FilmClosed(key)
            start = time.perf_counter()
            sup = superpose(self.mesh, CosineFilm(gamma, delta), formulation=self.formulation,
                            element=self.element, solver=self.solver)
            self.seconds += time.perf_counter() - start
            self.factorizations += 1
            if len(self._cache) > CACHE_SIZE:
                self._cache.clear()
            self._cache[key] = sup
        return sup

    def balance(self, beta: float, y: np.ndarray, full: bool = True):
        """Rates that balance the plunger load at state ``y``, and the film result where it is not linear."""
        self.nfev += 1
        sup = self.superposition(y[0], y[1])
        pump = self.pump
        try:
            return self.balancing_rates(sup, pump.load_vector(beta), float(pump.wedge(beta)),
                                        self.pocket_pressure(beta, y))
        except np.linalg.LinAlgError as exc:
            raise RuntimeError(f"equilibrium rates undefined at beta = {beta:.4f} rad, gamma = {y[0]:.4g}: "
                               f"{exc}") from None

    def pocket_pressure(self, beta: float, y: np.ndarray) -> float:
        """The pockets' pressure [-] at a state: the chamber's (a model that feeds them carries its own)."""
        return float(self.pump.inlet_pressure(beta))

    def balancing_rates(self, sup: Superposition, load: np.ndarray, wedge: float, inlet_pressure: float):
        """``(rates, None)``: the 2x2 superposition system (the film result is linear in the sources)."""
        return sup.rates_for_load(load, wedge, inlet_pressure), None

    def rates(self, beta: float, y: np.ndarray) -> np.ndarray:
        return self.balance(beta, y, full=False)[0]

    # -- start -------------------------------------------------------------------------------------

    def steady(self, beta: float, guess: tuple[float, float] = (0.5, math.pi - 0.5)) -> tuple[float, float]:
        """The steady state of angle ``beta`` (see :func:`steady_state`)."""
        pump = self.pump
        load = pump.load_vector(beta)
        wedge, ps = float(pump.wedge(beta)), float(pump.inlet_pressure(beta))
        scale = max(abs(load[0]), 1e-12)

        def residual(xy, share):
            g, d = math.hypot(*xy), math.atan2(xy[1], xy[0])
            try:
                sup = self.superposition(g, d)
            except FilmClosed:
                return np.array([1e3, 1e3]) * (1.0 + g)
            return (sup.force(wedge, (0.0, 0.0), share * ps) + share * load) / (share * scale)

        def solve(xy, share):
            sol = root(residual, xy, args=(share,), method="hybr", options={"xtol": 1e-12})
            ok = sol.success and np.max(np.abs(residual(sol.x, share))) < 1e-8
            return sol.x, ok, " ".join(str(sol.message).split())

        g0, d0 = guess
        xy, ok, msg = solve([g0 * math.cos(d0), g0 * math.sin(d0)], 1.0)
        share = 1.0
        if not ok:
            # continuation in the chamber pressure (load and pocket pressure together) from a light load
            xy, share, step = np.array([-0.05, 0.0]), 0.0, 0.05
            while share < 1.0 and step > 1e-4:
                trial = min(1.0, share + step)
                xt, ok_t, msg = solve(xy, trial)
                if ok_t:
                    xy, share, step = xt, trial, step * 1.5
                else:
                    step *= 0.5
            ok = share == 1.0 and ok_t
        if not ok:
            res = residual(xy, 1.0)
            raise RuntimeError(
                f"no steady state of {pump.name!r} at beta = {beta:.4f} rad: continuation in the chamber "
                f"pressure carried {100 * share:.0f} % of it; at the full load its last state, gamma = "
                f"{math.hypot(*xy):.3f}, delta = {math.atan2(xy[1], xy[0]) % (2 * math.pi):.3f} rad, leaves a "
                f"relative force residual {np.max(np.abs(res)):.3g} ({msg}). Without squeeze the film cannot "
                "carry this load (typically an off-centre pocket whose hydrostatic force has a component the "
                "wedge cannot balance short of contact); simulate(start='periodic') follows the squeeze-film "
                "motion instead")
        return float(math.hypot(*xy)), float(math.atan2(xy[1], xy[0]) % (2 * math.pi))

    def initial_state(self, settings) -> tuple[float, np.ndarray]:
        """The steady state at ``beta0`` (``"steady"``, ``"periodic"``) or the given ``(gamma, delta)``, whose
        film must stay above ``min_film``."""
        start, beta0 = settings.start, float(settings.beta0)
        if isinstance(start, str) and start in STARTS:
            return beta0, np.array(self.steady(beta0))
        y0 = np.array(start, float)
        film = self.smallest_film(beta0, y0)
        if film <= settings.min_film:
            raise ValueError(f"start (gamma, delta) must leave a film thicker than min_film = {settings.min_film:g} c "
                             f"over the surface, got {start!r} (smallest film {film:.4g} c)")
        return beta0, y0

    # -- stepping and samples ----------------------------------------------------------------------

    def stepper(self, beta0, y0, angles, settings, first_step, max_step):
        return scipy_stepper(self.rates, beta0, y0, float(angles[-1]), settings, first_step, max_step)

    def counters(self) -> dict[str, float]:
        return {"nfev": self.nfev, "factorizations": self.factorizations, "jacobians": self.jacobians,
                "seconds": self.seconds}

    def _restore(self, counters: Mapping[str, float]) -> None:
        self.nfev, self.factorizations = counters["nfev"], counters["factorizations"]
        self.jacobians, self.seconds = counters["jacobians"], counters["seconds"]

    def sample_state(self, beta: float, y: np.ndarray):
        """``(rates, result or None, superposition or None, extra columns)`` of one sample state."""
        sup = self.superposition(y[0], y[1])
        rates, res = self.balance(beta, y)
        return rates, res, sup, {}

    def sample(self, beta: float, y: np.ndarray) -> dict[str, object]:
        return {name: values[0] for name, values in self.samples(np.array([beta]), np.array([y])).items()}

    def samples(self, betas: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        """Rates, smallest film, friction and flows at the samples (SI).

        Each sample needs its own film state (a superposition: one numeric
        factorization) and its balancing rates; the flows and the friction of
        all the states solved without cavitation are then evaluated at once
        by the compiled linear maps (:func:`bearingfe.film.film_outputs`), with
        no per-sample form assembly. Cavitated and elastic states come with
        their result. Not counted in the run's counters.
        """
        counted = self.counters()
        try:
            return self._samples(betas, states)
        except FilmClosed as exc:  # the dense output between accepted steps left the admissible states
            raise RuntimeError(f"between the integrator's steps the interpolated state (gamma, delta) = "
                               f"{exc.args[0]} closes the film: the steps are too coarse; use a smaller rtol "
                               f"or max_step") from None
        finally:
            self._restore(counted)

    def _samples(self, betas: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        pump, sc = self.pump, self.pump.scale
        n = betas.size
        rates, h_min = np.empty((n, 2)), np.empty(n)
        flows: dict[str, np.ndarray] = {}
        friction, balance = np.empty(n), np.empty(n)
        extra: dict[str, np.ndarray] = {}
        linear: list[tuple[int, Superposition, np.ndarray]] = []

        def flush() -> None:  # the film outputs of the linear samples gathered, as one batch
            index = np.array([i for i, _, _ in linear])
            weights = np.column_stack([w for _, _, w in linear])
            u = np.column_stack([sup.fields @ w for _, sup, w in linear])
            batch = film_outputs([sup for _, sup, _ in linear], u, weights, weights[0])
            for k, v in batch.flows.items():
                flows.setdefault(k, np.zeros(n))[index] = v
            friction[index], balance[index] = batch.friction, batch.mass_balance
            linear.clear()

        for i, (b, y) in enumerate(zip(betas, states)):
            rates[i], res, sup, more = self.sample_state(b, y)
            h_min[i] = sup.h_min if sup is not None else res.h_min
            for k, v in more.items():
                extra.setdefault(k, np.empty(n))[i] = v
            if res is None:
                weights = source_weights(float(pump.wedge(b)), rates[i], self.pocket_pressure(b, y))
                sup.check_inlet(weights[3])
                linear.append((i, sup, weights))
                if len(linear) == SAMPLE_BLOCK:
                    flush()
                continue
            for k, v in res.flows.items():
                flows.setdefault(k, np.zeros(n))[i] = v
            friction[i], balance[i] = res.friction, res.mass_balance
        if linear:
            flush()
        zero = np.zeros(n)
        arc = sum((flows[k] for k in ("arc_start", "arc_end", "outer") if k in flows), zero)
        return {"gamma_rate": rates[:, 0], "delta_rate": rates[:, 1], "h_min": sc.to_thickness(h_min),
                "friction_moment": sc.to_moment(friction), "flow_inlet": sc.to_flow(flows.get("inlet", zero)),
                "flow_side": sc.to_flow(flows.get("side", zero)), "flow_arc": sc.to_flow(arc),
                "flow_squeeze": sc.to_flow(flows.get("squeeze", zero)), "mass_balance": sc.to_flow(balance),
                **extra}

    def statistics(self, output, runs: Sequence) -> dict[str, float]:
        """``nfev``, ``factorizations``: the integration's, start and periodic start included; ``steps``: the
        output run's."""
        return {"nfev": self.nfev, "factorizations": self.factorizations, "steps": output.steps}

    def solver_seconds(self) -> float:
        return self.seconds
