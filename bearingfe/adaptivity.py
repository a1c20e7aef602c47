r"""A posteriori error indicators and error-driven adaptive remeshing.

The film flux (units of the flow scale ``omega R0^2 c`` per unit length)::

    q = -h^3/12 grad p + wedge h/2 e_phi,        div q + dh/dt = 0

is what the Reynolds equation conserves (see :mod:`bearingfe.film.reference`).
A finite-element pressure ``p_h`` leaves two residuals: inside each element
``R_K = div q_h + dh/dt`` and across each interior edge the jump
``J_E = [q_h . n]`` of the normal flux. :func:`error_indicators` combines
them into the classical residual estimator (Verfuerth, *A Posteriori Error
Estimation Techniques for Finite Element Methods*, OUP 2013, ch. 1)::

    eta_K^2 = h_K^2 ||R_K||_K^2 + 1/2 sum_{E in dK interior} h_E ||J_E||_E^2

optionally with every integrand divided by ``h^3/12`` (``norm="energy"``),
which makes it a robust estimate of the energy-norm error whatever the
film-thickness contrast. :func:`load_indicators` multiplies the energy
indicators of the pressure and of a dual (adjoint) pressure for the load,
so that the elements are sized for the load, the quantity the package
reports, rather than for an energy norm that weights the thin film by
``h^3``.

:func:`adapt` repeats: mesh (gmsh, exact geometry and named boundaries) ->
:func:`bearingfe.solve_reynolds` -> indicators -> new element sizes, until
the load vector changes by less than ``tol`` (relative) between two levels.
Measurements against uniform and film-graded meshes: ``docs/adaptivity.md``
(``benchmarks/adaptivity.py``).
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import skfem
from scipy.sparse.csgraph import dijkstra
from scipy.spatial import cKDTree

from .film.thickness import Film
from .geometry.surface import Surface
from .core.checks import ResolutionWarning
from .core.linalg import DEFAULT_SOLVER, get_linear_solver
from .geometry.locate import cell_diameters
from .geometry.meshing import SupportMesh, give_facet_triangles, mesh_surface
from .core.parameters import Discretization, OperatingPoint, takes
from .film import forms
from .film.forms import along, film_flux, mapping, pressure_from_unknown, unknown_scale
from .geometry.runner import velocity_at
from .reynolds import CAVITATION, ELEMENTS, FORMULATIONS, ReynoldsResult, solve_reynolds
from .film.flows import ruptured_elements

__all__ = ["INDICATORS", "NORMS", "AdaptiveLevel", "AdaptiveResult", "AdaptivityError", "adapt",
           "error_indicators", "load_indicators", "size_field", "target_sizes"]

#: Largest ratio of neighbouring element sizes the size field allows, as a slope:
#: sizes may grow by at most ``GRADING`` times the distance travelled.
GRADING = 0.4


# -- error indicators ---------------------------------------------------------------

#: Weightings of :func:`error_indicators`.
NORMS = ("flux", "energy")
#: Indicators :func:`adapt` can drive the meshes with.
INDICATORS = ("load", "energy", "flux")


@dataclass(frozen=True, eq=False)
class _Field:
    """A finite-element field and the conservation law ``div q + source = 0`` it solves, with
    ``q = -h^3/12 grad p + wedge h/2 e_phi`` and ``p = u`` (direct) or ``h^(-3/2) u`` (pi)."""

    basis: object
    film: Film
    u: np.ndarray
    formulation: str
    element: str
    wedge: float
    source: Callable[[np.ndarray], np.ndarray]
    runner: object = None   # the runner's velocity (bearingfe.geometry.runner); None: along phi


def error_indicators(result: ReynoldsResult, *, norm: str = "flux") -> np.ndarray:
    r"""Residual error indicator ``eta_K`` of each element of a Reynolds solution.

    ``norm="flux"``:
    ``eta_K^2 = h_K^2 ||div q + dh/dt||_K^2 + 1/2 sum_E h_E ||[q . n]||_E^2``
    (interior edges ``E`` of ``K``; edges with a natural boundary condition,
    i.e. boundary edges that are neither ``outer`` nor ``inlet``, add
    ``h_E ||q_p . n||_E^2`` with ``q_p = -h^3/12 grad p`` in full) for the film
    flux ``q = -h^3/12 grad p + wedge h/2 e_phi``. ``h_K`` is the element
    diameter, ``h_E`` the edge length. ``eta_K`` has the units of a flow
    [omega R0^2 c]; summed, it bounds the dual norm of the flux residual, and
    the energy norm ``(int h^3/12 |grad(p - p_h)|^2)^(1/2)`` only through a
    factor ``(12 / h_min^3)^(1/2)``.

    ``norm="energy"``: every integrand divided by ``h^3/12`` at its point
    (Bernardi & Verfuerth, Numer. Math. 85 (2000) 579): then
    ``sum eta_K^2`` bounds the squared energy norm of the error with a
    constant that depends on the shape of the triangles but not on the
    film-thickness contrast (which reaches ``(1 + eps)^3/(1 - eps)^3 ~ 8e6``
    in a journal at ``eps = 0.99``). Its units are those of the energy norm
    ``(int h^3/12 |grad p|^2)^(1/2)``.

    Both scale like ``size^(k+1)`` per element on smooth solutions for
    elements of degree ``k``.

    ``div q = -h^2/4 grad h . grad p - h^3/12 Lap p + wedge/2 dh/dphi`` is
    evaluated at the quadrature points of ``result.basis`` with the film's
    exact derivatives. ``Lap p_h`` is zero for P1 on straight triangles;
    otherwise it is the divergence of the element-wise L2 projection of
    ``grad p_h`` onto discontinuous P1, which is exact for P2 on straight
    triangles (``grad p_h`` is linear there) and a consistent approximation
    on curved (``MeshTri2``) ones. For the pi formulation ``p = h^(-3/2) Pi``
    and the product rule is applied to the finite-element field ``Pi``.

    Elements of a ruptured zone (all element dofs at zero pressure and at
    least one of them in ``result.cavitated``) get 0: the Reynolds equation
    does not hold there. The jump on an edge between a ruptured and a full
    element (the discrete free boundary, where ``dp/dn = 0`` holds exactly)
    still counts half for the full element.

    Parameters
    ----------
    result : ReynoldsResult
        P1 or P2, pi or direct formulation, with or without cavitation.
    norm : {"flux", "energy"}

    Returns
    -------
    ndarray, shape (n_elements,)
        ``eta_K >= 0``.
    """
    if not isinstance(result, ReynoldsResult):
        raise ValueError(f"result must be a bearingfe.ReynoldsResult, got {type(result).__name__}")
    if norm not in NORMS:
        raise ValueError(f"norm must be one of {NORMS}, got {norm!r}")
    return np.sqrt(_primal_squared(result, 1.0 if norm == "energy" else 0.0,
                                   _Bases(result.basis, result.element)))


def _primal_squared(result: ReynoldsResult, weight: float, bases: "_Bases") -> np.ndarray:
    """``eta_K^2`` of the pressure of ``result`` (0 on ruptured elements)."""
    film = result.film
    rates = result.squeeze

    def hdot(x):
        shapes = film.rate_shapes(x[0], x[1])
        return rates[0] * np.asarray(shapes[0], float) + rates[1] * np.asarray(shapes[1], float)

    f = _Field(basis=result.basis, film=film, u=_unknown(result), formulation=result.formulation,
               element=result.element, wedge=result.wedge, source=hdot, runner=result.runner)
    squared = _squared_indicators(f, weight, bases)
    squared[_ruptured(result)] = 0.0
    return squared


def load_indicators(result: ReynoldsResult) -> np.ndarray:
    r"""Goal-oriented indicators of the error in the load ``|force|``.

    The load error is a linear functional of the pressure error ``e``:
    ``d . (F_h - F) = int e g`` with ``g = d . (cos phi, sin phi)`` and
    ``d = F_h / |F_h|``. With the dual (adjoint) pressure ``z``,
    ``int h^3/12 grad v . grad z = int g v`` for all ``v`` vanishing on the
    outline and the pockets (and, under cavitation, on the ruptured dofs:
    the linearization on the converged rupture set), Galerkin orthogonality
    gives ``int e g = int h^3/12 grad e . grad (z - z_h)``, bounded by the
    sum over the elements of the energy-norm errors of ``p`` and ``z``.
    Each is estimated by :func:`error_indicators` with ``norm="energy"``
    (for ``z`` with the source ``g``), so

    ``theta_K = eta_K(p_h) eta_K(z_h)``

    (the product estimator of Mommer & Stevenson, SIAM J. Numer. Anal. 47
    (2009) 861) estimates the share of element ``K`` in the load error, in
    the units of the load [mu omega R0^4 / c^2] up to a shape constant. It
    scales like ``size^(2k+2)`` per element for degree ``k``. The dual
    problem is solved in the direct form with the element of ``result``
    (one more factorization).

    Unlike the energy norm, the load weights the thin-film pressure: the
    dual pressure is large where ``h`` is small, so this indicator refines
    the pressure spike of a journal near ``eps = 1``, which the flux and
    energy indicators under-weight by ``h^3``.

    Parameters
    ----------
    result : ReynoldsResult

    Returns
    -------
    ndarray, shape (n_elements,)
        ``theta_K >= 0``.
    """
    if not isinstance(result, ReynoldsResult):
        raise ValueError(f"result must be a bearingfe.ReynoldsResult, got {type(result).__name__}")
    bases = _Bases(result.basis, result.element)
    primal = np.sqrt(_primal_squared(result, 1.0, bases))
    force = load_vector(result)
    norm_f = float(np.linalg.norm(force))
    if not norm_f > 0:
        raise ValueError("load_indicators needs a non-zero film force (the load direction is undefined)")
    d = force / norm_f

    def g(x):
        if d.size == 1:  # a plane film: the load is int p, normal to the plane
            return d[0] + 0.0 * x[0]
        return d[0] * np.cos(x[0]) + d[1] * np.sin(x[0])

    z = _dual_pressure(result, g)
    f = _Field(basis=result.basis, film=result.film, u=z, formulation="direct", element=result.element,
               wedge=0.0, source=lambda x: -g(x))
    dual = _squared_indicators(f, 1.0, bases)
    dual[_ruptured(result)] = 0.0
    return primal * np.sqrt(dual)


def load_vector(result: ReynoldsResult) -> np.ndarray:
    """The load the adaptivity refines for: the force ``int p (cos phi, sin phi)`` of a film on the unwrapped
    cylinder (the original runner, along ``phi``); ``[int p]`` on a plane whose runner is another
    (:mod:`bearingfe.geometry.runner`: a thrust pad, a slider at an angle), normal to the plane."""
    if getattr(result, "runner", None) is not None:
        return np.array([float(result.integral)])
    return np.asarray(result.force, float)


def _ruptured(result: ReynoldsResult) -> np.ndarray:
    if result.cavitated is None or not np.any(result.cavitated):
        return np.zeros(result.basis.mesh.nelements, bool)
    return ruptured_elements(result.basis.element_dofs, np.asarray(result.pressure), np.asarray(result.cavitated))


def _dual_pressure(result: ReynoldsResult, g: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """``z``: ``int h^3/12 grad v . grad z = int g v``, ``z = 0`` on outline, pockets and ruptured dofs."""
    basis = result.basis
    x = np.array(basis.global_coordinates())
    h = np.asarray(result.film.thickness(x[0], x[1]), float)
    A = forms.weighted_laplace.assemble(basis, c=h**3 / 12.0).tocsr()
    b = forms.load.assemble(basis, f=g(x))
    bnd = basis.mesh.boundaries or {}
    facets = [bnd[n] for n in ("outer", "inlet") if n in bnd]
    fixed = np.zeros(basis.N, bool)
    if facets:
        fixed[basis.get_dofs(np.concatenate(facets)).all()] = True
    if result.cavitated is not None:
        fixed |= np.asarray(result.cavitated, bool)
    free = np.flatnonzero(~fixed)
    z = np.zeros(basis.N)
    if free.size:
        z[free] = get_linear_solver(DEFAULT_SOLVER)(A[free][:, free])(b[free])
    return z


def _squared_indicators(f: _Field, weight: float, bases: "_Bases") -> np.ndarray:
    """``eta_K^2`` of a field, every integrand divided by ``(h^3/12)^weight``."""
    basis = f.basis
    x = bases.x
    _, dp, lap = _pressure_fields(f, basis, x, bases.laplacian(f.u))
    h = np.asarray(f.film.thickness(x[0], x[1]), float)
    dh = [np.asarray(g, float) for g in f.film.gradient(x[0], x[1])]
    div_q = (-0.25 * h**2 * (dh[0] * dp[0] + dh[1] * dp[1]) - h**3 / 12.0 * lap
             + 0.5 * f.wedge * along(velocity_at(f.runner, x), dh))
    residual = np.sum((div_q + f.source(x)) ** 2 * (h**3 / 12.0) ** -weight * basis.dx, axis=1)
    squared = bases.diameters**2 * residual + _jump_terms(f, weight, bases) + _natural_terms(f, weight, bases)
    return np.maximum(squared, 0.0)


class _Bases:
    """Film-independent bases of the indicators of one ``basis``, built on first use and
    shared by the fields evaluated on it (the pressure and the dual pressure)."""

    def __init__(self, basis, element: str) -> None:
        self.basis = basis
        self.element = element
        self.mesh = basis.mesh
        self.x = np.array(basis.global_coordinates())
        self.diameters = cell_diameters(self.mesh)
        self.intorder = 2 * (2 if element == "P2" else 1) + 2
        self._dg = None
        self._sides = None
        self._natural = None

    def laplacian(self, u: np.ndarray) -> np.ndarray:
        """``Lap u`` at the quadrature points (see :func:`error_indicators`)."""
        basis = self.basis
        if self.element == "P1" and isinstance(self.mesh, skfem.MeshTri1):
            return np.zeros_like(basis.dx)
        if self._dg is None:
            dg = skfem.Basis(self.mesh, skfem.ElementDG(skfem.ElementTriP1()), mapping=mapping(self.mesh),
                             quadrature=(basis.X, basis.W))
            self._dg = (dg, spla.factorized(forms.mass.assemble(dg).tocsc()))  # block diagonal, 3x3 blocks
        dg, solve = self._dg
        grad = basis.interpolate(u).grad
        total = np.zeros_like(basis.dx)
        for k in range(2):
            coefficients = solve(forms.load.assemble(dg, f=np.asarray(grad[k])))
            total += np.asarray(dg.interpolate(coefficients).grad[k])
        return total

    @property
    def sides(self):
        """Both sides of the interior facets (``None`` without any)."""
        if self._sides is None:
            give_facet_triangles(self.mesh)   # the package's build of the map, cheaper than scikit-fem's
        if self._sides is None and np.any(self.mesh.f2t[1] >= 0):
            self._sides = [skfem.InteriorFacetBasis(self.mesh, self.basis.elem, mapping=mapping(self.mesh),
                                                    side=k, intorder=self.intorder) for k in (0, 1)]
        return self._sides

    @property
    def natural(self):
        """Facet basis of the boundary edges that are neither ``outer`` nor ``inlet`` (or ``None``)."""
        if self._natural is None:
            bnd = self.mesh.boundaries or {}
            empty = np.zeros(0, np.int64)
            natural = np.setdiff1d(self.mesh.boundary_facets(),
                                   np.union1d(bnd.get("outer", empty), bnd.get("inlet", empty)))
            self._natural = (skfem.FacetBasis(self.mesh, self.basis.elem, mapping=mapping(self.mesh),
                                              facets=natural, intorder=self.intorder)
                             if natural.size else False)
        return self._natural or None


def _unknown(result: ReynoldsResult) -> np.ndarray:
    """The finite-element unknown: ``p`` (direct) or ``Pi = h^(3/2) p`` (pi) at the dofs."""
    pressure = np.asarray(result.pressure, float)
    if result.formulation == "direct":
        return pressure
    loc = result.basis.doflocs
    return pressure / unknown_scale(result.film.thickness(loc[0], loc[1]), result.formulation)


def _pressure_fields(f: _Field, basis, x: np.ndarray, lap_u):
    """``p``, ``grad p`` (and ``Lap p`` if ``lap_u`` is given) at the points ``x`` of ``basis``."""
    field_ = basis.interpolate(f.u)
    value, grad = np.array(field_), np.array(field_.grad)
    if f.formulation == "direct":
        return value, grad, lap_u
    film = f.film
    h = np.asarray(film.thickness(x[0], x[1]), float)
    dh = np.array([np.asarray(g, float) for g in film.gradient(x[0], x[1])])
    p, dp = pressure_from_unknown(value, grad, h, dh, f.formulation)
    if lap_u is None:
        return p, dp, None
    s = h**-1.5
    ds = -1.5 * h**-2.5 * dh
    lap_h = np.asarray(film.laplacian(x[0], x[1]), float)
    lap_s = -1.5 * h**-2.5 * lap_h + 3.75 * h**-3.5 * (dh[0] ** 2 + dh[1] ** 2)
    return p, dp, lap_s * value + 2.0 * (ds[0] * grad[0] + ds[1] * grad[1]) + s * lap_u


def _facet_lengths(mesh, facets: np.ndarray) -> np.ndarray:
    p, f = mesh.p, mesh.facets[:, facets]
    return np.linalg.norm(p[:, f[0]] - p[:, f[1]], axis=0)


def _pressure_flux_normal(f: _Field, fb, normals: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``-h^3/12 grad p . n`` at the quadrature points of a facet basis (the wedge part
    of ``q . n`` is continuous across edges and drops out of the jumps)."""
    x = np.array(fb.global_coordinates())
    _, dp, _ = _pressure_fields(f, fb, x, None)
    h = np.asarray(f.film.thickness(x[0], x[1]), float)
    q0, q1 = film_flux(h, dp, 0.0)
    return q0 * normals[0] + q1 * normals[1], h


