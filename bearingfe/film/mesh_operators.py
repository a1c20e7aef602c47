"""Everything about a mesh and an element that does not depend on the film, built once and cached on the mesh.

:class:`Operators` (:func:`operators`) holds the basis, the Dirichlet and interior
dofs, the boundary groups through which the flows leave, the pockets' moments and,
built on first use, the assemblies of the film system (:mod:`bearingfe.film.assembly`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from types import MappingProxyType
from typing import Mapping, NamedTuple

import numpy as np
import scipy.sparse as sp
import skfem
from skfem.mapping import MappingAffine
from skfem.quadrature import get_quadrature

from . import forms
from .assembly import ASSEMBLIES, DEFAULT_ASSEMBLY, Assembly
from .compiled import CompiledOperator
from .forms import mapping
from .flows import edge_groups
from ..core.blocks import blocks
from ..core.parameters import ELEMENTS
from ..geometry.meshing import SupportMesh

__all__ = ["Operators", "operators", "facet_basis", "facet_geometry", "facet_tables", "FacetTables",
           "quadrature_order", "LeanCellBasis", "pocket_moments", "affine_points", "boundary_facet_triangles",
           "BoundaryFacets", "boundary_facets"]


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
    basis: skfem.CellBasis  # a LeanCellBasis: its per-point arrays are built on first use
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
        """Quadrature-point coordinates, shape (2, n_elements, n_points) (built on first use; the same array as
        the compiled operator's points)."""
        def build():
            compiled = self._lazy.get(("assembly", "compiled"))
            if compiled is not None:
                return compiled.points
            b = self.basis
            if type(b.mapping) is MappingAffine and b.tind is None and b.mapping.dim == 2:
                return affine_points(b.mapping, b.X)
            return np.array(b.mapping.F(b.X, tind=b.tind))
        return self._get("x", build)

    def __post_init__(self) -> None:
        object.__setattr__(self, "_lazy", {})

    def _get(self, name: str, build):
        if name not in self._lazy:
            self._lazy[name] = build()
        return self._lazy[name]

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
        return self.assembly("compiled")

    def assembly(self, name: str = DEFAULT_ASSEMBLY) -> "Assembly":
        """The film-system assembly of :data:`bearingfe.film.assembly.ASSEMBLIES` by name, built on first use."""
        return self._get(("assembly", name), lambda: ASSEMBLIES[name](self))

    @property
    def corner_tables(self) -> tuple["FacetTables", Mapping[str, slice]]:
        """The basis functions, points, normals and weights on the facets of all :attr:`facet_groups` (in their
        order, :func:`facet_tables`) and, per group, the slice of its facets in them (for the compiled corner
        fluxes)."""
        def build():
            names = list(self.facet_groups)
            ends = np.cumsum([0] + [len(self.facet_groups[n]) for n in names])
            facets = np.concatenate([self.facet_groups[n] for n in names])
            tables = facet_tables(self.basis, facets, quadrature_order(self.element))
            return tables, MappingProxyType({n: slice(int(ends[k]), int(ends[k + 1])) for k, n in enumerate(names)})
        return self._get("corner_tables", build)

    @property
    def facet_bases(self) -> Mapping[str, skfem.FacetBasis]:
        """Facet bases of the outflow groups that share corner dofs (for the flows)."""
        return self._get("facet_bases", lambda: MappingProxyType({
            n: facet_basis(self.basis, f, quadrature_order(self.element))
            for n, f in self.facet_groups.items()}))


#: Cells :func:`affine_points` maps at a time (its temporaries, 2 x 16,384 x the points per cell, stay in cache).
AFFINE_BLOCK = 16384


def affine_points(mapping: MappingAffine, X: np.ndarray) -> np.ndarray:
    """The points ``F(X) = A X + b`` of a two-dimensional affine mapping at the reference points ``X``
    ``(2, n_points)``, shape ``(2, n_cells, n_points)`` (C order), in the same units as the mesh.

    The same numbers as scikit-fem's ``MappingAffine.F`` (``A[:, 0] X[0] + A[:, 1] X[1]``, then ``+ b``),
    computed block by block of :data:`AFFINE_BLOCK` cells into one array: its einsum, the sum with ``b`` and
    the copy each wrote an array as large as the answer (at 7.2e5 triangles x 6 points, 35 MB each, new
    memory the system has to supply: 0.24 s against 0.15 s per call, CPU time, one cold call each).
    """
    A, b = mapping.A, mapping.b
    n_cells = A.shape[2]
    out = np.empty((2, n_cells, X.shape[1]))
    for cells in blocks(n_cells, AFFINE_BLOCK):
        for i in range(2):
            o = out[i, cells]
            np.multiply(A[i, 0, cells, None], X[0], out=o)
            o += A[i, 1, cells, None] * X[1]
            o += b[i, cells, None]
    return out


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
    return mesh.cached(("operators", element), lambda: _build_operators(mesh, element))


def quadrature_order(element: str) -> int:
    """Quadrature order of the cell and facet integrals: ``2 k + 2`` for elements of degree ``k``."""
    return 6 if element == "P2" else 4


class LeanCellBasis(skfem.CellBasis):
    """A :class:`skfem.CellBasis` whose per-point arrays (the basis functions' values and gradients at the
    quadrature points, ``basis``, and the weights ``dx``) are computed on first use and can be dropped
    (:meth:`release`): the same numbers as scikit-fem's, without holding them for the life of the mesh.

    The compiled maps (:mod:`bearingfe.film.compiled`) keep what they need per element and release
    them; a rarer path that asks for them (the reference assembly, ``interpolate``) rebuilds them once.
    They are ``2 n_bfun + 1`` floats per quadrature point (the gradients and the weight; the values are
    broadcast): 7 for P1, 13 for P2.
    """

    def __init__(self, mesh: skfem.Mesh, elem: skfem.Element, mapping=None, intorder: int | None = None) -> None:
        rule = None if intorder is None else quadrature_rule(mesh.refdom, intorder)
        skfem.assembly.basis.AbstractBasis.__init__(self, mesh, elem, mapping, intorder, rule, mesh.refdom)
        self.tind = None
        self.nelems = mesh.nelements

    @property
    def basis(self) -> list:
        if self.__dict__.get("_values") is None:
            self.__dict__["_values"] = [self.elem.gbasis(self.mapping, self.X, j, tind=self.tind)
                                        for j in range(self.Nbfun)]
        return self.__dict__["_values"]

    @basis.setter
    def basis(self, value: list) -> None:
        self.__dict__["_values"] = value

    @property
    def dx(self) -> np.ndarray:
        if self.__dict__.get("_dx") is None:
            mapping = self.mapping
            if type(mapping) is MappingAffine and self.tind is None and np.ndim(self.W) == 1:
                # scikit-fem's |detDF| * W (detDF: the cell's determinant tiled over the points), written point
                # by point into the same layout (column-major: a point's weights in a row): the same numbers
                # without two temporaries of all points
                det = np.abs(mapping.detA)
                dx = np.empty((self.W.size, det.size))
                for k, w in enumerate(self.W):
                    np.multiply(det, w, out=dx[k])
                self.__dict__["_dx"] = dx.T
            else:
                self.__dict__["_dx"] = (np.abs(mapping.detDF(self.X, tind=self.tind))
                                        * np.broadcast_to(self.W, (self.nelems, self.W.shape[-1])))
        return self.__dict__["_dx"]

    @dx.setter
    def dx(self, value: np.ndarray) -> None:
        self.__dict__["_dx"] = value

    @property
    def quadrature_shape(self) -> tuple[int, int]:
        """``(n_cells, n_points)``: the shape of ``dx`` (without building it)."""
        return (int(self.nelems), int(np.shape(self.W)[-1]))

    def release(self) -> None:
        """Drop the per-point arrays (rebuilt on the next use)."""
        self.__dict__["_values"] = self.__dict__["_dx"] = None
        self._global_coordinates = self._mesh_parameters = None


def _build_operators(mesh: SupportMesh, element: str) -> Operators:
    start = time.perf_counter()
    m = mesh.mesh
    basis = LeanCellBasis(m, ELEMENTS[element](), mapping=mapping(m), intorder=quadrature_order(element))
    bnd = mesh.boundaries
    if "outer" not in bnd:
        raise ValueError("mesh has no boundary named 'outer'")
    outer = facet_dofs(basis, bnd["outer"])
    inlet = facet_dofs(basis, bnd["inlet"]) if "inlet" in bnd else np.zeros(0, dtype=np.int64)
    free = np.ones(basis.N, bool)
    free[outer] = False
    free[inlet] = False
    interior = np.flatnonzero(free)   # np.setdiff1d(arange, np.union1d(outer, inlet))'s answer without their sorts
    names = edge_groups(bnd)
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
        pocket_moments=pocket_moments(basis, bnd.get("inlet")),
        phi_range=phi_range, eigen_bound=eigen_bound, seconds=time.perf_counter() - start)


