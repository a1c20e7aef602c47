r"""One film state of the finite-element Reynolds equation: operators, condensed system, results.

Layers (each built once and reused by everything above it):

1. :class:`Operators` (:func:`operators`): everything about a mesh and an
   element that does not depend on the film, cached on the mesh.
2. :class:`Superposition` (:func:`superpose`): one film state. Its
   :class:`CondensedSystem` (the matrix on the interior dofs, its
   factorization, the four unit right sides and their Dirichlet data) is
   assembled and factorized once; the four unit fields (wedge, the two
   squeeze rates, inlet pressure) are its solutions.
3. :func:`build_result`: the one place that turns an unknown field into a
   :class:`ReynoldsResult` (pressure, loads, flows, friction), with or
   without a ruptured set. :meth:`Superposition.combine` (the linear model)
   and every cavitation model of :data:`bearingfe.cavitation.models.MODELS` end
   there.

The formulations (``"pi"``, ``"direct"``) and the equation are described
in :mod:`bearingfe.reynolds` and ``docs/formulations.md``; the weak forms
and pointwise formulas come from :mod:`bearingfe.film.forms`.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from functools import cached_property
from types import MappingProxyType
from typing import Callable, Mapping, Sequence

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import skfem
from skfem.quadrature import get_quadrature
from skfem.refdom import RefLine

from .thickness import Film
from . import forms
from .compiled import CompiledOperator, FilmFlows, compile_operator
from .forms import FilmAt, film_at, film_flux, mapping, pressure_from_unknown, shear, unknown_scale
from ..core.linalg import DEFAULT_SOLVER, Factorize, Solve, factorize_splu_sym, get_linear_solver
from ..geometry.meshing import SupportMesh
from ..core.parameters import ELEMENTS, FORMULATIONS, Discretization, OperatingPoint, takes

__all__ = [
    "ELEMENTS",
    "FORMULATIONS",
    "ASSEMBLIES",
    "SOURCES",
    "CoercivityError",
    "Operators",
    "operators",
    "CondensedSystem",
    "Superposition",
    "superpose",
    "ReynoldsResult",
    "build_result",
    "film_outputs",
    "source_weights",
    "system_matrix",
    "unit_sources",
    "pressure_at_quadrature",
    "outflow",
    "ruptured_elements",
    "probes",
]

#: How a film state's system is built: ``"compiled"`` (:mod:`bearingfe.film.compiled`, the default) or
#: ``"reference"`` (scikit-fem form assembly per film; the same numbers to round-off).
ASSEMBLIES = ("compiled", "reference")
#: Unit sources in the order of :attr:`Superposition.fields`.
SOURCES = ("wedge", "gamma_rate", "phi0_rate", "inlet")


class CoercivityError(RuntimeError):
    """The discrete substituted (Pi) operator is not positive definite."""


# -- per-mesh operators -------------------------------------------------------

@dataclass(frozen=True, eq=False)
class Operators:
    """Everything about a mesh and element that does not depend on the film.

    Built once per ``(mesh, element)`` by :func:`operators` and cached on
    the mesh object. ``laplace``, ``mass`` and ``facet_bases`` are built on
    first use (the direct form needs no Laplacian, the mass matrix serves
    only the rare eigenvalue check, the facet bases only the flows), which
    keeps a first force-only solve on a small mesh cheap.
    """

    mesh: SupportMesh
    element: str
    basis: skfem.CellBasis
    outer: np.ndarray
    inlet: np.ndarray
    interior: np.ndarray
    flow_groups: Mapping[str, tuple[np.ndarray, np.ndarray]]
    facet_groups: Mapping[str, np.ndarray]  # per outflow group, its facets at the corner dofs it shares
    pocket_moments: np.ndarray  # (area, int cos phi, int sin phi) over the pockets
    phi_range: tuple[float, float]
    eigen_bound: float  # lower bound of the first Dirichlet eigenvalue
    seconds: float

    @property
    def n_dofs(self) -> int:
        return int(self.basis.N)

    @property
    def boundary(self) -> np.ndarray:
        """Dirichlet dofs: the outline and the pocket contours."""
        return self._get("boundary", lambda: np.union1d(self.outer, self.inlet))

    @property
    def x(self) -> np.ndarray:
        """Quadrature-point coordinates, shape (2, n_elements, n_points)."""
        return self._x

    def __post_init__(self) -> None:
        object.__setattr__(self, "_x", np.array(self.basis.global_coordinates()))
        object.__setattr__(self, "_lazy", {})

    def _get(self, name: str, build):
        if name not in self._lazy:
            self._lazy[name] = build()
        return self._lazy[name]

    @property
    def angles(self) -> tuple[np.ndarray, np.ndarray]:
        """``cos phi`` and ``sin phi`` at the quadrature points (for :func:`bearingfe.film.forms.film_at`)."""
        return self._get("angles", lambda: (np.cos(self._x[0]), np.sin(self._x[0])))

    @property
    def laplace(self) -> sp.csr_matrix:
        """Stiffness matrix ``int grad u . grad v``."""
        return self._get("laplace", lambda: forms.laplace.assemble(self.basis).tocsr())

    @property
    def mass(self) -> sp.csr_matrix:
        """Mass matrix ``int u v``."""
        return self._get("mass", lambda: forms.mass.assemble(self.basis).tocsr())

    @property
    def compiled(self) -> CompiledOperator:
        """The film-independent linear maps (:mod:`bearingfe.film.compiled`), built on first use."""
        return self._get("compiled", lambda: compile_operator(self))

    @property
    def corner_basis(self) -> tuple[skfem.FacetBasis, Mapping[str, slice]]:
        """One facet basis over the facets of all :attr:`facet_groups` (in their order) and, per
        group, the slice of its facets in it (for the compiled corner fluxes)."""
        def build():
            names = list(self.facet_groups)
            ends = np.cumsum([0] + [len(self.facet_groups[n]) for n in names])
            facets = np.concatenate([self.facet_groups[n] for n in names])
            fb = _facet_basis(self.basis, facets, _intorder(self.element))
            return fb, MappingProxyType({n: slice(int(ends[k]), int(ends[k + 1])) for k, n in enumerate(names)})
        return self._get("corner_basis", build)

    @property
    def facet_bases(self) -> Mapping[str, skfem.FacetBasis]:
        """Facet bases of the outflow groups that share corner dofs (for the flows)."""
        return self._get("facet_bases", lambda: MappingProxyType({
            n: _facet_basis(self.basis, f, _intorder(self.element))
            for n, f in self.facet_groups.items()}))


def operators(mesh: SupportMesh, element: str = "P1") -> Operators:
    """Film-independent operators of a mesh (cached on the mesh).

    Parameters
    ----------
    mesh : SupportMesh
    element : {"P1", "P2"}
    """
    if not isinstance(mesh, SupportMesh):
        raise ValueError(f"mesh must be a bearingfe.SupportMesh, got {type(mesh).__name__}")
    if element not in ELEMENTS:
        raise ValueError(f"element must be one of {list(ELEMENTS)}, got {element!r}")
    key = ("operators", element)
    if key not in mesh._cache:
        mesh._cache[key] = _build_operators(mesh, element)
    return mesh._cache[key]


def _intorder(element: str) -> int:
    """Quadrature order of the cell and facet integrals: ``2 k + 2`` for elements of degree ``k``."""
    return 6 if element == "P2" else 4


def _build_operators(mesh: SupportMesh, element: str) -> Operators:
    start = time.perf_counter()
    m = mesh.mesh
    basis = skfem.Basis(m, ELEMENTS[element](), mapping=mapping(m), intorder=_intorder(element))
    bnd = mesh.boundaries
    if "outer" not in bnd:
        raise ValueError("mesh has no boundary named 'outer'")
    outer = basis.get_dofs(bnd["outer"]).all()
    inlet = basis.get_dofs(bnd["inlet"]).all() if "inlet" in bnd else np.zeros(0, dtype=np.int64)
    fixed = np.union1d(outer, inlet)
    interior = np.setdiff1d(np.arange(basis.N), fixed)
    names = [n for n in ("side", "arc_start", "arc_end") if n in bnd] or ["outer"]
    groups = _flow_groups(basis, bnd, names)
    facet_groups = _corner_facets(m, basis, bnd, groups) if len(names) > 1 else {}
    if inlet.size:
        groups["inlet"] = (inlet, np.ones(inlet.size))
    xy = m.p
    phi_range = (float(xy[0].min()), float(xy[0].max()))
    lengths = np.ptp(xy, axis=1)
    eigen_bound = float(np.pi**2 * np.sum(1.0 / lengths**2))
    return Operators(
        mesh=mesh, element=element, basis=basis,
        outer=outer, inlet=inlet, interior=interior, flow_groups=MappingProxyType(groups),
        facet_groups=MappingProxyType(facet_groups),
        pocket_moments=_pocket_moments(basis, bnd.get("inlet")),
        phi_range=phi_range, eigen_bound=eigen_bound, seconds=time.perf_counter() - start)


def _flow_groups(basis, bnd, names) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Boundary dofs per outflow group; dofs shared by two groups (corners) count half to each."""
    dofs = {n: basis.get_dofs(bnd[n]).all() for n in names}
    count = np.zeros(basis.N)
    for d in dofs.values():
        count[d] += 1
    return {n: (d, 1.0 / count[d]) for n, d in dofs.items()}


