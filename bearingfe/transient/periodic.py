"""The periodic start of the pump transient: a fixed point ``y = P(y)`` of the return map over one revolution.

Every method takes the model, the first guess and ``revolution(y, loose=False)``,
which integrates one revolution from ``y`` (a :class:`bearingfe.transient.stepping.Run`;
``loose``: at ``rtol = 1e-3`` at most), and returns a :class:`PeriodicStart`.
The residual of a revolution is ``max |(gamma, delta)(2 pi) - (gamma, delta)(0)|``
with the attitude difference wrapped into ``[-pi, pi)``.

==================  ==========================================================================
method              what it does
==================  ==========================================================================
``newton``          Newton shooting: the first revolution is a fixed-point step (from the
                    steady start the return map is far from linear), integrated loosely; the
                    second gives the monodromy matrix ``M = dP/dy`` (:func:`monodromy`), each
                    later one a Broyden update of it; the next start is
                    ``y + (I - M)^-1 (P(y) - y)`` (the fixed-point step where that leaves the
                    admissible states). The revolution that meets the tolerance verifies the
                    start and is not counted. Two-component states (``gamma, delta``) only.
``fixed-point``     ``y <- P(y)`` until the residual is below the tolerance; the start is then
                    ``P(y)`` and the output revolution is integrated afresh.
``anderson``        Anderson mixing of the last three revolutions (weighted by the model's
                    :meth:`~bearingfe.transient.base.Model.weights`); a mixed state whose
                    revolution does not complete falls back to the plain iterate. The
                    revolution that meets the tolerance verifies the start and is counted.
``one-revolution``  One revolution from the guess, then its end: no convergence test (the
                    residual of that revolution is reported); the film history of a model
                    that carries one (JFO) is that revolution's.
==================  ==========================================================================

The revolutions of the search are integrated at the run's settings, except for a model whose return map
converges only to its integrator's accuracy (``periodic_tied``: a fed pocket on a cavitating film): there
:func:`search_settings` ties ``rtol`` to ``PERIODIC_RTOL_RATIO periodic_tol`` (the revolution that verifies the
start, the output revolution of a one-turn run, is then integrated at that tolerance too).

A method that reaches ``max_iter`` revolutions without meeting the tolerance
raises ``RuntimeError``; a revolution that does not complete ends the search
at its start (the output run then stops the same way).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from types import MappingProxyType
from typing import Callable, Mapping

import numpy as np

from .base import wrapped

__all__ = ["PERIODIC_METHODS", "PERIODIC_RTOL_RATIO", "PeriodicStart", "search_settings", "newton_shooting", "fixed_point", "anderson", "one_revolution",
           "monodromy", "rate_jacobian", "expm2"]

#: Rate of the loose first revolution of Newton shooting (it moves the state by far more than that).
LOOSE_RTOL, LOOSE_ATOL = 1e-3, 1e-6
#: Revolutions Anderson mixing keeps.
ANDERSON_MEMORY = 3
#: The search's revolutions of a model with :attr:`~bearingfe.transient.base.Model.periodic_tied` are integrated at
#: ``rtol <= PERIODIC_RTOL_RATIO periodic_tol``: a revolution is only as accurate as its integrator, and the return
#: map of a stiff state (a fed pocket on a cavitating film) converges only to that accuracy (measured on the shipped
#: orifice pump with Swift-Stieber rupture: Anderson stalls at 5e-5 to 1.3e-4 with rtol = 1e-5 and reaches
#: periodic_tol = 1e-6 with rtol = 1e-7).
PERIODIC_RTOL_RATIO = 0.1


def search_settings(model, settings):
    """The settings of the periodic search's revolutions: ``settings``, with ``rtol`` (and a given ``atol``) tied
    to ``periodic_tol`` (:data:`PERIODIC_RTOL_RATIO`) for a model whose ``periodic_tied`` says its return map needs
    it; a tighter ``rtol`` asked for is kept."""
    rtol = PERIODIC_RTOL_RATIO * settings.periodic_tol
    if not getattr(model, "periodic_tied", False) or settings.rtol <= rtol:
        return settings
    atol = None if settings.atol is None else min(settings.atol, 1e-3 * rtol)
    return dataclasses.replace(settings, rtol=rtol, atol=atol)


@dataclass(frozen=True)
class PeriodicStart:
    """The periodic start found.

    Attributes
    ----------
    start : ndarray
        The state to start the output revolution from.
    iterations : int
        Revolutions counted (see the method).
    residual : float
        Residual of the revolution that ended the search (NaN if none completed).
    run : Run or None
        The completed revolution from ``start`` that met the tolerance (the
        output revolution when one revolution is asked for), or None.
    """

    start: np.ndarray
    iterations: int
    residual: float
    run: object | None = None


def _residual(run, y: np.ndarray) -> tuple[np.ndarray, float]:
    """``P(y) - y`` (attitude wrapped) and its largest ``(gamma, delta)`` component."""
    r = wrapped(run.y_end - y)
    return r, float(np.max(np.abs(r[:2])))


def _not_converged(name: str, iterations: int, residual: float, tol: float) -> RuntimeError:
    return RuntimeError(f"periodic start ({name}) did not converge in {iterations} revolutions "
                        f"(last residual {residual:.3g} >= periodic_tol = {tol}): a revolution is only as "
                        f"accurate as the integrator, so lower rtol (to periodic_tol / 10 or less) or raise "
                        f"periodic_tol (a scene's [run] table has both)")


def rate_jacobian(model, beta: float, y: np.ndarray, step: float = 1e-7) -> np.ndarray:
    """``d rates / d y`` at one state by forward differences (one extra rate evaluation per component)."""
    f0 = model.rates(beta, y)
    cols = []
    for j in range(np.size(y)):
        h = step * max(1.0, abs(float(y[j])))
        e = np.zeros(np.size(y))
        e[j] = h
        cols.append((model.rates(beta, y + e) - f0) / h)
    return np.column_stack(cols)


def expm2(a: np.ndarray) -> np.ndarray:
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


def monodromy(model, run, stride: int = 2) -> np.ndarray:
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
    jac = {i: rate_jacobian(model, betas[i], np.asarray(states[i], float)) for i in points}
    phi = np.eye(2)
    for i, j in zip(points[:-1], points[1:]):
        phi = expm2((betas[j] - betas[i]) * 0.5 * (jac[i] + jac[j])) @ phi
    return phi


def newton_shooting(model, y0: np.ndarray, revolution: Callable, admissible: Callable[[np.ndarray], bool],
                    tol: float, max_iter: int) -> PeriodicStart:
    """``"newton"``: Newton shooting on the return map (see the module docstring)."""
    y = np.asarray(y0, float)
    jacobian, previous = None, None
    iterations, residual = 0, math.nan
    while True:
        loose = iterations == 0
        run = revolution(y, loose=loose)
        if run.status != "completed":
            return PeriodicStart(y, iterations + 1, residual)
        r, residual = _residual(run, y)
        if residual < tol and not loose:
            return PeriodicStart(y, iterations, residual, run)
        iterations += 1
        if iterations == 2:
            jacobian = monodromy(model, run)
        elif jacobian is not None:
            dy, dp = y - previous[0], (y + r) - (previous[0] + previous[1])
            jacobian = jacobian + np.outer(dp - jacobian @ dy, dy) / float(dy @ dy)
        previous = (y, r)
        step = r if jacobian is None else np.linalg.solve(np.eye(2) - jacobian, r)
        trial = y + step
        # a Newton step that leaves the admissible states falls back to the fixed-point step
        y = trial if admissible(trial) else y + r
        if iterations >= max_iter:
            raise _not_converged("newton", iterations, residual, tol)


def fixed_point(model, y0: np.ndarray, revolution: Callable, admissible: Callable[[np.ndarray], bool],
                tol: float, max_iter: int) -> PeriodicStart:
    """``"fixed-point"``: ``y <- P(y)`` (see the module docstring)."""
    y = np.asarray(y0, float)
    iterations, residual = 0, math.nan
    while True:
        run = revolution(y)
        if run.status != "completed":
            return PeriodicStart(y, iterations + 1, residual)
        r, residual = _residual(run, y)
        iterations += 1
        y = y + r
        if residual < tol:
            return PeriodicStart(y, iterations, residual)
        if iterations >= max_iter:
            raise _not_converged("fixed-point", iterations, residual, tol)


def anderson(model, y0: np.ndarray, revolution: Callable, admissible: Callable[[np.ndarray], bool],
             tol: float, max_iter: int, memory: int = ANDERSON_MEMORY) -> PeriodicStart:
    """``"anderson"``: Anderson mixing of the last revolutions (see the module docstring)."""
    y = np.asarray(y0, float)
    xs, fs = [], []
    iterations = 0
    while True:
        run = revolution(y)
        if run.status != "completed" and xs:  # the mixed state failed: back to the plain iterate
            y, xs, fs = xs[-1] + fs[-1], [], []
            continue
        iterations += 1
        if run.status != "completed":
            return PeriodicStart(y, iterations, math.nan)
        f, residual = _residual(run, y)
        if residual < tol:
            return PeriodicStart(y, iterations, residual, run)
        if iterations >= max_iter:
            raise _not_converged("anderson", iterations, residual, tol)
        xs, fs = (xs + [y])[-(memory + 1):], (fs + [f])[-(memory + 1):]
        nxt = y + f
        if len(xs) > 1:
            weights = model.weights(y)
            dX = np.diff(np.array(xs), axis=0).T
            dF = np.diff(np.array(fs), axis=0).T
            coef = np.linalg.lstsq(dF * weights[:, None], f * weights, rcond=None)[0]
            mixed = y + f - (dX + dF) @ coef
            if np.all(np.isfinite(mixed)) and mixed[0] >= 0:
                nxt = mixed
        y = nxt


def one_revolution(model, y0: np.ndarray, revolution: Callable, admissible: Callable[[np.ndarray], bool],
                   tol: float, max_iter: int) -> PeriodicStart:
    """``"one-revolution"``: one revolution, then its end (see the module docstring)."""
    y = np.asarray(y0, float)
    run = revolution(y)
    if run.status != "completed":
        return PeriodicStart(y, 1, math.nan)
    return PeriodicStart(np.array(run.y_end, float), 1, _residual(run, y)[1])


#: Periodic-start methods by name: ``(model, y0, revolution, admissible, tol, max_iter) -> PeriodicStart``.
PERIODIC_METHODS: Mapping[str, Callable[..., PeriodicStart]] = MappingProxyType({
    "newton": newton_shooting, "fixed-point": fixed_point, "anderson": anderson, "one-revolution": one_revolution})
