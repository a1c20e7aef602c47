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
import threading
import time
import warnings
from pathlib import Path
from typing import Iterable, Mapping, Sequence

from ..core.limits import LimitError, check_limit, limit
from ..version import __version__
from .cases import RUNS
from .changes import apply_changes, check_change_name, expand_cases
from .outputs import OUTPUTS, STANDARD_OUTPUTS

__all__ = ["CacheWarning", "STATUSES", "best_design", "case_key", "case_status", "estimated_elements", "run_case",
           "run_case_timed", "sweep"]

#: A case's ``status`` in the table: it ran; its film closed (a result: the design does not carry
#: its load, :class:`bearingfe.sweep.cases.FilmRuptured`); it failed for another reason (``error``).
STATUSES = ("completed", "ruptured", "failed")


def case_status(error: str | None) -> str:
    """The :data:`STATUSES` entry of a case from its recorded ``error`` (``"<exception type>: <message>"``)."""
    if error is None:
        return "completed"
    return "ruptured" if error.startswith("FilmRuptured:") else "failed"


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

def _failed(outputs, message: str, seconds: float = math.nan) -> dict:
    return {"outputs": {_output_name(o): math.nan for o in outputs}, "seconds": seconds, "error": message}


def _run_local(tasks: dict, run, outputs, max_workers, progress: bool, time_limit: float
               ) -> Iterable[tuple[str, dict]]:
    from tqdm.auto import tqdm

    from .workers import run_pool

    workers = max_workers or os.cpu_count() or 1
    stream = run_pool(tasks, run_case, lambda design: (design, run, outputs), max_workers=workers,
                      time_limit=time_limit)
    with tqdm(total=len(tasks), disable=not progress, desc="cases") as bar:
        for key, ok, value in stream:
            bar.update(1)
            yield key, (value if ok else _failed(outputs, value))


def run_case_timed(design, run, outputs: Sequence, time_limit: float) -> dict:
    """:func:`run_case` with a time limit, for workers that are not ours to kill (Dask).

    The case runs in a thread; past ``time_limit`` seconds it is reported as
    failed at once (its computation ends with the worker's next restart or
    when it finishes; the result is dropped).
    """
    box: dict = {}
    thread = threading.Thread(target=lambda: box.update(record=run_case(design, run, outputs)), daemon=True)
    thread.start()
    thread.join(time_limit)
    if "record" in box:
        return box["record"]
    return _failed(outputs, f"CaseTimeout: the case ran past its time limit of {time_limit:g} s (raise it with "
                            f"sweep(time_limit=...) or [study] time_limit)", seconds=float(time_limit))


def _run_dask(client, tasks: dict, run, outputs, progress: bool, time_limit: float) -> Iterable[tuple[str, dict]]:
    from distributed import as_completed
    from tqdm.auto import tqdm

    futures = {client.submit(run_case_timed, design, run, outputs, time_limit, key=f"bearingfe-case-{key}"): key
               for key, design in tasks.items()}
    for future in tqdm(as_completed(list(futures)), total=len(futures), disable=not progress, desc="cases"):
        yield futures[future], _record(future, outputs)
        future.release()


def _record(future, outputs) -> dict:
    """The case record of a finished future; a dead worker or lost task becomes an error."""
    try:
        return future.result()
    except Exception as exc:
        return _failed(outputs, f"{type(exc).__name__}: {exc}")


# -- cache -------------------------------------------------------------------------

class CacheWarning(UserWarning):
    """A cache record was not used (damaged, edited, of another version or design): the case is recomputed."""


def _checksum(data: Mapping) -> str:
    body = {k: v for k, v in data.items() if k != "checksum"}
    return hashlib.sha256(json.dumps(body, sort_keys=True, allow_nan=False).encode()).hexdigest()


def _number_or_none(value) -> bool:
    return value is None or (isinstance(value, (int, float)) and not isinstance(value, bool)
                             and math.isfinite(value))


def _check_record(data, key: str, design, outputs) -> str | None:
    """Why a cache record cannot be used (None: it can)."""
    if not isinstance(data, dict):
        return "not a JSON object"
    names = [_output_name(o) for o in outputs]
    if not (isinstance(data.get("outputs"), dict) and sorted(data["outputs"]) == sorted(names)
            and all(_number_or_none(v) for v in data["outputs"].values())
            and _number_or_none(data.get("seconds")) and isinstance(data.get("error"), (str, type(None)))):
        return "fields missing or of the wrong type"
    if not isinstance(data.get("checksum"), str):
        return "no checksum (written by an older bearingfe?)"
    try:
        if data["checksum"] != _checksum(data):
            return "checksum does not match its content (edited or damaged)"
    except ValueError:
        return "not valid JSON numbers"
    if data.get("version") != _version():
        return f"written by bearingfe {data.get('version')!r}, this is {_version()}"
    if data.get("key") != key or data.get("design") != repr(design):
        return "it is the record of another case"
    return None


def _read_cached(cache: Path | None, key: str, design=None, outputs: Sequence = ()) -> dict | None:
    if cache is None:
        return None
    path = cache / f"{key}.json"
    if not path.exists():
        return None
    try:
        data = json.loads(path.read_text())
        why = _check_record(data, key, design, outputs)
    except (OSError, UnicodeDecodeError, json.JSONDecodeError, RecursionError) as exc:
        why = f"unreadable ({type(exc).__name__})"
    if why is not None:
        warnings.warn(f"cache record {path.name} not used: {why}; the case is computed again", CacheWarning,
                      stacklevel=3)
        return None
    outputs = {k: math.nan if v is None else float(v) for k, v in data["outputs"].items()}
    seconds = math.nan if data["seconds"] is None else float(data["seconds"])
    return {"outputs": outputs, "seconds": seconds, "error": data["error"]}


