"""The bearings built on the film solver: journal bearings and the pump's plunger shoe.

================  ============================================================
module            what it does
================  ============================================================
``journal``       Journal bearings with the same Reynolds machinery: performance, equilibrium, dynamic coefficients.
``hydrostatic``   Pockets fed through restrictors (capillary, orifice, constant flow): pressures, flows, stiffness.
``pump``          The eccentric radial-plunger pump: parameters, chamber-pressure cycle, swinging-plunger kinematics.
================  ============================================================
"""

from __future__ import annotations

from .journal import DynamicCoefficients, Groove, JournalBearing, equilibrium, dynamic_coefficients
from .hydrostatic import (SUPPLIES, Capillary, ConstantFlow, Orifice, PrescribedPressure, SuppliedResult, SupplyError,
                          pocket_transient, solve_supplied, supply_stiffness)
from .pump import EccentricPump, PressureCycle

__all__ = ["DynamicCoefficients", "Groove", "JournalBearing", "equilibrium", "dynamic_coefficients",
           "EccentricPump", "PressureCycle", "SUPPLIES", "Capillary", "ConstantFlow", "Orifice", "PrescribedPressure",
           "SuppliedResult", "SupplyError", "pocket_transient", "solve_supplied", "supply_stiffness"]
