r"""The plunger shoe over the pump cycle: quasi-static equilibrium integrated in time.

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
``h^-3``): the default integrator is LSODA (adaptive, switching to BDF where
stiff; Radau and BDF are available), stepped one step at a time so
that a trial state whose film would close (``h <= 0``) stops the run cleanly
at the last accepted step instead of failing. A terminal event stops the run
when the smallest film over the surface reaches ``min_film``; the result
then carries ``status = "ruptured"`` and a message with the shaft angle.

Start: the steady state at the start angle (rates zero under the load of
that instant), a given ``(gamma, delta)``, or the periodic state: a fixed
point of the return map ``P`` over one revolution, found by Newton shooting
with the monodromy matrix ``dP/dy`` from the variational equation along the
second revolution, Broyden-updated afterwards (or by plain fixed-point
iteration: the squeeze film damps the transient by a factor of about 20 per
revolution on the shipped pump, so that takes five to six revolutions).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping

import numpy as np
import scipy.integrate as si
from scipy.optimize import root

from ..cavitation import rates_for_load as cavitating_rates, solve_cavitating
from ..elastic.coupled import Compliance, ElasticError, balance_load, solve_elastic
from ..film.thickness import CosineFilm
from ..geometry.meshing import SupportMesh, mesh_surface
from ..bearings.pump import EccentricPump
from ..core.linalg import DEFAULT_SOLVER
from ..core.limits import check_limit
from ..core.parameters import Discretization, takes
from ..reynolds import CAVITATION, Superposition, superpose
from ..film.finite_volume import solve_jfo
from ..film import film_outputs, source_weights
from .jfo import jfo_run

__all__ = [
    "Trajectory",
    "simulate",
    "steady_state",
    "balance_ratio",
    "pump_mesh",
    "state_result",
    "LiftOffError",
    "INTEGRATORS",
    "IMPLICIT_INTEGRATORS",
    "STARTS",
]

#: Named starting states of :func:`simulate` (besides a given ``(gamma, delta)``).
STARTS = ("periodic", "steady")

#: Stepping integrators by name: scipy's implicit and switching methods, and the explicit
#: Runge-Kutta pairs for films that are not stiff (on the shipped pump RK23 reaches a given error
#: of the smallest film with fewer film solves than LSODA: docs/benchmarks_pump.md).
INTEGRATORS: Mapping[str, type] = MappingProxyType({"Radau": si.Radau, "BDF": si.BDF, "LSODA": si.LSODA,
                                                   "RK23": si.RK23, "RK45": si.RK45})
#: The implicit (or stiffness-switching) ones of :data:`INTEGRATORS`, for stiff systems.
IMPLICIT_INTEGRATORS = ("Radau", "BDF", "LSODA")


class LiftOffError(ValueError):
    """The pocket's hydrostatic lift exceeds the plunger force: no equilibrium with a closed film."""


class _FilmClosed(Exception):
    """A trial state of the integrator has h <= 0 somewhere on the surface."""


class _NoElasticBalance(Exception):
    """The coupled elastic film found no deflection carrying the load at a trial state (message: where, why)."""


# -- mesh and hydrostatic balance -------------------------------------------------------

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


# -- the right side -------------------------------------------------------------------------

