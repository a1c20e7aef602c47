"""Read mechanism descriptions (TOML) into the parameter objects of :mod:`bearingfe.machines`.

Each file has a top-level ``kind = "..."``; :data:`LOADERS` maps the kind to
a plain function ``(dict, file label) -> frozen parameter object``. To add a
kind, add one entry. All schema errors are ``ValueError`` naming the file and
the field, e.g. ``snt32.toml: [crank] rod: missing``.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path
from typing import Any, Callable

from bearingfe.machines import (
    CrankMechanism,
    CrankSlider,
    Drive,
    Linkage,
    Material,
    MillDrive,
    Rotor,
    RotorFrame,
)
from bearingfe.sections import ibeam

__all__ = ["LOADERS", "load_mechanism", "field", "drive_from", "material_from", "surface_from"]


def field(table: dict, section: str, name: str, label: str, kind: type = float, default: Any = ...):
    """Value ``table[name]`` checked for type; errors name ``label: [section] name``.

    ``kind`` float accepts TOML integers too. ``default`` (if given) is used
    when the field is absent.
    """
    where = f"{label}: [{section}] {name}" if section else f"{label}: {name}"
    if name not in table:
        if default is ...:
            raise ValueError(f"{where}: missing")
        return default
    value = table[name]
    if kind is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ValueError(f"{where}: expected a number, got {value!r}")
        return float(value)
    if kind is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise ValueError(f"{where}: expected an integer, got {value!r}")
        return value
    if not isinstance(value, kind):
        raise ValueError(f"{where}: expected {kind.__name__}, got {value!r}")
    return value


def _table(data: dict, name: str, label: str) -> dict:
    value = data.get(name)
    if value is None:
        raise ValueError(f"{label}: [{name}]: missing table")
    if not isinstance(value, dict):
        raise ValueError(f"{label}: [{name}]: expected a table, got {value!r}")
    return value


def _build(label: str, where: str, factory: Callable, **kwargs):
    """Call a dataclass constructor; re-raise its ValueError with file and table."""
    try:
        return factory(**kwargs)
    except ValueError as exc:
        raise ValueError(f"{label}: [{where}] {exc}") from None


def drive_from(data: dict, label: str) -> Drive:
    """``[drive]`` with exactly one of ``speed_rpm`` or ``omega`` (rad/s)."""
    t = _table(data, "drive", label)
    has_rpm, has_omega = "speed_rpm" in t, "omega" in t
    if has_rpm == has_omega:
        raise ValueError(f"{label}: [drive] speed_rpm/omega: give exactly one")
    if has_rpm:
        return _build(label, "drive", Drive.from_rpm, rpm=field(t, "drive", "speed_rpm", label))
    return _build(label, "drive", Drive, omega=field(t, "drive", "omega", label))


def material_from(t: dict, section: str, label: str) -> Material:
    """A material table: ``name``, ``youngs_modulus`` [Pa], optional ``density``."""
    return _build(
        label,
        section,
        Material,
        name=field(t, section, "name", label, str, default=section),
        youngs_modulus=field(t, section, "youngs_modulus", label),
        density=field(t, section, "density", label, default=0.0),
    )


def _crank_slider(data: dict, label: str) -> CrankMechanism:
    c = _table(data, "crank", label)
    m = data.get("masses", {})
    p = data.get("pump", {})
    f = lambda t, s, n, **kw: field(t, s, n, label, **kw)  # noqa: E731
    linkage = _build(
        label,
        "crank",
        CrankSlider,
        crank=f(c, "crank", "crank"),
        rod=f(c, "crank", "rod"),
        rod_cg_from_crank_pin=f(c, "crank", "rod_cg_from_crank_pin", default=None),
        rod_mass=f(m, "masses", "rod", default=0.0),
        rod_inertia=f(m, "masses", "rod_inertia", default=None),
        slider_mass=f(m, "masses", "slider", default=0.0),
        crank_mass=f(m, "masses", "crank", default=0.0),
        crank_cg_radius=f(m, "masses", "crank_cg_radius", default=0.0),
    )
    return _build(
        label,
        "pump",
        CrankMechanism,
        name=f(data, "", "name", kind=str),
        drive=drive_from(data, label),
        linkage=linkage,
        cylinders=f(p, "pump", "cylinders", kind=int, default=1),
        plunger_diameter=f(p, "pump", "plunger_diameter", default=0.0),
        cylinder_spacing=f(p, "pump", "cylinder_spacing", default=0.0),
        pressure=f(p, "pump", "pressure", default=0.0),
    )


def _rotor_frame(data: dict, label: str) -> RotorFrame:
    r = _table(data, "rotor", label)
    fr = _table(data, "frame", label)
    f = lambda t, s, n, **kw: field(t, s, n, label, **kw)  # noqa: E731
    rotor = _build(
        label,
        "rotor",
        Rotor,
        name=f(r, "rotor", "name", kind=str, default="rotor"),
        mass=f(r, "rotor", "mass"),
        shaft_length=f(r, "rotor", "shaft_length"),
        shaft_diameter=f(r, "rotor", "shaft_diameter"),
        eccentricity=f(r, "rotor", "eccentricity"),
        material=material_from(_table(r, "material", f"{label}: [rotor]"), "rotor.material", label),
    )

    def section(name: Any, key: str):
        if not isinstance(name, str):
            raise ValueError(f"{label}: [frame] {key}: expected a section name string, got {name!r}")
        try:
            return ibeam(name)
        except ValueError as exc:
            raise ValueError(f"{label}: [frame] {key}: {exc}") from None

    names = f(fr, "frame", "sections", kind=list, default=[])
    hr = f(fr, "frame", "height_range", kind=list, default=[0.1, 2.0])
    if len(hr) != 2 or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in hr):
        raise ValueError(f"{label}: [frame] height_range: expected [lo, hi] in m, got {hr!r}")
    return _build(
        label,
        "frame",
        RotorFrame,
        name=f(data, "", "name", kind=str),
        rotor=rotor,
        plate_mass=f(fr, "frame", "plate_mass"),
        column_material=material_from(_table(fr, "material", f"{label}: [frame]"), "frame.material", label),
        section=section(f(fr, "frame", "section", kind=str), "section"),
        height=f(fr, "frame", "height"),
        columns=f(fr, "frame", "columns", kind=int, default=1),
        axis=f(fr, "frame", "axis", kind=str, default="x"),
        sections=tuple(section(n, "sections") for n in names),
        height_range=(float(hr[0]), float(hr[1])),
    )


def _pair3(t: dict, name: str, label: str) -> tuple:
    v = field(t, "linkage", name, label, list)
    if len(v) != 3 or not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v):
        raise ValueError(f"{label}: [linkage] {name}: expected 3 numbers (joints O, A, B), got {v!r}")
    return tuple(float(x) for x in v)


def _linkage(data: dict, label: str) -> MillDrive:
    t = _table(data, "linkage", label)
    ld = data.get("load", {})
    f = lambda tt, s, n, **kw: field(tt, s, n, label, **kw)  # noqa: E731
    linkage = _build(
        label,
        "linkage",
        Linkage,
        crank=f(t, "linkage", "crank"),
        rod=f(t, "linkage", "rod"),
        pin_diameters=_pair3(t, "pin_diameters", label),
        pin_friction=_pair3(t, "pin_friction", label),
        guide_friction=f(t, "linkage", "guide_friction"),
    )
    return _build(
        label,
        "load",
        MillDrive,
        name=f(data, "", "name", kind=str),
        drive=drive_from(data, label),
        linkage=linkage,
        load=f(ld, "load", "force", default=0.0),
        idle_zone=math.radians(f(ld, "load", "idle_zone_deg", default=30.0)),
    )


def surface_from(data: dict, label: str):
    """``[surface]`` with ``arc = [a1, a2]`` [rad], ``half_width`` [-] and ``[[surface.inlets]]``.

    The same reader as scene files (:func:`bearingfe.scenes.surface_from`), except that a
    machine's shoe has no default size: ``arc`` and ``half_width`` are required here.
    """
    from .scenes import surface_from as read_surface

    t = _table(data, "surface", label)
    field(t, "surface", "arc", label, list)
    field(t, "surface", "half_width", label)
    return read_surface(t, label)


def _eccentric_pump(data: dict, label: str):
    from bearingfe.pump import EccentricPump, PressureCycle

    e, sh, pl, cy = (_table(data, n, label) for n in ("eccentric", "shoe", "plunger", "cycle"))
    f = lambda t, s, n, **kw: field(t, s, n, label, **kw)  # noqa: E731
    cycle = _build(label, "cycle", PressureCycle, discharge=f(cy, "cycle", "discharge"),
                   suction=f(cy, "cycle", "suction"),
                   compression=math.radians(f(cy, "cycle", "compression_deg", default=20.0)),
                   decompression=math.radians(f(cy, "cycle", "decompression_deg", default=20.0)))
    return _build(label, "eccentric", EccentricPump, name=f(data, "", "name", kind=str),
                  eccentricity=f(e, "eccentric", "eccentricity"), pivot_distance=f(e, "eccentric", "pivot_distance"),
                  radius=f(e, "eccentric", "radius"), clearance=f(sh, "shoe", "clearance"),
                  viscosity=f(sh, "shoe", "viscosity"), plunger_diameter=f(pl, "plunger", "diameter"),
                  preload=f(pl, "plunger", "preload", default=0.0), drive=drive_from(data, label),
                  cycle=cycle, surface=surface_from(data, label))


LOADERS: dict = {
    "crank_slider": _crank_slider,
    "rotor_frame": _rotor_frame,
    "linkage": _linkage,
    "eccentric_pump": _eccentric_pump,
}


def load_mechanism(path) -> Any:
    """Read a mechanism TOML file into its frozen parameter object.

    Parameters
    ----------
    path : str or Path
        A file such as ``mechanisms/snt32.toml``.

    Returns
    -------
    object
        :class:`~bearingfe.machines.CrankMechanism`,
        :class:`~bearingfe.machines.RotorFrame` or
        :class:`~bearingfe.machines.MillDrive` or
        :class:`~bearingfe.pump.EccentricPump`, by the file's ``kind``.

    Raises
    ------
    ValueError
        Unreadable TOML, unknown ``kind``, missing field, wrong type or value
        out of range; the message names the file and the field.
    """
    path = Path(path)
    label = path.name
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{label}: not valid TOML: {exc}") from None
    kind = field(data, "", "kind", label, str)
    if kind not in LOADERS:
        raise ValueError(f"{label}: kind: must be one of {sorted(LOADERS)}, got {kind!r}")
    return LOADERS[kind](data, label)
