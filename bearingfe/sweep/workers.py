"""Local worker processes of a design study: a time limit per case, no worker outlives its parent.

:func:`run_pool` runs ``function(*args)`` for each task in ``spawn``
processes (gmsh and the sparse factorizations are not thread-safe) and
yields the results as they finish. Unlike a ``ProcessPoolExecutor`` it

- kills the worker of a case that runs past ``time_limit`` and reports the
  case as failed (the other cases go on, in a fresh worker);
- reports a worker that dies (out of memory, killed) as a failed case;
- kills every worker when the parent leaves the loop for any reason
  (exception, Ctrl-C, SIGTERM turned into an exception by the caller);
- makes every worker end with its parent even when the parent is killed
  outright (SIGKILL): on Linux the kernel sends the worker SIGKILL when the
  parent dies (``prctl(PR_SET_PDEATHSIG)``), and on every platform a thread
  in the worker checks twice a second that its parent is still the process
  that started it.

The same module is the Dask worker preload the command line gives the
``LocalCluster`` it starts (``--scheduler local``): :func:`dask_setup` ties
each Dask worker process to the process that started it in the same way.
Dask's own tie (a thread waiting on a pipe) cannot run while a case holds
the GIL in compiled code, so without it such a worker outlives a killed parent.
"""

from __future__ import annotations

import math
import os
import sys
import threading
import time
from collections import deque
from typing import Any, Callable, Iterator

__all__ = ["CaseTimeout", "dask_setup", "run_pool"]

_STARTUP_GRACE = 120.0  # s a fresh worker may take to import the package before its case counts


class CaseTimeout(Exception):
    """A case ran past its time limit (its worker was killed)."""


def _die_with_parent(parent_pid: int) -> None:
    """End this process when ``parent_pid`` ends (Linux: PR_SET_PDEATHSIG; everywhere: a watcher thread)."""
    import signal

    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, int(signal.SIGKILL), 0, 0, 0)  # PR_SET_PDEATHSIG = 1
        except (OSError, AttributeError):
            pass  # the watcher below still ends it
    if os.getppid() != parent_pid:  # the parent died before the line above took effect
        os._exit(1)

    def watch() -> None:
        while True:
            time.sleep(0.5)
            if os.getppid() != parent_pid:
                os._exit(1)

    threading.Thread(target=watch, name="bearingfe-parent-watch", daemon=True).start()


def dask_setup(worker: Any = None) -> None:
    """Dask preload hook (``preload=["bearingfe.sweep.workers"]``): end this worker process with its parent.

    Parameters
    ----------
    worker : distributed.Worker, optional
        The worker being started (unused: the tie is per process).
    """
    _die_with_parent(os.getppid())


def _worker_main(conn, parent_pid: int) -> None:
    """Loop of a worker process: receive ``(function, args)``, send ``("started",)`` then the result."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C goes to the parent, which ends the workers
    _die_with_parent(parent_pid)
    while True:
        try:
            message = conn.recv()
        except (EOFError, OSError):
            return  # the parent closed its end
        if message is None:
            return
        conn.send(("started",))
        function, args = message
        try:
            conn.send(("done", function(*args)))
        except Exception as exc:  # the function raised or its result does not pickle
            conn.send(("error", f"{type(exc).__name__}: {exc}"))


class _Worker:
    def __init__(self, ctx):
        parent_end, child_end = ctx.Pipe()
        self.process = ctx.Process(target=_worker_main, args=(child_end, os.getpid()), daemon=True,
                                   name="bearingfe-sweep-worker")
        self.process.start()
        child_end.close()
        self.conn = parent_end
        self.key: Any = None
        self.deadline = math.inf

    def kill(self) -> None:
        if self.process.is_alive():
            self.process.kill()
        self.process.join(5)
        self.conn.close()


def run_pool(tasks: dict, function: Callable, args_of: Callable[[Any], tuple], *, max_workers: int,
             time_limit: float) -> Iterator[tuple[Any, bool, Any]]:
    """Run ``function(*args_of(task))`` for every task in worker processes; yield as they finish.

    Parameters
    ----------
    tasks : dict
        ``{key: task}``; ``args_of(task)`` gives the arguments (picklable).
    function : callable
        A top-level (picklable) function.
    max_workers : int
        Processes at most (fewer if there are fewer tasks).
    time_limit : float
        Seconds one task may run [s] (from when its worker picks it up).

    Yields
    ------
    (key, ok, value)
        ``ok`` True: ``value`` is the result; False: a one-line reason
        (time limit, worker died, the function raised).
    """
    import multiprocessing
    from multiprocessing.connection import wait

    ctx = multiprocessing.get_context("spawn")
    pending = deque(tasks.items())
    n = max(1, min(max_workers, len(pending)))
    idle: list[_Worker] = []
    busy: dict[Any, _Worker] = {}  # connection -> worker
    try:
        while pending or busy:
            while pending and len(busy) < n:
                key, task = pending.popleft()
                worker = idle.pop() if idle else _Worker(ctx)
                try:
                    worker.conn.send((function, args_of(task)))
                except Exception as exc:  # the task does not pickle
                    idle.append(worker)
                    yield key, False, f"{type(exc).__name__}: cannot send the case to a worker: {exc}"
                    continue
                worker.key, worker.deadline = key, time.monotonic() + time_limit + _STARTUP_GRACE
                busy[worker.conn] = worker
            now = time.monotonic()
            timeout = max(0.0, min(w.deadline for w in busy.values()) - now) if busy else 0.0
            for conn in wait(list(busy), timeout=min(timeout, 3600.0)):
                worker = busy[conn]
                try:
                    message = conn.recv()
                except (EOFError, OSError):
                    del busy[conn]
                    worker.kill()
                    code = worker.process.exitcode
                    yield worker.key, False, f"WorkerDied: the worker process ended (exit code {code}) during the case"
                    continue
                if message[0] == "started":
                    worker.deadline = time.monotonic() + time_limit
                    continue
                del busy[conn]
                idle.append(worker)
                yield worker.key, message[0] == "done", message[1]
            now = time.monotonic()
            for conn, worker in list(busy.items()):
                if now >= worker.deadline:
                    del busy[conn]
                    worker.kill()
                    yield worker.key, False, (f"CaseTimeout: the case ran past its time limit of {time_limit:g} s "
                                              f"and was stopped (raise it with sweep(time_limit=...) or "
                                              f"[study] time_limit)")
    finally:
        for worker in list(busy.values()) + idle:
            if worker.process.is_alive() and worker in idle:
                try:
                    worker.conn.send(None)
                except OSError:
                    pass
            worker.kill()