def _corner_facets(m: skfem.Mesh, basis, bnd, groups) -> dict[str, np.ndarray]:
    """Per outflow group, its facets next to the dofs it shares with another group (the corners
    of the outline): where the direct facet fluxes that split a corner dof's flow are non-zero.

    A vertex dof's basis function vanishes on the facets away from its vertex, so a group's
    facets that do not touch a shared vertex add nothing to those fluxes. If a shared dof is not
    a vertex dof, all the group's facets are kept."""
    shared = np.unique(np.concatenate([d[w < 1] for d, w in groups.values()] or [np.zeros(0, np.int64)]))
    vertex_dofs = np.asarray(basis.nodal_dofs)
    if vertex_dofs.shape[0] != 1 or not np.isin(shared, vertex_dofs[0]).all():
        return {n: bnd[n] for n in groups}
    at_shared = np.zeros(m.nvertices, dtype=bool)
    owner = np.full(basis.N, -1, dtype=np.int64)
    owner[vertex_dofs[0]] = np.arange(vertex_dofs.shape[1])
    at_shared[owner[shared]] = True
    out = {}
    for n in groups:
        f = np.asarray(bnd[n])
        near = f[at_shared[m.facets[:, f]].any(axis=0)]
        if near.size:  # a group without shared dofs needs no facet fluxes
            out[n] = near
    return out