@dataclass
class _Model:
    """Film states and rates of one run (not public: caches superpositions)."""

    pump: EccentricPump
    mesh: SupportMesh
    formulation: str
    element: str
    solver: str
    cavitation: str
    elastic: object = None  # bearingfe.elastic.coupled.Compliance on `mesh`, or None (rigid)
    nfev: int = 0
    factorizations: int = 0
    seconds: float = 0.0
    jacobians: int = 0
    _cache: dict = field(default_factory=dict)
    _warm: object = None
    _w: object = None  # last film opening of the elastic support [c]
    _reuse: dict = field(default_factory=dict)
    _phi_range: tuple[float, float] | None = None

    @property
    def phi_range(self) -> tuple[float, float]:
        if self._phi_range is None:  # asked at every step: computed once
            b = self.mesh.mesh.p[0]
            self._phi_range = (float(b.min()), float(b.max()))
        return self._phi_range

    def h_min(self, gamma: float, delta: float) -> float:
        if self.elastic is not None and self._w is not None:  # rigid film opened by the last deflection
            d = self.elastic.basis_doflocs
            return float(np.min(CosineFilm(max(gamma, 0.0), delta).thickness(d[0], d[1]) + self._w))
        return CosineFilm(max(gamma, 0.0), delta).minimum(self.phi_range)

    def superposition(self, gamma: float, delta: float) -> Superposition:
        key = (float(gamma), float(delta))
        sup = self._cache.get(key)
        if sup is None:
            if not (math.isfinite(gamma) and math.isfinite(delta)) or gamma < 0 or self.h_min(gamma, delta) <= 0:
                raise _FilmClosed(key)
            start = time.perf_counter()
            sup = superpose(self.mesh, CosineFilm(gamma, delta), formulation=self.formulation,
                            element=self.element, solver=self.solver)
            self.seconds += time.perf_counter() - start
            self.factorizations += 1
            if len(self._cache) > 8:
                self._cache.clear()
            self._cache[key] = sup
        return sup

    def rates(self, beta: float, y: np.ndarray) -> np.ndarray:
        return self.balance(beta, y, full=False)[0]

    def balance(self, beta: float, y: np.ndarray, full: bool = True):
        """Rates that balance the plunger load and, under cavitation, the cavitated solution."""
        self.nfev += 1
        if self.elastic is not None:
            return self._elastic_balance(beta, y, full)
        sup = self.superposition(y[0], y[1])
        pump = self.pump
        args = (pump.load_vector(beta), float(pump.wedge(beta)), float(pump.inlet_pressure(beta)))
        try:
            if self.cavitation == "none":
                return sup.rates_for_load(*args), None
            # Swift-Stieber or Gumbel: a small Newton on the two rates, warm-started
            # from the rupture set of the previous evaluation (bearingfe.cavitation.models)
            found = cavitating_rates(sup, *args, model=self.cavitation, warm_start=self._warm,
                                     solver=self.solver)
            self._warm = found.result
            return found.rates, found.result
        except np.linalg.LinAlgError as exc:
            raise RuntimeError(f"equilibrium rates undefined at beta = {beta:.4f} rad, gamma = {y[0]:.4g}: "
                               f"{exc}") from None


    def _elastic_balance(self, beta: float, y: np.ndarray, full: bool):
        """Rates and film opening on the elastic support (Newton on the deflection, warm-started)."""
        gamma, delta = float(y[0]), float(y[1])
        if not (math.isfinite(gamma) and math.isfinite(delta)) or gamma < 0 or self.h_min(gamma, delta) <= 0:
            raise _FilmClosed((gamma, delta))
        pump = self.pump
        start = time.perf_counter()
        try:
            found = balance_load(self.mesh, CosineFilm(gamma, delta), self.elastic, pump.load_vector(beta),
                                 wedge=float(pump.wedge(beta)), inlet_pressure=float(pump.inlet_pressure(beta)),
                                 element=self.element, cavitation=self.cavitation, solver=self.solver,
                                 initial=self._w, reuse=self._reuse, full_result=full)
        except ElasticError as exc:
            if "h_min" in str(exc):
                raise _FilmClosed((gamma, delta)) from None
            raise _NoElasticBalance(f"no equilibrium of the elastic film at beta = {beta:.4f} rad "
                                    f"({math.degrees(beta) % 360:.1f} deg), gamma = {gamma:.4g}: {exc}") from None
        self.seconds += time.perf_counter() - start
        self.factorizations += found.iterations
        self.jacobians += found.jacobians
        self._w = found.deflection
        return found.rates, found.result


def _check_cavitation(cavitation: str) -> None:
    if cavitation not in CAVITATION:
        raise ValueError(f"cavitation must be one of {CAVITATION}, got {cavitation!r}")


# -- steady state ------------------------------------------------------------------------------

@takes(Discretization)
def steady_state(pump: EccentricPump, mesh: SupportMesh | None = None, beta: float = 0.0, *,
                 formulation: str = "pi", element: str = "P1", solver: str = DEFAULT_SOLVER,
                 guess: tuple[float, float] = (0.5, math.pi - 0.5), _model: _Model | None = None
                 ) -> tuple[float, float]:
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
    model = _model or _Model(pump, pump_mesh(pump) if mesh is None else mesh, formulation, element, solver, "none")
    load = pump.load_vector(beta)
    wedge, ps = float(pump.wedge(beta)), float(pump.inlet_pressure(beta))
    scale = max(abs(load[0]), 1e-12)

    def residual(xy, share):
        g, d = math.hypot(*xy), math.atan2(xy[1], xy[0])
        try:
            sup = model.superposition(g, d)
        except _FilmClosed:
            return np.array([1e3, 1e3]) * (1.0 + g)
        return (sup.force(wedge, (0.0, 0.0), share * ps) + share * load) / (share * scale)

    def solve(xy, share):
        sol = root(residual, xy, args=(share,), method="hybr", options={"xtol": 1e-12})
        ok = sol.success and np.max(np.abs(residual(sol.x, share))) < 1e-8
        return sol.x, ok, " ".join(str(sol.message).split())

    g0, d0 = guess
    xy, ok, msg = solve([g0 * math.cos(d0), g0 * math.sin(d0)], 1.0)
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
    else:
        share = 1.0
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
    sol = type("S", (), {"x": xy})
    return float(math.hypot(*sol.x)), float(math.atan2(sol.x[1], sol.x[0]) % (2 * math.pi))


