"""bearingfe: finite-element Reynolds solver for bearing supports with inlet pockets.

Read from the bottom up, the folders are the pipeline: the parameter objects and
checks every layer uses, the support surface and its meshes, one film state,
the cavitation and elastic models built on it, the front door that chooses among
them, the bearings and the pump transient built on the front door, the machines
around the bearings, and at the edge the scenes, studies, files and pictures.
Each subpackage's docstring tables its modules.

=========================  =====================================================
module or package          what it does
=========================  =====================================================
``version``                the package version
``core``                   input schema, size limits, checks, scales, parameter objects, sparse solvers
``geometry``               support surfaces and pockets, the runner's motion, gmsh meshing, untrusted geometry files
``film``                   one film state: film models, forms, compiled operator, superposition, results, FD, FV
``cavitation``             cavitation models and their table (``MODELS``)
``elastic``                elastic supports (half-space, block, shoe body) and the coupled film
``reynolds``               ``solve_reynolds``: the front door of the Reynolds solvers
``adaptivity``             a posteriori error indicators, error-driven adaptive meshes
``bearings``               journal bearings (fixed and tilting pads), thrust bearings, rotor stability; pockets fed through restrictors; the pump and its plunger shoe
``validation``             closed-form and published-data checks
``thermal``                lubricants (viscosity-temperature laws, ISO VG, density, specific heat); heat balance
``transient``              the plunger shoe over the pump cycle (``simulate``)
``mechanisms``             crank drives, efficiency, rotors on frames, machine files (``mechanisms/*.toml``)
``sweep``                  design studies in processes or on a Dask cluster
``scenes``                 scene files run by the command line (``SCENES``)
``io``                     VTU/PVD, CSV and JSON outputs (atomic writes), output folders
``plot``                   pyvista fields and matplotlib curves (lazy imports)
``cli``                    the ``bearingfe`` command
=========================  =====================================================
"""


# The names are imported on first use (PEP 562), not on ``import bearingfe``: a run of one scene or
# ``bearingfe --version`` then loads only the modules it needs (the command line starts in a fraction of
# the time of importing every subpackage). ``from bearingfe import X`` and ``bearingfe.X`` work as before.
import importlib as _importlib
from importlib.util import find_spec as _find_spec

#: Public modules: name -> module path inside the package.
_MODULES = {
    "adaptivity": "adaptivity",
    "cavitation": "cavitation",
    "elastic": "elastic",
    "io": "io",
    "scenes": "scenes",
    "thermal": "thermal",
    "transient": "transient",
    "validation": "validation",
    "hydrostatic": "bearings.hydrostatic",
    "journal": "bearings.journal",
    "pump": "bearings.pump",
    "stability": "bearings.stability",
    "tilting_pad": "bearings.tilting_pad",
    "thrust": "bearings.thrust",
    "jfo": "film.finite_volume",
    "crank": "mechanisms.crank",
    "efficiency": "mechanisms.efficiency",
    "rotor": "mechanisms.rotor",
    "sweep": "sweep",
}
#: Public names: module path inside the package -> the names it gives.
_NAMES = {
    "adaptivity": ('AdaptiveLevel', 'AdaptiveResult', 'AdaptivityError', 'adapt', 'error_indicators',
                   'load_indicators'),
    "cavitation": ('CavitationError',),
    "elastic": ('Compliance', 'ElasticError', 'ElasticSolution', 'half_space', 'solve_elastic'),
    "film.finite_volume": ('JFOError', 'solve_jfo'),
    "core.limits": ('LimitError',),
    "film.fd": ('FDResult', 'solve_reynolds_fd'),
    "film.thickness": ('CosineFilm', 'Film', 'PlaneFilm', 'PolarProfileFilm', 'ProfileFilm', 'StepFilm', 'SumFilm', 'TaperFilm', 'TaperLandFilm',
                       'UniformFilm'),
    "geometry.runner": ('Rotating', 'Translating'),
    "geometry.surface": ('AnnularSector', 'Circle', 'Ellipse', 'Polygon', 'Recess', 'Rectangle', 'Shape', 'Slot', 'Surface'),
    "core.linalg": ('DEFAULT_SOLVER', 'LINEAR_SOLVERS', 'PatternFactorizer', 'available_solvers'),
    "core.machine": ('Drive', 'Material'),
    "mechanisms.machines": ('CrankMechanism', 'CrankSlider', 'Frame', 'Linkage', 'MillDrive', 'Rotor', 'RotorFrame',
                            'Section'),
    "mechanisms.files": ('LOADERS', 'load_mechanism'),
    "geometry.geofiles": ('GeometryFileError', 'MeshSizeError', 'UntrustedGeoError'),
    "geometry.meshing": ('SupportMesh', 'grid_mesh', 'load_mesh', 'mesh_surface', 'refine_uniformly'),
    "core.parameters": ('Discretization', 'OperatingPoint'),
    "core.scales": ('Scale',),
    "reynolds": ('CoercivityError', 'ReynoldsResult', 'Superposition', 'operators', 'solve_reynolds', 'superpose'),
    "scenes": ('SceneError',),
    "mechanisms.sections": ('ibeam', 'ibeams'),
    "sweep": ('CHANGES', 'OUTPUTS', 'PumpCase', 'ShoeCase', 'best_design', 'read_study'),
    "core.checks": ('ResolutionWarning', 'check_resolution'),
    "bearings.journal": ('DynamicCoefficients', 'Groove', 'JournalBearing', 'film_graded_size'),
    "bearings.pump": ('EccentricPump', 'PressureCycle'),
    "bearings.tilting_pad": ('TiltingPadBearing', 'TiltingPadGeometry'),
    "bearings.thrust": ('SliderPad', 'ThrustPad', 'pad_for_load', 'tilting_equilibrium'),
    "bearings.hydrostatic": ('Capillary', 'ConstantFlow', 'Orifice', 'PrescribedPressure', 'SupplyError',
                             'journal_dynamics', 'pocket_transient', 'solve_supplied', 'supply_dynamics',
                             'supply_stiffness'),
    "thermal": ('ConstantViscosity', 'Lubricant', 'ThermalError', 'VogelViscosity', 'WaltherViscosity'),
    "transient": ('LiftOffError', 'Trajectory', 'balance_ratio', 'simulate', 'steady_state'),
}
_ORIGIN = {name: module for module, names in _NAMES.items() for name in names}


