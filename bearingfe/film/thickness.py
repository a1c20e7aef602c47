"""Film-thickness models.

A film gives the non-dimensional thickness ``h = H / c`` over the surface,
its derivatives, and how it changes with its own state variables (for the
squeeze term of the Reynolds equation). Any object with these methods works
as a film (see :class:`Film`).

The models shipped here:

=========================  ===========================================================================
model                      the film
=========================  ===========================================================================
:class:`CosineFilm`        the rigid eccentric journal in a circular bore
:class:`UniformFilm`       parallel surfaces (a flat slider, a squeeze film)
:class:`TaperFilm`         an inclined plane along any direction (the inclined slider)
:class:`TaperLandFilm`     a taper down to a flat land (the taper-land pad)
:class:`ProfileFilm`       any piecewise-linear profile along a direction, steps allowed
                           (a Rayleigh step, several lands and tapers)
:class:`StepFilm`          a base film deepened by a constant over a region of any outline
:class:`SumFilm`           a base film plus static additions (``film + other`` makes one)
:class:`PlaneFilm`         a flat pad tilted over a flat runner (a thrust pad: pivot film, pitch, roll)
:class:`PolarProfileFilm`  a profile along the angle or the radius about a centre, steps allowed
                           (a thrust pad's taper-land or Rayleigh step)
=========================  ===========================================================================

Films with a kink or a step (``smooth = False``) have no Laplacian as a
function, which the substituted ``pi`` form needs: the solvers then use the
direct form and say so. Their steps are exact in the direct form, because the
wedge source is integrated by parts (:func:`bearingfe.film.forms.couette_source`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, Sequence, runtime_checkable

import numpy as np

from ..core.blocks import blocks
from ..core.checks import MAX_GAMMA, check_angle

__all__ = ["Film", "CosineFilm", "UniformFilm", "TaperFilm", "TaperLandFilm", "ProfileFilm", "StepFilm", "SumFilm",
           "PlaneFilm", "PolarProfileFilm",
           "is_smooth", "smallest_film"]


@runtime_checkable
class Film(Protocol):
    """What the Reynolds solvers need from a film model.

    All methods take arrays ``phi`` [rad] and ``z`` [-] of equal shape.
    """

    def thickness(self, phi: np.ndarray, z: np.ndarray) -> np.ndarray:
        """``h`` [-]."""

    def gradient(self, phi: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(dh/dphi, dh/dz)``."""

    def laplacian(self, phi: np.ndarray, z: np.ndarray) -> np.ndarray:
        """``d2h/dphi2 + d2h/dz2``."""

    def rate_shapes(self, phi: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, ...]:
        """``dh/dq_k`` for each state variable ``q_k``: the squeeze term is
        ``dh/dt = sum_k qdot_k * dh/dq_k``."""

    def minimum(self, phi_range: tuple[float, float]) -> float | None:
        """Exact smallest ``h`` over ``phi_range`` if known, else None."""

    # Optional, not part of the protocol: ``smooth`` (bool, default True): False for a film with a
    # kink or a step, whose Laplacian is no function (see is_smooth). ``fields_from_angles(cos_phi, sin_phi)`` returning
    # ``(h, (dh/dphi, dh/dz), laplacian, shapes)`` at points whose angles' cosines and sines are
    # given (:meth:`CosineFilm.fields_from_angles`); :func:`bearingfe.film.forms.film_at` uses it when
    # the caller passes them, which spares the trigonometric calls of every film state.


class _Addable:
    """``film + other``: the :class:`SumFilm` of a base film and a static addition."""

    smooth = True

    def __add__(self, other) -> "SumFilm":
        if not isinstance(other, Film):
            return NotImplemented
        return SumFilm(self, (other,))


def is_smooth(film) -> bool:
    """True if the film has a Laplacian as a function (no kink, no step): ``film.smooth``, default True."""
    return bool(getattr(film, "smooth", True))


