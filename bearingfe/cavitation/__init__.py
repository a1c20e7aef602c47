"""Cavitation models and their table (:data:`MODELS`): where and how a film ruptures.

:data:`MODELS` maps a model name to a :class:`CavitationModel` (its solver on a
finite-element film state, and whether the finite-volume scheme solves it too);
:func:`bearingfe.solve_reynolds` consults it. The contract every entry meets is in
:mod:`bearingfe.cavitation.models`.

=================  ==============================================================
module             what it does
=================  ==============================================================
``obstacle``       the obstacle problem on a condensed system (primal-dual active set)
``coarse``         its cold start by nested iteration on coarse-grid Galerkin problems
``swift_stieber``  ``p >= 0`` with a free boundary on a film state; warm and nested starts
``jfo``            mass-conserving (JFO) cavitation as a table entry (finite volumes)
``models``         the table :data:`MODELS`, its contract, the linear and Gumbel models
``rates``          squeeze rates that balance a load under cavitation (Newton)
=================  ==============================================================
"""

from __future__ import annotations

from .obstacle import CavitationError, ObstacleProblem, ObstacleSolution
from .swift_stieber import FilmProblem, obstacle_problem
from .models import CAVITATION, MODELS, CavitationModel, ModelOptions, solve_cavitating, solve_model
from .rates import RatesForLoad, rates_for_load

__all__ = ["CavitationError", "ObstacleProblem", "ObstacleSolution", "FilmProblem", "obstacle_problem", "CAVITATION",
           "MODELS", "CavitationModel", "ModelOptions", "solve_cavitating", "solve_model", "RatesForLoad",
           "rates_for_load"]
