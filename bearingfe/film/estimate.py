r"""How far a solve's load is from converged: the once-refined comparison.

A solve on a mesh of element size ``s`` and the same solve on that mesh
refined once (every triangle split in four, size ``s/2``) give the loads
``F_s`` and ``F_s/2``. Where the load error falls like ``C s^k`` (``k`` the
order of the discretization, :data:`LOAD_ORDERS`), Richardson's argument
gives the error of the coarse load and the converged value::

    F_s - F  ~  (F_s - F_s/2) / (1 - 2^-k),        F  ~  F_s/2 + (F_s/2 - F_s) / (2^k - 1)

The factor ``1 / (1 - 2^-k)`` is between 1 and 2 for every ``k >= 1``, so a
wrong order moves the estimate by less than a factor 2: what the estimate
needs is that both meshes are in the asymptotic range. Measured effectivities
(estimate over the true error, from closed forms and converged references)
are in ``docs/validation.md``: 0.92 to 1.01 on the smooth and stepped films
(P1 and P2) and the Swift-Stieber journal (P1 and P2), 0.95 to 1.1 on the
mass-conserving (JFO) pocket slider, 0.98 on an elastic (half-space) shoe
(P1; 0.88 with P2). P2 with Swift-Stieber cavitation converges more slowly
than order 4 near the free boundary (observed 3.4, then 2.2 on the journal),
so there the estimate is somewhat below the error (0.8 to 0.95); its
discrete condition bounds Bernstein coefficients, without which the load
converged irregularly and no estimate from one refinement could follow it
(:mod:`bearingfe.cavitation.swift_stieber`).

The load is measured twice, as ``force = int p (cos phi, sin phi)`` (a
journal's load) and as ``integral = int p`` (a pad's load);
:class:`LoadError` estimates the error of both and its ``relative`` is the
larger of their relative errors.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Mapping

import numpy as np

if TYPE_CHECKING:
    from .result import ReynoldsResult

__all__ = ["ERROR_TOLERANCE", "LOAD_ORDERS", "LoadError", "load_error", "load_order"]

#: Relative load error above which a result carries a note (and a ``ResolutionWarning`` is issued).
ERROR_TOLERANCE = 1e-2

#: Order ``k`` of the load error by ``(discretization, element)`` (:data:`bearingfe.reynolds.DISCRETIZATIONS`):
#: Galerkin P1 and P2 load errors fall like ``s^(2 deg)`` on smooth films and on steps on element edges,
#: also with Swift-Stieber cavitation on P1 (measured 2.0 on the journals of docs/validation.md); the
#: finite-volume scheme's load fell at order 1.8 to 2.7 on the JFO pocket slider (where it falls at order 1,
#: as on the unaligned gmsh meshes of pocketed pads, the estimate would be 0.67 of the error). Others: 1
#: (the largest factor, 2). P2 with Swift-Stieber cavitation falls at order 3.4 then 2.2 on the journal
#: (the free boundary): with the order 4 assumed, the estimate is 0.8 to 0.95 of the error there.
LOAD_ORDERS: Mapping[tuple[str, str], float] = MappingProxyType({
    ("finite-element", "P1"): 2.0,
    ("finite-element", "P2"): 4.0,
    ("finite-volume", "P1"): 2.0,
})


def load_order(discretization: str, element: str) -> float:
    """The order of :data:`LOAD_ORDERS` (1 for a pair it does not list)."""
    return float(LOAD_ORDERS.get((discretization, element), 1.0))


@dataclass(frozen=True)
class LoadError:
    """Estimated error of a solve's load, from the same solve on its mesh refined once.

    Attributes
    ----------
    force_error : float
        ``|F_s - F|`` of ``force`` [mu omega R0^4 / c^2].
    integral_error : float
        ``|I_s - I|`` of ``integral`` (same units).
    relative : float
        The larger of ``force_error / |force|`` and ``integral_error /
        |integral|`` [-], each counted where its load measure is at least
        :data:`NEGLIGIBLE` of the other (0 for a film without load and
        without change).
    refined_relative : float
        The same for the refined solve's load (``1 / (2^k - 1)`` of the
        change instead of ``1 / (1 - 2^-k)``): the error of a caller that
        reports the refined values [-].
    order : float
        Order ``k`` used (:data:`LOAD_ORDERS`).
    extrapolated_force : ndarray, shape (2,)
        Richardson's converged ``force``.
    extrapolated_integral : float
        Richardson's converged ``integral``.
    fine_dofs : int
        Unknowns of the refined solve.
    seconds : float
        Wall time of the refined solve (meshing included) [s].
    tolerance : float
        The ``relative`` above which the result carries a note [-].
    """

    force_error: float
    integral_error: float
    relative: float
    refined_relative: float
    order: float
    extrapolated_force: np.ndarray = field(repr=False)
    extrapolated_integral: float
    fine_dofs: int
    seconds: float
    tolerance: float = ERROR_TOLERANCE

    @property
    def exceeded(self) -> bool:
        """Whether ``relative`` exceeds ``tolerance``."""
        return not self.relative <= self.tolerance

    @property
    def note(self) -> str | None:
        """What the result's ``notes`` say when ``exceeded`` (None otherwise)."""
        if not self.exceeded:
            return None
        return (f"the load is not converged: its estimated error is {100 * self.relative:.3g} % (tolerance "
                f"{100 * self.tolerance:.3g} %; the same solve on the mesh refined once, Richardson at order "
                f"{self.order:g}); use a finer mesh, e.g. mesh_surface(..., refine=1), or bearingfe.adapt")