@dataclass(frozen=True)
class CosineFilm(_Addable):
    """Rigid journal in a circular bore: ``h = 1 + gamma cos(phi - phi0)``.

    Parameters
    ----------
    gamma : float
        Relative eccentricity of the bore centre [-], in ``[0, 1000]``
        (:data:`bearingfe.core.checks.MAX_GAMMA`). On a partial arc it may exceed
        1 as long as ``h > 0`` over the arc (checked by the solvers on the
        actual surface).
    phi0 : float
        Angle of the line of centres [rad]: where the film is thickest;
        ``|phi0| <= 1e6`` (:data:`bearingfe.core.checks.MAX_ANGLE`: beyond, the
        angle has no digits left for ``cos(phi - phi0)``).

    Notes
    -----
    The state variables are ``(gamma, phi0)``, so the squeeze shapes are
    ``dh/dgamma = cos(phi - phi0)`` and ``dh/dphi0 = gamma sin(phi - phi0)``.
    """

    gamma: float
    phi0: float = 0.0

    def __post_init__(self) -> None:
        gamma = float(self.gamma)
        if not (math.isfinite(gamma) and 0.0 <= gamma <= MAX_GAMMA):
            raise ValueError(f"CosineFilm.gamma must be a number in [0, {MAX_GAMMA:g}] (beyond, the film is "
                             f"thousands of clearances thick: not a thin film), got {self.gamma!r}")
        phi0 = check_angle(self.phi0, "CosineFilm.phi0")
        object.__setattr__(self, "gamma", gamma)
        object.__setattr__(self, "phi0", phi0)

    def thickness(self, phi, z):
        return 1.0 + self.gamma * np.cos(np.asarray(phi) - self.phi0) + 0.0 * np.asarray(z)

    def gradient(self, phi, z):
        dphi = -self.gamma * np.sin(np.asarray(phi) - self.phi0) + 0.0 * np.asarray(z)
        return dphi, np.zeros_like(dphi)

    def laplacian(self, phi, z):
        return -self.gamma * np.cos(np.asarray(phi) - self.phi0) + 0.0 * np.asarray(z)

    def rate_shapes(self, phi, z):
        s = np.asarray(phi) - self.phi0 + 0.0 * np.asarray(z)
        return np.cos(s), self.gamma * np.sin(s)

    def fields_from_angles(self, cos_phi: np.ndarray, sin_phi: np.ndarray):
        """``h``, ``(dh/dphi, dh/dz)``, the Laplacian and the squeeze shapes from ``cos phi`` and
        ``sin phi`` of the points (no trigonometric call: a mesh computes those once).

        ``cos(phi - phi0) = cos phi cos phi0 + sin phi sin phi0`` and
        ``sin(phi - phi0) = sin phi cos phi0 - cos phi sin phi0``, so the
        fields equal those of :meth:`thickness` and the others to round-off.
        Used by :func:`bearingfe.film.forms.film_at` when given the angles.
        """
        c0, s0 = math.cos(self.phi0), math.sin(self.phi0)
        c = cos_phi * c0 + sin_phi * s0
        s = sin_phi * c0 - cos_phi * s0
        gs = self.gamma * s
        gc = self.gamma * c
        return 1.0 + gc, (-gs, np.zeros_like(c)), -gc, (c, gs)

    def minimum(self, phi_range: tuple[float, float]) -> float:
        """Smallest ``h`` for ``phi`` in ``phi_range`` (the thinnest point may
        lie at an end of the range on a partial arc)."""
        lo, hi = phi_range
        # cos(phi - phi0) is smallest at phi = phi0 + pi (mod 2 pi) if it is in range
        k = math.ceil((lo - self.phi0 - math.pi) / (2 * math.pi))
        if self.phi0 + math.pi + 2 * math.pi * k <= hi:
            return 1.0 - self.gamma
        return float(min(self.thickness(np.array([lo, hi]), np.zeros(2))))


@dataclass(frozen=True)
class UniformFilm(_Addable):
    """Parallel surfaces: ``h`` the same everywhere (a flat slider, or a squeeze film).

    Parameters
    ----------
    h : float
        Film thickness [-], > 0. The state variable is ``h`` itself, so the
        squeeze shapes are ``(1, 0)``: ``squeeze=(dh/dt, 0)``.
    """

    h: float

    def __post_init__(self) -> None:
        h = float(self.h)
        if not (math.isfinite(h) and h > 0.0):
            raise ValueError(f"UniformFilm.h must be a finite number > 0, got {self.h!r}")
        object.__setattr__(self, "h", h)

    def thickness(self, phi, z):
        return self.h + 0.0 * np.asarray(phi, float) + 0.0 * np.asarray(z, float)

    def gradient(self, phi, z):
        zero = 0.0 * np.asarray(phi, float) + 0.0 * np.asarray(z, float)
        return zero, zero

    def laplacian(self, phi, z):
        return 0.0 * np.asarray(phi, float) + 0.0 * np.asarray(z, float)

    def rate_shapes(self, phi, z):
        zero = 0.0 * np.asarray(phi, float) + 0.0 * np.asarray(z, float)
        return zero + 1.0, zero

    def minimum(self, phi_range: tuple[float, float]) -> float:
        return self.h