#: Gauss-Legendre rules on the reference facet by integration order, tabulated once (scikit-fem
#: recomputes them for every facet basis; they are constants).
_LINE_RULES = {k: get_quadrature(RefLine, k) for k in (4, 6, 8)}


def _facet_basis(basis: skfem.CellBasis, facets: np.ndarray, intorder: int) -> skfem.FacetBasis:
    """A facet basis of ``basis``'s element and map on ``facets`` (its dof numbering and a tabulated
    quadrature rule: the same basis scikit-fem would build, without recomputing either)."""
    if basis.mesh.brefdom is not RefLine or intorder not in _LINE_RULES:
        return skfem.FacetBasis(basis.mesh, basis.elem, mapping=basis.mapping, facets=facets, dofs=basis.dofs,
                                intorder=intorder)
    return skfem.FacetBasis(basis.mesh, basis.elem, mapping=basis.mapping, facets=facets, dofs=basis.dofs,
                            quadrature=_LINE_RULES[intorder])


def _pocket_moments(basis: skfem.CellBasis, inlet_facets) -> np.ndarray:
    """Area and first trigonometric moments of the pocket regions.

    The pockets are holes in the mesh, so their integrals come from the
    divergence theorem on the pocket contours: with n the film's outward
    normal (pointing into the pocket),
    ``int_P 1 = -oint phi n_phi``, ``int_P cos = -oint sin(phi) n_phi``,
    ``int_P sin = oint cos(phi) n_phi``.
    """
    if inlet_facets is None or len(inlet_facets) == 0:
        return np.zeros(3)
    fb = _facet_basis(basis, inlet_facets, 8)  # the integrands need only the points, normals and weights
    phi = np.array(fb.global_coordinates())[0]
    nphi = np.array(fb.normals)[0]
    dx = fb.dx
    return np.array([-np.sum(phi * nphi * dx), -np.sum(np.sin(phi) * nphi * dx), np.sum(np.cos(phi) * nphi * dx)])


# -- film fields at quadrature points -----------------------------------------

