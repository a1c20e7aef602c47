"""Fill-reducing orderings of symmetric sparsity patterns, found without factorizing (nested dissection).

SuperLU (scipy) orders by minimum degree or COLAMD; on the large 2-D meshes of
this project nested dissection fills less (``O(n log n)`` entries in the factor
against the faster-growing fill of minimum degree) and, unlike the orderings
inside SuperLU, can be found without factorizing: the compiled path factors a
fresh mesh's matrix once, in the order found here, instead of a first time to
learn the order (:meth:`bearingfe.film.compiled.CompiledOperator.factorize_condensed`).

:func:`nested_dissection` bisects the graph recursively with vertex separators,
all the parts of one level at once (vectorized numpy and ``scipy.sparse.csgraph``):
each connected part is split at the median of the levels of a breadth-first search
from a pseudo-peripheral vertex; with vertex coordinates, at the median of its
longer extent instead (recursive coordinate bisection, cheaper and better on this
project's meshes). The separator is the smallest of three covers of the edges
between the halves: either half's vertices that touch the other, or each such
edge's end with more of them. Parts up to ``leaf`` vertices are ordered along the
last cut; separators come after the parts they separate, the deepest first.

Measured (``benchmarks/orderings.py``, docs/benchmarks.md): by coordinates, the
order costs 0.2-0.3 of the numeric factorization that follows it and the factors
fill 0.73x minimum degree's at 1e6 P1 unknowns; from the graph alone it costs
about as much as the factorization and fills less only from ~1e5 unknowns on
P1 and structured P2 meshes, never on gmsh P2 meshes up to 3e5.

The permutation ``order`` is such that ``A[order][:, order]`` is factored with
``permc_spec="NATURAL"`` (see :func:`bearingfe.core.linalg.factorize_splu_sym`).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import breadth_first_order, connected_components

__all__ = ["nested_dissection", "grid_dissection", "LEAF_SIZE", "NESTED_DISSECTION_FROM"]

#: Parts of at most this many vertices are not split further (measured on the grid P1 matrix of 1e5
#: unknowns, by coordinates: fill 2 % above that of 8, 3 % below that of 32).
LEAF_SIZE = 16

#: Unknowns from which the package orders by :func:`nested_dissection` (by the dofs' coordinates)
#: instead of SuperLU's minimum degree on ``A^T + A``. Measured (benchmarks/orderings.py, fill of
#: SuperLU's factors against minimum degree's): P1 0.92 (gmsh) and 1.05 (grid) at 1e4 unknowns, 0.80
#: and 0.88 at 1e5, 0.74 and 0.80 at 3e5, 0.73 (grid) at 1e6; P2 1.13 (gmsh) and 1.08 (grid) at 1e4,
#: 1.02 and 0.83 at 1e5, 0.93 and 0.74 at 3e5. From here on it also spares the compiled path the factorization that finds minimum
#: degree's order: the first solve on a fresh 1e5-unknown mesh took 0.68x (P1) and 0.44x (P2) the time.
NESTED_DISSECTION_FROM = 50_000


def _graph(pattern: sp.spmatrix) -> sp.csr_matrix:
    """The adjacency of a square pattern: ``A + A^T`` structure without the diagonal, CSR, sorted."""
    if not sp.issparse(pattern):
        raise ValueError(f"pattern must be a scipy sparse matrix, got {type(pattern).__name__}")
    if pattern.ndim != 2 or pattern.shape[0] != pattern.shape[1]:
        raise ValueError(f"pattern must be square, got shape {pattern.shape}")
    A = sp.csr_matrix(pattern)
    A = sp.csr_matrix((np.ones(A.nnz, dtype=np.int8), A.indices, A.indptr), shape=A.shape)
    G = (A + A.T).tocoo()
    off = G.row != G.col
    n = A.shape[0]
    return sp.csr_matrix((np.ones(int(off.sum()), dtype=np.int8), (G.row[off], G.col[off])), shape=(n, n))


def nested_dissection(pattern: sp.spmatrix, coordinates: np.ndarray | None = None,
                      leaf: int = LEAF_SIZE) -> np.ndarray:
    """A nested-dissection order of a symmetric sparsity pattern.

    Parameters
    ----------
    pattern : scipy sparse matrix, shape (n, n)
        Its structure (values ignored) is symmetrized: ``A + A^T``.
    coordinates : array (d, n) or (n, d), optional
        Vertex positions (any unit): parts are then cut at the median of their
        longer extent (recursive coordinate bisection) instead of at the middle
        of a breadth-first search from a pseudo-peripheral vertex.
    leaf : int
        Parts of at most this many vertices are not split (>= 2).

    Returns
    -------
    order : int array (n,)
        A permutation: ``A[order][:, order]`` is the reordered matrix (the vertex
        eliminated k-th is ``order[k]``).
    """
    if not (isinstance(leaf, (int, np.integer)) and leaf >= 2):
        raise ValueError(f"leaf must be an integer >= 2 (vertices), got {leaf!r}")
    G = _graph(pattern)
    n = G.shape[0]
    xy = None
    if coordinates is not None:
        xy = np.asarray(coordinates, dtype=float)
        if xy.ndim == 2 and xy.shape[0] == n and xy.shape[1] != n:
            xy = xy.T
        if xy.ndim != 2 or xy.shape[1] != n:
            raise ValueError(f"coordinates must have shape (d, {n}) or ({n}, d), got {np.shape(coordinates)}")
        if not np.all(np.isfinite(xy)):
            raise ValueError("coordinates must be finite")
    # the edges, each once (i < j) with coordinates, both ways (for the searches) without
    rows = np.repeat(np.arange(n, dtype=np.int32), np.diff(G.indptr))
    cols = G.indices.astype(np.int32)
    if xy is not None:
        upper = rows < cols
        rows, cols = rows[upper], cols[upper]
    active = np.ones(n, dtype=bool)
    side = np.zeros(n, dtype=np.int8)
    ones = np.ones(cols.size + n) if xy is None else None
    leaves: list[np.ndarray] = []
    separators: list[np.ndarray] = []
    # seq: the active vertices, each part contiguous; starts: where each part begins (and the end)
    seq = np.arange(n, dtype=np.int64)
    starts = np.array([0, n], dtype=np.int64)
    while seq.size:
        if xy is None:  # parts are the connected components (a level cut may leave several)
            # the graph's CSR arrays with room for a virtual vertex n (the searches' sources)
            indptr = np.zeros(n + 2, dtype=np.int32)
            np.cumsum(np.bincount(rows, minlength=n), out=indptr[1:n + 1])
            indices = np.empty(cols.size + n, dtype=np.int32)
            indices[:cols.size] = cols
            graph_parts = (ones, indices, indptr)
            graph = _csr(ones[:cols.size], cols, indptr[:n + 1], n)
            _, component = connected_components(graph, directed=True, connection="strong")
            seq = seq[np.argsort(component[seq], kind="stable")]
            cut = np.flatnonzero(np.diff(component[seq])) + 1
            starts = np.concatenate([[0], cut, [seq.size]]).astype(np.int64)
        size = np.diff(starts)
        part = np.repeat(np.arange(size.size), size)
        small = (size <= leaf)[part]
        if small.any():
            leaves.append(seq[small])
            active[seq[small]] = False
            seq = seq[~small]
            size = size[size > leaf]
            starts = np.concatenate([[0], np.cumsum(size)])
            part = np.repeat(np.arange(size.size), size)
        if not seq.size:
            break
        count = size.size
        if xy is None:
            value = _bfs_levels(graph_parts, seq, starts, part, n).astype(float)
            lo = np.zeros(count)
            extent = np.maximum.reduceat(value, starts[:-1]) + 1.0
        else:
            low = np.stack([np.minimum.reduceat(c[seq], starts[:-1]) for c in xy])
            high = np.stack([np.maximum.reduceat(c[seq], starts[:-1]) for c in xy])
            axis = np.argmax(high - low, axis=0)
            value = xy[axis[part], seq]
            lo = low[axis, np.arange(count)]
            extent = np.maximum((high - low)[axis, np.arange(count)], 1e-300) * (1.0 + 1e-9)
        # sort within each part by its value: the key is the part plus the value scaled into [0, 1)
        key = part + np.clip((value - lo[part]) / extent[part], 0.0, 1.0 - 1e-12)
        sort = np.argsort(key, kind="stable")
        seq, part = seq[sort], part[sort]
        within = np.arange(seq.size) - starts[part]
        right = within >= (size // 2)[part]
        side[seq] = np.where(right, 2, 1)
        # a separator covers every edge between the sides (every edge joins two vertices of one part:
        # the separators found so far are gone). Three covers, per part the smallest: the vertices of
        # the left side that touch the right, those of the right, and for each crossing edge its end
        # with more crossing edges (thinner where the sides interlock, as P2 dofs do)
        crossing = side[rows] != side[cols]
        r, c = rows[crossing], cols[crossing]
        degree = np.bincount(r, minlength=n) + np.bincount(c, minlength=n)
        touching = np.zeros(n, dtype=bool)
        touching[r] = True
        touching[c] = True
        greedy = np.zeros(n, dtype=bool)
        take_r = degree[r] >= degree[c]
        greedy[r[take_r]] = True
        greedy[c[~take_r]] = True
        t, g = touching[seq], greedy[seq]
        candidates = np.stack([t & ~right, t & right, g])
        sizes = np.stack([np.bincount(part[m], minlength=count) for m in candidates])
        separator = candidates[np.argmin(sizes, axis=0)[part], np.arange(seq.size)]
        separators.append(seq[separator])
        active[seq[separator]] = False
        side[seq] = 0
        keep = ~separator
        seq, label = seq[keep], 2 * part[keep] + right[keep]
        cut = np.flatnonzero(np.diff(label)) + 1
        starts = np.concatenate([[0], cut, [seq.size]]).astype(np.int64)
        live = active[rows] & active[cols]
        rows, cols = rows[live], cols[live]
    return np.concatenate(leaves + separators[::-1]).astype(np.int64) if n else np.zeros(0, dtype=np.int64)


def grid_dissection(index: np.ndarray, leaf: int = LEAF_SIZE) -> np.ndarray:
    """A nested-dissection order of the vertices of a tensor grid, in closed form from their line numbers.

    Each box of grid lines is cut at the middle line of its longer side (in lines), that line's vertices in
    the box being the separator, until a box holds at most ``leaf`` vertices: the recursive coordinate
    bisection :func:`nested_dissection` does by coordinates, without the graph. The order is valid for any
    pattern; it is a dissection where every edge joins vertices on the same or neighbouring lines in each
    direction (P1 on a grid, with or without its diagonals; boxes with holes, e.g. a grid's pockets, too).

    Parameters
    ----------
    index : int array (2, n)
        The grid line numbers of each vertex along the two axes (any non-negative integers).
    leaf : int
        Boxes of at most this many vertices are not cut (>= 2).

    Returns
    -------
    order : int array (n,)
        A permutation, as :func:`nested_dissection`'s: leaves first, then the separators, the deepest first.
    """
    if not (isinstance(leaf, (int, np.integer)) and leaf >= 2):
        raise ValueError(f"leaf must be an integer >= 2 (vertices), got {leaf!r}")
    index = np.asarray(index)
    if index.ndim != 2 or index.shape[0] != 2 or not np.issubdtype(index.dtype, np.integer):
        raise ValueError(f"index must be an integer array of shape (2, n), got {index.dtype} {index.shape}")
    n = index.shape[1]
    if n == 0:
        return np.zeros(0, dtype=np.int64)
    index = index.astype(np.int64)
    lo = index.min(axis=1)[:, None]
    hi = index.max(axis=1)[:, None] + 1
    vertex = np.arange(n, dtype=np.int64)   # the vertices still to place, and the box of each
    box = np.zeros(n, dtype=np.int64)
    leaves: list[np.ndarray] = []
    separators: list[np.ndarray] = []
    while vertex.size:
        count = np.bincount(box, minlength=lo.shape[1])
        small = (count <= leaf)[box]
        if small.any():
            leaves.append(vertex[small][np.argsort(box[small], kind="stable")])
            vertex, box = vertex[~small], box[~small]
            if not vertex.size:
                break
        extent = hi - lo
        boxes = np.arange(lo.shape[1])
        axis = (extent[1] > extent[0]).astype(np.int64)
        mid = lo[axis, boxes] + extent[axis, boxes] // 2
        axis_of = axis[box]   # per vertex: its box's cut axis and line, gathered once
        line, mid_of = index[axis_of, vertex], mid[box]
        cut = line == mid_of
        on = vertex[cut]      # the separators' other line number: gathered for them alone
        sep = np.lexsort((index[1 - axis_of[cut], on], box[cut]))
        separators.append(on[sep])
        right = line > mid_of
        keep = ~cut
        vertex, box = vertex[keep], 2 * box[keep] + right[keep]
        # the children's boxes: the left one ends at the cut line, the right one starts after it
        lo2, hi2 = np.repeat(lo, 2, axis=1), np.repeat(hi, 2, axis=1)
        hi2[axis, 2 * boxes] = mid
        lo2[axis, 2 * boxes + 1] = mid + 1
        lo, hi = lo2, hi2
    return np.concatenate(leaves + separators[::-1])


def _last_per_label(labels: np.ndarray, order: np.ndarray, count: int) -> np.ndarray:
    """For each label ``0..count-1``, the last vertex of ``order`` that carries it."""
    position = np.full(count, -1, dtype=np.int64)
    np.maximum.at(position, labels[order], np.arange(order.size, dtype=np.int64))
    return order[position]


def _csr(data, indices, indptr, n: int) -> sp.csr_matrix:
    """A CSR matrix from arrays known to be canonical (rows sorted, no duplicates): no checks, no copies."""
    graph = sp.csr_matrix((data, indices, indptr), shape=(n, n), copy=False)
    graph.has_sorted_indices = True
    graph.has_canonical_format = True
    return graph


def _bfs(graph_parts, sources: np.ndarray, n: int):
    """Breadth-first order and levels from several sources at once (a virtual vertex ``n`` joined to
    every source); returns the order (sources first) and the level of each vertex in it.

    ``graph_parts`` = (ones, indices, indptr) of the graph with room for the virtual vertex's row at
    the end of ``indices`` (its entries are written here)."""
    ones, indices, indptr = graph_parts
    end = int(indptr[n - 1 + 1]) if n else 0
    indices[end:end + sources.size] = sources
    indptr[n + 1] = end + sources.size
    graph = _csr(ones[:end + sources.size], indices[:end + sources.size], indptr, n + 1)
    order, parent = breadth_first_order(graph, n, directed=True, return_predecessors=True)
    order = order[1:]
    position = np.empty(n + 1, dtype=np.int64)
    position[order] = np.arange(order.size)
    position[n] = -1
    # parents' positions do not decrease along a breadth-first order: level L + 1 starts at the
    # first vertex whose parent is at or after the start of level L
    parent_position = position[parent[order]]
    bounds = [0]
    while True:
        nxt = int(np.searchsorted(parent_position, bounds[-1], side="left"))
        if nxt >= order.size:
            break
        bounds.append(nxt)
    level = np.searchsorted(np.asarray(bounds), np.arange(order.size), side="right") - 1
    return order, level


def _bfs_levels(graph_parts, seq, starts, part, n):
    """Levels (per vertex of ``seq``) of a breadth-first search in each connected part from a
    pseudo-peripheral vertex: the last vertex reached from the part's first vertex."""
    order, _ = _bfs(graph_parts, seq[starts[:-1]], n)
    label = np.full(n, -1, dtype=np.int64)
    label[seq] = part
    far = _last_per_label(label, order, starts.size - 1)
    order, level = _bfs(graph_parts, far, n)
    out = np.empty(n, dtype=np.int64)
    out[order] = level
    return out[seq]

