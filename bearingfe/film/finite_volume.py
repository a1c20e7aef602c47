r"""Mass-conserving cavitation: the Jakobsson-Floberg-Olsson (JFO) model in Elrod-Adams p-theta form.

Unknowns are the pressure ``p`` and the fill fraction ``theta`` (the part of
the gap filled with oil) at the mesh nodes. With the flux
``q = -h^3/12 grad p + wedge/2 theta h e_phi`` (units omega R0^2 c), the film
conserves mass::

    div q + d(theta h)/dt = 0,   p >= p_c,   0 <= theta <= 1,   (p - p_c)(1 - theta) = 0,

which is ``div(h^3 grad p) = 6 wedge d(theta h)/dphi + 12 d(theta h)/dt``. In
the full film ``theta = 1`` and this is the Reynolds equation; in a cavity
``p = p_c`` and the oil is carried by the Couette flux ``wedge/2 theta h``
alone. Boundaries and pockets feed oil: ``theta = 1`` there.

Discretization (P1, vertex-centred finite volumes on the median dual mesh):

- the Poiseuille part is the P1 Galerkin stiffness of ``h^3/12``, which is
  the median-dual finite-volume flux for an element-wise constant film;
- the Couette part is the flux ``wedge/2 h theta n_phi`` through each
  median-dual segment (edge midpoint to centroid) inside each triangle,
  with ``h`` taken at the segment midpoint (strictly inside the triangle)
  and ``theta`` from the upwind node. A step of ``h`` along element edges
  (a recess meshed conformally) is therefore crossed with the exact flux of
  each side: no derivative of ``h`` is ever formed;
- on a tensor grid (:func:`bearingfe.geometry.meshing.grid_mesh`) the Couette flux can
  instead pass through the faces of the nodes' box cells normal to ``phi``
  (``couette="grid"``): between ``phi``-neighbours only, so fronts along the
  sliding direction are not smeared sideways, with the film of each face
  integrated exactly across recess contours that cut the cells (rectangular
  pockets are holes of the grid, their edges on grid lines);
- on any mesh, ``couette="limited"`` takes theta at each median-dual segment
  midpoint from a limited linear reconstruction around the upwind node
  (second-order upwind, Barth-Jespersen limiter, lagged over a few solves),
  which removes most of the first-order flux's crosswind smearing;
- on any mesh, ``couette="streamline"`` takes theta at each median-dual segment
  from the foot of the sliding-direction line through the segment midpoint
  on its triangle's edge (P1 interpolation of the two nodes of that edge,
  upstream): a fill fraction that varies across the sliding direction is
  carried along it without crosswind smearing, in one linear flux (no
  limiter, no extra solves). A cavitated node on a recess contour refers
  its theta to its deepest film and each triangle takes ``theta h_max /
  h_side`` of it (the oil flux ``theta h`` is what is continuous across a
  film step in a cavity). The scheme is not positive: where theta would end
  below 0 (strong squeeze, long time steps) or the active set cycles, the
  segments out of those nodes are upwinded and the problem solved again.
  The default on gmsh meshes;
- the storage ``int theta h`` is lumped on the dual cells
  (``H_i = int h phi_i``); the steady squeeze term is ``theta_i int dh/dt
  phi_i``, a time step backward Euler ``(theta H - theta_old H_old)/dt``.

Every dual-segment flux leaves one cell and enters its neighbour, so the
scheme conserves mass exactly: the boundary flows (Couette and Poiseuille
parts) balance the pocket inflow and the squeeze to the solver's tolerance.

With ``P = p - p_c`` and ``r = 1 - theta`` each node carries one equation and
the complementarity ``P >= 0, r >= 0, P r = 0``: a mixed linear
complementarity problem, solved by the primal-dual active-set method, i.e.
semismooth Newton on ``min(P, r) = 0`` (Hintermueller, Ito & Kunisch, SIAM J.
Optim. 13 (2003) 865; for JFO see Woloszynski et al., Tribol. Lett. 58:18
(2015)): on the full set the unknown is ``P`` (``theta = 1``), on the
cavitated set ``theta`` (``p = p_c``); nodes with ``P < 0`` move to the cavity,
nodes with ``theta > 1`` back to the full film, until the sets stop
changing. A warm start (the cavity of a previous solution) usually ends it in
one or two linear solves; a cold solve with the grid flux on a ``grid_mesh`` of
:data:`NESTED_MIN` unknowns or more starts from the cavity of the same problem on
the grid with every other line (nested iteration, recursively), which halves
the fine-level factorizations (measured 4 against 7-8 on the dimpled slider at
1e5 and 3.6e5 unknowns); a cold solve on an unstructured mesh of
:data:`NESTED_MIN_UNSTRUCTURED` unknowns or more starts from the cavity of the same problem on a ``grid_mesh`` of its
surface with about a quarter of its nodes (grid flux; measured 4, 4 and 2
fine-level factorizations against 9, 8 and 6 on the pocket pad, the dimple and
the grooved journal of docs/jfo_gmsh.md at 2.3e4-4.7e4 nodes). Where the
discrete complementarity problem has more than one solution (the streamline
flux is not positive; seen once, at a node on a recess contour) a different
start may end on the other one, the two apart by far less than the
discretization error. The active-set matrices are factored in a
nested-dissection order found once per mesh (:data:`ORDERED_FROM`). The
equations and their derivation are in ``docs/jfo.md``.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time
import weakref
from dataclasses import dataclass
from types import MappingProxyType
from typing import Callable

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import MeshTri1
from scipy.sparse.csgraph import reverse_cuthill_mckee

from .thickness import Film
from .forms import along
from .flows import edge_groups
from ..core.banded import band_cholesky, band_limits, band_pays, band_plan, band_worth_trying, half_bandwidth
from ..core.blocks import blocks
from ..core.checks import check_operating_point, note_resolution
from ..core.compressed import compressed, csc_of, csr_sum, csr_transposed, csr_without_zeros, matvec, sorted_entries
from ..core.linalg import Factorize, dense_threads, factorize_splu, get_linear_solver
from ..core.pages import small_pages
from ..core.parameters import Discretization, OperatingPoint, takes
from ..geometry.meshing import SupportMesh, periodic_pairs, tensor_lines
from ..geometry.runner import is_along_phi, velocity_at
from ..geometry.surface import Circle
from .mesh_operators import Operators, boundary_facets, operators, pocket_moments
from .result import ReynoldsResult, runner_of

__all__ = ["JFOError", "solve_jfo", "FVSystem", "FVUnknowns", "active_set", "MAX_ITERATIONS", "TOLERANCE", "COUETTE_FLUXES", "LIMITER_SWEEPS", "ALIGNED_SOURCES",
           "UNSTRUCTURED_JFO_NOTE", "RECESS_JFO_NOTE", "TENSOR_SOURCES", "STREAMLINE_PASSES"]

#: Default cap on active-set iterations.
MAX_ITERATIONS = 80
#: Default relative tolerance of the sign tests (scaled by the largest |P| and 1 for theta).
TOLERANCE = 1e-10
#: Couette flux discretizations of :func:`solve_jfo` (``couette=``): ``"median"`` (median-dual segments,
#: any straight P1 mesh, first-order upwind), ``"grid"`` (box cells of a tensor grid, flux along the grid
#: lines only), ``"limited"`` (median-dual segments, second-order upwind with a Barth-Jespersen limiter)
#: ``"streamline"`` (median-dual segments, theta at the foot of the streamline through each segment: no
#: crosswind smearing; upwinded where theta would fall below 0) and ``"auto"`` (``"grid"`` on tensor grids,
#: :data:`TENSOR_SOURCES`, ``"median"`` on strips, :data:`ALIGNED_SOURCES`, else ``"streamline"``).
COUETTE_FLUXES = ("auto", "median", "grid", "limited", "streamline")


#: Mesh sources whose median-dual Couette flux carries a front along ``phi`` without crosswind smearing
#: (``strip_mesh``: one-dimensional films on a structured strip).
ALIGNED_SOURCES = ("strip",)
#: Note on a JFO result with a cavity solved by the median-dual flux of an unstructured mesh.
UNSTRUCTURED_JFO_NOTE = (
    "JFO with a cavity on an unstructured mesh with couette='median': the median-dual upwind Couette flux smears "
    "the fill fraction across the sliding direction, so loads and flows converge slowly (order about 1 or less; "
    "errors of several % on meshes of 1e4 nodes are measured in docs/jfo_gmsh.md); the default "
    "couette='streamline' removes the smearing, and for rectangular surfaces with rectangular pockets "
    "bearingfe.geometry.meshing.grid_mesh (couette='grid') too; or check the answer on a finer mesh")
#: Note on a JFO result with a cavity on an unstructured mesh of a surface with recesses (film steps).
RECESS_JFO_NOTE = (
    "JFO with a cavity on an unstructured mesh of a surface with recesses: a node on a recess contour carries one "
    "fill fraction for both film depths, a first-order error along the contours that dominates small loads "
    "(mesh_surface refines the contours by default, recess_size = size / 8: the dimpled slider of "
    "docs/jfo_gmsh.md is then 0.6 % off on 6,029 nodes, against 1.2 % on 11,903 nodes of uniform size); check "
    "the answer on a finer mesh (result.estimate_load_error())")


class JFOError(RuntimeError):
    """The JFO complementarity iteration did not converge (or theta left [0, 1])."""



# -- mesh geometry of the median dual ------------------------------------------------

@dataclass(frozen=True, eq=False)
class _Dual:
    """Median-dual segments of a straight P1 mesh: one per (triangle, edge)."""

    i: np.ndarray          # first node of the edge
    j: np.ndarray          # second node
    normal: np.ndarray     # (2, n) normal from i to j, scaled by the segment length
    midpoint: np.ndarray   # (2, n) segment midpoint (strictly inside its triangle)


def _dual(mesh: SupportMesh) -> _Dual:
    """The median dual of ``mesh`` (kept on the mesh)."""
    return mesh.cached("finite_volume.dual", lambda: median_dual(mesh.mesh))


def median_dual(m) -> _Dual:
    """The median-dual segments of a straight P1 triangle mesh ``m`` (a scikit-fem mesh): per (triangle,
    edge) the edge's nodes, the segment's normal from the first to the second scaled by its length, and
    its midpoint. Edge-pair major: segment ``e * n_triangles + k`` joins the nodes ``e`` and ``e + 1`` (mod 3)
    of triangle ``k`` (the three pairs computed at once as ``(3, n_triangles)`` arrays: half the time of a
    loop over the pairs, 2.9 against 5.7 ms CPU at 2.3e4 triangles, the same numbers bit for bit; the normals and
    midpoints written into the answer's arrays, negated in place: 1.42 against 1.73 ms at 1.4e4 triangles, 0.094
    against 0.106 at 962, mean of 100 calls)."""
    p, t = m.p, m.t[:3]
    nt = t.shape[1]
    x, y = p[0][t], p[1][t]                                   # (3, n_triangles): node e of each triangle
    gx, gy = (x[0] + x[1] + x[2]) / 3.0, (y[0] + y[1] + y[2]) / 3.0   # centroid
    nxt = [1, 2, 0]
    xj, yj = x[nxt], y[nxt]                                   # node e + 1
    mx, my = 0.5 * (x + xj), 0.5 * (y + yj)                   # edge midpoint
    # written into the answers' arrays (no stacked copies; the same operations, bit for bit)
    normal, midpoint = np.empty((2, 3, nt)), np.empty((2, 3, nt))
    nx, ny = np.subtract(gy, my, out=normal[0]), np.subtract(mx, gx, out=normal[1])   # (centroid - midpoint) turned
    flip = nx * (xj - x) + ny * (yj - y) < 0                  # ... to point from node e to node e + 1
    np.negative(normal, out=normal, where=flip)               # (-v is v * -1, bit for bit)
    np.multiply(np.add(mx, gx, out=midpoint[0]), 0.5, out=midpoint[0])
    np.multiply(np.add(my, gy, out=midpoint[1]), 0.5, out=midpoint[1])
    return _Dual(i=t.ravel(), j=t[nxt].ravel(), normal=normal.reshape(2, 3 * nt), midpoint=midpoint.reshape(2, 3 * nt))


@dataclass(frozen=True, eq=False)
class _GridFaces:
    """Box-cell faces of a tensor grid normal to phi: one per pair of phi-neighbours."""

    i: np.ndarray      # node (k, l)
    j: np.ndarray      # node (k + 1, l)
    x0: np.ndarray     # phi of the two nodes (the face lies midway)
    x1: np.ndarray
    lo: np.ndarray     # z range of the face (midway to the z-neighbours, or the edge)
    hi: np.ndarray
    box: np.ndarray    # (4, n_nodes) box cell of each node: phi_lo, phi_hi, z_lo, z_hi


def _grid_faces(mesh: SupportMesh) -> _GridFaces:
    """Faces of the box cells of a tensor-grid mesh (``grid_mesh``, ``strip_mesh``; kept on the mesh).

    The grid may have holes (the pockets of ``grid_mesh``, whole cells left out): a face between two
    ``phi``-neighbours then spans only the halves of the two grid rows that lie in the mesh.

    Raises
    ------
    ValueError
        If the mesh is not a tensor grid (possibly with whole cells left out) split into triangles.
    """
    return mesh.cached("finite_volume.grid_faces", lambda: _build_grid_faces(mesh))


def _build_grid_faces(mesh: SupportMesh) -> _GridFaces:
    """:func:`_grid_faces` built afresh: on a whole ``grid_mesh`` its numbering from its lines
    (:func:`~bearingfe.geometry.meshing.tensor_lines`), else found and checked from the nodes
    (:func:`_grid_numbering`)."""
    lines = tensor_lines(mesh)
    if lines is None:
        kx, ky, grid, inside = _grid_numbering(mesh.mesh)
    else:   # node iz + nz ix, every cell in the mesh
        nx, nz = lines[0].size, lines[1].size
        k = np.arange(nx * nz, dtype=np.int64)
        kx, ky, grid, inside = k // nz, k % nz, k.reshape(nx, nz), np.ones((nx - 1, nz - 1), bool)
    return _faces_on_grid(mesh.mesh.p, kx, ky, grid, inside)


def _grid_numbering(m) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The grid line numbers ``kx``, ``ky`` of each node of the mesh ``m``, the node at each grid point
    (``(nx, ny)``, -1 where none) and which grid cells are in the mesh (``(nx - 1, ny - 1)``).

    Raises
    ------
    ValueError
        If the mesh is not a tensor grid (possibly with whole cells left out) split into triangles.
    """
    p = m.p
    tol = 1e-9 * float(max(np.ptp(p[0]), np.ptp(p[1]), 1e-300))
    ux, kx = np.unique(np.round(p[0] / tol).astype(np.int64), return_inverse=True)
    uy, ky = np.unique(np.round(p[1] / tol).astype(np.int64), return_inverse=True)
    nx, ny = ux.size, uy.size
    grid = np.full((nx, ny), -1, dtype=np.int64)
    grid[kx, ky] = np.arange(p.shape[1])
    t = m.t[:3]
    cells = np.zeros((max(nx - 1, 1), max(ny - 1, 1)), np.int64)   # triangles per grid cell (2: in the mesh)
    kt, lt = kx[t], ky[t]
    tri_ok = (np.ptp(kt, axis=0) == 1) & (np.ptp(lt, axis=0) == 1)
    if np.all(tri_ok):   # counted by bincount (numpy's add.at is several times slower)
        flat = kt.min(axis=0) * cells.shape[1] + lt.min(axis=0)
        cells = np.bincount(flat, minlength=cells.size).reshape(cells.shape)
    if (nx < 2 or ny < 2 or np.bincount(kx * ny + ky, minlength=nx * ny).max() > 1 or not np.all(tri_ok)
            or np.any((cells != 0) & (cells != 2))):
        raise ValueError("couette='grid' needs a tensor-grid mesh (bearingfe.geometry.meshing.grid_mesh or strip_mesh): "
                         "nodes on the lines of a rectangular grid, each cell split into two triangles")
    return kx, ky, grid, cells == 2


def _faces_on_grid(p: np.ndarray, kx: np.ndarray, ky: np.ndarray, grid: np.ndarray,
                   inside: np.ndarray) -> _GridFaces:
    """The box faces of the grid numbered as :func:`_grid_numbering` numbers it (nodes ``p``)."""
    nx, ny = grid.shape
    xs = np.empty(nx)
    ys = np.empty(ny)
    xs[kx[::-1]], ys[ky[::-1]] = p[0, ::-1], p[1, ::-1]   # each grid line at its first node's coordinate
    ylo = np.concatenate([[ys[0]], 0.5 * (ys[:-1] + ys[1:])])
    yhi = np.concatenate([0.5 * (ys[:-1] + ys[1:]), [ys[-1]]])
    xlo = np.concatenate([[xs[0]], 0.5 * (xs[:-1] + xs[1:])])
    xhi = np.concatenate([0.5 * (xs[:-1] + xs[1:]), [xs[-1]]])
    box = np.array([xlo[kx], xhi[kx], ylo[ky], yhi[ky]])   # node n at grid[kx[n], ky[n]] (one node per point)
    # face between (k, l) and (k + 1, l): its lower half lies in the cell (k, l - 1), its upper half in (k, l)
    below = np.zeros((nx - 1, ny), bool)
    above = np.zeros((nx - 1, ny), bool)
    below[:, 1:] = inside
    above[:, :-1] = inside
    lo = np.where(below, ylo[None, :], ys[None, :])
    hi = np.where(above, yhi[None, :], ys[None, :])
    keep = (below | above).ravel()
    x0 = np.repeat(xs[:-1], ny)
    return _GridFaces(i=grid[:-1].ravel()[keep], j=grid[1:].ravel()[keep], box=box,
                      x0=x0[keep], x1=np.repeat(xs[1:], ny)[keep], lo=lo.ravel()[keep], hi=hi.ravel()[keep])


# -- limited linear reconstruction of theta on the median dual ------------------------------------

@dataclass(frozen=True, eq=False)
class _Reconstruction:
    """Second-order upwind values of theta on the median-dual segments: theta of the upwind node plus its
    limited nodal gradient times the offset to the segment midpoint (Barth-Jespersen limiter: the value
    stays within the range of theta over the node and its edge neighbours)."""

    i: np.ndarray          # segment nodes (flux positive from i to j)
    j: np.ndarray
    up: np.ndarray         # upwind node of each segment
    flux: np.ndarray       # wedge/2 h n_phi |segment| of each segment
    offset: np.ndarray     # (2, n_segments) segment midpoint minus the upwind node
    gradient: sp.csr_matrix   # (2 n_nodes, n_nodes): nodal theta -> area-weighted mean P1 gradient
    edges: np.ndarray      # (2, n_edges) node pairs of the mesh edges


def _reconstruction(mesh: SupportMesh, d: _Dual, flux: np.ndarray) -> _Reconstruction:
    m = mesh.mesh
    p, t = m.p, m.t[:3]
    x, y = p[0][t], p[1][t]
    det = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0])
    gx = np.array([y[1] - y[2], y[2] - y[0], y[0] - y[1]]) / det
    gy = np.array([x[2] - x[1], x[0] - x[2], x[1] - x[0]]) / det
    area = 0.5 * np.abs(det)
    n = m.nvertices
    node_area = np.bincount(t.ravel(), weights=np.tile(area, 3), minlength=n)
    rows, cols, vx, vy = [], [], [], []
    for a in range(3):
        for b in range(3):
            rows.append(t[a]), cols.append(t[b])
            vx.append(area * gx[b] / node_area[t[a]]), vy.append(area * gy[b] / node_area[t[a]])
    rows, cols = np.concatenate(rows), np.concatenate(cols)
    G = sp.vstack([sp.csr_matrix((np.concatenate(vx), (rows, cols)), shape=(n, n)),
                   sp.csr_matrix((np.concatenate(vy), (rows, cols)), shape=(n, n))]).tocsr()
    up = np.where(flux > 0, d.i, d.j)
    return _Reconstruction(i=d.i, j=d.j, up=up, flux=flux, offset=d.midpoint - p[:, up], gradient=G,
                           edges=m.facets)


def _limiter(rec: _Reconstruction, theta: np.ndarray) -> np.ndarray:
    """Barth-Jespersen factor in [0, 1] per node: the reconstructed values on the node's outgoing segments
    stay within the range of theta over the node and its edge neighbours."""
    n = theta.size
    g = (rec.gradient @ theta).reshape(2, n)
    delta = g[0, rec.up] * rec.offset[0] + g[1, rec.up] * rec.offset[1]
    a, b = rec.edges
    hi, lo = theta.copy(), theta.copy()
    np.maximum.at(hi, a, theta[b]), np.maximum.at(hi, b, theta[a])
    np.minimum.at(lo, a, theta[b]), np.minimum.at(lo, b, theta[a])
    room = np.where(delta > 0, hi[rec.up] - theta[rec.up], lo[rec.up] - theta[rec.up])
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(np.abs(delta) > 1e-14, room / delta, np.inf)
    alpha = np.ones(n)
    np.minimum.at(alpha, rec.up, np.clip(ratio, 0.0, 1.0))
    return alpha


def _limited_flux(rec: _Reconstruction, alpha: np.ndarray) -> sp.csr_matrix:
    """Outflow per cell of the reconstruction's increment over the first-order upwind flux, linear in
    theta for the limiter ``alpha`` (per node): ``sum_s (+-) f_s alpha_up grad_up theta . offset_s``."""
    n = alpha.size
    G = rec.gradient
    weight = rec.flux * alpha[rec.up]
    R = (sp.diags(weight * rec.offset[0]) @ G[:n][rec.up] + sp.diags(weight * rec.offset[1]) @ G[n:][rec.up])
    seg = np.arange(rec.up.size)
    E = sp.csr_matrix((np.concatenate([np.ones(seg.size), -np.ones(seg.size)]),
                       (np.concatenate([rec.i, rec.j]), np.concatenate([seg, seg]))), shape=(n, seg.size))
    return (E @ R).tocsr()


# -- streamline upwind values of theta on the median dual ---------------------------------------------

