"""The layout checks on fine outlines evaluate only the pairs that can matter, with the same numbers.

:func:`bearingfe.geometry.surface._polyline_distance` and ``_polylines_cross`` prune the point-edge and
edge-edge pairs of polylines with more than ``_DENSE_PAIRS`` pairs through a k-d tree. The reference is
the dense evaluation of every pair (``_points_to_segments``, ``_crossing_matrix``): the distance must be
the same floating-point number (the pruned pairs are evaluated with the same arithmetic) and the crossing
verdict the same, on random star-shaped polylines that cross, touch, nest or lie far apart.
"""

import numpy as np

from bearingfe import Circle, Rectangle
from bearingfe.geometry.surface import (_DENSE_PAIRS, _crossing_matrix, _points_to_segments, _polyline_distance,
                                        _polylines_cross)


def _dense_distance(p, q):
    return float(min(_points_to_segments(p, q).min(), _points_to_segments(q, p).min()))


def _star(rng, n, centre, scale):
    t = np.sort(rng.uniform(0.0, 2.0 * np.pi, n))
    r = scale * (1.0 + 0.3 * rng.uniform(size=n))
    return np.array([centre[0] + r * np.cos(t), centre[1] + 0.6 * r * np.sin(t)])


def test_pruned_pairs_give_the_dense_numbers():
    rng = np.random.default_rng(7)
    crossing = apart = 0
    for trial in range(120):
        n, m = rng.integers(70, 300, 2)  # n m > _DENSE_PAIRS: the pruned path
        assert n * m > _DENSE_PAIRS
        p = _star(rng, n, (0.0, 0.0), 1.0)
        q = _star(rng, m, rng.normal(size=2) * 0.6, rng.uniform(0.05, 1.5))
        if trial % 4 == 0:
            q = q * 1e-3 + 3.0  # tiny and far away
        dense = bool(_crossing_matrix(p, q).any())
        assert _polylines_cross(p, q) == dense
        assert _polyline_distance(p, q) == _dense_distance(p, q)  # exactly: the same pair, the same arithmetic
        crossing += dense
        apart += not dense
    assert crossing > 10 and apart > 10  # both verdicts were checked


def test_shipped_kind_of_outline_and_pocket():
    # a pocket (circle) inside a rectangular outline, both as fine as Surface draws them; the gap is the
    # closed form 0.3 - 0.1 = 0.2 to the polylines' resolution, and the same number as the dense pairs
    outline = Rectangle((0.0, 0.0), (1.0, 0.6)).boundary(720)
    pocket = Circle((0.0, 0.0), 0.1).boundary(720)
    gap = _polyline_distance(pocket, outline)
    assert gap == _dense_distance(pocket, outline)
    assert abs(gap - 0.2) < 1e-3
    assert not _polylines_cross(pocket, outline)
    over = Circle((0.47, 0.28), 0.1234).boundary(720)  # reaches over the corner: crosses both edges there
    assert _polylines_cross(over, outline) and bool(_crossing_matrix(over, outline).any())
