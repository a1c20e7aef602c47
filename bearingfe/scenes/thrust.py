"""The ``"thrust"`` scene: a thrust bearing of identical sector pads under an axial load, in SI units.

Scene file::

    kind = "thrust"
    title = "..."                        # optional
    [pads]
    n_pads = 6                           # 1 to 24
    inner_diameter = 0.100               # [m]
    outer_diameter = 0.200               # [m]
    angle_deg = 45.0                     # each pad [deg], at most 360 / n_pads
    pivot = "point"                      # point | line (tilting pads) | fixed (fixed geometry)
    pivot_offset = 0.6                   # pivot from the leading edge, fraction of the pad angle
    pivot_diameter = 0.150               # optional [m]; default the mean diameter
    pitch_urad = 0.0                     # fixed pads: tilt about the radial line [urad]
    roll_urad = 0.0                      # fixed pads: tilt about the circumferential line [urad]
    profile = [[0.0, 20e-6], [0.7, 0.0], [1.0, 0.0]]   # optional machined depth [fraction, m]
    profile_along = "angle"              # angle: radial step/taper lines | radius: circumferential ([m, m])
    [operating]
    speed = 3000.0                       # collar speed [rpm]
    viscosity = 0.03                     # [Pa s]; absent when [oil] is given
    load = 20e3                          # axial load on the bearing [N]
    load_range = [5e3, 40e3]             # the curve of film and power loss [N]
    load_points = 6
    [solver]
    size = 0.05                          # element size [outer radius]
    element = "P1"                       # P1 | P2
    cavitation = "reynolds"              # none | reynolds | jfo
    reference_film = 20e-6               # film scale of the non-dimensional solves [m]
    [output]
    pictures = ["pressure", "film", "curve"]
    [oil]                                # optional: the viscosity from the pads' heat balance instead
    grade = "VG 46"
    viscosity_index = 100.0
    supply_temperature_C = 45.0

Writes ``pressure.png`` and ``film.png`` (one pad, MPa and um over x and y in mm), ``curve.png``
(smallest film and power loss against load), ``pads.csv`` (one row per pad), ``curve.csv`` and
``summary.json`` (its ``table`` of quantity, value, unit). Tilting pads are solved in equilibrium on their
pivots (:func:`bearingfe.bearings.thrust.tilting_equilibrium`), fixed pads for the load
(:func:`bearingfe.bearings.thrust.pad_for_load`); with ``[oil]`` the viscosity is that of the effective
temperature of the pads' level-1 heat balance (:func:`bearingfe.thermal.thrust_temperature`), the curve at
the viscosity of that temperature.
"""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Callable

import numpy as np

from ..core.schema import (REQUIRED, Range, SchemaError, Table, anything, build, choice, choices, integer, number,
                           numbers, positive_number, read_table, text)

__all__ = ["SPEC", "PICTURES", "settings", "run"]

PICTURES = ("pressure", "film", "curve")
#: m^3/s -> l/min.
LITRES_PER_MINUTE = 6e4


def _profile(where, value):
    """``[[s, depth], ...]``: at least two pairs, ``s`` non-decreasing, depths >= 0."""
    ok = isinstance(value, list) and len(value) >= 2 and all(
        isinstance(p, list) and len(p) == 2 and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                      and math.isfinite(v) for v in p) for p in value)
    if ok:
        s = [float(p[0]) for p in value]
        ok = all(b >= a for a, b in zip(s, s[1:])) and s[-1] > s[0] and all(float(p[1]) >= 0 for p in value)
    if not ok:
        raise SchemaError(f"{where}: expected {_profile.accepts}; got {value!r}")
    return tuple((float(a), float(b)) for a, b in value)


_profile.accepts = "[[s, depth_m], ...]: 2 or more pairs, s non-decreasing, depth >= 0"


def _oil_fields() -> dict:
    from ..thermal.files import OIL

    return dict(OIL)


