"""Scene files: a TOML description of one computation and the runner that carries it out.

A scene file has a top-level ``kind``; :data:`SCENES` maps the kind to a
runner ``(scene dict, label, output dir, progress) -> summary dict``. To add
a kind (the pump transient), add one entry. Every schema error is a
:class:`SceneError` naming the file, the table and the field together with
what is allowed, e.g. ``default.toml: [solver] element: must be one of
'P1', 'P2'; got 'P3'``.

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
    linear_solver = "splu_sym"         # any key of bearingfe.linalg.LINEAR_SOLVERS
    [output]
    pictures = ["pressure", "wrapped", "film"]
    warp = 0.15                        # wrapped picture: radial push of the peak pressure [R0]
"""

from __future__ import annotations

import math
import time
import tomllib
from pathlib import Path
from types import MappingProxyType
from typing import Any, Callable, Mapping

__all__ = ["SceneError", "SCENES", "load_scene", "run_scene", "surface_from", "run_reynolds_scene"]

_MISSING = object()


class SceneError(ValueError):
    """A scene file is malformed: the message names the file, the field and what is allowed."""


# -- field checking -------------------------------------------------------------

def _number(where, value, *, positive=False, nonnegative=False):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise SceneError(f"{where}: expected a finite number, got {value!r}")
    if positive and not value > 0:
        raise SceneError(f"{where}: must be > 0, got {value!r}")
    if nonnegative and not value >= 0:
        raise SceneError(f"{where}: must be >= 0, got {value!r}")
    return float(value)


def _pair(where, value):
    if not (isinstance(value, list) and len(value) == 2):
        raise SceneError(f"{where}: expected a pair of numbers [x, y], got {value!r}")
    return tuple(_number(where, v) for v in value)


def _choice(allowed):
    def check(where, value):
        if value not in allowed:
            raise SceneError(f"{where}: must be one of {', '.join(repr(a) for a in allowed)}; got {value!r}")
        return value
    return check


def _choices(allowed):
    def check(where, value):
        if not isinstance(value, list):
            raise SceneError(f"{where}: expected a list drawn from {', '.join(repr(a) for a in allowed)}; "
                             f"got {value!r}")
        return tuple(_choice(allowed)(where, v) for v in value)
    return check


def _text(where, value):
    if not isinstance(value, str):
        raise SceneError(f"{where}: expected a string, got {value!r}")
    return value


def _flag(where, value):
    if not isinstance(value, bool):
        raise SceneError(f"{where}: expected true or false, got {value!r}")
    return value


def _positive(where, value):
    return _number(where, value, positive=True)


def _nonnegative(where, value):
    return _number(where, value, nonnegative=True)


def _points(where, value):
    if not (isinstance(value, list) and len(value) >= 3):
        raise SceneError(f"{where}: expected a list of at least 3 points [[phi, z], ...], got {value!r}")
    return tuple(_pair(where, p) for p in value)


def read_table(table: Any, label: str, section: str, spec: Mapping[str, tuple]) -> dict:
    """Check a TOML table against ``spec = {name: (check, default)}``; unknown names are errors."""
    if not isinstance(table, dict):
        raise SceneError(f"{label}: [{section}]: expected a table, got {table!r}")
    unknown = sorted(set(table) - set(spec))
    if unknown:
        raise SceneError(f"{label}: [{section}] {unknown[0]}: unknown field; allowed: {', '.join(spec)}")
    out = {}
    for name, (check, default) in spec.items():
        where = f"{label}: [{section}] {name}"
        if name not in table:
            if default is _MISSING:
                raise SceneError(f"{where}: missing (required)")
            out[name] = default
        else:
            out[name] = check(where, table[name])
    return out


# -- surfaces -------------------------------------------------------------------

def _shape_specs():
    from . import geometry as g

    return {
        "circle": (g.Circle, {"center": (_pair, _MISSING), "radius": (_positive, _MISSING)}),
        "ellipse": (g.Ellipse, {"center": (_pair, _MISSING), "semi_axes": (_pair, _MISSING),
                                "angle": (_number, 0.0)}),
        "rectangle": (g.Rectangle, {"center": (_pair, _MISSING), "size": (_pair, _MISSING),
                                    "angle": (_number, 0.0)}),
        "polygon": (g.Polygon, {"points": (_points, _MISSING)}),
        "slot": (g.Slot, {"center": (_pair, _MISSING), "length": (_positive, _MISSING),
                          "width": (_positive, _MISSING), "angle": (_number, 0.0)}),
    }


def _build(label: str, where: str, factory: Callable, **kwargs):
    try:
        return factory(**kwargs)
    except SceneError:
        raise
    except ValueError as exc:
        raise SceneError(f"{label}: [{where}] {exc}") from None


def surface_from(table: Any, label: str):
    """A :class:`~bearingfe.Surface` from a ``[surface]`` table with ``[[surface.inlets]]``."""
    from .geometry import Surface

    t = read_table(table, label, "surface", {"arc": (_pair, (-0.5, 0.5)), "half_width": (_positive, 0.5),
                                             "inlets": (lambda w, v: v, [])})
    if not isinstance(t["inlets"], list):
        raise SceneError(f"{label}: [surface] inlets: expected an array of tables [[surface.inlets]], "
                         f"got {t['inlets']!r}")
    specs = _shape_specs()
    inlets = []
    for k, item in enumerate(t["inlets"]):
        section = f"surface.inlets.{k}"
        if not isinstance(item, dict):
            raise SceneError(f"{label}: [{section}]: expected a table, got {item!r}")
        kind = _choice(tuple(specs))(f"{label}: [{section}] shape", item.get("shape"))
        factory, spec = specs[kind]
        fields = read_table({k2: v for k2, v in item.items() if k2 != "shape"}, label, section, spec)
        inlets.append(_build(label, section, factory, **fields))
    return _build(label, "surface", Surface, arc=t["arc"], half_width=t["half_width"], inlets=tuple(inlets))


