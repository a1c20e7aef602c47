"""Squeeze rates that balance a load under cavitation: a small Newton method on two unknowns.

Under cavitation the film force is no longer linear in the squeeze rates. The
transient finds the rates that balance a load with :func:`rates_for_load`: a
Newton method started from the superposition answer, whose Jacobian comes from
the same factorization on the converged rupture set.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .models import solve_cavitating
from .obstacle import CavitationError
from .swift_stieber import FilmProblem, obstacle_problem
from ..core.linalg import DEFAULT_SOLVER, Factorize
from ..core.parameters import OperatingPoint, takes
from ..film import ReynoldsResult, Superposition

__all__ = ["RatesForLoad", "rates_for_load"]



@dataclass(frozen=True, eq=False)
class RatesForLoad:
    """Squeeze rates that balance a load under cavitation.

    Attributes
    ----------
    rates : ndarray, shape (2,)
        ``(gamma_rate, phi0_rate)`` per radian of shaft turn.
    result : ReynoldsResult
        The cavitated solution at those rates.
    newton_iterations : int
    active_set_iterations : int
        Total over the Newton steps.
    residual : float
        ``|force + load|`` at the answer.
    """

    rates: np.ndarray
    result: ReynoldsResult
    newton_iterations: int
    active_set_iterations: int
    residual: float


#: Relative residual of the load balance accepted where no step on the rupture set lowers it (a force that
#: responds to the rates in one direction only, what is left lying across it): the transient runs' integrator
#: tolerance (``rtol = 1e-5``). Measured on the orifice pump's elastic support at 194.5 deg: 4.7e-7 to 1.1e-6.
STALLED = 1e-5


@takes(OperatingPoint)
def rates_for_load(sup: Superposition, load, wedge: float = 1.0, inlet_pressure: float = 0.0, *,
                   model: str = "reynolds", warm_start=None, tol: float = 1e-9, max_newton: int = 30,
                   solver: str | Factorize = DEFAULT_SOLVER) -> RatesForLoad:
    """Squeeze rates at which the cavitated film force balances a load (``force + load = 0``).

    A Newton method on the two rates: the first guess is the superposition
    answer (:meth:`Superposition.rates_for_load`, no cavitation); each step
    solves the complementarity problem (warm-started from the last rupture
    set) and takes the Jacobian from the two squeeze unit fields on that
    rupture set, with the same factorization. The force is piecewise linear
    in the rates, so the iteration ends in finitely many steps once the
    rupture set settles; a backtracking line search guards the first steps.

    Parameters
    ----------
    sup : Superposition
    load : (float, float)
        Applied load in the arc frame [mu omega R0^4 / c^2].
    wedge, inlet_pressure : float
        Or ``operating=`` an :class:`~bearingfe.core.parameters.OperatingPoint`
        (its ``squeeze`` is what is solved for: leave it at zero).
    model : {"reynolds", "gumbel"}
    warm_start : optional
        As in :func:`solve_cavitating`.
    tol : float
        Relative tolerance on ``|force + load|`` (scaled by ``|load|`` and the
        wedge force). Where the Newton step fails to lower the residual (a
        Jacobian on the rupture set that is singular, or a kink), damped
        Levenberg-Marquardt steps are tried; where none lowers it either, a
        residual within :data:`STALLED` is accepted (the set's force responds
        in one direction only) and a larger one is a :class:`CavitationError`.
    max_newton : int
        Cap; beyond it :class:`CavitationError`.
    """
    load = np.asarray(load, float)
    if load.shape != (2,) or not np.all(np.isfinite(load)):
        raise ValueError(f"load must be a finite pair, got {load!r}")
    if model not in ("reynolds", "gumbel"):
        raise ValueError(f"model must be 'reynolds' or 'gumbel', got {model!r}")
    rates = np.asarray(sup.rates_for_load(load, wedge, inlet_pressure), float)
    fp = obstacle_problem(sup, solver)
    scale = max(float(np.linalg.norm(load)), float(np.linalg.norm(sup.forces[:, 0] * wedge)), 1e-300)

    def evaluate(r, warm):
        res = solve_cavitating(sup, wedge, r, inlet_pressure, model=model, warm_start=warm, solver=solver)
        return res, res.force + load

    res, R = evaluate(rates, warm_start)
    total = res.iterations
    for k in range(1, max_newton + 1):
        norm = float(np.linalg.norm(R))
        if norm <= tol * scale:
            return RatesForLoad(rates=rates, result=res, newton_iterations=k - 1,
                                active_set_iterations=total, residual=norm)
        J = _rate_jacobian(sup, fp, res, model)
        found = None
        try:
            step = -np.linalg.solve(J, R)
        except np.linalg.LinAlgError:
            step = None
        t = 1.0
        while step is not None and np.all(np.isfinite(step)) and t >= 1e-3:
            trial, Rt = evaluate(rates + t * step, res)
            total += trial.iterations
            if np.linalg.norm(Rt) < (1 - 1e-4 * t) * norm:
                found = (rates + t * step, trial, Rt)
                break
            t *= 0.5
        if found is None:
            # the rupture set's Jacobian gives no descent: nearly singular on this set (most of the film
            # ruptured, the two squeeze fields' forces almost parallel) or a kink where the set jumps along
            # the step. Levenberg-Marquardt steps, shorter and turning towards the residual's descent as the
            # damping grows (never a step that raises the residual)
            JtJ, g = J.T @ J, J.T @ R
            mu = 1e-10 * max(float(np.trace(JtJ)), 1e-300)
            for _ in range(24):
                try:
                    step = -np.linalg.solve(JtJ + mu * np.eye(2), g)
                except np.linalg.LinAlgError:
                    step = None
                if step is not None and np.all(np.isfinite(step)):
                    trial, Rt = evaluate(rates + step, res)
                    total += trial.iterations
                    if np.linalg.norm(Rt) < (1 - 1e-4) * norm:
                        found = (rates + step, trial, Rt)
                        break
                mu *= 10.0
        if found is None:
            # a force that responds to the rates in one direction only (the Jacobian of rank 1): the residual across
            # it moves only when the rupture set changes, which the rates along the Jacobian's null direction do
            # not do locally; walk that direction both ways, doubling, until the set has changed enough to lower it
            _, sv, vt = np.linalg.svd(J)
            null = vt[-1]
            reach = max(float(np.linalg.norm(rates)), 1.0)
            for length in reach * 2.0 ** np.arange(-10, 4):
                for sign in (1.0, -1.0):
                    trial, Rt = evaluate(rates + sign * length * null, res)
                    total += trial.iterations
                    if np.linalg.norm(Rt) < (1 - 1e-4) * norm:
                        found = (rates + sign * length * null, trial, Rt)
                        break
                if found is not None:
                    break
        if found is None and norm <= STALLED * scale:
            # a stationary point of |force + load| on this rupture set: its force responds to the rates in one
            # direction only (the Jacobian of rank 1, measured condition 1e18 on the orifice pump's deflected
            # film, 73 % ruptured), and what is left lies across it: only a jump of the set could take it
            return RatesForLoad(rates=rates, result=res, newton_iterations=k, active_set_iterations=total,
                                residual=norm)
        if found is None:
            raise CavitationError(f"rates_for_load: no step lowers |force + load| = {norm:.3g} (scale {scale:.3g}) "
                                  "on the cavitated film (its force responds to the rates in one direction only, "
                                  "or gamma = 0 leaves phi0_rate undetermined)")
        rates, res, R = found
    raise CavitationError(f"rates_for_load: Newton did not converge in {max_newton} steps "
                          f"(|force + load| = {np.linalg.norm(R):.3g}, scale {scale:.3g})")


def _rate_jacobian(sup: Superposition, fp: FilmProblem, res: ReynoldsResult, model: str) -> np.ndarray:
    """d(force)/d(rates) on the current rupture set."""
    if model == "gumbel":
        keep = ~res.cavitated
        J = np.zeros((2, 2))
        for k in (1, 2):
            J[:, k - 1] = sup.loads(np.where(keep, sup.fields[:, k], 0.0))[0]
        return J
    active = res.cavitated[fp.interior]
    U = fp.solve_fixed(fp.rhs[:, 1:3], active)
    J = np.zeros((2, 2))
    for k in range(2):
        u = np.zeros(sup.operators.n_dofs)
        u[fp.interior] = U[:, k]
        J[:, k] = sup.loads(u)[0]
    return J