#: The ``"thrust"`` scene file: ``{name: (check, default) | Table}`` (see :mod:`bearingfe.core.schema`).
SPEC = {
    "kind": (anything, REQUIRED, "the scene kind (this section's name)"),
    "title": (text, None, "title of the pictures and tables (default: the file name)"),
    "pads": Table({
        "n_pads": (integer(Range(1, 24)), 6, "number of identical pads [-]"),
        "inner_diameter": (positive_number, REQUIRED, "inner diameter of the pads [m]"),
        "outer_diameter": (positive_number, REQUIRED, "outer diameter of the pads [m]"),
        "angle_deg": (number(Range(0.0, 360.0, lo_open=True)), REQUIRED, "angular extent of each pad [deg]"),
        "pivot": (choice(("point", "line", "fixed")), "point",
                  "tilting pads on a point or a line (radial rocker) pivot, or fixed-geometry pads"),
        "pivot_offset": (number(Range(0.0, 1.0, lo_open=True, hi_open=True)), 0.5,
                         "pivot from the leading edge as a fraction of the pad angle [-]"),
        "pivot_diameter": (positive_number, None, "diameter of the pivot circle [m] (default: the mean diameter)"),
        "pitch_urad": (number(), 0.0, "fixed pads: tilt about the radial line through the pivot [urad]"),
        "roll_urad": (number(), 0.0, "fixed pads: tilt about the circumferential line through the pivot [urad]"),
        "profile": (_profile, (), "machined depth [[s, depth_m], ...]: s a fraction of the angle, or a radius [m]"),
        "profile_along": (choice(("angle", "radius")), "angle",
                          "profile along the angle (radial step lines) or the radius (circumferential)"),
    }, required=True),
    "operating": Table({
        "speed": (positive_number, REQUIRED, "collar speed [rpm]"),
        "viscosity": (positive_number, None, "oil dynamic viscosity [Pa s] (or an [oil] table)"),
        "load": (positive_number, REQUIRED, "axial load on the bearing [N]"),
        "load_range": (numbers(2, "a pair [lowest_N, highest_N]"), None,
                       "load range of the curve [N] (default: 0.25 to 2 times the load)"),
        "load_points": (integer(Range(2, 40)), 6, "loads on the curve [-]"),
    }, required=True),
    "solver": Table({
        "size": (number(Range(0.0, 1.0, lo_open=True)), 0.05, "element size [outer radius]"),
        "element": (choice(("P1", "P2")), "P1", "finite element"),
        "cavitation": (choice(("none", "reynolds", "jfo")), "reynolds", "cavitation model"),
        "reference_film": (positive_number, 20e-6, "film scale of the non-dimensional solves [m]"),
    }),
    "output": Table({"pictures": (choices(PICTURES), PICTURES, "pictures to draw")}),
    "oil": Table(_oil_fields()),
}


def settings(data: dict, label: str, base_dir: Path | None = None) -> dict:
    """All validated settings of a ``"thrust"`` scene (SI)."""
    s = read_table(data, label, "", SPEC)
    pads, op = s["pads"], s["operating"]
    if not pads["outer_diameter"] > pads["inner_diameter"]:
        raise SchemaError(f"{label}: [pads] outer_diameter: must exceed inner_diameter "
                          f"({pads['inner_diameter']!r} m); got {pads['outer_diameter']!r}")
    if pads["angle_deg"] > 360.0 / pads["n_pads"] + 1e-9:
        raise SchemaError(f"{label}: [pads] angle_deg: must be at most 360 / n_pads = {360.0 / pads['n_pads']:.6g}; "
                          f"got {pads['angle_deg']!r}")
    if pads["pivot_diameter"] is not None and not pads["inner_diameter"] < pads["pivot_diameter"] < pads["outer_diameter"]:
        raise SchemaError(f"{label}: [pads] pivot_diameter: must be between the inner and outer diameters; "
                          f"got {pads['pivot_diameter']!r}")
    if pads["pivot"] != "fixed" and (pads["pitch_urad"] or pads["roll_urad"]):
        raise SchemaError(f"{label}: [pads] pitch_urad, roll_urad: only for pivot = 'fixed' (tilting pads find "
                          f"their own tilt)")
    rng = op["load_range"]
    if rng is None:
        op["load_range"] = (0.25 * op["load"], 2.0 * op["load"])
    elif not 0 < rng[0] < rng[1]:
        raise SchemaError(f"{label}: [operating] load_range: must be [lowest, highest] with 0 < lowest < highest "
                          f"[N]; got {list(rng)!r}")
    oil = s["oil"] if "oil" in data else None
    if (oil is None) == (op["viscosity"] is None):
        raise SchemaError(f"{label}: [operating] viscosity: give it or an [oil] table, exactly one; got "
                          f"viscosity = {op['viscosity']!r} and {'an' if oil else 'no'} [oil] table")
    if oil is not None:
        from ..thermal.files import check_oil

        check_oil(oil, label, "oil")
    return {"title": label if s["title"] is None else s["title"], "pads": pads, "operating": op,
            "solver": s["solver"], "output": s["output"], "oil": oil}


def _pad(s: dict, label: str):
    from ..bearings.thrust import ThrustPad

    p = s["pads"]
    return build(label, "pads", ThrustPad, inner_radius=p["inner_diameter"] / 2, outer_radius=p["outer_diameter"] / 2,
                 extent=math.radians(p["angle_deg"]), n_pads=p["n_pads"],
                 pivot_radius=None if p["pivot_diameter"] is None else p["pivot_diameter"] / 2,
                 pivot_offset=p["pivot_offset"], profile=p["profile"], profile_along=p["profile_along"])


