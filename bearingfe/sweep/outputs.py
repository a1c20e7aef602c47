"""Outputs of a design study: named reductions of a run's result to one float.

Results of a static solve (ReynoldsResult, non-dimensional) and of a
transient (arrays over the cycle, SI) are both accepted: scalars pass
through, arrays reduce over the cycle.
"""

from __future__ import annotations

from typing import Any, Callable

import numpy as np

__all__ = ["OUTPUTS", "OUTPUT_UNITS", "SI_OUTPUTS", "STANDARD_OUTPUTS", "csv_headers", "si_columns"]


def _h_min(result) -> float:
    """Smallest film thickness (over the cycle for a transient)."""
    return float(np.min(result.h_min))


def _peak_pressure(result) -> float:
    """Largest pressure (over the cycle for a transient)."""
    for name in ("peak_pressure", "max_pressure", "pressure_max"):
        if hasattr(result, name):
            return float(np.max(getattr(result, name)))
    raise AttributeError(f"{type(result).__name__} has no peak pressure")


def _flow_inlet(result) -> float:
    """Oil drawn from the pockets (mean over the cycle for a transient)."""
    if hasattr(result, "flow_inlet"):
        return float(np.mean(result.flow_inlet))
    return float(result.flows["inlet"])


def _friction_loss(result) -> float:
    """Friction power: moment times journal speed (mean over the cycle).

    Pump run: the run's :func:`~bearingfe.transient.trajectory.cycle_losses` (the pump scene's).
    Non-dimensional static result: ``friction * wedge`` [mu omega^2 R0^4 / c].
    """
    if getattr(result, "losses", None) is not None:
        return float(result.losses.friction_power)
    if hasattr(result, "friction_power"):
        return float(np.mean(result.friction_power))
    return float(result.friction * result.wedge)


def _pumping_power(result) -> float:
    """Hydraulic power lost through the pocket's restrictor and the film (mean over the cycle).

    Pump run: ``restrictor_power + film_power`` of the run's
    :func:`~bearingfe.transient.trajectory.cycle_losses` [W] (the pump scene's). Non-dimensional static
    result: the pockets' outflow times their pressure, ``flows["inlet"] * inlet_pressure``
    [mu omega^2 R0^4 / c] (the film's share of :func:`~bearingfe.transient.trajectory.power_columns`).
    """
    if getattr(result, "losses", None) is not None:
        return float(result.losses.pumping_power)
    if hasattr(result, "flows"):
        return float(result.flows.get("inlet", 0.0) * result.inlet_pressure)
    raise AttributeError(f"{type(result).__name__} has no pumping power (a pump run's losses or a film result)")


def _total_power(result) -> float:
    """Friction plus pumping power (mean over the cycle)."""
    return _friction_loss(result) + _pumping_power(result)


def _load(result) -> float:
    """Magnitude of the film force (static results)."""
    return float(np.hypot(*result.force))


#: Named outputs: ``result -> float``.
OUTPUTS: dict[str, Callable[[Any], float]] = {
    "h_min": _h_min,
    "peak_pressure": _peak_pressure,
    "flow_inlet": _flow_inlet,
    "friction_loss": _friction_loss,
    "pumping_power": _pumping_power,
    "total_power": _total_power,
    "load": _load,
    "balance_ratio": lambda result: float(result.balance_ratio),
}

#: The outputs of the issue: smallest film, peak pressure, inlet flow, friction loss.
STANDARD_OUTPUTS = ("h_min", "peak_pressure", "flow_inlet", "friction_loss")


#: Units of the outputs by run: a pump run reduces SI arrays, a shoe run non-dimensional results.
OUTPUT_UNITS: dict[str, dict[str, str]] = {
    "pump": {"h_min": "m", "peak_pressure": "Pa", "flow_inlet": "m^3/s", "friction_loss": "W", "pumping_power": "W",
             "total_power": "W", "load": "N", "balance_ratio": "-"},
    "shoe": {"h_min": "-", "peak_pressure": "-", "flow_inlet": "-", "friction_loss": "-", "pumping_power": "-",
             "total_power": "-", "load": "-", "balance_ratio": "-"},
}

#: Units of the change builders' values (:data:`bearingfe.sweep.changes.CHANGES`) and the table's own columns.
COLUMN_UNITS = {"pocket_fraction": "-", "pocket_position": "-", "seconds": "s",
                "pump.viscosity": "Pa s", "pump.clearance": "m", "pump.radius": "m"}


#: SI columns of a shoe run's non-dimensional outputs: output -> (SI column, unit, its scale as a function
#: of a :class:`bearingfe.core.scales.Scale`; the scales of :mod:`bearingfe.core.scales`).
SI_OUTPUTS: dict[str, tuple[str, str, Callable[[Any], float]]] = {
    "h_min": ("h_min_si", "m", lambda sc: sc.clearance),
    "peak_pressure": ("peak_pressure_si", "Pa", lambda sc: sc.pressure),
    "flow_inlet": ("flow_inlet_si", "m^3/s", lambda sc: sc.flow),
    "friction_loss": ("friction_loss_si", "W", lambda sc: sc.power),
    "pumping_power": ("pumping_power_si", "W", lambda sc: sc.power),
    "total_power": ("total_power_si", "W", lambda sc: sc.power),
    "load": ("load_si", "N", lambda sc: sc.force),
}


def si_columns(table, scale):
    """``table`` with an SI column beside each non-dimensional output it has (:data:`SI_OUTPUTS`):
    ``<output>_si`` right after ``<output>``, the value times its scale. ``scale`` None: the table as
    given. A new table (pandas.DataFrame); the outputs themselves are kept."""
    if scale is None:
        return table
    out = table.copy()
    for output, (name, _, factor) in SI_OUTPUTS.items():
        if output in out.columns and name not in out.columns:
            out.insert(out.columns.get_loc(output) + 1, name, out[output] * factor(scale))
    return out


def csv_headers(columns, run) -> dict[str, str]:
    """``{column: "column [unit]"}`` for the columns of a sweep table whose unit is known (the outputs of the
    run ``"pump"`` (SI) or ``"shoe"`` (non-dimensional, ``[-]``), a shoe run's SI columns
    (:func:`si_columns`), the change builders and ``seconds``); text
    columns (``status``, ``error``, ``key``...), a dotted-path change and a run given as a function keep
    their names."""
    units = {**(OUTPUT_UNITS.get(run, {}) if isinstance(run, str) else {}), **COLUMN_UNITS,
             **{name: unit for name, unit, _ in SI_OUTPUTS.values()}}
    return {c: f"{c} [{units[c]}]" for c in columns if c in units}
