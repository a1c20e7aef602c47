r"""Film rupture: the Reynolds (Swift-Stieber) and Gumbel cavitation conditions.

The source paper lets the pressure go negative. A real film ruptures where
the pressure would fall below the (near-zero) cavity pressure. Two models:

``"reynolds"`` (Swift-Stieber)
    ``p >= 0`` everywhere, and on the free boundary of the ruptured region
    both ``p = 0`` and ``dp/dn = 0``. In weak form this is the obstacle
    problem (a linear complementarity problem) on the condensed unknowns
    ``u`` (``p`` for the direct form, ``Pi = h^(3/2) p`` for the pi form;
    ``Pi >= 0`` iff ``p >= 0`` since ``h > 0``)::

        A u - b = lam,   u >= 0,   lam >= 0,   u * lam = 0.

    The multiplier ``lam`` is the nodal residual of the Reynolds equation:
    zero where the film is full, and non-negative where it has ruptured.
    It is solved by the primal-dual active-set method (Hintermueller, Ito
    & Kunisch, SIAM J. Optim. 13 (2003) 865), which is a semismooth Newton
    method for ``min(u, lam) = 0``: each iteration solves the equation on
    the current full-film set with ``u = 0`` on the ruptured set, then moves
    nodes with ``u < 0`` to the ruptured set and nodes with ``lam < 0`` back.
    It stops when the set no longer changes (then complementarity holds to
    round-off) and raises :class:`CavitationError` at the iteration cap or
    on a cycle. Factorizations are cached per active set, so a warm start
    from a previous solution with the same rupture set costs one
    back-substitution.
``"gumbel"`` (half-Sommerfeld)
    the linear solution with its negative part discarded: cheap, not a
    solution of any conservation law, kept as the textbook comparison.

Mass balance under cavitation: the Swift-Stieber model does not conserve
mass in the ruptured zone (there ``p = 0`` and the Couette flow ``h/2``
does not satisfy ``d(h/2)/dphi + dh/dt = 0``). The boundary flows
(``side``, arc edges) count only what crosses the boundary: the ruptured
zone's source ``d(h/2)/dphi + dh/dt`` is removed from the nodal residuals
of the boundary dofs next to it (counted in, it would bias the side flow by
O(element size), 1-5 % of the side-flow ratio on ordinary meshes).
``flows["cavitation"]`` is the rest: the flow the full film hands to the
ruptured zone net of that zone's non-conservation (out of the film
positive), so that ``inlet = side + arc edges + squeeze + cavitation`` up to
discretization error. With Gumbel the residual at the clipped dofs is reported the same way,
but the interior residual of the kept region is not zero either: Gumbel is
not a conservative model.

Under cavitation the force is no longer linear in the squeeze rates; the
transient finds the rates that balance a load with :func:`rates_for_load`,
a Newton method on two unknowns started from the superposition answer whose
Jacobian comes from the same factorization (on the converged active set).

The table of models
-------------------
:data:`MODELS` maps a model name to its solver (as ``scipy.integrate``'s
``METHODS`` table maps names to integrators); it is read-only and
:data:`bearingfe.reynolds.CAVITATION` lists its keys. Every entry is a
callable with the contract

``solve(sup, weights, options) -> ReynoldsResult``

``sup`` : :class:`~bearingfe.film.superposition.Superposition`
    one film state, with everything built once for it: ``sup.operators``
    (mesh, basis, dofs, quadrature points ``x``), ``sup.at`` (the film at
    the quadrature points, :class:`~bearingfe.film.forms.FilmAt`),
    ``sup.system`` (:class:`~bearingfe.film.superposition.CondensedSystem`: the
    assembled condensed matrix, its factorization, the unit right sides
    and their Dirichlet data) and the linear unit ``fields``.
``weights`` : ndarray, shape (4,)
    the operating point as weights of the unit sources ``(wedge,
    gamma_rate, phi0_rate, inlet_pressure)``, already checked finite (and
    ``inlet_pressure >= 0`` for every model but ``"none"``) by
    :func:`solve_model`.
``options`` : :class:`ModelOptions`
    ``sliding``, ``warm_start``, ``solver`` and the iteration controls; a
    model reads the ones it uses. A new model that needs an option adds a
    field (with a default) to :class:`ModelOptions`.

It returns the :class:`~bearingfe.film.superposition.ReynoldsResult` built by
:func:`~bearingfe.film.result.build_result` from its unknown field, the
model name, its iteration count and its ruptured dofs, so that loads,
flows and friction are computed in one place for every model. A model that
changes the film (e.g. an elastic one) calls an entry again on the
superposition of the new film.
"""

