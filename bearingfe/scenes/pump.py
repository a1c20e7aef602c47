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
    [elastic]
    enabled = false                                  # also run every design on an elastic support
    model = "half-space"                             # half-space | block | shoe (see below)
    dynamics = "squeeze"                             # squeeze | quasi-static (see below)
    [output]
    pictures = ["trajectory", "orbit", "pressure", "film", "deflection"]
    [thermal]
    enabled = false                                  # level-1 heat balance over the cycle (see below)
    grade = "VG 46"                                  # the oil: the [oil] fields of the journal scene
    kinematic_viscosity_100C = 6.8e-6
    supply_temperature_C = 46.0                      # optional: default where the oil has the file's viscosity

Writes ``trajectory_pocket.csv`` and ``trajectory_plain.csv`` (SI units; see
:meth:`bearingfe.Trajectory.columns`), ``trajectory.png``,
``orbit.png``, ``pressure.png`` and ``film.png`` (the pocketed shoe at its
thinnest film, in MPa and um, the shaft angle in the title),
``pressure.pvd`` with its VTU frames over the cycle, and ``summary.json``.

With ``[elastic] enabled`` every design is run again on the elastic support
(materials ``[shoe.material]`` and ``[eccentric.material]`` of the mechanism
file): ``trajectory_pocket_elastic.csv``, ``trajectory_plain_elastic.csv``,
``pressure_elastic.png``, ``film_elastic.png`` and ``deflection.png`` (the film
opening in um), and the summary compares the smallest film rigid against
elastic, with and without the pocket. ``deflection`` is drawn only then.
``model`` chooses the compliance: ``"half-space"`` (both surfaces elastic
half-spaces, :func:`bearingfe.elastic.half_space`), ``"block"`` (a flat
block of ``[shoe] thickness`` clamped over its back,
:func:`bearingfe.elastic.block_compliance`; ``"body"`` is its old name) or
``"shoe"`` (the real shoe body of the mechanism file: bore, back, seat on
the plunger, lining; gmsh tetrahedra, :func:`bearingfe.elastic.shoe.shoe_compliance`),
the last two with the eccentric as a half-space.
With ``[thermal] enabled`` every rigid design is run again at the
viscosity of its level-1 effective temperature
(:func:`bearingfe.thermal.cycle_temperature`: the cycle-mean heat balance of
the film, the fields of :data:`bearingfe.thermal.files.OIL`; without
``supply_temperature_C`` the oil is fed at the temperature where it has the
mechanism file's viscosity, so the isothermal run is the shipped model), and
the summary's ``thermal`` table has, per design, the effective and peak film
temperatures, the temperature rise over the cycle and the smallest film with
and without the thermal model. Off by default (the paper's isothermal model).
``dynamics = "squeeze"`` (default) integrates the pressure as a state so that
the rate of the deflection squeezes the film
(:func:`bearingfe.transient.elastic.simulate_elastic`; cavitation "none"
only); ``"quasi-static"`` lets the deflection follow the pressure
(``simulate(elastic=...)``, any cavitation model), which on the shipped pump
closes the plain shoe's film after the inner dead centre.
"""

from __future__ import annotations

import dataclasses
import time
from pathlib import Path
from typing import Callable

import numpy as np

from ..core.limits import check_limit
from ..core.parameters import ELEMENTS
from ..core.schema import (NONNEGATIVE, REQUIRED, SchemaError, Table, anything, build, choice, choices, flag, integer,
                     path_text, positive_number, read_table, text)

__all__ = ["run", "settings", "SPEC", "PICTURES"]

PICTURES = ("trajectory", "orbit", "pressure", "film", "deflection")
#: Support compliances of :mod:`bearingfe.elastic.coupled` by name.
ELASTIC_MODELS = ("half-space", "block", "shoe", "body")
#: How the deflection enters the squeeze term: its rate, or not at all (quasi-static).
DYNAMICS = ("squeeze", "quasi-static")


def _cavitation_models() -> tuple[str, ...]:
    from ..cavitation import MODELS

    return tuple(MODELS)


def _starts() -> tuple[str, ...]:
    from ..transient import STARTS

    return tuple(STARTS)


def _thermal_fields() -> dict:
    from ..thermal.files import OIL

    return {"enabled": (flag, False), **OIL}


#: The ``"pump"`` scene file: ``{name: (check, default) | Table}`` (see :mod:`bearingfe.core.schema`).
SPEC = {
    "kind": (anything, REQUIRED),
    "title": (text, None),
    "pump": Table({"mechanism": (path_text, "../mechanisms/eccentric_pump.toml"), "compare_plain": (flag, True)}),
    "run": Table({"revolutions": (positive_number, 1.0), "start": (choice(_starts), "periodic"),
                  "mesh_size": (positive_number, 0.08), "rtol": (positive_number, 1e-6),
                  "frames": (integer(NONNEGATIVE), 12), "cavitation": (choice(_cavitation_models), "none"),
                  "element": (choice(ELEMENTS), "P2")}),
    "elastic": Table({"enabled": (flag, False), "model": (choice(ELASTIC_MODELS), "half-space"),
                      "dynamics": (choice(DYNAMICS), "squeeze")}),
    "output": Table({"pictures": (choices(PICTURES), PICTURES)}),
    "thermal": Table(_thermal_fields()),
}


def settings(data: dict, label: str, base_dir: Path | None = None) -> dict:
    """All validated settings of a ``"pump"`` scene."""
    s = read_table(data, label, "", SPEC)
    path = Path(s["pump"]["mechanism"])
    if not path.is_absolute():
        path = (base_dir or Path.cwd()) / path
    if path.suffix != ".toml":
        raise SchemaError(f"{label}: [pump] mechanism: must name a mechanism file (.toml), got {path.name!r}")
    if not path.is_file():
        raise SchemaError(f"{label}: [pump] mechanism: file not found: {path}")
    if "deflection" in data.get("output", {}).get("pictures", ()) and not s["elastic"]["enabled"]:
        raise SchemaError(f"{label}: [output] pictures: 'deflection' needs [elastic] enabled = true")
    if s["elastic"]["enabled"] and s["elastic"]["dynamics"] == "squeeze" and s["run"]["cavitation"] != "none":
        raise SchemaError(f"{label}: [elastic] dynamics: 'squeeze' needs [run] cavitation = 'none' (the pressure "
                          f"is a state variable); got cavitation {s['run']['cavitation']!r}: use 'quasi-static'")
    if s["thermal"]["enabled"]:
        from ..thermal.files import check_oil

        check_oil(s["thermal"], label, "thermal", need_supply=False)
    return {"title": label if s["title"] is None else s["title"], "mechanism": path,
            "compare_plain": s["pump"]["compare_plain"], "run": s["run"], "output": s["output"],
            "elastic": s["elastic"], "thermal": s["thermal"]}


def run(data: dict, label: str, out_dir: Path, progress: Callable | None = None,
                   base_dir: Path | None = None) -> dict:
    """Simulate the pump (and its plain-shoe twin, and both on an elastic support), draw and write the results."""
    from ..geometry.surface import Surface
    from ..io.writers import write_csv, write_json, write_pvd
    from ..mechanisms.files import load_mechanism
    from ..transient import pump_mesh, simulate, simulate_elastic, state_result

    s = settings(data, label, base_dir)
    check_limit("revolutions", s["run"]["revolutions"])  # before any work (simulate checks it, too)
    check_limit("frames", s["run"]["frames"])
    pump = build(label, "pump", load_mechanism, path=s["mechanism"])
    designs = {"pocket": pump}
    if s["compare_plain"] and pump.surface.inlets:
        plain = Surface(arc=pump.surface.arc, half_width=pump.surface.half_width)
        designs["plain"] = dataclasses.replace(pump, surface=plain)
    run, pictures, elastic = s["run"], s["output"]["pictures"], s["elastic"]["enabled"]
    if not elastic:
        pictures = tuple(p for p in pictures if p != "deflection")
    steps = len(designs) * (2 if elastic else 1) + len(pictures) + 2
    tick = progress or (lambda done, total, what: None)
    start = time.perf_counter()
    runs, meshes, balance, compliances = {}, {}, {}, {}
    done = 0
    for name, p in designs.items():
        tick(done, steps, f"simulating: {name}")
        meshes[name] = pump_mesh(p, run["mesh_size"], order=2 if run["element"] == "P2" else 1)
        runs[name] = simulate(p, meshes[name], run["revolutions"], start=run["start"], rtol=run["rtol"],
                              cavitation=run["cavitation"], element=run["element"])
        balance[name] = runs[name].stats["balance_ratio"]  # simulate checks it before integrating
        done += 1
        if elastic:
            tick(done, steps, f"simulating: {name} on the elastic support")
            compliances[name] = _compliance(p, meshes[name], run["element"], s["elastic"]["model"])
            if s["elastic"]["dynamics"] == "squeeze":
                runs[f"{name}_elastic"] = simulate_elastic(p, compliances[name], run["revolutions"],
                                                           start=run["start"], rtol=run["rtol"])
            else:
                runs[f"{name}_elastic"] = simulate(p, meshes[name], run["revolutions"], start=run["start"],
                                                   rtol=run["rtol"], cavitation=run["cavitation"],
                                                   element=run["element"], elastic=compliances[name])
            done += 1
    tick(done, steps, "files")
    files = []
    for name, traj in runs.items():
        cols = traj.columns()
        files.append(write_csv(cols, out_dir / f"trajectory_{name}.csv", fields=list(cols)).name)
    states = {name: _thinnest(pump, meshes["pocket"], runs[name], run, compliances.get("pocket"))
              for name in (("pocket", "pocket_elastic") if elastic else ("pocket",))}
    for j, name in enumerate(pictures):
        tick(done + 1 + j, steps, f"picture: {name}")
        files += _draw(name, pump, runs, states, s["title"], out_dir)
    if run["frames"] > 0:
        main = runs["pocket"]
        frames = np.unique(np.linspace(0, main.beta.size - 1, int(run["frames"])).astype(int))
        results = [state_result(pump, meshes["pocket"], main, k, run["cavitation"], run["element"])
                   for k in frames]
        write_pvd(results, main.beta[frames], out_dir / "pressure.pvd")
        files.append("pressure.pvd")
    summary = _summary(s, runs, balance, meshes, time.perf_counter() - start, pump.scale, states)
    if s["thermal"]["enabled"]:
        tick(done, steps, "thermal: level-1 heat balance over the cycle")
        summary["thermal"] = _thermal(s, label, pump, designs, meshes)
        summary["table"][-1:-1] = [row for name, th in summary["thermal"].items() for row in (
            (f"{name}: effective film temperature (level 1)", th["effective_temperature_C"], "degC"),
            (f"{name}: temperature rise over the cycle", th["temperature_rise_K"], "K"),
            (f"{name}: smallest film, level 1", th["smallest_film_m"] * 1e6, "um"))]
    summary["files"] = files + ["summary.json"]
    write_json(summary, out_dir / "summary.json")
    tick(steps, steps, "done")
    return summary


def _thermal(s: dict, label: str, pump, designs: dict, meshes: dict) -> dict:
    """Every rigid design at its level-1 effective temperature (:func:`bearingfe.thermal.cycle_temperature`)."""
    from ..thermal import celsius, cycle_temperature
    from ..thermal.files import balance_of, lubricant_of

    th, run = s["thermal"], s["run"]
    oil = lubricant_of(th, label, "thermal")
    supply = None
    if th["supply_temperature_C"] is None:  # where the oil has the mechanism file's viscosity
        supply = build(label, "thermal", oil.temperature_at, pump.viscosity)
    balance = balance_of(th, label, "thermal", supply)
    out = {}
    for name, p in designs.items():
        r = cycle_temperature(p, meshes[name], oil, balance, revolutions=run["revolutions"], start=run["start"],
                              rtol=run["rtol"], cavitation=run["cavitation"], element=run["element"])
        out[name] = {"effective_temperature_C": celsius(r.temperature),
                     "supply_temperature_C": celsius(r.supply_temperature),
                     "temperature_rise_K": r.temperature_rise, "peak_temperature_C": celsius(r.peak_temperature),
                     "effective_viscosity_Pa_s": r.viscosity, "supply_viscosity_Pa_s": r.supply_viscosity,
                     "mean_power_W": r.friction_power, "smallest_film_m": r.smallest_film,
                     "isothermal_smallest_film_m": r.isothermal_smallest_film, "evaluations": r.evaluations}
    return out


def _compliance(pump, mesh, element: str, model: str):
    from ..elastic import NEEDS_BODY, compliance_of

    model = "block" if model == "body" else model  # "body" is the block's old name
    if model in NEEDS_BODY and pump.shoe_body is None:
        raise ValueError(f"[elastic] model {model!r} needs the shoe's depth: [shoe] thickness in the mechanism file")
    return compliance_of(model, mesh, pump.scale, pump.shoe_material, counterpart=pump.eccentric_material,
                         body=pump.shoe_body, element=element)


def _thinnest(pump, mesh, traj, run: dict, compliance=None) -> dict:
    """The film state of a run at its thinnest film, re-solved, with its SI figures."""
    from ..transient import state_result

    k = int(np.argmin(traj.h_min))
    res = state_result(pump, mesh, traj, k, run["cavitation"], run["element"],
                       elastic=compliance if traj.max_deflection is not None else None)
    sc = pump.scale
    d = res.basis.doflocs
    h = np.asarray(res.film.thickness(d[0], d[1]))
    at = int(np.argmin(h))
    on_edge = bool(np.isin(at, res.basis.get_dofs().all()))  # a boundary: the pressure there is prescribed
    return {"result": res, "beta_deg": float(np.degrees(traj.beta[k]) % 360.0),
            "film_um": sc.to_thickness(res.h_min) * 1e6,
            "pressure_at_thinnest_MPa": sc.to_pressure(float(res.pressure[at])) / 1e6,
            "thinnest_on_edge": on_edge,
            "peak_pressure_MPa": sc.to_pressure(res.max_pressure) / 1e6,
            "deflection_um": sc.to_thickness(res.max_deflection) * 1e6}


def _draw(name: str, pump, runs: dict, states: dict, title: str, out_dir: Path) -> list[str]:
    """One picture kind: the trajectory curves, or fields of the thinnest state (rigid and elastic)."""
    from ..plot import curves, fields

    main = runs["pocket"]
    if name == "trajectory":
        curves.trajectory_plot(main, out_dir / "trajectory.png", title=title)
        return ["trajectory.png"]
    if name == "orbit":
        curves.orbit_plot(main, out_dir / "orbit.png")
        return ["orbit.png"]
    sc = pump.scale
    units = {"pressure": dict(scale=sc.to_pressure(1.0) / 1e6, unit="MPa"),
             "film": dict(scale=sc.to_thickness(1.0) * 1e6, unit="um"),
             "deflection": dict(scale=sc.to_thickness(1.0) * 1e6, unit="um")}[name]
    draw = {"pressure": fields.pressure_picture, "film": fields.film_picture,
            "deflection": fields.deflection_picture}[name]
    written = []
    for key, state in states.items():
        if name == "deflection" and key != "pocket_elastic":
            continue
        support = "elastic" if key.endswith("elastic") else "rigid"
        heading = f"thinnest film ({support}): beta = {state['beta_deg']:.1f} deg, h_min = {state['film_um']:.2f} um"
        file = "deflection.png" if name == "deflection" else f"{name}{'_elastic' if key != 'pocket' else ''}.png"
        draw(state["result"], out_dir / file, surface=pump.surface, title=heading, **units)
        written.append(file)
    return written


def _film_ratio(pocket, plain, suffix: str) -> tuple[float | None, tuple]:
    """Smallest film pocket/plain, or ``None`` and the reason when a run did not complete (the smallest
    film of a stopped run is where it stopped, not a film of the cycle)."""
    statuses = {f"pocket{suffix}": pocket.status, f"plain{suffix}": plain.status}
    if all(status == "completed" for status in statuses.values()):
        ratio = pocket.smallest_film / plain.smallest_film
        return ratio, (ratio, "-")
    return None, ("not computed: " + ", ".join(f"{n} {st}" for n, st in statuses.items()), "")


def _summary(s: dict, runs: dict, balance: dict, meshes: dict, seconds: float, scale, states: dict) -> dict:
    table = []
    results = {}
    for name, traj in runs.items():
        design = name.removesuffix("_elastic")
        table += [(f"{name}: smallest film", traj.smallest_film * 1e6, "um"),
                  (f"{name}: balance ratio", balance[design], "-"),
                  (f"{name}: mean friction moment", float(np.mean(traj.friction_moment)), "N m"),
                  (f"{name}: mass balance (relative)", traj.mass_balance_relative, "-"),
                  (f"{name}: status", traj.status, "")]
        results[name] = {"smallest_film_m": traj.smallest_film, "balance_ratio": balance[design],
                         "status": traj.status, "message": traj.message, "nodes": meshes[design].n_nodes,
                         "mean_friction_moment_Nm": float(np.mean(traj.friction_moment)),
                         "mean_inlet_flow_m3s": float(np.mean(traj.flow_inlet)),
                         "mass_balance_relative": traj.mass_balance_relative,
                         "periodic_iterations": traj.periodic_iterations}
        if traj.max_deflection is not None:
            largest = float(np.max(traj.max_deflection))
            table.append((f"{name}: largest deflection", largest * 1e6, "um"))
            results[name]["largest_deflection_m"] = largest
    for key, st in states.items():
        table += [(f"{key}: thinnest film at beta", st["beta_deg"], "deg"),
                  (f"{key}: pressure at the thinnest film"
                   + (" (on a boundary of the film: its prescribed pressure)" if st["thinnest_on_edge"] else ""),
                   st["pressure_at_thinnest_MPa"], "MPa"),
                  (f"{key}: peak pressure at that state", st["peak_pressure_MPa"], "MPa")]
        results[key]["thinnest_state"] = {k: v for k, v in st.items() if k != "result"}
    for suffix, what in (("", ""), ("_elastic", ", elastic support")):
        if f"plain{suffix}" in runs:
            ratio, row = _film_ratio(runs[f"pocket{suffix}"], runs[f"plain{suffix}"], suffix)
            table.append((f"smallest film ratio pocket/plain{what}", *row))
            results[f"film_ratio{suffix}"] = ratio
    table.append(("seconds", seconds, "s"))
    return {"kind": "pump", "title": s["title"], "mechanism": str(s["mechanism"]), "run": s["run"],
            "elastic": s["elastic"], "results": results, "table": table}