def run(data: dict, label: str, out_dir: Path, progress: Callable | None = None,
        base_dir: Path | None = None) -> dict:
    """Mesh one pad, carry the load (tilting or fixed pads), draw and write the results (see the module)."""
    from ..bearings.thrust import load_curve
    from ..core.scales import Scale
    from ..io.writers import write_csv, write_json

    s = settings(data, label)
    pads, op, solver, out = s["pads"], s["operating"], s["solver"], s["output"]
    pictures = out["pictures"]
    steps = 4 + len(pictures)
    tick = progress or (lambda done, total, what: None)
    start = time.perf_counter()
    pad = _pad(s, label)
    tick(0, steps, "meshing")
    mesh = build(label, "solver", pad.mesh, solver["size"], order=2 if solver["element"] == "P2" else 1)
    omega = 2 * math.pi * op["speed"] / 60
    pivot = None if pads["pivot"] == "fixed" else pads["pivot"]
    tilt = dict(pitch=pads["pitch_urad"] * 1e-6, roll=pads["roll_urad"] * 1e-6)
    options = dict(cavitation=solver["cavitation"], element=solver["element"])
    tick(1, steps, "carrying the load")
    thermal = None
    if s["oil"] is not None:
        thermal = _thermal(s, label, pad, mesh, omega, pivot, tilt, options)
        viscosity = thermal.viscosity
    else:
        viscosity = op["viscosity"]
    scale = build(label, "operating", Scale, pad.outer_radius, solver["reference_film"], viscosity, omega)
    at = build(label, "operating", load_curve, pad, mesh, scale, [op["load"]], pivot=pivot, **tilt, **options)[0]
    tick(2, steps, "the load curve")
    loads = np.linspace(*op["load_range"], op["load_points"])
    curve = build(label, "operating", load_curve, pad, mesh, scale, loads, pivot=pivot, **tilt, **options)
    files = []
    draw = {"pressure": lambda: _field_picture(at, scale, pad, "pressure", out_dir / "pressure.png", s["title"]),
            "film": lambda: _field_picture(at, scale, pad, "film", out_dir / "film.png", s["title"]),
            "curve": lambda: _curve_picture(curve, op["load"], at, out_dir / "curve.png", s["title"])}
    for k, name in enumerate(pictures):
        tick(3 + k, steps, f"picture: {name}")
        files.append(draw[name]().name)
    tick(steps - 1, steps, "files")
    files.append(write_csv(_pad_columns(at, pad), out_dir / "pads.csv", fields=list(_pad_columns(at, pad))).name)
    cols = _curve_columns(curve)
    files.append(write_csv(cols, out_dir / "curve.csv", fields=list(cols)).name)
    summary = _summary(s, pad, mesh, scale, at, curve, thermal, time.perf_counter() - start)
    summary["files"] = files + ["summary.json"]
    write_json(summary, out_dir / "summary.json")
    tick(steps, steps, "done")
    return summary


def _thermal(s: dict, label: str, pad, mesh, omega: float, pivot, tilt: dict, options: dict):
    from ..thermal import thrust_temperature
    from ..thermal.files import balance_of, lubricant_of

    oil = s["oil"]
    return build(label, "oil", thrust_temperature, pad, mesh, s["operating"]["load"], omega,
                 lubricant_of(oil, label, "oil"), balance_of(oil, label, "oil"),
                 reference_film=s["solver"]["reference_film"], pivot=pivot, **tilt, **options)


def _row(perf) -> dict:
    f = perf.flows
    return {"load_N": perf.load, "h_pivot_um": perf.h_pivot * 1e6, "pitch_urad": perf.pitch * 1e6,
            "roll_urad": perf.roll * 1e6, "h_min_um": perf.h_min * 1e6, "p_max_MPa": perf.p_max / 1e6,
            "power_W": perf.power, "friction_torque_Nm": perf.friction_torque,
            "leading_flow_l_min": f.get("leading", 0.0) * LITRES_PER_MINUTE,
            "trailing_flow_l_min": f.get("trailing", 0.0) * LITRES_PER_MINUTE,
            "inner_flow_l_min": f.get("inner", 0.0) * LITRES_PER_MINUTE,
            "outer_flow_l_min": f.get("outer", 0.0) * LITRES_PER_MINUTE}


def _pad_columns(at, pad) -> dict[str, np.ndarray]:
    """One row per pad (identical pads: each carries ``1/n`` of the bearing's load, flows and power)."""
    n = pad.n_pads
    per = {k: v / n if k in ("load_N", "power_W", "friction_torque_Nm") or k.endswith("_l_min") else v
           for k, v in _row(at).items()}
    cols = {"pad": np.arange(1, n + 1, dtype=float),
            "leading_edge_deg": np.degrees(2 * math.pi * np.arange(n) / n)}
    cols.update({k: np.full(n, v) for k, v in per.items()})
    return cols


