"""The bearings built on the film solver: journal bearings and the pump's plunger shoe.

================  ============================================================
module            what it does
================  ============================================================
``journal``       Journal bearings with the same Reynolds machinery: performance, equilibrium, dynamic coefficients.
``pump``          The eccentric radial-plunger pump: parameters, chamber-pressure cycle, swinging-plunger kinematics.
================  ============================================================
"""