def _jump_terms(f: _Field, weight: float, bases: _Bases) -> np.ndarray:
    """``1/2 h_E ||[q . n]||_E^2`` of the interior edges, summed onto both neighbours."""
    mesh = f.basis.mesh
    out = np.zeros(mesh.nelements)
    sides = bases.sides
    if sides is None:
        return out
    normals = np.array(sides[0].normals)  # both sides use the outward normal of side 0
    q0, h = _pressure_flux_normal(f, sides[0], normals)
    q1, _ = _pressure_flux_normal(f, sides[1], normals)
    jump = (q0 - q1) * (h**3 / 12.0) ** (-weight / 2)
    edge = 0.5 * _facet_lengths(mesh, sides[0].find) * np.sum(jump**2 * sides[0].dx, axis=1)
    np.add.at(out, sides[0].tind, edge)
    np.add.at(out, sides[1].tind, edge)
    return out


def _natural_terms(f: _Field, weight: float, bases: _Bases) -> np.ndarray:
    """``h_E ||h^3/12 dp/dn||_E^2`` on boundary edges without a Dirichlet condition."""
    mesh = f.basis.mesh
    out = np.zeros(mesh.nelements)
    fb = bases.natural
    if fb is None:
        return out
    flux, h = _pressure_flux_normal(f, fb, np.array(fb.normals))
    flux = flux * (h**3 / 12.0) ** (-weight / 2)
    np.add.at(out, fb.tind, _facet_lengths(mesh, fb.find) * np.sum(flux**2 * fb.dx, axis=1))
    return out


