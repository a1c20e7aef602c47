"""Read mechanism descriptions (TOML) into the parameter objects of :mod:`bearingfe.mechanisms.machines`.

Each file has a top-level ``kind = "..."``; :data:`LOADERS` maps the kind to
a plain function ``(dict, file label) -> frozen parameter object``. To add a
kind, add one entry. Each kind's tables are checked against its spec in
:data:`SPECS` (:mod:`bearingfe.core.schema`: unknown names are errors), then the
parameter objects check their values. Every error is a
:class:`~bearingfe.core.schema.SchemaError` (a ``ValueError``) naming the file, the
table and the field, e.g. ``snt32.toml: [crank] rod: missing (required)``.

The ``[surface]`` table (outline and ``[[surface.inlets]]`` pockets, see
:data:`SHAPES`) is the same in mechanism and scene files:
:func:`read_surface`.
"""

from __future__ import annotations

import math
import warnings
from types import MappingProxyType
from typing import Any, Callable, Mapping

from ..geometry.surface import Circle, Ellipse, Polygon, Rectangle, Slot, Surface
from ..core.machine import Drive, Material
from ..elastic.shoe import SHOE_BACKS, SHOE_SEATS, ShoeBody
from .machines import CrankMechanism, CrankSlider, Linkage, MillDrive, Rotor, RotorFrame
from ..core.schema import (REQUIRED, SchemaError, Table, Tables, anything, build, choice, integer, number, numbers,
                              pair, points, positive_number, read_table, read_toml, required_field, text, texts)
from .sections import ibeam

__all__ = ["LOADERS", "SHAPES", "SPECS", "SURFACE", "load_mechanism", "mechanism_oil", "oil_given", "field", "drive_from", "material_from",
           "read_surface", "surface_from", "surface_of"]


# -- shared tables ------------------------------------------------------------------------

#: Pocket shapes of ``[[surface.inlets]]``: ``shape = name`` -> (constructor, fields).
SHAPES: Mapping[str, tuple[Callable, Mapping[str, tuple]]] = MappingProxyType({
    "circle": (Circle, {"center": (pair, REQUIRED, "centre (phi [rad], z [R0])"),
                        "radius": (positive_number, REQUIRED, "radius [R0]")}),
    "ellipse": (Ellipse, {"center": (pair, REQUIRED, "centre (phi [rad], z [R0])"),
                          "semi_axes": (pair, REQUIRED, "semi-axes along phi and z before the turn [R0]"),
                          "angle": (number(), 0.0, "turn of the axes from phi towards z [rad]")}),
    "rectangle": (Rectangle, {"center": (pair, REQUIRED, "centre (phi [rad], z [R0])"),
                              "size": (pair, REQUIRED, "side lengths along phi and z before the turn [R0]"),
                              "angle": (number(), 0.0, "turn from phi towards z [rad]")}),
    "polygon": (Polygon, {"points": (points, REQUIRED, "corners (phi [rad], z [R0]) in order")}),
    "slot": (Slot, {"center": (pair, REQUIRED, "centre (phi [rad], z [R0])"),
                    "length": (positive_number, REQUIRED, "length over the rounded ends [R0]"),
                    "width": (positive_number, REQUIRED, "width, the diameter of the rounded ends [R0]"),
                    "angle": (number(), 0.0, "turn of the length from phi towards z [rad]")}),
})

#: The ``[surface]`` table: ``arc = [a1, a2]`` [rad], ``half_width`` [-], ``[[surface.inlets]]``.
SURFACE = {"arc": (pair, (-0.5, 0.5), "angular extent [alpha1, alpha2] of the support surface [rad]"),
           "half_width": (positive_number, 0.5, "half width a = b / (2 R0) of the surface [-]"),
           "inlets": Tables(key="shape", variants={name: spec for name, (_, spec) in SHAPES.items()},
                            key_meaning="shape of one high-pressure inlet pocket")}

DRIVE = Table({"speed_rpm": (number(), None, "shaft speed [rpm] (give this or omega)"),
               "omega": (number(), None, "shaft angular speed [rad/s] (give this or speed_rpm)")}, required=True)
