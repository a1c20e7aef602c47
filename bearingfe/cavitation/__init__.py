"""Cavitation models and their table (``MODELS``).

================  ============================================================
module            what it does
================  ============================================================
``models``        Film rupture: the Reynolds (Swift-Stieber) and Gumbel cavitation conditions.
================  ============================================================
"""

from __future__ import annotations
from .models import (CavitationError, MODELS, ModelOptions, ObstacleSolution, ObstacleProblem, FilmProblem, obstacle_problem, solve_model, solve_cavitating, rates_for_load, RatesForLoad)

__all__ = ['CavitationError', 'MODELS', 'ModelOptions', 'ObstacleSolution', 'ObstacleProblem', 'FilmProblem', 'obstacle_problem', 'solve_model', 'solve_cavitating', 'rates_for_load', 'RatesForLoad']
