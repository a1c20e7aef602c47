r"""The plunger shoe over the pump cycle with mass-conserving (JFO) cavitation: the film's history.

Under JFO the fill fraction ``theta`` is a state of the film: oil that left a
cavity is not there when the film closes again. The quasi-static ODE of
:func:`bearingfe.simulate` (state ``(gamma, delta)``, rates from the load
balance) becomes a time-stepping scheme that carries ``theta``: backward Euler
in shaft angle with fixed steps ``dbeta``. At each step the rates
``r = (gamma_rate, delta_rate)`` solve the load balance

    F(r) + load(beta_{n+1}) = 0,   F(r) = film force of the JFO step from
    (theta_n, film_n) to film(y_n + dbeta r) over dbeta,

by Newton's method with a forward-difference Jacobian (each evaluation one
JFO solve, warm-started from the last cavity), so that the film's mass is
conserved from step to step (``solve_jfo(..., dt=, previous=)``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..film.thickness import CosineFilm
from ..film.finite_volume import solve_jfo
from ..geometry.meshing import SupportMesh
from ..bearings.pump import EccentricPump
from ..film import ReynoldsResult

__all__ = ["JFORun", "jfo_run"]


@dataclass(frozen=True, eq=False)
class JFORun:
    """Backward-Euler JFO run of the shoe (non-dimensional states, per step).

    Attributes
    ----------
    beta : ndarray
        Shaft angles [rad], the start included.
    y : ndarray, shape (n, 2)
        ``(gamma, delta)`` at each angle.
    rates : ndarray, shape (n, 2)
        ``(gamma_rate, delta_rate)`` per radian (the step's backward difference).
    results : list of ReynoldsResult
        The JFO solution at each angle (``theta`` carried from step to step).
    newton_iterations : int
        Total over the steps.
    solves : int
        JFO solves (Newton evaluations and Jacobian columns).
    status, message : str
        ``"completed"`` or ``"ruptured"`` (film thinner than the bound).
    """

    beta: np.ndarray
    y: np.ndarray
    rates: np.ndarray
    results: list
    newton_iterations: int
    solves: int
    status: str
    message: str


def _step(pump: EccentricPump, mesh: SupportMesh, prev: ReynoldsResult, y: np.ndarray, guess: np.ndarray,
          beta: float, dbeta: float, p_c: float, tol: float, max_newton: int):
    """One backward-Euler step: rates that balance the load at ``beta`` (Newton, forward-difference Jacobian)."""
    load = np.asarray(pump.load_vector(beta), float)
    wedge, p_s = float(pump.wedge(beta)), float(pump.inlet_pressure(beta)) if mesh.has_inlet else 0.0
    scale = max(float(np.hypot(*load)), 1e-300)
    solves = 0
    warm = prev

    def force(r, warm_start):
        nonlocal solves
        gamma, delta = y + dbeta * r
        if not (gamma >= 0 and CosineFilm(gamma, delta).minimum((float(mesh.mesh.p[0].min()),
                                                                 float(mesh.mesh.p[0].max()))) > 0):
            raise FloatingPointError(f"film closed at beta = {beta:.4f} rad (gamma = {gamma:.4g})")
        solves += 1
        res = solve_jfo(mesh, CosineFilm(gamma, delta), wedge=wedge, inlet_pressure=p_s, cavitation_pressure=p_c,
                        dt=dbeta, previous=prev, warm_start=warm_start)
        return res, res.force + load

    r = np.asarray(guess, float)
    res, R = force(r, warm)
    for k in range(1, max_newton + 1):
        if np.hypot(*R) <= tol * scale:
            return r, res, k - 1, solves
        J = np.zeros((2, 2))
        for j in range(2):
            h = 1e-6 * max(1.0, abs(r[j]))
            d = np.zeros(2)
            d[j] = h
            J[:, j] = (force(r + d, res)[1] - R) / h
        step = -np.linalg.solve(J, R)
        t = 1.0
        while True:
            trial, Rt = force(r + t * step, res)
            if np.hypot(*Rt) < (1 - 1e-4 * t) * np.hypot(*R) or t < 1e-3:
                break
            t *= 0.5
        r, res, R = r + t * step, trial, Rt
    raise RuntimeError(f"JFO pump step at beta = {beta:.4f} rad: Newton on the rates did not converge in "
                       f"{max_newton} iterations (|force + load| / |load| = {np.hypot(*R) / scale:.3g})")


def jfo_run(pump: EccentricPump, mesh: SupportMesh, y0, rates0, beta0: float, beta1: float, steps: int, *,
            cavitation_pressure: float = 0.0, bound: float = 0.0, initial: ReynoldsResult | None = None,
            tol: float = 1e-9, max_newton: int = 30) -> JFORun:
    """Backward-Euler JFO steps of the shoe from ``beta0`` to ``beta1``.

    Parameters
    ----------
    pump : EccentricPump
    mesh : SupportMesh
        Straight-sided P1 mesh of ``pump.surface``.
    y0, rates0 : (float, float)
        ``(gamma, delta)`` at ``beta0`` and a first guess of the rates.
    beta0, beta1 : float
        Shaft angles [rad], ``beta1 > beta0``.
    steps : int
        Number of equal steps, >= 1.
    cavitation_pressure : float
        ``p_c`` [-], gauge, ``<= 0``.
    bound : float
        Smallest film [c] that ends the run as ruptured.
    initial : ReynoldsResult, optional
        JFO state at ``beta0`` (its ``theta`` is the history carried in);
        default the steady JFO film at ``y0`` with ``rates0`` as squeeze.
    tol, max_newton
        Relative force tolerance and cap of the Newton iteration per step.
    """
    if not (isinstance(steps, int) and steps >= 1):
        raise ValueError(f"steps must be an integer >= 1, got {steps!r}")
    if not beta1 > beta0:
        raise ValueError(f"beta1 must exceed beta0, got {beta0!r}, {beta1!r}")
    y = np.asarray(y0, float)
    r = np.asarray(rates0, float)
    p_s0 = float(pump.inlet_pressure(beta0)) if mesh.has_inlet else 0.0
    res = initial if initial is not None else solve_jfo(
        mesh, CosineFilm(*y), wedge=float(pump.wedge(beta0)), squeeze=tuple(r), inlet_pressure=p_s0,
        cavitation_pressure=cavitation_pressure)
    dbeta = (beta1 - beta0) / steps
    betas, ys, rs, results = [beta0], [y.copy()], [r.copy()], [res]
    newton = solves = 0
    status, message = "completed", f"completed {(beta1 - beta0) / (2 * math.pi):.4g} revolutions"
    for n in range(1, steps + 1):
        beta = beta0 + n * dbeta
        try:
            r, res, k, s = _step(pump, mesh, res, y, r, beta, dbeta, cavitation_pressure, tol, max_newton)
        except FloatingPointError as exc:
            status, message = "ruptured", str(exc)
            break
        newton += k
        solves += s
        y = y + dbeta * r
        betas.append(beta), ys.append(y.copy()), rs.append(r.copy()), results.append(res)
        if res.h_min <= bound:
            status, message = "ruptured", f"smallest film reached {res.h_min:.4g} c at beta = {beta:.4f} rad"
            break
    return JFORun(beta=np.array(betas), y=np.array(ys), rates=np.array(rs), results=results,
                  newton_iterations=newton, solves=solves, status=status, message=message)
