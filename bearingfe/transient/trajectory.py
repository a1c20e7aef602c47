"""The result of a pump transient: :class:`Trajectory`, built in one place (:func:`make_trajectory`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType
from typing import Mapping

import numpy as np

from ..bearings.pump import EccentricPump

__all__ = ["Trajectory", "LiftOffError", "STATUSES", "SAMPLE_COLUMNS", "POCKET_COLUMNS", "make_trajectory",
           "report_columns", "power_columns", "CycleLosses", "cycle_losses"]

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
    flow_restrictor : ndarray or None
        Flow from the chamber through the plunger's restrictor into the pocket [m^3/s] (the
        ``"fed"`` model, :mod:`bearingfe.transient.fed`); None when the pocket is at the chamber
        pressure or there is none.
    flow_pocket_gap : ndarray or None
        ``dV/dt``: the rate at which the shoe's motion opens the gap over the pocket [m^3/s] (the
        ``"fed"`` model); what the restrictor feeds beyond it and ``flow_inlet`` compresses the
        pocket's oil: ``V/K dp_r/dt = flow_restrictor - flow_inlet - flow_pocket_gap``.
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
    flow_restrictor: np.ndarray | None = None
    flow_pocket_gap: np.ndarray | None = None

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
        for name in POCKET_COLUMNS:
            if getattr(self, name) is not None:
                cols[name] = np.asarray(getattr(self, name))
        return cols


#: The SI columns a model's samples give (:meth:`bearingfe.transient.base.Model.samples`).
SAMPLE_COLUMNS = ("gamma_rate", "delta_rate", "h_min", "friction_moment", "flow_inlet", "flow_side", "flow_arc",
                  "flow_squeeze", "mass_balance")

#: The optional SI columns of a model that feeds the pocket through a restrictor [m^3/s].
POCKET_COLUMNS = ("flow_restrictor", "flow_pocket_gap")


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
        :data:`SAMPLE_COLUMNS`, optionally ``max_deflection`` [m], those of :data:`POCKET_COLUMNS`,
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
        max_deflection=columns.get("max_deflection"), pressures=columns.get("pressures"),
        **{name: np.asarray(columns[name], float) for name in POCKET_COLUMNS if name in columns})


def report_columns(traj: Trajectory, scale, omega: float | None = None) -> dict[str, np.ndarray]:
    """A trajectory's columns as a person reads them, each headed ``"name [unit]"``.

    Angles in degrees, everything else SI (the load in N and the pocket pressure in Pa from
    ``scale``, :class:`bearingfe.core.scales.Scale`); the restrictor's flow and the pocket's gap
    rate when the run has them (:data:`POCKET_COLUMNS`); with the shaft speed ``omega`` [rad/s]
    also the powers of :func:`power_columns` [W]. The solver's non-dimensional pocket pressure
    and load are kept as extra columns named ``*_nondimensional [-]``.
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
    cols["pocket_pressure [Pa]"] = scale.to_pressure(np.asarray(traj.inlet_pressure, float))
    for name in POCKET_COLUMNS:
        if getattr(traj, name) is not None:
            cols[f"{name} [m^3/s]"] = getattr(traj, name)
    if omega is not None:
        cols.update({f"{name} [W]": v for name, v in power_columns(traj, scale, omega).items()})
    cols.update({"inlet_pressure_nondimensional [-]": traj.inlet_pressure,
                 "load_x_nondimensional [-]": traj.load[:, 0], "load_y_nondimensional [-]": traj.load[:, 1]})
    return {k: np.asarray(v, dtype=float) for k, v in cols.items()}


def power_columns(traj: Trajectory, scale, omega: float) -> dict[str, np.ndarray]:
    """The power lost at each sample [W], by where it goes.

    ``friction_power = M_f omega`` (the film's shear); ``restrictor_power = Q_r (p_ch - p_r)``, the
    flow through the plunger's restrictor times its pressure drop (0 when the pocket is at the
    chamber pressure: no restrictor); ``film_power = Q_film p_r``, the pocket's outflow into the film
    times its drop from the pocket to the surroundings (0 without a pocket). ``pumping_power`` is
    their hydraulic sum and ``total_power`` all three.

    Parameters
    ----------
    traj : Trajectory
    scale : Scale
        The run's scales (the pocket pressure to Pa).
    omega : float
        Shaft speed [rad/s].
    """
    p_r = scale.to_pressure(np.asarray(traj.inlet_pressure, float))
    friction = np.asarray(traj.friction_moment, float) * float(omega)
    film = np.asarray(traj.flow_inlet, float) * p_r
    restrictor = (np.zeros_like(film) if traj.flow_restrictor is None else
                  np.asarray(traj.flow_restrictor, float) * (np.asarray(traj.chamber_pressure, float) - p_r))
    return {"friction_power": friction, "restrictor_power": restrictor, "film_power": film,
            "pumping_power": restrictor + film, "total_power": friction + restrictor + film}


@dataclass(frozen=True)
class CycleLosses:
    """Leakage and power loss of a run over its samples (a cycle): means and peaks [SI].

    Flows in m^3/s (``* 6e4`` for l/min), pressures in Pa, powers in W (the mean power; times
    ``2 pi / omega`` it is the energy of one revolution in J). A peak is the largest sample.

    Attributes
    ----------
    pocket_pressure_mean, pocket_pressure_peak : float
        The pocket pressure (the chamber's when the pocket is not fed through a restrictor) [Pa].
    restrictor_flow_mean, restrictor_flow_peak : float or None
        Flow through the plunger's restrictor [m^3/s]; None without a restrictor.
    pocket_flow_mean, pocket_flow_peak : float
        The pocket's outflow into the film (``flow_inlet``) [m^3/s].
    side_flow_mean, side_flow_peak : float
        Out through the sides ``z = +-a`` (``flow_side``) [m^3/s].
    friction_power, restrictor_power, film_power : float
        Mean of each column of :func:`power_columns` [W].
    """

    pocket_pressure_mean: float
    pocket_pressure_peak: float
    restrictor_flow_mean: float | None
    restrictor_flow_peak: float | None
    pocket_flow_mean: float
    pocket_flow_peak: float
    side_flow_mean: float
    side_flow_peak: float
    friction_power: float
    restrictor_power: float
    film_power: float

    @property
    def pumping_power(self) -> float:
        """Mean hydraulic power lost through the restrictor and the film [W]."""
        return self.restrictor_power + self.film_power

    @property
    def total_power(self) -> float:
        """Mean friction plus pumping power [W]."""
        return self.friction_power + self.pumping_power


def cycle_losses(traj: Trajectory, pump: EccentricPump) -> CycleLosses:
    """The leakage and power loss of a run (:class:`CycleLosses`), from its samples."""
    power = power_columns(traj, pump.scale, pump.drive.omega)
    p_r = pump.scale.to_pressure(np.asarray(traj.inlet_pressure, float))
    q_r = traj.flow_restrictor

    def mean(a) -> float:
        return float(np.mean(a))

    return CycleLosses(pocket_pressure_mean=mean(p_r), pocket_pressure_peak=float(np.max(p_r)),
                       restrictor_flow_mean=None if q_r is None else mean(q_r),
                       restrictor_flow_peak=None if q_r is None else float(np.max(q_r)),
                       pocket_flow_mean=mean(traj.flow_inlet), pocket_flow_peak=float(np.max(traj.flow_inlet)),
                       side_flow_mean=mean(traj.flow_side), side_flow_peak=float(np.max(traj.flow_side)),
                       friction_power=mean(power["friction_power"]), restrictor_power=mean(power["restrictor_power"]),
                       film_power=mean(power["film_power"]))
