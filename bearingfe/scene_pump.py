"""The ``"pump"`` scene: the plunger shoe over the pump cycle, pocket against plain.

Scene file::

    kind = "pump"
    title = "..."                                    # optional
    [pump]
    mechanism = "../mechanisms/eccentric_pump.toml"  # relative to the scene file
    compare_plain = true                             # also run the shoe without its pockets
    [run]
    revolutions = 1.0
    start = "periodic"                               # periodic | steady
    mesh_size = 0.15                                 # element size [R0]
    element = "P2"                                   # P1 | P2 (P2 on a curved mesh)
    rtol = 1e-6
    frames = 12                                      # pressure fields in the PVD series
    cavitation = "none"                              # none | reynolds | gumbel | jfo (jfo: element P1)
    [output]
    pictures = ["trajectory", "orbit", "pressure"]

Writes ``trajectory_pocket.csv`` and ``trajectory_plain.csv`` (SI units; see
:meth:`bearingfe.Trajectory.columns`), ``trajectory.png``,
``orbit.png``, ``pressure.png`` (the pocketed shoe at its thinnest film),
``pressure.pvd`` with its VTU frames over the cycle, and ``summary.json``.
"""

from __future__ import annotations

import dataclasses
import time
from pathlib import Path
from typing import Callable

import numpy as np

from .limits import check_limit
from .schema import (NONNEGATIVE, REQUIRED, SchemaError, Table, anything, build, choice, choices, flag, integer,
                     path_text, positive_number, read_table, text)

__all__ = ["run_pump_scene", "pump_settings", "PUMP", "PICTURES"]

PICTURES = ("trajectory", "orbit", "pressure")


def _elements() -> tuple[str, ...]:
    from .parameters import ELEMENTS

    return tuple(ELEMENTS)


def _cavitation_models() -> tuple[str, ...]:
    from .cavitation import MODELS

    return tuple(MODELS)


def _starts() -> tuple[str, ...]:
    from .transient import STARTS

    return tuple(STARTS)


#: The ``"pump"`` scene file: ``{name: (check, default) | Table}`` (see :mod:`bearingfe.schema`).
PUMP = {
    "kind": (anything, REQUIRED),
    "title": (text, None),
    "pump": Table({"mechanism": (path_text, "../mechanisms/eccentric_pump.toml"), "compare_plain": (flag, True)}),
    "run": Table({"revolutions": (positive_number, 1.0), "start": (choice(_starts), "periodic"),
                  "mesh_size": (positive_number, 0.08), "rtol": (positive_number, 1e-6),
                  "frames": (integer(NONNEGATIVE), 12), "cavitation": (choice(_cavitation_models), "none"),
                  "element": (choice(_elements), "P2")}),
    "output": Table({"pictures": (choices(PICTURES), PICTURES)}),
}


def pump_settings(data: dict, label: str, base_dir: Path | None = None) -> dict:
    """All validated settings of a ``"pump"`` scene."""
    s = read_table(data, label, "", PUMP)
    path = Path(s["pump"]["mechanism"])
    if not path.is_absolute():
        path = (base_dir or Path.cwd()) / path
    if not path.is_file():
        raise SchemaError(f"{label}: [pump] mechanism: file not found: {path}")
    return {"title": label if s["title"] is None else s["title"], "mechanism": path,
            "compare_plain": s["pump"]["compare_plain"], "run": s["run"], "output": s["output"]}


