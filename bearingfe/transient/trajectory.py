"""The result of a pump transient: :class:`Trajectory`, built in one place (:func:`make_trajectory`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType
from typing import Mapping

import numpy as np

from ..bearings.pump import EccentricPump

__all__ = ["Trajectory", "LiftOffError", "STATUSES", "SAMPLE_COLUMNS", "make_trajectory", "report_columns"]

#: How a run ends (:attr:`Trajectory.status`).
STATUSES = ("completed", "ruptured", "no-equilibrium", "stalled")


class LiftOffError(ValueError):
    """The pocket's hydrostatic lift exceeds the plunger force: no equilibrium with a closed film."""


@dataclass(frozen=True, eq=False)
class Trajectory:
    """The plunger shoe over the pump cycle (arrays sampled at ``beta``).

    Attributes
    ----------
    t : ndarray
        Time from the start [s].
    beta : ndarray
        Shaft angle [rad].
    gamma, delta : ndarray
        Relative eccentricity [-] and attitude in the shoe frame [rad].
    gamma_rate, delta_rate : ndarray
        ``d gamma/d beta`` [-], ``d delta/d beta`` [-] (per radian of shaft turn).
    wedge : ndarray
        ``1 - dphi2/dbeta`` [-].
    inlet_pressure : ndarray
        Pocket pressure, non-dimensional [-]: the chamber's, or the pocket's own when it is fed
        through the plunger's restrictor (:mod:`bearingfe.transient.fed`).
    chamber_pressure : ndarray
        The chamber pressure in Pa.
    load : ndarray, shape (n, 2)
        Applied load on the shoe in the shoe frame (as the solver's ``force``) [-].
    h_min : ndarray
        Smallest film over the whole surface [m].
    friction_moment : ndarray
        Film shear moment on the eccentric about ``O2`` [N m].
    flow_inlet, flow_side, flow_arc, flow_squeeze : ndarray
        Flow out of the pockets, out through the sides ``z = +-a``, out
        through the arc edges (or the whole outline when it is not a
        rectangle), and the squeeze rate of the film volume [m^3/s].
    mass_balance : ndarray
        ``inlet - side - arc - squeeze`` [m^3/s].
    status : str
        One of :data:`STATUSES`: ``"completed"``; ``"ruptured"`` (an
        accepted state's smallest film reached ``min_film``, located on the
        integrator's dense output); ``"no-equilibrium"`` (on an elastic
        support, the coupled film found no deflection that carries the load:
        the support is too soft for it there, or the quasi-static model has
        no solution; the message says where and why); or ``"stalled"`` (every
        trial step from the last accepted state, down to the floor
        ``min_step``, closed the film or was rejected by the model's own
        solver, or the integrator itself failed; the message names the
        angle and the reason). A run that did not complete ends at its
        last accepted state (a rupture: at the located angle).
    message : str
    rupture_beta : float
        Shaft angle where a run that did not complete stopped [rad]; NaN if
        it completed.
    start : tuple of float
        Initial ``(gamma, delta)``.
    periodic_iterations : int
        Revolutions integrated to find the periodic start (0 unless started
        periodic): Newton shooting does not count the revolution that
        verified the start (it is the output revolution), Anderson mixing
        counts it, the fixed-point iteration counts its last revolution
        (the output revolution is integrated afresh from its end).
    periodic_residual : float
        ``max |y(2 pi) - y(0)|`` over ``(gamma, delta)`` (attitude wrapped) of
        the revolution that ended the search (NaN unless periodic).
    element : str
        Finite element of the run (``state_result`` re-solves with it).
    stats : mapping
        ``nfev``, ``factorizations``, ``steps``, ``seconds`` (wall time of
        the start and the integration), ``solver_seconds``,
        ``postprocess_seconds``, ``dofs``, ``balance_ratio``; on an elastic
        support also ``jacobians``; under JFO ``newton_iterations`` and
        ``cavitated_fraction_max``. What the counters cover is the model's
        (:meth:`bearingfe.transient.base.Model.statistics`).
    max_deflection : ndarray or None
        Largest film opening by the elastic support [m] (None: rigid).
    pressures : ndarray or None
        Nodal pressure [-] at each sample, shape (n, n_dofs), where the
        pressure is a state of the run
        (:func:`bearingfe.transient.elastic.simulate_elastic`); else None.
    """

    t: np.ndarray
    beta: np.ndarray
    gamma: np.ndarray
    delta: np.ndarray
    gamma_rate: np.ndarray
    delta_rate: np.ndarray
    wedge: np.ndarray
    inlet_pressure: np.ndarray
    chamber_pressure: np.ndarray
    load: np.ndarray
    h_min: np.ndarray
    friction_moment: np.ndarray
    flow_inlet: np.ndarray
    flow_side: np.ndarray
    flow_arc: np.ndarray
    flow_squeeze: np.ndarray
    mass_balance: np.ndarray
    status: str
    message: str
    rupture_beta: float
    start: tuple[float, float]
    periodic_iterations: int
    periodic_residual: float
    stats: Mapping[str, float]
    element: str = "P1"
    max_deflection: np.ndarray | None = None
    pressures: np.ndarray | None = None

    @property
    def smallest_film(self) -> float:
        """Smallest film thickness over the run [m]."""
        return float(np.min(self.h_min))

    @property
    def mass_balance_relative(self) -> float:
        """``max |mass_balance| / max(|flow_inlet| + |flow_side| + |flow_arc|)`` [-]."""
        scale = np.max(np.abs(self.flow_inlet) + np.abs(self.flow_side) + np.abs(self.flow_arc))
        return float(np.max(np.abs(self.mass_balance)) / scale) if scale > 0 else 0.0

    def columns(self) -> dict[str, np.ndarray]:
        """The sampled arrays by name (for a CSV or a DataFrame)."""
        names = ("t", "beta", "gamma", "delta", "gamma_rate", "delta_rate", "wedge", "inlet_pressure",
                 "chamber_pressure", "h_min", "friction_moment", "flow_inlet", "flow_side", "flow_arc",
                 "flow_squeeze", "mass_balance")
        cols = {n: np.asarray(getattr(self, n)) for n in names}
        cols["load_x"], cols["load_y"] = self.load[:, 0], self.load[:, 1]
        if self.max_deflection is not None:
            cols["max_deflection"] = np.asarray(self.max_deflection)
        return cols


