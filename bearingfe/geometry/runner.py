"""How the runner (the moving surface facing the support) slides over the support's plane.

The Reynolds equation's Couette term carries oil with the mean surface velocity; with the support
at rest it is half the runner's velocity ``U``. A film on the unwrapped journal or a slider has a
runner sliding uniformly along ``phi``; a thrust pad faces a collar rotating about the shaft axis,
whose velocity ``omega x r`` grows with the radius and turns with the angle. A runner here is that
velocity field over the support's plane, relative to a reference speed (the journal's ``omega R0``,
the collar's ``omega R0`` at the unit radius ``R0``):

======================  ==================================================================
runner                  velocity ``u = U / U_ref`` at ``(x, y)`` of the plane [-]
======================  ==================================================================
:class:`Translating`    uniform ``(cos a, sin a)`` (default ``a = 0``: along ``phi``, every
                        journal, slider and pump film)
:class:`Rotating`       ``sense (-(y - y_c), x - x_c)``: a collar turning about ``(x_c, y_c)``
                        (counter-clockwise for ``sense = +1``), speed 1 at the unit radius
======================  ==================================================================

Both fields are divergence free (rigid motions of the runner in its plane), which the conservative
Couette source needs (:func:`bearingfe.film.forms.couette_source`: ``div(h u) = u . grad h``).
The default runner (:data:`ALONG_PHI`) takes the package's original uniform path, unchanged to the
bit; any other runner gives the solvers its velocity at their points (:func:`velocity_at`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol, runtime_checkable

import numpy as np

__all__ = ["Runner", "Translating", "Rotating", "ALONG_PHI", "is_along_phi", "velocity_at", "require_along_phi"]


@runtime_checkable
class Runner(Protocol):
    """A divergence-free runner velocity field over the support's plane, relative to the reference speed."""

    def velocity(self, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(u_x, u_y)`` at the points [-]."""


@dataclass(frozen=True)
class Translating:
    """A runner sliding uniformly along a direction of the plane (a slider; the unwrapped journal).

    Parameters
    ----------
    angle : float
        Direction of the sliding from the ``phi`` (``x``) axis [rad], finite; 0 is the package's
        original runner (:data:`ALONG_PHI`).
    """

    angle: float = 0.0

    def __post_init__(self) -> None:
        angle = float(self.angle)
        if not math.isfinite(angle) or abs(angle) > 1e6:
            raise ValueError(f"Translating.angle must be a finite angle [rad] with |angle| <= 1e6, got {self.angle!r}")
        object.__setattr__(self, "angle", angle)

    def velocity(self, x, y):
        zero = 0.0 * np.asarray(x, float) + 0.0 * np.asarray(y, float)
        return zero + math.cos(self.angle), zero + math.sin(self.angle)


@dataclass(frozen=True)
class Rotating:
    """A runner (thrust collar) rotating about an axis normal to the plane through ``centre``.

    Parameters
    ----------
    centre : (float, float)
        The axis' trace in the plane [-] (units of the reference radius ``R0``).
    sense : {+1, -1}
        +1: counter-clockwise (from ``+x`` towards ``+y``), -1: clockwise.

    Notes
    -----
    ``u = sense (-(y - y_c), x - x_c)``: speed ``r / R0`` relative to ``omega R0``. The friction the
    solvers integrate along ``u`` (``int tau . u``) is then the friction torque over ``R0``, and
    ``friction * U_ref`` the power.
    """

    centre: tuple[float, float] = (0.0, 0.0)
    sense: int = 1

    def __post_init__(self) -> None:
        try:
            cx, cy = (float(v) for v in self.centre)
        except (TypeError, ValueError):
            raise ValueError(f"Rotating.centre must be a pair of numbers, got {self.centre!r}") from None
        if not (math.isfinite(cx) and math.isfinite(cy)):
            raise ValueError(f"Rotating.centre must be finite, got {self.centre!r}")
        if self.sense not in (1, -1):
            raise ValueError(f"Rotating.sense must be +1 (counter-clockwise) or -1 (clockwise), got {self.sense!r}")
        object.__setattr__(self, "centre", (cx, cy))

    def velocity(self, x, y):
        x, y = np.asarray(x, float), np.asarray(y, float)
        s = float(self.sense)
        return -s * (y - self.centre[1]), s * (x - self.centre[0])


#: The package's original runner: uniform sliding along ``phi`` at the reference speed.
ALONG_PHI = Translating(0.0)


def is_along_phi(runner) -> bool:
    """True for the original runner (uniform, along ``phi``): the solvers' uniform path, bit for bit."""
    return runner is None or (isinstance(runner, Translating) and runner.angle == 0.0)


def velocity_at(runner, x: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The runner's velocity at points ``x`` (shape ``(2, ...)``), or None for :data:`ALONG_PHI`
    (the callers then take their uniform path)."""
    if is_along_phi(runner):
        return None
    u0, u1 = runner.velocity(x[0], x[1])
    shape = np.shape(x[0])
    return np.broadcast_to(np.asarray(u0, float), shape).copy(), np.broadcast_to(np.asarray(u1, float), shape).copy()


def require_along_phi(mesh, what: str) -> None:
    """Refuse a mesh whose runner is not :data:`ALONG_PHI` on a path that carries the oil along ``phi`` only."""
    runner = getattr(mesh, "runner", None)
    if not is_along_phi(runner):
        raise ValueError(f"{what} takes the runner sliding uniformly along phi only (Translating(0)); "
                         f"this mesh's surface has runner={runner!r}")
