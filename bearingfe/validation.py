"""Comparisons of the FEM solver with closed forms and published data.

:data:`CHECKS` maps a name to a function ``(quick: bool) -> list[Check]``;
``bearingfe validate`` runs them all and prints the table. To add a
comparison, add one entry.

Closed forms used
-----------------
Annular hydrostatic pad (pocket radius ``r_i`` at ``p_s``, outline radius
``r_o`` at 0, uniform film ``h = 1``, no motion): ``p = p_s ln(r_o/r) / ln(r_o/r_i)``,
load ``W = pi p_s (r_o^2 - r_i^2) / (2 ln(r_o/r_i))`` (pocket included) and
flow ``Q = pi h^3 p_s / (6 ln(r_o/r_i))`` (Hamrock, Schmid & Jacobson,
*Fundamentals of Fluid Film Lubrication*, 2nd ed., ch. 6, circular step
pad).

The same pad with its recess fed from a supply ``p_s`` (:func:`fed_recess_pad`,
SI): with ``beta = p_r/p_s``, a capillary of conductance ``Kc`` holds ``beta = Kc/(Kc + K h^3)``
(``K h^3 = pi h^3 / (6 mu ln(r_o/r_i))`` the film's), an orifice ``C sqrt(p_s (1 - beta)) = K h^3 beta
p_s``; the stiffness ``-dW/dh`` is ``3 W (1 - beta)/h`` and ``6 W (1 - beta)/((2 - beta) h)``
(Rowe, *Hydrostatic, Aerostatic and Hybrid Bearing Design*, 2012, ch. 4-5).

Short-bearing (Ocvirk) limit: for ``a -> 0`` the journal-bearing equation
reduces to ``h^3 p_zz = 6 dh/dphi`` so ``p = 3 gamma sin(phi) (a^2 - z^2) / h^3``
with ``h = 1 + gamma cos(phi)``; over the full 360 deg film with no
cavitation the force is ``(0, 4 pi a^3 gamma / (1 - gamma^2)^(3/2))``
(Ocvirk 1952, NACA TN 2808; Hamrock et al. ch. 10). ``p = 0`` at
``phi = 0, 2 pi`` is exact for it, so an arc ``[0, 2 pi]`` with zero
pressure at its ends is the same problem; the finite-width correction is
``O(a^2)``: measured 0.06 %, 0.22 %, 0.89 % below Ocvirk at a = 0.025, 0.05, 0.1
(gamma = 0.5), hence the 0.5 % tolerance at a = 0.05.

Sliders (films that vary along the sliding only, infinitely wide: the 1-D
Reynolds equation, non-dimensional as the package solves it, ``(h^3 p')' = 6 h'``
with ``p = 0`` at both ends of a pad of length ``L``):

- any piecewise-constant film (:func:`stepped_slider`): the flux ``q`` is the same
  everywhere, ``p' = 12 (h_i/2 - q)/h_i^3`` in each land, so ``q = sum(6 L_i/h_i^2) /
  sum(12 L_i/h_i^3)`` and ``p`` is piecewise linear;
- the inclined slider (:func:`inclined_slider_load`), ``h`` falling linearly from
  ``h_in`` to ``h_out``, ``K = h_in/h_out - 1``: load coefficient ``W h_out^2/L^2 =
  6/K^2 (ln(1 + K) - 2K/(2 + K))``, largest 0.16024 at ``K = 1.1887``;
- the Rayleigh step (:func:`rayleigh_step_load`), inlet land ``h1`` over ``a``,
  outlet land ``h2``: ``W h2^2/L^2 = 3 (H - 1)/(H^3/alpha + 1/(1 - alpha))`` with
  ``H = h1/h2``, ``alpha = a/L``, largest 0.20627 at ``H = 1.8660``, ``alpha = 0.7182``
  (Hamrock, Schmid & Jacobson, ch. 8-9). Of finite width ``B`` (p = 0 on the sides
  too) it is a Fourier series in ``z``: in each land ``p`` is harmonic, continuous at
  the step, where the flux jump ``h1^3 p1' - h2^3 p2' = 6 (h1 - h2)`` sets the
  coefficients of ``p_step = sum P_n sin(k_n (z + B/2))`` over odd ``n``,
  ``k_n = n pi/B``: ``P_n = 24 (h1 - h2)/(n pi k_n (h1^3 coth(k_n a) + h2^3
  coth(k_n (L - a))))``, load ``sum P_n 2/k_n^2 (tanh(k_n a/2) + tanh(k_n (L - a)/2))``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType
from typing import Callable, Mapping

import numpy as np

__all__ = ["Check", "CHECKS", "RAIMONDI_BOYD", "run_checks", "annular_pad", "short_bearing", "raimondi_boyd",
           "PocketSlider", "SliderAnswer", "jfo_pocket_slider", "OscillatingSqueeze", "stepped_slider",
           "inclined_slider_load", "rayleigh_step_load", "film_steps", "fed_recess_pad"]

#: ``L/D -> eps -> (S, attitude [deg], (R/c) f, Q/(R c N L), Qs/Q, P/p_max)``: Raimondi & Boyd
#: (1958), ASLE Trans. 1, full 360-degree bearing, Swift-Stieber conditions, as reproduced in
#: Shigley's *Mechanical Engineering Design* (chapter on lubrication and journal bearings) and
#: Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film Lubrication*. Every row agrees digit for
#: digit with an independent public transcription of the Shigley tables; not checked against a scan
#: of the 1958 paper. Its own accuracy (docs/validation.md): the S of L/D = 1, eps = 0.4 contradicts
#: the row's own friction variable by 1.3 % (which implies S = 0.2606); three attitudes are 0.32-0.38 deg
#: off a converged solution that two independent methods agree on to 1e-4; at eps = 0.97 S is 1-3 % low.
RAIMONDI_BOYD: Mapping[float, Mapping[float, tuple]] = MappingProxyType({
    1.0: {0.1: (1.33, 79.5, 26.4, 3.37, 0.150, 0.540), 0.2: (0.631, 74.02, 12.8, 3.59, 0.280, 0.529),
          0.4: (0.264, 63.10, 5.79, 3.99, 0.497, 0.484), 0.6: (0.121, 50.58, 3.22, 4.33, 0.680, 0.415),
          0.8: (0.0446, 36.24, 1.70, 4.62, 0.842, 0.313), 0.9: (0.0188, 26.45, 1.05, 4.74, 0.919, 0.247),
          0.97: (0.00474, 15.47, 0.514, 4.82, 0.973, 0.152)},
    0.5: {0.1: (4.31, 81.62, 85.6, 3.43, 0.173, 0.523), 0.2: (2.03, 74.94, 40.9, 3.72, 0.318, 0.506),
          0.4: (0.779, 61.45, 17.0, 4.29, 0.552, 0.441), 0.6: (0.319, 48.14, 8.10, 4.85, 0.730, 0.365),
          0.8: (0.0923, 33.31, 3.26, 5.41, 0.874, 0.267), 0.9: (0.0313, 23.66, 1.60, 5.69, 0.939, 0.206),
          0.97: (0.00609, 13.75, 0.610, 5.88, 0.980, 0.126)},
    0.25: {0.1: (16.2, 82.31, 322.0, 3.45, 0.180, 0.515), 0.2: (7.57, 75.18, 153.0, 3.76, 0.330, 0.489),
           0.4: (2.83, 60.86, 61.1, 4.37, 0.567, 0.415), 0.6: (1.07, 46.72, 26.7, 4.99, 0.746, 0.334),
           0.8: (0.261, 31.04, 8.80, 5.60, 0.884, 0.240), 0.9: (0.0736, 21.85, 3.50, 5.91, 0.945, 0.180),
           0.97: (0.0101, 12.22, 0.922, 6.12, 0.984, 0.108)},
})


@dataclass(frozen=True)
class Check:
    """One computed quantity against its reference.

    Attributes
    ----------
    name : str
    reference : str
        Where the expected value comes from.
    computed, expected : float
    tolerance : float
        Allowed relative error.
    """

    name: str
    reference: str
    computed: float
    expected: float
    tolerance: float

    @property
    def error(self) -> float:
        """Relative error ``|computed - expected| / |expected|``."""
        return abs(self.computed - self.expected) / abs(self.expected)

    @property
    def passed(self) -> bool:
        return math.isfinite(self.computed) and self.error <= self.tolerance


def annular_pad(quick: bool = False, r_in: float = 0.1, r_out: float = 0.4) -> list[Check]:
    """Hydrostatic annular pad: load and flow against the closed form (P2 elements)."""
    from .film.thickness import CosineFilm
    from .geometry.surface import Circle, Surface
    from .geometry.meshing import mesh_surface
    from .reynolds import solve_reynolds

    surface = Surface(outer=Circle((0.0, 0.0), r_out), inlets=(Circle((0.0, 0.0), r_in),))
    size = 0.05 if quick else 0.02
    mesh = mesh_surface(surface, size, inlet_size=size / 3, order=2)
    res = solve_reynolds(mesh, CosineFilm(0.0), wedge=0.0, inlet_pressure=1.0, element="P2",
                         formulation="direct")
    log = math.log(r_out / r_in)
    ref = "closed form, annular step pad (Hamrock ch. 6)"
    return [Check("annular pad load W", ref, res.integral, math.pi * (r_out**2 - r_in**2) / (2 * log), 1e-4),
            Check("annular pad flow Q", ref, res.flows["inlet"], math.pi / (6 * log), 1e-4)]


def fed_recess_pad(quick: bool = False, r_in: float = 0.1, r_out: float = 0.4) -> list[Check]:
    """The annular pad's recess fed through a capillary (beta = 0.5) and an orifice (beta = 0.6): recess
    ratio, film flow and stiffness against the closed forms (P2; measured errors 4e-6 to 7e-6 at size 0.05,
    1e-6 at 0.025: docs/hydrostatic.md)."""
    from .bearings.hydrostatic import Capillary, Orifice, supply_stiffness
    from .core.parameters import Discretization
    from .core.scales import Scale
    from .film.thickness import UniformFilm
    from .geometry.surface import Circle, Surface
    from .geometry.meshing import mesh_surface

    scale = Scale(radius=0.05, clearance=20e-6, viscosity=0.05, speed=100.0)
    ps, c, mu = 5e6, scale.clearance, scale.viscosity
    log = math.log(r_out / r_in)
    film_k = math.pi * c**3 / (6 * mu * log)  # film flow per recess pressure [m^3/s/Pa]
    area = math.pi * scale.radius**2 * (r_out**2 - r_in**2) / (2 * log)  # load per recess pressure [m^2]
    d = 0.4e-3
    capillary = Capillary(diameter=d, length=math.pi * d**4 / (128 * mu * film_k), supply_pressure=ps)  # Kc = K
    cd, rho = 0.7, 860.0
    c_orifice = film_k * 0.6 * ps / math.sqrt(0.4 * ps)
    orifice = Orifice(diameter=math.sqrt(4 * c_orifice / (cd * math.pi * math.sqrt(2 / rho))),
                      discharge_coefficient=cd, density=rho, supply_pressure=ps)
    surface = Surface(outer=Circle((0.0, 0.0), r_out), inlets=(Circle((0.0, 0.0), r_in),))
    size = 0.05 if quick else 0.025
    mesh = mesh_surface(surface, size, inlet_size=size / 3, order=2)
    ref = "closed form, recess pad fed through a restrictor (Rowe ch. 4-5)"
    out = []
    for name, supply, beta in (("capillary", capillary, 0.5), ("orifice", orifice, 0.6)):
        st = supply_stiffness(mesh, UniformFilm, 1.0, supply, scale,
                              discretization=Discretization(element="P2", formulation="direct"))
        pocket, w = st.result.pockets[0], area * beta * ps
        k = 3 * w * (1 - beta) / c if name == "capillary" else 6 * w * (1 - beta) / ((2 - beta) * c)
        out += [Check(f"{name}-fed recess ratio beta", ref, pocket.ratio, beta, 1e-4),
                Check(f"{name}-fed recess flow Q [m^3/s]", ref, pocket.film_flow, film_k * beta * ps, 1e-4),
                Check(f"{name}-fed pad stiffness [N/m]", ref, st.stiffness, k, 1e-4)]
    return out


def short_bearing(quick: bool = False, half_width: float = 0.05, gamma: float = 0.5) -> list[Check]:
    """Narrow full journal bearing against the Ocvirk short-bearing load."""
    from .film.thickness import CosineFilm
    from .geometry.surface import Surface
    from .geometry.meshing import mesh_surface
    from .reynolds import solve_reynolds

    surface = Surface(arc=(0.0, 2 * math.pi), half_width=half_width)
    size = half_width / (2 if quick else 4)
    mesh = mesh_surface(surface, size, order=1)
    res = solve_reynolds(mesh, CosineFilm(gamma), wedge=1.0, element="P2")
    expected = 4 * math.pi * half_width**3 * gamma / (1 - gamma**2) ** 1.5
    return [Check(f"short bearing load, a = {half_width}, gamma = {gamma}",
                  "Ocvirk short-bearing limit (NACA TN 2808)", float(res.force[1]), expected, 5e-3)]


def raimondi_boyd(quick: bool = False, rows=((1.0, 0.6), (1.0, 0.8), (0.5, 0.6))) -> list[Check]:
    """Full journal bearings with Swift-Stieber cavitation against Raimondi & Boyd (1958).

    Sommerfeld number within 1 % and attitude angle within 1 % (about 0.3-0.5
    degree) on h-graded meshes; docs/validation.md has the full table.
    """
    from .bearings.journal import JournalBearing, performance

    out = []
    for ld, eps in rows:
        ref = RAIMONDI_BOYD[ld][eps]
        size = min(0.1, ld / 5) * (0.75 if quick else 0.4)
        perf = performance(JournalBearing(length_ratio=ld), eps, size=size)
        where = f"Raimondi & Boyd 1958, L/D = {ld:g}, eps = {eps:g}"
        out += [Check(f"Sommerfeld number, L/D {ld:g}, eps {eps:g}", where, perf.sommerfeld, ref[0], 1e-2),
                Check(f"attitude [deg], L/D {ld:g}, eps {eps:g}", where, perf.attitude, ref[1], 1e-2)]
    return out


@dataclass(frozen=True)
class SliderAnswer:
    """Per-unit-width answer of a 1-D slider [SI].

    Attributes
    ----------
    flow : float
        Volume flow per unit width [m^2/s] (the same everywhere in steady state).
    load : float
        ``int (p - p_edge) dx`` per unit width [N/m].
    reformation : float
        Where the film reforms in the pocket [m].
    theta_cavity : float
        Fill fraction in the cavity [-].
    peak_pressure : float
        Pressure at the pocket's trailing edge [Pa].
    """

    flow: float
    load: float
    reformation: float
    theta_cavity: float
    peak_pressure: float


@dataclass(frozen=True)
class _StepFilm:
    """``h = 1`` with a deeper band ``start < phi < end`` of thickness ``ratio`` (units of the outer film)."""

    start: float
    end: float
    ratio: float
    smooth = False  # a step at each end of the band

    def thickness(self, phi, z):
        phi = np.asarray(phi, float)
        return 1.0 + (self.ratio - 1.0) * ((phi > self.start) & (phi < self.end)) + 0.0 * np.asarray(z)

    def gradient(self, phi, z):
        zero = 0.0 * np.asarray(phi, float) + 0.0 * np.asarray(z)
        return zero, zero

    def laplacian(self, phi, z):
        return 0.0 * np.asarray(phi, float) + 0.0 * np.asarray(z)

    def rate_shapes(self, phi, z):
        zero = 0.0 * np.asarray(phi, float) + 0.0 * np.asarray(z)
        return zero, zero

    def minimum(self, phi_range) -> float:
        return 1.0


@dataclass(frozen=True)
class PocketSlider:
    r"""1-D slider with a deeper pocket, mass-conserving cavitation: the exact solution.

    A surface moves at ``speed`` over a pad of ``length`` whose film is
    ``h_out`` except on ``start < x < end`` (a pocket, film ``h_in``), with
    ``p_edge`` at both ends and cavity pressure ``p_cav`` [SI]. The pocket's
    leading edge is a divergent step: the film ruptures there (the pressure in
    the inlet land falls linearly from ``p_edge`` to ``p_cav`` at ``x = start``),
    the pocket carries a cavity of constant ``theta h`` up to the reformation
    point ``x_r``, full film again from ``x_r`` to ``end`` and through the
    outlet land. With the flux ``q = -h^3/(12 mu) p' + U theta h/2``,
    constant in steady state:

    - inlet land: ``q = U h_out/2 + h_out^3 (p_edge - p_cav) / (12 mu start)``;
    - cavity: ``theta_c = 2 q / (U h_in)``;
    - outlet land: ``p(end) = p_edge + 12 mu (q - U h_out/2) (length - end) / h_out^3``;
    - pocket full film: ``p' = 12 mu (U h_in/2 - q)/h_in^3`` from ``p_cav`` at ``x_r``:
      ``x_r = end - (p(end) - p_cav) h_in^3 / (12 mu (U h_in/2 - q))``.

    This is a JFO solution (``p >= p_cav``, ``0 < theta_c < 1``, flux continuous
    at the rupture step and at ``x_r``) when ``start < x_r < end``; the
    constructor checks it. Defaults: the reference case (20 mm, 1 m/s,
    0.01 Pa s, 1 um / 10 um, pocket 2-5 mm, 100 kPa, 50 kPa), derived in
    ``docs/jfo.md``.
    """

    length: float = 0.02
    speed: float = 1.0
    viscosity: float = 0.01
    h_out: float = 1e-6
    h_in: float = 10e-6
    start: float = 0.002
    end: float = 0.005
    p_edge: float = 1e5
    p_cav: float = 5e4

    def __post_init__(self) -> None:
        for name in ("length", "speed", "viscosity", "h_out", "h_in", "start", "end", "p_edge"):
            value = float(getattr(self, name))
            if not (math.isfinite(value) and value > 0):
                raise ValueError(f"PocketSlider.{name} must be a finite number > 0, got {value!r}")
        if not (0 < self.start < self.end < self.length):
            raise ValueError("PocketSlider needs 0 < start < end < length")
        if not (self.h_in > self.h_out and 0 <= self.p_cav < self.p_edge):
            raise ValueError("PocketSlider needs h_in > h_out and 0 <= p_cav < p_edge")
        ex = self.exact()
        if not (self.start < ex.reformation < self.end and 0 < ex.theta_cavity < 1):
            raise ValueError(f"no cavity inside the pocket for these parameters (x_r = {ex.reformation:.4g} m, "
                             f"theta = {ex.theta_cavity:.4g}): the closed form does not apply")

    def exact(self) -> SliderAnswer:
        """The closed-form JFO solution (see the class docstring)."""
        mu, U, ho, hi = self.viscosity, self.speed, self.h_out, self.h_in
        dp = self.p_edge - self.p_cav
        q = U * ho / 2 + ho**3 * dp / (12 * mu * self.start)
        p_end = self.p_edge + 12 * mu * (q - U * ho / 2) * (self.length - self.end) / ho**3
        x_r = self.end - (p_end - self.p_cav) * hi**3 / (12 * mu * (U * hi / 2 - q))
        load = (-dp * self.start / 2 - dp * (x_r - self.start)
                + (p_end - self.p_edge - dp) / 2 * (self.end - x_r) + (p_end - self.p_edge) * (self.length - self.end) / 2)
        return SliderAnswer(flow=q, load=load, reformation=x_r, theta_cavity=2 * q / (U * hi), peak_pressure=p_end)

    @property
    def pressure_scale(self) -> float:
        """``mu U L / h_out^2`` [Pa]: the package's ``p`` with ``R0 = length``, ``c = h_out``, ``wedge = 1``."""
        return self.viscosity * self.speed * self.length / self.h_out**2

    def film(self):
        """The non-dimensional step film (``phi = x / length``, ``h`` in units of ``h_out``)."""
        return _StepFilm(self.start / self.length, self.end / self.length, self.h_in / self.h_out)

    def solve(self, n: int, element: str = "P1") -> SliderAnswer:
        """Solve on a 2-D strip of ``n`` cells along (``n`` a multiple of the steps' grid) with JFO."""
        from .geometry.meshing import strip_mesh
        from .reynolds import solve_reynolds

        for x in (self.start, self.end):
            if abs(x / self.length * n - round(x / self.length * n)) > 1e-9:
                raise ValueError(f"n = {n} puts no node at x = {x} m; the step must lie on element edges")
        mesh = strip_mesh(n)
        width = float(np.ptp(mesh.mesh.p[1]))
        scale = self.pressure_scale
        res = solve_reynolds(mesh, self.film(), cavitation="jfo", element=element,
                             cavitation_pressure=(self.p_cav - self.p_edge) / scale)
        flow = res.flows["arc_end"] / width * self.speed * self.h_out
        theta_c = 2 * flow / (self.speed * self.h_in)
        # reformation from the void volume: int (1 - theta) dx = (x_r - start)(1 - theta_c)
        from skfem import LinearForm

        void = float(np.sum(LinearForm(lambda v, w: v).assemble(res.basis) * (1 - res.theta))) / width
        x = res.basis.doflocs[0]
        inside = (x > self.start / self.length + 1.5 / n) & (res.theta < 1)
        return SliderAnswer(flow=flow, load=res.integral / width * scale * self.length,
                            reformation=self.start + void * self.length / (1 - theta_c),
                            theta_cavity=float(np.median(res.theta[inside])) if inside.any() else 1.0,
                            peak_pressure=float(res.interpolate(self.end / self.length, 0.0)) * scale + self.p_edge)


