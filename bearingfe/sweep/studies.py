"""Study files: a design study (base object, changes, outputs, objective) read from TOML.

The format is described in ``docs/sweeps.md``; :func:`read_study` checks every
name against :data:`RUNS`, :data:`BASES`, :data:`OUTPUTS` and the change
builders before anything runs.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

from .cases import BASES, RUNS
from .changes import apply_changes, check_change_name, expand_cases
from .outputs import OUTPUTS, STANDARD_OUTPUTS

__all__ = ["Study", "read_study"]


@dataclass(frozen=True)
class Study:
    """A design study read from a TOML file (see ``docs/sweeps.md``).

    Attributes
    ----------
    name : str
    base : object
        The base parameter object: ``BASES[kind]()`` with ``[base.set]`` applied.
    changes : dict or list of dict
        The ``[grid]`` table or the ``[[cases]]`` list.
    run : str
        Key of :data:`RUNS`.
    outputs : tuple of str
        Keys of :data:`OUTPUTS`.
    objective : str
        Output that ranks the designs; ``sense`` is ``"max"`` or ``"min"``.
    time_limit : float or None
        ``[study] time_limit``: seconds one case may take (None: the default
        of :func:`~bearingfe.sweep.sweep`).
    """

    name: str
    base: Any
    changes: Any
    run: str
    outputs: tuple[str, ...]
    objective: str
    sense: str
    time_limit: float | None = None


def _table(data: Mapping, key: str, where: str) -> dict:
    value = data.get(key, {})
    if not isinstance(value, Mapping):
        raise ValueError(f"{where}: [{key}] must be a table, got {value!r}")
    return dict(value)


def _choice(table: Mapping, key: str, allowed, default, where: str):
    value = table.get(key, default)
    if value not in allowed:
        raise ValueError(f"{where}: {key} must be one of {sorted(allowed)}, got {value!r}")
    return value


def read_study(path: str | Path) -> Study:
    """Read and check a study file; every error names the file, table and field."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text())
    except OSError as exc:
        raise ValueError(f"cannot read study file {path}: {exc}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{path}: not valid TOML: {exc}") from None
    unknown = set(data) - {"study", "base", "grid", "cases"}
    if unknown:
        raise ValueError(f"{path}: unknown tables {sorted(unknown)}; allowed: study, base, grid, cases")
    study, base_table = _table(data, "study", str(path)), _table(data, "base", str(path))
    run = _choice(study, "run", RUNS, "shoe", f"{path} [study]")
    outputs = study.get("outputs", list(STANDARD_OUTPUTS))
    if not (isinstance(outputs, list) and outputs and all(o in OUTPUTS for o in outputs)):
        raise ValueError(f"{path} [study]: outputs must be a non-empty list of {sorted(OUTPUTS)}, got {outputs!r}")
    objective = _choice(study, "objective", outputs, outputs[0], f"{path} [study]")
    sense = _choice(study, "sense", ("max", "min"), "max", f"{path} [study]")
    time_limit = study.get("time_limit")
    if time_limit is not None and (isinstance(time_limit, bool) or not isinstance(time_limit, (int, float))
                                   or not 0 < time_limit < float("inf")):
        raise ValueError(f"{path} [study]: time_limit must be a number of seconds > 0, got {time_limit!r}")
    kind = _choice(base_table, "kind", BASES, run if run in BASES else "shoe", f"{path} [base]")
    settings = _table(base_table, "set", f"{path} [base]")
    base = BASES[kind]()
    for name, value in settings.items():
        try:
            check_change_name(base, name)
            base = apply_changes(base, {name: value})
        except ValueError as exc:
            raise ValueError(f"{path} [base.set] {name}: {exc}") from None
    if ("grid" in data) == ("cases" in data):
        raise ValueError(f"{path}: give exactly one of [grid] (a table of value lists) or [[cases]]")
    changes = data.get("grid", data.get("cases"))
    where = f"{path} [grid]" if "grid" in data else f"{path} [[cases]]"
    try:
        cases = expand_cases(changes)
        for name in dict.fromkeys(n for case in cases for n in case):
            check_change_name(base, name)
    except ValueError as exc:
        raise ValueError(f"{where}: {exc}") from None
    if not cases:
        raise ValueError(f"{where}: the study has no cases")
    return Study(name=str(study.get("name", path.stem)), base=base, changes=changes, run=run,
                 outputs=tuple(outputs), objective=objective, sense=sense, time_limit=time_limit)
