"""The ``"journal"`` scene: a journal bearing under a load, in SI units, through ``bearingfe run``.

Scene file::

    kind = "journal"
    title = "..."                        # optional
    [bearing]
    diameter = 0.100                     # D [m]
    length = 0.050                       # L [m]; L/D in [0.001, 4]
    radial_clearance = 75e-6             # c [m]; 0 < c <= D/20
    pads = [[-60.0, 300.0]]              # optional [deg]; absent: full 360 (Raimondi-Boyd)
    supply_pressure = 1.0e5              # [Pa] in the grooves (needs grooves)
    [[bearing.grooves]]                  # any number, each inside a pad (needs pads)
    angle_deg = 120.0
    width_deg = 20.0                     # in (0, 180)
    length_fraction = 0.8                # groove length / L, in (0, 1)
    [operating]
    speed = 3000.0                       # [rpm]; or speed_rad_s = 314.16 [rad/s] (exactly one of the two)
    viscosity = 0.018                    # [Pa s]; absent when [oil] is given
    load = 10.0e3                        # [N]
    load_direction_deg = -90.0           # load on the journal: gravity (-y) by default
    [solver]
    size = 0.05                          # element size [R], in (0, 1]
    min_size = 0.02                      # optional; default size sqrt(1 - eps) at the thinnest film
    cavitation = "reynolds"              # reynolds | none | jfo
    estimate_error = false               # also solve with half the element size
    [output]
    pictures = ["pressure", "wrapped", "film"]
    warp = 0.15                          # wrapped picture: radial push of the peak pressure [R]
    tables = ["pressure", "coefficients"]
    [limits]                             # optional design limits, flagged in the summary (SI)
    min_film = 15e-6                     # smallest film [m]
    max_pressure = 10e6                  # peak pressure [Pa]
    max_friction_power = 2000.0          # friction power [W]
    max_leakage = 5e-5                   # total flow into the film [m^3/s]
    [oil]                                # optional: the viscosity from the heat balance instead
    grade = "VG 32"                      # an ISO 3448 grade with its 100 degC viscosity, or
    kinematic_viscosity_100C = 5.4e-6    # [m^2/s] (the oil's data sheet)
    # kinematic_viscosity = [[40.0, 32e-6], [100.0, 5.4e-6]]   # Walther through [degC, m^2/s] pairs, or
    # vogel = [a, b, c]                  # mu = a exp(b/(T - c)) [Pa s, K, K]
    density_15C = 860.0                  # [kg/m^3]
    specific_heat = 1900.0               # optional [J/(kg K)]; default Cragoe's correlation
    supply_temperature_C = 40.0          # fresh oil [degC]
    carry_over = 0.0                     # hot-oil carry-over, in [0, 1]
    conducted_fraction = 0.0             # share of the friction power conducted away, in [0, 1)
    effective_fraction = 0.5             # T_eff = T_in + k dT, k in (0, 1]

    [tilting_pad]                        # optional: a tilting-pad bearing instead of fixed pads
    n_pads = 5                           # 2 to 12
    arc_deg = 60.0                       # each pad [deg]
    offset = 0.6                         # pivot from the leading edge, fraction of the arc
    preload = 0.25                       # m = 1 - C_b/C_p ([bearing] radial_clearance is C_p)
    load_on_pad = false                  # a pivot on the load line, or the load between two pads
    pivot_stiffness = 5e8                # [N/m]; absent: rigid pivots
    pad_inertia = 2e-5                   # about the pivot [kg m^2]
    pad_thickness = 0.012                # pad surface to the rocker line [m]
    rotor_mass = 800.0                   # [kg], rigid rotor on two such bearings (default 2 load / g)
    stability_speeds = [1500.0, 12000.0] # [rpm] (default 0.25 to 2 times the speed)
    stability_points = 8
    frequency_ratios = [0.5, 1.0, 1.5, 2.0]   # whirl frequency / speed of the tables

Angles are in the bearing frame: from ``+x`` (horizontal) towards ``+y``
(up), the direction in which the journal turns. The runner finds the
equilibrium under the load (:func:`bearingfe.bearings.journal.equilibrium`, Newton),
the eight film coefficients by linearization
(:func:`bearingfe.bearings.journal.dynamic_coefficients`), and writes
``summary.json``, ``pressure_field.csv`` (every node: pad, angle, axial
position, pressure [Pa], film [m], ruptured flag), ``coefficients.csv`` (the
ROSS ``BearingElement`` columns, SI) and the pictures ``pressure.png``,
``pressure_wrapped.png``, ``film.png`` (one per pad, ``_pad<k>``, when there
are several).

With ``[oil]`` the film's viscosity is not given but found: the effective
temperature of the level-1 heat balance
(:func:`bearingfe.thermal.effective_temperature`: friction power against the
heat carried by the side and trailing flows), and every result below is that
of the effective viscosity; the summary's ``thermal`` table has the
temperatures, the effective viscosity, the power loss and how far the
isothermal answer at the supply temperature moved. With ``estimate_error``
the half-size solve keeps that viscosity. Without ``[oil]`` nothing changes.

The summary (SI, unit in each key): eccentricity, attitude angle (from the
load line to the line of centres, in the direction of rotation), journal
position, minimum film, maximum pressure, Sommerfeld number
``S = mu N L D / W (R/c)^2``, friction torque and power (``T omega``), side
flow (out of the axial edges), total flow (into the film through the leading
edges of the pads and the grooves: Raimondi-Boyd's ``Q`` for the full
bearing) and groove flow; for the full bearing also the Raimondi-Boyd chart
variables. Stiffness ``K`` [N/m] and damping ``C`` [N s/m] are in the ROSS
frame (``x`` horizontal, ``y`` up, the journal turning from ``+x`` to ``+y``:
the bearing frame of the file, whatever the load direction), with their
non-dimensional forms ``K c/W``, ``C c omega/W`` and the keywords of
``ross.BearingElement`` (``n`` is the caller's). ``cost`` has nodes,
iterations and seconds; with ``estimate_error`` the whole computation is
repeated with half the element size and the relative changes are reported
(``K``, ``C``: largest entry change over largest entry); the values reported
are those of the given size.

Pictures show the pressure in MPa and the film in um, titled with the
eccentricity, attitude, peak pressure and smallest film: ``pressure.png`` and
``film.png`` over the angle in the bearing frame [deg] and the axial position
[mm], ``pressure_wrapped.png`` on the bearing's cylinder, the film rupture
boundary in red. The full bearing is meshed in the frame of the line of
largest film (``phi = 0`` there, as in Raimondi-Boyd), whose angle in the
bearing frame is in the summary. ``[limits]`` (optional, SI, ranges in
:data:`bearingfe.core.schema.LIMITS`) are flagged in the summary: each
``results.limits[name]`` has the value, the limit and ``ok``.
"""

from __future__ import annotations

import dataclasses
import math
import time
from pathlib import Path
from typing import Callable

import numpy as np

