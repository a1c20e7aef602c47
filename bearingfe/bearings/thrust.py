r"""Thrust bearings: annular sector pads facing a rotating collar, of fixed geometry or tilting on a pivot.

A pad (:class:`ThrustPad`, SI) is an annular sector of the collar's plane (its leading edge at angle 0,
the collar turning counter-clockwise, towards the trailing edge at ``extent``), meshed by gmsh with exact
circular rims (:class:`~bearingfe.geometry.surface.AnnularSector`); its film lives on the plane with the
runner's velocity ``omega x r`` (:class:`~bearingfe.geometry.runner.Rotating`), so every film model,
cavitation model and flow of the package applies. Non-dimensional inner currency: lengths in the outer
radius ``R0``, films in a reference film ``h_ref`` (the :class:`~bearingfe.core.scales.Scale`'s
``radius`` and ``clearance``), pressures in ``mu omega R0^2 / h_ref^2``.

The film of a pad (:meth:`ThrustPad.film`) is its position, a :class:`~bearingfe.film.thickness.PlaneFilm`
(the film at the pivot, the pitch about the radial line through the pivot, the roll about the
circumferential line through it), plus its machined profile (taper-land or Rayleigh step,
:class:`~bearingfe.film.thickness.PolarProfileFilm`).

- :func:`solve_pad`: one pad's performance for a given position (load, moments about the pivot, friction
  power, flows through the four edges, minimum film, peak pressure), and :class:`ThrustPerformance`
  for the bearing of ``n_pads`` identical pads;
- :func:`pad_for_load`: the film at the pivot that carries a load with the pad's tilt held (fixed
  geometry), by Newton;
- :func:`tilting_equilibrium`: a tilting pad on a point pivot (film, pitch and roll: zero moments about
  the pivot, the load through it) or a line pivot (film and pitch), by Newton on the unknowns with a
  finite-difference Jacobian, damped to keep the film positive, warm-started by the caller across loads;
- :func:`axial_coefficients`: the pad's stiffness and damping matrices over (film, pitch, roll) and the
  bearing's axial ``k_zz``, ``c_zz`` at a vibration frequency with the pads following (massless pads:
  the reduction of the impedance ``K + i Omega C`` onto the axial motion).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Mapping

import numpy as np

from ..core.scales import Scale
from ..film.thickness import PlaneFilm, PolarProfileFilm, SumFilm
from ..geometry.meshing import SupportMesh, mesh_surface
from ..geometry.runner import Rotating, Translating
from ..geometry.surface import AnnularSector, Surface

__all__ = ["ThrustPad", "SliderPad", "PadSolution", "ThrustPerformance", "ThrustError", "PIVOTS", "solve_pad", "pad_for_load",
           "tilting_equilibrium", "axial_coefficients", "AxialCoefficients", "performance", "carry", "load_curve"]

#: Pivot kinds: the unknowns of the pad's equilibrium beside the film at the pivot.
PIVOTS: Mapping[str, tuple[str, ...]] = MappingProxyType({
    "point": ("pitch", "roll"),   # spherical pivot: the pad tilts about both axes
    "line": ("pitch",),           # rocker line along the radius: the pad pitches only
})

#: Relative tolerance of the Newton solves on the load (and on the moments, relative to load x radius).
TOLERANCE = 1e-9
MAX_ITERATIONS = 40


class ThrustError(RuntimeError):
    """A thrust pad's Newton solve did not converge (the message says where it stood)."""


