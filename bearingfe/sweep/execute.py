"""Execution of a design study: cases in processes or on Dask, a resumable cache, one table.

Each case runs in its own process (gmsh and the sparse factorizations are
not thread-safe): local ``spawn`` processes by default, or the workers of a
``dask.distributed`` client (a ``LocalCluster`` or any scheduler address).
The worker function :func:`run_case` is pure: parameter object in, plain
record out; the parent process alone reads and writes the on-disk cache, so
workers on other machines need no shared file system. A case that raises,
or whose worker dies, is recorded as a failed row, never dropped.

The table is a :class:`pandas.DataFrame` (one row per case, in the order of
the cases): its columns mix floats (outputs), strings (errors, categorical
inputs such as a pocket shape) and booleans, it must hold ragged lists of
cases and failed rows as well as full grids, and it writes straight to CSV;
a pivot turns a grid back into a 2-D array for contour plots. (An
``xarray.Dataset`` fits only full grids of numeric inputs.)
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import time
from pathlib import Path
from typing import Iterable, Mapping, Sequence

from ..version import __version__
from .cases import RUNS
from .changes import apply_changes, check_change_name, expand_cases
from .outputs import OUTPUTS, STANDARD_OUTPUTS

__all__ = ["best_design", "case_key", "run_case", "sweep"]


# -- one case -----------------------------------------------------------------------

def _name_of(function) -> str:
    """``module:qualname`` of a function (a name passes through), as cache keys spell it.

    Functions of this package's modules are named as if they were still in the
    one ``bearingfe.sweep`` module, so keys written before the split still match.
    """
    if isinstance(function, str):
        return function
    module = function.__module__
    if module.startswith(f"{__package__}."):
        module = __package__
    return f"{module}:{function.__qualname__}"


def _version() -> str:
    return __version__


def case_key(design, run, outputs: Sequence) -> str:
    """Stable hash of a case: the changed object's repr, run and output names, package version."""
    text = "|".join([_version(), _name_of(run), ",".join(_name_of(o) for o in outputs), repr(design)])
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def _resolve(name_or_function, table: Mapping, what: str):
    if callable(name_or_function):
        return name_or_function
    if name_or_function not in table:
        raise ValueError(f"{what} must be one of {sorted(table)} or a function, got {name_or_function!r}")
    return table[name_or_function]


def run_case(design, run, outputs: Sequence) -> dict:
    """Run one case and reduce it to outputs; never raises.

    Returns ``{"outputs": {name: float}, "seconds": float, "error": str | None}``
    (outputs NaN on error). Top-level and pure, so it pickles to any worker.
    """
    start = time.perf_counter()
    try:
        result = _resolve(run, RUNS, "run")(design)
        values = {_output_name(o): float(_resolve(o, OUTPUTS, "output")(result)) for o in outputs}
        error = None
    except Exception as exc:  # recorded in the table, never dropped
        values = {_output_name(o): math.nan for o in outputs}
        error = f"{type(exc).__name__}: {exc}"
    return {"outputs": values, "seconds": time.perf_counter() - start, "error": error}


def _output_name(output) -> str:
    return output if isinstance(output, str) else output.__name__


# -- executors --------------------------------------------------------------------

def _run_local(tasks: dict, run, outputs, max_workers, progress: bool) -> Iterable[tuple[str, dict]]:
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed

    from tqdm.auto import tqdm

    workers = max(1, min(max_workers or os.cpu_count() or 1, len(tasks)))
    with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn")) as pool:
        futures = {pool.submit(run_case, design, run, outputs): key for key, design in tasks.items()}
        for future in tqdm(as_completed(futures), total=len(futures), disable=not progress, desc="cases"):
            yield futures[future], _record(future, outputs)


def _run_dask(client, tasks: dict, run, outputs, progress: bool) -> Iterable[tuple[str, dict]]:
    from distributed import as_completed
    from tqdm.auto import tqdm

    futures = {client.submit(run_case, design, run, outputs, key=f"bearingfe-case-{key}"): key
               for key, design in tasks.items()}
    for future in tqdm(as_completed(list(futures)), total=len(futures), disable=not progress, desc="cases"):
        yield futures[future], _record(future, outputs)
        future.release()


def _record(future, outputs) -> dict:
    """The case record of a finished future; a dead worker or lost task becomes an error."""
    try:
        return future.result()
    except Exception as exc:
        return {"outputs": {_output_name(o): math.nan for o in outputs}, "seconds": math.nan,
                "error": f"{type(exc).__name__}: {exc}"}


# -- cache -------------------------------------------------------------------------

def _read_cached(cache: Path | None, key: str) -> dict | None:
    if cache is None:
        return None
    path = cache / f"{key}.json"
    if not path.exists():
        return None
    try:
        record = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError):
        return None  # a torn write: run the case again
    record["outputs"] = {k: math.nan if v is None else v for k, v in record["outputs"].items()}
    return record


