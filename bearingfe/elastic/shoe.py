r"""The real shoe body: a 3-D gmsh mesh of the shoe, linear elasticity, condensed to the film dofs.

The shoe (:class:`bearingfe.elastic.shoe.ShoeBody`) lies behind its film
surface, the bore of radius ``R0`` over the arc ``psi in [a1, a2]`` and the
width ``|z| <= half_width`` (:class:`bearingfe.Surface`). In units of ``R0``,
with the eccentric's axis as the ``z`` axis and the plunger axis as ``y``,
the film point ``(psi, z)`` is ``(sin psi, cos psi, z)``. gmsh (OpenCASCADE)
meshes the body with tetrahedra in a confined child process
(:func:`bearingfe.geometry.geofiles.run_gmsh_worker`, the same sandbox as ``.geo``
files), graded from ``film_size`` on the bore and on the seat's rim to ``size`` elsewhere; the
seat is a disc of the back about the plunger axis, split off by the mesh.

Linear elasticity (P1 or P2 tetrahedra, scikit-fem; a lining as its own
material) is solved for every film pressure basis function at once, with one
factorization. The film pressure ``p = sum_j p_j phi_j`` pushes the bore
outwards, a traction ``p e_r``; its consistent nodal loads are

    F[k, j] = int_bore phi_j(psi, z) e_r . v_k dA,

integrated on the body's bore facets with ``phi_j`` found at each
quadrature point (the pockets, holes of the film mesh, are loaded with the
pocket pressure, a column ``f_pocket``). The film opening is the normal
displacement ``u . e_r`` of the bore, read at the film dofs as its
:math:`L^2` projection on the pressure basis, ``M w = F^T u`` (``M`` the
film mass matrix), so that

    C = M^-1 F^T K^-1 F,       M C = F^T K^-1 F  symmetric (reciprocity, to round-off).

The hold (``seat``): ``"clamped"`` sets ``u = 0`` on the seat;
``"frictionless"`` sets ``u . n = 0`` at every seat node (``n`` the normal
of the back) and, with three Lagrange multipliers, ``int u_x = int u_z =
int (x u_z - z u_x) = 0`` over the seat: exactly the rigid motions that the
normal condition leaves free are removed, so the body is not over-constrained
(the seat carries a contact pressure and a uniform sideways traction). In
both the displacement is relative to the plunger; the shoe's rigid motion is
the film balance's (the eccentricity and attitude of the pump transient).
The eccentric, if given, adds its half-space compliance
(:func:`bearingfe.elastic.half_space`).

Limits: the bore facets are chords of the cylinder (the geometry error is
second order in the facet size), and a pocket edge crossing a facet is
integrated by its quadrature points (a first-order error in the facet size
on the pocket's load, confined to that edge).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Optional

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import skfem
from skfem import BilinearForm
from skfem.helpers import ddot, sym_grad, trace

from .block import body_compliance
from .compliance import Compliance, check_dense_size
from ..geometry.geofiles import GeometryFileError, check_element_count, geo_timeout_limit, run_gmsh_worker
from ..core.machine import Material
from ..core.tempdirs import private_tempdir
from ..core.schema import nonnegative, positive
from ..geometry.meshing import SupportMesh
from ..core.scales import Scale
from ..film import operators

__all__ = ["ShoeBody", "SHOE_BACKS", "SHOE_SEATS", "ShoeMesh", "mesh_shoe", "shoe_compliance", "condense", "overlay", "BODY_ORDERS"]

#: Back faces of a shoe body: a plane across the plunger axis, or concentric with the bore.
SHOE_BACKS = ("flat", "concentric")
#: How the plunger holds the shoe at its seat (see :class:`ShoeBody`).
SHOE_SEATS = ("clamped", "frictionless")


@dataclass(frozen=True)
class ShoeBody:
    """A plunger shoe as an elastic body (the film surface is its bore: :class:`bearingfe.Surface`).

    The shoe's length and width are those of its film surface (the arc and
    the width of the bore); this adds what lies behind it.

    Parameters
    ----------
    thickness : float
        Depth of the body at the shoe centre, from the film to the back [m], > 0.
    back : {"flat", "concentric"}
        The back face: a plane across the plunger axis at ``thickness``
        behind the bore's apex (a slipper block, thicker at its ends), or a
        cylinder concentric with the bore (a shell of uniform thickness).
    seat : {"clamped", "frictionless"}
        How the plunger holds the shoe on the seat (a disc of
        ``seat_radius`` about the plunger axis on the back): ``"clamped"``
        fixes the seat (a shoe bonded or shrunk onto a rigid plunger head);
        ``"frictionless"`` lets it slide across the plunger but not move
        into it (a rigid flat or cylindrical seat without friction: the
        displacement normal to the back vanishes on the seat, the sideways
        displacement and the spin about the plunger axis vanish on average
        over it; the reactions are the seat's contact pressure and a uniform
        sideways traction).
    seat_radius : float, optional
        Radius of the seat disc [m], > 0 (:func:`bearingfe.elastic.shoe.mesh_shoe`
        checks that it fits on the back); None: the whole back is the seat
        (``"clamped"`` only).
    lining : Material, optional
        A bearing lining (e.g. bronze or white metal) of ``lining_thickness``
        on the bore; the rest of the body (the backing) is the shoe's material.
    lining_thickness : float
        [m], >= 0 and < ``thickness``; > 0 exactly when ``lining`` is given.
    """

    thickness: float
    back: str = "flat"
    seat: str = "clamped"
    seat_radius: Optional[float] = None
    lining: Optional["Material"] = None
    lining_thickness: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "thickness", positive("thickness", self.thickness, "m"))
        if self.back not in SHOE_BACKS:
            raise ValueError(f"back must be one of {SHOE_BACKS}, got {self.back!r}")
        if self.seat not in SHOE_SEATS:
            raise ValueError(f"seat must be one of {SHOE_SEATS}, got {self.seat!r}")
        if self.seat_radius is None:
            if self.seat != "clamped":
                raise ValueError("seat_radius must be given (> 0 m) for a 'frictionless' seat (the whole back "
                                 "sliding freely would leave the shoe free to move)")
        else:
            object.__setattr__(self, "seat_radius", positive("seat_radius", self.seat_radius, "m"))
        t = nonnegative("lining_thickness", self.lining_thickness, "m")
        if t >= self.thickness:
            raise ValueError(f"lining_thickness must be in [0, thickness = {self.thickness!r}) m, got {t!r}")
        object.__setattr__(self, "lining_thickness", t)
        if (self.lining is None) != (t == 0):
            raise ValueError("lining and lining_thickness go together: a lining Material with lining_thickness "
                             f"> 0 m, or neither; got lining={self.lining!r}, lining_thickness={t!r}")
        if self.lining is not None and not isinstance(self.lining, Material):
            raise ValueError(f"lining must be a bearingfe.Material, got {type(self.lining).__name__}")


#: Polynomial orders of the body's tetrahedra.
BODY_ORDERS = (1, 2)
#: Right-hand sides solved per block (memory: body dofs x this).
_BLOCK = 256


@dataclass(frozen=True, eq=False)
class ShoeMesh:
    """A tetrahedral mesh of the shoe body [R0].

    Attributes
    ----------
    mesh : skfem.MeshTet
    lining : ndarray of bool, shape (n_elements,)
        Elements of the lining.
    film : ndarray of int
        Boundary facets on the bore (the film face).
    seat : ndarray of int
        Boundary facets of the seat.
    body : ShoeBody
    flat_film : bool
        The film face is the plane ``y = 1`` (``x = psi``) instead of the bore.
    """

    mesh: skfem.MeshTet
    lining: np.ndarray
    film: np.ndarray
    seat: np.ndarray
    body: ShoeBody
    flat_film: bool = False

    def film_coordinates(self, x: np.ndarray) -> np.ndarray:
        """``(psi, z)`` of body points ``x`` (3, ...) on (or near) the film face."""
        if self.flat_film:
            return np.array([x[0], x[2]])
        return np.array([np.arctan2(x[0], x[1]), x[2]])

    def film_normal(self, x: np.ndarray) -> np.ndarray:
        """Unit vector along which the film opens at body points ``x`` (3, ...): ``e_r`` (``e_y`` if flat)."""
        if self.flat_film:
            return np.array([np.zeros_like(x[0]), np.ones_like(x[0]), np.zeros_like(x[0])])
        r = np.hypot(x[0], x[1])
        return np.array([x[0] / r, x[1] / r, np.zeros_like(x[0])])

    def back_normal(self, x: np.ndarray) -> np.ndarray:
        """Outward unit normal of the back at points ``x`` (3, n)."""
        if self.flat_film or self.body.back == "flat":
            return np.array([np.zeros_like(x[0]), np.ones_like(x[0]), np.zeros_like(x[0])])
        return self.film_normal(x)


def _checked_geometry(surface, radius: float, body: ShoeBody, margin: float,
                      flat_film: bool) -> tuple[float, float, float, float, float]:
    """Non-dimensional ``(a1, a2, half_width, thickness, seat)`` of the body [R0]; the seat must fit on the back."""
    if not (isinstance(margin, (int, float)) and math.isfinite(margin) and margin >= 0):
        raise ValueError(f"margin must be a finite number >= 0 [m], got {margin!r}")
    m = margin / radius
    a1, a2 = surface.arc[0] - m, surface.arc[1] + m
    if not (flat_film or -math.pi / 2 < a1 < a2 < math.pi / 2):
        raise ValueError(f"the shoe's arc (the film surface's arc {surface.arc} widened by the margin) must lie "
                         f"inside (-pi/2, pi/2) rad, got ({a1:.6g}, {a2:.6g})")
    t = body.thickness / radius
    hw = surface.half_width + m
    if body.seat_radius is None:
        return a1, a2, hw, t, 0.0
    seat = body.seat_radius / radius
    # the back's half-length across the plunger axis (flat back: the bore's ends; concentric: (1 + t) sin a)
    reach = (min(-a1, a2) if flat_film else
             min(abs(math.sin(a1)), abs(math.sin(a2))) * (1.0 if body.back == "flat" else 1.0 + t))
    largest = 0.9 * min(reach, hw)
    if not seat <= largest:
        raise ValueError(f"seat_radius must be in (0, {largest * radius:.6g}] m (0.9 of the back's half-width "
                         f"or half-length about the plunger axis), got {body.seat_radius!r}")
    return a1, a2, hw, t, seat


def _estimated_tets(a1: float, a2: float, hw: float, t: float, seat: float, size: float, film_size: float,
                    grading: float) -> float:
    """Tetrahedra of a mesh graded from ``film_size`` over ``grading`` to ``size`` (regular tets)."""
    volume = (math.sin(a2) - math.sin(a1) + 2 * t) * (t + 1 - math.cos(max(abs(a1), abs(a2)))) * 2 * hw
    near = min(volume, (a2 - a1) * 2 * hw * grading + 2 * math.pi * seat * math.pi * grading**2 / 2)
    regular = lambda h: h**3 / (6 * math.sqrt(2))  # noqa: E731
    return near / regular(film_size) + max(volume - near, 0.0) / regular(size)


def mesh_shoe(surface, radius: float, body: ShoeBody, size: float, *, film_size: float | None = None,
              grading: float | None = None, margin: float = 0.0, flat_film: bool = False,
              timeout: float | None = None, max_elements: int | None = None) -> ShoeMesh:
    """Mesh the shoe body with gmsh (OpenCASCADE) in the confined child process.

    Parameters
    ----------
    surface : Surface
        The film surface (its arc and width are the shoe's; pockets do not matter here).
    radius : float
        Eccentric radius ``R0`` [m], > 0 (the unit of the mesh).
    body : ShoeBody
    size : float
        Element size away from the film face [R0], > 0.
    film_size : float, optional
        Element size on the film face and the seat's rim [R0], > 0 (default ``size``).
    grading : float, optional
        Distance from the film face over which the size grows to ``size`` [R0]
        (default half the thickness).
    margin : float
        The body reaches beyond the film surface by this on every side [m],
        >= 0 (an unloaded rim of the bore).
    flat_film : bool
        A flat block under a flat film (``x = psi``, the film face ``y = 1``):
        the geometry of :func:`bearingfe.elastic.block_compliance`, for comparison.
    timeout : float, optional
        Seconds gmsh may take (default :func:`bearingfe.geometry.geofiles.geo_timeout_limit`).
    max_elements : int, optional
        Limit of the estimated number of tetrahedra (default the ``elements`` limit).

    Raises
    ------
    ValueError
        A parameter out of range (named), a seat that does not fit on the back.
    MeshSizeError
        Too many tetrahedra asked for.
    GeometryFileError
        gmsh failed or ran out of time.
    """
    if not isinstance(body, ShoeBody):
        raise ValueError(f"body must be a bearingfe.elastic.shoe.ShoeBody, got {type(body).__name__}")
    if not (isinstance(radius, (int, float)) and math.isfinite(radius) and radius > 0):
        raise ValueError(f"radius must be the eccentric radius R0 in m, > 0, got {radius!r}")
    a1, a2, hw, t, seat = _checked_geometry(surface, radius, body, margin, flat_film)
    size = _positive("size", size)
    film_size = size if film_size is None else _positive("film_size", film_size)
    grading = t / 2 if grading is None else _positive("grading", grading)
    estimate = _estimated_tets(a1, a2, hw, t, seat, size, film_size, grading)
    check_element_count(estimate, max_elements, what=f"the shoe body with size = {size:g}, film_size = "
                                                     f"{film_size:g} (tetrahedra)")
    seconds = geo_timeout_limit(timeout)
    geometry = dict(a1=a1, a2=a2, half_width=hw, thickness=t, back=body.back, seat=seat,
                    lining=body.lining_thickness / radius, size=size, film_size=film_size, grading=grading,
                    face="plane" if flat_film else "bore")
    with private_tempdir("shoe") as work:
        out = Path(work) / "shoe.json"
        result = run_gmsh_worker(dict(task="shoe", out=str(out), geometry=geometry), work, seconds, "shoe body",
                                 slow="a very fine mesh?", how="timeout=", ended="gmsh stopped")
        if "error" in result:
            raise GeometryFileError(f"shoe body: gmsh failed: {result['error']}")
        import json

        data = json.loads(out.read_text())
    return _shoe_mesh(data, body, flat_film)


def _positive(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = math.nan
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name} must be a finite element size > 0 [R0], got {value!r}")
    return v


def _shoe_mesh(data: dict, body: ShoeBody, flat_film: bool) -> ShoeMesh:
    """The skfem mesh and the film, seat and lining sets from the worker's node and element lists."""
    tags = np.asarray(data["tags"], np.int64)
    index = np.full(tags.max() + 1, -1, np.int64)
    index[tags] = np.arange(tags.size)
    p = np.asarray(data["coords"], float).reshape(-1, 3).T
    backing = index[np.asarray(data["backing"], np.int64)].reshape(-1, 4).T
    lining = index[np.asarray(data["lining"], np.int64)].reshape(-1, 4).T
    t = np.hstack([backing, lining])
    used = np.unique(t)  # gmsh keeps the nodes of removed construction entities: drop them
    renum = np.full(p.shape[1], -1, np.int64)
    renum[used] = np.arange(used.size)
    mesh = skfem.MeshTet(np.ascontiguousarray(p[:, used]), np.ascontiguousarray(renum[t]))
    is_lining = np.r_[np.zeros(backing.shape[1], bool), np.ones(lining.shape[1], bool)]

    def facets(key: str) -> np.ndarray:
        tri = np.sort(renum[index[np.asarray(data[key], np.int64)].reshape(-1, 3).T], axis=0)
        n = mesh.p.shape[1]
        have = np.sort(mesh.facets, axis=0).astype(np.int64)  # codes up to n^3: no int32
        code = lambda f: (f[0] * n + f[1]) * n + f[2]  # noqa: E731
        order = np.argsort(code(have))
        pos = np.searchsorted(code(have)[order], code(tri))
        found = order[np.minimum(pos, order.size - 1)]
        if not np.array_equal(code(have[:, found]), code(tri)):
            raise GeometryFileError(f"shoe body: the {key} triangles are not faces of the tetrahedra")
        return found

    return ShoeMesh(mesh=mesh, lining=is_lining, film=facets("film"), seat=facets("seat"), body=body,
                    flat_film=flat_film)


@BilinearForm
def _elasticity(u, v, w):
    """Isotropic linear elasticity with element-wise Lame parameters ``w.lam``, ``w.mu``."""
    return w.lam * trace(sym_grad(u)) * trace(sym_grad(v)) + 2.0 * w.mu * ddot(sym_grad(u), sym_grad(v))


def _lame(material: Material, reference: float) -> tuple[float, float]:
    """Lame parameters of ``material`` in units of the reference Young's modulus."""
    e, nu = material.youngs_modulus / reference, material.poisson_ratio
    return e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))


