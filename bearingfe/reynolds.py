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
in :mod:`bearingfe.film.forms`; the per-mesh operators, the film state
(:class:`Superposition` with its condensed system) and the one result
builder in :mod:`bearingfe.film.superposition`; the cavitation models and their
table in :mod:`bearingfe.cavitation.models`. This module is the front door:
:func:`solve_reynolds` and the names above, re-exported.
"""

from __future__ import annotations

import dataclasses

from .cavitation.models import MODELS, ModelOptions, solve_model
from .core.checks import check_operating_point, check_resolution
from .elastic.coupled import Compliance, solve_elastic
from .film.thickness import Film
from .film.finite_volume import solve_jfo
from .core.linalg import DEFAULT_SOLVER, Factorize
from .geometry.meshing import SupportMesh
from .core.parameters import ELEMENTS, FORMULATIONS, Discretization, OperatingPoint, takes
from .film import (SOURCES, CoercivityError, CondensedSystem, Operators, ReynoldsResult, Superposition, operators,
                   source_weights, superpose)

__all__ = [
    "ELEMENTS",
    "FORMULATIONS",
    "CAVITATION",
    "SOURCES",
    "Operators",
    "operators",
    "CondensedSystem",
    "Superposition",
    "superpose",
    "ReynoldsResult",
    "solve_reynolds",
    "CoercivityError",
    "Discretization",
    "OperatingPoint",
]

#: Names of the cavitation models (the keys of :data:`bearingfe.cavitation.models.MODELS`).
CAVITATION = tuple(MODELS)


@takes(OperatingPoint, Discretization)
def solve_reynolds(mesh: SupportMesh, film: Film, *, wedge: float = 1.0, squeeze=(0.0, 0.0),
                   inlet_pressure: float = 0.0, formulation: str = "pi", element: str = "P1",
                   cavitation: str = "none", sliding: float | None = None,
                   solver: str | Factorize = DEFAULT_SOLVER, on_indefinite: str = "fallback",
                   warm_start=None, cavitation_pressure: float = 0.0,
                   elastic: Compliance | None = None) -> ReynoldsResult:
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
    inlet_pressure : float
        Pocket pressure ``p_s`` [-].
    formulation : {"pi", "direct"}
    element : {"P1", "P2"}
    cavitation : str
        A model of :data:`bearingfe.cavitation.models.MODELS` (:data:`CAVITATION`):
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
        (:func:`bearingfe.elastic.coupled.half_space`): the film becomes
        ``h_rigid + C p`` and is solved with its pressure by Newton
        (:func:`bearingfe.elastic.coupled.solve_elastic`, direct form; the result's
        ``deflection``, ``max_deflection`` and ``elastic_iterations`` report it).
        Raises :class:`bearingfe.elastic.coupled.ElasticError` if it does not converge.
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
        added to ``notes``.

    Raises
    ------
    ValueError
        A bad argument, e.g. ``|inlet_pressure| > 1e12``
        (:func:`bearingfe.core.checks.check_operating_point`).
    """
    if cavitation not in CAVITATION:
        raise ValueError(f"cavitation must be one of {CAVITATION}, got {cavitation!r}")
    finite_volumes = isinstance(mesh, SupportMesh) and mesh.needs_finite_volumes
    if cavitation == "jfo" or (finite_volumes and cavitation in ("none", "reynolds")) or (
            cavitation == "reynolds" and float(cavitation_pressure) != 0.0):
        if elastic is not None:
            raise ValueError("elastic= is not supported with the finite-volume solver (cavitation='jfo', "
                             "a non-zero cavitation_pressure, recessed or periodic surfaces)")
        return solve_jfo(mesh, film, wedge=wedge, squeeze=squeeze, inlet_pressure=inlet_pressure,
                         cavitation_pressure=cavitation_pressure, element=element, sliding=sliding,
                         warm_start=warm_start, cavitation=cavitation)
    if float(cavitation_pressure) != 0.0:
        raise ValueError(f"cavitation_pressure must be 0 with cavitation={cavitation!r}, got "
                         f"{cavitation_pressure!r} (it applies to 'reynolds' and 'jfo')")
    weights = source_weights(wedge, squeeze, inlet_pressure)
    check_operating_point(wedge, squeeze, inlet_pressure)
    if inlet_pressure != 0.0 and not mesh.has_inlet:
        raise ValueError("inlet_pressure is non-zero but the mesh has no 'inlet' boundary (no pocket)")
    if elastic is not None:
        res = solve_elastic(mesh, film, elastic, wedge=wedge, squeeze=squeeze, inlet_pressure=inlet_pressure,
                            element=element, cavitation=cavitation, sliding=sliding, solver=solver).result
        if formulation != "direct":
            note = "elastic support: the direct form was used (the deflected film is a nodal field)"
            res = dataclasses.replace(res, notes=res.notes + (note,))
        return res
    sup = superpose(mesh, film, formulation=formulation, element=element, solver=solver,
                    on_indefinite=on_indefinite)
    result = solve_model(sup, weights, cavitation, ModelOptions(sliding=sliding, warm_start=warm_start,
                                                                solver=solver))
    unresolved = check_resolution(mesh, film, stacklevel=3)  # ResolutionWarning (bearingfe.core.checks)
    return result if unresolved is None else dataclasses.replace(result, notes=(*result.notes, unresolved))
