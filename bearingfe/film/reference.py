r"""The reference assembly: the film system, loads and flows by scikit-fem form assembly, film by film.

It implements the interface of :mod:`bearingfe.film.assembly` with the weak forms of
:mod:`bearingfe.film.forms` assembled afresh for every film state, as a textbook
finite-element code would. It is the test oracle of the compiled assembly
(:mod:`bearingfe.film.compiled`, the production path), which must give the same numbers
to round-off, and the documentation of what those compiled maps compute.

Flows are the consistent boundary fluxes from the weak-form residual (units
``omega R0^2 c``): the flux ``q = -h^3/12 grad p + wedge h/2 e_phi`` tested with each
boundary basis function gives the flow through that part of the boundary; summed
over all dofs it equals ``-int dh/dt`` exactly, so the interior residual measures
the discretization's mass-balance error. A corner dof shared by two edges (e.g.
``side`` and ``arc_start``) carries the flux of both: it is split by the direct
facet integrals of ``q . n`` on each edge, and only the (small) difference between
the residual and those integrals is shared equally.

With a mask of ruptured dofs, the residual at those dofs is the flow the full film
hands to the ruptured zone. In the ruptured elements
(:func:`bearingfe.film.flows.ruptured_elements`) the Couette flow is not conserved
(``div q + dh/dt = wedge/2 dh/dphi + dh/dt != 0``); that source is added back to the
residual so that a boundary dof next to the ruptured zone reports the flow through
the boundary only (without it the side flow of a cavitated film is biased by
O(element size)), and ``flows["cavitation"]`` takes the difference, so the balance
identity ``inlet = outflows + squeeze + cavitation`` is unchanged.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Mapping, Sequence

import numpy as np
import scipy.sparse as sp
import skfem

from . import forms
from .compiled import FilmFlows
from .flows import named_flows, outflow, ruptured_elements
from .forms import FilmAt, along, couette_source, film_at, film_flux, pressure_from_unknown, shear, unknown_scale
from ..geometry.runner import velocity_at
from ..core.linalg import Factorize, Solve

if TYPE_CHECKING:
    from .mesh_operators import Operators
    from .thickness import Film

__all__ = ["ReferenceAssembly", "ReferenceSystem", "system_matrix", "unit_sources", "pressure_at_quadrature"]


def system_matrix(ops: "Operators", at: FilmAt, formulation: str) -> sp.csr_matrix:
    """The Reynolds operator on all dofs: ``int h^3 grad u . grad v`` (direct) or
    ``int grad u . grad v - int D u v`` (pi)."""
    if formulation == "direct":
        return forms.weighted_laplace.assemble(ops.basis, c=at.h**3).tocsr()
    return (ops.laplace - forms.weighted_mass.assemble(ops.basis, c=at.D)).tocsr()


def unit_sources(ops: "Operators", at: FilmAt, formulation: str) -> np.ndarray:
    """Load vectors of the four unit sources (the inlet one is zero): the wedge in conservative
    form (:func:`bearingfe.film.forms.couette_source`), the squeeze rates ``int 12 s dh/dq_k v``."""
    weight = unknown_scale(at.h, formulation)
    basis = ops.basis
    c = couette_source(at.h, formulation)
    u = velocity_at(ops.mesh.runner, ops.x)
    f0, f1 = (c, np.zeros_like(at.h)) if u is None else (c * u[0], c * u[1])
    return np.column_stack([
        forms.gradient_load.assemble(basis, f0=f0, f1=f1),
        forms.load.assemble(basis, f=weight * 12.0 * at.shapes[0]),
        forms.load.assemble(basis, f=weight * 12.0 * at.shapes[1]),
        np.zeros(basis.N),
    ])


def pressure_at_quadrature(ops: "Operators", at: FilmAt, u: np.ndarray, formulation: str):
    """Pressure and its gradient at the quadrature points from the unknown ``u``."""
    field_ = ops.basis.interpolate(u)
    return pressure_from_unknown(np.array(field_), field_.grad, at.h, at.dh, formulation)


class ReferenceSystem:
    """One film state's system by form assembly (see :class:`bearingfe.film.assembly.FilmSystem`)."""

    def __init__(self, ops: "Operators", at: FilmAt, formulation: str) -> None:
        self.ops, self.at, self.formulation = ops, at, formulation
        self.A = system_matrix(ops, at, formulation)

    def full_matrix(self) -> sp.csr_matrix:
        return self.A

    def condensed_matrix(self) -> sp.csr_matrix:
        I = self.ops.interior
        return self.A[I][:, I]

    def rhs(self, lift: np.ndarray) -> np.ndarray:
        F = unit_sources(self.ops, self.at, self.formulation)
        I, B = self.ops.interior, self.ops.boundary
        return -F[I] - self.A[I][:, B] @ lift[B]

    def factorize(self, factorize: Factorize) -> Solve:
        return factorize(self.condensed_matrix())

    def unit_loads(self, U: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        forces = np.zeros((2, U.shape[1]))
        integrals = np.zeros(U.shape[1])
        for k in range(U.shape[1]):
            forces[:, k], integrals[k] = _loads(self.ops, self.at, U[:, k], self.formulation)
        return forces, integrals


def _loads(ops: "Operators", at: FilmAt, u: np.ndarray, formulation: str) -> tuple[np.ndarray, float]:
    p, _ = pressure_at_quadrature(ops, at, u, formulation)
    x, dx = ops.x, ops.basis.dx
    return (np.array([np.sum(p * np.cos(x[0]) * dx), np.sum(p * np.sin(x[0]) * dx)]), float(np.sum(p * dx)))


class ReferenceAssembly:
    """The film system of one ``(mesh, element)`` by scikit-fem form assembly (the test oracle)."""

    def __init__(self, ops: "Operators") -> None:
        self.ops = ops

    def system(self, at: FilmAt, formulation: str) -> ReferenceSystem:
        return ReferenceSystem(self.ops, at, formulation)

    def film_at(self, film: "Film") -> FilmAt:
        return film_at(film, self.ops.x)

    def field_loads(self, at: FilmAt, formulation: str, u: np.ndarray) -> tuple[np.ndarray, float]:
        return _loads(self.ops, at, u, formulation)

    def outputs(self, states: Sequence[tuple["Film", FilmAt, str]], u: np.ndarray, weights: np.ndarray,
                sliding: np.ndarray, cavitated: np.ndarray | None = None) -> FilmFlows:
        per_state = [self._outputs(film, at, formulation, u[:, s], weights[:, s], float(sliding[s]),
                                   None if cavitated is None else cavitated[:, s])
                     for s, (film, at, formulation) in enumerate(states)]
        names = per_state[0][0].keys()
        return FilmFlows(flows={k: np.array([f[k] for f, _, _ in per_state]) for k in names},
                         mass_balance=np.array([b for _, b, _ in per_state]),
                         friction=np.array([fr for _, _, fr in per_state]))

    def _outputs(self, film, at, formulation, u, weights, sliding, cavitated):
        ops = self.ops
        _, dp = pressure_at_quadrature(ops, at, u, formulation)
        flows, balance = _flows(ops, film, at, u, formulation, dp, float(weights[0]), weights[1:3], cavitated)
        direction = velocity_at(ops.mesh.runner, ops.x)
        friction = float(np.sum(shear(at.h, dp, sliding, direction=direction) * ops.basis.dx))
        return flows, balance, friction


def _flows(ops: "Operators", film: "Film", at: FilmAt, u: np.ndarray, formulation: str, dp,
           wedge: float, rates, cavitated: np.ndarray | None = None) -> tuple[dict[str, float], float]:
    """Consistent boundary fluxes from the weak-form residual (see the module docstring)."""
    hdot = rates[0] * at.shapes[0] + rates[1] * at.shapes[1]
    direction = velocity_at(ops.mesh.runner, ops.x)
    q0, q1 = film_flux(at.h, dp, wedge, direction=direction)
    r = forms.flux_residual.assemble(ops.basis, q0=q0, q1=q1, hdot=hdot)
    direct = {name: _facet_flux(fb, film, u, formulation, wedge, ops.mesh.runner)
              for name, fb in ops.facet_bases.items()}
    flows = _group_flows(ops, r, direct, hdot)
    balance = flows["inlet"] - outflow(flows) - flows["squeeze"]
    if cavitated is None:
        return flows, float(balance)
    cavitation = float(np.sum(r[cavitated]))
    ruptured = ruptured_elements(ops.basis.element_dofs, u, cavitated)
    corrected = dict(flows)
    if ruptured.any():
        source = np.where(ruptured[:, None], 0.5 * wedge * along(direction, at.dh) + hdot, 0.0)
        corrected = _group_flows(ops, r + forms.load.assemble(ops.basis, f=source), direct, hdot)
    corrected["cavitation"] = (cavitation + (corrected["inlet"] - flows["inlet"])
                               - (outflow(corrected) - outflow(flows)))
    return corrected, float(balance - cavitation)


def _group_flows(ops: "Operators", r: np.ndarray, direct: Mapping[str, np.ndarray], hdot) -> dict[str, float]:
    """Flows through the boundary groups from the nodal residual ``r`` (corners split by ``direct``)."""
    shared = np.zeros(ops.n_dofs)
    for name, (dofs, weights) in ops.flow_groups.items():
        if name in direct:
            shared[dofs[weights < 1]] += direct[name][dofs[weights < 1]]
    by_group = []
    for name, (dofs, weights) in ops.flow_groups.items():
        corner = weights < 1
        value = np.sum(r[dofs[~corner]])
        if corner.any():
            c = dofs[corner]
            value += np.sum(direct[name][c] + (r[c] - shared[c]) * weights[corner])
        by_group.append(float(value))
    flows = named_flows(tuple(ops.flow_groups), np.array(by_group), float(np.sum(hdot * ops.basis.dx)))
    return {k: float(v) for k, v in flows.items()}


def _facet_flux(fb: skfem.FacetBasis, film: "Film", u: np.ndarray, formulation: str, wedge: float,
                runner=None) -> np.ndarray:
    """``int q . n v ds`` on the facets of ``fb`` from the solution gradient."""
    x = np.array(fb.global_coordinates())
    at = film_at(film, x)
    field_ = fb.interpolate(u)
    _, dp = pressure_from_unknown(np.array(field_), field_.grad, at.h, at.dh, formulation)
    n = np.array(fb.normals)
    q0, q1 = film_flux(at.h, dp, wedge, direction=velocity_at(runner, x))
    return forms.load.assemble(fb, f=q0 * n[0] + q1 * n[1])