# -- the result ------------------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class Trajectory:
    """The plunger shoe over the pump cycle (arrays sampled at ``beta``).

    Attributes
    ----------
    t : ndarray
        Time from the start [s].
    beta : ndarray
        Shaft angle [rad].
    gamma, delta : ndarray
        Relative eccentricity [-] and attitude in the shoe frame [rad].
    gamma_rate, delta_rate : ndarray
        ``d gamma/d beta`` [-], ``d delta/d beta`` [-] (per radian of shaft turn).
    wedge : ndarray
        ``1 - dphi2/dbeta`` [-].
    inlet_pressure : ndarray
        Pocket (chamber) pressure, non-dimensional [-].
    chamber_pressure : ndarray
        The same in Pa.
    load : ndarray, shape (n, 2)
        Applied load on the shoe in the shoe frame (as the solver's ``force``) [-].
    h_min : ndarray
        Smallest film over the whole surface [m].
    friction_moment : ndarray
        Film shear moment on the eccentric about ``O2`` [N m].
    flow_inlet, flow_side, flow_arc, flow_squeeze : ndarray
        Flow out of the pockets, out through the sides ``z = +-a``, out
        through the arc edges (or the whole outline when it is not a
        rectangle), and the squeeze rate of the film volume [m^3/s].
    mass_balance : ndarray
        ``inlet - side - arc - squeeze`` [m^3/s].
    status : str
        ``"completed"``, ``"ruptured"`` (the film reached ``min_film`` or
        closed), or ``"no-equilibrium"`` (on an elastic support, the coupled
        film found no deflection that carries the load: the support is too
        soft for it there, or the quasi-static model has no solution; the
        message says where and why). A run that did not complete ends at its
        last accepted state.
    message : str
    rupture_beta : float
        Shaft angle where a run that did not complete stopped (the film
        reached ``min_film`` or closed, or no elastic equilibrium); NaN if it
        completed.
    start : tuple of float
        Initial ``(gamma, delta)``.
    periodic_iterations : int
        Revolutions integrated to find the periodic start, not counting the
        output revolution (0 unless started periodic).
    periodic_residual : float
        ``max |y(2 pi) - y(0)|`` (attitude wrapped) of the revolution that
        ended the search: with ``"newton"`` the output revolution itself,
        with ``"fixed-point"`` the last iteration (NaN unless periodic).
    element : str
        Finite element of the run (``state_result`` re-solves with it).
    stats : mapping
        ``nfev``, ``factorizations``, ``steps``, ``seconds`` (wall time of
        the integration), ``solver_seconds``, ``dofs``; on an elastic
        support also ``jacobians`` (of the coupled Newton).
    max_deflection : ndarray or None
        Largest film opening by the elastic support [m] (None: rigid).
    pressures : ndarray or None
        Nodal pressure [-] at each sample, shape (n, n_dofs), where the
        pressure is a state of the run
        (:func:`bearingfe.transient.elastic.simulate_elastic`); else None.
    """

    t: np.ndarray
    beta: np.ndarray
    gamma: np.ndarray
    delta: np.ndarray
    gamma_rate: np.ndarray
    delta_rate: np.ndarray
    wedge: np.ndarray
    inlet_pressure: np.ndarray
    chamber_pressure: np.ndarray
    load: np.ndarray
    h_min: np.ndarray
    friction_moment: np.ndarray
    flow_inlet: np.ndarray
    flow_side: np.ndarray
    flow_arc: np.ndarray
    flow_squeeze: np.ndarray
    mass_balance: np.ndarray
    status: str
    message: str
    rupture_beta: float
    start: tuple[float, float]
    periodic_iterations: int
    periodic_residual: float
    stats: Mapping[str, float]
    element: str = "P1"
    max_deflection: np.ndarray | None = None
    pressures: np.ndarray | None = None

    @property
    def smallest_film(self) -> float:
        """Smallest film thickness over the run [m]."""
        return float(np.min(self.h_min))

    @property
    def mass_balance_relative(self) -> float:
        """``max |mass_balance| / max(|flow_inlet| + |flow_side| + |flow_arc|)`` [-]."""
        scale = np.max(np.abs(self.flow_inlet) + np.abs(self.flow_side) + np.abs(self.flow_arc))
        return float(np.max(np.abs(self.mass_balance)) / scale) if scale > 0 else 0.0

    def columns(self) -> dict[str, np.ndarray]:
        """The sampled arrays by name (for a CSV or a DataFrame)."""
        names = ("t", "beta", "gamma", "delta", "gamma_rate", "delta_rate", "wedge", "inlet_pressure",
                 "chamber_pressure", "h_min", "friction_moment", "flow_inlet", "flow_side", "flow_arc",
                 "flow_squeeze", "mass_balance")
        cols = {n: np.asarray(getattr(self, n)) for n in names}
        cols["load_x"], cols["load_y"] = self.load[:, 0], self.load[:, 1]
        if self.max_deflection is not None:
            cols["max_deflection"] = np.asarray(self.max_deflection)
        return cols


# -- integration -------------------------------------------------------------------------------------

@dataclass
class _Run:
    segments: list  # (t0, t1, dense)
    end: float
    y_end: np.ndarray
    status: str
    message: str
    rupture_beta: float
    steps: int