def _zeros(phi, z) -> np.ndarray:
    return 0.0 * np.asarray(phi, float) + 0.0 * np.asarray(z, float)


def _positive_film(name: str, value) -> float:
    value = float(value)
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"{name} must be a finite film thickness > 0 [c], got {value!r}")
    return value


class _Profile(_Addable):
    """A film that varies along one direction only: ``h = profile(s)``, ``s = (phi, z) . (cos a, sin a)``.

    Subclasses give :meth:`knots` (abscissae ``s`` and thicknesses, piecewise linear
    between them, constant beyond the ends unless :attr:`extend` is True) and
    ``direction`` (the angle ``a`` [rad] of the direction in the ``(phi, z)`` plane,
    0: along the sliding). The state variable is a uniform change of the film, so the
    squeeze shapes are ``(1, 0)``: ``squeeze = (dh/dt, 0)``.
    """

    extend = False

    def knots(self) -> tuple[np.ndarray, np.ndarray]:  # pragma: no cover - every subclass defines it
        raise NotImplementedError

    def _s(self, phi, z) -> np.ndarray:
        a = float(self.direction)
        return np.asarray(phi, float) * math.cos(a) + np.asarray(z, float) * math.sin(a)

    def thickness(self, phi, z):
        s, h = self.knots()
        x = self._s(phi, z)
        if self.extend:  # one straight segment, extended: an inclined plane
            return h[0] + (h[1] - h[0]) * (x - s[0]) / (s[1] - s[0])
        return _interpolate(x, s, h)

    def _slope(self, x: np.ndarray) -> np.ndarray:
        s, h = self.knots()
        if self.extend:
            return np.full(np.shape(x), (h[1] - h[0]) / (s[1] - s[0]))
        return _piecewise_slope(x, s, h)

    def gradient(self, phi, z):
        g = self._slope(self._s(phi, z)) + _zeros(phi, z)
        a = float(self.direction)
        return g * math.cos(a), g * math.sin(a)

    def laplacian(self, phi, z):
        return _zeros(phi, z)

    def rate_shapes(self, phi, z):
        zero = _zeros(phi, z)
        return zero + 1.0, zero

    def minimum(self, phi_range: tuple[float, float]) -> float | None:
        """Exact when the profile runs along ``phi`` (``direction = 0``); None otherwise."""
        if float(self.direction) != 0.0:
            return None
        s, h = self.knots()
        lo, hi = phi_range
        inside = (s > lo) & (s < hi)
        ends = self.thickness(np.array([lo, hi]), np.zeros(2))
        return float(min(np.min(ends), np.min(h[inside], initial=np.inf)))


@dataclass(frozen=True)
class TaperFilm(_Profile):
    """An inclined plane: ``h_in`` at ``s = start`` falling linearly to ``h_out`` at ``s = end`` (the
    inclined-slider pad), extended linearly beyond.

    Parameters
    ----------
    h_in, h_out : float
        Film at ``start`` and at ``end`` [c], > 0.
    start, end : float
        Abscissae along the direction [-] (``phi`` [rad] for ``direction = 0``), ``start != end``.
    direction : float
        Angle of the taper's direction in the ``(phi, z)`` plane [rad]; 0 runs along the sliding.

    Notes
    -----
    The plane has no kink, so it is smooth (``laplacian = 0``). A plane that
    reaches ``h <= 0`` on the surface is refused by the solvers.
    """

    h_in: float
    h_out: float
    start: float = 0.0
    end: float = 1.0
    direction: float = 0.0
    extend = True

    def __post_init__(self) -> None:
        object.__setattr__(self, "h_in", _positive_film("TaperFilm.h_in", self.h_in))
        object.__setattr__(self, "h_out", _positive_film("TaperFilm.h_out", self.h_out))
        _check_abscissae("TaperFilm", (self.start, self.end), strict=True)
        object.__setattr__(self, "direction", check_angle(self.direction, "TaperFilm.direction"))

    def knots(self) -> tuple[np.ndarray, np.ndarray]:
        return np.array([float(self.start), float(self.end)]), np.array([self.h_in, self.h_out])