MATERIAL = Table({"name": (text, None, "material name"),
                  "youngs_modulus": (number(), REQUIRED, "Young's modulus E [Pa]"),
                  "density": (number(), 0.0, "density [kg/m^3]"),
                  "poisson_ratio": (number(), 0.3, "Poisson's ratio [-]")}, required=True)
#: An optional material of a film surface (``[shoe.material]``, ``[eccentric.material]``): steel if absent.
SURFACE_MATERIAL = Table({"name": (text, None, "material name"),
                          "youngs_modulus": (number(), 210e9, "Young's modulus E [Pa]"),
                          "density": (number(), 7850.0, "density [kg/m^3]"),
                          "poisson_ratio": (number(), 0.3, "Poisson's ratio [-]")})


#: How the plunger holds the shoe body (``[shoe.seat]``, see :class:`bearingfe.elastic.shoe.ShoeBody`).
SHOE_SEAT = Table({"kind": (choice(SHOE_SEATS), "clamped", "how the plunger holds the shoe's seat"),
                   "radius": (number(), None, "radius of the seat disc on the back [m]")})
#: A bearing lining on the shoe's bore (``[shoe.lining]``): its thickness [m] and material.
SHOE_LINING = Table({"thickness": (number(), None, "thickness of the bearing lining on the bore [m]"),
                     "name": (text, None, "lining material name"),
                     "youngs_modulus": (number(), None, "lining Young's modulus [Pa]"),
                     "density": (number(), 0.0, "lining density [kg/m^3]"),
                     "poisson_ratio": (number(), 0.3, "lining Poisson's ratio [-]")})


#: How the shoe pocket is fed from the chamber (``[shoe.supply]``): ``"pressure"`` (the chamber pressure,
#: the default) or a restrictor in the plunger (:class:`bearingfe.bearings.hydrostatic.Restrictor`).
SHOE_SUPPLY = Table({
    "kind": (choice(lambda: ("pressure", *_restrictor().FIELDS)), "pressure",
             "the chamber pressure in the pocket, or a restrictor in the plunger"),
    "diameter": (number(), None, "restrictor bore diameter [m]"),
    "length": (number(), None, "capillary length [m]"),
    "discharge_coefficient": (number(), None, "orifice discharge coefficient Cd [-]"),
    "density": (number(), None, "oil density for the orifice law [kg/m^3]"),
    "pocket_volume": (number(), None, "oil volume of the pocket and its feed [m^3] (its compressibility)"),
    "bulk_modulus": (number(), None, "oil bulk modulus K [Pa]")})


def _restrictor():
    from ..bearings.hydrostatic import Restrictor  # the bearings import the solver: read when a file is

    return Restrictor


def shoe_supply_of(t: dict, label: str):
    """The restrictor of a ``[shoe.supply]`` table read against :data:`SHOE_SUPPLY` (None: the chamber pressure)."""
    given = {k: v for k, v in t.items() if k != "kind" and v is not None}
    if t["kind"] == "pressure":
        if given:
            raise SchemaError(f"{label}: [shoe.supply] {next(iter(given))}: not taken by kind = 'pressure' "
                              f"(the pocket at the chamber pressure); give kind = 'capillary' or 'orifice'")
        return None
    if "diameter" not in given:
        raise SchemaError(f"{label}: [shoe.supply] diameter: missing (required by kind = {t['kind']!r})")
    return build(label, "shoe.supply", _restrictor(), kind=t["kind"], **given)


def shoe_body_of(sh: dict, label: str) -> ShoeBody | None:
    """The shoe body of a ``[shoe]`` table (``thickness``, ``back``, ``[shoe.seat]``, ``[shoe.lining]``)."""
    seat, lining = sh["seat"], sh["lining"]
    if sh["thickness"] is None:
        given = [n for n, v in (("back", sh["back"] != "flat"), ("seat", seat["kind"] != "clamped"
                                or seat["radius"] is not None), ("lining", lining["thickness"] is not None)) if v]
        if given:
            raise SchemaError(f"{label}: [shoe] thickness: missing (the shoe body's depth [m], needed by "
                              f"[shoe] {given[0]})")
        return None
    material = None
    if lining["thickness"] is not None:
        if lining["youngs_modulus"] is None:
            raise SchemaError(f"{label}: [shoe.lining] youngs_modulus: missing (required with a lining thickness)")
        material = build(label, "shoe.lining", Material, name="lining" if lining["name"] is None else lining["name"],
                         youngs_modulus=lining["youngs_modulus"], density=lining["density"],
                         poisson_ratio=lining["poisson_ratio"])
    return build(label, "shoe", ShoeBody, thickness=sh["thickness"], back=sh["back"], seat=seat["kind"],
                 seat_radius=seat["radius"], lining=material,
                 lining_thickness=0.0 if lining["thickness"] is None else lining["thickness"])


