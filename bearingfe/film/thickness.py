"""Film-thickness models.

A film gives the non-dimensional thickness ``h = H / c`` over the surface,
its derivatives, and how it changes with its own state variables (for the
squeeze term of the Reynolds equation). Any object with these methods works
as a film (see :class:`Film`); :class:`CosineFilm` is the rigid eccentric
journal against a circular bore.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

from ..core.checks import MAX_GAMMA, check_angle

__all__ = ["Film", "CosineFilm", "UniformFilm", "smallest_film"]


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

    # Optional, not part of the protocol: ``fields_from_angles(cos_phi, sin_phi)`` returning
    # ``(h, (dh/dphi, dh/dz), laplacian, shapes)`` at points whose angles' cosines and sines are
    # given (:meth:`CosineFilm.fields_from_angles`); :func:`bearingfe.film.forms.film_at` uses it when
    # the caller passes them, which spares the trigonometric calls of every film state.


@dataclass(frozen=True)
class CosineFilm:
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
class UniformFilm:
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