@dataclass(frozen=True)
class TaperLandFilm(_Profile):
    """A taper down to a flat land: ``h_land + depth`` at ``s = start``, falling linearly to ``h_land``
    at ``s = land_start``, flat ``h_land`` beyond (and ``h_land + depth`` before ``start``).

    Parameters
    ----------
    h_land : float
        Film over the land [c], > 0.
    depth : float
        Extra film at the taper's leading edge [c], >= 0.
    start, land_start : float
        Abscissae along the direction where the taper begins and the land begins [-],
        ``start < land_start``.
    direction : float
        Angle of the direction in the ``(phi, z)`` plane [rad]; 0 runs along the sliding.
    """

    h_land: float
    depth: float
    start: float = 0.0
    land_start: float = 0.5
    direction: float = 0.0
    smooth = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "h_land", _positive_film("TaperLandFilm.h_land", self.h_land))
        depth = float(self.depth)
        if not (math.isfinite(depth) and depth >= 0.0):
            raise ValueError(f"TaperLandFilm.depth must be a finite number >= 0 [c], got {self.depth!r}")
        object.__setattr__(self, "depth", depth)
        _check_abscissae("TaperLandFilm", (self.start, self.land_start), strict=True)
        object.__setattr__(self, "direction", check_angle(self.direction, "TaperLandFilm.direction"))

    def knots(self) -> tuple[np.ndarray, np.ndarray]:
        return (np.array([float(self.start), float(self.land_start)]),
                np.array([self.h_land + self.depth, self.h_land]))


@dataclass(frozen=True)
class ProfileFilm(_Profile):
    """Any piecewise-linear film profile along one direction, steps allowed.

    Parameters
    ----------
    points : sequence of (s, h)
        Abscissae along the direction [-] (non-decreasing) and the film there [c] (> 0),
        linear in between and constant beyond the ends. Two points at the same ``s``
        make a step, e.g. the Rayleigh step ``((0, h1), (a, h1), (a, h2), (L, h2))``;
        the film at the step itself takes the second value.
    direction : float
        Angle of the direction in the ``(phi, z)`` plane [rad]; 0 runs along the sliding
        (a step line across the sliding), ``pi/2`` across it.
    """

    points: tuple
    direction: float = 0.0

    def __post_init__(self) -> None:
        try:
            pts = tuple((float(s), float(h)) for s, h in self.points)
        except (TypeError, ValueError):
            raise ValueError(f"ProfileFilm.points must be (s, h) pairs of numbers, got {self.points!r}") from None
        if len(pts) < 2:
            raise ValueError(f"ProfileFilm.points must have at least 2 points, got {len(pts)}")
        _check_abscissae("ProfileFilm", [s for s, _ in pts], strict=False)
        for s, h in pts:
            _positive_film(f"ProfileFilm.points h at s = {s:g}", h)
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "direction", check_angle(self.direction, "ProfileFilm.direction"))

    @property
    def smooth(self) -> bool:
        """One straight piece only (no kink, no step inside the profile)."""
        return len(self.points) == 2 or all(self._slopes_equal())

    def _slopes_equal(self):
        s, h = self.knots()
        slopes = [(h[k + 1] - h[k]) / (s[k + 1] - s[k]) if s[k + 1] > s[k] else math.inf for k in range(len(s) - 1)]
        return [math.isclose(a, slopes[0], rel_tol=1e-12, abs_tol=1e-15) for a in slopes]

    def knots(self) -> tuple[np.ndarray, np.ndarray]:
        return np.array([s for s, _ in self.points]), np.array([h for _, h in self.points])


