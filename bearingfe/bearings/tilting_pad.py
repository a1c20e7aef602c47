r"""Tilting-pad journal bearings: equilibrium of the shaft and the pads, and Lund's pad-assembly reduction.

Coordinates and scales are those of :mod:`bearingfe.bearings.journal` with the pad
clearance ``C_p`` as the clearance ``c``: ``h = H/C_p``, ``p = P C_p^2/(mu omega R^2)``,
forces in ``mu omega R^4/C_p^2``. The bearing frame is ROSS's (``x`` horizontal,
``y`` vertical, the static load on the journal along ``-y``); the journal turns
towards ``+phi``.

Pad ``i`` (pivot angle ``theta_i``, arc ``(theta_i - f beta, theta_i + (1 - f) beta)``
with ``f`` the pivot offset and ``beta`` the arc) turns on a rocker pivot by ``delta_i``;
its film is

``h = 1 - m cos(phi - theta_i) - x cos(phi) - y sin(phi) - q_i sin(phi - theta_i)``

with ``m = 1 - C_b/C_p`` the preload and ``q_i = R_piv delta_i / C_p`` the pad
rotation as the film change it makes at a quarter turn from the pivot (the film
changes linearly with the rotation, first order). That is a journal at the
effective position ``(x, y) + m n_i + q_i t_i`` (``n_i = (cos theta_i, sin theta_i)``,
``t_i = (-sin theta_i, cos theta_i)``) in a bore of clearance ``C_p``, so every pad
film is solved and linearized by :func:`bearingfe.bearings.journal.position_state`
and :func:`~bearingfe.bearings.journal.force_derivatives` on the pad meshes of
:func:`~bearingfe.bearings.journal.journal_mesh`.

The generalized force of the pad rotation is ``Q_i = int p dh/dq_i = -F_i . t_i``
(``F_i`` the pad's film force on the pad): a pad with no moment about its pivot
carries its load through the pivot. The equilibrium solves ``sum F_i = W`` and
``F_i . t_i = 0`` for ``(x, y, q_1 .. q_n)``: Newton's method on the shaft
position with the linearized stiffness of the shaft with re-balanced pads
(``sum_i D_i - (D_i t_i)(t_i^T D_i)/(t_i^T D_i t_i)``, ``D_i = dF_i/dx'``), each
step first turning every loaded pad to zero moment by a bracketed Newton
iteration on its rotation (slope ``t_i^T D_i t_i``). A pad the shaft is no nearer
than the preload puts it (``x . n_i + m <= 0``) carries nothing: its film
diverges everywhere, its coefficients are zero. The pad's own friction moment
(a pivot below the pad surface) is neglected, as in Lund's and Someya's analyses.
The full coefficients are ``sum_i T_i^T D_i T_i`` (and the same of
``dF_i/dx'dot``) with ``T_i = dx'_i/du`` over ``u = (x, y, q_1 .. q_n)``.

Flexible pivots (radial stiffness ``k``): pad ``i`` also moves out along its
pivot line by ``xi_i``, so its effective position is ``x + (m - xi_i) n_i + q_i t_i``,
and ``k xi_i = F_i . n_i`` at equilibrium (Newton's steps on ``xi_i`` kept inside the
bracket ``[0, s_i)``, ``s_i = x . n_i + m``, around the moment balance); ``xi_i`` joins the
degrees of freedom (massless), the spring on its row. With the pivot offset from the pad's
middle the pad carries a finite load ``F(0+)`` by its tilt alone however little the shaft closes
its film, and none once it does not: a spring with ``k s_i < F(0+)`` pushes the pad out to that
edge, where it sits (``EDGE_GAP`` short of it) carrying the spring's ``k xi_i``; the shaft then
sees that pad's spring alone. So the equilibrium is found from a cold start on soft pivots too.

Dynamic coefficients over the shaft and pad degrees of freedom, and the 2x2
coefficients of the journal at whirl frequency ``Omega`` (Lund 1964): with the
impedance ``Z(nu) = K + i nu C - nu^2 M`` (``nu = Omega/omega``, ``M`` the pad
mass parameter on the pad rows), ``Z_red = Z_jj - Z_jp Z_pp^-1 Z_pj``,
``K(Omega) = Re Z_red``, ``C(Omega) = Im Z_red / nu``. The non-dimensional pad
mass is ``M = (I_p / R_piv^2) C_p^3 omega / (mu R^4)`` (:meth:`TiltingPadBearing.pad_mass`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import skfem

from ..geometry.meshing import SupportMesh, refine_uniformly
from ..geometry.surface import Surface
from .journal import (EQUILIBRIUM_CAVITATION, DynamicCoefficients, JournalBearing, force_derivatives,
                      journal_mesh, position_state)

__all__ = [
    "TiltingPadGeometry",
    "TiltingPadBearing",
    "TiltingPadEquilibrium",
    "PadAssemblyCoefficients",
    "TiltingPadConvergenceError",
    "TILTING_PAD_CAVITATION",
    "tilting_pad_meshes",
    "tilting_pad_equilibrium",
    "pad_assembly_coefficients",
    "reduced_coefficients",
    "ross_table",
    "ross_table_of",
]

#: Cavitation models of free (tilting) pads; locked pads take every model of
#: :data:`~bearingfe.bearings.journal.EQUILIBRIUM_CAVITATION`.
TILTING_PAD_CAVITATION = ("reynolds", "jfo")

#: Smallest film thickness [C_p] a Newton step may bring a pad to (it is cut back before).
H_FLOOR = 0.01


class TiltingPadConvergenceError(RuntimeError):
    """Newton's method found no equilibrium of the shaft and the pads."""


# -- parameters ---------------------------------------------------------------------------------

