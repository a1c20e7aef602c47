"""The plunger shoe over the pump cycle: film models, one stepping loop, one periodic start.

A film model (:data:`MODELS`, the contract in :mod:`bearingfe.transient.base`)
turns the shoe's state into rates and samples; every model is integrated by
the same loop with the same settings (:class:`Integration`), started by the
same periodic methods (:data:`PERIODIC_METHODS`) and sampled into the same
:class:`Trajectory`. The doors are :func:`simulate` (rigid, cavitating, JFO,
quasi-static elastic) and :func:`simulate_elastic` (the squeeze of the
deflection).

================  ============================================================
module            what it does
================  ============================================================
``base``          The contract of a film model (``Model``) and the trial-state exceptions.
``settings``      ``Integration``: the frozen integration settings, checked once; the integrators.
``trajectory``    ``Trajectory``, the result, and the one place that builds it.
``events``        Events as plain functions with ``terminal``/``direction``: the film rupture.
``stepping``      The one stepping loop: closing trial steps retaken shorter, events located.
``periodic``      The periodic start: Newton shooting, fixed point, Anderson, one revolution.
``driver``        One transient of any model: start, periodic start, output run, samples.
``rigid``         The rigid film (2x2 superposition rates); steady state, balance ratio, mesh.
``cavitating``    The rigid film with Swift-Stieber or Gumbel rupture (warm-started Newton).
``fed``           The rigid film with the pocket fed through the plunger's restrictor: its pressure a state;
                  with Swift-Stieber or Gumbel rupture (``FedCavitating``), with JFO (``FedJFO``).
``jfo``           The rigid film with JFO cavitation: backward Euler carrying the fill fraction.
``elastic``       The elastic support: squeeze of the deflection (``simulate_elastic``), quasi-static (fed pocket too).
``quasi_static``  ``simulate``: the door of every model but the squeeze one; the ``MODELS`` table.
``results``       ``state_result``: the film of one sample, re-solved for pictures and fields.
================  ============================================================
"""

from __future__ import annotations

from .base import FilmClosed, Model, NoEquilibrium, TrialRejected
from .elastic import BAUMGARTE, ElasticSqueeze, FedQuasiStaticElastic, QuasiStaticElastic, simulate_elastic
from .fed import Fed, FedCavitating, FedJFO
from .jfo import JFO
from .cavitating import Cavitating
from .periodic import PERIODIC_METHODS, PeriodicStart
from .quasi_static import MODELS, balance_ratio, pump_mesh, simulate, steady_state
from .results import state_result
from .rigid import Rigid
from .settings import IMPLICIT_INTEGRATORS, INTEGRATORS, STARTS, Integration
from .stepping import Run, integrate
from .trajectory import STATUSES, LiftOffError, Trajectory

__all__ = ["Trajectory", "simulate", "steady_state", "balance_ratio", "pump_mesh", "state_result", "LiftOffError",
           "INTEGRATORS", "IMPLICIT_INTEGRATORS", "STARTS", "STATUSES", "PERIODIC_METHODS", "PeriodicStart",
           "MODELS", "Model", "Rigid", "Cavitating", "JFO", "Fed", "FedCavitating", "FedJFO", "QuasiStaticElastic", "FedQuasiStaticElastic", "ElasticSqueeze", "Integration",
           "Run", "integrate", "TrialRejected", "FilmClosed", "NoEquilibrium", "simulate_elastic", "BAUMGARTE"]