def read_surface(table: Any, label: str, *, required: tuple[str, ...] = ()) -> Surface:
    """A :class:`~bearingfe.Surface` from a ``[surface]`` table (:data:`SURFACE`).

    ``required`` names fields that have no default (a machine's shoe gives
    its ``arc`` and ``half_width``).
    """
    spec = {k: (required_field(v) if k in required else v) for k, v in SURFACE.items()}
    return surface_of(read_table(table, label, "surface", spec), label)


def surface_of(t: dict, label: str) -> Surface:
    """The surface of a ``[surface]`` table already read against :data:`SURFACE`."""
    inlets = tuple(build(label, f"surface.inlets.{k}", SHAPES[item["shape"]][0],
                         **{n: v for n, v in item.items() if n != "shape"})
                   for k, item in enumerate(t["inlets"]))
    return build(label, "surface", Surface, arc=t["arc"], half_width=t["half_width"], inlets=inlets)


def drive_of(t: dict, label: str) -> Drive:
    """The drive of a ``[drive]`` table read against ``DRIVE``: exactly one of ``speed_rpm``, ``omega``."""
    if (t["speed_rpm"] is None) == (t["omega"] is None):
        raise SchemaError(f"{label}: [drive] speed_rpm/omega: give exactly one")
    if t["speed_rpm"] is not None:
        return build(label, "drive", Drive.from_rpm, rpm=t["speed_rpm"])
    return build(label, "drive", Drive, omega=t["omega"])


def material_of(t: dict, section: str, label: str) -> Material:
    """The material of a table read against ``MATERIAL`` (``name`` defaults to the table's name)."""
    return build(label, section, Material, name=section if t["name"] is None else t["name"],
                 youngs_modulus=t["youngs_modulus"], density=t["density"], poisson_ratio=t["poisson_ratio"])


# -- the kinds --------------------------------------------------------------------------

def _kinds() -> tuple[str, ...]:
    return tuple(LOADERS)


def _oil_fields() -> dict:
    """The ``[oil]`` table of a machine with an oil film: the fields of the scenes' ``[oil]``
    (:data:`bearingfe.thermal.files.OIL`)."""
    from ..thermal.files import OIL

    return dict(OIL)


def _file(tables: dict) -> dict:
    return {"kind": (choice(_kinds), REQUIRED, "the kind of machine"), "name": (text, REQUIRED, "the machine's name"),
            **tables}