def __getattr__(name: str):
    """Import a public name's module on first use and keep the name (PEP 562)."""
    if name in _MODULES:
        value = _importlib.import_module(f"{__name__}.{_MODULES[name]}")
    elif name in _ORIGIN:
        value = getattr(_importlib.import_module(f"{__name__}.{_ORIGIN[name]}"), name)
    elif not name.startswith("_") and _find_spec(f"{__name__}.{name}") is not None:
        value = _importlib.import_module(f"{__name__}.{name}")  # a subpackage: bearingfe.film, ...
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))


from .version import __version__

__all__ = [
    "AdaptiveLevel", "AdaptiveResult", "AdaptivityError", "adapt", "adaptivity", "error_indicators",
    "load_indicators",
    "LimitError",
    "Discretization", "OperatingPoint",
    "CHANGES", "OUTPUTS", "PumpCase", "SceneError", "ShoeCase", "best_design", "io", "read_study", "scenes", "sweep",
    "validation",
    "Compliance", "ElasticError", "ElasticSolution", "elastic", "half_space", "solve_elastic",
    "CavitationError", "JFOError", "jfo", "solve_jfo", "DynamicCoefficients", "Groove", "JournalBearing", "ResolutionWarning", "cavitation",
    "film_graded_size", "journal", "TiltingPadBearing", "TiltingPadGeometry", "tilting_pad", "stability",
    "Capillary", "ConstantFlow", "Orifice", "PrescribedPressure", "SupplyError", "hydrostatic", "pocket_transient", "solve_supplied",
    "supply_dynamics", "supply_stiffness", "journal_dynamics",
    "EccentricPump", "LiftOffError", "PressureCycle", "Trajectory", "balance_ratio", "pump", "simulate",
    "steady_state", "transient",
    "Circle", "CoercivityError", "CosineFilm", "ProfileFilm", "StepFilm", "SumFilm", "TaperFilm",
    "TaperLandFilm", "UniformFilm", "CrankMechanism", "CrankSlider", "Drive", "Ellipse",
    "DEFAULT_SOLVER", "FDResult", "Film", "Frame", "LINEAR_SOLVERS", "PatternFactorizer", "available_solvers", "LOADERS", "Linkage", "Material", "MillDrive", "Polygon", "Recess",
    "Rectangle", "ReynoldsResult", "Rotor", "RotorFrame", "Scale", "Section", "Shape", "Slot", "Superposition",
    "GeometryFileError", "MeshSizeError", "UntrustedGeoError", "check_resolution",
    "SupportMesh", "Surface", "crank", "efficiency", "ibeam", "ibeams", "load_mechanism", "load_mesh",
    "mesh_surface", "grid_mesh", "operators", "refine_uniformly", "rotor", "solve_reynolds", "solve_reynolds_fd", "superpose",
    "thermal", "ConstantViscosity", "Lubricant", "ThermalError", "VogelViscosity", "WaltherViscosity",
    "AnnularSector", "PlaneFilm", "PolarProfileFilm", "Rotating", "SliderPad", "ThrustPad", "Translating",
    "pad_for_load", "thrust", "tilting_equilibrium",
]
