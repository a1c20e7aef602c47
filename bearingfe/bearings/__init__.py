"""The bearings built on the film solver: journal bearings and the pump's plunger shoe.

================  ============================================================
module            what it does
================  ============================================================
``journal``       Journal bearings with the same Reynolds machinery: performance, equilibrium, dynamic coefficients.
``pump``          The eccentric radial-plunger pump: parameters, chamber-pressure cycle, swinging-plunger kinematics.
================  ============================================================
"""

from __future__ import annotations

from .journal import DynamicCoefficients, Groove, JournalBearing, equilibrium, dynamic_coefficients
from .pump import EccentricPump, PressureCycle

__all__ = ["DynamicCoefficients", "Groove", "JournalBearing", "equilibrium", "dynamic_coefficients",
           "EccentricPump", "PressureCycle"]
