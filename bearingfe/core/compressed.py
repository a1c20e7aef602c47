"""Sparse matrices from arrays at hand: scipy's own kernels without its sparse objects' checks.

The small systems of a film solve build a dozen compressed (CSR/CSC) matrices and take a dozen products with them
per solve. scipy's constructors and operators check their input, search an index dtype and dispatch on the
operand's type: about 13 us a matrix and 2.5 us a product, several times the arithmetic at a few hundred
unknowns. The functions here take the arrays the caller made itself and call the kernels scipy's own operations
call (``scipy.sparse._sparsetools``), giving the same arrays bit for bit.

Those kernels and the sparse objects' attributes are scipy's internals. The first call checks once, on a small
matrix, that every kernel is there and gives what scipy's public operations give; if one does not (another scipy
version), every function here takes scipy's public path, with the same results.
"""

from __future__ import annotations

import functools

import numpy as np
import scipy.sparse as sp

try:   # scipy's compiled kernels (private: checked by kernels_usable before any use)
    from scipy.sparse import _sparsetools
except ImportError:   # pragma: no cover - depends on the installed scipy
    _sparsetools = None

__all__ = ["compressed", "csr_of", "matvec", "sorted_entries", "csr_sum", "csr_product", "csr_transposed", "csc_of",
           "csr_without_zeros", "kernels_usable"]

_CLASSES = {"csr": sp.csr_matrix, "csc": sp.csc_matrix}
_INT32_MAX = 2**31 - 1


def _held(data: np.ndarray, indices: np.ndarray, indptr: np.ndarray, shape: tuple[int, int], fmt: str):
    """A sparse matrix object of ``fmt`` holding the arrays themselves, made without its constructor."""
    cls = _CLASSES[fmt]
    A = cls.__new__(cls)
    A.maxprint = _maxprint()
    A._shape = (int(shape[0]), int(shape[1]))
    A.data, A.indices, A.indptr = data, indices, indptr
    return A


@functools.cache
def _maxprint() -> int:
    """scipy's default number of entries printed (an attribute every sparse object carries)."""
    return sp.csr_matrix((1, 1)).maxprint


def compressed(data: np.ndarray, indices: np.ndarray, indptr: np.ndarray, shape: tuple[int, int],
               fmt: str = "csr", canonical: bool = False) -> sp.csr_matrix | sp.csc_matrix:
    """``sp.csr_matrix((data, indices, indptr), shape=shape)`` (or ``csc_matrix``, ``fmt``) holding the given
    arrays themselves.

    Where the arrays are what scipy's checks would keep (``int32`` indices and index pointers, 1-D, ``indptr`` of
    ``shape[major] + 1`` entries from 0 to ``data.size == indices.size``) the checks are skipped (under 1 us
    against about 13); any other input goes through scipy's constructor. The indices are not scanned: the caller
    vouches that they lie in range and that ``indptr`` does not decrease.

    Parameters
    ----------
    data, indices, indptr : numpy.ndarray
        The compressed arrays (values, column (row) indices, row (column) pointers).
    shape : tuple of int
        Rows and columns.
    fmt : {"csr", "csc"}
        Row- or column-compressed.
    canonical : bool
        The caller vouches that each row's (column's) indices increase without repeats (scipy's
        ``has_canonical_format``, which scipy would otherwise find at first use).
    """
    if fmt not in _CLASSES:
        raise ValueError(f"fmt must be 'csr' or 'csc', got {fmt!r}")
    major = shape[0] if fmt == "csr" else shape[1]
    if (kernels_usable() and indices.dtype == indptr.dtype == np.int32
            and data.ndim == indices.ndim == indptr.ndim == 1 and indptr.size == major + 1
            and indices.size == data.size and max(shape) < _INT32_MAX
            and int(indptr[0]) == 0 and int(indptr[-1]) == data.size):
        A = _held(data, indices, indptr, shape, fmt)
    else:
        A = _CLASSES[fmt]((data, indices, indptr), shape=shape)
    if canonical:
        A.has_canonical_format = True
    return A