# -- target sizes -----------------------------------------------------------------------

def _mean_edges(mesh) -> np.ndarray:
    """Mean edge length of each (vertex) triangle: the size gmsh aims at."""
    p, t = mesh.p, mesh.t[:3]
    return np.mean([np.linalg.norm(p[:, t[i]] - p[:, t[(i + 1) % 3]], axis=0) for i in range(3)], axis=0)


def target_sizes(mesh: SupportMesh, eta: np.ndarray, *, rate: float, growth: float, size: float,
                 min_size: float) -> tuple[np.ndarray, float]:
    """Element sizes for the next mesh by equidistribution of the indicators.

    ``s_K = h_K (t / eta_K)^(1/rate)`` for indicators that scale like
    ``eta_K ~ h_K^rate`` (``k+1`` for the flux and energy indicators of
    degree ``k``, ``2k+2`` for the load indicator), clipped
    to ``[max(h_K/4, min_size), min(2 h_K, size)]``, with the level ``t``
    chosen (bisection on ``log t``) so that the new mesh has about
    ``growth`` times as many elements (``sum (h_K/s_K)^2``).

    Returns
    -------
    sizes : ndarray, shape (n_elements,)
    at_floor : float
        Fraction of the elements whose size is held up by ``min_size``
        (refinement limited by it).
    """
    h = _mean_edges(mesh.mesh)
    lower = np.minimum(np.maximum(h / 4, min_size), size)
    upper = np.maximum(np.minimum(2 * h, size), lower)
    eta = np.asarray(eta, float)

    def sizes(log_t):
        with np.errstate(divide="ignore"):
            s = h * np.exp((log_t - np.log(eta)) / rate)
        return np.clip(s, lower, upper)

    wanted = growth * h.size
    positive = eta[eta > 0]
    if positive.size == 0:
        return upper, 0.0
    lo, hi = math.log(positive.min()) - 10.0, math.log(positive.max()) + 10.0  # all at lower / upper clip
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if np.sum((h / sizes(mid)) ** 2) > wanted:
            lo = mid
        else:
            hi = mid
    s = sizes(hi)
    at_floor = float(np.mean((s <= lower * (1 + 1e-9)) & (min_size > h / 4)))
    return s, at_floor