@dataclass(frozen=True)
class PlaneFilm(_Addable):
    """A flat pad tilted over a flat runner: ``h = h_pivot + slope . ((x, y) - pivot)`` (a thrust pad,
    the film at its pivot and its pitch and roll as the two slopes).

    Parameters
    ----------
    h_pivot : float
        Film at the pivot [c]; the plane may be thinner elsewhere, the solvers refuse ``h <= 0``.
    pivot : (float, float)
        The pivot's position in the plane [-].
    slope : (float, float)
        ``(dh/dx, dh/dy)`` [c per unit length].
    second_rates : bool
        Which state variables the squeeze shapes are: False (default) ``(h_pivot, slope_x)``, shapes
        ``(1, x - x_p)``; True ``(slope_y, -)``, shapes ``(y - y_p, 0)`` (the roll rate's column of a pad's
        damping).
    """

    h_pivot: float
    pivot: tuple[float, float] = (0.0, 0.0)
    slope: tuple[float, float] = (0.0, 0.0)
    second_rates: bool = False

    def __post_init__(self) -> None:
        h = float(self.h_pivot)
        if not math.isfinite(h):
            raise ValueError(f"PlaneFilm.h_pivot must be a finite number [c], got {self.h_pivot!r}")
        object.__setattr__(self, "h_pivot", h)
        for name in ("pivot", "slope"):
            try:
                a, b = (float(v) for v in getattr(self, name))
            except (TypeError, ValueError):
                raise ValueError(f"PlaneFilm.{name} must be a pair of numbers, got {getattr(self, name)!r}") from None
            if not (math.isfinite(a) and math.isfinite(b)):
                raise ValueError(f"PlaneFilm.{name} must be finite, got {getattr(self, name)!r}")
            object.__setattr__(self, name, (a, b))

    def thickness(self, phi, z):
        return (self.h_pivot + self.slope[0] * (np.asarray(phi, float) - self.pivot[0])
                + self.slope[1] * (np.asarray(z, float) - self.pivot[1]))

    def gradient(self, phi, z):
        zero = _zeros(phi, z)
        return zero + self.slope[0], zero + self.slope[1]

    def laplacian(self, phi, z):
        return _zeros(phi, z)

    def rate_shapes(self, phi, z):
        zero = _zeros(phi, z)
        if self.second_rates:
            return zero + (np.asarray(z, float) - self.pivot[1]), zero
        return zero + 1.0, zero + (np.asarray(phi, float) - self.pivot[0])

    def minimum(self, phi_range: tuple[float, float]) -> float | None:
        return None