def csr_of(A) -> sp.csr_matrix:
    """``sp.csr_matrix(A)``, but a ``csr_matrix`` itself as it is: scipy's constructor would check its arrays and
    wrap the same arrays in a new object (about 8 us, a few per film state)."""
    return A if type(A) is sp.csr_matrix else sp.csr_matrix(A)


def matvec(A: sp.spmatrix, x: np.ndarray) -> np.ndarray:
    """``A @ x``: for a CSR or CSC matrix of float64 values and a float64 vector, scipy's kernel of that product
    (``csr_matvec`` or ``csc_matvec`` into zeros: the same sums in the same order) without scipy's dispatch
    (about 2.5 us a product); for a float64 ``x`` of ``k > 1`` columns the kernel scipy takes for it
    (``csr_matvecs`` or ``csc_matvecs``, on ``x`` in C order); anything else (one column among them) through
    ``A @ x``."""
    fmt = getattr(A, "format", None)
    if (fmt in _CLASSES and type(x) is np.ndarray and x.dtype == np.float64 and A.data.dtype == np.float64
            and A.indices.dtype == A.indptr.dtype and x.shape[0] == A.shape[1] and kernels_usable()):
        M, N = A.shape
        if x.ndim == 1:
            y = np.zeros(M)
            (_sparsetools.csr_matvec if fmt == "csr" else _sparsetools.csc_matvec)(M, N, A.indptr, A.indices,
                                                                                 A.data, x, y)
            return y
        if x.ndim == 2 and x.shape[1] > 1:
            k = x.shape[1]
            y = np.zeros((M, k))
            (_sparsetools.csr_matvecs if fmt == "csr" else _sparsetools.csc_matvecs)(M, N, k, A.indptr, A.indices,
                                                                                   A.data, x.ravel(), y.ravel())
            return y
    return A @ x


def sorted_entries(rows: np.ndarray, cols: np.ndarray, values: np.ndarray, n: int) -> sp.csr_matrix:
    """``sp.csr_matrix((values, (rows, cols)), shape=(n, n))`` with sorted indices: entries sharing a place summed.

    scipy's kernels of that conversion (``coo_tocsr``; ``csr_sort_indices`` where the indices are not sorted
    already; ``csr_sum_duplicates`` where a place is given twice or more) on ``int32`` copies of the places,
    without the sparse objects' checks between them (0.05 against 0.11 ms for the P1 pattern of 529 nodes); the
    same arrays, the repeated entries' sums included (the same kernels on the same arrays: the same order).
    More than ``2**31 - 1`` rows or entries take scipy's conversion.
    """
    size = rows.size
    if n < _INT32_MAX and size < _INT32_MAX and kernels_usable():
        indptr = np.empty(n + 1, np.int32)
        indices = np.empty(size, np.int32)
        data = np.empty(size, values.dtype)
        _sparsetools.coo_tocsr(n, n, size, rows.astype(np.int32), cols.astype(np.int32), values, indptr, indices, data)
        if not _sparsetools.csr_has_sorted_indices(n, indptr, indices):   # (scipy's sort_indices tests it first)
            _sparsetools.csr_sort_indices(n, indptr, indices, data)
        if not _sparsetools.csr_has_canonical_format(n, indptr, indices):   # a place twice: scipy's sum_duplicates
            _sparsetools.csr_sum_duplicates(n, n, indptr, indices, data)
            nnz = int(indptr[-1])
            indices, data = indices[:nnz].copy(), data[:nnz].copy()
        return compressed(data, indices, indptr, (n, n), canonical=True)
    P = sp.csr_matrix((values, (rows, cols)), shape=(n, n))
    P.sort_indices()
    return P


def _int32_canonical(A: sp.spmatrix) -> bool:
    """Whether ``A`` is CSR with ``int32`` indices and canonical (sorted, no repeats)."""
    return A.format == "csr" and A.indices.dtype == A.indptr.dtype == np.int32 and A.has_canonical_format


