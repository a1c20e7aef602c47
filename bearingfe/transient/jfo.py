r"""The plunger shoe with mass-conserving (JFO) cavitation: the film's history is a state.

Under JFO the fill fraction ``theta`` is a state of the film: oil that left a
cavity is not there when the film closes again. The quasi-static ODE of the
rigid model (state ``(gamma, delta)``, rates from the load balance) becomes a
time-stepping scheme that carries ``theta``: backward Euler in shaft angle
(:class:`BackwardEuler`, a scipy :class:`~scipy.integrate.OdeSolver`, so that
the stepping loop of :mod:`bearingfe.transient.stepping` drives it like the
others), one step to each output sample. At each step the rates
``r = (gamma_rate, delta_rate)`` solve the load balance

    F(r) + load(beta_{n+1}) = 0,   F(r) = film force of the JFO step from
    (theta_n, film_n) to film(y_n + dbeta r) over dbeta,

by Newton's method with a forward-difference Jacobian (each evaluation one
JFO solve, warm-started from the last cavity), so that the film's mass is
conserved from step to step (``solve_jfo(..., dt=, previous=)``). A Newton
trial whose film closes is halved (line search); a step whose Newton cannot
avoid closing the film raises :class:`~bearingfe.transient.base.FilmClosed`,
and the loop retakes it shorter (the steps then grow back to the samples), as
it does a step whose Newton does not converge or meets a singular Jacobian
(:class:`~bearingfe.transient.base.TrialRejected`).

Between steps the state is the linear interpolant (the dense output of a
first-order method); the film at an angle inside a step (where the rupture
event is located) is the backward-Euler film of that state from the step's
start, with the step's rates.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np
from scipy.integrate import DenseOutput, OdeSolver

from ..bearings.pump import EccentricPump
from ..core import DEFAULT_SOLVER
from ..film import CosineFilm, ReynoldsResult, solve_jfo
from ..geometry import SupportMesh
from .base import FilmClosed, Model, TrialRejected
from .rigid import Rigid

__all__ = ["JFO", "JFOState", "BackwardEuler", "LinearDense"]


@dataclass(frozen=True, eq=False)
class JFOState:
    """An accepted JFO state: ``(gamma, delta)``, the step's rates [-] and the film (its ``theta`` is the history)."""

    y: np.ndarray
    rates: np.ndarray
    result: ReynoldsResult


class LinearDense(DenseOutput):
    """Linear interpolant of a backward-Euler step (exact at both ends)."""

    def __init__(self, t_old: float, t: float, y_old: np.ndarray, y: np.ndarray) -> None:
        super().__init__(t_old, t)
        self.y_old, self.y = np.asarray(y_old, float), np.asarray(y, float)

    def _call_impl(self, t):
        x = (np.asarray(t, float) - self.t_old) / (self.t - self.t_old)
        values = self.y_old[:, None] + np.outer(self.y - self.y_old, np.atleast_1d(x))
        values[:, np.atleast_1d(t) == self.t] = self.y[:, None]
        values[:, np.atleast_1d(t) == self.t_old] = self.y_old[:, None]
        return values[:, 0] if np.ndim(t) == 0 else values


class BackwardEuler(OdeSolver):
    """Backward-Euler steps of the JFO model to each of ``angles`` (a scipy ``OdeSolver``).

    Parameters
    ----------
    model : JFO
    beta0 : float
        An accepted angle of the model (its state there is the start).
    angles : ndarray
        The run's sample angles [rad]: each step ends on the next one.
    first_step, max_step : float, optional
        A shorter first step [rad] (a step retaken after its trial closed the
        film); the steps then double up to ``max_step`` (None: to the samples).
    """

    def __init__(self, model: JFO, beta0: float, angles: np.ndarray, first_step: float | None = None,
                 max_step: float | None = None) -> None:
        state = model.states[beta0]
        super().__init__(self._no_rates, beta0, state.y, float(angles[-1]), vectorized=False)
        self.model, self.state, self.angles = model, state, np.asarray(angles, float)
        self.max_step = max_step
        self.h = first_step if first_step is not None else max_step
        self.y_old = None

    @staticmethod
    def _no_rates(t, y):
        raise NotImplementedError("backward Euler steps the JFO model directly")

    @property
    def h_abs(self) -> float:
        """Length of the next step [rad] (as scipy's integrators name it)."""
        return self._target() - self.t

    def _target(self) -> float:
        """End of the next step: the next sample angle, or sooner while the steps are shortened."""
        beyond = self.angles[self.angles > self.t]
        sample = float(beyond[0]) if beyond.size else self.t_bound
        if self.h is None or self.t + self.h >= sample - 1e-9 * self.h:
            return sample
        return self.t + self.h

    def _step_impl(self):
        beta = self._target()
        self.state = self.model.backward_euler(self.t, self.state, beta)
        self.y_old, self.t, self.y = self.y, beta, self.state.y
        if self.h is not None:
            grown = 2.0 * self.h
            self.h = grown if self.max_step is None or grown < self.max_step else self.max_step
        return True, None

    def _dense_output_impl(self):
        return LinearDense(self.t_old, self.t, self.y_old, self.y)