@dataclass(frozen=True)
class PolarProfileFilm(_Addable):
    """A piecewise-linear profile along the angle or the radius about a centre, steps allowed: a thrust pad's
    machined taper-land or Rayleigh step (step lines radial for ``along="angle"``, circumferential for
    ``along="radius"``), added to the pad's :class:`PlaneFilm` (``plane + profile``).

    Parameters
    ----------
    points : sequence of (s, h)
        Abscissae (angle from ``start`` [rad], or radius [-]; non-decreasing) and the film there [c]
        (>= 0: an addition may be zero on the land), linear in between, constant beyond the ends; two
        points at one abscissa make a step (the film at the step takes the second value).
    along : {"angle", "radius"}
    centre : (float, float)
        The centre of the angles and radii (the runner's axis) [-].
    start : float
        Angle of the abscissa 0 for ``along="angle"`` [rad] (the pad's leading edge).
    """

    points: tuple
    along: str = "angle"
    centre: tuple[float, float] = (0.0, 0.0)
    start: float = 0.0

    def __post_init__(self) -> None:
        try:
            pts = tuple((float(s), float(h)) for s, h in self.points)
        except (TypeError, ValueError):
            raise ValueError(f"PolarProfileFilm.points must be (s, h) pairs of numbers, got {self.points!r}") from None
        if len(pts) < 2:
            raise ValueError(f"PolarProfileFilm.points must have at least 2 points, got {len(pts)}")
        _check_abscissae("PolarProfileFilm", [s for s, _ in pts], strict=False)
        for s_, h in pts:
            if not (math.isfinite(h) and h >= 0.0):
                raise ValueError(f"PolarProfileFilm.points: film at s = {s_:g} must be finite and >= 0 [c], got {h!r}")
        if self.along not in ("angle", "radius"):
            raise ValueError(f"PolarProfileFilm.along must be 'angle' or 'radius', got {self.along!r}")
        try:
            cx, cy = (float(v) for v in self.centre)
        except (TypeError, ValueError):
            raise ValueError(f"PolarProfileFilm.centre must be a pair of numbers, got {self.centre!r}") from None
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "centre", (cx, cy))
        object.__setattr__(self, "start", check_angle(self.start, "PolarProfileFilm.start"))

    @property
    def smooth(self) -> bool:
        """One straight piece along the angle (``theta`` is harmonic: no Laplacian left); False otherwise."""
        return len(self.points) == 2 and self.along == "angle"

    def knots(self) -> tuple[np.ndarray, np.ndarray]:
        return np.array([s for s, _ in self.points]), np.array([h for _, h in self.points])

    def _polar(self, x, y):
        dx, dy = np.asarray(x, float) - self.centre[0], np.asarray(y, float) - self.centre[1]
        r = np.hypot(dx, dy)
        return dx, dy, r, np.mod(np.arctan2(dy, dx) - self.start + math.pi, 2 * math.pi) - math.pi

    def _abscissa(self, x, y):
        dx, dy, r, angle = self._polar(x, y)
        return angle if self.along == "angle" else r

    def thickness(self, phi, z):
        s, h = self.knots()
        return _interpolate(self._abscissa(phi, z), s, h)

    def _slope(self, x: np.ndarray) -> np.ndarray:
        return _piecewise_slope(x, *self.knots())

    def gradient(self, phi, z):
        dx, dy, r, angle = self._polar(phi, z)
        with np.errstate(divide="ignore", invalid="ignore"):
            if self.along == "angle":
                g = self._slope(angle) / r**2
                return -g * dy, g * dx
            g = self._slope(r) / r
            return g * dx, g * dy

    def laplacian(self, phi, z):
        """0 along the angle (harmonic); ``slope / r`` along the radius (inside each piece)."""
        dx, dy, r, angle = self._polar(phi, z)
        if self.along == "angle":
            return _zeros(phi, z)
        with np.errstate(divide="ignore", invalid="ignore"):
            return self._slope(r) / r

    def rate_shapes(self, phi, z):
        zero = _zeros(phi, z)
        return zero + 1.0, zero

    def minimum(self, phi_range: tuple[float, float]) -> float | None:
        return None


def _piecewise_slope(x: np.ndarray, s: np.ndarray, h: np.ndarray) -> np.ndarray:
    """Slope of the piecewise-linear ``h(s)`` at ``x`` (0 outside the knots and at a step)."""
    out = np.zeros(np.shape(x))
    for k in range(len(s) - 1):
        if s[k + 1] > s[k]:
            inside = (x > s[k]) & (x < s[k + 1])
            out = np.where(inside, (h[k + 1] - h[k]) / (s[k + 1] - s[k]), out)
    return out


#: Knots up to which :func:`_interpolate` finds each point's piece by comparisons with the inner knots (one
#: vectorized comparison per knot) instead of a binary search (``np.searchsorted``): the same piece, 2.3x less
#: CPU time at 3 knots (48 against 111 us at 6,000 points, best of 2,000 calls).
COMPARED_KNOTS = 8


