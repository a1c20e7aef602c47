"""Nested dissection (bearingfe.core.ordering): a permutation whose separators separate, and that fills less.

Expected values: the structure of nested dissection (a separator eliminated after the parts it
separates disconnects them; on an m x m grid the top separator has m vertices when cut by
coordinates) and the fill measured against SuperLU's minimum degree on A^T + A
(benchmarks/orderings.py: 0.92 of it on the gmsh P1 matrix of about 1e4 unknowns below).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.sparse.csgraph import connected_components

import bearingfe as bf
from bearingfe.core.ordering import grid_dissection, nested_dissection
from benchmarks.orderings import matrix

SYM = dict(diag_pivot_thresh=0.0, options={"SymmetricMode": True})


def _grid(m: int):
    """The 5-point pattern of an m x m grid and its vertex coordinates (row-major numbering)."""
    line = sp.diags([1.0, 1.0], [-1, 1], shape=(m, m))
    eye = sp.identity(m)
    A = (sp.kron(eye, line) + sp.kron(line, eye) + 4.0 * sp.identity(m * m)).tocsr()
    x, y = np.meshgrid(np.arange(m, dtype=float), np.arange(m, dtype=float))
    return A, np.stack([x.ravel(), y.ravel()])


def _fill(A, order=None) -> int:
    if order is None:
        lu = spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A", **SYM)
    else:
        lu = spla.splu(sp.csc_matrix(A)[order][:, order].tocsc(), permc_spec="NATURAL", **SYM)
    return lu.L.nnz + lu.U.nnz


@pytest.mark.parametrize("by", ["graph", "coordinates"])
def test_the_order_is_a_permutation_whose_last_vertices_separate_the_rest(by):
    m = 61
    A, xy = _grid(m)
    order = nested_dissection(A, xy if by == "coordinates" else None)
    np.testing.assert_array_equal(np.sort(order), np.arange(m * m))
    # the last vertices are the top separator: by coordinates a cut across the grid at the median (m
    # vertices; a step where the median falls inside a grid line); from the graph a level of a
    # breadth-first search, a diagonal of at most m vertices on this grid plus the vertices of the
    # level before it where the median splits it. Removing them leaves two halves.
    top = m if by == "coordinates" else 2 * m
    for size in range(m // 2, top + 1):
        rest = np.sort(order[: m * m - size])
        count, label = connected_components(A[rest][:, rest], directed=False)
        if count == 2:
            break
    else:
        raise AssertionError(f"no top separator of at most {top} vertices")
    halves = np.bincount(label)
    assert halves.min() >= 0.4 * rest.size


def test_grid_dissection_cuts_at_the_middle_line_and_fills_as_the_coordinate_dissection():
    # the closed form on a grid's line numbers: a permutation, the last m vertices the middle line (whose
    # removal leaves two halves of equal size), every separator after the box it cuts; the fill within 5 %
    # of nested_dissection by coordinates (the same cuts, its separators from the graph: measured 0.7 % more
    # on the 600 x 600 dimple grid, 0.98 here and 0.97 with a hole, as a grid's pocket makes one)
    m = 61
    A, xy = _grid(m)
    index = xy.astype(np.int64)
    order = grid_dissection(index)
    np.testing.assert_array_equal(np.sort(order), np.arange(m * m))
    top = order[-m:]
    assert np.unique(index[0, top]).size == 1 and index[0, top[0]] == m // 2
    rest = np.sort(order[:-m])
    count, label = connected_components(A[rest][:, rest], directed=False)
    assert count == 2 and np.bincount(label).tolist() == [m * (m // 2)] * 2
    assert _fill(A, order) <= 1.05 * _fill(A, nested_dissection(A, xy))
    hole = (np.abs(index[0] - 20) < 6) & (np.abs(index[1] - 40) < 9)
    keep = np.flatnonzero(~hole)
    holed = grid_dissection(index[:, keep])
    np.testing.assert_array_equal(np.sort(holed), np.arange(keep.size))
    assert _fill(A[keep][:, keep], holed) <= 1.05 * _fill(A[keep][:, keep], nested_dissection(A[keep][:, keep], xy[:, keep]))
    assert grid_dissection(np.zeros((2, 0), dtype=int)).size == 0
    with pytest.raises(ValueError, match="leaf"):
        grid_dissection(index, leaf=1)
    with pytest.raises(ValueError, match="index must be an integer array"):
        grid_dissection(xy)


def test_disconnected_and_tiny_patterns():
    A, xy = _grid(20)
    two = sp.block_diag([A, A, sp.identity(3)]).tocsr()       # two grids and three isolated vertices
    for coordinates in (None, np.hstack([xy, xy + 100.0, np.zeros((2, 3))])):
        order = nested_dissection(two, coordinates)
        np.testing.assert_array_equal(np.sort(order), np.arange(two.shape[0]))
    assert nested_dissection(sp.csr_matrix((0, 0))).size == 0
    np.testing.assert_array_equal(nested_dissection(sp.identity(1).tocsr()), [0])


def test_nested_dissection_fills_less_than_minimum_degree_on_a_gmsh_mesh():
    # measured: 0.92 of minimum degree's fill with coordinates, 1.04 from the graph alone, at 9834
    # unknowns (benchmarks/orderings.py; the graph-alone order wins from ~3e4 unknowns on)
    A, xy = matrix("gmsh", "P1", 1e4)
    mmd = _fill(A)
    assert _fill(A, nested_dissection(A, xy)) <= 0.95 * mmd
    assert _fill(A, nested_dissection(A)) <= 1.10 * mmd


def test_bad_input_is_named():
    A, xy = _grid(5)
    with pytest.raises(ValueError, match="leaf"):
        nested_dissection(A, leaf=1)
    with pytest.raises(ValueError, match="square"):
        nested_dissection(sp.csr_matrix(np.ones((2, 3))))
    with pytest.raises(ValueError, match="coordinates must have shape"):
        nested_dissection(A, xy[:, :-1])
    with pytest.raises(ValueError, match="finite"):
        nested_dissection(A, np.full_like(xy, math.nan))
    with pytest.raises(ValueError, match="sparse"):
        nested_dissection(np.ones((3, 3)))


def test_factorize_splu_sym_with_coordinates_gives_minimum_degrees_solution(monkeypatch):
    # the same SPD matrix factored in two orders without pivoting: equal to round-off (measured 1.3e-14
    # relative on this gmsh P2 matrix; 1e-12 allows the other orders of summation of other machines)
    from bearingfe.core import linalg

    A, xy = matrix("gmsh", "P2", 3e3)
    b = np.random.default_rng(1).standard_normal((A.shape[0], 3))
    reference = linalg.factorize_splu_sym(A)(b)
    monkeypatch.setattr(linalg, "NESTED_DISSECTION_FROM", 0)
    for rhs, ref in ((b, reference), (b[:, 0], reference[:, 0])):
        x = linalg.factorize_splu_sym(A, xy)(rhs)
        assert x.shape == ref.shape
        assert np.abs(x - ref).max() <= 1e-12 * np.abs(reference).max()


def test_grid_dissection_order_is_the_one_of_record():
    """The exact order on a 7 x 5 grid of lines, whole (leaves of 2) and with a hole on its middle line (leaves of
    3): the order the implementation gave before its separators' second line numbers were gathered for them
    alone (recorded from it; a change of order changes the factorizations' round-off)."""
    i, j = np.meshgrid(np.arange(7), np.arange(5), indexing="ij")
    index = np.stack([i.ravel(), j.ravel()])
    assert grid_dissection(index, leaf=2).tolist() == [
        0, 1, 10, 11, 3, 4, 13, 14, 20, 21, 30, 31, 23, 24, 33, 34, 5, 6, 8, 9, 25, 26, 28, 29, 2, 7, 12, 22, 27, 32,
        15, 16, 17, 18, 19]
    keep = ~((index[0] == 3) & (index[1] >= 1) & (index[1] <= 2))
    assert grid_dissection(index[:, keep], leaf=3).tolist() == [
        0, 1, 10, 11, 3, 4, 13, 14, 18, 19, 28, 29, 21, 22, 31, 32, 5, 6, 8, 9, 23, 24, 26, 27, 2, 7, 12, 20, 25, 30,
        15, 16, 17]