def facet_dofs(basis: skfem.CellBasis, facets: np.ndarray) -> np.ndarray:
    """The dofs on ``facets`` of a triangle mesh's basis, sorted: those of their vertices and their own
    (``basis.get_dofs(facets).all()``, the same array, by a mask instead of scikit-fem's views and sort)."""
    if basis.mesh.dim() != 2:  # (edge dofs, which 3-D meshes have, are not counted here)
        return basis.get_dofs(facets).all()
    f = np.asarray(facets)
    nodal, own = np.asarray(basis.nodal_dofs), np.asarray(basis.facet_dofs)
    on = np.zeros(basis.N, dtype=bool)
    on[nodal[:, basis.mesh.facets[:, f]].ravel()] = True
    if own.size:  # (P1 has none)
        on[own[:, f].ravel()] = True
    return np.flatnonzero(on).astype(np.result_type(nodal, own))


def _flow_groups(basis, bnd, names) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Boundary dofs per outflow group; dofs shared by two groups (corners) count half to each."""
    dofs = {n: facet_dofs(basis, bnd[n]) for n in names}
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
    shared = np.concatenate([d[w < 1] for d, w in groups.values()] or [np.zeros(0, np.int64)])   # (repeats: marks)
    vertex_dofs = np.asarray(basis.nodal_dofs)
    every_dof = vertex_dofs.shape[1] == basis.N   # (P1: the vertex dofs, distinct, are all the dofs; no search)
    if vertex_dofs.shape[0] != 1 or not (every_dof or np.isin(shared, vertex_dofs[0]).all()):
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


#: Quadrature rules by reference domain and integration order, tabulated on first use (scikit-fem
#: recomputes them for every basis; they are constants, shared read-only by the bases).
_RULES: dict = {}


def quadrature_rule(refdom, intorder: int) -> tuple[np.ndarray, np.ndarray]:
    """scikit-fem's quadrature rule ``(points, weights)`` of order ``intorder`` on ``refdom``, computed once."""
    key = (refdom, intorder)
    if key not in _RULES:
        _RULES[key] = get_quadrature(refdom, intorder)
    return _RULES[key]