def size_field(mesh: SupportMesh, sizes: np.ndarray, grading: float = GRADING) -> Callable:
    """``f(phi, z) -> size`` for :func:`bearingfe.mesh_surface` from element sizes.

    Nodal sizes are the smallest of the adjacent elements', then limited to
    grow by at most ``grading`` per unit distance along mesh edges (exact
    multi-source shortest paths), so that gmsh sees a smooth field; a query
    point takes the size of the nearest node of ``mesh`` (which differs from
    the linear interpolant by at most ``grading`` times an element size).
    """
    m = mesh.mesh
    t, nv = m.t[:3], m.p.shape[1]
    nodal = np.full(nv, np.inf)
    for i in range(3):
        np.minimum.at(nodal, t[i], sizes)
    used = np.isfinite(nodal)
    a, b = m.facets[0], m.facets[1]
    length = grading * np.linalg.norm(m.p[:, a] - m.p[:, b], axis=0)
    source = np.flatnonzero(used)
    rows = np.concatenate([a, b, np.full(source.size, nv)])
    cols = np.concatenate([b, a, source])
    graph = sp.csr_matrix((np.concatenate([length, length, nodal[source]]), (rows, cols)), shape=(nv + 1, nv + 1))
    limited = dijkstra(graph, directed=True, indices=nv)[:nv]
    points = m.p[:, used].T
    values = limited[used]
    tree = cKDTree(points)

    def f(phi, z):
        _, k = tree.query((float(phi), float(z)))
        return float(values[k])

    return f


