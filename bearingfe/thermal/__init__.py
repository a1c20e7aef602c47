"""Thermal models: the lubricant's properties over temperature and the bearing's heat balance.

The Reynolds solvers of the package are isoviscous; this layer says which viscosity the film
really has. Level 1: one effective temperature from the heat balance of the whole film,
iterated to a fixed point with the isoviscous solver.

================  ============================================================
module            what it does
================  ============================================================
``lubricant``     viscosity-temperature laws (constant, Vogel, Walther/ASTM D341), ISO VG grades, density, specific heat
``heat_balance``  level 1: the effective temperature of a journal bearing from its heat balance
``pump_cycle``    level 1 over the pump cycle: the plunger shoe's effective temperature
``files``         the ``[oil]`` fields of scene files: their schema, the lubricant and balance they build
================  ============================================================
"""

from __future__ import annotations

from .lubricant import (ISO_VG, VISCOSITY_LAWS, ConstantViscosity, Lubricant, ViscosityLaw, VogelViscosity,
                        WaltherViscosity, celsius, iso_vg, kelvin)
from .heat_balance import (EffectiveTemperature, FilmTemperatures, HeatBalance, JournalDuty, ThermalError,
                           effective_temperature, film_temperatures)
from .pump_cycle import CycleTemperature, cycle_temperature

__all__ = ["ISO_VG", "VISCOSITY_LAWS", "ConstantViscosity", "Lubricant", "ViscosityLaw", "VogelViscosity",
           "WaltherViscosity", "celsius", "iso_vg", "kelvin", "EffectiveTemperature", "FilmTemperatures",
           "HeatBalance", "JournalDuty", "ThermalError", "effective_temperature", "film_temperatures",
           "CycleTemperature", "cycle_temperature"]
