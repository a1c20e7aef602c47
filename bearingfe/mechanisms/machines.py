"""Shared parameter objects for the machine models (SI units, frozen, validated).

Grouped by how long they live: a :class:`~bearingfe.core.machine.Drive` is the operating point, the
linkage/rotor/section objects are the design, and the ``*Mechanism`` objects
bundle what one TOML file in ``mechanisms/`` describes.

================================  ==========================================
object                            what it holds
================================  ==========================================
:class:`CrankSlider`              central crank-slider geometry and masses
:class:`CrankMechanism`           crank-slider machine (pump): drive + linkage
:class:`Linkage`                  crank-slider with joint friction (paper 003)
:class:`MillDrive`                linkage + drive + stand load + idle zones
:class:`Section`                  beam cross-section (area, Ix, Iy, mass/m)
:class:`Rotor`                    unbalanced rotor on a simply supported shaft
:class:`Frame`                    plate mass + total lateral column stiffness
:class:`RotorFrame`               rotor, plate and column design (paper 002)
================================  ==========================================
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional

from ..core.machine import Drive, Material
from ..core.schema import finite, nonnegative, positive

__all__ = [
    "CrankSlider",
    "CrankMechanism",
    "Linkage",
    "MillDrive",
    "Section",
    "Rotor",
    "Frame",
    "RotorFrame",
]


@dataclass(frozen=True)
class CrankSlider:
    """Central (in-line) crank-slider: geometry and link masses.

    Parameters
    ----------
    crank : float
        Crank radius r [m] (eccentricity of an eccentric drive), > 0.
    rod : float
        Connecting-rod length l between the crank pin A and wrist pin B [m],
        must exceed ``crank``.
    rod_mass : float
        Rod mass M3 [kg], >= 0.
    rod_cg_from_crank_pin : float, optional
        Distance l_a from the crank pin A to the rod's centre of mass [m],
        in [0, rod]. Default: rod/2.
    rod_inertia : float, optional
        Rod moment of inertia about its centre of mass J_S [kg m^2], >= 0.
        ``None`` (unknown) makes the residual inertia moment unavailable.
    slider_mass : float
        Mass of the reciprocating set (crosshead, plunger) M2 [kg], >= 0.
    crank_mass : float
        Mass of the crank / eccentric assembly M1 [kg], >= 0.
    crank_cg_radius : float
        Distance of the crank assembly's centre of mass from the shaft axis
        rho1 [m], >= 0.
    """

    crank: float
    rod: float
    rod_mass: float = 0.0
    rod_cg_from_crank_pin: Optional[float] = None
    rod_inertia: Optional[float] = None
    slider_mass: float = 0.0
    crank_mass: float = 0.0
    crank_cg_radius: float = 0.0

    def __post_init__(self) -> None:
        positive("crank", self.crank, "m")
        positive("rod", self.rod, "m")
        if self.rod <= self.crank:
            raise ValueError(
                f"rod must be longer than crank (rod > {self.crank!r} m), got {self.rod!r} m"
            )
        nonnegative("rod_mass", self.rod_mass, "kg")
        nonnegative("slider_mass", self.slider_mass, "kg")
        nonnegative("crank_mass", self.crank_mass, "kg")
        nonnegative("crank_cg_radius", self.crank_cg_radius, "m")
        if self.rod_cg_from_crank_pin is None:
            object.__setattr__(self, "rod_cg_from_crank_pin", 0.5 * self.rod)
        la = finite("rod_cg_from_crank_pin", self.rod_cg_from_crank_pin)
        if not 0.0 <= la <= self.rod:
            raise ValueError(
                f"rod_cg_from_crank_pin must be in [0, rod={self.rod!r}] m, got {la!r}"
            )
        if self.rod_inertia is not None:
            nonnegative("rod_inertia", self.rod_inertia, "kg m^2")

    @property
    def lam(self) -> float:
        """Crank-to-rod ratio lambda = r/l [-]."""
        return self.crank / self.rod

    @property
    def rod_cg_from_wrist_pin(self) -> float:
        """Distance l_b from the rod's centre of mass to the wrist pin B [m]."""
        return self.rod - self.rod_cg_from_crank_pin

    @property
    def stroke(self) -> float:
        """Slider stroke 2 r [m]."""
        return 2.0 * self.crank