SPECS: Mapping[str, dict] = MappingProxyType({
    "crank_slider": _file({
        "drive": DRIVE,
        "crank": Table({"crank": (number(), REQUIRED, "crank radius l1 [m]"),
                        "rod": (number(), REQUIRED, "connecting-rod length l2 [m]"),
                        "rod_cg_from_crank_pin": (number(), None, "rod centre of mass from the crank pin [m]")},
                       required=True),
        "masses": Table({"crank": (number(), 0.0, "crank mass [kg]"),
                         "crank_cg_radius": (number(), 0.0, "radius of the crank's centre of mass [m]"),
                         "slider": (number(), 0.0, "slider (crosshead, plunger) mass [kg]"),
                         "rod": (number(), 0.0, "connecting-rod mass [kg]"),
                         "rod_inertia": (number(), None, "rod moment of inertia about its centre of mass [kg m^2]")}),
        "pump": Table({"cylinders": (integer(), 1, "number of cylinders"),
                       "plunger_diameter": (number(), 0.0, "plunger diameter [m]"),
                       "cylinder_spacing": (number(), 0.0, "axial spacing of the cylinders [m]"),
                       "pressure": (number(), 0.0, "discharge pressure [Pa]")})}),
    "rotor_frame": _file({
        "rotor": Table({"name": (text, "rotor", "rotor name"), "mass": (number(), REQUIRED, "rotor mass [kg]"),
                        "shaft_length": (number(), REQUIRED, "shaft length between supports [m]"),
                        "shaft_diameter": (number(), REQUIRED, "shaft diameter [m]"),
                        "eccentricity": (number(), REQUIRED, "mass eccentricity (unbalance) [m]"),
                        "material": MATERIAL}, required=True),
        "frame": Table({"plate_mass": (number(), REQUIRED, "mass of the frame plate [kg]"),
                        "section": (text, REQUIRED, "I-beam of the columns (GOST 8239 designation, e.g. '20a')"),
                        "height": (number(), REQUIRED, "column height [m]"),
                        "columns": (integer(), 1, "number of columns"),
                        "axis": (text, "x", "bending axis of the section ('x' strong, 'y' weak)"),
                        "sections": (texts, (), "sections to compare in the column-height study"),
                        "height_range": (numbers(2, "[lo, hi] in m"), (0.1, 2.0),
                                         "column heights searched [m]"),
                        "material": MATERIAL},
                       required=True)}),
    "linkage": _file({
        "drive": DRIVE,
        "linkage": Table({"crank": (number(), REQUIRED, "crank radius l1 [m]"),
                          "rod": (number(), REQUIRED, "connecting-rod length l2 [m]"),
                          "pin_diameters": (numbers(3, "3 numbers (joints O, A, B)"), REQUIRED,
                                            "journal diameters of the main bearing, crank pin and wrist pin [m]"),
                          "pin_friction": (numbers(3, "3 numbers (joints O, A, B)"), REQUIRED,
                                           "friction coefficients of those joints [-]"),
                          "guide_friction": (number(), REQUIRED, "friction coefficient of the slider guide [-]")},
                         required=True),
        "load": Table({"force": (number(), 0.0, "working force on the slider [N]"),
                       "idle_zone_deg": (number(), 30.0, "crank angle without load at each dead centre [deg]")})}),
    "eccentric_pump": _file({
        "drive": DRIVE,
        "eccentric": Table({"eccentricity": (number(), REQUIRED, "eccentricity E = |O1 O2|, half the stroke [m]"),
                            "pivot_distance": (number(), REQUIRED, "distance E2 = |O1 B| from the shaft to the plunger pivot [m]"),
                            "radius": (number(), REQUIRED, "eccentric radius R0 [m]"),
                            "material": SURFACE_MATERIAL}, required=True),
        "shoe": Table({"clearance": (number(), REQUIRED, "radial clearance c of the shoe bore [m]"),
                       "viscosity": (number(), None, "oil dynamic viscosity [Pa s] (or an [oil] table)"),
                       "thickness": (number(), None, "depth of the shoe body from the film to its back [m]"),
                       "back": (choice(SHOE_BACKS), "flat", "shape of the shoe's back"),
                       "material": SURFACE_MATERIAL, "seat": SHOE_SEAT, "lining": SHOE_LINING,
                       "supply": SHOE_SUPPLY}, required=True),
        "plunger": Table({"diameter": (number(), REQUIRED, "plunger diameter [m]"),
                          "preload": (number(), 0.0, "constant force pressing the shoe onto the eccentric (spring, retaining ring) [N]")},
                         required=True),
        "cycle": Table({"discharge": (number(), REQUIRED, "chamber pressure during discharge [Pa]"),
                        "suction": (number(), REQUIRED, "chamber pressure during suction [Pa]"),
                        "compression_deg": (number(), 20.0, "shaft angle of the rise to discharge pressure [deg]"),
                        "decompression_deg": (number(), 20.0, "shaft angle of the fall to suction pressure [deg]")},
                       required=True),
        "surface": Table({k: (required_field(v) if k in ("arc", "half_width") else v) for k, v in SURFACE.items()},
                         required=True),
        "oil": Table(_oil_fields())}),
})
"""Each kind's file: ``{name: (check, default) | Table}`` (see :mod:`bearingfe.core.schema`)."""


def _crank_slider(d: dict, label: str) -> CrankMechanism:
    c, m, p = d["crank"], d["masses"], d["pump"]
    linkage = build(label, "crank", CrankSlider, crank=c["crank"], rod=c["rod"],
                    rod_cg_from_crank_pin=c["rod_cg_from_crank_pin"], rod_mass=m["rod"],
                    rod_inertia=m["rod_inertia"], slider_mass=m["slider"], crank_mass=m["crank"],
                    crank_cg_radius=m["crank_cg_radius"])
    return build(label, "pump", CrankMechanism, name=d["name"], drive=drive_of(d["drive"], label), linkage=linkage,
                 cylinders=p["cylinders"], plunger_diameter=p["plunger_diameter"],
                 cylinder_spacing=p["cylinder_spacing"], pressure=p["pressure"])


