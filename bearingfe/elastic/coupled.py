r"""Elastic support: compliance of the film surfaces and the coupled (EHD) film.

Under pressure the shoe and the eccentric deform; the film becomes
``h = h_rigid + w(p)`` (all in units of the clearance ``c``). This module
builds the linear map ``w = C p`` once per mesh (the *compliance*) and solves
the Reynolds equation on the deforming film.

Elastic half-space (Boussinesq)
-------------------------------
Two elastic half-spaces pressed apart by ``P(X)`` move apart by (Johnson,
*Contact Mechanics*, 1985, eq. 3.21 with both bodies)

    W(X) = 1/(pi E*) int P(Y) / |X - Y| dA(Y),    1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.

In the solver's variables (``X = R0 x``, ``P = P_s p`` with the pressure
scale ``P_s = mu omega R0^2/c^2`` of :class:`bearingfe.Scale`)

    w = W/c = kappa int p(y)/|x - y| dA(y),    kappa = P_s R0 / (pi E* c)   [-].

``C[i, j] = kappa int phi_j(y) / |x_i - y| dA(y)``: the deflection at dof
``i`` (collocation) per unit pressure at dof ``j``, and the pockets (holes of
the mesh, at ``p_s``) add ``kappa p_s int_pocket 1/|x_i - y| dA``. The
integrals are exact (closed form, no quadrature): on a straight triangle
``T`` the integrand ``phi_j / r`` is a polynomial of degree <= 2 in
``rho = y - x`` over ``|rho|``, and every triangle is the signed sum of the
three triangles it spans with the observation point. In polar coordinates
about that point, ``int rho^m / r dA = int R(theta)^(m+1)/(m+1) e^m
dtheta``, which along an edge at distance ``d`` (``s`` its arc length from
the foot of the perpendicular, ``R^2 = d^2 + s^2``) is

    int rho^m / r = d/(m+1) int (d n + s t)^m / R ds,

with ``int ds/R = asinh(s/|d|)``, ``int s ds/R = R`` and
``int s^2 ds/R = (s R - d^2 asinh(s/|d|))/2``. The pocket areas come from the
same edge terms on their contours. Curved (``MeshTri2``) meshes are
integrated on the straight triangles of their vertices (the pocket contour by
its chords); the deflection is still collocated at the curved dofs.

The half-space ignores the finite shoe (its thickness, how it is held); a
block clamped at its back is stiffer. :func:`shoe_body` models the shoe as
such a block: 3-D linear elasticity (P1 tetrahedra, scikit-fem) solved once
per film pressure basis function and condensed to a dense compliance on the
film dofs, with the eccentric as a half-space on top.

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
The deflected film is a nodal field (its Laplacian is not a function), so
the direct form of the Reynolds equation is used; any cavitation model
works (the solve is called as a black box, warm-started from the previous
rupture set). The deflection is quasi-static: ``dw/dt`` does not enter the
squeeze term (the squeeze rates are those of the rigid state variables).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import skfem
from skfem import BilinearForm

from ..film.compiled import interpolation_maps
from ..cavitation import MODELS, ModelOptions, rates_for_load, solve_model
from ..film.thickness import Film
from ..film.forms import load as load_form, weighted_laplace
from ..core.limits import check_limit
from ..core.linalg import DEFAULT_SOLVER, dense_threads
from ..core.machine import Material
from ..geometry.meshing import SupportMesh
from ..core.scales import Scale
from ..film import operators, source_weights, superpose
from ..geometry.locate import barycentric, nearest_cells, probe_matrices

__all__ = [
    "Compliance",
    "DeflectedFilm",
    "ElasticError",
    "ElasticSolution",
    "combined_modulus",
    "half_space",
    "shoe_body",
    "body_compliance",
    "rectangle_deflection",
    "solve_elastic",
    "balance_load",
    "ElasticBalance",
    "pressure_sensitivity",
    "newton",
    "check_dense_size",
    "ChordBalance",
]

#: Default tolerance of the coupled solve on ``max |C p - w|`` [clearance].
TOLERANCE = 1e-8
#: Default cap on coupled iterations.
MAX_ITERATIONS = 100


class ElasticError(RuntimeError):
    """The coupled elastic film (EHD) iteration did not converge or the film closed."""


def combined_modulus(first: Material, second: Material | None = None) -> float:
    """Contact modulus ``E*`` of two elastic bodies [Pa].

    ``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2``; with one material the other
    body is rigid. Steel on steel (210 GPa, 0.3): 115.4 GPa.
    """
    total = 0.0
    for m in (first, second):
        if m is None:
            continue
        if not isinstance(m, Material):
            raise ValueError(f"materials must be bearingfe.Material, got {type(m).__name__}")
        total += (1.0 - m.poisson_ratio**2) / m.youngs_modulus
    return math.inf if total == 0.0 else 1.0 / total


# -- exact integrals of rho^m / |rho| over triangles -------------------------------------------

def _edge_moments(x: np.ndarray, a: np.ndarray, b: np.ndarray, order: int) -> list[np.ndarray]:
    """Signed integrals of ``rho^m/|rho|`` (``rho = y - x``, m <= order) over the triangles ``(x, a, b)``.

    ``x`` has shape (2, n, 1), ``a`` and ``b`` (2, 1, k): results broadcast to
    (n, k). Returns ``[I0]``, ``[I0, I1x, I1y]`` or ``[I0, I1x, I1y, I2xx,
    I2xy, I2yy]``. Positive when ``x, a, b`` turn counter-clockwise.
    """
    e = b - a
    length = np.sqrt(e[0] ** 2 + e[1] ** 2)
    t = e / length
    n = np.array([t[1], -t[0]])
    ax, bx = a - x, b - x
    d = ax[0] * n[0] + ax[1] * n[1]
    sa = ax[0] * t[0] + ax[1] * t[1]
    sb = bx[0] * t[0] + bx[1] * t[1]
    ra = np.sqrt(ax[0] ** 2 + ax[1] ** 2)
    rb = np.sqrt(bx[0] ** 2 + bx[1] ** 2)
    ad = np.maximum(np.abs(d), 1e-300)
    j0 = np.arcsinh(sb / ad) - np.arcsinh(sa / ad)
    # d > 0 when x lies on the left of a -> b; the frame (n, t) is right-handed
    out = [d * j0]
    if order >= 1:
        j1 = rb - ra
        out += [0.5 * d * (d * n[k] * j0 + t[k] * j1) for k in range(2)]
    if order >= 2:
        j2 = 0.5 * (sb * rb - sa * ra) - 0.5 * d * d * j0
        for i, k in ((0, 0), (0, 1), (1, 1)):
            out.append(d / 3.0 * (d * d * n[i] * n[k] * j0 + d * (n[i] * t[k] + t[i] * n[k]) * j1
                                  + t[i] * t[k] * j2))
    return out


def _barycentric(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Barycentric coordinates as affine maps: ``lambda_i(y) = c_i + g_i . y``.

    ``v`` has shape (2, 3, k) (vertices of k straight triangles); returns
    ``c`` (3, k) and ``g`` (3, 2, k).
    """
    x0, x1, x2 = v[:, 0], v[:, 1], v[:, 2]
    det = (x1[0] - x0[0]) * (x2[1] - x0[1]) - (x2[0] - x0[0]) * (x1[1] - x0[1])
    g = np.empty((3, 2, v.shape[2]))
    c = np.empty((3, v.shape[2]))
    for i in range(3):
        p, q = v[:, (i + 1) % 3], v[:, (i + 2) % 3]
        g[i, 0] = (p[1] - q[1]) / det
        g[i, 1] = (q[0] - p[0]) / det
        c[i] = (p[0] * q[1] - q[0] * p[1]) / det
    return c, g