def _h_min(ops: Operators, film: Film, at: FilmAt) -> float:
    exact = film.minimum(ops.phi_range) if hasattr(film, "minimum") else None
    if exact is not None:
        return float(exact)
    doflocs = ops.basis.doflocs
    return float(min(at.h.min(), np.min(film.thickness(doflocs[0], doflocs[1]))))


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
        ``"compiled"`` or ``"reference"`` (see :data:`ASSEMBLIES`).
    """

    operators: Operators
    film: Film
    formulation: str
    fields: np.ndarray
    forces: np.ndarray
    integrals: np.ndarray
    h_min: float
    coercivity: float
    notes: tuple[str, ...]
    cost: Mapping[str, float]
    at: FilmAt = field(repr=False)
    system: CondensedSystem = field(repr=False)
    assembly: str = "compiled"

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
        if self.assembly == "compiled":
            co = ops.compiled
            p = unknown_scale(self.at.h.ravel(), self.formulation) * (co.value @ u)
            values = co.loads @ p
            force, integral = values[:2].copy(), float(values[2])
        else:
            p, _ = pressure_at_quadrature(ops, self.at, u, self.formulation)
            x, dx = ops.x, ops.basis.dx
            force = np.array([np.sum(p * np.cos(x[0]) * dx), np.sum(p * np.sin(x[0]) * dx)])
            integral = float(np.sum(p * dx))
        force += inlet_pressure * ops.pocket_moments[1:]
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
              assembly: str = "compiled") -> Superposition:
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
    assembly : {"compiled", "reference"}
        ``"compiled"``: the film-independent maps of :mod:`bearingfe.film.compiled`
        (sparse mat-vecs per film); ``"reference"``: scikit-fem form assembly
        per film. Same numbers to round-off.
    discretization : Discretization, optional
        ``formulation``, ``element`` and ``solver`` in one object
        (:class:`bearingfe.core.parameters.Discretization`) instead of the keywords.
    """
    if formulation not in FORMULATIONS:
        raise ValueError(f"formulation must be one of {FORMULATIONS}, got {formulation!r}")
    if on_indefinite not in ("fallback", "raise"):
        raise ValueError(f"on_indefinite must be 'fallback' or 'raise', got {on_indefinite!r}")
    if assembly not in ASSEMBLIES:
        raise ValueError(f"assembly must be one of {ASSEMBLIES}, got {assembly!r}")
    if type(film) not in _FILM_TYPES:  # a Protocol isinstance check costs ~30 us: once per type
        if not isinstance(film, Film):
            raise ValueError(f"film must implement the bearingfe.Film protocol, got {type(film).__name__}")
        _FILM_TYPES.add(type(film))
    if isinstance(mesh, SupportMesh) and mesh.needs_finite_volumes:
        raise ValueError("the surface has recesses (film steps) or is periodic: solve it with "
                         "solve_reynolds(..., cavitation='none', 'reynolds' or 'jfo'), whose finite-volume fluxes "
                         "are exact across the steps and which identifies the periodic seam")
    ops = operators(mesh, element)
    factorize = get_linear_solver(solver)
    t0 = time.perf_counter()
    at = film_at(film, ops.x, ops.angles if assembly == "compiled" else None)
    h_min = _h_min(ops, film, at)
    if not h_min > 0:
        raise ValueError(f"film thickness reaches h_min = {h_min:.4g} <= 0 on the surface "
                         f"(film {film!r}): the shoe would touch the journal")
    build = _CompiledBuild(ops, at) if assembly == "compiled" else _ReferenceBuild(ops, at)
    notes: list[str] = []
    coercivity = math.nan
    build.assemble(formulation)
    if formulation == "pi":
        coercivity = _coercivity(ops, at, build.full_matrix)
        if not coercivity > 1e-10 * ops.eigen_bound:
            msg = (f"the discrete pi operator is not positive definite (smallest eigenvalue "
                   f"{coercivity:.3g}); the direct form div(h^3 grad p) was used instead")
            if on_indefinite == "raise":
                raise CoercivityError(msg)
            notes.append(msg)
            formulation = "direct"
            build.assemble(formulation)
    g = _lift(ops, film, formulation)
    rhs = build.rhs(formulation, g)
    t1 = time.perf_counter()
    solve = build.factorize(factorize)
    t2 = time.perf_counter()
    I, B = ops.interior, ops.boundary
    U = np.zeros((ops.n_dofs, 4))
    U[B] = g[B]
    U[I] = np.asarray(solve(rhs)).reshape(I.size, 4)
    t3 = time.perf_counter()
    forces, integrals = build.unit_loads(U, formulation)
    cost = {"assembly": t1 - t0, "factorization": t2 - t1, "solve": t3 - t2, "dofs": float(ops.n_dofs),
            "mesh_operators": ops.seconds}
    system = CondensedSystem(rhs=rhs, lift=g, interior=I, boundary=B, factorize=factorize, solve=solve,
                             build_matrix=build.condensed_matrix)
    return Superposition(operators=ops, film=film, formulation=formulation, fields=U, forces=forces,
                         integrals=integrals, h_min=h_min, coercivity=coercivity, notes=tuple(notes),
                         cost=MappingProxyType(cost), at=at, system=system, assembly=assembly)


_FILM_TYPES: set[type] = set()


def _lift(ops: Operators, film: Film, formulation: str) -> np.ndarray:
    """Dirichlet data of the four unit sources: the inlet column is 1 (direct) or ``h^(3/2)`` (pi)
    on the pocket dofs."""
    g = np.zeros((ops.n_dofs, 4))
    if ops.inlet.size:
        loc = ops.basis.doflocs[:, ops.inlet]
        g[ops.inlet, 3] = np.asarray(film.thickness(loc[0], loc[1])) ** 1.5 if formulation == "pi" else 1.0
    return g


class _ReferenceBuild:
    """The system of a film by scikit-fem form assembly (the reference for the compiled maps)."""

    def __init__(self, ops: Operators, at: FilmAt) -> None:
        self.ops, self.at = ops, at

    def assemble(self, formulation: str) -> None:
        self.A = system_matrix(self.ops, self.at, formulation)

    def full_matrix(self) -> sp.csr_matrix:
        return self.A

    def rhs(self, formulation: str, g: np.ndarray) -> np.ndarray:
        F = unit_sources(self.ops, self.at, formulation)
        I, B = self.ops.interior, self.ops.boundary
        return -F[I] - self.A[I][:, B] @ g[B]

    def condensed_matrix(self) -> sp.csr_matrix:
        I = self.ops.interior
        return self.A[I][:, I]

    def factorize(self, factorize: Factorize) -> Solve:
        return factorize(self.condensed_matrix())

    def unit_loads(self, U: np.ndarray, formulation: str):
        return _unit_loads(self.ops, self.at, U, formulation)


