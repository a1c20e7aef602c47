"""Thermal models: the lubricant's properties over temperature and the bearing's heat balance.

The Reynolds solvers of the package are isoviscous; this layer says which viscosity the film
really has. Level 1: one effective temperature from the heat balance of the whole film,
iterated to a fixed point with the isoviscous solver. Level 2: the film's mean temperature as a field,
with the viscosity varying over the film.

===================  ============================================================
module               what it does
===================  ============================================================
``lubricant``        viscosity-temperature laws (constant, Vogel, Walther/ASTM D341), ISO VG grades, density, specific heat
``viscosity_index``  ASTM D2270: the viscosity index from the 40 and 100 degC viscosities, and back
``heat_balance``     level 1: the effective temperature of a journal bearing from its heat balance
``pump_cycle``       level 1 over the pump cycle: the plunger shoe's effective temperature
``pad_balance``      level 1 of pad bearings (thrust pads, tilting-pad journals): the effective temperature from their heat balance
``film_energy``      level 2: the film's mean temperature field (energy equation) coupled to a Reynolds equation with viscosity varying over the film
``files``            the ``[oil]`` fields of scene and machine files: their schema, the lubricant and balance they build
===================  ============================================================
"""

from __future__ import annotations

from ..core.lazy import lazy_names

#: Public names by module, imported on first use (PEP 562): reading an ``[oil]`` table
#: (``thermal.files``) does not import the journal solver behind the heat balance.
_NAMES = {
    "lubricant": ("ISO_VG", "VISCOSITY_LAWS", "ConstantViscosity", "Lubricant", "ViscosityLaw", "VogelViscosity",
                  "WaltherViscosity", "celsius", "iso_vg", "kelvin"),
    "heat_balance": ("EffectiveTemperature", "FilmTemperatures", "HeatBalance", "JournalDuty", "ThermalError",
                     "effective_temperature", "film_temperatures", "mixed_inlet"),
    "viscosity_index": ("reference_viscosities", "viscosity_40", "viscosity_100", "viscosity_index"),
    "film_energy": ("FilmEnergy", "Pad", "PadLevel1", "film_energy", "journal_pad", "pad_level1", "pad_mesh",
                    "slider_reference"),
    "pump_cycle": ("CycleTemperature", "cycle_temperature", "shoe_pad"),
    "pad_balance": ("ThrustTemperature", "TiltingPadTemperature", "thrust_temperature", "tilting_pad_temperature"),
}
__getattr__, __dir__, __all__ = lazy_names(__name__, _NAMES, globals())
