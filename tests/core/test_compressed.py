"""Sparse matrices from arrays at hand (bearingfe.core.compressed): scipy's kernels called directly give, bit for
bit, what scipy's public operations give; and where those kernels are not usable, the public path gives it."""

import numpy as np
import pytest
import scipy.sparse as sp

from bearingfe.core import compressed as cm


@pytest.mark.parametrize("fmt", ["csr", "csc"])
def test_compressed_is_scipys_matrix_of_the_same_arrays(fmt):
    """compressed() holds the given int32 arrays themselves and gives the matrix scipy's constructor gives (the
    same class, shape, arrays and products); other index dtypes go through scipy's constructor (int64 indices
    of a small matrix come back as scipy's int32)."""
    from bearingfe.core.compressed import compressed

    cls = sp.csr_matrix if fmt == "csr" else sp.csc_matrix
    A = cls(sp.random(40, 30, density=0.2, random_state=3))
    A.sum_duplicates()
    data, indices, indptr = A.data, A.indices.astype(np.int32), A.indptr.astype(np.int32)
    B = compressed(data, indices, indptr, A.shape, fmt=fmt, canonical=True)
    ref = cls((data, indices, indptr), shape=A.shape)
    assert type(B) is type(ref) and B.shape == ref.shape and B.format == fmt
    assert B.data is data and B.indices is indices and B.indptr is indptr
    assert B.has_canonical_format and B.has_sorted_indices
    x = np.arange(30.0)
    assert np.array_equal(B @ x, ref @ x) and np.array_equal((B + ref).toarray(), 2 * ref.toarray())
    assert repr(B) == repr(ref)
    wide = compressed(data, indices.astype(np.int64), indptr.astype(np.int64), A.shape, fmt=fmt)
    assert wide.indices.dtype == ref.indices.dtype and np.array_equal(wide.toarray(), ref.toarray())
    with pytest.raises(ValueError, match="index pointer"):   # inconsistent arrays: scipy's checks see them
        compressed(data[:-1], indices[:-1], indptr, A.shape, fmt=fmt)


def test_compressed_refuses_an_unknown_format():
    from bearingfe.core.compressed import compressed

    with pytest.raises(ValueError, match="fmt"):
        compressed(np.ones(1), np.zeros(1, np.int32), np.array([0, 1], np.int32), (1, 1), fmt="coo")


@pytest.mark.parametrize("fmt", ["csr", "csc"])
def test_matvec_is_scipys_product(fmt):
    """matvec() calls scipy's kernel of A @ x directly: the same vector bit for bit on random matrices (int32 and
    int64 indices, a strided vector), and scipy's kernel of several columns on 2-D right sides (C and Fortran
    order, a column slice); other inputs (a coo matrix, one column, integer values) go through A @ x and give its
    answer."""
    from bearingfe.core.compressed import matvec

    rng = np.random.default_rng(2)
    for k in range(6):
        n, m = (int(v) for v in rng.integers(1, 50, size=2))
        A = sp.random(n, m, density=0.3, random_state=k, format=fmt)
        x = rng.normal(size=2 * m)[::2]   # strided
        assert np.array_equal(matvec(A, x), A @ x)
        wide = A.copy()
        wide.indices, wide.indptr = wide.indices.astype(np.int64), wide.indptr.astype(np.int64)
        assert np.array_equal(matvec(wide, x), A @ x)
        X = rng.normal(size=(m, 5))
        for right in (X, np.asfortranarray(X), X[:, 1:4], X[:, :1]):
            got = matvec(A, right)
            assert got.shape == (n, right.shape[1]) and np.array_equal(got, A @ right)
    assert np.array_equal(matvec(A.tocoo(), x), A @ x)
    ints = np.arange(m)
    assert np.array_equal(matvec(A, ints), A @ ints)


def test_csr_of_keeps_a_csr_matrix_and_converts_the_rest():
    """csr_of() returns a csr_matrix itself (the arrays scipy's constructor would wrap again) and converts any
    other input as sp.csr_matrix does (CSC, COO, dense: the same arrays)."""
    A = sp.random(9, 7, density=0.3, random_state=3, format="csr")
    assert cm.csr_of(A) is A
    for other in (A.tocsc(), A.tocoo(), A.toarray()):
        got, want = cm.csr_of(other), sp.csr_matrix(other)
        assert type(got) is sp.csr_matrix
        for name in ("indptr", "indices", "data"):
            assert np.array_equal(getattr(got, name), getattr(want, name))


