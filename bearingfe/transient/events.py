"""Events of the pump transient, scipy style: plain functions of ``(beta, y)`` with ``terminal`` and ``direction``.

As in :func:`scipy.integrate.solve_ivp`, an event is a function whose zero
marks the event, with the attributes ``terminal`` (the run ends there) and
``direction`` (-1: only a crossing from positive to negative counts). The
stepping loop tests the event at each accepted state and locates a crossing
on the integrator's dense output of that step (:func:`locate`).
"""

from __future__ import annotations

from typing import Callable

import numpy as np

__all__ = ["film_rupture", "crossed", "locate", "BISECTIONS"]

#: Bisections of a step to locate an event: 2^-60 of a step is below the round-off of the angle.
BISECTIONS = 60


def film_rupture(model, min_film: float) -> Callable[[float, np.ndarray], float]:
    """The film-rupture event: ``smallest film - min_film`` [c], terminal, falling.

    Parameters
    ----------
    model : bearingfe.transient.base.Model
        Gives the smallest film of a state (:meth:`~bearingfe.transient.base.Model.smallest_film`).
    min_film : float
        The film [c] at which the run stops as ruptured.
    """

    def rupture(beta: float, y: np.ndarray) -> float:
        return model.smallest_film(beta, y) - min_film

    rupture.terminal = True
    rupture.direction = -1
    return rupture


def crossed(event: Callable, before: float, after: float) -> bool:
    """Whether ``event`` happened between two accepted states whose event values are ``before``, ``after``.

    A falling event (``direction < 0``) happens when the value is ``<= 0``
    after a positive value; a rising one the other way round; one without
    direction either way.
    """
    direction = getattr(event, "direction", 0)
    falling = before > 0 >= after
    rising = before < 0 <= after
    return falling if direction < 0 else rising if direction > 0 else falling or rising


def locate(event: Callable, dense: Callable, beta_old: float, beta_new: float, bisections: int = BISECTIONS
           ) -> float:
    """Angle in ``(beta_old, beta_new]`` where ``event`` on the dense output ``dense`` first reaches zero [rad].

    Bisection, which assumes nothing about the event's shape inside the
    step: it keeps the end where the event has happened (its value is
    ``<= 0`` for a falling event) and the other where it has not.
    """
    sign = -1.0 if getattr(event, "direction", 0) >= 0 and event(beta_old, dense(beta_old)) < 0 else 1.0
    lo, hi = beta_old, beta_new
    for _ in range(bisections):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if sign * event(mid, dense(mid)) > 0 else (lo, mid)
    return hi