from ..core.schema import (LIMITS_TABLE, REQUIRED, Range, SchemaError, Table, Tables, anything, build, check_limits,
                           choice, choices, flag, integer, nonnegative_number, number, numbers, positive_number,
                           read_table, text)

__all__ = ["run", "settings", "pressure_columns", "SPEC", "PICTURES", "TABLES"]

PICTURES = ("pressure", "wrapped", "film")
TABLES = ("pressure", "coefficients")


# -- the schema -------------------------------------------------------------------------

#: What the ``pads`` field accepts (its error messages and the file-format reference).
_PAD_RULE = "a list of pads [[start_deg, end_deg], ...] with start < end <= start + 360, not overlapping"


def _pads(where, value):
    """Pads ``[[start_deg, end_deg], ...]``: start < end <= start + 360, no two overlapping."""
    rule = _PAD_RULE
    if not (isinstance(value, list) and value):
        raise SchemaError(f"{where}: expected {rule}; got {value!r}")
    pads = []
    for pad in value:
        if not (isinstance(pad, list) and len(pad) == 2):
            raise SchemaError(f"{where}: expected {rule}; got {pad!r}")
        a, b = (number()(where, v) for v in pad)
        if not a < b <= a + 360.0:
            raise SchemaError(f"{where}: expected {rule}; got {pad!r}")
        pads.append((a, b))
    ordered = sorted(((a % 360.0, a % 360.0 + b - a) for a, b in pads))
    for (a1, b1), (a2, _) in zip(ordered, ordered[1:] + [(ordered[0][0] + 360.0, None)]):
        if b1 > a2 + 1e-9:
            raise SchemaError(f"{where}: expected {rule}; pads overlap after {a1:g} deg")
    return tuple(pads)


_pads.accepts = _PAD_RULE


def _cavitation_models() -> tuple[str, ...]:
    from ..bearings.journal import EQUILIBRIUM_CAVITATION

    return tuple(EQUILIBRIUM_CAVITATION)


_OPEN_UNIT = Range(0.0, 1.0, lo_open=True, hi_open=True)


def _oil_fields() -> dict:
    from ..thermal.files import OIL

    return dict(OIL)


def _ratios(where, value):
    """Whirl frequency over rotor speed: 1 to 20 increasing numbers > 0."""
    if not (isinstance(value, list) and 1 <= len(value) <= 20 and all(
            isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0 for v in value)
            and all(b > a for a, b in zip(value, value[1:]))):
        raise SchemaError(f"{where}: expected {_ratios.accepts}; got {value!r}")
    return tuple(float(v) for v in value)


_ratios.accepts = "1 to 20 increasing numbers > 0 [-]"


def _tilting_fields() -> dict:
    """The ``[tilting_pad]`` table: the bearing is a tilting-pad bearing (:class:`bearingfe.TiltingPadBearing`)."""
    return {
        "n_pads": (integer(Range(2, 12)), 5, "number of pads [-]"),
        "arc_deg": (number(Range(0.0, 180.0, lo_open=True, hi_open=True)), 60.0, "angular extent of each pad [deg]"),
        "offset": (number(_OPEN_UNIT), 0.5, "pivot from the leading edge as a fraction of the arc [-]"),
        "preload": (number(Range(0.0, 1.0, hi_open=True)), 0.0, "preload m = 1 - C_b/C_p [-]"),
        "load_on_pad": (flag, False, "a pivot on the load line (true) or the load between two pads (false)"),
        "pivot_stiffness": (positive_number, None, "radial stiffness of each pivot [N/m] (default: rigid)"),
        "pad_inertia": (nonnegative_number, 0.0, "moment of inertia of a pad about its pivot [kg m^2]"),
        "pad_thickness": (nonnegative_number, 0.0, "pad surface to pivot (rocker) line [m]"),
        "rotor_mass": (positive_number, None,
                       "rigid rotor on two such bearings for the stability map [kg] (default: 2 load / g)"),
        "stability_speeds": (numbers(2, "a pair [lowest_rpm, highest_rpm]"), None,
                             "speed range of the stability map [rpm] (default: 0.25 to 2 times the speed)"),
        "stability_points": (integer(Range(2, 40)), 8, "speeds in the stability map [-]"),
        "frequency_ratios": (_ratios, (0.5, 1.0, 1.5, 2.0),
                             "whirl frequency over speed of the coefficient tables and ROSS files [-]"),
    }


#: The ``"journal"`` scene file: ``{name: (check, default) | Table | Tables}`` (see :mod:`bearingfe.core.schema`).
SPEC = {
    "kind": (anything, REQUIRED, "the scene kind (this section's name)"),
    "title": (text, None, "title of the pictures and tables (default: the file name)"),
    "bearing": Table({
        "diameter": (positive_number, REQUIRED, "journal diameter D [m]"),
        "length": (positive_number, REQUIRED, "bearing length L [m]"),
        "radial_clearance": (positive_number, REQUIRED, "radial clearance c [m]"),
        "pads": (_pads, None, "film arcs [[start_deg, end_deg], ...] from +x towards +y [deg] (default: 360)"),
        "grooves": Tables({"angle_deg": (number(), REQUIRED, "groove centre angle [deg]"),
                           "width_deg": (number(Range(0.0, 180.0, lo_open=True, hi_open=True)), REQUIRED,
                                         "groove angular width [deg]"),
                           "length_fraction": (number(_OPEN_UNIT), 0.8, "groove length over L [-]")}),
        "supply_pressure": (nonnegative_number, 0.0, "oil pressure in the grooves [Pa]")}, required=True),
    "operating": Table({"speed": (positive_number, None, "journal speed [rpm] (or speed_rad_s)"),
                        "speed_rad_s": (positive_number, None, "journal angular speed [rad/s] (or speed)"),
                        "viscosity": (positive_number, None, "oil dynamic viscosity [Pa s] (or an [oil] table)"),
                        "load": (positive_number, REQUIRED, "load on the journal [N]"),
                        "load_direction_deg": (number(), -90.0, "direction of the load from +x towards +y [deg]")},
                       required=True),
    "solver": Table({"size": (number(Range(0.0, 1.0, lo_open=True)), 0.05, "element size [R]"),
                     "min_size": (number(Range(0.0, 1.0, lo_open=True)), None,
                                  "element size at the thinnest film [R] (default: size sqrt(1 - eps))"),
                     "cavitation": (choice(_cavitation_models), "reynolds", "cavitation model"),
                     "estimate_error": (flag, False, "repeat with half the element size and report the changes")}),
    "output": Table({"pictures": (choices(PICTURES), PICTURES, "pictures to draw"),
                     "warp": (nonnegative_number, 0.15, "radial push of the peak pressure in the wrapped picture [R]"),
                     "tables": (choices(TABLES), TABLES, "CSV tables to write")}),
    "limits": LIMITS_TABLE,
    "oil": Table(_oil_fields()),
    "tilting_pad": Table(_tilting_fields()),
}


