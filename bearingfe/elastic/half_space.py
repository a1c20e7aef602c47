r"""The compliance of two elastic half-spaces under the film (Boussinesq), integrated exactly.

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
"""

from __future__ import annotations

import math
import time

import numpy as np
import scipy.sparse as sp
import skfem

from .compliance import Compliance, check_dense_size, contact_modulus
from ..core.scales import Scale
from ..film import operators
from ..film.mesh_operators import boundary_facet_triangles
from ..geometry.meshing import SupportMesh

__all__ = ["influence_matrix", "rectangle_deflection", "half_space", "element_integrals", "pocket_integrals"]


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


def element_integrals(x: np.ndarray, v: np.ndarray, element: str) -> np.ndarray:
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


def pocket_integrals(x: np.ndarray, m: skfem.Mesh, facets: np.ndarray) -> np.ndarray:
    """``int_pockets 1/|x - y| dA`` from the pocket contours (chords of the inlet facets)."""
    if facets is None or len(facets) == 0:
        return np.zeros(x.shape[1])
    ends = m.facets[:, facets]
    a, b = m.p[:, ends[0]], m.p[:, ends[1]]
    t = m.t[:3, boundary_facet_triangles(m, facets)]   # without the facet-to-triangle map of every facet
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
        block = element_integrals(x[:, start:start + rows], v, element)
        for k, s in enumerate(select):
            G[start:start + rows] += (s.T @ block[k].T).T
    pocket = pocket_integrals(x, m, mesh.boundaries.get("inlet"))
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
    e_star = contact_modulus(modulus)
    check_dense_size(operators(mesh, element).n_dofs)
    start = time.perf_counter()
    G, pocket = influence_matrix(mesh, element)
    kappa = 0.0 if math.isinf(e_star) else scale.pressure * scale.radius / (math.pi * e_star * scale.clearance)
    return Compliance(mesh=mesh, element=element, model="half-space", matrix=kappa * G, pocket=kappa * pocket,
                      modulus=e_star, scale=scale, seconds=time.perf_counter() - start)
