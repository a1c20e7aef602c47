"""Scene files: a TOML description of one computation and the runner that carries it out.

A scene file has a top-level ``kind``; :data:`SCENES` maps the kind to a
runner ``(scene dict, label, output dir, progress) -> summary dict``. To add
a kind (the pump transient), add one entry. Each kind's file is described
by a spec read with :func:`bearingfe.core.schema.read_table` (:data:`REYNOLDS`,
:data:`bearingfe.scenes.pump.PUMP`, :data:`bearingfe.scenes.journal.JOURNAL`):
to add an option, add one ``name: (check, default)`` entry to its table.
Every schema error is a :class:`SceneError` (the
:class:`~bearingfe.core.schema.SchemaError` of every input file) naming the file,
the table and the field together with what is allowed, e.g.
``default.toml: [solver] element: must be one of 'P1', 'P2'; got 'P3'``.

===========  ==================================================================
module       scene kind
===========  ==================================================================
``pump``     ``"pump"``: the plunger shoe with and without its pocket over a revolution
``journal``  ``"journal"``: a journal bearing from a file in SI units
===========  ==================================================================

The ``"reynolds"`` scene (a static solve)::

    kind = "reynolds"
    title = "..."                      # optional
    [surface]
    arc = [-0.5, 0.5]                  # rad
    half_width = 0.4                   # a = b / (2 R0)
    [[surface.inlets]]                 # any number of pockets
    shape = "circle"                   # circle | ellipse | rectangle | polygon | slot
    center = [0.0, 0.0]
    radius = 0.16
    [film]
    gamma = 0.6
    phi0 = 0.3                         # rad
    [operating]
    wedge = 1.0
    squeeze = [0.0, 0.0]               # (gamma_rate, phi0_rate) per radian of shaft turn
    inlet_pressure = 2.0               # p_s, non-dimensional
    [solver]
    size = 0.04
    inlet_size = 0.02                  # optional
    element = "P2"                     # P1 | P2
    formulation = "pi"                 # pi | direct
    linear_solver = "splu_sym"         # any key of bearingfe.core.linalg.LINEAR_SOLVERS
    [output]
    pictures = ["pressure", "wrapped", "film"]
    warp = 0.15                        # wrapped picture: radial push of the peak pressure [R0]
"""

from __future__ import annotations

import time
from pathlib import Path
from types import MappingProxyType
from typing import Callable, Mapping

from ..core.linalg import DEFAULT_SOLVER, LINEAR_SOLVERS
from ..mechanisms.files import SURFACE, surface_from, surface_of
from ..core.parameters import ELEMENTS, FORMULATIONS
from ..core.schema import (REQUIRED, SchemaError, Table, anything, build, choice, choices, nonnegative_number, number,
                     pair, positive_number, read_table, read_toml, text)

__all__ = ["SceneError", "SCENES", "REYNOLDS", "load_scene", "run_scene", "surface_from", "run_reynolds_scene",
           "reynolds_settings"]

#: The error of a malformed scene file (every input file's :class:`~bearingfe.core.schema.SchemaError`).
SceneError = SchemaError


# -- loading --------------------------------------------------------------------

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


# -- the static Reynolds scene ----------------------------------------------------

PICTURES = ("pressure", "wrapped", "film")


#: The ``"reynolds"`` scene file: ``{name: (check, default) | Table}`` (see :mod:`bearingfe.core.schema`).
REYNOLDS = {
    "kind": (anything, REQUIRED),
    "title": (text, None),
    "surface": Table(SURFACE),
    "film": Table({"gamma": (nonnegative_number, REQUIRED), "phi0": (number(), 0.0)}, required=True),
    "operating": Table({"wedge": (number(), 1.0), "squeeze": (pair, (0.0, 0.0)),
                        "inlet_pressure": (number(), 0.0)}),
    "solver": Table({"size": (positive_number, 0.05), "inlet_size": (positive_number, None),
                     "element": (choice(ELEMENTS), "P1"), "formulation": (choice(FORMULATIONS), "pi"),
                     "linear_solver": (choice(LINEAR_SOLVERS), None)}),
    "output": Table({"pictures": (choices(PICTURES), PICTURES), "warp": (nonnegative_number, 0.15)}),
}


def reynolds_settings(data: dict, label: str) -> dict:
    """All validated settings of a ``"reynolds"`` scene."""
    s = read_table(data, label, "", REYNOLDS)
    s["title"] = label if s["title"] is None else s["title"]
    if s["solver"]["linear_solver"] is None:
        s["solver"]["linear_solver"] = DEFAULT_SOLVER
    s["surface"] = surface_of(s["surface"], label)
    del s["kind"]
    return s


