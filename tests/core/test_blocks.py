"""bearingfe.core.blocks: the one home of cutting index ranges into blocks (checked against its definition)."""

import numpy as np
import pytest

from bearingfe.core.blocks import blocks


@pytest.mark.parametrize("n, size", [(0, 3), (1, 3), (7, 3), (9, 3), (10, 1), (5, 16384)])
def test_blocks_cover_the_range_in_order_each_at_most_size(n, size):
    cut = blocks(n, size)
    # definition: consecutive, in order, every index once, each block non-empty and at most ``size``
    assert np.array_equal(np.concatenate([np.arange(n)[b] for b in cut] + [np.zeros(0, int)]), np.arange(n))
    assert all(0 < b.stop - b.start <= size for b in cut)
    assert len(cut) == -(-n // size)   # ceil(n / size) blocks


def test_blocks_refuse_a_size_below_one():
    with pytest.raises(ValueError, match="size must be >= 1"):
        blocks(5, 0)