def _curve_columns(curve) -> dict[str, np.ndarray]:
    rows = [_row(p) for p in curve]
    return {k: np.array([r[k] for r in rows]) for k in rows[0]}


def _field_picture(at, scale, pad, kind: str, path: Path, title: str) -> Path:
    from ..plot.maps import Panel, field_panels

    res = at.pad.result
    if kind == "pressure":
        panel = Panel(res, "pressure", scale.pressure / 1e6, "MPa", scale.radius, plane=True, surface=pad.surface(),
                      title=f"{title}: one pad's pressure, p_max {at.p_max / 1e6:.3g} MPa")
    else:
        panel = Panel(res, "film", scale.clearance * 1e6, "um", scale.radius, plane=True, surface=pad.surface(),
                      title=f"{title}: one pad's film, h_min {at.h_min * 1e6:.3g} um")
    field_panels([[panel]], path, panel_size=(6.0, 5.0))
    return path


def _curve_picture(curve, load: float, at, path: Path, title: str) -> Path:
    """Smallest film and power loss against the load, the operating load marked."""
    from matplotlib.figure import Figure

    from ..plot.figures import frame, save

    cols = _curve_columns(curve)
    fig = Figure(figsize=(7.0, 4.2))
    ax = fig.add_subplot(frame(fig, top=0.75, bottom=0.55, left=0.85, right=0.85)[0, 0])
    kn = cols["load_N"] / 1e3
    ax.plot(kn, cols["h_min_um"], "o-", color="tab:blue", label="smallest film")
    ax.set_xlabel("axial load [kN]")
    ax.set_ylabel("smallest film [um]", color="tab:blue")
    ax.axvline(load / 1e3, color="0.4", ls="--", lw=0.8, label=f"operating load {load / 1e3:.4g} kN")
    ax.grid(True, alpha=0.3)
    twin = ax.twinx()
    twin.plot(kn, cols["power_W"], "s-", color="tab:red", label="power loss")
    twin.set_ylabel("power loss [W]", color="tab:red")
    lines = ax.get_legend_handles_labels()
    more = twin.get_legend_handles_labels()
    ax.legend(lines[0] + more[0], lines[1] + more[1], loc="upper center", fontsize="small")
    ax.set_title(f"{title}\nsmallest film and power loss against load", fontsize="medium")
    save(fig, path)
    return path


def _summary(s: dict, pad, mesh, scale, at, curve, thermal, seconds: float) -> dict:
    r = _row(at)
    table = [("pads", pad.n_pads, ""), ("nodes per pad", mesh.n_nodes, ""),
             ("load", r["load_N"], "N"), ("film at the pivot", r["h_pivot_um"], "um"),
             ("pitch", r["pitch_urad"], "urad"), ("roll", r["roll_urad"], "urad"),
             ("smallest film", r["h_min_um"], "um"), ("peak pressure", r["p_max_MPa"], "MPa"),
             ("power loss", r["power_W"], "W"), ("friction torque", r["friction_torque_Nm"], "N m"),
             ("flow in at the leading edges", r["leading_flow_l_min"], "l/min"),
             ("flow out at the trailing edges", r["trailing_flow_l_min"], "l/min"),
             ("flow out at the inner rims", r["inner_flow_l_min"], "l/min"),
             ("flow out at the outer rims", r["outer_flow_l_min"], "l/min"),
             ("viscosity", scale.viscosity * 1e3, "mPa s")]
    summary = {"kind": "thrust", "title": s["title"], "pads": s["pads"], "operating": s["operating"],
               "solver": s["solver"], "results": r, "curve": [_row(p) for p in curve],
               "notes": list(at.pad.result.notes)}
    if thermal is not None:
        from ..thermal import celsius

        th = {"effective_temperature_C": celsius(thermal.temperature),
              "supply_temperature_C": celsius(thermal.supply_temperature),
              "temperature_rise_K": thermal.heat.rise, "effective_viscosity_Pa_s": thermal.viscosity,
              "supply_viscosity_Pa_s": thermal.supply_viscosity,
              "isothermal_min_film_um": thermal.isothermal.h_min * 1e6,
              "evaluations": thermal.evaluations, "residual_K": thermal.residual}
        summary["thermal"] = th
        table += [("effective temperature", th["effective_temperature_C"], "degC"),
                  ("temperature rise", th["temperature_rise_K"], "K"),
                  ("smallest film, isothermal at supply", th["isothermal_min_film_um"], "um")]
    table.append(("seconds", seconds, "s"))
    summary["table"] = [list(row) for row in table]
    return summary