def _element_integrals(x: np.ndarray, v: np.ndarray, element: str) -> np.ndarray:
    """``int_T phi_k / |x - y| dA`` for observation points ``x`` (2, n) and straight triangles ``v`` (2, 3, k).

    Local basis in scikit-fem's order (P2: vertices, then edges 01, 12, 02).
    Returns shape (nloc, n, k).
    """
    X = x[:, :, None]
    order = 2 if element == "P2" else 1
    moments = [0.0] * (6 if order == 2 else 3)
    for i in range(3):
        a, b = v[:, i][:, None, :], v[:, (i + 1) % 3][:, None, :]
        for k, m in enumerate(_edge_moments(X, a, b, order)):
            moments[k] = moments[k] + m
    e1, e2 = v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]
    orientation = np.sign(e1[0] * e2[1] - e1[1] * e2[0])  # clockwise triangles integrate negatively
    moments = [mo * orientation for mo in moments]
    M0, M1 = moments[0], moments[1:3]
    c, g = _barycentric(v)
    L = c[:, None, :] + g[:, 0][:, None, :] * X[0] + g[:, 1][:, None, :] * X[1]  # lambda_i(x): (3, n, k)

    def lin(i):  # int lambda_i / r
        return L[i] * M0 + g[i, 0] * M1[0] + g[i, 1] * M1[1]

    if order == 1:
        return np.array([lin(i) for i in range(3)])
    M2 = moments[3:6]

    def quad(i, j):  # int lambda_i lambda_j / r
        gg = (g[i, 0] * g[j, 0] * M2[0] + (g[i, 0] * g[j, 1] + g[i, 1] * g[j, 0]) * M2[1]
              + g[i, 1] * g[j, 1] * M2[2])
        return (L[i] * L[j] * M0 + (L[i] * g[j, 0] + L[j] * g[i, 0]) * M1[0]
                + (L[i] * g[j, 1] + L[j] * g[i, 1]) * M1[1] + gg)

    vertex = [2.0 * quad(i, i) - lin(i) for i in range(3)]
    edges = [4.0 * quad(i, j) for i, j in ((0, 1), (1, 2), (0, 2))]
    return np.array(vertex + edges)