# -- the adaptive loop --------------------------------------------------------------------

@dataclass(frozen=True)
class AdaptiveLevel:
    """One mesh of an adaptive sequence.

    Attributes
    ----------
    n_nodes, n_elements, n_dofs : int
        Mesh vertices, triangles and finite-element unknowns.
    force : ndarray, shape (2,)
        ``int p (cos phi, sin phi)`` [mu omega R0^4 / c^2].
    load : float
        ``|force|``.
    estimate : float
        ``|force - force_previous| / |force|`` (NaN on the first level).
    indicator : float
        ``(sum eta_K^2)^(1/2)`` of the indicator that drives the meshes
        (units as in :func:`error_indicators` / :func:`load_indicators`).
    smallest_size : float
        Shortest element edge [-].
    iterations : int
        Active-set iterations of the cavitation solve (0 without).
    meshing_seconds, solve_seconds, seconds : float
        gmsh time (with the size field), :func:`solve_reynolds` time, and the
        whole level (meshing, solve, indicators, next sizes) [s].
    """

    n_nodes: int
    n_elements: int
    n_dofs: int
    force: np.ndarray
    load: float
    estimate: float
    indicator: float
    smallest_size: float
    iterations: int
    meshing_seconds: float
    solve_seconds: float
    seconds: float