@dataclass(frozen=True)
class TiltingPadGeometry:
    """Non-dimensional geometry of a tilting-pad journal bearing (the solvers' currency).

    Parameters
    ----------
    length_ratio : float
        ``L/D`` [-], in (0, 4].
    n_pads : int
        Number of pads, 2 to 12.
    arc : float
        Angular extent of each pad [rad], ``n_pads * arc < 2 pi``.
    offset : float
        Pivot position from the leading edge as a fraction of the arc [-], in (0, 1) (0.5: centred);
        both pad edges within 90 degrees of the pivot.
    preload : float
        ``m = 1 - C_b/C_p`` [-], in [0, 1).
    load_on_pad : bool
        ``True``: a pivot on the ``-y`` axis (load on pad); ``False``: the ``-y`` axis half way between
        two pivots (load between pads).
    """

    length_ratio: float
    n_pads: int = 4
    arc: float = math.radians(80.0)
    offset: float = 0.5
    preload: float = 0.0
    load_on_pad: bool = False

    def __post_init__(self) -> None:
        if not (math.isfinite(self.length_ratio) and 0 < self.length_ratio <= 4):
            raise ValueError(f"length_ratio (L/D) must be in (0, 4], got {self.length_ratio!r}")
        if isinstance(self.n_pads, bool) or not isinstance(self.n_pads, (int, np.integer)) or not 2 <= self.n_pads <= 12:
            raise ValueError(f"n_pads must be an integer in [2, 12], got {self.n_pads!r}")
        if not (math.isfinite(self.arc) and 0 < self.arc and self.n_pads * self.arc < 2 * math.pi):
            raise ValueError(f"arc must be > 0 rad with n_pads * arc < 2 pi, got {self.arc!r}")
        if not (math.isfinite(self.offset) and 0 < self.offset < 1):
            raise ValueError(f"offset must be in (0, 1), got {self.offset!r}")
        if not max(self.offset, 1 - self.offset) * self.arc < math.pi / 2:
            raise ValueError("each pad edge must lie within 90 degrees of the pivot (offset x arc and "
                             f"(1 - offset) x arc < pi/2), got arc {self.arc!r} rad, offset {self.offset!r}")
        if not (math.isfinite(self.preload) and 0 <= self.preload < 1):
            raise ValueError(f"preload must be in [0, 1), got {self.preload!r}")
        if not isinstance(self.load_on_pad, bool):
            raise ValueError(f"load_on_pad must be True or False, got {self.load_on_pad!r}")
        object.__setattr__(self, "n_pads", int(self.n_pads))

    @property
    def pivots(self) -> np.ndarray:
        """Pivot angles [rad], shape (n_pads,), the first one at or after ``-pi/2``."""
        pitch = 2 * math.pi / self.n_pads
        first = -math.pi / 2 + (0.0 if self.load_on_pad else pitch / 2)
        return first + pitch * np.arange(self.n_pads)

    @property
    def arcs(self) -> tuple[tuple[float, float], ...]:
        """Pad arcs ``(leading edge, trailing edge)`` [rad] (the journal turns towards ``+phi``)."""
        return tuple((float(t - self.offset * self.arc), float(t + (1 - self.offset) * self.arc))
                     for t in self.pivots)

    @property
    def fixed_pads(self) -> JournalBearing:
        """The fixed-pad bearing of the same pad surfaces (the pads' meshes and film solves)."""
        return JournalBearing(self.length_ratio, pads=self.arcs)

    def normals(self) -> tuple[np.ndarray, np.ndarray]:
        """Unit vectors along (``n``) and across (``t``, towards ``+phi``) each pivot line, shape (n_pads, 2)."""
        th = self.pivots
        return np.column_stack([np.cos(th), np.sin(th)]), np.column_stack([-np.sin(th), np.cos(th)])


