"""Blocks of consecutive indices: long vectorized passes cut into pieces whose temporaries stay in cache.

A numpy expression over a million points makes each temporary a new array of megabytes, memory the system
supplies page by page; the same expression over blocks of a few thousand reuses the same few cache-sized
temporaries. The block sizes are set where the pass lives (each documented with its measurement); this module
is the one home of the cutting.
"""

from __future__ import annotations

__all__ = ["blocks"]


def blocks(n: int, size: int) -> list[slice]:
    """Consecutive slices of at most ``size`` indices covering ``range(n)``.

    Parameters
    ----------
    n : int
        Number of indices, >= 0.
    size : int
        Largest block, >= 1.

    Returns
    -------
    list of slice
        ``[slice(0, size), slice(size, 2 size), ..., slice(., n)]`` (empty for ``n = 0``).
    """
    if size < 1:
        raise ValueError(f"size must be >= 1, got {size!r}")
    return [slice(lo, min(lo + size, n)) for lo in range(0, n, size)]