@dataclass(frozen=True)
class ThrustPad:
    """One pad of a thrust bearing of identical pads (SI).

    Parameters
    ----------
    inner_radius, outer_radius : float
        Pad radii [m], ``0 < inner < outer``.
    extent : float
        Pad angle [rad], in ``(0, 2 pi / n_pads]``.
    n_pads : int
        Number of identical pads of the bearing, >= 1.
    pivot_radius : float or None
        Radius of the pivot [m] (default the mean radius), inside the pad.
    pivot_offset : float
        Angular position of the pivot from the leading edge as a fraction of ``extent``, in ``(0, 1)``
        (0.5: centred; tilting pads in one direction of rotation are offset, typically 0.58-0.6).
    profile : sequence of (s, depth)
        The machined profile added to the flat pad: abscissae (fraction of ``extent`` from the leading
        edge for ``profile_along="angle"``, radius [m] for ``"radius"``) and extra depth [m] (>= 0), linear
        in between, two points at one abscissa a step. Empty: a flat pad.
    profile_along : {"angle", "radius"}
        Step and taper lines radial (``"angle"``) or circumferential (``"radius"``).
    pockets : tuple of Shape
        Pockets (at ``pocket_pressure``) inside the pad, in the non-dimensional plane (units of the outer
        radius, the collar's axis at the origin).
    addition : Film or None
        Any user film added to the pad's position and profile (a chamfer on a rim, waviness, a measured
        form error), non-dimensional: ``h(x, y)`` [h_ref] over the plane in units of the outer radius.
    """

    inner_radius: float
    outer_radius: float
    extent: float
    n_pads: int = 1
    pivot_radius: float | None = None
    pivot_offset: float = 0.5
    profile: tuple = ()
    profile_along: str = "angle"
    pockets: tuple = ()
    addition: object = None

    def __post_init__(self) -> None:
        from ..film.thickness import Film

        if self.addition is not None and not isinstance(self.addition, Film):
            raise ValueError(f"ThrustPad.addition must be a film (the bearingfe.Film protocol) or None, "
                             f"got {type(self.addition).__name__}")
        ri, ro = float(self.inner_radius), float(self.outer_radius)
        if not (math.isfinite(ri) and math.isfinite(ro) and 0.0 < ri < ro):
            raise ValueError(f"ThrustPad: need 0 < inner_radius < outer_radius [m], got {self.inner_radius!r}, "
                             f"{self.outer_radius!r}")
        if not (isinstance(self.n_pads, (int, np.integer)) and self.n_pads >= 1):
            raise ValueError(f"ThrustPad.n_pads must be an integer >= 1, got {self.n_pads!r}")
        extent = float(self.extent)
        if not (math.isfinite(extent) and 0.0 < extent <= 2 * math.pi / self.n_pads + 1e-12):
            raise ValueError(f"ThrustPad.extent must be in (0, 2 pi / n_pads = {2 * math.pi / self.n_pads:.6g}] [rad], "
                             f"got {self.extent!r}")
        rp = 0.5 * (ri + ro) if self.pivot_radius is None else float(self.pivot_radius)
        if not (math.isfinite(rp) and ri < rp < ro):
            raise ValueError(f"ThrustPad.pivot_radius must be in ({ri!r}, {ro!r}) [m], got {self.pivot_radius!r}")
        offset = float(self.pivot_offset)
        if not (math.isfinite(offset) and 0.0 < offset < 1.0):
            raise ValueError(f"ThrustPad.pivot_offset must be in (0, 1) (fraction of the pad angle), got {self.pivot_offset!r}")
        if self.profile_along not in ("angle", "radius"):
            raise ValueError(f"ThrustPad.profile_along must be 'angle' or 'radius', got {self.profile_along!r}")
        object.__setattr__(self, "inner_radius", ri)
        object.__setattr__(self, "outer_radius", ro)
        object.__setattr__(self, "extent", extent)
        object.__setattr__(self, "pivot_radius", rp)
        object.__setattr__(self, "pivot_offset", offset)
        object.__setattr__(self, "profile", tuple((float(s), float(d)) for s, d in self.profile))
        object.__setattr__(self, "pockets", tuple(self.pockets))

    # -- the non-dimensional pad ----------------------------------------------------------------

    @property
    def sector(self) -> AnnularSector:
        """The pad's outline in units of the outer radius, leading edge at angle 0."""
        return AnnularSector(self.inner_radius / self.outer_radius, 1.0, start=0.0, extent=self.extent)

    def surface(self) -> Surface:
        """The pad's surface: its sector, its pockets, the collar rotating counter-clockwise about the origin."""
        return Surface(outer=self.sector, inlets=self.pockets, runner=Rotating((0.0, 0.0), 1))

    def mesh(self, size: float, *, order: int = 1, **options) -> SupportMesh:
        """The pad meshed by gmsh (``size`` in units of the outer radius; options of :func:`mesh_surface`)."""
        return mesh_surface(self.surface(), size, order=order, **options)

    @property
    def outline(self) -> AnnularSector:
        return self.sector

    @property
    def lever(self) -> float:
        """The pad's length along the sliding at the pivot [-]: the scale of its moments."""
        return self.pivot_radius / self.outer_radius * self.extent

    @property
    def pivot(self) -> tuple[float, float]:
        """The pivot's position [-] (units of the outer radius)."""
        r, a = self.pivot_radius / self.outer_radius, self.pivot_offset * self.extent
        return (r * math.cos(a), r * math.sin(a))

    @property
    def axes(self) -> tuple[np.ndarray, np.ndarray]:
        """Unit vectors at the pivot: circumferential (along the sliding) and radial."""
        a = self.pivot_offset * self.extent
        return np.array([-math.sin(a), math.cos(a)]), np.array([math.cos(a), math.sin(a)])

    def film(self, scale: Scale, h_pivot: float, pitch: float = 0.0, roll: float = 0.0, *,
             second_rates: bool = False):
        """The pad's film [h_ref] for its position.

        Parameters
        ----------
        scale : Scale
            ``radius`` the outer radius [m], ``clearance`` the reference film ``h_ref`` [m].
        h_pivot : float
            Film at the pivot [m].
        pitch : float
            Rotation about the radial line through the pivot [rad], > 0: the film grows towards the leading
            edge (a converging film under the collar).
        roll : float
            Rotation about the circumferential line through the pivot [rad], > 0: the film grows outwards.
        """
        q = self.state(scale, h_pivot, pitch, roll)
        return self.film_of_state(q, second_rates=second_rates)

    def state(self, scale: Scale, h_pivot: float, pitch: float = 0.0, roll: float = 0.0) -> np.ndarray:
        """``(h_pivot, pitch, roll)`` [m, rad, rad] as the non-dimensional state (film [h_ref], slopes [h_ref/R0])."""
        ratio = scale.radius / scale.clearance
        return np.array([h_pivot / scale.clearance, pitch * ratio, roll * ratio])

    def position(self, scale: Scale, q: np.ndarray) -> tuple[float, float, float]:
        """The non-dimensional state back in SI: ``(h_pivot [m], pitch [rad], roll [rad])``."""
        ratio = scale.clearance / scale.radius
        return float(q[0] * scale.clearance), float(q[1] * ratio), float(q[2] * ratio)

    def film_of_state(self, q: np.ndarray, *, second_rates: bool = False, scale: Scale | None = None):
        """The film of a non-dimensional state ``q = (h_pivot, pitch slope, roll slope)`` (see :meth:`state`)."""
        t, r = self.axes
        slope = -q[1] * t + q[2] * r
        plane = PlaneFilm(float(q[0]), self.pivot, (float(slope[0]), float(slope[1])), second_rates=second_rates)
        extras = tuple(f for f in (self._profile(scale), self.addition) if f is not None)
        return SumFilm(plane, extras) if extras else plane

    def _profile(self, scale: Scale | None):
        if not self.profile:
            return None
        if scale is None:
            raise ValueError("a pad with a profile needs the scale to make its depths non-dimensional")
        if self.profile_along == "angle":
            pts = tuple((s * self.extent, d / scale.clearance) for s, d in self.profile)
        else:
            pts = tuple((s / self.outer_radius, d / scale.clearance) for s, d in self.profile)
        return PolarProfileFilm(pts, along=self.profile_along, centre=(0.0, 0.0), start=0.0)