def _streamline_weights(mesh: SupportMesh, d: _Dual, direction, grad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nodes ``(3, n_segments)`` and weights of theta at the foot of each median-dual segment's streamline.

    ``direction``: the sliding's sign along ``e_phi`` (a float), or the Couette velocity at each segment's
    midpoint (two arrays: a runner other than the original, :mod:`bearingfe.geometry.runner`); ``grad``: the
    gradients of the triangles' barycentric functions ``(2, 3, n_triangles)`` (:attr:`_Cells.grad`).
    From the segment midpoint the line along ``-direction`` (upstream of the sliding) is followed to
    the edge of the segment's triangle; theta there is the P1 interpolation of the triangle's nodes (two
    non-zero weights, both >= 0). A fill fraction that varies across the sliding direction only is thus
    carried without crosswind smearing (the foot lies on the same ``z`` as the segment), and the exact
    cavity solution (``theta h`` constant along ``phi``) is met for a linear ``theta``.
    """
    m = mesh.mesh
    p, t = m.p, m.t[:3]
    nt = t.shape[1]
    # segments are ordered edge-pair major (median_dual): segment e * nt + k lies in triangle k, so the
    # per-triangle arrays broadcast over the pairs as (3 nodes, 1, n_triangles) against (3 pairs, n_triangles)
    gx, gy = grad[0][:, None, :], grad[1][:, None, :]     # d lambda_k / d phi, d lambda_k / d z
    xs, ys = d.midpoint.reshape(2, 3, nt)
    nxt = t[[1, 2, 0]]                                    # lambda_k vanishes at node k + 1 (and k + 2)
    lam = gx * (xs - p[0][nxt][:, None, :]) + gy * (ys - p[1][nxt][:, None, :])
    if np.ndim(direction) == 0:
        rate = np.broadcast_to(-direction * gx, lam.shape)   # d lambda / d tau along the upstream ray
    else:
        rate = -(direction[0].reshape(3, nt) * gx + direction[1].reshape(3, nt) * gy)
    with np.errstate(divide="ignore", invalid="ignore"):
        tau = -lam / rate
    tau[~(rate < 0)] = np.inf                             # the ray leaves the triangle where lambda_k hits 0
    step = np.minimum(np.minimum(tau[0], tau[1]), tau[2])
    step[~np.isfinite(step)] = 0.0
    w = lam + rate * step
    np.maximum(w, 0.0, out=w)
    w /= w[0] + w[1] + w[2]
    return np.tile(t, (1, 3)), w.reshape(3, 3 * nt)


def _aligned_weights(mesh: SupportMesh, d: _Dual, sign: float, grad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_streamline_weights` for sliding along ``sign * e_phi``, found once per mesh and sign (read-only
    arrays: the flux's callers copy before they change them)."""
    def build() -> tuple[np.ndarray, np.ndarray]:
        nodes, w = _streamline_weights(mesh, d, sign, grad)
        nodes.flags.writeable = w.flags.writeable = False
        return nodes, w

    return mesh.cached(("finite_volume.aligned_weights", sign), build)


@dataclass(frozen=True, eq=False)
class _Streamline:
    """The streamline flux's pieces: segments, their fluxes ``f``, foot nodes and weights, upwind nodes."""

    d: _Dual
    flux: np.ndarray
    nodes: np.ndarray      # (3, n_segments)
    weights: np.ndarray    # (3, n_segments), >= 0, summing to 1
    up: np.ndarray         # upwind node of each segment
    scale: np.ndarray | None = None      # (3, n_segments): deepest film at the node / film on the segment's side
    up_scale: np.ndarray | None = None   # (n_segments,): the same for the upwind node
    pattern: "_P1Pattern | None" = None  # the mesh's P1 pattern, where it has one (_p1_pattern)

    def matrices(self, n: int, upwinded: np.ndarray) -> tuple[sp.csr_matrix, sp.csr_matrix | None]:
        """The flux of full and of cavitated nodes' theta, with the segments ``upwinded`` (bool per segment)
        taking theta of their upwind node."""
        w = np.where(upwinded, 0.0, self.weights)
        w[0] += np.where(upwinded, 1.0, 0.0)
        nt = self.nodes.shape[1] // 3
        t = self.nodes[:, :nt]   # the foot nodes are the segment's triangle's (median_dual's segment order)
        first = None
        if upwinded.any():   # the upwinded segments' first weight goes to their upwind node's column
            pair = np.arange(upwinded.size) // nt
            first = np.where(upwinded, np.where(self.up == self.d.i, pair, (pair + 1) % 3), 0)
        if self.scale is None:
            return _streamline_flux(n, t, self.flux, w, first, self.pattern), None
        s = self.scale.copy()
        s[0] = np.where(upwinded, self.up_scale, s[0])
        return _streamline_fluxes(n, t, self.flux, w, w * s, first, self.pattern)


def _contour_scales(mesh: SupportMesh, film: Film, d: _Dual, f: np.ndarray):
    """Per segment and node of its triangle: the deepest film around the node over the film at the node on
    the triangle's side (1 except at nodes on recess contours), and the same for the segment's upwind node;
    None without recesses.

    In a cavity the oil flux ``theta h`` is carried along ``phi`` and is continuous across a recess contour,
    while ``theta`` jumps; a contour node has one unknown for both sides, so its cavitated ``theta`` refers to
    its deepest film and each triangle takes ``theta h_max / h_side`` of it (the same oil flux on both sides).
    """
    surface = mesh.surface
    if surface is None or not getattr(surface, "recesses", ()):
        return None, None
    m = mesh.mesh
    p, t = m.p, m.t[:3]
    nt = t.shape[1]
    x, y = p[0][t], p[1][t]                                  # (3, n_triangles)
    gx, gy = x.mean(axis=0), y.mean(axis=0)
    # just inside the triangle (its side of a step), the nodes' points as rows of 3 per triangle
    depth = _rows_depth(surface, (x + 1e-6 * (gx - x)).T, (y + 1e-6 * (gy - y)).T).T
    deepest = np.zeros(m.nvertices)
    deep = depth > 0                                         # the rest leaves deepest at 0: not scattered
    np.maximum.at(deepest, t[deep], depth[deep])
    ht = _film_at(film, p[0], p[1])[t]
    scale = (ht + deepest[t]) / (ht + depth)                 # (3, n_triangles)
    first = np.repeat(np.arange(3), nt)                      # segment e * nt + k joins nodes e, e + 1 of k
    local_up = np.where(f > 0, first, (first + 1) % 3)
    return np.tile(scale, (1, 3)), scale[local_up, np.tile(np.arange(nt), 3)]


#: Passes of ``couette="streamline"`` at most that upwind the segments out of nodes with theta < 0 or
#: switching in an active-set cycle (each one warm-started active-set solve).
STREAMLINE_PASSES = 8


def _streamline_flux(n: int, t: np.ndarray, f: np.ndarray, w: np.ndarray,
                     first: np.ndarray | None = None, pattern: "_P1Pattern | None" = None) -> sp.csr_matrix:
    """Outflow per dual cell of ``f_s theta(foot_s)`` through each median-dual segment (from ``i`` to ``j``,
    :func:`median_dual`'s order: segment ``e * n_triangles + k`` joins the nodes ``e`` and ``e + 1`` of
    triangle ``k``), theta at the foot ``sum_b w[b] theta(t[b])`` over the triangle's nodes ``t`` ``(3,
    n_triangles)``; ``first``: per segment the local node (0..2) that takes the weight ``w[0]`` (default 0).
    Summed per triangle into its 3 x 3 block first (the P1 stiffness's pattern: 9 entries a triangle for
    the sort into CSR, not 18 per segment triple); with the mesh's ``pattern`` (:func:`_p1_pattern`, of the
    triangles ``t``) the blocks are summed straight onto it (:func:`_on_pattern`), without the sort."""
    if pattern is not None:
        return _on_pattern(pattern, _flux_blocks(t.shape[1], f, w, first))
    rows, cols = _block_places(t)
    return sp.csr_matrix((_flux_blocks(t.shape[1], f, w, first), (rows, cols)), shape=(n, n))


def _streamline_fluxes(n: int, t: np.ndarray, f: np.ndarray, w: np.ndarray, w2: np.ndarray,
                       first: np.ndarray | None = None,
                       pattern: "_P1Pattern | None" = None) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """:func:`_streamline_flux` of the weights ``w`` and of ``w2`` (the full and the cavitated nodes' theta of
    a surface with recesses), sorted into CSR at once: the two as the real and imaginary parts of one complex
    matrix, whose sort and sums of duplicates are those of each part alone (the places depend on the indices
    only, the sums are per part in the same order): the same matrices bit for bit, 0.36 against 0.44 ms CPU
    at 810 nodes, 5.0 against 6.6 ms at 11,903 (the dimple, mean of 10-120 calls). With the mesh's ``pattern``
    each summed onto it (:func:`_on_pattern`)."""
    nt = t.shape[1]
    if pattern is not None:
        return (_on_pattern(pattern, _flux_blocks(nt, f, w, first)),
                _on_pattern(pattern, _flux_blocks(nt, f, w2, first)))
    rows, cols = _block_places(t)
    both = np.empty(9 * nt, complex)
    both.real = _flux_blocks(nt, f, w, first)
    both.imag = _flux_blocks(nt, f, w2, first)
    Z = sp.csr_matrix((both, (rows, cols)), shape=(n, n))
    return (sp.csr_matrix((Z.data.real.copy(), Z.indices, Z.indptr), shape=(n, n)),
            sp.csr_matrix((Z.data.imag.copy(), Z.indices.copy(), Z.indptr.copy()), shape=(n, n)))


def _block_places(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rows and columns of the 3 x 3 blocks of the triangles ``t`` (:func:`_flux_blocks`' entries)."""
    return np.repeat(t, 3, axis=0).ravel(), np.tile(t, (3, 1)).ravel()


def _flux_blocks(nt: int, f: np.ndarray, w: np.ndarray, first: np.ndarray | None) -> np.ndarray:
    """The 3 x 3 blocks ``(row node, column node, triangle)``, flat, of :func:`_streamline_flux`."""
    local = np.zeros((3, 3, nt))   # (row node, column node, triangle)
    flat = local.reshape(-1)
    k = np.arange(nt)
    for e in range(3):
        seg = slice(e * nt, (e + 1) * nt)
        a, b = e, (e + 1) % 3
        for c in range(3):
            v = f[seg] * w[c, seg]
            if c == 0 and first is not None:
                col = first[seg]
                flat[(3 * a + col) * nt + k] += v
                flat[(3 * b + col) * nt + k] -= v
            else:
                local[a, c] += v
                local[b, c] -= v
    return flat


@dataclass(frozen=True, eq=False)
class _P1Pattern:
    """The CSR pattern of the P1 matrices of a triangle mesh (each node with itself and its edge neighbours,
    sorted) and where the terms go on it, from the edges of the triangles (:func:`_p1_pattern`).

    The values are gathered per slot first: edge ``e`` from its lower to its higher node is slot ``e``, the
    other way ``n_edges + e``, the diagonal of node ``i`` slot ``2 n_edges + i``; ``take`` maps each stored
    entry of the CSR arrays to its slot."""

    indptr: np.ndarray
    indices: np.ndarray
    take: np.ndarray        # (nnz,) the slot of each stored entry
    diagonal: np.ndarray    # (n,) the place of each node's diagonal entry
    off: np.ndarray         # (nnz,) bool: the off-diagonal entries
    edge: np.ndarray        # (3, n_triangles): the edge of each triangle's node pair (e, e + 1) (the mesh's t2f)
    t: np.ndarray           # (3, n_triangles): the triangles, nodes increasing
    n_edges: int

    @functools.cached_property
    def block_slot(self) -> np.ndarray:
        """(9 n_triangles,) the slot of each entry of :func:`_flux_blocks`' 3 x 3 blocks (built at the first
        flux: a stiffness alone does not need it)."""
        t, edge, n_edges = self.t, self.edge, self.n_edges
        block_slot = np.empty((3, 3, t.shape[1]), np.int64)   # (row node, column node, triangle): _flux_blocks'
        pair = {(0, 1): 0, (1, 2): 1, (0, 2): 2}
        for a in range(3):
            for c in range(3):   # (the row's node is the higher one where a > c: nodes increasing)
                if a == c:
                    np.add(t[a], 2 * n_edges, out=block_slot[a, c])
                else:
                    np.add(edge[pair[min(a, c), max(a, c)]], n_edges if a > c else 0, out=block_slot[a, c])
        return block_slot.ravel()


def _p1_pattern(mesh: SupportMesh) -> _P1Pattern | None:
    """:class:`_P1Pattern` of a straight triangle mesh from scikit-fem's edges of the triangles (kept on the
    mesh); None where they are not at hand (``t2f``, built with the mesh's facets: finding them would cost more
    than the sorts it saves on a mesh solved once; :func:`_stiffness_pattern` finds its own at a mesh's second
    stiffness) or the pattern does not take the triangles (:func:`_pattern_of`). Kept: about 120 bytes a
    triangle (the blocks' slots 72, built at the first flux, the entries' slots and places 40, the rows 4 a
    node). The streamline flux is summed on this one only (on it the flux's diagonal differs from the scipy
    conversion's by round-off: :func:`_on_pattern`), so a mesh keeps the one or the other from its first solve."""
    return mesh.cached("finite_volume.p1_pattern", lambda: _build_p1_pattern(mesh.mesh))


def _build_p1_pattern(m) -> _P1Pattern | None:
    """:func:`_p1_pattern` built afresh from scikit-fem's facets and ``t2f``."""
    if not (hasattr(m, "_t2f") and hasattr(m, "_facets")) or m.t.shape[0] != 3 or m.dim() != 2:
        return None
    return _pattern_of(m.t, int(m.nvertices), np.asarray(m.facets), np.asarray(m.t2f))


def _stiffness_pattern(mesh: SupportMesh, flux: bool = False) -> _P1Pattern | None:
    """The pattern the mesh's stiffness is summed on (:func:`_stiffness_on`), the one place that decides when
    it is built. Where the streamline flux is summed on it too (``flux``) and scikit-fem's edges are at hand,
    :func:`_p1_pattern` from the first stiffness; else from the mesh's second stiffness on (None at the first:
    :func:`_stiffness_of` keeps scipy's sums, and a mesh solved once pays no pattern): :func:`_p1_pattern`
    where scikit-fem's edges are at hand, else the pattern of the triangles' own edges
    (:func:`_triangle_edges`, the same arrays)."""
    if flux:
        pattern = _p1_pattern(mesh)
        if pattern is not None:
            return pattern
    kept = mesh.cached("finite_volume.stiffness_pattern", dict)   # {"seen": True} after the first, then "pattern"
    if "pattern" not in kept:
        if not kept.get("seen"):
            kept["seen"] = True
            return None
        m = mesh.mesh
        pattern = _p1_pattern(mesh) if hasattr(m, "_t2f") else None
        if pattern is None and m.t.shape[0] == 3 and m.dim() == 2:
            pattern = _pattern_of(m.t, int(m.nvertices), *_triangle_edges(m.t, int(m.nvertices)))
        kept["pattern"] = pattern
    return kept["pattern"]


def _triangle_edges(t: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The edges ``(2, n_edges)`` (lower node, higher node; sorted) of the triangles ``t`` and the edge of each
    triangle's node pairs (0, 1), (1, 2), (0, 2) (``(3, n_triangles)``): scikit-fem's ``facets`` and ``t2f`` for
    triangles whose nodes are increasing."""
    a, b = t[[0, 1, 0]], t[[1, 2, 2]]
    keys = np.minimum(a, b).astype(np.int64) * n + np.maximum(a, b)
    unique, edge = np.unique(keys.ravel(), return_inverse=True)
    return np.array([unique // n, unique % n]), edge.reshape(t.shape)


def _pattern_of(t: np.ndarray, n: int, facets: np.ndarray, edge: np.ndarray) -> _P1Pattern | None:
    """:class:`_P1Pattern` of the triangles ``t`` with the edges ``facets`` and each triangle's ``edge`` of its
    node pairs (0, 1), (1, 2), (0, 2): the pattern by one conversion of its entries, each numbered by its slot,
    into CSR (each entry once: the slot numbers come back as the values, in the CSR order). None where the
    triangles' nodes are not increasing, the edges do not match them, or an edge has more than two triangles."""
    n_edges = facets.shape[1]
    # each triangle's nodes increasing (scikit-fem sorts them): the pairs' lower nodes are 0, 1, 0, higher 1, 2, 2
    if (edge.shape != t.shape or not (np.all(t[0] < t[1]) and np.all(t[1] < t[2]))
            or not np.array_equal(facets[0][edge], t[[0, 1, 0]]) or not np.array_equal(facets[1][edge], t[[1, 2, 2]])
            or np.bincount(edge.ravel(), minlength=n_edges).max(initial=0) > 2):
        return None
    nodes = np.arange(n)
    # each row's entries below, on and above the diagonal in this order: with scikit-fem's facets (sorted by their
    # lower, then higher node) the conversion's rows come out sorted, without the sort (0.06 against 0.10 ms at
    # 1,936 nodes, CPU, mean of 2,000); the slots as numbered above, the same arrays
    rows = np.concatenate([facets[1], nodes, facets[0]])
    cols = np.concatenate([facets[0], nodes, facets[1]])
    slots = np.concatenate([n_edges + np.arange(n_edges), 2 * n_edges + nodes, np.arange(n_edges)])
    P = sorted_entries(rows, cols, slots.astype(float), n)
    take = P.data.astype(np.int64)
    if take.size != rows.size:   # (repeated facets)
        return None
    is_diagonal = take >= 2 * n_edges
    diagonal = np.empty(n, np.int64)
    diagonal[take[is_diagonal] - 2 * n_edges] = np.flatnonzero(is_diagonal)
    return _P1Pattern(indptr=P.indptr, indices=P.indices, take=take, diagonal=diagonal,
                      off=~is_diagonal, edge=edge, t=t, n_edges=n_edges)


def _on_pattern(pattern: _P1Pattern, blocks_flat: np.ndarray) -> sp.csr_matrix:
    """The matrix of the triangles' 3 x 3 blocks (:func:`_flux_blocks`' flat order) on ``pattern``: each slot the
    sum of its entries (``np.bincount``, in the blocks' order), explicit zeros kept (as scipy's conversion keeps
    them). The same pattern as the conversion of the blocks into CSR; the values the same sums (two terms at an
    edge, any order: bit for bit; a node's diagonal sums its triangles' terms in another order: round-off)."""
    slots = np.bincount(pattern.block_slot, weights=blocks_flat, minlength=2 * pattern.n_edges + pattern.diagonal.size)
    n = pattern.diagonal.size
    return compressed(slots[pattern.take], pattern.indices.copy(), pattern.indptr.copy(), (n, n), canonical=True)


# -- P1 cell formulas on the arrays (no scikit-fem assembly) -------------------------------------------

#: Cells (triangles) or faces the passes over quadrature points of the assembly take at a time (:func:`_blocks`):
#: their temporaries, a few hundred kB each, stay in cache and are reused, where arrays of all points (35 MB
#: each at 7.2e5 triangles x 6 points) were new memory the system had to supply, page by page.
BLOCK = 16384


@dataclass(frozen=True, eq=False)
class _Cells:
    """What the P1 integrals of the scheme need, per mesh: the triangles, the gradients of their
    barycentric functions (constant per triangle), the barycentric coordinates of the reference
    quadrature points and the quadrature weights (the basis's own points and weights)."""

    t: np.ndarray      # (3, n_triangles)
    grad: np.ndarray   # (2, 3, n_triangles): d lambda_k / d (phi, z)
    lam: np.ndarray    # (3, n_points): lambda_k at the reference quadrature points
    dx: np.ndarray     # (n_triangles, n_points)
    n: int             # nodes (dofs)


def _cells(mesh: SupportMesh, ops: Operators) -> _Cells:
    """The P1 triangles of ``mesh`` with their gradients and quadrature (kept on the mesh)."""
    return mesh.cached("finite_volume.cells", lambda: _build_cells(mesh, ops))


def _build_cells(mesh: SupportMesh, ops: Operators) -> _Cells:
    """:func:`_cells` built afresh."""
    m = mesh.mesh
    p, t = m.p, m.t[:3]
    grad = np.empty((2, 3, t.shape[1]))   # written block by block: no temporaries of all triangles
    for block in blocks(t.shape[1], BLOCK):
        x, y = p[0][t[:, block]], p[1][t[:, block]]
        det = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0])
        for k, (a, b) in enumerate(((1, 2), (2, 0), (0, 1))):
            np.subtract(y[a], y[b], out=grad[0, k, block])
            np.subtract(x[b], x[a], out=grad[1, k, block])
        grad[:, :, block] /= det
    X = np.asarray(ops.basis.X)
    return _Cells(t=t, grad=grad, lam=np.array([1.0 - X[0] - X[1], X[0], X[1]]), dx=np.asarray(ops.basis.dx),
                  n=int(m.nvertices))


def _integrals(cells: _Cells, f_q: np.ndarray) -> np.ndarray:
    """``int_T f`` per triangle from ``f`` at the quadrature points."""
    return _integrals_of(f_q, cells.dx)


def _integrals_of(f_q: np.ndarray, dx: np.ndarray) -> np.ndarray:
    """The quadrature sums ``sum_k f_k dx_k`` of the rows of ``f_q`` and ``dx`` (some triangles' integrals)."""
    return np.sum(f_q * dx, axis=1)


def _stiffness(cells: _Cells, c_q: np.ndarray) -> sp.csr_matrix:
    """``int c grad phi_i . grad phi_j`` from ``c`` at the quadrature points (:func:`_stiffness_of` its
    integrals over the triangles)."""
    return _stiffness_of(cells, _integrals(cells, c_q))


def _stiffness_of(cells: _Cells, w: np.ndarray, pattern: _P1Pattern | None = None) -> sp.csr_matrix:
    """``int c grad phi_i . grad phi_j`` from ``w = int_T c`` per triangle (P1: the gradients are constant on
    a triangle, so each triangle contributes ``int_T c`` times their products). Summed from the 3 edges of each
    triangle (``A + A^T``), the diagonal from the rows' sums (a triangle's barycentric gradients sum to zero): 3
    entries a triangle instead of 9; the entries that sum to exactly zero, across the diagonals of a square
    grid, are left out. On the mesh's P1 ``pattern`` (:func:`_stiffness_pattern`) without a sort
    (:func:`_stiffness_on`); without one (a mesh's first stiffness) by scipy's kernels of those sums on the arrays
    (:func:`_stiffness_converted`). Both give bit for bit scipy's sparse sums
    (the COO conversion of ``U``, ``U + U^T``, the rows' sums), the pattern's without their sorts (CPU, mean of
    300 calls, load ~4: 0.17-0.18 against 0.38-0.45 ms at the pocket pad's 1,936 nodes, 0.81-0.86 against
    0.88-0.93 ms on a 70 x 70 grid; a mesh's second call, the pattern built from scikit-fem's edges, 0.75 and
    2.5 ms)."""
    vals = _edge_terms(cells, w)
    if pattern is not None:
        return _stiffness_on(pattern, vals)
    return _stiffness_converted(cells.t, vals, cells.n)


def _stiffness_converted(t: np.ndarray, vals: np.ndarray, n: int) -> sp.csr_matrix:
    """:func:`_stiffness_of` from the edge terms ``vals`` without a pattern: scipy's sparse sums by its own kernels on
    the arrays, without its sparse objects between them (:mod:`bearingfe.core.compressed`): ``U`` the conversion of
    the terms at each triangle's node pairs ``(0, 1), (1, 2), (2, 0)`` (:func:`~bearingfe.core.compressed.sorted_entries`),
    ``A = U + U^T`` (:func:`~bearingfe.core.compressed.csr_sum`, sums of zero dropped), the rows' sums by numpy's
    ``add.reduceat`` over the rows with entries (as scipy's ``sum(axis=1)``) and ``A`` plus the negated nonzero sums
    on the diagonal (``a + (-d)``, the number ``a - d`` of scipy's ``A - diag(d)``): the same arrays."""
    a, b = [0, 1, 2], [1, 2, 0]
    U = sorted_entries(t[a].ravel(), t[b].ravel(), vals, n)
    A = csr_sum(U, csr_transposed(U))
    sums = np.zeros(n)
    rows = np.flatnonzero(A.indptr[1:] > A.indptr[:-1])
    if rows.size:
        sums[rows] = np.add.reduceat(A.data, A.indptr[rows])
    on = np.flatnonzero(sums)   # (scipy's diagonal matrix keeps the nonzero values only)
    indptr = np.zeros(n + 1, A.indptr.dtype)
    indptr[on + 1] = 1
    np.cumsum(indptr, out=indptr)
    return csr_sum(A, compressed(-sums[on], on.astype(A.indptr.dtype), indptr, (n, n), canonical=True))


def _stiffness_on(pattern: _P1Pattern, vals: np.ndarray) -> sp.csr_matrix:
    """:func:`_stiffness_of` from the edge terms ``vals`` on the mesh's P1 ``pattern``: each edge's (at most two)
    terms summed (``np.bincount``; two terms in any order: the entry of ``U + U^T``), then the rows' sums
    (:func:`_rows_summed`). The same arrays bit for bit as the sparse sums, without their sorts."""
    n_edges, n = pattern.n_edges, pattern.diagonal.size
    per_edge = np.bincount(pattern.edge.ravel(), weights=vals, minlength=n_edges)
    slots = np.zeros(2 * n_edges + n)
    slots[:n_edges] = per_edge
    slots[n_edges:2 * n_edges] = per_edge
    return _rows_summed(slots[pattern.take], pattern.indices, pattern.indptr, pattern.diagonal, pattern.off)


def _rows_summed(data: np.ndarray, indices: np.ndarray, indptr: np.ndarray, diagonal: np.ndarray,
                 off: np.ndarray) -> sp.csr_matrix:
    """The stiffness from its off-diagonal entries: ``data`` (written in place) on the canonical CSR arrays
    ``indices`` and ``indptr`` of ``n`` rows with one diagonal entry each (at ``diagonal``; ``off`` the mask of
    the others). The entries that are zero left out (as scipy's sums drop them), each row's remaining off-diagonal
    entries summed by numpy's ``add.reduceat`` over the rows that have any (as scipy's ``sum(axis=1)``) and
    negated onto the diagonal, a zero diagonal left out: ``A - diag(A 1)`` as scipy's sparse sums give it.

    Where zeros are left out (a grid's cancelled diagonals), they go by
    :func:`~bearingfe.core.compressed.csr_without_zeros` (scipy's kernel), the off-diagonal ones with the
    diagonal's slots zeroed first: the same arrays as numpy's masks, in less time
    (the whole 1.01 against 1.54 ms at 10,201 grid nodes, 0.24 against 0.39 at 2,601; CPU, best of 3 x 300 calls, load ~4)."""
    n = diagonal.size
    off_values = data[off]
    off_ptr = indptr - np.arange(n + 1)   # each row's off-diagonal entries among them (one diagonal a row)
    if not np.all(off_values):   # (grids' diagonals): the rows' sums run over the nonzero entries only, as scipy's
        data[diagonal] = 0.0
        nonzero = csr_without_zeros(compressed(data, indices, indptr, (n, n), canonical=True))
        off_values, off_ptr = nonzero.data, nonzero.indptr
    sums = np.zeros(n)
    rows = np.flatnonzero(off_ptr[1:] > off_ptr[:-1])
    if rows.size:
        sums[rows] = np.add.reduceat(off_values, off_ptr[rows])
    data[diagonal] = -sums
    if not np.all(data):
        return csr_without_zeros(compressed(data, indices, indptr, (n, n), canonical=True))
    return compressed(data, indices.copy(), indptr.copy(), (n, n), canonical=True)


def _edge_terms(cells: _Cells, w: np.ndarray) -> np.ndarray:
    """The terms ``w (grad lambda_k . grad lambda_k+1)`` of :func:`_stiffness_of` at the triangles' edges ``(k,
    k + 1)``, edge-pair major (flat, ``3 n_triangles``), written block by block (:data:`BLOCK` triangles): the
    same numbers as the products of the gathered gradient rows at once, without their five temporaries of all
    edges (600 x 600 dimple cells, 7.2e5 triangles: 5.8 against 23-25 ms CPU, mean of 10 calls, load ~3)."""
    g = cells.grad
    vals = np.empty((3, w.size))
    for block in blocks(w.size, BLOCK):
        wb = w[block]
        for k in range(3):
            o = vals[k, block]
            np.multiply(g[0, k, block], g[0, (k + 1) % 3, block], out=o)
            o += g[1, k, block] * g[1, (k + 1) % 3, block]
            o *= wb
    return vals.ravel()


def _load(cells: _Cells, f_q: np.ndarray | None) -> np.ndarray:
    """``int f phi_i`` for every node; ``f_q`` None: ``f = 1`` (the lumped nodal areas, without an array of
    ones at the quadrature points)."""
    fw = cells.dx if f_q is None else f_q * cells.dx
    return sum(np.bincount(cells.t[a], weights=_weighted(fw, cells.lam[a]), minlength=cells.n) for a in range(3))


def _weighted(values: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """``values @ weights`` for a few columns, by columns: no threaded BLAS call (whose threads wait for
    each other on a busy machine) for a product this thin."""
    out = values[:, 0] * weights[0]
    for q in range(1, weights.size):
        out = out + values[:, q] * weights[q]
    return out


#: Triangles :func:`_interpolate` takes at a time (its temporaries of 2,048 x 6 points stay in cache): 0.65
#: against 0.94 ms CPU at 7,375 nodes, 1.03-1.09 against 1.67 ms at 11,903 (blocks of 1,024-8,192 alike; the
#: 16,384 of :data:`BLOCK` spill; mean of 40 calls).
INTERPOLATE_BLOCK = 2048


def _interpolate(cells: _Cells, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A P1 field's values at the quadrature points ``(n_triangles, n_points)`` and its gradient
    ``(2, n_triangles)`` (constant per triangle).

    The values ``sum_k u_k lambda_k`` by numpy's ``einsum`` (no BLAS), written block by block into the answer:
    the products summed over ``k = 0, 1, 2`` in that order, as the broadcast expression ``u_0 lambda_0 + u_1
    lambda_1 + u_2 lambda_2`` sums them, whose inner loops ran over the 6 points of a triangle only (the values
    0.21 against 0.52 ms CPU at 7,375 nodes, 0.018 against 0.040 at 529, mean of 500 calls)."""
    ut = u[cells.t]
    g, lam = cells.grad, cells.lam
    values = np.empty((ut.shape[1], lam.shape[1]))
    for b in blocks(ut.shape[1], INTERPOLATE_BLOCK):   # no temporaries of all points
        np.einsum("kt,kq->tq", ut[:, b], lam, out=values[b])
    return values, g[:, 0] * ut[0] + g[:, 1] * ut[1] + g[:, 2] * ut[2]


def _point_sum(term: Callable[[slice], np.ndarray], out: np.ndarray) -> float:
    """``np.sum`` of ``term`` over all triangles, ``term(b)`` its values at the quadrature points of the
    triangles ``b`` (a slice): written block by block (:data:`BLOCK`) into ``out`` (C order, ``(n_triangles,
    n_points)``, overwritten) and summed once, without the temporaries of all points. The sum of the whole
    product in C order: the same rounding as ``np.sum`` of it written at once (C-ordered where its first
    factor is, as the P1 values of :func:`_interpolate` and ``1/h`` are)."""
    for b in blocks(out.shape[0], BLOCK):
        out[b] = term(b)
    return float(np.sum(out))


def _recess_depth(surface, phi, z) -> np.ndarray:
    """``surface.recess_depth`` with each recess's test only on the points inside its bounding box
    (:func:`_recess_plan`): the same values at a fraction of the cost on many recesses."""
    phi, z = np.broadcast_arrays(np.asarray(phi, float), np.asarray(z, float))
    plan = _recess_plan(surface, phi)
    return surface.recess_depth(phi, z) if plan is None else _planned_depth(plan, phi, z)


def _recess_plan(surface, phi, buckets: int = 4096):
    """Per recess, the points whose ``phi`` lies in its bounding box's range: the points sorted once into
    ``buckets`` strips along ``phi`` (a linear-time sort of small integers), each recess takes the strips
    its box spans. None where the plain test is as cheap (few recesses or points)."""
    recesses = surface.recesses
    phi = np.asarray(phi, float)
    if len(recesses) < 4 or phi.size < 4096:
        return None
    fp = phi.ravel()
    lo_phi, hi_phi = float(fp.min()), float(fp.max())
    width = (hi_phi - lo_phi) / buckets or 1.0
    key = np.clip(((fp - lo_phi) / width).astype(np.int64), 0, buckets - 1).astype(np.int16)
    order = np.argsort(key, kind="stable")
    starts = np.searchsorted(key[order], np.arange(buckets + 1))
    plan = []
    for r, (lo, hi) in zip(recesses, _recess_boxes(surface)):
        k0 = min(max(math.floor((lo[0] - lo_phi) / width), 0), buckets - 1)   # Python clamps: no numpy call
        k1 = min(max(math.floor((hi[0] - lo_phi) / width), 0), buckets - 1)   # per recess
        idx = order[starts[k0]:starts[k1 + 1]]
        plan.append((r, lo, hi, idx))
    return plan


def _planned_depth(plan, phi: np.ndarray, z: np.ndarray) -> np.ndarray:
    """The recess depth at the points of a :func:`_recess_plan` (same ``phi``; any ``z``)."""
    fp, fz = np.ravel(phi), np.ravel(z)
    out = np.zeros(fp.size)
    for r, lo, hi, idx in plan:
        zi = fz[idx]
        keep = idx[(zi >= lo[1]) & (zi <= hi[1])]
        out[keep] += r.depth * r.shape.contains(fp[keep], fz[keep])
    return out.reshape(np.shape(phi))


@dataclass(frozen=True, eq=False)
class _RecessTable:
    """The recesses of a surface as arrays, found once per surface (:func:`_recess_table`): their bounding boxes
    (their boundary's, padded by 1 % of their size and 1e-12) as ``(lo, hi)`` pairs and as ``(2, n)`` arrays
    ``lo``, ``hi``, their depths [units of c], and, where every recess is a circle, the centres ``(2, n)``, the
    radii and their squares [-] (else None): one vectorised test of all recesses instead of one per recess."""

    surface: object
    boxes: list[tuple[np.ndarray, np.ndarray]]
    lo: np.ndarray
    hi: np.ndarray
    depth: np.ndarray
    centre: np.ndarray | None
    radius: np.ndarray | None
    radius2: np.ndarray | None


_TABLES: dict = {}


def _recess_table(surface) -> _RecessTable:
    """:class:`_RecessTable` of ``surface``, kept per surface object (a small table keyed by its id, holding the
    surface so the id is not reused while kept)."""
    key = id(surface)
    hit = _TABLES.get(key)
    if hit is not None and hit.surface is surface:
        return hit
    boxes = []
    for r in surface.recesses:
        b = r.shape.boundary()
        lo, hi = b.min(axis=1), b.max(axis=1)
        pad = 0.01 * (hi - lo) + 1e-12
        boxes.append((lo - pad, hi + pad))
    lo, hi = (np.array([b[k] for b in boxes]).reshape(-1, 2).T.copy() for k in (0, 1))
    circles = _all_circles(surface)
    table = _RecessTable(
        surface, boxes, lo, hi, np.array([float(r.depth) for r in surface.recesses]),
        np.array([r.shape.center for r in surface.recesses]).reshape(-1, 2).T.copy() if circles else None,
        np.array([r.shape.radius for r in surface.recesses]) if circles else None,
        np.array([r.shape.radius**2 for r in surface.recesses]) if circles else None)
    if len(_TABLES) > 64:
        _TABLES.clear()
    _TABLES[key] = table
    return table


def _recess_boxes(surface) -> list[tuple[np.ndarray, np.ndarray]]:
    """Bounding boxes of the recesses (their boundary's, padded by 1 % of their size and 1e-12), found once
    per surface (:func:`_recess_table`; :func:`_overlaps`, :func:`_recess_plan`, :func:`_line_recess`)."""
    return _recess_table(surface).boxes


# -- film with recesses --------------------------------------------------------------

def _film_at(film: Film, phi: np.ndarray, z: np.ndarray) -> np.ndarray:
    """``film.thickness`` at the points ``(phi, z)`` as a float array of their shape [units of c]: a film may
    answer a scalar or an array that broadcasts; an answer of the points' shape is taken as it is (adding
    ``0 phi`` to it, as to the others, would write a copy and change at most the sign of a zero)."""
    h = np.asarray(film.thickness(phi, z), dtype=float)
    return h if h.shape == np.shape(phi) else h + 0.0 * phi


def _thickness(mesh: SupportMesh, film: Film, phi: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Film thickness plus the depth of any recess of the surface at the points."""
    h = _film_at(film, phi, z)
    surface = mesh.surface
    if surface is not None and getattr(surface, "recesses", ()):
        h = h + _recess_depth(surface, phi, z)
    return h


#: Gauss-Legendre points and weights on [-1, 1] for the smooth film along a face.
_GAUSS = (np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 9.0)


def _renumbered(rows: list[np.ndarray], chosen: np.ndarray, n: int) -> list[np.ndarray]:
    """Each index array of ``rows`` (indices below ``n``, per recess: :func:`_overlaps`) restricted to the
    indices ``chosen`` and given as places in ``chosen`` (in the order of ``rows``)."""
    place = np.full(n, -1)
    place[chosen] = np.arange(np.size(chosen))
    return [p[p >= 0] for p in (place[r] for r in rows)]


def _in_any(rows: list[np.ndarray], n: int) -> np.ndarray:
    """Mask of the ``n`` rectangles in any of the index arrays ``rows`` (per recess, :func:`_overlaps`): near a
    recess's bounding box (with a margin of 1 % of its size, :func:`_recess_boxes`); elsewhere the recess depth
    is zero and need not be sampled."""
    near = np.zeros(n, bool)
    for r in rows:
        near[r] = True
    return near


#: Rectangles from which :func:`_overlaps` sorts them by ``x0`` (with 4 recesses or more). Measured (CPU time,
#: best of 5 x 20 calls, the 5 x 5 dimples' grid triangles and faces): the plain test 0.45 against 0.50 ms at 20,000
#: rectangles, 0.90 against 0.80 ms at 39,200, 2.99 against 1.48 ms at 80,000.
OVERLAPS_SORTED_FROM = 32768


def _overlaps(surface, x0, x1, z0, z1) -> list[np.ndarray]:
    """Per recess of ``surface`` (in order), the indices of the rectangles ``[x0, x1] x [z0, z1]`` (1-D arrays,
    increasing) that overlap its bounding box (:func:`_recess_boxes`, found once per surface).

    From :data:`OVERLAPS_SORTED_FROM` rectangles and 4 recesses on, the rectangles are sorted once by ``x0`` and
    each recess tests only those whose ``x0`` lies between its box's ends, the lower end moved back by twice the
    widest rectangle (and a margin for rounding): two binary searches per recess, the same indices as testing all
    of them, at a fraction of the cost on many recesses.
    """
    table = _recess_table(surface)
    boxes = table.boxes
    x0, x1, z0, z1 = (np.ravel(v) for v in (x0, x1, z0, z1))

    def overlapping(lo, hi, idx=None):
        if idx is None:
            return np.flatnonzero((x1 >= lo[0]) & (x0 <= hi[0]) & (z1 >= lo[1]) & (z0 <= hi[1]))
        return idx[(x1[idx] >= lo[0]) & (x0[idx] <= hi[0]) & (z1[idx] >= lo[1]) & (z0[idx] <= hi[1])]

    first, last = (float(x0.min()), float(x0.max())) if x0.size else (math.nan, math.nan)
    reach = float(np.max(x1 - x0)) if x0.size else math.nan
    if len(boxes) < 4 or x0.size < OVERLAPS_SORTED_FROM or not math.isfinite(first + last + reach):
        return [overlapping(lo, hi) for lo, hi in boxes]
    order = np.argsort(x0, kind="stable")
    xs = x0[order]
    lo0, hi0 = table.lo[0], table.hi[0]
    # x1 >= lo0 needs x0 >= lo0 - (x1 - x0) >= lo0 - 2 reach (reach: the widest x1 - x0, rounded)
    start = np.searchsorted(xs, lo0 - 2.0 * reach - 1e-15 * np.abs(lo0), "left")
    stop = np.searchsorted(xs, hi0, "right")
    return [np.sort(overlapping(lo, hi, order[a:b])) for (lo, hi), a, b in zip(boxes, start, stop)]


def _boxed_depth(surface, x0, x1, z0, z1, X: np.ndarray, Z: np.ndarray) -> np.ndarray:
    """``surface.recess_depth(X, Z)`` of points grouped in rectangles: row ``k`` of ``X``, ``Z``
    (``(n, k_points)``) lies in ``[x0_k, x1_k] x [z0_k, z1_k]``. Each recess tests only the rows whose
    rectangle overlaps its bounding box (:func:`_recess_boxes`, the box :func:`_recess_plan` also trusts),
    the recesses added in their order: the same values as the plain test, without sorting the points (cells
    and boxes of a grid, each near one recess contour, sampled many times). Circular recesses take a rectangle
    wholly inside or outside a circle from its box alone (:func:`_circle_depth`)."""
    rows = _overlaps(surface, x0, x1, z0, z1)
    return _depth_on_rows(surface, rows, X, Z, (np.ravel(x0), np.ravel(x1), np.ravel(z0), np.ravel(z1)))


def _depth_on_rows(surface, rows: list[np.ndarray], X: np.ndarray, Z: np.ndarray,
                   boxes: tuple[np.ndarray, ...] | None = None) -> np.ndarray:
    """The recess depth at the points ``X``, ``Z`` (``(n, k_points)``), each recess of ``surface`` tested on
    its own ``rows`` only (one index array per recess, in order: at least the rows with a point in its
    bounding box, :func:`_recess_boxes`; more rows give the same values), the recesses added in their order.
    Where every recess is a circle, all (row, recess) pairs are tested at once (:func:`_circle_depth`, which
    takes the rows' rectangles ``boxes`` where given)."""
    table = _recess_table(surface)
    if table.centre is not None and rows:
        sizes = [r.size for r in rows]
        return _circle_depth(table, np.concatenate(rows), np.repeat(np.arange(len(rows)), sizes), X, Z, boxes)
    out = np.zeros(np.shape(X))
    for r, idx in zip(surface.recesses, rows):
        if idx.size:
            out[idx] += r.depth * r.shape.contains(X[idx], Z[idx])
    return out


#: Points :func:`_circle_depth` tests at a time (its temporaries stay in cache; read at each call).
CIRCLE_POINTS = 4096
#: Relative margin on ``r^2`` by which :func:`_circle_depth` takes a rectangle as inside or outside a circle
#: without testing its points (far above the rounding of a point's test and of its place in the rectangle).
CIRCLE_MARGIN = 1e-9


def _circle_depth(table: _RecessTable, idx: np.ndarray, which: np.ndarray, X: np.ndarray, Z: np.ndarray,
                  boxes: tuple[np.ndarray, ...] | None = None) -> np.ndarray:
    """:func:`_depth_on_rows` of circular recesses (``table.centre`` set) from the pairs ``(idx[k], which[k])``
    of a row of ``X``, ``Z`` and a recess: each pair's points tested as
    :meth:`~bearingfe.geometry.surface.Circle.contains` does (the same arithmetic), in blocks of about
    :data:`CIRCLE_POINTS` points, the terms ``depth * inside`` added onto 0 in the pairs' order (a row in several
    recesses' lists by ``np.add.at``): the same values bit for bit as the loop over recesses.

    ``boxes``: ``(x0, x1, z0, z1)``, row ``k``'s points lie in ``[x0_k, x1_k] x [z0_k, z1_k]``. A pair whose
    rectangle lies inside its circle (its farthest corner within ``1 - CIRCLE_MARGIN`` of ``r^2``) gives its row
    the depth at every point, one outside it (its nearest point beyond ``1 + CIRCLE_MARGIN``) nothing, untested:
    the margin is far above the rounding of the points' test, so the same values (recesses do not overlap: a row
    inside one circle has no point in another)."""
    out = np.zeros(np.shape(X))
    if idx.size == 0:
        return out
    inside = None
    if boxes is not None:
        x0, x1, z0, z1 = (v[idx] for v in boxes)
        cx, cz, r2 = table.centre[0][which], table.centre[1][which], table.radius2[which]
        x0 -= cx
        x1 -= cx
        z0 -= cz
        z1 -= cz
        far = np.maximum(x0 * x0, x1 * x1) + np.maximum(z0 * z0, z1 * z1)
        dx, dz = np.maximum(np.maximum(x0, -x1), 0.0), np.maximum(np.maximum(z0, -z1), 0.0)
        inside = far < r2 * (1.0 - CIRCLE_MARGIN)
        cut = ~inside & (dx * dx + dz * dz <= r2 * (1.0 + CIRCLE_MARGIN))
        inside = np.flatnonzero(inside)
        idx_all, which_all = idx, which
        idx, which = idx[cut], which[cut]
    once = np.zeros(out.shape[0], bool)
    once[idx] = True
    once = np.count_nonzero(once) == idx.size   # each row in one recess's list: its term alone
    col = (slice(None),) + (None,) * (out.ndim - 1)
    for b in blocks(idx.size, max(1, CIRCLE_POINTS // max(1, out[0].size))):
        i, w = idx[b], which[b]
        x, z = X[i], Z[i]
        x -= table.centre[0][w][col]
        x *= x
        z -= table.centre[1][w][col]
        z *= z
        x += z
        terms = table.depth[w][col] * (x < table.radius2[w][col])
        if once:
            out[i] = terms
        else:
            np.add.at(out, i, terms)
    if inside is not None and inside.size:   # after the tested pairs: their zeros in such a row are no term
        out[idx_all[inside]] = table.depth[which_all[inside]][col]
    return out


def _rows_depth(surface, X: np.ndarray, Z: np.ndarray) -> np.ndarray:
    """:func:`_boxed_depth` of points grouped in rows (``(n, k)``: a triangle's quadrature points, a line's
    samples), each row's rectangle its points' bounding box (column by column: numpy's reduction along a
    short last axis is many times slower)."""
    X, Z = np.asarray(X), np.asarray(Z)
    x0, x1, z0, z1 = X[:, 0].copy(), X[:, 0].copy(), Z[:, 0].copy(), Z[:, 0].copy()
    for k in range(1, X.shape[1]):
        np.minimum(x0, X[:, k], out=x0)
        np.maximum(x1, X[:, k], out=x1)
        np.minimum(z0, Z[:, k], out=z0)
        np.maximum(z1, Z[:, k], out=z1)
    return _boxed_depth(surface, x0, x1, z0, z1, X, Z)


def _line_recess(surface, x: np.ndarray, lo: np.ndarray, hi: np.ndarray, pieces: int = 8,
                 bisections: int = 30, sections: int = 32) -> np.ndarray:
    """``int depth dz`` of the recesses along the segments ``phi = x, lo < z < hi``, exact: each
    crossing of a recess contour located to ``2**-bisections`` of a sub-interval (1e-9 for 30) in
    ``pieces`` sub-intervals per segment (at most one crossing per sub-interval: recesses wider than
    an eighth of a cell). A circle's contour is crossed where its chord on the line ends (closed form);
    other contours' crossings are searched together, recess by recess (only the crossed recess's own
    test), each round testing ``sections - 1`` points of every bracket at once and keeping the part where
    the test changes: ``log2(sections)`` halvings per round. Where every recess is a circle, each line
    takes its chords' overlap with ``[lo, hi]`` directly (no samples, no condition on the recess width)."""
    if _all_circles(surface):
        return _line_circles(surface, x, lo, hi)
    z = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, pieces + 1)
    d = _rows_depth(surface, x[:, None] + 0.0 * z, z)
    a, b, da, db = z[:, :-1], z[:, 1:], d[:, :-1], d[:, 1:]
    piece = np.where(da == db, da * (b - a), 0.0)
    seg, k = np.nonzero(da != db)
    if seg.size:
        aa, bb, dA, xs = a[seg, k].copy(), b[seg, k].copy(), da[seg, k], x[seg]
        groups, owned = [], np.zeros(seg.size, bool)
        exact = np.zeros(seg.size, bool)   # crossings of a circle's contour: found in closed form
        found = np.empty(seg.size)
        for r, (blo, bhi) in zip(surface.recesses, _recess_boxes(surface)):
            cand = np.flatnonzero(~owned & (xs >= blo[0]) & (xs <= bhi[0]) & (bb >= blo[1]) & (aa <= bhi[1]))
            if cand.size:
                inside = r.shape.contains(xs[cand], aa[cand])
                crossed = inside != r.shape.contains(xs[cand], bb[cand])
                cand, inside = cand[crossed], inside[crossed]
                if cand.size:
                    owned[cand] = True
                    if isinstance(r.shape, Circle):
                        exact[cand] = True
                        found[cand] = np.clip(_circle_crossing(r.shape, xs[cand], inside), aa[cand], bb[cand])
                    else:
                        groups.append((cand, lambda px, pz, r=r, inside=inside:
                                       r.shape.contains(px, pz) == inside[:, None]))
        rest = np.flatnonzero(~owned)   # not one recess's crossing (none should be left): the surface's depth
        if rest.size:
            groups.append((rest, lambda px, pz, dA=dA[rest]: surface.recess_depth(px, pz) == dA[:, None]))
        if groups:
            todo = np.flatnonzero(~exact)
            found[todo] = _bisect_crossings(groups, todo, xs, aa, bb, bisections, sections)
        piece[seg, k] = dA * (found - a[seg, k]) + db[seg, k] * (b[seg, k] - found)
    return piece.sum(axis=1)


def _all_circles(surface) -> bool:
    """Whether every recess of ``surface`` is a circle (line integrals in closed form, :func:`_line_circles`)."""
    return all(isinstance(r.shape, Circle) for r in surface.recesses)


def _line_circles(surface, x: np.ndarray, lo: np.ndarray, hi: np.ndarray,
                  rows: list[np.ndarray] | None = None) -> np.ndarray:
    """:func:`_line_recess` where every recess is a circle (recesses do not overlap): the depth times the
    part of each chord ``|z - cz| < sqrt(r^2 - (x - cx)^2)`` in ``[lo, hi]``, the lines near each circle's
    box only: ``rows`` per recess (:func:`_overlaps` of the lines by default; more lines give the same values,
    a line off a circle having no chord in it). All pairs of a line and a circle at once, each line's terms
    summed in the circles' order (``bincount`` adds its weights in their order)."""
    rows = _overlaps(surface, x, x, lo, hi) if rows is None else rows
    if not rows or sum(r.size for r in rows) == 0:
        return np.zeros(np.shape(x))
    idx = np.concatenate(rows)
    which = np.repeat(np.arange(len(rows)), [r.size for r in rows])
    return _line_circle_pairs(surface, x, lo, hi, idx, which)


def _line_circle_pairs(surface, x: np.ndarray, lo: np.ndarray, hi: np.ndarray, idx: np.ndarray,
                       which: np.ndarray) -> np.ndarray:
    """:func:`_line_circles` of the pairs ``(idx[k], which[k])`` of a line and a circle (recess ``which[k]``),
    the pairs of the circles in their order (each line's terms summed in that order)."""
    out = np.zeros(np.shape(x))
    if idx.size == 0:
        return out
    table = _recess_table(surface)
    cx, cz, radius, depth = table.centre[0][which], table.centre[1][which], table.radius[which], table.depth[which]
    half = np.sqrt(np.maximum(radius * radius - (x[idx] - cx) ** 2, 0.0))
    chord = np.minimum(hi[idx], cz + half) - np.maximum(lo[idx], cz - half)
    return out + np.bincount(idx, weights=depth * np.maximum(chord, 0.0), minlength=out.size).reshape(out.shape)


def _circle_crossing(circle: Circle, x: np.ndarray, inside: np.ndarray) -> np.ndarray:
    """Where the lines ``phi = x`` cross the contour of ``circle`` upwards in ``z``: leaving it (its upper
    chord end) where ``inside`` (the bracket's lower end lies in it), else entering it (the lower end)."""
    (cx, cz), r = circle.center, circle.radius
    half = np.sqrt(np.maximum(r * r - (x - cx) ** 2, 0.0))
    return np.where(inside, cz + half, cz - half)


def _bisect_crossings(groups, todo: np.ndarray, xs: np.ndarray, aa: np.ndarray, bb: np.ndarray,
                      bisections: int, sections: int) -> np.ndarray:
    """The crossings of the brackets ``todo`` (indices into ``xs``, ``aa``, ``bb``), each to ``2**-bisections``
    of its bracket: rounds of ``sections - 1`` points per bracket, each group ``(indices, same_side)`` testing
    its own brackets; returns the midpoints of the last brackets."""
    where = np.full(xs.size, -1, np.int64)
    where[todo] = np.arange(todo.size)
    groups = [(where[idx], test) for idx, test in groups]
    aa, bb, px = aa[todo].copy(), bb[todo].copy(), xs[todo][:, None]
    halvings = max(1, int(round(math.log2(sections))))
    fractions = np.arange(1, sections) / sections
    rows = np.arange(todo.size)
    for _ in range(-(-bisections // halvings)):
        c = aa[:, None] + (bb - aa)[:, None] * fractions
        left = np.empty(c.shape, bool)
        for idx, same_side in groups:
            left[idx] = same_side(px[idx], c[idx])
        first = np.where(left.all(axis=1), sections - 1, np.argmin(left, axis=1))   # first point past it
        aa, bb = (np.where(first > 0, c[rows, np.maximum(first - 1, 0)], aa),
                  np.where(first < sections - 1, c[rows, np.minimum(first, sections - 2)], bb))
    return 0.5 * (aa + bb)


def _face_film(mesh: SupportMesh, film: Film, x0: np.ndarray, x1: np.ndarray, lo: np.ndarray, hi: np.ndarray,
               lines: int = 8) -> np.ndarray:
    """Mean over ``x0 < phi < x1`` of ``int h dz`` on ``lo < z < hi``: the film of a box face, averaged
    over the two cells it joins, so that a step between two nodes acts on both in proportion to its
    position (as the P1 Galerkin wedge term does) instead of on the nearer face only.

    The film by 3 x 3 Gauss points (interior: a step of the film on a node line is integrated
    exactly); the recess depth by the midpoint rule on ``lines`` lines in ``phi``, each line
    integral exact in ``z`` (:func:`_line_recess`), where the outer lines and the middle line
    disagree (a recess contour crosses the rectangle), else by the middle line."""
    mean = _face_smooth(film, x0, x1, lo, hi)
    surface = mesh.surface
    if surface is None or not surface.recesses:
        return mean
    return mean + _face_recess(surface, x0, x1, lo, hi, lines)


def _face_smooth(film: Film, x0: np.ndarray, x1: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """The film part of :func:`_face_film`: 3 x 3 Gauss points per rectangle, one call of the film per block
    of :data:`BLOCK` rectangles (1-D arrays; others in one call)."""
    if np.ndim(x0) != 1:
        return _face_smooth_block(film, x0, x1, lo, hi)
    mean = np.empty(np.shape(x0))
    for b in blocks(mean.size, BLOCK):
        mean[b] = _face_smooth_block(film, x0[b], x1[b], lo[b], hi[b])
    return mean


def _face_smooth_block(film: Film, x0: np.ndarray, x1: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """:func:`_face_smooth` of some rectangles, the film called once at their 9 points each."""
    g, w = _GAUSS
    gx, gz = np.repeat(g, 3)[:, None], np.tile(g, 3)[:, None]
    x = 0.5 * (x0 + x1) + 0.5 * gx * (x1 - x0)
    z = 0.5 * (lo + hi) + 0.5 * gz * (hi - lo)
    terms = (0.25 * np.outer(w, w).ravel()[:, None] * (hi - lo)) * _film_at(film, x, z)
    mean = np.zeros_like(x0)
    for term in terms:   # summed in the order of the points
        mean += term
    return mean


def _face_recess(surface, x0: np.ndarray, x1: np.ndarray, lo: np.ndarray, hi: np.ndarray,
                 lines: int = 8, over: list[np.ndarray] | None = None) -> np.ndarray:
    """The recess part of :func:`_face_film` (film-independent): the mean over ``x0 < phi < x1`` of
    ``int depth dz`` on ``lo < z < hi``, by the midpoint rule on ``lines`` lines where the outer and the
    middle lines disagree, else by the middle line. The rectangles near each recess are found once
    (:func:`_overlaps`, or ``over`` where the caller has them); where every recess is a circle, a rectangle's
    lines are taken near the recesses it is near (the lines lie in it)."""
    out = np.zeros_like(x0)
    over = _overlaps(surface, x0, x1, lo, hi) if over is None else over
    near = np.flatnonzero(_in_any(over, np.size(x0)))
    x0, x1, lo, hi = x0[near], x1[near], lo[near], hi[near]
    circles = _all_circles(surface)

    def lines_at(ks, idx):   # line integrals on the lines ks of the rectangles idx, shape (len(ks), len(idx))
        x = np.concatenate([x0[idx] + (k + 0.5) / lines * (x1[idx] - x0[idx]) for k in ks])
        a, b = np.tile(lo[idx], len(ks)), np.tile(hi[idx], len(ks))
        if not circles:
            return _line_recess(surface, x, a, b).reshape(len(ks), -1)
        places = _renumbered(over, near[idx], out.size)   # a rectangle's lines at its place + j len(idx)
        return _line_circle_pairs(surface, x, a, b, *_line_pairs(places, len(ks), idx.size)).reshape(len(ks), -1)

    outer = (0, lines // 2, lines - 1)
    first, middle, last = lines_at(outer, np.arange(near.size))
    cut = np.flatnonzero((first != middle) | (middle != last))
    depth = middle
    if cut.size:   # the lines not sampled yet, with the three that were
        others = [k for k in range(lines) if k not in outer]
        depth[cut] = (lines_at(others, cut).sum(axis=0) + first[cut] + middle[cut] + last[cut]) / lines
    out[near] = depth
    return out


def _line_pairs(places: list[np.ndarray], lines: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The pairs ``(line, recess)`` of :func:`_face_recess`'s ``lines`` lines of ``n`` rectangles, a rectangle's
    line ``j`` numbered ``place + j n``, from each recess's rectangles ``places`` (:func:`_renumbered`): recess by
    recess, in each line by line, the places in their order (the order of concatenating, per recess, its places
    shifted to each line), built at once for all recesses."""
    sizes = np.fromiter((p.size for p in places), np.int64, len(places))
    which = np.repeat(np.arange(len(places)), lines * sizes)
    if not places or sizes.sum() == 0:
        return np.zeros(0, np.int64), which
    flat = np.concatenate(places)
    recess = np.repeat(np.arange(len(places)), sizes)
    start = np.cumsum(sizes) - sizes
    line = np.arange(lines, dtype=np.int64)[:, None]
    # the pair of place e of recess k on line j goes to lines * start_k + j * size_k + e
    pos = (np.arange(flat.size) + (lines - 1) * start[recess])[None, :] + line * sizes[recess][None, :]
    idx = np.empty(lines * flat.size, np.int64)
    idx[pos] = flat[None, :] + n * line
    return idx, which


def _grid_face_film(mesh: SupportMesh, film: Film, g: _GridFaces) -> np.ndarray:
    """:func:`_face_film` of the box faces ``g`` of ``mesh``, the recess part found once per mesh."""
    surface = mesh.surface
    if surface is None or not surface.recesses:
        return _face_film(mesh, film, g.x0, g.x1, g.lo, g.hi)
    depth = mesh.cached("finite_volume.face_recess",
                        lambda: _face_recess(surface, g.x0, g.x1, g.lo, g.hi, over=_face_overlaps(mesh, g)))
    return _face_smooth(film, g.x0, g.x1, g.lo, g.hi) + depth


def _face_overlaps(mesh: SupportMesh, g: _GridFaces) -> list[np.ndarray] | None:
    """:func:`_overlaps` of the box faces ``g`` of a whole grid (:func:`~bearingfe.geometry.meshing.tensor_lines`)
    from its lines (:func:`_tensor_overlaps`): there every face is kept, face ``iz + nz ix`` spanning
    ``[phi_ix, phi_ix+1] x [lo_iz, hi_iz]``; None on any other mesh."""
    lines = tensor_lines(mesh)
    if lines is None:
        return None
    xs, nz = lines[0], lines[1].size
    return _tensor_overlaps(mesh.surface, (xs[:-1], xs[1:]), (g.lo[:nz], g.hi[:nz]))


def _vertex_depth(mesh: SupportMesh) -> np.ndarray | None:
    """The recess depth at the mesh's vertices (:func:`_recess_depth`, found once per mesh; read-only; on a whole
    grid each recess tests the nodes in its box, found from the grid lines: the same values); None without
    recesses."""
    surface = mesh.surface
    if surface is None or not getattr(surface, "recesses", ()):
        return None

    def build() -> np.ndarray:
        p, lines = mesh.mesh.p, tensor_lines(mesh)
        if lines is None:
            depth = _recess_depth(surface, p[0], p[1])
        else:   # node iz + nz ix at (phi_ix, z_iz): each recess tests the nodes in its box (_tensor_overlaps)
            xs, zs = lines
            rows = _tensor_overlaps(surface, (xs, xs), (zs, zs))
            depth = _depth_on_rows(surface, rows, p[0][:, None], p[1][:, None])[:, 0]
        depth.flags.writeable = False
        return depth

    return mesh.cached("finite_volume.vertex_depth", build)


def _dof_thickness(mesh: SupportMesh, film: Film, doflocs: np.ndarray) -> np.ndarray:
    """:func:`_thickness` at the dofs ``doflocs``, the recess depth kept per mesh where they are its vertices
    (P1 on a straight mesh): the same values."""
    depth = _vertex_depth(mesh)
    if depth is None or doflocs.shape != mesh.mesh.p.shape or not np.array_equal(doflocs, mesh.mesh.p):
        return _thickness(mesh, film, *doflocs)
    return _film_at(film, doflocs[0], doflocs[1]) + depth


def _quadrature_depth(mesh: SupportMesh, x: np.ndarray) -> np.ndarray | None:
    """The recess depth at the quadrature points ``x`` of ``mesh`` (found once per mesh); None without recesses.
    On straight triangles each recess tests the triangles near it (:func:`_triangle_recesses`, shared with the
    cut cells); else the points' own bounding boxes (:func:`_rows_depth`): the same values."""
    surface = mesh.surface
    if surface is None or not getattr(surface, "recesses", ()):
        return None

    def build() -> np.ndarray:
        rows = _triangle_recesses(mesh) if x.shape[1] == mesh.mesh.t.shape[1] else None
        if rows is None:
            return _rows_depth(surface, x[0], x[1])
        return _depth_on_rows(surface, rows, x[0], x[1], _triangle_boxes(mesh))

    # (n_triangles, n_points), per quadrature rule
    return mesh.cached(("finite_volume.quadrature_depth", x.shape[1:]), build)


def _triangle_recesses(mesh: SupportMesh) -> list[np.ndarray] | None:
    """Per recess of ``mesh.surface`` (in order), the triangles whose corners' bounding box overlaps its box
    (:func:`_overlaps`, increasing indices), found once per mesh; None unless the triangles are straight
    (``MeshTri1``: every point of a triangle, its quadrature points and sub-cell centroids, lies in its
    corners' box up to round-off, outside any recess box the recess test trusts)."""
    if type(mesh.mesh) is not MeshTri1:
        return None

    def build() -> list[np.ndarray]:
        lines = tensor_lines(mesh)
        if lines is not None:   # both triangles of each cell: the cell's box
            xs, zs = lines
            return _tensor_overlaps(mesh.surface, (xs[:-1], xs[1:]), (zs[:-1], zs[1:]), copies=2)
        t = mesh.mesh.t[:3]
        px, pz = mesh.mesh.p[0, t], mesh.mesh.p[1, t]
        return _overlaps(mesh.surface, px.min(axis=0), px.max(axis=0), pz.min(axis=0), pz.max(axis=0))

    return mesh.cached("finite_volume.triangle_recesses", build)


def _triangle_boxes(mesh: SupportMesh) -> tuple[np.ndarray, ...] | None:
    """``(x0, x1, z0, z1)`` per triangle of a whole tensor grid (:func:`~bearingfe.geometry.meshing.tensor_lines`):
    its cell's box, which its corners span (triangles ``c`` and ``c + n_cells`` of cell ``c = iz + nz ix``, ``nz``
    cells a column); None on any other mesh."""
    lines = tensor_lines(mesh)
    if lines is None:
        return None
    xs, zs = lines
    nx, nz = xs.size - 1, zs.size - 1
    return (np.tile(np.repeat(xs[:-1], nz), 2), np.tile(np.repeat(xs[1:], nz), 2),
            np.tile(zs[:-1], 2 * nx), np.tile(zs[1:], 2 * nx))


def _tensor_overlaps(surface, x: tuple[np.ndarray, np.ndarray], z: tuple[np.ndarray, np.ndarray],
                     copies: int = 1) -> list[np.ndarray]:
    """:func:`_overlaps` of the rectangles of a tensor product, ``[x_lo[i], x_hi[i]] x [z_lo[j], z_hi[j]]`` numbered
    ``j + nz i`` (``x = (x_lo, x_hi)``, ``z`` alike, each array increasing), and of ``copies - 1`` more copies of
    them numbered on (``+ nx nz`` each: a grid's two triangles per cell, :func:`~bearingfe.geometry.meshing.
    tensor_lines`): each recess's box (:func:`_recess_boxes`) takes the rectangles whose column and row ranges meet
    its own, found by two binary searches per axis for all boxes at once, and their cells numbered for all boxes
    at once (no loop over the recesses). The same increasing indices, without a test per rectangle."""
    (x_lo, x_hi), (z_lo, z_hi) = x, z
    nx, nz = x_lo.size, z_lo.size
    table = _recess_table(surface)
    if not table.boxes:
        return []
    lo, hi = table.lo, table.hi
    # column i meets [lo, hi] where x_hi[i] >= lo and x_lo[i] <= hi (rows alike)
    i0, i1 = np.searchsorted(x_hi, lo[0], "left"), np.searchsorted(x_lo, hi[0], "right") - 1
    j0, j1 = np.searchsorted(z_hi, lo[1], "left"), np.searchsorted(z_lo, hi[1], "right") - 1
    # box k spans columns i0..i1 and rows j0..j1: its cell r (w = j1 - j0 + 1 rows a column) is
    # nz (i0 + r // w) + j0 + r % w, column by column as the rows increase
    w = np.maximum(j1 - j0 + 1, 0)
    count = np.maximum(i1 - i0 + 1, 0) * w
    start = np.cumsum(count) - count
    total = int(start[-1] + count[-1])
    r = np.arange(total, dtype=np.int64)
    r -= np.repeat(start, count)
    cells, row = np.divmod(r, np.repeat(w, count))   # (column - i0, row - j0) of each box's cell r
    cells *= nz
    cells += row
    cells += np.repeat(nz * i0 + j0, count)
    if copies > 1:   # each box's cells, then their copies
        cells = cells[None, :] + nx * nz * np.arange(copies, dtype=np.int64)[:, None]
        return [cells[:, a:a + k].ravel() for a, k in zip(start.tolist(), count.tolist())]
    return [cells[a:a + k] for a, k in zip(start.tolist(), count.tolist())]


def _film_q(mesh: SupportMesh, film: Film, x: np.ndarray) -> np.ndarray:
    """:func:`_thickness` at the quadrature points ``x`` of ``mesh`` ``(n_triangles, n_points)``, the recess
    depth found once per mesh; the film called once per :data:`BLOCK` triangles."""
    depth = _quadrature_depth(mesh, x)
    h = np.empty(x.shape[1:])
    for b in blocks(h.shape[0], BLOCK):
        h[b] = _film_at(film, x[0, b], x[1, b])
        if depth is not None:
            h[b] += depth[b]
    return h


def _film_integrals(cells: _Cells, h_q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``1/h`` at the quadrature points and ``int_T h^3/12`` per triangle (the stiffness's weights,
    :func:`_integrals` of ``h^3/12``), by blocks of :data:`BLOCK` triangles: ``h^3`` at every point is never
    held."""
    inv_q = np.empty(h_q.shape)
    w = np.empty(h_q.shape[0])
    for b in blocks(h_q.shape[0], BLOCK):
        np.divide(1.0, h_q[b], out=inv_q[b])
        w[b] = _integrals_of(h_q[b] ** 3 / 12.0, cells.dx[b])
    return inv_q, w


def _cell_means(mesh: SupportMesh, film: Film, x: np.ndarray, subdivisions: int = 8):
    """The triangles a recess contour cuts (a grid mesh with recesses) and the means of ``h``, ``1/h`` and
    ``h^3`` over their ``subdivisions**2`` sub-triangle centroids (the P1 stiffness needs only ``int_T h^3``,
    which plain quadrature gets wrong across a step); None elsewhere (:func:`_with_cell_means`)."""
    surface = mesh.surface
    if mesh.source != "grid" or surface is None or not surface.recesses:
        return None
    cut, pts, depth = _cut_cells(mesh, x, subdivisions)
    if cut.size == 0:
        return None
    hh = _film_at(film, pts[0], pts[1]) + depth   # as _thickness
    return cut, hh.mean(axis=1), (1.0 / hh).mean(axis=1), (hh**3).mean(axis=1)


def _with_cell_means(cells: _Cells, means, h_q: np.ndarray, inv_q: np.ndarray, w: np.ndarray) -> None:
    """Puts the cut triangles' means (:func:`_cell_means`) into ``h`` and ``1/h`` at their quadrature points
    and their ``int_T h^3/12`` into ``w``, in place."""
    cut, h, inv, h3 = means
    h_q[cut] = h[:, None]
    inv_q[cut] = inv[:, None]
    w[cut] = _integrals_of(np.repeat(h3[:, None], h_q.shape[1], axis=1) / 12.0, cells.dx[cut])


def _cut_cells(mesh: SupportMesh, x: np.ndarray, subdivisions: int):
    """The triangles of a grid mesh a recess contour cuts, the centroids of their ``subdivisions**2``
    sub-triangles ``(2, n_cut, n_sub)`` and the recess depth there (film-independent: found once per mesh)."""
    return mesh.cached(("finite_volume.cut_cells", subdivisions), lambda: _build_cut_cells(mesh, x, subdivisions))


def _build_cut_cells(mesh: SupportMesh, x: np.ndarray, subdivisions: int):
    """:func:`_cut_cells` built afresh: each recess tests the triangles near it (:func:`_triangle_recesses`,
    the quadrature depth's own lists)."""
    surface = mesh.surface
    m = mesh.mesh
    t = m.t[:3]
    over = _triangle_recesses(mesh)
    if over is None:
        px, pz = m.p[0, t], m.p[1, t]
        over = _overlaps(surface, px.min(axis=0), px.max(axis=0), pz.min(axis=0), pz.max(axis=0))
    near = np.flatnonzero(_in_any(over, t.shape[1]))
    dep_q = _quadrature_depth(mesh, x)[near]
    dep_v = _vertex_depth(mesh)[t[:, near]]   # the depth is pointwise: as tested per triangle
    # not all equal, by rows (numpy's reduction along the short first axis of this gathered, not C-ordered
    # array, np.ptp, took 0.25 against 0.01 ms at 3,528 triangles)
    varies = (dep_v[1] != dep_v[0]) | (dep_v[2] != dep_v[0]) | (dep_v[0] != dep_q[:, 0])
    for k in range(1, dep_q.shape[1]):   # a depth that varies over the points (numpy's ptp along a short last
        varies |= dep_q[:, k] != dep_q[:, 0]   # axis is many times slower)
    cut = near[varies]
    lam = _subcentroids(subdivisions)                                    # (n^2, 3)
    corners = m.p[:, t[:, cut]]                                          # (2, 3, n_cut)
    pts = np.einsum("sk,dkc->dcs", lam, corners)                         # (2, n_cut, n^2)
    rows = _renumbered(over, cut, t.shape[1])   # each recess tests the cut cells near it
    return cut, pts, _depth_on_rows(surface, rows, pts[0], pts[1])


@functools.cache
def _subcentroids(n: int) -> np.ndarray:
    """The barycentric coordinates ``(n^2, 3)`` of the centroids of a triangle's ``n^2`` sub-triangles (``n``
    subdivisions of each side; upright ones, then inverted ones), made once per ``n`` (read-only)."""
    lam = [((i + 1 / 3) / n, (j + 1 / 3) / n) for i in range(n) for j in range(n - i)]
    lam += [((i + 2 / 3) / n, (j + 2 / 3) / n) for i in range(n - 1) for j in range(n - 1 - i)]
    lam = np.array([(1 - a - b, a, b) for a, b in lam])
    lam.flags.writeable = False
    return lam


def _rate(film: Film, phi: np.ndarray, z: np.ndarray, squeeze) -> np.ndarray:
    """``dh/dt`` at the points for the squeeze rates ``squeeze`` (zeros without one: allocated, never written)."""
    if squeeze[0] == 0.0 and squeeze[1] == 0.0:
        return np.zeros(np.shape(phi))
    shapes = film.rate_shapes(phi, z)
    return squeeze[0] * np.asarray(shapes[0], float) + squeeze[1] * np.asarray(shapes[1], float)


@dataclass(frozen=True, eq=False)
class FVSystem:
    """Discrete JFO operators of one film state and operating point (all dofs)."""

    K: sp.csr_matrix       # Poiseuille: int h^3/12 grad p . grad v
    C: sp.csr_matrix       # upwind Couette outflow of theta per dual cell
    storage: np.ndarray    # diagonal coefficient of theta in the time/squeeze term
    source: np.ndarray     # theta-independent part of the time term (-theta_old H_old/dt)
    area: np.ndarray       # lumped nodal areas int phi_i
    h_q: np.ndarray        # h at the quadrature points (cell means on cut triangles of a grid)
    hdot_q: np.ndarray     # dh/dt at the quadrature points
    inv_h_q: np.ndarray    # 1/h at the quadrature points (for the shear)
    faces: _GridFaces | None = None       # grid flux: the box faces ...
    face_film: np.ndarray | None = None   # ... and their mean film (int h dz / face length)
    reconstruction: "_Reconstruction | _Streamline | None" = None   # couette="limited" / "streamline"
    couette: str = "median"                         # the Couette flux (COUETTE_FLUXES, "auto" resolved)
    C_cavity: sp.csr_matrix | None = None   # outflow of cavitated nodes' theta where it differs from C's


def _assemble(ops: Operators, mesh: SupportMesh, film: Film, wedge: float, squeeze, dt, previous,
              couette: str = "median", rough: bool = False) -> FVSystem:
    """The operators of the scheme; ``rough``: ``h^3`` at the quadrature points also on the cells a recess
    contour cuts (a nested start's coarse level: no sub-cell means, :data:`NESTED_CELL_MEANS`)."""
    basis = ops.basis
    x = ops.x
    h_q = _film_q(mesh, film, x)
    if not h_q.min() > 0:
        raise ValueError(f"film thickness reaches {h_q.min():.4g} <= 0 on the surface (film {film!r})")
    hdot_q = _rate(film, x[0], x[1], squeeze)
    cells = _cells(mesh, ops)
    inv_h_q, w = _film_integrals(cells, h_q)
    means = None if rough else _cell_means(mesh, film, x)
    if means is not None:
        _with_cell_means(cells, means, h_q, inv_h_q, w)
    K = _stiffness_of(cells, w, _stiffness_pattern(mesh, flux=couette == "streamline"))
    pattern = _p1_pattern(mesh) if couette == "streamline" else None   # the flux's: scikit-fem's edges only
    rec = None
    if couette == "grid":   # box cells: flux wedge/2 theta int h dz through the faces normal to phi
        g = _grid_faces(mesh)
        fi, fj = g.i, g.j
        face_film = _grid_face_film(mesh, film, g)
        f = 0.5 * wedge * face_film
    else:                   # median dual: one segment per (triangle, edge)
        d = _dual(mesh)
        fi, fj = d.i, d.j
        u = velocity_at(mesh.runner, d.midpoint)
        normal_speed = d.normal[0] if u is None else u[0] * d.normal[0] + u[1] * d.normal[1]
        f = 0.5 * wedge * _thickness(mesh, film, d.midpoint[0], d.midpoint[1]) * normal_speed
        rec = _reconstruction(mesh, d, f) if couette == "limited" else None
    up = np.where(f > 0, fi, fj)
    n = basis.N
    C_cavity = None
    if couette == "streamline":
        sign = math.copysign(1.0, wedge)
        nodes, w = (_aligned_weights(mesh, d, sign, cells.grad) if u is None
                    else _streamline_weights(mesh, d, (sign * u[0], sign * u[1]), cells.grad))
        scale, up_scale = _contour_scales(mesh, film, d, f)
        rec = _Streamline(d=d, flux=f, nodes=nodes, weights=w, up=up, scale=scale, up_scale=up_scale, pattern=pattern)
        C, C_cavity = rec.matrices(n, np.zeros(f.size, bool))
    else:
        C = sorted_entries(np.concatenate([fi, fj]), np.concatenate([up, up]), np.concatenate([f, -f]), n)
    area = _load(cells, None)
    no_squeeze = squeeze[0] == 0.0 and squeeze[1] == 0.0   # as _rate: dh/dt = 0, its load 0
    storage = np.zeros(n) if no_squeeze else _load(cells, hdot_q)
    source = np.zeros(n)
    if dt is not None:
        H = _load(cells, h_q)
        px = previous.film
        H_old = _load(cells, _film_q(mesh, px, x))
        storage = storage + H / dt
        source = -previous.theta * H_old / dt
    grid = dict(faces=g, face_film=face_film / (g.hi - g.lo)) if couette == "grid" else {}
    return FVSystem(K=K, C=C, storage=storage, source=source, area=area, h_q=h_q, hdot_q=hdot_q, inv_h_q=inv_h_q,
                   reconstruction=rec, couette=couette, C_cavity=C_cavity, **grid)


# -- the complementarity solve ----------------------------------------------------------

@dataclass(frozen=True)
class _Solution:
    p: np.ndarray
    theta: np.ndarray
    cavity: np.ndarray
    iterations: int
    residual: float
    factorizations: int = 0       # new factorizations of the active-set matrices
    solve: Callable[[np.ndarray], np.ndarray] | None = dataclasses.field(default=None, compare=False, repr=False)
    # the last factorization's solve (of the set it factorized: a nested start's coarse correction)


@dataclass(frozen=True, eq=False)
class FVUnknowns:
    """Map from the unknowns (interior dofs, seam pairs of a periodic mesh merged) to all dofs."""

    S: sp.csr_matrix        # (n_dofs, m): full = S @ reduced (zero rows on fixed dofs)
    rep: np.ndarray         # (m,) a dof of each unknown
    fixed: np.ndarray       # dofs with given pressure and theta = 1
    coordinates: np.ndarray | None = None   # (2, m) positions of the unknowns (for a fill-reducing order)
    on_grid: bool = False   # the unknowns lie on the lines of a grid_mesh without a seam (grid_dissection)
    _order: dict = dataclasses.field(default_factory=dict, repr=False)   # the order, found once


def _unknowns(mesh: SupportMesh, ops: Operators) -> FVUnknowns:
    """The unknowns of ``mesh`` (cached on it, with the fill-reducing order found for them)."""
    return mesh.cached(("finite_volume.unknowns", ops.n_dofs), lambda: _build_unknowns(mesh, ops))


def _build_unknowns(mesh: SupportMesh, ops: Operators) -> FVUnknowns:
    n, I = ops.n_dofs, ops.interior   # I sorted, without repeats
    start, end = periodic_pairs(mesh)
    if start.size:
        rep_of = np.arange(n)
        rep_of[end] = start
        reps = np.unique(rep_of[I])
        cols = np.searchsorted(reps, rep_of[I])
        S = sp.csr_matrix((np.ones(I.size), (I, cols)), shape=(n, reps.size))
    else:   # each interior dof its own unknown: S selects them (row I[k] has a 1 in column k)
        reps, S = I, _selection(I, n)
    fixed = np.ones(n, bool)
    fixed[I] = False
    unk = FVUnknowns(S=S, rep=reps, fixed=np.flatnonzero(fixed), coordinates=np.asarray(ops.basis.doflocs)[:, reps],
                     on_grid=mesh.source == "grid" and not start.size)
    if not start.size:
        unk._order["selects"] = True   # (_selects: S was built as the selection of the dofs rep)
    return unk


def _selection(rows: np.ndarray, n: int) -> sp.csr_matrix:
    """``sp.csr_matrix((np.ones(m), (rows, np.arange(m))), shape=(n, m))`` for ``m`` increasing ``rows`` without
    repeats, written as its CSR arrays (a row's pointer steps by one at each of ``rows``): the same arrays as
    scipy's conversion of those entries, without its sort (0.01 against 0.08 ms CPU at 529 dofs)."""
    m = rows.size
    if n >= 2**31 - 1:
        return sp.csr_matrix((np.ones(m), (rows, np.arange(m))), shape=(n, m))
    indptr = np.zeros(n + 1, np.int32)
    indptr[rows + 1] = 1
    np.cumsum(indptr, out=indptr)
    return compressed(np.ones(m), np.arange(m, dtype=np.int32), indptr, (n, m), canonical=True)


_REDUCED: "weakref.WeakKeyDictionary[FVSystem, tuple]" = weakref.WeakKeyDictionary()


def _reduced(system: FVSystem, unk: FVUnknowns, p_fixed: np.ndarray, p_c: float):
    """Condensed matrices and the fixed part ``b`` of the residual ``K P + G theta + b`` (the last ones kept
    on the system: the first guess of the cavity and the active set condense the same)."""
    hit = _REDUCED.get(system)
    if hit is not None and hit[0] is unk and hit[2] == p_c and np.array_equal(hit[1], p_fixed):
        return hit[3]
    out = _condensed(system, unk, p_fixed, p_c)
    _REDUCED[system] = (unk, p_fixed.copy(), p_c, out)
    return out


def _condensed(system: FVSystem, unk: FVUnknowns, p_fixed: np.ndarray, p_c: float):
    K, G = system.K, _with_storage(system.C, system.storage)
    p0 = np.full(p_fixed.size, p_c)
    p0[unk.fixed] = p_fixed[unk.fixed]   # P = p - p_c on the unknowns
    theta0 = np.zeros(p_fixed.size)
    theta0[unk.fixed] = 1.0              # edges and pockets feed full film
    r = matvec(K, p0) + matvec(G, theta0) + system.source
    if _selects(unk):                    # each unknown one dof (no periodic seam): S selects the dofs rep
        rep = unk.rep                    # the same matrices as S^T A S, whose products drop exact zeros
        return _selected(K, rep), _selected(G, rep), r[rep]
    St = unk.S.T.tocsr()
    return (St @ K @ unk.S).tocsr(), (St @ G @ unk.S).tocsr(), St @ r


def _selects(unk: FVUnknowns) -> bool:
    """Whether ``unk.S`` is the selection of the dofs ``unk.rep`` (increasing), unknown ``k`` dof ``rep[k]`` (found
    once, kept on ``unk``; :func:`_build_unknowns` notes it where it built ``S`` so)."""
    kept = unk._order.get("selects")
    if kept is None:
        S = sp.csr_matrix(unk.S)
        m = S.shape[1]
        kept = unk._order["selects"] = (S.nnz == m and np.array_equal(np.flatnonzero(np.diff(S.indptr)), unk.rep)
                                        and np.array_equal(S.indices, np.arange(m)) and bool(np.all(S.data == 1.0)))
    return kept


def _selected(A: sp.csr_matrix, rows: np.ndarray) -> sp.csr_matrix:
    """``A[rows][:, rows]`` without its explicit zeros, indices sorted (canonical, as a sparse product gives).
    ``rows`` increasing without repeats and ``A`` canonical CSR: the kept entries picked by a mask over the stored
    ones and renumbered (the same arrays, bit for bit, as scipy's two fancy indexings and clean-ups, without
    them: 0.10 against 0.15 ms CPU at 529 nodes, mean of 2,000 calls, load ~4)."""
    n = A.shape[0]
    if (A.format == "csr" and A.has_canonical_format and A.shape[0] == A.shape[1] and rows.ndim == 1
            and (rows.size < 2 or bool(np.all(rows[1:] > rows[:-1])))
            and (rows.size == 0 or 0 <= rows[0] <= rows[-1] < n)):
        number = np.full(n, -1, dtype=A.indices.dtype)
        number[rows] = np.arange(rows.size, dtype=A.indices.dtype)
        row_of = np.repeat(number, np.diff(A.indptr))
        keep = (row_of >= 0) & (number[A.indices] >= 0) & (A.data != 0)
        counts = np.bincount(row_of[keep], minlength=rows.size) if rows.size else np.zeros(0, np.int64)
        indptr = np.zeros(rows.size + 1, dtype=A.indptr.dtype)
        np.cumsum(counts, out=indptr[1:])
        # an increasing renumbering of sorted rows without repeats: canonical
        return compressed(A.data[keep], number[A.indices[keep]], indptr, (rows.size, rows.size), canonical=True)
    B = A[rows][:, rows].tocsr()
    B.eliminate_zeros()
    B.sort_indices()
    return B


def _reduced_cavity(system: FVSystem, unk: FVUnknowns, G: sp.csr_matrix) -> sp.csr_matrix:
    """Condensed operator of the cavitated unknowns' theta (``G`` where the system has no separate one)."""
    if system.C_cavity is None:
        return G
    St = unk.S.T.tocsr()
    return (St @ _with_storage(system.C_cavity, system.storage) @ unk.S).tocsr()


def _with_storage(C: sp.csr_matrix, storage: np.ndarray) -> sp.csr_matrix:
    """``C + diag(storage)`` as scipy's sum gives it (CSR, entries that are zero dropped). Without storage (a
    steady solve without squeeze) a canonical ``C`` is copied without its zeros instead: ``c + 0`` is ``c``, so the
    same arrays bit for bit, without the diagonal matrix and the sparse sum (0.04 against 0.16 ms CPU at 529
    nodes, mean of 2,000 calls)."""
    if C.format == "csr" and C.has_canonical_format and not np.any(storage):
        return csr_without_zeros(C)
    return (C + sp.diags(storage)).tocsr()


def _effective(system: FVSystem, unk: FVUnknowns, cavity: np.ndarray) -> FVSystem:
    """The system with one Couette operator: the cavitated columns from ``C_cavity`` (for the flows)."""
    if system.C_cavity is None:
        return system
    cav = matvec(unk.S, cavity.astype(float)) > 0.5
    C, Cc = system.C, system.C_cavity
    if (C.format == Cc.format == "csr" and C.has_canonical_format and Cc.has_canonical_format
            and np.array_equal(C.indptr, Cc.indptr) and np.array_equal(C.indices, Cc.indices)):
        # one pattern (the streamline flux's): each stored entry from one of the two, as the column products
        # and their sum below, without them (0.05 against 0.45 ms CPU at 810 nodes); canonical, where the
        # products' sum keeps each row's cavitated columns first (the flows' sums then add in another order)
        M = compressed(np.where(cav[C.indices], Cc.data, C.data), C.indices.copy(), C.indptr.copy(), C.shape)
        M.eliminate_zeros()
        return dataclasses.replace(system, C=M, C_cavity=None)
    C = (C @ sp.diags((~cav).astype(float)) + Cc @ sp.diags(cav.astype(float))).tocsr()
    return dataclasses.replace(system, C=C, C_cavity=None)


#: Largest number of switched unknowns solved by a low-rank update of the last factorization
#: (Sherman-Morrison-Woodbury) instead of a new one, in the tail of the active-set iteration: counted among
#: those whose column was not solved for yet on that factorization (each a new pair of triangular solves; the
#: columns of its earlier steps are kept), at most twice as many in all. Counting every switched unknown instead
#: refactorized when a step added a few to a Woodbury step's: the streamline pocket pad of docs/jfo_gmsh.md at
#: 28,947 nodes went from 22 switched unknowns to 25 (3 of them new): 2 fine factorizations against 3, 437-462
#: against 521-539 ms CPU of a cold solve (two interleaved pairs, load 2); the grid dimple at 40,401 nodes 1
#: against 2 (0.40 against 0.51 s CPU, one cold solve each); the same sets, the answers equal to round-off (1e-13
#: relative in theta).
LOW_RANK_SWITCHES = 24
#: A banded factorization (:class:`_BandedLU`) of half-bandwidth ``kd`` takes at most ``kd //`` this many new
#: columns by a low-rank update (fewer than :data:`LOW_RANK_SWITCHES` below a half-bandwidth of 72): a column
#: costs a banded solve, about ``3 kd`` multiply-adds per unknown, a refactorization about ``kd^2`` (measured in
#: the cold solves of the 5 x 5 dimples, CPU: 0.2 ms a column against 1-2 ms a refactorization at 6,676 unknowns
#: and half-bandwidth 18, 0.24 against 2.7-3.4 ms at 4,846 and 31, 0.09-0.13 against 1.2-1.7 ms at 2,401 and 49).
BANDED_KD_PER_COLUMN = 3
#: Unknowns from which the active-set matrices are factored in a nested-dissection order of the unknowns'
#: coordinates (:func:`bearingfe.core.ordering.nested_dissection`), found once per mesh, with diagonal
#: pivots preferred (SuperLU's symmetric mode, threshold :data:`PIVOT_THRESHOLD`) instead of SuperLU's
#: COLAMD with partial pivoting. Measured on the converged active-set matrix (load 2.7 on 2 cores): 0.13 s
#: against 0.28 s at 4.4e4 unknowns (gmsh, streamline flux), 0.48 s against 0.89 s at 1.6e5 (grid flux),
#: the order found in 0.06 s and 0.29 s. On a ``grid_mesh`` without a seam the order is the grid's own
#: dissection in closed form (:func:`bearingfe.core.ordering.grid_dissection`): at 600 x 600 dimple cells
#: 0.09-0.15 against 0.47-0.49 s, fill 0.7 % more, the same factorization time within the noise (load 3).
ORDERED_FROM = 5000
#: :data:`ORDERED_FROM` for unknowns on a ``grid_mesh`` without a seam, whose order is the grid's dissection in
#: closed form (no graph partitioning to pay): the ordered factorizations win from fewer unknowns there. CPU time of
#: cold solves of the 5 x 5 dimples (the order found in each solve), median of 5 interleaved, load 4-5 on 2 cores:
#: 56.2 against 60.3 ms at 5,041 nodes, 29.4 against 30.3 at 2,601, 19.9 against 21.0 at 1,681; on gmsh meshes,
#: whose nested-dissection order costs a partitioning, 1,000 unknowns were no gain (27.4 against 25.7 ms on the
#: pocket pad at 1,936 nodes, 30.8 against 32.4 on the dimple at 1,964).
ORDERED_FROM_GRID = 1000
#: Threshold of the partial pivoting of the ordered factorization (a diagonal pivot is kept while it is
#: at least this fraction of its column's largest entry).
PIVOT_THRESHOLD = 0.01


def _ordered_splu(unk: FVUnknowns, K: sp.csc_matrix, G: sp.csc_matrix) -> Factorize:
    """SuperLU of the active-set matrices in the nested-dissection order of ``unk`` (from
    :data:`ORDERED_FROM` unknowns on, :data:`ORDERED_FROM_GRID` on a grid, else COLAMD); the order is found once
    and kept on ``unk``. A solve whose residual is not at round-off falls back to COLAMD with partial pivoting."""
    m = K.shape[0]
    band = _set_band(unk, K, G)
    if band is not None:
        return _factorize_banded(*band)
    if m < (ORDERED_FROM_GRID if unk.on_grid else ORDERED_FROM) or unk.coordinates is None:
        return factorize_splu
    order = unk._order.get("order")
    if order is None or order.size != m:
        from ..core.ordering import grid_dissection, nested_dissection

        if unk.on_grid:   # the unknowns' grid line numbers: the dissection in closed form
            index = np.stack([np.unique(c, return_inverse=True)[1].ravel() for c in unk.coordinates])
            order = grid_dissection(index)
        else:
            order = nested_dissection((abs(K) + abs(G)).tocsr(), unk.coordinates)
        unk._order["order"] = order
    return _factorize_in_order(order)


def _set_band_max() -> int:
    """Largest half-bandwidth (reverse Cuthill-McKee order of the pattern of ``|K| + |G|``) at which the
    active-set matrices are factored by banded LU with partial pivoting (LAPACK ``dgbtrf``, one BLAS thread)
    instead of SuperLU: :data:`bearingfe.core.banded.BAND_LIMITS` ``["active_set_lu"]`` (read at each call)."""
    return band_limits("active_set_lu").kd_max


def _set_band(unk: FVUnknowns, K: sp.spmatrix, G: sp.spmatrix) -> tuple[np.ndarray, int] | None:
    """The reverse Cuthill-McKee order of the unknowns for the pattern of ``|K| + |G|`` and its
    half-bandwidth, kept on ``unk`` per pattern (on a grid without a seam its lines' order,
    :func:`_grid_band_order`, where its band fits); None if that exceeds :func:`_set_band_max`, or at once for
    more unknowns than the ``"active_set_lu"`` limits try (a square grid's band is then wider: no pattern or
    order built on a fresh larger mesh, only a strip much longer than wide would have fitted)."""
    if not band_worth_trying(K.shape[0], "active_set_lu"):
        return None
    grid = _grid_band_order(unk)
    if grid is not None:   # the grid's line order: no union pattern, no graph search (else as below)
        kd = max(half_bandwidth(K, grid), half_bandwidth(G, grid))   # |i - j|: CSR or CSC alike
        if kd <= _set_band_max():
            return grid, kd
    kept = unk._order.get("set_band")
    given = ((K.format, K.indptr, K.indices, G.format, G.indptr, G.indices)
             if K.format in ("csr", "csc") and G.format in ("csr", "csc") else None)
    if kept is not None and given is not None and kept[3] is not None and _same_pattern(kept[3], given):
        return kept[2]   # the same matrices' patterns as last time: the same union pattern
    pattern = _union_pattern(K, G)
    kept = unk._order.get("set_band")
    if kept is None or not (np.array_equal(kept[0], pattern.indptr) and np.array_equal(kept[1], pattern.indices)):
        perm = _full_film_order(unk, pattern)
        if perm is None:
            perm = reverse_cuthill_mckee(pattern, symmetric_mode=True).astype(np.int64)
        kd = half_bandwidth(pattern, perm)
        kept = (pattern.indptr.copy(), pattern.indices.copy(), (perm, kd) if kd <= _set_band_max() else None)
    # with the given matrices' own patterns: the next call with the same ones skips the union pattern
    unk._order["set_band"] = kept[:3] + (None if given is None else
                                         tuple(a if isinstance(a, str) else a.copy() for a in given),)
    return kept[2]


#: Whether the banded LU of the active-set matrices of a grid's unknowns (``FVUnknowns.on_grid``: a ``grid_mesh``
#: without a seam) takes its lines' order (:func:`_grid_band_order`) instead of the reverse Cuthill-McKee order of
#: the union pattern of ``|K| + |G|`` (:func:`_set_band`): the same half-bandwidth on the square grids of
#: docs/jfo_dimples.md (49 at 50 x 50 cells, 29 at 30 x 30; narrower on uneven cells) without the union pattern and
#: the graph search: :func:`_set_band` 0.16-0.18 against 0.60-0.66 ms, the factorizations the same 5.15 ms, the
#: cold solve at 50 x 50 cells 0.25-0.65 ms less (CPU, 40 interleaved fresh solves, load 4 on 2 cores). The factors
#: differ in rounding only. Left out for the full-film guess's banded Cholesky (:func:`_full_film_banded`): its
#: plan in this order saved 0.2 ms but the factorization took 0.95 against 0.80 ms.
GRID_BAND_ORDER = True


def _grid_band_order(unk: FVUnknowns) -> np.ndarray | None:
    """The unknowns of a grid without a seam (``unk.on_grid``) line by line across the axis with more lines, each
    line's from its largest coordinate down (kept on ``unk``): a grid_mesh's diagonals join ``(ix, iz)`` to
    ``(ix + 1, iz + 1)``, so in this order the half-bandwidth is one line's unknowns, as reverse Cuthill-McKee
    finds on a square grid; None elsewhere or without :data:`GRID_BAND_ORDER` (read at each call)."""
    if not (GRID_BAND_ORDER and unk.on_grid) or unk.coordinates is None:
        return None
    order = unk._order.get("grid_band")
    if order is None:
        phi, z = unk.coordinates
        inner, outer = (z, phi) if _distinct_count(z) <= _distinct_count(phi) else (phi, z)
        order = np.lexsort((-inner, outer)).astype(np.int64)
        unk._order["grid_band"] = order
    return order


def _distinct_count(values: np.ndarray) -> int:
    """``np.unique(values).size`` of finite values (a grid's coordinates): the changes along them sorted, one sort
    (none where they are sorted already, as a grid's node numbering leaves its ``phi``), without ``np.unique``'s
    mask and copy of the distinct values."""
    if values.size == 0:
        return 0
    if not np.all(values[1:] >= values[:-1]):
        values = np.sort(values)
    return 1 + int(np.count_nonzero(values[1:] != values[:-1]))


def _full_film_order(unk: FVUnknowns, pattern: sp.csr_matrix) -> np.ndarray | None:
    """The reverse Cuthill-McKee order the full-film guess's band plan (:func:`_full_film_banded`, kept on ``unk``)
    found for the pattern of its ``K`` where that equals ``pattern`` (sorted CSR), else None: the same function of
    the same pattern, so the same order, without a second graph search. On a fresh gmsh mesh the union pattern
    of the active-set matrices is ``K``'s own (the Couette operator's entries lie on ``K``'s pattern: every page
    mesh of docs/jfo_gmsh.md up to 7,731 nodes), and the search costs about 0.09 ms at 433 unknowns."""
    kept = unk._order.get("band")
    if kept is None or kept[2] is None:
        return None
    if not (np.array_equal(kept[0], pattern.indptr) and np.array_equal(kept[1], pattern.indices)):
        return None
    return kept[2].perm


def _union_pattern(K: sp.spmatrix, G: sp.spmatrix) -> sp.csr_matrix:
    """The symmetric pattern of ``|K| + |G|`` and its transpose (sorted CSR, entries that sum to zero dropped,
    as scipy's sums drop them). Two canonical matrices of one compressed format are read as they are (a CSC
    matrix's arrays are its transpose's CSR arrays: the same symmetric pattern), without the conversions to
    CSR: 0.13 against 0.19 ms CPU at 433 unknowns, 0.27 against 0.44 at 2,855 (mean of 300 calls; the same
    arrays, values included); with ``int32`` indices the sums and the transpose by scipy's own kernels
    (:func:`~bearingfe.core.compressed.csr_sum`, :func:`~bearingfe.core.compressed.csr_transposed`) without its sparse matrices' checks in between."""
    if K.format == G.format and K.format in ("csr", "csc") and K.has_canonical_format and G.has_canonical_format:
        A = compressed(np.abs(K.data), K.indices, K.indptr, K.shape[::-1] if K.format == "csc" else K.shape,
                       canonical=True)
        B = compressed(np.abs(G.data), G.indices, G.indptr, G.shape[::-1] if G.format == "csc" else G.shape,
                       canonical=True)
        U = csr_sum(A, B)   # (scipy's kernels on int32 arrays, else scipy's sums: the same arrays)
        return csr_sum(U, csr_transposed(U))
    U = (abs(sp.csr_matrix(K)) + abs(sp.csr_matrix(G))).tocsr()
    pattern = (U + U.T).tocsr()
    pattern.sort_indices()
    return pattern


def _same_pattern(a: tuple, b: tuple) -> bool:
    """Whether two tuples of formats and index arrays (:func:`_set_band`'s key) are equal."""
    return all(x == y if isinstance(x, str) else np.array_equal(x, y) for x, y in zip(a, b))


def _factorize_banded(perm: np.ndarray, kd: int) -> "_BandedLU":
    """Banded LU with partial pivoting (LAPACK ``dgbtrf``, lower and upper half-bandwidth ``kd``) of matrices
    whose pattern lies in that band of the order ``perm``; an exactly singular one falls back to COLAMD
    (:func:`~bearingfe.core.linalg.factorize_splu`)."""
    return _BandedLU(perm, kd)


#: LAPACK's banded LU (``dgbtrf``) works by blocks only where the lower half-bandwidth reaches its block size (32
#: in OpenBLAS's and the reference ``ilaenv``); narrower, its unblocked loop is slower per entry. A half-bandwidth
#: from :data:`BAND_PAD_FROM` up to it is therefore stored and factored as this one (:class:`_BandedLU`: zero
#: extra diagonals, the same pivots, rounding only). ``dgbtrf`` alone (CPU, best of 3 x 20, 4,846 unknowns, the
#: front band of the 5 x 5 dimples at 100 x 100 cells): half-bandwidth 24 1.39 ms, 28 1.71, 31 2.29, 32 1.59,
#: 33 1.62, 34 1.80 ms.
BAND_BLOCK = 32
#: Smallest half-bandwidth :class:`_BandedLU` widens to :data:`BAND_BLOCK` (read when it is made).
BAND_PAD_FROM = 28


class _BandedLU:
    """:func:`_factorize_banded`'s factorization: called with a sparse matrix, or (:meth:`from_band`) with the
    values of a pattern whose places in LAPACK's band storage were found once (:meth:`places`), which skips the
    sparse matrix of each set (its format checks, the COO conversion and the reordering of its indices)."""

    def __init__(self, perm: np.ndarray, kd: int):
        self.perm, self.kd = perm, kd
        # the band as stored and factored: kd, or LAPACK's block size where kd lies just below it (BAND_PAD_FROM)
        self.width = BAND_BLOCK if BAND_PAD_FROM <= kd < BAND_BLOCK else kd
        self.inverse = np.argsort(perm)
        self._spare: list[np.ndarray] = []   # band storage of factorizations no longer in use (_storage)

    def _storage(self) -> np.ndarray:
        """Zeroed band storage ``(3 kd + 1) n`` (flat): the array of a factorization whose solve is gone, where
        there is one, else a new one. A new array of a few MB is memory the system supplies page by page, which
        cost as much as a third of a factorization (2,401 unknowns, half-bandwidth 49: 0.6 of 1.7 ms)."""
        if self._spare:
            ab = self._spare.pop()
            ab.fill(0.0)
            return ab
        return np.zeros((3 * self.width + 1) * self.perm.size)

    def places(self, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """Flat (column-major) places in the band storage of the entries ``(rows, cols)`` (unknown numbers)."""
        i, j = self.inverse[rows], self.inverse[cols]
        return (2 * self.width + i - j) + (3 * self.width + 1) * j.astype(np.int64)

    def __call__(self, M: sp.spmatrix) -> Callable[[np.ndarray], np.ndarray]:
        A = sp.coo_matrix(M)
        return self.from_band(A.data, self.places(A.row, A.col), lambda: M)

    def from_band(self, values: np.ndarray, places: np.ndarray,
                  matrix: Callable[[], sp.spmatrix]) -> Callable[[np.ndarray], np.ndarray]:
        """The factorization of the matrix with ``values`` at the band ``places`` (zeros elsewhere; explicit zeros
        among them are no entries); ``matrix()`` builds it as a sparse matrix for the singular fallback."""
        from scipy.linalg.lapack import dgbtrf, dgbtrs

        kd, perm, inverse = self.width, self.perm, self.inverse
        n = perm.size
        flat = self._storage()
        flat[places] = values   # LAPACK band storage with kd extra rows for the pivoting's fill
        ab = flat.reshape((3 * kd + 1, n), order="F")
        with dense_threads(1):
            lu, piv, info = dgbtrf(ab, kd, kd, overwrite_ab=1)
        if info != 0:
            self._spare.append(flat)
            return factorize_splu(matrix())

        def solve(b: np.ndarray) -> np.ndarray:
            b = np.asarray(b, dtype=float)
            with dense_threads(1):
                x, _ = dgbtrs(lu, kd, kd, b[perm], piv)
            return x[inverse]

        if np.shares_memory(lu, flat):   # the factors in place: the storage serves again once solve is gone
            weakref.finalize(solve, self._spare.append, flat)
        return solve


def _factorize_in_order(order: np.ndarray) -> Factorize:
    """SuperLU of matrices in the fixed fill-reducing ``order`` with diagonal pivots preferred (SuperLU's
    symmetric mode, threshold :data:`PIVOT_THRESHOLD`). A matrix exactly singular in this order, or whose
    first solve's residual is not at round-off (pivots too small for this set), falls back to COLAMD with
    partial pivoting (:func:`~bearingfe.core.linalg.factorize_splu`)."""
    inverse = np.argsort(order)

    def factorize(M: sp.spmatrix) -> Callable[[np.ndarray], np.ndarray]:
        M = sp.csc_matrix(M)
        scale = float(np.abs(M.data).max(initial=0.0))
        fallback, checked = [], []
        try:
            lu = spla.splu(M[order][:, order].tocsc(), permc_spec="NATURAL", diag_pivot_thresh=PIVOT_THRESHOLD,
                           options={"SymmetricMode": True})
        except RuntimeError:   # exactly singular in this order
            fallback.append(factorize_splu(M))

        def solve(b: np.ndarray) -> np.ndarray:
            b = np.asarray(b, dtype=float)
            if fallback:
                return fallback[0](b)
            x = lu.solve(b[order])[inverse]
            if checked:   # the factorization's first solve was at round-off
                return x
            checked.append(True)
            r = M @ x - b
            bound = 1e-10 * (scale * np.abs(x).max(initial=0.0) + np.abs(b).max(initial=0.0))
            if not np.abs(r).max(initial=0.0) <= bound:   # also NaN
                fallback.append(factorize_splu(M))
                return fallback[0](b)
            return x

        return solve

    return factorize


#: Largest system whose set matrices are picked on the union pattern (:func:`_column_choice`); above it the
#: pattern's set-up costs more than the few builds it saves (CPU of a cold 600 x 600 dimple solve, all levels:
#: 16 builds 0.28 s picked against 0.07 s by products; at 50 x 50 cells 1 ms against 2 ms, at 100 x 100 equal).
CHOICE_UP_TO = 5000


def _column_choice(K: sp.csc_matrix, G: sp.csc_matrix,
                   kept: dict | None = None) -> tuple[sp.csc_matrix, np.ndarray, np.ndarray, np.ndarray]:
    """The union sparsity pattern of two square CSC matrices of one shape (sorted, canonical), the values of
    ``K`` and of ``G`` on it (0 where a matrix has no entry) and each stored entry's column index.

    Lets :meth:`_SetSolver.matrix` assemble ``K diag(~cav) + G diag(cav)`` for a new set by one selection
    per entry. ``kept``: a dict (the unknowns' ``_order``) that keeps the pattern part (the union, the
    columns, the places of ``K``'s and ``G``'s entries on it) for canonical ``K`` and ``G`` of the same
    patterns: a repeated solve on the mesh then only places its values (the same values)."""
    canonical = kept is not None and K.has_canonical_format and G.has_canonical_format
    arrays = (K.indptr, K.indices, G.indptr, G.indices)
    hit = kept.get("choice") if canonical else None
    if hit is not None and all(np.array_equal(a, b) for a, b in zip(hit[0], arrays)):
        pattern, column, at_k, at_g = hit[1]
        k_data, g_data = np.zeros(pattern.nnz), np.zeros(pattern.nnz)
        k_data[at_k], g_data[at_g] = K.data, G.data
        return pattern, k_data, g_data, column
    ones_k = sp.csc_matrix((np.ones(K.nnz), K.indices, K.indptr), shape=K.shape)
    ones_g = sp.csc_matrix((np.ones(G.nnz), G.indices, G.indptr), shape=G.shape)
    pattern = (ones_k + ones_g).tocsc()
    pattern.sort_indices()
    column = np.repeat(np.arange(pattern.shape[1]), np.diff(pattern.indptr))
    keys = column * np.int64(pattern.shape[0]) + pattern.indices   # ascending: sorted columns, sorted rows

    def on_pattern(A: sp.csc_matrix) -> tuple[np.ndarray, np.ndarray]:
        A = sp.csc_matrix(A, copy=True)
        A.sum_duplicates()   # canonical, as the products would sum them
        a_column = np.repeat(np.arange(A.shape[1]), np.diff(A.indptr))
        at = np.searchsorted(keys, a_column * np.int64(A.shape[0]) + A.indices)
        out = np.zeros(pattern.nnz)
        out[at] = A.data
        return out, at

    (k_data, at_k), (g_data, at_g) = on_pattern(K), on_pattern(G)
    if canonical:
        kept["choice"] = (tuple(a.copy() for a in arrays), (pattern, column, at_k, at_g))
    return pattern, k_data, g_data, column


class _SetSolver:
    """Solves of the active-set systems ``M(cav) y = rhs``, ``M = K diag(full) + G diag(cav)``.

    A set that differs from the last factorized one in ``k`` columns, at most :data:`LOW_RANK_SWITCHES` of
    them not solved for yet on that factorization and ``2 LOW_RANK_SWITCHES`` in all (a banded factorization:
    fewer, :data:`BANDED_KD_PER_COLUMN`), is solved by
    Sherman-Morrison-Woodbury on it (an extra triangular solve per new column, cached per column while the
    factorization lives), accepted with its residual at a fresh factorization's accuracy; larger changes, or a
    residual that is not at round-off, refactorize.

    Measured and left out (the dimpled slider of docs/jfo_dimples.md, 2e4 .. 1e5 unknowns): keeping the
    first factorization's COLAMD column ordering for the later sets (SuperLU with ``NATURAL`` on the
    permuted columns) saves COLAMD but the row pivoting of the changed sets fills in far more (a
    factorization went from 0.07 s to 1.6 s at 2.2e4 unknowns). GMRES preconditioned
    with the last factorization was measured in its place for the moderate changes (50 .. 2,000 switched
    unknowns of the dimpled slider at 1e4 .. 4e4 unknowns): ``M0^-1 M`` is the identity plus a change of
    rank ``k`` whose eigenvalues do not cluster (the switched columns change from the Poiseuille to the
    Couette operator), so it needed 30 to over 60 iterations to round-off, more than a factorization costs.
    What is kept instead (:func:`_ordered_splu`): one nested-dissection order of the unknowns applied to rows
    and columns alike, with diagonal pivots preferred (SuperLU's symmetric mode): the changed sets then
    pivot little and fill like the first, about half COLAMD's factorization time. Also measured and left out
    (the dimpled slider at 1.6e5 and 3.6e5 unknowns, converged matrix, best of 2-5 interleaved on a loaded
    machine): SuperLU's ``relax`` (1 .. 64: no change in fill or time) and ``panel_size`` (1 .. 32: within
    +-15 % noise, no trend at 3.6e5), ``Equil=False`` (same), SuperLU's own ``MMD_AT_PLUS_A`` in symmetric
    mode (30 % less fill, slower), and solving the Woodbury columns as one block of right sides (SuperLU's
    triangular solves cost the same per column either way: 0.015-0.018 s per column for 1, 8 and 40 columns
    at 1.6e5 unknowns), so :data:`LOW_RANK_SWITCHES` stays near one factorization's worth of solves. The block
    solve runs with one BLAS thread (:func:`bearingfe.core.linalg.dense_threads`): SuperLU's solve of several
    right sides calls BLAS, whose two threads wait for each other on a busy machine (measured at load 3 on
    2 cores: 24 columns 54 ms with two threads against 7.6 ms with one at 9,801 unknowns, 57 against 2.4 ms
    at 2,855 on a gmsh mesh; the Woodbury steps of cold solves 13-34 against 43-184 ms at 11,903 nodes).
    """

    def __init__(self, K: sp.csr_matrix, G: sp.csr_matrix, factorize: Factorize, unk: FVUnknowns | None = None):
        self.K, self.G = csc_of(K), csc_of(G)
        self.factorize = factorize
        self.unk = unk
        if factorize is factorize_splu and unk is not None:
            self.factorize = _ordered_splu(unk, self.K, self.G)
        self.solve = None
        self.base = None
        self.z: dict[int, np.ndarray] = {}
        self.factorizations = 0
        self._choice: tuple[sp.csc_matrix, np.ndarray, np.ndarray, np.ndarray] | None = None
        self._places: tuple | None = None   # K's and G's entries with their band storage places (_band_values)

    def matrix(self, cav: np.ndarray) -> sp.csc_matrix:
        """``M(cav) = K diag(~cav) + G diag(cav)``: column ``j`` of ``G`` where ``cav[j]``, else of ``K``.

        Up to :data:`CHOICE_UP_TO` unknowns built on the union pattern of ``K`` and ``G`` (found once per
        solver, :func:`_column_choice`) by picking each stored entry from one of the two, explicit zeros
        dropped: the same entries as the sparse products and sum (above, those products)."""
        if self.K.shape[0] > CHOICE_UP_TO:
            return (self.K @ sp.diags((~cav).astype(float)) + self.G @ sp.diags(cav.astype(float))).tocsc()
        pattern, k_data, g_data, column = self._picked()
        M = compressed(np.where(cav[column], g_data, k_data), pattern.indices.copy(), pattern.indptr.copy(),
                       pattern.shape, fmt="csc")
        M.eliminate_zeros()   # in place: hence the copies of the kept pattern
        return M

    def _picked(self) -> tuple[sp.csc_matrix, np.ndarray, np.ndarray, np.ndarray]:
        """:func:`_column_choice` of ``K`` and ``G`` (found once per solver, the pattern part kept on the unknowns)."""
        if self._choice is None:
            self._choice = _column_choice(self.K, self.G, None if self.unk is None else self.unk._order)
        return self._choice

    def _refactorize(self, cav: np.ndarray, M: sp.csc_matrix | None = None) -> None:
        """Factorizes the set ``cav`` (its matrix ``M``, built here where not given): a banded factorization
        (:class:`_BandedLU`) takes the values of ``K`` and ``G`` straight into its band storage
        (:meth:`_band_values`), without a sparse matrix per set."""
        self.solve, self.z = None, {}   # the last factorization's storage may serve the new one
        if M is None and isinstance(self.factorize, _BandedLU):
            values, places = self._band_values(cav)
            solve = self.factorize.from_band(values, places, lambda: self.matrix(cav))
        else:
            solve = self.factorize(self.matrix(cav) if M is None else M)
        self.solve, self.base, self.z = solve, cav.copy(), {}
        self.factorizations += 1

    def _band_values(self, cav: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The entries of ``M(cav)``, ``K``'s in the columns outside ``cav`` and ``G``'s in those in it (``+ 0.0``
        turns a ``-0.0`` into the ``0`` of an absent entry; an explicit zero is the same zero), and their places
        in the band storage of :attr:`factorize`: the same band as :meth:`matrix`'s entries placed there. Each
        matrix's places and columns are found once per solver (no union pattern of the two)."""
        if self._places is None:
            self._places = (_band_entries(self.K, self.factorize), _band_entries(self.G, self.factorize))
        (k_data, k_places, k_column), (g_data, g_places, g_column) = self._places
        keep_k, keep_g = ~cav[k_column], cav[g_column]
        return (np.concatenate([k_data[keep_k], g_data[keep_g]]) + 0.0,
                np.concatenate([k_places[keep_k], g_places[keep_g]]))

    def __call__(self, cav: np.ndarray, rhs: np.ndarray) -> np.ndarray:
        if self.solve is not None:
            J = np.flatnonzero(cav != self.base)
            limit = self._low_rank_limit()
            if 0 < J.size <= 2 * limit and sum(1 for j in J if j not in self.z) <= limit:
                y = self._woodbury(J, rhs)   # its residual M y - rhs without forming M
                if y is not None and np.abs(matvec(self.K, np.where(cav, 0.0, y))
                                            + matvec(self.G, np.where(cav, y, 0.0))
                                            - rhs).max() <= 1e-11 * max(np.abs(rhs).max(), 1e-300):
                    return y
            elif J.size == 0:
                return np.asarray(self.solve(rhs), float)
        self._refactorize(cav)
        return np.asarray(self.solve(rhs), float)

    def _low_rank_limit(self) -> int:
        """:data:`LOW_RANK_SWITCHES`; for a banded factorization (:class:`_BandedLU`) at most its half-bandwidth
        over :data:`BANDED_KD_PER_COLUMN` (read at each call)."""
        if isinstance(self.factorize, _BandedLU):
            return min(LOW_RANK_SWITCHES, max(1, self.factorize.kd // BANDED_KD_PER_COLUMN))
        return LOW_RANK_SWITCHES

    def _woodbury(self, J: np.ndarray, rhs: np.ndarray) -> np.ndarray | None:
        new = [j for j in J if j not in self.z]
        if new:   # column change of switching j away from the factorized set: G_j - K_j or K_j - G_j
            sign = np.where(self.base[new], -1.0, 1.0)
            U = _column_change(self.K, self.G, np.asarray(new), sign)
            with dense_threads(1):   # SuperLU's block solve calls BLAS: threaded, it waits on a busy machine
                Z = np.asarray(self.solve(U), float).reshape(U.shape)
            for k, j in enumerate(new):
                self.z[j] = Z[:, k]
        Z = np.column_stack([self.z[j] for j in J])
        w = np.asarray(self.solve(rhs), float)
        C = np.eye(J.size) + Z[J, :]
        try:
            return w - Z @ np.linalg.solve(C, w[J])
        except np.linalg.LinAlgError:
            return None


def _band_entries(A: sp.csc_matrix, banded: _BandedLU) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The stored values of the CSC matrix ``A`` (duplicates summed), their places in the band storage of
    ``banded`` and their column indices."""
    if not A.has_canonical_format:
        A = sp.csc_matrix(A, copy=True)
        A.sum_duplicates()
    column = np.repeat(np.arange(A.shape[1]), np.diff(A.indptr))
    return A.data, banded.places(A.indices, column), column


def _column_change(K: sp.csc_matrix, G: sp.csc_matrix, columns: np.ndarray, sign: np.ndarray) -> np.ndarray:
    """``((G - K)[:, columns] @ diag(sign)).toarray()``: the dense columns of the change of switching the unknowns
    ``columns`` (``sign`` +-1 each), written from the CSC arrays of canonical ``K`` and ``G`` (no sparse matrices
    in between; the same values, a zero as ``+0.0``), else by the sparse products."""
    if not (K.format == G.format == "csc" and K.has_canonical_format and G.has_canonical_format):
        return ((G[:, columns] - K[:, columns]) @ sp.diags(sign)).toarray()
    U = np.zeros((K.shape[0], columns.size))
    for k, j in enumerate(columns):
        g, kk = slice(G.indptr[j], G.indptr[j + 1]), slice(K.indptr[j], K.indptr[j + 1])
        U[G.indices[g], k] = G.data[g]
        U[K.indices[kk], k] -= K.data[kk]
    U *= sign
    U += 0.0   # -0.0 (a zero times -1) as the +0.0 of an entry the sparse difference leaves out
    return U


#: Unknowns from which a set change too large for a low-rank update is first iterated on a band around the
#: switched unknowns (:func:`_band_set`), the rest held at the last global solve, before the next global
#: factorization, which then factorizes the band's set instead of an intermediate one. Measured on the 5 x 5
#: dimples of docs/jfo_dimples.md (best of 2-3 interleaved, load 0.3-0.8): 2 against 3 fine factorizations
#: at 1e4, 4e4, 1.6e5 and 3.6e5 unknowns. One band pass alone left 15 switches at 1.6e5 and 44-52 at 3.6e5
#: (whatever its width: 6, 12 and 20 rings measured): the far-field change its fixed rim does not see; the
#: global correction solves between :data:`BAND_PASSES` passes leave 1 and 10 (Woodbury steps). The fine level
#: (factorizations, Woodbury, the rest with the band) of cold solves, benchmarks/jfo_dimples.py's ``stages``
#: interleaved at load 0.4-0.85: 1.8 against 2.1-2.2 s at 1.6e5, 4.8-4.9 against 5.2-5.6 s at 3.6e5 (the
#: factorizations 2.9-3.0 against 4.5-4.9 s, the band's passes about 0.7 s of it).
BAND_FROM = 50_000
#: Graph rings of neighbours around the switched unknowns that make the band of :func:`_band_set`.
BAND_RINGS = 6
#: Active-set iterations of the band subproblem at most (it stops earlier when its set repeats).
BAND_ITERATIONS = 20
#: Passes of the band iteration, each after the first started from one global correction solve.
BAND_PASSES = 3


def _grown(seed: np.ndarray, pattern: sp.csr_matrix, rings: int) -> np.ndarray:
    """The boolean ``seed`` grown by ``rings`` rings of neighbours in ``pattern`` (``|K| + |Gc|``, CSR)."""
    band = seed.copy()
    for _ in range(rings):
        band = band | (pattern @ band.astype(float) > 0)
    return band


def _band_plan(pattern: sp.csr_matrix, band: np.ndarray) -> tuple[np.ndarray, np.ndarray, Factorize]:
    """The boolean ``band``, its unknowns ``B`` and the factorization of its matrices (:func:`_band_factorize`
    in the reverse Cuthill-McKee order of the band's rows and columns of ``pattern``, ``|K| + |Gc|``)."""
    B = np.flatnonzero(band)
    band_pattern = pattern[B][:, B]   # |KBB| + |GcBB| (sorted: the same arrays)
    band_pattern.sort_indices()
    order = np.asarray(reverse_cuthill_mckee(band_pattern, symmetric_mode=True))
    # in the band's reverse Cuthill-McKee order (0.056 against 0.086 s for COLAMD on the 6.2e4-unknown band of
    # the 600 x 600 dimples: thin, the per-column overhead dominates), by banded LU where that order's band is
    # narrow (_band_factorize); Woodbury for a few switches, as globally
    return band, B, _band_factorize(band_pattern, order)


def _band_set(K: sp.csr_matrix, Gc: sp.csr_matrix, G: sp.csr_matrix, b: np.ndarray, cav: np.ndarray,
              y: np.ndarray, new: np.ndarray, tol: float, tol_p: float, solve=None, seed: np.ndarray | None = None,
              passes: int = BAND_PASSES, converge: bool = False, rings: int = BAND_RINGS,
              iterations: int = BAND_ITERATIONS, pattern: sp.csr_matrix | None = None,
              plan: tuple | None = None) -> np.ndarray:
    """The active set iterated on a band of :data:`BAND_RINGS` neighbour rings around the unknowns where
    ``new`` differs from ``cav``, the unknowns outside the band held at the global solution ``y`` on ``cav``
    (their set is the same in both). With ``solve`` (the last global factorization's solve), each of
    :data:`BAND_PASSES` passes then corrects the whole field by one solve of the residual of the band's set
    (the far-field change the band's fixed rim does not see) and iterates the band again from it.
    Returns the proposed next set (``new`` outside the band); the caller's global solve on it decides
    convergence, so the band only changes which sets are factorized on the way. ``seed``: the unknowns the band
    grows from instead of the switched ones; ``passes``: the passes at most; ``converge``: stop once a pass's
    correction leaves the band's set as the band iteration left it; ``rings``, ``iterations``: the band's width
    and its active-set iterations in a pass at most; ``pattern``: ``|K| + |Gc|`` (CSR) where the caller has it
    (built here otherwise); ``plan``: the band and its factorization (:func:`_band_plan`) where the caller found
    them (``seed`` and ``rings`` then unused)."""
    if plan is None:
        if pattern is None:
            pattern = (abs(K) + abs(Gc)).tocsr()
        plan = _band_plan(pattern, _grown((new != cav) if seed is None else seed, pattern, rings))
    band, B, band_factorize = plan
    out = np.flatnonzero(~band)
    co = cav[out]
    KB, GcB, GB = K[B], Gc[B], G[B]
    KBB, GcBB, GBB = KB[:, B].tocsc(), GcB[:, B].tocsc(), GB[:, B]
    KBo, GcBo = KB[:, out], GcB[:, out]
    base = -b[B] - GB[:, out] @ (~co).astype(float)
    c = new[B].copy()
    y = y.copy()
    passes = passes if solve is not None else 1
    band_solver = _SetSolver(KBB, GcBB, band_factorize)
    last = None
    for npass in range(passes):
        yo = y[out]
        fixed = base - KBo @ np.where(co, 0.0, yo) - GcBo @ np.where(co, yo, 0.0)
        seen = set()
        for _ in range(iterations):
            yb = band_solver(c, fixed - GBB @ (~c).astype(float))
            if not np.all(np.isfinite(yb)):
                break
            P = np.where(c, 0.0, yb)
            nc = np.where(c, yb < 1.0 - tol, P < -tol_p)
            if np.array_equal(nc, c):
                break
            seen.add(np.packbits(c).tobytes())
            if np.packbits(nc).tobytes() in seen:
                break
            c = nc
        if solve is None or npass == passes - 1 or not np.all(np.isfinite(yb)):
            break
        y[B] = yb
        full = cav.copy()
        full[B] = c
        r = -b - G @ (~full).astype(float) - K @ np.where(full, 0.0, y) - Gc @ np.where(full, y, 0.0)
        y = y + np.asarray(solve(r), float)
        if converge:   # the band's set carried to the next pass as it is; stop once a pass leaves it so
            if last is not None and np.array_equal(last, c):
                break
            last = c.copy()
            continue
        P = np.where(full, 0.0, y)
        c = np.where(full, y < 1.0 - tol, P < -tol_p)[B]
    out_set = new.copy()
    out_set[B] = c
    return out_set


#: Unknowns from which a cold grid solve with a nested start iterates the starting set before its first fine
#: factorization (:func:`_two_grid_set`): on a band around the carried cavity's fronts, each pass corrected
#: by the coarse level's last factorization. Measured on the 5 x 5 dimples of docs/jfo_dimples.md (best of 2-4
#: interleaved, load 2-3.8 on 2 cores): 1 fine factorization against 2 from 6.3e4 nodes on (1.7 against 2.4 s
#: at 6.3e4, 2.5 against 2.8 at 9e4, cavitation stage 6.6-9.2 against 11.9-14.4 s at 3.6e5); below, 1 against
#: 3 with the wide band (:data:`TWO_GRID_RINGS`), which costs more than the two factorizations it saves (1.9
#: against 1.45 s at 4e4, 0.48 against 0.38 s at 1e4); the narrow band (:data:`TWO_GRID_NARROW_RINGS`) saves
#: there (CPU time of cold solves, median of 7 interleaved, load 2.5-3 on 2 cores: 346 against 497 ms at 40,401
#: nodes, 174 against 210 ms at 19,881, 98 against 106 ms at 10,201; 1 fine factorization against 3), even at
#: 9,216 nodes (86.5 against 87.6 ms; 8,836 unknowns), but not at 7,396 (76.8 against 71.2 ms) or 5,041 nodes
#: (65 against 54 ms). Left out: stopping the coarse level below it earlier (2 % of its nodes
#: switching instead of :data:`NESTED_ROUGH`) saved a coarse factorization at 3.6e5 but took 6 fine ones at 4e4.
TWO_GRID_FROM = 8000
#: Unknowns from which, below :data:`TWO_GRID_FROM`, a nested start takes :func:`_two_grid_set` where its band's
#: matrices factor by banded LU (:func:`_band_factorize`: the band around short fronts is thin), and else starts
#: from the carried set as it is (the band of many fronts, factored by SuperLU, cost more than it saved). CPU time
#: of cold solves on fresh meshes, min of 11 interleaved, load 1-1.7 on 2 cores: docs/jfo_gmsh.md's pocket pad on
#: its 6,336-node grid 49.5-54.2 against 56.9-58.1 ms (1 fine factorization against 2; band 956 of 5,952
#: unknowns), the 5 x 5 dimples of docs/jfo_dimples.md at 80 x 80 cells 69.9-72.4 against 77.8-78.4 ms (1 against
#: 3); refused (a band of 3,136 of 4,761 unknowns at 70 x 70 cells, SuperLU): 63.6-67.7 against 63.0-63.1 ms, the
#: test and the interpolated start it needs about 1.6 ms; the grooved journal's 5,062-node grid takes a band of 402
#: and saves a Woodbury step only, 43.4 against 41.0 ms (min of 21). Measured and left at 4,000: 1,500 (the
#: streamline flux's nested starts from NESTED_MIN_UNSTRUCTURED) cost more on the pocket pad (streamline 1,936
#: nodes 27.6 against 25.9 ms, contour-refined 2,741 nodes 33.6 against 31.6 ms, min of 15, load ~5; the same
#: fine factorizations) and no less on the grooved journal (2,548 nodes 34.5 against 34.9 ms, 1 against 2).
TWO_GRID_BANDED_FROM = 4000
#: :data:`TWO_GRID_PASSES` of a band taken below :data:`TWO_GRID_FROM` (:data:`TWO_GRID_BANDED_FROM`): one, the
#: band iterated from the interpolated coarse solution without the coarse level's corrections. CPU time of cold
#: solves on fresh meshes, min of 9 interleaved, load ~4.4 on 2 cores, against 4 passes: the 5 x 5 dimples at 80 x 80
#: cells 69.4 against 73.3 ms, docs/jfo_gmsh.md's pocket pad grid 6,336 nodes 53.8 against 55.2 ms and streamline
#: 7,375 nodes 92.4 against 96.6 ms, the grooved journal grid 5,062 nodes 45.6 against 46.1 ms and contour-refined
#: 7,731 nodes 99.6 against 99.8 ms (medians 46.2 against 48.1, 104.2 against 105.9); the same fine factorizations.
TWO_GRID_BANDED_PASSES = 1
#: Whether a nested start of the streamline flux (its coarse level a ``grid_mesh``, :func:`_grid_under`) also takes
#: :func:`_two_grid_set` (as the grid flux does; the coarse level's correction interpolated bilinearly to the
#: unstructured mesh's unknowns) on surfaces without recesses. CPU time of one cold solve each, load ~5 on 2
#: cores, docs/jfo_gmsh.md's meshes: pocket pad 28,947 nodes 438 against 552 ms, contour-refined 8,962 nodes 109
#: against 117 ms (1 fine factorization against 2), grooved journal 22,698 nodes 332 against 387 ms and
#: contour-refined 26,414 nodes 374 against 438 ms (1 against 2); the answers within 2e-13 in theta. Not on
#: surfaces with recesses: on the dimple's meshes (the streamline flux refers a cavitated contour node's theta to
#: its deepest film) the band's start ended on another complementarity solution (1 and 5 nodes' sets differ at
#: 11,903 and 16,808 nodes, theta by up to 0.23), and at 6,029 nodes took 5 fine factorizations against 3.
TWO_GRID_STREAMLINE = True
#: Passes of :func:`_two_grid_set` at most (it stops once a coarse correction leaves the band's set as it was),
#: from :data:`TWO_GRID_WIDE_FROM` unknowns on.
TWO_GRID_PASSES = 4
#: :data:`TWO_GRID_PASSES` from :data:`TWO_GRID_FROM` up to :data:`TWO_GRID_WIDE_FROM` unknowns (the narrow band).
#: CPU time of cold solves on fresh meshes, min of 3-7 interleaved against 4 passes, load ~4.7 on 2 cores: the
#: 5 x 5 dimples at 100, 140 and 200 cells 110.6 against 121.8, 222.7 against 233.6, 483 against 495 ms;
#: docs/jfo_gmsh.md's pocket pad contour-refined 8,962 nodes 118.1 against 121.5 ms (medians 122.9 against
#: 131.7), streamline 28,947 nodes 426 against 461 ms, the grooved journal streamline 22,698 nodes 359 against
#: 368 ms and grid 19,674 nodes 217 against 218 ms (medians 221 against 232); the same fine factorizations. One
#: pass cost more there (28,947 nodes: 488 ms).
TWO_GRID_NARROW_PASSES = 2
#: Neighbour rings of the band of :func:`_two_grid_set` around the carried cavity's fronts, from
#: :data:`TWO_GRID_WIDE_FROM` unknowns on (below: :data:`TWO_GRID_NARROW_RINGS`).
TWO_GRID_RINGS = 6
#: Unknowns from which the band of :func:`_two_grid_set` takes :data:`TWO_GRID_RINGS` rings.
TWO_GRID_WIDE_FROM = 50_000
#: Neighbour rings of the band of :func:`_two_grid_set` below :data:`TWO_GRID_WIDE_FROM` unknowns. The carried
#: cavity is wrong almost only on its front nodes (on the 5 x 5 dimples at 1e4 and 4e4 unknowns: 444 and 992
#: nodes, all on the front or one ring off it), and on these grids the fronts of the 25 dimples fill much of the
#: domain: six rings made the band about the whole grid.
TWO_GRID_NARROW_RINGS = 2
#: Active-set iterations of the band in each pass of :func:`_two_grid_set` at most.
TWO_GRID_ITERATIONS = 20


def _band_factorize(pattern: sp.csr_matrix, order: np.ndarray) -> Factorize:
    """The factorization of :func:`_band_set`'s band matrices (of ``pattern``) in the fill-reducing ``order``:
    banded LU (:func:`_factorize_banded`) where the band pays (:data:`bearingfe.core.banded.BAND_LIMITS`
    ``["front_band_lu"]``: the band around the fronts is thin, half-bandwidth 17-31 on the 5 x 5 dimples at
    100-200 cells per side; from 280 cells it is long enough for SuperLU to win), else SuperLU in it
    (:func:`_factorize_in_order`)."""
    order = np.asarray(order, np.int64)
    kd = half_bandwidth(pattern, order)
    pays = band_pays(pattern.shape[0], kd, "front_band_lu")
    return _factorize_banded(order, kd) if pays else _factorize_in_order(order)


def _two_grid_set(K: sp.csr_matrix, Gc: sp.csr_matrix, G: sp.csr_matrix, b: np.ndarray, cav: np.ndarray,
                  start: Callable[[], tuple], tol: float, p_c: float) -> np.ndarray:
    """The set a nested start carries (``cav``), iterated without a fine factorization: :func:`_band_set` on a
    band around its fronts (the unknowns with a neighbour of the other kind) from the coarse solution interpolated
    to the unknowns, each pass followed by the coarse-grid correction of the residual (the far field's response to
    the band's change, which is smooth), up to :func:`_two_grid_passes` passes; ``start()`` gives both, ``(y,
    correct)``, called only once the band is taken. Below :data:`TWO_GRID_FROM` unknowns a band whose matrices do
    not factor by banded LU is refused: ``cav`` as it is. The caller's global solves on the returned set decide
    convergence: this only changes which set is factorized first."""
    pattern = (abs(K) + abs(Gc)).tocsr()
    f = cav.astype(float)
    front = (pattern @ f > 0) & ~cav | (pattern @ (1.0 - f) > 0) & cav
    rings = TWO_GRID_RINGS if cav.size >= TWO_GRID_WIDE_FROM else TWO_GRID_NARROW_RINGS
    plan = _band_plan(pattern, _grown(front, pattern, rings))
    if cav.size < TWO_GRID_FROM and not isinstance(plan[2], _BandedLU):
        return cav
    y, correct = start()
    tol_p = tol * max(float(np.abs(np.where(cav, 0.0, y)).max(initial=0.0)), abs(p_c), 1e-300)
    return _band_set(K, Gc, G, b, cav, y, cav, tol, tol_p, correct, passes=_two_grid_passes(cav.size), converge=True,
                     iterations=TWO_GRID_ITERATIONS, pattern=pattern, plan=plan)


def _two_grid_passes(unknowns: int) -> int:
    """The passes of :func:`_two_grid_set`'s band at most for ``unknowns`` unknowns: :data:`TWO_GRID_PASSES` from
    :data:`TWO_GRID_WIDE_FROM` on, :data:`TWO_GRID_NARROW_PASSES` from :data:`TWO_GRID_FROM`, else
    :data:`TWO_GRID_BANDED_PASSES` (read at each call)."""
    if unknowns >= TWO_GRID_WIDE_FROM:
        return TWO_GRID_PASSES
    return TWO_GRID_NARROW_PASSES if unknowns >= TWO_GRID_FROM else TWO_GRID_BANDED_PASSES


def _takes_two_grid(unknowns: int) -> bool:
    """Whether a nested start of ``unknowns`` unknowns tries :func:`_two_grid_set`: from :data:`TWO_GRID_FROM`
    unknowns on, and from :data:`TWO_GRID_BANDED_FROM` where its band factors by banded LU (read at each call)."""
    return unknowns >= min(TWO_GRID_FROM, TWO_GRID_BANDED_FROM)


def _two_grid_flux(mesh: SupportMesh, couette: str) -> bool:
    """Whether a nested start with the Couette flux ``couette`` on ``mesh`` carries :func:`_two_grid_set`'s start:
    the grid flux; the streamline flux where :data:`TWO_GRID_STREAMLINE` and ``mesh``'s surface has no recesses
    (read at each call)."""
    if couette == "grid":
        return True
    return (couette == "streamline" and TWO_GRID_STREAMLINE and mesh.surface is not None
            and not mesh.surface.recesses)


def active_set(system: FVSystem, unk: FVUnknowns, p_fixed: np.ndarray, p_c: float, cavity: np.ndarray,
                factorize: Factorize, tol: float, max_iterations: int, fixed: bool = False,
                negative: bool = False, rough: int = 0, guess=None) -> _Solution:
    """Primal-dual active set (semismooth Newton on min(P, 1 - theta)) on the unknowns;
    ``fixed``: one solve on the given sets (no sign tests); ``negative``: return a converged cavity with
    ``theta < 0`` instead of raising (the streamline flux upwinds there and solves again); ``rough``: return
    the solution of the last set once the next one differs from it in at most this many unknowns (a nested
    start's coarse level, whose cavity the finer level moves by more anyway). A cycle raises
    :class:`JFOError` with the unknowns that switch in it as its ``switching`` attribute. ``guess``: a nested
    start's :func:`_two_grid_start` (called for ``(y, correct)``, the coarse solution on the unknowns (``P`` or
    ``theta`` by ``cavity``) and its coarse-grid correction of a residual, once a band is taken): from
    :data:`TWO_GRID_FROM` unknowns (:func:`_takes_two_grid`) the set is first iterated on a band around the fronts
    of ``cavity`` with those corrections (:func:`_two_grid_set`), before any factorization."""
    KII, GII, b = _reduced(system, unk, p_fixed, p_c)
    GcII = _reduced_cavity(system, unk, GII)
    cav = cavity.copy()
    seen: set[bytes] = set()
    scale = float(np.abs(b).max(initial=0.0)) or 1.0
    solver = _SetSolver(KII, GcII, factorize, unk)
    if guess is not None and not (fixed or rough) and _takes_two_grid(cav.size):
        cav = _two_grid_set(KII, GcII, GII, b, cav, guess, tol, p_c)
    for it in range(1, max_iterations + 1):
        full = ~cav
        rhs = -b - matvec(GII, full.astype(float))
        y = solver(cav, rhs)
        if not np.all(np.isfinite(y)):
            raise JFOError("the linear solve of the JFO active-set step returned non-finite values "
                           "(singular system: is every film region connected to a fixed-pressure edge?)")
        P = np.where(full, y, 0.0)
        theta = np.where(cav, y, 1.0)
        tol_p = tol * max(float(np.abs(P).max(initial=0.0)), abs(p_c), 1e-300)
        new = cav if fixed else np.where(cav, theta < 1.0 - tol, P < -tol_p)
        if (not (fixed or rough) and cav.size >= BAND_FROM and solver.base is not None and not np.array_equal(new, cav)
                and np.count_nonzero(new != solver.base) > LOW_RANK_SWITCHES):
            proposed = _band_set(KII, GcII, GII, b, cav, y, new, tol, tol_p, solver.solve)
            if not np.array_equal(proposed, cav) and np.packbits(proposed).tobytes() not in seen:
                new = proposed
        if np.array_equal(new, cav) or (rough and np.count_nonzero(new != cav) <= rough):
            if theta.min(initial=1.0) < -tol and not (negative or rough):
                raise JFOError(f"fill fraction theta = {theta.min():.3g} < 0 at the converged cavity: the "
                               "film empties faster than the Couette flow refills it (time step too long, "
                               "or a squeeze rate no oil film can follow)")
            res = matvec(KII, P) + matvec(GII, full.astype(float)) + matvec(GcII, np.where(cav, theta, 0.0)) + b
            return _Solution(p=P + p_c, theta=theta, cavity=cav, iterations=it,
                             residual=float(np.abs(res).max(initial=0.0)) / scale,
                             factorizations=solver.factorizations, solve=solver.solve)
        key = np.packbits(new).tobytes()
        if key in seen:
            error = JFOError(f"JFO active-set iteration cycles after {it} iterations "
                             f"({int(new.sum())} cavitated dofs); refine the mesh or warm-start closer")
            error.switching = np.flatnonzero(new != cav)
            raise error
        seen.add(np.packbits(cav).tobytes())
        cav = new
    error = JFOError(f"JFO active-set iteration did not converge in {max_iterations} iterations "
                     f"({int(cav.sum())} cavitated dofs); raise max_iterations or warm-start closer")
    error.switching = np.flatnonzero(new != cav)
    raise error


def _obstacle(system: FVSystem, unk: FVUnknowns, p_fixed: np.ndarray, p_c: float, cavity: np.ndarray,
              factorize: Factorize, tol: float, max_iterations: int) -> _Solution:
    """Swift-Stieber on the same discretization: theta = 1 everywhere, ``P >= 0``, multiplier
    ``lam = K P + G 1 + b >= 0`` (the oil the ruptured zone creates), ``P lam = 0``; primal-dual active set."""
    KII, GII, b = _reduced(system, unk, p_fixed, p_c)
    f = -(b + GII @ np.ones(b.size))
    cav = cavity.copy()
    seen: set[bytes] = set()
    scale = float(np.abs(f).max(initial=0.0)) or 1.0
    for it in range(1, max_iterations + 1):
        full = np.flatnonzero(~cav)
        P = np.zeros(b.size)
        if full.size:
            P[full] = np.asarray(factorize(KII[full][:, full].tocsc())(f[full]), float)
        lam = KII @ P - f
        lam[full] = 0.0
        tol_p = tol * max(float(np.abs(P).max(initial=0.0)), 1e-300)
        new = np.where(cav, lam > -tol * scale, P < -tol_p)
        if np.array_equal(new, cav):
            return _Solution(p=P + p_c, theta=np.ones(b.size), cavity=cav, iterations=it,
                             residual=float(np.abs((KII @ P - f)[full]).max(initial=0.0)) / scale)
        key = np.packbits(new).tobytes()
        if key in seen:
            raise JFOError(f"Swift-Stieber active-set iteration cycles after {it} iterations")
        seen.add(np.packbits(cav).tobytes())
        cav = new
    raise JFOError(f"Swift-Stieber active-set iteration did not converge in {max_iterations} iterations")


#: Limiter updates of ``couette="limited"`` at most (each one active-set solve, warm-started).
LIMITER_SWEEPS = 6


def _limited_solve(system: FVSystem, unk: FVUnknowns, p_fixed: np.ndarray, p_c: float, sol: _Solution,
                   factorize: Factorize, tol: float, max_iterations: int, ops: Operators):
    """``couette="limited"``: from the first-order solution, the limiter of the last theta frozen and the
    second-order flux solved implicitly (one linear complementarity problem, warm-started on the last
    cavity), until the limiter stops changing or after :data:`LIMITER_SWEEPS` updates. The returned system
    carries the flux of the final solution (its flows balance exactly)."""
    free = np.zeros(ops.n_dofs, bool)
    free[ops.interior] = True
    rec, C1 = system.reconstruction, system.C
    alpha = None
    if not np.any(sol.theta < 1.0):   # no cavity: theta = 1, nothing to reconstruct
        return system, sol
    for _sweep in range(LIMITER_SWEEPS):
        new = _limiter(rec, np.where(free, unk.S @ sol.theta, 1.0))
        if alpha is not None and np.abs(new - alpha).max() <= 1e-12:
            break
        alpha = new
        system = dataclasses.replace(system, C=(C1 + _limited_flux(rec, alpha)).tocsr())
        sol = active_set(system, unk, p_fixed, p_c, sol.cavity, factorize, tol, max_iterations)
    return system, sol


def _streamline_solve(system: FVSystem, unk: FVUnknowns, p_fixed: np.ndarray, p_c: float, cavity: np.ndarray,
                      factorize: Factorize, tol: float, max_iterations: int, ops: Operators, guess=None):
    """``couette="streamline"``: the active set on the streamline flux; where it ends with ``theta < 0`` or
    cycles (the flux is not positive: a cell's outflow takes theta of its neighbours), the segments out of
    those nodes take theta of their upwind node instead (first-order upwind, positive) and the problem is
    solved again, warm-started, up to :data:`STREAMLINE_PASSES` times. The upwinded set only grows, so the
    passes end. Returns the system of the final flux, the solution and the number of upwinded segments."""
    st = system.reconstruction
    n = ops.n_dofs
    free = np.zeros(n, bool)
    free[ops.interior] = True
    upwinded = np.zeros(st.up.size, bool)
    start = cavity
    for _ in range(STREAMLINE_PASSES):
        try:
            first, guess = guess, None   # a nested start's guess starts the first pass only
            sol = active_set(system, unk, p_fixed, p_c, cavity, factorize, tol, max_iterations, negative=True,
                             guess=first)
        except JFOError as error:
            switching = getattr(error, "switching", None)
            if switching is None or switching.size == 0:
                raise
            mark = np.zeros(unk.rep.size)
            mark[switching] = 1.0
            bad = matvec(unk.S, mark) > 0.5
            cavity = start
        else:
            bad = np.where(free, matvec(unk.S, sol.theta), 1.0) < -tol
            if not bad.any():
                return _effective(system, unk, sol.cavity), sol, int(upwinded.sum())
            cavity = sol.cavity
        new = upwinded | bad[st.up]
        if np.array_equal(new, upwinded):
            break
        upwinded = new
        C, C_cavity = st.matrices(n, upwinded)
        system = dataclasses.replace(system, C=C, C_cavity=C_cavity)
    raise JFOError("the streamline JFO solve keeps ending with theta < 0 or cycling after upwinding "
                   f"{int(upwinded.sum())} segments: the film empties faster than the Couette flow refills it "
                   "(time step too long, or a squeeze rate no oil film can follow); try couette='median'")


def _initial_cavity(system: FVSystem, unk: FVUnknowns, p_fixed: np.ndarray, p_c: float,
                    factorize: Factorize) -> np.ndarray:
    """Cavity guess: where the full-film (theta = 1) solution falls below p_c; factored in the order of the
    active-set matrices (:func:`_ordered_splu`, the order found here is theirs too): about half COLAMD's time
    from :data:`ORDERED_FROM` unknowns on."""
    KII, GII, b = _reduced(system, unk, p_fixed, p_c)
    rhs = -b - matvec(GII, np.ones(b.size))
    if factorize is factorize_splu:
        P = _full_film_banded(unk, KII, rhs)
        if P is not None:
            return P < 0
    K = KII.tocsc()
    if factorize is factorize_splu:
        factorize = _ordered_splu(unk, K, GII.tocsc())
    P = np.asarray(factorize(K)(rhs), float)
    return P < 0


def _full_film_banded(unk: FVUnknowns, K: sp.csr_matrix, rhs: np.ndarray) -> np.ndarray | None:
    """``K^-1 rhs`` by banded Cholesky in the reverse Cuthill-McKee order (:func:`bearingfe.core.banded.band_plan`,
    the plan kept on ``unk`` for ``K``'s pattern), the full-film system of :func:`_initial_cavity` (symmetric
    positive definite: the Poiseuille operator alone); None where ``K`` is not symmetric, the band does not pay
    (:data:`bearingfe.core.banded.BAND_LIMITS` ``["full_film_guess"]``; larger systems start from a coarse
    level, :data:`NESTED_MIN`, or keep SuperLU), or it is not positive definite."""
    if not band_worth_trying(K.shape[0], "full_film_guess"):
        return None
    K = sp.csr_matrix(K)
    K.sort_indices()
    kept = unk._order.get("band")
    if kept is not None and np.array_equal(kept[0], K.indptr) and np.array_equal(kept[1], K.indices):
        plan = kept[2]
    else:
        plan = band_plan(np.arange(K.nnz), K.indices, K.indptr, K.shape[0], kind="full_film_guess")
        unk._order["band"] = (K.indptr.copy(), K.indices.copy(), plan)
    if plan is None or not _symmetric(K):
        return None
    with dense_threads(1):
        solve = band_cholesky(plan, K.data)
        return None if solve is None else solve(rhs)


def _symmetric(K: sp.csr_matrix) -> bool:
    """Whether a CSR matrix with sorted indices equals its transpose: its arrays are those of the transpose in
    CSR (canonical), compared as they are (an explicit zero, or a repeated entry, without its mirror counts as a
    difference: none of the solver's matrices has one). 0.07 against 0.11 ms CPU (``(K != K.T).nnz``) at 433
    unknowns, 0.10 against 0.16 at 1,800 (the pocket pad's full-film matrix, mean of 500 calls)."""
    if K.shape[0] != K.shape[1]:
        return False
    T = csr_transposed(K)
    return (np.array_equal(T.indptr, K.indptr) and np.array_equal(T.indices, K.indices)
            and np.array_equal(T.data, K.data))


# -- the fill inside the box cells of a grid ------------------------------------------------

def _box_fill(mesh: SupportMesh, film: Film, system: FVSystem, theta: np.ndarray, wedge: float,
              samples: int = 8) -> tuple[float, float]:
    """Shear deficit ``int (1 - fill)/h`` and area ``int [fill < 1]`` of the emptied box cells of a grid.

    In a steady cavity the pressure is uniform, so the oil flux ``theta h`` is constant along ``phi``:
    inside the box of an emptied node the fill is ``min(1, theta_i hbar_i / h)``, with ``theta_i hbar_i``
    the flux through its downstream face (with a squeeze or a time step, the same rule neglects the
    change of the flux across one box). A box that straddles a rupture step thus keeps the full film on
    its upstream part (a box-wise ``theta_i`` would starve it, a bias of half a cell along every rupture
    line). Integrated by the midpoint rule on ``samples**2`` points per box.
    """
    g = system.faces
    n = theta.size
    hbar = np.full(n, np.nan)
    hbar[g.i if wedge >= 0 else g.j] = system.face_film
    emptied = np.flatnonzero(theta < 1.0 - 1e-12)
    deficit = cavity = 0.0
    for start in range(0, emptied.size, BOX_FILL_CHUNK):  # in blocks of boxes: arrays that stay in cache
        d, a = _box_fill_block(mesh, film, g.box, theta, hbar, emptied[start:start + BOX_FILL_CHUNK], samples)
        deficit, cavity = deficit + d, cavity + a
    return deficit, cavity


#: Emptied boxes :func:`_box_fill` integrates at a time (``samples**2`` points each: 64 x 4096 = 262,144 points, a
#: few MB per array; one block for all boxes took 0.81 s on 68,000 boxes, its arrays many times the cache).
BOX_FILL_CHUNK = 4096


def _box_fill_block(mesh: SupportMesh, film: Film, box: np.ndarray, theta: np.ndarray, hbar: np.ndarray,
                    emptied: np.ndarray, samples: int) -> tuple[float, float]:
    """:func:`_box_fill`'s two integrals over the boxes ``emptied`` (node indices)."""
    c = theta[emptied] * hbar[emptied]
    b = box[:, emptied]
    t = (np.arange(samples) + 0.5) / samples
    X = (b[0][:, None] + (b[1] - b[0])[:, None] * t).repeat(samples, axis=1)
    Z = np.tile(b[2][:, None] + (b[3] - b[2])[:, None] * t, (1, samples))
    h = _film_at(film, X, Z)
    surface = mesh.surface
    if surface is not None and getattr(surface, "recesses", ()):   # each recess tests the boxes near it
        h = h + _boxed_depth(surface, b[0], b[1], b[2], b[3], X, Z)   # not in place: h may be the film's array
    outlet = ~np.isfinite(c)   # no downstream face: box-wise (the mean film of those boxes only)
    if outlet.any():   # (c is this function's own array)
        c[outlet] = theta[emptied[outlet]] * h[outlet].mean(axis=1)
    w = ((b[1] - b[0]) * (b[3] - b[2]) / samples**2)[:, None]
    fill = np.divide(c[:, None], h)   # min(1, c / h), in place from here: no temporaries of all points
    np.minimum(fill, 1.0, out=fill)
    partial = fill < 1.0 - 1e-12
    term = np.subtract(1.0, fill, out=fill)
    np.multiply(w, term, out=term)
    deficit = float(np.sum(np.divide(term, h, out=term)))
    return deficit, float(np.sum(np.multiply(w, partial, out=term)))


# -- flows ------------------------------------------------------------------------------

def _facet_flux(mesh: SupportMesh, film: Film, wedge: float, grad_p: np.ndarray, theta: np.ndarray,
                facets) -> np.ndarray | dict[str, np.ndarray]:
    """Outward flux ``q . n`` through the half-facets of boundary ``facets``, per node; ``facets`` an array,
    or a dict of named arrays (one pass over all of them: their triangles found and the film evaluated once;
    a dict of the named results). The facets' geometry is kept on the mesh (:func:`_facet_frame`).

    ``grad_p`` is the (element-wise constant) P1 pressure gradient, shape (2, n_elements).
    """
    m = mesh.mesh
    named = facets if isinstance(facets, dict) else {None: facets}
    sizes = [np.size(f) for f in named.values()]
    n_nodes = m.nvertices   # (scikit-fem finds it at each call: the largest node number of t)
    results = {k: np.zeros(n_nodes) for k in named}
    every = np.concatenate([np.asarray(f, np.int64) for f in named.values()]) if named else np.zeros(0, np.int64)
    if every.size:
        fr = _facet_frame(mesh, every)
        n, u2 = fr.normal, fr.velocity
        g = grad_p[:, fr.elem]
        h2 = _thickness(mesh, film, fr.quarters[0], fr.quarters[1])
        ends = np.cumsum([0] + sizes)
        for side, node in enumerate((fr.a, fr.b)):
            part = slice(side * every.size, (side + 1) * every.size)
            h = h2[part]
            un = n[0] if u2 is None else u2[0][part] * n[0] + u2[1][part] * n[1]
            qn = -h**3 / 12.0 * np.sum(g * n, axis=0) + 0.5 * wedge * theta[node] * h * un
            contribution = 0.5 * fr.length * qn
            for k, lo, hi in zip(named, ends[:-1], ends[1:]):   # each group's own sums, in its facets' order
                np.add.at(results[k], node[lo:hi], contribution[lo:hi])
    return results if isinstance(facets, dict) else results[None]


@dataclass(frozen=True, eq=False)
class _FacetFrame:
    """The geometry of some boundary facets for :func:`_facet_flux`: their nodes, triangles, lengths, outward
    unit normals, the points a quarter along them from each end (``(2, 2 n)``: near ``a``, then near ``b``) and
    the runner's velocity there (None: along ``phi``)."""

    a: np.ndarray
    b: np.ndarray
    elem: np.ndarray
    length: np.ndarray
    normal: np.ndarray
    quarters: np.ndarray
    velocity: tuple | None


def _facet_frame(mesh: SupportMesh, facets: np.ndarray) -> _FacetFrame:
    """:class:`_FacetFrame` of the boundary ``facets`` (int64 array), kept on the mesh per facet list: a repeated
    solve on the mesh finds its flows' facets' triangles and normals once (the flows' facet fluxes of the pocket pad
    of docs/jfo_gmsh.md 0.12 against 0.25 ms CPU at 529 nodes, 0.14 against 0.41 at 7,375, mean of 300-2,000
    calls; the same numbers bit for bit)."""
    return mesh.cached(("finite_volume.facet_frame", facets.tobytes()), lambda: _build_facet_frame(mesh, facets))


def _build_facet_frame(mesh: SupportMesh, facets: np.ndarray) -> _FacetFrame:
    """:func:`_facet_frame` built afresh."""
    m = mesh.mesh
    a, b, elem, length, n = boundary_facets(m, facets)
    pa, pb = m.p[:, a], m.p[:, b]
    quarters = np.concatenate([0.75 * pa + 0.25 * pb, 0.25 * pa + 0.75 * pb], axis=1)   # near a, near b
    frame = _FacetFrame(a=a, b=b, elem=elem, length=length, normal=n, quarters=quarters,
                        velocity=velocity_at(mesh.runner, quarters))
    for x in (a, b, elem, length, n, quarters):   # shared by the solves on the mesh
        x.flags.writeable = False
    return frame


def _flows(mesh: SupportMesh, ops: Operators, film: Film, system: FVSystem, wedge: float,
           p: np.ndarray, theta: np.ndarray, created: bool = False,
           pockets: bool = False, grad_p: np.ndarray | None = None) -> tuple[dict[str, float], float]:
    """Boundary flows from the dual-cell balance of the boundary dofs (exactly conservative); with
    ``pockets`` also each pocket's own inflow under its name (not counted again in the balance).
    ``grad_p``: the P1 gradient of ``p`` per triangle, if the caller has it."""
    basis = ops.basis
    storage = system.storage * theta + system.source
    # outflow through interior segments + storage
    balance_rest = matvec(system.K, p) + matvec(system.C, theta) + storage
    outflow = -balance_rest   # what leaves a boundary dof's cell through the boundary
    groups = {k: ops.flow_groups[k][0] for k in edge_groups(mesh.boundaries)}
    count = np.zeros(basis.N)
    for d in groups.values():
        count[d] += 1
    if grad_p is None:
        grad_p = _interpolate(_cells(mesh, ops), p)[1]
    # the direct facet fluxes count at the corner dofs only: each group's facets that touch one (the same
    # sums, in the same order, as over all its facets)
    none = np.zeros(0, np.int64)
    direct = _facet_flux(mesh, film, wedge, grad_p, theta, {k: ops.facet_groups.get(k, none) for k in groups})
    corner = count > 1
    shared = np.zeros(basis.N)
    for k in groups:
        shared += direct[k]
    flows = {}
    for k, d in groups.items():
        c = corner[d]
        value = float(np.sum(outflow[d[~c]]))
        cd = d[c]
        value += float(np.sum(direct[k][cd] + (outflow[cd] - shared[cd]) / count[cd]))
        flows[k] = value
    flows["inlet"] = -float(np.sum(outflow[ops.inlet])) if ops.inlet.size else 0.0
    own = {name: -float(np.sum(outflow[d])) for name, d in _pocket_dofs(mesh, ops).items()} if pockets else {}
    flows["squeeze"] = float(np.sum(storage))
    if created:  # Swift-Stieber: the oil the ruptured zone creates (negative: flows into the film)
        flows["cavitation"] = -float(np.sum(balance_rest[ops.interior]))
    total_out = sum(v for k, v in flows.items() if k not in ("inlet", "squeeze"))
    # = minus the sum of the interior dofs' residuals: zero to solver tolerance
    return {**flows, **own}, flows["inlet"] - total_out - flows["squeeze"]


def _pressures(inlet_pressure):
    """The pocket pressure as a float, or one per pocket as a tuple of floats."""
    return tuple(map(float, inlet_pressure)) if isinstance(inlet_pressure, tuple) else float(inlet_pressure)


def _pocket_dofs(mesh: SupportMesh, ops: Operators) -> dict[str, np.ndarray]:
    """The dofs of each pocket's contour, by name (:func:`bearingfe.film.pockets.pocket_names`)."""
    from .pockets import pocket_names

    return {name: ops.basis.get_dofs(mesh.boundaries[name]).all() for name in pocket_names(mesh)}


def _pocket_values(mesh: SupportMesh, ops: Operators, inlet_pressure) -> np.ndarray:
    """The Dirichlet values: 0 on the outline, the pocket pressure (or each pocket's own) on the pockets."""
    p_fixed = np.zeros(ops.n_dofs)
    if not isinstance(inlet_pressure, tuple):
        p_fixed[ops.inlet] = inlet_pressure
        return p_fixed
    dofs = _pocket_dofs(mesh, ops)
    if len(dofs) != len(inlet_pressure):
        raise ValueError(f"inlet_pressure must give one value per pocket ({len(dofs)}: {', '.join(dofs)}), "
                         f"got {len(inlet_pressure)}")
    for d, value in zip(dofs.values(), inlet_pressure):
        p_fixed[d] = value
    return p_fixed


def _pocket_loads(mesh: SupportMesh, ops: Operators, inlet_pressure) -> np.ndarray:
    """``(int p, int p cos, int p sin)`` over the pockets (holes of the mesh) at their pressures."""
    if not isinstance(inlet_pressure, tuple):
        return inlet_pressure * ops.pocket_moments
    return sum(value * pocket_moments(ops.basis, mesh.boundaries[name])
               for name, value in zip(_pocket_dofs(mesh, ops), inlet_pressure))


# -- public entry point --------------------------------------------------------------------

def _check_inputs(mesh, film, element, wedge, squeeze, inlet_pressure, cavitation_pressure, dt, previous):
    if not isinstance(mesh, SupportMesh):
        raise ValueError(f"mesh must be a bearingfe.SupportMesh, got {type(mesh).__name__}")
    if element != "P1":
        raise ValueError(f"cavitation='jfo' supports element='P1' only (the finite-volume Couette flux "
                         f"is built on the P1 median dual), got element={element!r}")
    if mesh.geometry_order != 1:
        raise ValueError("cavitation='jfo' needs a straight-sided mesh (mesh_surface(..., order=1))")
    if not isinstance(film, Film):
        raise ValueError(f"film must implement the bearingfe.Film protocol, got {type(film).__name__}")
    try:
        sq = tuple(float(s) for s in squeeze)
        if len(sq) != 2:
            raise ValueError
    except (TypeError, ValueError):
        raise ValueError(f"squeeze must be a pair (gamma_rate, phi0_rate), got {squeeze!r}") from None
    pockets = inlet_pressure if isinstance(inlet_pressure, tuple) else (inlet_pressure,)
    inlet_pressure = min(pockets) if min(pockets) < 0 else max(pockets, key=abs)  # the one the checks need
    values = [float(wedge), *sq, float(inlet_pressure), float(cavitation_pressure)]
    if not np.all(np.isfinite(values)):
        raise ValueError(f"wedge, squeeze, inlet_pressure and cavitation_pressure must be finite, got {values}")
    check_operating_point(wedge, sq, inlet_pressure, cavitation_pressure)
    if inlet_pressure != 0.0 and not mesh.has_inlet:
        raise ValueError("inlet_pressure is non-zero but the mesh has no 'inlet' boundary (no pocket)")
    if cavitation_pressure > min(0.0, inlet_pressure):
        raise ValueError(f"cavitation_pressure must be <= the edge pressure 0 and the pocket pressure "
                         f"{inlet_pressure!r} (the film is full where oil is fed), got {cavitation_pressure!r}")
    if (dt is None) != (previous is None):
        raise ValueError("a time step needs both dt and previous (the result of the step before)")
    if dt is not None:
        if not (math.isfinite(float(dt)) and dt > 0):
            raise ValueError(f"dt must be a finite time step > 0, got {dt!r}")
        if not isinstance(previous, ReynoldsResult) or previous.theta is None:
            raise ValueError("previous must be a ReynoldsResult of cavitation='jfo' (it carries theta)")
        if previous.theta.shape != (operators(mesh, "P1").n_dofs,) or previous.basis.mesh is not mesh.mesh:
            raise ValueError("previous must be a solution on the same mesh")
        if sq != (0.0, 0.0):
            raise ValueError("with a time step the film change comes from previous.film -> film: "
                             f"squeeze must be (0, 0), got {squeeze!r}")
    return sq


def _warm_cavity(warm_start, ops: Operators, unk: FVUnknowns) -> np.ndarray | None:
    """Cavity mask on the unknowns from a previous result (same mesh, or another mesh of the same
    surface: nearest-node transfer, i.e. nested iteration) or from a boolean mask on the dofs."""
    if warm_start is None:
        return None
    if isinstance(warm_start, ReynoldsResult):
        if warm_start.cavitated is None:
            raise ValueError("warm_start must be a cavitated ReynoldsResult or a boolean mask "
                             f"of length {ops.n_dofs}")
        mask = warm_start.cavitated
        if warm_start.basis.N != ops.n_dofs or warm_start.basis.mesh is not ops.basis.mesh:
            from scipy.spatial import cKDTree

            _, nearest = cKDTree(warm_start.basis.doflocs.T).query(ops.basis.doflocs.T)
            mask = mask[nearest]
    else:
        mask = warm_start
    mask = np.asarray(mask, bool)
    if mask.shape != (ops.n_dofs,):
        raise ValueError(f"warm_start mask must have length {ops.n_dofs}, got shape {mask.shape}")
    return mask[unk.rep]


#: Mesh sources that are tensor grids aligned with ``phi`` when nothing refined them unevenly
#: (:func:`bearingfe.bearings.journal.structured_journal_mesh`): ``couette="auto"`` takes the grid flux on
#: them when their cells check out as a tensor grid.
TENSOR_SOURCES = ("grid", "structured")


def _auto_couette(mesh: SupportMesh) -> str:
    """``"grid"`` on tensor-grid meshes (``grid_mesh``, an unrefined structured journal mesh), ``"median"`` on
    meshes whose median dual is aligned with ``phi`` already (:data:`ALIGNED_SOURCES`), else ``"streamline"``."""
    if not is_along_phi(mesh.runner):
        return "streamline"
    if mesh.source in ALIGNED_SOURCES:
        return "median"
    if mesh.source not in TENSOR_SOURCES:
        return "streamline"
    try:
        _grid_faces(mesh)
    except ValueError:
        return "streamline"
    return "grid"


#: Unknowns from which a cold grid solve (``couette="grid"`` on ``grid_mesh``) starts from the cavity of the
#: same problem on the grid with every other line (nested iteration, recursively down to fewer unknowns).
#: Measured (best of 4 interleaved, load 0.3-0.8 on 2 cores; the 5 x 5 dimples of docs/jfo_dimples.md, the
#: pocket pad and the dimple of docs/jfo_gmsh.md): even below 4,000 nodes; from there on a win (pocket pad
#: 45.8 against 54.5 ms at 4,872 nodes, 101 against 187 ms at 9,840; the 5 x 5 dimples 150 against 163 ms
#: at 10,201, 628 against 751 ms at 40,401: 3 fine factorizations against 5), and the same fine
#: factorizations at 7.9e4 and 1.6e5 nodes (one more coarse level).
NESTED_MIN = 4000
#: A nested start's coarse level stops its active-set iteration once a step would switch at most this
#: fraction of its nodes (the finer level's own steps move the cavity by more: its discretization shifts
#: the fronts by a cell): a rough coarse cavity, not a converged one.
NESTED_ROUGH = 0.005
#: Weight of the full-film ``P / max P`` against the cavity's ``theta - 1`` in the sign carried from a nested
#: start's coarse level (see :func:`_nested_cavity`). ``P`` is small beside ``theta - 1`` (non-dimensional
#: 1e-3 .. 1e-2 against 0.1 .. 1 on the dimpled slider): unscaled, a fine node between a full and a cavitated
#: coarse node falls in the cavity, while the finer grid's cavity is the smaller one (its fronts move
#: inwards by about a coarse cell). Measured on the dimpled slider of docs/jfo_dimples.md (grid flux,
#: 200x200, 400x400 and 600x600 cells, rough coarse levels): fine factorizations 3, 3, 3 at weights 3, 10
#: and 30; 3, 4, 4 at 1e-4 (about the unscaled start); 3, 3, 4 at 1; 4, 4, 4 at 100.
NESTED_P_WEIGHT = 10.0
#: Whether a nested start's coarse levels integrate ``h^3`` over the grid cells a recess contour cuts by the
#: sub-cell means (:func:`_cell_means`), as the finest level does. Off: the coarse levels take the plain
#: quadrature there, their cavity only starts the finer level (measured on the 5 x 5 dimples of
#: docs/jfo_dimples.md at 1e4 .. 1.6e5 nodes: the same fine factorizations and answers to 1e-14, the coarse
#: levels' sub-cell sampling saved: 3-6 % of a cold solve at 1e4 .. 4e4 nodes, load 1 on 2 cores).
NESTED_CELL_MEANS = False
#: Whether the fixed dofs of a nested start's coarse level (edges, pockets: full film at their own pressure)
#: carry their ``P = p - p_c`` into the interpolated sign, as the unknowns do; without it they read 0, a front,
#: and every fine node between a coarse cavity node and a fed pocket's edge starts in the cavity. Measured on
#: the grooved journal of docs/jfo_gmsh.md on meshes refined at the groove (many fine nodes there): 2 against 4
#: fine factorizations at 2,548 nodes, 2 against 6 at 4,419, 1 against 6 at 7,731 (94 against 187 ms); the
#: other cases of that page and the 5 x 5 dimples the same counts (their edges are at or near ``p_c``).
#: Measured and left out: widening the carried cavity by a ring of neighbours (``|K|``'s pattern) where a level
#: iterates from it alone (below :data:`TWO_GRID_FROM`). On the 5 x 5 dimples of docs/jfo_dimples.md at 70 x 70
#: cells the carried set (1,393 unknowns: 250 not in the final cavity of 1,246, 103 of it missing) widens to a
#: superset that the active set shrinks in 2 fine factorizations against 3 (44 against 52 ms CPU, median of 8
#: interleaved, load ~8); but the carried sets of docs/jfo_gmsh.md's pocket pad (5,280 nodes) and of a journal
#: with a fed 20-degree groove (100 x 40 grid, 8,028 nodes) are within 25-36 nodes of their final ones, and the ring's
#: 150-170 extra nodes cost a factorization more (3 against 2). Widening only downstream (the upwind Couette
#: operator's neighbours) left every count as it was; only upstream took 3 against 2 on the journal and the
#: gmsh-page dimple.
NESTED_FIXED_SIGN = True


def _coarser_grid(mesh: SupportMesh) -> SupportMesh | None:
    """The grid mesh of ``mesh.surface`` on every other grid line of ``mesh`` (the outline's and the
    pockets' edges kept); None if ``mesh`` is not a ``grid_mesh`` or has too few lines to coarsen.

    Kept per mesh (while ``mesh`` lives; the coarser levels together have about a third of its nodes): a
    repeated cold solve on ``mesh`` reuses the coarse levels and what is cached on them (operators, faces,
    recess integrals, orders) instead of meshing and setting them up again."""
    return mesh.cached("finite_volume.coarser_grid", lambda: _coarser_lines(mesh))


def _coarser_lines(mesh: SupportMesh) -> SupportMesh | None:
    """:func:`_coarser_grid` built afresh."""
    from ..geometry import meshing

    surface = mesh.surface
    if mesh.source != "grid" or surface is None or not surface.is_rectangular:
        return None
    pockets = tuple(meshing._axis_rectangle(shape, k) for k, shape in enumerate(surface.inlets))
    a1, a2 = surface.arc
    a = surface.half_width
    known = tensor_lines(mesh)   # a whole grid's lines: the nodes' distinct coordinates, without sorting them
    lines = []
    for axis, keep in ((0, [a1, a2] + [x for r in pockets for x in r[:2]]),
                       (1, [-a, a] + [z for r in pockets for z in r[2:]])):
        u = np.unique(mesh.mesh.p[axis]) if known is None else known[axis]
        if u.size < 9:
            return None
        tol = 1e-9 * float(np.ptp(u))
        must = u[np.min(np.abs(u[:, None] - np.array(keep)[None, :]), axis=1) <= tol]
        lines.append(np.unique(np.concatenate([u[::2], must])))
    return meshing._grid_on_lines(surface, lines[0], lines[1], pockets, None)


#: A cold solve on an unstructured mesh (``couette`` ``"streamline"``, ``"median"`` or ``"limited"``) of
#: :data:`NESTED_MIN_UNSTRUCTURED` unknowns or more starts from the cavity of the same problem on a ``grid_mesh``
#: of the surface with about a quarter of its nodes (:func:`_grid_under`, the grid flux; itself nested from
#: :data:`NESTED_MIN` on).
NESTED_UNSTRUCTURED = True
#: Unknowns from which a cold solve on an unstructured mesh takes the nested start (:data:`NESTED_UNSTRUCTURED`):
#: lower than a grid's :data:`NESTED_MIN`, since the fine level's factorizations cost more there (the streamline
#: flux's wider stencil) while the coarse grid is a quarter of the nodes. Measured (docs/jfo_gmsh.md's cases,
#: uniform and contour-refined gmsh meshes, best of 4 interleaved, load 1 on 2 cores): even at about 1,500 nodes
#: (pocket pad 22.0 against 22.1 ms at 1,340 nodes, 16.6 against 19.2 ms at 963), a win from 2,000 on (pocket pad
#: 31.8 against 35.8 ms at 1,936 nodes, 45.7 against 70.2 at 2,952, 103 against 184 ms at 7,375 nodes: 2 against
#: 6 fine factorizations; the dimple 49 against 75 ms at 3,055 nodes). The threshold counts unknowns, not nodes:
#: lowered from 2,000 to 1,500 so that the meshes of about 1,950 nodes (1,744 and 1,804 unknowns) take it (CPU
#: time of cold solves, median of 7 interleaved, load 4 on 2 cores: pocket pad 22.9 against 28.4 ms at 1,936
#: nodes, 1 fine factorization against 3; the dimple 28.9 against 31.5 ms at 1,964 nodes), while the dimple at
#: 1,415 nodes (about 1,290 unknowns) does not gain (24.1 against 22.0 ms).
NESTED_MIN_UNSTRUCTURED = 1500


def _grid_under(mesh: SupportMesh) -> SupportMesh | None:
    """A ``grid_mesh`` of ``mesh.surface`` with about a quarter of ``mesh``'s nodes (cells twice the mean
    spacing), for the nested start of an unstructured mesh; None where there is no such grid (no surface,
    an outline or pockets a grid cannot follow, a runner not along ``phi``).

    Kept per mesh, as :func:`_coarser_grid`: a repeated cold solve on ``mesh`` reuses the grid and what is
    cached on it (operators, cells, unknowns, orders) instead of meshing and setting it up again (CPU of repeated
    cold solves of docs/jfo_gmsh.md's streamline pocket pad on one mesh, 3 interleaved process pairs of 30 solves,
    load ~5: 19.2-22.5 against 25.4-28.3 ms at 1,936 nodes; a fresh mesh the same)."""
    return mesh.cached("finite_volume.grid_under", lambda: _build_grid_under(mesh))


def _build_grid_under(mesh: SupportMesh) -> SupportMesh | None:
    """:func:`_grid_under` built afresh."""
    from ..geometry.meshing import grid_mesh

    surface = mesh.surface
    if surface is None or mesh.source == "grid" or not surface.is_rectangular or not is_along_phi(mesh.runner):
        return None
    area = surface.area - surface.inlet_area
    try:
        return grid_mesh(surface, 2.0 * math.sqrt(area / mesh.n_nodes))
    except ValueError:
        return None


def _nested_cavity(mesh: SupportMesh, film: Film, wedge: float, sq, inlet_pressure: float, p_c: float,
                   couette: str, cavitation: str, factorize: Factorize, tol: float, max_iterations: int,
                   ops: Operators, unk: FVUnknowns, guess: bool = True) -> tuple[np.ndarray | None, dict, tuple | None]:
    """Cavity to start a cold grid solve from: the converged cavity on the coarser grid
    (:func:`_coarser_grid`, itself started the same way), carried to the unknowns by the sign of the
    bilinear interpolation of ``P / max P`` (full film, weighted by :data:`NESTED_P_WEIGHT`) and ``theta - 1``
    (cavity); None where there is no coarser grid (or it fails: the caller starts cold). The coarse level
    stops its iteration early (:data:`NESTED_ROUGH`). With ``guess`` (a fine level that is not itself a rough
    coarse level) of the fluxes of :func:`_two_grid_flux` and from :data:`TWO_GRID_FROM` unknowns
    (:func:`_takes_two_grid`), also returns the start of :func:`_two_grid_set`: :func:`_two_grid_start` on this
    coarse level, which builds the coarse solution interpolated to the unknowns and its coarse-grid correction
    when called (else None)."""
    coarse = _coarser_grid(mesh) if couette == "grid" else _grid_under(mesh)
    if coarse is None:
        return None, {}, None
    try:
        _, cops, _, cunk, csol, _, info = _complementarity(coarse, film, wedge, sq, inlet_pressure, p_c, None, None,
                                                            "grid", cavitation, factorize, tol, max_iterations,
                                                            None, time.perf_counter(),
                                                            rough=int(NESTED_ROUGH * coarse.n_nodes))
    except JFOError:
        return None, {}, None
    # the sign of P (full film) or of theta - 1 (cavity), interpolated bilinearly from the coarse grid's
    # nodes: a front between two coarse nodes lands between them, where the coarse solution puts it
    P = csol.p - p_c
    scale = float(np.abs(P).max(initial=0.0)) or 1.0
    d = cunk.S @ np.where(csol.cavity, csol.theta - 1.0, NESTED_P_WEIGHT * P / scale)
    if NESTED_FIXED_SIGN:   # edges and pockets: full film at their own pressure (not 0, which reads as a front)
        d[cunk.fixed] = NESTED_P_WEIGHT * (_pocket_values(coarse, cops, inlet_pressure)[cunk.fixed] - p_c) / scale
    cp = cops.basis.doflocs
    lines = [np.unique(cp[0]), np.unique(cp[1])]
    values = np.zeros((lines[0].size, lines[1].size))   # nodes in pockets (holes) stay 0: no fine node reads them
    values[np.searchsorted(lines[0], cp[0]), np.searchsorted(lines[1], cp[1])] = d
    fine = ops.basis.doflocs[:, unk.rep]
    k = [np.clip(np.searchsorted(u, c, side="right") - 1, 0, u.size - 2) for u, c in zip(lines, fine)]
    t = [np.clip((c - u[i]) / (u[i + 1] - u[i]), 0.0, 1.0) for u, c, i in zip(lines, fine, k)]
    value = ((1 - t[0]) * (1 - t[1]) * values[k[0], k[1]] + t[0] * (1 - t[1]) * values[k[0] + 1, k[1]]
             + (1 - t[0]) * t[1] * values[k[0], k[1] + 1] + t[0] * t[1] * values[k[0] + 1, k[1] + 1])
    info = dict(info)
    info["nested_levels"] = info.get("nested_levels", 0.0) + 1.0
    info["coarse_iterations"] = info.get("coarse_iterations", 0.0) + float(csol.iterations)
    cavity = value < 0.0
    start = None
    if guess and _two_grid_flux(mesh, couette) and _takes_two_grid(unk.rep.size) and csol.solve is not None:
        start = functools.partial(_two_grid_start, coarse, cops, cunk, csol, inlet_pressure, p_c, cavity, lines,
                                  values.shape, k, t)
    return cavity, info, start


def _two_grid_start(coarse: SupportMesh, cops: Operators, cunk: FVUnknowns, csol: _Solution, inlet_pressure,
                    p_c: float, cavity: np.ndarray, lines: list, shape: tuple, k: list, t: list) -> tuple:
    """:func:`_two_grid_set`'s start from a nested start's coarse level (:func:`_nested_cavity`: its mesh,
    operators, unknowns and solution; its grid ``lines``, ``shape`` of the nodes' values on them, the unknowns'
    cells ``k`` and coordinates ``t`` in them): the coarse solution interpolated bilinearly to the unknowns (``P``
    in the full film, ``theta`` in ``cavity``) and the coarse-grid correction of a residual, ``(y, correct)``;
    built only once the band is taken."""
    unknowns = k[0].size
    cp = cops.basis.doflocs
    # the bilinear interpolation from the coarse dofs to the unknowns as a matrix (pocket holes: no column)
    index = np.full(shape, -1)
    index[np.searchsorted(lines[0], cp[0]), np.searchsorted(lines[1], cp[1])] = np.arange(cp.shape[1])
    rows = np.tile(np.arange(unknowns), 4)
    cols = np.concatenate([index[k[0], k[1]], index[k[0] + 1, k[1]], index[k[0], k[1] + 1],
                           index[k[0] + 1, k[1] + 1]])
    w = np.concatenate([(1 - t[0]) * (1 - t[1]), t[0] * (1 - t[1]), (1 - t[0]) * t[1], t[0] * t[1]])
    keep = cols >= 0
    I = sp.csr_matrix((w[keep], (rows[keep], cols[keep])), shape=(unknowns, cp.shape[1]))
    fixed = _pocket_values(coarse, cops, inlet_pressure)
    p_all = cunk.S @ (csol.p - p_c)
    p_all[cunk.fixed] = fixed[cunk.fixed] - p_c
    theta_all = cunk.S @ csol.theta
    theta_all[cunk.fixed] = 1.0
    y = np.where(cavity, I @ theta_all, I @ p_all)
    kept: list[sp.csr_matrix] = []   # the interpolation from the coarse unknowns and its transpose, at first use

    def correct(r: np.ndarray) -> np.ndarray:
        if not kept:
            Iu = (I @ cunk.S).tocsr()
            kept.extend((Iu, Iu.T.tocsr()))
        return kept[0] @ np.asarray(csol.solve(kept[1] @ r), float)

    return y, correct

def _complementarity(mesh: SupportMesh, film: Film, wedge: float, sq, inlet_pressure: float, p_c: float, dt,
                     previous, couette: str, cavitation: str, factorize: Factorize, tol: float,
                     max_iterations: int, warm_start, start: float, rough: int = 0):
    """Assembly and the complementarity solve of :func:`solve_jfo` (inputs checked, ``couette`` resolved);
    ``rough`` as in :func:`active_set` (the grid flux only: a nested start's coarse level, assembled without
    the cut cells' sub-cell means unless :data:`NESTED_CELL_MEANS`).
    Returns the time the assembly ended, the operators, system, unknowns, solution, the number of upwinded
    segments and the costs of a nested start."""
    ops = operators(mesh, "P1")
    system = _assemble(ops, mesh, film, wedge, sq, dt, previous, couette, rough=bool(rough) and not NESTED_CELL_MEANS)
    t1 = time.perf_counter()
    p_fixed = _pocket_values(mesh, ops, inlet_pressure)
    unk = _unknowns(mesh, ops)
    cavity = _warm_cavity(warm_start, ops, unk)
    upwinded, nested, guess = 0, {}, None
    if cavitation == "none":
        sol = active_set(system, unk, p_fixed, p_c, np.zeros(unk.rep.size, bool), factorize, tol, 1, fixed=True)
    else:
        if (cavity is None and dt is None and cavitation == "jfo"
                and (unk.rep.size >= NESTED_MIN if couette == "grid"
                     else NESTED_UNSTRUCTURED and unk.rep.size >= NESTED_MIN_UNSTRUCTURED)):
            cavity, nested, guess = _nested_cavity(mesh, film, wedge, sq, inlet_pressure, p_c, couette, cavitation,
                                            factorize, tol, max_iterations, ops, unk, guess=not rough)
        if cavity is None:
            cavity = _initial_cavity(system, unk, p_fixed, p_c, factorize)
            nested = dict(nested, first_guess_factorizations=1.0)  # beside the active set's own count
        if couette == "streamline" and cavitation == "jfo":
            system, sol, upwinded = _streamline_solve(system, unk, p_fixed, p_c, cavity, factorize, tol,
                                                      max_iterations, ops, guess=guess)
        elif cavitation == "jfo":
            sol = active_set(system, unk, p_fixed, p_c, cavity, factorize, tol, max_iterations, rough=rough,
                             guess=guess)
        else:
            sol = _obstacle(system, unk, p_fixed, p_c, cavity, factorize, tol, max_iterations)
        if couette == "limited" and cavitation == "jfo":
            system, sol = _limited_solve(system, unk, p_fixed, p_c, sol, factorize, tol, max_iterations, ops)
    return t1, ops, system, unk, sol, upwinded, nested


@takes(OperatingPoint, Discretization)
def solve_jfo(mesh: SupportMesh, film: Film, *, wedge: float = 1.0, squeeze=(0.0, 0.0),
              inlet_pressure: float = 0.0, cavitation_pressure: float = 0.0, element: str = "P1",
              sliding: float | None = None, solver: str | Factorize = "splu", warm_start=None,
              dt: float | None = None, previous: ReynoldsResult | None = None,
              tol: float = TOLERANCE, max_iterations: int = MAX_ITERATIONS,
              cavitation: str = "jfo", couette: str = "auto") -> ReynoldsResult:
    """Solve the film with mass-conserving (JFO / Elrod-Adams) cavitation.

    Parameters
    ----------
    mesh : SupportMesh
        Straight-sided mesh; recesses of ``mesh.surface`` deepen the film.
    film : Film
        Film thickness model (non-dimensional, units of c).
    wedge : float
        Entrainment factor: the Couette flux is ``wedge/2 theta h`` along phi.
    squeeze : (float, float)
        ``(gamma_rate, phi0_rate)`` per radian of shaft turn (steady squeeze term
        ``theta dh/dt``).
    inlet_pressure : float
        Pocket pressure ``p_s`` [-] (gauge, the edges are at 0).
    cavitation_pressure : float
        Cavity pressure ``p_c`` [-], gauge, ``<= 0`` (may be negative).
    element : {"P1"}
        Only P1: any other choice is refused with a ValueError.
    sliding : float, optional
        Sliding speed for the shear; default ``wedge``. The Couette shear acts
        on the oil fraction ``theta``.
    solver : str or callable
        Factorization of the non-symmetric active-set systems (``"splu"``).
    warm_start : ReynoldsResult or bool mask, optional
        Cavitated dofs of a previous solution: on the same mesh, or on another
        mesh of the same surface (transferred node by nearest node, e.g. from a
        coarser mesh: nested iteration).
    dt, previous : float, ReynoldsResult, optional
        One backward-Euler step of ``d(theta h)/dt`` from the JFO result
        ``previous`` (its film and theta) to ``film`` over ``dt`` [rad of
        shaft turn]; ``squeeze`` must then be zero.
    tol, max_iterations
        Sign tolerance and cap of the active-set iteration.
    cavitation : {"jfo", "reynolds", "none"}
        The same discretization with ``theta = 1``: ``"reynolds"``
        (Swift-Stieber, ``p >= p_c``; the oil it creates in the ruptured zone
        is booked as ``flows["cavitation"]``) and ``"none"`` (no pressure
        bound). :func:`bearingfe.solve_reynolds` uses them for recessed and
        periodic surfaces.
    couette : {"auto", "median", "grid", "limited", "streamline"}
        Discretization of the Couette flux ``wedge/2 theta h``. ``"median"``:
        through the median-dual segments of any straight P1 mesh (first-order
        upwinding smears fronts that run along ``phi`` sideways, by a width of
        order sqrt(mesh size)). ``"grid"``: through the faces of the box cells
        of a tensor-grid mesh (:func:`bearingfe.geometry.meshing.grid_mesh`,
        :func:`bearingfe.geometry.meshing.strip_mesh`), i.e. between ``phi``-neighbours
        only, with ``int h dz`` over each face exact across recess steps: no
        crosswind smearing. ``"limited"``: the median-dual segments with
        ``theta`` reconstructed linearly from the upwind node (its mean P1
        gradient, Barth-Jespersen limited) at each segment midpoint: second
        order where theta is smooth, much less sideways smearing on
        unstructured meshes, a few times the cost (the limiter is lagged:
        up to :data:`LIMITER_SWEEPS` warm-started solves). ``"auto"``:
        ``"grid"`` on tensor-grid meshes (``grid_mesh``, the structured
        journal mesh; :data:`TENSOR_SOURCES`), ``"median"`` on strip meshes
        (:data:`ALIGNED_SOURCES`), else ``"streamline"``.
        ``"streamline"``: the median-dual segments with ``theta`` at the
        foot of the sliding line through each segment midpoint on the edge of
        its triangle (linear, one active-set solve like ``"median"``): no
        crosswind smearing, so loads and flows of pockets, grooves and
        periodic seams converge at first order or better on gmsh meshes
        (docs/jfo_gmsh.md). A cavitated node on a recess contour refers its
        ``theta`` to its deepest film (each triangle takes the same oil flux
        ``theta h``); the error left is first order at recess contours (refine
        the mesh there; such results carry :data:`RECESS_JFO_NOTE`). The flux
        is not positive: where the solution ends with ``theta < 0`` or the
        active set cycles, the segments out of those nodes are upwinded and
        the problem solved again (at most :data:`STREAMLINE_PASSES` times;
        ``result.cost["upwinded_segments"]`` counts them). See
        ``docs/jfo.md``.

    Returns
    -------
    ReynoldsResult
        ``cavitation="jfo"``, ``theta`` (fill fraction at the dofs),
        ``cavitated`` (dofs at ``p = p_c``), ``cavitated_fraction`` (area with
        ``theta < 1`` over the film area), flows with their Couette and
        Poiseuille parts and ``mass_balance`` at solver tolerance. ``cost``:
        times [s] of the stages and counts: ``factorizations`` of the active
        set, ``first_guess_factorizations`` (1 where a cold start guessed its cavity
        from a full-film solve: on this grid, or on the coarsest grid of a
        nested start), the nested start's ``nested_levels`` and
        ``coarse_iterations``.

    Raises
    ------
    JFOError
        If the active-set iteration does not converge, cycles, or ends with ``theta < 0``.
    """
    start = time.perf_counter()
    if cavitation not in ("jfo", "reynolds", "none"):
        raise ValueError(f"cavitation must be 'jfo', 'reynolds' or 'none', got {cavitation!r}")
    sq = _check_inputs(mesh, film, element, wedge, squeeze, inlet_pressure, cavitation_pressure, dt, previous)
    if not (0 < tol < 1e-2):
        raise ValueError(f"tol must be in (0, 1e-2), got {tol!r}")
    if not (isinstance(max_iterations, int) and max_iterations >= 1):
        raise ValueError(f"max_iterations must be an integer >= 1, got {max_iterations!r}")
    if sliding is not None and not math.isfinite(float(sliding)):
        raise ValueError(f"sliding must be finite, got {sliding!r}")
    if couette not in COUETTE_FLUXES:
        raise ValueError(f"couette must be one of {COUETTE_FLUXES}, got {couette!r}")
    if couette == "auto":
        couette = _auto_couette(mesh)
    if couette == "grid" and not is_along_phi(mesh.runner):
        raise ValueError(f"couette='grid' carries the oil along phi only; the mesh's runner is {mesh.runner!r}: "
                         "use couette='streamline' (the default for it) or 'median'")
    factorize = factorize_splu if solver in ("splu", "splu_sym") else get_linear_solver(solver)
    p_c = float(cavitation_pressure)
    # the large arrays on small pages (bearingfe.core.pages: no wait for the kernel's compaction into huge pages)
    with small_pages():
        with dense_threads(1):   # SuperLU's solves call BLAS: threaded, its threads wait on a busy machine
            t1, ops, system, unk, sol, upwinded, nested = _complementarity(
                mesh, film, float(wedge), sq, _pressures(inlet_pressure), p_c, dt, previous, couette, cavitation,
                factorize, tol, max_iterations, warm_start, start)
        t2 = time.perf_counter()
        free = np.zeros(ops.n_dofs, bool)
        free[ops.interior] = True
        p_fixed = _pocket_values(mesh, ops, inlet_pressure)
        p = np.where(free, matvec(unk.S, sol.p), p_fixed)
        theta = np.where(free, matvec(unk.S, sol.theta), 1.0)
        cavitated = matvec(unk.S, sol.cavity.astype(float)) > 0.5
        cost = {"assembly": t1 - start, "cavitation": t2 - t1}
        result = _result(mesh, ops, film, system, float(wedge), sq, _pressures(inlet_pressure), p_c, sliding, p,
                         theta, cavitated, sol, cost, start, cavitation)
    # counts, not times: added after the postprocess time (the time left over from the timed entries)
    counts = dict(nested, **({"upwinded_segments": float(upwinded)}
                             if couette == "streamline" and cavitation == "jfo" else {}))
    if counts:
        result = dataclasses.replace(result, cost=MappingProxyType({**result.cost, **counts}))
    # a static solve notes its film's resolution (the smooth film: recess steps lie on element edges)
    return result if dt is not None else note_resolution(result, mesh, film, stacklevel=3)


def _phi_trig(mesh: SupportMesh, x0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``cos`` and ``sin`` of ``phi`` at the quadrature points ``x0`` ``(n_triangles, n_points)`` [rad] of
    ``mesh`` (the load's direction). On a whole tensor grid (:func:`~bearingfe.geometry.meshing.tensor_lines`:
    triangle ``c`` and ``c + (nx - 1)(nz - 1)`` split cell ``c = iz + (nz - 1) ix``), where every triangle of a
    grid column has the same ``phi`` at its points as the column's first of its half (checked: the same
    numbers), each column's are taken once and repeated along ``z``: the same values without a ``cos`` and a
    ``sin`` of every point (CPU, mean of 50 calls: 0.07 against 0.24 ms at 50 x 50 cells, 0.33 against 1.02 ms
    at 100 x 100)."""
    lines = tensor_lines(mesh)
    if lines is not None and x0.ndim == 2:
        nx, nz = lines[0].size - 1, lines[1].size - 1
        if x0.shape[0] == 2 * nx * nz and nz > 1:
            cells = x0.reshape(2, nx, nz, x0.shape[1])
            first = np.ascontiguousarray(cells[:, :, :1, :])
            if bool(np.all(cells == first)):
                return tuple(np.repeat(f(first), nz, axis=2).reshape(x0.shape) for f in (np.cos, np.sin))
    return np.cos(x0), np.sin(x0)


def _result(mesh, ops, film, system, wedge, sq, inlet_pressure, p_c, sliding, p, theta, cavitated, sol,
            cost, start, model) -> ReynoldsResult:
    basis = ops.basis
    cells = _cells(mesh, ops)
    x, dx = ops.x, cells.dx
    pq, dp = _interpolate(cells, p)
    flows, balance = _flows(mesh, ops, film, system, wedge, p, theta, created=model == "reynolds",
                            pockets=isinstance(inlet_pressure, tuple), grad_p=dp)
    dp = dp[:, :, None]
    sliding = wedge if sliding is None else float(sliding)
    area = system.area
    emptied = cavitated if model == "reynolds" else theta < 1.0 - 1e-12
    cav_fraction = float(np.sum(area[emptied]) / np.sum(area))
    buffer = np.empty(pq.shape)   # the terms of the sums over the quadrature points (_point_sum)
    if system.faces is not None and model == "jfo":   # grid: the fill inside each box cell (_box_fill)
        deficit, cavity = _box_fill(mesh, film, system, theta, wedge)
        inv_h, h, dp0 = system.inv_h_q, system.h_q, dp[0]
        friction = _point_sum(lambda b: (sliding * inv_h[b] + 0.5 * h[b] * dp0[b]) * dx[b], buffer) - sliding * deficit
        cav_fraction = cavity / float(np.sum(area))
    else:
        u = velocity_at(mesh.runner, x)
        speed2 = 1.0 if u is None else u[0] ** 2 + u[1] ** 2
        theta_q = _interpolate(cells, theta)[0]   # the median dual's shear (the grid's is the box fill's)
        friction = float(np.sum((theta_q * sliding * speed2 * system.inv_h_q
                                 + 0.5 * system.h_q * along(u, dp)) * dx))
    pm = _pocket_loads(mesh, ops, inlet_pressure)
    cos_x, sin_x = _phi_trig(mesh, x[0])
    force = np.array([_point_sum(lambda b: pq[b] * cos_x[b] * dx[b], buffer),
                      _point_sum(lambda b: pq[b] * sin_x[b] * dx[b], buffer)])
    force = force + pm[1:]
    integral = float(_point_sum(lambda b: pq[b] * dx[b], buffer) + pm[0])
    if isinstance(inlet_pressure, tuple):
        inlet_pressure = max(inlet_pressure)
    h_min = float(min(system.h_q.min(), _dof_thickness(mesh, film, np.asarray(basis.doflocs)).min()))
    notes = (f"cavitation={model!r} solves the direct (conservative) form with finite-volume Couette fluxes",)
    first_order_unstructured = system.couette == "median" and mesh.source not in ALIGNED_SOURCES
    if model == "jfo" and bool(np.any(emptied)):
        if first_order_unstructured:
            notes += (UNSTRUCTURED_JFO_NOTE,)
        elif system.couette == "streamline" and mesh.surface is not None and mesh.surface.recesses:
            notes += (RECESS_JFO_NOTE,)
    cost = dict(cost, postprocess=time.perf_counter() - start - sum(cost.values()), dofs=float(ops.n_dofs),
                mesh_operators=ops.seconds, active_set_residual=sol.residual, factorizations=float(sol.factorizations))
    return ReynoldsResult(
        basis=basis, pressure=p, film=film, wedge=wedge, squeeze=sq, inlet_pressure=inlet_pressure,
        formulation="direct", element="P1", force=force, integral=integral, h_min=h_min,
        flows=MappingProxyType(flows), mass_balance=float(balance), friction=friction,
        coercivity=math.nan, notes=notes, cost=MappingProxyType(cost), cavitation=model,
        iterations=sol.iterations if model != "none" else 0, cavitated=cavitated if model != "none" else None,
        theta=theta if model == "jfo" else None, cavitated_fraction=cav_fraction, cavitation_pressure=p_c,
        runner=runner_of(mesh))
