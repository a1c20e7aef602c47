r"""Compiled film operator: the film-independent linear maps of a mesh and element, built once.

Everything the Reynolds equation needs from a film state enters through a few
fields at the quadrature points (``h^3`` or ``D``, the sources, ``h`` and its
gradient). What does not depend on the film is built once per
``(mesh, element)``:

- the interpolation maps ``E`` (values) and ``G_phi``, ``G_z``
  (gradients) from dofs to the ``n_q`` quadrature points (:attr:`CompiledOperator.maps`);
- the sparsity pattern of the system matrix and the scatters
  ``S_stiff``, ``S_mass`` (upper triangle ``x n_q``; both
  forms are symmetric) such that the matrix of a film is ``A.data =
  (S_stiff @ h^3)[twins]`` (direct form) or ``A.data = (S_stiff @ 1 -
  S_mass @ D)[twins]`` (pi form), with the index maps that cut out the
  condensed blocks ``A[I, I]`` and ``A[I, inlet]``;
- the fill-reducing ordering of ``A[I, I]`` (the symbolic part SuperLU lets
  one keep; see :class:`bearingfe.core.linalg.PatternFactorizer`), so a new film
  costs one numeric factorization;
- the maps from quadrature values to loads (``cos phi dx``, ``sin phi dx``,
  ``dx``), to the source vectors (``E^T dx`` on the interior dofs) and to the
  boundary flows of each outflow group (three dense ``n_groups x n_q``
  matrices, plus the facet maps of the corner dofs).

On affine cells (straight-sided meshes, P1 and P2) the maps and scatters are kept per element
(:class:`_AffineMaps`, :class:`_AffineScatter`): the reference element's values and gradients at
the points, each cell's inverse Jacobian and its dofs; a product runs over the cells and scatter-adds.
That is a few hundred bytes per cell instead of the per-point matrices (about 1.5 kB per P1 cell),
and the mesh's basis then drops its own per-point arrays
(:class:`~bearingfe.film.mesh_operators.LeanCellBasis`). Curved cells keep the sparse per-point
maps (:class:`_SparseMaps`, :class:`Scatter`). The sparse ``E``, ``G`` and the load table are built
on first use for the paths that take them as matrices (elastic, dynamic coefficients).

A film state then costs sparse mat-vecs, one numeric factorization and the
solves; flows and friction of many states (a trajectory) are dense
products over the stacked samples (:meth:`CompiledOperator.outputs`).
The scikit-fem assembly (:func:`bearingfe.film.superposition.superpose` with
``assembly="reference"``) gives the same numbers to round-off (tests/test_compiled.py).
"""

from __future__ import annotations

import functools
import threading
from dataclasses import dataclass, field
from typing import Callable, Mapping, Sequence

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .flows import named_flows, outflow, ruptured_elements
from .forms import FilmAt, along, couette_source, film_at, film_flux, shear, unknown_scale
from ..core.banded import band_cholesky, band_plan
from ..core.compressed import compressed
from ..core.linalg import Factorize, Solve, factorize_splu_sym
from ..core.ordering import NESTED_DISSECTION_FROM, nested_dissection
from ..geometry.runner import is_along_phi, velocity_at

__all__ = ["CompiledOperator", "compile_operator", "FilmFlows", "Scatter", "interpolation_maps"]


#: SuperLU panel and supernode sizes of the numeric factorization up to ``_SMALL_PANELS_UP_TO``
#: unknowns: one-column panels and no relaxed supernodes. The Reynolds matrices are 2-D FEM
#: patterns with little fill in the minimum-degree order, so there the supernodal dense kernels (and
#: a threaded BLAS behind them) cost more than they save: measured 1.4-2.4x faster than SuperLU's
#: defaults from 214 to 17670 unknowns on the pump's P2 meshes. Larger systems keep the defaults
#: (not measured there). The factors are the same up to round-off.
_SMALL_PANELS = {"panel_size": 1, "relax": 1}
_SMALL_PANELS_UP_TO = 20000


def _interpolation(basis, n_dofs: int) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
    """``E``, ``G_phi``, ``G_z``: dofs -> values / gradients at the points of ``basis`` (cell or facet)."""
    return _point_rows(np.asarray(basis.element_dofs), _basis_tables(basis), n_dofs)


def _basis_tables(basis) -> np.ndarray:
    """The values and the two gradient components of the basis functions of ``basis`` at its points,
    ``(3, n_bfun, n_cells, n_points)``."""
    return np.array([[np.asarray(part(phi[0])) for phi in basis.basis]
                     for part in (np.asarray, lambda f: f.grad[0], lambda f: f.grad[1])])


def _point_rows(dofs: np.ndarray, tables: np.ndarray, n_dofs: int) -> tuple[sp.csr_matrix, ...]:
    """The sparse maps dofs -> points of :func:`_basis_tables`' ``tables`` on cells (or facets) of ``dofs``
    ``(n_bfun, n_cells)``, one per table.

    Row ``cell * n_points + point`` holds the ``n_bfun`` basis functions of its cell, so the CSR
    arrays are written directly (columns sorted per row: the canonical form a COO build gives).
    """
    nb, n_cells, n_points = tables.shape[1:]
    sort = np.argsort(dofs, axis=0, kind="stable")  # per cell: its dofs in increasing order
    cols = np.take_along_axis(dofs, sort, axis=0).T  # (n_cells, nb)
    indices = np.broadcast_to(cols[:, None, :], (n_cells, n_points, nb)).ravel().astype(np.int32)
    indptr = np.arange(0, n_cells * n_points * nb + 1, nb, dtype=np.int32)
    out = []
    for v in tables:  # (nb, n_cells, n_points)
        v = np.take_along_axis(v, sort[:, :, None], axis=0).transpose(1, 2, 0)
        m = sp.csr_matrix((np.ascontiguousarray(v).ravel(), indices, indptr), shape=(n_cells * n_points, n_dofs))
        m.has_sorted_indices = True
        out.append(m)
    return tuple(out)


def interpolation_maps(basis) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
    """Sparse maps from the dofs of ``basis`` to the values and the two gradient components at its own
    quadrature points, each of shape ``(n_cells * n_points, basis.N)`` (rows in ``basis.dx`` order)."""
    return _interpolation(basis, basis.N)


def _pattern(dofs: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, tuple[np.ndarray, int], np.ndarray]:
    """The CSR pattern of the element matrices' union, symmetric: ``(indptr, indices, (twins, n_upper),
    upper_rows)``.

    ``twins`` (:func:`_twins`) gives every entry its upper-triangle twin's index among the ``n_upper``
    upper-triangle entries (row-major); ``upper_rows`` ``(n_pairs, n_cells)`` the upper entry each local
    pair ``i <= j`` of each cell adds to. Found from the local pairs ``i <= j`` alone: their distinct
    ``(min, max)`` dof pairs are the upper triangle; row ``r`` of the full pattern is then the strict
    upper entries of column ``r`` (transposed, in row order: a stable sort by column) followed by the
    upper entries of row ``r``.
    """
    nb = dofs.shape[0]
    i, j = np.triu_indices(nb)  # the local pairs i <= j, row-major (the order of the scatters' pairs)
    a, b = dofs[i].astype(np.int64), dofs[j].astype(np.int64)
    keys = np.minimum(a, b) * n + np.maximum(a, b)
    unique, upper_rows = np.unique(keys.ravel(), return_inverse=True)
    row, col = unique // n, unique % n
    n_upper = unique.size
    strict = np.flatnonzero(row < col)
    by_column = col[strict] if n > 2**16 else col[strict].astype(np.uint16)  # numpy sorts 16-bit integers by radix
    lower = strict[np.argsort(by_column, kind="stable")]  # the strict upper entries by column, rows increasing
    n_lower, n_up = np.bincount(col[strict], minlength=n), np.bincount(row, minlength=n)
    indptr = np.concatenate([[0], np.cumsum(n_lower + n_up)])
    first_lower, first_upper = np.cumsum(n_lower) - n_lower, np.cumsum(n_up) - n_up
    at_lower = indptr[col[lower]] + np.arange(lower.size) - first_lower[col[lower]]
    at_upper = indptr[row] + n_lower[row] + np.arange(n_upper) - first_upper[row]
    indices = np.empty(int(indptr[-1]), dtype=np.int32)
    indices[at_lower], indices[at_upper] = row[lower], col
    index = np.int32 if n_upper < 2**31 else np.int64
    twins = np.empty(indices.size, dtype=index)
    twins[at_lower], twins[at_upper] = lower, np.arange(n_upper)
    return indptr, indices, (twins, int(n_upper)), upper_rows.reshape(keys.shape).astype(index)


