r"""Finite-element solution of the Reynolds equation on a support surface.

Non-dimensional form (see ``docs/formulations.md``)::

    div(h^3 grad p) = 6 wedge dh/dphi + 12 (gamma_rate dh/dgamma + phi0_rate dh/dphi0)

in the film region of the unwrapped plane ``(phi, z)``, with ``p = 0`` on
the outline and ``p = p_s`` on the pocket contours. Rates are per radian of
shaft turn; the scales are ``P = mu omega R0^2 / c^2 p``.

Two formulations:

``"direct"``
    the conservative form above, stiffness weighted by ``h^3`` (assembled for
    each film).
``"pi"``
    the source paper's substitution ``p = h^(-3/2) Pi``:
    ``Laplace(Pi) + D Pi = h^(-3/2) f`` with
    ``D = -3/(4 h^2) (2 h Laplace(h) + |grad h|^2)``. The Laplacian is
    assembled once per mesh; only the ``D``-weighted mass matrix changes with
    the film.

Because the equation is linear in the sources, one factorization serves four
unit right sides (wedge, the two squeeze rates, inlet pressure):
:func:`superpose` returns them and :meth:`Superposition.combine` builds any
operating point, which is what the pump transient calls at each step.

Where things live: the weak forms and the pressure, flux and shear formulas
in :mod:`bearingfe.film.forms`; the film state (:class:`Superposition` with its
condensed system) in :mod:`bearingfe.film.superposition` and its result in
:mod:`bearingfe.film.result`; the cavitation models and their table in
:mod:`bearingfe.cavitation`; the elastic coupling in :mod:`bearingfe.elastic`.

This module is the front door. :func:`solve_reynolds` checks its inputs once,
then chooses from two tables: :func:`discretization_for` picks the
discretization a model needs on a mesh (:data:`DISCRETIZATIONS`: the Galerkin
finite-element film state, or the finite-volume scheme of recessed, periodic
and mass-conserving films), and :data:`PATHS` maps the support (``"rigid"`` or
``"elastic"``) and that discretization to the function that solves it. Every
path takes the same parameter objects and returns a ``ReynoldsResult``.
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings
from types import MappingProxyType
from typing import Callable, Mapping

from .cavitation import CAVITATION, MODELS, ModelOptions, solve_model
from .core.checks import ResolutionWarning, check_operating_point, note_resolution
from .core.linalg import DEFAULT_SOLVER, Factorize
from .core.pages import small_pages
from .core.parameters import ELEMENTS, FORMULATIONS, Discretization, OperatingPoint, takes
from .elastic import Compliance, compliance_on, solve_elastic
from .film import (ERROR_TOLERANCE, SOURCES, CoercivityError, CondensedSystem, Film, Operators, ReynoldsResult,
                   Superposition, load_order, operators, solve_jfo, superpose)
from .geometry.meshing import SupportMesh, refine_once

__all__ = [
    "ELEMENTS",
    "FORMULATIONS",
    "CAVITATION",
    "DISCRETIZATIONS",
    "PATHS",
    "SOURCES",
    "Operators",
    "operators",
    "CondensedSystem",
    "Superposition",
    "superpose",
    "ReynoldsResult",
    "solve_reynolds",
    "RefinedSolve",
    "discretization_for",
    "CoercivityError",
    "Discretization",
    "OperatingPoint",
]

#: The discretizations a film is solved with.
DISCRETIZATIONS = ("finite-element", "finite-volume")


def discretization_for(mesh: SupportMesh, cavitation: str, cavitation_pressure: float = 0.0) -> str:
    """The discretization of :data:`DISCRETIZATIONS` that solves ``cavitation`` on ``mesh``.

    The Galerkin finite-element film state unless something asks for the
    finite-volume scheme: a model that has only that scheme (JFO), a recessed or
    periodic surface (``mesh.needs_finite_volumes``), or a non-zero cavity
    pressure. A model without a finite-volume scheme is then refused, naming why.
    """
    model = MODELS[cavitation]
    reasons = []
    if not model.finite_element:
        reasons.append(f"cavitation={cavitation!r} is solved by finite volumes only")
    if isinstance(mesh, SupportMesh) and mesh.needs_finite_volumes:
        reasons.append("the surface has recesses (film steps) or is periodic")
    if float(cavitation_pressure) != 0.0:
        reasons.append(f"cavitation_pressure = {cavitation_pressure!r} is not 0")
    if not reasons:
        return "finite-element"
    if not model.finite_volume or (float(cavitation_pressure) != 0.0 and not model.cavity_pressure):
        able = [name for name, m in MODELS.items() if m.finite_volume and
                (m.cavity_pressure or float(cavitation_pressure) == 0.0)]
        raise ValueError(f"{'; '.join(reasons)}: that needs the finite-volume scheme, which solves cavitation "
                         f"in {tuple(able)}, not {cavitation!r}")
    return "finite-volume"


def _rigid_finite_element(mesh, film, operating: OperatingPoint, discretization: Discretization, cavitation: str,
                          options: ModelOptions, on_indefinite: str, compliance=None) -> ReynoldsResult:
    if isinstance(operating.inlet_pressure, tuple):  # each pocket at its own pressure: one unit field per pocket
        from .cavitation.models import solve_pocket_state
        from .film.pockets import pocket_film, pocket_names

        pf = pocket_film(mesh, film, discretization, on_indefinite)
        result = solve_pocket_state(pf, pocket_names(mesh), operating.inlet_pressure, operating, cavitation, options)
        return note_resolution(result, mesh, film, stacklevel=4)
    # the large arrays of the assembly, the model's solves and the result on small pages (bearingfe.core.pages:
    # no wait for the kernel's compaction into huge pages)
    with small_pages():
        sup = superpose(mesh, film, formulation=discretization.formulation, element=discretization.element,
                        solver=discretization.solver, on_indefinite=on_indefinite)
        result = solve_model(sup, operating.weights, cavitation, options)
    return note_resolution(result, mesh, film, stacklevel=4)  # each path notes its film's resolution


def _rigid_finite_volume(mesh, film, operating: OperatingPoint, discretization: Discretization, cavitation: str,
                         options: ModelOptions, on_indefinite: str, compliance=None) -> ReynoldsResult:
    # the scheme's own linear solver and the direct form (it says so in the result's notes)
    return solve_jfo(mesh, film, operating=operating, element=discretization.element,
                     cavitation_pressure=options.cavitation_pressure, warm_start=options.warm_start,
                     cavitation=cavitation)


def _elastic_finite_element(mesh, film, operating: OperatingPoint, discretization: Discretization, cavitation: str,
                            options: ModelOptions, on_indefinite: str, compliance=None) -> ReynoldsResult:
    res = solve_elastic(mesh, film, compliance, operating=operating, element=discretization.element,
                        solver=discretization.solver, cavitation=cavitation).result
    if discretization.formulation != "direct":
        note = "elastic support: the direct form was used (the deflected film is a nodal field)"
        res = dataclasses.replace(res, notes=res.notes + (note,))
    return res


#: How a film is solved, by ``(support, discretization)``: ``solve(mesh, film, operating, discretization,
#: cavitation, options, on_indefinite, compliance) -> ReynoldsResult``.
PATHS: Mapping[tuple[str, str], Callable[..., ReynoldsResult]] = MappingProxyType({
    ("rigid", "finite-element"): _rigid_finite_element,
    ("rigid", "finite-volume"): _rigid_finite_volume,
    ("elastic", "finite-element"): _elastic_finite_element,
})


@dataclasses.dataclass(frozen=True, eq=False)
class RefinedSolve:
    """The solve of a result again on its mesh refined once (a result's ``refined``).

    Calling it with the coarse result meshes the refinement
    (:func:`bearingfe.geometry.meshing.refine_once`), solves the same path
    there, started from the coarse rupture set where there is one (nested
    iteration), and returns ``(fine, order, seconds)``: the fine result, the
    order of the load error of the path (:func:`bearingfe.film.estimate.load_order`)
    and the wall time [s]. The fine mesh's own resolution warnings are not
    issued (the coarse solve has issued its own).
    """

    mesh: SupportMesh
    film: Film
    path: tuple[str, str]
    operating: OperatingPoint
    discretization: Discretization
    cavitation: str
    options: ModelOptions
    on_indefinite: str
    elastic: Compliance | None = None

    def __call__(self, coarse: ReynoldsResult) -> tuple[ReynoldsResult, float, float]:
        start = time.perf_counter()
        fine_mesh = refine_once(self.mesh)
        warm = coarse if coarse.cavitated is not None else None
        options = dataclasses.replace(self.options, warm_start=warm)
        # the support's compliance on the refined mesh (the half-space's: see bearingfe.elastic.REBUILDS)
        elastic = None if self.elastic is None else compliance_on(self.elastic, fine_mesh)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ResolutionWarning)
            fine = PATHS[self.path](fine_mesh, self.film, self.operating, self.discretization, self.cavitation,
                                   options, self.on_indefinite, elastic)
        return fine, load_order(self.path[1], self.discretization.element), time.perf_counter() - start


@takes(OperatingPoint, Discretization)
def solve_reynolds(mesh: SupportMesh, film: Film, *, wedge: float = 1.0, squeeze=(0.0, 0.0),
                   inlet_pressure=0.0, formulation: str = "pi", element: str = "P1",
                   cavitation: str = "none", sliding: float | None = None,
                   solver: str | Factorize = DEFAULT_SOLVER, on_indefinite: str = "fallback",
                   warm_start=None, cavitation_pressure: float = 0.0,
                   elastic: Compliance | None = None, estimate_error: bool = False,
                   error_tolerance: float = ERROR_TOLERANCE) -> ReynoldsResult:
    """Solve the Reynolds equation on a meshed support surface.

    Parameters
    ----------
    mesh : SupportMesh
        From :func:`bearingfe.mesh_surface` or :func:`bearingfe.load_mesh`.
    film : Film
        E.g. ``CosineFilm(gamma, phi0)``.
    wedge : float
        Entrainment factor of the wedge term ``6 wedge dh/dphi`` (1 for a
        journal turning under a fixed shoe) [-].
    squeeze : (float, float)
        ``(gamma_rate, phi0_rate)`` per radian of shaft turn.
    inlet_pressure : float, sequence of float or mapping
        Pocket pressure ``p_s`` [-]: one for every pocket, or one per pocket (a sequence in the order of
        :func:`bearingfe.film.pockets.pocket_names`, or a mapping ``name -> value`` naming each
        pocket once). With one per pocket the result's ``flows`` hold each pocket's film outflow under its
        name (``"inlet_0"``, ...) beside the total ``"inlet"``, its loads count each pocket at its pressure,
        and its ``inlet_pressure`` is the largest of them.
    formulation : {"pi", "direct"}
    element : {"P1", "P2"}
    cavitation : str
        A model of :data:`bearingfe.cavitation.MODELS` (:data:`CAVITATION`):
        ``"none"`` lets the pressure go negative (as in the source paper);
        ``"reynolds"``: Swift-Stieber ``p >= 0`` with a free boundary, solved
        as a complementarity problem; ``"gumbel"``: negative part discarded
        (see :mod:`bearingfe.cavitation.models`); ``"jfo"``: mass-conserving
        (Elrod-Adams p-theta) cavitation, P1 only (see :mod:`bearingfe.film.finite_volume`).
        Recessed and periodic surfaces (``mesh.needs_finite_volumes``) are
        solved by the finite-volume scheme of :mod:`bearingfe.film.finite_volume` with
        ``"none"``, ``"reynolds"`` or ``"jfo"``.
    sliding : float, optional
        Sliding speed of the journal relative to the shoe for the Couette
        shear; default ``wedge``.
    solver : str or callable
        Sparse linear solver (:data:`bearingfe.core.linalg.LINEAR_SOLVERS`).
    on_indefinite : {"fallback", "raise"}
        See :func:`superpose`.
    warm_start : ReynoldsResult or bool mask, optional
        Rupture set of a previous cavitated solution on the same mesh, or a
        cavitated result on another (e.g. coarser) mesh of the same surface,
        interpolated: nested iteration keeps the active-set count bounded
        under refinement (docs/validation.md).
    cavitation_pressure : float
        Cavity pressure ``p_c`` [-] (gauge: the edges are at 0), ``<= 0``,
        for ``"jfo"`` and ``"reynolds"`` (``p >= p_c``). A non-zero value
        with ``"reynolds"`` is solved by the finite-volume Swift-Stieber of
        :mod:`bearingfe.film.finite_volume` (P1, direct form); ``"gumbel"`` needs 0.
    elastic : Compliance, optional
        Compliance of the support surfaces on this mesh and element
        (:func:`bearingfe.elastic.half_space`): the film becomes
        ``h_rigid + C p`` and is solved with its pressure by Newton
        (:func:`bearingfe.elastic.coupled.solve_elastic`, direct form; the result's
        ``deflection``, ``max_deflection`` and ``elastic_iterations`` report it).
        Raises :class:`bearingfe.elastic.coupled.ElasticError` if it does not converge.
    estimate_error : bool
        Also solve on the mesh refined once and estimate how far the load is
        from converged (:mod:`bearingfe.film.estimate`): ``load_error`` of the
        result, and a note in ``notes`` (with a :class:`bearingfe.ResolutionWarning`)
        if its relative value exceeds ``error_tolerance``. It costs about 4
        to 10 times the solve (the refined mesh has 4 times the unknowns;
        more on tiny meshes, where gmsh's remeshing dominates), so it is
        off by default; every result can still estimate it later, on
        demand, with
        :meth:`ReynoldsResult.estimate_load_error` (same numbers, same note
        as a warning). With ``elastic=`` the compliance is built again on
        the refined mesh, which the half-space can (:data:`bearingfe.elastic.REBUILDS`;
        others raise ``ValueError``), and counts against the dense-size limit there.
    error_tolerance : float
        Relative load error above which the result gets the note [-], > 0.
    operating : OperatingPoint, optional
        ``wedge``, ``squeeze``, ``inlet_pressure`` and ``sliding`` in one
        object (:class:`bearingfe.core.parameters.OperatingPoint`) instead of the
        keywords.
    discretization : Discretization, optional
        ``element``, ``formulation`` and ``solver`` in one object
        (:class:`bearingfe.core.parameters.Discretization`) instead of the keywords.

    Returns
    -------
    ReynoldsResult
        If the mesh does not resolve the film where it is thinnest
        (:func:`bearingfe.core.checks.check_resolution`), a
        :class:`bearingfe.ResolutionWarning` is issued and its message
        added to ``notes``; the same for a load error estimate above
        ``error_tolerance``.

    Raises
    ------
    ValueError
        A bad argument, e.g. ``|inlet_pressure| > 1e12`` or ``cavitation_pressure``
        outside ``[-1e6, 0]`` (:func:`bearingfe.core.checks.check_operating_point`, which every
        path calls, the finite-volume, elastic and finite-difference solvers too).
    """
    if cavitation not in CAVITATION:
        raise ValueError(f"cavitation must be one of {CAVITATION}, got {cavitation!r}")
    if not isinstance(inlet_pressure, (int, float)):  # one value per pocket, read against the mesh's pockets
        from .film.pockets import pocket_pressures

        inlet_pressure = pocket_pressures(mesh, inlet_pressure)
    largest = max(inlet_pressure, key=abs) if isinstance(inlet_pressure, tuple) else inlet_pressure
    check_operating_point(wedge, squeeze, largest, cavitation_pressure)
    operating = OperatingPoint(wedge=wedge, squeeze=squeeze, inlet_pressure=inlet_pressure, sliding=sliding)
    discretization = Discretization(element=element, formulation=formulation, solver=solver)
    if largest != 0.0 and not mesh.has_inlet:
        raise ValueError("inlet_pressure is non-zero but the mesh has no 'inlet' boundary (no pocket)")
    options = ModelOptions(sliding=sliding, warm_start=warm_start, solver=solver,
                           cavitation_pressure=float(cavitation_pressure))
    support = "rigid" if elastic is None else "elastic"
    path = (support, discretization_for(mesh, cavitation, cavitation_pressure))
    if path not in PATHS:
        raise ValueError(f"elastic= is not supported with the {path[1]} solver (cavitation='jfo', a non-zero "
                         "cavitation_pressure, recessed or periodic surfaces)")
    if not (isinstance(error_tolerance, (int, float)) and math.isfinite(error_tolerance) and error_tolerance > 0):
        raise ValueError(f"error_tolerance must be a finite relative error > 0, got {error_tolerance!r}")
    result = PATHS[path](mesh, film, operating, discretization, cavitation, options, on_indefinite, elastic)
    # without the caller's warm start (the refined solve starts from this result): results made in a loop
    # from the previous one must not hold on to all of them
    refined = RefinedSolve(mesh, film, path, operating, discretization, cavitation,
                           dataclasses.replace(options, warm_start=None), on_indefinite, elastic)
    result = dataclasses.replace(result, refined=refined)
    if not estimate_error:
        return result
    with warnings.catch_warnings():  # issued below, at the caller's line
        warnings.simplefilter("ignore", ResolutionWarning)
        estimate = result.estimate_load_error(error_tolerance)
    if estimate.note is None:
        return dataclasses.replace(result, load_error=estimate)
    warnings.warn(ResolutionWarning(estimate.note), stacklevel=3)
    notes = (*result.notes, estimate.note)
    return dataclasses.replace(result, load_error=estimate, notes=notes)