def settings(data: dict, label: str, base_dir: Path | None = None) -> dict:
    """All validated settings of a ``"journal"`` scene (SI, angles in degrees)."""
    s = read_table(data, label, "", SPEC)
    bearing, solver, op = s["bearing"], s["solver"], s["operating"]
    if (op["speed"] is None) == (op["speed_rad_s"] is None):
        raise SchemaError(f"{label}: [operating] speed: give exactly one of speed [rpm] and speed_rad_s [rad/s]; "
                          f"got speed = {op['speed']!r}, speed_rad_s = {op['speed_rad_s']!r}")
    if op["speed"] is None:
        op["speed"] = op["speed_rad_s"] * 60 / (2 * math.pi)  # the runner reads rpm
    op["speed_rad_s"] = 2 * math.pi * op["speed"] / 60
    _check_proportions(bearing, label)
    _check_grooves(bearing, label)
    if solver["min_size"] is not None and solver["min_size"] > solver["size"]:
        raise SchemaError(f"{label}: [solver] min_size: must be in (0, size = {solver['size']:g}]; "
                          f"got {solver['min_size']!r}")
    oil = s["oil"] if "oil" in data else None
    _check_oil(s["operating"], oil, label)
    tilting = s["tilting_pad"] if "tilting_pad" in data else None
    if tilting is not None:
        _check_tilting(s, tilting, oil, label)
    return {"title": label if s["title"] is None else s["title"], "bearing": bearing,
            "operating": op, "solver": solver, "output": s["output"], "limits": s["limits"], "oil": oil,
            "tilting_pad": tilting}


def _check_tilting(s: dict, t: dict, oil, label: str) -> None:
    """What a tilting-pad bearing takes of the other tables: no fixed pads or grooves, a load along -y
    (the pads are laid out about it), a cavitation model with a pad moment balance; [oil] gives the pads' level-1
    heat balance (:func:`bearingfe.thermal.tilting_pad_temperature`)."""
    from ..bearings.tilting_pad import TILTING_PAD_CAVITATION

    b = s["bearing"]
    for name in ("pads", "grooves"):
        if b[name]:
            raise SchemaError(f"{label}: [bearing] {name}: must be absent with [tilting_pad] (the pads are "
                              f"n_pads, arc_deg, offset there); got {b[name]!r}")
    if b["supply_pressure"]:
        raise SchemaError(f"{label}: [bearing] supply_pressure: must be 0 with [tilting_pad]")
    if s["operating"]["load_direction_deg"] != -90.0:
        raise SchemaError(f"{label}: [operating] load_direction_deg: must be -90 with [tilting_pad] (load on "
                          f"or between pads: [tilting_pad] load_on_pad); got {s['operating']['load_direction_deg']!r}")
    if s["solver"]["cavitation"] not in TILTING_PAD_CAVITATION:
        raise SchemaError(f"{label}: [solver] cavitation: must be one of {TILTING_PAD_CAVITATION} with "
                          f"[tilting_pad] (a free pad needs film rupture to balance); got {s['solver']['cavitation']!r}")
    if s["solver"]["estimate_error"]:
        raise SchemaError(f"{label}: [solver] estimate_error: not with [tilting_pad]")
    if t["stability_speeds"] is not None and not 0 < t["stability_speeds"][0] < t["stability_speeds"][1]:
        raise SchemaError(f"{label}: [tilting_pad] stability_speeds: must be [lowest, highest] with "
                          f"0 < lowest < highest [rpm]; got {list(t['stability_speeds'])!r}")


def _check_oil(op: dict, oil: dict | None, label: str) -> None:
    """Either ``[operating] viscosity`` or ``[oil]``; in ``[oil]`` one lubricant and a supply temperature."""
    if oil is None:
        if op["viscosity"] is None:
            raise SchemaError(f"{label}: [operating] viscosity: missing (required without an [oil] table)")
        return
    if op["viscosity"] is not None:
        raise SchemaError(f"{label}: [operating] viscosity: must be absent with an [oil] table (the heat "
                          f"balance finds the viscosity); got {op['viscosity']!r}")
    from ..thermal.files import check_oil

    check_oil(oil, label, "oil")


def _check_proportions(b: dict, label: str) -> None:
    ratio = b["length"] / b["diameter"]
    if not 1e-3 <= ratio <= 4.0:
        raise SchemaError(f"{label}: [bearing] length: L/D must be in [0.001, 4]; got L/D = {ratio:.4g}")
    if not b["radial_clearance"] <= b["diameter"] / 20:
        raise SchemaError(f"{label}: [bearing] radial_clearance: must be in (0, diameter/20 = "
                          f"{b['diameter'] / 20:g}] m (a thin film, c/R <= 0.1); got {b['radial_clearance']!r}")


def _check_grooves(b: dict, label: str) -> None:
    items = b["grooves"]
    if items and b["pads"] is None:
        raise SchemaError(f"{label}: [bearing] grooves: need pads = [[start_deg, end_deg], ...] "
                          "(the full Raimondi-Boyd bearing has no grooves)")
    if b["supply_pressure"] > 0 and not items:
        raise SchemaError(f"{label}: [bearing] supply_pressure: needs [[bearing.grooves]] to feed; "
                          f"must be 0 without grooves; got {b['supply_pressure']!r}")
    for k, g in enumerate(items):
        half = g["width_deg"] / 2
        if not any(a + half < a + (g["angle_deg"] - a) % 360.0 < b_ - half for a, b_ in b["pads"]):
            raise SchemaError(f"{label}: [bearing.grooves.{k}] angle_deg: the groove (width {g['width_deg']:g} deg) "
                              f"must lie inside one of the pads {list(map(list, b['pads']))}; "
                              f"got {g['angle_deg']!r}")


# -- the run ------------------------------------------------------------------------------

def _scale(s: dict):
    from ..core.scales import Scale

    b, op = s["bearing"], s["operating"]
    return Scale(radius=b["diameter"] / 2, clearance=b["radial_clearance"], viscosity=op["viscosity"],
                 speed=op["speed_rad_s"])


def _bearing(s: dict, scale, label: str):
    from ..bearings.journal import Groove, JournalBearing

    b = s["bearing"]
    pads = None if b["pads"] is None else tuple((math.radians(p), math.radians(q)) for p, q in b["pads"])
    grooves = tuple(Groove(math.radians(g["angle_deg"]), math.radians(g["width_deg"]), g["length_fraction"])
                    for g in b["grooves"])
    return build(label, "bearing", JournalBearing, length_ratio=b["length"] / b["diameter"], pads=pads,
                  grooves=grooves, supply_pressure=scale.from_pressure(b["supply_pressure"]))


def _load(s: dict, scale) -> np.ndarray:
    """Applied load on the journal in the bearing frame [mu omega R^4/c^2]."""
    theta = math.radians(s["operating"]["load_direction_deg"])
    return scale.from_force(s["operating"]["load"]) * np.array([math.cos(theta), math.sin(theta)])


