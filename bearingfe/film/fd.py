"""Finite-difference reference solver of the Reynolds equation (paper 004's method).

The film domain is the default rectangular outline ``[alpha1, alpha2] x [-a, a]``
of a :class:`~bearingfe.geometry.surface.Surface`, covered by a uniform grid of
``n_phi x n_z`` nodes (boundary nodes included). Pockets are marked by the grid
nodes inside them (a staircase, ``surface.in_pocket``); those nodes and the
outline nodes carry Dirichlet values, every other node is an unknown.

Two five-point discretisations are offered (``formulation``):

``"pi"``
    The paper's eq. (7): with ``p = h^(-3/2) Pi``,
    ``Laplace(Pi) + D Pi = h^(-3/2) f``,
    ``D = -(3 / (4 h^2)) (2 h Laplace(h) + |grad h|^2)``; the standard
    five-point Laplacian plus ``D`` on the diagonal. ``Pi = p_s h^(3/2)`` on
    pockets and 0 on the outline.
``"direct"``
    The conservative scheme for ``div(h^3 grad p) = f`` with ``h^3`` taken at
    the half-points between nodes (the film thickness evaluated there).

Both are second order on smooth solutions. The right-hand side is
``f = 6 wedge dh/dphi + 12 sum_k qdot_k dh/dq_k`` (``film.gradient`` and
``film.rate_shapes`` at the nodes).

Two linear solvers are offered (``method``): ``"direct"`` (scipy sparse LU on
the unknown nodes) and ``"seidel"``, the paper's Gauss-Seidel iteration run
until the relative change ``sum|x^(n+1) - x^n| / sum|x^(n+1)|`` over the
unknowns falls below ``tol`` (the paper's stopping rule). The sweep is
vectorised in red-black (checkerboard) order: every red node is updated from
black neighbours and then every black node from the new red values. For the
five-point stencil this is an exact Gauss-Seidel method (for a consistently
ordered matrix it has the same convergence rate as the lexicographic sweep);
``omega_relax != 1`` turns it into SOR.

``cavitation="reynolds"`` imposes the Swift-Stieber condition ``p >= 0`` by
Christopherson's projected SOR (Proc. IMechE 146 (1941) 126): each
Gauss-Seidel update is followed by ``x = max(x, 0)``. It shares nothing with
the finite-element active-set method of :mod:`bearingfe.cavitation.models` (other
discretisation, other algorithm), which makes it the independent reference
for the free boundary; it needs ``method="seidel"`` and, on fine grids,
over-relaxation (``omega_relax`` about 1.9).

Flows are the discrete conservative fluxes of the dual (finite-volume) cells
of the node grid; see :func:`solve_reynolds_fd` (Notes).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Sequence

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..core.checks import check_operating_point
from ..core.limits import LimitError, check_limit
from .forms import film_flux
from .thickness import is_smooth
from ..geometry.surface import Surface
from ..core.parameters import FORMULATIONS, Discretization, OperatingPoint, takes

__all__ = ["FDResult", "solve_reynolds_fd", "FORMULATIONS", "METHODS"]

#: Linear solvers, by name (the formulations are :data:`bearingfe.core.parameters.FORMULATIONS`).
METHODS = ("direct", "seidel")


@dataclass(frozen=True, eq=False)
class FDResult:
    """Finite-difference solution of the Reynolds equation.

    Attributes
    ----------
    phi : ndarray, shape (n_phi,)
        Grid angles [rad].
    z : ndarray, shape (n_z,)
        Grid axial coordinates [-] (``Z / R0``).
    pressure : ndarray, shape (n_z, n_phi)
        Non-dimensional pressure ``p = P c^2 / (mu omega R0^2)`` at the nodes
        (pocket nodes at the inlet pressure, outline nodes at 0).
    force : ndarray, shape (2,)
        ``(integral p cos(phi), integral p sin(phi)) dphi dz`` over the whole
        outline, pockets included (trapezoid rule on the grid).
    integral : float
        ``integral p dphi dz`` over the outline (trapezoid rule).
    h_min : float
        Smallest film thickness over the film [-].
    flows : dict of str to float
        Non-dimensional flows [omega R0^2 c]: ``side`` (out through
        ``z = +-a``), ``arc_start`` (out through ``phi = alpha1``),
        ``arc_end`` (out through ``phi = alpha2``), ``inlet`` (out of the
        pockets into the film), ``squeeze`` (integral of ``dh/dt`` over the
        film cells) and ``balance`` = ``inlet - side - arc_start - arc_end -
        squeeze`` (the discretisation's mass-balance residual).
    iterations : int
        Seidel sweeps done (0 for the direct solve).
    formulation, method : str
        As requested.
    seconds : float
        Wall time of the solve [s] (assembly + linear solve + outputs).
    """

    phi: np.ndarray
    z: np.ndarray
    pressure: np.ndarray
    force: np.ndarray
    integral: float
    h_min: float
    flows: dict
    iterations: int
    formulation: str
    method: str
    seconds: float


@dataclass(frozen=True)
class _Grid:
    """Uniform node grid of the rectangular outline, arrays of shape (n_z, n_phi)."""

    phi: np.ndarray
    z: np.ndarray
    dphi: float
    dz: float
    fixed: np.ndarray  # outline or pocket node
    pocket: np.ndarray  # pocket node

    @property
    def PHI(self) -> np.ndarray:
        return np.broadcast_to(self.phi[None, :], self.fixed.shape)

    @property
    def Z(self) -> np.ndarray:
        return np.broadcast_to(self.z[:, None], self.fixed.shape)


@dataclass(frozen=True)
class _Stencil:
    """Five-point equations ``cP x_P + cE x_E + cW x_W + cN x_N + cS x_S = b``
    on the full grid (only rows of unknown nodes are used); ``x`` holds the
    Dirichlet values on fixed nodes."""

    cP: np.ndarray
    cE: np.ndarray
    cW: np.ndarray
    cN: np.ndarray
    cS: np.ndarray
    b: np.ndarray
    x: np.ndarray


@takes(OperatingPoint, Discretization)
def solve_reynolds_fd(
    surface: Surface,
    film,
    shape: Sequence[int] = (101, 81),
    *,
    wedge: float = 1.0,
    squeeze: Sequence[float] = (0.0, 0.0),
    inlet_pressure: float = 0.0,
    formulation: str = "pi",
    method: str = "direct",
    tol: float = 1e-10,
    max_iter: int = 200_000,
    omega_relax: float = 1.0,
    cavitation: str = "none",
) -> FDResult:
    """Solve the Reynolds equation by five-point finite differences.

    Parameters
    ----------
    surface : Surface
        Support surface with the default rectangular outline (``outer=None``).
    film : Film
        Film model (e.g. :class:`~bearingfe.film.thickness.CosineFilm`); ``h > 0`` on the grid.
    shape : (int, int)
        ``(n_phi, n_z)`` nodes including the boundary, each >= 3.
    wedge : float
        Factor of the wedge term ``6 wedge dh/dphi`` [-] (1 for the journal
        turning at omega against a fixed shoe).
    squeeze : sequence of float
        Rates of the film's state variables per radian of shaft turn, one per
        ``film.rate_shapes`` (for CosineFilm ``(dgamma, dphi0)``).
    inlet_pressure : float
        Non-dimensional pocket pressure ``p_s`` [-].
    formulation : {"pi", "direct"}
        Substituted (paper eq. 7) or direct conservative discretisation.
    method : {"direct", "seidel"}
        Sparse direct solve or red-black Gauss-Seidel (SOR) iteration.
    tol : float
        Seidel stopping rule: relative change per sweep below ``tol`` (> 0).
    max_iter : int
        Seidel sweep cap; reaching it raises RuntimeError.
    omega_relax : float
        Relaxation factor in (0, 2); 1 is Gauss-Seidel.
    cavitation : {"none", "reynolds"}
        ``"reynolds"``: Swift-Stieber rupture (``p >= 0``) by projected SOR
        (needs ``method="seidel"``). The flows then include the ruptured
        zone's non-conserved Couette flow in the outline cells next to it.
    operating, discretization : optional
        :class:`~bearingfe.core.parameters.OperatingPoint` (``wedge``, ``squeeze``,
        ``inlet_pressure``) and :class:`~bearingfe.core.parameters.Discretization`
        (``formulation``) instead of the keywords.

    Returns
    -------
    FDResult

    Raises
    ------
    ValueError
        Invalid inputs, a non-rectangular outline, or ``h <= 0`` on the grid.
    RuntimeError
        Seidel did not converge within ``max_iter`` sweeps, or the solution is
        not finite.

    Notes
    -----
    Flows use the dual cells of the node grid (``dphi x dz``, halved or
    quartered on the outline). The discrete flux through the face between
    neighbours is ``(-(h_f^3 / 12) dp / ds + wedge h_f / 2 [phi faces]) * l``
    with ``h_f`` at the face midpoint and ``l`` the face length. ``inlet`` is
    the net outflow of the pocket cells; the flow through the outline is
    taken from the conservation of each outline cell (outflow = -(net flux to
    its neighbours) - dh/dt * cell area). Corner cells give ``-wedge h / 2``
    times their arc-edge length to the arc edge (the exact flux there, since
    ``grad p = 0`` at a corner) and the rest to ``side``. ``squeeze`` sums
    ``dh/dt`` over all non-pocket cells (the staircase film). The ``balance``
    residual is then exactly the sum over unknown cells of the scheme's
    truncation of the flux balance: O(dphi^2) for the direct form (the wedge
    term uses the exact ``dh/dphi`` instead of the face difference), and
    the residual of the direct scheme applied to the Pi solution for "pi".
    """
    start = time.perf_counter()
    n_phi, n_z = _check_shape(shape)
    _check_choice(formulation, FORMULATIONS, "formulation")
    _check_choice(method, METHODS, "method")
    _check_choice(cavitation, ("none", "reynolds"), "cavitation")
    if cavitation == "reynolds" and method != "seidel":
        raise ValueError("cavitation='reynolds' is solved by projected SOR: use method='seidel'")
    tol, max_iter, omega_relax = _check_iteration(tol, max_iter, omega_relax)
    grid = _make_grid(surface, n_phi, n_z)
    rates = _check_rates(film, grid, squeeze)
    _check_film(film, grid)
    wedge, inlet_pressure = _finite(wedge, "wedge"), _finite(inlet_pressure, "inlet_pressure")
    check_operating_point(wedge, squeeze, inlet_pressure)

    if formulation == "pi" and not is_smooth(film):
        raise ValueError("formulation='pi' needs a smooth film (the film has a kink or a step, whose Laplacian "
                         "is no function): use formulation='direct', whose wedge term takes the step exactly")
    f = _rhs(film, grid, wedge, rates) if formulation == "pi" else _conservative_rhs(film, grid, wedge, rates)
    if formulation == "pi":
        stencil = _pi_stencil(film, grid, f, inlet_pressure)
    else:
        stencil = _direct_stencil(film, grid, f, inlet_pressure)
    if method == "direct":
        x, iterations = _solve_sparse(stencil, grid), 0
    else:
        x, iterations = _solve_seidel(stencil, grid, tol, max_iter, omega_relax,
                                      project=cavitation == "reynolds")
    if not np.all(np.isfinite(x)):
        raise RuntimeError("finite-difference solution is not finite (singular or indefinite system)")
    h = film.thickness(grid.PHI, grid.Z)
    p = x * h ** -1.5 if formulation == "pi" else x
    flows = _flows(film, grid, p, wedge, rates)
    integral, force = _integrals(grid, p)
    return FDResult(
        phi=grid.phi, z=grid.z, pressure=p, force=force, integral=integral,
        h_min=_h_min(film, surface, grid, h), flows=flows, iterations=iterations,
        formulation=formulation, method=method, seconds=time.perf_counter() - start)


# -- validation ----------------------------------------------------------------

def _check_shape(shape) -> tuple[int, int]:
    try:
        n_phi, n_z = shape
    except (TypeError, ValueError):
        raise ValueError(f"shape must be a pair (n_phi, n_z) of integers >= 3, got {shape!r}") from None
    for name, n in (("shape[0] (n_phi)", n_phi), ("shape[1] (n_z)", n_z)):
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 3:
            raise ValueError(f"{name} must be an integer >= 3, got {n!r}")
    return int(n_phi), int(n_z)


def _check_choice(value: str, allowed: tuple[str, ...], name: str) -> None:
    if value not in allowed:
        raise ValueError(f"unknown {name} {value!r}; allowed: {', '.join(repr(a) for a in allowed)}")


def _finite(value: float, name: str) -> float:
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a finite number, got {value!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"{name} must be a finite number, got {value!r}")
    return value


def _check_iteration(tol, max_iter, omega_relax) -> tuple[float, int, float]:
    tol = _finite(tol, "tol")
    if tol <= 0:
        raise ValueError(f"tol must be > 0, got {tol!r}")
    if isinstance(max_iter, bool) or not isinstance(max_iter, (int, np.integer)) or max_iter < 1:
        raise ValueError(f"max_iter must be an integer >= 1, got {max_iter!r}")
    omega_relax = _finite(omega_relax, "omega_relax")
    if not 0.0 < omega_relax < 2.0:
        raise ValueError(f"omega_relax must be in (0, 2), got {omega_relax!r}")
    return tol, int(max_iter), omega_relax


def _check_rates(film, grid: _Grid, squeeze) -> tuple[float, ...]:
    try:
        rates = tuple(_finite(r, "squeeze[i]") for r in squeeze)
    except TypeError:
        raise ValueError(f"squeeze must be a sequence of numbers, got {squeeze!r}") from None
    n = len(film.rate_shapes(grid.phi[:1], grid.z[:1]))
    if len(rates) != n:
        raise ValueError(f"squeeze needs {n} rates (one per film.rate_shapes), got {len(rates)}")
    return rates


def _make_grid(surface: Surface, n_phi: int, n_z: int) -> _Grid:
    if not isinstance(surface, Surface):
        raise ValueError(f"surface must be a bearingfe.Surface, got {type(surface).__name__}")
    if not surface.is_rectangular:
        raise ValueError("surface.outer must be None: the FD solver supports only the rectangular outline")
    if surface.recesses:
        raise ValueError("surface.recesses: the FD solver does not model recesses (film steps); solve with "
                         "solve_reynolds (finite volumes) instead")
    if surface.periodic:
        raise ValueError("surface.periodic: the FD solver does not model a periodic seam (its arc ends are held "
                         "at 0); solve with solve_reynolds (finite volumes) instead")
    try:
        check_limit("elements", n_phi * n_z)
    except LimitError as exc:
        raise LimitError(f"shape = ({n_phi}, {n_z}) of the FD grid: {exc}") from None
    (a1, a2), a = surface.arc, surface.half_width
    phi, z = np.linspace(a1, a2, n_phi), np.linspace(-a, a, n_z)
    pocket = surface.in_pocket(phi[None, :], z[:, None])
    fixed = pocket.copy()
    fixed[[0, -1], :] = True
    fixed[:, [0, -1]] = True
    return _Grid(phi, z, (a2 - a1) / (n_phi - 1), 2 * a / (n_z - 1), fixed, pocket)


def _check_film(film, grid: _Grid) -> None:
    """h > 0 at the nodes and at the half-points used by the direct scheme."""
    phi = np.concatenate([grid.phi, 0.5 * (grid.phi[1:] + grid.phi[:-1])])
    z = np.concatenate([grid.z, 0.5 * (grid.z[1:] + grid.z[:-1])])
    h = film.thickness(phi[None, :], z[:, None])
    h_min = float(np.min(h))
    if not (np.all(np.isfinite(h)) and h_min > 0):
        gamma = getattr(film, "gamma", None)
        what = f"gamma = {gamma!r} gives " if gamma is not None else ""
        raise ValueError(f"film thickness must be > 0 on the grid: {what}h_min = {h_min:.4g}")


# -- discretisation ------------------------------------------------------------

def _rhs(film, grid: _Grid, wedge: float, rates: tuple[float, ...]) -> np.ndarray:
    """``f = 6 wedge dh/dphi + 12 dh/dt`` at the nodes."""
    dh_dphi, _ = film.gradient(grid.PHI, grid.Z)
    return 6.0 * wedge * dh_dphi + 12.0 * _dh_dt(film, grid, rates)


def _conservative_rhs(film, grid: _Grid, wedge: float, rates: tuple[float, ...]) -> np.ndarray:
    """``f`` of the direct scheme with the wedge term as a difference of the film between the half-points,
    ``6 wedge (h(phi + dphi/2) - h(phi - dphi/2)) / dphi``: conservative, so a step of the film between two
    nodes enters with its full jump (the nodal ``dh/dphi`` would miss it). At the grid's ends the one-sided
    half-point is the node itself (those nodes hold fixed pressures anyway)."""
    hx, _ = _face_h(film, grid)
    h = film.thickness(grid.PHI, grid.Z) + 0.0 * grid.PHI
    east = np.concatenate([hx, h[:, -1:]], axis=1)
    west = np.concatenate([h[:, :1], hx], axis=1)
    step = np.full(grid.phi.shape, grid.dphi)
    step[0] = step[-1] = 0.5 * grid.dphi
    return 6.0 * wedge * (east - west) / step[None, :] + 12.0 * _dh_dt(film, grid, rates)


def _dh_dt(film, grid: _Grid, rates: tuple[float, ...]) -> np.ndarray:
    shapes = film.rate_shapes(grid.PHI, grid.Z)
    out = np.zeros(grid.fixed.shape)
    for rate, s in zip(rates, shapes):
        out = out + rate * np.broadcast_to(s, out.shape)
    return out


def _pi_stencil(film, grid: _Grid, f: np.ndarray, inlet_pressure: float) -> _Stencil:
    """Five-point Laplacian of Pi plus D on the diagonal (paper eq. 7)."""
    h = film.thickness(grid.PHI, grid.Z)
    gx, gz = film.gradient(grid.PHI, grid.Z)
    D = -(3.0 / (4.0 * h**2)) * (2.0 * h * film.laplacian(grid.PHI, grid.Z) + gx**2 + gz**2)
    ex, ez = 1.0 / grid.dphi**2, 1.0 / grid.dz**2
    ones = np.ones(grid.fixed.shape)
    x = np.where(grid.pocket, inlet_pressure * h**1.5, 0.0)
    return _Stencil(cP=D - 2 * (ex + ez), cE=ex * ones, cW=ex * ones, cN=ez * ones, cS=ez * ones,
                    b=h**-1.5 * f, x=x)


def _face_h(film, grid: _Grid) -> tuple[np.ndarray, np.ndarray]:
    """Film thickness at phi-face midpoints (n_z, n_phi-1) and z-face midpoints (n_z-1, n_phi)."""
    phi_m, z_m = 0.5 * (grid.phi[1:] + grid.phi[:-1]), 0.5 * (grid.z[1:] + grid.z[:-1])
    return film.thickness(phi_m[None, :], grid.z[:, None]), film.thickness(grid.phi[None, :], z_m[:, None])


def _direct_stencil(film, grid: _Grid, f: np.ndarray, inlet_pressure: float) -> _Stencil:
    """Conservative five-point ``div(h^3 grad p)`` with h^3 at the half-points."""
    hx, hz = _face_h(film, grid)
    kx, kz = hx**3 / grid.dphi**2, hz**3 / grid.dz**2
    shape = grid.fixed.shape
    cE, cW, cN, cS = (np.zeros(shape) for _ in range(4))
    cE[:, :-1], cW[:, 1:] = kx, kx
    cN[:-1, :], cS[1:, :] = kz, kz
    x = np.where(grid.pocket, inlet_pressure, 0.0)
    return _Stencil(cP=-(cE + cW + cN + cS), cE=cE, cW=cW, cN=cN, cS=cS, b=f, x=x)


# -- linear solvers ------------------------------------------------------------

def _solve_sparse(st: _Stencil, grid: _Grid) -> np.ndarray:
    """Assemble the unknown nodes only (fixed neighbours go to the right side) and LU-solve."""
    unknown = ~grid.fixed
    index = np.full(grid.fixed.shape, -1, dtype=np.int64)
    index[unknown] = np.arange(int(unknown.sum()))
    jj, ii = np.nonzero(unknown)
    rows, cols, vals = [index[jj, ii]], [index[jj, ii]], [st.cP[jj, ii]]
    rhs = st.b[jj, ii].copy()
    for coef, dj, di in ((st.cE, 0, 1), (st.cW, 0, -1), (st.cN, 1, 0), (st.cS, -1, 0)):
        c, nj, ni = coef[jj, ii], jj + dj, ii + di
        free = unknown[nj, ni]
        rows.append(index[jj, ii][free])
        cols.append(index[nj, ni][free])
        vals.append(c[free])
        rhs -= np.where(free, 0.0, c * st.x[nj, ni])
    n = rhs.size
    A = sp.csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
    x = st.x.copy()
    if n:
        x[jj, ii] = spla.spsolve(A, rhs)
    return x


def _solve_seidel(st: _Stencil, grid: _Grid, tol: float, max_iter: int, omega: float,
                  project: bool = False) -> tuple[np.ndarray, int]:
    """Red-black Gauss-Seidel (SOR for omega != 1) to the paper's relative-change rule;
    ``project``: Christopherson's projection ``x = max(x, 0)`` after each update."""
    x = st.x.copy()
    inner = (slice(1, -1), slice(1, -1))
    J, I = np.meshgrid(np.arange(x.shape[0]), np.arange(x.shape[1]), indexing="ij")
    unknown = ~grid.fixed[inner]
    colours = [unknown & ((J + I)[inner] % 2 == c) for c in (0, 1)]
    if not unknown.any():
        return x, 0
    inv = 1.0 / st.cP[inner]
    b, cE, cW, cN, cS = (a[inner] * inv for a in (st.b, st.cE, st.cW, st.cN, st.cS))
    change = math.inf
    for sweep in range(1, max_iter + 1):
        old = x[inner][unknown]
        for colour in colours:
            gs = b - cE * x[1:-1, 2:] - cW * x[1:-1, :-2] - cN * x[2:, 1:-1] - cS * x[:-2, 1:-1]
            x_in = x[inner]
            x_in[colour] += omega * (gs[colour] - x_in[colour])
            if project:
                x_in[colour] = np.maximum(x_in[colour], 0.0)
        new = x[inner][unknown]
        change = _relative_change(new, old)
        if change < tol:
            return x, sweep
        if not math.isfinite(change):
            break
    raise RuntimeError(
        f"Seidel iteration did not converge: max_iter = {max_iter} sweeps reached with relative "
        f"change {change:.3g} > tol = {tol:.3g}")


def _relative_change(new: np.ndarray, old: np.ndarray) -> float:
    """The paper's rule: sum |x_new - x_old| / sum |x_new| (0 when both are 0)."""
    num, den = float(np.abs(new - old).sum()), float(np.abs(new).sum())
    if den == 0.0:
        return 0.0 if num == 0.0 else math.inf
    return num / den


# -- outputs -------------------------------------------------------------------

def _weights(n: int, d: float) -> np.ndarray:
    """Trapezoid weights (= dual-cell lengths) of n nodes spaced d."""
    w = np.full(n, d)
    w[[0, -1]] = d / 2
    return w


def _integrals(grid: _Grid, p: np.ndarray) -> tuple[float, np.ndarray]:
    w = _weights(grid.z.size, grid.dz)[:, None] * _weights(grid.phi.size, grid.dphi)[None, :]
    wp = w * p
    force = np.array([np.sum(wp * np.cos(grid.phi)), np.sum(wp * np.sin(grid.phi))])
    return float(wp.sum()), force


def _h_min(film, surface: Surface, grid: _Grid, h: np.ndarray) -> float:
    """Exact minimum when the film knows it (z-independent films), else the grid minimum over film nodes."""
    exact = film.minimum(surface.arc) if hasattr(film, "minimum") else None
    return float(exact) if exact is not None else float(h[~grid.pocket].min())


def _net_outflow(film, grid: _Grid, p: np.ndarray, wedge: float) -> np.ndarray:
    """Net discrete outflow of every dual cell through its faces to neighbouring cells."""
    hx, hz = _face_h(film, grid)
    wz = _weights(grid.z.size, grid.dz)[:, None]
    wphi = _weights(grid.phi.size, grid.dphi)[None, :]
    fx = film_flux(hx, (np.diff(p, axis=1) / grid.dphi, 0.0), wedge)[0] * wz
    fz = film_flux(hz, (0.0, np.diff(p, axis=0) / grid.dz), 0.0)[1] * wphi
    out = np.zeros(p.shape)
    out[:, :-1] += fx
    out[:, 1:] -= fx
    out[:-1, :] += fz
    out[1:, :] -= fz
    return out


def _corner_arc_flows(film, grid: _Grid, wedge: float) -> np.ndarray:
    """Outflow of the four corner cells through their arc-edge halves, shape (2, 2).

    At a corner ``p = 0`` on both edges, so ``grad p = 0`` and the flux is the
    Couette part ``wedge h / 2 e_phi``: out of ``phi = alpha1`` it is
    ``-wedge h / 2`` per unit length, out of ``phi = alpha2`` ``+wedge h / 2``.
    """
    phi, z = grid.phi[[0, -1]][:, None], grid.z[[0, -1]][None, :]
    h = film.thickness(phi + 0 * z, z + 0 * phi)
    return np.array([[-1.0], [1.0]]) * 0.5 * wedge * h * grid.dz / 2


def _flows(film, grid: _Grid, p: np.ndarray, wedge: float, rates: tuple[float, ...]) -> dict:
    """Inlet, side and arc-edge flows from the conservative dual-cell fluxes."""
    area = _weights(grid.z.size, grid.dz)[:, None] * _weights(grid.phi.size, grid.dphi)[None, :]
    source = _dh_dt(film, grid, rates) * area
    net = _net_outflow(film, grid, p, wedge)
    edge = -net - source  # outflow of each outline cell through the outline
    corners = _corner_arc_flows(film, grid, wedge)  # (start, end) x (bottom, top)
    arc_start = float(edge[1:-1, 0].sum() + corners[0].sum())
    arc_end = float(edge[1:-1, -1].sum() + corners[1].sum())
    corner_total = float(edge[[0, -1, 0, -1], [0, 0, -1, -1]].sum())
    side = float(edge[[0, -1], 1:-1].sum()) + corner_total - float(corners.sum())
    inlet = float(net[grid.pocket].sum())
    squeeze = float(source[~grid.pocket].sum())
    return dict(side=side, arc_start=arc_start, arc_end=arc_end, inlet=inlet, squeeze=squeeze,
                balance=inlet - side - arc_start - arc_end - squeeze)
