r"""The Swift-Stieber (Reynolds) cavitation condition on a film state: ``p >= 0`` with a free boundary.

On the condensed unknowns ``u`` of a film state (``p`` for the direct form,
``Pi = h^(3/2) p`` for the pi form: ``Pi >= 0`` iff ``p >= 0`` since ``h > 0``)
the condition is the obstacle problem of :mod:`bearingfe.cavitation.obstacle`,
posed on the superposition's own condensed matrix and started with its
factorization of the full film. The multiplier is the nodal residual of the
Reynolds equation: zero where the film is full, non-negative where it ruptured.

Warm starts: the rupture set of a previous solution on the same mesh (the
previous time step), or of a solution on another mesh of the same surface
(nested iteration: a new dof is ruptured if it lies in a ruptured element of the
previous mesh), which keeps the active-set count bounded under refinement.
"""

from __future__ import annotations

import time
import weakref
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np

from .coarse import NESTED_MIN, nested_start
from .obstacle import MAX_ITERATIONS, TOLERANCE, CavitationError, ObstacleProblem
from ..core.linalg import DEFAULT_SOLVER, Factorize, get_linear_solver
from ..film import ReynoldsResult, Superposition, build_result
from ..film.flows import ruptured_elements
from ..geometry.locate import containing_cells

if TYPE_CHECKING:
    from .models import ModelOptions

__all__ = ["FilmProblem", "obstacle_problem", "solve_swift_stieber", "warm_mask"]

@dataclass(frozen=True, eq=False)
class FilmProblem:
    """The complementarity problem of a film state on its condensed system.

    Attributes
    ----------
    problem : ObstacleProblem
        On ``sup.system.matrix`` (no reassembly); its cache starts with the
        superposition's own factorization of the full-film set.
    interior, boundary : ndarray of int
    rhs : ndarray, shape (n_interior, 4)
        Unit right sides of the condensed system.
    lift : ndarray, shape (n_dofs, 4)
        Dirichlet data of the unit sources.
    """

    problem: ObstacleProblem
    interior: np.ndarray
    boundary: np.ndarray
    rhs: np.ndarray
    lift: np.ndarray


_PROBLEMS: "weakref.WeakKeyDictionary[Superposition, FilmProblem]" = weakref.WeakKeyDictionary()


def obstacle_problem(sup: Superposition, solver: str | Factorize = DEFAULT_SOLVER, *,
                     tol: float = TOLERANCE, max_iterations: int = MAX_ITERATIONS) -> FilmProblem:
    """The condensed complementarity problem of a film state (cached per superposition)."""
    cached = _PROBLEMS.get(sup)
    if cached is not None and cached.problem.tol == tol and cached.problem.max_iterations == max_iterations:
        return cached
    system = sup.system
    factorize = get_linear_solver(solver)
    problem = ObstacleProblem(system.matrix, factorize, tol=tol, max_iterations=max_iterations)
    if factorize is system.factorize:
        problem.add_factorization(np.ones(problem.n, bool), system.solve)
    fp = FilmProblem(problem=problem, interior=system.interior, boundary=system.boundary, rhs=system.rhs,
                     lift=system.lift)
    _PROBLEMS[sup] = fp
    return fp


def warm_mask(fp: FilmProblem, sup: Superposition, wts: np.ndarray, warm_start) -> np.ndarray:
    if warm_start is None:
        return (sup.fields @ wts)[fp.interior] < 0.0
    basis = sup.operators.basis
    if isinstance(warm_start, ReynoldsResult) and warm_start.cavitated is not None \
            and warm_start.basis is not basis and warm_start.basis.mesh is not basis.mesh:
        return _transferred_mask(warm_start, basis)[fp.interior]
    mask = warm_start.cavitated if isinstance(warm_start, ReynoldsResult) else warm_start
    mask = np.asarray(mask, bool) if mask is not None else None
    if mask is None or mask.shape != (sup.operators.n_dofs,):
        raise ValueError("warm_start must be a cavitated ReynoldsResult (on any mesh of the same surface) "
                         f"or a boolean mask of length {sup.operators.n_dofs}")
    return mask[fp.interior]


