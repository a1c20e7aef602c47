"""The rigid film with film rupture: the Swift-Stieber (``"reynolds"``) or Gumbel condition at every state.

The rates that balance the plunger load no longer follow from a 2x2 linear
system: :func:`bearingfe.cavitation.rates_for_load` finds them by a small
Newton on the cavitated film force, warm-started from the rupture set of the
previous evaluation (the integrator's states follow each other closely).
Everything else is the rigid model's (:class:`bearingfe.transient.rigid.Rigid`).
"""

from __future__ import annotations

import numpy as np

from ..bearings.pump import EccentricPump
from ..cavitation import rates_for_load
from ..core import DEFAULT_SOLVER
from ..film import Superposition
from ..geometry import SupportMesh
from .rigid import Rigid

__all__ = ["Cavitating", "CAVITATION_MODELS"]

#: The cavitation models of :data:`bearingfe.cavitation.MODELS` this model integrates.
CAVITATION_MODELS = ("reynolds", "gumbel")


class Cavitating(Rigid):
    """The rigid film with a cavitation condition (``"reynolds"`` or ``"gumbel"``).

    Parameters
    ----------
    pump, mesh, formulation, element, solver
        As :class:`~bearingfe.transient.rigid.Rigid`.
    cavitation : {"reynolds", "gumbel"}
    """

    name = "cavitating"

    def __init__(self, pump: EccentricPump, mesh: SupportMesh, *, cavitation: str = "reynolds",
                 formulation: str = "pi", element: str = "P1", solver: str = DEFAULT_SOLVER) -> None:
        if cavitation not in CAVITATION_MODELS:
            raise ValueError(f"cavitation must be one of {CAVITATION_MODELS}, got {cavitation!r}")
        super().__init__(pump, mesh, formulation=formulation, element=element, solver=solver)
        self.cavitation = cavitation
        self._warm = None  # the last cavitated result: its rupture set starts the next Newton

    def balancing_rates(self, sup: Superposition, load: np.ndarray, wedge: float, inlet_pressure: float):
        """``(rates, cavitated result)`` by the warm-started Newton of :func:`bearingfe.cavitation.rates_for_load`."""
        found = rates_for_load(sup, load, wedge, inlet_pressure, model=self.cavitation, warm_start=self._warm,
                               solver=self.solver)
        self._warm = found.result
        return found.rates, found.result
