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
        wedge force).
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
        if np.linalg.norm(R) <= tol * scale:
            return RatesForLoad(rates=rates, result=res, newton_iterations=k - 1,
                                active_set_iterations=total, residual=float(np.linalg.norm(R)))
        J = _rate_jacobian(sup, fp, res, model)
        try:
            step = -np.linalg.solve(J, R)
        except np.linalg.LinAlgError:
            raise CavitationError("the squeeze Jacobian is singular under cavitation "
                                  "(gamma = 0 leaves phi0_rate undetermined)") from None
        t = 1.0
        while True:
            trial, Rt = evaluate(rates + t * step, res)
            total += trial.iterations
            if np.linalg.norm(Rt) < (1 - 1e-4 * t) * np.linalg.norm(R) or t < 1e-3:
                break
            t *= 0.5
        rates, res, R = rates + t * step, trial, Rt
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