def _write_cached(cache: Path | None, key: str, case: Mapping, design, record: dict) -> None:
    if cache is None:
        return
    data = {"key": key, "version": _version(), "changes": {k: _jsonable(v) for k, v in case.items()},
            "design": repr(design), "outputs": {k: None if math.isnan(v) else v
                                                for k, v in record["outputs"].items()},
            "seconds": None if math.isnan(record["seconds"]) else record["seconds"],
            "error": record["error"]}
    tmp = cache / f".{key}.json.tmp"
    tmp.write_text(json.dumps(data, indent=1))
    os.replace(tmp, cache / f"{key}.json")  # atomic: a killed sweep leaves no torn file


def _jsonable(value):
    try:
        json.dumps(value)
        return value
    except TypeError:
        return repr(value)


# -- the sweep ----------------------------------------------------------------------

def sweep(base, changes, outputs: Sequence = STANDARD_OUTPUTS, *, run="shoe", client=None,
          cache: str | Path | None = None, retry_failed: bool = False, max_workers: int | None = None,
          progress: bool = False):
    """Run a design study: every case in its own process, results in one table.

    Parameters
    ----------
    base : dataclass instance
        The base parameter object (e.g. a pump or a :class:`ShoeCase`).
    changes : mapping or sequence of mappings
        A grid ``{name: [values, ...]}`` (Cartesian product) or a list of
        cases ``[{name: value, ...}, ...]``. Names are change builders
        (:data:`CHANGES`) or dotted field paths of ``base``.
    outputs : sequence
        Names from :data:`OUTPUTS` (or top-level functions ``result -> float``).
    run : str or callable
        Name from :data:`RUNS` or a top-level (picklable) function
        ``parameter object -> result``; ``"shoe"`` (default) solves one film
        state, ``"pump"`` the pump over a revolution (:class:`PumpCase`).
    client : distributed.Client, optional
        Run on this Dask cluster instead of local processes.
    cache : path, optional
        Directory of per-case JSON records keyed by :func:`case_key`;
        finished cases found there are not rerun.
    retry_failed : bool
        Rerun cached cases that failed.
    max_workers : int, optional
        Local processes (default: CPU count).
    progress : bool
        Show a tqdm progress bar.

    Returns
    -------
    pandas.DataFrame
        One row per case in input order: the change names, the outputs,
        ``seconds`` (run time of the case), ``error`` (None or the message),
        ``cached`` (True if read from the cache) and ``key``.
    """
    import pandas as pd

    cases = expand_cases(changes)
    outputs = list(outputs)
    if not outputs:
        raise ValueError("outputs must name at least one output")
    for o in outputs:
        _resolve(o, OUTPUTS, "outputs[i]")
    _resolve(run, RUNS, "run")
    if max_workers is not None and not (isinstance(max_workers, int) and max_workers >= 1):
        raise ValueError(f"max_workers must be an integer >= 1, got {max_workers!r}")
    names = list(dict.fromkeys(name for case in cases for name in case))
    for name in names:
        check_change_name(base, name)
    cache = Path(cache) if cache is not None else None
    if cache is not None:
        cache.mkdir(parents=True, exist_ok=True)

    keys, designs, records, cached = [], {}, {}, {}
    for case in cases:
        try:
            design = apply_changes(base, case)
            key = case_key(design, run, outputs)
            designs.setdefault(key, (case, design))
        except Exception as exc:  # an impossible design fails at once, in this process, uncached
            key = case_key((base, sorted(case.items(), key=str)), run, outputs)
            records[key] = {"outputs": {_output_name(o): math.nan for o in outputs}, "seconds": 0.0,
                            "error": f"{type(exc).__name__}: {exc}"}
            cached[key] = False
        keys.append(key)
        hit = _read_cached(cache, key) if key not in records else None
        if hit is not None and (hit["error"] is None or not retry_failed):
            records[key], cached[key] = hit, True

    tasks = {key: design for key, (case, design) in designs.items() if key not in records}
    if tasks:
        stream = (_run_dask(client, tasks, run, outputs, progress) if client is not None
                  else _run_local(tasks, run, outputs, max_workers, progress))
        for key, record in stream:
            records[key], cached[key] = record, False
            _write_cached(cache, key, *designs[key], record)

    rows = []
    for case, key in zip(cases, keys):
        record = records[key]
        rows.append({**{n: case.get(n) for n in names}, **record["outputs"], "seconds": record["seconds"],
                     "error": record["error"], "cached": cached[key], "key": key})
    columns = names + [_output_name(o) for o in outputs] + ["seconds", "error", "cached", "key"]
    table = pd.DataFrame(rows, columns=columns)
    table["error"] = table["error"].astype(object).where(table["error"].notna(), None)
    return table


def best_design(table, output: str = "h_min", sense: str = "max"):
    """The row of the best successful case (``sense`` "max" or "min" of ``output``)."""
    if sense not in ("max", "min"):
        raise ValueError(f"sense must be 'max' or 'min', got {sense!r}")
    if output not in table.columns:
        raise ValueError(f"output {output!r} is not a column of the table")
    ok = table[table["error"].isna()]
    if ok.empty:
        raise ValueError("no case of the sweep succeeded")
    return ok.loc[ok[output].idxmax() if sense == "max" else ok[output].idxmin()]
