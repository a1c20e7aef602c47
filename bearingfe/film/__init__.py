"""One film state of the Reynolds equation: film models, weak forms, the compiled operator, superposition and results, and the finite-difference and finite-volume discretizations.

================  ============================================================
module            what it does
================  ============================================================
``thickness``     Film-thickness models.
``forms``         The Reynolds equation's weak forms and pointwise formulas, written once.
``compiled``      Compiled film operator: the film-independent linear maps of a mesh and element, built once.
``superposition`` One film state of the finite-element Reynolds equation: operators, condensed system, results.
``fd``            Finite-difference reference solver of the Reynolds equation (paper 004's method).
``finite_volume`` Mass-conserving cavitation: the Jakobsson-Floberg-Olsson (JFO) model in Elrod-Adams p-theta form.
================  ============================================================
"""

from __future__ import annotations

from .thickness import CosineFilm, Film, UniformFilm
from .superposition import (SOURCES, CoercivityError, Operators, ReynoldsResult, Superposition, film_outputs, operators,
                            source_weights, superpose)
from .finite_volume import JFOError, solve_jfo
from .fd import FDResult, solve_reynolds_fd

__all__ = ["CosineFilm", "Film", "UniformFilm", "SOURCES", "CoercivityError", "Operators", "ReynoldsResult",
           "Superposition", "film_outputs", "operators", "source_weights", "superpose", "JFOError", "solve_jfo",
           "FDResult", "solve_reynolds_fd"]
