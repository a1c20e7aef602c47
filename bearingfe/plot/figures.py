"""Fixed figure layout, saving, and pictures drawn in parallel (matplotlib object API).

The pictures place their axes with margins and gaps given in inches
(:func:`frame`) instead of a layout engine: matplotlib's constrained or tight
layout measures every tick label and title before it draws, which cost more
than the physics of the main scene. :func:`save` writes with the package's
resolution, PNGs with light compression (files a little larger, several
times faster to write). :func:`draw_in_parallel` draws independent pictures
in forked processes when the process may use more than one core.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Callable, Sequence

__all__ = ["DPI", "PNG_COMPRESSION", "PROCESSES", "frame", "save", "draw_in_parallel"]

#: Resolution of the saved pictures [dots per inch].
DPI = 100
#: zlib level of the saved PNGs (0 none ... 9 smallest; PIL's default 6 takes several times longer).
PNG_COMPRESSION = 1
#: Processes :func:`draw_in_parallel` uses by default (``None``: the cores this process may use; 1: draw
#: everything here, e.g. to keep the figure objects).
PROCESSES: int | None = None


def frame(fig, *, top: float, bottom: float, left: float = 0.8, right: float = 0.25, nrows: int = 1, ncols: int = 1,
          wgap: float = 0.0, hgap: float = 0.0, **kwargs):
    """A :class:`~matplotlib.gridspec.GridSpec` of ``fig`` whose margins and gaps are given in inches.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    top, bottom, left, right : float
        Distance of the grid from the figure's edges [in] (room for titles, labels, tick labels).
    nrows, ncols : int
    wgap, hgap : float
        Gaps between the columns and between the rows [in].
    **kwargs
        Passed on (e.g. ``height_ratios``).
    """
    w, h = fig.get_size_inches()
    width = (w - left - right - (ncols - 1) * wgap) / ncols
    height = (h - top - bottom - (nrows - 1) * hgap) / nrows
    if width <= 0 or height <= 0:
        raise ValueError(f"figure of {w:.3g} x {h:.3g} in too small for its margins and gaps")
    return fig.add_gridspec(nrows, ncols, left=left / w, right=1.0 - right / w, top=1.0 - top / h,
                            bottom=bottom / h, wspace=wgap / width, hspace=hgap / height, **kwargs)


def save(fig, path):
    """Save ``fig`` at :data:`DPI` (format from the suffix; PNGs at :data:`PNG_COMPRESSION`); returns ``fig``."""
    if path is not None:
        png = Path(path).suffix.lower() == ".png"
        fig.savefig(path, dpi=DPI, **({"pil_kwargs": {"compress_level": PNG_COMPRESSION}} if png else {}))
    return fig


def _cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def draw_in_parallel(jobs: Sequence[Callable[[], list]], processes: int | None = None) -> list[list]:
    """Run picture jobs (each returns the list of files it wrote), some in forked child processes.

    The jobs are dealt round-robin to ``processes`` workers (default :data:`PROCESSES`; at most the
    number of jobs); worker 0 is this process, the others are ``fork`` children that
    inherit the data to draw (nothing is pickled but each job's file list and an error). Without
    ``fork`` (not POSIX) or with one core the jobs run here in turn. Returns the jobs' results in the
    order of ``jobs``; the first error of a child is raised again here.
    """
    processes = PROCESSES if processes is None else processes
    n = min(len(jobs), _cores() if processes is None else int(processes))
    if n < 2 or sys.platform == "win32" or not hasattr(os, "fork"):
        return [job() for job in jobs]
    import multiprocessing

    ctx = multiprocessing.get_context("fork")
    shares = [list(range(w, len(jobs), n)) for w in range(n)]

    def child(indices, conn):
        try:
            conn.send(("ok", [jobs[i]() for i in indices]))
        except BaseException as exc:  # reported to the parent, which raises it
            conn.send(("error", exc))
        finally:
            conn.close()

    children = []
    for indices in shares[1:]:
        here, there = ctx.Pipe(duplex=False)
        proc = ctx.Process(target=child, args=(indices, there), daemon=True)
        proc.start()
        there.close()
        children.append((indices, here, proc))
    results: list = [None] * len(jobs)
    for i in shares[0]:
        results[i] = jobs[i]()
    error = None
    for indices, conn, proc in children:
        try:
            status, value = conn.recv()
        except EOFError:
            status, value = "error", RuntimeError(f"a picture process ended without a result "
                                                  f"(exit code {proc.exitcode})")
        proc.join()
        if status == "error":
            error = error or value
        else:
            for i, files in zip(indices, value):
                results[i] = files
    if error is not None:
        raise error
    return results