def csr_sum(A: sp.csr_matrix, B: sp.csr_matrix) -> sp.csr_matrix:
    """``A + B`` of two CSR matrices of one shape: for canonical ones with ``int32`` indices scipy's kernel of that
    sum (``csr_plus_csr``: each row's entries merged in order, entries that sum to zero dropped) on their arrays,
    the arrays scipy's ``A + B`` gives, without its checks; else scipy's sum."""
    if not (_int32_canonical(A) and _int32_canonical(B) and A.shape == B.shape and kernels_usable()):
        return (A + B).tocsr()
    n, m = A.shape
    size = A.nnz + B.nnz
    indptr = np.empty(n + 1, np.int32)
    indices = np.empty(size, np.int32)
    data = np.empty(size, np.result_type(A.data, B.data))
    _sparsetools.csr_plus_csr(n, m, A.indptr, A.indices, A.data, B.indptr, B.indices, B.data, indptr, indices, data)
    nnz = int(indptr[-1])
    return compressed(data[:nnz], indices[:nnz], indptr, (n, m), canonical=True)


def csr_product(A: sp.csr_matrix, B: sp.csr_matrix) -> sp.csr_matrix:
    """``A @ B`` of two CSR matrices: for ``int32`` indices scipy's kernels of that product (``csr_matmat_maxnnz``
    to size it, ``csr_matmat``: each row's sums in the order of ``A``'s entries, sums of zero dropped, indices in
    the kernel's order, not sorted) on their arrays, the arrays scipy's ``A @ B`` gives, without its checks and
    conversions (about 40 us of scipy's objects a product); else scipy's product. ``int32`` results only: a
    product with ``2**31 - 1`` entries or more takes scipy's product."""
    if not (A.format == B.format == "csr" and A.indices.dtype == A.indptr.dtype == np.int32
            and B.indices.dtype == B.indptr.dtype == np.int32 and A.shape[1] == B.shape[0] and kernels_usable()):
        return (A @ B).tocsr()
    n, m = A.shape[0], B.shape[1]
    nnz = _sparsetools.csr_matmat_maxnnz(n, m, A.indptr, A.indices, B.indptr, B.indices)
    if not 0 < nnz < _INT32_MAX:
        return (A @ B).tocsr()
    indptr = np.empty(n + 1, np.int32)
    indices = np.empty(nnz, np.int32)
    data = np.empty(nnz, np.result_type(A.data, B.data))
    _sparsetools.csr_matmat(n, m, A.indptr, A.indices, A.data, B.indptr, B.indices, B.data, indptr, indices, data)
    kept = int(indptr[-1])
    return compressed(data[:kept], indices[:kept], indptr, (n, m))


def csr_transposed(A: sp.csr_matrix) -> sp.csr_matrix:
    """``A.T.tocsr()``: for a CSR matrix with ``int32`` indices scipy's kernel of that conversion (``csr_tocsc``:
    the same arrays, each row's indices sorted, repeated entries kept) without its checks, canonical where ``A``
    is; else scipy's conversion."""
    if not (A.format == "csr" and A.indices.dtype == A.indptr.dtype == np.int32 and kernels_usable()):
        return A.T.tocsr()
    n, m = A.shape
    indptr = np.empty(m + 1, np.int32)
    indices = np.empty(A.nnz, np.int32)
    data = np.empty(A.nnz, A.data.dtype)
    _sparsetools.csr_tocsc(n, m, A.indptr, A.indices, A.data, indptr, indices, data)
    T = compressed(data, indices, indptr, (m, n), canonical=A.has_canonical_format)
    T.has_sorted_indices = True
    return T


def csc_of(A: sp.csr_matrix) -> sp.csc_matrix:
    """``A.tocsc()``: for a canonical CSR matrix with ``int32`` indices the arrays of :func:`csr_transposed` (the
    kernel of scipy's conversion: the same arrays) without scipy's checks, else scipy's conversion."""
    if not (_int32_canonical(A) and kernels_usable()):
        return A.tocsc()
    T = csr_transposed(A)
    return compressed(T.data, T.indices, T.indptr, A.shape, fmt="csc", canonical=True)


