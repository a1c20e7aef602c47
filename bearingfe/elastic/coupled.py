r"""The coupled (EHD) film: the Reynolds equation on a film opened by its own pressure.

Coupled solve
-------------
``h = h_rigid + C p(h)`` is solved for the nodal deflection ``w`` by
Newton's method on ``F(w) = C p(h_rigid + w) - w``, with the Jacobian
``C dp/dw - I`` from the linearized Reynolds operator
(:func:`pressure_sensitivity`; semismooth on the rupture set under
cavitation) and backtracking. A plain fixed point ``w -> C p`` diverges as
soon as the film is thin where the pressure is high (``p ~ h^-2``: the
classical EHD instability), which the pump reaches. Convergence test:
``max |C p(h_rigid + w) - w| <= tol`` (clearance units; default ``1e-8``)
at the returned state; :class:`ElasticError` otherwise.

Matrix-free (Newton-Krylov)
---------------------------
With a compliance held as its product only (``Compliance.matrix is None``, the
FFT half-space of :mod:`bearingfe.elastic.convolution`) the Jacobian is never
formed: the Newton step solves ``(I - C dp/dw) dw = F`` by GMRES, each product
costing one FFT convolution and one solve with the factors of the film's
Reynolds matrix ``A_FF`` (``dp/dw v = -A_FF^-1 B_F v``): the superposition's own
factors when no dof is ruptured, else one factorization per Jacobian (under
Swift-Stieber the cavitation problem's of the free set, which then preconditions
the next state's active-set steps of :func:`solve_elastic`). The Jacobian is
taken afresh at every step (full Newton, not the dense path's chord). This is GMRES on the pressure form ``A + B_h C`` right-preconditioned
by the film's own factorization (``(A + B_h C) A^-1 = I + B_h C A^-1`` has the
spectrum of ``I - C dp/dw``). Memory and time then grow like the film
(``O(N log N)`` per product), and the dense-size cap does not apply. The GMRES
tolerance is relative, ``min(1e-2, max |F|)`` (inexact Newton: superlinear
near the answer); the convergence test is the same as the dense path's.
The deflected film is a nodal field (its Laplacian is not a function), so
the direct form of the Reynolds equation is used; any cavitation model
works (the solve is called as a black box, warm-started from the previous
rupture set; under Swift-Stieber only within :data:`WARM_MOVE` of its deflection,
else from the model's cold start). The deflection is quasi-static: ``dw/dt`` does not enter the
squeeze term (the squeeze rates are those of the rigid state variables).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import BilinearForm

from .compliance import MAX_ITERATIONS, TOLERANCE, Compliance, ElasticError, check_dense_size
from .krylov import RESTART, gmres
from ..cavitation import MODELS, ModelOptions, rates_for_load, solve_model
from ..cavitation.swift_stieber import cached_problem, obstacle_problem
from ..core.checks import check_elastic, check_operating_point, note_resolution
from ..core.linalg import DEFAULT_SOLVER, dense_threads
from ..core.pages import small_pages
from ..core.parameters import Discretization, OperatingPoint, takes
from ..film import Film, operators, source_weights, superpose
from ..film.compiled import interpolation_maps
from ..film.forms import load as load_form, weighted_laplace
from ..geometry.locate import probe_matrices
from ..geometry.meshing import SupportMesh
from ..geometry.runner import require_along_phi

__all__ = ["DeflectedFilm", "ElasticSolution", "solve_elastic", "pocket_deflections", "balance_load", "ElasticBalance", "ChordBalance",
           "pressure_sensitivity", "sensitivity_operator", "newton", "solve_rigid_h_min"]

# -- the deflected film ----------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class _Evaluator:
    """Evaluation of nodal fields of one basis at point sets (cached per point set)."""

    basis: object
    quadrature: np.ndarray
    cache: dict = field(default_factory=dict)

    def at(self, x: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        if x.shape == self.quadrature.shape and np.array_equal(x, self.quadrature):
            if "quadrature" not in self.cache:  # the basis's own points: exact sparse maps, no cell search
                self.cache["quadrature"] = interpolation_maps(self.basis)
            shape = x.shape[1:]
            return tuple((P @ w).reshape(shape) for P in self.cache["quadrature"])
        flat = x.reshape(2, -1)
        key = (flat.shape, hash(flat.tobytes()))
        if key not in self.cache:
            if len(self.cache) > 16:
                kept = self.cache.get("quadrature")
                self.cache.clear()
                if kept is not None:
                    self.cache["quadrature"] = kept
            self.cache[key] = probe_matrices(self.basis, flat)
        shape = x.shape[1:]
        return tuple((P @ w).reshape(shape) for P in self.cache[key])


_EVALUATORS: dict = {}


def _evaluator(basis) -> _Evaluator:
    ev = _EVALUATORS.get(id(basis))
    if ev is None or ev.basis is not basis:
        if len(_EVALUATORS) > 8:
            _EVALUATORS.clear()
        ev = _Evaluator(basis, np.array(basis.global_coordinates()))
        _EVALUATORS[id(basis)] = ev
    return ev


@dataclass(frozen=True, eq=False)
class DeflectedFilm:
    """A rigid film opened by a nodal deflection field: ``h = rigid.h + w`` [c].

    Implements the :class:`bearingfe.Film` protocol. The squeeze shapes are
    the rigid film's (quasi-static deflection). ``laplacian`` returns the
    rigid film's: the Laplacian of a piecewise-polynomial field is not a
    function, which is why the coupled solve uses the direct form.

    Parameters
    ----------
    rigid : Film
    basis : skfem.CellBasis
        The basis of the deflection dofs (the Reynolds basis of the mesh).
    deflection : ndarray, shape (basis.N,)
        Film opening ``w`` [c] at the dofs.
    """

    rigid: Film
    basis: object
    deflection: np.ndarray

    def __post_init__(self) -> None:
        w = np.asarray(self.deflection, float)
        if w.shape != (self.basis.N,) or not np.all(np.isfinite(w)):
            raise ValueError(f"deflection must be {self.basis.N} finite values (one per dof), got shape {w.shape}")
        object.__setattr__(self, "deflection", w)

    @property
    def max_deflection(self) -> float:
        """Largest film opening [c] at the dofs."""
        return float(self.deflection.max(initial=0.0))

    def _at(self, phi, z):
        phi, z = np.broadcast_arrays(np.asarray(phi, float), np.asarray(z, float))
        return _evaluator(self.basis).at(np.array([phi, z]), self.deflection)

    def thickness(self, phi, z):
        return np.asarray(self.rigid.thickness(phi, z)) + self._at(phi, z)[0]

    def gradient(self, phi, z):
        g = self.rigid.gradient(phi, z)
        _, wx, wy = self._at(phi, z)
        return np.asarray(g[0]) + wx, np.asarray(g[1]) + wy

    def laplacian(self, phi, z):
        return self.rigid.laplacian(phi, z)

    def rate_shapes(self, phi, z):
        return self.rigid.rate_shapes(phi, z)

    def minimum(self, phi_range):
        return None


# -- the coupled iteration --------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class Coupled:
    """Converged fixed point ``w = g(w)`` of the coupled film.

    Attributes
    ----------
    deflection : ndarray
        ``w`` [c] at the dofs.
    payload : object
        What ``g`` returned beside ``g(w)`` at the converged state (the film solution).
    iterations : int
        Evaluations of ``g`` (one Reynolds solve each).
    residual : float
        ``max |g(w) - w|`` [c] at the returned state.
    history : tuple of float
        The residual after each accepted step.
    jacobians : int
        Jacobians built (the others were reused).
    krylov_iterations : int
        GMRES iterations (Jacobian products) over all steps (matrix-free path; 0 for dense Jacobians).
    """

    deflection: np.ndarray
    payload: object
    iterations: int
    residual: float
    history: tuple[float, ...]
    jacobians: int = 0
    krylov_iterations: int = 0


def newton(evaluate, jacobian, w0: np.ndarray, *, tol: float = TOLERANCE,
           max_iterations: int = MAX_ITERATIONS, reuse: dict | None = None) -> Coupled:
    """Newton's method on ``F(w) = g(w) - w = 0`` with backtracking and a stated convergence test.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(w) -> (g(w), payload)``; raises :class:`ElasticError` if
        the film closes at ``w`` (then the step is halved).
    jacobian : callable
        ``jacobian(w, payload) -> dg/dw``: dense (n x n), or a
        :class:`scipy.sparse.linalg.LinearOperator` (its products only: the
        step is then solved by GMRES, see the module notes, the Jacobian is
        taken afresh at every step, and ``reuse`` keeps no factors).
    w0 : ndarray
        Start (zero, or the deflection of a nearby state).
    tol : float
        Stop when ``max |g(w) - w| <= tol`` [c].
    max_iterations : int
        Cap on evaluations of ``g``; beyond it :class:`ElasticError`.
    reuse : dict, optional
        Holder of the LU factors of ``dg/dw - I`` between calls (a run of
        nearby states, e.g. the pump transient): steps start with the old
        factors (a chord step) and the Jacobian is rebuilt only when a step
        reduces ``max |F|`` by less than 4x.

    Notes
    -----
    A full step is taken when it reduces ``|F|_2`` (or meets the tolerance);
    else it is halved down to 1/1024. Under a cavitation condition ``g`` is
    piecewise smooth and this is a semismooth Newton method on the current
    rupture set.
    """
    if not (0 < tol < 1):
        raise ValueError(f"tol must be in (0, 1) [clearance], got {tol!r}")
    if not (isinstance(max_iterations, int) and max_iterations >= 1):
        raise ValueError(f"max_iterations must be an integer >= 1, got {max_iterations!r}")
    with dense_threads(1):  # dense n x n algebra: threads only wait for each other on a busy machine
        return _newton(evaluate, jacobian, w0, tol, max_iterations, reuse)


def _newton(evaluate, jacobian, w0: np.ndarray, tol: float, max_iterations: int, reuse: dict | None) -> Coupled:
    """The iteration of :func:`newton` (arguments checked there)."""
    import scipy.linalg as sla

    w = np.asarray(w0, float).copy()
    g, payload = evaluate(w)
    F = g - w
    history = [float(np.abs(F).max(initial=0.0))]
    count, jacobians, products = 1, 0, [0]
    lu = None if reuse is None else reuse.get("lu")
    if lu is not None and lu[0].shape[0] != w.size:
        lu = None
    while history[-1] > tol:
        if count >= max_iterations:
            raise ElasticError(
                f"the elastic film (EHD) iteration did not converge in {max_iterations} solves: "
                f"max |C p - w| = {history[-1]:.3g} c > tol = {tol:.3g} c (last residuals "
                f"{', '.join(f'{h:.2g}' for h in history[-4:])}); the support may be too soft for this "
                "load (deflection much larger than the film): raise max_iterations or check the modulus")
        fresh = lu is None
        if fresh:
            J = jacobian(w, payload)
            if isinstance(J, spla.LinearOperator):
                lu = (_KRYLOV, J)
            else:
                lu = sla.lu_factor(J - np.eye(w.size), check_finite=False)
            jacobians += 1
        if lu[0] is _KRYLOV:
            step = _krylov_step(lu[1], F, history[-1], products)
        else:
            step = -sla.lu_solve(lu, F, check_finite=False)
        if not np.all(np.isfinite(step)):
            raise ElasticError("the Jacobian of the elastic film is singular (I - C dp/dw): no unique "
                               "deflection at this state")
        t, norm, accepted = 1.0, float(np.linalg.norm(F)), False
        while True:
            count += 1
            try:
                g_t, payload_t = evaluate(w + t * step)
                F_t = g_t - (w + t * step)
                if np.linalg.norm(F_t) < (1 - 1e-4 * t) * norm or np.abs(F_t).max() <= tol:
                    accepted = True
                    break
            except ElasticError:
                pass
            if not fresh:
                break  # an old Jacobian: rebuild it rather than shorten the step
            t *= 0.5
            if t < 1e-3 or count >= max_iterations:
                raise ElasticError(
                    f"the elastic film (EHD) Newton step found no decrease of max |C p - w| = "
                    f"{history[-1]:.3g} c after {count} solves (the film closes or the rupture set jumps "
                    "along the step); the support may be too soft for this load")
        if not accepted:
            lu = None
            continue
        w, payload, F = w + t * step, payload_t, F_t
        history.append(float(np.abs(F).max(initial=0.0)))
        if not fresh and history[-1] > 0.25 * history[-2]:
            lu = None
        elif lu[0] is _KRYLOV and history[-1] > tol:
            lu = None  # a matrix-free Jacobian costs no factorization of its own: take a fresh one (full Newton)
    if reuse is not None:
        reuse["lu"] = None if (lu is not None and lu[0] is _KRYLOV) else lu
    return Coupled(deflection=w, payload=payload, iterations=count, residual=history[-1],
                   history=tuple(history), jacobians=jacobians, krylov_iterations=products[0])


_KRYLOV = np.empty((0, 0))  # marks a matrix-free Jacobian in place of LU factors (its shape never matches)


def _krylov_step(J: spla.LinearOperator, F: np.ndarray, residual: float, products: list) -> np.ndarray:
    """The Newton step ``(dg/dw - I) s = -F`` by GMRES on the products of ``dg/dw`` (inexact Newton: at most
    ``KRYLOV_CYCLES`` restart cycles; a step short of its tolerance is judged by the backtracking)."""

    def matvec(v):
        products[0] += 1
        return J.matvec(v) - v

    step, _ = gmres(matvec, -F, rtol=min(1e-2, max(residual, 1e-12)), what="the elastic film's Jacobian (I - C dp/dw)",
                    max_iterations=KRYLOV_CYCLES * min(F.size, RESTART), must_converge=False)
    return step


#: Restart cycles of GMRES in one inexact Newton step of the coupled film.
KRYLOV_CYCLES = 20


#: Largest change of the deflection [c] since the last cavitated state at which :func:`solve_elastic` starts
#: the next state's Swift-Stieber rupture set from that one's (preconditioned by the last Jacobian's factors);
#: beyond it the cavitation model's cold start (nested coarse grids). Measured on the 'elastic P1' kind at 3e4 unknowns
#: (Newton moves of 0.17, 0.097, 0.012, 1.4e-4 c): from the warm set the first two took 30 and 15 active-set steps
#: with 9 and 4 factorizations of 3e4 unknowns (the cavity shrinking a layer a step), from the cold start 4 and 3
#: steps with one; the third took 4 steps and no factorization warm against the coarse grids' and one cold.
WARM_MOVE = 0.05


@BilinearForm
def _film_sensitivity(u, v, w):
    # d/dh_j of int h^3 grad p . grad v_i - int 6 wedge h dv_i/dphi (the wedge in conservative form,
    # bearingfe.film.forms.couette_source), for h = ... + w_j phi_j
    return 3.0 * w.h2 * u * (w.gp0 * v.grad[0] + w.gp1 * v.grad[1]) - 6.0 * w.wedge * u * v.grad[0]


def pressure_sensitivity(basis, film: Film, pressure: np.ndarray, wedge: float, free: np.ndarray, *,
                         rates_balance: bool = False) -> np.ndarray:
    """``dp/dw``: change of the nodal pressure with the nodal film opening (direct form).

    Linearization of ``int h^3 grad p . grad v - int 6 wedge h dv/dphi + int 12 dh/dt v = 0``
    at the solution ``pressure`` on ``film`` (a :class:`DeflectedFilm`) with
    ``p`` held at its Dirichlet values and on the ruptured set, i.e.
    ``dp_F/dw = -A_FF^-1 B_F``. With ``rates_balance`` the squeeze rates move
    with ``w`` so that the film force stays the same (the transient's load
    balance): ``dp/dw + U dr/dw`` with the unit squeeze fields ``U`` on the same set.

    Parameters
    ----------
    basis : skfem.CellBasis
    film : Film
    pressure : ndarray
        Nodal pressure [-].
    wedge : float
    free : ndarray of bool
        Dofs where the pressure is an unknown (interior, not ruptured).

    Returns
    -------
    ndarray, shape (n_dofs, n_dofs)
    """
    return sensitivity_operator(basis, film, pressure, wedge, free, rates_balance=rates_balance)(np.eye(basis.N))


def sensitivity_operator(basis, film: Film, pressure: np.ndarray, wedge: float, free: np.ndarray, *,
                         rates_balance: bool = False, system=None, problem=None):
    """``v -> (dp/dw) v`` without forming ``dp/dw`` (:func:`pressure_sensitivity`'s products).

    One sparse factorization of ``A_FF`` at the call (none when ``system``, the
    :class:`~bearingfe.film.superposition.CondensedSystem` of the same film in
    the direct form, already factors it: its interior is the free set); each
    product is a sparse product and one solve with those factors. ``problem``:
    the Swift-Stieber :class:`~bearingfe.cavitation.FilmProblem` of the same
    film state on P1 (its matrix is ``A[I, I]``), whose factorization of the
    free set is taken (the one its active-set iteration ended on, else one made
    there in the film's fill-reducing order and kept). ``v`` of shape
    ``(n_dofs,)`` or ``(n_dofs, k)``.
    """
    x = np.array(basis.global_coordinates())
    h = np.asarray(film.thickness(x[0], x[1]))
    gp = basis.interpolate(pressure).grad
    A = weighted_laplace.assemble(basis, c=h**3).tocsr()
    B = _film_sensitivity.assemble(basis, h2=h**2, gp0=gp[0], gp1=gp[1], wedge=np.full(h.shape, float(wedge)))
    idx = np.flatnonzero(free)
    n = basis.N
    if not idx.size:
        return lambda v: np.zeros(np.shape(v))
    if system is not None and np.array_equal(np.asarray(system.interior), idx):
        solve = system.solve
    else:
        found = _problem_factors(np.asarray(free, bool), problem)
        solve = spla.splu(sp.csc_matrix(A[idx][:, idx])).solve if found is None else found[1]
    BF = B.tocsr()[idx]
    U = L = M = None
    if rates_balance:
        shapes = film.rate_shapes(x[0], x[1])
        U = np.zeros((n, 2))
        for k in range(2):
            U[idx, k] = -solve(load_form.assemble(basis, f=12.0 * np.asarray(shapes[k]))[idx])
        cos = load_form.assemble(basis, f=np.cos(x[0]))
        sin = load_form.assemble(basis, f=np.sin(x[0]))
        L = np.vstack([cos, sin])
        # the rates keep the force: (L U)^-1, or its pseudo-inverse where the free film's force responds to the
        # rates in one direction only (most of a fed shoe's film ruptured: the rates across it are not moved)
        M = np.linalg.pinv(L @ U, rcond=1e-12)

    def apply(v):
        v = np.asarray(v, float)
        out = np.zeros(v.shape)
        bv = BF @ v
        out[idx] = -solve(np.asarray(bv))
        if U is not None:
            out = out - U @ (M @ (L @ out))
        return out

    return apply


def _problem_factors(free: np.ndarray, problem) -> tuple[np.ndarray, object] | None:
    """The Swift-Stieber ``problem``'s factorization of the free dofs ``free`` (a mask of all dofs) as
    ``(free set in its unknowns, solve)``, or None: no problem, a P2 problem (its unknowns are not the dofs), or
    a free dof off its interior."""
    if problem is None or problem.change is not None:
        return None
    own = free[np.asarray(problem.interior)]
    if np.count_nonzero(own) != np.count_nonzero(free):
        return None
    return own, problem.problem.factorization(own)


@dataclass(frozen=True, eq=False)
class ElasticSolution:
    """Film on an elastic support.

    Attributes
    ----------
    result : ReynoldsResult
        The Reynolds solution on the deflected film (``result.film`` is the
        :class:`DeflectedFilm`, ``result.h_min`` its smallest thickness).
    deflection : ndarray
        Film opening ``w`` [c] at the dofs.
    iterations : int
        Coupled iterations (Reynolds solves).
    residual : float
        ``max |C p - w|`` [c] at the answer.
    max_deflection : float
        Largest ``w`` [c].
    rigid_h_min : float
        Smallest film of the rigid surfaces at the same state [c].
    history : tuple of float
    krylov_iterations : int
        GMRES iterations (Jacobian products) of the matrix-free path; 0 with a dense compliance.
    """

    result: object
    deflection: np.ndarray
    iterations: int
    residual: float
    max_deflection: float
    rigid_h_min: float
    history: tuple[float, ...]
    krylov_iterations: int = 0


def _check_compliance(compliance: Compliance, mesh: SupportMesh, element: str) -> None:
    if not isinstance(compliance, Compliance):
        raise ValueError(f"elastic must be a bearingfe.elastic.Compliance, got {type(compliance).__name__}")
    if compliance.dense:
        check_dense_size(compliance.n_dofs)
    require_along_phi(mesh, "the elastic support")
    if compliance.mesh is not mesh:
        raise ValueError("elastic: the compliance was built on another mesh; build it on this one")
    if compliance.element != element:
        raise ValueError(f"elastic: the compliance was built for element {compliance.element!r}, "
                         f"the solve uses {element!r}")


@takes(OperatingPoint, Discretization)
def solve_elastic(mesh: SupportMesh, film: Film, compliance: Compliance, *, wedge: float = 1.0,
                  squeeze=(0.0, 0.0), inlet_pressure: float = 0.0, element: str = "P1",
                  cavitation: str = "none", sliding: float | None = None, solver=DEFAULT_SOLVER,
                  tol: float = TOLERANCE, max_iterations: int = MAX_ITERATIONS,
                  initial: np.ndarray | None = None) -> ElasticSolution:
    """Reynolds equation on the film opened by its own pressure: ``h = h_rigid + C p``.

    Parameters
    ----------
    mesh, film, wedge, squeeze, inlet_pressure, element, cavitation, sliding, solver
        As in :func:`bearingfe.solve_reynolds` (the direct form is used); the operating
        point and the discretization may come as ``operating=`` and ``discretization=``
        objects (:mod:`bearingfe.core.parameters`) instead.
    compliance : Compliance
        From :func:`half_space` on the same mesh and element.
    tol, max_iterations
        See :func:`newton` (iterations count Reynolds solves).
    initial : ndarray, optional
        Starting deflection [c] (default zero).

    Returns
    -------
    ElasticSolution
        Its ``result`` carries ``deflection`` and ``elastic_iterations``.

    Raises
    ------
    ElasticError
        No convergence within ``max_iterations``, or the film closes.
    """
    _check_compliance(compliance, mesh, element)
    if cavitation not in MODELS:
        raise ValueError(f"cavitation must be one of {tuple(MODELS)}, got {cavitation!r}")
    pockets = inlet_pressure if isinstance(inlet_pressure, tuple) else None  # one pressure per pocket
    check_operating_point(wedge, squeeze, max(pockets, key=abs) if pockets else inlet_pressure)
    weights = source_weights(wedge, squeeze, 1.0 if pockets else inlet_pressure)
    ops = operators(mesh, element)
    basis = ops.basis
    warm, last = [None, None], [None, None]  # (the last cavitated solution, its deflection), (solution, film)
    kept = [None]  # (free set, solve): the last Jacobian's factorization in the Swift-Stieber problem's unknowns
    if pockets:
        from ..cavitation.models import solve_pocket_state
        from ..film.pockets import pocket_film, pocket_names

        names = pocket_names(mesh)
        columns = pocket_deflections(compliance, names)
        if len(pockets) != len(names):
            raise ValueError(f"inlet_pressure must give one value per pocket ({len(names)}: {', '.join(names)}), "
                             f"got {len(pockets)}")
        opening = columns @ np.asarray(pockets, float)

    def evaluate(w):
        near = warm[0] is not None and (cavitation != "reynolds" or float(np.abs(w - warm[1]).max()) <= WARM_MOVE)
        options = ModelOptions(sliding=sliding, warm_start=warm[0] if near else None, solver=solver)
        deflected = DeflectedFilm(film, basis, w)
        try:
            if pockets:  # one unit field per pocket: each pocket at its own pressure
                pf = pocket_film(mesh, deflected, Discretization(element=element, formulation="direct", solver=solver))
                sup = pf.whole
            else:
                sup = superpose(mesh, deflected, formulation="direct", element=element, solver=solver, lazy=True)
        except ValueError as exc:
            if "h_min" in str(exc):
                raise ElasticError(str(exc)) from None
            raise
        if pockets:
            res = solve_pocket_state(pf, names, pockets, OperatingPoint(wedge=wedge, squeeze=tuple(weights[1:3])),
                                     cavitation, options)
        else:
            if kept[0] is not None and near and cavitation == "reynolds":
                # the last Jacobian's factors (a nearby film, the rupture set this solve starts from) precondition
                # its active-set steps in place of this film's full-film factorization
                obstacle_problem(sup, solver, tol=options.tol,
                                 max_iterations=options.max_iterations).problem.precondition(*kept[0])
            res = solve_model(sup, weights, cavitation, options)
        if res.cavitated is not None and cavitation != "gumbel":
            warm[:] = [res, w]
        last[:] = [res, sup]  # the factorized film of the last state: the Krylov Jacobian's solves
        if pockets:
            return compliance.apply(np.asarray(res.pressure, float)) + opening, res
        return compliance.deflection(res.pressure, inlet_pressure), res

    interior = np.zeros(basis.N, bool)
    interior[ops.interior] = True

    def jacobian(w, res):
        if not compliance.dense:
            return _jacobian_operator(compliance, res, interior, cavitation,
                                      sup=last[1] if last[0] is res else None, kept=kept)
        return compliance.matrix @ _sensitivity(res, interior, cavitation)

    w0 = np.zeros(basis.N) if initial is None else np.asarray(initial, float)
    with small_pages():  # each Newton step's film solve and Jacobian: large fresh arrays (bearingfe.core.pages)
        out = newton(evaluate, jacobian, w0, tol=tol, max_iterations=max_iterations)
    result = dataclasses.replace(out.payload, deflection=out.deflection, elastic_iterations=out.iterations)
    result = _checked(result, out.deflection, compliance, mesh, film)
    return ElasticSolution(result=result, deflection=out.deflection, iterations=out.iterations,
                           residual=out.residual, max_deflection=float(out.deflection.max(initial=0.0)),
                           rigid_h_min=solve_rigid_h_min(film, basis), history=out.history,
                           krylov_iterations=out.krylov_iterations)


def pocket_deflections(compliance: Compliance, names) -> np.ndarray:
    """The film opening [c] under each pocket at unit pressure, the others at 0: shape ``(n_dofs, n)``.

    The compliance carries the opening under every pocket at once (``compliance.pocket``); one pocket's own
    is the half-space's integral over that pocket's contour (:func:`bearingfe.elastic.half_space.pocket_integrals`),
    so pockets at different pressures are taken on the half-space (and rigid) supports only.

    Raises
    ------
    ValueError
        Several pockets on a compliance model whose opening per pocket is not known.
    """
    names = tuple(names)
    if len(names) == 1:
        return np.asarray(compliance.pocket, float)[:, None]
    if compliance.model != "half-space":
        raise ValueError(f"elastic: pockets at different pressures need each pocket's own opening, which the "
                         f"{compliance.model!r} compliance does not give; use half_space() or one pressure")
    from .half_space import pocket_integrals

    ops = operators(compliance.mesh, compliance.element)
    m = compliance.mesh.mesh
    kappa = (0.0 if math.isinf(compliance.modulus) else
             compliance.scale.pressure * compliance.scale.radius / (math.pi * compliance.modulus
                                                                     * compliance.scale.clearance))
    return np.column_stack([kappa * pocket_integrals(ops.basis.doflocs, m, compliance.mesh.boundaries[n])
                            for n in names])


def _checked(result, deflection: np.ndarray, compliance: Compliance, mesh: SupportMesh, film: Film):
    """The elastic result within linear elasticity (:func:`bearingfe.core.checks.check_elastic`), with
    notes on a large deflection and on the rigid film's resolution."""
    note = check_elastic(deflection, result.pressure, compliance.scale, compliance.modulus)
    if note is not None:
        result = dataclasses.replace(result, notes=(*result.notes, note))
    return note_resolution(result, mesh, film, stacklevel=4)


def _sensitivity(res, interior: np.ndarray, cavitation: str, rates_balance: bool = False) -> np.ndarray:
    """dp/dw of a solution under its cavitation model (semismooth: on the current rupture set)."""
    args = (res.basis, res.film, res.pressure, res.wedge)
    if res.cavitated is None or cavitation == "gumbel":  # Gumbel clips the linear solution afterwards
        S = pressure_sensitivity(*args, interior, rates_balance=rates_balance)
        if res.cavitated is not None:
            S[res.cavitated] = 0.0
        return S
    return pressure_sensitivity(*args, interior & ~res.cavitated, rates_balance=rates_balance)


def _jacobian_operator(compliance: Compliance, res, interior: np.ndarray, cavitation: str,
                       rates_balance: bool = False, sup=None, kept: list | None = None) -> spla.LinearOperator:
    """``dg/dw = C dp/dw`` as products (the matrix-free :func:`_sensitivity`, then ``C`` applied); ``sup``:
    the film's superposition at this state, if at hand: its factorized direct system and its Swift-Stieber
    problem's factors (:func:`sensitivity_operator`); ``kept[0]`` is then set to that problem's factorization
    of the free set ``(free, solve)``."""
    args = (res.basis, res.film, res.pressure, res.wedge)
    clipped = res.cavitated is not None and cavitation == "gumbel"
    free = interior if (res.cavitated is None or clipped) else interior & ~res.cavitated
    system = problem = None
    if sup is not None:
        system = sup.system
        problem = cached_problem(sup) if cavitation == "reynolds" and not clipped else None
    S = sensitivity_operator(*args, free, rates_balance=rates_balance, system=system, problem=problem)
    if kept is not None:
        found = _problem_factors(free, problem)  # the factorization the operator above made or found (cached)
        if found is not None:
            kept[0] = found

    def matvec(v):
        s = S(np.ravel(v))
        if clipped:
            s[res.cavitated] = 0.0
        return compliance.apply(s)

    n = compliance.n_dofs
    return spla.LinearOperator((n, n), matvec=matvec, dtype=float)


@dataclass(frozen=True, eq=False)
class ElasticBalance:
    """Squeeze rates that balance a load on an elastic support.

    Attributes
    ----------
    rates : ndarray, shape (2,)
        ``(gamma_rate, phi0_rate)`` per radian of shaft turn.
    result : ReynoldsResult or None
        The film solution at those rates (None unless asked for).
    deflection : ndarray
        Film opening ``w`` [c] at the dofs.
    iterations, jacobians : int
        Reynolds solves and Jacobians built.
    residual : float
        ``max |C p - w|`` [c].
    """

    rates: np.ndarray
    result: object
    deflection: np.ndarray
    iterations: int
    jacobians: int
    residual: float


class ChordBalance:
    """The quasi-static coupled film that balances a load, by a chord Newton whose factors are kept.

    Unknowns: the interior pressure ``p_I`` and the two squeeze rates ``r``;
    equations: the Reynolds residual on the film ``h = h_rigid + C p`` (direct
    form) and the load balance ``L p + p_s F_pocket + load = 0``. The Jacobian

        [[A_II + B_h C_I, S], [L_I, 0]]

    (``B_h`` the film sensitivity of the residual, ``S`` the unit squeeze
    sources) is dense; it is factored once and reused over the iterations and
    over the calls (a run of nearby states: the pump transient), and rebuilt
    only when a step shrinks by less than half from the one before. An
    iteration costs the residual (sparse products with the quadrature points
    of the compiled operator, no assembly) and one dense solve: no sparse
    factorization at all. Cavitation ``"none"`` only.

    Convergence: the last step moves the film opening by at most ``tol``
    [c] (``max |C_I dp_I|``) and the rates by at most ``tol`` relative.

    Parameters
    ----------
    compliance : Compliance
    tol : float
        [c], in (0, 1).
    max_iterations : int
        Residual evaluations per call, >= 1.

    Attributes
    ----------
    state : ndarray or None
        The last answer ``(p_I, r)``: the start of the next call (set it to seed the first).
    jacobians : int
        Jacobians built so far.
    """

    def __init__(self, compliance: Compliance, tol: float = TOLERANCE, max_iterations: int = MAX_ITERATIONS):
        if not isinstance(compliance, Compliance):
            raise ValueError(f"compliance must be a bearingfe.elastic.Compliance, got {type(compliance).__name__}")
        if not compliance.dense:
            raise ValueError(f"ChordBalance factors a dense Jacobian: it needs a dense compliance, got the "
                             f"{compliance.model!r} product (balance_load takes it by Newton-Krylov)")
        if not (0 < tol < 1):
            raise ValueError(f"tol must be in (0, 1) [clearance], got {tol!r}")
        if not (isinstance(max_iterations, int) and max_iterations >= 1):
            raise ValueError(f"max_iterations must be an integer >= 1, got {max_iterations!r}")
        check_dense_size(compliance.n_dofs)
        self.compliance, self.tol, self.max_iterations = compliance, float(tol), max_iterations
        ops = operators(compliance.mesh, compliance.element)
        co = ops.compiled
        self.ops, self.co, self.I, self.inlet = ops, co, ops.interior, ops.inlet
        C = np.asarray(compliance.matrix, float)
        self.C_I = np.ascontiguousarray(C[:, self.I])
        self.c_in = C[:, self.inlet].sum(axis=1) + compliance.pocket
        self.E, self.Gp, self.Gz, self.dx = co.value, co.grad[0], co.grad[1], co.dx
        self.GpT, self.GzT = self.Gp.T.tocsr()[self.I], self.Gz.T.tocsr()[self.I]
        self.src = co.sources
        # the wedge source in conservative form, -int 6 wedge h dv/dphi (bearingfe.film.forms.couette_source):
        # its points -> interior map, and its derivative in the nodal opening w (h = h_rigid + E w)
        self.phi_src = co.phi_sources
        self.phi_src_E = (self.phi_src @ self.E).tocsr()
        L = np.asarray(co.loads[:2] @ co.value)
        self.LI = L[:, self.I]
        self.L_in = L[:, self.inlet].sum(axis=1) + np.asarray(ops.pocket_moments[1:], float)
        self.state: np.ndarray | None = None
        self.jacobians = 0
        self.contraction = 0.1  # a chord step must shrink the film step 10x, else the Jacobian is rebuilt
        self._lu = None

    def _film(self, film: Film):
        x, d = self.co.x, self.ops.basis.doflocs
        shapes = [np.asarray(s, float) for s in film.rate_shapes(x[0], x[1])]
        return (np.asarray(film.thickness(x[0], x[1]), float), np.asarray(film.gradient(x[0], x[1])[0], float),
                np.asarray(film.thickness(d[0], d[1]), float), shapes,
                np.column_stack([self.src @ (12.0 * s) for s in shapes]))

    def _residual(self, rigid, y: np.ndarray, wedge: float, ps: float, load: np.ndarray):
        h0, dh0, hd0, _, S = rigid
        n = self.I.size
        pI, r = y[:n], y[n:]
        p = np.zeros(self.compliance.n_dofs)
        p[self.inlet] = ps
        p[self.I] = pI
        w = self.C_I @ pI + ps * self.c_in
        h = h0 + self.E @ w
        h_dofs = hd0 + w
        if not (np.all(h > 0) and np.all(h_dofs > 0)):
            raise ElasticError(f"film closed: h_min = {min(h.min(), h_dofs.min()):.3g} c <= 0")
        gp, gz = self.Gp @ p, self.Gz @ p
        h3 = h**3 * self.dx
        R = self.GpT @ (h3 * gp) + self.GzT @ (h3 * gz) - 6.0 * wedge * (self.phi_src @ h) + S @ r
        G = self.LI @ pI + ps * self.L_in + load
        return np.concatenate([R, G]), (h, gp, gz, w)

    def _jacobian(self, rigid, st, wedge: float) -> np.ndarray:
        h, gp, gz, _ = st
        n = self.I.size
        h2 = 3.0 * h**2 * self.dx
        Bh = (self.GpT @ sp.diags(h2 * gp) + self.GzT @ sp.diags(h2 * gz)) @ self.E - 6.0 * wedge * self.phi_src_E
        J = np.zeros((n + 2, n + 2))
        J[:n, :n] = self.co.condensed(self.co.matrix_data("direct", h, None)).toarray() + Bh @ self.C_I
        J[:n, n:] = rigid[4]
        J[n:, :n] = self.LI
        return J

    def solve(self, film: Film, load, wedge: float, inlet_pressure: float) -> tuple[np.ndarray, int, int, float]:
        """``(p_I, r)`` of the film ``film`` opened by its pressure under ``load``, from :attr:`state`.

        Returns the answer, the residual evaluations, the Jacobians built and
        the size of the last step. Raises :class:`ElasticError` if the film
        closes, a fresh Jacobian does not contract, or ``max_iterations`` is reached.
        """
        import scipy.linalg as sla

        if self.state is None:
            raise ValueError("ChordBalance.state is None: seed it with a solution (p_I, rates)")
        load = np.asarray(load, float)
        ps, wedge = float(inlet_pressure), float(wedge)
        rigid = self._film(film)
        y, n = self.state.copy(), self.I.size
        count, built, previous, age = 0, 0, math.inf, 0
        with dense_threads(1):
            while True:
                if count >= self.max_iterations:
                    raise ElasticError(f"the chord iteration of the elastic film did not converge in "
                                       f"{self.max_iterations} residuals (last step {previous:.3g})")
                F, st = self._residual(rigid, y, wedge, ps, load)
                count += 1
                if self._lu is None:
                    self._lu = sla.lu_factor(self._jacobian(rigid, st, wedge), check_finite=False)
                    self.jacobians += 1
                    built, age = built + 1, 0
                dy = -sla.lu_solve(self._lu, F, check_finite=False)
                dw = float(np.abs(self.C_I @ dy[:n]).max(initial=0.0))  # contraction measured on the film
                size = max(dw, float(np.abs(dy[n:]).max()) / max(1.0, float(np.abs(y[n:]).max())))
                if not math.isfinite(size):
                    self._lu = None
                    raise ElasticError("the Jacobian of the elastic film is singular")
                if age > 0 and dw > self.contraction * previous and size > self.tol:
                    self._lu = None
                    if age == 1 and dw > previous:  # after a fresh Jacobian: Newton itself diverges here
                        raise ElasticError(f"the chord iteration of the elastic film does not contract (film "
                                           f"step {previous:.3g} c then {dw:.3g} c)")
                    continue
                y += dy
                previous, age = dw, age + 1
                if size <= self.tol:
                    break
        self.state = y
        return y, count, built, size


@takes(OperatingPoint, Discretization)
def balance_load(mesh: SupportMesh, film: Film, compliance: Compliance, load, *, wedge: float = 1.0,
                 inlet_pressure: float = 0.0, element: str = "P1", cavitation: str = "none", solver=None,
                 initial: np.ndarray | None = None, reuse: dict | None = None, tol: float = TOLERANCE,
                 max_iterations: int = MAX_ITERATIONS, full_result: bool = True) -> ElasticBalance:
    """Squeeze rates and film opening at which the film on an elastic support balances ``load``.

    Solves ``force(h_rigid + w, rates) + load = 0`` together with ``w = C p``:
    for each ``w`` the rates come from the superposition (or the cavitated
    Newton of :func:`bearingfe.cavitation.rates_for_load`), and Newton on
    ``w`` uses ``dp/dw`` with the rates moving to keep the force
    (:func:`pressure_sensitivity`). What the pump transient calls at each
    right-side evaluation, warm-started (``initial``, ``reuse``) from the last.

    Parameters
    ----------
    mesh, film, compliance, wedge, inlet_pressure, element, cavitation, solver
        As in :func:`solve_elastic`.
    load : (float, float)
        Applied load in the arc frame [mu omega R0^4 / c^2].
    initial : ndarray, optional
        Starting deflection [c].
    reuse : dict, optional
        What is kept between calls (a run of nearby states): the Jacobian
        factors of :func:`newton`, and without cavitation a
        :class:`ChordBalance` started from the last answer, which then
        solves the call with no sparse factorization (the damped Newton above
        takes over when it does not contract, and seeds it again).
    full_result : bool
        Also build the full :class:`ReynoldsResult` (flows, friction) at the answer.
    """
    _check_compliance(compliance, mesh, element)
    ops = operators(mesh, element)
    basis = ops.basis
    opts = {} if solver is None else {"solver": solver}
    chord = None
    if cavitation == "none" and reuse is not None and compliance.dense:  # the chord factors a dense Jacobian
        chord = reuse.get("chord")
        if not (isinstance(chord, ChordBalance) and chord.compliance is compliance and chord.tol == tol):
            chord = reuse["chord"] = ChordBalance(compliance, tol=tol, max_iterations=max_iterations)
        if chord.state is not None:
            try:
                y, count, built, size = chord.solve(film, load, wedge, inlet_pressure)
            except ElasticError:
                chord.state = None  # far from the last state, or the film closes on the way: the damped Newton
            else:
                n = ops.interior.size
                w = chord.C_I @ y[:n] + float(inlet_pressure) * chord.c_in
                res = None
                if full_result:
                    sup = superpose(mesh, DeflectedFilm(film, basis, w), formulation="direct", element=element,
                                    **opts)
                    res = sup.combine(wedge, y[n:], inlet_pressure)
                return ElasticBalance(rates=y[n:].copy(), result=res, deflection=w, iterations=count,
                                      jacobians=built, residual=size)
    interior = np.zeros(basis.N, bool)
    interior[ops.interior] = True
    warm, last = [None], [None, None]

    def evaluate(w):
        try:
            sup = superpose(mesh, DeflectedFilm(film, basis, w), formulation="direct", element=element, **opts)
        except ValueError as exc:
            if "h_min" in str(exc):
                raise ElasticError(str(exc)) from None
            raise
        try:
            if cavitation == "none":
                rates = sup.rates_for_load(load, wedge, inlet_pressure)
                res = _Pressure(basis, sup.film, sup.fields @ np.r_[wedge, rates, inlet_pressure], wedge, None)
            else:
                found = rates_for_load(sup, load, wedge, inlet_pressure, model=cavitation, warm_start=warm[0],
                                       **opts)
                rates, res = found.rates, found.result
                warm[0] = res
        except np.linalg.LinAlgError as exc:
            raise ElasticError(f"no equilibrium rates on the deflected film: {exc}") from None
        last[:] = [res, sup]
        return compliance.deflection(res.pressure, inlet_pressure), (sup, rates, res)

    def jacobian(w, payload):
        if not compliance.dense:
            return _jacobian_operator(compliance, payload[2], interior, cavitation, rates_balance=True,
                                      sup=last[1] if last[0] is payload[2] else None)
        return compliance.matrix @ _sensitivity(payload[2], interior, cavitation, rates_balance=True)

    w0 = np.zeros(basis.N) if initial is None else np.asarray(initial, float)
    out = newton(evaluate, jacobian, w0, tol=tol, max_iterations=max_iterations, reuse=reuse)
    sup, rates, res = out.payload
    if chord is not None:  # seed the chord iteration of the next call with this answer
        chord.state = np.concatenate([res.pressure[ops.interior], np.asarray(rates, float)])
    if full_result and cavitation == "none":
        res = sup.combine(wedge, rates, inlet_pressure)
    return ElasticBalance(rates=np.asarray(rates, float), result=res if full_result else None,
                          deflection=out.deflection, iterations=out.iterations, jacobians=out.jacobians,
                          residual=out.residual)


@dataclass(frozen=True)
class _Pressure:
    """The pieces of a solution that the linearization needs (without flows and friction)."""

    basis: object
    film: Film
    pressure: np.ndarray
    wedge: float
    cavitated: object


def solve_rigid_h_min(film: Film, basis) -> float:
    """Smallest rigid film over the dofs and quadrature points of ``basis`` [c]."""
    x = np.array(basis.global_coordinates())
    d = basis.doflocs
    return float(min(np.min(film.thickness(x[0], x[1])), np.min(film.thickness(d[0], d[1]))))


