"""Parameter objects every machine shares (SI units, frozen, validated): its drive and its materials.

:class:`Drive` is the operating point of a machine (the shaft speed);
:class:`Material` an elastic material. Bearings (the pump's shoe, its elastic
support) and mechanisms (cranks, rotors) take them alike, so they live below both.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .schema import finite, nonnegative, positive

__all__ = ["Drive", "Material"]


@dataclass(frozen=True)
class Drive:
    """Operating point: constant angular speed of the driving shaft.

    Parameters
    ----------
    omega : float
        Shaft angular speed [rad/s], > 0.
    """

    omega: float

    def __post_init__(self) -> None:
        positive("omega", self.omega, "rad/s")

    @classmethod
    def from_rpm(cls, rpm: float) -> "Drive":
        """Drive from a speed in revolutions per minute (> 0)."""
        positive("speed_rpm", rpm, "rpm")
        return cls(omega=2.0 * math.pi * float(rpm) / 60.0)

    @property
    def rpm(self) -> float:
        """Shaft speed [1/min]."""
        return self.omega * 60.0 / (2.0 * math.pi)

    @property
    def period(self) -> float:
        """Time of one revolution [s]."""
        return 2.0 * math.pi / self.omega


@dataclass(frozen=True)
class Material:
    """Elastic material.

    Parameters
    ----------
    name : str
        Label.
    youngs_modulus : float
        Young's modulus E [Pa], > 0.
    density : float
        Density [kg/m^3], >= 0 (0 if not needed).
    poisson_ratio : float
        Poisson's ratio nu [-], in (-1, 0.5); 0.3 (steel) by default.
    """

    name: str
    youngs_modulus: float
    density: float = 0.0
    poisson_ratio: float = 0.3

    def __post_init__(self) -> None:
        positive("youngs_modulus", self.youngs_modulus, "Pa")
        nonnegative("density", self.density, "kg/m^3")
        nu = finite("poisson_ratio", self.poisson_ratio)
        if not -1.0 < nu < 0.5:
            raise ValueError(f"poisson_ratio must be in (-1, 0.5), got {self.poisson_ratio!r}")
