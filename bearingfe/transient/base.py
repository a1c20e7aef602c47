"""What the stepping loop needs of a film model of the pump transient (the contract of :data:`MODELS`).

A model turns the shoe's state ``y = (gamma, delta, ...)`` at a shaft angle
``beta`` into what the loop of :mod:`bearingfe.transient.stepping` and the
periodic start of :mod:`bearingfe.transient.periodic` ask for:

=======================  ===================================================================
method                   what it gives
=======================  ===================================================================
``initial_state``        ``(beta0, y0)`` of a run from the settings' ``start``
``smallest_film``        the smallest film of a state [c]: the admissibility test of the
                         states (``> 0``) and the rupture event (``min_film``)
``stepper``              a scipy :class:`~scipy.integrate.OdeSolver` from a state (the
                         stepping method and its dense output)
``rates``                ``dy/dbeta`` of a state (models whose rates are a function of the
                         state: the scipy integrators and Newton shooting use it)
``sample``/``samples``   the SI columns of :class:`bearingfe.Trajectory` at states
``statistics``           the counters of the run (``nfev``, ``factorizations``, ``steps``...)
=======================  ===================================================================

A trial state that closes the film raises :class:`FilmClosed` (a
:class:`TrialRejected`, as is a step the model's own solver cannot take):
the loop rejects the trial step and retakes it shorter. A trial state where
no film carries the load raises :class:`NoEquilibrium`: the run stops there.
"""

from __future__ import annotations

import abc
import math
from typing import Mapping, Sequence

import numpy as np
from scipy.integrate import OdeSolver

from .trajectory import Trajectory

__all__ = ["Model", "TrialRejected", "FilmClosed", "NoEquilibrium", "wrapped"]


class TrialRejected(RuntimeError):
    """A trial step the model cannot take (message: why): the stepping loop retakes it shorter.

    A RuntimeError, so that one escaping the loop is a failed run, not a traceback."""


class FilmClosed(TrialRejected):
    """A trial state of the integrator has ``h <= 0`` somewhere on the surface (args: the state)."""


class NoEquilibrium(RuntimeError):
    """No film state carries the load at a trial state (message: where and why).

    A RuntimeError, so that one escaping the stepping loop is a failed run, not a traceback."""


def wrapped(d: np.ndarray) -> np.ndarray:
    """State difference with the attitude difference (index 1) wrapped into ``[-pi, pi)``."""
    d = np.array(d, float)
    d[1] = (d[1] + math.pi) % (2 * math.pi) - math.pi
    return d


class Model(abc.ABC):
    """A film model of the pump transient (see the module docstring for the contract).

    Class attributes
    ----------------
    name : str
        Its key in :data:`bearingfe.transient.MODELS`.
    periodic_methods : tuple of str
        The keys of :data:`bearingfe.transient.PERIODIC_METHODS` it supports.
    periodic_default : str
        Its measured-best periodic method.
    integrators : tuple of str or None
        The keys of :data:`bearingfe.transient.INTEGRATORS` it supports (None: all).
    periodic_tied : bool
        Its periodic search needs ``rtol`` tied to ``periodic_tol``
        (:func:`bearingfe.transient.periodic.search_settings`).
    starts : tuple of str
        What its ``start`` may be besides ``"steady"`` and ``"periodic"``: ``"state"``
        (a given ``(gamma, delta)``), ``"trajectory"`` (a run to continue).

    Instance attributes
    -------------------
    pump : EccentricPump
    element : str
        Finite element of its film.
    dofs : float
        Size of its film problem (nodes or dofs), for the run's ``stats``.
    """

    name: str = ""
    periodic_methods: tuple[str, ...] = ()
    periodic_default: str = ""
    integrators: tuple[str, ...] | None = None
    periodic_tied: bool = False
    starts: tuple[str, ...] = ("state",)

    pump: object
    element: str
    dofs: float

    @classmethod
    def check(cls, settings) -> None:
        """Raise a ``ValueError`` naming the field if ``settings`` asks what this model cannot do (before any
        work: a class method)."""
        if cls.integrators is not None and settings.method not in cls.integrators:
            raise ValueError(f"method must be one of {list(cls.integrators)} for the {cls.name} model, "
                             f"got {settings.method!r}")
        method = settings.periodic_method
        if settings.periodic and method is not None and method not in cls.periodic_methods:
            raise ValueError(f"periodic_method must be one of {cls.periodic_methods} for the {cls.name} model, "
                             f"got {method!r}")
        start = settings.start
        if isinstance(start, Trajectory) and "trajectory" not in cls.starts:
            raise ValueError(f"start: the {cls.name} model does not continue a Trajectory (only the elastic squeeze "
                             f"model does: bearingfe.transient.elastic.simulate_elastic); give 'steady', 'periodic' "
                             f"or (gamma, delta)")
        if isinstance(start, tuple) and "state" not in cls.starts:
            raise ValueError(f"start must be 'periodic', 'steady' or a Trajectory of simulate_elastic for the "
                             f"{cls.name} model (its state holds the pressures), got {start!r}")

    @abc.abstractmethod
    def initial_state(self, settings) -> tuple[float, np.ndarray]:
        """``(beta0 [rad], y0)``: the start of the run that ``settings.start`` names."""

    @abc.abstractmethod
    def smallest_film(self, beta: float, y: np.ndarray) -> float:
        """Smallest film of state ``y`` at ``beta`` over the surface [c] (<= 0: the film is closed)."""

    @abc.abstractmethod
    def stepper(self, beta0: float, y0: np.ndarray, angles: np.ndarray, settings, first_step: float | None,
                max_step: float | None) -> OdeSolver:
        """An integrator from ``(beta0, y0)`` toward ``angles[-1]`` (``angles``: the run's sample angles).

        ``first_step`` and ``max_step`` [rad] are the stepping loop's: None
        for the integrator's own first step and the settings' ``max_step``;
        shorter after a rejected trial step.
        """

    def rates(self, beta: float, y: np.ndarray) -> np.ndarray:
        """``dy/dbeta`` at a state (models whose rates are a function of the state)."""
        raise NotImplementedError(f"the {self.name} model has no rates as a function of the state")

    def begin(self, beta0: float, y0: np.ndarray) -> None:
        """A run starts from ``(beta0, y0)`` (a model with a history picks it up here)."""

    def end(self, run) -> None:
        """A run ended (a model with a history keeps the end of a completed run here)."""

    @abc.abstractmethod
    def sample(self, beta: float, y: np.ndarray) -> dict[str, object]:
        """The SI columns of one sample (:data:`bearingfe.transient.trajectory.SAMPLE_COLUMNS`, ...)."""

    def samples(self, betas: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        """The SI columns at every sample (one :meth:`sample` each; a model may batch them)."""
        rows = [self.sample(float(b), y) for b, y in zip(betas, states)]
        if not rows:
            raise ValueError("samples: no states")
        return {name: np.array([row[name] for row in rows]) for name in rows[0]}

    def weights(self, y: np.ndarray) -> np.ndarray:
        """Weights of the state's components in a mixed (Anderson) periodic step [-]."""
        return np.ones(np.size(y))

    @abc.abstractmethod
    def statistics(self, output, runs: Sequence) -> Mapping[str, float]:
        """The counters of the run: ``output`` is the output run, ``runs`` every integration of it."""

    def solver_seconds(self) -> float | None:
        """Seconds spent in film solves (None: not measured apart from the run)."""
        return None