def _integrate(model: _Model, beta0: float, y0, beta1: float, *, method: str, rtol: float, atol: float,
               max_step: float, bound: float) -> _Run:
    solver = INTEGRATORS[method](model.rates, beta0, np.asarray(y0, float), beta1, rtol=rtol, atol=atol,
                                 max_step=max_step)
    segments, steps = [], 0
    status, message, rupture = "completed", "", math.nan
    event = lambda y: model.h_min(y[0], y[1]) - bound  # noqa: E731
    while solver.status == "running":
        t_old = solver.t
        try:
            msg = solver.step()
        except _FilmClosed:
            status, rupture = "ruptured", float(t_old)
            message = (f"film closed (h <= 0) in a trial step after beta = {t_old:.4f} rad "
                       f"({math.degrees(t_old) % 360:.1f} deg); stopped at the last accepted state")
            break
        except _NoElasticBalance as exc:
            status, rupture = "no-equilibrium", float(t_old)
            message = f"{exc}; stopped at the last accepted state (beta = {t_old:.4f} rad)"
            break
        if solver.status == "failed":
            raise RuntimeError(f"integrator {method} failed at beta = {solver.t:.4f} rad: {msg}")
        steps += 1
        dense = solver.dense_output()
        if event(solver.y) <= 0.0:
            lo, hi = t_old, solver.t
            for _ in range(60):  # bisection on the dense output: robust, no sign assumptions inside
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if event(dense(mid)) > 0 else (lo, mid)
            segments.append((t_old, hi, dense))
            status, rupture = "ruptured", float(hi)
            message = (f"film ruptured: smallest film reached {bound:.4g} c at beta = {hi:.4f} rad "
                       f"({math.degrees(hi) % 360:.1f} deg)")
            return _Run(segments, hi, dense(hi), status, message, rupture, steps)
        segments.append((t_old, solver.t, dense))
    if status == "completed":
        message = f"completed {(solver.t - beta0) / (2 * math.pi):.4g} revolutions"
    end = solver.t if status == "completed" else (segments[-1][1] if segments else beta0)
    y_end = solver.y if status == "completed" else (segments[-1][2](end) if segments else np.asarray(y0, float))
    return _Run(segments, float(end), np.asarray(y_end, float), status, message, rupture, steps)


#: Ways to find the periodic start: Newton shooting on the return map, or plain fixed-point iteration.
PERIODIC_METHODS = ("newton", "fixed-point")


def _wrapped(d: np.ndarray) -> np.ndarray:
    """State difference with the attitude difference wrapped into ``[-pi, pi)``."""
    d = np.array(d, float)
    d[1] = (d[1] + math.pi) % (2 * math.pi) - math.pi
    return d


def _rate_jacobian(model: _Model, beta: float, y: np.ndarray, step: float = 1e-7) -> np.ndarray:
    """``d rates / d (gamma, delta)`` at one state by forward differences (two extra film solves)."""
    f0 = model.rates(beta, y)
    cols = []
    for j in range(2):
        h = step * max(1.0, abs(float(y[j])))
        e = np.zeros(2)
        e[j] = h
        cols.append((model.rates(beta, y + e) - f0) / h)
    return np.column_stack(cols)


def _expm2(a: np.ndarray) -> np.ndarray:
    """``exp(a)`` of a real 2x2 matrix in closed form (scipy's ``expm`` costs milliseconds per call).

    With ``a = t/2 I + b``, ``b^2 = s^2 I`` (``s^2 = t^2/4 - det a``), so
    ``exp(a) = e^(t/2) (cosh(s) I + sinh(s)/s b)``; ``s`` is imaginary for
    complex eigenvalues, where the same formula gives ``cos`` and ``sin``.
    """
    half = 0.5 * (a[0, 0] + a[1, 1])
    b = a - half * np.eye(2)
    s2 = b[0, 0] ** 2 + b[0, 1] * b[1, 0]
    if s2 > 1e-8:  # real eigenvalues half +- s: combine the exponentials (no cosh overflow)
        s = math.sqrt(s2)
        up, down = math.exp(half + s), math.exp(half - s)
        c, sh = 0.5 * (up + down), 0.5 * (up - down) / s
    elif s2 < -1e-8:
        s = math.sqrt(-s2)
        e = math.exp(half)
        c, sh = e * math.cos(s), e * math.sin(s) / s
    else:
        e = math.exp(half)
        c, sh = e * (1.0 + 0.5 * s2), e * (1.0 + s2 / 6.0)
    return c * np.eye(2) + sh * b


def _monodromy(model: _Model, run: _Run, stride: int = 2) -> np.ndarray:
    """Jacobian ``d y(end) / d y(start)`` of the revolution ``run`` (the return map's derivative).

    The variational equation ``Phi' = J(beta) Phi`` along the computed
    trajectory, with ``J = d rates/d y`` by forward differences at every
    ``stride``-th accepted step of the integrator (and the last) and the
    second-order Magnus step ``Phi <- exp(dbeta (J_i + J_j)/2) Phi`` between
    them: three film solves per point, no extra integration. On the shipped
    pump ``stride = 2`` costs about two thirds of a revolution and gives the
    same periodic state as every step to 4e-8.
    """
    betas = [run.segments[0][0]] + [seg[1] for seg in run.segments]
    states = [run.segments[0][2](betas[0])] + [seg[2](seg[1]) for seg in run.segments]
    points = list(range(0, len(betas), stride))
    if points[-1] != len(betas) - 1:
        points.append(len(betas) - 1)
    jac = {i: _rate_jacobian(model, betas[i], np.asarray(states[i], float)) for i in points}
    phi = np.eye(2)
    for i, j in zip(points[:-1], points[1:]):
        phi = _expm2((betas[j] - betas[i]) * 0.5 * (jac[i] + jac[j])) @ phi
    return phi


