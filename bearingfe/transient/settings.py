"""How a pump transient is integrated: one frozen settings object, checked once.

Every model of :data:`bearingfe.transient.MODELS` is integrated by the same
stepping loop (:mod:`bearingfe.transient.stepping`) with the same settings:
the scipy integrator and its tolerances, the film that ends a run as
ruptured, the output samples, the start and the periodic-start search.
:class:`Integration` checks each field once, in ``__post_init__``, with an
error that names the field and its allowed range; what depends on the film
model (an implicit integrator for stiff pressure modes, a periodic method
that needs a two-component state) is checked by the model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import Mapping

import numpy as np
import scipy.integrate as si

from ..core import LimitError, check_limit
from .periodic import PERIODIC_METHODS
from .trajectory import Trajectory

__all__ = ["Integration", "INTEGRATORS", "IMPLICIT_INTEGRATORS", "STARTS", "MIN_STEP", "positive"]

#: Named starting states (besides a given ``(gamma, delta)`` or a trajectory to continue).
STARTS = ("periodic", "steady")

#: Stepping integrators by name: scipy's implicit and switching methods, and the explicit
#: Runge-Kutta pairs for films that are not stiff (on the shipped pump RK23 reaches a given error
#: of the smallest film with fewer film solves than LSODA: docs/benchmarks_pump.md).
INTEGRATORS: Mapping[str, type] = MappingProxyType({"Radau": si.Radau, "BDF": si.BDF, "LSODA": si.LSODA,
                                                   "RK23": si.RK23, "RK45": si.RK45})
#: The implicit (or stiffness-switching) ones of :data:`INTEGRATORS`, for stiff systems.
IMPLICIT_INTEGRATORS = ("Radau", "BDF", "LSODA")

#: Default floor of a step [rad] retaken after its trial closed the film: below it the run stops as "stalled".
MIN_STEP = 1e-9


def positive(name: str, value) -> float:
    """``value`` as a float if it is a finite number > 0, else a ``ValueError`` naming ``name``."""
    if isinstance(value, bool) or not (isinstance(value, (int, float, np.floating, np.integer))
                                       and math.isfinite(value) and value > 0):
        raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    return float(value)


#: Shortest run [revolutions]: 1e-300 revolutions made an integration span lost in round-off that never ended.
MIN_REVOLUTIONS = 1e-6


@dataclass(frozen=True)
class Integration:
    """Settings of one pump transient, shared by every film model.

    Attributes
    ----------
    revolutions : float
        Length of the output run in shaft turns, > 0 and at most
        ``max_revolutions``.
    start : {"steady", "periodic"}, (gamma, delta) or Trajectory
        The steady state at ``beta0``; the periodic state (by
        ``periodic_method``); a given relative eccentricity [-] and attitude
        [rad] (``gamma > 0``); or a trajectory to continue (models whose
        state it holds: the elastic squeeze model).
    beta0 : float
        Shaft angle at the start [rad], finite.
    method : str
        A key of :data:`INTEGRATORS`.
    rtol : float
        Relative tolerance of the integrator, in (0, 1).
    atol : float, optional
        Absolute tolerance on ``(gamma [-], delta [rad])``, > 0; default
        ``1e-3 rtol``.
    max_step : float
        Largest step [rad], > 0.
    min_step : float
        Floor [rad], in (0, ``max_step``), of a step retaken shorter: a
        trial step whose state closes the film (or that the model's own
        solver rejects) is retaken from the last accepted state with half
        the length (:mod:`bearingfe.transient.stepping`); below this floor
        the run stops as ``"stalled"``.
    min_film : float
        Smallest film [c] (clearances), in (0, 1): an accepted state whose
        smallest film reaches it ends the run as ``"ruptured"``.
    points_per_revolution : int
        Output samples per turn, >= 8.
    periodic_method : str, optional
        A key of :data:`bearingfe.transient.PERIODIC_METHODS`; default the
        model's own (its measured-best method).
    periodic_tol : float
        Periodic start: tolerance on ``(gamma [-], delta [rad])`` over one
        revolution, > 0.
    periodic_max_iter : int
        Periodic start: largest number of revolutions, >= 1.
    max_revolutions : float, optional
        Largest ``revolutions`` accepted (a guard against runaway work);
        default the ``revolutions`` limit of :mod:`bearingfe.core.limits`.
    """

    revolutions: float = 1.0
    start: object = "steady"
    beta0: float = 0.0
    method: str = "LSODA"
    rtol: float = 1e-5
    atol: float | None = None
    max_step: float = math.pi / 8
    min_step: float = MIN_STEP
    min_film: float = 0.02
    points_per_revolution: int = 180
    periodic_method: str | None = None
    periodic_tol: float = 1e-6
    periodic_max_iter: int = 30
    max_revolutions: float | None = None

    def __post_init__(self) -> None:
        set_ = object.__setattr__
        if isinstance(self.revolutions, bool) or not (isinstance(self.revolutions, (int, float))
                                                      and math.isfinite(self.revolutions) and self.revolutions > 0):
            raise ValueError(f"revolutions must be a finite number > 0, got {self.revolutions!r}")
        if self.revolutions < MIN_REVOLUTIONS:  # a span lost in the start angle's round-off never ends
            raise ValueError(f"revolutions must be a finite number > 0 and at least {MIN_REVOLUTIONS:g} (a shorter "
                             f"run is a single state: use steady_state), got {self.revolutions!r}")
        check_limit("revolutions", self.revolutions, self.max_revolutions, "max_revolutions")
        set_(self, "start", _checked_start(self.start))
        if not (isinstance(self.beta0, (int, float)) and math.isfinite(self.beta0)):
            raise ValueError(f"beta0 must be a finite angle [rad], got {self.beta0!r}")
        if not (isinstance(self.method, str) and self.method in INTEGRATORS):
            raise ValueError(f"method must be one of {list(INTEGRATORS)}, got {self.method!r}")
        for name in ("rtol", "max_step", "min_step", "periodic_tol"):
            set_(self, name, positive(name, getattr(self, name)))
        if self.atol is not None:
            set_(self, "atol", positive("atol", self.atol))
        if not self.rtol < 1:
            raise ValueError(f"rtol must be in (0, 1) (a relative tolerance of 1 or more allows 100 % error), "
                             f"got {self.rtol!r}")
        if not self.min_step < self.max_step:
            raise ValueError(f"min_step must be in (0, max_step = {self.max_step:g} rad), got {self.min_step!r}")
        if not (isinstance(self.min_film, (int, float)) and 0 < self.min_film < 1):
            raise ValueError(f"min_film must be in (0, 1) clearances, got {self.min_film!r}")
        set_(self, "points_per_revolution", _count("points_per_revolution", self.points_per_revolution, 8))
        try:
            check_limit("samples", self.points_per_revolution * self.revolutions)
        except LimitError as exc:
            raise LimitError(f"points_per_revolution x revolutions = {self.points_per_revolution} x "
                             f"{self.revolutions:g}: {exc}") from None
        if self.periodic_method is not None and self.periodic_method not in PERIODIC_METHODS:
            raise ValueError(f"periodic_method must be one of {tuple(PERIODIC_METHODS)}, got "
                             f"{self.periodic_method!r}")
        set_(self, "periodic_max_iter", _count("periodic_max_iter", self.periodic_max_iter, 1))

    @property
    def absolute_tolerance(self) -> float:
        """``atol``, or its default ``1e-3 rtol``."""
        return 1e-3 * self.rtol if self.atol is None else self.atol

    @property
    def periodic(self) -> bool:
        """The run starts from the periodic state."""
        return isinstance(self.start, str) and self.start == "periodic"

    def loosened(self, rtol: float, atol: float) -> Integration:
        """The same settings with tolerances no tighter than ``rtol``, ``atol``."""
        return replace(self, rtol=max(self.rtol, rtol), atol=max(self.absolute_tolerance, atol))

    def output_angles(self, beta0: float) -> np.ndarray:
        """Shaft angles [rad] of the output samples from ``beta0``: ``points_per_revolution`` a turn."""
        n = max(int(round(self.points_per_revolution * self.revolutions)), 2) + 1
        return np.linspace(beta0, beta0 + 2 * math.pi * self.revolutions, n)

    def revolution_angles(self, beta0: float) -> np.ndarray:
        """Shaft angles [rad] of one revolution from ``beta0`` at ``points_per_revolution`` a turn."""
        return np.linspace(beta0, beta0 + 2 * math.pi, int(self.points_per_revolution) + 1)


def _count(name: str, value, smallest: int) -> int:
    """``value`` as an int if it is a whole number >= ``smallest``, else a ``ValueError`` naming ``name``."""
    whole = (isinstance(value, (int, np.integer)) or (isinstance(value, float) and value.is_integer()))
    if isinstance(value, bool) or not (whole and value >= smallest):
        raise ValueError(f"{name} must be an integer >= {smallest}, got {value!r}")
    return int(value)


def _checked_start(start):
    """``start`` as given if it is a name of :data:`STARTS` or a trajectory, else a checked ``(gamma, delta)``."""
    if isinstance(start, Trajectory) or (isinstance(start, str) and start in STARTS):
        return start
    allowed = "'steady', 'periodic', (gamma, delta) or a Trajectory to continue"
    if isinstance(start, str):
        raise ValueError(f"start must be {allowed}, got {start!r}")
    try:
        y0 = tuple(float(v) for v in start)
    except (TypeError, ValueError):
        raise ValueError(f"start must be {allowed}, got {start!r}") from None
    if len(y0) != 2 or not all(math.isfinite(v) for v in y0):
        raise ValueError(f"start (gamma, delta) must be two finite numbers, got {start!r}")
    if y0[0] <= 0:
        raise ValueError(f"start gamma must be > 0 (at gamma = 0 the shoe is concentric, the attitude angle "
                         f"delta is undefined and the squeeze rates are singular), got {start!r}")
    return y0