@dataclass(frozen=True)
class CrankMechanism:
    """A crank-slider machine: z equal cranks at 360/z degrees (e.g. a plunger pump).

    Parameters
    ----------
    name : str
        Label.
    drive : Drive
        Crankshaft speed.
    linkage : CrankSlider
        Geometry and masses of one crank-slider.
    cylinders : int
        Number of cranks z (>= 1), phased 360/z degrees apart.
    plunger_diameter : float
        Plunger diameter [m], > 0 (0 if not a pump).
    cylinder_spacing : float
        Axial distance between neighbouring crank planes [m], >= 0 (for the
        resultant inertia moment).
    pressure : float
        Working pressure [Pa], >= 0 (informational).
    """

    name: str
    drive: Drive
    linkage: CrankSlider
    cylinders: int = 1
    plunger_diameter: float = 0.0
    cylinder_spacing: float = 0.0
    pressure: float = 0.0

    def __post_init__(self) -> None:
        if not isinstance(self.cylinders, int) or isinstance(self.cylinders, bool) or self.cylinders < 1:
            raise ValueError(f"cylinders must be an integer >= 1, got {self.cylinders!r}")
        nonnegative("plunger_diameter", self.plunger_diameter, "m")
        nonnegative("cylinder_spacing", self.cylinder_spacing, "m")
        nonnegative("pressure", self.pressure, "Pa")


@dataclass(frozen=True)
class Linkage:
    """Crank-slider with friction in its joints (paper 003's stand drive).

    Parameters
    ----------
    crank : float
        Crank radius l1 [m], > 0.
    rod : float
        Rod length l2 [m], > crank.
    pin_diameters : tuple of 3 float
        Journal diameters (d1 main bearing O, d2 crank pin A, d3 wrist pin B)
        [m], each >= 0.
    pin_friction : tuple of 3 float
        Friction coefficients (mu1, mu2, mu3) of those joints [-], in [0, 1).
    guide_friction : float
        Friction coefficient mu4 of the slider (stand) on its guides [-],
        in [0, 1).
    """

    crank: float
    rod: float
    pin_diameters: tuple = (0.0, 0.0, 0.0)
    pin_friction: tuple = (0.0, 0.0, 0.0)
    guide_friction: float = 0.0

    def __post_init__(self) -> None:
        positive("crank", self.crank, "m")
        positive("rod", self.rod, "m")
        if self.rod <= self.crank:
            raise ValueError(
                f"rod must be longer than crank (rod > {self.crank!r} m), got {self.rod!r} m"
            )
        for name, values in (("pin_diameters", self.pin_diameters), ("pin_friction", self.pin_friction)):
            if len(tuple(values)) != 3:
                raise ValueError(f"{name} must have 3 entries (joints O, A, B), got {values!r}")
        object.__setattr__(self, "pin_diameters", tuple(float(v) for v in self.pin_diameters))
        object.__setattr__(self, "pin_friction", tuple(float(v) for v in self.pin_friction))
        for i, d in enumerate(self.pin_diameters):
            nonnegative(f"pin_diameters[{i}]", d, "m")
        for i, mu in enumerate(self.pin_friction + (self.guide_friction,)):
            name = f"pin_friction[{i}]" if i < 3 else "guide_friction"
            if not 0.0 <= finite(name, mu) < 1.0:
                raise ValueError(f"{name} must be in [0, 1), got {mu!r}")

    @property
    def lam(self) -> float:
        """Crank-to-rod ratio l1/l2 [-]."""
        return self.crank / self.rod


@dataclass(frozen=True)
class MillDrive:
    """Crank drive of a rolling stand (cold pilger mill, paper 003).

    Parameters
    ----------
    name : str
        Label.
    drive : Drive
        Crank speed.
    linkage : Linkage
        Geometry and friction.
    load : float
        Technological force T on the stand, opposing its motion in the
        working zones [N], >= 0.
    idle_zone : float
        Crank-angle width of each no-rolling zone, centred on a dead centre
        [rad], in [0, pi).
    """

    name: str
    drive: Drive
    linkage: Linkage
    load: float = 0.0
    idle_zone: float = math.radians(30.0)

    def __post_init__(self) -> None:
        nonnegative("load", self.load, "N")
        if not 0.0 <= finite("idle_zone", self.idle_zone) < math.pi:
            raise ValueError(f"idle_zone must be in [0, pi) rad, got {self.idle_zone!r}")