@dataclass(frozen=True, eq=False)
class AdaptiveResult:
    """Outcome of :func:`adapt`.

    Attributes
    ----------
    result : ReynoldsResult
        Solution on the last mesh.
    mesh : SupportMesh
        The last mesh.
    levels : tuple of AdaptiveLevel
        Every mesh of the sequence, coarse to fine.
    indicators : ndarray
        ``eta_K`` on the last mesh.
    converged : bool
        Whether the load changed by less than ``tol`` between the last two levels.
    tol : float
    reason : str
        Why the loop stopped (``"converged"``, or the limit that stopped it).
    """

    result: ReynoldsResult
    mesh: SupportMesh
    levels: tuple[AdaptiveLevel, ...]
    indicators: np.ndarray = field(repr=False)
    converged: bool
    tol: float
    reason: str

    @property
    def error_estimate(self) -> float:
        """Relative change of the load vector between the last two levels."""
        return self.levels[-1].estimate

    @property
    def force(self) -> np.ndarray:
        return self.result.force

    @property
    def load(self) -> float:
        return float(np.linalg.norm(load_vector(self.result)))

    @property
    def n_nodes(self) -> tuple[int, ...]:
        return tuple(lv.n_nodes for lv in self.levels)

    @property
    def seconds(self) -> float:
        return float(sum(lv.seconds for lv in self.levels))


_INDICATOR_FUNCTIONS = {
    "load": load_indicators,
    "energy": lambda r: error_indicators(r, norm="energy"),
    "flux": error_indicators,
}


def _check_inputs(surface, film, size, tol, max_levels, min_size, growth, max_nodes, formulation, element,
                  cavitation, on_unconverged, indicator) -> tuple[float, float]:
    if not isinstance(surface, Surface):
        raise ValueError(f"surface must be a bearingfe.Surface, got {type(surface).__name__}")
    if not isinstance(film, Film):
        raise ValueError(f"film must implement the bearingfe.Film protocol, got {type(film).__name__}")
    size = float(size)
    if not (math.isfinite(size) and size > 0):
        raise ValueError(f"size must be a finite element size > 0, got {size!r}")
    if not (isinstance(tol, (int, float)) and 0 < tol < 1):
        raise ValueError(f"tol must be in (0, 1) (relative load change), got {tol!r}")
    if not (isinstance(max_levels, int) and not isinstance(max_levels, bool) and 2 <= max_levels <= 30):
        raise ValueError(f"max_levels must be an integer in 2..30, got {max_levels!r}")
    min_size = size * 1e-6 if min_size is None else float(min_size)
    if not (math.isfinite(min_size) and 0 < min_size <= size):
        raise ValueError(f"min_size must be in (0, size={size:g}], got {min_size!r}")
    if not (isinstance(growth, (int, float)) and 1.2 <= growth <= 16):
        raise ValueError(f"growth must be in [1.2, 16] (element-count factor per level), got {growth!r}")
    if not (isinstance(max_nodes, int) and max_nodes >= 100):
        raise ValueError(f"max_nodes must be an integer >= 100, got {max_nodes!r}")
    if formulation not in FORMULATIONS:
        raise ValueError(f"formulation must be one of {FORMULATIONS}, got {formulation!r}")
    if element not in ELEMENTS:
        raise ValueError(f"element must be one of {list(ELEMENTS)}, got {element!r}")
    if cavitation not in CAVITATION:
        raise ValueError(f"cavitation must be one of {CAVITATION}, got {cavitation!r}")
    if indicator not in INDICATORS:
        raise ValueError(f"indicator must be one of {INDICATORS}, got {indicator!r}")
    if on_unconverged not in ("warn", "raise"):
        raise ValueError(f"on_unconverged must be 'warn' or 'raise', got {on_unconverged!r}")
    return size, min_size


