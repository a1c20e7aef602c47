"""The bearings built on the film solver: journal bearings (fixed and tilting pads), fed pockets, rotor
stability, thrust bearings and the pump's plunger shoe.

================  ============================================================
module            what it does
================  ============================================================
``journal``       Journal bearings with the same Reynolds machinery: performance, equilibrium, dynamic coefficients.
``hydrostatic``   Pockets fed through restrictors (capillary, orifice, constant flow): pressures, flows, stiffness.
``stability``     Stability of a rigid symmetric rotor on two identical bearings: damped eigenvalues, log decrement, Lund's threshold.
``pump``          The eccentric radial-plunger pump: parameters, chamber-pressure cycle, swinging-plunger kinematics.
``tilting_pad``   Tilting-pad journal bearings: equilibrium of the shaft and the pads, and Lund's pad-assembly reduction.
``thrust``        Thrust bearings: annular sector pads on a rotating collar, fixed geometry or tilting on a pivot.
================  ============================================================
"""

from __future__ import annotations

from ..core.lazy import lazy_names

#: Public names by module, imported on first use (PEP 562): the pump's shoe (``bearings.pump``) does not
#: load the journal, tilting-pad and hydrostatic solvers (the main scene starts faster).
_NAMES = {
    "journal": ("DynamicCoefficients", "Groove", "JournalBearing", "equilibrium", "dynamic_coefficients"),
    "hydrostatic": ("SUPPLIES", "Capillary", "ConstantFlow", "Orifice", "PrescribedPressure", "SuppliedResult",
                    "SupplyError", "SupportDynamics", "pocket_transient", "solve_supplied", "supply_dynamics",
                    "supply_stiffness", "JournalDynamics", "journal_dynamics"),
    "pump": ("EccentricPump", "PressureCycle"),
    "stability": ("RotorModes", "log_decrement_map", "lund_threshold", "rotor_modes", "threshold_speed"),
    "tilting_pad": ("PadAssemblyCoefficients", "TiltingPadBearing", "TiltingPadEquilibrium", "TiltingPadGeometry",
                    "pad_assembly_coefficients", "ross_table", "tilting_pad_equilibrium"),
    "thrust": ("AxialCoefficients", "PIVOTS", "SliderPad", "ThrustError", "ThrustPad", "ThrustPerformance",
               "axial_coefficients", "carry", "load_curve", "pad_for_load", "solve_pad", "tilting_equilibrium"),
}
__getattr__, __dir__, __all__ = lazy_names(__name__, _NAMES, globals())
