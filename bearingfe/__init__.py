"""bearingfe: finite-element Reynolds solver for bearing supports with inlet pockets.

Modules in data-flow order: input files and geometry, meshes, the film and its
parameters, the Reynolds solvers and the models built on them, the machines,
studies and scenes, and the outputs at the edge.

=========================  =====================================================
module                     what it does
=========================  =====================================================
``version``                the package version
``schema``                 one schema for input files: field checks, tables, errors
``limits``                 size guards (revolutions, frames, cases, elements, case time)
``geometry``               support-surface outlines, inlet pockets and recesses (any shape)
``geofiles``               untrusted geometry files: ``.geo`` allow-list and sandbox, ``.msh`` as data
``gmsh_worker``            the child process in which gmsh parses and meshes one ``.geo`` script
``meshing``                gmsh meshing, structured grids, ``.geo``/``.msh`` reading, named edges, periodic seams
``film``                   film-thickness models (``CosineFilm``)
``parameters``             operating point and discretization objects (``operating=``)
``checks``                 ranges of solver inputs, thin-film resolution check (``ResolutionWarning``)
``forms``                  weak forms; pressure (pi chain rule), flux and shear formulas
``linalg``                 pluggable sparse solvers, factorizations that keep their ordering
``compiled``               compiled film operator: film-independent maps of a mesh, built once
``superposition``          per-mesh operators, one film state's condensed system, results
``cavitation``             cavitation models and their table (``MODELS``)
``jfo``                    mass-conserving (JFO / Elrod-Adams p-theta) cavitation, finite volumes
``elastic``                elastic support (EHD): half-space and shoe-body compliance, coupled film
``shoe_body``              the real shoe body: 3-D gmsh mesh, linear elasticity, compliance on the film dofs
``reynolds``               ``solve_reynolds``: the front door of the Reynolds solvers
``fd``                     finite-difference reference (the source paper's scheme)
``adaptivity``             a posteriori error indicators, error-driven adaptive meshes
``scales``                 non-dimensional <-> SI conversion
``journal``                journal bearings: charts, equilibrium, dynamic coefficients
``machines``               shared parameter objects of machines (SI)
``sections``               rolled-steel sections (GOST 8239 I-beams) for frames
``mechanism_files``        TOML parameter files in ``mechanisms/``
``pump``                   eccentric radial-plunger pump, swinging-plunger kinematics
``transient``              the plunger shoe over the pump cycle (``simulate``)
``transient_jfo``          the pump cycle under JFO cavitation: the film's history (theta)
``elastic_transient``      the pump cycle on an elastic support with the deflection's squeeze
``crank``                  crank-slider kinematics and inertia forces
``efficiency``             crank-slider efficiency against the pressure angle
``rotor``                  unbalanced rotor on an elastic frame
``validation``             closed-form and published-data checks
``sweep``                  design studies in processes or on a Dask cluster
``scenes``                 scene files run by the command line (``reynolds`` kind, registry)
``scene_pump``             the pump scene: shoe with and without its pocket over a revolution
``scene_journal``          the journal scene: a journal bearing from a file in SI units
``io``                     VTU/PVD, CSV and JSON outputs (atomic writes)
``outfolder``              output folders: manifest, lock, all-or-nothing move into place
``plot``                   pyvista fields and matplotlib curves (lazy imports)
``cli``                    the ``bearingfe`` command
=========================  =====================================================
"""

from . import (adaptivity, cavitation, crank, elastic, efficiency, io, jfo, journal, pump, rotor, scenes, transient,
               validation)
from .adaptivity import AdaptiveLevel, AdaptiveResult, AdaptivityError, adapt, error_indicators, load_indicators
from .cavitation import CavitationError
from .elastic import Compliance, ElasticError, ElasticSolution, half_space, solve_elastic
from .jfo import JFOError, solve_jfo
from .limits import LimitError
from .fd import FDResult, solve_reynolds_fd
from .film import CosineFilm, Film
from .geometry import Circle, Ellipse, Polygon, Recess, Rectangle, Shape, Slot, Surface
from .linalg import DEFAULT_SOLVER, LINEAR_SOLVERS, PatternFactorizer, available_solvers
from .machines import (CrankMechanism, CrankSlider, Drive, Frame, Linkage, Material, MillDrive, Rotor,
                       RotorFrame, Section)
from .mechanism_files import LOADERS, load_mechanism
from .geofiles import GeometryFileError, MeshSizeError, UntrustedGeoError
from .meshing import SupportMesh, grid_mesh, load_mesh, mesh_surface, refine_uniformly
from .parameters import Discretization, OperatingPoint
from .scales import Scale
from .reynolds import (CoercivityError, ReynoldsResult, Superposition, operators, solve_reynolds,
                       superpose)
from .scenes import SceneError
from .sections import ibeam, ibeams
from .sweep import CHANGES, OUTPUTS, PumpCase, ShoeCase, best_design, read_study  # module bearingfe.sweep: sweep()
from .checks import ResolutionWarning, check_resolution
from .journal import DynamicCoefficients, Groove, JournalBearing, film_graded_size
from .pump import EccentricPump, PressureCycle
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
    "film_graded_size", "journal",
    "EccentricPump", "LiftOffError", "PressureCycle", "Trajectory", "balance_ratio", "pump", "simulate",
    "steady_state", "transient",
    "Circle", "CoercivityError", "CosineFilm", "CrankMechanism", "CrankSlider", "Drive", "Ellipse",
    "DEFAULT_SOLVER", "FDResult", "Film", "Frame", "LINEAR_SOLVERS", "PatternFactorizer", "available_solvers", "LOADERS", "Linkage", "Material", "MillDrive", "Polygon", "Recess",
    "Rectangle", "ReynoldsResult", "Rotor", "RotorFrame", "Scale", "Section", "Shape", "Slot", "Superposition",
    "GeometryFileError", "MeshSizeError", "UntrustedGeoError", "check_resolution",
    "SupportMesh", "Surface", "crank", "efficiency", "ibeam", "ibeams", "load_mechanism", "load_mesh",
    "mesh_surface", "grid_mesh", "operators", "refine_uniformly", "rotor", "solve_reynolds", "solve_reynolds_fd", "superpose",
]