class AdaptivityError(RuntimeError):
    """The adaptive loop stopped before the load met the tolerance (``on_unconverged="raise"``)."""


@takes(OperatingPoint, Discretization, rename={"mesh_size": "size"})
def adapt(surface: Surface, film: Film, *, size: float, tol: float = 1e-3, max_levels: int = 8,
          wedge: float = 1.0, squeeze=(0.0, 0.0), inlet_pressure: float = 0.0, formulation: str = "direct",
          element: str = "P1", cavitation: str = "none", min_size: float | None = None,
          indicator: str = "load", growth: float = 2.5, max_nodes: int = 400_000, solver=DEFAULT_SOLVER,
          on_unconverged: str = "warn", on_level: Callable[[AdaptiveLevel], None] | None = None,
          verbose: bool = False) -> AdaptiveResult:
    """Solve the Reynolds equation on a sequence of error-adapted gmsh meshes.

    Level 0 is a uniform mesh of ``size``. Each further mesh is made by gmsh
    from the surface itself (exact curved pocket outlines, named boundaries)
    with a size field from the previous level's indicators
    (:func:`target_sizes`: equidistribution at about ``growth`` times the
    elements; :func:`size_field`: graded, nearest-node lookup). Cavitated
    solves (``"reynolds"``) start from the previous level's rupture set
    (nested iteration). The loop stops when the load vector (:func:`load_vector`: the force on a
    journal-like film, ``int p`` on a plane pad) changes by less than ``tol`` between two successive levels,
    ``|F_n - F_(n-1)| / |F_n| < tol``; that change is the reported error
    estimate. If the error falls by a factor ``r`` per level it
    overestimates the last level's error by ``r - 1`` (measured: 2 to 10);
    like any difference of two levels it can, rarely, be small by
    coincidence while the error is not.

    Parameters
    ----------
    surface : Surface
    film : Film
    size : float
        Element size of the first mesh and the largest size ever used [-], > 0.
    tol : float
        Relative load change that ends the loop, in (0, 1).
    max_levels : int
        Most meshes (solves), 2..30.
    wedge, squeeze, inlet_pressure, formulation, element, cavitation, solver
        As in :func:`bearingfe.solve_reynolds` (P2 uses curved order-2 geometry).
    operating : OperatingPoint, optional
        ``wedge``, ``squeeze`` and ``inlet_pressure`` in one object
        (:class:`bearingfe.core.parameters.OperatingPoint`; ``sliding`` is not used).
    discretization : Discretization, optional
        ``element``, ``formulation``, ``solver``, ``size`` (its ``mesh_size``)
        and ``min_size`` in one object (:class:`bearingfe.core.parameters.Discretization`).
    min_size : float, optional
        Smallest element size [-], in ``(0, size]``; default ``size * 1e-6``
        (no practical limit). If the sizes asked for fall below it the
        refinement stalls there and a warning says so.
    indicator : {"load", "energy", "flux"}
        What drives the sizes: :func:`load_indicators` (goal-oriented, the
        default), or :func:`error_indicators` with ``norm="energy"`` or
        ``"flux"``.
    growth : float
        Element-count factor from one level to the next, in [1.2, 16].
    max_nodes : int
        The loop stops (unconverged) rather than solve on a mesh with more nodes.
    on_unconverged : {"warn", "raise"}
        If ``tol`` is not met: issue a :class:`bearingfe.bearings.journal.ResolutionWarning`
        naming the cause and return the last level, or raise :class:`AdaptivityError`.
    on_level : callable, optional
        Called with each finished :class:`AdaptiveLevel` (progress reporting).
    verbose : bool
        Let gmsh print its log.

    Returns
    -------
    AdaptiveResult
    """
    size, min_size = _check_inputs(surface, film, size, tol, max_levels, min_size, growth, max_nodes,
                                   formulation, element, cavitation, on_unconverged, indicator)
    order = 2 if element == "P2" else 1
    rate = (order + 1) * (2 if indicator == "load" else 1)
    levels: list[AdaptiveLevel] = []
    previous = None
    size_function, held, reason = None, 0.0, f"max_levels={max_levels} reached"
    for level in range(max_levels):
        start = time.perf_counter()
        mesh = mesh_surface(surface, size, size_function=size_function, order=order, verbose=verbose,
                            min_size=min_size if size_function is not None else None)
        meshed = time.perf_counter()
        if mesh.n_nodes > max_nodes:
            if previous is None:
                raise ValueError(f"the first mesh (size={size:g}) has {mesh.n_nodes} nodes > "
                                 f"max_nodes={max_nodes}: use a larger size")
            reason = f"the next mesh has {mesh.n_nodes} nodes > max_nodes={max_nodes}"
            break
        res = solve_reynolds(mesh, film, wedge=wedge, squeeze=squeeze, inlet_pressure=inlet_pressure,
                             formulation=formulation, element=element, cavitation=cavitation, solver=solver,
                             warm_start=previous.result if (cavitation == "reynolds" and previous) else None)
        solved = time.perf_counter()
        estimate = _load_change(res, previous.result if previous else None, level)
        eta = _INDICATOR_FUNCTIONS[indicator](res)
        converged = estimate < tol  # False on the first level (NaN)
        next_held = held
        if not converged and level + 1 < max_levels:
            sizes, next_held = target_sizes(mesh, eta, rate=rate, growth=growth, size=size, min_size=min_size)
            size_function = size_field(mesh, sizes)
        levels.append(_level_record(mesh, res, eta, estimate, start, meshed, solved))
        if on_level is not None:
            on_level(levels[-1])
        previous = AdaptiveResult(result=res, mesh=mesh, levels=tuple(levels), indicators=eta,
                                  converged=bool(converged), tol=float(tol), reason="converged")
        if converged:
            if held > 0:
                warnings.warn(ResolutionWarning(_held_text(held, min_size) + ": the load change "
                                                f"{estimate:.3g} may understate the error"), stacklevel=2)
                return replace(previous, reason="converged; " + _held_text(held, min_size))
            return previous
        held = next_held
    if held > 0:
        reason += "; " + _held_text(held, min_size)
    message = (f"adapt() stopped before the load converged: {reason}; the last load change is "
               f"{levels[-1].estimate:.3g} (tol={tol:g}) on {levels[-1].n_nodes} nodes. Raise max_levels "
               "or max_nodes, lower min_size, or loosen tol")
    if on_unconverged == "raise":
        raise AdaptivityError(message)
    warnings.warn(ResolutionWarning(message), stacklevel=2)
    return replace(previous, converged=False, reason=reason)


