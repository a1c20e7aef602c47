"""The compliance of an elastic support: the linear map from film pressure to film opening.

:class:`Compliance` is what every elastic model of :data:`bearingfe.elastic.COMPLIANCES`
builds and what the coupled film (:mod:`bearingfe.elastic.coupled`) and the elastic
transient take: ``w = C p + p_s c_pocket`` on the film dofs, in clearances. Most models hold
``C`` as a dense matrix, so its size is guarded (:func:`check_dense_size`); the
half-space on a uniform grid (:func:`bearingfe.elastic.convolution.half_space_fft`)
holds only its product (:meth:`Compliance.apply`, an FFT convolution) and has no cap.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..core.limits import check_limit
from ..core.machine import Material
from ..core.scales import Scale
from ..film import operators
from ..geometry.meshing import SupportMesh

__all__ = ["ElasticError", "Compliance", "combined_modulus", "contact_modulus", "check_dense_size",
           "TOLERANCE", "MAX_ITERATIONS"]

#: Default tolerance of the coupled solve on ``max |C p - w|`` [clearance].
TOLERANCE = 1e-8
#: Default cap on coupled iterations.
MAX_ITERATIONS = 100


class ElasticError(RuntimeError):
    """The coupled elastic film (EHD) iteration did not converge or the film closed."""



def combined_modulus(first: Material, second: Material | None = None) -> float:
    """Contact modulus ``E*`` of two elastic bodies [Pa].

    ``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2``; with one material the other
    body is rigid. Steel on steel (210 GPa, 0.3): 115.4 GPa.
    """
    total = 0.0
    for m in (first, second):
        if m is None:
            continue
        if not isinstance(m, Material):
            raise ValueError(f"materials must be bearingfe.Material, got {type(m).__name__}")
        total += (1.0 - m.poisson_ratio**2) / m.youngs_modulus
    return math.inf if total == 0.0 else 1.0 / total


@dataclass(frozen=True, eq=False)
class Compliance:
    """Linear map from the film pressure to the deflection of the film surfaces.

    ``w = matrix @ p + inlet_pressure * pocket`` with ``p`` the nodal
    pressure (the dofs of :attr:`ReynoldsResult.pressure`) and ``w`` the
    opening of the film at the same dofs, in units of the clearance.

    Attributes
    ----------
    mesh : SupportMesh
    element : str
    model : str
        ``"half-space"``, ``"body"`` (the block of :func:`shoe_body`) or ``"shoe"``
        (:func:`bearingfe.elastic.shoe.shoe_compliance`).
    matrix : ndarray, shape (n_dofs, n_dofs), or None
        Deflection [c] per unit non-dimensional pressure; None for a
        compliance held as its product only (``operator``).
    pocket : ndarray, shape (n_dofs,)
        Deflection [c] per unit pocket pressure.
    modulus : float
        Contact modulus ``E*`` [Pa] (``inf``: rigid).
    scale : Scale
    seconds : float
        Build time [s].
    operator : callable, optional
        ``operator(p) -> C p`` (``p`` of shape ``(n_dofs,)`` or ``(n_dofs, k)``)
        when ``matrix`` is None (e.g. ``model="half-space-fft"``).
    """

    mesh: SupportMesh
    element: str
    model: str
    matrix: np.ndarray
    pocket: np.ndarray
    modulus: float
    scale: Scale
    seconds: float
    operator: Callable[[np.ndarray], np.ndarray] | None = None

    def __post_init__(self) -> None:
        if self.matrix is None and self.operator is None:
            raise ValueError("a Compliance needs its matrix or its operator (the product C p)")

    @property
    def n_dofs(self) -> int:
        return int(np.shape(self.pocket)[0])

    @property
    def dense(self) -> bool:
        """Whether :attr:`matrix` is held (else only the product :meth:`apply`)."""
        return self.matrix is not None

    def apply(self, pressure: np.ndarray) -> np.ndarray:
        """``C p`` [c] for the nodal pressure(s) ``p`` [-], shape ``(n_dofs,)`` or ``(n_dofs, k)``."""
        p = np.asarray(pressure, float)
        return self.matrix @ p if self.matrix is not None else np.asarray(self.operator(p), float)

    def to_dense(self) -> np.ndarray:
        """The matrix ``C`` (for a compliance held as its product: ``C`` applied to the identity; small meshes)."""
        if self.matrix is not None:
            return self.matrix
        check_dense_size(self.n_dofs)
        return self.apply(np.eye(self.n_dofs))

    @property
    def basis_doflocs(self) -> np.ndarray:
        """Coordinates ``(phi, z)`` of the dofs where the deflection is given, shape (2, n_dofs)."""
        return operators(self.mesh, self.element).basis.doflocs

    def deflection(self, pressure: np.ndarray, inlet_pressure: float = 0.0) -> np.ndarray:
        """Film opening ``w`` [c] at the dofs for the nodal pressure ``p`` [-]."""
        p = np.asarray(pressure, float)
        if p.shape != (self.n_dofs,):
            raise ValueError(f"pressure must have one value per dof ({self.n_dofs}), got shape {p.shape}")
        return self.apply(p) + float(inlet_pressure) * self.pocket


def contact_modulus(modulus) -> float:
    """``E*`` [Pa] from a number, a :class:`Material` or a pair of them (the other body rigid if one)."""
    if isinstance(modulus, Material):
        return combined_modulus(modulus)
    if isinstance(modulus, tuple) and len(modulus) == 2 and all(isinstance(m, Material) for m in modulus):
        return combined_modulus(*modulus)
    try:
        value = float(modulus)
    except (TypeError, ValueError):
        raise ValueError(f"modulus must be E* in Pa (> 0, inf for rigid), a Material or a pair of them, "
                         f"got {modulus!r}") from None
    if not value > 0 or math.isnan(value):
        raise ValueError(f"modulus must be E* in Pa, > 0 (inf for rigid), got {modulus!r}")
    return value


def check_dense_size(n_dofs: int) -> None:
    """Refuse a dense compliance on more than ``limit("compliance")`` film dofs (:mod:`bearingfe.core.limits`).

    The compliance is a dense ``n x n`` matrix, and the coupled solves and the
    elastic transient factor dense matrices of that size: memory grows as
    ``n^2`` (about 64 n^2 bytes in :func:`bearingfe.transient.elastic.simulate_elastic`,
    1 GB at 4000 dofs) and time as ``n^3``. ``docs/elastic.md`` has the
    measured costs by mesh size.
    """
    check_limit("compliance", n_dofs)