def _solve(bearing, load, size, min_size, cavitation, eq=None):
    """Equilibrium (unless given) and coefficients, timed."""
    from ..bearings.journal import dynamic_coefficients, equilibrium

    t0 = time.perf_counter()
    if eq is None:
        eq = equilibrium(bearing, load, size=size, min_size=min_size, cavitation=cavitation)
    t1 = time.perf_counter()
    # finite-volume (JFO) solutions keep no Galerkin system to linearize: central differences instead
    dc = dynamic_coefficients(eq, method="finite-difference" if cavitation == "jfo" else "linearized")
    return eq, dc, t1 - t0, time.perf_counter() - t1


def _fixed_frame(dc, force):
    """The coefficients in the bearing frame of the file (``x`` horizontal, ``y`` up).

    :func:`bearingfe.bearings.journal.dynamic_coefficients` turns its frame so that
    the load points along ``-y``; this turns it back (the identity for a
    gravity load), so that a load in any direction gives coefficients in the
    fixed frame a rotor model uses.
    """
    direction = math.atan2(force[1], force[0])
    c, s = math.cos(-math.pi / 2 - direction), math.sin(-math.pi / 2 - direction)
    Q = np.array([[c, -s], [s, c]])
    return dataclasses.replace(dc, K=Q.T @ dc.K @ Q, C=Q.T @ dc.C @ Q)


def run(data: dict, label: str, out_dir: Path, progress: Callable | None = None,
                      base_dir: Path | None = None) -> dict:
    """Equilibrium, dynamic coefficients, pictures and tables of a journal bearing scene.

    Returns the summary written to ``summary.json`` (SI units; see the
    module docstring for the files).
    """
    from ..io.writers import write_json

    s = settings(data, label)
    solver, out = s["solver"], s["output"]
    tick = progress or (lambda done, total, what: None)
    if s["tilting_pad"] is not None:
        return _run_tilting(s, label, out_dir, tick)
    thermal, t_thermal = None, 0.0
    if s["oil"] is not None:
        tick(0, 1, "effective temperature (heat balance)")
        t0 = time.perf_counter()
        thermal = _thermal(s, label)
        t_thermal = time.perf_counter() - t0
        s = {**s, "operating": {**s["operating"], "viscosity": thermal.viscosity}}
    scale = _scale(s)
    bearing = _bearing(s, scale, label)
    load = _load(s, scale)
    n_pics = len(out["pictures"]) * len(bearing.surfaces())
    steps = 2 + int(solver["estimate_error"]) + n_pics
    tick(0, steps, "equilibrium and coefficients")
    eq, dc, t_eq, t_dc = _solve(bearing, load, solver["size"], solver["min_size"], solver["cavitation"],
                                None if thermal is None else thermal.equilibrium)
    t_eq += t_thermal
    fine = None
    if solver["estimate_error"]:
        tick(1, steps, "error estimate (half the element size)")
        half = None if solver["min_size"] is None else solver["min_size"] / 2
        fine = _solve(bearing, load, solver["size"] / 2, half, solver["cavitation"])
    summary = _summary(s, scale, bearing, eq, dc, {"equilibrium": t_eq, "coefficients": t_dc}, fine)
    if thermal is not None:
        summary["thermal"] = _thermal_summary(thermal, s["oil"])
        summary["table"][9:9] = _thermal_rows(summary["thermal"])
    done = 1 + int(solver["estimate_error"])
    t0 = time.perf_counter()
    files = _tables(out["tables"], s, scale, eq, summary, out_dir)
    files += _pictures(out, bearing, eq, scale, out_dir, lambda k, what: tick(done + k, steps, what), s["title"])
    summary["cost"]["seconds"]["output"] = time.perf_counter() - t0
    summary["files"] = files + ["summary.json"]
    tick(steps - 1, steps, "summary")
    write_json(summary, out_dir / "summary.json")
    tick(steps, steps, "done")
    return summary


# -- tilting pads ----------------------------------------------------------------------------

#: Standard gravity [m/s^2]: a rotor carried by its weight (the default rotor of the stability map).
GRAVITY = 9.80665


def _tilting_bearing(s: dict, label: str):
    from ..bearings.tilting_pad import TiltingPadBearing

    b, t = s["bearing"], s["tilting_pad"]
    return build(label, "tilting_pad", TiltingPadBearing, radius=b["diameter"] / 2, length=b["length"],
                 pad_clearance=b["radial_clearance"], n_pads=t["n_pads"], arc=math.radians(t["arc_deg"]),
                 offset=t["offset"], preload=t["preload"], load_on_pad=t["load_on_pad"],
                 pad_inertia=t["pad_inertia"], pad_thickness=t["pad_thickness"],
                 pivot_stiffness=math.inf if t["pivot_stiffness"] is None else t["pivot_stiffness"])


