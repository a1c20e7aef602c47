"""Every name a user imports from ``bearingfe`` keeps working across the package's reorganisations.

The expected list is the package's public ``__all__`` as it stood before the
modules moved into folders (96 names, written out here so that a name cannot
vanish with the code that defines it). Deeper module paths may change; these may not.
"""

import types

import pytest

import bearingfe as bf

PUBLIC = (
    "AdaptiveLevel", "AdaptiveResult", "AdaptivityError", "CHANGES", "CavitationError", "Circle", "CoercivityError",
    "Compliance", "CosineFilm", "CrankMechanism", "CrankSlider", "DEFAULT_SOLVER", "Discretization", "Drive",
    "DynamicCoefficients", "EccentricPump", "ElasticError", "ElasticSolution", "Ellipse", "FDResult", "Film", "Frame",
    "GeometryFileError", "Groove", "JFOError", "JournalBearing", "LINEAR_SOLVERS", "LOADERS", "LiftOffError",
    "LimitError", "Linkage", "Material", "MeshSizeError", "MillDrive", "OUTPUTS", "OperatingPoint",
    "PatternFactorizer", "Polygon", "PressureCycle", "PumpCase", "Recess", "Rectangle", "ResolutionWarning",
    "ReynoldsResult", "Rotor", "RotorFrame", "Scale", "SceneError", "Section", "Shape", "ShoeCase", "Slot",
    "Superposition", "SupportMesh", "Surface", "Trajectory", "UntrustedGeoError", "adapt", "adaptivity",
    "available_solvers", "balance_ratio", "best_design", "cavitation", "check_resolution", "crank", "efficiency",
    "elastic", "error_indicators", "film_graded_size", "grid_mesh", "half_space", "ibeam", "ibeams", "io", "jfo",
    "journal", "load_indicators", "load_mechanism", "load_mesh", "mesh_surface", "operators", "pump", "read_study",
    "refine_uniformly", "rotor", "scenes", "simulate", "solve_elastic", "solve_jfo", "solve_reynolds",
    "solve_reynolds_fd", "steady_state", "superpose", "sweep", "transient", "validation",
)
#: Of those, the ones that are modules (or packages) a user reaches names through.
MODULES = ("adaptivity", "cavitation", "crank", "efficiency", "elastic", "io", "jfo", "journal", "pump", "rotor",
           "scenes", "sweep", "transient", "validation")


def test_the_list_is_the_one_of_record():
    assert len(PUBLIC) == len(set(PUBLIC)) == 96


@pytest.mark.parametrize("name", PUBLIC)
def test_every_public_name_is_still_there(name):
    assert name in bf.__all__, f"bearingfe.__all__ lost {name!r}"
    value = getattr(bf, name)
    assert isinstance(value, types.ModuleType) == (name in MODULES)


@pytest.mark.parametrize("module, names", [
    ("cavitation", ("MODELS", "ModelOptions", "rates_for_load", "solve_cavitating", "ObstacleProblem")),
    ("elastic", ("Compliance", "half_space", "solve_elastic", "balance_load", "ChordBalance", "shoe_compliance")),
    ("transient", ("simulate", "steady_state", "Trajectory", "pump_mesh", "state_result", "simulate_elastic")),
    ("io", ("write_vtu", "write_pvd", "write_csv", "write_json")),
    ("jfo", ("solve_jfo", "JFOError")),
    ("journal", ("JournalBearing", "equilibrium", "dynamic_coefficients", "performance")),
    ("pump", ("EccentricPump", "PressureCycle")),
    ("hydrostatic", ("SUPPLIES", "Capillary", "Orifice", "ConstantFlow", "PrescribedPressure", "solve_supplied",
                     "supply_stiffness", "SupplyError")),
    ("stability", ("rotor_modes", "lund_threshold", "log_decrement_map", "threshold_speed")),
    ("tilting_pad", ("TiltingPadBearing", "TiltingPadGeometry", "tilting_pad_equilibrium", "pad_assembly_coefficients",
                     "reduced_coefficients")),
    ("scenes", ("SCENES", "run_scene", "load_scene")),
    ("thermal", ("Lubricant", "VISCOSITY_LAWS", "ISO_VG", "iso_vg", "WaltherViscosity", "VogelViscosity",
                 "HeatBalance", "JournalDuty", "effective_temperature", "ThermalError")),
])
def test_the_modules_keep_their_main_names(module, names):
    # the names the README, the examples and the docs reach through bf.<module>
    missing = [n for n in names if not hasattr(getattr(bf, module), n)]
    assert missing == []