@dataclass(frozen=True)
class SliderPad:
    """An infinitely wide flat pad over a translating runner (the 1-D slider, its reference): a rectangle
    periodic across the sliding (width ``2 pi``, no side leakage), the runner sliding along ``z`` from the
    leading edge ``z = -length/2`` to the trailing edge ``z = +length/2``; the same protocol as
    :class:`ThrustPad` for :func:`solve_pad`, :func:`tilting_equilibrium` (on a ``"line"`` pivot) and
    :func:`axial_coefficients`, in units of the scale's radius.

    Parameters
    ----------
    length : float
        Pad length along the sliding [-], > 0.
    pivot_offset : float
        Pivot position from the leading edge as a fraction of the length, in ``(0, 1)``.
    """

    length: float = 1.0
    pivot_offset: float = 0.5
    n_pads: int = 1
    pockets: tuple = ()

    def __post_init__(self) -> None:
        if not (math.isfinite(float(self.length)) and float(self.length) > 0):
            raise ValueError(f"SliderPad.length must be a finite number > 0, got {self.length!r}")
        if not (0.0 < float(self.pivot_offset) < 1.0):
            raise ValueError(f"SliderPad.pivot_offset must be in (0, 1), got {self.pivot_offset!r}")

    def surface(self) -> Surface:
        return Surface(arc=(-math.pi, math.pi), half_width=0.5 * self.length, periodic=True,
                       runner=Translating(math.pi / 2))

    def mesh(self, size: float, *, order: int = 1, **options) -> SupportMesh:
        return mesh_surface(self.surface(), size, order=order, **options)

    @property
    def outline(self):
        return self.surface().outline

    @property
    def lever(self) -> float:
        return float(self.length)

    @property
    def pivot(self) -> tuple[float, float]:
        return (0.0, (self.pivot_offset - 0.5) * self.length)

    @property
    def axes(self) -> tuple[np.ndarray, np.ndarray]:
        return np.array([0.0, 1.0]), np.array([1.0, 0.0])

    def state(self, scale: Scale, h_pivot: float, pitch: float = 0.0, roll: float = 0.0) -> np.ndarray:
        return ThrustPad.state(self, scale, h_pivot, pitch, roll)

    def position(self, scale: Scale, q: np.ndarray) -> tuple[float, float, float]:
        return ThrustPad.position(self, scale, q)

    def film_of_state(self, q: np.ndarray, *, second_rates: bool = False, scale: Scale | None = None):
        t, r = self.axes
        slope = -q[1] * t + q[2] * r
        return PlaneFilm(float(q[0]), self.pivot, (float(slope[0]), float(slope[1])), second_rates=second_rates)