def facet_basis(basis: skfem.CellBasis, facets: np.ndarray, intorder: int) -> skfem.FacetBasis:
    """A facet basis of ``basis``'s element and map on ``facets`` (its dof numbering and a tabulated
    quadrature rule: the same basis scikit-fem would build, without recomputing either)."""
    return skfem.FacetBasis(basis.mesh, basis.elem, mapping=basis.mapping, facets=facets, dofs=basis.dofs,
                            quadrature=quadrature_rule(basis.mesh.brefdom, intorder))


class FacetTables(NamedTuple):
    """A cell basis's functions and map at the quadrature points of some facets (:func:`facet_tables`)."""

    dofs: np.ndarray     # (n_bfun, n_facets): the dofs of each facet's triangle
    tables: np.ndarray   # (3, n_bfun, n_facets, n_points): the basis functions' values, d/dphi and d/dz
    x: np.ndarray        # (2, n_facets, n_points): the points
    normals: np.ndarray  # (2, n_facets, n_points): the outward normals
    dx: np.ndarray       # (n_facets, n_points): the weights (Jacobian included)


def _facet_points(basis: skfem.CellBasis, facets: np.ndarray, intorder: int):
    """``(cells, Y, x, normals, dx)`` on ``facets``: each facet's triangle (scikit-fem's first), the points in
    its reference coordinates and in the plane, the outward normals and the weights; the calls a
    :class:`skfem.FacetBasis` makes (one side, facets given as an array)."""
    m, mapping = basis.mesh, basis.mapping
    X, W = quadrature_rule(m.brefdom, intorder)
    find = np.asarray(facets)
    cells = boundary_facet_triangles(m, find)   # the triangle of each facet, which orients the normals
    own = _facet_map(mapping, find)
    if own is None:
        x, det = mapping.G(X, find=find), mapping.detDG(X, find=find)
    else:   # scikit-fem's G and detDG on these facets' map
        B, c, det_b = own
        x, det = (np.einsum("ijk,jl", B, X).T + c.T).T, np.tile(det_b, (X.shape[-1], 1)).T
    Y = mapping.invF(x, tind=cells)
    normals = mapping.normals(Y, cells, find, m.t2f)
    dx = np.abs(det) * np.broadcast_to(W, (find.size, W.shape[-1]))
    return cells, Y, np.asarray(x), np.asarray(normals), dx