def _twins(indptr: np.ndarray, indices: np.ndarray, n: int) -> tuple[np.ndarray, int]:
    """For every entry of a symmetric pattern, the index of its upper-triangle twin among the
    upper-triangle entries; and their number."""
    rows = np.repeat(np.arange(n), np.diff(indptr))
    keys = rows.astype(np.int64) * n + indices
    lo, hi = np.minimum(rows, indices).astype(np.int64), np.maximum(rows, indices)
    twin = np.searchsorted(keys, lo * n + hi)
    upper = rows <= indices
    rank = np.cumsum(upper) - 1
    rank = rank[twin]
    return rank.astype(np.int32) if rank.size < 2**31 else rank, int(upper.sum())


def _pair_values(basis, kind: str) -> tuple[list[tuple[int, int]], np.ndarray]:
    """The local pairs ``i <= j`` and ``grad phi_i . grad phi_j dx`` (stiff) or ``phi_i phi_j dx``
    (mass) at every point, shape ``(n_pairs, n_cells, n_points)``."""
    nb = len(basis.basis)
    pairs = [(i, j) for i in range(nb) for j in range(i, nb)]
    data = np.empty((len(pairs), *basis.dx.shape))
    for k, (i, j) in enumerate(pairs):
        vi, vj = basis.basis[i][0], basis.basis[j][0]
        if kind == "stiff":
            data[k] = vi.grad[0] * vj.grad[0] + vi.grad[1] * vj.grad[1]
        else:
            data[k] = np.asarray(vi) * np.asarray(vj)
    data *= basis.dx
    return pairs, data


@dataclass(frozen=True, eq=False)
class Scatter:
    """``c -> S @ c``: the upper-triangle values of ``int c grad u . grad v`` (stiff) or
    ``int c u v`` (mass) on the pattern, for a field ``c`` at the quadrature points.

    Kept as the per-point products of the local pairs (``values``, ``(n_pairs, n_cells,
    n_points)``) and the upper entry each pair of each cell adds to (``rows``): a film costs
    one contraction over the points and one scatter-add, and building it sorts nothing.
    """

    values: np.ndarray
    rows: np.ndarray
    n_upper: int

    def __matmul__(self, c: np.ndarray) -> np.ndarray:
        per_pair = np.einsum("pcq,cq->pc", self.values, np.reshape(c, self.values.shape[1:]))
        return np.bincount(self.rows, weights=per_pair.ravel(), minlength=self.n_upper)

    def tocsr(self) -> sp.csr_matrix:
        """``S`` as a sparse matrix ``(n_upper, n_q)``."""
        n_pairs, n_cells, n_points = self.values.shape
        cols = np.arange(n_cells * n_points).reshape(n_cells, n_points)
        return sp.csr_matrix((self.values.ravel(), (np.repeat(self.rows, n_points),
                                                    np.tile(cols.ravel(), n_pairs))),
                             shape=(self.n_upper, n_cells * n_points))


def _scatter(basis, rows: np.ndarray, n_upper: int, kind: str) -> Scatter:
    """``S`` with ``A.data = (S @ c)[twins]`` for ``int c grad u . grad v`` (stiff) or ``int c u v``
    (mass): both are symmetric, so only the local pairs ``i <= j`` are summed, onto the upper
    triangle (``rows``, :func:`_pattern`), and the lower one copies it."""
    _, values = _pair_values(basis, kind)
    return Scatter(values=values, rows=rows.ravel(), n_upper=n_upper)


def _points(basis) -> np.ndarray:
    """The quadrature points of ``basis``, ``(2, n_cells, n_points)`` (scikit-fem's ``global_coordinates``)."""
    return np.asarray(basis.mapping.F(basis.X, tind=basis.tind))


def _release(basis) -> None:
    """Drop a basis's per-point arrays if it can rebuild them
    (:class:`~bearingfe.film.mesh_operators.LeanCellBasis`)."""
    release = getattr(basis, "release", None)
    if release is not None:
        release()


def _rows_of(columns: list[np.ndarray], values: list[np.ndarray], n_columns: int) -> sp.csr_matrix:
    """A CSR matrix whose row ``s`` holds ``values[s]`` at the increasing ``columns[s]``, exact zeros dropped
    (the entries ``sp.csr_matrix`` takes from the dense rows)."""
    keep = [v != 0.0 for v in values]
    counts = [int(k.sum()) for k in keep]
    indptr = np.concatenate([[0], np.cumsum(counts)]).astype(np.int32)
    data = np.concatenate([v[k] for v, k in zip(values, keep)]) if values else np.zeros(0)
    indices = (np.concatenate([c[k] for c, k in zip(columns, keep)]) if columns else np.zeros(0)).astype(np.int32)
    out = sp.csr_matrix((data, indices, indptr), shape=(len(values), n_columns))
    out.has_sorted_indices = True
    return out


def _block(indptr, indices, rows: np.ndarray, cols: np.ndarray, n: int):
    """Data positions and CSR pattern of the block ``A[rows][:, cols]`` of a CSR pattern (``n`` columns):
    ``(positions, indices, indptr)``, each row's columns sorted (what scipy's fancy indexing and
    ``sort_indices`` give, found by index arithmetic on the arrays)."""
    rows, cols = np.asarray(rows, dtype=np.int64), np.asarray(cols, dtype=np.int64)
    where = np.full(n, -1, dtype=np.int64)  # column -> its place among cols, -1 if not taken
    where[cols] = np.arange(cols.size)
    starts, counts = np.asarray(indptr[rows], dtype=np.int64), np.diff(indptr)[rows].astype(np.int64)
    first = np.cumsum(counts) - counts
    entries = np.repeat(starts - first, counts) + np.arange(int(counts.sum()))  # the rows' entries, in row order
    column = where[indices[entries]]
    taken = column >= 0
    row = np.repeat(np.arange(rows.size), counts)[taken]
    entries, column = entries[taken], column[taken]
    if column.size > 1:
        key = row * max(cols.size, 1) + column
        if np.any(key[1:] < key[:-1]):  # cols not increasing (or a row's columns unsorted): sort each row
            order = np.argsort(key, kind="stable")
            entries, column, row = entries[order], column[order], row[order]
    indptr_out = np.concatenate([[0], np.cumsum(np.bincount(row, minlength=rows.size))])
    return entries, column.astype(np.int32), indptr_out.astype(np.int32)


