"""Conversion between the non-dimensional Reynolds problem and SI units.

With eccentric radius ``R0``, radial clearance ``c``, viscosity ``mu`` and
shaft speed ``omega`` the solver's variables scale as

==================  ==========================  ===========
quantity            scale                        SI unit
==================  ==========================  ===========
pressure            ``mu omega R0^2 / c^2``      Pa
force               ``mu omega R0^4 / c^2``      N
flow                ``omega R0^2 c``             m^3/s
friction moment     ``mu omega R0^4 / c``        N m
friction power      ``mu omega^2 R0^4 / c``      W
film thickness      ``c``                        m
length (phi, z)     ``R0``                       m
time                ``1 / omega`` per radian     s
==================  ==========================  ===========
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["MIN_CLEARANCE_RATIO", "SCALE_FIELDS", "Scale", "scale_of"]

#: Smallest clearance ratio ``c / R0`` [-]: below it the scales (``R0^2 / c^2``) leave the range of floating
#: point (``c = 1e-300`` m gave "float division by zero", ``D = 1e15`` m degenerate film outlines).
MIN_CLEARANCE_RATIO = 1e-7


@dataclass(frozen=True)
class Scale:
    """Scales of a bearing support.

    Parameters
    ----------
    radius : float
        Journal (eccentric) radius ``R0`` [m], > 0.
    clearance : float
        Radial clearance ``c`` [m], 0 < c < radius.
    viscosity : float
        Dynamic viscosity ``mu`` [Pa s], > 0.
    speed : float
        Shaft angular speed ``omega`` [rad/s], > 0.
    """

    radius: float
    clearance: float
    viscosity: float
    speed: float

    def __post_init__(self) -> None:
        for name in ("radius", "clearance", "viscosity", "speed"):
            value = float(getattr(self, name))
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"Scale.{name} must be a finite number > 0, got {getattr(self, name)!r}")
            object.__setattr__(self, name, value)
        if self.clearance >= self.radius:
            raise ValueError(f"Scale.clearance must be smaller than radius ({self.radius} m), got {self.clearance}")
        if not self.clearance >= MIN_CLEARANCE_RATIO * self.radius:
            raise ValueError(f"Scale.clearance must be at least {MIN_CLEARANCE_RATIO:g} of the radius "
                             f"({self.radius:g} m; real bearings have c/R of 1e-4 or more), got {self.clearance!r}")
        for name in ("pressure", "force", "flow", "moment", "power"):
            try:
                value = getattr(self, name)
            except (OverflowError, ZeroDivisionError):  # float ** overflows with an error, not to inf
                value = math.inf
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"Scale: radius = {self.radius:g} m, clearance = {self.clearance:g} m, viscosity = "
                                 f"{self.viscosity:g} Pa s and speed = {self.speed:g} rad/s give a {name} scale of "
                                 f"{value!r}, not a finite number > 0: the inputs are out of scale")

    @property
    def pressure(self) -> float:
        """Pressure scale ``mu omega R0^2 / c^2`` [Pa]."""
        return self.viscosity * self.speed * self.radius**2 / self.clearance**2

    @property
    def force(self) -> float:
        """Force scale ``mu omega R0^4 / c^2`` [N]."""
        return self.pressure * self.radius**2

    @property
    def flow(self) -> float:
        """Flow scale ``omega R0^2 c`` [m^3/s]."""
        return self.speed * self.radius**2 * self.clearance

    @property
    def moment(self) -> float:
        """Friction-moment scale ``mu omega R0^4 / c`` [N m]."""
        return self.viscosity * self.speed * self.radius**4 / self.clearance

    @property
    def power(self) -> float:
        """Friction-power scale ``mu omega^2 R0^4 / c`` [W]."""
        return self.moment * self.speed

    def to_pressure(self, p: float) -> float:
        """Non-dimensional pressure -> Pa."""
        return p * self.pressure

    def from_pressure(self, pressure_pa: float) -> float:
        """Pa -> non-dimensional pressure."""
        return pressure_pa / self.pressure

    def to_force(self, f: float) -> float:
        """Non-dimensional force -> N."""
        return f * self.force

    def from_force(self, force_n: float) -> float:
        """N -> non-dimensional force."""
        return force_n / self.force

    def to_flow(self, q: float) -> float:
        """Non-dimensional flow -> m^3/s."""
        return q * self.flow

    def to_moment(self, m: float) -> float:
        """Non-dimensional friction moment -> N m."""
        return m * self.moment

    def to_thickness(self, h: float) -> float:
        """Non-dimensional film thickness -> m."""
        return h * self.clearance


def _scale_fields() -> dict:
    from .schema import positive_number

    return {"radius": (positive_number, None, "eccentric (journal) radius R0 [m]"),
            "clearance": (positive_number, None, "radial clearance c [m]"),
            "viscosity": (positive_number, None, "oil dynamic viscosity [Pa s]"),
            "speed_rpm": (positive_number, None, "shaft speed [rpm] (or omega)"),
            "omega": (positive_number, None, "shaft angular speed [rad/s] (or speed_rpm)")}


#: The ``[scale]`` table of the input files that report a non-dimensional problem in SI (the ``"reynolds"``
#: scene, shoe studies): ``{name: (check, default, meaning)}`` (:mod:`bearingfe.core.schema`); read with
#: :func:`scale_of`.
SCALE_FIELDS = _scale_fields()


def scale_of(table: dict, label: str) -> Scale:
    """The :class:`Scale` of a checked ``[scale]`` table (:data:`SCALE_FIELDS`): all of radius, clearance and
    viscosity, and exactly one of ``speed_rpm`` and ``omega``; errors name the file ``label`` and the field."""
    from .machine import Drive
    from .schema import SchemaError, build

    for name in ("radius", "clearance", "viscosity"):
        if table[name] is None:
            raise SchemaError(f"{label}: [scale] {name}: missing (required with [scale])")
    if (table["speed_rpm"] is None) == (table["omega"] is None):
        raise SchemaError(f"{label}: [scale] speed_rpm/omega: give exactly one (speed_rpm [rpm] or omega [rad/s])")
    omega = Drive.from_rpm(table["speed_rpm"]).omega if table["speed_rpm"] is not None else table["omega"]
    return build(label, "scale", Scale, radius=table["radius"], clearance=table["clearance"],
                 viscosity=table["viscosity"], speed=omega)