def _facet_map(mapping, find: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """scikit-fem's affine boundary map of a triangle mesh, ``(B, c, detB)`` of shapes ``(2, 1, n)``, ``(2, n)``
    and ``(n,)``, on the facets ``find`` only: its own formulas (``c = p[:, a]``, ``B = p[:, b] - p[:, a]``,
    ``detB = sqrt(B_00^2 + B_10^2)``, elementwise: the same numbers as its slices), where it has not built the map
    of every facet yet (which a pocket contour's few facets would pay for: 0.09 ms of the 0.2 ms of the pocket
    moments at the pocket pad grid's 432 nodes, CPU, mean of 500 fresh meshes). None for another map or where
    scikit-fem's is at hand."""
    if type(mapping) is not MappingAffine or mapping.dim != 2 or hasattr(mapping, "_B"):
        return None
    m = mapping.mesh
    a, b = m.facets[0, find], m.facets[1, find]
    B = np.empty((2, 1, find.size))
    c = np.empty((2, find.size))
    for i in range(2):
        c[i] = m.p[i, a]
        B[i, 0] = m.p[i, b] - m.p[i, a]
    return B, c, np.sqrt(B[0, 0] ** 2 + B[1, 0] ** 2)


def boundary_facet_triangles(m: skfem.Mesh, facets: np.ndarray) -> np.ndarray:
    """The triangle of each of the boundary ``facets`` of a triangle mesh: scikit-fem's facet-to-triangle map
    ``m.f2t[0, facets]`` where the mesh has it already, else read off scikit-fem's triangle-to-facet map ``t2f``
    where the mesh has that (:func:`_facet_owners`), else found among the triangles with two nodes on the facets
    (the map of every facet costs 3 ms at 7,375 nodes, built for a pocket contour's 80 facets; these triangles
    0.1 ms). Facets that are not each an edge of exactly one triangle (interior facets) take the map.
    """
    facets = np.asarray(facets)
    if hasattr(m, "_f2t") or facets.size == 0:   # scikit-fem's cache of the map
        return m.f2t[0, facets]
    if hasattr(m, "_t2f"):
        found = _facet_owners(m.t2f, facets, m.facets.shape[1])
        return m.f2t[0, facets] if found is None else found
    n = np.int64(m.nvertices)   # (scikit-fem's nvertices is the largest node number of t, found at each call)
    a, b = m.facets[:, facets].astype(np.int64)
    t = m.t[:3]
    mark = np.zeros(n, bool)
    mark[a], mark[b] = True, True
    m0, m1, m2 = mark[t[0]], mark[t[1]], mark[t[2]]
    cand = np.flatnonzero((m0 & m1) | (m2 & (m0 | m1)))   # the triangles with two nodes or more on the facets
    tc = t[:, cand].astype(np.int64)
    keys = np.minimum(a, b) * n + np.maximum(a, b)          # each facet's node pair
    order = np.argsort(keys)
    sorted_keys = keys[order]
    found = np.full(facets.size, -1, np.int64)
    count = np.zeros(facets.size, np.int64)
    for i, j in ((0, 1), (1, 2), (2, 0)):                   # each candidate's three edges
        edge = np.minimum(tc[i], tc[j]) * n + np.maximum(tc[i], tc[j])
        at = np.minimum(np.searchsorted(sorted_keys, edge), keys.size - 1)
        hit = sorted_keys[at] == edge
        np.add.at(count, order[at[hit]], 1)
        found[order[at[hit]]] = cand[hit]
    if not np.all(count == 1):   # a facet of two triangles (or of none, or a repeated facet): the map
        return m.f2t[0, facets]
    return found


def _facet_owners(t2f: np.ndarray, facets: np.ndarray, n_facets: int) -> np.ndarray | None:
    """The triangle of each of ``facets`` from scikit-fem's triangle-to-facet map ``t2f`` (``(3, n_triangles)``):
    where a triangle's entry names one of them; None where one of them is the facet of other than exactly one
    triangle, or is repeated (the same answers as the node-pair search of :func:`boundary_facet_triangles`, in
    0.013 against 0.062 ms CPU for a pocket's 16 facets at 529 nodes, about the same at 7,375)."""
    wanted = np.zeros(n_facets, bool)
    wanted[facets] = True
    if np.count_nonzero(wanted) != facets.size:   # a repeated facet
        return None
    flat = t2f.ravel()
    at = np.flatnonzero(wanted[flat])          # the entries (facet slot, triangle) of the wanted facets
    if at.size != facets.size:                 # then each wanted facet has one entry where each has one or more
        return None
    owner = np.full(n_facets, -1, np.int64)
    owner[flat[at]] = at % t2f.shape[1]
    found = owner[facets]
    return found if np.all(found >= 0) else None


class BoundaryFacets(NamedTuple):
    """Straight boundary facets of a triangle mesh (:func:`boundary_facets`), in the units of the mesh."""

    a: np.ndarray        # (n_facets,) first node (scikit-fem's facet order)
    b: np.ndarray        # (n_facets,) second node
    elem: np.ndarray     # (n_facets,) the facet's triangle
    length: np.ndarray   # (n_facets,)
    normal: np.ndarray   # (2, n_facets) outward unit normal (away from the triangle)


def boundary_facets(m: skfem.Mesh, facets: np.ndarray) -> BoundaryFacets:
    """The nodes, triangle (:func:`boundary_facet_triangles`), length and outward unit normal of each of the
    boundary ``facets`` of a straight triangle mesh ``m``: the tangent ``b - a`` turned and pointed away from the
    triangle's centroid (the one home of this normal: the flows' facet fluxes and the pockets' moments)."""
    facets = np.asarray(facets)
    a, b = m.facets[:, facets]
    elem = boundary_facet_triangles(m, facets)
    pa, pb = m.p[:, a], m.p[:, b]
    tvec = pb - pa
    length = np.linalg.norm(tvec, axis=0)
    n = np.array([tvec[1], -tvec[0]]) / length
    centre = m.p[:, m.t[:3, elem]].mean(axis=1)
    n[:, np.sum(n * (0.5 * (pa + pb) - centre), axis=0) < 0] *= -1
    return BoundaryFacets(a=a, b=b, elem=elem, length=length, normal=n)


def facet_geometry(basis: skfem.CellBasis, facets: np.ndarray, intorder: int
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The quadrature points, outward normals and weights on ``facets`` of the map of ``basis``:
    ``(x, n, dx)`` of shapes ``(2, n_facets, n_points)`` twice and ``(n_facets, n_points)``.

    The same calls and numbers as :func:`facet_basis`'s ``global_coordinates()``, ``normals`` and ``dx``,
    without the basis functions at the points, which an integral of geometric quantities does not need.
    """
    return _facet_points(basis, facets, intorder)[2:]


def facet_tables(basis: skfem.CellBasis, facets: np.ndarray, intorder: int) -> FacetTables:
    """The basis functions of an H1 element (values and gradients), the points, normals and weights on
    ``facets``: the numbers of :func:`facet_basis` (``basis[j][0]``, its ``grad``, ``global_coordinates()``,
    ``normals``, ``dx``) from the same calls, without the facet basis object (the map's inverse Jacobian
    computed once for all the basis functions, not once for each)."""
    cells, Y, x, normals, dx = _facet_points(basis, facets, intorder)
    invDF = basis.mapping.invDF(Y, cells)
    tables = np.empty((3, basis.Nbfun, *dx.shape))
    for j in range(basis.Nbfun):
        phi, dphi = basis.elem.lbasis(Y, j)
        tables[0, j] = np.broadcast_to(phi, dx.shape)
        tables[1:, j] = np.einsum("ijkl,ikl->jkl", invDF, dphi)
    return FacetTables(dofs=np.asarray(basis.dofs.element_dofs)[:, cells], tables=tables, x=x, normals=normals,
                       dx=dx)


def pocket_moments(basis: skfem.CellBasis, inlet_facets) -> np.ndarray:
    """Area and first trigonometric moments of the pocket regions.

    The pockets are holes in the mesh, so their integrals come from the
    divergence theorem on the pocket contours: with n the film's outward
    normal (pointing into the pocket),
    ``int_P 1 = -oint phi n_phi``, ``int_P cos = -oint sin(phi) n_phi``,
    ``int_P sin = oint cos(phi) n_phi``.

    (Computing them from the facets' ends instead of scikit-fem's facet map saved 0.15 ms at 529 nodes but moved
    them by round-off, 2.7e-16, which the pump's quasi-static elastic transient carries to 1.2e-9 of a rate, past
    its pinned numbers: not done.)
    """
    if inlet_facets is None or len(inlet_facets) == 0:
        return np.zeros(3)
    x, n, dx = facet_geometry(basis, np.asarray(inlet_facets), 8)  # only the points, normals and weights
    phi, nphi = x[0], n[0]
    return np.array([-np.sum(phi * nphi * dx), -np.sum(np.sin(phi) * nphi * dx), np.sum(np.cos(phi) * nphi * dx)])