class _AffineMaps:
    """The interpolation maps ``E``, ``G_phi``, ``G_z`` of an H1 element on affine cells, kept per element.

    On an affine cell the basis functions' values at the quadrature points are the reference element's
    (the same on every cell) and their gradients are the reference gradients through the cell's constant
    inverse Jacobian: ``grad phi_i = J^-T grad_ref phi_i``. So the maps need, besides the element's dofs,
    ``n_cells x 4`` Jacobian entries and a few reference tables, instead of ``3 x n_bfun`` floats (and
    indices) per quadrature point; their products are the same sums in another order (round-off).

    Arrays: ``dofs`` ``(n_cells, n_bfun)``, ``phi`` ``(n_bfun, n_points)``, ``dphi`` ``(2, n_bfun, n_points)``
    (reference gradient ``m`` of basis function ``i`` at point ``q``), ``inv`` ``(2, 2, n_cells)``
    (``d xi_m / d x_k``), ``dx`` ``(n_cells, n_points)``.
    """

    def __init__(self, basis, dx: np.ndarray) -> None:
        dofs = np.asarray(basis.element_dofs)
        self.n = int(basis.N)
        self.dofs = np.ascontiguousarray(dofs.T.astype(np.int32 if self.n < 2**31 - 1 else np.int64))
        X = basis.X
        phi, dphi = zip(*(basis.elem.lbasis(X, i) for i in range(dofs.shape[0])))
        self.phi = np.array([np.broadcast_to(p, X.shape[1:]) for p in phi], dtype=float)          # (nb, Q)
        self.dphi = np.array([np.broadcast_to(g, X.shape) for g in dphi], dtype=float).transpose(1, 0, 2).copy()
        self.inv = np.ascontiguousarray(basis.mapping.invA)                                     # (2, 2, C)
        self.dx = dx
        self.shape = dx.shape
        #: the reference gradients do not vary over the points (P1): the gradients are per-cell constants
        self.constant_gradients = bool(np.all(self.dphi == self.dphi[:, :, :1]))

    @staticmethod
    def applies(basis) -> bool:
        """Whether ``basis`` is an H1 (identity-transformed) element on affine cells in 2-D."""
        from skfem.element import ElementH1
        from skfem.mapping import MappingAffine
        return (isinstance(basis.elem, ElementH1) and type(basis.mapping) is MappingAffine
                and basis.mesh.dim() == 2 and getattr(basis, "tind", None) is None)

    # -- dofs -> points ---------------------------------------------------------------

    def _columns(self, u: np.ndarray, one) -> np.ndarray:
        u = np.asarray(u, dtype=float)
        if u.ndim == 1:
            return one(u).ravel()
        if u.shape[1] == 1:
            return one(u[:, 0]).reshape(-1, 1)
        return np.stack([one(u[:, s]).ravel() for s in range(u.shape[1])], axis=1)

    def values(self, u: np.ndarray) -> np.ndarray:
        """``E @ u`` for ``u`` of shape ``(n_dofs,)`` or ``(n_dofs, S)``: values at the points, ``(n_q[, S])``."""
        return self._columns(u, lambda v: self._values_of(v[self.dofs]))

    def gradient(self, u: np.ndarray, k: int) -> np.ndarray:
        """``G_k @ u`` (``k = 0``: d/dphi, ``1``: d/dz)."""
        return self._columns(u, lambda v: self._gradient_of(v[self.dofs], self.inv, k))

    def _values_of(self, local: np.ndarray) -> np.ndarray:
        """Values at the points of some cells of a field whose dof values on them are ``local``
        ``(n_cells, n_bfun)``: ``(n_cells, n_points)``."""
        return np.einsum("ci,iq->cq", local, self.phi)

    def _gradient_of(self, local: np.ndarray, inv: np.ndarray, k: int) -> np.ndarray:
        """Gradient component ``k`` at the points of some cells (their inverse Jacobians ``inv``,
        ``(2, 2, n_cells)``) of a field whose dof values on them are ``local``."""
        if self.constant_gradients:  # per cell, then spread over its points (no per-point temporaries)
            g = (inv[0, k] * np.einsum("ci,i->c", local, self.dphi[0, :, 0])
                 + inv[1, k] * np.einsum("ci,i->c", local, self.dphi[1, :, 0]))
            return np.broadcast_to(g[:, None], (local.shape[0], self.shape[1]))
        return (inv[0, k][:, None] * np.einsum("ci,iq->cq", local, self.dphi[0])
                + inv[1, k][:, None] * np.einsum("ci,iq->cq", local, self.dphi[1]))

    def field_rows(self, U: np.ndarray) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
        """``(G_phi U)^T``, ``(G_z U)^T`` and ``(E U)^T``: the gradient components and values at the points of
        the fields ``U`` ``(n_dofs, S)``, as sparse ``(S, n_q)`` rows.

        Each field is evaluated on the cells where it has a non-zero dof only (boundary groups touch a thin
        layer of cells); the rows hold the non-zeros of the dense products, the same numbers in the same order.
        """
        U = np.asarray(U, dtype=float)
        n_points = self.shape[1]
        columns, parts = [], ([], [], [])
        touched = np.any(U[self.dofs] != 0.0, axis=1)  # (n_cells, S): the cells where each field lives
        for s in range(U.shape[1]):
            cells = np.flatnonzero(touched[:, s])
            local, inv = U[self.dofs[cells], s], self.inv[:, :, cells]
            columns.append((cells[:, None] * n_points + np.arange(n_points)).ravel())
            for out, f in zip(parts, (self._gradient_of(local, inv, 0), self._gradient_of(local, inv, 1),
                                      self._values_of(local))):
                out.append(np.ravel(f))
        return tuple(_rows_of(columns, values, self.shape[0] * n_points) for values in parts)

    # -- points -> dofs ---------------------------------------------------------------

    def _scatter(self, local: np.ndarray) -> np.ndarray:
        return np.bincount(self.dofs.ravel(), weights=local.ravel(), minlength=self.n)

    def _integrals(self, w: np.ndarray, one) -> np.ndarray:
        w = np.asarray(w, dtype=float)
        if w.ndim == 1:
            return self._scatter(one(w.reshape(self.shape)))
        return np.stack([self._scatter(one(w[:, s].reshape(self.shape))) for s in range(w.shape[1])], axis=1)

    def integrate_value(self, w: np.ndarray) -> np.ndarray:
        """``E^T @ w``: point values ``(n_q[, S])`` -> their sums against each basis function ``(n_dofs[, S])``."""
        return self._integrals(w, lambda v: np.einsum("cq,iq->ci", v, self.phi))

    def integrate_gradient(self, w: np.ndarray, k: int) -> np.ndarray:
        """``G_k^T @ w``."""
        return self._integrals(w, lambda v: (np.einsum("cq,iq->ci", v, self.dphi[0]) * self.inv[0, k][:, None]
                                             + np.einsum("cq,iq->ci", v, self.dphi[1]) * self.inv[1, k][:, None]))

    def sparse(self) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
        """``E``, ``G_phi``, ``G_z`` as sparse matrices ``(n_q, n_dofs)`` (for the rarer paths that take them)."""
        C, Q = self.shape
        nb = self.phi.shape[0]
        sort = np.argsort(self.dofs, axis=1, kind="stable")
        cols = np.take_along_axis(self.dofs, sort, axis=1)
        indices = np.broadcast_to(cols[:, None, :], (C, Q, nb)).ravel().astype(np.int32)
        indptr = np.arange(0, C * Q * nb + 1, nb, dtype=np.int64)
        value = np.broadcast_to(self.phi.T[None], (C, Q, nb))
        grads = [(self.inv[0, k][:, None, None] * self.dphi[0].T[None]
                  + self.inv[1, k][:, None, None] * self.dphi[1].T[None]) for k in range(2)]
        out = []
        for v in (value, *grads):
            v = np.take_along_axis(np.broadcast_to(v, (C, Q, nb)), np.broadcast_to(sort[:, None, :], (C, Q, nb)),
                                   axis=2)
            m = sp.csr_matrix((np.ascontiguousarray(v).ravel(), indices, indptr), shape=(C * Q, self.n))
            m.has_sorted_indices = True
            out.append(m)
        return tuple(out)