from __future__ import annotations

import time
import weakref
from dataclasses import dataclass
from types import MappingProxyType
from typing import Callable, Mapping

import numpy as np
import scipy.sparse as sp

from ..film.finite_volume import solve_model_jfo
from ..core.linalg import DEFAULT_SOLVER, Factorize, get_linear_solver
from ..core.parameters import OperatingPoint, takes
from ..film import ReynoldsResult, Superposition, build_result, source_weights
from ..film.flows import ruptured_elements
from ..geometry.locate import containing_cells

__all__ = [
    "CavitationError",
    "MODELS",
    "ModelOptions",
    "ObstacleSolution",
    "ObstacleProblem",
    "FilmProblem",
    "obstacle_problem",
    "solve_model",
    "solve_cavitating",
    "rates_for_load",
    "RatesForLoad",
]

#: Default relative tolerance on the sign tests of the active-set iteration.
TOLERANCE = 1e-10
#: Default cap on active-set iterations.
MAX_ITERATIONS = 60


class CavitationError(RuntimeError):
    """The complementarity (cavitation) iteration did not converge."""


@dataclass(frozen=True, eq=False)
class ObstacleSolution:
    """Solution of ``A u - b = lam, u >= 0, lam >= 0, u lam = 0``.

    Attributes
    ----------
    u : ndarray
        Unknowns on the condensed (interior) dofs.
    multiplier : ndarray
        ``lam = A u - b`` (zero on the full-film set).
    active : ndarray of bool
        Ruptured (cavitated) dofs, where ``u = 0``.
    iterations : int
        Active-set iterations (linear solves) used.
    factorizations : int
        New factorizations among them (the rest came from the cache).
    """

    u: np.ndarray
    multiplier: np.ndarray
    active: np.ndarray
    iterations: int
    factorizations: int

    def complementarity(self) -> tuple[float, float, float]:
        """``(min u, min lam, max |u lam|)``: the three conditions to check."""
        return (float(self.u.min(initial=0.0)), float(self.multiplier.min(initial=0.0)),
                float(np.abs(self.u * self.multiplier).max(initial=0.0)))


