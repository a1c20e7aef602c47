r"""Finite-element solution of the Reynolds equation on a support surface.

Non-dimensional form (see ``docs/formulations.md``)::

    div(h^3 grad p) = 6 wedge dh/dphi + 12 (gamma_rate dh/dgamma + phi0_rate dh/dphi0)

in the film region of the unwrapped plane ``(phi, z)``, with ``p = 0`` on
the outline and ``p = p_s`` on the pocket contours. Rates are per radian of
shaft turn; the scales are ``P = mu omega R0^2 / c^2 p``.

Two formulations:

``"direct"``
    the conservative form above, stiffness weighted by ``h^3`` (assembled for
    each film).
``"pi"``
    the source paper's substitution ``p = h^(-3/2) Pi``:
    ``Laplace(Pi) + D Pi = h^(-3/2) f`` with
    ``D = -3/(4 h^2) (2 h Laplace(h) + |grad h|^2)``. The Laplacian is
    assembled once per mesh; only the ``D``-weighted mass matrix changes with
    the film.

Because the equation is linear in the sources, one factorization serves four
unit right sides (wedge, the two squeeze rates, inlet pressure):
:func:`superpose` returns them and :meth:`Superposition.combine` builds any
operating point, which is what the pump transient calls at each step.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import skfem
from skfem import BilinearForm, LinearForm
from skfem.helpers import dot, grad
from skfem.mapping import MappingIsoparametric

from .film import Film
from .linalg import DEFAULT_SOLVER, Factorize, get_linear_solver
from .meshing import SupportMesh

__all__ = [
    "ELEMENTS",
    "FORMULATIONS",
    "CAVITATION",
    "Operators",
    "operators",
    "Superposition",
    "superpose",
    "ReynoldsResult",
    "solve_reynolds",
    "CoercivityError",
]

ELEMENTS: Mapping[str, type] = MappingProxyType({"P1": skfem.ElementTriP1, "P2": skfem.ElementTriP2})
FORMULATIONS = ("pi", "direct")
CAVITATION = ("none", "reynolds", "gumbel", "jfo")
#: Unit sources in the order of :attr:`Superposition.fields`.
SOURCES = ("wedge", "gamma_rate", "phi0_rate", "inlet")


class CoercivityError(RuntimeError):
    """The discrete substituted (Pi) operator is not positive definite."""


# -- weak forms ---------------------------------------------------------------

@BilinearForm
def _laplace(u, v, w):
    return dot(grad(u), grad(v))


@BilinearForm
def _mass(u, v, w):
    return u * v


@BilinearForm
def _weighted_mass(u, v, w):
    return w.c * u * v


@BilinearForm
def _weighted_laplace(u, v, w):
    return w.c * dot(grad(u), grad(v))


@LinearForm
def _source(v, w):
    return w.f * v


@LinearForm
def _flux_residual(v, w):
    # int q . grad v - int dh/dt v = boundary flux of q tested with v
    return w.q0 * v.grad[0] + w.q1 * v.grad[1] - w.hdot * v


# -- per-mesh operators -------------------------------------------------------

class _TolerantMapping(MappingIsoparametric):
    """Isoparametric mapping whose inverse (Newton) stops at a step of 1e-9 in reference
    coordinates instead of scikit-fem's 1e-12, which round-off alone exceeds on curved
    elements smaller than ~1e-3 away from the origin (the iteration then never stops).
    Newton converges quadratically, so the point is accurate to round-off either way."""

    def invF(self, x, tind=None, newton_max_iters=50, newton_tol=1e-9):
        return super().invF(x, tind=tind, newton_max_iters=newton_max_iters, newton_tol=newton_tol)


def _mapping(m: skfem.Mesh):
    """``None`` (scikit-fem's default) on straight meshes, a :class:`_TolerantMapping` on curved ones."""
    if getattr(m, "affine", True):
        return None
    if not hasattr(m, "_bearingfe_mapping"):
        object.__setattr__(m, "_bearingfe_mapping", _TolerantMapping(m, m.elem(), m.bndelem))
    return m._bearingfe_mapping


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
    facet_groups: Mapping[str, np.ndarray]  # facets of the outflow groups that share corner dofs
    pocket_moments: np.ndarray  # (area, int cos phi, int sin phi) over the pockets
    phi_range: tuple[float, float]
    eigen_bound: float  # lower bound of the first Dirichlet eigenvalue
    seconds: float

    @property
    def n_dofs(self) -> int:
        return int(self.basis.N)

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
    def laplace(self) -> sp.csr_matrix:
        """Stiffness matrix ``int grad u . grad v``."""
        return self._get("laplace", lambda: _laplace.assemble(self.basis).tocsr())

    @property
    def mass(self) -> sp.csr_matrix:
        """Mass matrix ``int u v``."""
        return self._get("mass", lambda: _mass.assemble(self.basis).tocsr())

    @property
    def facet_bases(self) -> Mapping[str, skfem.FacetBasis]:
        """Facet bases of the outflow groups that share corner dofs (for the flows)."""
        order = 2 if self.element == "P2" else 1
        return self._get("facet_bases", lambda: MappingProxyType({
            n: skfem.FacetBasis(self.mesh.mesh, self.basis.elem, mapping=_mapping(self.mesh.mesh), facets=f,
                                intorder=2 * order + 2)
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


def _build_operators(mesh: SupportMesh, element: str) -> Operators:
    start = time.perf_counter()
    m = mesh.mesh
    order = 2 if element == "P2" else 1
    basis = skfem.Basis(m, ELEMENTS[element](), mapping=_mapping(m), intorder=2 * order + 2)
    bnd = mesh.boundaries
    if "outer" not in bnd:
        raise ValueError("mesh has no boundary named 'outer'")
    outer = basis.get_dofs(bnd["outer"]).all()
    inlet = basis.get_dofs(bnd["inlet"]).all() if "inlet" in bnd else np.zeros(0, dtype=np.int64)
    fixed = np.union1d(outer, inlet)
    interior = np.setdiff1d(np.arange(basis.N), fixed)
    names = [n for n in ("side", "arc_start", "arc_end") if n in bnd] or ["outer"]
    groups = _flow_groups(basis, bnd, names)
    facet_groups = {n: bnd[n] for n in names} if len(names) > 1 else {}
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
        pocket_moments=_pocket_moments(m, bnd.get("inlet"), element),
        phi_range=phi_range, eigen_bound=eigen_bound, seconds=time.perf_counter() - start)


def _flow_groups(basis, bnd, names) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Boundary dofs per outflow group; dofs shared by two groups (corners) count half to each."""
    dofs = {n: basis.get_dofs(bnd[n]).all() for n in names}
    count = np.zeros(basis.N)
    for d in dofs.values():
        count[d] += 1
    return {n: (d, 1.0 / count[d]) for n, d in dofs.items()}


def _pocket_moments(m: skfem.Mesh, inlet_facets, element: str) -> np.ndarray:
    """Area and first trigonometric moments of the pocket regions.

    The pockets are holes in the mesh, so their integrals come from the
    divergence theorem on the pocket contours: with n the film's outward
    normal (pointing into the pocket),
    ``int_P 1 = -oint phi n_phi``, ``int_P cos = -oint sin(phi) n_phi``,
    ``int_P sin = oint cos(phi) n_phi``.
    """
    if inlet_facets is None or len(inlet_facets) == 0:
        return np.zeros(3)
    fb = skfem.FacetBasis(m, skfem.ElementTriP1(), mapping=_mapping(m), facets=inlet_facets, intorder=8)
    phi = np.array(fb.global_coordinates())[0]
    nphi = np.array(fb.normals)[0]
    dx = fb.dx
    return np.array([-np.sum(phi * nphi * dx), -np.sum(np.sin(phi) * nphi * dx), np.sum(np.cos(phi) * nphi * dx)])


# -- film fields at quadrature points -----------------------------------------

@dataclass(frozen=True)
class _FilmAt:
    h: np.ndarray
    dh: tuple[np.ndarray, np.ndarray]
    shapes: tuple[np.ndarray, np.ndarray]
    D: np.ndarray


def _film_at(film: Film, x: np.ndarray) -> _FilmAt:
    h = np.asarray(film.thickness(x[0], x[1]), dtype=float)
    dh = tuple(np.asarray(g, dtype=float) for g in film.gradient(x[0], x[1]))
    lap = np.asarray(film.laplacian(x[0], x[1]), dtype=float)
    shapes = tuple(np.asarray(s, dtype=float) for s in film.rate_shapes(x[0], x[1]))
    if len(shapes) != 2:
        raise ValueError("film.rate_shapes must return two shapes (dh/dgamma, dh/dphi0)")
    with np.errstate(divide="ignore", invalid="ignore"):  # h <= 0 is reported by the caller
        D = -0.75 * (2 * h * lap + dh[0] ** 2 + dh[1] ** 2) / h**2
    return _FilmAt(h=h, dh=dh, shapes=shapes, D=D)


def _h_min(ops: Operators, film: Film, at: _FilmAt) -> float:
    exact = film.minimum(ops.phi_range) if hasattr(film, "minimum") else None
    if exact is not None:
        return float(exact)
    doflocs = ops.basis.doflocs
    return float(min(at.h.min(), np.min(film.thickness(doflocs[0], doflocs[1]))))


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
    _at: _FilmAt = field(repr=False)

    def coefficients(self, wedge: float = 1.0, inlet_pressure: float = 0.0) -> np.ndarray:
        """The paper's force coefficients in the arc frame.

        Returns ``[[a1, a2, a3], [b1, b2, b3]]`` such that the film force is
        ``(a1, b1) gamma_rate + (a2, b2) phi0_rate + (a3, b3)``.
        """
        self._check_inlet(inlet_pressure)
        constant = wedge * self.forces[:, 0] + inlet_pressure * self.forces[:, 3]
        return np.column_stack([self.forces[:, 1], self.forces[:, 2], constant])

    def force(self, wedge: float = 1.0, squeeze=(0.0, 0.0), inlet_pressure: float = 0.0) -> np.ndarray:
        """Film force ``(int p cos phi, int p sin phi)`` at an operating point."""
        self._check_inlet(inlet_pressure)
        return self.forces @ _weights(wedge, squeeze, inlet_pressure)

    def _check_inlet(self, inlet_pressure: float) -> None:
        if inlet_pressure != 0.0 and not self.operators.inlet.size:
            raise ValueError("inlet_pressure is non-zero but the mesh has no 'inlet' boundary (no pocket)")

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
        c = self.coefficients(wedge, inlet_pressure)
        matrix = c[:, :2]
        if abs(np.linalg.det(matrix)) <= 1e-14 * np.abs(matrix).max() ** 2:
            raise np.linalg.LinAlgError(
                "squeeze coefficients are singular (gamma = 0 leaves phi0_rate undetermined)")
        return np.linalg.solve(matrix, -load - c[:, 2])

    def combine(self, wedge: float = 1.0, squeeze=(0.0, 0.0), inlet_pressure: float = 0.0,
                sliding: float | None = None) -> "ReynoldsResult":
        """The full solution at an operating point (pressure, loads, flows, friction)."""
        start = time.perf_counter()
        wts = _weights(wedge, squeeze, inlet_pressure)
        self._check_inlet(inlet_pressure)
        if sliding is not None and not math.isfinite(float(sliding)):
            raise ValueError(f"sliding must be finite, got {sliding!r}")
        u = self.fields @ wts
        ops = self.operators
        p, dp = _pressure_at_quadrature(ops, self._at, u, self.formulation)
        sliding = wedge if sliding is None else float(sliding)
        flows, balance = _flows(ops, self.film, self._at, u, self.formulation, p, dp, wedge, wts[1:3])
        friction = float(np.sum((sliding / self._at.h + 0.5 * self._at.h * dp[0]) * ops.basis.dx))
        cost = dict(self.cost, postprocess=time.perf_counter() - start)
        return ReynoldsResult(
            basis=ops.basis, pressure=_pressure_dofs(ops, self.film, u, self.formulation),
            film=self.film, wedge=float(wedge), squeeze=(float(wts[1]), float(wts[2])),
            inlet_pressure=float(inlet_pressure), formulation=self.formulation, element=ops.element,
            force=self.forces @ wts, integral=float(self.integrals @ wts), h_min=self.h_min,
            flows=MappingProxyType(flows), mass_balance=balance, friction=friction,
            coercivity=self.coercivity, notes=self.notes, cost=MappingProxyType(cost))


def _weights(wedge, squeeze, inlet_pressure) -> np.ndarray:
    try:
        gr, pr = (float(s) for s in squeeze)
    except (TypeError, ValueError):
        raise ValueError(f"squeeze must be a pair (gamma_rate, phi0_rate), got {squeeze!r}") from None
    w = np.array([float(wedge), gr, pr, float(inlet_pressure)])
    if not np.all(np.isfinite(w)):
        raise ValueError(f"wedge, squeeze and inlet_pressure must be finite, got {w.tolist()}")
    return w


def _needs_finite_volumes(mesh) -> bool:
    """Recessed or periodic surfaces: only the finite-volume solver (bearingfe.jfo) handles them."""
    surface = getattr(mesh, "surface", None)
    return surface is not None and (bool(surface.recesses) or surface.periodic)


def superpose(mesh: SupportMesh, film: Film, *, formulation: str = "pi", element: str = "P1",
              solver: str | Factorize = DEFAULT_SOLVER, on_indefinite: str = "fallback") -> Superposition:
    """Factorize the Reynolds operator of a film state once and solve four unit problems.

    Parameters
    ----------
    mesh : SupportMesh
    film : Film
    formulation : {"pi", "direct"}
    element : {"P1", "P2"}
    solver : str or callable
        Sparse solver from :data:`bearingfe.linalg.LINEAR_SOLVERS`.
    on_indefinite : {"fallback", "raise"}
        What to do if the discrete pi operator is not positive definite:
        switch to the direct form (and say so in ``notes``) or raise
        :class:`CoercivityError`.
    """
    if formulation not in FORMULATIONS:
        raise ValueError(f"formulation must be one of {FORMULATIONS}, got {formulation!r}")
    if on_indefinite not in ("fallback", "raise"):
        raise ValueError(f"on_indefinite must be 'fallback' or 'raise', got {on_indefinite!r}")
    if not isinstance(film, Film):
        raise ValueError(f"film must implement the bearingfe.Film protocol, got {type(film).__name__}")
    if _needs_finite_volumes(mesh):
        raise ValueError("the surface has recesses (film steps) or is periodic: solve it with "
                         "solve_reynolds(..., cavitation='none', 'reynolds' or 'jfo'), whose finite-volume fluxes "
                         "are exact across the steps and which identifies the periodic seam")
    ops = operators(mesh, element)
    factorize = get_linear_solver(solver)
    t0 = time.perf_counter()
    at = _film_at(film, ops.x)
    h_min = _h_min(ops, film, at)
    if not h_min > 0:
        raise ValueError(f"film thickness reaches h_min = {h_min:.4g} <= 0 on the surface "
                         f"(film {film!r}): the shoe would touch the journal")
    notes: list[str] = []
    coercivity = math.nan
    A = _system_matrix(ops, at, formulation)
    if formulation == "pi":
        coercivity = _coercivity(ops, at, A)
        if not coercivity > 1e-10 * ops.eigen_bound:
            msg = (f"the discrete pi operator is not positive definite (smallest eigenvalue "
                   f"{coercivity:.3g}); the direct form div(h^3 grad p) was used instead")
            if on_indefinite == "raise":
                raise CoercivityError(msg)
            notes.append(msg)
            formulation = "direct"
            A = _system_matrix(ops, at, formulation)
    F, g = _sources(ops, film, at, formulation)
    t1 = time.perf_counter()
    I, B = ops.interior, _boundary(ops)
    solve = factorize(A[I][:, I])
    t2 = time.perf_counter()
    U = np.zeros((ops.n_dofs, 4))
    U[B] = g[B]
    rhs = -F[I] - A[I][:, B] @ g[B]
    U[I] = np.asarray(solve(rhs)).reshape(I.size, 4)
    t3 = time.perf_counter()
    forces, integrals = _unit_loads(ops, at, U, formulation)
    cost = {"assembly": t1 - t0, "factorization": t2 - t1, "solve": t3 - t2, "dofs": float(ops.n_dofs),
            "mesh_operators": ops.seconds}
    return Superposition(operators=ops, film=film, formulation=formulation, fields=U, forces=forces,
                         integrals=integrals, h_min=h_min, coercivity=coercivity, notes=tuple(notes),
                         cost=MappingProxyType(cost), _at=at)


def _boundary(ops: Operators) -> np.ndarray:
    return np.union1d(ops.outer, ops.inlet)


def _system_matrix(ops: Operators, at: _FilmAt, formulation: str) -> sp.csr_matrix:
    if formulation == "direct":
        return _weighted_laplace.assemble(ops.basis, c=at.h**3).tocsr()
    return (ops.laplace - _weighted_mass.assemble(ops.basis, c=at.D)).tocsr()


def _coercivity(ops: Operators, at: _FilmAt, A: sp.csr_matrix) -> float:
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
    AI, MI = A[I][:, I].tocsc(), ops.mass[I][:, I].tocsc()
    shift = -(max(d_max, 0.0) + 1.0)
    vals = spla.eigsh(AI, k=1, M=MI, sigma=shift, which="LM", return_eigenvectors=False)
    return float(vals.min())


def _sources(ops: Operators, film: Film, at: _FilmAt, formulation: str) -> tuple[np.ndarray, np.ndarray]:
    """Load vectors ``int f_k v`` of the four unit sources and their Dirichlet data."""
    weight = at.h**-1.5 if formulation == "pi" else 1.0
    basis = ops.basis
    F = np.column_stack([
        _source.assemble(basis, f=weight * 6.0 * at.dh[0]),
        _source.assemble(basis, f=weight * 12.0 * at.shapes[0]),
        _source.assemble(basis, f=weight * 12.0 * at.shapes[1]),
        np.zeros(basis.N),
    ])
    g = np.zeros((basis.N, 4))
    if ops.inlet.size:
        if formulation == "pi":
            loc = basis.doflocs[:, ops.inlet]
            g[ops.inlet, 3] = np.asarray(film.thickness(loc[0], loc[1])) ** 1.5
        else:
            g[ops.inlet, 3] = 1.0
    return F, g


def _pressure_at_quadrature(ops: Operators, at: _FilmAt, u: np.ndarray, formulation: str):
    """Pressure and its gradient at the quadrature points from the unknown ``u``."""
    field_ = ops.basis.interpolate(u)
    value, gradient = np.array(field_), field_.grad
    if formulation == "direct":
        return value, gradient
    s = at.h**-1.5
    p = s * value
    dp = np.array([s * gradient[k] - 1.5 * p / at.h * at.dh[k] for k in range(2)])
    return p, dp


def _unit_loads(ops: Operators, at: _FilmAt, U: np.ndarray, formulation: str):
    x, dx = ops.x, ops.basis.dx
    cos, sin = np.cos(x[0]) * dx, np.sin(x[0]) * dx
    forces = np.zeros((2, 4))
    integrals = np.zeros(4)
    for k in range(4):
        p, _ = _pressure_at_quadrature(ops, at, U[:, k], formulation)
        forces[:, k] = np.sum(p * cos), np.sum(p * sin)
        integrals[k] = np.sum(p * dx)
    forces[:, 3] += ops.pocket_moments[1:]  # pockets at unit pressure
    integrals[3] += ops.pocket_moments[0]
    return forces, integrals


def _pressure_dofs(ops: Operators, film: Film, u: np.ndarray, formulation: str) -> np.ndarray:
    if formulation == "direct":
        return u.copy()
    loc = ops.basis.doflocs
    return u * np.asarray(film.thickness(loc[0], loc[1])) ** -1.5


def _flows(ops: Operators, film: Film, at: _FilmAt, u: np.ndarray, formulation: str, p, dp,
           wedge: float, rates, ruptured: np.ndarray | None = None) -> tuple[dict[str, float], float]:
    """Consistent boundary fluxes from the weak-form residual (units omega R0^2 c).

    The flux ``q = -h^3/12 grad p + wedge h/2 e_phi`` tested with each
    boundary basis function gives the flow through that part of the
    boundary; summed over all dofs it equals ``-int dh/dt`` exactly, so the
    interior residual measures the discretization's mass-balance error.
    ``ruptured`` (a mask of elements, optional) marks where the film has
    ruptured: there the Couette flow is not conserved (``div q + dh/dt =
    wedge/2 dh/dphi + dh/dt != 0``), and that source is added back to the
    residual so that a boundary dof next to the ruptured zone reports the
    flow through the boundary only. Without it the side flow of a
    cavitated film is biased by O(element size).
    A corner dof shared by two edges (e.g. ``side`` and ``arc_start``)
    carries the flux of both: it is split by the direct facet integrals of
    ``q . n`` on each edge, and only the (small) difference between the
    residual and those integrals is shared equally.
    """
    h = at.h
    hdot = rates[0] * at.shapes[0] + rates[1] * at.shapes[1]
    q0 = -h**3 / 12.0 * dp[0] + 0.5 * wedge * h
    q1 = -h**3 / 12.0 * dp[1]
    r = _flux_residual.assemble(ops.basis, q0=q0, q1=q1, hdot=hdot)
    if ruptured is not None and ruptured.any():
        source = np.where(ruptured[:, None], 0.5 * wedge * at.dh[0] + hdot, 0.0)
        r = r + _source_load.assemble(ops.basis, s=source)
    direct = {name: _facet_flux(fb, film, u, formulation, wedge) for name, fb in ops.facet_bases.items()}
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
    outflow = _outflow(flows)
    balance = flows["inlet"] - outflow - flows["squeeze"]
    return flows, float(balance)


def _outflow(flows: dict) -> float:
    """Flow out through the boundary groups (everything but the pocket inflow and the squeeze)."""
    return float(sum(v for k, v in flows.items() if k not in ("inlet", "squeeze")))


@LinearForm
def _source_load(v, w):
    return w.s * v


@LinearForm
def _normal_flux(v, w):
    return w.qn * v


def _facet_flux(fb: skfem.FacetBasis, film: Film, u: np.ndarray, formulation: str, wedge: float) -> np.ndarray:
    """``int q . n v ds`` on the facets of ``fb`` from the solution gradient."""
    x = np.array(fb.global_coordinates())
    at = _film_at(film, x)
    field_ = fb.interpolate(u)
    p, dp = np.array(field_), field_.grad
    if formulation == "pi":
        s = at.h**-1.5
        p = s * p
        dp = np.array([s * dp[k] - 1.5 * p / at.h * at.dh[k] for k in range(2)])
    n = np.array(fb.normals)
    qn = (-at.h**3 / 12.0 * dp[0] + 0.5 * wedge * at.h) * n[0] - at.h**3 / 12.0 * dp[1] * n[1]
    return _normal_flux.assemble(fb, qn=qn)


# -- the result -----------------------------------------------------------------

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
        Cavitation model used (see :mod:`bearingfe.cavitation`).
    iterations : int
        Active-set iterations of the cavitation solve (0 without).
    cavitated : ndarray of bool or None
        Ruptured dofs (``p = p_c`` imposed by the cavitation condition).
    theta : ndarray or None
        Fill fraction at the dofs (``cavitation="jfo"`` only; 1 in the full film).
    cavitated_fraction : float
        Film area with ``theta < 1`` over the film area (``"jfo"``).
    cavitation_pressure : float
        Cavity pressure ``p_c`` [-] (gauge).
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

    @property
    def max_pressure(self) -> float:
        """Largest nodal pressure (pockets included)."""
        return float(max(self.pressure.max(), self.inlet_pressure))

    def interpolate(self, phi, z) -> np.ndarray:
        """Pressure at arbitrary points of the film (NaN-free: points must lie in the mesh)."""
        pts = np.vstack([np.ravel(phi), np.ravel(z)]).astype(float)
        return (_probes(self.basis, pts) @ self.pressure).reshape(np.shape(phi))


def _probes(basis: skfem.CellBasis, x: np.ndarray) -> sp.coo_matrix:
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


def solve_reynolds(mesh: SupportMesh, film: Film, *, wedge: float = 1.0, squeeze=(0.0, 0.0),
                   inlet_pressure: float = 0.0, formulation: str = "pi", element: str = "P1",
                   cavitation: str = "none", sliding: float | None = None,
                   solver: str | Factorize = DEFAULT_SOLVER, on_indefinite: str = "fallback",
                   warm_start=None, cavitation_pressure: float = 0.0) -> ReynoldsResult:
    """Solve the Reynolds equation on a meshed support surface.

    Parameters
    ----------
    mesh : SupportMesh
        From :func:`bearingfe.mesh_surface` or :func:`bearingfe.load_mesh`.
    film : Film
        E.g. ``CosineFilm(gamma, phi0)``.
    wedge : float
        Entrainment factor of the wedge term ``6 wedge dh/dphi`` (1 for a
        journal turning under a fixed shoe) [-].
    squeeze : (float, float)
        ``(gamma_rate, phi0_rate)`` per radian of shaft turn.
    inlet_pressure : float
        Pocket pressure ``p_s`` [-].
    formulation : {"pi", "direct"}
    element : {"P1", "P2"}
    cavitation : {"none", "reynolds", "gumbel", "jfo"}
        ``"none"`` lets the pressure go negative (as in the source paper);
        ``"reynolds"``: Swift-Stieber ``p >= 0`` with a free boundary, solved
        as a complementarity problem; ``"gumbel"``: negative part discarded
        (see :mod:`bearingfe.cavitation`); ``"jfo"``: mass-conserving
        (Elrod-Adams p-theta) cavitation, P1 only (see :mod:`bearingfe.jfo`).
    sliding : float, optional
        Sliding speed of the journal relative to the shoe for the Couette
        shear; default ``wedge``.
    solver : str or callable
        Sparse linear solver (:data:`bearingfe.linalg.LINEAR_SOLVERS`).
    on_indefinite : {"fallback", "raise"}
        See :func:`superpose`.
    warm_start : ReynoldsResult or bool mask, optional
        Rupture set of a previous cavitated solution on the same mesh, or a
        cavitated result on another (e.g. coarser) mesh of the same surface,
        interpolated: nested iteration keeps the active-set count bounded
        under refinement (docs/validation.md).
    cavitation_pressure : float
        Cavity pressure ``p_c`` [-] (gauge: the edges are at 0), ``<= 0``;
        used by ``"jfo"`` (other models need the default 0).

    Returns
    -------
    ReynoldsResult
    """
    if cavitation not in CAVITATION:
        raise ValueError(f"cavitation must be one of {CAVITATION}, got {cavitation!r}")
    if cavitation == "jfo" or (_needs_finite_volumes(mesh) and cavitation in ("none", "reynolds")):
        from .jfo import solve_jfo
        return solve_jfo(mesh, film, wedge=wedge, squeeze=squeeze, inlet_pressure=inlet_pressure,
                         cavitation_pressure=cavitation_pressure, element=element, sliding=sliding,
                         warm_start=warm_start, cavitation=cavitation)
    if float(cavitation_pressure) != 0.0:
        raise ValueError(f"cavitation_pressure is used by cavitation='jfo' only so far, got "
                         f"{cavitation_pressure!r} with cavitation={cavitation!r}")
    _weights(wedge, squeeze, inlet_pressure)
    if inlet_pressure != 0.0 and not mesh.has_inlet:
        raise ValueError("inlet_pressure is non-zero but the mesh has no 'inlet' boundary (no pocket)")
    sup = superpose(mesh, film, formulation=formulation, element=element, solver=solver,
                    on_indefinite=on_indefinite)
    if cavitation != "none":
        from .cavitation import solve_cavitating
        return solve_cavitating(sup, wedge, squeeze, inlet_pressure, sliding, model=cavitation,
                                warm_start=warm_start, solver=solver)
    return sup.combine(wedge, squeeze, inlet_pressure, sliding)
