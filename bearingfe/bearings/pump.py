r"""The eccentric radial-plunger pump: parameters, chamber-pressure cycle, swinging-plunger kinematics.

Geometry (paper 004; ``docs/formulations.md``, section "The eccentric pump")
----------------------------------------------------------------------------
The shaft axis ``O1`` is the origin; the shaft angle is ``beta = omega tau``,
counter-clockwise. The eccentric centre is ``O2 = E (cos beta, sin beta)``.
The plunger's cylinder pivots about the fixed point ``B = (-E2, 0)``, so the
plunger axis is the line ``B -> O2``. Its direction (the *swing angle*) and
the pivot distance ``|O2 B| = E lam`` are, with ``e2 = E2/E``::

    phi2 = atan2(sin beta, e2 + cos beta),     lam = sqrt(1 + e2^2 + 2 e2 cos beta),
    dphi2/dbeta = (1 + e2 cos beta)/lam^2,     dlam/dbeta = -e2 sin beta / lam.

The plunger stroke is ``E (lam_max - lam) = E (1 + e2 - lam)`` (``2E`` in
all): the chamber is compressed (discharge) while ``lam`` decreases, i.e. for
``beta`` in ``(0, pi)``; ``beta = 0`` is the outer and ``beta = pi`` the inner
dead centre.

Shoe frame (the coordinates the Reynolds solver sees)
-----------------------------------------------------
The shoe sits on the side of the eccentric that faces the pivot ``B``. Its
angle ``psi`` is measured about ``O2`` counter-clockwise from the direction
``O2 -> shoe centre``, i.e. from the direction ``phi2 + pi``::

    phi = phi2 + pi + psi          (phi: angle about O2 in the fixed frame).

A :class:`bearingfe.Surface` for the pump therefore has its arc around
``psi = 0`` and its pockets in ``(psi, z)``. In this frame

* the shoe is at rest and the eccentric surface slides at
  ``(omega - dphi2/dtau) R0``: the solver's ``wedge = 1 - dphi2/dbeta``;
* the film is ``h = 1 + gamma cos(psi - delta)`` with
  ``delta = phi0 - phi2 - pi``, where ``phi0`` is the fixed-frame direction
  of the bore centre seen from ``O2`` (the thickest film);
* the squeeze term at a fixed point of the shoe is
  ``dh/dbeta|psi = gamma' cos(psi - delta) + gamma delta' sin(psi - delta)``,
  so the solver's "phi0_rate" *is* ``delta' = d delta/dbeta``. Written in the
  fixed frame the same equation reads
  ``6 (1 + phi2') dh/dphi + 12 (gamma' cos + gamma phi0' sin)`` (docs/formulations.md):
  substituting ``d/dbeta|phi = d/dbeta|psi - phi2' d/dpsi`` turns
  ``6 (1 + phi2')`` into ``6 (1 - phi2')`` and ``phi0'`` into
  ``delta' + phi2'``; the two forms are identical. The state of the
  transient is therefore ``(gamma, delta)`` and no rate conversion is needed;
  ``phi0 = delta + phi2 + pi`` if the fixed-frame angle is wanted.
* The plunger force ``F`` pushes the shoe towards ``O2``, i.e. along
  ``psi = pi``: the applied load on the shoe in the solver's frame is
  ``(-f, 0)`` with ``f = F c^2/(mu omega R0^4)``. The film force
  ``int p (cos psi, sin psi)`` pushes the shoe away from the journal;
  equilibrium is ``film force + (-f, 0) = 0``. Under load the shoe closes
  the film at ``psi = 0``: ``delta`` stays near ``pi``.

These signs are checked in ``tests/test_pump.py`` against finite
differences of the positions of material points of the eccentric and of the
shoe.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..geometry.surface import Surface
from ..core.machine import Drive, Material
from ..elastic.shoe import ShoeBody
from .hydrostatic import PrescribedPressure, Restrictor, Supply
from ..core.scales import Scale
from ..core.schema import nonnegative, positive

__all__ = [
    "PressureCycle",
    "EccentricPump",
    "swing_angle",
    "swing_rate",
    "pivot_ratio",
    "pivot_ratio_rate",
    "plunger_stroke",
    "shoe_wedge",
    "attitude",
]


# -- kinematics (pure functions of beta and e2) ----------------------------------

def _check_e2(e2: float) -> float:
    e2 = float(e2)
    if not (math.isfinite(e2) and e2 > 1.0):
        raise ValueError(f"e2 = E2/E must be a finite number > 1 (pivot outside the eccentric circle), got {e2!r}")
    return e2


def swing_angle(beta, e2: float) -> np.ndarray:
    """Plunger swing angle ``phi2 = atan2(sin beta, e2 + cos beta)`` [rad].

    Parameters
    ----------
    beta : array_like
        Shaft angle [rad].
    e2 : float
        Pivot distance over eccentricity ``E2/E`` [-], > 1.
    """
    e2 = _check_e2(e2)
    beta = np.asarray(beta, dtype=float)
    return np.arctan2(np.sin(beta), e2 + np.cos(beta))


def swing_rate(beta, e2: float) -> np.ndarray:
    """``dphi2/dbeta = (1 + e2 cos beta)/lam^2`` [-]."""
    e2 = _check_e2(e2)
    beta = np.asarray(beta, dtype=float)
    return (1.0 + e2 * np.cos(beta)) / (1.0 + e2**2 + 2.0 * e2 * np.cos(beta))


def pivot_ratio(beta, e2: float) -> np.ndarray:
    """``lam = |O2 B|/E = sqrt(1 + e2^2 + 2 e2 cos beta)`` [-]."""
    e2 = _check_e2(e2)
    return np.sqrt(1.0 + e2**2 + 2.0 * e2 * np.cos(np.asarray(beta, dtype=float)))


def pivot_ratio_rate(beta, e2: float) -> np.ndarray:
    """``dlam/dbeta = -e2 sin beta / lam`` [-]."""
    beta = np.asarray(beta, dtype=float)
    return -_check_e2(e2) * np.sin(beta) / pivot_ratio(beta, e2)


def plunger_stroke(beta, e2: float) -> np.ndarray:
    """Plunger displacement into the cylinder over ``E``: ``1 + e2 - lam`` (0 .. 2) [-]."""
    return 1.0 + _check_e2(e2) - pivot_ratio(beta, e2)


def shoe_wedge(beta, e2: float) -> np.ndarray:
    """Sliding speed of the eccentric under the shoe, ``1 - dphi2/dbeta``, in units ``omega R0``."""
    return 1.0 - swing_rate(beta, e2)


def attitude(phi0, beta, e2: float) -> np.ndarray:
    """Shoe-frame attitude ``delta = phi0 - phi2 - pi`` of a fixed-frame line-of-centres angle ``phi0`` [rad]."""
    return np.asarray(phi0, dtype=float) - swing_angle(beta, e2) - math.pi


# -- chamber pressure ---------------------------------------------------------------

def _ramp(x: np.ndarray) -> np.ndarray:
    """Raised cosine from 0 at x <= 0 to 1 at x >= 1 (C1)."""
    x = np.clip(x, 0.0, 1.0)
    return 0.5 * (1.0 - np.cos(math.pi * x))


def _ramp_scalar(x: float) -> float:
    """:func:`_ramp` of one number."""
    x = min(max(x, 0.0), 1.0)
    return 0.5 * (1.0 - math.cos(math.pi * x))


@dataclass(frozen=True)
class PressureCycle:
    """Chamber pressure over one turn, tied to the plunger stroke.

    Discharge while the plunger moves in (``beta`` in ``(0, pi)``), suction
    while it moves out. The pressure rises from suction to discharge over
    the first ``compression`` radians after the outer dead centre
    (``beta = 0``) and falls back over the first ``decompression`` radians
    after the inner dead centre (``beta = pi``), both as raised-cosine ramps
    (continuous slope, so an adaptive integrator steps through them).

    Parameters
    ----------
    discharge : float
        Discharge pressure [Pa], >= suction.
    suction : float
        Suction (boost) pressure [Pa], >= 0.
    compression : float
        Compression angle [rad], in (0, pi).
    decompression : float
        Decompression angle [rad], in (0, pi).
    """

    discharge: float
    suction: float
    compression: float = math.radians(20.0)
    decompression: float = math.radians(20.0)

    def __post_init__(self) -> None:
        for name in ("discharge", "suction", "compression", "decompression"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"PressureCycle.{name} must be a finite number, got {v!r}")
            object.__setattr__(self, name, float(v))
        if self.suction < 0:
            raise ValueError(f"PressureCycle.suction must be >= 0 Pa, got {self.suction}")
        if self.discharge < self.suction:
            raise ValueError(f"PressureCycle.discharge must be >= suction ({self.suction} Pa), got {self.discharge}")
        for name in ("compression", "decompression"):
            if not 0.0 < getattr(self, name) < math.pi:
                raise ValueError(f"PressureCycle.{name} must be in (0, pi) rad, got {getattr(self, name)}")

    def fraction(self, beta) -> np.ndarray:
        """0 at suction, 1 at discharge, smooth ramps in between [-]."""
        if isinstance(beta, float):  # one angle (an integrator's call): the same formulas without arrays
            b = beta % (2.0 * math.pi)
            if b < math.pi:
                return np.float64(_ramp_scalar(b / self.compression))
            return np.float64(1.0 - _ramp_scalar((b - math.pi) / self.decompression))
        b = np.mod(np.asarray(beta, dtype=float), 2.0 * math.pi)
        up = _ramp(b / self.compression)
        down = _ramp((b - math.pi) / self.decompression)
        return np.where(b < math.pi, up, 1.0 - down)

    def pressure(self, beta) -> np.ndarray:
        """Chamber pressure [Pa] at shaft angle ``beta`` [rad]."""
        return self.suction + (self.discharge - self.suction) * self.fraction(beta)


# -- the pump -----------------------------------------------------------------------

#: Structural steel: E = 210 GPa, nu = 0.3, 7850 kg/m^3 (the default of both film surfaces).
STEEL = Material("steel", 210e9, density=7850.0, poisson_ratio=0.3)

@dataclass(frozen=True)
class EccentricPump:
    """A radial-plunger pump with an eccentric drive and swinging plungers (SI units).

    Parameters
    ----------
    eccentricity : float
        ``E = |O1 O2|`` [m], > 0 (half the stroke).
    pivot_distance : float
        ``E2 = |O1 B|`` [m], > ``eccentricity + radius`` (the pivot lies
        outside the eccentric).
    radius : float
        Eccentric radius ``R0`` [m], > 0.
    clearance : float
        Radial clearance ``c`` of the shoe bore [m], 0 < c < radius / 100.
    surface : Surface
        The shoe surface in shoe coordinates ``(psi, z = Z/R0)``, arc inside
        ``(-pi/2, pi/2)`` (see the module docstring), with its pockets.
    plunger_diameter : float
        [m], > 0.
    viscosity : float
        Oil viscosity [Pa s], > 0.
    drive : Drive
        Shaft speed (shared with :mod:`bearingfe.mechanisms.crank`).
    cycle : PressureCycle
        Chamber pressure; the pockets are fed at this pressure.
    preload : float
        Constant force pressing the shoe onto the eccentric (spring,
        retaining ring) [N], >= 0. The applied force must stay > 0 over the
        cycle: ``suction > 0`` or ``preload > 0``.
    name : str
    shoe_material, eccentric_material : Material
        Elastic data of the shoe and of the eccentric (the two film
        surfaces), for an elastic support (:mod:`bearingfe.elastic.coupled`);
        default :data:`STEEL` (210 GPa, nu = 0.3, 7850 kg/m^3).
    shoe_thickness : float, optional
        Depth of the shoe body between the film and its seat on the plunger
        [m], > 0 (for :func:`bearingfe.elastic.block_compliance`); None if not given.
    shoe_body : ShoeBody, optional
        The shoe as an elastic body (depth, back, seat on the plunger,
        lining) for :func:`bearingfe.elastic.shoe.shoe_compliance`; default a
        flat-backed body clamped over its whole back when ``shoe_thickness``
        is given. Its thickness is ``shoe_thickness`` (given either way).
    shoe_supply : Restrictor, optional
        How the pocket is fed from the chamber: a capillary or an orifice in the plunger
        (:class:`bearingfe.bearings.hydrostatic.Restrictor`); None: the pocket is at the chamber
        pressure (an infinitely stiff supply). :meth:`pocket_supply` gives the pocket's supply at a
        chamber pressure for :func:`bearingfe.solve_supplied` (the steady balance; the cycle's
        transient still holds the pocket at the chamber pressure).
    """

    eccentricity: float
    pivot_distance: float
    radius: float
    clearance: float
    surface: Surface
    plunger_diameter: float
    viscosity: float
    drive: Drive
    cycle: PressureCycle
    preload: float = 0.0
    name: str = "eccentric pump"
    shoe_material: Material = STEEL
    eccentric_material: Material = STEEL
    shoe_thickness: float | None = None
    shoe_body: ShoeBody | None = None
    shoe_supply: Restrictor | None = None
    _scale: Scale = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        own = "EccentricPump"
        for n in ("eccentricity", "pivot_distance", "radius", "clearance", "plunger_diameter", "viscosity"):
            object.__setattr__(self, n, positive(f"{own}.{n}", getattr(self, n)))
        object.__setattr__(self, "preload", nonnegative(f"{own}.preload", self.preload, "N"))
        if self.pivot_distance <= self.eccentricity + self.radius:
            raise ValueError(f"{own}.pivot_distance must exceed eccentricity + radius "
                             f"({self.eccentricity + self.radius} m), got {self.pivot_distance}")
        if self.clearance >= self.radius / 100.0:
            raise ValueError(f"{own}.clearance must be < radius/100 ({self.radius / 100} m) for the thin-film "
                             f"model, got {self.clearance}")
        if not isinstance(self.surface, Surface):
            raise ValueError(f"{own}.surface must be a bearingfe.Surface, got {type(self.surface).__name__}")
        a1, a2 = self.surface.arc
        if not (-math.pi / 2 < a1 < a2 < math.pi / 2):
            raise ValueError(f"{own}.surface.arc must lie inside (-pi/2, pi/2) rad around the shoe centre "
                             f"psi = 0, got {self.surface.arc}")
        if not isinstance(self.drive, Drive):
            raise ValueError(f"{own}.drive must be a bearingfe.Drive, got {type(self.drive).__name__}")
        if not isinstance(self.cycle, PressureCycle):
            raise ValueError(f"{own}.cycle must be a bearingfe.bearings.pump.PressureCycle, got {type(self.cycle).__name__}")
        if self.shoe_thickness is not None:
            object.__setattr__(self, "shoe_thickness", positive(f"{own}.shoe_thickness", self.shoe_thickness))
        if self.shoe_body is not None:
            if not isinstance(self.shoe_body, ShoeBody):
                raise ValueError(f"{own}.shoe_body must be a bearingfe.elastic.shoe.ShoeBody, got "
                                 f"{type(self.shoe_body).__name__}")
            if self.shoe_thickness is None:
                object.__setattr__(self, "shoe_thickness", self.shoe_body.thickness)
            elif self.shoe_thickness != self.shoe_body.thickness:
                raise ValueError(f"{own}.shoe_thickness ({self.shoe_thickness} m) must equal "
                                 f"shoe_body.thickness ({self.shoe_body.thickness} m)")
        elif self.shoe_thickness is not None:
            object.__setattr__(self, "shoe_body", ShoeBody(self.shoe_thickness))
        if self.shoe_supply is not None and not isinstance(self.shoe_supply, Restrictor):
            raise ValueError(f"{own}.shoe_supply must be a bearingfe.bearings.hydrostatic.Restrictor or None, got "
                             f"{type(self.shoe_supply).__name__}")
        for n in ("shoe_material", "eccentric_material"):
            if not isinstance(getattr(self, n), Material):
                raise ValueError(f"{own}.{n} must be a bearingfe.Material, got {type(getattr(self, n)).__name__}")
        if self.cycle.suction <= 0 and self.preload <= 0:
            raise ValueError(f"{own}: the applied force vanishes during suction; give cycle.suction > 0 Pa "
                             f"or preload > 0 N")
        object.__setattr__(self, "_scale", Scale(self.radius, self.clearance, self.viscosity, self.drive.omega))

    @property
    def scale(self) -> Scale:
        """Non-dimensional <-> SI scales of the shoe film."""
        return self._scale

    def pocket_supply(self, chamber_pressure: float) -> Supply:
        """The shoe pocket's supply at a chamber pressure [Pa]: the chamber pressure itself, or the
        plunger's restrictor fed from it (:attr:`shoe_supply`)."""
        if self.shoe_supply is None:
            return PrescribedPressure(chamber_pressure)
        return self.shoe_supply.fed_from(chamber_pressure)

    @property
    def e2(self) -> float:
        """``E2/E`` [-]."""
        return self.pivot_distance / self.eccentricity

    @property
    def plunger_area(self) -> float:
        """[m^2]."""
        return math.pi * self.plunger_diameter**2 / 4.0

    @property
    def stroke(self) -> float:
        """Full plunger stroke ``2 E`` [m]."""
        return 2.0 * self.eccentricity

    @property
    def displacement(self) -> float:
        """Geometric volume per plunger and revolution [m^3]."""
        return self.plunger_area * self.stroke

    def chamber_pressure(self, beta) -> np.ndarray:
        """Chamber (and pocket) pressure [Pa]."""
        return self.cycle.pressure(beta)

    def plunger_force(self, beta) -> np.ndarray:
        """Force pushing the shoe onto the eccentric along the plunger axis [N]."""
        return self.chamber_pressure(beta) * self.plunger_area + self.preload

    def load(self, beta) -> np.ndarray:
        """Non-dimensional load ``f = F c^2/(mu omega R0^4)`` [-] (magnitude)."""
        return self.plunger_force(beta) / self.scale.force

    def load_vector(self, beta: float) -> np.ndarray:
        """Applied load on the shoe in the solver's frame, ``(-f, 0)`` [-]."""
        return np.array([-float(self.load(beta)), 0.0])

    def inlet_pressure(self, beta) -> np.ndarray:
        """Pocket pressure in solver units ``p_s = P c^2/(mu omega R0^2)`` [-]; zero
        for a shoe without pockets (nothing carries the chamber pressure to the film)."""
        if not self.surface.inlets:
            return np.zeros(np.shape(beta))
        return self.chamber_pressure(beta) / self.scale.pressure

    def wedge(self, beta) -> np.ndarray:
        """Solver ``wedge = 1 - dphi2/dbeta`` [-]."""
        return shoe_wedge(beta, self.e2)

    def swing(self, beta) -> np.ndarray:
        """``phi2`` [rad]."""
        return swing_angle(beta, self.e2)
