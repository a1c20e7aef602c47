"""Cases of a design study: parameter objects and the run functions that solve them.

:data:`RUNS` names the run functions (``parameter object -> result``) and
:data:`BASES` the default parameter objects of study files. The run
functions are top level here, so they pickle by reference to worker
processes and Dask workers.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable

import numpy as np

from ..geometry.surface import Circle, Surface
from ..core.parameters import ELEMENTS
from ..core.schema import one_of

if TYPE_CHECKING:  # the transient is imported when a pump case runs
    from ..transient.trajectory import CycleLosses

__all__ = ["BASES", "RUNS", "FilmRuptured", "PumpCase", "PumpOutcome", "ShoeCase", "run_pump", "run_shoe"]


class FilmRuptured(RuntimeError):
    """The film of a case closed over the cycle (the run's status ``"ruptured"``): a result of the study,
    the design does not carry its load, not a failure of the program; the table's ``status`` says
    ``"ruptured"``."""


# -- a cheap static case (built on the core) ----------------------------------

@functools.lru_cache(maxsize=1)
def _default_shoe_surface() -> Surface:
    """The default shoe of :class:`ShoeCase`, built on first use (its layout checks take ~50 ms,
    which a class-level default spent at every ``import bearingfe``)."""
    return Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=(Circle((0.0, 0.0), 0.12),))


@dataclass(frozen=True)
class ShoeCase:
    """A shoe with pockets under a fixed film: one static Reynolds solve.

    Parameters
    ----------
    surface : Surface
        Outline and pockets in ``(phi, z)``.
    gamma : float
        Relative eccentricity of the cosine film [-], >= 0.
    phi0 : float
        Angle of the thickest film [rad]; the film is thinnest at ``phi0 + pi``.
    inlet_pressure : float
        Non-dimensional pocket pressure ``p_s`` [-] (ignored without pockets).
    mesh_size : float
        gmsh element size [-], > 0.
    element : {"P1", "P2"}
    """

    surface: Surface = field(default_factory=lambda: _default_shoe_surface())
    gamma: float = 0.6
    phi0: float = math.pi
    inlet_pressure: float = 1.0
    mesh_size: float = 0.08
    element: str = "P1"

    def __post_init__(self) -> None:
        if not isinstance(self.surface, Surface):
            raise ValueError(f"ShoeCase.surface must be a bearingfe.Surface, got {type(self.surface).__name__}")
        for name, low in (("gamma", 0.0), ("phi0", -math.inf), ("inlet_pressure", -math.inf)):
            value = float(getattr(self, name))
            if not (math.isfinite(value) and value >= low):
                raise ValueError(f"ShoeCase.{name} must be a finite number >= {low}, got {getattr(self, name)!r}")
            object.__setattr__(self, name, value)
        size = float(self.mesh_size)
        if not (math.isfinite(size) and size > 0):
            raise ValueError(f"ShoeCase.mesh_size must be a finite number > 0, got {self.mesh_size!r}")
        object.__setattr__(self, "mesh_size", size)
        one_of("ShoeCase.element", self.element, ELEMENTS)


def run_shoe(case: ShoeCase):
    """Mesh the shoe and solve the static Reynolds problem -> :class:`ReynoldsResult`.

    Raises ``ValueError`` if the film closes on the surface (``h_min <= 0``).
    """
    from ..film.thickness import CosineFilm
    from ..geometry.meshing import mesh_surface
    from ..reynolds import solve_reynolds

    mesh = mesh_surface(case.surface, case.mesh_size)
    pressure = case.inlet_pressure if case.surface.inlets else 0.0
    return solve_reynolds(mesh, CosineFilm(case.gamma, case.phi0), inlet_pressure=pressure,
                          element=case.element)


# -- the pump over its cycle -----------------------------------------------------------

_PUMP_FILE = Path(__file__).resolve().parents[2] / "mechanisms" / "eccentric_pump.toml"


def _shipped_pump():
    from ..mechanisms.files import load_mechanism

    if not _PUMP_FILE.is_file():
        raise ValueError(f"the shipped pump file is not here ({_PUMP_FILE}); give [base] a pump of your own")
    return load_mechanism(_PUMP_FILE)


@dataclass(frozen=True)
class PumpCase:
    """The eccentric pump over one revolution, with the run's numerical settings.

    Parameters
    ----------
    pump : EccentricPump
        Default: ``mechanisms/eccentric_pump.toml``. Its ``surface`` is what
        the pocket changes act on (``pump.surface``).
    mesh_size : float
        Element size [R0], > 0.
    element : {"P1", "P2"}
        P2 runs on a curved (order-2) mesh.
    start : {"periodic", "steady"}
        Converged periodic state, or the steady state at the start angle.
    cavitation : {"none", "reynolds", "gumbel"}
    """

    pump: Any = field(default_factory=_shipped_pump)
    mesh_size: float = 0.2
    element: str = "P2"
    start: str = "periodic"
    cavitation: str = "none"

    def __post_init__(self) -> None:
        from ..cavitation import MODELS
        from ..bearings.pump import EccentricPump
        from ..transient import STARTS

        if not isinstance(self.pump, EccentricPump):
            raise ValueError(f"PumpCase.pump must be a bearingfe.EccentricPump, got {type(self.pump).__name__}")
        size = float(self.mesh_size)
        if not (math.isfinite(size) and size > 0):
            raise ValueError(f"PumpCase.mesh_size must be a finite number > 0, got {self.mesh_size!r}")
        object.__setattr__(self, "mesh_size", size)
        for name, allowed in (("element", ELEMENTS), ("start", STARTS), ("cavitation", MODELS)):
            one_of(f"PumpCase.{name}", getattr(self, name), allowed)


@dataclass(frozen=True)
class PumpOutcome:
    """What a design study keeps of one pump revolution (SI units).

    ``h_min`` [m], ``flow_inlet`` [m^3/s] and ``friction_power`` [W] are
    arrays over the cycle; ``peak_pressure`` [Pa] is the largest film or
    pocket pressure over a dozen states spread over the cycle; ``losses`` the
    run's leakage and mean power lost (friction, restrictor, film:
    :func:`bearingfe.transient.trajectory.cycle_losses`, as the pump scene reports them).
    """

    h_min: np.ndarray
    flow_inlet: np.ndarray
    friction_power: np.ndarray
    peak_pressure: float
    balance_ratio: float
    losses: CycleLosses | None = None


def run_pump(case: PumpCase) -> PumpOutcome:
    """Simulate one revolution of ``case.pump``; :class:`FilmRuptured` if the film closes, ``RuntimeError``
    if the run stops for another reason, ``LiftOffError`` if the shoe lifts off."""
    from ..transient import pump_mesh, simulate, state_result
    from ..transient.trajectory import cycle_losses, power_columns

    pump = case.pump
    mesh = pump_mesh(pump, case.mesh_size, order=2 if case.element == "P2" else 1)
    traj = simulate(pump, mesh, 1.0, start=case.start, element=case.element, cavitation=case.cavitation)
    if traj.status == "ruptured":
        raise FilmRuptured(traj.message)
    if traj.status != "completed":
        raise RuntimeError(traj.message)
    frames = np.unique(np.linspace(0, traj.beta.size - 1, 12).astype(int))
    peak = max(float(state_result(pump, mesh, traj, k, case.cavitation, case.element).max_pressure)
               for k in frames) * pump.scale.pressure
    return PumpOutcome(h_min=traj.h_min, flow_inlet=traj.flow_inlet,
                       friction_power=power_columns(traj, pump.scale, pump.drive.omega)["friction_power"],
                       peak_pressure=peak, balance_ratio=traj.stats["balance_ratio"], losses=cycle_losses(traj, pump))


#: Run functions by name: ``parameter object -> result``.
RUNS: dict[str, Callable[[Any], Any]] = {"shoe": run_shoe, "pump": run_pump}

#: Base parameter objects by name (study files): ``() -> default object``.
BASES: dict[str, Callable[[], Any]] = {"shoe": ShoeCase, "pump": PumpCase}