def _write_cached(cache: Path | None, key: str, case: Mapping, design, record: dict) -> None:
    if cache is None:
        return
    data = {"key": key, "version": _version(), "changes": {k: _jsonable(v) for k, v in case.items()},
            "design": repr(design), "outputs": {k: None if not math.isfinite(v) else v
                                                for k, v in record["outputs"].items()},
            "seconds": None if not math.isfinite(record["seconds"]) else record["seconds"],
            "error": record["error"]}
    data["checksum"] = _checksum(data)
    tmp = cache / f".{key}.json.tmp"
    tmp.write_text(json.dumps(data, indent=1))
    os.replace(tmp, cache / f"{key}.json")  # atomic: a killed sweep leaves no torn file


def _jsonable(value):
    try:
        json.dumps(value, allow_nan=False)
        return value
    except (TypeError, ValueError):
        return repr(value)


# -- size guards --------------------------------------------------------------------

def estimated_elements(design) -> float | None:
    """Triangles a mesh of ``design`` will have: ``2.3 area / mesh_size^2`` (None if it has no mesh size).

    A design with a ``mesh_size`` and a surface (``surface`` or ``pump.surface``).
    An equilateral triangle of side ``h`` has area ``0.433 h^2``, so a
    surface of area ``A`` takes about ``2.3 A / h^2`` of them (gmsh's
    meshes come within a few tens of percent of this).
    """
    size = getattr(design, "mesh_size", None)
    surface = getattr(design, "surface", None) or getattr(getattr(design, "pump", None), "surface", None)
    if not isinstance(size, (int, float)) or not size > 0 or not hasattr(surface, "area"):
        return None
    return 2.31 * float(surface.area) / float(size) ** 2


# -- the sweep ----------------------------------------------------------------------

def sweep(base, changes, outputs: Sequence = STANDARD_OUTPUTS, *, run="shoe", client=None,
          cache: str | Path | None = None, retry_failed: bool = False, max_workers: int | None = None,
          progress: bool = False, time_limit: float | None = None, max_cases: int | None = None,
          max_elements: float | None = None):
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
    time_limit : float, optional
        Seconds one case may run [s]; a case past it is stopped (its local
        worker killed) and recorded as failed with ``CaseTimeout``. Default
        the ``case_seconds`` limit of :mod:`bearingfe.core.limits` (3600 s).
    max_cases, max_elements : optional
        Size guards checked before any case runs: the number of cases and
        the estimated triangles of each case's mesh
        (:func:`estimated_elements`); defaults from :mod:`bearingfe.core.limits`.

    Cache records carry a SHA-256 checksum of their content and the package
    version; a record that does not match (edited, damaged, another version
    or another case) is not used: the case is computed again and a
    :class:`CacheWarning` says why. The checksum catches damage and edits,
    not a forger who recomputes it.

    Returns
    -------
    pandas.DataFrame
        One row per case in input order: the change names, the outputs,
        ``seconds`` (run time of the case), ``status`` (:data:`STATUSES`),
        ``error`` (None or the message), ``cached`` (True if read from the cache) and ``key``.
    """
    import pandas as pd

    cases = expand_cases(changes, max_cases)
    outputs = list(outputs)
    if not outputs:
        raise ValueError("outputs must name at least one output")
    for o in outputs:
        _resolve(o, OUTPUTS, "outputs[i]")
    _resolve(run, RUNS, "run")
    if max_workers is not None and not (isinstance(max_workers, int) and max_workers >= 1):
        raise ValueError(f"max_workers must be an integer >= 1, got {max_workers!r}")
    if time_limit is None:
        time_limit = limit("case_seconds")
    if isinstance(time_limit, bool) or not isinstance(time_limit, (int, float)) or not 0 < time_limit < math.inf:
        raise ValueError(f"time_limit must be a number of seconds > 0, got {time_limit!r}")
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
        except Exception as exc:  # an impossible design fails at once, in this process, uncached
            design, key, error = None, case_key((base, sorted(case.items(), key=str)), run, outputs), exc
        else:
            error = None
            elements = estimated_elements(design)
            if elements is not None:
                try:
                    check_limit("elements", elements, max_elements, "max_elements")
                except LimitError as exc:
                    raise LimitError(f"case {case}: {exc}") from None
            designs.setdefault(key, (case, design))
        if error is not None:
            records[key] = _failed(outputs, f"{type(error).__name__}: {error}", seconds=0.0)
            cached[key] = False
        if key in keys:  # a repeated case: shares the first one's record or run
            keys.append(key)
            continue
        keys.append(key)
        hit = _read_cached(cache, key, design, outputs) if key not in records else None
        if hit is not None and (hit["error"] is None or not retry_failed):
            records[key], cached[key] = hit, True

    tasks = {key: design for key, (case, design) in designs.items() if key not in records}
    if tasks:
        stream = (_run_dask(client, tasks, run, outputs, progress, time_limit) if client is not None
                  else _run_local(tasks, run, outputs, max_workers, progress, time_limit))
        for key, record in stream:
            records[key], cached[key] = record, False
            _write_cached(cache, key, *designs[key], record)

    rows = []
    for case, key in zip(cases, keys):
        record = records[key]
        rows.append({**{n: case.get(n) for n in names}, **record["outputs"], "seconds": record["seconds"],
                     "status": case_status(record["error"]), "error": record["error"], "cached": cached[key],
                     "key": key})
    columns = names + [_output_name(o) for o in outputs] + ["seconds", "status", "error", "cached", "key"]
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