def _run_tilting(s: dict, label: str, out_dir: Path, tick: Callable) -> dict:
    """The ``[tilting_pad]`` scene: equilibrium of the shaft and the pads, the reduced coefficients over the
    whirl frequencies, the stability map of a rigid rotor on two such bearings, pictures, tables and ROSS
    files."""
    from ..bearings.stability import log_decrement_map, threshold_speed
    from ..bearings.tilting_pad import (TiltingPadConvergenceError, pad_assembly_coefficients, ross_table_of,
                                        tilting_pad_equilibrium, tilting_pad_meshes)
    from ..core.scales import Scale
    from ..io.writers import write_csv, write_json, write_ross3_bearing, write_ross_bearings

    b, op, t, solver, out = s["bearing"], s["operating"], s["tilting_pad"], s["solver"], s["output"]
    bearing = _tilting_bearing(s, label)
    geometry = bearing.geometry
    omega, load = op["speed_rad_s"], op["load"]
    meshes = build(label, "solver", tilting_pad_meshes, geometry, solver["size"])
    thermal = None
    if s["oil"] is not None:  # the viscosity of the pads' level-1 heat balance
        thermal = _tilting_thermal(s, label, bearing, meshes)
        mu = thermal.viscosity
    else:
        mu = op["viscosity"]
    scale = build(label, "bearing", Scale, radius=bearing.radius, clearance=bearing.pad_clearance, viscosity=mu,
                  speed=omega)
    steps = 4
    tick(0, steps, "equilibrium and coefficients")
    solved: dict = {}

    def solve(speed: float):
        """Equilibrium and full coefficients at a speed [rad/s], warm-started from the nearest speed solved."""
        if speed not in solved:
            near = min(solved, key=lambda v: abs(v - speed)) if solved else None
            args = (geometry, (0.0, -load / bearing.force_scale(mu, speed)))
            options = dict(meshes=meshes, cavitation=solver["cavitation"],
                           pivot_stiffness=bearing.pivot_stiffness_parameter(mu, speed))
            try:
                eq = build(label, "tilting_pad", tilting_pad_equilibrium, *args, **options,
                           start=None if near is None else solved[near][0])
            except TiltingPadConvergenceError:
                if near is None:
                    raise
                # the warm start (another speed: on flexible pivots another pivot stiffness parameter too)
                # can lead Newton astray where the cold start does not
                eq = build(label, "tilting_pad", tilting_pad_equilibrium, *args, **options)
            solved[speed] = (eq, pad_assembly_coefficients(eq))
        return solved[speed]

    t0 = time.perf_counter()
    eq, full = solve(omega)
    t_eq = time.perf_counter() - t0
    ratios = np.asarray(t["frequency_ratios"])
    pad_mass = bearing.pad_mass(mu, omega)
    sync = full.reduced(1.0, pad_mass=pad_mass)
    K, C = sync.to_si(viscosity=mu, speed=omega, radius=bearing.radius, clearance=bearing.pad_clearance)
    tick(1, steps, "stability map")
    lo, hi = (0.25 * op["speed"], 2.0 * op["speed"]) if t["stability_speeds"] is None else t["stability_speeds"]
    speeds = np.linspace(lo, hi, t["stability_points"]) * math.pi / 30
    rotor_mass = 2 * load / GRAVITY if t["rotor_mass"] is None else t["rotor_mass"]
    t0 = time.perf_counter()
    delta = log_decrement_map(speeds, lambda v: solve(float(v))[1],
                              lambda v: 0.5 * rotor_mass * bearing.pad_clearance * v**2 / load,
                              lambda v: bearing.pad_mass(mu, v))
    threshold = threshold_speed(speeds, delta)
    # coefficients over (rotor speed, whirl frequency): the map's speeds, whirl at the ratios of the speed
    table = ross_table_of(bearing, mu, speeds, ratios * omega, lambda v: solve(v)[1])
    t_map = time.perf_counter() - t0
    results = [st.results[0] for st in eq.pads.states if st is not None]
    film = _film_results(eq, scale, results)
    r_pivot = bearing.radius + bearing.pad_thickness
    pads = [{"pivot_deg": math.degrees(float(th)), "loaded": not bool(idle),
             "rotation_rad": float(q) * bearing.pad_clearance / r_pivot,
             "load_N": float(np.hypot(*f)) * bearing.force_scale(mu, omega),
             "pivot_deflection_m": 0.0 if eq.deflections is None else float(d) * bearing.pad_clearance}
            for th, q, f, idle, d in zip(geometry.pivots, eq.tilts, eq.pad_forces, eq.idle,
                                         np.zeros(geometry.n_pads) if eq.deflections is None else eq.deflections)]
    verdicts = check_limits({"min_film": film["min_film_m"], "max_pressure": film["max_pressure_Pa"],
                             "max_friction_power": film["friction_power_W"], "max_leakage": film["total_flow_m3s"]},
                            s["limits"])
    res = {"eccentricity": eq.eps, "attitude_deg": eq.attitude, "sommerfeld": eq.sommerfeld,
           "journal_position_m": (np.asarray(eq.position) * bearing.pad_clearance).tolist(), **film,
           "pads": pads, "newton_iterations": eq.newton_iterations, "limits": verdicts,
           "within_limits": all(v["ok"] for v in verdicts.values())}
    coefficients = {"frequency_ratio": ratios.tolist(), "frequency_rad_s": (ratios * omega).tolist(),
                    "K_N_per_m": K.tolist(), "C_Ns_per_m": C.tolist(),
                    "K_nondimensional": sync.K.tolist(), "C_nondimensional": sync.C.tolist(),
                    "pad_mass_nondimensional": pad_mass}
    per_ratio = [full.reduced(float(r), pad_mass=pad_mass).to_si(viscosity=mu, speed=omega, radius=bearing.radius,
                                                                  clearance=bearing.pad_clearance) for r in ratios]
    stability = {"speed_rpm": (speeds * 30 / math.pi).tolist(), "log_decrement": delta.tolist(),
                 "threshold_rpm": threshold * 30 / math.pi if math.isfinite(threshold) else None,
                 "rotor_mass_kg": rotor_mass, "rotor": "rigid, symmetric, on two such bearings"}
    summary = {"kind": "journal", "title": s["title"], "bearing": {**_bearing_echo(b), "tilting_pad": dict(t)},
               "operating": dict(op), "scales": _scales(scale), "results": res, "coefficients": coefficients,
               "stability": stability, "limits": dict(s["limits"]),
               "cost": {"nodes": sum(m.n_nodes for m in meshes), "seconds": {"equilibrium": t_eq,
                                                                             "stability_and_tables": t_map}}}
    tick(2, steps, "pictures and tables")
    t0 = time.perf_counter()
    files = []
    if "coefficients" in out["tables"]:
        cols = {"frequency_ratio [-]": ratios, "frequency [rad/s]": ratios * omega}
        for name, unit, which in (("k", "N/m", 0), ("c", "N s/m", 1)):
            for i, a in enumerate("xy"):
                for j, c_ in enumerate("xy"):
                    cols[f"{name}{a}{c_} [{unit}]"] = np.array([kc[which][i, j] for kc in per_ratio])
        files.append(write_csv(cols, out_dir / "coefficients.csv", fields=list(cols)).name)
        files += [p.name for p in write_ross_bearings(table, out_dir, tag="tilting_pad")]
        files.append(write_ross3_bearing(table, out_dir / "tilting_pad_ross3.toml", tag="tilting_pad").name)
    cols = {"speed [rpm]": speeds * 30 / math.pi, "speed [rad/s]": speeds, "log_decrement [-]": delta,
            "eccentricity [-]": np.array([solve(float(v))[0].eps for v in speeds])}
    files.append(write_csv(cols, out_dir / "stability.csv", fields=list(cols)).name)
    if "pressure" in out["pictures"]:
        files.append(_tilting_pressure_picture(eq, meshes, bearing, scale, pads, out_dir / "pressure.png",
                                               s["title"]).name)
    files.append(_stability_picture(stability, op["speed"], out_dir / "stability.png", s["title"]).name)
    summary["cost"]["seconds"]["output"] = time.perf_counter() - t0
    summary["table"] = _tilting_table(res, K, C, stability, summary["cost"])
    if thermal is not None:
        summary["thermal"] = _thermal_summary(thermal, s["oil"])
        summary["table"][-1:-1] = _thermal_rows(summary["thermal"])
    summary["files"] = files + ["summary.json"]
    tick(3, steps, "summary")
    write_json(summary, out_dir / "summary.json")
    tick(steps, steps, "done")
    return summary


def _tilting_thermal(s: dict, label: str, bearing, meshes):
    """The effective temperature of the scene's tilting pads (:func:`bearingfe.thermal.tilting_pad_temperature`)."""
    from ..thermal import tilting_pad_temperature
    from ..thermal.files import balance_of, lubricant_of

    oil, op, solver = s["oil"], s["operating"], s["solver"]
    return build(label, "oil", tilting_pad_temperature, bearing, op["load"], op["speed_rad_s"],
                 lubricant_of(oil, label, "oil"), balance_of(oil, label, "oil"), meshes=meshes,
                 cavitation=solver["cavitation"])


