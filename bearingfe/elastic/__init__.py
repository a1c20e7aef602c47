"""Elastic supports: compliances of the film surfaces (:data:`COMPLIANCES`) and the coupled (EHD) film.

A compliance maps the film pressure to the film's opening on the film dofs
(:class:`Compliance`); :data:`COMPLIANCES` tables the models that build one from
the support's materials and body: the Boussinesq half-space, the shoe as a block
clamped at its back, and the real shoe body meshed from the machine file. The
coupled film (:func:`solve_elastic`, :func:`balance_load`) takes any of them.

===============  ==================================================================
module           what it does
===============  ==================================================================
``compliance``   the :class:`Compliance` every model builds; contact modulus; size guard
``half_space``   two elastic half-spaces under the film, influence coefficients exact
``convolution``  the half-space applied by FFT: exact on a uniform grid mesh, through a grid on any other
``block``        the shoe as a 3-D block held at its back; any body's openings as a compliance
``shoe``         the real shoe body (gmsh tetrahedra, seat, lining) and its :class:`ShoeBody`
``coupled``      the film opened by its own pressure: Newton, load balance, chord balance
``krylov``       restarted GMRES of the matrix-free solves (coupled Newton steps, the transient's squeeze)
===============  ==================================================================
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Callable, Mapping

from .compliance import Compliance, ElasticError, check_dense_size, combined_modulus, contact_modulus
from .half_space import half_space, influence_matrix, rectangle_deflection
from .convolution import GridConvolution, half_space_fft, half_space_grid
from .block import block_compliance, body_compliance
from .shoe import BODY_ORDERS, SHOE_BACKS, SHOE_SEATS, ShoeBody, ShoeMesh, condense, mesh_shoe, overlay, shoe_compliance
from .coupled import (ChordBalance, DeflectedFilm, ElasticBalance, ElasticSolution, balance_load, newton,
                      pressure_sensitivity, solve_elastic)

__all__ = ["COMPLIANCES", "NEEDS_BODY", "REBUILDS", "compliance_of", "compliance_on", "Compliance", "ElasticError", "body_compliance", "check_dense_size",
           "combined_modulus", "contact_modulus", "half_space", "half_space_fft", "half_space_grid", "GridConvolution", "influence_matrix", "rectangle_deflection",
           "block_compliance", "BODY_ORDERS", "SHOE_BACKS", "SHOE_SEATS", "ShoeBody", "ShoeMesh", "condense",
           "mesh_shoe", "overlay", "shoe_compliance", "ChordBalance", "DeflectedFilm", "ElasticBalance",
           "ElasticSolution", "balance_load", "newton", "pressure_sensitivity", "solve_elastic"]


def _half_space(mesh, scale, shoe, counterpart, body, element):
    return half_space(mesh, scale, shoe if counterpart is None else (shoe, counterpart), element)


def _half_space_fft(mesh, scale, shoe, counterpart, body, element):
    return half_space_fft(mesh, scale, shoe if counterpart is None else (shoe, counterpart), element)


def _half_space_grid(mesh, scale, shoe, counterpart, body, element):
    return half_space_grid(mesh, scale, shoe if counterpart is None else (shoe, counterpart), element)


def _block(mesh, scale, shoe, counterpart, body, element):
    return block_compliance(mesh, scale, shoe, body.thickness, counterpart=counterpart, element=element)


def _shoe(mesh, scale, shoe, counterpart, body, element):
    return shoe_compliance(mesh, scale, shoe, body, counterpart=counterpart, element=element)


#: Elastic support models by name: ``build(mesh, scale, shoe, counterpart, body, element) -> Compliance``
#: with the shoe's :class:`~bearingfe.core.machine.Material`, the counterpart's (None: rigid) and the
#: shoe's :class:`ShoeBody` (the block and the shoe need it; the half-space ignores it). ``"half-space-fft"``
#: is the half-space on a uniform grid mesh (:func:`bearingfe.grid_mesh`, P1) held as its FFT product:
#: no dense matrix and no size cap. ``"half-space-grid"``: the same on any mesh through an auxiliary uniform
#: grid (approximate, error falling like the grid spacing squared; :func:`half_space_grid`).
COMPLIANCES: Mapping[str, Callable[..., Compliance]] = MappingProxyType({
    "half-space": _half_space,
    "half-space-fft": _half_space_fft,
    "half-space-grid": _half_space_grid,
    "block": _block,
    "shoe": _shoe,
})
#: Models of :data:`COMPLIANCES` that need the shoe's body (its depth at least).
NEEDS_BODY = ("block", "shoe")


#: Models whose compliance can be built again on another mesh of the same surface from the compliance
#: itself (its contact modulus, scale and element): ``rebuild(compliance, mesh) -> Compliance``. The block
#: and the shoe need their bodies, which a compliance does not keep.
REBUILDS: Mapping[str, Callable[[Compliance, object], Compliance]] = MappingProxyType({
    "half-space": lambda c, mesh: half_space(mesh, c.scale, c.modulus, c.element),
    "half-space-fft": lambda c, mesh: half_space_fft(mesh, c.scale, c.modulus, c.element),
    "half-space-grid": lambda c, mesh: half_space_grid(mesh, c.scale, c.modulus, c.element),
})


def compliance_on(compliance: Compliance, mesh) -> Compliance:
    """The same support's compliance on another mesh of the surface (e.g. the mesh refined once).

    Raises
    ------
    ValueError
        For a model not in :data:`REBUILDS`, naming the ones that are; or
        (from the model) beyond the dense-size limit.
    """
    if compliance.model not in REBUILDS:
        raise ValueError(f"the {compliance.model!r} compliance cannot be built on another mesh from itself (it needs "
                         f"the support's body); models that can: {tuple(REBUILDS)}")
    return REBUILDS[compliance.model](compliance, mesh)


def compliance_of(model: str, mesh, scale, shoe, *, counterpart=None, body: ShoeBody | None = None,
                  element: str = "P1") -> Compliance:
    """The compliance of a support by the name of its model in :data:`COMPLIANCES`.

    Raises
    ------
    ValueError
        An unknown model, or a model of :data:`NEEDS_BODY` without ``body``.
    """
    if model not in COMPLIANCES:
        raise ValueError(f"elastic model must be one of {tuple(COMPLIANCES)}, got {model!r}")
    if model in NEEDS_BODY and body is None:
        raise ValueError(f"elastic model {model!r} needs the shoe's body (its depth at least: a ShoeBody)")
    return COMPLIANCES[model](mesh, scale, shoe, counterpart, body, element)
