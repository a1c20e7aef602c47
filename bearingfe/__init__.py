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
``geometry``               support surfaces and pockets, gmsh meshing, untrusted geometry files
``film``                   one film state: film models, forms, compiled operator, superposition, results, FD, FV
``cavitation``             cavitation models and their table (``MODELS``)
``elastic``                elastic supports (half-space, block, shoe body) and the coupled film
``reynolds``               ``solve_reynolds``: the front door of the Reynolds solvers
``adaptivity``             a posteriori error indicators, error-driven adaptive meshes
``bearings``               journal bearings (fixed and tilting pads), rotor stability; pockets fed through restrictors; the pump and its plunger shoe
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

from . import adaptivity, cavitation, elastic, io, scenes, thermal, transient, validation
from .bearings import hydrostatic, journal, pump, stability, tilting_pad
from .film import finite_volume as jfo
from .mechanisms import crank, efficiency, rotor
from .adaptivity import AdaptiveLevel, AdaptiveResult, AdaptivityError, adapt, error_indicators, load_indicators
from .cavitation import CavitationError
from .elastic import Compliance, ElasticError, ElasticSolution, half_space, solve_elastic
from .film.finite_volume import JFOError, solve_jfo
from .core.limits import LimitError
from .film.fd import FDResult, solve_reynolds_fd
from .film.thickness import (CosineFilm, Film, ProfileFilm, StepFilm, SumFilm, TaperFilm, TaperLandFilm,
                             UniformFilm)
from .geometry.surface import Circle, Ellipse, Polygon, Recess, Rectangle, Shape, Slot, Surface
from .core.linalg import DEFAULT_SOLVER, LINEAR_SOLVERS, PatternFactorizer, available_solvers
from .core.machine import Drive, Material
from .mechanisms.machines import (CrankMechanism, CrankSlider, Frame, Linkage, MillDrive, Rotor,
                       RotorFrame, Section)
from .mechanisms.files import LOADERS, load_mechanism
from .geometry.geofiles import GeometryFileError, MeshSizeError, UntrustedGeoError
from .geometry.meshing import SupportMesh, grid_mesh, load_mesh, mesh_surface, refine_uniformly
from .core.parameters import Discretization, OperatingPoint
from .core.scales import Scale
from .reynolds import (CoercivityError, ReynoldsResult, Superposition, operators, solve_reynolds,
                       superpose)
from .scenes import SceneError
from .mechanisms.sections import ibeam, ibeams
from .sweep import CHANGES, OUTPUTS, PumpCase, ShoeCase, best_design, read_study  # module bearingfe.sweep: sweep()
from .core.checks import ResolutionWarning, check_resolution
from .bearings.journal import DynamicCoefficients, Groove, JournalBearing, film_graded_size
from .bearings.pump import EccentricPump, PressureCycle
from .bearings.tilting_pad import TiltingPadBearing, TiltingPadGeometry
from .bearings.hydrostatic import (Capillary, ConstantFlow, Orifice, PrescribedPressure, SupplyError, pocket_transient,
                                   solve_supplied, supply_stiffness)
from .thermal import ConstantViscosity, Lubricant, ThermalError, VogelViscosity, WaltherViscosity
from .transient import LiftOffError, Trajectory, balance_ratio, simulate, steady_state

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
    "supply_stiffness",
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
]
