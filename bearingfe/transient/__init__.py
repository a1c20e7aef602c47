"""The plunger shoe over the pump cycle.

================  ============================================================
module            what it does
================  ============================================================
``quasi_static``  The plunger shoe over the pump cycle: quasi-static equilibrium integrated in time.
``jfo``           The plunger shoe over the pump cycle with mass-conserving (JFO) cavitation: the film's history.
``elastic``       The plunger shoe on an elastic support over the pump cycle, with the squeeze of the deflection.
================  ============================================================
"""

from __future__ import annotations
from .quasi_static import (Trajectory, simulate, steady_state, balance_ratio, pump_mesh, state_result, LiftOffError, INTEGRATORS, IMPLICIT_INTEGRATORS, STARTS)
from .jfo import (JFORun, jfo_run)
from .quasi_static import PERIODIC_METHODS
from .elastic import (simulate_elastic, BAUMGARTE)

__all__ = ['Trajectory', 'simulate', 'steady_state', 'balance_ratio', 'pump_mesh', 'state_result', 'LiftOffError', 'INTEGRATORS', 'IMPLICIT_INTEGRATORS', 'STARTS', 'JFORun', 'jfo_run', 'simulate_elastic', 'BAUMGARTE', 'PERIODIC_METHODS']
