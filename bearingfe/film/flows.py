"""Named film flows, written once for every discretization and every transient.

A film's flows are the boundary fluxes of ``q = -h^3/12 grad p + wedge h/2 e_phi``
[omega R0^2 c], grouped by the boundary they leave through: ``side`` (z = +-a),
``arc_start``, ``arc_end`` (a thrust pad's sector: ``arc_start``, ``arc_end``, ``inner_rim``,
``outer_rim``; or the whole ``outer`` outline when it has no named edges), ``inlet`` (out of the pockets into the film: the sign is turned),
``squeeze`` (``int dh/dt``: the film volume's rate) and, under cavitation,
``cavitation`` (what the full film hands to the ruptured zone). The balance
``inlet = outflow + squeeze (+ cavitation)`` holds up to discretization error.
"""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np

__all__ = ["named_flows", "outflow", "ruptured_elements", "sink_dofs", "bernstein_edges", "NOT_OUTFLOWS", "EDGE_GROUPS", "edge_groups"]

#: Named outline edges a flow leaves through, when the mesh has them: the rectangle's ``side`` (both
#: ``z = +-a``), ``arc_start``, ``arc_end``; an annular sector's (a thrust pad's) ``arc_start``,
#: ``arc_end``, ``inner_rim`` and ``outer_rim``. A mesh with none of them has one group, ``outer``.
EDGE_GROUPS = ("side", "arc_start", "arc_end", "inner_rim", "outer_rim")


def edge_groups(boundaries) -> list[str]:
    """The outflow groups of a mesh's boundaries: its named edges (:data:`EDGE_GROUPS`) or ``["outer"]``."""
    return [name for name in EDGE_GROUPS if name in boundaries] or ["outer"]

#: Flow names that are not a boundary's outflow.
NOT_OUTFLOWS = ("inlet", "squeeze", "cavitation")


def named_flows(groups: Sequence[str], residual: np.ndarray, squeeze) -> dict[str, np.ndarray]:
    """Flows by name from the nodal flux residual summed per boundary group.

    Parameters
    ----------
    groups : sequence of str
        The boundary groups in the order of ``residual``'s rows (``"inlet"`` among them
        if the surface has pockets).
    residual : ndarray, shape (n_groups, ...)
        Outward flux through each group (for ``"inlet"``: into the pockets).
    squeeze : float or ndarray
        ``int dh/dt`` over the film (same trailing shape).
    """
    flows = {name: residual[k] for k, name in enumerate(groups)}
    flows["inlet"] = -flows["inlet"] if "inlet" in flows else np.zeros_like(np.asarray(squeeze, float))
    flows["squeeze"] = squeeze
    return flows


def outflow(flows: Mapping[str, np.ndarray]):
    """Flow out through the boundary groups: everything but :data:`NOT_OUTFLOWS`."""
    return sum(v for k, v in flows.items() if k not in NOT_OUTFLOWS)


def ruptured_elements(element_dofs: np.ndarray, u: np.ndarray, cavitated: np.ndarray) -> np.ndarray:
    """Elements with zero pressure at every dof and at least one ruptured dof.

    ``element_dofs`` (n_local, n_cells) as a scikit-fem basis has them; ``u`` and
    ``cavitated`` are per dof, with optional trailing sample axes.
    """
    return np.all(u[element_dofs] == 0.0, axis=0) & np.any(cavitated[element_dofs], axis=0)


def sink_dofs(basis, cavitated: np.ndarray, interior: np.ndarray) -> np.ndarray:
    """The dofs whose nodal residuals make up the flow the full film hands to the ruptured zone.

    On P1 the ruptured dofs themselves: the residual vanishes at every other unknown. On P2 the
    Swift-Stieber condition holds on Bernstein coefficients of the edges between free vertices
    (:func:`bernstein_edges`): the multiplier of a ruptured edge
    coefficient ``v_mid = 2 u_mid - (u_a + u_b) / 2`` also shows in the nodal residuals of the edge's ends,
    so those (free) vertices are added; the rows of that change of basis sum to one, so the sum is the
    multipliers'. For the Swift-Stieber model only (:func:`bearingfe.film.result.build_result`): another
    model's residuals at those vertices are not multipliers. ``cavitated`` is per dof; ``interior`` the unknowns.
    """
    if np.asarray(basis.facet_dofs).shape[0] != 1 or np.asarray(basis.nodal_dofs).shape[0] != 1:
        return cavitated
    free = np.zeros(int(basis.N), bool)
    free[interior] = True
    middle, a, b = bernstein_edges(basis, free)
    cut = np.asarray(cavitated, bool)[middle]
    sink = np.array(cavitated, bool, copy=True)
    np.logical_or.at(sink, a, cut)
    np.logical_or.at(sink, b, cut)
    return sink


def bernstein_edges(basis, free: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The edges of a P2 basis whose coefficient is a Bernstein one: both ends and the middle free.

    The Swift-Stieber condition on P2 holds on these coefficients
    (:mod:`bearingfe.cavitation.swift_stieber`), and their multipliers enter the flow into the
    ruptured zone (:func:`sink_dofs`).

    Parameters
    ----------
    basis : skfem.CellBasis
        A P2 basis (one dof per vertex and per edge).
    free : ndarray of bool, shape (n_dofs,)
        The dofs that are unknowns (not Dirichlet).

    Returns
    -------
    (middle, a, b) : ndarrays of int
        The edges' midside dofs and their end dofs.
    """
    nodal, edge = np.asarray(basis.nodal_dofs[0]), np.asarray(basis.facet_dofs[0])
    a, b = (nodal[k] for k in basis.mesh.facets)
    keep = free[edge] & free[a] & free[b]
    return edge[keep], a[keep], b[keep]