def jfo_pocket_slider(quick: bool = False) -> list[Check]:
    """The pocket slider with JFO cavitation against its closed form (:class:`PocketSlider`)."""
    case = PocketSlider()
    ex = case.exact()
    num = case.solve(160 if quick else 640)
    ref = "closed form, 1-D pocket slider with JFO cavitation (docs/jfo.md)"
    return [Check("JFO pocket slider load [N/m]", ref, num.load, ex.load, 1e-3),
            Check("JFO pocket slider flow [m^2/s]", ref, num.flow, ex.flow, 1e-6),
            Check("JFO pocket slider reformation [m]", ref, num.reformation, ex.reformation, 1e-2),
            Check("JFO pocket slider peak pressure [Pa]", ref, num.peak_pressure, ex.peak_pressure, 1e-3)]


@dataclass(frozen=True)
class OscillatingSqueeze:
    r"""1-D squeeze film between parallel plates with an oscillating gap, JFO cavitation (transient).

    Non-dimensional (the package's scales, no sliding): a strip ``0 < x < 1``
    with ``p = 0`` at both ends, gap ``h(t) = mean + amplitude cos(t)`` uniform
    in ``x``, cavity pressure ``p_c < 0``. The case is of the type of Ausas,
    Jai & Buscaglia (J. Tribol. 131, 031702, 2009), with our own parameters.
    While the plates approach, the film is full and
    ``p = 6 h'/h^3 (x^2 - x)``. Once they separate fast enough
    (``1.5 h'/h^3 > -p_c``) a cavity ``(1/2 - c, 1/2 + c)`` opens at the
    centre; with ``l = 1/2 - c`` the full film on each side is
    ``p = p_c + A y + 6 h'/h^3 y^2`` (``y`` from the front), ``p(l) = 0``:
    ``A = (-p_c - 6 h' l^2/h^3)/l``. Mass across the front gives
    ``c' (1 - theta_f) h = -h^3 A / 12`` with ``theta_f = h(tau)/h(t)`` the
    fill of the cavity where the front is (cavitated at time ``tau``, no
    flux in the cavity since there is no Couette flow). The front advances
    with ``A = 0`` (``l^2 = -p_c h^3/(6 h')``, fresh cavity has
    ``theta = 1``) and recedes by the ODE; :meth:`reference` integrates it
    implicitly (a scalar root per step, so the stiff turn-around is stable)
    and returns the cavity half-length and the load ``int p dx``.
    """

    mean: float = 1.0
    amplitude: float = 0.5
    p_cav: float = -0.1

    def __post_init__(self) -> None:
        if not (0 < self.amplitude < self.mean and math.isfinite(self.mean)):
            raise ValueError("OscillatingSqueeze needs 0 < amplitude < mean")
        if not (math.isfinite(self.p_cav) and self.p_cav < 0):
            raise ValueError(f"OscillatingSqueeze.p_cav must be < 0, got {self.p_cav!r}")

    def h(self, t):
        return self.mean + self.amplitude * np.cos(t)

    def h_rate(self, t):
        return -self.amplitude * np.sin(t)

    def reference(self, t_end: float = 2 * math.pi, steps: int = 40000) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(t, c, load)`` on ``steps`` equal steps of ``[0, t_end]`` from a full film at rest (t = 0)."""
        from scipy.optimize import brentq

        dt, c, pc = t_end / steps, 0.0, self.p_cav
        hist_c: list[float] = []   # front positions reached while the cavity grew ...
        hist_t: list[float] = []   # ... and when: the fill there is h(tau)/h(t)
        out = np.zeros((3, steps + 1))
        for k in range(steps + 1):
            t = k * dt
            H, Hd = float(self.h(t)), float(self.h_rate(t))
            grow = 0.5 - math.sqrt(-pc * H**3 / (6 * Hd)) if Hd > 0 else -math.inf
            if k and c > 0:
                c = self._recede(c, dt, t, H, Hd, max(grow, 0.0), hist_c, hist_t, brentq)
            if grow > c:
                while hist_c and hist_c[-1] >= c:
                    hist_c.pop(), hist_t.pop()
                hist_c.append(max(c, 0.0)), hist_t.append(t - dt if k else t)
                hist_c.append(grow), hist_t.append(t)
                c = grow
            if c <= 0:
                c, hist_c, hist_t = 0.0, [], []
            out[:, k] = t, c, self._load(c, H, Hd)
        return out[0], out[1], out[2]

    def _recede(self, c, dt, t, H, Hd, lo, hist_c, hist_t, brentq) -> float:
        pc = self.p_cav

        def speed(x):
            l = 0.5 - x
            A = (-pc - 6 * Hd * l**2 / H**3) / l
            fill = float(self.h(np.interp(x, hist_c, hist_t))) / H
            return -H**2 * A / (12 * max(1.0 - fill, 1e-300))

        if lo >= c:
            return c
        g = lambda x: (x - c) / dt - speed(x)  # backward Euler; g(lo) <= 0 <= g(c)
        return lo if g(lo) >= 0 else brentq(g, lo, c, xtol=1e-14)

    def _load(self, c, H, Hd) -> float:
        if c <= 0:
            return -Hd / H**3
        l = 0.5 - c
        A = (-self.p_cav - 6 * Hd * l**2 / H**3) / l
        return 2 * (self.p_cav * 0.5 + A * l**2 / 2 + 2 * Hd / H**3 * l**3)

    def solve(self, n: int, steps: int, t_end: float = 2 * math.pi):
        """Backward-Euler JFO steps on a strip of ``n`` cells: ``(t, c, load, mass_balance)`` per step."""
        from .film.thickness import UniformFilm
        from .film.finite_volume import solve_jfo
        from .geometry.meshing import strip_mesh

        mesh = strip_mesh(n, rows=1)
        width = float(np.ptp(mesh.mesh.p[1]))
        res = solve_jfo(mesh, UniformFilm(float(self.h(0.0))), wedge=0.0, cavitation_pressure=self.p_cav)
        dt = t_end / steps
        out = np.zeros((4, steps))
        for k in range(1, steps + 1):
            t = k * dt
            res = solve_jfo(mesh, UniformFilm(float(self.h(t))), wedge=0.0, cavitation_pressure=self.p_cav,
                            dt=dt, previous=res, warm_start=res)
            out[:, k - 1] = t, res.cavitated_fraction / 2, res.integral / width, res.mass_balance
        return out


#: Validation checks by name.
# -- sliders: films with tapers and steps ------------------------------------------------

def film_steps(lengths, films) -> tuple[float, np.ndarray, float]:
    """The exact 1-D slider with a piecewise-constant film (see the module docstring).

    Parameters
    ----------
    lengths, films : sequence of float
        Length [-] and film [c] of each land, in the sliding direction.

    Returns
    -------
    flow : float
        ``q`` per unit width [omega R0^2 c / R0] (the Couette part ``h/2`` included).
    pressures : ndarray
        ``p`` at the land boundaries, the ends included (zero there).
    load : float
        ``int p dx`` per unit width.
    """
    L = np.asarray(lengths, float)
    h = np.asarray(films, float)
    if L.shape != h.shape or L.size < 1 or np.any(L <= 0) or np.any(h <= 0):
        raise ValueError("lengths and films must be positive and of one length")
    q = float(np.sum(6 * L / h**2) / np.sum(12 * L / h**3))
    slopes = 12 * (h / 2 - q) / h**3
    pressures = np.concatenate([[0.0], np.cumsum(slopes * L)])
    load = float(np.sum(0.5 * (pressures[1:] + pressures[:-1]) * L))
    return q, pressures, load


def stepped_slider(*, h1: float, h2: float, a: float, length: float = 1.0) -> tuple[float, float]:
    """``(flow, load)`` per unit width of the infinitely wide Rayleigh step (:func:`film_steps`)."""
    q, _, load = film_steps([a, length - a], [h1, h2])
    return q, load


def inclined_slider_load(h_in: float, h_out: float, length: float = 1.0) -> float:
    """Load per unit width of the infinitely wide inclined slider, ``h`` linear from ``h_in`` to ``h_out``."""
    K = h_in / h_out - 1.0
    return 6.0 / K**2 * (math.log1p(K) - 2 * K / (2 + K)) * length**2 / h_out**2


def rayleigh_step_load(h1: float, h2: float, a: float, length: float = 1.0, width: float | None = None,
                       terms: int = 4001) -> float:
    """Load of the Rayleigh step: infinitely wide (``width=None``, per unit width) or of finite ``width``.

    The finite width is the Fourier series of the module docstring, summed over
    ``terms`` odd harmonics (the terms fall like ``n^-3``: 4001 leave a relative
    tail below 1e-8).
    """
    if width is None:
        return stepped_slider(h1=h1, h2=h2, a=a, length=length)[1]
    n = np.arange(1, 2 * terms, 2, dtype=float)
    k = n * math.pi / width
    P = 24.0 * (h1 - h2) / (n * math.pi * k * (h1**3 / np.tanh(k * a) + h2**3 / np.tanh(k * (length - a))))
    return float(np.sum(P * 2.0 / k**2 * (np.tanh(k * a / 2) + np.tanh(k * (length - a) / 2))))


def rayleigh_step(quick: bool = False) -> list[Check]:
    """The finite-width Rayleigh step on the Galerkin path (a step film, P2) against its Fourier series."""
    from .film.thickness import ProfileFilm
    from .geometry.meshing import grid_mesh
    from .geometry.surface import Surface
    from .reynolds import solve_reynolds

    h1, h2, a, width = 1.866, 1.0, 0.7, 1.0
    surface = Surface(arc=(0.0, 1.0), half_width=width / 2)
    film = ProfileFilm(((0.0, h1), (a, h1), (a, h2), (1.0, h2)))
    size = 0.05 if quick else 0.025
    res = solve_reynolds(grid_mesh(surface, size), film, formulation="direct", element="P2")
    exact = rayleigh_step_load(h1, h2, a, 1.0, width)
    return [Check(f"Rayleigh step load W, B = L (P2, size {size:g})", "Fourier series of the step (module docstring)",
                  res.integral, exact, 1e-5)]


CHECKS: Mapping[str, Callable[[bool], list[Check]]] = MappingProxyType({
    "annular_pad": annular_pad,
    "fed_recess_pad": fed_recess_pad,
    "short_bearing": short_bearing,
    "raimondi_boyd": raimondi_boyd,
    "jfo_pocket_slider": jfo_pocket_slider,
    "rayleigh_step": rayleigh_step,
})


def run_checks(quick: bool = False, names=None) -> list[Check]:
    """Run the named checks (default: all) and return their rows."""
    names = list(CHECKS) if names is None else list(names)
    for name in names:
        if name not in CHECKS:
            raise ValueError(f"unknown check {name!r}; allowed: {', '.join(CHECKS)}")
    return [row for name in names for row in CHECKS[name](quick)]