@dataclass(frozen=True)
class TiltingPadBearing:
    """A tilting-pad journal bearing in SI units.

    Parameters
    ----------
    radius : float
        Journal radius ``R`` [m].
    length : float
        Pad length ``L`` [m], ``L/D`` in (0, 4].
    pad_clearance : float
        Machined pad clearance ``C_p`` [m], ``< R/100``.
    n_pads, offset, preload, load_on_pad
        As :class:`TiltingPadGeometry`.
    arc : float
        Pad arc [rad].
    pad_inertia : float
        Moment of inertia of a pad about its pivot [kg m^2], >= 0.
    pad_thickness : float
        Radial distance from the pad surface to the rocker line [m], >= 0 (``R_piv = R + t``).
    pivot_stiffness : float
        Radial stiffness of each pivot [N/m], > 0 (``inf``: rigid).
    """

    radius: float
    length: float
    pad_clearance: float
    n_pads: int = 4
    arc: float = math.radians(80.0)
    offset: float = 0.5
    preload: float = 0.0
    load_on_pad: bool = False
    pad_inertia: float = 0.0
    pad_thickness: float = 0.0
    pivot_stiffness: float = math.inf

    def __post_init__(self) -> None:
        for name in ("radius", "length", "pad_clearance"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"{name} must be a finite number > 0 [m], got {v!r}")
        if not self.pad_clearance < self.radius / 100:
            raise ValueError(f"pad_clearance must be below radius/100 (a thin film), got {self.pad_clearance!r} m "
                             f"for radius {self.radius!r} m")
        for name in ("pad_inertia", "pad_thickness"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise ValueError(f"{name} must be a finite number >= 0, got {v!r}")
        if not (isinstance(self.pivot_stiffness, (int, float)) and self.pivot_stiffness > 0
                and not math.isnan(self.pivot_stiffness)):
            raise ValueError(f"pivot_stiffness must be > 0 [N/m] (inf: rigid), got {self.pivot_stiffness!r}")
        self.geometry  # checks the rest

    @property
    def geometry(self) -> TiltingPadGeometry:
        """The non-dimensional geometry."""
        return TiltingPadGeometry(self.length / (2 * self.radius), self.n_pads, self.arc, self.offset,
                                  self.preload, self.load_on_pad)

    def force_scale(self, viscosity: float, speed: float) -> float:
        """``mu omega R^4 / C_p^2`` [N] for ``mu`` [Pa s] and ``omega`` [rad/s]."""
        _check_positive(viscosity=viscosity, speed=speed)
        return viscosity * speed * self.radius**4 / self.pad_clearance**2

    def pivot_stiffness_parameter(self, viscosity: float, speed: float) -> float:
        """Non-dimensional pivot stiffness ``k C_p^3 / (mu omega R^4)`` [-] (``inf`` for rigid pivots)."""
        return self.pivot_stiffness * self.pad_clearance / self.force_scale(viscosity, speed)

    def pad_mass(self, viscosity: float, speed: float) -> float:
        """Non-dimensional pad mass ``(I_p/R_piv^2) C_p^3 omega / (mu R^4)`` [-]."""
        _check_positive(viscosity=viscosity, speed=speed)
        r_pivot = self.radius + self.pad_thickness
        return self.pad_inertia / r_pivot**2 * self.pad_clearance**3 * speed / (viscosity * self.radius**4)


def _check_positive(**values: float) -> None:
    for name, v in values.items():
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {v!r}")


# -- films -------------------------------------------------------------------------------------

def tilting_pad_meshes(geometry: TiltingPadGeometry, size: float, *, refine: int = 0) -> tuple[SupportMesh, ...]:
    """Meshes of the pads: one uniform mesh of a pad on the arc ``(0, arc)`` (element size ``size`` [-], by
    :func:`~bearingfe.bearings.journal.journal_mesh`, cached), split ``refine`` times
    (:func:`~bearingfe.geometry.meshing.refine_uniformly`: nested meshes for convergence studies), and
    turned to every pad: all pads, and every orientation of the bearing, share one discretization, so
    the discrete bearing keeps the bearing's symmetries."""
    if not (isinstance(size, (int, float)) and math.isfinite(size) and 0 < size <= 1):
        raise ValueError(f"size must be in (0, 1], got {size!r}")
    if isinstance(refine, bool) or not isinstance(refine, int) or not 0 <= refine <= 4:
        raise ValueError(f"refine must be an integer in [0, 4], got {refine!r}")
    pad = JournalBearing(geometry.length_ratio, pads=((0.0, geometry.arc),))
    (first,) = journal_mesh(pad, float(size), min_size=float(size))
    if refine:
        first = refine_uniformly(first, refine)
    out = []
    m = first.mesh
    for start, end in geometry.arcs:
        mesh = skfem.MeshTri1(m.p + np.array([[start], [0.0]]), m.t).with_boundaries(dict(m.boundaries))
        surface = Surface(arc=(start, end), half_width=geometry.length_ratio)
        out.append(SupportMesh(mesh=mesh, surface=surface, size=first.size, source=first.source))
    return tuple(out)


def _effective(geometry: TiltingPadGeometry, xy: np.ndarray, tilts: np.ndarray, velocity=None,
               tilt_rates=None) -> tuple[np.ndarray, np.ndarray]:
    """Effective journal positions (and velocities) of the pads, shape (n_pads, 2)."""
    n, t = geometry.normals()
    pos = np.asarray(xy, float)[None, :] + geometry.preload * n + np.asarray(tilts, float)[:, None] * t
    vel = np.zeros_like(pos)
    if velocity is not None:
        vel = np.asarray(velocity, float)[None, :] + np.asarray(tilt_rates, float)[:, None] * t
    return pos, vel


def _pad_h_min(arc: tuple[float, float], pos: np.ndarray) -> float:
    """Smallest ``1 - x' cos(phi) - y' sin(phi)`` over the arc."""
    a, b = arc
    angles = [a, b]
    peak = math.atan2(pos[1], pos[0])
    peak = a + (peak - a) % (2 * math.pi)
    if peak <= b:
        angles.append(peak)
    return float(min(1 - pos[0] * math.cos(p) - pos[1] * math.sin(p) for p in angles))


def _h_min(geometry: TiltingPadGeometry, xy, tilts) -> float:
    pos, _ = _effective(geometry, xy, tilts)
    return min(_pad_h_min(arc, p) for arc, p in zip(geometry.arcs, pos))


@dataclass(frozen=True, eq=False)
class _Pads:
    """Solutions of every pad at one shaft position and set of pad rotations."""

    states: tuple             # one journal state per pad (None for an idle pad)
    forces: np.ndarray        # (n, 2) film force on each pad
    kinds: np.ndarray         # (n,) ACTIVE, IDLE or CONCENTRIC
    deflections: np.ndarray   # (n,) outward pivot deflections [C_p]

    @property
    def idle(self) -> np.ndarray:
        """Pads that carry no load (idle or concentric)."""
        return self.kinds != ACTIVE


#: Kinds of pad: carrying load; unloaded (the shaft farther from the pivot than the preload puts it);
#: concentric (exactly at the preload's distance: a uniform film, no pressure, an empty rupture set).
ACTIVE, IDLE, CONCENTRIC = 0, 1, 2

#: ``|s_i|`` below this (``s_i = x . n_i + m`` [C_p]) makes a pad concentric.
CONCENTRIC_BAND = 1e-6


def _kinds(geometry: TiltingPadGeometry, xy, cavitation: str) -> np.ndarray:
    """The kind of each pad at shaft position ``xy``.

    With cavitation a pad whose pivot the shaft is no nearer than the preload puts it
    (``s_i = x . n_i + m < 0``) carries no load: it turns until its film diverges everywhere (its
    pressure vanishes as it turns) and its coefficients are zero. At ``s_i = 0`` the film of the
    aligned pad is uniform: no pressure and no rupture, so its coefficients are those of the full film
    (the load-on-pad bearing without preload has its two side pads there). Without cavitation every
    pad carries pressure."""
    if cavitation == "none":
        return np.full(geometry.n_pads, ACTIVE)
    n, _ = geometry.normals()
    s = n @ np.asarray(xy, float) + geometry.preload
    return np.where(s > CONCENTRIC_BAND, ACTIVE, np.where(s < -CONCENTRIC_BAND, IDLE, CONCENTRIC))


def _idle_tilts(geometry: TiltingPadGeometry, xy) -> tuple[np.ndarray, np.ndarray]:
    """Rotation of each pad at which its film stops converging at the trailing edge and diverges
    elsewhere, ``q* = s tan(gamma) - x . t`` (``gamma`` the pivot-to-trailing-edge angle), and its
    gradient in ``(x, y)``, shape (n_pads, 2): the limit an unloaded pad turns to."""
    n, t = geometry.normals()
    gamma = (1 - geometry.offset) * geometry.arc
    xy = np.asarray(xy, float)
    s = n @ xy + geometry.preload
    return s * math.tan(gamma) - t @ xy, math.tan(gamma) * n - t


def _pad_state(geometry: TiltingPadGeometry, mesh, i: int, xy, q: float, cavitation: str, element: str,
               warm=None, velocity=(0.0, 0.0), rate: float = 0.0):
    """Pad ``i``'s film with the shaft at ``xy`` moving at ``velocity`` and the pad at rotation ``q`` turning at
    ``rate`` (a journal at the pad's effective position)."""
    n, t = geometry.normals()
    pos = np.asarray(xy, float) + geometry.preload * n[i] + q * t[i]
    vel = np.asarray(velocity, float) + rate * t[i]
    return position_state(geometry.fixed_pads, (mesh,), pos[0], pos[1], cavitation, velocity=vel,
                          warm_start=warm, element=element)


def _pad_derivatives(geometry: TiltingPadGeometry, mesh, i: int, state, xy, q: float, cavitation: str,
                     element: str, damping: bool = True, step: float = 1e-6) -> tuple[np.ndarray, np.ndarray | None]:
    """``dF_i/dx'`` and ``dF_i/dx'dot`` of pad ``i`` (linearized; finite-volume films by central differences
    warm-started from ``state``; ``damping=False`` skips the second)."""
    if all(sup is not None for sup in state.sups):
        return force_derivatives(state)
    D, E = np.zeros((2, 2)), np.zeros((2, 2))

    def force(at, vel=(0.0, 0.0)):
        return _pad_state(geometry, mesh, i, np.asarray(xy, float) + at, q, cavitation, element, warm=state,
                          velocity=vel).force
    for j in range(2):
        d = np.zeros(2)
        d[j] = step
        D[:, j] = (force(d) - force(-d)) / (2 * step)
        if damping:
            E[:, j] = (force(np.zeros(2), d) - force(np.zeros(2), -d)) / (2 * step)
    return D, (E if damping else None)


# -- equilibrium --------------------------------------------------------------------------------

@dataclass(frozen=True)
class TiltingPadEquilibrium:
    """Static equilibrium of the shaft and the pads under a load.

    Attributes
    ----------
    eps : float
        Shaft eccentricity ``e/C_p`` [-].
    attitude : float
        Angle from the load line to the line of centres [deg].
    position : ndarray, shape (2,)
        Shaft centre [C_p], bearing frame.
    tilts : ndarray, shape (n_pads,)
        Pad rotations ``q_i = R_piv delta_i / C_p`` [-] (positive: towards ``+phi``).
    force : ndarray, shape (2,)
        Film force on the pads (= the applied load on the journal) [mu omega R^4/C_p^2].
    pad_forces : ndarray, shape (n_pads, 2)
        Film force on each pad.
    idle : ndarray of bool, shape (n_pads,)
        Unloaded pads (the shaft no nearer their pivot than the preload puts it): no pressure, turned
        to where their film stops converging, zero coefficients.
    newton_iterations : int
        Newton steps of the shaft (each turns every loaded pad to zero moment first).
    residual : float
        Force imbalance over ``|load|`` (each pad's moment is balanced to a tenth of ``tol`` of its force).
    locked : bool
        Pads held at their given rotations (a fixed-pad bearing).
    deflections : ndarray, shape (n_pads,)
        Outward deflection of each pivot [C_p] (zero on rigid pivots).
    pivot_stiffness : float
        Of the equilibrium [-] (``inf``: rigid).
    """

    eps: float
    attitude: float
    position: np.ndarray
    tilts: np.ndarray
    force: np.ndarray
    pad_forces: np.ndarray
    idle: np.ndarray
    newton_iterations: int
    residual: float
    locked: bool = False
    deflections: np.ndarray | None = None
    pivot_stiffness: float = math.inf
    geometry: TiltingPadGeometry | None = field(repr=False, compare=False, default=None)
    meshes: tuple = field(repr=False, compare=False, default=())
    cavitation: str = "reynolds"
    element: str = "P1"
    pads: _Pads | None = field(repr=False, compare=False, default=None)

    @property
    def sommerfeld(self) -> float:
        """``S = (R/C_p)^2 mu N L D / W`` [-]."""
        return 2 * self.geometry.length_ratio / (math.pi * float(np.hypot(*self.force)))


def _aligned(geometry: TiltingPadGeometry, xy) -> np.ndarray:
    """Pad rotations that keep each pad concentric with the shaft's tangential motion (``x' . t = 0``)."""
    _, t = geometry.normals()
    return -(t @ np.asarray(xy, float))


def _balance_pad(geometry: TiltingPadGeometry, mesh, i: int, xy, q0: float, w: float, cavitation: str,
                 element: str, warm, tol: float, max_steps: int = 60):
    """Rotation of loaded pad ``i`` at which its moment about the pivot vanishes: ``(q, state, dF/dx')``;
    the moment (as a force at the pad surface) to ``tol`` of the pad's force.

    The pad's moment ``r(q) = F_i . t_i`` is zero on the unloaded range (rotations at which its film
    diverges everywhere, up to ``q_lo``), negative just above it (pressure near the trailing edge turns
    the pad further) and positive once the pad carries its load ahead of the pivot: the loaded
    rotation is the root where ``r`` changes from negative to positive. Newton's steps on ``r`` (slope
    ``t_i . D t_i`` from the linearization) are kept inside the bracket of that change, bisected when
    they leave it; rotations that close the film count as ``r > 0``.
    """
    n, t = geometry.normals()
    xy = np.asarray(xy, float)
    s = float(n[i] @ xy) + geometry.preload
    lead = geometry.offset * geometry.arc
    lo = -float(t[i] @ xy) - s * math.tan(lead) if lead < math.pi / 2 else -math.inf
    hi = math.inf
    q = q0 if q0 > lo else -float(t[i] @ xy)  # aligned lies above the unloaded range
    jump = 0.05
    for _ in range(max_steps):
        pos = xy + geometry.preload * n[i] + q * t[i]
        if _pad_h_min(geometry.arcs[i], pos) <= H_FLOOR:
            hi, r, d = q, 1.0, math.nan
        else:
            state = _pad_state(geometry, mesh, i, xy, q, cavitation, element, warm=warm)
            warm = state
            D, _ = _pad_derivatives(geometry, mesh, i, state, xy, q, cavitation, element, damping=False)
            r, d = float(state.force @ t[i]) / w, float(t[i] @ D @ t[i]) / w
            # relative to the pad's own force: near the unloaded range force and moment vanish together
            if abs(r) <= tol * float(np.hypot(*state.force)) / w or abs(r) <= 1e-2 * tol:
                return q, state, D
            if r > 0:
                hi = q
            else:
                lo = q
        new = q - r / d if d > 0 else math.nan
        if not lo < new < hi:
            if math.isfinite(lo) and math.isfinite(hi):
                new = 0.5 * (lo + hi)
            else:
                new = q + (jump if r < 0 else -jump)
                jump *= 2
        if hi - lo <= 1e-13 * max(1.0, abs(q)):
            break
        q = new
    raise TiltingPadConvergenceError(
        f"tilting-pad equilibrium: no rotation of pad {i} balances its moment about the pivot "
        f"(shaft at {xy.round(6).tolist()}, moment {r:.3g} of the load)")


#: Film left at a pad pushed out to the edge of its loaded range: ``x'' . n + m`` [C_p] (see _balance_pivot).
EDGE_GAP = 1e-7


def _balance_pivot(geometry: TiltingPadGeometry, mesh, i: int, xy, q0: float, w: float, cavitation: str,
                   element: str, warm, tol: float, k: float, xi0: float | None):
    """Loaded pad ``i`` on a pivot spring ``k``: the outward deflection ``xi`` at which the spring carries
    the film's radial force, with the pad balanced about its pivot. Returns ``(xi, q, state, D, force)``.

    The pad sees the shaft at ``xy - xi n``, nearer its pivot than the preload puts it by
    ``s = s0 - xi`` (``s0 = n . xy + m > 0``); its radial force ``F(s)`` rises with ``s`` and the spring's
    ``k xi`` with ``xi``, so ``g(xi) = F(s0 - xi) - k xi`` falls on ``[0, s0)`` and has at most one
    root there. Newton's steps on ``g`` (slope ``-(n K n + k)``, ``K`` the pad's condensed stiffness)
    are kept inside the bracket of its change of sign and bisected when they leave it: no cap on the
    deflection, no step that jumps past the pad's unloaded range.

    ``F`` does not vanish as ``s -> 0+`` on a pad with an offset pivot: the pad carries a load ``F(0+)``
    by its tilt alone, and drops it at ``s = 0``, where it is counted unloaded. A spring with
    ``k s0 < F(0+)`` therefore pushes the pad out to that edge (``g`` stays positive on ``[0, s0)``):
    the pad sits at ``s = EDGE_GAP`` carrying the spring's ``k xi``, the film's force scaled down to it
    (``force`` differs from ``state.force`` then), and the shaft sees the spring alone.
    """
    n, t = geometry.normals()
    xy = np.asarray(xy, float)
    s0 = float(n[i] @ xy) + geometry.preload
    edge = s0 - min(EDGE_GAP, 0.5 * s0)
    lo, hi = 0.0, edge  # g(lo) >= 0 (the film pushes, the spring is slack); g(hi) not known yet
    edge_checked = False
    xi = 0.0 if xi0 is None or not math.isfinite(xi0) else min(max(xi0, 0.0), edge)
    q, state = q0, warm
    for _ in range(80):
        q, state, D = _balance_pad(geometry, mesh, i, xy - xi * n[i], q, w, cavitation, element, state, tol)
        K = _condensed(D, t[i], n[i], k, deflected=False)
        radial = float(state.force @ n[i])
        excess = radial - k * xi
        if abs(excess) <= tol * float(np.hypot(*state.force)) or abs(excess) <= 1e-2 * tol * w:
            return xi, q, state, D, state.force
        if excess > 0:
            lo = xi
            if xi == edge:  # the film pushes harder than the spring right up to the unloaded edge
                return xi, q, state, D, state.force * (k * xi / radial)
        else:
            hi = xi
            edge_checked = True
        new = xi + excess / (float(n[i] @ K @ n[i]) + k)
        if not lo < new < hi:
            new = edge if not edge_checked and new >= hi else 0.5 * (lo + hi)
            edge_checked = edge_checked or new == edge
        if hi - lo <= 1e-14 * max(1.0, s0):
            break
        xi = new
    raise TiltingPadConvergenceError(f"tilting-pad equilibrium: the pivot of pad {i} found no deflection "
                                     f"that carries its film force (imbalance {excess:.3g})")


def _balance(geometry: TiltingPadGeometry, meshes, xy, tilts, w: float, cavitation: str, element: str,
             warm: "_Pads | None", tol: float, locked: bool, pivot_stiffness: float = math.inf
             ) -> tuple[_Pads, np.ndarray, list]:
    """Every pad at shaft position ``xy``: loaded pads turned to zero moment (locked: held) and, on
    flexible pivots, pushed out until the pivot spring carries the film's radial force; unloaded ones
    where their film stops converging, concentric ones aligned. Returns the pads, their rotations and
    each pad's condensed shaft stiffness (None for pads without load)."""
    n, t = geometry.normals()
    xy = np.asarray(xy, float)
    tilts = np.array(tilts, float)
    deflections = np.zeros(geometry.n_pads)
    kinds = np.full(geometry.n_pads, ACTIVE) if locked else _kinds(geometry, xy, cavitation)
    free, _ = _idle_tilts(geometry, xy)
    states, forces, stiffness = [], np.zeros((geometry.n_pads, 2)), []
    for i, mesh in enumerate(meshes):
        if kinds[i] != ACTIVE:
            tilts[i] = free[i]  # the same as aligned when concentric
            # a concentric pad: the uniform film, linearized on its empty rupture set
            states.append(None if kinds[i] == IDLE else position_state(geometry.fixed_pads, (mesh,), 0.0, 0.0,
                                                                      "none", element=element))
            stiffness.append(None)
            continue
        start = warm.states[i] if warm is not None and warm.kinds[i] == ACTIVE else None
        if locked:
            state = _pad_state(geometry, mesh, i, xy, tilts[i], cavitation, element, warm=start)
            D, _ = _pad_derivatives(geometry, mesh, i, state, xy, tilts[i], cavitation, element, damping=False)
            stiffness.append(D)
        else:
            if math.isfinite(pivot_stiffness):
                xi, tilts[i], state, D, force = _balance_pivot(geometry, mesh, i, xy, tilts[i], w, cavitation, element,
                                                               start, tol, pivot_stiffness,
                                                               None if warm is None else float(warm.deflections[i]))
            else:
                xi = 0.0
                tilts[i], state, D = _balance_pad(geometry, mesh, i, xy, tilts[i], w, cavitation, element, start, tol)
                force = state.force
            deflections[i] = xi
            stiffness.append(_condensed(D, t[i], n[i], pivot_stiffness, deflected=True) if force is state.force
                             else pivot_stiffness * np.outer(force / float(force @ n[i]), n[i]))
            forces[i] = force
        states.append(state)
        if locked:
            forces[i] = state.force
    return _Pads(states=tuple(states), forces=forces, kinds=kinds, deflections=deflections), tilts, stiffness


def _condensed(D: np.ndarray, t: np.ndarray, n: np.ndarray, pivot_stiffness: float, deflected: bool) -> np.ndarray:
    """A loaded pad's stiffness seen by the shaft: ``D = dF/dx'`` with the pad re-balanced about its pivot
    (``D - (D t)(t^T D)/(t^T D t)``) and, ``deflected`` on a pivot spring ``k``, in series with it along
    the pivot line (``K - (K n)(n^T K)/(n^T K n + k)``)."""
    K = D.copy()
    d = float(t @ D @ t)
    if abs(d) > 1e-12 * float(np.abs(D).max()):
        K = K - np.outer(D @ t, t @ D) / d
    if deflected and math.isfinite(pivot_stiffness):
        K = K - np.outer(K @ n, n @ K) / (float(n @ K @ n) + pivot_stiffness)
    return K


def _shaft_stiffness(stiffness: list) -> np.ndarray:
    """``dW/dx`` of the shaft: the sum of the pads' condensed stiffnesses (locked pads: their ``D``)."""
    return sum((K for K in stiffness if K is not None), np.zeros((2, 2)))


def tilting_pad_equilibrium(geometry: TiltingPadGeometry, load, *, size: float = 0.05,
                            cavitation: str = "reynolds", element: str = "P1", tol: float = 1e-8,
                            max_newton: int = 60, start: TiltingPadEquilibrium | None = None,
                            locked_tilts=None, meshes=None, pivot_stiffness: float = math.inf
                            ) -> TiltingPadEquilibrium:
    """Shaft position and pad rotations that carry a load, by Newton's method.

    Parameters
    ----------
    geometry : TiltingPadGeometry
    load : (float, float)
        Applied load on the journal, bearing frame [mu omega R^4/C_p^2].
    size : float
        Element size of the pad meshes [-] (:func:`tilting_pad_meshes`).
    cavitation : {"reynolds", "jfo"}
        Film model of every pad: Swift-Stieber, or mass-conserving (finite volumes, derivatives by
        central differences); locked pads also take ``"none"``.
    element : {"P1", "P2"}
    tol : float
        On the force imbalance over ``|load|``; each pad's moment about its pivot (as a force at the pad's
        surface) to ``tol / 10`` of the pad's force.
    max_newton : int
    start : TiltingPadEquilibrium, optional
        Warm start: its position, rotations and rupture sets (another load or speed of the same
        bearing and meshes). Cold start otherwise: the shaft at ``eps = 0.5`` along the load, each pad
        aligned with it.
    locked_tilts : sequence of float, optional
        Hold the pads at these rotations and balance the force only (a fixed-pad bearing;
        all zeros with no preload is :class:`~bearingfe.bearings.journal.JournalBearing` with ``pads=arcs``).
    meshes : tuple of SupportMesh, optional
        The pad meshes (default :func:`tilting_pad_meshes` at ``size``).
    pivot_stiffness : float
        Radial stiffness of every pivot, ``k C_p^3 / (mu omega R^4)`` [-]
        (:meth:`TiltingPadBearing.pivot_stiffness_parameter`), > 0; ``inf``: rigid pivots. A flexible
        pivot lets its pad move out along the pivot line until the spring carries the film's radial force.

    Raises
    ------
    TiltingPadConvergenceError
        If Newton does not reach ``tol`` in ``max_newton`` steps, or its steps cannot lower the imbalance.
    """
    load = np.asarray(load, float)
    if load.shape != (2,) or not np.all(np.isfinite(load)) or not np.hypot(*load) > 0:
        raise ValueError(f"load must be a finite non-zero pair, got {load!r}")
    locked = locked_tilts is not None
    allowed = EQUILIBRIUM_CAVITATION if locked else TILTING_PAD_CAVITATION
    if cavitation not in allowed:
        raise ValueError(f"cavitation must be one of {allowed} (without cavitation an unloaded pad's film "
                         f"pulls it shut: it has no moment balance), got {cavitation!r}")
    if not (0 < tol < 1e-2):
        raise ValueError(f"tol must be in (0, 1e-2), got {tol!r}")
    if not (isinstance(pivot_stiffness, (int, float)) and pivot_stiffness > 0 and not math.isnan(pivot_stiffness)):
        raise ValueError(f"pivot_stiffness must be > 0 (inf: rigid), got {pivot_stiffness!r}")
    if locked_tilts is not None and math.isfinite(pivot_stiffness):
        raise ValueError("locked pads have no pivot to deflect: give pivot_stiffness=inf")
    meshes = tilting_pad_meshes(geometry, size) if meshes is None else tuple(meshes)
    if len(meshes) != geometry.n_pads:
        raise ValueError(f"need one mesh per pad ({geometry.n_pads}), got {len(meshes)}")
    w = float(np.hypot(*load))
    if start is not None:
        xy, tilts, warm = np.array(start.position, float), np.array(start.tilts, float), start.pads
    else:
        xy, warm = 0.5 * load / w, None
        tilts = _aligned(geometry, xy)
    if locked:
        tilts = np.asarray(locked_tilts, float)
        if tilts.shape != (geometry.n_pads,) or not np.all(np.isfinite(tilts)):
            raise ValueError(f"locked_tilts must be {geometry.n_pads} finite numbers, got {locked_tilts!r}")
        if start is None and not _h_min(geometry, xy, tilts) > H_FLOOR:
            xy = np.zeros(2)
    def state_at(at, rotations, previous):
        pads, rotations, derivatives = _balance(geometry, meshes, at, rotations, w, cavitation, element, previous,
                                                0.1 * tol, locked, pivot_stiffness)
        return pads, rotations, derivatives, float(np.max(np.abs(pads.forces.sum(axis=0) - load))) / w

    def open_films(at, rotations) -> bool:
        if locked:
            return _h_min(geometry, at, rotations) > H_FLOOR
        n, _ = geometry.normals()
        return float(np.max(n @ at)) + geometry.preload < 1 - H_FLOOR

    if not open_films(xy, tilts):
        raise ValueError("the start puts a pad on the shaft: start from another equilibrium")
    pads, tilts, derivatives, res = state_at(xy, tilts, warm)
    for k in range(max_newton + 1):
        if res <= tol:
            return _result(geometry, meshes, pads, xy, tilts, load, k, res, locked, cavitation, element,
                           pivot_stiffness)
        if k == max_newton:
            break
        K = _shaft_stiffness(derivatives) / w
        R = (pads.forces.sum(axis=0) - load) / w
        step = -np.linalg.lstsq(K, R, rcond=1e-12)[0]
        # at most 0.3 C_p per step, halved until every film stays open and the imbalance falls
        t_step = min(1.0, 0.3 / max(float(np.hypot(*step)), 1e-300))
        for _ in range(30):
            new_xy = xy + t_step * step
            if open_films(new_xy, tilts):
                new = state_at(new_xy, tilts, pads)
                if new[3] < res or t_step < 1e-3:
                    break
            t_step *= 0.5
        else:
            raise TiltingPadConvergenceError(
                f"tilting-pad equilibrium: no Newton step keeps the films open (imbalance {res:.3g} of the load); "
                "the load may be beyond what the pads carry")
        xy = new_xy
        pads, tilts, derivatives, res = new
    raise TiltingPadConvergenceError(
        f"tilting-pad equilibrium: Newton did not converge in {max_newton} steps (force imbalance {res:.3g} "
        f"of the load)")


def _result(geometry, meshes, pads: _Pads, xy, tilts, load, k, res, locked, cavitation, element, pivot_stiffness):
    F = pads.forces.sum(axis=0)
    theta_load = math.atan2(load[1], load[0])
    att = (math.atan2(xy[1], xy[0]) - theta_load + math.pi) % (2 * math.pi) - math.pi
    return TiltingPadEquilibrium(eps=float(np.hypot(*xy)), attitude=math.degrees(abs(att)), position=np.array(xy),
                                 tilts=np.array(tilts), force=F, pad_forces=pads.forces.copy(),
                                 idle=pads.idle.copy(), newton_iterations=k, residual=res, locked=locked,
                                 deflections=pads.deflections.copy(), pivot_stiffness=float(pivot_stiffness),
                                 geometry=geometry, meshes=tuple(meshes), cavitation=cavitation, element=element,
                                 pads=pads)


# -- coefficients -----------------------------------------------------------------------------

@dataclass(frozen=True)
class PadAssemblyCoefficients:
    """Stiffness and damping over the shaft and pad degrees of freedom at an equilibrium.

    The degrees of freedom are ``(x, y, q_1, .., q_n)`` [C_p] and, on flexible pivots, the outward pivot
    deflections ``(xi_1, .., xi_n)``; ``K = -d f/d u`` and ``C = -d f/d udot`` with ``f`` the film's
    generalized forces on the shaft and on the pads (and the pivot springs on their rows).

    Attributes
    ----------
    K, C : ndarray, shape (n_pads + 2, n_pads + 2) or (2 n_pads + 2, 2 n_pads + 2)
        Non-dimensional ``K C_p / W`` and ``C C_p omega / W``.
    load : float
        ``|W|`` [mu omega R^4 / C_p^2].
    eps, attitude : float
        Of the equilibrium [-], [deg].
    active : ndarray of bool, shape (n_pads,)
        Pads with coefficients (unloaded pads have zero rows and drop out of the reduction; concentric
        pads stay in).
    pivots : bool
        Whether the pivot deflections are degrees of freedom (flexible pivots).
    """

    K: np.ndarray
    C: np.ndarray
    load: float
    eps: float
    attitude: float
    active: np.ndarray
    pivots: bool = False

    def system(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``K``, ``C`` of the shaft and the active pads' freedoms, and which of those are pad rotations
        (the rows that carry the pads' inertia)."""
        active = np.asarray(self.active, bool)
        keep = np.concatenate([[True, True], active, active if self.pivots else []]).astype(bool)
        rotations = np.concatenate([[False, False], np.ones(active.size, bool),
                                    np.zeros(active.size if self.pivots else 0, bool)])
        return self.K[np.ix_(keep, keep)], self.C[np.ix_(keep, keep)], rotations[keep]

    def reduced(self, frequency_ratio: float = 1.0, pad_mass: float = 0.0) -> DynamicCoefficients:
        """The journal's 2x2 ``K(Omega)``, ``C(Omega)`` by the pad-assembly reduction (see :func:`reduced_coefficients`)."""
        return reduced_coefficients(self, frequency_ratio, pad_mass)

    def locked(self) -> DynamicCoefficients:
        """The pads held still (infinite pad inertia): the shaft block of ``K`` and ``C``."""
        return DynamicCoefficients(K=self.K[:2, :2].copy(), C=self.C[:2, :2].copy(), load=self.load, eps=self.eps,
                                   attitude=self.attitude, method="tilting-pad, pads locked")


def pad_assembly_coefficients(eq: TiltingPadEquilibrium) -> PadAssemblyCoefficients:
    """The full coefficients over the shaft and pad degrees of freedom at an equilibrium.

    ``K = sum_i T_i^T (dF_i/dx') T_i`` and ``C = sum_i T_i^T (dF_i/dx'dot) T_i`` with ``T_i`` the map
    from ``(x, y, q_1..q_n[, xi_1..xi_n])`` to pad ``i``'s effective journal position
    ``x'_i = x + (m - xi_i) n_i + q_i t_i``, plus the pivot stiffness on the ``xi`` rows; the pad
    derivatives are linearized on each pad's rupture set (``"jfo"``: central differences).
    """
    geometry = eq.geometry
    if geometry is None or eq.pads is None:
        raise ValueError("the equilibrium carries no solution (build it with tilting_pad_equilibrium())")
    n_pads = geometry.n_pads
    normal, t = geometry.normals()
    pivots = math.isfinite(eq.pivot_stiffness)
    n = n_pads + 2 + (n_pads if pivots else 0)
    K, C = np.zeros((n, n)), np.zeros((n, n))
    deflections = np.zeros(n_pads) if eq.deflections is None else eq.deflections
    for i in range(n_pads):
        if eq.pads.kinds[i] == IDLE:
            continue
        state = eq.pads.states[i]
        D, E = _pad_derivatives(geometry, eq.meshes[i], i, state, eq.position - deflections[i] * normal[i],
                                eq.tilts[i], eq.cavitation if eq.pads.kinds[i] == ACTIVE else "none", eq.element)
        T = np.zeros((2, n))
        T[:, :2] = np.eye(2)
        T[:, 2 + i] = t[i]
        if pivots:
            T[:, 2 + n_pads + i] = -normal[i]
            K[2 + n_pads + i, 2 + n_pads + i] += eq.pivot_stiffness
        K += T.T @ D @ T
        C += T.T @ E @ T
    w = float(np.hypot(*eq.force))
    diagonal = np.abs(np.diag(K)[2:2 + n_pads]) + np.abs(np.diag(C)[2:2 + n_pads])
    active = (eq.pads.kinds != IDLE) & (diagonal > 1e-12 * max(float(np.abs(K[:2, :2]).max()), 1e-300))
    return PadAssemblyCoefficients(K=K / w, C=C / w, load=w, eps=eq.eps, attitude=eq.attitude, active=active,
                                   pivots=pivots)


def reduced_coefficients(full: PadAssemblyCoefficients, frequency_ratio: float = 1.0,
                         pad_mass: float = 0.0) -> DynamicCoefficients:
    """The journal's 2x2 stiffness and damping at whirl frequency ``Omega`` (Lund's pad-assembly reduction).

    ``Z(nu) = K + i nu C - nu^2 M`` over ``(x, y, q_1..q_n[, xi_1..xi_n])``, ``M`` the pad mass on the
    rotation rows (the pivot deflections are massless);
    ``Z_red = Z_jj - Z_jp Z_pp^-1 Z_pj``, ``K(Omega) = Re Z_red``, ``C(Omega) = Im Z_red / nu`` (at
    ``nu = 0`` its limit, the derivative of ``Im Z_red``).

    Parameters
    ----------
    full : PadAssemblyCoefficients
    frequency_ratio : float
        ``nu = Omega/omega`` [-], >= 0 (1: synchronous whirl).
    pad_mass : float
        Non-dimensional pad mass ``M`` of every pad, :meth:`TiltingPadBearing.pad_mass` [-], >= 0
        (divided here by the load, as ``K`` and ``C`` are).
    """
    nu = float(frequency_ratio)
    if not (math.isfinite(nu) and nu >= 0):
        raise ValueError(f"frequency_ratio must be >= 0, got {frequency_ratio!r}")
    if not (math.isfinite(pad_mass) and pad_mass >= 0):
        raise ValueError(f"pad_mass must be >= 0, got {pad_mass!r}")
    K, C, rotations = full.system()
    j, p = slice(0, 2), slice(2, K.shape[0])
    if nu == 0:
        if K.shape[0] > 2 and not np.linalg.cond(K[p, p]) < 1e12:
            raise ValueError("a pad has no tilt stiffness (a concentric pad without pressure): the static "
                             "reduction is undefined; use frequency_ratio > 0")
        Kpp_inv_Kpj = np.linalg.solve(K[p, p], K[p, j]) if K.shape[0] > 2 else np.zeros((0, 2))
        Kred = K[j, j] - K[j, p] @ Kpp_inv_Kpj
        X = np.linalg.solve(K[p, p], C[p, j]) if K.shape[0] > 2 else np.zeros((0, 2))
        Y = np.linalg.solve(K[p, p].T, K[j, p].T).T if K.shape[0] > 2 else np.zeros((2, 0))
        Cred = C[j, j] - C[j, p] @ Kpp_inv_Kpj - K[j, p] @ X + Y @ C[p, p] @ Kpp_inv_Kpj
        method = "tilting-pad reduction, Omega = 0"
    else:
        Z = K + 1j * nu * C
        Z[p, p] -= nu**2 * pad_mass / full.load * np.diag(rotations[2:].astype(float))
        Zred = Z[j, j] - Z[j, p] @ np.linalg.solve(Z[p, p], Z[p, j]) if K.shape[0] > 2 else Z[j, j]
        Kred, Cred = Zred.real, Zred.imag / nu
        method = f"tilting-pad reduction, Omega/omega = {nu:g}"
    return DynamicCoefficients(K=np.array(Kred), C=np.array(Cred), load=full.load, eps=full.eps,
                               attitude=full.attitude, method=method)


# -- coefficient tables ---------------------------------------------------------------------------

def ross_table(bearing: TiltingPadBearing, load: float, viscosity: float, speeds, frequencies, *,
               size: float = 0.05, cavitation: str = "reynolds", element: str = "P1") -> dict:
    """Reduced coefficients over (rotor speed, whirl frequency), ROSS ``BearingElement`` keywords per speed.

    At each speed the equilibrium under the load (warm-started from the previous speed, on the bearing's
    pivots) gives the full coefficients, reduced at every whirl frequency with the pads' mass at that
    speed (:meth:`TiltingPadBearing.pad_mass`).

    Parameters
    ----------
    bearing : TiltingPadBearing
    load : float
        Static load on the journal [N], > 0, along ``-y`` (gravity).
    viscosity : float
        [Pa s], > 0.
    speeds, frequencies : sequence of float
        Rotor speeds and whirl frequencies [rad/s], > 0, increasing.
    size, cavitation, element
        As :func:`tilting_pad_equilibrium`.

    Returns
    -------
    dict
        ``speed`` and ``frequency`` (lists [rad/s]), and ``kxx, kxy, kyx, kyy`` [N/m], ``cxx, cxy, cyx, cyy``
        [N s/m] as nested lists of shape ``(len(speed), len(frequency))``: row ``i`` with ``frequency`` is
        the bearing at ``speed[i]``, ``ross.BearingElement(n=..., frequency=frequency, kxx=kxx[i], ...)``
        (ROSS up to 2.4 takes coefficients over frequency only; ROSS 3.x the whole table,
        ``BearingElement(n=..., speed=speed, frequency=frequency, kxx=kxx, ...)``; it is not imported).
        Files in ROSS's own format: one per speed, :func:`bearingfe.io.writers.write_ross_bearings`
        (ROSS 2.x); the 2-D table in one file, :func:`bearingfe.io.writers.write_ross3_bearing` (ROSS 3.x).
    """
    _check_positive(load=load, viscosity=viscosity)
    speeds, frequencies = np.asarray(speeds, float), np.asarray(frequencies, float)
    for name, v in (("speeds", speeds), ("frequencies", frequencies)):
        if v.ndim != 1 or not v.size or not np.all(np.isfinite(v) & (v > 0)) or not np.all(np.diff(v) > 0):
            raise ValueError(f"{name} must be positive, finite and increasing, got {v!r}")
    geometry = bearing.geometry
    meshes = tilting_pad_meshes(geometry, size)
    eq = None

    def full_at(speed):
        nonlocal eq
        eq = tilting_pad_equilibrium(geometry, (0.0, -load / bearing.force_scale(viscosity, speed)), meshes=meshes,
                                     start=eq, cavitation=cavitation, element=element,
                                     pivot_stiffness=bearing.pivot_stiffness_parameter(viscosity, speed))
        return pad_assembly_coefficients(eq)

    return ross_table_of(bearing, viscosity, speeds, frequencies, full_at)


def ross_table_of(bearing: TiltingPadBearing, viscosity: float, speeds, frequencies, full_at) -> dict:
    """:func:`ross_table` from coefficients already found: ``full_at(speed)`` gives the
    :class:`PadAssemblyCoefficients` at each rotor speed [rad/s] (the equilibrium under the load there),
    reduced here at every whirl frequency with the pads' mass at that speed."""
    speeds, frequencies = np.asarray(speeds, float), np.asarray(frequencies, float)
    table = {f"{k}{a}{b}": np.zeros((speeds.size, frequencies.size)) for k in "kc" for a in "xy" for b in "xy"}
    for i, speed in enumerate(speeds):
        full = full_at(float(speed))
        mass = bearing.pad_mass(viscosity, speed)
        for j, frequency in enumerate(frequencies):
            K, C = full.reduced(frequency / speed, pad_mass=mass).to_si(
                viscosity=viscosity, speed=speed, radius=bearing.radius, clearance=bearing.pad_clearance)
            for a, ia in (("x", 0), ("y", 1)):
                for b, ib in (("x", 0), ("y", 1)):
                    table[f"k{a}{b}"][i, j] = K[ia, ib]
                    table[f"c{a}{b}"][i, j] = C[ia, ib]
    out = {"speed": speeds.tolist(), "frequency": frequencies.tolist()}
    out.update({k: v.tolist() for k, v in table.items()})
    return out