@dataclass(frozen=True)
class Section:
    """Beam cross-section.

    Parameters
    ----------
    name : str
        Designation, e.g. ``"20a"``.
    area : float
        Area [m^2], > 0.
    ix, iy : float
        Second moments of area about the strong (x) and weak (y) axis [m^4], > 0.
    mass_per_length : float
        Linear mass [kg/m], > 0.
    source : str
        Where the numbers come from.
    """

    name: str
    area: float
    ix: float
    iy: float
    mass_per_length: float
    source: str = ""

    def __post_init__(self) -> None:
        positive("area", self.area, "m^2")
        positive("ix", self.ix, "m^4")
        positive("iy", self.iy, "m^4")
        positive("mass_per_length", self.mass_per_length, "kg/m")

    def second_moment(self, axis: str) -> float:
        """Second moment of area [m^4] about ``axis`` ('x' strong, 'y' weak)."""
        if axis == "x":
            return self.ix
        if axis == "y":
            return self.iy
        raise ValueError(f"axis must be 'x' or 'y', got {axis!r}")


@dataclass(frozen=True)
class Rotor:
    """Unbalanced rotor at mid-span of a simply supported shaft (paper 002).

    Parameters
    ----------
    name : str
        Label (motor type).
    mass : float
        Rotor mass m [kg], > 0.
    shaft_length : float
        Bearing span l [m], > 0.
    shaft_diameter : float
        Shaft diameter d [m], > 0.
    eccentricity : float
        Mass-centre offset e [m], >= 0.
    material : Material
        Shaft material (E1).
    """

    name: str
    mass: float
    shaft_length: float
    shaft_diameter: float
    eccentricity: float
    material: Material

    def __post_init__(self) -> None:
        positive("mass", self.mass, "kg")
        positive("shaft_length", self.shaft_length, "m")
        positive("shaft_diameter", self.shaft_diameter, "m")
        nonnegative("eccentricity", self.eccentricity, "m")


@dataclass(frozen=True)
class Frame:
    """Elastic frame reduced to one lateral degree of freedom.

    Parameters
    ----------
    mass : float
        Plate (frame) mass M [kg], > 0.
    stiffness : float
        Total lateral stiffness C of the columns [N/m], > 0.
    """

    mass: float
    stiffness: float

    def __post_init__(self) -> None:
        positive("mass", self.mass, "kg")
        positive("stiffness", self.stiffness, "N/m")


@dataclass(frozen=True)
class RotorFrame:
    """Rotor on a plate carried by cantilever columns: the design of paper 002.

    Parameters
    ----------
    name : str
        Label.
    rotor : Rotor
        The motor rotor.
    plate_mass : float
        Plate mass M [kg], > 0.
    column_material : Material
        Column material (E2).
    section : Section
        Reference column section.
    height : float
        Reference column height L [m], > 0.
    columns : int
        Number of columns acting in parallel, >= 1.
    axis : str
        Bending axis of the column section, 'x' (strong) or 'y' (weak).
    sections : tuple of Section
        Candidate sections for the design table (may be empty).
    height_range : tuple of 2 float
        Column heights scanned by the design method [m].
    """

    name: str
    rotor: Rotor
    plate_mass: float
    column_material: Material
    section: Section
    height: float
    columns: int = 1
    axis: str = "x"
    sections: tuple = field(default_factory=tuple)
    height_range: tuple = (0.1, 2.0)

    def __post_init__(self) -> None:
        positive("plate_mass", self.plate_mass, "kg")
        positive("height", self.height, "m")
        if not isinstance(self.columns, int) or isinstance(self.columns, bool) or self.columns < 1:
            raise ValueError(f"columns must be an integer >= 1, got {self.columns!r}")
        if self.axis not in ("x", "y"):
            raise ValueError(f"axis must be 'x' or 'y', got {self.axis!r}")
        lo, hi = self.height_range
        positive("height_range[0]", lo, "m")
        if not finite("height_range[1]", hi) > lo:
            raise ValueError(f"height_range must be (lo, hi) with 0 < lo < hi, got {self.height_range!r}")
        object.__setattr__(self, "sections", tuple(self.sections))
