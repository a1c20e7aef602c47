"""Mass-conserving (JFO / Elrod-Adams p-theta) cavitation as an entry of :data:`bearingfe.cavitation.MODELS`.

The model is solved by the finite-volume scheme of :mod:`bearingfe.film.finite_volume`
(the fill fraction lives on its median-dual cells); the front door
(:func:`bearingfe.solve_reynolds`) calls that scheme directly, without building a
Galerkin film state. This entry serves callers that already hold one
(:func:`bearingfe.cavitation.solve_model`).
"""

from __future__ import annotations

import numpy as np

from ..film import ReynoldsResult, solve_jfo
from ..film.finite_volume import MAX_ITERATIONS

__all__ = ["solve_model_jfo"]


def solve_model_jfo(sup, weights: np.ndarray, options) -> ReynoldsResult:
    """``"jfo"``: the film state ``sup`` (its mesh and film) at the operating point ``weights =
    (wedge, gamma_rate, phi0_rate, inlet_pressure)``, with ``options.cavitation_pressure``,
    ``sliding`` and ``warm_start``. The Galerkin system of ``sup`` is not used."""
    max_iterations = max(int(options.max_iterations), MAX_ITERATIONS)
    return solve_jfo(sup.operators.mesh, sup.film, wedge=float(weights[0]), squeeze=tuple(weights[1:3]),
                     inlet_pressure=float(weights[3]), cavitation_pressure=options.cavitation_pressure,
                     sliding=options.sliding, warm_start=options.warm_start,
                     element=sup.operators.element, max_iterations=max_iterations)