def _periodic_start(model: _Model, y0: np.ndarray, beta0: float, opts: dict, method: str, tol: float,
                    max_iter: int) -> tuple[np.ndarray, int, float, _Run | None]:
    """Periodic state ``y = P(y)`` of the return map ``P`` over one revolution from ``beta0``.

    ``"newton"``: the first revolution is a fixed-point step (from the steady
    start the return map is far from linear), integrated at ``rtol = 1e-3``
    at most as it moves the state by far more than that; the second also gives the
    monodromy matrix ``M = dP/dy`` (:func:`_monodromy`) and each later one a
    Broyden update of it; the next start is the Newton step
    ``y + (I - M)^-1 (P(y) - y)``. A revolution whose end matches its start
    within ``tol`` ends the search and is itself the output revolution: the
    count excludes it, as it excludes the output revolution of the
    fixed-point iteration.

    ``"fixed-point"``: ``y <- P(y)`` until ``|P(y) - y| < tol``; the start
    is then ``P(y)`` and the output revolution is integrated afresh.

    Returns
    -------
    start, iterations, residual, run
        ``run`` is the verified revolution from ``start`` (``None`` if the
        output revolution still has to be integrated).
    """
    y = np.asarray(y0, float)
    jacobian, previous = None, None
    iterations, residual = 0, math.nan
    while True:
        loose = method == "newton" and iterations == 0
        step_opts = dict(opts, rtol=max(opts["rtol"], 1e-3), atol=max(opts["atol"], 1e-6)) if loose else opts
        run = _integrate(model, beta0, y, beta0 + 2 * math.pi, **step_opts)
        if run.status != "completed":
            return y, iterations + 1, residual, None
        r = _wrapped(run.y_end - y)
        residual = float(np.max(np.abs(r)))
        if method == "fixed-point":
            iterations += 1
            y = y + r
            if residual < tol:
                return y, iterations, residual, None
        else:
            if residual < tol and not loose:
                return y, iterations, residual, run
            iterations += 1
            if iterations == 2:
                jacobian = _monodromy(model, run)
            elif jacobian is not None:
                dy, dp = y - previous[0], (y + r) - (previous[0] + previous[1])
                jacobian = jacobian + np.outer(dp - jacobian @ dy, dy) / float(dy @ dy)
            previous = (y, r)
            step = r if jacobian is None else np.linalg.solve(np.eye(2) - jacobian, r)
            trial = y + step
            # a Newton step that leaves the admissible states falls back to the fixed-point step
            ok = np.all(np.isfinite(trial)) and trial[0] >= 0 and model.h_min(*trial) > opts["bound"]
            y = trial if ok else y + r
        if iterations >= max_iter:
            raise RuntimeError(f"periodic start ({method}) did not converge in {iterations} revolutions "
                               f"(last residual {residual:.3g} >= periodic_tol = {tol})")


def _sample(run: _Run, betas: np.ndarray, y0) -> tuple[np.ndarray, np.ndarray]:
    betas = betas[betas <= run.end + 1e-12]
    if run.status != "completed" and (betas.size == 0 or betas[-1] < run.end):
        betas = np.append(betas, run.end)
    ys = np.empty((betas.size, 2))
    k = 0
    for i, b in enumerate(betas):
        if not run.segments:
            ys[i] = y0
            continue
        while k < len(run.segments) - 1 and b > run.segments[k][1]:
            k += 1
        ys[i] = run.segments[k][2](min(max(b, run.segments[k][0]), run.segments[k][1]))
    return betas, ys