class _CompiledBuild:
    """The system of a film from the compiled maps: mat-vecs, one numeric factorization."""

    def __init__(self, ops: Operators, at: FilmAt) -> None:
        self.ops, self.co = ops, ops.compiled
        self.h, self.D = at.h.ravel(), at.D.ravel()
        self.at = at

    def assemble(self, formulation: str) -> None:
        self.data = self.co.matrix_data(formulation, self.h, self.D)

    def full_matrix(self) -> sp.csr_matrix:
        return self.co.matrix(self.data)

    def rhs(self, formulation: str, g: np.ndarray) -> np.ndarray:
        """The right sides, and (kept for :meth:`unit_loads`) the load weights of the dofs.

        Both are ``E^T`` of fields at the points: the sources ``dx s f_k``
        and the load densities ``s (cos phi, sin phi, 1) dx`` (``p = s u``),
        so one sparse product serves the six columns.
        """
        at, co = self.at, self.co
        s = unknown_scale(self.h, formulation)
        sdx = s * co.dx
        fields = np.empty((self.h.size, 6))
        fields[:, 0] = 6.0 * sdx * at.dh[0].ravel()
        fields[:, 1] = 12.0 * sdx * at.shapes[0].ravel()
        fields[:, 2] = 12.0 * sdx * at.shapes[1].ravel()
        fields[:, 3:] = (co.loads * s).T
        weights = co.transposed_value @ fields
        self.load_weights = weights[:, 3:]
        rhs = np.empty((self.ops.interior.size, 4))
        rhs[:, :3] = -weights[self.ops.interior, :3]
        rhs[:, 3] = -co.coupling_times(self.data, g[self.ops.inlet, 3]) if self.ops.inlet.size else 0.0
        return rhs

    def condensed_matrix(self) -> sp.csr_matrix:
        return self.co.condensed(self.data)

    def factorize(self, factorize: Factorize) -> Solve:
        if factorize is factorize_splu_sym:
            return self.co.factorize_condensed(self.data)
        return factorize(self.condensed_matrix())

    def unit_loads(self, U: np.ndarray, formulation: str):
        values = self.load_weights.T @ U  # the weights of rhs(), same formulation
        forces, integrals = values[:2].copy(), values[2].copy()
        forces[:, 3] += self.ops.pocket_moments[1:]  # pockets at unit pressure
        integrals[3] += self.ops.pocket_moments[0]
        return forces, integrals


def system_matrix(ops: Operators, at: FilmAt, formulation: str) -> sp.csr_matrix:
    """The Reynolds operator on all dofs: ``int h^3 grad u . grad v`` (direct) or
    ``int grad u . grad v - int D u v`` (pi)."""
    if formulation == "direct":
        return forms.weighted_laplace.assemble(ops.basis, c=at.h**3).tocsr()
    return (ops.laplace - forms.weighted_mass.assemble(ops.basis, c=at.D)).tocsr()


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


def unit_sources(ops: Operators, at: FilmAt, formulation: str) -> np.ndarray:
    """Load vectors ``int f_k v`` of the four unit sources (:data:`SOURCES`; the inlet one is zero)."""
    weight = unknown_scale(at.h, formulation)
    basis = ops.basis
    return np.column_stack([
        forms.load.assemble(basis, f=weight * 6.0 * at.dh[0]),
        forms.load.assemble(basis, f=weight * 12.0 * at.shapes[0]),
        forms.load.assemble(basis, f=weight * 12.0 * at.shapes[1]),
        np.zeros(basis.N),
    ])


def pressure_at_quadrature(ops: Operators, at: FilmAt, u: np.ndarray, formulation: str):
    """Pressure and its gradient at the quadrature points from the unknown ``u``."""
    field_ = ops.basis.interpolate(u)
    return pressure_from_unknown(np.array(field_), field_.grad, at.h, at.dh, formulation)


def _unit_loads(ops: Operators, at: FilmAt, U: np.ndarray, formulation: str):
    x, dx = ops.x, ops.basis.dx
    cos, sin = np.cos(x[0]) * dx, np.sin(x[0]) * dx
    forces = np.zeros((2, 4))
    integrals = np.zeros(4)
    for k in range(4):
        p, _ = pressure_at_quadrature(ops, at, U[:, k], formulation)
        forces[:, k] = np.sum(p * cos), np.sum(p * sin)
        integrals[k] = np.sum(p * dx)
    forces[:, 3] += ops.pocket_moments[1:]  # pockets at unit pressure
    integrals[3] += ops.pocket_moments[0]
    return forces, integrals


def _pressure_dofs(ops: Operators, film: Film, u: np.ndarray, formulation: str) -> np.ndarray:
    if formulation == "direct":
        return u.copy()
    loc = ops.basis.doflocs
    return u * unknown_scale(film.thickness(loc[0], loc[1]), formulation)


# -- flows ---------------------------------------------------------------------------------