def _rotor_frame(d: dict, label: str) -> RotorFrame:
    r, fr = d["rotor"], d["frame"]
    rotor = build(label, "rotor", Rotor, name=r["name"], mass=r["mass"], shaft_length=r["shaft_length"],
                  shaft_diameter=r["shaft_diameter"], eccentricity=r["eccentricity"],
                  material=material_of(r["material"], "rotor.material", label))
    return build(label, "frame", RotorFrame, name=d["name"], rotor=rotor, plate_mass=fr["plate_mass"],
                 column_material=material_of(fr["material"], "frame.material", label),
                 section=_section(fr["section"], "section", label), height=fr["height"], columns=fr["columns"],
                 axis=fr["axis"], sections=tuple(_section(n, "sections", label) for n in fr["sections"]),
                 height_range=fr["height_range"])


def _section(name: str, key: str, label: str):
    return build(label, "frame", lambda: _named(key, ibeam, name))


def _named(key: str, factory: Callable, *args):
    """``factory(*args)`` with its ``ValueError`` prefixed by the field name."""
    try:
        return factory(*args)
    except ValueError as exc:
        raise ValueError(f"{key}: {exc}") from None


def _linkage(d: dict, label: str) -> MillDrive:
    t, ld = d["linkage"], d["load"]
    linkage = build(label, "linkage", Linkage, crank=t["crank"], rod=t["rod"], pin_diameters=t["pin_diameters"],
                    pin_friction=t["pin_friction"], guide_friction=t["guide_friction"])
    return build(label, "load", MillDrive, name=d["name"], drive=drive_of(d["drive"], label), linkage=linkage,
                 load=ld["force"], idle_zone=math.radians(ld["idle_zone_deg"]))


def _eccentric_pump(d: dict, label: str):
    from ..bearings.pump import EccentricPump, PressureCycle

    e, sh, pl, cy = (d[n] for n in ("eccentric", "shoe", "plunger", "cycle"))
    viscosity = _shoe_viscosity(sh["viscosity"], d["oil"], label)
    cycle = build(label, "cycle", PressureCycle, discharge=cy["discharge"], suction=cy["suction"],
                  compression=math.radians(cy["compression_deg"]),
                  decompression=math.radians(cy["decompression_deg"]))
    return build(label, "eccentric", EccentricPump, name=d["name"], eccentricity=e["eccentricity"],
                 pivot_distance=e["pivot_distance"], radius=e["radius"], clearance=sh["clearance"],
                 viscosity=viscosity, plunger_diameter=pl["diameter"], preload=pl["preload"],
                 drive=drive_of(d["drive"], label), cycle=cycle, surface=surface_of(d["surface"], label),
                 shoe_material=material_of(sh["material"], "shoe.material", label), shoe_thickness=sh["thickness"],
                 shoe_body=shoe_body_of(sh, label), shoe_supply=shoe_supply_of(sh["supply"], label),
                 eccentric_material=material_of(e["material"], "eccentric.material", label))


def oil_given(oil: dict) -> bool:
    """True if a read ``[oil]`` table names a lubricant (an absent table reads as its defaults)."""
    return any(oil[k] is not None for k in ("grade", "kinematic_viscosity", "vogel"))


def _shoe_viscosity(viscosity: float | None, oil: dict, label: str) -> float:
    """``[shoe] viscosity``, or the ``[oil]`` table's viscosity at its supply temperature (one of the two)."""
    from ..thermal.files import check_oil, lubricant_of
    from ..thermal.lubricant import kelvin

    if not oil_given(oil):
        given = [k for k, v in oil.items() if v is not None and v != _oil_fields()[k][1]]
        if given:
            raise SchemaError(f"{label}: [oil] {given[0]}: the table names no lubricant (give grade with "
                              f"kinematic_viscosity_100C, kinematic_viscosity or vogel)")
        if viscosity is None:
            raise SchemaError(f"{label}: [shoe] viscosity: missing (required without an [oil] table)")
        return viscosity
    if viscosity is not None:
        raise SchemaError(f"{label}: [shoe] viscosity: must be absent with an [oil] table (the oil's viscosity at "
                          f"its supply temperature is the film's)")
    check_oil(oil, label, "oil")
    lubricant = lubricant_of(oil, label, "oil")
    return build(label, "oil", lubricant.viscosity, kelvin(oil["supply_temperature_C"]))