class _SparseMaps:
    """The interpolation maps as sparse matrices (any element and mapping: curved cells)."""

    def __init__(self, basis, dx: np.ndarray) -> None:
        self.E, self.Gx, self.Gz = _interpolation(basis, basis.N)
        self.shape = dx.shape
        # the transposes, made once: views on the same arrays (no copy); ``E.T`` per call costs more than
        # the product itself (a film state integrates several fields)
        self._transposed = (self.E.T, self.Gx.T, self.Gz.T)

    def values(self, u):
        return self.E @ u

    def gradient(self, u, k: int):
        return (self.Gx, self.Gz)[k] @ u

    def integrate_value(self, w):
        return self._transposed[0] @ w

    def integrate_gradient(self, w, k: int):
        return self._transposed[1 + k] @ w

    def sparse(self):
        return self.E, self.Gx, self.Gz

    def field_rows(self, U: np.ndarray) -> tuple[sp.csr_matrix, sp.csr_matrix, sp.csr_matrix]:
        """``(G_phi U)^T``, ``(G_z U)^T``, ``(E U)^T`` as sparse ``(S, n_q)`` rows
        (see :meth:`_AffineMaps.field_rows`)."""
        return tuple(sp.csr_matrix(np.asarray(M @ U).T) for M in (self.Gx, self.Gz, self.E))


@dataclass(frozen=True, eq=False)
class _AffineScatter:
    """``c -> S @ c`` (see :class:`Scatter`) on affine cells: ``grad phi_i . grad phi_j = sum_mn M_mn
    dphi_i,m dphi_j,n`` with the cell's constant ``M = J^-1 J^-T`` (stiff), ``phi_i phi_j`` the reference
    element's (mass): per film one contraction of ``dx c`` with reference tables and ``n_cells x 3``
    cell constants, no per-point pair values kept."""

    tables: np.ndarray     # (r, n_pairs, n_points): reference products (r = 3 stiff: mn = 00, 11, 01 + 10; 1 mass)
    cells: np.ndarray      # (r, n_cells): M_00, M_11, M_01 (stiff) or ones (mass)
    dx: np.ndarray         # (n_cells, n_points)
    rows: np.ndarray       # (n_pairs * n_cells,): the upper entry each pair of each cell adds to
    n_upper: int
    constant: bool = False  # the tables do not vary over the points (P1 stiffness)

    def per_pair(self, c: np.ndarray) -> np.ndarray:
        """``int c (pair product)`` per local pair and cell, ``(n_pairs, n_cells)``."""
        w = self.dx * np.reshape(c, self.dx.shape)
        if self.constant:  # P1: the reference gradients are constants
            t = np.einsum("c,rp->rpc", w.sum(axis=1), self.tables[:, :, 0])
        else:
            t = np.einsum("cq,rpq->rpc", w, self.tables)
        return np.einsum("rpc,rc->pc", t, self.cells)

    def __matmul__(self, c: np.ndarray) -> np.ndarray:
        return np.bincount(self.rows, weights=self.per_pair(c).ravel(), minlength=self.n_upper)

    def tocsr(self) -> sp.csr_matrix:
        """``S`` as a sparse matrix ``(n_upper, n_q)``."""
        n_cells, n_points = self.dx.shape
        values = np.einsum("rpq,rc->pcq", self.tables, self.cells) * self.dx
        cols = np.arange(n_cells * n_points).reshape(n_cells, n_points)
        n_pairs = values.shape[0]
        return sp.csr_matrix((values.ravel(), (np.repeat(self.rows, n_points), np.tile(cols.ravel(), n_pairs))),
                             shape=(self.n_upper, n_cells * n_points))


def _affine_scatter(maps: _AffineMaps, rows: np.ndarray, n_upper: int, kind: str) -> _AffineScatter:
    nb = maps.phi.shape[0]
    pairs = [(i, j) for i in range(nb) for j in range(i, nb)]
    I, J = np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])
    if kind == "stiff":
        d = maps.dphi
        tables = np.stack([d[0, I] * d[0, J], d[1, I] * d[1, J], d[0, I] * d[1, J] + d[1, I] * d[0, J]])
        inv = maps.inv
        cells = np.stack([inv[0, 0] ** 2 + inv[0, 1] ** 2, inv[1, 0] ** 2 + inv[1, 1] ** 2,
                          inv[0, 0] * inv[1, 0] + inv[0, 1] * inv[1, 1]])
    else:
        tables = (maps.phi[I] * maps.phi[J])[None]
        cells = np.ones((1, maps.shape[0]))
    return _AffineScatter(tables=tables, cells=cells, dx=maps.dx, rows=rows.ravel(), n_upper=n_upper,
                          constant=bool(np.all(tables == tables[:, :, :1])))


@dataclass(frozen=True)
class FilmFlows:
    """Flows, mass balance and friction of one or many film states (arrays over the samples)."""

    flows: Mapping[str, np.ndarray]
    mass_balance: np.ndarray
    friction: np.ndarray