def csr_without_zeros(A: sp.csr_matrix) -> sp.csr_matrix:
    """A copy of ``A`` without its explicit zeros (``B = A.copy(); B.eliminate_zeros()``): for a canonical CSR matrix
    with ``int32`` indices scipy's kernel of that (``csr_eliminate_zeros``) on copies of its arrays, canonical,
    without scipy's copy and checks (the same arrays); else scipy's."""
    if not (_int32_canonical(A) and kernels_usable()):
        B = A.copy()
        B.eliminate_zeros()
        return B
    data, indices, indptr = A.data.copy(), A.indices.copy(), A.indptr.copy()
    _sparsetools.csr_eliminate_zeros(A.shape[0], A.shape[1], indptr, indices, data)
    nnz = int(indptr[-1])
    if nnz < data.size:
        data, indices = data[:nnz].copy(), indices[:nnz].copy()
    return compressed(data, indices, indptr, A.shape, canonical=True)


@functools.cache
def kernels_usable() -> bool:
    """Whether scipy's kernels and sparse objects behave here as the functions of this module assume: checked
    once, on a small unsymmetric matrix with a repeated entry's sum and a cancelling one, against scipy's public
    operations (arrays equal bit for bit). False sends every function here to scipy's public path."""
    if _sparsetools is None:
        return False
    try:
        return _kernels_agree()
    except Exception:   # a changed kernel signature or object layout in another scipy version
        return False


def _kernels_agree() -> bool:
    """The check of :func:`kernels_usable` (raises or returns False where a kernel or object differs)."""
    rng = np.random.default_rng(7)
    n = 9
    dense = np.where(rng.random((n, n)) < 0.35, rng.standard_normal((n, n)), 0.0)
    dense[2, 5] = 1.0
    rows, cols = np.nonzero(dense)
    A = sp.csr_matrix(dense)
    B = sp.csr_matrix(np.where(dense != 0, -dense * (rng.random((n, n)) < 0.5), 0.0) + np.eye(n))
    x = rng.standard_normal(n)

    def same(M, R) -> bool:
        return (M.format == R.format and M.shape == R.shape and M.indices.dtype == R.indices.dtype
                and np.array_equal(M.indptr, R.indptr) and np.array_equal(M.indices, R.indices)
                and np.array_equal(M.data, R.data) and np.array_equal(M.toarray(), R.toarray()))

    held = _held(A.data.copy(), A.indices.astype(np.int32), A.indptr.astype(np.int32), A.shape, "csr")
    reference = sp.csr_matrix(dense)
    reference.sort_indices()
    S = sp.csr_matrix((dense[rows, cols], (rows, cols)), shape=(n, n))
    S.sort_indices()
    twice = rng.permutation(rows.size)[:6]   # places given two and three times, in shuffled order
    order = rng.permutation(rows.size + 9)
    repeated = tuple(np.concatenate([v, v[twice], v[twice[:3]]])[order] for v in (rows, cols, dense[rows, cols] + 0.1))
    checks = (
        same(held, reference) and repr(held) == repr(reference) and held.nnz == reference.nnz,
        np.array_equal(held @ x, A @ x),
        _raw_sorted(rows, cols, dense[rows, cols], n, S),
        _raw_sorted(*repeated, n, sp.csr_matrix((repeated[2], repeated[:2]), shape=(n, n))),
        _raw_matvec(A, x), _raw_matvec(A.tocsc(), x),
        _raw_matvec(A, np.column_stack([x, x[::-1]])), _raw_matvec(A.tocsc(), np.column_stack([x, x[::-1]])),
        _raw_sum(A, B), _raw_transposed(A), _raw_product(A, B), _raw_without_zeros(B),
    )
    return all(bool(c) for c in checks)