def mechanism_oil(path) -> dict | None:
    """The checked ``[oil]`` table of a mechanism file (the fields of :data:`bearingfe.thermal.files.OIL`),
    or None if the file has none.

    Raises
    ------
    SchemaError
        As :func:`load_mechanism`.
    """
    data, label = read_toml(path, "mechanism file")
    if "oil" not in data:
        return None
    kind = read_table({"kind": data["kind"]} if "kind" in data else {}, label, "",
                      {"kind": (choice(_kinds), REQUIRED)})["kind"]
    if "oil" not in SPECS[kind]:
        raise SchemaError(f"{label}: [oil]: not a table of kind {kind!r}")
    oil = read_table(data, label, "", SPECS[kind])["oil"]
    if not oil_given(oil):
        raise SchemaError(f"{label}: [oil]: the table names no lubricant (give grade with kinematic_viscosity_100C, "
                          f"kinematic_viscosity or vogel)")
    from ..thermal.files import check_oil

    check_oil(oil, label, "oil")
    return oil


LOADERS: dict = {
    "crank_slider": _crank_slider,
    "rotor_frame": _rotor_frame,
    "linkage": _linkage,
    "eccentric_pump": _eccentric_pump,
}


# -- the readers of single tables (kept for callers of the first version) --------------------

def field(table: dict, section: str, name: str, label: str, kind: type = float, default: Any = ...):
    """Deprecated: one field of a table; use a spec and :func:`bearingfe.core.schema.read_table`."""
    warnings.warn("bearingfe.mechanisms.files.field is deprecated; describe the table with a spec and read it "
                  "with bearingfe.core.schema.read_table", DeprecationWarning, stacklevel=2)
    check = {float: number(), int: integer(), str: text}.get(kind, anything)
    return read_table({name: table[name]} if name in table else {}, label, section,
                      {name: (check, REQUIRED if default is ... else default)})[name]


def drive_from(data: dict, label: str) -> Drive:
    """``[drive]`` of a file with exactly one of ``speed_rpm`` or ``omega`` (rad/s)."""
    return drive_of(read_table(data, label, "", {"drive": DRIVE})["drive"], label)


def material_from(t: dict, section: str, label: str) -> Material:
    """A material table: ``name``, ``youngs_modulus`` [Pa], optional ``density``."""
    return material_of(read_table(t, label, section, MATERIAL.spec), section, label)


def surface_from(data: dict, label: str) -> Surface:
    """``[surface]`` of a file, with ``arc`` and ``half_width`` required (a machine's shoe)."""
    if "surface" not in data:
        raise SchemaError(f"{label}: [surface]: missing table (required)")
    return read_surface(data["surface"], label, required=("arc", "half_width"))


def load_mechanism(path) -> Any:
    """Read a mechanism TOML file into its frozen parameter object.

    Parameters
    ----------
    path : str or Path
        A file such as ``mechanisms/snt32.toml``.

    Returns
    -------
    object
        :class:`~bearingfe.mechanisms.machines.CrankMechanism`,
        :class:`~bearingfe.mechanisms.machines.RotorFrame` or
        :class:`~bearingfe.mechanisms.machines.MillDrive` or
        :class:`~bearingfe.bearings.pump.EccentricPump`, by the file's ``kind``.

    Raises
    ------
    SchemaError
        (a ``ValueError``) Missing file, unreadable TOML, unknown ``kind``,
        unknown, missing or mistyped field, or a value out of range; the
        message names the file, the table and the field.
    """
    data, label = read_toml(path, "mechanism file")
    kind = read_table({"kind": data["kind"]} if "kind" in data else {}, label, "",
                      {"kind": (choice(_kinds), REQUIRED)})["kind"]
    return LOADERS[kind](read_table(data, label, "", SPECS[kind]), label)
