"""Outputs of a design study: named reductions of a run's result to one float.

Results of a static solve (ReynoldsResult, non-dimensional) and of a
transient (arrays over the cycle, SI) are both accepted: scalars pass
through, arrays reduce over the cycle.
"""

from __future__ import annotations

from typing import Any, Callable

import numpy as np

__all__ = ["OUTPUTS", "STANDARD_OUTPUTS"]


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