def _postprocess(model: _Model, betas: np.ndarray, ys: np.ndarray) -> dict[str, np.ndarray]:
    """Rates, smallest film, friction and flows at the samples.

    Each sample needs its own film state (a superposition: one numeric
    factorization) and its balancing rates; the flows and the friction of all
    the states solved without cavitation are then evaluated at once by the
    compiled linear maps (:func:`bearingfe.film.result.film_outputs`), with
    no per-sample form assembly. Cavitated states come with their result.
    """
    pump, sc = model.pump, model.pump.scale
    n = betas.size
    rates, h_min = np.empty((n, 2)), np.empty(n)
    flows: dict[str, np.ndarray] = {}
    friction, balance = np.empty(n), np.empty(n)
    linear: list[tuple[int, Superposition, np.ndarray]] = []
    deflection = np.empty(n) if model.elastic is not None else None
    for i, (b, y) in enumerate(zip(betas, ys)):
        sup = model.superposition(y[0], y[1]) if model.elastic is None else None
        rates[i], res = model.balance(b, y)
        h_min[i] = sup.h_min if sup is not None else res.h_min  # the elastic result: the deflected film
        if deflection is not None:
            deflection[i] = sc.to_thickness(float(np.max(model._w)))
        if res is None:
            weights = source_weights(float(pump.wedge(b)), rates[i], float(pump.inlet_pressure(b)))
            sup.check_inlet(weights[3])
            linear.append((i, sup, weights))
            continue
        for k, v in res.flows.items():
            flows.setdefault(k, np.zeros(n))[i] = v
        friction[i], balance[i] = res.friction, res.mass_balance
    if linear:
        index = np.array([i for i, _, _ in linear])
        weights = np.column_stack([w for _, _, w in linear])
        u = np.column_stack([sup.fields @ w for _, sup, w in linear])
        batch = film_outputs([sup for _, sup, _ in linear], u, weights, weights[0])
        for k, v in batch.flows.items():
            flows.setdefault(k, np.zeros(n))[index] = v
        friction[index], balance[index] = batch.friction, batch.mass_balance
    zero = np.zeros(n)
    arc = sum((flows[k] for k in ("arc_start", "arc_end", "outer") if k in flows), zero)
    return {"gamma_rate": rates[:, 0], "delta_rate": rates[:, 1], "h_min": sc.to_thickness(h_min),
            "friction_moment": sc.to_moment(friction), "flow_inlet": sc.to_flow(flows.get("inlet", zero)),
            "flow_side": sc.to_flow(flows.get("side", zero)), "flow_arc": sc.to_flow(arc),
            "flow_squeeze": sc.to_flow(flows.get("squeeze", zero)), "mass_balance": sc.to_flow(balance),
            **({} if deflection is None else {"max_deflection": deflection})}