@dataclass(eq=False)
class CompiledOperator:
    """Film-independent linear maps of one ``(mesh, element)`` (see the module docstring).

    Built by :func:`compile_operator`; the :class:`~bearingfe.film.superposition.Operators`
    of a mesh keep one. The scatter matrices are built on first use (the
    direct form needs no mass scatter).
    """

    n_dofs: int
    interior: np.ndarray
    inlet: np.ndarray
    dx: np.ndarray                 # (n_q,) weights
    maps: object                   # E, G_phi, G_z: _AffineMaps (per element) or _SparseMaps (curved cells)
    indptr: np.ndarray             # CSR pattern of A (n_dofs x n_dofs)
    indices: np.ndarray
    groups: tuple[str, ...]        # flow groups (boundary edges and the pockets)
    _basis: object = field(repr=False)
    _rows: np.ndarray = field(repr=False)  # (n_pairs, n_cells): the upper entry each local pair i <= j adds to
    _lazy: dict = field(default_factory=dict, repr=False)
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False)
    runner: object = None          # the mesh's runner if not the original one (bearingfe.geometry.runner)

    def __getstate__(self) -> dict:
        self._flow_maps()  # built, so that the copy needs no operators to build them from
        state = self.__dict__.copy()
        del state["_lock"]
        return state

    def _flow_maps(self) -> tuple:
        """``(group_maps, corners, corner_weights)`` of :func:`_flow_maps`, built on the first flow computed: a
        Newton step's film solve reads the force and the rupture set only (on a journal's pads 1-2 ms per mesh
        of a few hundred dofs, most of what compiling a small mesh costs)."""
        if "flows" not in self._lazy:
            with self._lock:
                if "flows" not in self._lazy:
                    self._lazy["flows"] = self._lazy.pop("flow_builder")()
        return self._lazy["flows"]

    @property
    def group_maps(self) -> tuple:
        """3 x ``(n_groups, n_q)`` sparse: group sums of the residual of ``q_phi dx``, ``q_z dx``, ``dh/dt dx``."""
        return self._flow_maps()[0]

    @property
    def corners(self) -> tuple:
        """Facet data of the corner dofs (see :meth:`_corner_terms`)."""
        return self._flow_maps()[1]

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state, _lock=threading.Lock())

    @property
    def angles(self) -> tuple[np.ndarray, np.ndarray]:
        """``cos phi`` and ``sin phi`` at the quadrature points (for :func:`bearingfe.film.forms.film_at`)."""
        def build():
            phi = self.points[0] if "x" in self._lazy else _points(self._basis)[0]  # no points kept for this
            return np.cos(phi), np.sin(phi)
        return self._get("angles", build)

    @property
    def x(self) -> np.ndarray:
        """The quadrature points, ``(2, n_q)`` (built on first use: a film evaluated from the angles of the
        points, :attr:`angles`, never needs them)."""
        return self._get("x", lambda: _points(self._basis).reshape(2, -1))

    @property
    def points(self) -> np.ndarray:
        """The quadrature points shaped as the basis has them, ``(2, n_cells, n_points)``."""
        return self.x.reshape(2, *self.maps.shape)

    @property
    def value(self) -> sp.csr_matrix:
        """``E``: dofs -> values at the points, a sparse ``(n_q, n_dofs)`` matrix (built on first use: the
        film solves use the per-element :attr:`maps`; the elastic and dynamic paths take the matrix)."""
        return self._get("sparse_maps", self.maps.sparse)[0]

    @property
    def grad(self) -> tuple[sp.csr_matrix, sp.csr_matrix]:
        """``(G_phi, G_z)``: dofs -> gradient components at the points (sparse, built on first use)."""
        return self._get("sparse_maps", self.maps.sparse)[1:]

    @property
    def loads(self) -> np.ndarray:
        """``(3, n_q)``: ``cos phi dx``, ``sin phi dx``, ``dx`` (built on first use)."""
        return self._get("loads", lambda: np.array([self.angles[0].ravel() * self.dx,
                                                    self.angles[1].ravel() * self.dx, self.dx]))

    def _load_moments(self, p: np.ndarray) -> np.ndarray:
        """``loads @ p`` without the ``(3, n_q)`` table: ``int p (cos phi, sin phi, 1)``."""
        pdx = p * (self.dx if p.ndim == 1 else self.dx[:, None])
        cos, sin = self.angles[0].ravel(), self.angles[1].ravel()
        # einsum's own loops, not BLAS: a threaded dot waited for its threads for ms on a busy machine
        # (18 ms a call at 1e3 unknowns, two threads, load 5; the cavitating results' loads)
        return np.array([np.einsum("q,q...->...", cos, pdx), np.einsum("q,q...->...", sin, pdx), pdx.sum(axis=0)])

    @property
    def nnz(self) -> int:
        return int(self.indices.size)

    def _get(self, name: str, build: Callable):
        if name not in self._lazy:
            self._lazy[name] = build()
        return self._lazy[name]

    @property
    def stiffness_scatter(self) -> Scatter:
        """``S_stiff``: ``A.data = (S_stiff @ c)[twins]`` for ``int c grad u . grad v``."""
        return self._get("stiff", lambda: self._scatter("stiff"))

    @property
    def mass_scatter(self) -> Scatter:
        """``S_mass``: ``A.data = (S_mass @ c)[twins]`` for ``int c u v``."""
        return self._get("mass", lambda: self._scatter("mass"))

    def _scatter(self, kind: str):
        if isinstance(self.maps, _AffineMaps):
            return _affine_scatter(self.maps, self._rows, self.twins[1], kind)
        out = _scatter(self._basis, self._rows, self.twins[1], kind)
        _release(self._basis)  # the per-point arrays it needed: rebuilt on the next use
        return out

    @property
    def twins(self) -> tuple[np.ndarray, int]:
        """Index of each pattern entry's upper-triangle twin, and the number of upper entries."""
        return self._get("twins", lambda: _twins(self.indptr, self.indices, self.n_dofs))

    @property
    def transposed_value(self) -> sp.csc_matrix:
        """``E^T``: (weighted) point values -> their integrals against each basis function (a view of ``E``:
        no copy, the transposed product runs on the same arrays)."""
        return self.value.T

    @property
    def transposed_phi_gradient(self) -> sp.csc_matrix:
        """``G_phi^T``: (weighted) point values -> their integrals against each basis function's ``d/dphi``
        (a view)."""
        return self.grad[0].T

    @property
    def transposed_z_gradient(self) -> sp.csc_matrix:
        """``G_z^T``: (weighted) point values -> their integrals against each basis function's ``d/dz`` (a view)."""
        return self.grad[1].T

    @property
    def runner_at(self) -> tuple[np.ndarray, np.ndarray] | None:
        """The runner's velocity ``u`` at the points, or None for the original runner (``e_phi``)."""
        if self.runner is None:  # the original runner: no points needed
            return None
        return self._get("runner_at", lambda: velocity_at(self.runner, self.x))

    def couette_load(self, c: np.ndarray) -> np.ndarray:
        """``int c u . grad v`` for every basis function ``v``: the conservative Couette load of a density
        ``c`` at the points (:func:`bearingfe.film.forms.couette_source`; ``int c dv/dphi`` for ``u = e_phi``)."""
        u = self.runner_at
        m = self.maps
        if u is None:
            return m.integrate_gradient(self.dx * c, 0)
        return m.integrate_gradient(self.dx * c * u[0], 0) + m.integrate_gradient(self.dx * c * u[1], 1)

    @property
    def sources(self) -> sp.csr_matrix:
        """``(E^T dx)[I]``: a density at the points -> its integral against each interior basis function
        (built on first use: only the dynamic coefficients and the elastic paths ask for it)."""
        def build():
            E = self.value
            scaled = sp.csr_matrix((E.data * np.repeat(self.dx, np.diff(E.indptr)), E.indices, E.indptr),
                                   shape=E.shape)
            return scaled.T.tocsr()[self.interior]
        return self._get("sources", build)

    @property
    def phi_sources(self) -> sp.csr_matrix:
        """``(G_phi^T dx)[I]``: a density ``c`` at the points -> ``int c dv/dphi`` on the interior dofs."""
        def build():
            G = self.grad[0]
            scaled = sp.csr_matrix((G.data * np.repeat(self.dx, np.diff(G.indptr)), G.indices, G.indptr), shape=G.shape)
            return scaled.T.tocsr()[self.interior]
        return self._get("phi_sources", build)

    @property
    def laplace_data(self) -> np.ndarray:
        """Values of ``int grad u . grad v`` on the upper triangle of the pattern."""
        return self._get("laplace", lambda: self.stiffness_scatter @ np.ones(self.dx.size))

    def _blocks(self):
        def build():
            I, inlet = self.interior, self.inlet
            return (_block(self.indptr, self.indices, I, I, self.n_dofs),
                    _block(self.indptr, self.indices, I, inlet, self.n_dofs))
        return self._get("blocks", build)

    # -- the system of a film -------------------------------------------------------------

    def matrix_data(self, formulation: str, h: np.ndarray, D: np.ndarray, viscosity: np.ndarray | None = None
                    ) -> np.ndarray:
        """Values of the system matrix on the pattern for a film (``h``, ``D`` at the points).

        ``viscosity``, optional (direct form only): the viscosity at the points relative to the scale's, for a
        film whose viscosity varies (the coefficient ``h^3 / mu``); without it the isoviscous matrix, unchanged.
        """
        if viscosity is not None:
            if formulation != "direct":
                raise ValueError(f"a varying viscosity needs formulation 'direct' (the pi form's substitution "
                                 f"assumes one viscosity), got {formulation!r}")
            return (self.stiffness_scatter @ (h**3 / viscosity))[self.twins[0]]
        if formulation == "direct":
            upper = self.stiffness_scatter @ h**3
        else:
            upper = self.laplace_data - self.mass_scatter @ D
        return upper[self.twins[0]]

    def matrix(self, data: np.ndarray) -> sp.csr_matrix:
        """The full matrix from its values on the pattern."""
        return sp.csr_matrix((data, self.indices, self.indptr), shape=(self.n_dofs, self.n_dofs))

    def condensed(self, data: np.ndarray) -> sp.csr_matrix:
        """``A[I, I]`` from the values on the pattern."""
        (sel, idx, ptr), _ = self._blocks()
        n = self.interior.size
        return compressed(data[sel], idx, ptr, (n, n))

    def coupling(self, data: np.ndarray) -> sp.csr_matrix:
        """``A[I, inlet]`` from the values on the pattern."""
        _, (sel, idx, ptr) = self._blocks()
        return compressed(data[sel], idx, ptr, (self.interior.size, self.inlet.size))

    def coupling_times(self, data: np.ndarray, g: np.ndarray) -> np.ndarray:
        """``A[I, inlet] @ g`` from the values on the pattern (no matrix built)."""
        def build():
            _, (sel, idx, ptr) = self._blocks()
            return sel, idx, np.repeat(np.arange(ptr.size - 1), np.diff(ptr))
        sel, idx, rows = self._get("coupling", build)
        return np.bincount(rows, weights=data[sel] * g[idx], minlength=self.interior.size)

    def factorize_condensed(self, data: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
        """Numeric factorization of ``A[I, I]``: banded Cholesky where the pattern's half-bandwidth
        in the reverse Cuthill-McKee order pays (:func:`~bearingfe.core.banded.band_pays`, a pattern factored
        again and again: ``"kept_pattern"``; small meshes), else SuperLU
        (symmetric mode) in a fill-reducing order found once for the pattern (:meth:`_order`). A
        matrix that is not positive definite in floating point goes to SuperLU.

        Every film, the first included, is factored in that order from the same matrix object,
        so a film's numbers do not depend on the films solved on the mesh before it."""
        band = self._band_plan()
        if band is not None:
            solve = band_cholesky(band, data)
            if solve is not None:
                return solve
            # not positive definite in floating point: SuperLU (diagonal pivots) as for wider bands
        n = self.interior.size
        if "order" not in self._lazy:
            self._lazy["order"] = self._order(data)
        order, inverse, psel, template = self._lazy["order"]
        with self._lock:  # one matrix object per mesh: fill and factor it in one go (threads)
            template.data[:] = data[psel]
            lu = spla.splu(template, permc_spec="NATURAL", diag_pivot_thresh=0.0, options={"SymmetricMode": True},
                           **(_SMALL_PANELS if n <= _SMALL_PANELS_UP_TO else {}))

        def solve(b: np.ndarray) -> np.ndarray:
            return lu.solve(np.asarray(b, dtype=float)[order])[inverse]

        return solve

    @property
    def condensed_order(self) -> np.ndarray | None:
        """The fill-reducing order of ``A[I, I]`` its SuperLU factorizations use (positions in the interior
        dofs), or None if none was needed yet (banded Cholesky). The order restricted to a subset of the
        dofs is a good order of that subset's block (its fill is part of the whole block's): the
        cavitation models factor their free sets in it."""
        found = self._lazy.get("order")
        return None if found is None else found[0]

    def _order(self, data: np.ndarray):
        """The fill-reducing order of ``A[I, I]`` and the kept matrix object it is factored in.

        From :data:`~bearingfe.core.ordering.NESTED_DISSECTION_FROM` unknowns on: nested dissection
        by the interior dofs' coordinates (:func:`~bearingfe.core.ordering.nested_dissection`), found
        from the pattern alone, so a fresh mesh's first film costs one factorization. Below: minimum
        degree on ``A^T + A``, which fills less there, read off a first factorization of ``data``
        (that factorization rounds differently and is not used for solves)."""
        (sel, idx, ptr), _ = self._blocks()
        n = self.interior.size
        if n >= NESTED_DISSECTION_FROM:
            pattern = sp.csr_matrix((np.ones(sel.size, dtype=np.int8), idx, ptr), shape=(n, n))
            order = nested_dissection(pattern, np.asarray(self._basis.doflocs)[:, self.interior])
        else:
            # the small panels change the supernodes, not the order (perm_c is the same): faster here too
            lu = spla.splu(sp.csc_matrix((data[sel], idx, ptr), shape=(n, n)), permc_spec="MMD_AT_PLUS_A",
                           diag_pivot_thresh=0.0, options={"SymmetricMode": True},
                           **(_SMALL_PANELS if n <= _SMALL_PANELS_UP_TO else {}))
            order = np.argsort(lu.perm_c)
        positions, indices, indptr = _block(ptr, idx, order, order, n)
        # A is symmetric, so the CSR arrays of the permuted block are its CSC arrays too; the
        # matrix object is kept and only its values change (SuperLU copies them when it factors)
        permuted = sp.csc_matrix((np.zeros(positions.size), indices, indptr), shape=(n, n))
        permuted.has_sorted_indices = True
        return order, np.argsort(order), sel[positions], permuted

    @property
    def banded(self) -> bool:
        """True if ``A[I, I]`` is factored by banded Cholesky (see :meth:`factorize_condensed`)."""
        return self._band_plan() is not None

    def _band_plan(self):
        """Banded storage of ``A[I, I]`` in the reverse Cuthill-McKee order, or None if its band does not pay
        (:func:`~bearingfe.core.banded.band_plan`, ``"kept_pattern"``; built once per pattern)."""
        def build():
            (sel, idx, ptr), _ = self._blocks()
            return band_plan(sel, idx, ptr, self.interior.size, kind="kept_pattern")
        return self._get("band", build)

    # -- pressure, loads, flows and friction -----------------------------------------------

    def pressure(self, u: np.ndarray, h: np.ndarray, dh: np.ndarray, pi: np.ndarray):
        """``p`` and ``grad p`` at the points for unknowns ``u`` (``(n_dofs, S)``), films
        ``h``, ``dh`` (``(n_q, S)``, ``(2, n_q, S)``) and a mask of pi-form samples ``(S,)``."""
        value = self.maps.values(u)
        gradient = np.empty((2, *value.shape))
        gradient[0], gradient[1] = self.maps.gradient(u, 0), self.maps.gradient(u, 1)
        if not np.any(pi):  # direct form: p = u (no temporaries of the chain rule)
            return value, gradient
        s = np.where(pi, h**-1.5, 1.0)
        p = s * value
        dp = s * gradient - np.where(pi, 1.5 * p / h, 0.0) * dh
        return p, dp

    def smoothness_defect(self, film, at: FilmAt) -> float:
        """How far a film's reported derivatives are from its thickness: 0 for a smooth film (to quadrature
        error, about 1e-7 and less on coarse meshes), of order 1 for a film with a step or a kink.

        Two identities that hold for test functions ``v`` vanishing on the Dirichlet boundary, when ``h``
        is smooth: the wedge source ``int 6 h^(-3/2) dh/dphi v`` equals its conservative form
        (:func:`bearingfe.film.forms.couette_source`), which only sees ``h`` and so sees a step; and
        ``int lap(h) v = -int grad h . grad v``, which a kink breaks (its Laplacian has a line mass).
        Returned: the larger of the two residuals, each relative to the size of its terms (the same
        integrals with absolute values). The pi form needs both identities.
        """
        h, (hx, hz) = at.h.ravel(), (at.dh[0].ravel(), at.dh[1].ravel())
        lap = np.asarray(film.laplacian(*self.points), float).ravel() * np.ones_like(h)
        dx = self.dx
        c = couette_source(h, "pi")
        u = self.runner_at
        pointwise = 6.0 * h**-1.5 * along(u, (hx, hz))
        absolute_value, absolute_phi, absolute_z = self._absolute_maps()
        I = self.interior
        m = self.maps
        wedge = (self.couette_load(c) - m.integrate_value(dx * pointwise))[I]
        if u is None:
            couette_size = absolute_phi @ (dx * np.abs(c))
        else:
            couette_size = absolute_phi @ (dx * np.abs(c * u[0])) + absolute_z @ (dx * np.abs(c * u[1]))
        wedge_size = (couette_size + absolute_value @ (dx * np.abs(pointwise)))[I]
        laplace = (m.integrate_value(dx * lap) + m.integrate_gradient(dx * hx, 0)
                   + m.integrate_gradient(dx * hz, 1))[I]
        laplace_size = (absolute_value @ (dx * np.abs(lap)) + absolute_phi @ (dx * np.abs(hx))
                        + absolute_z @ (dx * np.abs(hz)))[I]
        tiny = 1e-300
        return float(max(np.max(np.abs(wedge) / (wedge_size + tiny), initial=0.0),
                         np.max(np.abs(laplace) / (laplace_size + tiny), initial=0.0)))

    def _absolute_maps(self):
        return self._get("absolute_maps", lambda: tuple(abs(m).T.tocsr() for m in (self.value, *self.grad)))

    # -- the assembly interface (bearingfe.film.assembly) ---------------------------------

    def film_at(self, film) -> FilmAt:
        """The film's fields at the quadrature points (trigonometric values of the points computed once)."""
        if getattr(film, "fields_from_angles", None) is not None:  # the angles are all it needs
            return film_at(film, None, self.angles)
        return film_at(film, self.points, self.angles)

    def system(self, at: FilmAt, formulation: str) -> "CompiledSystem":
        """The system of a film state in a formulation (values on the pattern: no sparse build)."""
        return CompiledSystem(self, at, formulation)

    def field_loads(self, at: FilmAt, formulation: str, u: np.ndarray) -> tuple[np.ndarray, float]:
        """Force ``int p (cos phi, sin phi)`` and ``int p`` of an unknown field (pockets not included)."""
        p = unknown_scale(at.h.ravel(), formulation) * self.maps.values(u)
        values = self._load_moments(p)
        return values[:2].copy(), float(values[2])

    def outputs(self, states: Sequence, u: np.ndarray, weights: np.ndarray, sliding: np.ndarray,
                cavitated: np.ndarray | None = None) -> FilmFlows:
        """Flows, mass balance and friction of ``S`` film states ``(film, at, formulation)`` at once."""
        h = _columns([at.h.ravel() for _, at, _ in states])  # one state: views, no copies
        pi = np.array([formulation == "pi" for _, _, formulation in states])
        # the film's gradient enters the pi form's pressure and the ruptured source only
        dh = (np.stack([_columns([at.dh[k].ravel() for _, at, _ in states]) for k in range(2)])
              if pi.any() or cavitated is not None else None)
        hdot = np.zeros(h.shape)
        for k in (1, 2):  # the squeeze rates' shapes (a rate that is zero in every state adds nothing)
            if np.any(weights[k]):
                hdot += weights[k] * _columns([at.shapes[k - 1].ravel() for _, at, _ in states])
        return self.field_outputs(u, [film for film, _, _ in states], h, dh, hdot, weights, np.asarray(sliding, float),
                                  pi, cavitated)

    def field_outputs(self, u: np.ndarray, films: Sequence, h: np.ndarray, dh: np.ndarray, hdot: np.ndarray,
                      weights: np.ndarray, sliding: np.ndarray, pi: np.ndarray,
                      cavitated: np.ndarray | None = None) -> FilmFlows:
        """Flows, mass balance and friction of ``S`` film states at once.

        Parameters
        ----------
        u : ndarray, shape (n_dofs, S)
            Unknowns (``p`` or ``Pi``).
        films : sequence of Film, length S
            For the facet fluxes of the corner dofs.
        h, dh, hdot : ndarray
            Film thickness, its gradient and ``dh/dt`` at the points, shapes
            ``(n_q, S)``, ``(2, n_q, S)``, ``(n_q, S)``; ``dh`` may be None if no sample is in the pi
            form and ``cavitated`` is None (it is not needed then).
        weights : ndarray, shape (4, S)
            Unit-source weights; the wedge is ``weights[0]``.
        sliding : ndarray, shape (S,)
        pi : ndarray of bool, shape (S,)
            Samples in the pi form (the others are direct).
        cavitated : ndarray of bool, shape (n_dofs, S), optional
            Ruptured dofs (see :mod:`bearingfe.film.reference`).
        """
        wedge = weights[0]
        dp = self.pressure(u, h, dh, pi)[1]
        direction = self._direction(self.runner_at)
        dxc = self.dx[:, None]
        friction = np.sum(shear(h, dp, sliding, direction=direction) * dxc, axis=0)
        q0, q1 = film_flux(h, dp, wedge, direction=direction)
        del dp  # the point fields are few at a time: on 1e6 unknowns each is 0.1 GB
        q0 *= dxc  # the fluxes are this function's own arrays: weighted in place
        q1 *= dxc
        qx, qz, qh = q0, q1, hdot * dxc
        residual = self.group_maps[0] @ qx + self.group_maps[1] @ qz - self.group_maps[2] @ qh
        residual = residual + self._corner_terms(u, films, wedge, pi)
        squeeze = np.sum(qh, axis=0)
        flows = named_flows(self.groups, residual, squeeze)
        balance = flows["inlet"] - outflow(flows) - flows["squeeze"]
        if cavitated is not None:
            m = self.maps
            r = m.integrate_gradient(qx, 0) + m.integrate_gradient(qz, 1) - m.integrate_value(qh)
            cavitation = np.sum(np.where(cavitated, r, 0.0), axis=0)
            source = self._ruptured_source(u, cavitated, wedge, along(direction, dh), hdot)
            corrected = named_flows(self.groups, residual + self.group_maps[2] @ (source * dxc), squeeze)
            corrected["cavitation"] = (cavitation + (corrected["inlet"] - flows["inlet"])
                                       - (outflow(corrected) - outflow(flows)))
            flows, balance = corrected, balance - cavitation
        return FilmFlows(flows=flows, mass_balance=balance, friction=friction)

    @staticmethod
    def _direction(u):
        """The runner's velocity at the points shaped to broadcast against ``(n_points, S)`` arrays."""
        return None if u is None else (u[0][:, None], u[1][:, None])

    def _ruptured_source(self, u, cavitated, wedge, dh_along, hdot) -> np.ndarray:
        """``wedge/2 u . grad h + dh/dt`` in the ruptured elements (zero elsewhere), at the points."""
        ruptured = ruptured_elements(self._basis.element_dofs, u, cavitated)  # (n_cells, S)
        n_points = self.maps.shape[1]
        mask = np.repeat(ruptured, n_points, axis=0)
        return np.where(mask, 0.5 * wedge * dh_along + hdot, 0.0)

    def _corner_terms(self, u, films, wedge, pi) -> np.ndarray:
        """Per group: direct facet fluxes at its corner dofs minus their weighted shared sum."""
        out = np.zeros((len(self.groups), u.shape[1]))
        if not self.corners:
            return out
        E, Gx, Gz, normals, x, parts = self.corners  # the facet points of all groups, stacked
        at = [film_at(f, x) for f in films]
        h = np.stack([a.h for a in at], axis=1)
        dh = np.stack([np.stack(a.dh) for a in at], axis=2)
        value, gx, gz = E @ u, Gx @ u, Gz @ u
        s = np.where(pi, h**-1.5, 1.0)
        p = s * value
        chain = np.where(pi, 1.5 * p / h, 0.0)
        dp0, dp1 = s * gx - chain * dh[0], s * gz - chain * dh[1]
        q0, q1 = film_flux(h, (dp0, dp1), wedge, direction=self._direction(velocity_at(self.runner, x)))
        qn = q0 * normals[0][:, None] + q1 * normals[1][:, None]
        direct = {name: phi_ds @ qn[rows] for name, (rows, phi_ds) in parts.items()}  # (n_corner_dofs, S)
        weights_of = self._flow_maps()[2]  # group -> (n_corner_dofs,): its weight there, or 0
        shared = sum(np.where(weights_of[name][:, None] > 0, d, 0.0) for name, d in direct.items())
        for k, name in enumerate(self.groups):
            if name in direct:
                w = weights_of[name]
                member = w > 0
                out[k] = np.sum(direct[name][member] - w[member, None] * shared[member], axis=0)
        return out


def _columns(fields: Sequence[np.ndarray]) -> np.ndarray:
    """Point fields of ``S`` states as the columns of an ``(n_q, S)`` array (a view for one state)."""
    return fields[0][:, None] if len(fields) == 1 else np.stack(fields, axis=1)


class CompiledSystem:
    """One film state's system from the compiled maps: mat-vecs on the pattern, one numeric factorization
    (see :class:`bearingfe.film.assembly.FilmSystem`)."""

    def __init__(self, co: CompiledOperator, at: FilmAt, formulation: str) -> None:
        self.co, self.at, self.formulation = co, at, formulation
        self.h, self.D = at.h.ravel(), at.D.ravel()
        self.data = co.matrix_data(formulation, self.h, self.D)
        self._weights: np.ndarray | None = None

    def full_matrix(self) -> sp.csr_matrix:
        return self.co.matrix(self.data)

    def condensed_matrix(self) -> sp.csr_matrix:
        return self.co.condensed(self.data)

    def _source_weights(self) -> np.ndarray:
        """The loads of the three unit sources (the wedge ``G_phi^T (dx c)`` with ``c`` its conservative
        density, :func:`bearingfe.film.forms.couette_source`; the squeeze rates ``E^T (dx 12 s dh/dq_k)``)
        and the load weights ``E^T (s (cos phi, sin phi, 1) dx)`` (``p = s u``)."""
        if self._weights is None:
            at, co = self.at, self.co
            s = unknown_scale(self.h, self.formulation)
            sdx = s * co.dx
            cos, sin = co.angles[0].ravel(), co.angles[1].ravel()
            # the five point fields as the columns of one (n_q, 5) table integrated in one product: each column's
            # sums are those of its own product, term by term in the same order (the same numbers to the bit)
            fields = np.empty((5, sdx.size)).T
            fields[:, 0] = 12.0 * sdx * at.shapes[0].ravel()
            fields[:, 1] = 12.0 * sdx * at.shapes[1].ravel()
            fields[:, 2] = cos * sdx
            fields[:, 3] = sin * sdx
            fields[:, 4] = sdx
            integrated = co.maps.integrate_value(fields)
            self._weights = np.empty((integrated.shape[0], 6))
            self._weights[:, 0] = co.couette_load(couette_source(self.h, self.formulation))  # through G_phi^T
            self._weights[:, 1:] = integrated
        return self._weights

    def rhs(self, lift: np.ndarray) -> np.ndarray:
        co = self.co
        weights = self._source_weights()
        rhs = np.empty((co.interior.size, 4))
        rhs[:, :3] = -weights[co.interior, :3]
        rhs[:, 3] = -co.coupling_times(self.data, lift[co.inlet, 3]) if co.inlet.size else 0.0
        return rhs

    def factorize(self, factorize: Factorize) -> Solve:
        if factorize is factorize_splu_sym:  # the ordering kept per mesh, or banded Cholesky
            return self.co.factorize_condensed(self.data)
        return factorize(self.condensed_matrix())

    def unit_loads(self, U: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        values = self._source_weights()[:, 3:].T @ U
        return values[:2].copy(), values[2].copy()


def _flow_maps(ops, maps, n: int, groups: tuple) -> tuple:
    """The maps of the flows out of each group (:meth:`CompiledOperator.group_maps`, ``corners`` and the corner
    dofs' weights per group) of :func:`compile_operator`."""
    A = np.zeros((len(groups), n))
    corner_dofs = set()
    for k, name in enumerate(groups):
        dofs, w = ops.flow_groups[name]
        corner = w < 1
        A[k, dofs[~corner]] = 1.0
        if name in ops.facet_groups:
            A[k, dofs[corner]] = w[corner]
            corner_dofs.update(dofs[corner].tolist())
        else:  # a group without facet fluxes: its corner dofs count with their weight only
            A[k, dofs[corner]] = w[corner]
    # sparse: only the points of the elements next to a group are non-zero (and a sparse product
    # keeps clear of a threaded BLAS, which on a loaded machine costs more than the product itself)
    group_maps = maps.field_rows(A.T)
    corners: tuple = ()
    weights_of: dict = {}
    if ops.facet_groups and corner_dofs:
        cdofs = np.array(sorted(corner_dofs))
        facet, parts = ops.corner_tables  # the basis on the corner facets of all groups
        dofs, tables, dx = facet.dofs, facet.tables, facet.dx  # (nb, n_facets), (3, nb, n_facets, n_points)
        n_facets, n_points = dx.shape
        # each corner dof's basis function times the facet weights at every facet point (a facet's dofs
        # are distinct, so at most one of its basis functions is the corner dof's)
        phi_ds = np.zeros((cdofs.size, n_facets, n_points))  # (n_corner_dofs, n_facets, n_points)
        at = np.minimum(np.searchsorted(cdofs, dofs), cdofs.size - 1)
        for i in range(dofs.shape[0]):
            f = np.flatnonzero(cdofs[at[i]] == dofs[i])
            phi_ds[at[i, f], f] = tables[0, i, f] * dx[f]
        keep = np.zeros(n_facets, dtype=bool)
        weights_of, kept = {}, {}
        for name, facets in parts.items():
            # only the facets where a corner dof's basis function lives contribute
            per_facet = np.abs(phi_ds[:, facets]).max(axis=(0, 2))
            keep[facets] = per_facet > 1e-14 * per_facet.max()
            # column-major, the layout it had as the transpose of a sparse matrix's dense copy: BLAS rounds
            # ``phi_ds @ q`` differently in the two layouts, and so the flows stay the same to the bit
            kept[name] = np.asfortranarray(phi_ds[:, facets][:, keep[facets]].reshape(cdofs.size, -1))
            dofs_g, w = ops.flow_groups[name]
            wc = np.zeros(cdofs.size)
            corner = w < 1
            wc[np.searchsorted(cdofs, dofs_g[corner])] = w[corner]
            weights_of[name] = wc
        ends = np.cumsum([0] + [kept[name].shape[1] for name in parts])
        on = np.repeat(keep, n_points)
        normals = facet.normals.reshape(2, -1)[:, on]
        xf = facet.x.reshape(2, -1)[:, on]
        Ef, Gfx, Gfz = _point_rows(dofs[:, keep], tables[:, :, keep], n)  # the rows of the kept facets' points
        corners = (Ef, Gfx, Gfz, normals, xf,
                   {name: (slice(ends[k], ends[k + 1]), kept[name]) for k, name in enumerate(parts)})
    return group_maps, corners, weights_of


def compile_operator(ops) -> CompiledOperator:
    """Build the compiled operator of :class:`~bearingfe.film.superposition.Operators` ``ops``."""
    basis, n = ops.basis, ops.n_dofs
    cell_dx = np.ascontiguousarray(basis.dx)  # (n_cells, n_points); dx below is a view of it
    maps = (_AffineMaps if _AffineMaps.applies(basis) else _SparseMaps)(basis, cell_dx)
    indptr, indices, twins, upper = _pattern(np.asarray(basis.element_dofs), n)
    dx = cell_dx.ravel()
    I = ops.interior
    groups = tuple(ops.flow_groups)
    lazy: dict = {}
    if "x" in ops._lazy:  # the points the operators already hold (not a second copy)
        lazy["x"] = np.asarray(ops.x).reshape(2, -1)
    lazy["twins"] = twins
    lazy["flow_builder"] = functools.partial(_flow_maps, ops, maps, n, groups)
    _release(basis)  # the per-point arrays of the basis: the maps keep what they need
    return CompiledOperator(n_dofs=n, interior=I, inlet=ops.inlet, dx=dx, maps=maps,
                            indptr=indptr, indices=indices, groups=groups,
                            _basis=basis, _rows=upper,
                            _lazy=lazy, runner=None if is_along_phi(ops.mesh.runner) else ops.mesh.runner)