def _pieces(s: np.ndarray, h: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per piece ``k`` of the knots ``(s, h)``: the piece that holds its points (a zero-length piece, a step,
    never does: the next one, as often as needed), and that piece's start ``s``, start ``h``, rise in ``h`` and
    length (1 for a step that remains, the last piece)."""
    last = len(s) - 2
    k = np.arange(last + 1)
    while True:
        flat = (s[k + 1] <= s[k]) & (k < last)
        if not np.any(flat):
            break
        k = np.where(flat, k + 1, k)
    span = s[k + 1] - s[k]
    return k, s[k], h[k], h[k + 1] - h[k], np.where(span > 0, span, 1.0)


#: :func:`_pieces` of the knots seen, keyed by their bytes (a film's knots are its constants: each solve evaluates
#: the film 4-5 times, each of which found them again: 15-30 us of a 25-60 us call at a small mesh's points). Cleared
#: past :data:`PIECES_KEPT` entries.
_PIECES: dict = {}
PIECES_KEPT = 64


def _pieces_kept(s: np.ndarray, h: np.ndarray) -> tuple[np.ndarray, ...]:
    """:func:`_pieces` of the knots ``(s, h)``, found once per knots (:data:`_PIECES`; the arrays read-only)."""
    key = (s.dtype.str, h.dtype.str, s.tobytes(), h.tobytes())
    hit = _PIECES.get(key)
    if hit is None:
        if len(_PIECES) >= PIECES_KEPT:
            _PIECES.clear()
        hit = _PIECES[key] = _pieces(s, h)
        for a in hit:
            a.flags.writeable = False
    return hit


#: Points :func:`_interpolate` takes at a time: its half-dozen temporaries of a block stay in cache (at 86,000
#: quadrature points, 7,375 nodes: 0.7 against 2.1 ms CPU in one piece, mean of 50 calls).
INTERPOLATE_BLOCK = 16384


def _interpolate(x: np.ndarray, s: np.ndarray, h: np.ndarray) -> np.ndarray:
    """Piecewise-linear ``h(x)`` through the knots ``(s, h)``, constant beyond the ends and right-continuous
    at a step (two knots at one abscissa: the film at the step is the second one).

    Each point's piece is the last whose start is ``<= x`` (clipped to the first and last; up to
    :data:`COMPARED_KNOTS` knots counted by comparisons, else by a binary search), moved past steps
    (:func:`_pieces`, per piece once); in it ``h_k + (h_{k+1} - h_k) (x - s_k) / (s_{k+1} - s_k)``; by blocks
    of :data:`INTERPOLATE_BLOCK` points."""
    x = np.asarray(x, float)
    pieces = _pieces_kept(s, h)
    if x.size <= INTERPOLATE_BLOCK:
        return _interpolate_block(x, s, h, pieces)
    out = np.empty(x.shape)
    flat, into = x.reshape(-1), out.reshape(-1)
    for block in blocks(flat.size, INTERPOLATE_BLOCK):
        into[block] = _interpolate_block(flat[block], s, h, pieces)
    return out


def _interpolate_block(x: np.ndarray, s: np.ndarray, h: np.ndarray, pieces) -> np.ndarray:
    """:func:`_interpolate` of some points, the pieces (:func:`_pieces`) given."""
    n = len(s) - 1
    move, s0, h0, rise, span = pieces
    if len(s) <= COMPARED_KNOTS:
        k = np.zeros(x.shape, np.intp)
        for j in range(1, n):
            k += x >= s[j]
    else:
        k = np.clip(np.searchsorted(s, x, side="right") - 1, 0, n - 1)
    k = move[k]
    with np.errstate(invalid="ignore"):   # x = +-inf on a flat piece: inf * 0, replaced by the end value
        inner = h0[k] + rise[k] * (x - s0[k]) / span[k]
    return np.where(x < s[0], h[0], np.where(x >= s[-1], h[-1], inner))


def _check_abscissae(owner: str, values: Sequence[float], strict: bool) -> None:
    s = [float(v) for v in values]
    if not all(math.isfinite(v) for v in s):
        raise ValueError(f"{owner}: abscissae must be finite numbers, got {list(values)!r}")
    ordered = all(b > a for a, b in zip(s, s[1:])) if strict else all(b >= a for a, b in zip(s, s[1:]))
    if not ordered or (not strict and s[-1] <= s[0]):
        rule = "strictly increasing" if strict else "non-decreasing, with a positive length"
        raise ValueError(f"{owner}: abscissae must be {rule}, got {s!r}")


@dataclass(frozen=True)
class StepFilm(_Addable):
    """A base film deepened by ``depth`` over a region of any outline (a step, a recess, a pocket).

    ``h = base.h + depth`` inside ``region``, ``base.h`` outside. The region's edge
    is a step of the film; a mesh whose element edges follow it integrates the step
    exactly (elsewhere the step is integrated by quadrature points: first order).

    Parameters
    ----------
    region : Shape
        A closed region in the ``(phi, z)`` plane (:class:`bearingfe.Rectangle`,
        :class:`bearingfe.Circle`, :class:`bearingfe.Polygon`, ...).
    depth : float
        Added film inside the region [c], finite; it may be negative (a raised pad)
        as long as the film stays > 0.
    base : Film
        The film outside the region (its squeeze shapes are the step film's).
    """

    region: object
    depth: float
    base: Film
    smooth = False

    def __post_init__(self) -> None:
        if not callable(getattr(self.region, "contains", None)):
            raise ValueError(f"StepFilm.region must be a bearingfe shape (Circle, Rectangle, Polygon, ...), "
                             f"got {type(self.region).__name__}")
        depth = float(self.depth)
        if not math.isfinite(depth):
            raise ValueError(f"StepFilm.depth must be a finite number [c], got {self.depth!r}")
        object.__setattr__(self, "depth", depth)
        if not isinstance(self.base, Film):
            raise ValueError(f"StepFilm.base must be a film (the bearingfe.Film protocol), got {type(self.base).__name__}")

    def _inside(self, phi, z) -> np.ndarray:
        phi, z = np.broadcast_arrays(np.asarray(phi, float), np.asarray(z, float))
        return np.asarray(self.region.contains(phi.ravel(), z.ravel()), bool).reshape(phi.shape)

    def thickness(self, phi, z):
        return np.asarray(self.base.thickness(phi, z), float) + self.depth * self._inside(phi, z)

    def gradient(self, phi, z):
        return self.base.gradient(phi, z)

    def laplacian(self, phi, z):
        return self.base.laplacian(phi, z)

    def rate_shapes(self, phi, z):
        return self.base.rate_shapes(phi, z)

    def minimum(self, phi_range: tuple[float, float]) -> float | None:
        """The base film's minimum when the step only deepens it (``depth >= 0``); else None."""
        if self.depth < 0:
            return None
        base = self.base.minimum(phi_range) if hasattr(self.base, "minimum") else None
        return None if base is None else float(base)


@dataclass(frozen=True)
class SumFilm(_Addable):
    """A base film plus static additions: ``h = base.h + sum(extra.h)``.

    The squeeze shapes are the base film's (the additions are fixed geometry:
    tapers, steps, lands machined into the surface). ``CosineFilm(0.5) +
    TaperLandFilm(...)`` makes one.

    Parameters
    ----------
    base : Film
    extras : tuple of Film
        Each adds its thickness, gradient and Laplacian.
    """

    base: Film
    extras: tuple = ()

    def __post_init__(self) -> None:
        extras = tuple(self.extras)
        for f in (self.base, *extras):
            if not isinstance(f, Film):
                raise ValueError(f"SumFilm terms must be films (the bearingfe.Film protocol), got {type(f).__name__}")
        object.__setattr__(self, "extras", extras)

    def __add__(self, other) -> "SumFilm":
        if not isinstance(other, Film):
            return NotImplemented
        return SumFilm(self.base, (*self.extras, other))

    @property
    def smooth(self) -> bool:
        return all(is_smooth(f) for f in (self.base, *self.extras))

    def thickness(self, phi, z):
        return sum((np.asarray(f.thickness(phi, z), float) for f in self.extras),
                   np.asarray(self.base.thickness(phi, z), float))

    def gradient(self, phi, z):
        parts = [f.gradient(phi, z) for f in (self.base, *self.extras)]
        return (sum(np.asarray(g[0], float) for g in parts), sum(np.asarray(g[1], float) for g in parts))

    def laplacian(self, phi, z):
        return sum(np.asarray(f.laplacian(phi, z), float) for f in (self.base, *self.extras))

    def rate_shapes(self, phi, z):
        return self.base.rate_shapes(phi, z)

    def minimum(self, phi_range: tuple[float, float]) -> float | None:
        return None


def smallest_film(film: Film, phi_range: tuple[float, float], values: np.ndarray | None = None,
                  points: np.ndarray | None = None) -> float:
    """Smallest film thickness over a surface [c], the one rule every solver uses.

    The film's exact minimum over ``phi_range`` when it knows it
    (:meth:`Film.minimum`); else the smallest of ``values`` (thicknesses already
    evaluated, e.g. at the quadrature points) and of the film at ``points``
    (shape ``(2, n)``, e.g. the dofs).
    """
    exact = film.minimum(phi_range) if hasattr(film, "minimum") else None
    if exact is not None:
        return float(exact)
    candidates = []
    if values is not None:
        candidates.append(float(np.min(values)))
    if points is not None:
        candidates.append(float(np.min(film.thickness(points[0], points[1]))))
    if not candidates:
        raise ValueError("smallest_film: the film has no exact minimum; give values or points to search")
    return min(candidates)
