"""Points on a triangle mesh: which cell holds a point, field values there, and cell sizes.

One home for the mesh queries the solvers share:

- :func:`containing_cells`: the triangle that holds each point (-1 if none),
  from a k-d tree of the centroids and barycentric tests on the nearest ones;
- :func:`nearest_cells`: the same, falling back to the nearest centroid for
  points just outside (round-off on curved edges);
- :func:`probe_matrices`: sparse maps from the dofs of a scikit-fem basis to
  the value and the two gradient components of a field at given points (also on
  curved ``MeshTri2`` meshes, for which scikit-fem has no element finder);
- :func:`probes`: the value map alone (``basis.probes`` that works on curved meshes);
- :func:`cell_diameters`: the longest edge of each triangle.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["containing_cells", "nearest_cells", "barycentric", "probe_matrices", "probes", "cell_diameters"]

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


def nearest_cells(p: np.ndarray, t: np.ndarray, points: np.ndarray, candidates: int = 8) -> np.ndarray:
    """As :func:`containing_cells`, but a point in no candidate gets the cell of the nearest centroid."""
    found, nearest = _search(p, np.asarray(t)[:3], np.asarray(points, float), candidates)
    return np.where(found >= 0, found, nearest)


def probe_matrices(basis, x: np.ndarray) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
    """Sparse maps ``(n, basis.N)`` from dofs to the value and the gradient ``(d/dphi, d/dz)`` of a field
    at the points ``x`` (2, n). Cells are found on the straight triangles of the mesh's vertices; the
    reference coordinates then come from the basis's own (possibly curved) mapping."""
    x = np.asarray(x, float)
    m = basis.mesh
    cells = nearest_cells(m.p, m.t, x)
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


def cell_diameters(mesh) -> np.ndarray:
    """Longest edge of each (vertex) triangle of a scikit-fem mesh."""
    p, t = mesh.p, mesh.t[:3]
    edges = [np.linalg.norm(p[:, t[i]] - p[:, t[(i + 1) % 3]], axis=0) for i in range(3)]
    return np.max(edges, axis=0)