def test_scipys_kernels_are_usable_here():
    """The check of scipy's private kernels and object layout passes on the scipy installed with the package: the
    fast path is the one the film solves take (a scipy that changes them sends every function to its public path,
    with the same results: the next test)."""
    assert cm.kernels_usable()


def test_every_function_gives_scipys_arrays_on_either_path(monkeypatch):
    """Each function of the module, on the kernels and with them declared unusable, gives the arrays of scipy's
    public operation (reference: scipy's constructor, conversion, sum, transpose, sparse and vector products), bit
    for bit."""
    rng = np.random.default_rng(19)
    n = 23
    A = sp.random(n, n, density=0.2, random_state=4, format="csr")
    B = sp.random(n, n, density=0.2, random_state=5, format="csr")
    x = rng.normal(size=n)
    rows, cols = np.nonzero(A.toarray())
    values = A.toarray()[rows, cols]
    Z = A.copy()   # explicit zeros: every third stored entry, the first and the last
    Z.data[::3], Z.data[-1] = 0.0, 0.0

    def results():
        return {"compressed": cm.compressed(A.data, A.indices, A.indptr, A.shape, canonical=True),
                "sum": cm.csr_sum(A, B), "product": cm.csr_product(A, B), "transposed": cm.csr_transposed(A), "csc": cm.csc_of(A),
                "sorted": cm.sorted_entries(rows, cols, values, n), "matvec": cm.matvec(A, x),
                "without_zeros": cm.csr_without_zeros(Z)}

    want = {"compressed": A, "sum": (A + B).tocsr(), "product": (A @ B).tocsr(), "transposed": A.T.tocsr(), "csc": A.tocsc(),
            "sorted": sp.csr_matrix((values, (rows, cols)), shape=(n, n)), "matvec": A @ x, "without_zeros": Z.copy()}
    want["without_zeros"].eliminate_zeros()
    want["sorted"].sort_indices()
    fast = results()
    monkeypatch.setattr(cm, "kernels_usable", lambda: False)
    public = results()
    for got in (fast, public):
        assert np.array_equal(got["matvec"], want["matvec"])
        for key in ("compressed", "sum", "product", "transposed", "csc", "sorted", "without_zeros"):
            assert got[key].format == want[key].format and got[key].shape == want[key].shape
            for name in ("indptr", "indices", "data"):
                assert np.array_equal(getattr(got[key], name), getattr(want[key], name)), (key, name)


def test_sorted_entries_sums_repeated_places_as_scipys_conversion(monkeypatch):
    """Places given two and three times, in shuffled order (as the P1 stiffness of a fresh mesh gives each edge's
    terms both ways): sorted_entries sums them as scipy's conversion does (``coo_tocsr``, ``csr_sort_indices``,
    ``csr_sum_duplicates``), the same arrays bit for bit (reference: ``sp.csr_matrix((values, (rows, cols)))``),
    on the kernels and on the public path; entries that sum to zero are kept, as scipy keeps them; already sorted
    places (no sort needed) too."""
    rng = np.random.default_rng(23)
    n = 31
    places = rng.permutation(n * n)[:200]
    places = np.concatenate([places, places[:60], places[:20]])[rng.permutation(280)]
    rows, cols = places // n, places % n
    values = rng.normal(size=places.size)
    values[places == places[0]] = [1.5, -1.5, 0.0][: int(np.sum(places == places[0]))]
    for order in (np.arange(places.size), np.argsort(places, kind="stable")):
        want = sp.csr_matrix((values[order], (rows[order], cols[order])), shape=(n, n))
        got = cm.sorted_entries(rows[order], cols[order], values[order], n)
        with monkeypatch.context() as m:
            m.setattr(cm, "kernels_usable", lambda: False)
            public = cm.sorted_entries(rows[order], cols[order], values[order], n)
        for M in (got, public):
            assert M.has_canonical_format and M.nnz == 200
            for name in ("indptr", "indices", "data"):
                assert np.array_equal(getattr(M, name), getattr(want, name)), name
                assert getattr(M, name).dtype == getattr(want, name).dtype
