"""One pump transient of any film model: start, periodic start, output run, samples, :class:`Trajectory`.

:func:`run_transient` is what both public doors (:func:`bearingfe.simulate`,
:func:`bearingfe.transient.elastic.simulate_elastic`) call once they have
chosen the model (:data:`bearingfe.transient.MODELS`) and checked the
settings (:class:`bearingfe.transient.settings.Integration`).
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings

import numpy as np

from ..core.checks import OutOfRangeWarning, check_elastic
from .base import Model
from .periodic import LOOSE_ATOL, LOOSE_RTOL, PERIODIC_METHODS, search_settings
from .settings import Integration
from .stepping import integrate, states_at
from .trajectory import Trajectory, make_trajectory

__all__ = ["run_transient"]


def run_transient(model: Model, settings: Integration, *, balance_ratio: float) -> Trajectory:
    """Integrate ``model`` as ``settings`` say and sample the output run.

    Parameters
    ----------
    model : bearingfe.transient.base.Model
    settings : Integration
    balance_ratio : float
        The pump's hydrostatic balance ratio [-] (:func:`bearingfe.balance_ratio`), kept in ``stats``.

    Raises
    ------
    ValueError
        ``settings`` asks what the model cannot do (message names the field).
    RuntimeError
        The periodic start did not converge.
    """
    model.check(settings)
    clock = time.perf_counter()
    beta0, y0 = model.initial_state(settings)
    runs = []

    search = search_settings(model, settings)

    def revolution(y: np.ndarray, loose: bool = False):
        step = search.loosened(LOOSE_RTOL, LOOSE_ATOL) if loose else search
        runs.append(integrate(model, y, step.revolution_angles(beta0), step))
        return runs[-1]

    def admissible(y: np.ndarray) -> bool:
        return bool(np.all(np.isfinite(y)) and y[0] >= 0 and model.smallest_film(beta0, y) > settings.min_film)

    iterations, residual, verified = 0, math.nan, None
    if settings.periodic:
        method = settings.periodic_method or model.periodic_default
        found = PERIODIC_METHODS[method](model, y0, revolution, admissible, settings.periodic_tol,
                                         settings.periodic_max_iter)
        y0, iterations, residual, verified = found.start, found.iterations, found.residual, found.run
    angles = settings.output_angles(beta0)
    if verified is not None and settings.revolutions == 1:
        output = verified  # the revolution that verified the periodic state is the output revolution
    else:
        output = integrate(model, y0, angles, settings)
        runs.append(output)
    seconds = time.perf_counter() - clock
    betas, states = states_at(output, angles, y0)
    columns = model.samples(betas, states)
    stats = dict(model.statistics(output, runs), seconds=seconds)
    solver_seconds = model.solver_seconds()
    stats.update(solver_seconds=seconds if solver_seconds is None else solver_seconds, dofs=float(model.dofs),
                 balance_ratio=balance_ratio, postprocess_seconds=time.perf_counter() - clock - seconds)
    traj = make_trajectory(model.pump, beta0, betas, states, columns, status=output.status,
                           message=output.message, rupture_beta=output.rupture_beta, start=y0,
                           periodic_iterations=iterations, periodic_residual=residual, element=model.element,
                           stats=stats)
    return _checked_elastic(traj, getattr(model, "compliance", None))


def _checked_elastic(traj: Trajectory, compliance) -> Trajectory:
    """An elastic run within linear elasticity (:func:`bearingfe.core.checks.check_elastic`): its largest
    opening and pressure over the samples; a note on a large opening is warned and added to the message."""
    if compliance is None or traj.max_deflection is None:
        return traj
    scale = compliance.scale
    opening = np.asarray(traj.max_deflection, float) / scale.clearance  # [m] -> [c]
    pressure = np.zeros(0) if traj.pressures is None else np.asarray(traj.pressures, float)
    note = check_elastic(opening, pressure, scale, compliance.modulus)
    if note is None:
        return traj
    warnings.warn(OutOfRangeWarning(note), stacklevel=3)
    return dataclasses.replace(traj, message=f"{traj.message}; {note}" if traj.message else note)