def _load_change(res: ReynoldsResult, previous: ReynoldsResult | None, level: int) -> float:
    """``|F - F_previous| / |F|`` (NaN without a previous level)."""
    load = float(np.linalg.norm(load_vector(res)))
    if not (math.isfinite(load) and load > 0):
        raise ValueError(f"the load |force| = {load!r} on level {level}: a relative load change is "
                         "undefined (no film force); adapt() needs a loaded film")
    if previous is None:
        return math.nan
    return float(np.linalg.norm(load_vector(res) - load_vector(previous))) / load


def _held_text(held: float, min_size: float) -> str:
    return (f"{100 * held:.2g} % of the elements of the last mesh were held at min_size={min_size:.3g}, "
            "which limits the refinement")


def _level_record(mesh: SupportMesh, res: ReynoldsResult, eta: np.ndarray, estimate: float, start: float,
                  meshed: float, solved: float) -> AdaptiveLevel:
    p, f = mesh.mesh.p, mesh.mesh.facets
    return AdaptiveLevel(
        n_nodes=mesh.n_nodes, n_elements=mesh.n_elements, n_dofs=int(res.basis.N), force=res.force.copy(),
        load=float(np.linalg.norm(load_vector(res))), estimate=estimate, indicator=float(np.sqrt(np.sum(eta**2))),
        smallest_size=float(np.linalg.norm(p[:, f[0]] - p[:, f[1]], axis=0).min()),
        iterations=int(res.iterations), meshing_seconds=meshed - start, solve_seconds=solved - meshed,
        seconds=time.perf_counter() - start)
