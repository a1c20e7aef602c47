"""Points on a triangle mesh: which cell holds a point, field values there, and cell sizes.

One home for the mesh queries the solvers share:

- :func:`containing_cells`: the triangle that holds each point (-1 if none),
  from a k-d tree of the centroids and barycentric tests on the nearest ones;
- :func:`lattice_cells`: the same for the nodes of a uniform lattice, by visiting
  each triangle's bounding box (no search);
- :func:`nearest_cells`: the same, falling back to the nearest centroid for
  points just outside (round-off on curved edges);
- :func:`probe_matrices`: sparse maps from the dofs of a scikit-fem basis to
  the value and the two gradient components of a field at given points (also on
  curved ``MeshTri2`` meshes, for which scikit-fem has no element finder);
- :func:`probes`: the value map alone (``basis.probes`` that works on curved meshes);
- :func:`values_in_cells`: a P1 or P2 field's values at points whose straight cells are known (no search);
- :func:`cell_diameters`: the longest edge of each triangle.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["containing_cells", "lattice_cells", "nearest_cells", "barycentric", "probe_matrices", "probes",
           "values_in_cells", "cell_diameters"]

#: Barycentric slack of the inside test: a point on an edge belongs to both cells.
INSIDE_TOLERANCE = 1e-10


def barycentric(p: np.ndarray, t: np.ndarray, cells: np.ndarray, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Barycentric coordinates ``(l1, l2)`` of ``points`` (2, n) in the straight triangles ``t[:, cells]``
    of the vertices ``p``: the point is ``a + l1 (b - a) + l2 (c - a)``."""
    a, b, c = (p[:, t[i, cells]] for i in range(3))
    v0, v1, v2 = b - a, c - a, points - a
    det = v0[0] * v1[1] - v0[1] * v1[0]
    l1 = (v2[0] * v1[1] - v2[1] * v1[0]) / det
    l2 = (v0[0] * v2[1] - v0[1] * v2[0]) / det
    return l1, l2


def _search(p: np.ndarray, t: np.ndarray, points: np.ndarray, candidates: int):
    from scipy.spatial import cKDTree  # here: scipy.spatial is a tenth of a second to import

    centroids = p[:, t].mean(axis=1)
    k = min(candidates, t.shape[1])
    _, near = cKDTree(centroids.T).query(points.T, k=k)
    near = np.reshape(near, (points.shape[1], k))
    out = np.full(points.shape[1], -1)
    for j in range(k):
        e = near[:, j]
        l1, l2 = barycentric(p, t, e, points)
        tol = INSIDE_TOLERANCE
        inside = (l1 >= -tol) & (l2 >= -tol) & (l1 + l2 <= 1 + tol) & (out < 0)
        out[inside] = e[inside]
    return out, near[:, 0]


def containing_cells(p: np.ndarray, t: np.ndarray, points: np.ndarray, candidates: int = 12) -> np.ndarray:
    """Index of the straight triangle ``(p, t[:3])`` containing each point (2, n); -1 if none among the
    ``candidates`` nearest by centroid."""
    return _search(p, np.asarray(t)[:3], np.asarray(points, float), candidates)[0]


def lattice_cells(p: np.ndarray, t: np.ndarray, origin, step, shape) -> np.ndarray:
    """The straight triangle ``(p, t[:3])`` holding each node ``origin + (i step[0], k step[1])`` of a
    lattice of ``shape = (nx, nz)`` nodes, as an array ``(nx, nz)`` (-1 where none does).

    Each triangle visits the lattice nodes of its bounding box (barycentric test, as
    :func:`containing_cells`): no search, ``O(cells + nodes)`` when the lattice is about as fine as the
    mesh. A node on an edge shared by two triangles gets one of them."""
    t = np.asarray(t)[:3]
    (ox, oz), (hx, hz), (nx, nz) = origin, step, shape
    v = p[:, t]                                                    # (2, 3, n)
    i0 = np.maximum(np.ceil((v[0].min(axis=0) - ox) / hx - 1e-9).astype(np.int64), 0)
    i1 = np.minimum(np.floor((v[0].max(axis=0) - ox) / hx + 1e-9).astype(np.int64), nx - 1)
    k0 = np.maximum(np.ceil((v[1].min(axis=0) - oz) / hz - 1e-9).astype(np.int64), 0)
    k1 = np.minimum(np.floor((v[1].max(axis=0) - oz) / hz + 1e-9).astype(np.int64), nz - 1)
    wide = np.maximum(k1 - k0 + 1, 0)
    counts = np.maximum(i1 - i0 + 1, 0) * wide
    cells = np.repeat(np.arange(t.shape[1]), counts)
    j = np.arange(cells.size) - np.repeat(np.cumsum(counts) - counts, counts)
    i = i0[cells] + j // wide[cells]
    k = k0[cells] + j % wide[cells]
    l1, l2 = barycentric(p, t, cells, np.array([ox + i * hx, oz + k * hz]))
    tol = INSIDE_TOLERANCE
    inside = (l1 >= -tol) & (l2 >= -tol) & (l1 + l2 <= 1 + tol)
    out = np.full(nx * nz, -1)
    out[i[inside] * nz + k[inside]] = cells[inside]
    return out.reshape(nx, nz)