# -- one pad's performance ---------------------------------------------------------------------

@dataclass(frozen=True)
class PadSolution:
    """One pad's film for a position (non-dimensional; :class:`ThrustPerformance` gives the SI bearing).

    Attributes
    ----------
    state : ndarray, shape (3,)
        ``(h_pivot, pitch slope, roll slope)`` [h_ref, h_ref/R0].
    load : float
        ``int p dA`` [-] (pockets included).
    moments : ndarray, shape (2,)
        ``int p (X . e_theta)``, ``int p (X . e_r)`` about the pivot [-] (``X`` from the pivot): zero for a
        pad in equilibrium on a point pivot (the first only, on a line pivot).
    result : ReynoldsResult
        The film solve (pressure, flows by edge, friction along the collar's velocity).
    """

    state: np.ndarray
    load: float
    moments: np.ndarray
    result: object


def solve_pad(pad: ThrustPad, mesh: SupportMesh, q, *, scale: Scale | None = None, squeeze=(0.0, 0.0),
              second_rates: bool = False, **solve_options) -> PadSolution:
    """One pad's film at the non-dimensional state ``q`` (:meth:`ThrustPad.state`).

    ``solve_options`` go to :func:`bearingfe.solve_reynolds` (``cavitation``, ``element``, ``formulation``,
    ``inlet_pressure`` for pockets, ...); ``squeeze`` the rates of the film's state (``(dh_pivot/dt,
    d(pitch slope)/dt)`` [h_ref omega], or ``(d(roll slope)/dt, 0)`` with ``second_rates``).
    """
    from ..reynolds import solve_reynolds

    q = np.asarray(q, float)
    film = pad.film_of_state(q, second_rates=second_rates, scale=scale)
    options = dict(solve_options)
    if not getattr(film, "smooth", True) or isinstance(film, SumFilm):
        options.setdefault("formulation", "direct")
    res = solve_reynolds(mesh, film, squeeze=squeeze, **options)
    load, moments = _pad_loads(pad, res)
    return PadSolution(state=q, load=load, moments=moments, result=res)