def _clip(poly: list, tri: np.ndarray) -> list:
    """Sutherland-Hodgman: the part of the convex polygon ``poly`` inside the triangle ``tri`` (2, 3)."""
    a, b, c = tri.T
    ccw = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0
    edges = ((a, b), (b, c), (c, a)) if ccw else ((a, c), (c, b), (b, a))
    for p, q in edges:
        if not poly:
            break
        side = [(q[0] - p[0]) * (v[1] - p[1]) - (q[1] - p[1]) * (v[0] - p[0]) for v in poly]
        out = []
        for k, v in enumerate(poly):
            u, su = poly[k - 1], side[k - 1]
            if side[k] >= 0:
                if su < 0:
                    out.append(u + (v - u) * (su / (su - side[k])))
                out.append(v)
            elif su >= 0:
                out.append(u + (v - u) * (su / (su - side[k])))
        poly = out
    return poly


def overlay(body: np.ndarray, film: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Triangles covering the intersections of two planar triangulations.

    Parameters
    ----------
    body, film : ndarray, shape (2, 3, n)
        Vertices of the triangles of each.

    Returns
    -------
    pieces : ndarray, shape (2, 3, m)
        Triangles (fans of the convex intersection polygons).
    of_body, of_film : ndarray of int, shape (m,)
        The triangle of each side that holds each piece.
    """
    from scipy.spatial import cKDTree

    cb, cf = body.mean(axis=1), film.mean(axis=1)
    rb = np.linalg.norm(body - cb[:, None], axis=0).max()
    rf = np.linalg.norm(film - cf[:, None], axis=0).max()
    near = cKDTree(cf.T).query_ball_point(cb.T, rb + rf + 1e-12)
    pieces, ib, jf = [], [], []
    for i, cands in enumerate(near):
        tri = [body[:, k, i] for k in range(3)]
        for j in cands:
            poly = _clip(tri, film[:, :, j])
            for k in range(1, len(poly) - 1):
                piece = np.array([poly[0], poly[k], poly[k + 1]]).T
                area = 0.5 * abs((piece[0, 1] - piece[0, 0]) * (piece[1, 2] - piece[1, 0])
                                 - (piece[0, 2] - piece[0, 0]) * (piece[1, 1] - piece[1, 0]))
                if area > 1e-14:
                    pieces.append(piece)
                    ib.append(i)
                    jf.append(j)
    if not pieces:
        return np.zeros((2, 3, 0)), np.zeros(0, int), np.zeros(0, int)
    return np.stack(pieces, axis=2), np.array(ib), np.array(jf)


def _barycentric_of(tri: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Coordinates ``(l1, l2)`` of points ``x`` (2, n) on the triangles ``tri`` (2, 3, n) (affine)."""
    v0, v1, v2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0], x - tri[:, 0]
    det = v0[0] * v1[1] - v0[1] * v1[0]
    return np.array([(v2[0] * v1[1] - v2[1] * v1[0]) / det, (v0[0] * v2[1] - v0[1] * v2[0]) / det])


