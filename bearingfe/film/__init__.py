"""One film state of the Reynolds equation: film models, weak forms, the compiled operator, superposition and results, and the finite-difference and finite-volume discretizations.

================  ============================================================
module            what it does
================  ============================================================
``thickness``     Film-thickness models.
``forms``         The Reynolds equation's weak forms and pointwise formulas, written once.
``compiled``      Compiled film operator: the film-independent linear maps of a mesh and element, built once.
``mesh_operators`` Everything about a mesh and an element that does not depend on the film, built once.
``assembly``      How a film state's system is assembled: one interface, two implementations, one table.
``reference``     The reference assembly: the film system, loads and flows by scikit-fem form assembly.
``superposition`` One film state of the finite-element Reynolds equation: operators, condensed system, results.
``result``        The result of one film state and the one place that builds it.
``estimate``      How far a solve's load is from converged: the once-refined comparison (Richardson).
``flows``         Named film flows, written once for every discretization and every transient.
``pockets``       The pockets as unknowns: their names, one pressure per pocket, one unit field per pocket.
``fd``            Finite-difference reference solver of the Reynolds equation (paper 004's method).
``finite_volume`` Mass-conserving cavitation: the Jakobsson-Floberg-Olsson (JFO) model in Elrod-Adams p-theta form.
``polar_fd``      Finite-difference reference of a thrust pad's film on a polar grid (an independent check of the FEM).
================  ============================================================
"""

from __future__ import annotations

from .thickness import (CosineFilm, Film, PlaneFilm, PolarProfileFilm, ProfileFilm, StepFilm, SumFilm, TaperFilm,
                        TaperLandFilm, UniformFilm, is_smooth, smallest_film)
from .mesh_operators import Operators, operators
from .assembly import ASSEMBLIES
from .superposition import SOURCES, CoercivityError, CondensedSystem, Superposition, source_weights, superpose
from .result import ReynoldsResult, build_result, film_outputs
from .estimate import ERROR_TOLERANCE, LOAD_ORDERS, LoadError, load_error, load_order
from .finite_volume import JFOError, solve_jfo
from .fd import FDResult, solve_reynolds_fd

__all__ = ["CosineFilm", "Film", "PlaneFilm", "PolarProfileFilm", "ProfileFilm", "StepFilm", "SumFilm", "TaperFilm", "TaperLandFilm", "UniformFilm",
           "is_smooth", "smallest_film", "Operators", "operators", "ASSEMBLIES", "SOURCES",
           "CoercivityError", "CondensedSystem", "Superposition", "source_weights", "superpose", "ReynoldsResult",
           "build_result", "film_outputs", "ERROR_TOLERANCE", "LOAD_ORDERS", "LoadError", "load_error", "load_order", "JFOError", "solve_jfo", "FDResult", "solve_reynolds_fd"]