def _pad_loads(pad: ThrustPad, res) -> tuple[float, np.ndarray]:
    """``int p`` and the moments of ``p`` about the pivot along the pad's axes, pockets included."""
    basis = res.basis
    p = np.asarray(basis.interpolate(res.pressure))
    x = np.asarray(basis.global_coordinates())
    dx = np.asarray(basis.dx)
    xp = pad.pivot
    t, r = pad.axes
    X, Y = x[0] - xp[0], x[1] - xp[1]
    load = float(np.sum(p * dx))
    m = np.array([np.sum(p * (X * t[0] + Y * t[1]) * dx), np.sum(p * (X * r[0] + Y * r[1]) * dx)])
    if res.inlet_pressure != 0.0:
        area, cx, cy = _pocket_moments(basis)
        X, Y = cx - xp[0] * area, cy - xp[1] * area   # int over the pockets of (x - x_p), (y - y_p)
        load += res.inlet_pressure * area
        m += res.inlet_pressure * np.array([X * t[0] + Y * t[1], X * r[0] + Y * r[1]])
    return load, m


def _pocket_moments(basis) -> tuple[float, float, float]:
    """``int 1``, ``int x``, ``int y`` over the pockets (the mesh's holes, curved edges included), by the
    divergence theorem on their contours: with ``n`` the film's outward normal (into the pocket),
    ``int_P 1 = -oint x n_x``, ``int_P x = -oint x^2/2 n_x``, ``int_P y = -oint y^2/2 n_y``."""
    from ..film.mesh_operators import facet_geometry

    facets = (basis.mesh.boundaries or {}).get("inlet")
    if facets is None or len(facets) == 0:
        return 0.0, 0.0, 0.0
    x, n, dx = facet_geometry(basis, np.asarray(facets), 8)  # the points, normals and weights only
    return (float(-np.sum(x[0] * n[0] * dx)), float(-np.sum(0.5 * x[0] ** 2 * n[0] * dx)),
            float(-np.sum(0.5 * x[1] ** 2 * n[1] * dx)))


# -- the bearing in SI ------------------------------------------------------------------------

@dataclass(frozen=True)
class ThrustPerformance:
    """A thrust bearing of ``n_pads`` identical pads at one position of its pads (SI).

    Attributes
    ----------
    load : float
        Axial load capacity of the bearing [N].
    power : float
        Friction power loss [W] (the collar's shear work).
    friction_torque : float
        [N m].
    flows : mapping
        Per bearing [m^3/s]: ``leading`` (into the film through the leading edges), ``trailing``,
        ``inner`` and ``outer`` (out through the rims), ``pocket`` (out of the pockets into the film);
        ``cavitation`` under Swift-Stieber.
    h_min : float
        Smallest film [m].
    p_max : float
        Peak pressure [Pa].
    h_pivot, pitch, roll : float
        The pad's position [m, rad, rad].
    pad : PadSolution
    """

    load: float
    power: float
    friction_torque: float
    flows: Mapping[str, float]
    h_min: float
    p_max: float
    h_pivot: float
    pitch: float
    roll: float
    pad: PadSolution = field(repr=False)


#: The flows of the bearing by the edge names of the pad's mesh (sign: + out of the film, but the
#: leading edge and the pockets count what enters).
_EDGE_FLOWS = (("leading", "arc_start", -1.0), ("trailing", "arc_end", 1.0), ("inner", "inner_rim", 1.0),
               ("outer", "outer_rim", 1.0), ("pocket", "inlet", 1.0), ("cavitation", "cavitation", 1.0))


def performance(pad: ThrustPad, scale: Scale, sol: PadSolution) -> ThrustPerformance:
    """The bearing's SI performance from one pad's solution."""
    res, n = sol.result, pad.n_pads
    flows = {name: sign * n * scale.to_flow(float(res.flows[key]))
             for name, key, sign in _EDGE_FLOWS if key in res.flows}
    torque = n * scale.to_moment(float(res.friction))
    h_pivot, pitch, roll = pad.position(scale, sol.state)
    return ThrustPerformance(load=n * scale.to_force(sol.load), power=torque * scale.speed, friction_torque=torque,
                             flows=MappingProxyType(flows), h_min=scale.to_thickness(res.h_min),
                             p_max=scale.to_pressure(float(np.max(res.pressure))) if res.pressure.size else 0.0,
                             h_pivot=h_pivot, pitch=pitch, roll=roll, pad=sol)


# -- Newton solves -----------------------------------------------------------------------------