def _tilting_table(r: dict, K, C, stability: dict, cost: dict) -> list:
    rows = [("eccentricity ratio", r["eccentricity"], "-"), ("attitude angle", r["attitude_deg"], "deg"),
            ("minimum film", r["min_film_m"] * 1e6, "um"), ("peak pressure", r["max_pressure_Pa"], "Pa"),
            ("Sommerfeld number", r["sommerfeld"], "-"), ("friction power", r["friction_power_W"], "W"),
            ("side flow", r["side_flow_m3s"] * 6e4, "l/min")]
    rows += [(f"pad {k + 1} at {p['pivot_deg']:.0f} deg: rotation", p["rotation_rad"] * 1e6, "urad")
             for k, p in enumerate(r["pads"])]
    rows += [(f"pad {k + 1}: load", p["load_N"], "N") for k, p in enumerate(r["pads"])]
    rows += [(f"limit {name}: {v['value']:.4g} {v['relation']} {v['limit']:.4g} {v['unit']}",
              "ok" if v["ok"] else "VIOLATED", "") for name, v in r["limits"].items()]
    rows += [(f"k{a}{b} (synchronous)", float(K[i, j]), "N/m") for i, a in enumerate("xy") for j, b in enumerate("xy")]
    rows += [(f"c{a}{b} (synchronous)", float(C[i, j]), "N s/m") for i, a in enumerate("xy")
             for j, b in enumerate("xy")]
    rows += [("smallest log decrement over the map", min(stability["log_decrement"]), "-"),
             ("stability threshold", "none in the map" if stability["threshold_rpm"] is None
              else stability["threshold_rpm"], "" if stability["threshold_rpm"] is None else "rpm"),
             ("nodes", cost["nodes"], ""), ("seconds", sum(cost["seconds"].values()), "s")]
    return [list(row) for row in rows]


def _tilting_pressure_picture(eq, meshes, bearing, scale, pads: list, path: Path, title: str) -> Path:
    """Every loaded pad's pressure [MPa] over the angle [deg] and the axial position [mm], one colour scale,
    each pad outlined and labelled with its rotation [urad] and load [kN]."""
    from matplotlib.figure import Figure
    from matplotlib.tri import Triangulation

    from ..plot.figures import frame, save
    from ..plot.maps import gouraud, sampled

    fig = Figure(figsize=(10.0, 4.6))
    ax = fig.add_subplot(frame(fig, top=0.8, bottom=0.55, left=0.8, right=0.3)[0, 0])
    to_mm = bearing.radius * 1e3
    drawn = [(sampled(st.results[0]), st) for st in eq.pads.states if st is not None]
    hi = max((float(v.max()) for (_, _, v), _ in drawn), default=1.0) * scale.pressure / 1e6
    art = None
    for (xy, tri, v), _ in drawn:
        art = gouraud(ax, Triangulation(np.degrees(xy[0]), xy[1] * to_mm, tri.T), v * scale.pressure / 1e6,
                      "viridis", 0.0, hi or 1.0)
    half = bearing.length / 2 * 1e3
    for (start, end), pad in zip(bearing.geometry.arcs, pads):
        a, e = math.degrees(start), math.degrees(end)
        ax.plot([a, e, e, a, a], [-half, -half, half, half, -half], color="k", lw=0.8)
        ax.plot([pad["pivot_deg"]] * 2, [-half, half], color="w" if pad["loaded"] else "0.5", lw=0.8, ls=":")
        ax.text((a + e) / 2, half * 1.08, f"{pad['rotation_rad'] * 1e6:.3g} urad\n{pad['load_N'] / 1e3:.3g} kN",
                ha="center", va="bottom", fontsize="small")
    ax.set_ylim(-half * 1.05, half * 1.6)
    ax.set_xlabel("angle from +x towards +y [deg] (pivots dotted)")
    ax.set_ylabel("z [mm]")
    if art is not None:
        from matplotlib.ticker import AutoLocator

        from ..plot.colour_bars import colour_bar

        colour_bar(ax, art, "p [MPa]", AutoLocator())
    ax.set_title(f"{title}\n{len(pads)} tilting pads: eps = {eq.eps:.3g}, attitude = {eq.attitude:.3g} deg; "
                 f"pad rotation and load above each pad", fontsize="medium")
    save(fig, path)
    return path


def _stability_picture(stability: dict, speed_rpm: float, path: Path, title: str) -> Path:
    """The smallest log decrement of the rigid rotor against speed, the operating speed and any threshold."""
    from matplotlib.figure import Figure

    from ..plot.figures import frame, save

    fig = Figure(figsize=(7.0, 4.2))
    ax = fig.add_subplot(frame(fig, top=0.75, bottom=0.55, left=0.85, right=0.25)[0, 0])
    rpm, delta = np.asarray(stability["speed_rpm"]), np.asarray(stability["log_decrement"])
    ax.plot(rpm, delta, "o-", color="tab:green", label="smallest log decrement")
    ax.axhline(0.0, color="red", lw=0.8, label="stability limit")
    ax.axvline(speed_rpm, color="0.4", ls="--", lw=0.8, label=f"operating speed {speed_rpm:.4g} rpm")
    if stability["threshold_rpm"] is not None:
        ax.axvline(stability["threshold_rpm"], color="red", ls=":", label=f"threshold {stability['threshold_rpm']:.4g} rpm")
    ax.set_xlabel("speed [rpm]")
    ax.set_ylabel("log decrement [-]")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    ax.set_title(f"{title}\nstability map: {stability['rotor_mass_kg']:.4g} kg {stability['rotor']}",
                 fontsize="medium")
    save(fig, path)
    return path


# -- the heat balance ----------------------------------------------------------------------

def _thermal(s: dict, label: str):
    """The effective temperature of the scene's bearing (:func:`bearingfe.thermal.effective_temperature`)."""
    from ..thermal import JournalDuty, effective_temperature
    from ..thermal.files import balance_of, lubricant_of

    b, op, oil, solver = s["bearing"], s["operating"], s["oil"], s["solver"]
    duty = build(label, "operating", JournalDuty, radius=b["diameter"] / 2, clearance=b["radial_clearance"],
                 speed=2 * math.pi * op["speed"] / 60, load=op["load"],
                 load_direction=math.radians(op["load_direction_deg"]), supply_pressure=b["supply_pressure"])
    balance = balance_of(oil, label, "oil")
    lubricant = lubricant_of(oil, label, "oil")
    # the bearing at any viscosity: its supply pressure is made non-dimensional at each trial temperature
    scale = _scale({**s, "operating": {**op, "viscosity": lubricant.viscosity(balance.supply_temperature)}})
    bearing = _bearing(s, scale, label)
    return effective_temperature(bearing, duty, lubricant, balance, size=solver["size"],
                                 min_size=solver["min_size"], cavitation=solver["cavitation"])


