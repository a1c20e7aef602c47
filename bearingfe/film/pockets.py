"""The pockets of a support surface as unknowns of the film: their names, one pressure per pocket, and one
unit field per pocket.

A pocket is a hole of the mesh with an ``inlet`` boundary (``inlet_0``, ``inlet_1``, ... on meshes of
:func:`bearingfe.mesh_surface`). The film is linear in the pocket pressures, so a linear film state holds
each pocket at its own pressure as a sum of unit fields (:class:`PocketFilm`), and each pocket's film
outflow is a flux residual summed over its contour (:func:`pocket_flows`). The front door reads its
``inlet_pressure`` against the mesh here (:func:`pocket_pressures`); the restrictors balance the pockets on
these fields (:mod:`bearingfe.bearings.hydrostatic`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from ..core.parameters import Discretization
from ..core.schema import finite
from ..geometry.meshing import SupportMesh
from .result import ReynoldsResult, film_outputs
from .superposition import Superposition, superpose
from .thickness import Film

__all__ = ["pocket_names", "pocket_pressures", "PocketFilm", "pocket_film", "pocket_flows", "pocket_unknown"]


def pocket_unknown(sup: Superposition, res: ReynoldsResult) -> np.ndarray:
    """The unknown (``p`` or ``Pi``) of a result on its film state's dofs."""
    if sup.formulation == "direct":
        return np.asarray(res.pressure, float)
    loc = sup.operators.basis.doflocs
    return np.asarray(res.pressure, float) * np.asarray(sup.film.thickness(loc[0], loc[1])) ** 1.5


def pocket_names(mesh: SupportMesh) -> tuple[str, ...]:
    """The mesh's pockets, one boundary name each: ``inlet_0``, ``inlet_1``, ... (meshes of
    :func:`bearingfe.mesh_surface`), or the one ``inlet`` of a mesh read from a file; () without pockets."""
    bnd = mesh.boundaries
    named = sorted((n for n in bnd if n.startswith("inlet_") and n[6:].isdigit()), key=lambda n: int(n[6:]))
    if named:
        return tuple(named)
    return ("inlet",) if mesh.has_inlet else ()


def pocket_pressures(mesh: SupportMesh, inlet_pressure) -> float | tuple[float, ...]:
    """The front door's ``inlet_pressure`` read against the mesh's pockets [-].

    A number is returned as a float (every pocket at it); a sequence (one value per pocket, in the order
    of :func:`pocket_names`) or a mapping ``name -> value`` (every pocket named once) as a tuple in
    :func:`pocket_names` order.

    Raises
    ------
    ValueError
        The mesh has no pockets, a sequence of the wrong length, a mapping with unknown or missing names,
        or a value that is not a finite number.
    """
    if not isinstance(inlet_pressure, (Mapping, str)) and np.ndim(inlet_pressure) == 0:
        return finite("inlet_pressure", inlet_pressure.item() if isinstance(inlet_pressure, np.ndarray)
                      else inlet_pressure)
    names = pocket_names(mesh)
    if not names:
        raise ValueError("inlet_pressure: one value per pocket was given but the mesh has no pockets "
                         "('inlet' boundaries)")
    if isinstance(inlet_pressure, Mapping):
        given = set(inlet_pressure)
        if given != set(names):
            unknown, missing = sorted(map(str, given - set(names))), sorted(set(names) - given)
            raise ValueError(f"inlet_pressure: a mapping must name every pocket once ({', '.join(names)}); "
                             f"unknown {unknown}, missing {missing}")
        values = [inlet_pressure[n] for n in names]
    else:
        try:
            values = list(inlet_pressure)
        except TypeError:
            raise ValueError(f"inlet_pressure must be a number, one value per pocket ({', '.join(names)}) or a "
                             f"mapping name -> value, got {type(inlet_pressure).__name__}") from None
        if len(values) != len(names):
            raise ValueError(f"inlet_pressure must give one value per pocket ({len(names)}: {', '.join(names)}), "
                             f"got {len(values)}")
    return tuple(finite(f"inlet_pressure[{n!r}]", v) for n, v in zip(names, values))