def _flows(ops: Operators, film: Film, at: FilmAt, u: np.ndarray, formulation: str, dp,
           wedge: float, rates, cavitated: np.ndarray | None = None) -> tuple[dict[str, float], float]:
    """Consistent boundary fluxes from the weak-form residual (units omega R0^2 c).

    The flux ``q = -h^3/12 grad p + wedge h/2 e_phi`` tested with each
    boundary basis function gives the flow through that part of the
    boundary; summed over all dofs it equals ``-int dh/dt`` exactly, so the
    interior residual measures the discretization's mass-balance error.
    A corner dof shared by two edges (e.g. ``side`` and ``arc_start``)
    carries the flux of both: it is split by the direct facet integrals of
    ``q . n`` on each edge, and only the (small) difference between the
    residual and those integrals is shared equally.

    ``cavitated`` (a mask of ruptured dofs, optional): the residual at those
    dofs is the flow the full film hands to the ruptured zone. In the
    ruptured elements (:func:`ruptured_elements`) the Couette flow is not
    conserved (``div q + dh/dt = wedge/2 dh/dphi + dh/dt != 0``); that source
    is added back to the residual so that a boundary dof next to the
    ruptured zone reports the flow through the boundary only (without it
    the side flow of a cavitated film is biased by O(element size)), and
    ``flows["cavitation"]`` takes the difference, so the balance identity
    ``inlet = outflows + squeeze + cavitation`` is unchanged.
    """
    hdot = rates[0] * at.shapes[0] + rates[1] * at.shapes[1]
    q0, q1 = film_flux(at.h, dp, wedge)
    r = forms.flux_residual.assemble(ops.basis, q0=q0, q1=q1, hdot=hdot)
    direct = {name: _facet_flux(fb, film, u, formulation, wedge) for name, fb in ops.facet_bases.items()}
    flows = _group_flows(ops, r, direct, hdot)
    balance = flows["inlet"] - outflow(flows) - flows["squeeze"]
    if cavitated is None:
        return flows, float(balance)
    cavitation = float(np.sum(r[cavitated]))
    ruptured = ruptured_elements(ops.basis, u, cavitated)
    corrected = dict(flows)
    if ruptured.any():
        source = np.where(ruptured[:, None], 0.5 * wedge * at.dh[0] + hdot, 0.0)
        corrected = _group_flows(ops, r + forms.load.assemble(ops.basis, f=source), direct, hdot)
    corrected["cavitation"] = (cavitation + (corrected["inlet"] - flows["inlet"])
                               - (outflow(corrected) - outflow(flows)))
    return corrected, float(balance - cavitation)


def _group_flows(ops: Operators, r: np.ndarray, direct: Mapping[str, np.ndarray], hdot) -> dict[str, float]:
    """Flows through the boundary groups from the nodal residual ``r`` (corners split by ``direct``)."""
    shared = np.zeros(ops.n_dofs)
    for name, (dofs, weights) in ops.flow_groups.items():
        if name in direct:
            shared[dofs[weights < 1]] += direct[name][dofs[weights < 1]]
    flows = {}
    for name, (dofs, weights) in ops.flow_groups.items():
        corner = weights < 1
        value = np.sum(r[dofs[~corner]])
        if corner.any():
            c = dofs[corner]
            value += np.sum(direct[name][c] + (r[c] - shared[c]) * weights[corner])
        flows[name] = float(value)
    flows["inlet"] = -flows["inlet"] if "inlet" in flows else 0.0  # out of the pockets into the film
    flows["squeeze"] = float(np.sum(hdot * ops.basis.dx))
    return flows


def outflow(flows: Mapping[str, float]) -> float:
    """Flow out through the boundary groups (everything but the pocket inflow, the squeeze and
    the cavitation term)."""
    return float(sum(v for k, v in flows.items() if k not in ("inlet", "squeeze", "cavitation")))


def _facet_flux(fb: skfem.FacetBasis, film: Film, u: np.ndarray, formulation: str, wedge: float) -> np.ndarray:
    """``int q . n v ds`` on the facets of ``fb`` from the solution gradient."""
    x = np.array(fb.global_coordinates())
    at = film_at(film, x)
    field_ = fb.interpolate(u)
    _, dp = pressure_from_unknown(np.array(field_), field_.grad, at.h, at.dh, formulation)
    n = np.array(fb.normals)
    q0, q1 = film_flux(at.h, dp, wedge)
    return forms.load.assemble(fb, f=q0 * n[0] + q1 * n[1])


def ruptured_elements(basis: skfem.CellBasis, u: np.ndarray, cavitated: np.ndarray) -> np.ndarray:
    """Elements with zero pressure at every dof and at least one ruptured dof."""
    dofs = basis.element_dofs
    return np.all(u[dofs] == 0.0, axis=0) & np.any(cavitated[dofs], axis=0)


# -- the result -----------------------------------------------------------------