def nearest_cells(p: np.ndarray, t: np.ndarray, points: np.ndarray, candidates: int = 8) -> np.ndarray:
    """As :func:`containing_cells`, but a point in no candidate gets the cell of the nearest centroid."""
    found, nearest = _search(p, np.asarray(t)[:3], np.asarray(points, float), candidates)
    return np.where(found >= 0, found, nearest)


def probe_matrices(basis, x: np.ndarray, cells: np.ndarray | None = None
                   ) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
    """Sparse maps ``(n, basis.N)`` from dofs to the value and the gradient ``(d/dphi, d/dz)`` of a field
    at the points ``x`` (2, n). Cells are found on the straight triangles of the mesh's vertices
    (:func:`nearest_cells`), unless the caller has them (``cells``, one per point, e.g. from
    :func:`containing_cells`); the reference coordinates then come from the basis's own (possibly curved)
    mapping."""
    x = np.asarray(x, float)
    m = basis.mesh
    if cells is None:
        cells = nearest_cells(m.p, m.t, x)
    elif np.shape(cells) != (x.shape[1],) or np.min(cells, initial=0) < 0:
        raise ValueError(f"cells must hold one cell (>= 0) per point ({x.shape[1]}), got shape {np.shape(cells)}")
    ref = basis.mapping.invF(x[:, :, None], tind=cells)
    rows = np.tile(np.arange(x.shape[1]), basis.Nbfun)
    cols = basis.element_dofs[:, cells].ravel()
    fields = [basis.elem.gbasis(basis.mapping, ref, k, tind=cells)[0] for k in range(basis.Nbfun)]
    out = []
    for values in ([np.asarray(f)[:, 0] for f in fields], [f.grad[0][:, 0] for f in fields],
                   [f.grad[1][:, 0] for f in fields]):
        out.append(sp.coo_matrix((np.concatenate(values), (rows, cols)), shape=(x.shape[1], basis.N)).tocsr())
    return tuple(out)


def probes(basis, x: np.ndarray) -> sp.csr_matrix:
    """``basis.probes(x)``, also on curved ``MeshTri2`` meshes (the value map of :func:`probe_matrices`)."""
    import skfem

    if not isinstance(basis.mesh, skfem.MeshTri2):
        return basis.probes(x)
    return probe_matrices(basis, x)[0]


def values_in_cells(basis, u: np.ndarray, points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """Values of a field at points whose cells are known: the Lagrange shape functions of a P1 or P2 basis on
    straight triangles at the points' barycentric coordinates (:func:`barycentric`) in their cells, without the
    element search and the reference mapping of :func:`probes` (e.g. at the dofs of a mesh split from
    ``basis``'s, each in its parent triangle: :func:`~bearingfe.geometry.meshing.split_parents`).

    Parameters
    ----------
    basis : skfem.CellBasis
        ``ElementTriP1`` or ``ElementTriP2`` on a straight-sided ``MeshTri1``.
    u : numpy.ndarray
        The field's dof values, shape ``(basis.N,)`` [any unit].
    points : numpy.ndarray
        Shape ``(2, n)``, in the mesh's coordinates.
    cells : numpy.ndarray of int
        Shape ``(n,)``: a triangle holding each point (a point outside its cell gets the polynomial's
        extension).

    Returns
    -------
    numpy.ndarray
        Shape ``(n,)``, in the unit of ``u``.
    """
    import skfem

    if type(basis.mesh) is not skfem.MeshTri1 or type(basis.elem) not in (skfem.ElementTriP1, skfem.ElementTriP2):
        raise ValueError("basis must be ElementTriP1 or ElementTriP2 on a straight MeshTri1, got "
                         f"{type(basis.elem).__name__} on {type(basis.mesh).__name__}")
    u, points, cells = np.asarray(u), np.asarray(points, float), np.asarray(cells)
    if u.shape != (basis.N,):
        raise ValueError(f"u must have shape ({basis.N},), got {u.shape}")
    if points.ndim != 2 or points.shape[0] != 2 or cells.shape != (points.shape[1],):
        raise ValueError(f"points must have shape (2, n) and cells (n,), got {points.shape} and {cells.shape}")
    m = basis.mesh
    l1, l2 = barycentric(m.p, m.t, cells, points)
    l0 = 1.0 - l1 - l2
    v = u[basis.element_dofs[:, cells]]  # rows: the vertices, then (P2) the facets (0, 1), (1, 2), (0, 2)
    if v.shape[0] == 3:
        return v[0] * l0 + v[1] * l1 + v[2] * l2
    return (v[0] * l0 * (2 * l0 - 1) + v[1] * l1 * (2 * l1 - 1) + v[2] * l2 * (2 * l2 - 1)
            + 4 * (v[3] * l0 * l1 + v[4] * l1 * l2 + v[5] * l0 * l2))


def cell_diameters(mesh) -> np.ndarray:
    """Longest edge of each (vertex) triangle of a scikit-fem mesh."""
    p, t = mesh.p, mesh.t[:3]
    edges = [np.linalg.norm(p[:, t[i]] - p[:, t[(i + 1) % 3]], axis=0) for i in range(3)]
    return np.max(edges, axis=0)
