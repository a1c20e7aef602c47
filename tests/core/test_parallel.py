"""Jobs shared with forked processes (bearingfe.core.parallel)."""

from __future__ import annotations

import os
from types import MappingProxyType

import pytest

from bearingfe.core.parallel import in_processes


def _job(path, k):
    def job():
        path.write_text(str(os.getpid()))
        return {"k": k, "frozen": MappingProxyType({"pid": os.getpid()})}
    return job


def test_jobs_run_in_two_processes_and_keep_their_order(tmp_path):
    """Four jobs on two workers: this process runs the 1st and 3rd, a forked child the others; the
    results (a frozen mapping included) come back in the jobs' order, the same as with one worker."""
    jobs = [_job(tmp_path / f"{k}.txt", k) for k in range(4)]
    results = in_processes(jobs, processes=2)
    assert [r["k"] for r in results] == [0, 1, 2, 3]
    pids = [r["frozen"]["pid"] for r in results]
    assert isinstance(results[1]["frozen"], MappingProxyType)
    assert pids[0] == pids[2] == os.getpid() and pids[1] == pids[3] != os.getpid()
    assert [int((tmp_path / f"{k}.txt").read_text()) for k in range(4)] == pids
    serial = in_processes(jobs, processes=1)
    assert [r["k"] for r in serial] == [0, 1, 2, 3] and {r["frozen"]["pid"] for r in serial} == {os.getpid()}


def test_an_error_in_a_child_is_raised_here(tmp_path):
    def bad():
        raise ValueError("no such design")

    with pytest.raises(ValueError, match="no such design"):
        in_processes([_job(tmp_path / "a.txt", 0), bad], processes=2)


def test_a_child_that_dies_is_an_error(tmp_path):
    def dies():
        os._exit(3)

    with pytest.raises(RuntimeError, match="ended without a result"):
        in_processes([_job(tmp_path / "a.txt", 0), dies], processes=2)


def test_after_fork_runs_here_once_after_the_children_exist(tmp_path):
    """after_fork runs in this process only (not in a child), once, whether or not children are forked."""
    calls = []
    in_processes([_job(tmp_path / f"{k}.txt", k) for k in range(2)], processes=2,
                 after_fork=lambda: calls.append(os.getpid()))
    in_processes([_job(tmp_path / "c.txt", 0)], processes=1, after_fork=lambda: calls.append(os.getpid()))
    assert calls == [os.getpid(), os.getpid()]


def test_preload_loads_the_picture_modules_without_drawing():
    """plot.preload imports matplotlib's figure machinery in a thread; no pyplot state."""
    import sys

    from bearingfe.plot import preload

    preload().join()
    assert "matplotlib.figure" in sys.modules and "matplotlib.backends.backend_agg" in sys.modules
    assert "matplotlib.pyplot" not in sys.modules or sys.modules["matplotlib.pyplot"].get_fignums() == []
