"""Independent jobs of one run shared with forked processes when the process may use more than one core.

A scene's designs and pictures are independent of each other: :func:`in_processes` runs a list of
jobs (functions of no argument) on ``processes`` workers, this process being one of them and the
others ``fork`` children that inherit everything the jobs need (meshes, caches, results), so nothing
is pickled on the way out; each child's results come back pickled (a frozen mapping,
:class:`types.MappingProxyType`, included). With one core, or without ``fork`` (not POSIX), the jobs
run here in turn: the results are the same either way.
"""

from __future__ import annotations

import copyreg
import io
import os
import pickle
import signal
import sys
from types import MappingProxyType
from typing import Any, Callable, Sequence

__all__ = ["PROCESSES", "cores", "in_processes"]

#: Workers :func:`in_processes` uses by default (``None``: the cores this process may use; 1: every job
#: in this process, e.g. to keep objects a job makes that are not returned).
PROCESSES: int | None = None


def cores() -> int:
    """The cores this process may use (its CPU affinity where the system tells it)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def _frozen(items: dict) -> MappingProxyType:
    return MappingProxyType(items)


def _dumps(value) -> bytes:
    """``pickle.dumps`` that also takes frozen mappings (rebuilt as frozen mappings)."""
    buffer = io.BytesIO()
    pickler = pickle.Pickler(buffer, protocol=pickle.HIGHEST_PROTOCOL)
    pickler.dispatch_table = copyreg.dispatch_table.copy()
    pickler.dispatch_table[MappingProxyType] = lambda m: (_frozen, (dict(m),))
    pickler.dump(value)
    return buffer.getvalue()


def _child(jobs, indices, conn) -> None:
    """A worker's share: its jobs' results, or the first error, sent to the parent."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)  # a stopped run ends the child at once, with no clean-up
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # of the parent's (inherited handlers)
    try:
        message = ("ok", [jobs[i]() for i in indices])
    except BaseException as exc:  # the parent raises it
        message = ("error", exc)
    try:
        data = _dumps(message)
    except Exception as exc:  # a result or an error that does not pickle
        data = _dumps(("error", RuntimeError(f"{type(exc).__name__}: {exc} (in a child process: "
                                             f"{str(message[1])[:200]})")))
    conn.send_bytes(data)
    conn.close()


def in_processes(jobs: Sequence[Callable[[], Any]], processes: int | None = None, *,
                 after_fork: Callable[[], Any] | None = None) -> list:
    """The results of ``jobs`` (functions of no argument), in their order, run on ``processes`` workers.

    Parameters
    ----------
    jobs : sequence of callables
        Independent jobs; those given to children must return picklable results (frozen mappings are).
    processes : int, optional
        Workers (default :data:`PROCESSES`, at most the number of jobs). Jobs are dealt round-robin:
        worker 0 (this process) runs jobs 0, n, 2n, ...; give the dearest first.
    after_fork : callable, optional
        Called in this process once the children exist, before its own jobs (e.g. to start a thread, which
        must not run while a process forks: the child would inherit its locks held).

    Raises
    ------
    Exception
        The first error of a job (this process's own first, then the children's in order).
    """
    processes = PROCESSES if processes is None else processes
    n = min(len(jobs), cores() if processes is None else max(1, int(processes)))
    if n < 2 or sys.platform == "win32" or not hasattr(os, "fork"):
        if after_fork is not None:
            after_fork()
        return [job() for job in jobs]
    import multiprocessing

    ctx = multiprocessing.get_context("fork")
    shares = [list(range(w, len(jobs), n)) for w in range(n)]
    children = []
    try:
        for indices in shares[1:]:
            here, there = ctx.Pipe(duplex=False)
            proc = ctx.Process(target=_child, args=(jobs, indices, there), daemon=True)
            proc.start()
            there.close()
            children.append((indices, here, proc))
        results: list = [None] * len(jobs)
        if after_fork is not None:
            after_fork()
        for i in shares[0]:
            results[i] = jobs[i]()
        error = None
        for indices, conn, proc in children:
            try:
                status, value = pickle.loads(conn.recv_bytes())
            except EOFError:
                status, value = "error", RuntimeError(f"a child process ended without a result "
                                                      f"(exit code {proc.exitcode})")
            if status == "error":
                error = error or value
            else:
                for i, result in zip(indices, value):
                    results[i] = result
        if error is not None:
            raise error
        return results
    finally:
        for _, conn, proc in children:
            conn.close()
            if proc.is_alive():
                proc.terminate()
            proc.join()