class ObstacleProblem:
    """The condensed obstacle problem ``A u >= b`` type LCP with factorization reuse.

    Parameters
    ----------
    A : sparse matrix, shape (n, n)
        Condensed system matrix (interior dofs).
    factorize : callable
        ``factorize(A_FF) -> solve`` (see :mod:`bearingfe.core.linalg`).
    tol : float
        Relative tolerance of the sign tests (scaled by ``max |u|`` and
        ``max |b|``), guards against flipping nodes on round-off.
    max_iterations : int
        Cap on active-set iterations; beyond it :class:`CavitationError`.
    cache_size : int
        Number of factorizations (one per active set) kept.
    """

    def __init__(self, A: sp.spmatrix, factorize: Factorize, *, tol: float = TOLERANCE,
                 max_iterations: int = MAX_ITERATIONS, cache_size: int = 4) -> None:
        if not (0 < tol < 1e-2):
            raise ValueError(f"tol must be in (0, 1e-2), got {tol!r}")
        if not (isinstance(max_iterations, int) and max_iterations >= 1):
            raise ValueError(f"max_iterations must be an integer >= 1, got {max_iterations!r}")
        self.A = sp.csr_matrix(A)
        self.n = self.A.shape[0]
        self.factorize = factorize
        self.tol = float(tol)
        self.max_iterations = max_iterations
        self._cache: dict[bytes, object] = {}
        self._cache_size = int(cache_size)

    def _solver(self, free: np.ndarray):
        key = np.packbits(free).tobytes()
        if key in self._cache:
            return self._cache[key], 0
        idx = np.flatnonzero(free)
        solve = self.factorize(self.A[idx][:, idx]) if idx.size else (lambda b: np.zeros_like(b))
        if len(self._cache) >= self._cache_size:
            self._cache.pop(next(iter(self._cache)))
        self._cache[key] = solve
        return solve, 1

    def add_factorization(self, free: np.ndarray, solve) -> None:
        """Put a factorization of ``A[free][:, free]`` made elsewhere in the cache."""
        free = np.asarray(free, bool)
        if free.shape != (self.n,):
            raise ValueError(f"free must be a boolean mask of length {self.n}")
        if len(self._cache) >= self._cache_size:
            self._cache.pop(next(iter(self._cache)))
        self._cache[np.packbits(free).tobytes()] = solve

    def solve_fixed(self, b: np.ndarray, active: np.ndarray) -> np.ndarray:
        """Solve with ``u = 0`` on a given active set (the linearization on a
        fixed rupture set); ``b`` may have several columns."""
        free = ~np.asarray(active, bool)
        solve, _ = self._solver(free)
        b = np.asarray(b, float)
        u = np.zeros_like(b)
        if free.any():
            u[free] = np.asarray(solve(b[free])).reshape(b[free].shape)
        return u

    def solve(self, b: np.ndarray, active: np.ndarray | None = None) -> ObstacleSolution:
        """Primal-dual active-set iteration from an initial rupture set.

        Parameters
        ----------
        b : ndarray, shape (n,)
        active : ndarray of bool, optional
            Warm start (e.g. the rupture set of a previous solution, or
            where the unconstrained solution is negative); default empty.
        """
        b = np.asarray(b, float)
        if b.shape != (self.n,) or not np.all(np.isfinite(b)):
            raise ValueError(f"b must be a finite vector of length {self.n}")
        active = np.zeros(self.n, bool) if active is None else np.asarray(active, bool).copy()
        if active.shape != (self.n,):
            raise ValueError(f"active must be a boolean mask of length {self.n}")
        seen: set[bytes] = set()
        factorizations = 0
        scale_b = float(np.abs(b).max(initial=0.0))
        for it in range(1, self.max_iterations + 1):
            free = ~active
            solve, new = self._solver(free)
            factorizations += new
            u = np.zeros(self.n)
            if free.any():
                u[free] = solve(b[free])
            if not np.all(np.isfinite(u)):
                raise CavitationError("the linear solve on the full-film set returned non-finite values "
                                      "(singular operator: is the film region connected to a p = 0 edge?)")
            lam = self.A @ u - b
            lam[free] = 0.0
            tol_u = self.tol * float(np.abs(u).max(initial=0.0))
            tol_l = self.tol * max(scale_b, float(np.abs(lam).max(initial=0.0)))
            new_active = np.where(active, lam > -tol_l, u < -tol_u)
            if np.array_equal(new_active, active):
                return ObstacleSolution(u=u, multiplier=lam, active=active, iterations=it,
                                        factorizations=factorizations)
            seen.add(np.packbits(active).tobytes())
            key = np.packbits(new_active).tobytes()
            if key in seen:
                raise CavitationError(
                    f"cavitation active-set iteration cycles after {it} iterations "
                    f"({int(new_active.sum())} ruptured dofs): the discrete operator is far from an "
                    "M-matrix (try element='P1', formulation='direct' or a finer mesh)")
            active = new_active
        raise CavitationError(
            f"cavitation active-set iteration did not converge in {self.max_iterations} iterations "
            f"({int(active.sum())} ruptured dofs); raise max_iterations or check the mesh")


# -- the obstacle problem of a film state -------------------------------------------

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


def _warm_mask(fp: FilmProblem, sup: Superposition, wts: np.ndarray, warm_start) -> np.ndarray:
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


# -- the models and their table ------------------------------------------------------

@dataclass(frozen=True)
class ModelOptions:
    """Options of one model solve (see the module docstring for the contract).

    Attributes
    ----------
    sliding : float, optional
        Couette speed of the shear (default: the wedge weight).
    warm_start : ReynoldsResult or bool mask, optional
        A previous solution (any mesh of the same surface) or rupture mask
        to start the nonlinear iteration from.
    solver : str or callable
        Sparse solver for factorizations the model makes itself.
    tol : float
        Relative tolerance of the sign tests of the active-set iteration.
    max_iterations : int
        Cap on the model's iterations.
    cavitation_pressure : float
        Cavity pressure ``p_c`` [-] (gauge, ``<= 0``) of ``"jfo"``.
    """

    sliding: float | None = None
    warm_start: object = None
    solver: str | Factorize = DEFAULT_SOLVER
    tol: float = TOLERANCE
    max_iterations: int = MAX_ITERATIONS
    cavitation_pressure: float = 0.0


#: ``solve(sup, weights, options) -> ReynoldsResult`` (see the module docstring).
ModelSolver = Callable[[Superposition, np.ndarray, ModelOptions], ReynoldsResult]


def solve_linear(sup: Superposition, weights: np.ndarray, options: ModelOptions) -> ReynoldsResult:
    """``"none"``: the superposition itself; the pressure may go negative (the source paper)."""
    return sup.combine(weights[0], weights[1:3], weights[3], options.sliding)


def solve_gumbel(sup: Superposition, weights: np.ndarray, options: ModelOptions) -> ReynoldsResult:
    """``"gumbel"``: the linear solution with its negative part set to zero."""
    u = sup.fields @ weights
    cavitated = np.zeros(u.size, bool)
    cavitated[sup.operators.interior] = u[sup.operators.interior] < 0
    u = np.where(cavitated, 0.0, u)
    return build_result(sup, u, weights, options.sliding, cavitation="gumbel", cavitated=cavitated)