def _thermal_summary(t, oil: dict) -> dict:
    """The heat balance in the summary (SI; temperatures also in degC)."""
    from ..thermal import celsius

    def rel(new, old):
        return (new - old) / old
    return {
        "model": "level 1: effective temperature from the heat balance of the whole film",
        "effective_temperature_C": celsius(t.temperature), "supply_temperature_C": celsius(t.supply_temperature),
        "inlet_temperature_C": celsius(t.inlet_temperature), "outlet_temperature_C": celsius(t.outlet_temperature),
        "temperature_rise_K": t.temperature_rise, "effective_viscosity_Pa_s": t.viscosity,
        "supply_viscosity_Pa_s": t.supply_viscosity, "density_kg_m3": t.density,
        "specific_heat_J_kgK": t.specific_heat, "power_loss_W": t.friction_power,
        "convected_power_W": t.convected_power, "conducted_power_W": t.conducted_power,
        "leading_flow_m3s": t.leading_flow, "side_flow_m3s": t.side_flow, "supply_flow_m3s": t.supply_flow,
        "carry_over": oil["carry_over"], "conducted_fraction": oil["conducted_fraction"],
        "effective_fraction": oil["effective_fraction"],
        "isothermal": {"at": "the supply temperature", "eccentricity": t.isothermal_eccentricity,
                       "min_film_m": t.isothermal_min_film, "power_loss_W": t.isothermal_friction_power},
        "moved": {"eccentricity": t.eccentricity - t.isothermal_eccentricity,
                  "min_film": rel(t.min_film, t.isothermal_min_film),
                  "power_loss": rel(t.friction_power, t.isothermal_friction_power)},
        "evaluations": t.evaluations, "residual_K": t.residual, "oil": dict(oil)}


def _thermal_rows(th: dict) -> list:
    rows = [("effective temperature", th["effective_temperature_C"], "degC"),
            ("temperature rise", th["temperature_rise_K"], "K"),
            ("effective viscosity", th["effective_viscosity_Pa_s"] * 1e3, "mPa s"),
            ("min film change from isothermal", th["moved"]["min_film"] * 100, "%")]
    return [list(row) for row in rows]


# -- results ---------------------------------------------------------------------------------

def _film_results(eq, scale, results=None) -> dict:
    """Films, pressures, friction and flows of the pads at the equilibrium (or of the pad ``results``
    given), in SI."""
    results = eq.state.results if results is None else results
    flows = [{k: scale.to_flow(v) for k, v in r.flows.items()} for r in results]
    side = sum(f["side"] for f in flows)
    inlet = sum(f["inlet"] for f in flows)
    # net flow into the film through the grooves and the leading edge of every pad (full bearing:
    # Raimondi-Boyd's Q, the flow into the film at the line of largest film)
    total = sum(f["inlet"] - f["arc_start"] for f in flows)
    torque = scale.to_moment(sum(r.friction for r in results))
    return {"min_film_m": scale.to_thickness(min(r.h_min for r in results)),
            "max_pressure_Pa": scale.to_pressure(max(r.max_pressure for r in results)),
            "friction_torque_Nm": torque, "friction_power_W": torque * scale.speed,
            "side_flow_m3s": side, "total_flow_m3s": total, "inlet_flow_m3s": inlet, "pad_flows_m3s": flows}


def _summary(s: dict, scale, bearing, eq, dc, seconds: dict, fine) -> dict:
    b, op = s["bearing"], s["operating"]
    W, L, D, c = op["load"], b["length"], b["diameter"], b["radial_clearance"]
    N = op["speed"] / 60.0
    film = _film_results(eq, scale)
    dcf = _fixed_frame(dc, eq.force)
    K, C = dcf.to_si(viscosity=op["viscosity"], speed=scale.speed, radius=scale.radius, clearance=c)
    results = {"eccentricity": eq.eps, "attitude_deg": eq.attitude,
               "position_m": [float(v) * c for v in eq.position],
               **film,
               "sommerfeld": op["viscosity"] * N * L * D / W * (scale.radius / c) ** 2,
               "mean_pressure_Pa": W / (L * D), "load_nondim": float(np.hypot(*_load(s, scale))),
               "force_residual": eq.residual}
    if bearing.pads is None:
        results["raimondi_boyd"] = {
            "sommerfeld": results["sommerfeld"], "attitude_deg": eq.attitude,
            "friction_variable": film["friction_torque_Nm"] / (W * c),           # (R/c) f = T/(W c)
            "flow_variable": film["total_flow_m3s"] / (scale.radius * c * N * L),  # Q/(R c N L)
            "side_flow_ratio": film["side_flow_m3s"] / film["total_flow_m3s"],     # Qs/Q
            "max_pressure_ratio": W / (L * D) / film["max_pressure_Pa"]}            # P/p_max
    coefficients = {
        "frame": "ROSS: x horizontal, y up, the journal turning from +x to +y (the bearing frame of the file)",
        "K_N_per_m": K, "C_Ns_per_m": C, "K_c_over_W": dcf.K, "C_c_omega_over_W": dcf.C,
        "load_nondim": dc.load, "method": dc.method}
    ross = dcf.to_ross_kwargs(viscosity=op["viscosity"], speed=scale.speed, radius=scale.radius, clearance=c)
    pictures_frame = math.degrees(eq.state.rotation) % 360.0 if bearing.pads is None else 0.0
    cost = {"nodes": sum(m.n_nodes for m in eq.meshes), "newton_iterations": eq.newton_iterations,
            "active_set_iterations": [r.iterations for r in eq.state.results],
            "seconds": dict(seconds)}
    summary = {"kind": "journal", "title": s["title"], "bearing": _bearing_echo(b), "operating": dict(op),
               "solver": dict(s["solver"]), "scales": _scales(scale),
               "results": results, "coefficients": coefficients, "ross_bearing_element": ross,
               "pictures_phi0_deg": pictures_frame, "cost": cost,
               "error_estimate": None if fine is None else _error_estimate(eq, dcf, film, fine, scale)}
    if fine is not None:
        cost["seconds"]["error_estimate"] = fine[2] + fine[3]
    verdicts = check_limits({"min_film": film["min_film_m"], "max_pressure": film["max_pressure_Pa"],
                             "max_friction_power": film["friction_power_W"], "max_leakage": film["total_flow_m3s"]},
                            s["limits"])
    results["limits"] = verdicts
    results["within_limits"] = all(v["ok"] for v in verdicts.values())
    summary["limits"] = dict(s["limits"])
    summary["table"] = _table(results, K, C, summary["error_estimate"], cost)
    return summary


def _bearing_echo(b: dict) -> dict:
    out = dict(b)
    out["pads"] = None if b["pads"] is None else [list(p) for p in b["pads"]]
    out["grooves"] = [dict(g) for g in b["grooves"]]
    out["length_over_diameter"] = b["length"] / b["diameter"]
    return out


def _scales(scale) -> dict:
    return {"pressure_Pa": scale.pressure, "force_N": scale.force, "flow_m3s": scale.flow,
            "moment_Nm": scale.moment, "length_m": scale.radius, "film_m": scale.clearance,
            "omega_rad_s": scale.speed}


