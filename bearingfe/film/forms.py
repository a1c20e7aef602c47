r"""The Reynolds equation's weak forms and pointwise formulas, written once.

Every solver of the package (:mod:`bearingfe.film.superposition`,
:mod:`bearingfe.cavitation.models`, :mod:`bearingfe.bearings.journal`,
:mod:`bearingfe.adaptivity`, :mod:`bearingfe.film.fd`) takes its forms and its
pressure, flux and shear formulas from here (notation of
``docs/formulations.md``, non-dimensional):

- pressure from the unknown (the pi form's chain rule): with
  ``p = s Pi``, ``s = h^(-3/2)``: ``grad p = s grad Pi - 3/2 p grad h / h``
  (:func:`pressure_from_unknown`); the direct form's unknown is ``p``;
- film flux ``q = -h^3/12 grad p + wedge h/2 u`` [omega R0^2 c]
  (:func:`film_flux`);
- shear on the runner along its velocity ``tau . u = sliding |u|^2/h + h/2 u . grad p``
  [mu omega R0 / c] (:func:`shear`; ``u = e_phi`` on the journal: ``sliding/h + h/2 dp/dphi``),
  whose integral is the friction force (and moment);
- the runner's velocity ``u`` (:mod:`bearingfe.geometry.runner`): ``e_phi`` unless a ``direction``
  field is passed (a thrust collar's ``omega x r``); the Couette terms carry ``u``;
- the viscous dissipation ``mu sliding^2/h + h^3/(12 mu) |grad p|^2`` (:func:`dissipation`), the heat
  source of the film's energy equation (:mod:`bearingfe.thermal.film_energy`);
- a viscosity varying over the film (level 2 of :mod:`bearingfe.thermal`): the direct form's
  coefficient ``h^3 / mu`` in :func:`weighted_laplace`, and the optional ``viscosity`` of
  :func:`film_flux` and :func:`shear`; the isoviscous formulas are unchanged without it;
- the substitution coefficient ``D = -3/(4 h^2) (2 h Lap h + |grad h|^2)``
  (:func:`film_at`);
- the wedge source in conservative form (:func:`couette_source`).

The weak forms are scikit-fem forms with their coefficients passed as
fields (``w.c``, ``w.f`` at the quadrature points).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import skfem
from skfem import BilinearForm, LinearForm
from skfem.helpers import dot, grad
from skfem.mapping import MappingAffine, MappingIsoparametric

__all__ = ["laplace", "mass", "weighted_mass", "weighted_laplace", "load", "gradient_load", "flux_residual",
           "couette_source", "FilmAt",
           "film_at", "unknown_scale", "pressure_from_unknown", "film_flux", "along", "shear", "dissipation", "TolerantMapping",
           "mapping", "straight_edges", "STRAIGHT_TOLERANCE"]


# -- weak forms ----------------------------------------------------------------------

@BilinearForm
def laplace(u, v, w):
    """``int grad u . grad v``."""
    return dot(grad(u), grad(v))


@BilinearForm
def mass(u, v, w):
    """``int u v``."""
    return u * v


@BilinearForm
def weighted_mass(u, v, w):
    """``int c u v`` (``c`` a field at the quadrature points)."""
    return w.c * u * v


@BilinearForm
def weighted_laplace(u, v, w):
    """``int c grad u . grad v`` (``c = h^3`` is the direct Reynolds operator)."""
    return w.c * dot(grad(u), grad(v))


@LinearForm
def load(v, w):
    """``int f v``: a source, a normal flux on facets (``f = q . n``), or a lumped area (``f = 1``)."""
    return w.f * v


@LinearForm
def gradient_load(v, w):
    """``int (f0 dv/dphi + f1 dv/dz)``: a source in divergence form, ``-int div(f) v`` integrated by parts."""
    return w.f0 * v.grad[0] + w.f1 * v.grad[1]


@LinearForm
def flux_residual(v, w):
    """``int q . grad v - int dh/dt v``: the boundary flux of ``q`` tested with ``v``."""
    return w.q0 * v.grad[0] + w.q1 * v.grad[1] - w.hdot * v


# -- film fields and pointwise formulas -------------------------------------------------

@dataclass(frozen=True)
class FilmAt:
    """A film's fields at a set of points (e.g. the quadrature points).

    Attributes
    ----------
    h : ndarray
        Thickness [c].
    dh : (ndarray, ndarray)
        ``(dh/dphi, dh/dz)``.
    shapes : (ndarray, ndarray)
        ``dh/dgamma`` and ``dh/dphi0`` (the squeeze shapes).
    D : ndarray
        Coefficient of the pi form, ``-3/(4 h^2) (2 h Lap h + |grad h|^2)``.
    """

    h: np.ndarray
    dh: tuple[np.ndarray, np.ndarray]
    shapes: tuple[np.ndarray, np.ndarray]
    D: np.ndarray


def film_at(film, x: np.ndarray, angles: tuple[np.ndarray, np.ndarray] | None = None) -> FilmAt:
    """Evaluate a :class:`~bearingfe.film.thickness.Film` at points ``x`` (shape ``(2, ...)``).

    ``angles``, optional: ``(cos x[0], sin x[0])``, computed once per set of
    points; a film with ``fields_from_angles`` (:class:`~bearingfe.film.thickness.CosineFilm`)
    then needs no trigonometric call (same fields to round-off).
    """
    fast = getattr(film, "fields_from_angles", None) if angles is not None else None
    if fast is not None:
        h, dh, lap, shapes = fast(*angles)
    else:
        h = np.asarray(film.thickness(x[0], x[1]), dtype=float)
        dh = tuple(np.asarray(g, dtype=float) for g in film.gradient(x[0], x[1]))
        lap = np.asarray(film.laplacian(x[0], x[1]), dtype=float)
        shapes = tuple(np.asarray(s, dtype=float) for s in film.rate_shapes(x[0], x[1]))
    if len(shapes) != 2:
        raise ValueError("film.rate_shapes must return two shapes (dh/dgamma, dh/dphi0)")
    with np.errstate(divide="ignore", invalid="ignore"):  # h <= 0 is reported by the caller
        D = -0.75 * (2 * h * lap + dh[0] ** 2 + dh[1] ** 2) / h**2
    return FilmAt(h=h, dh=dh, shapes=shapes, D=D)


def unknown_scale(h, formulation: str):
    """``s`` in ``p = s u``: ``h^(-3/2)`` for the pi form, 1 for the direct form."""
    return np.asarray(h, dtype=float) ** -1.5 if formulation == "pi" else 1.0


def pressure_from_unknown(value, gradient, h, dh, formulation: str) -> tuple[np.ndarray, np.ndarray]:
    """Pressure and its gradient from the unknown's value and gradient at the same points.

    ``p = u`` for the direct form; for the pi form ``p = h^(-3/2) Pi`` and
    ``grad p = h^(-3/2) grad Pi - 3/2 p grad h / h`` (the chain rule).
    """
    value, gradient = np.asarray(value), np.asarray(gradient)
    if formulation == "direct":
        return value, gradient
    s = np.asarray(h) ** -1.5
    p = s * value
    dp = np.array([s * gradient[k] - 1.5 * p / h * dh[k] for k in range(2)])
    return p, dp


def couette_source(h, formulation: str):
    """The wedge (Couette) source of the Reynolds equation in conservative form, per unit wedge.

    For a runner velocity ``u`` other than ``e_phi`` (divergence free, :mod:`bearingfe.geometry.runner`)
    the density multiplies ``u . grad v`` instead of ``dv/dphi`` (``div(h u) = u . grad h``).

    The source ``6 wedge dh/dphi`` is tested in divergence form, integrated by parts
    against test functions that vanish on the Dirichlet boundary:
    ``int 6 dh/dphi v = -int 6 h dv/dphi``. So the load of the wedge column is
    ``int c dv/dphi`` with ``c = -6 h`` in the direct form; in the pi form the
    source is ``h^(-3/2) 6 dh/dphi = -12 d(h^(-1/2))/dphi``, so ``c = 12 h^(-1/2)``.
    Only ``h`` enters, never its derivative: a film with a step (a Rayleigh step,
    a pocket edge, a user film with a jump) contributes its jump exactly, where
    ``dh/dphi`` at quadrature points would miss it.

    The density is shifted by a constant (its value at the first point), which the
    integral does not see (the derivatives of the test functions integrate to zero
    over the film) and which makes the source of a uniform film vanish exactly,
    not to round-off.
    """
    h = np.asarray(h, dtype=float)
    c = -6.0 * h if formulation == "direct" else 12.0 * h**-0.5
    return c - c.flat[0] if c.size else c


def film_flux(h, dp, wedge: float, viscosity=None, direction=None, fill=None) -> tuple[np.ndarray, np.ndarray]:
    """``q = -h^3/12 grad p + wedge h/2 u`` (Poiseuille plus Couette) [omega R0^2 c].

    ``direction``, optional: the runner's velocity ``u`` at the same points, relative to the reference
    speed (:func:`bearingfe.geometry.runner.velocity_at`); without it ``u = e_phi`` (the original runner).
    ``viscosity``, optional: a viscosity varying over the film, relative to the scale's (a field at the
    same points, or in SI with ``h`` [m], ``p`` [Pa], ``wedge = U`` [m/s]: ``q = -h^3/(12 mu) grad p +
    U h/2`` [m^2/s]); without it the isoviscous formula, unchanged.
    ``fill``, optional: the JFO fill fraction ``theta`` [-]: in a cavity the Couette flux carries the
    liquid's share, ``wedge theta h/2 u``.
    """
    c = -np.asarray(h) ** 3 / 12.0
    if viscosity is not None:
        c = c / viscosity
    couette = 0.5 * wedge * h if fill is None else 0.5 * wedge * fill * h
    if direction is None:
        return c * dp[0] + couette, c * dp[1]
    return c * dp[0] + couette * direction[0], c * dp[1] + couette * direction[1]


def along(direction, vector):
    """``u . v``: a vector field's component along the runner's velocity ``u`` (``v[0]`` for ``u = e_phi``)."""
    if direction is None:
        return vector[0]
    return direction[0] * vector[0] + direction[1] * vector[1]


def _speed_squared(direction):
    return 1.0 if direction is None else direction[0] ** 2 + direction[1] ** 2


def shear(h, dp, sliding: float, viscosity=None, direction=None, fill=None):
    """Shear on the runner along its velocity, ``tau . u = sliding |u|^2/h + h/2 u . grad p``
    [mu omega R0 / c]; its integral is the friction force (the friction torque over ``R0`` for a
    rotating runner; times the reference speed, the friction power).

    ``dp``: the pressure gradient ``(dp/dphi, dp/dz)``; ``direction``: the runner's velocity ``u``
    (:func:`film_flux`), default ``e_phi``: then ``sliding/h + h/2 dp/dphi``.
    ``viscosity``, optional: relative to the scale's, a field at the same points (or in SI: ``mu U/h +
    h/2 dp/dx`` [Pa] with ``sliding = U``); the Poiseuille part does not depend on it.
    ``fill``, optional: the JFO fill fraction ``theta`` [-]: in a cavity only the liquid's share of the
    gap is sheared, ``theta mu U/h``; without it the full film's.
    """
    speed = sliding * _speed_squared(direction)
    couette = speed / h if viscosity is None else viscosity * speed / h
    if fill is not None:
        couette = fill * couette
    return couette + 0.5 * h * along(direction, dp)


def dissipation(h, dp, sliding: float, viscosity=1.0, direction=None, fill=None):
    """Viscous dissipation per unit area ``mu sliding^2 |u|^2/h + h^3/(12 mu) |grad p|^2``
    [mu (omega R0)^2 / c, or W/m^2 in SI]: the heat source of the film's energy equation; its integral
    equals the friction power when ``p`` solves the Reynolds equation (Couette shear work plus the
    Poiseuille flow's pressure work). ``direction``: the runner's velocity ``u`` (:func:`film_flux`);
    ``fill``, optional: the JFO fill fraction ``theta`` [-]; in a cavity only the liquid's share
    dissipates, ``theta mu sliding^2 |u|^2/h``."""
    couette = viscosity * sliding**2 * _speed_squared(direction) / h
    if fill is not None:
        couette = fill * couette
    return couette + np.asarray(h) ** 3 / (12.0 * viscosity) * (dp[0] ** 2 + dp[1] ** 2)


# -- curved elements ---------------------------------------------------------------------

class TolerantMapping(MappingIsoparametric):
    """Isoparametric mapping whose inverse (Newton) stops at a step of 1e-9 in reference
    coordinates instead of scikit-fem's 1e-12, which round-off alone exceeds on curved
    elements smaller than ~1e-3 away from the origin (the iteration then never stops).
    Newton converges quadratically, so the point is accurate to round-off either way."""

    def invF(self, x, tind=None, newton_max_iters=50, newton_tol=1e-9):
        return super().invF(x, tind=tind, newton_max_iters=newton_max_iters, newton_tol=newton_tol)


def mapping(m: skfem.Mesh):
    """The reference mapping of a mesh, one per mesh (kept on it).

    ``None`` (scikit-fem's default, affine) on straight-sided meshes; an
    affine mapping too on a quadratic (``MeshTri2``) mesh whose edges are all
    straight (:func:`straight_edges`, e.g. a rectangle with rectangular
    pockets meshed with ``order=2``), where the isoparametric map is affine
    and only costs more; a :class:`TolerantMapping` on curved meshes.
    """
    if getattr(m, "affine", True):
        return None
    if not hasattr(m, "_bearingfe_mapping"):
        chosen = MappingAffine(m) if straight_edges(m) else TolerantMapping(m, m.elem(), m.bndelem)
        object.__setattr__(m, "_bearingfe_mapping", chosen)
    return m._bearingfe_mapping


#: Largest distance of a quadratic mesh's edge node from its edge's midpoint, relative to the mesh's
#: extent, for the edge to count as straight (gmsh places them at the midpoint to round-off).
STRAIGHT_TOLERANCE = 1e-12


def straight_edges(m: skfem.Mesh) -> bool:
    """True if every edge node of a quadratic triangle mesh lies at its edge's midpoint
    (to :data:`STRAIGHT_TOLERANCE` of the mesh's extent): the element maps are then affine."""
    if not isinstance(m, skfem.MeshTri2):
        return bool(getattr(m, "affine", True))
    vertices = int(m.t.max()) + 1
    edge_nodes = m.doflocs[:, vertices:]
    if edge_nodes.shape[1] != m.facets.shape[1]:  # not the vertex-then-edge node layout scikit-fem builds
        return False
    midpoints = 0.5 * (m.doflocs[:, m.facets[0]] + m.doflocs[:, m.facets[1]])
    extent = float(np.ptp(m.doflocs, axis=1).max())
    return bool(np.abs(edge_nodes - midpoints).max(initial=0.0) <= STRAIGHT_TOLERANCE * extent)