def _pocket_mesh(mesh: SupportMesh, name: str, names: Sequence[str]) -> SupportMesh:
    """The mesh with only pocket ``name`` as its ``inlet`` (the other pockets join the outline at 0):
    the same dofs, so its unit inlet field is pocket ``name``'s and its ``inlet`` flow is that pocket's."""
    if len(names) == 1:
        return mesh
    def build() -> SupportMesh:
        bnd = mesh.boundaries
        others = [np.asarray(bnd[n]) for n in names if n != name]
        new = dict(bnd, inlet=np.asarray(bnd[name]), outer=np.union1d(bnd["outer"], np.concatenate(others)))
        return SupportMesh(mesh=_replacing_boundaries(mesh.mesh, new), surface=mesh.surface, size=mesh.size,
                           source=mesh.source)

    return mesh.cached(("pocket mesh", name), build)


def _replacing_boundaries(m, boundaries: Mapping[str, np.ndarray]):
    """A scikit-fem mesh with its boundaries replaced (``with_boundaries`` only adds to them)."""
    return dataclasses.replace(m, _boundaries={k: np.asarray(v) for k, v in boundaries.items()})


@dataclass(frozen=True, eq=False)
class PocketFilm:
    """The film of a support with its pockets as unknowns: one unit field per pocket (linear models).

    Attributes
    ----------
    whole : Superposition
        The film state with all pockets as its ``inlet``.
    pockets : tuple of Superposition
        One per pocket: its ``inlet`` column is that pocket at unit pressure, the others at 0.
    """

    whole: Superposition
    pockets: tuple[Superposition, ...]

    def state(self, pressures: np.ndarray) -> Superposition:
        """The film state whose ``inlet`` column holds every pocket at its pressure (weight 1)."""
        p = np.asarray(pressures, float)
        fields = self.whole.fields.copy()
        fields[:, 3] = sum(pk * s.fields[:, 3] for pk, s in zip(p, self.pockets))
        whole = self.whole.system
        system = dataclasses.replace(
            whole, build_matrix=lambda: whole.matrix,  # the matrix does not depend on the pocket data: built once
            rhs=_column(self.whole.system.rhs, sum(pk * s.system.rhs[:, 3] for pk, s in zip(p, self.pockets))),
            lift=_column(self.whole.system.lift, sum(pk * s.system.lift[:, 3] for pk, s in zip(p, self.pockets))))
        forces = _column(self.whole.forces, sum(pk * s.forces[:, 3] for pk, s in zip(p, self.pockets)))
        integrals = self.whole.integrals.copy()
        integrals[3] = sum(pk * s.integrals[3] for pk, s in zip(p, self.pockets))
        units = (fields, forces, integrals)
        return dataclasses.replace(self.whole, unit_solutions=lambda: units, system=system)

    def pocket_moments(self, pressures: np.ndarray) -> np.ndarray:
        """``(area, int cos, int sin)`` of the pockets weighted by their pressures."""
        return sum(pk * s.operators.pocket_moments for pk, s in zip(np.asarray(pressures, float), self.pockets))


def _column(a: np.ndarray, values) -> np.ndarray:
    out = a.copy()
    out[..., 3] = values
    return out


def pocket_film(mesh: SupportMesh, film: Film, discretization: Discretization = Discretization(),
                on_indefinite: str = "fallback") -> PocketFilm:
    """The unit fields of each pocket of ``mesh`` (:class:`PocketFilm`): one factorization per pocket."""
    names = pocket_names(mesh)
    if not names:
        raise ValueError("the mesh has no pockets ('inlet' boundaries): nothing to feed")

    def sup(m: SupportMesh) -> Superposition:
        return superpose(m, film, formulation=discretization.formulation, element=discretization.element,
                         solver=discretization.solver, on_indefinite=on_indefinite)

    whole = sup(mesh)
    pockets = tuple(whole if len(names) == 1 else sup(_pocket_mesh(mesh, n, names)) for n in names)
    if any(s.formulation != whole.formulation for s in pockets):  # the film decides it: cannot happen
        raise RuntimeError("the pockets' film states chose different formulations")
    return PocketFilm(whole=whole, pockets=pockets)


def pocket_flows(pf: PocketFilm, u: np.ndarray, weights: np.ndarray,
                 cavitated: np.ndarray | None = None) -> np.ndarray:
    """Film outflow of each pocket [omega R0^2 c] of unknown fields ``u`` (n_dofs, S) at source weights
    (4, S): the consistent flux residual summed over each pocket's contour (:mod:`bearingfe.film.flows`).

    Returns shape ``(n_pockets, S)``.
    """
    u = np.asarray(u, float)
    weights = np.asarray(weights, float)
    S = u.shape[1]
    cav = None if cavitated is None else np.asarray(cavitated)  # the shear speed is no part of the flows
    return np.array([film_outputs([s] * S, u, weights, weights[0], cav).flows["inlet"] for s in pf.pockets])