def _film_floor(pad: ThrustPad, q: np.ndarray) -> float:
    """Smallest film of the plane at the pad's corners (the plane's minimum over the convex sector's hull)."""
    t, r = pad.axes
    slope = -q[1] * t + q[2] * r
    xy = pad.outline.boundary(256)
    return float(np.min(q[0] + slope[0] * (xy[0] - pad.pivot[0]) + slope[1] * (xy[1] - pad.pivot[1])))


def _jacobian(residual, q: np.ndarray, r: np.ndarray, free: list[int]) -> np.ndarray:
    """Forward-difference Jacobian of ``residual`` over the entries ``free`` of ``q`` (one solve each)."""
    J = np.empty((len(free), len(free)))
    for j, k in enumerate(free):
        dq = np.zeros_like(q)
        dq[k] = 1e-6 * max(abs(q[k]), 1e-2 * q[0], 1e-3)
        J[:, j] = (residual(q + dq)[0] - r) / dq[k]
    return J


def _newton(residual, q0: np.ndarray, free: list[int], scales: np.ndarray, pad: ThrustPad, what: str,
            tol: float, max_iterations: int):
    """Damped quasi-Newton on ``residual(q)[:len(free)] = 0`` over the entries ``free`` of ``q``: a
    finite-difference Jacobian, kept with Broyden's rank-one updates while full steps at least halve the
    residual (one film solve a step instead of ``1 + len(free)``), differenced again otherwise; steps are
    halved until the film stays positive and the residual norm falls."""
    q = np.array(q0, float)
    r, sol = residual(q)
    history = []
    J, fresh = None, False
    it = 0
    while it < max_iterations:
        norm = float(np.max(np.abs(r / scales)))
        if not history or history[-1] != norm:
            history.append(norm)
        if norm < tol:
            return q, sol, it
        if J is None:
            J, fresh = _jacobian(residual, q, r, free), True
        try:
            step = np.linalg.solve(J, -r)
        except np.linalg.LinAlgError:
            raise ThrustError(f"{what}: singular Jacobian at state {q.tolist()} (residuals {history})") from None
        lam, trial_norm = 1.0, math.inf
        while lam > 1e-4:
            trial = q.copy()
            trial[free] += lam * step
            if _film_floor(pad, trial) > 0.02 * trial[0] > 0:
                rt, st = residual(trial)
                trial_norm = float(np.max(np.abs(rt / scales)))
                if trial_norm < (1 - 1e-4 * lam) * norm:
                    break
            lam *= 0.5
        else:
            if not fresh:  # the updated Jacobian led nowhere: difference it again and retry from here
                J = None
                continue
            raise ThrustError(f"{what}: no step reduces the residual from state {q.tolist()} "
                              f"(relative residuals by iteration: {[f'{v:.2e}' for v in history]})")
        if lam == 1.0 and trial_norm < 0.5 * norm:  # Broyden's update along the full step
            J = J + np.outer(rt - r - J @ step, step) / float(step @ step)
            fresh = False
        else:  # a shortened or a weak step: the linear model is poor here, difference it again
            J = None
        q, r, sol = trial, rt, st
        it += 1
    raise ThrustError(f"{what}: no convergence in {max_iterations} iterations "
                      f"(relative residuals: {[f'{v:.2e}' for v in history[-5:]]})")


def _warm(solve_options: dict):
    """The solve options with the last cavitated result as the next solve's warm start (its rupture set):
    Newton's states differ by little, so the next active-set solve starts from the right set."""
    state: dict = {}
    cavitating = solve_options.get("cavitation", "none") not in ("none", "gumbel")

    def options() -> dict:
        if cavitating and "result" in state and "warm_start" not in solve_options:
            return dict(solve_options, warm_start=state["result"])
        return solve_options

    def keep(sol: PadSolution) -> PadSolution:
        if cavitating:
            state["result"] = sol.result
        return sol
    return options, keep


