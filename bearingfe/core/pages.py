"""Memory pages of the large arrays a solve allocates: NumPy's transparent-huge-page advice switched off.

NumPy advises the kernel to back every large array with transparent huge pages (``madvise(MADV_HUGEPAGE)``).
Where the kernel's ``transparent_hugepage/defrag`` setting is ``madvise`` (a common default), a fault in such
an array waits for the kernel to compact memory into a free 2 MB page: on a busy machine whose memory is
fragmented that is system time, paid on every fresh array. :func:`small_pages` keeps NumPy from giving that
advice while a large solve runs, so its arrays take ordinary 4 kB pages.
"""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Iterator

import numpy as np

__all__ = ["SMALL_PAGES", "small_pages"]

#: Whether :func:`small_pages` switches NumPy's huge-page advice off (read at each call). Measured on the JFO
#: solve of the 5 x 5 dimples at 600 x 600 cells (361,201 nodes; docs/jfo_dimples.md), two cold solves per
#: process, two processes each, load about 3 on 2 cores: 4.62-4.85 s CPU and 0.64-0.76 s system time a solve
#: without the advice, 5.34-5.86 s and 1.25-1.81 s with it (about twice the page faults without it, each far
#: cheaper); at 100 to 300 cells no slower (median CPU of 3-10 interleaved solves: 0.111 against 0.113 s,
#: 0.394 against 0.398 s, 1.12 against 1.21 s).
#: The finite-element Reynolds solve (linear, Swift-Stieber, Gumbel) and the elastic film solve use it too: CPU
#: median of cold solves, 3e5 P1 unknowns, 4.99 -> 3.91 s linear, 8.67 -> 8.13 Swift-Stieber, 5.66 -> 4.42 Gumbel
#: (system time about halved); elastic at 1e5 15.1-16.6 against 16.1-17.5 s; equal at 1e3 and 1e4. The kernel
#: grants huge pages only where its memory allows, so the gain varies with the machine's state.
SMALL_PAGES = True

_LOCK = threading.Lock()
#: Open :func:`small_pages` contexts in the process (any thread) and the advice before the first of them opened.
_OPEN = {"count": 0, "previous": True}


def _advice_switch():
    """NumPy's switch of its huge-page advice (``_set_madvise_hugepage``: takes the new setting, returns the
    previous one), or None where this NumPy has none."""
    core = getattr(np, "_core", None) or getattr(np, "core", None)
    multiarray = getattr(core, "multiarray", None)
    return getattr(multiarray, "_set_madvise_hugepage", None)


@contextlib.contextmanager
def small_pages() -> Iterator[None]:
    """Context in which NumPy allocates its arrays without the transparent-huge-page advice (where
    :data:`SMALL_PAGES` is set and NumPy has the switch); the setting before the first open context is
    restored when the last one closes.

    Arrays allocated inside keep their pages after the exit; it changes no value. The setting is NumPy's,
    for the whole process: a thread that allocates while another thread's context is open allocates without
    the advice too (the same values, a different cost). The contexts are counted across threads, so contexts
    of two threads that open and close interleaved leave the advice as it was before the first.
    """
    switch = _advice_switch() if SMALL_PAGES else None
    if switch is None:
        yield
        return
    with _LOCK:
        previous = bool(switch(False))
        if _OPEN["count"] == 0:
            _OPEN["previous"] = previous
        _OPEN["count"] += 1
    try:
        yield
    finally:
        with _LOCK:
            _OPEN["count"] -= 1
            if _OPEN["count"] == 0:
                switch(_OPEN["previous"])