#: The SI columns a model's samples give (:meth:`bearingfe.transient.base.Model.samples`).
SAMPLE_COLUMNS = ("gamma_rate", "delta_rate", "h_min", "friction_moment", "flow_inlet", "flow_side", "flow_arc",
                  "flow_squeeze", "mass_balance")


def make_trajectory(pump: EccentricPump, beta0: float, betas: np.ndarray, states: np.ndarray,
                    columns: Mapping[str, np.ndarray], *, status: str, message: str, rupture_beta: float,
                    start: np.ndarray, periodic_iterations: int, periodic_residual: float, element: str,
                    stats: Mapping[str, float]) -> Trajectory:
    """The :class:`Trajectory` of a run: the pump's cycle at the samples, the model's columns and the run's figures.

    Parameters
    ----------
    pump : EccentricPump
    beta0 : float
        Shaft angle of the start [rad] (``t = 0``).
    betas : ndarray, shape (n,)
        Shaft angles of the samples [rad].
    states : ndarray, shape (n, m)
        The model's states at the samples: ``(gamma [-], delta [rad], ...)``.
    columns : mapping
        The model's SI columns at the samples: every name of
        :data:`SAMPLE_COLUMNS`, optionally ``max_deflection`` [m],
        ``pressures`` (shape (n, n_dofs), non-dimensional) and ``inlet_pressure``
        (the pocket pressure [-] of a model that carries it; default the chamber's).
    status, message, rupture_beta
        How the run ended (:data:`STATUSES`; ``rupture_beta`` NaN if it completed).
    start : array_like
        The initial state (its ``gamma``, ``delta`` are kept).
    periodic_iterations, periodic_residual, element, stats
        As the fields of :class:`Trajectory`.
    """
    if status not in STATUSES:
        raise ValueError(f"status must be one of {STATUSES}, got {status!r}")
    missing = [name for name in SAMPLE_COLUMNS if name not in columns]
    if missing:
        raise ValueError(f"columns: missing {missing}")
    betas = np.asarray(betas, float)
    f = pump.load(betas)
    return Trajectory(
        t=(betas - beta0) / pump.drive.omega, beta=betas, gamma=states[:, 0], delta=states[:, 1],
        wedge=pump.wedge(betas),
        inlet_pressure=np.asarray(columns["inlet_pressure"], float) if "inlet_pressure" in columns
        else pump.inlet_pressure(betas),
        chamber_pressure=pump.chamber_pressure(betas), load=np.column_stack([-f, np.zeros_like(f)]),
        **{name: np.asarray(columns[name], float) for name in SAMPLE_COLUMNS},
        status=status, message=message, rupture_beta=math.nan if status == "completed" else float(rupture_beta),
        start=(float(start[0]), float(start[1])), periodic_iterations=int(periodic_iterations),
        periodic_residual=float(periodic_residual), element=element, stats=MappingProxyType(dict(stats)),
        max_deflection=columns.get("max_deflection"), pressures=columns.get("pressures"))


def report_columns(traj: Trajectory, scale) -> dict[str, np.ndarray]:
    """A trajectory's columns as a person reads them, each headed ``"name [unit]"``.

    Angles in degrees, everything else SI (the load in N from ``scale``,
    :class:`bearingfe.core.scales.Scale`); the solver's non-dimensional pocket
    pressure and load are kept as extra columns named ``*_nondimensional [-]``.
    """
    cols = {"t [s]": traj.t, "beta [deg]": np.degrees(traj.beta), "gamma [-]": traj.gamma,
            "delta [deg]": np.degrees(traj.delta), "gamma_rate [1/rad]": traj.gamma_rate,
            "delta_rate [-]": traj.delta_rate, "wedge [-]": traj.wedge,
            "chamber_pressure [Pa]": traj.chamber_pressure, "h_min [m]": traj.h_min,
            "friction_moment [N m]": traj.friction_moment, "flow_inlet [m^3/s]": traj.flow_inlet,
            "flow_side [m^3/s]": traj.flow_side, "flow_arc [m^3/s]": traj.flow_arc,
            "flow_squeeze [m^3/s]": traj.flow_squeeze, "mass_balance [m^3/s]": traj.mass_balance,
            "load_x [N]": scale.to_force(traj.load[:, 0]), "load_y [N]": scale.to_force(traj.load[:, 1])}
    if traj.max_deflection is not None:
        cols["max_deflection [m]"] = traj.max_deflection
    cols.update({"inlet_pressure_nondimensional [-]": traj.inlet_pressure,
                 "load_x_nondimensional [-]": traj.load[:, 0], "load_y_nondimensional [-]": traj.load[:, 1]})
    return {k: np.asarray(v, dtype=float) for k, v in cols.items()}