def pad_for_load(pad: ThrustPad, mesh: SupportMesh, scale: Scale, load: float, *, pitch: float = 0.0,
                 roll: float = 0.0, h_guess: float | None = None, tol: float = TOLERANCE,
                 max_iterations: int = MAX_ITERATIONS, **solve_options) -> ThrustPerformance:
    """The bearing with fixed-geometry pads (their tilt held) carrying an axial ``load`` [N]: the film at the
    pivot by Newton.

    ``h_guess`` [m]: the first film at the pivot (default ``scale.clearance``); ``solve_options`` as in
    :func:`solve_pad`. Raises :class:`ThrustError` if Newton stalls (e.g. a load beyond what a pad whose
    film cannot converge carries).
    """
    _check_load(load)
    target = scale.from_force(load) / pad.n_pads
    q0 = pad.state(scale, scale.clearance if h_guess is None else h_guess, pitch, roll)
    options, keep = _warm(solve_options)

    def residual(q):
        sol = keep(solve_pad(pad, mesh, q, scale=scale, **options()))
        return np.array([sol.load - target]), sol

    q, sol, _ = _newton(residual, q0, [0], np.array([target]), pad, "pad_for_load", tol, max_iterations)
    return performance(pad, scale, sol)


def tilting_equilibrium(pad: ThrustPad, mesh: SupportMesh, scale: Scale, load: float, *, pivot: str = "point",
                        start: tuple[float, float, float] | None = None, tol: float = TOLERANCE,
                        max_iterations: int = MAX_ITERATIONS, **solve_options) -> ThrustPerformance:
    """The tilting pads' equilibrium under an axial ``load`` [N] on the bearing: the film at the pivot, the
    pitch (and the roll on a point pivot) at which each pad carries ``load / n_pads`` through its pivot with
    no moment about it.

    Parameters
    ----------
    pivot : {"point", "line"}
        :data:`PIVOTS`: a line pivot holds the roll at ``start``'s (0 by default).
    start : (h_pivot [m], pitch [rad], roll [rad]), optional
        Where Newton starts: a neighbouring load's equilibrium (warm start); default ``h_ref`` at the pivot
        and a pitch that doubles the film from trailing to leading edge.
    """
    _check_load(load)
    if pivot not in PIVOTS:
        raise ValueError(f"pivot must be one of {list(PIVOTS)}, got {pivot!r}")
    target = scale.from_force(load) / pad.n_pads
    if start is None:
        start = (scale.clearance, scale.clearance / (pad.lever * scale.radius), 0.0)
    q0 = pad.state(scale, *start)
    free = [0, 1] if pivot == "line" else [0, 1, 2]
    lever = pad.lever

    options, keep = _warm(solve_options)

    def residual(q):
        sol = keep(solve_pad(pad, mesh, q, scale=scale, **options()))
        r = np.array([sol.load - target, *sol.moments])[: len(free)]
        return r, sol

    scales = np.array([target, target * lever, target * lever])[: len(free)]
    q, sol, _ = _newton(residual, q0, free, scales, pad, "tilting_equilibrium", tol, max_iterations)
    return performance(pad, scale, sol)


def _check_load(load: float) -> None:
    value = float(load)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"load must be a finite axial force > 0 [N], got {load!r}")


# -- stiffness and damping ----------------------------------------------------------------------

@dataclass(frozen=True)
class AxialCoefficients:
    """A thrust bearing's axial stiffness and damping at an operating position (SI).

    Attributes
    ----------
    k_zz, c_zz : float
        Axial stiffness [N/m] and damping [N s/m] of the bearing at ``frequency`` with the pads following
        (massless tilting pads; for fixed-geometry pads the pad rows are not reduced).
    frequency : float
        Vibration frequency of the reduction [rad/s].
    stiffness, damping : ndarray, shape (3, 3)
        One pad's matrices ``-d(load, pitch moment, roll moment)/d(h_pivot, pitch, roll)`` and their rates,
        non-dimensional (load [mu omega R0^4/h_ref^2], moments times R0; states [h_ref], [h_ref/R0]; rates
        per ``1/omega``).
    """

    k_zz: float
    c_zz: float
    frequency: float
    stiffness: np.ndarray
    damping: np.ndarray


