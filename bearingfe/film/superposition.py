r"""One film state of the finite-element Reynolds equation: one factorization, four unit solutions.

:class:`Superposition` (:func:`superpose`) is one film state on a mesh. Its
:class:`CondensedSystem` (the matrix on the interior dofs, its factorization, the
four unit right sides and their Dirichlet data) is assembled and factorized once
by an assembly of :data:`bearingfe.film.assembly.ASSEMBLIES`; the four unit fields
(wedge, the two squeeze rates, inlet pressure) are its solutions, and any
operating point is their weighted sum (:meth:`Superposition.combine`), turned into
a :class:`~bearingfe.film.result.ReynoldsResult` by
:func:`~bearingfe.film.result.build_result`, where every cavitation model's
answer ends too.

The formulations (``"pi"``, ``"direct"``) and the equation are described in
:mod:`bearingfe.reynolds` and ``docs/formulations.md``; the weak forms and the
pointwise formulas come from :mod:`bearingfe.film.forms`; what does not depend on
the film, from :mod:`bearingfe.film.mesh_operators`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from functools import cached_property
from types import MappingProxyType
from typing import Callable, Mapping

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .assembly import ASSEMBLIES
from .forms import FilmAt
from .mesh_operators import Operators, operators
from .result import ReynoldsResult, build_result
from .thickness import Film, is_smooth, smallest_film
from ..core.linalg import DEFAULT_SOLVER, Factorize, Solve, get_linear_solver
from ..core.parameters import FORMULATIONS, Discretization, OperatingPoint, takes
from ..geometry.meshing import SupportMesh

__all__ = [
    "SOURCES",
    "CoercivityError",
    "CondensedSystem",
    "Superposition",
    "superpose",
    "source_weights",
]

#: Unit sources in the order of :attr:`Superposition.fields`.
SOURCES = ("wedge", "gamma_rate", "phi0_rate", "inlet")


class CoercivityError(RuntimeError):
    """The discrete substituted (Pi) operator is not positive definite."""


# -- the condensed system of a film state -------------------------------------------------

@dataclass(frozen=True, eq=False)
class CondensedSystem:
    """The linear system of one film state on the interior (free) dofs, assembled once.

    With ``I`` the interior and ``B`` the Dirichlet dofs (outline and
    pockets), the unknown of the unit source ``k`` is ``U[:, k] =
    lift[:, k]`` on ``B`` and solves ``matrix U[I, k] = rhs[:, k]``.

    Attributes
    ----------
    matrix : sparse matrix, shape (n_I, n_I)
        ``A[I, I]``: the direct operator ``int h^3 grad u . grad v`` or the
        pi operator ``int grad u . grad v - int D u v``.
    rhs : ndarray, shape (n_I, 4)
        ``-F[I] - A[I, B] lift[B]`` of the four unit sources (:data:`SOURCES`).
    lift : ndarray, shape (n_dofs, 4)
        Dirichlet data of the unit sources (the inlet column: ``1`` or
        ``h^(3/2)`` on the pocket dofs).
    interior, boundary : ndarray of int
        The dofs ``I`` and ``B``.
    factorize : callable
        The sparse solver used (``factorize(A) -> solve``).
    solve : callable
        ``matrix^-1 b`` (the factorization of the full-film system).
    """

    rhs: np.ndarray
    lift: np.ndarray
    interior: np.ndarray
    boundary: np.ndarray
    factorize: Factorize
    solve: Solve
    build_matrix: Callable[[], sp.spmatrix] = field(repr=False)

    @cached_property
    def matrix(self) -> sp.spmatrix:
        """``A[I, I]`` (built on first use: the linear model needs only the factorization)."""
        return self.build_matrix()

    def full(self, u_interior: np.ndarray, weights: np.ndarray) -> np.ndarray:
        """The unknown on all dofs from its interior values and the source weights."""
        u = self.lift @ weights
        u[self.interior] = u_interior
        return u



# -- superposition -------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class Superposition:
    """Unit solutions of one film state: one factorization, four right sides.

    Attributes
    ----------
    operators : Operators
    film : Film
    formulation : str
        The formulation actually used (``"direct"`` after a fallback).
    fields : ndarray, shape (n_dofs, 4)
        Unknown (``p`` for direct, ``Pi`` for pi) for a unit wedge, unit
        ``gamma_rate``, unit ``phi0_rate`` and unit inlet pressure.
    forces : ndarray, shape (2, 4)
        ``int p (cos phi, sin phi)`` of each unit field, pockets included.
    integrals : ndarray, shape (4,)
        ``int p`` of each unit field, pockets included.
    h_min : float
        Smallest film thickness over the surface [-].
    coercivity : float
        Lower bound (or computed value) of the smallest eigenvalue of the
        condensed operator relative to the mass matrix; NaN for direct.
    notes : tuple of str
        What the solver decided on its own (e.g. a fallback).
    cost : mapping
        Wall times [s] of assembly, factorization and solves; ``dofs``.
    at : FilmAt
        The film at the quadrature points of ``operators.basis``.
    system : CondensedSystem
        The assembled and factorized system the fields solve (reused by
        the cavitation models).
    assembly : str
        The assembly that built it: a key of :data:`bearingfe.film.assembly.ASSEMBLIES`
        (``"compiled"``; ``"reference"`` is the test oracle).
    unit_solutions : callable
        ``() -> (fields, forces, integrals)``: called once, on the first use of one of them
        (at once unless :func:`superpose` was called with ``lazy=True``).
    """

    operators: Operators
    film: Film
    formulation: str
    h_min: float
    coercivity: float
    notes: tuple[str, ...]
    cost: Mapping[str, float]
    at: FilmAt = field(repr=False)
    system: CondensedSystem = field(repr=False)
    assembly: str = "compiled"
    unit_solutions: Callable[[], tuple[np.ndarray, np.ndarray, np.ndarray]] = field(repr=False, default=None)

    @cached_property
    def _units(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return self.unit_solutions()

    @property
    def fields(self) -> np.ndarray:
        return self._units[0]

    @property
    def forces(self) -> np.ndarray:
        return self._units[1]

    @property
    def integrals(self) -> np.ndarray:
        return self._units[2]

    @takes(OperatingPoint)
    def coefficients(self, wedge: float = 1.0, inlet_pressure: float = 0.0) -> np.ndarray:
        """The paper's force coefficients in the arc frame.

        Returns ``[[a1, a2, a3], [b1, b2, b3]]`` such that the film force is
        ``(a1, b1) gamma_rate + (a2, b2) phi0_rate + (a3, b3)``.
        """
        self.check_inlet(inlet_pressure)
        constant = wedge * self.forces[:, 0] + inlet_pressure * self.forces[:, 3]
        return np.column_stack([self.forces[:, 1], self.forces[:, 2], constant])

    @takes(OperatingPoint)
    def force(self, wedge: float = 1.0, squeeze=(0.0, 0.0), inlet_pressure: float = 0.0) -> np.ndarray:
        """Film force ``(int p cos phi, int p sin phi)`` at an operating point (or ``operating=``
        an :class:`~bearingfe.core.parameters.OperatingPoint`)."""
        self.check_inlet(inlet_pressure)
        return self.forces @ source_weights(wedge, squeeze, inlet_pressure)

    def check_inlet(self, inlet_pressure: float) -> None:
        """Raise if a pocket pressure is given on a mesh without pockets."""
        if inlet_pressure != 0.0 and not self.operators.inlet.size:
            raise ValueError("inlet_pressure is non-zero but the mesh has no 'inlet' boundary (no pocket)")

    @takes(OperatingPoint)
    def rates_for_load(self, load: np.ndarray, wedge: float = 1.0, inlet_pressure: float = 0.0) -> np.ndarray:
        """Squeeze rates ``(gamma_rate, phi0_rate)`` at which the film force
        balances an applied load: ``force + load = 0`` (paper eq. 14).

        Raises
        ------
        np.linalg.LinAlgError
            If the 2x2 system is singular (e.g. ``gamma = 0`` makes the
            ``phi0_rate`` column vanish).
        """
        load = np.asarray(load, dtype=float)
        if load.shape != (2,) or not np.all(np.isfinite(load)):
            raise ValueError(f"load must be two finite numbers (F_cos, F_sin), got {load!r}")
        self.check_inlet(inlet_pressure)
        # the 2x2 system of coefficients() by Cramer's rule: an integrator calls this at every step,
        # where LAPACK's call overhead is most of the cost
        (w0, a, b, s0), (w1, c, d, s1) = self.forces.tolist()
        det = a * d - b * c
        if abs(det) <= 1e-14 * max(abs(a), abs(b), abs(c), abs(d)) ** 2:
            raise np.linalg.LinAlgError(
                "squeeze coefficients are singular (gamma = 0 leaves phi0_rate undetermined)")
        r0 = -float(load[0]) - (wedge * w0 + inlet_pressure * s0)
        r1 = -float(load[1]) - (wedge * w1 + inlet_pressure * s1)
        return np.array([(d * r0 - b * r1) / det, (a * r1 - c * r0) / det])

    def loads(self, u: np.ndarray, inlet_pressure: float = 0.0) -> tuple[np.ndarray, float]:
        """Force ``int p (cos phi, sin phi)`` and ``int p`` of an unknown field ``u``
        (pockets at ``inlet_pressure``)."""
        ops = self.operators
        force, integral = ops.assembly(self.assembly).field_loads(self.at, self.formulation, u)
        force = force + inlet_pressure * ops.pocket_moments[1:]
        return force, integral + inlet_pressure * ops.pocket_moments[0]

    @takes(OperatingPoint)
    def combine(self, wedge: float = 1.0, squeeze=(0.0, 0.0), inlet_pressure: float = 0.0,
                sliding: float | None = None) -> "ReynoldsResult":
        """The full solution at an operating point (pressure, loads, flows, friction).

        The operating point is given by the keywords or as ``operating=`` an
        :class:`~bearingfe.core.parameters.OperatingPoint`.
        """
        wts = source_weights(wedge, squeeze, inlet_pressure)
        self.check_inlet(inlet_pressure)
        if sliding is not None and not math.isfinite(float(sliding)):
            raise ValueError(f"sliding must be finite, got {sliding!r}")
        return build_result(self, self.fields @ wts, wts, sliding)


def source_weights(wedge, squeeze, inlet_pressure) -> np.ndarray:
    """The operating point as weights of the unit sources (:data:`SOURCES`), checked finite."""
    try:
        gr, pr = (float(s) for s in squeeze)
    except (TypeError, ValueError):
        raise ValueError(f"squeeze must be a pair (gamma_rate, phi0_rate), got {squeeze!r}") from None
    w = np.array([float(wedge), gr, pr, float(inlet_pressure)])
    if not np.all(np.isfinite(w)):
        raise ValueError(f"wedge, squeeze and inlet_pressure must be finite, got {w.tolist()}")
    return w


@takes(Discretization)
def superpose(mesh: SupportMesh, film: Film, *, formulation: str = "pi", element: str = "P1",
              solver: str | Factorize = DEFAULT_SOLVER, on_indefinite: str = "fallback",
              assembly: str = "compiled", lazy: bool = False) -> Superposition:
    """Factorize the Reynolds operator of a film state once and solve four unit problems.

    Parameters
    ----------
    mesh : SupportMesh
    film : Film
    formulation : {"pi", "direct"}
    element : {"P1", "P2"}
    solver : str or callable
        Sparse solver from :data:`bearingfe.core.linalg.LINEAR_SOLVERS`. With the
        default (``"splu_sym"``) and the compiled assembly the fill-reducing
        ordering is found once per mesh and each film costs one numeric
        factorization.
    on_indefinite : {"fallback", "raise"}
        What to do if the discrete pi operator is not positive definite:
        switch to the direct form (and say so in ``notes``) or raise
        :class:`CoercivityError`.
    assembly : str
        A key of :data:`bearingfe.film.assembly.ASSEMBLIES`: ``"compiled"`` (the
        film-independent maps of :mod:`bearingfe.film.compiled`: sparse mat-vecs per
        film) or ``"reference"`` (scikit-fem form assembly per film, the test
        oracle). Same numbers to round-off.
    lazy : bool
        Defer the factorization and the four unit solutions to their first use (``fields``,
        ``forces``, ``integrals``, ``system.solve``; ``cost`` gets ``factorization`` and ``solve``
        then): for a caller that needs only the system, e.g. a cavitating solve from a warm
        rupture set, which factorizes its own free sets. Same numbers either way.
    discretization : Discretization, optional
        ``formulation``, ``element`` and ``solver`` in one object
        (:class:`bearingfe.core.parameters.Discretization`) instead of the keywords.
    """
    if formulation not in FORMULATIONS:
        raise ValueError(f"formulation must be one of {FORMULATIONS}, got {formulation!r}")
    if on_indefinite not in ("fallback", "raise"):
        raise ValueError(f"on_indefinite must be 'fallback' or 'raise', got {on_indefinite!r}")
    if assembly not in ASSEMBLIES:
        raise ValueError(f"assembly must be one of {tuple(ASSEMBLIES)}, got {assembly!r}")
    if type(film) not in _FILM_TYPES:  # a Protocol isinstance check costs ~30 us: once per type
        if not isinstance(film, Film):
            raise ValueError(f"film must implement the bearingfe.Film protocol, got {type(film).__name__}")
        _FILM_TYPES.add(type(film))
    if isinstance(mesh, SupportMesh) and mesh.needs_finite_volumes:
        raise ValueError("the surface has recesses (film steps) or is periodic: solve it with "
                         "solve_reynolds(..., cavitation='none', 'reynolds' or 'jfo'), whose finite-volume fluxes "
                         "are exact across the steps and which identifies the periodic seam")
    ops = operators(mesh, element)
    assembler = ops.assembly(assembly)
    factorize = get_linear_solver(solver)
    t0 = time.perf_counter()
    at = assembler.film_at(film)
    h_min = smallest_film(film, ops.phi_range, values=at.h, points=ops.basis.doflocs)
    if not h_min > 0:
        raise ValueError(f"film thickness reaches h_min = {h_min:.4g} <= 0 on the surface "
                         f"(film {film!r}): the shoe would touch the journal")
    notes: list[str] = []
    coercivity = math.nan
    if formulation == "pi" and not _smooth_on(ops, film, at):
        notes.append("the film has a kink or a step (no Laplacian as a function, which the pi form needs): "
                     "the direct form div(h^3 grad p) was used, whose wedge source takes the step exactly")
        formulation = "direct"
    system = assembler.system(at, formulation)
    if formulation == "pi":
        coercivity = _coercivity(ops, at, system.full_matrix)
        if not coercivity > 1e-10 * ops.eigen_bound:
            msg = (f"the discrete pi operator is not positive definite (smallest eigenvalue "
                   f"{coercivity:.3g}); the direct form div(h^3 grad p) was used instead")
            if on_indefinite == "raise":
                raise CoercivityError(msg)
            notes.append(msg)
            formulation = "direct"
            system = assembler.system(at, formulation)
    g = _lift(ops, film, formulation)
    rhs = system.rhs(g)
    t1 = time.perf_counter()
    cost = {"assembly": t1 - t0, "dofs": float(ops.n_dofs), "mesh_operators": ops.seconds}
    solve = _Deferred(lambda: system.factorize(factorize), cost)
    I, B = ops.interior, ops.boundary

    def unit_solutions():
        solve.made()
        t2 = time.perf_counter()
        U = np.zeros((ops.n_dofs, 4))
        U[B] = g[B]
        U[I] = np.asarray(solve(rhs)).reshape(I.size, 4)
        cost["solve"] = time.perf_counter() - t2
        forces, integrals = system.unit_loads(U)
        forces[:, 3] += ops.pocket_moments[1:]  # pockets at unit pressure
        integrals[3] += ops.pocket_moments[0]
        return U, forces, integrals

    condensed = CondensedSystem(rhs=rhs, lift=g, interior=I, boundary=B, factorize=factorize, solve=solve,
                                build_matrix=system.condensed_matrix)
    sup = Superposition(operators=ops, film=film, formulation=formulation, h_min=h_min, coercivity=coercivity,
                        notes=tuple(notes), cost=MappingProxyType(cost), at=at, system=condensed,
                        assembly=assembly, unit_solutions=unit_solutions)
    if not lazy:
        sup.fields  # noqa: B018 (the factorization and the unit solutions now)
    return sup


class _Deferred:
    """A factorization made on its first use (its wall time into ``cost["factorization"]``)."""

    def __init__(self, make: Callable[[], Solve], cost: dict):
        self._make, self._solve, self._cost = make, None, cost

    def made(self) -> Solve:
        if self._solve is None:
            t = time.perf_counter()
            self._solve = self._make()
            self._cost["factorization"] = time.perf_counter() - t
        return self._solve

    def __call__(self, b):
        return (self._solve or self.made())(b)


_FILM_TYPES: set[type] = set()

#: Largest :meth:`~bearingfe.film.compiled.CompiledOperator.smoothness_defect` of a film the pi form accepts:
#: smooth films measure 1e-7 and below (quadrature error), a step or a kink about 1.
SMOOTHNESS_LIMIT = 1e-4


def _smooth_on(ops: Operators, film: Film, at: FilmAt) -> bool:
    """Whether the pi form may take ``film``: a film that says whether it is smooth (a ``smooth`` attribute,
    :func:`~bearingfe.film.thickness.is_smooth`: every model of the package does) is taken at its word; one that
    does not (a user's film) is measured: its derivatives must agree with its thickness on this mesh, which a
    step or a kink breaks."""
    if hasattr(film, "smooth"):
        return is_smooth(film)
    return ops.compiled.smoothness_defect(film, at) <= SMOOTHNESS_LIMIT


def _lift(ops: Operators, film: Film, formulation: str) -> np.ndarray:
    """Dirichlet data of the four unit sources: the inlet column is 1 (direct) or ``h^(3/2)`` (pi)
    on the pocket dofs."""
    g = np.zeros((ops.n_dofs, 4))
    if ops.inlet.size:
        loc = ops.basis.doflocs[:, ops.inlet]
        g[ops.inlet, 3] = np.asarray(film.thickness(loc[0], loc[1])) ** 1.5 if formulation == "pi" else 1.0
    return g


def _coercivity(ops: Operators, at: FilmAt, full_matrix: Callable[[], sp.spmatrix]) -> float:
    """Smallest eigenvalue of the condensed pi operator relative to the mass matrix.

    Cheap sufficient test first: Dirichlet eigenvalues only grow when the
    domain shrinks and Galerkin eigenvalues lie above the exact ones, so
    ``lambda_1 >= pi^2 (1/L_phi^2 + 1/L_z^2)`` for the bounding box, and
    ``u^T M_D u <= max(D) u^T M u``. If that bound does not settle it, the
    smallest eigenvalue is computed (shift-invert Lanczos below the spectrum).
    """
    d_max = float(at.D.max())
    if ops.eigen_bound > d_max:
        return ops.eigen_bound - d_max
    I = ops.interior
    A = full_matrix()
    AI, MI = A[I][:, I].tocsc(), ops.mass[I][:, I].tocsc()
    shift = -(max(d_max, 0.0) + 1.0)
    vals = spla.eigsh(AI, k=1, M=MI, sigma=shift, which="LM", return_eigenvectors=False)
    return float(vals.min())