class JFO(Model):
    """The rigid film with JFO cavitation, carried from accepted step to accepted step.

    Parameters
    ----------
    pump : EccentricPump
    mesh : SupportMesh
        Straight-sided P1 mesh of ``pump.surface``.
    formulation, solver
        Of the rigid film of the steady start and its rates (the first guess).
    element : {"P1"}
    cavitation_pressure : float
        ``p_c`` [-], gauge, ``<= 0``.
    tol, max_newton
        Relative force tolerance and cap of the Newton iteration per step.
    """

    name = "jfo"
    periodic_methods = ("one-revolution",)
    periodic_default = "one-revolution"

    def __init__(self, pump: EccentricPump, mesh: SupportMesh, *, formulation: str = "pi", element: str = "P1",
                 solver: str = DEFAULT_SOLVER, cavitation_pressure: float = 0.0, tol: float = 1e-9,
                 max_newton: int = 30) -> None:
        if element != "P1":
            raise ValueError(f"cavitation='jfo' supports element='P1' only, got {element!r}")
        self.pump, self.mesh, self.element = pump, mesh, element
        self.rigid = Rigid(pump, mesh, formulation=formulation, element=element, solver=solver)
        self.dofs = float(mesh.n_nodes)
        self.cavitation_pressure, self.tol, self.max_newton = float(cavitation_pressure), tol, max_newton
        self.states: dict[float, JFOState] = {}
        self.carry: JFOState | None = None  # the end of the last completed run
        self.solves = self.newton_iterations = 0
        self.cavitated_fraction_max = 0.0

    def initial_state(self, settings) -> tuple[float, np.ndarray]:
        return self.rigid.initial_state(settings)

    def smallest_film(self, beta: float, y: np.ndarray) -> float:
        return self.rigid.smallest_film(beta, y)

    def pocket_pressure(self, beta: float, y: np.ndarray) -> float:
        """The pocket's pressure [-] at a state: the chamber's (0 without a pocket; a fed model carries its own)."""
        return float(self.pump.inlet_pressure(beta)) if self.mesh.has_inlet else 0.0

    def begin(self, beta0: float, y0: np.ndarray) -> None:
        """The film at the start: the end of the last completed run if it starts there (its history),
        else the steady JFO film with the rigid rates as squeeze."""
        if self.carry is not None and np.array_equal(self.carry.y, y0):
            state = self.carry
        else:
            rates = np.asarray(self.rigid.rates(beta0, y0), float)
            result = solve_jfo(self.mesh, CosineFilm(*y0[:2]), wedge=float(self.pump.wedge(beta0)),
                               squeeze=tuple(rates[:2]), inlet_pressure=self.pocket_pressure(beta0, y0),
                               cavitation_pressure=self.cavitation_pressure)
            state = JFOState(np.array(y0, float), np.asarray(rates, float), result)
        self.states = {float(beta0): state}
        self.solves = self.newton_iterations = 0

    def end(self, run) -> None:
        self.carry = self.states[run.end] if run.status == "completed" else None

    def stepper(self, beta0, y0, angles, settings, first_step, max_step):
        return BackwardEuler(self, float(beta0), angles, first_step, max_step)

    def backward_euler(self, beta_old: float, state: JFOState, beta: float) -> JFOState:
        """One backward-Euler step from ``state`` at ``beta_old`` to ``beta``: the rates that balance the load
        there (Newton, forward-difference Jacobian), recorded as the accepted state at ``beta``."""
        dbeta = beta - beta_old
        load = np.asarray(self.pump.load_vector(beta), float)
        scale = max(float(np.hypot(*load)), 1e-300)
        y, prev = state.y, state.result

        def residual(r, warm_start):
            return self.step_residual(beta, dbeta, state, r, warm_start, load, scale)

        r = np.asarray(state.rates, float)
        m = r.size
        res, R = residual(r, prev)
        for k in range(self.max_newton + 1):
            if np.linalg.norm(R) <= self.tol:
                self.newton_iterations += k
                accepted = JFOState(y + dbeta * r, r, res)
                self.states[float(beta)] = accepted
                return accepted
            if k == self.max_newton:
                break
            J = np.zeros((m, m))
            for j in range(m):
                h = 1e-6 * max(1.0, abs(r[j]))
                d = np.zeros(m)
                d[j] = h
                J[:, j] = (residual(r + d, res)[1] - R) / h
            try:
                step = -np.linalg.solve(J, R)
            except np.linalg.LinAlgError:
                raise TrialRejected(f"JFO step to beta = {beta:.4f} rad: the Jacobian of the load balance in the "
                                    f"rates is singular") from None
            r, res, R = self._line_search(residual, r, step, res, R)
        raise TrialRejected(f"JFO step to beta = {beta:.4f} rad: Newton on the rates did not converge in "
                            f"{self.max_newton} iterations (residual {np.linalg.norm(R):.3g}: |force + load| / "
                            f"|load|{self.residual_note})")

    #: What the step's residual holds beyond the load balance (for the messages).
    residual_note = ""

    def step_residual(self, beta: float, dbeta: float, state: JFOState, r: np.ndarray, warm_start,
                      load: np.ndarray, scale: float):
        """``(JFO result, residual [-])`` of the backward-Euler step with rates ``r``: ``(force + load) / |load|``
        of the film at ``y + dbeta r`` from the history of ``state``."""
        y = state.y + dbeta * r
        gamma, delta = y[:2]
        if not (gamma >= 0 and self.rigid.smallest_film(beta, (gamma, delta)) > 0):
            raise FilmClosed((float(gamma), float(delta)))
        self.solves += 1
        res = solve_jfo(self.mesh, CosineFilm(gamma, delta), wedge=float(self.pump.wedge(beta)),
                        inlet_pressure=self.pocket_pressure(beta, y), cavitation_pressure=self.cavitation_pressure,
                        dt=dbeta, previous=state.result, warm_start=warm_start)
        return res, (res.force + load) / scale

    @staticmethod
    def _line_search(force, r, step, res, R):
        """Backtracking on ``|force + load|``; a trial that closes the film counts as no decrease."""
        t = 1.0
        while True:
            try:
                trial, Rt = force(r + t * step, res)
            except FilmClosed:
                if t < 1e-3:
                    raise
                t *= 0.5
                continue
            if np.linalg.norm(Rt) < (1 - 1e-4 * t) * np.linalg.norm(R) or t < 1e-3:
                return r + t * step, trial, Rt
            t *= 0.5

    def part_step(self, beta: float, y: np.ndarray) -> JFOState:
        """The film at an angle inside an accepted step: the backward-Euler film of the interpolated state
        ``y`` from the step's start, with the step's rates."""
        before = max(b for b in self.states if b < beta)
        after = min((b for b in self.states if b > beta), default=None)
        start = self.states[before]
        rates = self.states[after].rates if after is not None else start.rates
        result = solve_jfo(self.mesh, CosineFilm(*y[:2]), wedge=float(self.pump.wedge(beta)),
                           inlet_pressure=self.pocket_pressure(beta, y), cavitation_pressure=self.cavitation_pressure,
                           dt=beta - before, previous=start.result, warm_start=start.result)
        return JFOState(np.asarray(y, float), np.asarray(rates, float), result)

    def sample(self, beta: float, y: np.ndarray) -> dict[str, object]:
        state = self.states.get(float(beta))
        if state is None:
            state = self.part_step(float(beta), y)
        res, sc = state.result, self.pump.scale
        flows = res.flows
        self.cavitated_fraction_max = max(self.cavitated_fraction_max, float(res.cavitated_fraction))
        arc = sum(v for k, v in flows.items() if k in ("arc_start", "arc_end", "outer"))
        return {"gamma_rate": state.rates[0], "delta_rate": state.rates[1], "h_min": sc.to_thickness(res.h_min),
                "friction_moment": sc.to_moment(res.friction), "flow_inlet": sc.to_flow(flows.get("inlet", 0.0)),
                "flow_side": sc.to_flow(flows.get("side", 0.0)), "flow_arc": sc.to_flow(arc),
                "flow_squeeze": sc.to_flow(flows["squeeze"]), "mass_balance": sc.to_flow(res.mass_balance),
                **self.sample_extra(float(beta), state)}

    def sample_extra(self, beta: float, state: JFOState) -> dict[str, float]:
        """Columns a model adds to a sample (a fed pocket's); none here."""
        return {}

    def samples(self, betas: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        self.cavitated_fraction_max = 0.0
        return super().samples(betas, states)

    def statistics(self, output, runs: Sequence) -> dict[str, float]:
        """The output run's: JFO solves (``nfev``, ``factorizations``), steps, Newton iterations, and the
        largest cavitated fraction of the samples."""
        return {"nfev": float(self.solves), "factorizations": float(self.solves), "steps": float(output.steps),
                "newton_iterations": float(self.newton_iterations),
                "cavitated_fraction_max": self.cavitated_fraction_max}
