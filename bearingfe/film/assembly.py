"""How a film state's system is assembled: one small interface, two implementations, one table.

A film state (:func:`bearingfe.film.superposition.superpose`) needs from an
assembly of the Reynolds operator on one ``(mesh, element)``:

- :meth:`Assembly.film_at`: the film's fields at the quadrature points;
- :meth:`Assembly.system`: the film's :class:`FilmSystem` in a formulation
  (``"pi"`` or ``"direct"``): its full and condensed matrices, the right sides of the
  four unit sources for given Dirichlet data, a factorization of the condensed matrix
  and the loads of unit fields;
- :meth:`Assembly.field_loads`: the force ``int p (cos phi, sin phi)`` and ``int p`` of an
  unknown field (pockets not included);
- :meth:`Assembly.outputs`: flows, mass balance and friction of many film states at
  once (:class:`~bearingfe.film.compiled.FilmFlows`).

:data:`ASSEMBLIES` tables the implementations: ``"compiled"``
(:mod:`bearingfe.film.compiled`: film-independent maps built once per mesh, the
production path) and ``"reference"`` (:mod:`bearingfe.film.reference`: scikit-fem
form assembly per film, the test oracle). They give the same numbers to round-off.
An :class:`~bearingfe.film.mesh_operators.Operators` builds each on first use
(``ops.assembly(name)``).
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Callable, Mapping, Protocol, Sequence

import numpy as np
import scipy.sparse as sp

from .compiled import FilmFlows, compile_operator
from .forms import FilmAt
from .reference import ReferenceAssembly
from ..core.linalg import Factorize, Solve

__all__ = ["FilmSystem", "Assembly", "ASSEMBLIES", "DEFAULT_ASSEMBLY"]


class FilmSystem(Protocol):
    """The system of one film state in one formulation."""

    def full_matrix(self) -> sp.spmatrix:
        """The operator on all dofs."""

    def condensed_matrix(self) -> sp.spmatrix:
        """``A[I, I]`` on the interior dofs ``I``."""

    def rhs(self, lift: np.ndarray) -> np.ndarray:
        """``-F[I] - A[I, B] lift[B]`` of the four unit sources, shape ``(n_I, 4)``."""

    def factorize(self, factorize: Factorize) -> Solve:
        """A solve with ``A[I, I]`` (the assembly may keep its own ordering or storage)."""

    def unit_loads(self, U: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Forces ``(2, k)`` and ``int p`` ``(k,)`` of the unknown fields ``U`` (n_dofs, k), pockets not included."""


class Assembly(Protocol):
    """The film-system assembly of one ``(mesh, element)`` (see the module docstring)."""

    def film_at(self, film) -> FilmAt:
        ...

    def system(self, at: FilmAt, formulation: str) -> FilmSystem:
        ...

    def field_loads(self, at: FilmAt, formulation: str, u: np.ndarray) -> tuple[np.ndarray, float]:
        ...

    def outputs(self, states: Sequence[tuple[object, FilmAt, str]], u: np.ndarray, weights: np.ndarray,
                sliding: np.ndarray, cavitated: np.ndarray | None = None) -> FilmFlows:
        ...


#: The assemblies by name: ``name -> build(operators)``.
ASSEMBLIES: Mapping[str, Callable[..., Assembly]] = MappingProxyType({
    "compiled": compile_operator,
    "reference": ReferenceAssembly,
})
#: The production assembly.
DEFAULT_ASSEMBLY = "compiled"