def _pocket_integrals(x: np.ndarray, m: skfem.Mesh, facets: np.ndarray) -> np.ndarray:
    """``int_pockets 1/|x - y| dA`` from the pocket contours (chords of the inlet facets)."""
    if facets is None or len(facets) == 0:
        return np.zeros(x.shape[1])
    ends = m.facets[:, facets]
    a, b = m.p[:, ends[0]], m.p[:, ends[1]]
    t = m.t[:3, m.f2t[0, facets]]
    third = m.p[:, np.where((t != ends[0]) & (t != ends[1]), t, -1).max(axis=0)]
    ccw = (b[0] - a[0]) * (third[1] - a[1]) - (b[1] - a[1]) * (third[0] - a[0]) > 0
    sign = np.where(ccw, -1.0, 1.0)  # the film lies left of a -> b when ccw: the pocket right
    (I0,) = _edge_moments(x[:, :, None], a[:, None, :], b[:, None, :], 0)
    return I0 @ sign


def influence_matrix(mesh: SupportMesh, element: str = "P1", points: np.ndarray | None = None,
                     chunk: int = 200_000) -> tuple[np.ndarray, np.ndarray]:
    """Geometric influence coefficients of the film ``int phi_j / |x_i - y| dA`` [R0].

    Parameters
    ----------
    mesh : SupportMesh
    element : {"P1", "P2"}
    points : ndarray, shape (2, n), optional
        Observation points ``x_i`` in ``(phi, z)``; default the dofs of the
        element's basis (:attr:`bearingfe.reynolds.Operators.basis`).
    chunk : int
        Observation-point x element pairs per vectorized block (memory).

    Returns
    -------
    G : ndarray, shape (n, n_dofs)
    pocket : ndarray, shape (n,)
        ``int_pockets 1/|x_i - y| dA`` (the pockets are holes of the mesh).
    """
    basis = operators(mesh, element).basis
    m = mesh.mesh
    x = np.asarray(basis.doflocs if points is None else points, float)
    if x.ndim != 2 or x.shape[0] != 2 or not np.all(np.isfinite(x)):
        raise ValueError(f"points must be a finite array of shape (2, n), got shape {np.shape(points)}")
    v = m.p[:, m.t[:3]]
    dofs = basis.element_dofs
    nel = v.shape[2]
    G = np.zeros((x.shape[1], basis.N))
    rows = max(1, chunk // nel)
    select = [sp.csr_matrix((np.ones(nel), (np.arange(nel), dofs[k])), shape=(nel, basis.N))
              for k in range(dofs.shape[0])]
    for start in range(0, x.shape[1], rows):
        block = _element_integrals(x[:, start:start + rows], v, element)
        for k, s in enumerate(select):
            G[start:start + rows] += (s.T @ block[k].T).T
    pocket = _pocket_integrals(x, m, mesh.boundaries.get("inlet"))
    return G, pocket


def rectangle_deflection(x: np.ndarray, y: np.ndarray, a: float, b: float) -> np.ndarray:
    """Love's closed form: ``int 1/|X - Y| dA(Y)`` over the rectangle ``|Y1| <= a, |Y2| <= b``.

    Love (Phil. Trans. R. Soc. A 228 (1929) 377); Johnson, *Contact
    Mechanics* (1985) eq. 3.25. The half-space deflection under a uniform
    pressure ``P`` on the rectangle is ``P/(pi E*)`` times this. Sum of the four
    corner rectangles, each ``F(u, v) = u asinh(v/u) + v asinh(u/v)``
    (signed by the side the point lies on).
    """
    x, y = np.asarray(x, float), np.asarray(y, float)

    def corner(u, v):
        u, v = np.asarray(u, float), np.asarray(v, float)
        au, av = np.maximum(np.abs(u), 1e-300), np.maximum(np.abs(v), 1e-300)
        f = au * np.arcsinh(av / au) + av * np.arcsinh(au / av)
        return np.sign(u) * np.sign(v) * f

    return corner(a - x, b - y) + corner(a + x, b - y) + corner(a - x, b + y) + corner(a + x, b + y)


@dataclass(frozen=True, eq=False)
class Compliance:
    """Linear map from the film pressure to the deflection of the film surfaces.

    ``w = matrix @ p + inlet_pressure * pocket`` with ``p`` the nodal
    pressure (the dofs of :attr:`ReynoldsResult.pressure`) and ``w`` the
    opening of the film at the same dofs, in units of the clearance.

    Attributes
    ----------
    mesh : SupportMesh
    element : str
    model : str
        ``"half-space"``, ``"body"`` (the block of :func:`shoe_body`) or ``"shoe"``
        (:func:`bearingfe.elastic.shoe.shoe_compliance`).
    matrix : ndarray, shape (n_dofs, n_dofs)
        Deflection [c] per unit non-dimensional pressure.
    pocket : ndarray, shape (n_dofs,)
        Deflection [c] per unit pocket pressure.
    modulus : float
        Contact modulus ``E*`` [Pa] (``inf``: rigid).
    scale : Scale
    seconds : float
        Build time [s].
    """

    mesh: SupportMesh
    element: str
    model: str
    matrix: np.ndarray
    pocket: np.ndarray
    modulus: float
    scale: Scale
    seconds: float

    @property
    def n_dofs(self) -> int:
        return int(self.matrix.shape[1])

    @property
    def basis_doflocs(self) -> np.ndarray:
        """Coordinates ``(phi, z)`` of the dofs where the deflection is given, shape (2, n_dofs)."""
        return operators(self.mesh, self.element).basis.doflocs

    def deflection(self, pressure: np.ndarray, inlet_pressure: float = 0.0) -> np.ndarray:
        """Film opening ``w`` [c] at the dofs for the nodal pressure ``p`` [-]."""
        p = np.asarray(pressure, float)
        if p.shape != (self.n_dofs,):
            raise ValueError(f"pressure must have one value per dof ({self.n_dofs}), got shape {p.shape}")
        return self.matrix @ p + float(inlet_pressure) * self.pocket


def _check_modulus(modulus) -> float:
    if isinstance(modulus, Material):
        return combined_modulus(modulus)
    if isinstance(modulus, tuple) and len(modulus) == 2 and all(isinstance(m, Material) for m in modulus):
        return combined_modulus(*modulus)
    try:
        value = float(modulus)
    except (TypeError, ValueError):
        raise ValueError(f"modulus must be E* in Pa (> 0, inf for rigid), a Material or a pair of them, "
                         f"got {modulus!r}") from None
    if not value > 0 or math.isnan(value):
        raise ValueError(f"modulus must be E* in Pa, > 0 (inf for rigid), got {modulus!r}")
    return value


def half_space(mesh: SupportMesh, scale: Scale, modulus, element: str = "P1") -> Compliance:
    """Compliance of two elastic half-spaces under the film (Boussinesq), exact influence coefficients.

    Parameters
    ----------
    mesh : SupportMesh
        The film mesh in ``(phi, z)`` [R0].
    scale : Scale
        Gives ``R0``, ``c`` and the pressure scale.
    modulus : float, Material or (Material, Material)
        Contact modulus ``E*`` [Pa] (``math.inf``: rigid), or the materials of
        one (the other rigid) or both surfaces (:func:`combined_modulus`).
    element : {"P1", "P2"}

    Returns
    -------
    Compliance
        Dense; ``matrix[i, j] = kappa int phi_j / |x_i - y|`` with
        ``kappa = P_s R0/(pi E* c)``.
    """
    if not isinstance(scale, Scale):
        raise ValueError(f"scale must be a bearingfe.Scale, got {type(scale).__name__}")
    e_star = _check_modulus(modulus)
    check_dense_size(operators(mesh, element).n_dofs)
    start = time.perf_counter()
    G, pocket = influence_matrix(mesh, element)
    kappa = 0.0 if math.isinf(e_star) else scale.pressure * scale.radius / (math.pi * e_star * scale.clearance)
    return Compliance(mesh=mesh, element=element, model="half-space", matrix=kappa * G, pocket=kappa * pocket,
                      modulus=e_star, scale=scale, seconds=time.perf_counter() - start)


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
    """

    deflection: np.ndarray
    payload: object
    iterations: int
    residual: float
    history: tuple[float, ...]
    jacobians: int = 0


def newton(evaluate, jacobian, w0: np.ndarray, *, tol: float = TOLERANCE,
           max_iterations: int = MAX_ITERATIONS, reuse: dict | None = None) -> Coupled:
    """Newton's method on ``F(w) = g(w) - w = 0`` with backtracking and a stated convergence test.

    Parameters
    ----------
    evaluate : callable
        ``evaluate(w) -> (g(w), payload)``; raises :class:`ElasticError` if
        the film closes at ``w`` (then the step is halved).
    jacobian : callable
        ``jacobian(w, payload) -> dg/dw`` (dense, n x n).
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
    count, jacobians = 1, 0
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
            lu = sla.lu_factor(jacobian(w, payload) - np.eye(w.size), check_finite=False)
            jacobians += 1
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
    if reuse is not None:
        reuse["lu"] = lu
    return Coupled(deflection=w, payload=payload, iterations=count, residual=history[-1],
                   history=tuple(history), jacobians=jacobians)


@BilinearForm
def _film_sensitivity(u, v, w):
    # d/dh_j of int h^3 grad p . grad v_i + 6 wedge dh/dphi v_i, for h = ... + w_j phi_j
    return 3.0 * w.h2 * u * (w.gp0 * v.grad[0] + w.gp1 * v.grad[1]) + 6.0 * w.wedge * u.grad[0] * v


def pressure_sensitivity(basis, film: Film, pressure: np.ndarray, wedge: float, free: np.ndarray, *,
                         rates_balance: bool = False) -> np.ndarray:
    """``dp/dw``: change of the nodal pressure with the nodal film opening (direct form).

    Linearization of ``int h^3 grad p . grad v + int (6 wedge dh/dphi + 12 dh/dt) v = 0``
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
    x = np.array(basis.global_coordinates())
    h = np.asarray(film.thickness(x[0], x[1]))
    gp = basis.interpolate(pressure).grad
    A = weighted_laplace.assemble(basis, c=h**3).tocsr()
    B = _film_sensitivity.assemble(basis, h2=h**2, gp0=gp[0], gp1=gp[1], wedge=np.full(h.shape, float(wedge)))
    idx = np.flatnonzero(free)
    out = np.zeros((basis.N, basis.N))
    if not idx.size:
        return out
    lu = spla.splu(sp.csc_matrix(A[idx][:, idx]))
    out[idx] = -lu.solve(np.asarray(B.tocsr()[idx].todense()))
    if rates_balance:
        shapes = film.rate_shapes(x[0], x[1])
        U = np.zeros((basis.N, 2))
        for k in range(2):
            U[idx, k] = -lu.solve(load_form.assemble(basis, f=12.0 * np.asarray(shapes[k]))[idx])
        cos = load_form.assemble(basis, f=np.cos(x[0]))
        sin = load_form.assemble(basis, f=np.sin(x[0]))
        L = np.vstack([cos, sin])
        M = L @ U
        out = out - U @ np.linalg.solve(M, L @ out)
    return out


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
    """

    result: object
    deflection: np.ndarray
    iterations: int
    residual: float
    max_deflection: float
    rigid_h_min: float
    history: tuple[float, ...]


def check_dense_size(n_dofs: int) -> None:
    """Refuse a dense compliance on more than ``limit("compliance")`` film dofs (:mod:`bearingfe.core.limits`).

    The compliance is a dense ``n x n`` matrix, and the coupled solves and the
    elastic transient factor dense matrices of that size: memory grows as
    ``n^2`` (about 64 n^2 bytes in :func:`bearingfe.transient.elastic.simulate_elastic`,
    1 GB at 4000 dofs) and time as ``n^3``. ``docs/elastic.md`` has the
    measured costs by mesh size.
    """
    check_limit("compliance", n_dofs)


def _check_compliance(compliance: Compliance, mesh: SupportMesh, element: str) -> None:
    if not isinstance(compliance, Compliance):
        raise ValueError(f"elastic must be a bearingfe.elastic.coupled.Compliance, got {type(compliance).__name__}")
    check_dense_size(compliance.n_dofs)
    if compliance.mesh is not mesh:
        raise ValueError("elastic: the compliance was built on another mesh; build it on this one")
    if compliance.element != element:
        raise ValueError(f"elastic: the compliance was built for element {compliance.element!r}, "
                         f"the solve uses {element!r}")


def solve_elastic(mesh: SupportMesh, film: Film, compliance: Compliance, *, wedge: float = 1.0,
                  squeeze=(0.0, 0.0), inlet_pressure: float = 0.0, element: str = "P1",
                  cavitation: str = "none", sliding: float | None = None, solver=DEFAULT_SOLVER,
                  tol: float = TOLERANCE, max_iterations: int = MAX_ITERATIONS,
                  initial: np.ndarray | None = None) -> ElasticSolution:
    """Reynolds equation on the film opened by its own pressure: ``h = h_rigid + C p``.

    Parameters
    ----------
    mesh, film, wedge, squeeze, inlet_pressure, element, cavitation, sliding, solver
        As in :func:`bearingfe.solve_reynolds` (the direct form is used).
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
    weights = source_weights(wedge, squeeze, inlet_pressure)
    ops = operators(mesh, element)
    basis = ops.basis
    warm = [None]

    def evaluate(w):
        try:
            sup = superpose(mesh, DeflectedFilm(film, basis, w), formulation="direct", element=element,
                            solver=solver)
        except ValueError as exc:
            if "h_min" in str(exc):
                raise ElasticError(str(exc)) from None
            raise
        res = solve_model(sup, weights, cavitation, ModelOptions(sliding=sliding, warm_start=warm[0], solver=solver))
        if res.cavitated is not None and cavitation != "gumbel":
            warm[0] = res
        return compliance.deflection(res.pressure, inlet_pressure), res

    interior = np.zeros(basis.N, bool)
    interior[ops.interior] = True

    def jacobian(w, res):
        return compliance.matrix @ _sensitivity(res, interior, cavitation)

    w0 = np.zeros(basis.N) if initial is None else np.asarray(initial, float)
    out = newton(evaluate, jacobian, w0, tol=tol, max_iterations=max_iterations)
    result = dataclasses.replace(out.payload, deflection=out.deflection, elastic_iterations=out.iterations)
    return ElasticSolution(result=result, deflection=out.deflection, iterations=out.iterations,
                           residual=out.residual, max_deflection=float(out.deflection.max(initial=0.0)),
                           rigid_h_min=solve_rigid_h_min(film, basis), history=out.history)


def _sensitivity(res, interior: np.ndarray, cavitation: str, rates_balance: bool = False) -> np.ndarray:
    """dp/dw of a solution under its cavitation model (semismooth: on the current rupture set)."""
    args = (res.basis, res.film, res.pressure, res.wedge)
    if res.cavitated is None or cavitation == "gumbel":  # Gumbel clips the linear solution afterwards
        S = pressure_sensitivity(*args, interior, rates_balance=rates_balance)
        if res.cavitated is not None:
            S[res.cavitated] = 0.0
        return S
    return pressure_sensitivity(*args, interior & ~res.cavitated, rates_balance=rates_balance)


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
            raise ValueError(f"compliance must be a bearingfe.elastic.coupled.Compliance, got {type(compliance).__name__}")
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
        self.src_grad = (self.src @ self.Gp).tocsr()
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
        R = self.GpT @ (h3 * gp) + self.GzT @ (h3 * gz) + 6.0 * wedge * (self.src @ dh0 + self.src_grad @ w) + S @ r
        G = self.LI @ pI + ps * self.L_in + load
        return np.concatenate([R, G]), (h, gp, gz, w)

    def _jacobian(self, rigid, st, wedge: float) -> np.ndarray:
        h, gp, gz, _ = st
        n = self.I.size
        h2 = 3.0 * h**2 * self.dx
        Bh = (self.GpT @ sp.diags(h2 * gp) + self.GzT @ sp.diags(h2 * gz)) @ self.E + 6.0 * wedge * self.src_grad
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
    if cavitation == "none" and reuse is not None:
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
    warm = [None]

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
        return compliance.deflection(res.pressure, inlet_pressure), (sup, rates, res)

    def jacobian(w, payload):
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


# -- the shoe body: 3-D linear elasticity condensed to the film dofs --------------------------

def _graded(length: float, size: float, top_size: float) -> np.ndarray:
    """Coordinates from ``-length`` to 0 with spacing ``top_size`` at 0 growing geometrically to ``size``."""
    z, step = [0.0], top_size
    while z[-1] > -length:
        z.append(z[-1] - step)
        step = min(size, step * 1.4)
    z[-1] = -length
    if len(z) > 2 and z[-2] - z[-1] < 0.3 * step:
        z.pop(-2)
    return np.array(z[::-1])


def shoe_body(mesh: SupportMesh, scale: Scale, shoe: Material, thickness: float, *,
              counterpart: Material | None = None, element: str = "P1", margin: float = 0.0,
              size: float | None = None) -> Compliance:
    """Compliance of the shoe as a 3-D elastic block held at its back, condensed to the film dofs.

    The shoe is the block over the film's bounding box (widened by ``margin``
    on each side) of depth ``thickness``, flat (the arc's curvature is left
    out), clamped on its back face (seated on the plunger), free on its sides.
    Linear elasticity with P1 tetrahedra on a tensor mesh graded towards the
    film face is solved once for each film pressure basis function
    (``int phi_j n . v`` on the film face; the pockets load it with ``p_s``)
    and the normal displacement of the film face is read at the film dofs:
    a dense compliance on the film dofs, like :func:`half_space`. The other
    surface (the eccentric), if given, adds its own half-space compliance.

    Parameters
    ----------
    mesh : SupportMesh
    scale : Scale
    shoe : Material
    thickness : float
        Depth of the shoe body [m], > 0.
    counterpart : Material, optional
        The eccentric (a half-space); default rigid.
    element : {"P1", "P2"}
        Of the film (the pressure basis).
    margin : float
        Extra width of the body beyond the film on every side [m], >= 0.
    size : float, optional
        Element size of the body away from the film face [R0] (default the
        film mesh size).
    """
    if not isinstance(scale, Scale):
        raise ValueError(f"scale must be a bearingfe.Scale, got {type(scale).__name__}")
    if not isinstance(shoe, Material):
        raise ValueError(f"shoe must be a bearingfe.Material, got {type(shoe).__name__}")
    if not (math.isfinite(thickness) and thickness > 0):
        raise ValueError(f"thickness must be a finite number > 0 [m], got {thickness!r}")
    if not (math.isfinite(margin) and margin >= 0):
        raise ValueError(f"margin must be a finite number >= 0 [m], got {margin!r}")
    start = time.perf_counter()
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    basis2 = operators(mesh, element).basis
    check_dense_size(basis2.N)
    h = float(size if size is not None else mesh.size)
    if not (math.isfinite(h) and h > 0):
        raise ValueError(f"size must be a finite element size > 0 [R0], got {size!r}")
    lo, hi = mesh.mesh.p.min(axis=1) - margin / scale.radius, mesh.mesh.p.max(axis=1) + margin / scale.radius
    axes = [np.linspace(lo[k], hi[k], max(2, int(math.ceil((hi[k] - lo[k]) / h))) + 1) for k in range(2)]
    zs = _graded(thickness / scale.radius, 2 * h, h / 2)
    body = skfem.MeshTet.init_tensor(axes[0], axes[1], zs)
    lam, mu = lame_parameters(1.0, shoe.poisson_ratio)  # E = 1: displacements scale with 1/E
    vb = skfem.Basis(body, skfem.ElementVector(skfem.ElementTetP1()))
    K = linear_elasticity(lam, mu).assemble(vb).tocsr()
    top = body.facets_satisfying(lambda x: np.isclose(x[2], 0.0))
    back = body.facets_satisfying(lambda x: np.isclose(x[2], zs[0]))
    fb = skfem.FacetBasis(body, vb.elem, facets=top, intorder=4)
    xq = np.array(fb.global_coordinates())  # (3, n_facets, n_q)
    pts = xq[:2].reshape(2, -1)
    P, film_mask, pocket_mask = _film_face_probe(basis2, mesh, pts)
    dx = np.asarray(fb.dx).ravel()
    Nz = _normal_component_values(fb)  # (n_q_total, vb.N): z-component of the vector basis at the points
    F = (Nz.T @ sp.diags(-dx)) @ P        # pressure pushes into the body (-z): (vb.N, n_film)
    f_pocket = Nz.T @ (-dx * pocket_mask)
    fixed = vb.get_dofs(back).all()
    free = np.setdiff1d(np.arange(vb.N), fixed)
    lu = spla.splu(sp.csc_matrix(K[free][:, free]))
    U = np.zeros((vb.N, P.shape[1] + 1))
    rhs = np.column_stack([np.asarray(F[free].todense()), f_pocket[free]])
    U[free] = lu.solve(rhs)
    d = basis2.doflocs
    probe = vb.probes(np.vstack([d, np.zeros(d.shape[1])]))  # displacement components at the film dofs
    uz = probe @ U  # rows: the dofs' ux, uy, uz stacked by component
    n = d.shape[1]
    opening = -np.asarray(uz)[2 * n:3 * n] if uz.shape[0] == 3 * n else -np.asarray(uz)
    return body_compliance(mesh, scale, shoe, opening[:, :-1], opening[:, -1], model="body", element=element,
                           counterpart=counterpart, start=start)


def body_compliance(mesh: SupportMesh, scale: Scale, shoe: Material, opening: np.ndarray, pocket: np.ndarray, *,
                    model: str, element: str, counterpart: Material | None = None,
                    start: float | None = None) -> Compliance:
    """The :class:`Compliance` of an elastic body from its film openings under unit loads.

    Parameters
    ----------
    mesh, scale, element
        The film mesh, its scales and element.
    shoe : Material
        The body's material; ``opening`` was computed with Young's modulus 1
        and pressures in units of ``scale.pressure``.
    opening : ndarray, shape (n, n)
        Film opening at each film dof under the unit load of each film dof,
        from the body solved with Young's modulus 1, lengths in R0 and
        pressures in units of ``scale.pressure`` [R0]; the factor
        ``p_scale R0 / (E c)`` makes it clearances per unit pressure.
    pocket : ndarray, shape (n,)
        The opening under a unit pressure over the pockets (same units).
    model : str
        Name of the body model (``"body"``, ``"shoe"``).
    counterpart : Material, optional
        The other surface, an elastic half-space added in series.
    start : float, optional
        ``time.perf_counter()`` when the build began (for ``seconds``).
    """
    factor = scale.pressure * scale.radius / (shoe.youngs_modulus * scale.clearance)
    matrix, pocket = factor * np.asarray(opening), factor * np.asarray(pocket)
    e_star = shoe.youngs_modulus / (1 - shoe.poisson_ratio**2)
    if counterpart is not None:
        other = half_space(mesh, scale, counterpart, element)
        matrix, pocket = matrix + other.matrix, pocket + other.pocket
        e_star = combined_modulus(shoe, counterpart)
    seconds = math.nan if start is None else time.perf_counter() - start
    return Compliance(mesh=mesh, element=element, model=model, matrix=matrix, pocket=pocket, modulus=e_star,
                      scale=scale, seconds=seconds)


def _film_face_probe(basis2, mesh: SupportMesh, pts: np.ndarray):
    """Film basis values at points of the film face; which points lie in the film, which in a pocket."""
    m = mesh.mesh
    cells = nearest_cells(m.p, m.t, pts)
    l1, l2 = barycentric(m.p, m.t, cells, pts)
    inside = (l1 >= -1e-9) & (l2 >= -1e-9) & (l1 + l2 <= 1 + 1e-9)
    # basis values from the barycentric coordinates of the straight triangles (exact on straight
    # meshes; on curved ones the film face is loaded as if the pocket edges were their chords)
    lam = np.array([1.0 - l1 - l2, l1, l2])[:, inside]
    if basis2.Nbfun == 3:
        vals = lam
    else:  # scikit-fem's P2 order: vertices, then edges 01, 12, 02
        vals = np.array([lam[0] * (2 * lam[0] - 1), lam[1] * (2 * lam[1] - 1), lam[2] * (2 * lam[2] - 1),
                         4 * lam[0] * lam[1], 4 * lam[1] * lam[2], 4 * lam[0] * lam[2]])
    rows = np.tile(np.flatnonzero(inside), vals.shape[0])
    cols = basis2.element_dofs[:, cells[inside]].ravel()
    P = sp.coo_matrix((vals.ravel(), (rows, cols)), shape=(pts.shape[1], basis2.N))
    # the surface is the rectangle arc x (-a, a): its points outside the film elements are pocket points
    (a1, a2), half = mesh.surface.arc, mesh.surface.half_width
    in_box = (pts[0] >= a1) & (pts[0] <= a2) & (np.abs(pts[1]) <= half)
    pocket = (~inside & in_box).astype(float)
    return sp.csr_matrix(P), inside, pocket


def _normal_component_values(fb) -> sp.csr_matrix:
    """Values of the z-component of each vector basis function at the facet quadrature points."""
    n_f, n_q = np.asarray(fb.dx).shape
    rows, cols, vals = [], [], []
    dofs = fb.element_dofs  # (Nbfun, n_facets)
    for k in range(fb.Nbfun):
        v = np.asarray(fb.basis[k][0])  # (3, n_f, n_q) vector values
        comp = v[2]
        r = np.arange(n_f * n_q).reshape(n_f, n_q)
        rows.append(r.ravel())
        cols.append(np.repeat(dofs[k], n_q))
        vals.append(comp.ravel())
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n_f * n_q, fb.N))