def load_error(coarse: "ReynoldsResult", fine: "ReynoldsResult", *, order: float,
               tolerance: float = ERROR_TOLERANCE, seconds: float = math.nan) -> LoadError:
    """The :class:`LoadError` of ``coarse`` from the same solve on its mesh refined once.

    Parameters
    ----------
    coarse, fine : ReynoldsResult
        The solve and its refined twin.
    order : float
        Order of the load error, >= 1 (:func:`load_order`).
    tolerance : float
        Relative error above which the result gets a note, > 0.
    seconds : float
        Wall time of the refined solve [s].
    """
    if not (math.isfinite(order) and order >= 1):
        raise ValueError(f"order must be a finite number >= 1, got {order!r}")
    if not (math.isfinite(tolerance) and tolerance > 0):
        raise ValueError(f"tolerance must be a finite relative error > 0, got {tolerance!r}")
    grow = 1.0 / (1.0 - 2.0**-order)       # error of the coarse value per unit change
    tail = 1.0 / (2.0**order - 1.0)        # error of the fine value per unit change
    f_c, f_f = np.asarray(coarse.force, float), np.asarray(fine.force, float)
    i_c, i_f = float(coarse.integral), float(fine.integral)
    force_error = grow * float(np.linalg.norm(f_c - f_f))
    integral_error = grow * abs(i_c - i_f)
    relative = _relative(((force_error, float(np.linalg.norm(f_f))), (integral_error, abs(i_f))))
    return LoadError(force_error=force_error, integral_error=integral_error, relative=relative,
                     refined_relative=relative * tail / grow, order=float(order),
                     extrapolated_force=f_f + tail * (f_f - f_c), extrapolated_integral=i_f + tail * (i_f - i_c),
                     fine_dofs=int(fine.basis.N), seconds=float(seconds), tolerance=float(tolerance))


#: A load measure smaller than this fraction of the other is not compared to its own size (the ``int p`` of a
#: full-Sommerfeld journal cancels to nearly 0, the force of a pad centred on ``phi = 0`` may too).
NEGLIGIBLE = 1e-2


def _relative(measures) -> float:
    """The largest ``error / |value|`` over ``(error, |value|)`` pairs whose value is not negligible."""
    largest = max(value for _, value in measures)
    if largest == 0.0:
        return 0.0 if all(error == 0.0 for error, _ in measures) else math.inf
    return max(error / value for error, value in measures if value >= NEGLIGIBLE * largest)