# -- loading --------------------------------------------------------------------

def load_scene(path: str | Path) -> tuple[dict, str]:
    """Read a scene file; returns ``(data, label)``. Checks that ``kind`` is known."""
    path = Path(path)
    if not path.is_file():
        raise SceneError(f"scene file not found: {path}")
    label = path.name
    try:
        data = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"{label}: not valid TOML: {exc}") from None
    kind = data.get("kind", _MISSING)
    if kind is _MISSING:
        raise SceneError(f"{label}: kind: missing (required); allowed: {', '.join(repr(k) for k in SCENES)}")
    _choice(tuple(SCENES))(f"{label}: kind", kind)
    return data, label


def run_scene(path: str | Path, out_dir: str | Path, progress: Callable | None = None) -> dict:
    """Load a scene file and run it through its kind's runner; returns the summary.

    Paths inside a scene file (e.g. the pump's mechanism file) are relative to
    the scene file's folder.
    """
    data, label = load_scene(path)
    return SCENES[data["kind"]](data, label, Path(out_dir), progress, base_dir=Path(path).resolve().parent)


# -- the static Reynolds scene ----------------------------------------------------

_REYNOLDS_TABLES = ("kind", "title", "surface", "film", "operating", "solver", "output")
PICTURES = ("pressure", "wrapped", "film")


def reynolds_settings(data: dict, label: str) -> dict:
    """All validated settings of a ``"reynolds"`` scene."""
    from .linalg import DEFAULT_SOLVER, LINEAR_SOLVERS
    from .reynolds import ELEMENTS, FORMULATIONS

    unknown = sorted(set(data) - set(_REYNOLDS_TABLES))
    if unknown:
        raise SceneError(f"{label}: {unknown[0]}: unknown table or field; allowed: {', '.join(_REYNOLDS_TABLES)}")
    return {
        "title": _text(f"{label}: title", data.get("title", label)),
        "surface": surface_from(data.get("surface", {}), label),
        "film": read_table(_required(data, "film", label), label, "film",
                           {"gamma": (_nonnegative, _MISSING), "phi0": (_number, 0.0)}),
        "operating": read_table(data.get("operating", {}), label, "operating",
                                {"wedge": (_number, 1.0), "squeeze": (_pair, (0.0, 0.0)),
                                 "inlet_pressure": (_number, 0.0)}),
        "solver": read_table(data.get("solver", {}), label, "solver",
                             {"size": (_positive, 0.05), "inlet_size": (_positive, None),
                              "element": (_choice(tuple(ELEMENTS)), "P1"),
                              "formulation": (_choice(FORMULATIONS), "pi"),
                              "linear_solver": (_choice(tuple(LINEAR_SOLVERS)), DEFAULT_SOLVER)}),
        "output": read_table(data.get("output", {}), label, "output",
                             {"pictures": (_choices(PICTURES), PICTURES), "warp": (_nonnegative, 0.15)}),
    }


def _required(data: dict, name: str, label: str):
    if name not in data:
        raise SceneError(f"{label}: [{name}]: missing table (required)")
    return data[name]


def run_reynolds_scene(data: dict, label: str, out_dir: Path, progress: Callable | None = None,
                       base_dir: Path | None = None) -> dict:
    """Mesh, solve, draw and write one static Reynolds problem.

    Writes ``pressure.png`` (and ``pressure_wrapped.png``, ``film.png`` as
    asked), ``field.vtu`` and ``summary.json`` into ``out_dir``; returns the
    summary (with a ``table`` of ``(quantity, value, unit)`` rows).
    """
    from .film import CosineFilm
    from .io import write_json, write_vtu
    from .meshing import mesh_surface
    from .plot import fields
    from .reynolds import solve_reynolds

    s = reynolds_settings(data, label)
    film = _build(label, "film", CosineFilm, **s["film"])
    solver, op, out = s["solver"], s["operating"], s["output"]
    pictures = out["pictures"]
    steps = 3 + len(pictures)
    tick = progress or (lambda done, total, what: None)
    start = time.perf_counter()
    tick(0, steps, "meshing")
    mesh = _build(label, "solver", mesh_surface, surface=s["surface"], size=solver["size"],
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
    """The pump transient scene (:mod:`bearingfe.scene_pump`)."""
    from .scene_pump import run_pump_scene as run

    return run(data, label, out_dir, progress, base_dir)


def run_journal_scene(data: dict, label: str, out_dir: Path, progress: Callable | None = None,
                      base_dir: Path | None = None) -> dict:
    """The journal bearing scene (:mod:`bearingfe.scene_journal`)."""
    from .scene_journal import run_journal_scene as run

    return run(data, label, out_dir, progress, base_dir)


SCENES: Mapping[str, Callable[..., dict]] = MappingProxyType({"reynolds": run_reynolds_scene,
                                                              "pump": run_pump_scene,
                                                              "journal": run_journal_scene})