def _raw_sorted(rows, cols, values, n, S) -> bool:
    indptr, indices, data = np.empty(n + 1, np.int32), np.empty(rows.size, np.int32), np.empty(rows.size)
    _sparsetools.coo_tocsr(n, n, rows.size, rows.astype(np.int32), cols.astype(np.int32), values, indptr, indices, data)
    if not _sparsetools.csr_has_sorted_indices(n, indptr, indices):
        _sparsetools.csr_sort_indices(n, indptr, indices, data)
    if not _sparsetools.csr_has_canonical_format(n, indptr, indices):
        _sparsetools.csr_sum_duplicates(n, n, indptr, indices, data)
    k = int(indptr[-1])
    return (bool(_sparsetools.csr_has_canonical_format(n, indptr, indices[:k])) and np.array_equal(indptr, S.indptr)
            and np.array_equal(indices[:k], S.indices) and np.array_equal(data[:k], S.data))


def _raw_without_zeros(A) -> bool:
    Z = A.copy()
    Z.data[::2] = 0.0
    indptr, indices, data = Z.indptr.astype(np.int32), Z.indices.astype(np.int32), Z.data.copy()
    _sparsetools.csr_eliminate_zeros(Z.shape[0], Z.shape[1], indptr, indices, data)
    Z.eliminate_zeros()
    k = int(indptr[-1])
    return np.array_equal(indptr, Z.indptr) and np.array_equal(indices[:k], Z.indices) and np.array_equal(data[:k], Z.data)


def _raw_matvec(A, x) -> bool:
    M, N = A.shape
    y = np.zeros((M,) + x.shape[1:])
    indptr, indices = A.indptr.astype(np.int32), A.indices.astype(np.int32)
    if x.ndim == 1:
        kernel = _sparsetools.csr_matvec if A.format == "csr" else _sparsetools.csc_matvec
        kernel(M, N, indptr, indices, A.data, x, y)
    else:
        kernel = _sparsetools.csr_matvecs if A.format == "csr" else _sparsetools.csc_matvecs
        kernel(M, N, x.shape[1], indptr, indices, A.data, x.ravel(), y.ravel())
    return np.array_equal(y, A @ x)


def _raw_sum(A, B) -> bool:
    n, m = A.shape
    indptr, indices = np.empty(n + 1, np.int32), np.empty(A.nnz + B.nnz, np.int32)
    data = np.empty(A.nnz + B.nnz)
    _sparsetools.csr_plus_csr(n, m, A.indptr.astype(np.int32), A.indices.astype(np.int32), A.data,
                              B.indptr.astype(np.int32), B.indices.astype(np.int32), B.data, indptr, indices, data)
    R = (A + B).tocsr()
    k = int(indptr[-1])
    return np.array_equal(indptr, R.indptr) and np.array_equal(indices[:k], R.indices) and np.array_equal(data[:k], R.data)


def _raw_transposed(A) -> bool:
    n, m = A.shape
    indptr, indices, data = np.empty(m + 1, np.int32), np.empty(A.nnz, np.int32), np.empty(A.nnz)
    _sparsetools.csr_tocsc(n, m, A.indptr.astype(np.int32), A.indices.astype(np.int32), A.data, indptr, indices, data)
    R = A.T.tocsr()
    return np.array_equal(indptr, R.indptr) and np.array_equal(indices, R.indices) and np.array_equal(data, R.data)


def _raw_product(A, B) -> bool:
    n, m = A.shape[0], B.shape[1]
    a = (A.indptr.astype(np.int32), A.indices.astype(np.int32))
    b = (B.indptr.astype(np.int32), B.indices.astype(np.int32))
    nnz = _sparsetools.csr_matmat_maxnnz(n, m, *a, *b)
    indptr, indices, data = np.empty(n + 1, np.int32), np.empty(nnz, np.int32), np.empty(nnz)
    _sparsetools.csr_matmat(n, m, *a, A.data, *b, B.data, indptr, indices, data)
    R = (A @ B).tocsr()
    k = int(indptr[-1])
    return (np.array_equal(indptr, R.indptr) and np.array_equal(indices[:k], R.indices)
            and np.array_equal(data[:k], R.data))
