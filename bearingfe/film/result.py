"""The result of one film state: :class:`ReynoldsResult`, and the one place that builds it.

:func:`build_result` turns an unknown field of a film state (the linear
superposition's, or any cavitation model's) into a :class:`ReynoldsResult`:
pressure, loads, flows, mass balance and friction, the last three from the
film state's assembly (:mod:`bearingfe.film.assembly`). :func:`film_outputs`
does the same for many states of one mesh at once (a trajectory).
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings
from dataclasses import dataclass
from types import MappingProxyType
from typing import TYPE_CHECKING, Callable, Mapping, Sequence

import numpy as np
import skfem

from ..core.checks import ResolutionWarning
from .compiled import FilmFlows
from .estimate import ERROR_TOLERANCE, LoadError, load_error
from .flows import sink_dofs
from .forms import unknown_scale
from .thickness import Film
from ..geometry.locate import probes
from ..geometry.runner import is_along_phi

if TYPE_CHECKING:
    from .mesh_operators import Operators
    from .superposition import Superposition

__all__ = ["ReynoldsResult", "build_result", "film_outputs", "pressure_dofs"]


def pressure_dofs(ops: "Operators", film: Film, u: np.ndarray, formulation: str) -> np.ndarray:
    """Nodal pressure from the unknown (``p = h^(-3/2) Pi`` in the pi form)."""
    if formulation == "direct":
        return u.copy()
    loc = ops.basis.doflocs
    return u * unknown_scale(film.thickness(loc[0], loc[1]), formulation)




# -- the result -----------------------------------------------------------------

def build_result(sup: "Superposition", u: np.ndarray, weights: np.ndarray, sliding: float | None = None, *,
                 cavitation: str = "none", iterations: int = 0, cavitated: np.ndarray | None = None,
                 extra_cost: Mapping[str, float] | None = None, lazy: bool = False) -> "ReynoldsResult":
    """The :class:`ReynoldsResult` of an unknown field ``u`` of a film state.

    Parameters
    ----------
    sup : Superposition
        The film state (operators, film, formulation).
    u : ndarray, shape (n_dofs,)
        The unknown (``p`` or ``Pi``) on all dofs.
    weights : ndarray, shape (4,)
        The operating point as weights of the unit sources (:func:`source_weights`).
    sliding : float, optional
        Couette speed of the shear; default the wedge weight.
    cavitation : str
        Name of the model that produced ``u`` (``"none"``: the linear
        superposition, whose force and ``int p`` are the weighted unit loads).
    iterations : int
        Iterations of the model's nonlinear solve.
    cavitated : ndarray of bool, optional
        Ruptured dofs; with it the flows get a ``"cavitation"`` entry (see
        :mod:`bearingfe.film.reference`) and the loads are integrated from ``u``.
    extra_cost : mapping, optional
        Model wall times merged into ``cost``.
    lazy : bool
        Compute ``flows``, ``mass_balance`` and ``friction`` on their first use (the pressure, force and
        ``int p`` at once): for a caller that needs only the force and the rupture set of most of its
        results (a Newton iteration's intermediate states). Same values either way.
    """
    start = time.perf_counter()
    ops = sup.operators
    wedge, inlet_pressure = float(weights[0]), float(weights[3])
    sliding = wedge if sliding is None else float(sliding)
    if cavitated is None:
        force, integral = sup.forces @ weights, float(sup.integrals @ weights)
    else:
        force, integral = sup.loads(u, inlet_pressure)
    cost = dict(sup.cost, **(extra_cost or {}))

    def outputs() -> dict:
        t = time.perf_counter()
        # the Swift-Stieber multipliers' dofs (on P2 also the ends of ruptured Bernstein edges): their residuals
        # are the flow into the ruptured zone; the other models' flows take the ruptured dofs as they are
        sink = None if cavitated is None else (sink_dofs(ops.basis, cavitated, ops.interior)
                                               if cavitation == "reynolds" else cavitated)
        out = film_outputs([sup], u[:, None], np.asarray(weights, float)[:, None], np.array([sliding]),
                           None if sink is None else sink[:, None])
        if "postprocess" in cost:  # computed after the result was made (lazy): its time added
            cost["postprocess"] += time.perf_counter() - t
        return dict(flows=MappingProxyType({k: float(v[0]) for k, v in out.flows.items()}),
                    mass_balance=float(out.mass_balance[0]), friction=float(out.friction[0]))

    done = {} if lazy else outputs()
    res = ReynoldsResult(
        basis=ops.basis, pressure=pressure_dofs(ops, sup.film, u, sup.formulation), film=sup.film,
        wedge=wedge, squeeze=(float(weights[1]), float(weights[2])), inlet_pressure=inlet_pressure,
        formulation=sup.formulation, element=ops.element, force=force, integral=integral,
        h_min=sup.h_min, flows=done.get("flows"), mass_balance=done.get("mass_balance"),
        friction=done.get("friction"), coercivity=sup.coercivity, notes=sup.notes, cost=MappingProxyType(cost),
        cavitation=cavitation, iterations=int(iterations), cavitated=cavitated, runner=runner_of(ops.mesh))
    cost["postprocess"] = time.perf_counter() - start
    if lazy:
        for name in _DEFERRED:  # no instance values: ReynoldsResult.__getattr__ computes them on first use
            del res.__dict__[name]
        res.__dict__["_outputs"] = outputs
    return res


#: The outputs a lazy :func:`build_result` computes on their first use.
_DEFERRED = ("flows", "mass_balance", "friction")


def runner_of(mesh) -> object:
    """The mesh's runner for a result: None for the original one (uniform along ``phi``)."""
    return None if is_along_phi(mesh.runner) else mesh.runner


def film_outputs(sups: Sequence["Superposition"], u: np.ndarray, weights: np.ndarray, sliding: np.ndarray,
                 cavitated: np.ndarray | None = None) -> FilmFlows:
    """Flows, mass balance and friction of many film states of one mesh at once (compiled maps).

    Parameters
    ----------
    sups : sequence of Superposition, length S
        Film states on the same mesh and element.
    u : ndarray, shape (n_dofs, S)
        An unknown field of each state.
    weights : ndarray, shape (4, S)
        Unit-source weights of each (:func:`source_weights`).
    sliding : ndarray, shape (S,)
        Couette speed of the shear of each.
    cavitated : ndarray of bool, shape (n_dofs, S), optional
        Ruptured dofs of each.

    Returns
    -------
    FilmFlows
        Arrays over the samples, as :class:`ReynoldsResult` has them for one
        (``flows`` [omega R0^2 c], ``mass_balance``, ``friction`` [mu omega R0^4 / c]).
    """
    ops, assembly = sups[0].operators, sups[0].assembly
    if any(s.operators is not ops or s.assembly != assembly for s in sups):
        raise ValueError("film_outputs needs film states of one mesh, element and assembly")
    states = [(s.film, s.at, s.formulation) for s in sups]
    return ops.assembly(assembly).outputs(states, u, weights, np.asarray(sliding, float), cavitated)


@dataclass(frozen=True, eq=False)
class ReynoldsResult:
    """Solution of the Reynolds equation for one film state and operating point.

    Attributes
    ----------
    basis : skfem.CellBasis
        The finite-element basis; ``pressure`` holds its dofs.
    pressure : ndarray
        Non-dimensional pressure ``p = P c^2 / (mu omega R0^2)`` at the dofs
        (``p``, not ``Pi``, for both formulations).
    force : ndarray, shape (2,)
        ``int p (cos phi, sin phi) dphi dz`` over the surface, pockets
        included at their pressure [units mu omega R0^4 / c^2].
    integral : float
        ``int p dphi dz`` (the load of a flat pad), pockets included.
    h_min : float
        Smallest film thickness over the surface [c].
    flows : mapping
        ``inlet`` (out of the pockets into the film), ``side`` (out through
        z = +-a), ``arc_start``, ``arc_end`` (out through the arc edges; only
        ``outer`` for a non-rectangular outline) and ``squeeze``
        (``int dh/dt``) [units omega R0^2 c]. Inlet = outflows + squeeze.
    mass_balance : float
        ``inlet - outflows - squeeze``: zero up to discretization error.
    friction : float
        Shear force on the journal surface ``int (sliding/h + h/2 dp/dphi)``
        over the film, which is also the friction moment [mu omega R0^4/c]
        (the deep pockets carry negligible shear).
    formulation, element : str
        What was used (``formulation`` is ``"direct"`` after a fallback).
    coercivity : float
        Smallest-eigenvalue bound of the pi operator (NaN for direct).
    notes : tuple of str
        Decisions the solver made on its own.
    cost : mapping
        Wall times [s]: ``mesh_operators`` (once per mesh), ``assembly``,
        ``factorization``, ``solve``, ``postprocess``; and ``dofs``.
    cavitation : str
        Cavitation model used (see :mod:`bearingfe.cavitation.models`).
    iterations : int
        Active-set iterations of the cavitation solve (0 without).
    cavitated : ndarray of bool or None
        Ruptured dofs (``p = p_c`` imposed by the cavitation condition).
    theta : ndarray or None
        Fill fraction at the dofs (``cavitation="jfo"`` only; 1 in the full film).
    cavitated_fraction : float
        Film area with ``theta < 1`` (``"jfo"``) or ruptured (finite-volume
        ``"reynolds"``) over the film area.
    cavitation_pressure : float
        Cavity pressure ``p_c`` [-] (gauge).
    deflection : ndarray or None
        Film opening by an elastic support [c] at the dofs (``film`` is then
        the deflected film); None on rigid surfaces (:mod:`bearingfe.elastic.coupled`).
    elastic_iterations : int
        Reynolds solves of the coupled elastic (EHD) Newton iteration (0: rigid).
    load_error : LoadError or None
        The load's estimated error (:mod:`bearingfe.film.estimate`) if the
        solve was asked for it (``solve_reynolds(..., estimate_error=True)``);
        otherwise :meth:`estimate_load_error` computes it on demand.
    runner : Runner or None
        The mesh's runner (:mod:`bearingfe.geometry.runner`) when it is not the original uniform sliding
        along ``phi`` (None): the Couette terms of ``flows``, ``friction`` and the error indicators carry
        its velocity.
    refined : callable or None
        ``refined(self) -> (fine, order, seconds)``: the same solve on the
        mesh refined once, the order of its load error
        (:data:`bearingfe.film.estimate.LOAD_ORDERS`) and its wall time [s];
        set by :func:`bearingfe.solve_reynolds` (None for results built by
        other doors).
    """

    basis: skfem.CellBasis
    pressure: np.ndarray
    film: Film
    wedge: float
    squeeze: tuple[float, float]
    inlet_pressure: float
    formulation: str
    element: str
    force: np.ndarray
    integral: float
    h_min: float
    flows: Mapping[str, float]
    mass_balance: float
    friction: float
    coercivity: float
    notes: tuple[str, ...]
    cost: Mapping[str, float]
    cavitation: str = "none"
    iterations: int = 0
    cavitated: np.ndarray | None = None
    theta: np.ndarray | None = None
    cavitated_fraction: float = 0.0
    cavitation_pressure: float = 0.0
    deflection: np.ndarray | None = None
    elastic_iterations: int = 0
    load_error: LoadError | None = None
    runner: object = None
    refined: Callable[["ReynoldsResult"], tuple["ReynoldsResult", float, float]] | None = dataclasses.field(
        default=None, repr=False)
    _estimates: dict = dataclasses.field(default_factory=dict, init=False, repr=False)

    def __getattr__(self, name: str):
        # only reached for an attribute missing from the instance: the outputs of a lazy build_result
        outputs = self.__dict__.get("_outputs")
        if name not in _DEFERRED or outputs is None:
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
        self.__dict__.update(outputs())
        del self.__dict__["_outputs"]
        return self.__dict__[name]

    def __getstate__(self) -> dict:
        for name in _DEFERRED:  # a lazy result's outputs computed before copying or pickling
            getattr(self, name)
        return self.__dict__

    def estimate_load_error(self, tolerance: float = ERROR_TOLERANCE) -> LoadError:
        """How far the load is from converged: the same solve on the mesh refined once (lazy).

        The first call solves again on the once-refined mesh (about 4 to 10
        times this solve's cost; the estimate is kept, so later calls are
        free) and compares the loads (:func:`bearingfe.film.estimate.load_error`).
        If the estimated relative error exceeds ``tolerance`` a
        :class:`bearingfe.ResolutionWarning` is issued with the
        :attr:`LoadError.note`; ``solve_reynolds(..., estimate_error=True)``
        also puts it in ``notes``.

        Parameters
        ----------
        tolerance : float
            Relative load error above which the estimate warns [-], > 0.

        Raises
        ------
        ValueError
            Where there is no refined solve (``refined`` is None).
        """
        if not (math.isfinite(tolerance) and tolerance > 0):
            raise ValueError(f"tolerance must be a finite relative error > 0, got {tolerance!r}")
        if "estimate" not in self._estimates:
            if self.load_error is not None:
                self._estimates["estimate"] = self.load_error
            elif self.refined is None:
                raise ValueError("this result has no refined solve to compare with (a result not made by "
                                 "bearingfe.solve_reynolds): solve again on "
                                 "bearingfe.geometry.meshing.refine_once(mesh) and use film.estimate.load_error")
            else:
                fine, order, seconds = self.refined(self)
                self._estimates["estimate"] = load_error(self, fine, order=order, seconds=seconds)
        estimate = dataclasses.replace(self._estimates["estimate"], tolerance=float(tolerance))
        if estimate.exceeded:
            warnings.warn(ResolutionWarning(estimate.note), stacklevel=2)
        return estimate

    @property
    def max_deflection(self) -> float:
        """Largest film opening by the elastic support [c] (0 on rigid surfaces)."""
        return 0.0 if self.deflection is None else float(np.max(self.deflection, initial=0.0))

    @property
    def max_pressure(self) -> float:
        """Largest nodal pressure (pockets included)."""
        return float(max(self.pressure.max(), self.inlet_pressure))

    def interpolate(self, phi, z) -> np.ndarray:
        """Pressure at arbitrary points of the film (NaN-free: points must lie in the mesh)."""
        pts = np.vstack([np.ravel(phi), np.ravel(z)]).astype(float)
        return (probes(self.basis, pts) @ self.pressure).reshape(np.shape(phi))