def _transferred_mask(previous: ReynoldsResult, basis) -> np.ndarray:
    """Rupture set of ``previous`` carried to the dofs of ``basis`` (another mesh of the same surface).

    A new dof is ruptured if it lies in an element of the previous mesh
    whose pressure is zero throughout (a ruptured element). This is the
    nested-iteration start that keeps the active-set count bounded under
    refinement: the free boundary is then wrong by about one coarse element
    instead of by the whole difference between the Gumbel and the
    Swift-Stieber rupture sets. Dofs outside the previous mesh start full.
    """
    old = previous.basis
    ruptured = ruptured_elements(old.element_dofs, np.asarray(previous.pressure), previous.cavitated)
    cells = containing_cells(old.mesh.p, old.mesh.t, np.asarray(basis.doflocs))
    return np.where(cells >= 0, ruptured[np.maximum(cells, 0)], False)


def solve_swift_stieber(sup: Superposition, weights: np.ndarray, options: "ModelOptions") -> ReynoldsResult:
    """``"reynolds"``: ``p >= 0`` with a free boundary, by the primal-dual active-set method.

    Without a warm start, a system of :data:`~bearingfe.cavitation.coarse.NESTED_MIN`
    unknowns or more starts from the rupture set of nested coarse-grid problems
    (:func:`~bearingfe.cavitation.coarse.nested_start`), and the active-set steps
    reuse the last factorization as a preconditioner (:class:`ObstacleProblem`).
    Should that path fail (a coarse problem or the iteration from its start not
    converging), the plain method is run from the default start and the result's
    ``notes`` say so.
    """
    t0 = time.perf_counter()
    fp = obstacle_problem(sup, options.solver, tol=options.tol, max_iterations=options.max_iterations)
    b = fp.rhs @ weights
    start = warm_mask(fp, sup, weights, options.warm_start)
    cost = {}
    notes = ()
    krylov = fp.problem.krylov_iterations
    if options.warm_start is None and fp.problem.n >= NESTED_MIN:
        points = np.asarray(sup.operators.basis.doflocs)[:, fp.interior].T
        try:
            start, info = nested_start(fp.problem.A, b, points, fp.problem.factorize, tol=options.tol,
                                       max_iterations=options.max_iterations)
            cost["cavitation_coarse_iterations"] = float(info["coarse_iterations"])
        except (CavitationError, RuntimeError, ValueError, np.linalg.LinAlgError) as exc:
            # a coarse problem failed (e.g. a singular coarse matrix): start from the default set
            notes += (f"cavitation: the coarse-grid start failed ({exc}); started from the linear solution",)
            cost["cavitation_fallback"] = 1.0
        cost["cavitation_coarse"] = time.perf_counter() - t0
    try:
        sol = fp.problem.solve(b, start)
    except CavitationError as exc:
        if not fp.problem.reuse and options.warm_start is not None:
            raise
        # the plain method: a factorization per active set, from the default start
        plain = ObstacleProblem(fp.problem.A, fp.problem.factorize, tol=options.tol,
                                max_iterations=options.max_iterations, reuse=False)
        sol = plain.solve(b, warm_mask(fp, sup, weights, options.warm_start))
        notes += (f"cavitation: the nested/reused-factorization path failed ({exc}); solved by the plain "
                  "active-set method",)
        cost["cavitation_fallback"] = 1.0
    cavitated = np.zeros(sup.operators.n_dofs, bool)
    cavitated[fp.interior] = sol.active
    cost.update({"cavitation": time.perf_counter() - t0, "cavitation_factorizations": float(sol.factorizations),
                 "cavitation_krylov_iterations": float(fp.problem.krylov_iterations - krylov)})
    res = build_result(sup, sup.system.full(sol.u, weights), weights, options.sliding, cavitation="reynolds",
                       iterations=sol.iterations, cavitated=cavitated, extra_cost=cost)
    return replace(res, notes=res.notes + notes) if notes else res
