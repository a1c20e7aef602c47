r"""Finite-difference reference of a thrust pad's film on a polar grid (an independent check of the FEM).

On an annular sector (:class:`~bearingfe.geometry.surface.AnnularSector`) under a runner rotating about
the sector's centre (:class:`~bearingfe.geometry.runner.Rotating`), the Reynolds equation of the package
(``div(h^3 grad p) = 6 wedge u . grad h``, ``u = sense r e_theta``), multiplied by ``r``, reads in polar
coordinates

.. math::

    \partial_r (r h^3 \partial_r p) + \frac{1}{r} \partial_\theta (h^3 \partial_\theta p)
    = 6\,\mathrm{wedge}\,\mathrm{sense}\; r\, \partial_\theta h,

with ``p = 0`` on the four edges. :func:`solve_sector_fd` discretizes it by the conservative five-point
scheme on a uniform ``(r, theta)`` grid (film at the cell faces, the Couette term as a difference of the
face films, so a step across ``theta`` is taken exactly in flux form), second order for smooth films,
and integrates the load and its moments by the trapezoidal rule in ``r dr dtheta``. It shares no code
with the finite-element path (other coordinates, other unknowns, other quadrature): the agreement of
the two under refinement is a check of the FEM's runner velocity field, its sector meshes and its loads.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

__all__ = ["SectorFD", "solve_sector_fd"]


@dataclass(frozen=True)
class SectorFD:
    """Polar finite-difference solution of a sector pad's film (non-dimensional, as the FEM's).

    Attributes
    ----------
    r, theta : ndarray
        Grid radii and angles from the sector's start [-, rad].
    pressure : ndarray, shape (len(r), len(theta))
        Pressure at the grid nodes [-] (0 on the edges).
    load : float
        ``int p dA`` [-].
    moment : (float, float)
        ``int p (x - x_c) dA`` and ``int p (y - y_c) dA`` about the sector's centre [-].
    """

    r: np.ndarray
    theta: np.ndarray
    pressure: np.ndarray
    load: float
    moment: tuple[float, float]


def solve_sector_fd(sector, film, n_r: int, n_theta: int, *, wedge: float = 1.0, sense: int = 1) -> SectorFD:
    """Solve the full film (no cavitation) of ``film`` on ``sector`` on an ``n_r x n_theta``-cell polar grid.

    Parameters
    ----------
    sector : AnnularSector
        The pad's outline; the runner rotates about its centre.
    film : Film
        Thickness ``h(x, y)`` [c] in the sector's plane.
    n_r, n_theta : int
        Cells across the radius and the angle, each >= 2.
    wedge : float
        Couette factor (the runner's speed at the unit radius over the reference speed).
    sense : {+1, -1}
        The runner's sense of rotation (+1: counter-clockwise, from ``start`` towards ``start + extent``).
    """
    for name, n in (("n_r", n_r), ("n_theta", n_theta)):
        if not (isinstance(n, (int, np.integer)) and n >= 2):
            raise ValueError(f"{name} must be an integer >= 2, got {n!r}")
    if sense not in (1, -1):
        raise ValueError(f"sense must be +1 or -1, got {sense!r}")
    ri, ro = sector.inner_radius, sector.outer_radius
    r = np.linspace(ri, ro, n_r + 1)
    t = np.linspace(0.0, sector.extent, n_theta + 1)
    dr, dt = r[1] - r[0], t[1] - t[0]

    def h_at(rr, tt):
        a = sector.start + tt
        x, y = sector.centre[0] + rr * np.cos(a), sector.centre[1] + rr * np.sin(a)
        return np.asarray(film.thickness(x, y), float) + 0.0 * x

    R, T = np.meshgrid(r, t, indexing="ij")
    rf = 0.5 * (r[1:] + r[:-1])                                  # radial faces
    Rr, Tr = np.meshgrid(rf, t, indexing="ij")
    hr3 = h_at(Rr, Tr) ** 3                                      # (n_r, n_theta + 1)
    tf = 0.5 * (t[1:] + t[:-1])                                  # angular faces
    Rt, Tt = np.meshgrid(r, tf, indexing="ij")
    ht = h_at(Rt, Tt)                                            # (n_r + 1, n_theta)
    if min(hr3.min(), ht.min()) <= 0:
        raise ValueError("the film reaches h <= 0 on the sector")
    ni, nj = n_r - 1, n_theta - 1
    index = np.arange(ni * nj).reshape(ni, nj)
    rows, cols, vals = [], [], []
    rhs = np.zeros(ni * nj)
    I, J = np.meshgrid(np.arange(1, n_r), np.arange(1, n_theta), indexing="ij")
    k = index.ravel()
    cr_plus = (rf[I] * hr3[I, J] / dr**2).ravel()                # face i + 1/2
    cr_minus = (rf[I - 1] * hr3[I - 1, J] / dr**2).ravel()       # face i - 1/2
    ct_plus = (ht[I, J] ** 3 / (r[I] * dt**2)).ravel()           # face j + 1/2
    ct_minus = (ht[I, J - 1] ** 3 / (r[I] * dt**2)).ravel()
    rows.append(k), cols.append(k), vals.append(-(cr_plus + cr_minus + ct_plus + ct_minus))
    for di, dj, c in ((1, 0, cr_plus), (-1, 0, cr_minus), (0, 1, ct_plus), (0, -1, ct_minus)):
        ii, jj = (I + di).ravel(), (J + dj).ravel()
        inside = (ii >= 1) & (ii <= ni) & (jj >= 1) & (jj <= nj)
        rows.append(k[inside]), cols.append(index[ii[inside] - 1, jj[inside] - 1]), vals.append(c[inside])
    rhs[:] = (6.0 * wedge * sense * r[I] * (ht[I, J] - ht[I, J - 1]) / dt).ravel()
    A = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(k.size, k.size))
    p = np.zeros((n_r + 1, n_theta + 1))
    p[1:-1, 1:-1] = spla.spsolve(A.tocsc(), rhs).reshape(ni, nj)
    w = np.outer(_trapezoid(n_r) * dr, _trapezoid(n_theta) * dt) * R
    a = sector.start + T
    load = float(np.sum(w * p))
    moment = (float(np.sum(w * p * R * np.cos(a))), float(np.sum(w * p * R * np.sin(a))))
    return SectorFD(r=r, theta=t, pressure=p, load=load, moment=moment)


def _trapezoid(n: int) -> np.ndarray:
    w = np.ones(n + 1)
    w[0] = w[-1] = 0.5
    return w
