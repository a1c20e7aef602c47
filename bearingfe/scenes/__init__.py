"""Scene files: a TOML description of one computation and the runner that carries it out.

A scene file has a top-level ``kind``; :data:`SCENES` maps the kind to a
runner ``(scene dict, label, output dir, progress) -> summary dict``. To add
a kind (the pump transient), add one entry. Each kind's file is described
by a spec read with :func:`bearingfe.core.schema.read_table` (the ``SPEC`` of each
scene module):
to add an option, add one ``name: (check, default)`` entry to its table.
Every schema error is a :class:`SceneError` (the
:class:`~bearingfe.core.schema.SchemaError` of every input file) naming the file,
the table and the field together with what is allowed, e.g.
``default.toml: [solver] element: must be one of 'P1', 'P2'; got 'P3'``.

============  =================================================================
module        scene kind
============  =================================================================
``reynolds``  ``"reynolds"``: one static film solve (surface, film, operating point)
``pump``      ``"pump"``: the plunger shoe with and without its pocket over a revolution
``journal``   ``"journal"``: a journal bearing from a file in SI units
``thrust``    ``"thrust"``: a thrust bearing of sector pads (tilting or fixed) in SI units
============  =================================================================
"""

from __future__ import annotations

import importlib
from collections.abc import Iterator
from pathlib import Path
from typing import Callable, Mapping

from ..core.schema import SchemaError, choice, read_toml

__all__ = ["SceneError", "SCENES", "SETTINGS", "load_scene", "run_scene"]

#: The error of a malformed scene file (every input file's :class:`~bearingfe.core.schema.SchemaError`).
SceneError = SchemaError

#: Scene kind -> the module of this package that runs it (its ``run``, ``settings`` and ``SPEC``).
_KINDS = ("reynolds", "pump", "journal", "thrust")


class _ByKind(Mapping):
    """A read-only table ``kind -> <scene module>.<attribute>`` that imports a kind's module when that kind
    is first looked up: running one scene does not import the others (the journal's and the thrust
    bearing's solvers, the thermal models), which shortens the command line's start."""

    def __init__(self, attribute: str) -> None:
        self._attribute = attribute

    def __getitem__(self, kind: str) -> Callable[..., dict]:
        if kind not in _KINDS:
            raise KeyError(kind)
        return getattr(importlib.import_module(f"{__name__}.{kind}"), self._attribute)

    def __iter__(self) -> Iterator[str]:
        return iter(_KINDS)

    def __len__(self) -> int:
        return len(_KINDS)

    def __repr__(self) -> str:
        return f"<scene kinds {', '.join(_KINDS)}: {self._attribute}>"


#: Scene kinds and their runners: ``run(data, label, out_dir, progress, base_dir) -> summary``.
SCENES: Mapping[str, Callable[..., dict]] = _ByKind("run")
#: Scene kinds and the readers of their files: ``settings(data, label, base_dir) -> settings``.
SETTINGS: Mapping[str, Callable[..., dict]] = _ByKind("settings")


def load_scene(path: str | Path) -> tuple[dict, str]:
    """Read a scene file; returns ``(data, label)``. Checks that ``kind`` is known."""
    data, label = read_toml(path, "scene file")
    if "kind" not in data:
        raise SceneError(f"{label}: kind: missing (required); allowed: {', '.join(repr(k) for k in SCENES)}")
    choice(tuple(SCENES))(f"{label}: kind", data["kind"])
    return data, label


def run_scene(path: str | Path, out_dir: str | Path, progress: Callable | None = None) -> dict:
    """Load a scene file and run it through its kind's runner; returns the summary.

    Paths inside a scene file (e.g. the pump's mechanism file) are relative to
    the scene file's folder.
    """
    data, label = load_scene(path)
    return SCENES[data["kind"]](data, label, Path(out_dir), progress, base_dir=Path(path).resolve().parent)