def _directional_values(fb, direction: np.ndarray) -> sp.csr_matrix:
    """``v_k . d`` at the facet quadrature points for every vector basis function [rows: points]."""
    n_f, n_q = np.asarray(fb.dx).shape
    r = np.arange(n_f * n_q).reshape(n_f, n_q).ravel()
    rows, cols, vals = [], [], []
    for k in range(fb.Nbfun):
        v = np.asarray(fb.basis[k][0])  # (3, n_f, n_q)
        rows.append(r)
        cols.append(np.repeat(fb.element_dofs[k], n_q))
        vals.append((v * direction).sum(axis=0).ravel())
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n_f * n_q, fb.N))


def _piece_points(pieces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Quadrature points (2, m * nq) and weights of the triangles ``pieces`` (degree 4: exact for P2 x P2)."""
    from skfem.quadrature import get_quadrature
    from skfem.refdom import RefTri

    X, W = get_quadrature(RefTri, 4)
    a, e1, e2 = pieces[:, 0], pieces[:, 1] - pieces[:, 0], pieces[:, 2] - pieces[:, 0]
    pts = a[:, :, None] + e1[:, :, None] * X[0] + e2[:, :, None] * X[1]  # (2, m, nq)
    twice = np.abs(e1[0] * e2[1] - e1[1] * e2[0])
    return pts.reshape(2, -1), (twice[:, None] * W[None, :]).ravel()


def _body_values(shoe: ShoeMesh, vb, facets: np.ndarray, tri2: np.ndarray, pts: np.ndarray) -> sp.csr_matrix:
    """``v_k . e`` (``e`` the opening direction) at film-plane points ``pts`` (2, n) of the body facets
    ``facets`` (n,) whose film-plane triangles are ``tri2`` (2, 3, n) [rows: points]."""
    m = shoe.mesh
    lam = _barycentric_of(tri2, pts)
    V = m.p[:, m.facets[:, facets]]  # (3, 3, n)
    X3 = V[:, 0] * (1 - lam[0] - lam[1]) + V[:, 1] * lam[0] + V[:, 2] * lam[1]
    tets = m.f2t[0, facets]
    ref = vb.mapping.invF(X3[:, :, None], tind=tets)
    e = shoe.film_normal(X3)
    n = pts.shape[1]
    vals = [(np.asarray(vb.elem.gbasis(vb.mapping, ref, k, tind=tets)[0])[:, :, 0] * e).sum(axis=0)
            for k in range(vb.Nbfun)]
    return sp.coo_matrix((np.concatenate(vals), (np.tile(np.arange(n), vb.Nbfun), vb.element_dofs[:, tets].ravel())),
                         shape=(n, vb.N)).tocsr()


def _film_loads(shoe: ShoeMesh, vb, mesh: SupportMesh, basis) -> tuple[sp.csc_matrix, np.ndarray]:
    """Consistent body loads of the film pressure basis ``F`` (body dofs, film dofs) and of the pockets.

    Integrated exactly (degree 4 on the pieces where a body facet meets a film
    triangle, both seen in the film plane ``(psi, z)``, with ``dA = dpsi dz``);
    the pockets are the rest of the outline: ``f_pocket = f_outline - F 1``.
    """
    m3, fm = shoe.mesh, mesh.mesh
    body2 = shoe.film_coordinates(m3.p[:, m3.facets[:, shoe.film]])  # (2, 3, nb)
    pieces, ib, jf = overlay(body2, fm.p[:, fm.t[:3]])
    pts, wts = _piece_points(pieces)
    nq = pts.shape[1] // max(pieces.shape[2], 1)
    bi, fj = np.repeat(ib, nq), np.repeat(jf, nq)
    N = _body_values(shoe, vb, shoe.film[bi], body2[:, :, bi], pts)
    ref = _barycentric_of(fm.p[:, fm.t[:3, fj]], pts)[:, :, None]
    # reference coordinates from the straight triangle of the vertices: exact on straight elements; on the
    # curved ones of a MeshTri2 (along pocket edges) the load is placed as if the edges were their chords
    vals = [np.asarray(basis.elem.gbasis(basis.mapping, ref, k, tind=fj)[0])[:, 0] for k in range(basis.Nbfun)]
    P = sp.coo_matrix((np.concatenate(vals), (np.tile(np.arange(pts.shape[1]), basis.Nbfun),
                                              basis.element_dofs[:, fj].ravel())),
                      shape=(pts.shape[1], basis.N)).tocsr()
    F = (N.T @ sp.diags(wts) @ P).tocsc()
    (a1, a2), hw = mesh.surface.arc, mesh.surface.half_width
    box = np.array([[[a1, a2, a2], [-hw, -hw, hw]], [[a1, a2, a1], [-hw, hw, hw]]]).transpose(1, 2, 0)
    pieces, ib, _ = overlay(body2, box)
    pts, wts = _piece_points(pieces)
    bi = np.repeat(ib, pts.shape[1] // max(pieces.shape[2], 1))
    f_outline = _body_values(shoe, vb, shoe.film[bi], body2[:, :, bi], pts).T @ wts
    return F, f_outline - F @ np.ones(basis.N)


def _seat_constraints(shoe: ShoeMesh, vb) -> sp.csr_matrix:
    """Rows of the frictionless seat: ``n . u = 0`` at each seat node, and the mean sideways motions."""
    m = shoe.mesh
    dofs = vb.nodal_dofs[:, np.unique(m.facets[:, shoe.seat])]
    if vb.edge_dofs.size:  # P2: the edge midpoints
        dofs = np.hstack([dofs, vb.edge_dofs[:, np.unique(m.f2e[:, shoe.seat])]])
    # dofs (3, n_points): the x, y, z dofs of each seat point
    where = vb.doflocs[:, dofs[0]]
    n = shoe.back_normal(where)
    k = dofs.shape[1]
    normal = sp.csr_matrix((n.T.ravel(), (np.repeat(np.arange(k), 3), dofs.T.ravel())), shape=(k, vb.N))
    fb = skfem.FacetBasis(shoe.mesh, vb.elem, facets=shoe.seat, intorder=2 * vb.elem.maxdeg)
    x = np.array(fb.global_coordinates())
    one = np.ones_like(x[0])
    zero = np.zeros_like(x[0])
    rows = [np.array([one, zero, zero]), np.array([zero, zero, one]), np.array([-x[2], zero, x[0]])]
    dx = np.asarray(fb.dx).ravel()
    mean = np.array([_directional_values(fb, d).T @ dx for d in rows])
    return sp.vstack([normal, sp.csr_matrix(mean)]).tocsr()


def _solver(shoe: ShoeMesh, vb, K: sp.csr_matrix):
    """``f -> u`` solving the held body (one factorization for every right side)."""
    if shoe.body.seat == "clamped":
        fixed = vb.get_dofs(shoe.seat).all()
        free = np.setdiff1d(np.arange(vb.N), fixed)
        lu = spla.splu(sp.csc_matrix(K[free][:, free]))

        def solve(F):
            U = np.zeros((vb.N, F.shape[1]))
            U[free] = lu.solve(np.asarray(F[free].todense()) if sp.issparse(F) else F[free])
            return U
        return solve
    B = _seat_constraints(shoe, vb)
    m = B.shape[0]
    A = sp.bmat([[K, B.T], [B, None]], format="csc")
    lu = spla.splu(A)

    def solve(F):
        rhs = np.zeros((vb.N + m, F.shape[1]))
        rhs[:vb.N] = np.asarray(F.todense()) if sp.issparse(F) else F
        return lu.solve(rhs)[:vb.N]
    return solve


def shoe_compliance(mesh: SupportMesh, scale: Scale, shoe: Material, body: ShoeBody, *,
                    counterpart: Material | None = None, element: str = "P1", order: int = 2,
                    size: float | None = None, film_size: float | None = None, margin: float = 0.0,
                    flat_film: bool = False, timeout: float | None = None, max_elements: int | None = None) -> Compliance:
    """Compliance of the real shoe body on the film dofs (3-D gmsh mesh, linear elasticity, condensed).

    Parameters
    ----------
    mesh : SupportMesh
        The film mesh in ``(psi, z)`` [R0]; its surface is the shoe's bore.
    scale : Scale
    shoe : Material
        The shoe's material (the backing, when there is a lining).
    body : ShoeBody
        Depth, back, seat and lining.
    counterpart : Material, optional
        The eccentric, as an elastic half-space added on top; default rigid.
    element : {"P1", "P2"}
        Of the film (the pressure basis).
    order : {1, 2}
        Of the body's tetrahedra.
    size, film_size : float, optional
        Body element size away from the film and on it [R0]; default twice
        the film mesh size and the film mesh size.
    margin : float
        The body reaches beyond the film surface by this on every side [m], >= 0.
    flat_film : bool
        A flat block under a flat film (see :func:`mesh_shoe`).
    timeout, max_elements
        Limits of the gmsh child (see :func:`mesh_shoe`).

    Returns
    -------
    Compliance
        ``model = "shoe"``; ``matrix`` [c per unit pressure] with
        ``M @ matrix`` symmetric (``M`` the film mass matrix).

    Raises
    ------
    ValueError
        A parameter out of range (named); see also :func:`mesh_shoe`.
    LimitError
        More film dofs than the ``compliance`` limit (:func:`bearingfe.elastic.check_dense_size`).
    """
    if not isinstance(scale, Scale):
        raise ValueError(f"scale must be a bearingfe.Scale, got {type(scale).__name__}")
    if not isinstance(shoe, Material):
        raise ValueError(f"shoe must be a bearingfe.Material, got {type(shoe).__name__}")
    if counterpart is not None and not isinstance(counterpart, Material):
        raise ValueError(f"counterpart must be a bearingfe.Material or None, got {type(counterpart).__name__}")
    if order not in BODY_ORDERS:
        raise ValueError(f"order must be one of {BODY_ORDERS} (body tetrahedra), got {order!r}")
    start = time.perf_counter()
    ops = operators(mesh, element)  # checks the element
    check_dense_size(ops.basis.N)
    film = mesh.size if film_size is None else film_size
    body_mesh = mesh_shoe(mesh.surface, scale.radius, body, 2 * film if size is None else size,
                          film_size=film, margin=margin, flat_film=flat_film, timeout=timeout,
                          max_elements=max_elements)
    return condense(body_mesh, mesh, scale, shoe, ops, element=element, order=order, counterpart=counterpart,
                    start=start)


def condense(shoe_mesh: ShoeMesh, mesh: SupportMesh, scale: Scale, shoe: Material, ops=None, *,
             element: str = "P1", order: int = 2, counterpart: Material | None = None,
             start: float | None = None) -> Compliance:
    """The compliance of a meshed shoe body on the film dofs (see :func:`shoe_compliance`)."""
    start = time.perf_counter() if start is None else start
    ops = operators(mesh, element) if ops is None else ops
    body = shoe_mesh.body
    elem = skfem.ElementVector(skfem.ElementTetP2() if order == 2 else skfem.ElementTetP1())
    vb = skfem.Basis(shoe_mesh.mesh, elem, intorder=max(1, 2 * (order - 1)))
    lam, mu = np.empty(shoe_mesh.mesh.t.shape[1]), np.empty(shoe_mesh.mesh.t.shape[1])
    lam[:], mu[:] = _lame(shoe, shoe.youngs_modulus)
    if body.lining is not None:
        lam[shoe_mesh.lining], mu[shoe_mesh.lining] = _lame(body.lining, shoe.youngs_modulus)
    nq = vb.X.shape[1]
    K = _elasticity.assemble(vb, lam=np.repeat(lam[:, None], nq, axis=1),
                             mu=np.repeat(mu[:, None], nq, axis=1)).tocsr()
    F, f_pocket = _film_loads(shoe_mesh, vb, mesh, ops.basis)
    solve = _solver(shoe_mesh, vb, K)
    S = np.empty((ops.basis.N, ops.basis.N))
    FT = F.T.tocsr()
    for j in range(0, ops.basis.N, _BLOCK):
        S[:, j:j + _BLOCK] = FT @ solve(F[:, j:j + _BLOCK])
    s_pocket = FT @ solve(f_pocket[:, None])[:, 0]
    lu = spla.splu(sp.csc_matrix(ops.mass))
    return body_compliance(mesh, scale, shoe, lu.solve(S), lu.solve(s_pocket), model="shoe", element=element,
                           counterpart=counterpart, start=start)