def solve_swift_stieber(sup: Superposition, weights: np.ndarray, options: ModelOptions) -> ReynoldsResult:
    """``"reynolds"``: ``p >= 0`` with a free boundary, by the primal-dual active-set method."""
    t0 = time.perf_counter()
    fp = obstacle_problem(sup, options.solver, tol=options.tol, max_iterations=options.max_iterations)
    sol = fp.problem.solve(fp.rhs @ weights, _warm_mask(fp, sup, weights, options.warm_start))
    cavitated = np.zeros(sup.operators.n_dofs, bool)
    cavitated[fp.interior] = sol.active
    cost = {"cavitation": time.perf_counter() - t0, "cavitation_factorizations": float(sol.factorizations)}
    return build_result(sup, sup.system.full(sol.u, weights), weights, options.sliding, cavitation="reynolds",
                        iterations=sol.iterations, cavitated=cavitated, extra_cost=cost)


#: The cavitation models by name (read-only): ``name -> solve(sup, weights, options)``.
MODELS: Mapping[str, ModelSolver] = MappingProxyType({
    "none": solve_linear,
    "reynolds": solve_swift_stieber,
    "gumbel": solve_gumbel,
    "jfo": solve_model_jfo,
})


def solve_model(sup: Superposition, weights: np.ndarray, model: str = "none",
                options: ModelOptions = ModelOptions()) -> ReynoldsResult:
    """Solve a film state at an operating point with a model of :data:`MODELS`.

    Parameters
    ----------
    sup : Superposition
    weights : array_like, shape (4,)
        ``(wedge, gamma_rate, phi0_rate, inlet_pressure)``.
    model : str
        A key of :data:`MODELS`.
    options : ModelOptions
    """
    if model not in MODELS:
        raise ValueError(f"cavitation model must be one of {tuple(MODELS)}, got {model!r}")
    weights = source_weights(weights[0], weights[1:3], weights[3])
    if model != "none" and weights[3] < 0:
        raise ValueError(f"inlet_pressure must be >= 0 with cavitation (p >= 0), got {weights[3]!r}")
    return MODELS[model](sup, weights, options)


@takes(OperatingPoint)
def solve_cavitating(sup: Superposition, wedge: float = 1.0, squeeze=(0.0, 0.0), inlet_pressure: float = 0.0,
                     sliding: float | None = None, *, model: str = "reynolds", warm_start=None,
                     solver: str | Factorize = DEFAULT_SOLVER, tol: float = TOLERANCE,
                     max_iterations: int = MAX_ITERATIONS) -> ReynoldsResult:
    """Solution of one film state with a cavitation model.

    Parameters
    ----------
    sup : Superposition
        The film state (:func:`bearingfe.superpose`); its linear fields are
        the default warm start (ruptured where the linear solution is negative).
    wedge, squeeze, inlet_pressure, sliding
        As in :func:`bearingfe.solve_reynolds` (or ``operating=`` an
        :class:`~bearingfe.core.parameters.OperatingPoint`).
    model : str
        A cavitation model of :data:`MODELS` (not ``"none"``): ``"reynolds"``
        or ``"gumbel"``.
    warm_start : ReynoldsResult or bool mask, optional
        Rupture set of a previous solution: on the same mesh (e.g. the
        previous time step), or a cavitated result on another mesh of the
        same surface (e.g. a coarser one: nested iteration), whose pressure
        is interpolated to this mesh's dofs.
    solver, tol, max_iterations
        Sparse solver, sign tolerance and iteration cap of the active-set
        method (:class:`ObstacleProblem`).

    Returns
    -------
    ReynoldsResult
        With ``cavitation``, ``iterations`` (active-set iterations) and
        ``cavitated`` (mask of ruptured dofs) filled in.

    Raises
    ------
    CavitationError
        If the active-set iteration does not converge within the cap.
    """
    wts = source_weights(wedge, squeeze, inlet_pressure)
    if model == "none" or model not in MODELS:
        raise ValueError(f"model must be one of {_CAVITATING}, got {model!r}")
    options = ModelOptions(sliding=sliding, warm_start=warm_start, solver=solver, tol=tol,
                           max_iterations=max_iterations)
    return solve_model(sup, wts, model, options)


_CAVITATING = tuple(name for name in MODELS if name != "none")


