"""Study files: a design study (base object, changes, outputs, objective) read from TOML.

The format is described in ``docs/sweeps.md``; :func:`read_study` checks every
name against :data:`RUNS`, :data:`BASES`, :data:`OUTPUTS` and the change
builders before anything runs.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..core.scales import SCALE_FIELDS, Scale, scale_of
from ..core.schema import SchemaError, Table, anything, choice, choices, positive_number, read_table, read_toml, text
from .cases import BASES, RUNS
from .changes import apply_changes, check_change_name, expand_cases
from .outputs import OUTPUTS, STANDARD_OUTPUTS

__all__ = ["STUDY", "Study", "read_study"]


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
    scale : Scale or None
        ``[scale]`` of a ``"shoe"`` study: the radius, clearance, viscosity and speed that turn its
        non-dimensional outputs into SI columns beside them (:func:`~bearingfe.sweep.si_columns`).
    """

    name: str
    base: Any
    changes: Any
    run: str
    outputs: tuple[str, ...]
    objective: str
    sense: str
    time_limit: float | None = None
    scale: Scale | None = None


def _settings(where: str, value) -> dict:
    if not isinstance(value, dict):
        raise SchemaError(f"{where}: expected a table of field = value; got {value!r}")
    return value


_settings.accepts = "a table of field = value (the base object's fields)"


#: The study file: ``{name: (check, default) | Table}`` (see :mod:`bearingfe.core.schema`); the names in
#: ``[base.set]``, ``[grid]`` and ``[[cases]]`` are checked against the base object and the change builders.
STUDY = {
    "study": Table({"name": (text, None, "study name (default: the file name)"),
                    "run": (choice(lambda: RUNS), "shoe", "what one case computes"),
                    "outputs": (choices(lambda: OUTPUTS, empty=False), tuple(STANDARD_OUTPUTS),
                                "result columns of the table"),
                    "objective": (text, None, "output the best design is chosen by (default: the first)"),
                    "sense": (choice(("max", "min")), "max", "whether the objective is maximised or minimised"),
                    "time_limit": (positive_number, None, "time limit of one case [s] (default 3600)")}),
    "base": Table({"kind": (choice(lambda: BASES), None, "the base object the changes apply to"),
                   "set": (_settings, {}, "fields of the base object set before the changes")}),
    "grid": (anything, None, "changes and their values: every combination is a case"),
    "cases": (anything, None, "cases given one by one, each a table of changes"),
    "scale": Table(SCALE_FIELDS),  # a "shoe" study's outputs also in SI
}


def read_study(path: str | Path) -> Study:
    """Read and check a study file; every error names the file, table and field."""
    data, label = read_toml(path, "study file")
    s = read_table(data, label, "", STUDY)
    study, base_table = s["study"], s["base"]
    run, outputs = study["run"], study["outputs"]
    objective = outputs[0] if study["objective"] is None else study["objective"]
    choice(outputs)(f"{label}: [study] objective", objective)
    kind = base_table["kind"] or (run if run in BASES else "shoe")
    base = BASES[kind]()
    for name, value in base_table["set"].items():
        try:
            check_change_name(base, name)
            base = apply_changes(base, {name: value})
        except ValueError as exc:
            raise SchemaError(f"{label}: [base.set] {name}: {exc}") from None
    if (s["grid"] is None) == (s["cases"] is None):
        raise SchemaError(f"{label}: give exactly one of [grid] (a table of value lists) or [[cases]]")
    changes = s["grid"] if s["cases"] is None else s["cases"]
    where = f"{label}: [grid]" if s["cases"] is None else f"{label}: [[cases]]"
    try:
        cases = expand_cases(changes)
        for name in dict.fromkeys(n for case in cases for n in case):
            check_change_name(base, name)
    except ValueError as exc:
        raise SchemaError(f"{where}: {exc}") from None
    if not cases:
        raise SchemaError(f"{where}: the study has no cases")
    scale = None
    if "scale" in data:
        if run != "shoe":
            raise SchemaError(f"{label}: [scale]: only for run = \"shoe\" (a {run!r} run reports SI already)")
        scale = scale_of(s["scale"], label)
    name = Path(path).stem if study["name"] is None else study["name"]
    return Study(name=name, base=base, changes=changes, run=run, outputs=tuple(outputs), objective=objective,
                 sense=study["sense"], time_limit=study["time_limit"], scale=scale)
