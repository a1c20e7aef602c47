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
    back-substitution. From a cold start the free boundary would move by
    about one layer of dofs per iteration (7 .. 52 iterations, each with a
    factorization, at 1e3 .. 1e5 unknowns); instead the start is the rupture
    set of nested coarse-grid problems (:mod:`bearingfe.cavitation.coarse`)
    and the steps after the first factorization are conjugate-gradient
    solves preconditioned with it (:class:`~bearingfe.cavitation.obstacle.ObstacleProblem`),
    which keeps the cost within a few factorizations at every size
    (``docs/benchmarks.md``, part ``cavitation``). If that path fails, the
    plain method runs and the result's ``notes`` say so.
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

import dataclasses
from dataclasses import dataclass
from types import MappingProxyType
from typing import Callable, Mapping, Sequence

import numpy as np

from .jfo import solve_model_jfo
from .obstacle import MAX_ITERATIONS, TOLERANCE
from .swift_stieber import solve_swift_stieber
from ..core.linalg import DEFAULT_SOLVER, Factorize
from ..core.parameters import OperatingPoint, takes
from ..film import ReynoldsResult, Superposition, build_result, source_weights
from ..film.pockets import PocketFilm, pocket_flows, pocket_unknown

__all__ = ["ModelOptions", "ModelSolver", "CavitationModel", "MODELS", "CAVITATION", "solve_model", "solve_cavitating",
           "solve_linear", "solve_gumbel", "solve_pocket_state"]


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


@dataclass(frozen=True)
class CavitationModel:
    """An entry of :data:`MODELS`: a model's solver on a finite-element film state, and what else it has.

    Called like its solver, ``model(sup, weights, options)``.

    Attributes
    ----------
    solve : ModelSolver
        ``solve(sup, weights, options) -> ReynoldsResult`` on a Galerkin film state.
    finite_element : bool
        The solver works on the Galerkin film state (False: it only hands the film
        to the finite-volume scheme).
    finite_volume : bool
        The finite-volume scheme of :mod:`bearingfe.film.finite_volume` solves it too,
        which is how recessed and periodic surfaces are solved.
    cavity_pressure : bool
        It takes a non-zero cavity pressure (on the finite-volume scheme).
    """

    solve: ModelSolver
    finite_element: bool = True
    finite_volume: bool = False
    cavity_pressure: bool = False

    def __call__(self, sup: Superposition, weights: np.ndarray, options: ModelOptions) -> ReynoldsResult:
        return self.solve(sup, weights, options)


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


#: The cavitation models by name (read-only).
MODELS: Mapping[str, CavitationModel] = MappingProxyType({
    "none": CavitationModel(solve_linear, finite_volume=True),
    "reynolds": CavitationModel(solve_swift_stieber, finite_volume=True, cavity_pressure=True),
    "gumbel": CavitationModel(solve_gumbel),
    "jfo": CavitationModel(solve_model_jfo, finite_element=False, finite_volume=True, cavity_pressure=True),
})
#: Names of the cavitation models (the keys of :data:`MODELS`).
CAVITATION = tuple(MODELS)


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


def solve_pocket_state(pf: PocketFilm, names: Sequence[str], pressures: np.ndarray, operating: OperatingPoint,
                       cavitation: str, options: ModelOptions) -> ReynoldsResult:
    """The film of ``pf`` with each pocket at its own pressure [-], under a cavitation model.

    The inlet column of :meth:`PocketFilm.state` holds the pockets at their pressures (weight 1); the
    result's loads count each pocket at its own pressure, its ``flows`` hold each pocket's film outflow
    under its name beside the total ``"inlet"``, and its ``inlet_pressure`` is the largest pocket pressure.
    """
    p = np.asarray(pressures, float)
    weights = np.array([operating.wedge, *operating.squeeze, 1.0])
    res = solve_model(pf.state(p), weights, cavitation, options)
    u = pocket_unknown(pf.whole, res)
    cav = None if res.cavitated is None else res.cavitated[:, None]
    q = pocket_flows(pf, u[:, None], weights[:, None], cav)[:, 0]
    if res.cavitated is not None:  # the model's loads count the pockets at the column's unit weight
        force, integral = pf.whole.loads(u, 0.0)
        moments = pf.pocket_moments(p)
        res = dataclasses.replace(res, force=force + moments[1:], integral=integral + moments[0])
    flows = MappingProxyType({**res.flows, **{n: float(qk) for n, qk in zip(names, q)}})
    return dataclasses.replace(res, flows=flows, inlet_pressure=float(np.max(p)))
