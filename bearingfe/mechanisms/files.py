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
                              pair, points, positive_number, read_table, read_toml, text, texts)
from .sections import ibeam

__all__ = ["LOADERS", "SHAPES", "SPECS", "SURFACE", "load_mechanism", "field", "drive_from", "material_from",
           "read_surface", "surface_from", "surface_of"]


# -- shared tables ------------------------------------------------------------------------

#: Pocket shapes of ``[[surface.inlets]]``: ``shape = name`` -> (constructor, fields).
SHAPES: Mapping[str, tuple[Callable, Mapping[str, tuple]]] = MappingProxyType({
    "circle": (Circle, {"center": (pair, REQUIRED), "radius": (positive_number, REQUIRED)}),
    "ellipse": (Ellipse, {"center": (pair, REQUIRED), "semi_axes": (pair, REQUIRED), "angle": (number(), 0.0)}),
    "rectangle": (Rectangle, {"center": (pair, REQUIRED), "size": (pair, REQUIRED), "angle": (number(), 0.0)}),
    "polygon": (Polygon, {"points": (points, REQUIRED)}),
    "slot": (Slot, {"center": (pair, REQUIRED), "length": (positive_number, REQUIRED),
                    "width": (positive_number, REQUIRED), "angle": (number(), 0.0)}),
})

#: The ``[surface]`` table: ``arc = [a1, a2]`` [rad], ``half_width`` [-], ``[[surface.inlets]]``.
SURFACE = {"arc": (pair, (-0.5, 0.5)), "half_width": (positive_number, 0.5),
           "inlets": Tables(key="shape", variants={name: spec for name, (_, spec) in SHAPES.items()})}

DRIVE = Table({"speed_rpm": (number(), None), "omega": (number(), None)}, required=True)
MATERIAL = Table({"name": (text, None), "youngs_modulus": (number(), REQUIRED), "density": (number(), 0.0),
                  "poisson_ratio": (number(), 0.3)}, required=True)
#: An optional material of a film surface (``[shoe.material]``, ``[eccentric.material]``): steel if absent.
SURFACE_MATERIAL = Table({"name": (text, None), "youngs_modulus": (number(), 210e9), "density": (number(), 7850.0),
                          "poisson_ratio": (number(), 0.3)})


#: How the plunger holds the shoe body (``[shoe.seat]``, see :class:`bearingfe.elastic.shoe.ShoeBody`).
SHOE_SEAT = Table({"kind": (choice(SHOE_SEATS), "clamped"), "radius": (number(), None)})
#: A bearing lining on the shoe's bore (``[shoe.lining]``): its thickness [m] and material.
SHOE_LINING = Table({"thickness": (number(), None), "name": (text, None), "youngs_modulus": (number(), None),
                     "density": (number(), 0.0), "poisson_ratio": (number(), 0.3)})


#: How the shoe pocket is fed from the chamber (``[shoe.supply]``): ``"pressure"`` (the chamber pressure,
#: the default) or a restrictor in the plunger (:class:`bearingfe.bearings.hydrostatic.Restrictor`).
SHOE_SUPPLY = Table({"kind": (choice(lambda: ("pressure", *_restrictor().FIELDS)), "pressure"), "diameter": (number(), None),
                     "length": (number(), None), "discharge_coefficient": (number(), None),
                     "density": (number(), None), "pocket_volume": (number(), None),
                     "bulk_modulus": (number(), None)})


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
    spec = {k: ((v[0], REQUIRED) if k in required else v) for k, v in SURFACE.items()}
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


def _file(tables: dict) -> dict:
    return {"kind": (choice(_kinds), REQUIRED), "name": (text, REQUIRED), **tables}


SPECS: Mapping[str, dict] = MappingProxyType({
    "crank_slider": _file({
        "drive": DRIVE,
        "crank": Table({"crank": (number(), REQUIRED), "rod": (number(), REQUIRED),
                        "rod_cg_from_crank_pin": (number(), None)}, required=True),
        "masses": Table({"crank": (number(), 0.0), "crank_cg_radius": (number(), 0.0), "slider": (number(), 0.0),
                         "rod": (number(), 0.0), "rod_inertia": (number(), None)}),
        "pump": Table({"cylinders": (integer(), 1), "plunger_diameter": (number(), 0.0),
                       "cylinder_spacing": (number(), 0.0), "pressure": (number(), 0.0)})}),
    "rotor_frame": _file({
        "rotor": Table({"name": (text, "rotor"), "mass": (number(), REQUIRED), "shaft_length": (number(), REQUIRED),
                        "shaft_diameter": (number(), REQUIRED), "eccentricity": (number(), REQUIRED),
                        "material": MATERIAL}, required=True),
        "frame": Table({"plate_mass": (number(), REQUIRED), "section": (text, REQUIRED), "height": (number(), REQUIRED),
                        "columns": (integer(), 1), "axis": (text, "x"), "sections": (texts, ()),
                        "height_range": (numbers(2, "[lo, hi] in m"), (0.1, 2.0)), "material": MATERIAL},
                       required=True)}),
    "linkage": _file({
        "drive": DRIVE,
        "linkage": Table({"crank": (number(), REQUIRED), "rod": (number(), REQUIRED),
                          "pin_diameters": (numbers(3, "3 numbers (joints O, A, B)"), REQUIRED),
                          "pin_friction": (numbers(3, "3 numbers (joints O, A, B)"), REQUIRED),
                          "guide_friction": (number(), REQUIRED)}, required=True),
        "load": Table({"force": (number(), 0.0), "idle_zone_deg": (number(), 30.0)})}),
    "eccentric_pump": _file({
        "drive": DRIVE,
        "eccentric": Table({"eccentricity": (number(), REQUIRED), "pivot_distance": (number(), REQUIRED),
                            "radius": (number(), REQUIRED), "material": SURFACE_MATERIAL}, required=True),
        "shoe": Table({"clearance": (number(), REQUIRED), "viscosity": (number(), REQUIRED),
                       "thickness": (number(), None), "back": (choice(SHOE_BACKS), "flat"),
                       "material": SURFACE_MATERIAL, "seat": SHOE_SEAT, "lining": SHOE_LINING,
                       "supply": SHOE_SUPPLY}, required=True),
        "plunger": Table({"diameter": (number(), REQUIRED), "preload": (number(), 0.0)}, required=True),
        "cycle": Table({"discharge": (number(), REQUIRED), "suction": (number(), REQUIRED),
                        "compression_deg": (number(), 20.0), "decompression_deg": (number(), 20.0)},
                       required=True),
        "surface": Table({k: ((v[0], REQUIRED) if k in ("arc", "half_width") else v) for k, v in SURFACE.items()},
                         required=True)}),
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
    cycle = build(label, "cycle", PressureCycle, discharge=cy["discharge"], suction=cy["suction"],
                  compression=math.radians(cy["compression_deg"]),
                  decompression=math.radians(cy["decompression_deg"]))
    return build(label, "eccentric", EccentricPump, name=d["name"], eccentricity=e["eccentricity"],
                 pivot_distance=e["pivot_distance"], radius=e["radius"], clearance=sh["clearance"],
                 viscosity=sh["viscosity"], plunger_diameter=pl["diameter"], preload=pl["preload"],
                 drive=drive_of(d["drive"], label), cycle=cycle, surface=surface_of(d["surface"], label),
                 shoe_material=material_of(sh["material"], "shoe.material", label), shoe_thickness=sh["thickness"],
                 shoe_body=shoe_body_of(sh, label), shoe_supply=shoe_supply_of(sh["supply"], label),
                 eccentric_material=material_of(e["material"], "eccentric.material", label))


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
