"""Outputs of a design study: named reductions of a run's result to one float.

Results of a static solve (ReynoldsResult, non-dimensional) and of a
transient (arrays over the cycle, SI) are both accepted: scalars pass
through, arrays reduce over the cycle.
"""

from __future__ import annotations

from typing import Any, Callable

import numpy as np

__all__ = ["OUTPUTS", "OUTPUT_UNITS", "STANDARD_OUTPUTS", "csv_headers"]


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

    Non-dimensional static result: ``friction * wedge`` [mu omega^2 R0^4 / c].
    """
    if hasattr(result, "friction_power"):
        return float(np.mean(result.friction_power))
    return float(result.friction * result.wedge)


def _load(result) -> float:
    """Magnitude of the film force (static results)."""
    return float(np.hypot(*result.force))


#: Named outputs: ``result -> float``.
OUTPUTS: dict[str, Callable[[Any], float]] = {
    "h_min": _h_min,
    "peak_pressure": _peak_pressure,
    "flow_inlet": _flow_inlet,
    "friction_loss": _friction_loss,
    "load": _load,
    "balance_ratio": lambda result: float(result.balance_ratio),
}

#: The outputs of the issue: smallest film, peak pressure, inlet flow, friction loss.
STANDARD_OUTPUTS = ("h_min", "peak_pressure", "flow_inlet", "friction_loss")


#: Units of the outputs by run: a pump run reduces SI arrays, a shoe run non-dimensional results.
OUTPUT_UNITS: dict[str, dict[str, str]] = {
    "pump": {"h_min": "m", "peak_pressure": "Pa", "flow_inlet": "m^3/s", "friction_loss": "W", "load": "N",
             "balance_ratio": "-"},
    "shoe": {"h_min": "-", "peak_pressure": "-", "flow_inlet": "-", "friction_loss": "-", "load": "-",
             "balance_ratio": "-"},
}

#: Units of the change builders' values (:data:`bearingfe.sweep.changes.CHANGES`) and the table's own columns.
COLUMN_UNITS = {"pocket_fraction": "-", "pocket_position": "-", "seconds": "s",
                "pump.viscosity": "Pa s", "pump.clearance": "m", "pump.radius": "m"}


def csv_headers(columns, run) -> dict[str, str]:
    """``{column: "column [unit]"}`` for the columns of a sweep table whose unit is known (the outputs of the
    run ``"pump"`` (SI) or ``"shoe"`` (non-dimensional, ``[-]``), the change builders and ``seconds``); text
    columns (``status``, ``error``, ``key``...), a dotted-path change and a run given as a function keep
    their names."""
    units = {**(OUTPUT_UNITS.get(run, {}) if isinstance(run, str) else {}), **COLUMN_UNITS}
    return {c: f"{c} [{units[c]}]" for c in columns if c in units}