@dataclass(frozen=True, eq=False)
class RatesForLoad:
    """Squeeze rates that balance a load under cavitation.

    Attributes
    ----------
    rates : ndarray, shape (2,)
        ``(gamma_rate, phi0_rate)`` per radian of shaft turn.
    result : ReynoldsResult
        The cavitated solution at those rates.
    newton_iterations : int
    active_set_iterations : int
        Total over the Newton steps.
    residual : float
        ``|force + load|`` at the answer.
    """

    rates: np.ndarray
    result: ReynoldsResult
    newton_iterations: int
    active_set_iterations: int
    residual: float


@takes(OperatingPoint)
def rates_for_load(sup: Superposition, load, wedge: float = 1.0, inlet_pressure: float = 0.0, *,
                   model: str = "reynolds", warm_start=None, tol: float = 1e-9, max_newton: int = 30,
                   solver: str | Factorize = DEFAULT_SOLVER) -> RatesForLoad:
    """Squeeze rates at which the cavitated film force balances a load (``force + load = 0``).

    A Newton method on the two rates: the first guess is the superposition
    answer (:meth:`Superposition.rates_for_load`, no cavitation); each step
    solves the complementarity problem (warm-started from the last rupture
    set) and takes the Jacobian from the two squeeze unit fields on that
    rupture set, with the same factorization. The force is piecewise linear
    in the rates, so the iteration ends in finitely many steps once the
    rupture set settles; a backtracking line search guards the first steps.

    Parameters
    ----------
    sup : Superposition
    load : (float, float)
        Applied load in the arc frame [mu omega R0^4 / c^2].
    wedge, inlet_pressure : float
        Or ``operating=`` an :class:`~bearingfe.core.parameters.OperatingPoint`
        (its ``squeeze`` is what is solved for: leave it at zero).
    model : {"reynolds", "gumbel"}
    warm_start : optional
        As in :func:`solve_cavitating`.
    tol : float
        Relative tolerance on ``|force + load|`` (scaled by ``|load|`` and the
        wedge force).
    max_newton : int
        Cap; beyond it :class:`CavitationError`.
    """
    load = np.asarray(load, float)
    if load.shape != (2,) or not np.all(np.isfinite(load)):
        raise ValueError(f"load must be a finite pair, got {load!r}")
    if model not in ("reynolds", "gumbel"):
        raise ValueError(f"model must be 'reynolds' or 'gumbel', got {model!r}")
    rates = np.asarray(sup.rates_for_load(load, wedge, inlet_pressure), float)
    fp = obstacle_problem(sup, solver)
    scale = max(float(np.linalg.norm(load)), float(np.linalg.norm(sup.forces[:, 0] * wedge)), 1e-300)

    def evaluate(r, warm):
        res = solve_cavitating(sup, wedge, r, inlet_pressure, model=model, warm_start=warm, solver=solver)
        return res, res.force + load

    res, R = evaluate(rates, warm_start)
    total = res.iterations
    for k in range(1, max_newton + 1):
        if np.linalg.norm(R) <= tol * scale:
            return RatesForLoad(rates=rates, result=res, newton_iterations=k - 1,
                                active_set_iterations=total, residual=float(np.linalg.norm(R)))
        J = _rate_jacobian(sup, fp, res, model)
        try:
            step = -np.linalg.solve(J, R)
        except np.linalg.LinAlgError:
            raise CavitationError("the squeeze Jacobian is singular under cavitation "
                                  "(gamma = 0 leaves phi0_rate undetermined)") from None
        t = 1.0
        while True:
            trial, Rt = evaluate(rates + t * step, res)
            total += trial.iterations
            if np.linalg.norm(Rt) < (1 - 1e-4 * t) * np.linalg.norm(R) or t < 1e-3:
                break
            t *= 0.5
        rates, res, R = rates + t * step, trial, Rt
    raise CavitationError(f"rates_for_load: Newton did not converge in {max_newton} steps "
                          f"(|force + load| = {np.linalg.norm(R):.3g}, scale {scale:.3g})")


def _rate_jacobian(sup: Superposition, fp: FilmProblem, res: ReynoldsResult, model: str) -> np.ndarray:
    """d(force)/d(rates) on the current rupture set."""
    if model == "gumbel":
        keep = ~res.cavitated
        J = np.zeros((2, 2))
        for k in (1, 2):
            J[:, k - 1] = sup.loads(np.where(keep, sup.fields[:, k], 0.0))[0]
        return J
    active = res.cavitated[fp.interior]
    U = fp.problem.solve_fixed(fp.rhs[:, 1:3], active)
    J = np.zeros((2, 2))
    for k in range(2):
        u = np.zeros(sup.operators.n_dofs)
        u[fp.interior] = U[:, k]
        J[:, k] = sup.loads(u)[0]
    return J