@takes(Discretization)
def simulate(pump: EccentricPump, mesh: SupportMesh | None = None, revolutions: float = 1.0, *,
             start: str | tuple[float, float] = "steady", beta0: float = 0.0, cavitation: str = "none",
             method: str = "LSODA", rtol: float = 1e-5, atol: float | None = None, max_step: float = math.pi / 8,
             min_film: float | None = None, points_per_revolution: int = 180, mesh_size: float | None = None,
             formulation: str = "pi", element: str | None = None, solver: str = DEFAULT_SOLVER,
             periodic_tol: float = 1e-6, periodic_max_iter: int = 30,
             periodic_method: str = "newton", max_revolutions: float | None = None,
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
        (mass-conserving) carries the fill fraction over the cycle: fixed
        backward-Euler steps, ``points_per_revolution`` of them per turn
        (:mod:`bearingfe.transient.jfo`; ``method``, ``rtol``, ``atol`` and
        ``max_step`` do not apply; P1 only). ``start="periodic"`` then runs
        one revolution first and starts from its end (film history included).
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
        largest number of revolutions.
    periodic_method : {"newton", "fixed-point"}
        ``"newton"`` (default): Newton shooting on the return map with the
        monodromy matrix of the second revolution, Broyden-updated; three
        revolutions on the shipped pump, plus the output revolution, which
        verifies the residual. ``"fixed-point"``: iterate the return map
        (five to six revolutions there, plus the output revolution).
    max_revolutions : float, optional
        Largest ``revolutions`` accepted (a guard against runaway work);
        default the ``revolutions`` limit of :mod:`bearingfe.core.limits` (100).
    elastic : Compliance, optional
        Compliance of the support on ``mesh`` (:func:`bearingfe.elastic.coupled.half_space`):
        at every shaft angle the film ``h_rigid + w`` and the rates are found
        together (:func:`bearingfe.elastic.coupled.balance_load`, the direct form):
        without cavitation by a chord Newton from the last answer whose dense
        Jacobian is kept over the right sides (:class:`bearingfe.elastic.coupled.ChordBalance`;
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
    if not (isinstance(revolutions, (int, float)) and math.isfinite(revolutions) and revolutions > 0):
        raise ValueError(f"revolutions must be a finite number > 0, got {revolutions!r}")
    check_limit("revolutions", revolutions, max_revolutions, "max_revolutions")
    if method not in INTEGRATORS:
        raise ValueError(f"method must be one of {list(INTEGRATORS)}, got {method!r}")
    for name, v in (("rtol", rtol), ("atol", 1.0 if atol is None else atol), ("max_step", max_step)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {v!r}")
    if not rtol < 1:
        raise ValueError(f"rtol must be in (0, 1) (a relative tolerance of 1 or more allows 100 % error), got {rtol!r}")
    atol = 1e-3 * rtol if atol is None else atol
    if int(points_per_revolution) < 8:
        raise ValueError(f"points_per_revolution must be >= 8, got {points_per_revolution!r}")
    min_film = 0.02 * pump.clearance if min_film is None else float(min_film)
    if not 0 < min_film < pump.clearance:
        raise ValueError(f"min_film must be in (0, clearance = {pump.clearance} m), got {min_film!r}")
    _check_cavitation(cavitation)
    if periodic_method not in PERIODIC_METHODS:
        raise ValueError(f"periodic_method must be one of {PERIODIC_METHODS}, got {periodic_method!r}")
    if not (isinstance(periodic_tol, (int, float)) and math.isfinite(periodic_tol) and periodic_tol > 0):
        raise ValueError(f"periodic_tol must be a finite number > 0, got {periodic_tol!r}")
    if not (isinstance(periodic_max_iter, int) and periodic_max_iter >= 1):
        raise ValueError(f"periodic_max_iter must be an integer >= 1, got {periodic_max_iter!r}")
    if element is None:
        if elastic is not None and isinstance(elastic, Compliance):
            element = elastic.element
        else:
            element = "P2" if mesh is None or getattr(mesh, "geometry_order", 1) == 2 else "P1"
    if elastic is not None:
        if not isinstance(elastic, Compliance):
            raise ValueError(f"elastic must be a bearingfe.elastic.coupled.Compliance, got {type(elastic).__name__}")
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
    ratio = balance_ratio(pump, mesh, formulation=formulation, element=element)
    if ratio >= 1.0:
        raise LiftOffError(f"{pump.name!r}: the pockets' hydrostatic lift is {ratio:.3f} x the plunger force "
                           f"(balance ratio >= 1): the shoe lifts off, there is no equilibrium with a closed "
                           f"film; make the pockets smaller or the plunger larger")
    if cavitation == "jfo":
        return _simulate_jfo(pump, mesh, revolutions, start, beta0, int(points_per_revolution),
                             min_film / pump.clearance, ratio, formulation, element, solver)
    model = _Model(pump, mesh, formulation, element, solver, cavitation)
    bound = min_film / pump.clearance
    opts = dict(method=method, rtol=rtol, atol=atol, max_step=max_step, bound=bound)
    t_start = time.perf_counter()
    iterations, residual = 0, math.nan
    y0 = _initial_state(pump, model, start, beta0, bound)
    found = None
    model.elastic = elastic  # set after the steady start, which is the rigid one
    if start == "periodic":
        y0, iterations, residual, found = _periodic_start(model, y0, beta0, opts, periodic_method, periodic_tol,
                                                          periodic_max_iter)
    beta1 = beta0 + 2 * math.pi * revolutions
    if found is not None and revolutions == 1:
        run = found  # the revolution that verified the periodic state is the output revolution
    else:
        run = _integrate(model, beta0, y0, beta1, **opts)
    n = max(int(round(points_per_revolution * revolutions)), 2) + 1
    betas, ys = _sample(run, np.linspace(beta0, beta1, n), y0)
    seconds = time.perf_counter() - t_start
    counts = {"nfev": model.nfev, "factorizations": model.factorizations, "steps": run.steps,
              "seconds": seconds, "solver_seconds": model.seconds}
    if elastic is not None:
        counts["jacobians"] = model.jacobians
    try:
        post = _postprocess(model, betas, ys)
    except _FilmClosed as exc:  # the dense output between accepted steps left the admissible states
        raise RuntimeError(f"between the integrator's steps the interpolated state (gamma, delta) = {exc.args[0]} "
                           f"closes the film: the steps are too coarse for rtol = {rtol:g}; use a smaller rtol "
                           f"or max_step") from None
    f = pump.load(betas)
    return Trajectory(
        t=(betas - beta0) / pump.drive.omega, beta=betas, gamma=ys[:, 0], delta=ys[:, 1],
        wedge=pump.wedge(betas), inlet_pressure=pump.inlet_pressure(betas),
        chamber_pressure=pump.chamber_pressure(betas), load=np.column_stack([-f, np.zeros_like(f)]),
        status=run.status, message=run.message, rupture_beta=run.rupture_beta, start=(float(y0[0]), float(y0[1])),
        periodic_iterations=iterations, periodic_residual=residual, element=element,
        stats=MappingProxyType(dict(counts, dofs=float(mesh.n_nodes), balance_ratio=ratio,
                                    postprocess_seconds=time.perf_counter() - t_start - seconds)),
        **post)


def state_result(pump: EccentricPump, mesh: SupportMesh, traj: Trajectory, k: int, cavitation: str = "none",
                 element: str | None = None, elastic: Compliance | None = None):
    """Re-solve the film of sample ``k`` of a trajectory (shoe frame): pressure field, flows, friction.

    The same film state, rates and pocket pressure that the run balanced, so
    the film force equals ``-traj.load[k]``; use it for pictures, fields and
    peak pressures (``Trajectory`` keeps only the reduced arrays). ``element``
    defaults to the run's (``traj.element``).
    """
    film = CosineFilm(float(traj.gamma[k]), float(traj.delta[k]))
    element = traj.element if element is None else element
    p_s = float(traj.inlet_pressure[k]) if mesh.has_inlet else 0.0
    rates = (float(traj.gamma_rate[k]), float(traj.delta_rate[k]))
    if elastic is not None:  # the coupled film at the run's rates: result.film is the deflected film
        return solve_elastic(mesh, film, elastic, wedge=float(traj.wedge[k]), squeeze=rates, inlet_pressure=p_s,
                             element=element, cavitation=cavitation).result
    if cavitation == "jfo":  # the steady JFO film of that state (the run's history is not re-played)
        return solve_jfo(mesh, film, wedge=float(traj.wedge[k]), squeeze=rates, inlet_pressure=p_s, element=element)
    sup = superpose(mesh, film, element=element)
    if cavitation == "none":
        return sup.combine(float(traj.wedge[k]), rates, p_s)
    return solve_cavitating(sup, float(traj.wedge[k]), rates, p_s, model=cavitation)



def _initial_state(pump: EccentricPump, model: "_Model", start, beta0: float, bound: float) -> np.ndarray:
    """``(gamma, delta)`` to start from: the steady state at ``beta0`` for ``"steady"`` and
    ``"periodic"``, else the user's pair, checked (finite, ``gamma > 0``, film above ``bound`` [c])."""
    if isinstance(start, str) and start in STARTS:
        return np.array(steady_state(pump, beta=beta0, _model=model))
    if isinstance(start, str):
        raise ValueError(f"start must be 'steady', 'periodic' or (gamma, delta), got {start!r}")
    try:
        y0 = np.array([float(v) for v in start])
    except (TypeError, ValueError):
        raise ValueError(f"start must be 'steady', 'periodic' or (gamma, delta), got {start!r}") from None
    if y0.shape != (2,) or not np.all(np.isfinite(y0)):
        raise ValueError(f"start (gamma, delta) must be two finite numbers, got {start!r}")
    if y0[0] <= 0:
        raise ValueError(f"start gamma must be > 0 (at gamma = 0 the shoe is concentric, the attitude angle "
                         f"delta is undefined and the squeeze rates are singular), got {start!r}")
    if model.h_min(*y0) <= bound:
        raise ValueError(f"start (gamma, delta) must leave a film thicker than min_film = {bound:g} c over the "
                         f"surface, got {start!r} (smallest film {model.h_min(*y0):.4g} c)")
    return y0

def _simulate_jfo(pump: EccentricPump, mesh: SupportMesh, revolutions: float, start, beta0: float, per_rev: int,
                  bound: float, ratio: float, formulation: str, element: str, solver: str) -> Trajectory:
    """``simulate(..., cavitation="jfo")``: backward-Euler steps carrying theta (bearingfe.transient.jfo)."""
    if element != "P1":
        raise ValueError(f"cavitation='jfo' supports element='P1' only, got {element!r}")
    t_start = time.perf_counter()
    model = _Model(pump, mesh, formulation, element, solver, "none")
    y0 = _initial_state(pump, model, start, beta0, bound)
    rates0 = model.rates(beta0, y0)
    initial, iterations, residual = None, 0, math.nan
    if start == "periodic":  # one revolution to build the film history, then start from its end
        first = jfo_run(pump, mesh, y0, rates0, beta0, beta0 + 2 * math.pi, per_rev, bound=bound)
        iterations = 1
        if first.status == "completed":
            d = first.y[-1] - y0
            d[1] = (d[1] + math.pi) % (2 * math.pi) - math.pi
            residual = float(np.max(np.abs(d)))
            y0, rates0, initial = first.y[-1], first.rates[-1], first.results[-1]
    steps = max(int(round(per_rev * revolutions)), 1)
    run = jfo_run(pump, mesh, y0, rates0, beta0, beta0 + 2 * math.pi * revolutions, steps, bound=bound,
                  initial=initial)
    seconds = time.perf_counter() - t_start
    betas, sc = run.beta, pump.scale
    res = run.results
    flows = [r.flows for r in res]
    f = pump.load(betas)
    return Trajectory(
        t=(betas - beta0) / pump.drive.omega, beta=betas, gamma=run.y[:, 0], delta=run.y[:, 1],
        gamma_rate=run.rates[:, 0], delta_rate=run.rates[:, 1], wedge=pump.wedge(betas),
        inlet_pressure=pump.inlet_pressure(betas), chamber_pressure=pump.chamber_pressure(betas),
        load=np.column_stack([-f, np.zeros_like(f)]),
        h_min=np.array([sc.to_thickness(r.h_min) for r in res]),
        friction_moment=np.array([sc.to_moment(r.friction) for r in res]),
        flow_inlet=np.array([sc.to_flow(fl.get("inlet", 0.0)) for fl in flows]),
        flow_side=np.array([sc.to_flow(fl.get("side", 0.0)) for fl in flows]),
        flow_arc=np.array([sc.to_flow(sum(v for k, v in fl.items() if k in ("arc_start", "arc_end", "outer")))
                           for fl in flows]),
        flow_squeeze=np.array([sc.to_flow(fl["squeeze"]) for fl in flows]),
        mass_balance=np.array([sc.to_flow(r.mass_balance) for r in res]),
        status=run.status, message=run.message,
        rupture_beta=float(betas[-1]) if run.status != "completed" else math.nan,
        start=(float(y0[0]), float(y0[1])), periodic_iterations=iterations, periodic_residual=residual,
        stats=MappingProxyType({"nfev": float(run.solves), "factorizations": float(run.solves),
                                "steps": float(len(betas) - 1), "seconds": seconds, "solver_seconds": seconds,
                                "dofs": float(mesh.n_nodes), "balance_ratio": ratio,
                                "newton_iterations": float(run.newton_iterations),
                                "cavitated_fraction_max": max(r.cavitated_fraction for r in res)}))
