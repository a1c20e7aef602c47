"""The ``"reynolds"`` scene: one static film solve from a file, its pictures and its numbers.

A scene file of this kind::

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
    estimate_error = false             # also solve on the mesh refined once: the load's estimated error
    [output]
    pictures = ["pressure", "wrapped", "film"]
    warp = 0.15                        # wrapped picture: radial push of the peak pressure [R0]
    [scale]                            # optional: report in SI
    radius = 0.05                      # R0 [m]
    clearance = 20e-6                  # c [m], < radius
    viscosity = 0.03                   # mu [Pa s]
    speed_rpm = 1500.0                 # or omega = 157.08 [rad/s]: exactly one

The inputs are non-dimensional (lengths in R0, films in c, pressures in
``mu omega R0^2 / c^2``). Without ``[scale]`` the outputs are too, named as
such (``field.vtu``: ``pressure_nondimensional``...; the table's units are
the scales). With ``[scale]`` (:class:`bearingfe.core.scales.Scale`) every
output is SI besides: the table in N, Pa, m, N m, W, m^3/s and l/min,
``results_si`` in the summary, ``field.vtu`` in Pa and m on the surface in
metres (:func:`bearingfe.io.writers.write_vtu`), the pictures in MPa and um
over ``phi`` [deg] and ``z`` [mm].
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Callable

from ..core.linalg import DEFAULT_SOLVER, LINEAR_SOLVERS
from ..core.parameters import ELEMENTS, FORMULATIONS
from ..core.scales import SCALE_FIELDS, scale_of
from ..core.schema import (REQUIRED, SchemaError, Table, anything, build, choice, choices, flag,
                           nonnegative_number, number, pair, positive_number, read_table, text)
from ..mechanisms.files import SURFACE, surface_of

__all__ = ["SPEC", "PICTURES", "settings", "run"]


PICTURES = ("pressure", "wrapped", "film")


#: The ``"reynolds"`` scene file: ``{name: (check, default) | Table}`` (see :mod:`bearingfe.core.schema`).
SPEC = {
    "kind": (anything, REQUIRED, "the scene kind (this section's name)"),
    "title": (text, None, "title of the pictures and tables (default: the file name)"),
    "surface": Table(SURFACE),
    "film": Table({"gamma": (nonnegative_number, REQUIRED, "relative eccentricity of the film h = 1 + gamma cos(phi - phi0) [-]"),
                   "phi0": (number(), 0.0, "angle of the thickest film [rad]")}, required=True),
    "operating": Table({"wedge": (number(), 1.0, "sliding (wedge) factor of the Couette term [-]"),
                        "squeeze": (pair, (0.0, 0.0), "(gamma_rate, phi0_rate) per radian of shaft turn [-]"),
                        "inlet_pressure": (number(), 0.0, "pocket pressure p_s [mu omega R0^2 / c^2]")}),
    "solver": Table({"size": (positive_number, 0.05, "element size [R0]"),
                     "inlet_size": (positive_number, None, "element size at the pockets [R0] (default: size)"),
                     "element": (choice(ELEMENTS), "P1", "finite element"),
                     "formulation": (choice(FORMULATIONS), "pi", "unknown: p (direct) or Pi = h^(3/2) p (pi)"),
                     "linear_solver": (choice(LINEAR_SOLVERS), None, "sparse solver (default: the package's)"),
                     "estimate_error": (flag, False, "also solve on the mesh refined once and report the load error")}),
    "output": Table({"pictures": (choices(PICTURES), PICTURES, "pictures to draw"),
                     "warp": (nonnegative_number, 0.15, "radial push of the peak pressure in the wrapped picture [R0]")}),
    "scale": Table(SCALE_FIELDS),
}

#: m^3/s -> l/min.
LITRES_PER_MINUTE = 6e4


def settings(data: dict, label: str, base_dir: Path | None = None) -> dict:
    """All validated settings of a ``"reynolds"`` scene."""
    s = read_table(data, label, "", SPEC)
    s["title"] = label if s["title"] is None else s["title"]
    if s["solver"]["linear_solver"] is None:
        s["solver"]["linear_solver"] = DEFAULT_SOLVER
    s["surface"] = surface_of(s["surface"], label)
    s["scale"] = scale_of(s["scale"], label) if "scale" in data else None
    del s["kind"]
    return s


def run(data: dict, label: str, out_dir: Path, progress: Callable | None = None,
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

    s = settings(data, label)
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
                         element=solver["element"], solver=solver["linear_solver"],
                         estimate_error=solver["estimate_error"])
    files = []
    sc = s["scale"]
    p_unit = dict(scale=sc.pressure / 1e6, unit="MPa") if sc else {}
    h_unit = dict(scale=sc.clearance * 1e6, unit="um") if sc else {}
    heading = (f"{s['title']}: gamma = {s['film']['gamma']:g}, p_max = "
               + (f"{sc.to_pressure(res.max_pressure) / 1e6:.3g} MPa" if sc else f"{res.max_pressure:.3g} [-]"))

    def field_map(kind, file, unit):
        from ..plot import maps

        scale, shown = (unit["scale"], unit["unit"]) if unit else (1.0, "-")
        panel = maps.Panel(res, kind, scale, shown, radius=sc.radius if sc else None, title=heading,
                           surface=s["surface"])
        maps.field_panels([[panel]], out_dir / file, panel_size=(8.0, 5.0))
        return out_dir / file

    draw = {"pressure": lambda: field_map("pressure", "pressure.png", p_unit),
            "wrapped": lambda: fields.pressure_picture(res, out_dir / "pressure_wrapped.png", view="wrapped",
                                                       warp=out["warp"], surface=s["surface"], title=heading,
                                                       **p_unit),
            "film": lambda: field_map("film", "film.png", h_unit)}
    for k, name in enumerate(pictures):
        tick(2 + k, steps, f"picture: {name}")
        files.append(draw[name]().name)
    tick(steps - 1, steps, "files")
    files.append(write_vtu(res, out_dir / "field.vtu", sc).name)
    summary = _reynolds_summary(s, mesh, res, time.perf_counter() - start)
    summary["files"] = files + ["summary.json"]
    write_json(summary, out_dir / "summary.json")
    tick(steps, steps, "done")
    return summary


def _reynolds_summary(s: dict, mesh, res, seconds: float) -> dict:
    flows = dict(res.flows)
    sc = s["scale"]
    if sc is not None:
        return _si_summary(s, mesh, res, seconds, sc)
    table = [
        ("nodes", mesh.n_nodes, ""), ("dofs", int(res.basis.N), ""),
        ("force (cos phi)", res.force[0], "mu w R0^4/c^2"), ("force (sin phi)", res.force[1], "mu w R0^4/c^2"),
        ("int p", res.integral, "mu w R0^4/c^2"), ("max p", res.max_pressure, "mu w R0^2/c^2"),
        ("h_min", res.h_min, "c"), ("friction", res.friction, "mu w R0^4/c"),
    ] + [(f"flow {k}", v, "w R0^2 c") for k, v in flows.items()] + [
        ("mass balance", res.mass_balance, "w R0^2 c")] + (
        [] if res.load_error is None else [("load error (estimated)", res.load_error.relative, "-")]) + [
        ("seconds", seconds, "s")]
    return {
        "kind": "reynolds", "title": s["title"],
        "surface": {"arc": s["surface"].arc, "half_width": s["surface"].half_width,
                    "inlet_fraction": s["surface"].inlet_fraction},
        "film": s["film"], "operating": s["operating"], "solver": s["solver"],
        "formulation_used": res.formulation, "notes": list(res.notes),
        "results": {"force": res.force, "integral": res.integral, "max_pressure": res.max_pressure,
                    "h_min": res.h_min, "friction": res.friction, "flows": flows,
                    "mass_balance": res.mass_balance,
                    "load_error": None if res.load_error is None else res.load_error.relative},
        "table": [list(row) for row in table],
    }


def _si_summary(s: dict, mesh, res, seconds: float, sc) -> dict:
    """The summary with ``[scale]``: the table in SI, ``results_si`` besides the non-dimensional ``results``."""
    flows = {k: sc.to_flow(v) for k, v in res.flows.items()}
    si = {"force_N": [sc.to_force(f) for f in res.force], "load_N": sc.to_force(float(abs(complex(*res.force)))),
          "peak_pressure_Pa": sc.to_pressure(res.max_pressure), "min_film_m": sc.to_thickness(res.h_min),
          "friction_moment_Nm": sc.to_moment(res.friction),
          "friction_power_W": sc.to_moment(res.friction) * res.wedge * sc.speed,
          "flows_m3s": flows, "mass_balance_m3s": sc.to_flow(res.mass_balance)}
    table = [("nodes", mesh.n_nodes, ""), ("dofs", int(res.basis.N), ""),
             ("force (cos phi)", si["force_N"][0], "N"), ("force (sin phi)", si["force_N"][1], "N"),
             ("load", si["load_N"], "N"), ("peak pressure", si["peak_pressure_Pa"], "Pa"),
             ("smallest film", si["min_film_m"] * 1e6, "um"), ("friction moment", si["friction_moment_Nm"], "N m"),
             ("friction power", si["friction_power_W"], "W")]
    table += [(f"flow {k}", v * LITRES_PER_MINUTE, "l/min") for k, v in flows.items()]
    table += [("mass balance", si["mass_balance_m3s"], "m^3/s")]
    if res.load_error is not None:
        table.append(("load error (estimated)", res.load_error.relative, "-"))
    table.append(("seconds", seconds, "s"))
    summary = _reynolds_summary({**s, "scale": None}, mesh, res, seconds)
    summary.update({"scale": {"radius_m": sc.radius, "clearance_m": sc.clearance, "viscosity_Pas": sc.viscosity,
                              "omega_rad_s": sc.speed, "pressure_Pa": sc.pressure, "force_N": sc.force},
                    "results_si": si, "table": [list(row) for row in table]})
    return summary