def _error_estimate(eq, dcf, film: dict, fine, scale) -> dict:
    """Change of each result when the element size is halved (the summary keeps the coarser values)."""
    eq_f, dc_f, *_ = fine
    dcf_f = _fixed_frame(dc_f, eq_f.force)
    film_f = _film_results(eq_f, scale)

    def rel(a, b):
        return abs(b - a) / abs(a)
    return {"method": "same equilibrium and coefficients with half the element size; relative changes",
            "nodes": sum(m.n_nodes for m in eq_f.meshes),
            "eccentricity": rel(eq.eps, eq_f.eps), "attitude_deg": abs(eq_f.attitude - eq.attitude),
            "min_film": rel(film["min_film_m"], film_f["min_film_m"]),
            "max_pressure": rel(film["max_pressure_Pa"], film_f["max_pressure_Pa"]),
            "friction_power": rel(film["friction_power_W"], film_f["friction_power_W"]),
            "K": float(np.abs(dcf_f.K - dcf.K).max() / np.abs(dcf.K).max()),
            "C": float(np.abs(dcf_f.C - dcf.C).max() / np.abs(dcf.C).max())}


def _table(r: dict, K, C, err, cost) -> list:
    rows = [("eccentricity ratio", r["eccentricity"], "-"), ("attitude angle", r["attitude_deg"], "deg"),
            ("minimum film", r["min_film_m"] * 1e6, "um"), ("peak pressure", r["max_pressure_Pa"], "Pa"),
            ("Sommerfeld number", r["sommerfeld"], "-"), ("friction torque", r["friction_torque_Nm"], "N m"),
            ("friction power", r["friction_power_W"], "W"), ("side flow", r["side_flow_m3s"] * 6e4, "l/min"),
            ("total flow", r["total_flow_m3s"] * 6e4, "l/min")]
    if r["inlet_flow_m3s"] != 0.0:  # grooves
        rows.append(("groove (supply) flow", r["inlet_flow_m3s"] * 6e4, "l/min"))
    rows += [(f"limit {name}: {v['value']:.4g} {v['relation']} {v['limit']:.4g} {v['unit']}",
              "ok" if v["ok"] else "VIOLATED", "") for name, v in r["limits"].items()]
    rows += [(f"k{a}{b}", float(K[i, j]), "N/m") for i, a in enumerate("xy") for j, b in enumerate("xy")]
    rows += [(f"c{a}{b}", float(C[i, j]), "N s/m") for i, a in enumerate("xy") for j, b in enumerate("xy")]
    if err is not None:
        rows += [("error estimate: eccentricity", err["eccentricity"], "-"), ("error estimate: K", err["K"], "-"),
                 ("error estimate: C", err["C"], "-")]
    rows += [("nodes", cost["nodes"], ""), ("Newton iterations", cost["newton_iterations"], ""),
             ("seconds", sum(cost["seconds"].values()), "s")]
    return [list(row) for row in rows]


# -- files -------------------------------------------------------------------------------------

def pressure_columns(eq, scale) -> dict[str, np.ndarray]:
    """Every mesh node of every pad, headed ``"name [unit]"``: ``pad``, ``phi [deg]`` (bearing frame,
    [0, 360)), ``z [m]`` (from the mid-plane), ``pressure [Pa]``, ``film [m]`` and ``ruptured [-]`` (1
    where the film has ruptured)."""
    cols = {k: [] for k in ("pad", "phi_deg", "z_m", "pressure_Pa", "film_m", "ruptured")}
    for k, res in enumerate(eq.state.results):
        nv = int(res.basis.mesh.nvertices)
        phi, z = np.asarray(res.basis.mesh.p[:, :nv], float)
        cav = np.zeros(nv) if res.cavitated is None else np.asarray(res.cavitated, float)[:nv]
        cols["pad"].append(np.full(nv, k + 1.0))
        cols["phi_deg"].append(np.degrees(phi + eq.state.rotation) % 360.0)
        cols["z_m"].append(z * scale.radius)
        cols["pressure_Pa"].append(scale.to_pressure(np.asarray(res.pressure, float)[:nv]))
        cols["film_m"].append(scale.to_thickness(np.asarray(res.film.thickness(phi, z), float)))
        cols["ruptured"].append(cav)
    headers = {"pad": "pad [-]", "phi_deg": "phi [deg]", "z_m": "z [m]", "pressure_Pa": "pressure [Pa]",
               "film_m": "film [m]", "ruptured": "ruptured [-]"}
    return {headers[k]: np.concatenate(v) for k, v in cols.items()}


def _tables(names, s: dict, scale, eq, summary: dict, out_dir: Path) -> list[str]:
    from ..io.writers import write_csv

    files = []
    if "pressure" in names:
        cols = pressure_columns(eq, scale)
        files.append(write_csv(cols, out_dir / "pressure_field.csv", fields=list(cols)).name)
    if "coefficients" in names:
        ross = summary["ross_bearing_element"]
        units = {"frequency": "rad/s", **{f"k{a}{b}": "N/m" for a in "xy" for b in "xy"},
                 **{f"c{a}{b}": "N s/m" for a in "xy" for b in "xy"}}
        cols = {f"{k} [{u}]": np.asarray(ross[k], float) for k, u in units.items()}
        files.append(write_csv(cols, out_dir / "coefficients.csv", fields=list(cols)).name)
    return files


def _pictures(out: dict, bearing, eq, scale, out_dir: Path, tick: Callable, title: str = "") -> list[str]:
    from ..plot import fields, maps

    p_mpa = dict(scale=scale.to_pressure(1.0) / 1e6, unit="MPa")
    h_um = dict(scale=scale.to_thickness(1.0) * 1e6, unit="um")
    surfaces = bearing.surfaces()
    offset = float(np.degrees(eq.state.rotation))
    files, k = [], 0
    for j, (res, surface) in enumerate(zip(eq.state.results, surfaces)):
        suffix = f"_pad{j + 1}" if len(surfaces) > 1 else ""
        where = f"pad {j + 1}: " if len(surfaces) > 1 else ""
        heading = (f"{where}eccentricity {eq.eps:.3f}, attitude {eq.attitude:.1f} deg, "
                   f"p_max = {scale.to_pressure(res.max_pressure) / 1e6:.3g} MPa, "
                   f"h_min = {scale.to_thickness(res.h_min) * 1e6:.3g} um")

        def field_map(kind, file, unit):
            panel = maps.Panel(res, kind, *unit.values(), radius=scale.radius, title=heading, surface=surface,
                               offset_deg=offset, true_aspect=False)
            maps.field_panels([[panel]], out_dir / file, title=title, panel_size=(10.0, 3.6))
            return out_dir / file

        draw = {"pressure": lambda: field_map("pressure", f"pressure{suffix}.png", p_mpa),
                "wrapped": lambda: fields.pressure_picture(res, out_dir / f"pressure_wrapped{suffix}.png",
                                                           view="wrapped", warp=out["warp"], surface=surface,
                                                           title=heading, **p_mpa),
                "film": lambda: field_map("film", f"film{suffix}.png", h_um)}
        for name in out["pictures"]:
            tick(k, f"picture: {name}{suffix}")
            files.append(draw[name]().name)
            k += 1
    return files