def axial_coefficients(pad: ThrustPad, mesh: SupportMesh, scale: Scale, at: ThrustPerformance, *,
                       pivot: str | None = "point", frequency: float | None = None,
                       **solve_options) -> AxialCoefficients:
    """Linearise the pad's film about ``at``: stiffness and damping over (film, pitch, roll) by finite
    differences of the load and moments, reduced onto the axial motion.

    Parameters
    ----------
    pivot : {"point", "line"} or None
        The pad's freedoms that follow the motion (massless pads); None: fixed-geometry pads (no reduction).
    frequency : float, optional
        Vibration frequency [rad/s] of the reduction; default the collar's speed.
    """
    if pivot is not None and pivot not in PIVOTS:
        raise ValueError(f"pivot must be one of {list(PIVOTS)} or None, got {pivot!r}")
    q = at.pad.state
    base = np.array([at.pad.load, *at.pad.moments])
    K = np.empty((3, 3))
    for k in range(3):
        dq = np.zeros(3)
        dq[k] = 1e-6 * max(abs(q[k]), 1e-2 * q[0], 1e-3)
        s = solve_pad(pad, mesh, q + dq, scale=scale, **solve_options)
        K[:, k] = -(np.array([s.load, *s.moments]) - base) / dq[k]
    rates = np.empty((3, 3))   # columns: d/dt of (h_pivot, slope_x, slope_y) (PlaneFilm's squeeze shapes)
    eps = 1e-6
    for k, (squeeze, second) in enumerate((((eps, 0.0), False), ((0.0, eps), False), ((eps, 0.0), True))):
        s = solve_pad(pad, mesh, q, scale=scale, squeeze=squeeze, second_rates=second, **solve_options)
        rates[:, k] = -(np.array([s.load, *s.moments]) - base) / eps
    t, r = pad.axes   # slope = -pitch t + roll r
    C = np.column_stack([rates[:, 0], -t[0] * rates[:, 1] - t[1] * rates[:, 2], r[0] * rates[:, 1] + r[1] * rates[:, 2]])
    omega = scale.speed if frequency is None else float(frequency)
    if not (math.isfinite(omega) and omega > 0):
        raise ValueError(f"frequency must be a finite number > 0 [rad/s], got {frequency!r}")
    Z = K + 1j * (omega / scale.speed) * C
    follow = [] if pivot is None else [1 + i for i in range(len(PIVOTS[pivot]))]
    z = Z[0, 0] - (Z[0, follow] @ np.linalg.solve(Z[np.ix_(follow, follow)], Z[follow, 0]) if follow else 0.0)
    k_scale = pad.n_pads * scale.force / scale.clearance
    # rates are per unit non-dimensional time (1/omega): the damping in SI is Im(z) / Omega times the force/film scale
    return AxialCoefficients(k_zz=float(z.real * k_scale), c_zz=float(z.imag * k_scale / omega),
                             frequency=omega, stiffness=K, damping=C)


def carry(pad, mesh: SupportMesh, scale: Scale, load: float, *, pivot: str | None = "point", pitch: float = 0.0,
          roll: float = 0.0, start: tuple[float, float, float] | None = None, **solve_options) -> ThrustPerformance:
    """The bearing under ``load`` [N]: tilting pads in equilibrium on their pivots (``pivot`` of
    :data:`PIVOTS`), or fixed-geometry pads (``pivot=None``: the tilt ``pitch``, ``roll`` [rad] held, the film
    at the pivot found). ``start``: a neighbouring solution's ``(h_pivot, pitch, roll)`` (warm start)."""
    if pivot is None:
        return pad_for_load(pad, mesh, scale, load, pitch=pitch, roll=roll,
                            h_guess=None if start is None else start[0], **solve_options)
    return tilting_equilibrium(pad, mesh, scale, load, pivot=pivot, start=start, **solve_options)


def load_curve(pad, mesh: SupportMesh, scale: Scale, loads, *, pivot: str | None = "point", pitch: float = 0.0,
               roll: float = 0.0, **solve_options) -> tuple[ThrustPerformance, ...]:
    """The bearing over ``loads`` [N] (each > 0), every solve warm-started from the previous one with its film
    and tilt scaled by ``(W_prev / W)^(1/2)`` (the rigid isoviscous film's similarity)."""
    out: list[ThrustPerformance] = []
    start = None
    for w in loads:
        if out:
            k = math.sqrt(out[-1].load / float(w))
            prev = out[-1]
            start = (prev.h_pivot * k, prev.pitch * k if pivot is not None else pitch,
                     prev.roll * k if pivot == "point" else roll)
        out.append(carry(pad, mesh, scale, w, pivot=pivot, pitch=pitch, roll=roll, start=start, **solve_options))
    return tuple(out)