def run_reynolds_scene(data: dict, label: str, out_dir: Path, progress: Callable | None = None,
                       base_dir: Path | None = None) -> dict:
    """Mesh, solve, draw and write one static Reynolds problem.

    Writes ``pressure.png`` (and ``pressure_wrapped.png``, ``film.png`` as
    asked), ``field.vtu`` and ``summary.json`` into ``out_dir``; returns the
    summary (with a ``table`` of ``(quantity, value, unit)`` rows).
    """
    from ..film.thickness import CosineFilm
    from ..io.writers import write_json, write_vtu
    from ..geometry.meshing import mesh_surface
    from ..plot import fields
    from ..reynolds import solve_reynolds

    s = reynolds_settings(data, label)
    film = build(label, "film", CosineFilm, **s["film"])
    solver, op, out = s["solver"], s["operating"], s["output"]
    pictures = out["pictures"]
    steps = 3 + len(pictures)
    tick = progress or (lambda done, total, what: None)
    start = time.perf_counter()
    tick(0, steps, "meshing")
    mesh = build(label, "solver", mesh_surface, surface=s["surface"], size=solver["size"],
                  inlet_size=solver["inlet_size"], order=2 if solver["element"] == "P2" else 1)
    tick(1, steps, "solving")
    res = solve_reynolds(mesh, film, wedge=op["wedge"], squeeze=op["squeeze"],
                         inlet_pressure=op["inlet_pressure"], formulation=solver["formulation"],
                         element=solver["element"], solver=solver["linear_solver"])
    files = []
    draw = {"pressure": lambda: fields.pressure_picture(res, out_dir / "pressure.png", surface=s["surface"]),
            "wrapped": lambda: fields.pressure_picture(res, out_dir / "pressure_wrapped.png", view="wrapped",
                                                       warp=out["warp"], surface=s["surface"]),
            "film": lambda: fields.film_picture(res, out_dir / "film.png", surface=s["surface"])}
    for k, name in enumerate(pictures):
        tick(2 + k, steps, f"picture: {name}")
        files.append(draw[name]().name)
    tick(steps - 1, steps, "files")
    files.append(write_vtu(res, out_dir / "field.vtu").name)
    summary = _reynolds_summary(s, mesh, res, time.perf_counter() - start)
    summary["files"] = files + ["summary.json"]
    write_json(summary, out_dir / "summary.json")
    tick(steps, steps, "done")
    return summary


def _reynolds_summary(s: dict, mesh, res, seconds: float) -> dict:
    flows = dict(res.flows)
    table = [
        ("nodes", mesh.n_nodes, ""), ("dofs", int(res.basis.N), ""),
        ("force (cos phi)", res.force[0], "mu w R0^4/c^2"), ("force (sin phi)", res.force[1], "mu w R0^4/c^2"),
        ("int p", res.integral, "mu w R0^4/c^2"), ("max p", res.max_pressure, "mu w R0^2/c^2"),
        ("h_min", res.h_min, "c"), ("friction", res.friction, "mu w R0^4/c"),
    ] + [(f"flow {k}", v, "w R0^2 c") for k, v in flows.items()] + [
        ("mass balance", res.mass_balance, "w R0^2 c"), ("seconds", seconds, "s")]
    return {
        "kind": "reynolds", "title": s["title"],
        "surface": {"arc": s["surface"].arc, "half_width": s["surface"].half_width,
                    "inlet_fraction": s["surface"].inlet_fraction},
        "film": s["film"], "operating": s["operating"], "solver": s["solver"],
        "formulation_used": res.formulation, "notes": list(res.notes),
        "results": {"force": res.force, "integral": res.integral, "max_pressure": res.max_pressure,
                    "h_min": res.h_min, "friction": res.friction, "flows": flows,
                    "mass_balance": res.mass_balance},
        "table": [list(row) for row in table],
    }


#: Scene kinds and their runners.
def run_pump_scene(data: dict, label: str, out_dir: Path, progress: Callable | None = None,
                   base_dir: Path | None = None) -> dict:
    """The pump transient scene (:mod:`bearingfe.scenes.pump`)."""
    from .pump import run_pump_scene as run

    return run(data, label, out_dir, progress, base_dir)


def run_journal_scene(data: dict, label: str, out_dir: Path, progress: Callable | None = None,
                      base_dir: Path | None = None) -> dict:
    """The journal bearing scene (:mod:`bearingfe.scenes.journal`)."""
    from .journal import run_journal_scene as run

    return run(data, label, out_dir, progress, base_dir)


SCENES: Mapping[str, Callable[..., dict]] = MappingProxyType({"reynolds": run_reynolds_scene,
                                                              "pump": run_pump_scene,
                                                              "journal": run_journal_scene})