def build_result(sup: Superposition, u: np.ndarray, weights: np.ndarray, sliding: float | None = None, *,
                 cavitation: str = "none", iterations: int = 0, cavitated: np.ndarray | None = None,
                 extra_cost: Mapping[str, float] | None = None) -> "ReynoldsResult":
    """The :class:`ReynoldsResult` of an unknown field ``u`` of a film state.

    Parameters
    ----------
    sup : Superposition
        The film state (operators, film, formulation).
    u : ndarray, shape (n_dofs,)
        The unknown (``p`` or ``Pi``) on all dofs.
    weights : ndarray, shape (4,)
        The operating point as weights of the unit sources (:func:`source_weights`).
    sliding : float, optional
        Couette speed of the shear; default the wedge weight.
    cavitation : str
        Name of the model that produced ``u`` (``"none"``: the linear
        superposition, whose force and ``int p`` are the weighted unit loads).
    iterations : int
        Iterations of the model's nonlinear solve.
    cavitated : ndarray of bool, optional
        Ruptured dofs; with it the flows get a ``"cavitation"`` entry (see
        :func:`_flows`) and the loads are integrated from ``u``.
    extra_cost : mapping, optional
        Model wall times merged into ``cost``.
    """
    start = time.perf_counter()
    ops, at = sup.operators, sup.at
    wedge, inlet_pressure = float(weights[0]), float(weights[3])
    sliding = wedge if sliding is None else float(sliding)
    if sup.assembly == "compiled":
        out = film_outputs([sup], u[:, None], np.asarray(weights, float)[:, None], np.array([sliding]),
                           None if cavitated is None else cavitated[:, None])
        flows = {k: float(v[0]) for k, v in out.flows.items()}
        balance, friction = float(out.mass_balance[0]), float(out.friction[0])
    else:
        _, dp = pressure_at_quadrature(ops, at, u, sup.formulation)
        flows, balance = _flows(ops, sup.film, at, u, sup.formulation, dp, wedge, weights[1:3], cavitated)
        friction = float(np.sum(shear(at.h, dp[0], sliding) * ops.basis.dx))
    if cavitated is None:
        force, integral = sup.forces @ weights, float(sup.integrals @ weights)
    else:
        force, integral = sup.loads(u, inlet_pressure)
    cost = dict(sup.cost, **(extra_cost or {}), postprocess=time.perf_counter() - start)
    return ReynoldsResult(
        basis=ops.basis, pressure=_pressure_dofs(ops, sup.film, u, sup.formulation), film=sup.film,
        wedge=wedge, squeeze=(float(weights[1]), float(weights[2])), inlet_pressure=inlet_pressure,
        formulation=sup.formulation, element=ops.element, force=force, integral=integral,
        h_min=sup.h_min, flows=MappingProxyType(flows), mass_balance=float(balance), friction=friction,
        coercivity=sup.coercivity, notes=sup.notes, cost=MappingProxyType(cost),
        cavitation=cavitation, iterations=int(iterations), cavitated=cavitated)


def film_outputs(sups: Sequence[Superposition], u: np.ndarray, weights: np.ndarray, sliding: np.ndarray,
                 cavitated: np.ndarray | None = None) -> FilmFlows:
    """Flows, mass balance and friction of many film states of one mesh at once (compiled maps).

    Parameters
    ----------
    sups : sequence of Superposition, length S
        Film states on the same mesh and element.
    u : ndarray, shape (n_dofs, S)
        An unknown field of each state.
    weights : ndarray, shape (4, S)
        Unit-source weights of each (:func:`source_weights`).
    sliding : ndarray, shape (S,)
        Couette speed of the shear of each.
    cavitated : ndarray of bool, shape (n_dofs, S), optional
        Ruptured dofs of each.

    Returns
    -------
    FilmFlows
        Arrays over the samples, as :class:`ReynoldsResult` has them for one
        (``flows`` [omega R0^2 c], ``mass_balance``, ``friction`` [mu omega R0^4 / c]).
    """
    ops = sups[0].operators
    if any(s.operators is not ops for s in sups):
        raise ValueError("film_outputs needs film states of one mesh and element")
    h = np.stack([s.at.h.ravel() for s in sups], axis=1)
    dh = np.stack([np.stack([s.at.dh[0].ravel(), s.at.dh[1].ravel()]) for s in sups], axis=2)
    shapes = np.stack([np.stack([s.at.shapes[0].ravel(), s.at.shapes[1].ravel()]) for s in sups], axis=2)
    hdot = weights[1] * shapes[0] + weights[2] * shapes[1]
    pi = np.array([s.formulation == "pi" for s in sups])
    return ops.compiled.outputs(u, [s.film for s in sups], h, dh, hdot, weights, np.asarray(sliding, float), pi,
                                cavitated)


