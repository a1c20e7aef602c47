r"""Lubricants: viscosity-temperature laws, density and specific heat of petroleum oils (SI, frozen, validated).

Temperatures are absolute [K], dynamic viscosities [Pa s], kinematic
viscosities [m^2/s], densities [kg/m^3], specific heats [J/(kg K)].

Viscosity-temperature laws (:data:`VISCOSITY_LAWS`, one protocol: ``dynamic(T, density)``):

- :class:`ConstantViscosity`: ``mu`` independent of temperature (the isoviscous model of every
  other solver of the package).
- :class:`VogelViscosity`: ``mu = a exp(b / (T - c))`` (Vogel 1921); :meth:`VogelViscosity.through`
  fits it through three measured points in closed form.
- :class:`WaltherViscosity`: ASTM D341, ``log10 log10(nu + 0.7) = A - B log10 T`` with ``nu`` in
  mm^2/s and ``T`` in K; :meth:`WaltherViscosity.through` fits it through two kinematic viscosities
  (the 0.7 form holds for ``nu >= 2 mm^2/s``; D341's extra terms for thinner oils are not used).

ISO viscosity grades (:data:`ISO_VG`): the ISO 3448 mid-point kinematic viscosities at 40 degC (each
grade spans +-10 % about it). :func:`iso_vg` makes a Walther lubricant of a grade through its 40 degC
mid-point and a 100 degC viscosity that the caller gives (from the oil's data sheet, or from a
viscosity index by :func:`bearingfe.thermal.viscosity_index.viscosity_100`, ASTM D2270).

Density: linear in temperature, ``rho(T) = rho_ref - gamma (T - T_ref)``. The slope ``gamma``
[kg/(m^3 K)] defaults to the average temperature correction of petroleum products of GOST 3900-85
(Mendeleev's correlation): ``gamma = 1.828 - 1.32e-3 rho_20`` with ``rho_20`` the density at 20 degC
[kg/m^3] (0.686 kg/(m^3 K) for ``rho_20 = 865``, about 0.08 %/K).

Specific heat: Cragoe's correlation for petroleum oils (C. S. Cragoe, *Thermal properties of
petroleum products*, U.S. Bureau of Standards Miscellaneous Publication 97, 1929):
``c = (0.388 + 0.00045 t_F) / sqrt(s)`` Btu/(lb degF) with ``t_F`` in degF and ``s`` the specific
gravity at 60/60 degF, i.e. ``c_p = (1684.8 + 3.3913 (T - 273.15)) / sqrt(s)`` J/(kg K)
(1 Btu/(lb degF) = 4186.8 J/(kg K)); ``s`` is taken as ``rho(15.56 degC) / 999.0``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType
from typing import Mapping, Protocol, runtime_checkable

import numpy as np

from ..core.schema import Range, finite, in_range, positive

__all__ = ["ViscosityLaw", "ConstantViscosity", "VogelViscosity", "WaltherViscosity", "VISCOSITY_LAWS", "ISO_VG",
           "Lubricant", "iso_vg", "celsius", "kelvin", "gost_density_slope", "cragoe_specific_heat"]

#: 0 degC [K].
ZERO_CELSIUS = 273.15
#: The temperature of petroleum densities (15 degC) [K].
REFERENCE_TEMPERATURE = 288.15
#: Density of water at 60 degF [kg/m^3] (specific gravity 60/60 degF of Cragoe's correlation).
WATER_60F = 999.0
#: Offset of the Walther (ASTM D341) double logarithm [mm^2/s].
WALTHER_SHIFT = 0.7

_TEMPERATURE = Range(0.0, lo_open=True)


def kelvin(celsius_value: float) -> float:
    """Temperature [degC] -> [K]."""
    return float(celsius_value) + ZERO_CELSIUS


def celsius(kelvin_value: float) -> float:
    """Temperature [K] -> [degC]."""
    return float(kelvin_value) - ZERO_CELSIUS


def _temperature(name: str, value) -> float:
    return in_range(name, value, _TEMPERATURE, "K")


def _temperatures(value) -> np.ndarray:
    """An array of absolute temperatures [K], each finite and > 0."""
    t = np.asarray(value, dtype=float)
    if not (np.all(np.isfinite(t)) and np.all(t > 0)):
        raise ValueError(f"temperature must be finite and > 0 K everywhere, got min {np.nanmin(t)!r}")
    return t


@runtime_checkable
class ViscosityLaw(Protocol):
    """A viscosity-temperature law: ``dynamic(T, density)`` [Pa s] at ``T`` [K] for an oil of that
    density [kg/m^3] (laws of the kinematic viscosity multiply by it; the others ignore it)."""

    def dynamic(self, temperature: float, density: float) -> float:  # pragma: no cover - protocol
        ...


@dataclass(frozen=True)
class ConstantViscosity:
    """A viscosity independent of temperature (the isoviscous model).

    Parameters
    ----------
    viscosity : float
        Dynamic viscosity ``mu`` [Pa s], > 0.
    """

    viscosity: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "viscosity", positive("ConstantViscosity.viscosity", self.viscosity, "Pa s"))

    def dynamic(self, temperature: float, density: float) -> float:
        """``mu`` [Pa s] whatever the temperature."""
        _temperature("temperature", temperature)
        return self.viscosity

    def dynamic_field(self, temperature: np.ndarray, density: np.ndarray) -> np.ndarray:
        """:meth:`dynamic` over an array of temperatures [K] (checked > 0)."""
        return np.full(_temperatures(temperature).shape, self.viscosity)


@dataclass(frozen=True)
class VogelViscosity:
    """Vogel's law ``mu = a exp(b / (T - c))``.

    Parameters
    ----------
    a : float
        Viscosity factor [Pa s], > 0.
    b : float
        Temperature factor [K], > 0.
    c : float
        Temperature offset [K], in [0, 400): the law holds for ``T > c``.
    """

    a: float
    b: float
    c: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "a", positive("VogelViscosity.a", self.a, "Pa s"))
        object.__setattr__(self, "b", positive("VogelViscosity.b", self.b, "K"))
        object.__setattr__(self, "c", in_range("VogelViscosity.c", self.c, Range(0.0, 400.0, hi_open=True), "K"))

    def dynamic(self, temperature: float, density: float = math.nan) -> float:
        """``mu(T)`` [Pa s]; ``T`` [K] must exceed ``c``."""
        t = _temperature("temperature", temperature)
        if not t > self.c:
            raise ValueError(f"temperature must be > VogelViscosity.c = {self.c:g} K, got {temperature!r}")
        return self.a * math.exp(self.b / (t - self.c))

    def dynamic_field(self, temperature: np.ndarray, density: np.ndarray | None = None) -> np.ndarray:
        """:meth:`dynamic` over an array of temperatures [K] (each must exceed ``c``)."""
        t = _temperatures(temperature)
        if not np.all(t > self.c):
            raise ValueError(f"temperature must be > VogelViscosity.c = {self.c:g} K, got min {t.min()!r}")
        return self.a * np.exp(self.b / (t - self.c))

    @classmethod
    def through(cls, *points: tuple[float, float]) -> "VogelViscosity":
        """The Vogel law through three points ``(T [K], mu [Pa s])`` with distinct temperatures and
        viscosities falling as the temperature rises (closed form: ``c`` from the ratio of the
        logarithmic differences, then ``b`` and ``a``).

        Raises
        ------
        ValueError
            Not three such points, or no Vogel law with ``b > 0`` and ``0 <= c < min(T)`` fits them.
        """
        if len(points) != 3:
            raise ValueError(f"VogelViscosity.through needs three points (T [K], mu [Pa s]), got {len(points)}")
        pts = sorted((_temperature(f"points[{k}][0]", t), positive(f"points[{k}][1]", m, "Pa s"))
                     for k, (t, m) in enumerate(points))
        (t1, m1), (t2, m2), (t3, m3) = pts
        if not (t1 < t2 < t3 and m1 > m2 > m3):
            raise ValueError("VogelViscosity.through needs distinct temperatures with the viscosity falling as "
                             f"the temperature rises, got {points!r}")
        r = math.log(m1 / m2) / math.log(m2 / m3)
        den = (t2 - t1) - r * (t3 - t2)
        if den == 0:
            raise ValueError(f"VogelViscosity.through: no Vogel law (c at infinity) fits {points!r}")
        c = ((t2 - t1) * t3 - r * (t3 - t2) * t1) / den
        if not 0 <= c < t1:
            raise ValueError(f"VogelViscosity.through: the fit needs c = {c:.6g} K, outside [0, {t1:g}) K")
        b = math.log(m1 / m3) / (1 / (t1 - c) - 1 / (t3 - c))
        return cls(a=m1 / math.exp(b / (t1 - c)), b=b, c=c)


@dataclass(frozen=True)
class WaltherViscosity:
    """Walther's law (ASTM D341): ``log10 log10(nu + 0.7) = A - B log10 T``, ``nu`` [mm^2/s], ``T`` [K].

    Parameters
    ----------
    A : float
        Intercept [-], finite.
    B : float
        Slope [-], > 0 (the viscosity falls as the temperature rises).
    """

    A: float
    B: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "A", finite("WaltherViscosity.A", self.A))
        object.__setattr__(self, "B", positive("WaltherViscosity.B", self.B))

    def kinematic(self, temperature: float) -> float:
        """Kinematic viscosity [m^2/s] at ``T`` [K]."""
        t = _temperature("temperature", temperature)
        return (10.0 ** (10.0 ** (self.A - self.B * math.log10(t))) - WALTHER_SHIFT) * 1e-6

    def dynamic(self, temperature: float, density: float) -> float:
        """Dynamic viscosity ``nu(T) rho`` [Pa s] for an oil of density ``rho`` [kg/m^3] at ``T``."""
        return self.kinematic(temperature) * positive("density", density, "kg/m^3")

    def dynamic_field(self, temperature: np.ndarray, density: np.ndarray) -> np.ndarray:
        """:meth:`dynamic` over arrays of temperatures [K] and densities [kg/m^3] (the same formula)."""
        t = _temperatures(temperature)
        return (10.0 ** (10.0 ** (self.A - self.B * np.log10(t))) - WALTHER_SHIFT) * 1e-6 * np.asarray(density)

    @classmethod
    def through(cls, first: tuple[float, float], second: tuple[float, float]) -> "WaltherViscosity":
        """The law through two points ``(T [K], nu [m^2/s])`` (exactly, to round-off).

        Raises
        ------
        ValueError
            Equal temperatures, a viscosity below 2 mm^2/s (where the 0.7 form of D341 does not
            hold), or a viscosity that does not fall as the temperature rises.
        """
        (t1, n1), (t2, n2) = sorted((_temperature(f"point[{k}] temperature", t),
                                     positive(f"point[{k}] kinematic viscosity", n, "m^2/s"))
                                    for k, (t, n) in enumerate((first, second)))
        for n in (n1, n2):
            if n < 2e-6:
                raise ValueError(f"WaltherViscosity.through: kinematic viscosity must be >= 2e-06 m^2/s "
                                 f"(the range of the ASTM D341 0.7 form), got {n!r}")
        if not (t1 < t2 and n1 > n2):
            raise ValueError("WaltherViscosity.through needs two temperatures with the viscosity falling as "
                             f"the temperature rises, got {first!r}, {second!r}")
        z1, z2 = (math.log10(math.log10(n * 1e6 + WALTHER_SHIFT)) for n in (n1, n2))
        B = (z1 - z2) / (math.log10(t2) - math.log10(t1))
        return cls(A=z1 + B * math.log10(t1), B=B)


#: Viscosity-temperature laws by name (the ``[oil]`` table of scene files chooses among them).
VISCOSITY_LAWS: Mapping[str, type] = MappingProxyType({
    "constant": ConstantViscosity, "vogel": VogelViscosity, "walther": WaltherViscosity})

#: ISO 3448 viscosity grades: mid-point kinematic viscosity at 40 degC [m^2/s] (limits +-10 %).
ISO_VG: Mapping[str, float] = MappingProxyType({
    "VG 2": 2.2e-6, "VG 3": 3.2e-6, "VG 5": 4.6e-6, "VG 7": 6.8e-6,
    **{f"VG {g}": g * 1e-6 for g in (10, 15, 22, 32, 46, 68, 100, 150, 220, 320, 460, 680, 1000, 1500, 2200, 3200)}})


def gost_density_slope(density_20: float) -> float:
    """Fall of the density per kelvin [kg/(m^3 K)] of a petroleum product of density ``rho_20``
    [kg/m^3] at 20 degC: ``1.828 - 1.32e-3 rho_20`` (GOST 3900-85, average temperature corrections)."""
    rho = in_range("density_20", density_20, Range(600.0, 1100.0), "kg/m^3")
    return 1.828 - 1.32e-3 * rho


def cragoe_specific_heat(temperature: float, specific_gravity: float) -> float:
    """Cragoe's specific heat of a petroleum oil [J/(kg K)] at ``T`` [K] and specific gravity
    ``s`` (60/60 degF) [-]: ``(1684.8 + 3.3913 (T - 273.15)) / sqrt(s)``."""
    t = _temperature("temperature", temperature)
    s = in_range("specific_gravity", specific_gravity, Range(0.6, 1.1), "")
    return (1684.8 + 3.3913 * (t - ZERO_CELSIUS)) / math.sqrt(s)


@dataclass(frozen=True)
class Lubricant:
    """A lubricating oil: its viscosity law, density and specific heat (SI).

    Parameters
    ----------
    viscosity_law : ViscosityLaw
        One of :data:`VISCOSITY_LAWS` (or any object with ``dynamic(T, density)``).
    density : float
        Density ``rho_ref`` at ``reference_temperature`` [kg/m^3], in [600, 1100].
    reference_temperature : float
        Temperature of ``density`` [K], > 0; 15 degC by default.
    density_slope : float, optional
        Fall of the density per kelvin ``gamma`` [kg/(m^3 K)], in [0, 3]; ``None``: GOST 3900-85
        (:func:`gost_density_slope`).
    specific_heat : float, optional
        A constant specific heat [J/(kg K)], in [500, 5000]; ``None``: Cragoe's correlation
        (:func:`cragoe_specific_heat`).
    name : str
        Label.

    Raises
    ------
    ValueError
        A value outside its range; the message names the field.
    """

    viscosity_law: ViscosityLaw
    density: float = 870.0
    reference_temperature: float = REFERENCE_TEMPERATURE
    density_slope: float | None = None
    specific_heat: float | None = None
    name: str = "oil"

    def __post_init__(self) -> None:
        if not isinstance(self.viscosity_law, ViscosityLaw):
            raise ValueError(f"Lubricant.viscosity_law must have dynamic(T, density), got {self.viscosity_law!r}")
        object.__setattr__(self, "density", in_range("Lubricant.density", self.density, Range(600.0, 1100.0),
                                                     "kg/m^3"))
        object.__setattr__(self, "reference_temperature",
                           _temperature("Lubricant.reference_temperature", self.reference_temperature))
        if self.density_slope is None:
            # the GOST slope is of the density at 20 degC: solve rho_20 = rho_ref - gamma (20 degC - T_ref)
            dt = kelvin(20.0) - self.reference_temperature
            slope = (1.828 - 1.32e-3 * self.density) / (1 - 1.32e-3 * dt)
            gost_density_slope(self.density - slope * dt)  # the correlation's range
            object.__setattr__(self, "density_slope", slope)
        else:
            object.__setattr__(self, "density_slope", in_range("Lubricant.density_slope", self.density_slope,
                                                               Range(0.0, 3.0), "kg/(m^3 K)"))
        if self.specific_heat is not None:
            object.__setattr__(self, "specific_heat", in_range("Lubricant.specific_heat", self.specific_heat,
                                                               Range(500.0, 5000.0), "J/(kg K)"))

    def density_at(self, temperature: float) -> float:
        """Density [kg/m^3] at ``T`` [K]."""
        t = _temperature("temperature", temperature)
        rho = self.density - self.density_slope * (t - self.reference_temperature)
        if not rho > 0:
            raise ValueError(f"temperature {temperature!r} K is beyond the linear density law of {self.name!r}")
        return rho

    def specific_heat_at(self, temperature: float) -> float:
        """Specific heat [J/(kg K)] at ``T`` [K]."""
        if self.specific_heat is not None:
            _temperature("temperature", temperature)
            return self.specific_heat
        return cragoe_specific_heat(temperature, self.density_at(kelvin(15.56)) / WATER_60F)

    def viscosity(self, temperature: float) -> float:
        """Dynamic viscosity [Pa s] at ``T`` [K]."""
        return self.viscosity_law.dynamic(temperature, self.density_at(temperature))

    def viscosity_field(self, temperature) -> np.ndarray:
        """Dynamic viscosity [Pa s] over an array of temperatures [K] (a film's field): the law's
        ``dynamic_field`` when it has one (the formula of :meth:`viscosity` on arrays, equal to round-off),
        else :meth:`viscosity` point by point."""
        t = _temperatures(temperature)
        rho = self.density - self.density_slope * (t - self.reference_temperature)
        if not np.all(rho > 0):
            raise ValueError(f"temperature {t.max()!r} K is beyond the linear density law of {self.name!r}")
        field = getattr(self.viscosity_law, "dynamic_field", None)
        if field is not None:
            return np.asarray(field(t, rho), dtype=float)
        return np.vectorize(self.viscosity, otypes=[float])(t)

    def kinematic_viscosity(self, temperature: float) -> float:
        """Kinematic viscosity [m^2/s] at ``T`` [K]."""
        return self.viscosity(temperature) / self.density_at(temperature)

    def temperature_at(self, viscosity: float, low: float = 250.0, high: float = 473.15) -> float:
        """The temperature [K] in ``[low, high]`` at which the oil has the dynamic ``viscosity`` [Pa s].

        Raises
        ------
        ValueError
            The viscosity is not reached between ``low`` and ``high`` (the message gives the range).
        """
        from scipy.optimize import brentq

        mu = positive("viscosity", viscosity, "Pa s")
        lo, hi = _temperature("low", low), _temperature("high", high)
        ends = (self.viscosity(lo) - mu, self.viscosity(hi) - mu)
        if ends[0] * ends[1] > 0:
            raise ValueError(f"viscosity must be in [{self.viscosity(hi):.4g}, {self.viscosity(lo):.4g}] Pa s "
                             f"(the oil {self.name!r} between {lo:g} and {hi:g} K), got {viscosity!r}")
        return float(brentq(lambda t: self.viscosity(t) - mu, lo, hi, xtol=1e-10, rtol=1e-14))


def iso_vg(grade: str, viscosity_100: float, **properties) -> Lubricant:
    """An oil of an ISO 3448 grade: Walther through the grade's 40 degC mid-point and ``viscosity_100``.

    Parameters
    ----------
    grade : str
        A key of :data:`ISO_VG` (``"VG 32"``).
    viscosity_100 : float
        Kinematic viscosity at 100 degC [m^2/s] (the oil's data sheet), in [2e-6, nu_40).
    **properties
        ``density``, ``reference_temperature``, ``density_slope``, ``specific_heat`` of :class:`Lubricant`.
    """
    if grade not in ISO_VG:
        raise ValueError(f"grade must be one of {', '.join(repr(g) for g in ISO_VG)}, got {grade!r}")
    nu40 = ISO_VG[grade]
    nu100 = in_range("viscosity_100", viscosity_100, Range(2e-6, nu40, hi_open=True), "m^2/s")
    law = WaltherViscosity.through((kelvin(40.0), nu40), (kelvin(100.0), nu100))
    return Lubricant(law, name=f"ISO {grade}", **properties)