def run_pump_scene(data: dict, label: str, out_dir: Path, progress: Callable | None = None,
                   base_dir: Path | None = None) -> dict:
    """Simulate the pump (and its plain-shoe twin), draw and write the results."""
    from .geometry import Surface
    from .io import write_csv, write_json, write_pvd
    from .mechanism_files import load_mechanism
    from .plot import curves
    from .transient import pump_mesh, simulate, state_result

    s = pump_settings(data, label, base_dir)
    check_limit("revolutions", s["run"]["revolutions"])  # before any work (simulate checks it, too)
    check_limit("frames", s["run"]["frames"])
    pump = build(label, "pump", load_mechanism, path=s["mechanism"])
    designs = {"pocket": pump}
    if s["compare_plain"] and pump.surface.inlets:
        plain = Surface(arc=pump.surface.arc, half_width=pump.surface.half_width)
        designs["plain"] = dataclasses.replace(pump, surface=plain)
    run, pictures = s["run"], s["output"]["pictures"]
    steps = len(designs) + len(pictures) + 2
    tick = progress or (lambda done, total, what: None)
    start = time.perf_counter()
    runs, meshes, balance = {}, {}, {}
    for k, (name, p) in enumerate(designs.items()):
        tick(k, steps, f"simulating: {name}")
        meshes[name] = pump_mesh(p, run["mesh_size"], order=2 if run["element"] == "P2" else 1)
        runs[name] = simulate(p, meshes[name], run["revolutions"], start=run["start"], rtol=run["rtol"],
                              cavitation=run["cavitation"], element=run["element"])
        balance[name] = runs[name].stats["balance_ratio"]  # simulate checks it before integrating
    done = len(designs)
    tick(done, steps, "files")
    files = []
    for name, traj in runs.items():
        cols = traj.columns()
        files.append(write_csv(cols, out_dir / f"trajectory_{name}.csv", fields=list(cols)).name)
    main = runs["pocket"]
    draw = {
        "trajectory": lambda: curves.trajectory_plot(main, out_dir / "trajectory.png", title=s["title"]),
        "orbit": lambda: curves.orbit_plot(main, out_dir / "orbit.png"),
        "pressure": lambda: _thinnest_picture(pump, meshes["pocket"], main, out_dir / "pressure.png", run),
    }
    for j, name in enumerate(pictures):
        tick(done + 1 + j, steps, f"picture: {name}")
        draw[name]()
        files.append(f"{name}.png")
    if run["frames"] > 0:
        frames = np.unique(np.linspace(0, main.beta.size - 1, int(run["frames"])).astype(int))
        results = [state_result(pump, meshes["pocket"], main, k, run["cavitation"], run["element"])
                   for k in frames]
        write_pvd(results, main.beta[frames], out_dir / "pressure.pvd")
        files.append("pressure.pvd")
    summary = _summary(s, runs, balance, meshes, time.perf_counter() - start)
    summary["files"] = files + ["summary.json"]
    write_json(summary, out_dir / "summary.json")
    tick(steps, steps, "done")
    return summary


def _thinnest_picture(pump, mesh, traj, path: Path, run: dict):
    from .plot import fields
    from .transient import state_result

    k = int(np.argmin(traj.h_min))
    res = state_result(pump, mesh, traj, k, run["cavitation"], run["element"])
    return fields.pressure_picture(res, path, surface=pump.surface)


def _summary(s: dict, runs: dict, balance: dict, meshes: dict, seconds: float) -> dict:
    table = []
    results = {}
    for name, traj in runs.items():
        table += [(f"{name}: smallest film", traj.smallest_film * 1e6, "um"),
                  (f"{name}: balance ratio", balance[name], "-"),
                  (f"{name}: mean friction moment", float(np.mean(traj.friction_moment)), "N m"),
                  (f"{name}: mass balance (relative)", traj.mass_balance_relative, "-"),
                  (f"{name}: status", traj.status, "")]
        results[name] = {"smallest_film_m": traj.smallest_film, "balance_ratio": balance[name],
                         "status": traj.status, "message": traj.message, "nodes": meshes[name].n_nodes,
                         "mean_friction_moment_Nm": float(np.mean(traj.friction_moment)),
                         "mean_inlet_flow_m3s": float(np.mean(traj.flow_inlet)),
                         "mass_balance_relative": traj.mass_balance_relative,
                         "periodic_iterations": traj.periodic_iterations}
    if "plain" in runs:
        statuses = {name: traj.status for name, traj in runs.items()}
        if all(status == "completed" for status in statuses.values()):
            ratio = runs["pocket"].smallest_film / runs["plain"].smallest_film
            table.append(("smallest film ratio pocket/plain", ratio, "-"))
        else:  # the smallest film of a ruptured run is where it stopped, not a film of the cycle
            ratio = None
            table.append(("smallest film ratio pocket/plain",
                          "not computed: " + ", ".join(f"{n} {st}" for n, st in statuses.items()), ""))
        results["film_ratio"] = ratio
    table.append(("seconds", seconds, "s"))
    return {"kind": "pump", "title": s["title"], "mechanism": str(s["mechanism"]), "run": s["run"],
            "results": results, "table": table}