@dataclass(frozen=True, eq=False)
class ReynoldsResult:
    """Solution of the Reynolds equation for one film state and operating point.

    Attributes
    ----------
    basis : skfem.CellBasis
        The finite-element basis; ``pressure`` holds its dofs.
    pressure : ndarray
        Non-dimensional pressure ``p = P c^2 / (mu omega R0^2)`` at the dofs
        (``p``, not ``Pi``, for both formulations).
    force : ndarray, shape (2,)
        ``int p (cos phi, sin phi) dphi dz`` over the surface, pockets
        included at their pressure [units mu omega R0^4 / c^2].
    integral : float
        ``int p dphi dz`` (the load of a flat pad), pockets included.
    h_min : float
        Smallest film thickness over the surface [c].
    flows : mapping
        ``inlet`` (out of the pockets into the film), ``side`` (out through
        z = +-a), ``arc_start``, ``arc_end`` (out through the arc edges; only
        ``outer`` for a non-rectangular outline) and ``squeeze``
        (``int dh/dt``) [units omega R0^2 c]. Inlet = outflows + squeeze.
    mass_balance : float
        ``inlet - outflows - squeeze``: zero up to discretization error.
    friction : float
        Shear force on the journal surface ``int (sliding/h + h/2 dp/dphi)``
        over the film, which is also the friction moment [mu omega R0^4/c]
        (the deep pockets carry negligible shear).
    formulation, element : str
        What was used (``formulation`` is ``"direct"`` after a fallback).
    coercivity : float
        Smallest-eigenvalue bound of the pi operator (NaN for direct).
    notes : tuple of str
        Decisions the solver made on its own.
    cost : mapping
        Wall times [s]: ``mesh_operators`` (once per mesh), ``assembly``,
        ``factorization``, ``solve``, ``postprocess``; and ``dofs``.
    cavitation : str
        Cavitation model used (see :mod:`bearingfe.cavitation.models`).
    iterations : int
        Active-set iterations of the cavitation solve (0 without).
    cavitated : ndarray of bool or None
        Ruptured dofs (``p = p_c`` imposed by the cavitation condition).
    theta : ndarray or None
        Fill fraction at the dofs (``cavitation="jfo"`` only; 1 in the full film).
    cavitated_fraction : float
        Film area with ``theta < 1`` (``"jfo"``) or ruptured (finite-volume
        ``"reynolds"``) over the film area.
    cavitation_pressure : float
        Cavity pressure ``p_c`` [-] (gauge).
    deflection : ndarray or None
        Film opening by an elastic support [c] at the dofs (``film`` is then
        the deflected film); None on rigid surfaces (:mod:`bearingfe.elastic.coupled`).
    elastic_iterations : int
        Reynolds solves of the coupled elastic (EHD) Newton iteration (0: rigid).
    """

    basis: skfem.CellBasis
    pressure: np.ndarray
    film: Film
    wedge: float
    squeeze: tuple[float, float]
    inlet_pressure: float
    formulation: str
    element: str
    force: np.ndarray
    integral: float
    h_min: float
    flows: Mapping[str, float]
    mass_balance: float
    friction: float
    coercivity: float
    notes: tuple[str, ...]
    cost: Mapping[str, float]
    cavitation: str = "none"
    iterations: int = 0
    cavitated: np.ndarray | None = None
    theta: np.ndarray | None = None
    cavitated_fraction: float = 0.0
    cavitation_pressure: float = 0.0
    deflection: np.ndarray | None = None
    elastic_iterations: int = 0

    @property
    def max_deflection(self) -> float:
        """Largest film opening by the elastic support [c] (0 on rigid surfaces)."""
        return 0.0 if self.deflection is None else float(np.max(self.deflection, initial=0.0))

    @property
    def max_pressure(self) -> float:
        """Largest nodal pressure (pockets included)."""
        return float(max(self.pressure.max(), self.inlet_pressure))

    def interpolate(self, phi, z) -> np.ndarray:
        """Pressure at arbitrary points of the film (NaN-free: points must lie in the mesh)."""
        pts = np.vstack([np.ravel(phi), np.ravel(z)]).astype(float)
        return (probes(self.basis, pts) @ self.pressure).reshape(np.shape(phi))


def probes(basis: skfem.CellBasis, x: np.ndarray) -> sp.coo_matrix:
    """``basis.probes(x)``, also on curved MeshTri2 meshes.

    scikit-fem has no element finder for quadratic meshes, so cells are
    found on the straight-sided mesh of the same vertices and the reference
    coordinates then come from the curved (isoparametric) mapping.
    """
    if not isinstance(basis.mesh, skfem.MeshTri2):
        return basis.probes(x)
    cells = skfem.MeshTri1(basis.mesh.p, basis.mesh.t).element_finder()(*x)
    ref = basis.mapping.invF(x[:, :, None], tind=cells)
    values = np.array([basis.elem.gbasis(basis.mapping, ref, k, tind=cells)[0]
                       for k in range(basis.Nbfun)]).ravel()
    rows = np.tile(np.arange(x.shape[1]), basis.Nbfun)
    cols = basis.element_dofs[:, cells].ravel()
    return sp.coo_matrix((values, (rows, cols)), shape=(x.shape[1], basis.N))


