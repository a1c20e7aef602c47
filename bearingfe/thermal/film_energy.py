r"""Level 2: the film's mean temperature as a field, coupled to a Reynolds equation whose viscosity varies over the film.

A plane pad (or a full journal bearing unwrapped from its line of largest film,
:func:`journal_pad`) of length ``L`` (along the sliding direction ``x``) and width ``B`` (``y``), film
thickness ``h(x, y)`` [m], runner sliding at ``U`` [m/s] in ``+x``; SI throughout. On the same P1
triangle mesh:

- Reynolds with the viscosity of the local temperature ``mu(T)``:
  ``div(h^3/(12 mu) grad p) = U/2 dh/dx``, weakly
  ``int h^3/(12 mu) grad p . grad v = int U h/2 dv/dx`` (the package's weak forms
  :func:`bearingfe.film.forms.weighted_laplace` and :func:`~bearingfe.film.forms.gradient_load`, the
  coefficient a field at the quadrature points), ``p = 0`` on the pressure edges: the two ends
  ``x = 0, L`` and, with ``sides="ambient"``, the sides; with ``sides="closed"`` the sides carry no
  flow (the infinitely wide pad). Swift-Stieber: ``p >= 0`` with a non-negative residual where
  ``p = 0`` (the primal-dual active set method, ``cavitation="reynolds"``); the heat of a ruptured
  zone is then convected by the full-film flux, the Couette flow ``U h/2``. With ``cavitation="jfo"``
  the film conserves mass (JFO in Elrod-Adams form, as :mod:`bearingfe.film.finite_volume`: Galerkin
  Poiseuille of ``h^3/(12 mu)``, median-dual upwind Couette flux ``U theta h/2``, ``p >= 0``,
  ``0 <= theta <= 1``, ``p (1 - theta) = 0``), and in a cavity only the liquid's share of the gap
  carries heat and dissipates: the flux is the liquid's ``U theta h/2`` and the Couette dissipation
  ``theta mu U^2/h`` (the shear ``theta mu U/h``); where ``theta = 1`` these are the full film's.
- The mean film flux ``q = -h^3/(12 mu) grad p + U h/2 e_x`` [m^2/s].
- The energy equation of the film's mean temperature, convection and viscous heating, optionally a
  heat-transfer coefficient ``alpha`` [W/(m^2 K)] to walls at ``T_w`` (both walls together):
  ``rho c_p q . grad T = Phi - alpha (T - T_w)``, ``Phi = mu U^2/h + h^3/(12 mu) |grad p|^2`` [W/m^2];
  no conduction within the film (pure convection), so Galerkin alone would oscillate: streamline
  upwind Petrov-Galerkin (SUPG), test functions ``v + tau q . grad v`` with
  ``tau = ((2|q|/h_e)^2 + (alpha/(rho c_p))^2)^(-1/2)`` and ``h_e = 2|q| / sum_a |q . grad phi_a|``
  (the element's length along the flow). The supply temperature ``T_s`` enters weakly on the inflow
  boundary (``q . n < 0``): ``int rho c_p |q . n| (T - T_s) v ds``, so no boundary node is forced.
- Coupling: fixed point, ``T_(k+1) = T_k + omega (T_new - T_k)``, until the largest change is
  below ``tolerance`` [K].

Energy balance (exact for the discrete equations, to solver round-off). The energy equation tested
with ``v = 1`` (the SUPG terms vanish: ``grad 1 = 0``) and Reynolds' consistent nodal boundary
flows ``r_i = int q . grad phi_i`` (zero at every node Reynolds solves for) give

``int Phi = rho c_p sum_i r_i (T_i - T_s) + rho c_p int_in |q . n| (T - T_s) ds + int alpha (T - T_w)``:

the dissipated power equals the heat carried out by the flows (relative to the supply; the second
term is the inflow's share, which vanishes as the mesh is refined) plus the heat conducted to the
walls. :class:`FilmEnergy` reports each term and the balance's residual. ``rho`` and ``c_p`` are
taken at the supply temperature.

With ``cavitation="jfo"`` the energy equation is discretized on the cells that conserve the oil (the
median-dual cells of the JFO): each cell's heat flow to a neighbour is the oil flow between them
(Poiseuille ``K_ij (p_j - p_i)`` plus the upwind Couette flux of the dual segments) times the upwind
temperature, the dissipation and wall heat lumped on the cells, and the oil entering at a boundary
node at its inlet temperature. The matrix is an M-matrix (no temperature below the coldest inlet)
and the balance ``int Phi = rho c_p (sum_out r_i (T_i - T_s) - sum_in |r_i| (T_in,i - T_s)) +
conducted`` holds to round-off because the JFO's nodal flows ``r_i`` vanish inside the film to its
solver's tolerance; it is first-order upwind (more numerical diffusion than SUPG: on a film without
cavity the two discretizations differ by a few per cent of the rise, measured in the tests).

Hot-oil carry-over (``carry_over = lambda``): the oil entering the leading edge ``x = 0`` is the mix
of fresh oil and ``lambda`` of the trailing edge's outflow at its flow-weighted temperature
(:func:`bearingfe.thermal.heat_balance.mixed_inlet`), updated in the same fixed point; the other
inflows (sides) enter at ``T_s``. The balance then counts the heat that leaves the film net of what
re-enters.

With a :class:`~bearingfe.thermal.lubricant.ConstantViscosity` the viscosity field is uniform and
the pressure is the isoviscous solution of the same forms (the coefficient ``h^3/(12 mu)``); the
Reynolds solvers of the rest of the package (compiled operators, journal and pump paths) are not
touched by this module.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
import scipy.sparse as sp
import skfem
from skfem import Basis, BilinearForm, ElementTriP1, FacetBasis, LinearForm, MeshTri
from skfem.helpers import dot, grad

from ..core.linalg import factorize_splu
from ..core.schema import Range, in_range, nonnegative, positive
from ..film.finite_volume import JFOError, active_set, FVSystem, FVUnknowns, median_dual
from ..film.forms import dissipation, film_flux, gradient_load, load, shear, weighted_laplace
from .heat_balance import HeatBalance, ThermalError, film_temperatures, fixed_point, mixed_inlet
from .lubricant import ConstantViscosity, Lubricant

__all__ = ["Pad", "FilmEnergy", "PadLevel1", "SliderReference", "journal_pad", "pad_mesh", "film_energy", "pad_level1",
           "slider_reference", "SIDES", "CAVITATION"]

#: Pressure conditions on the pad's sides ``y = 0, B``: ambient (``p = 0``) or closed (no flow).
SIDES = ("ambient", "closed")
#: Cavitation models of :func:`film_energy` (names as in :data:`bearingfe.cavitation.MODELS`): ``"reynolds"``
#: (Swift-Stieber, ``p >= 0``; the ruptured film stays full) and ``"jfo"`` (mass-conserving, with the fill
#: fraction ``theta``: only the liquid's share of a cavitated gap carries heat and dissipates).
CAVITATION = ("reynolds", "jfo")


@dataclass(frozen=True)
class Pad:
    """A plane pad under a sliding runner (SI).

    Parameters
    ----------
    length : float
        ``L`` along the sliding direction [m], > 0.
    width : float
        ``B`` across it [m], > 0.
    thickness : callable
        ``h(x, y)`` [m], vectorised over arrays of ``x``, ``y`` [m]; > 0 over the pad.
    speed : float
        Runner speed ``U`` [m/s], > 0, towards ``+x`` (``x = 0`` is the leading edge).
    sides : str
        One of :data:`SIDES`.
    """

    length: float
    width: float
    thickness: Callable[[np.ndarray, np.ndarray], np.ndarray]
    speed: float
    sides: str = "ambient"

    def __post_init__(self) -> None:
        object.__setattr__(self, "length", positive("Pad.length", self.length, "m"))
        object.__setattr__(self, "width", positive("Pad.width", self.width, "m"))
        object.__setattr__(self, "speed", positive("Pad.speed", self.speed, "m/s"))
        if not callable(self.thickness):
            raise ValueError(f"Pad.thickness must be a callable h(x, y) [m], got {self.thickness!r}")
        if self.sides not in SIDES:
            raise ValueError(f"Pad.sides must be one of {SIDES}, got {self.sides!r}")

    @classmethod
    def inclined(cls, length: float, width: float, outlet_film: float, ratio: float, speed: float,
                 sides: str = "ambient") -> "Pad":
        """The inclined slider: ``h = h_o (1 + K (1 - x/L))`` with outlet film ``h_o`` [m] and
        convergence ratio ``K = h_i/h_o - 1`` (``ratio``, > 0)."""
        h0 = positive("outlet_film", outlet_film, "m")
        k = positive("ratio", ratio)
        L = positive("length", length, "m")
        return cls(length, width, lambda x, y: h0 * (1.0 + k * (1.0 - np.asarray(x) / L)) + 0.0 * np.asarray(y),
                   speed, sides)


def journal_pad(radius: float, length: float, clearance: float, eccentricity_ratio: float, omega: float) -> Pad:
    """A full 360-degree journal bearing unwrapped from its line of largest film (the Raimondi-Boyd bearing of
    :func:`bearingfe.bearings.journal.performance`): ``x = R phi`` in ``[0, 2 pi R]``, ``y`` along the axis,
    ``h = c (1 + eps cos(x/R))``, the journal's surface at ``U = omega R``, ambient pressure on all edges (oil
    fed at the line of largest film at the supply temperature: no hot-oil carry-over).

    Parameters
    ----------
    radius, length, clearance : float
        ``R``, ``L``, ``c`` [m], > 0.
    eccentricity_ratio : float
        ``eps`` in [0, 1).
    omega : float
        Shaft speed [rad/s], > 0.
    """
    R = positive("radius", radius, "m")
    c = positive("clearance", clearance, "m")
    eps = in_range("eccentricity_ratio", eccentricity_ratio, Range(0.0, 1.0, hi_open=True))
    U = positive("omega", omega, "rad/s") * R
    return Pad(2.0 * np.pi * R, length, lambda x, y: c * (1.0 + eps * np.cos(np.asarray(x) / R)) + 0.0 * np.asarray(y),
               U, "ambient")


def pad_mesh(pad: Pad, nx: int, ny: int) -> MeshTri:
    """A structured triangle mesh of the pad, ``nx`` by ``ny`` cells (each cut in two) [m]."""
    for name, n in (("nx", nx), ("ny", ny)):
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise ValueError(f"{name} must be an integer >= 1, got {n!r}")
    return MeshTri.init_tensor(np.linspace(0.0, pad.length, nx + 1), np.linspace(0.0, pad.width, ny + 1))


@dataclass(frozen=True)
class FilmEnergy:
    """A pad's film at the fixed point of pressure and temperature (level 2, SI).

    Attributes
    ----------
    mesh : skfem.MeshTri
        The film's mesh [m].
    pressure, temperature : ndarray
        Nodal pressure [Pa] and mean film temperature [K].
    viscosity : ndarray
        ``mu(T)`` at the nodes [Pa s].
    load : float
        ``int p`` [N].
    friction : float
        Shear force on the runner ``int (mu U/h + h/2 dp/dx)`` [N].
    power : float
        Dissipated power ``int Phi`` [W].
    friction_power : float
        ``U`` times ``friction`` [W]; equals ``power`` for the discrete Reynolds solution (its weak
        form tested with the pressure itself; with JFO, whose Couette flux is finite-volume, to the
        discretization).
    inflow : float
        Oil entering the film [m^3/s] (the negative consistent boundary flows).
    convected : float
        Heat carried out by the boundary flows, ``rho c_p sum r_i (T_i - T_s)`` [W] (with JFO the
        outflows at their cells' temperatures, the inflows at their inlet temperatures), net of the
        carried-over heat that re-enters.
    inflow_heat : float
        The weak inlet condition's share, ``rho c_p int_in |q.n| (T - T_in)`` [W] (-> 0 with the mesh;
        0 with JFO, whose inlet is nodal).
    conducted : float
        Heat to the walls, ``int alpha (T - T_w)`` [W] (lumped on the cells with JFO).
    balance_residual : float
        ``|power - convected - inflow_heat - conducted| / power`` [-].
    mean_temperature, max_temperature, outlet_temperature : float
        Area mean, largest, and flow-weighted mean of the outflow [K].
    density, specific_heat : float
        ``rho``, ``c_p`` at the supply temperature [kg/m^3, J/(kg K)].
    iterations : int
        Fixed-point iterations.
    change : float
        Last largest temperature change [K].
    cavitated : int
        Nodes held at zero pressure by the cavitation condition.
    fill : ndarray
        The fill fraction ``theta`` at the nodes [-] (1 everywhere with ``cavitation="reynolds"``).
    inlet_temperature : float
        Of the oil entering the leading edge ``x = 0`` [K]: the supply temperature, or its mix with
        the carried-over oil.
    carried_flow : float
        ``lambda Q_t``, the trailing edge's outflow carried over to the leading edge [m^3/s].
    trailing_temperature : float
        Flow-weighted mean temperature of the outflow through the trailing edge ``x = L`` [K].
    """

    mesh: MeshTri
    pressure: np.ndarray
    temperature: np.ndarray
    viscosity: np.ndarray
    load: float
    friction: float
    power: float
    friction_power: float
    inflow: float
    convected: float
    inflow_heat: float
    conducted: float
    balance_residual: float
    mean_temperature: float
    max_temperature: float
    outlet_temperature: float
    density: float
    specific_heat: float
    iterations: int
    change: float
    cavitated: int
    fill: np.ndarray
    inlet_temperature: float
    carried_flow: float
    trailing_temperature: float


def _viscosity(lubricant: Lubricant, t: np.ndarray) -> np.ndarray:
    """``mu(T)`` [Pa s] pointwise (:meth:`~bearingfe.thermal.lubricant.Lubricant.viscosity_field`)."""
    return lubricant.viscosity_field(t)


@BilinearForm
def _energy(u, v, w):
    """``int (q . grad u + beta u) (v + tau q . grad v)`` (SUPG)."""
    qgu = w.q0 * u.grad[0] + w.q1 * u.grad[1]
    qgv = w.q0 * v.grad[0] + w.q1 * v.grad[1]
    return (qgu + w.beta * u) * (v + w.tau * qgv)


@LinearForm
def _energy_load(v, w):
    """``int s (v + tau q . grad v)`` with ``s = Phi/(rho c_p) + beta T_w``."""
    return w.s * (v + w.tau * (w.q0 * v.grad[0] + w.q1 * v.grad[1]))


@BilinearForm
def _inlet(u, v, w):
    return w.a * u * v


@LinearForm
def _inlet_load(v, w):
    return w.a * w.t * v


class _Film:
    """The mesh's bases, quadrature fields of ``h`` and the pressure boundary, built once."""

    def __init__(self, pad: Pad, mesh: MeshTri):
        self.pad, self.mesh = pad, mesh
        if not isinstance(mesh, MeshTri):
            raise ValueError(f"mesh must be a scikit-fem MeshTri of the pad (pad_mesh), got {type(mesh).__name__}")
        lo, hi = mesh.p.min(axis=1), mesh.p.max(axis=1)
        if not np.allclose([lo[0], lo[1], hi[0], hi[1]], [0.0, 0.0, pad.length, pad.width], rtol=0,
                           atol=1e-9 * max(pad.length, pad.width)):
            raise ValueError(f"mesh must cover the pad [0, {pad.length:g}] x [0, {pad.width:g}] m, got "
                             f"[{lo[0]:g}, {hi[0]:g}] x [{lo[1]:g}, {hi[1]:g}] m")
        self.basis = Basis(mesh, ElementTriP1())
        self.facets = FacetBasis(mesh, ElementTriP1(), facets=mesh.boundary_facets())
        x = np.asarray(self.basis.global_coordinates())
        self.h = np.asarray(pad.thickness(x[0], x[1]), dtype=float) * np.ones(x[0].shape)
        xf = np.asarray(self.facets.global_coordinates())
        self.hf = np.asarray(pad.thickness(xf[0], xf[1]), dtype=float) * np.ones(xf[0].shape)
        if not (np.all(np.isfinite(self.h)) and self.h.min() > 0 and np.all(np.isfinite(self.hf))
                and self.hf.min() > 0):
            raise ValueError("Pad.thickness must be finite and > 0 over the pad")
        L, B = pad.length, pad.width
        tol = 1e-9 * max(L, B)
        p = mesh.p
        ends = (np.abs(p[0]) < tol) | (np.abs(p[0] - L) < tol)
        sides = (np.abs(p[1]) < tol) | (np.abs(p[1] - B) < tol)
        self.dirichlet = np.flatnonzero(ends | sides) if pad.sides == "ambient" else np.flatnonzero(ends)
        self.leading, self.trailing = np.flatnonzero(np.abs(p[0]) < tol), np.flatnonzero(np.abs(p[0] - L) < tol)
        U = pad.speed
        self.couette = gradient_load.assemble(self.basis, f0=0.5 * U * self.h, f1=np.zeros_like(self.h))
        self.area = float(self.basis.dx.sum())
        self.cells = load.assemble(self.basis, f=np.ones_like(self.h))  # median-dual cell areas int phi_i [m^2]

    def pressure(self, mu_q: np.ndarray) -> tuple[np.ndarray, int]:
        """Reynolds with ``mu`` at the quadrature points; Swift-Stieber (``p >= 0``, the residual ``A p - b >= 0``
        where ``p = 0``) by the primal-dual active set method, started from the unconstrained solution."""
        A = weighted_laplace.assemble(self.basis, c=self.h**3 / (12.0 * mu_q)).tocsr()
        b = self.couette
        n = self.basis.N
        ambient = np.zeros(n, dtype=bool)
        ambient[self.dirichlet] = True
        active = np.zeros(n, dtype=bool)
        for _ in range(n + 1):
            fixed = np.flatnonzero(ambient | active)
            p = np.zeros(n)
            free = np.setdiff1d(np.arange(n), fixed)
            if free.size:
                p[free] = skfem.solve(*skfem.condense(A, b, D=fixed, x=p))[free]
            multiplier = np.where(active, A @ p - b, 0.0)
            scale = max(np.abs(p).max(), 1e-300)
            new = ~ambient & ((p < -1e-12 * scale) | (active & (multiplier > 0)))
            if np.array_equal(new, active):
                return p, int(active.sum())
            active = new
        raise ThermalError("the Swift-Stieber active set did not settle")  # pragma: no cover

    def _couette_operator(self) -> sp.csr_matrix:
        """The Couette outflow of the fill fraction per node, ``C theta``: median-dual finite volumes,
        ``U/2 h theta_upwind n_x`` through each dual segment (``h`` at its midpoint), as the package's JFO
        (:func:`bearingfe.film.finite_volume.solve_jfo`, ``couette="median"``). Its columns sum to zero:
        every flux that leaves a cell enters a neighbour (mass is conserved)."""
        if not hasattr(self, "_couette"):
            U, n = self.pad.speed, self.basis.N
            d = median_dual(self.mesh)
            hm = np.asarray(self.pad.thickness(d.midpoint[0], d.midpoint[1]), float) * np.ones(d.i.size)
            f = 0.5 * U * hm * d.normal[0]
            up = np.where(f > 0, d.i, d.j)
            self._segments = (d.i, d.j, f, up)
            self._couette = sp.coo_matrix((np.concatenate([f, -f]), (np.concatenate([d.i, d.j]),
                                                                     np.concatenate([up, up]))), shape=(n, n)).tocsr()
        return self._couette

    def jfo(self, mu_q: np.ndarray, cavity: np.ndarray | None) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                                         np.ndarray]:
        """Reynolds with mass-conserving (JFO, Elrod-Adams) cavitation and ``mu`` at the quadrature points:
        ``K P + C theta = 0`` at every free node with ``P >= 0``, ``0 <= theta <= 1``, ``P (1 - theta) = 0``
        (``K`` the Galerkin Poiseuille stiffness of ``h^3/(12 mu)``, ``C`` of :meth:`_couette_operator`), by
        the primal-dual active set of :mod:`bearingfe.film.finite_volume`, warm-started on ``cavity`` (a mask
        of the free nodes). Returns ``p`` [Pa], ``theta`` [-], the cavity mask and the consistent nodal
        flows out through the boundary, ``-(K p + C theta)`` [m^3/s] (what the cell's interior outflow
        leaves for the boundary to supply, with the sign of ``int q . grad phi_i``; zero at free nodes to
        the solver's tolerance)."""
        K = weighted_laplace.assemble(self.basis, c=self.h**3 / (12.0 * mu_q)).tocsr()
        C = self._couette_operator()
        n = self.basis.N
        free = np.setdiff1d(np.arange(n), self.dirichlet)
        S = sp.csr_matrix((np.ones(free.size), (free, np.arange(free.size))), shape=(n, free.size))
        zeros = np.zeros(n)
        system = FVSystem(K=K, C=C, storage=zeros, source=zeros, area=zeros, h_q=self.h, hdot_q=0 * self.h,
                         inv_h_q=1.0 / self.h)
        start = np.zeros(free.size, bool) if cavity is None else cavity
        try:
            sol = active_set(system, FVUnknowns(S=S, rep=free, fixed=self.dirichlet), zeros, 0.0, start,
                              factorize_splu, 1e-10, 200)
        except JFOError as exc:
            raise ThermalError(f"the JFO cavitation of the film did not settle: {exc}") from exc
        p, theta = S @ sol.p, np.ones(n)
        theta[free] = sol.theta
        # the trailing edge feeds nothing downstream: its nodes carry the oil that reaches them, the inflow-weighted
        # theta of their upwind neighbours (not the full film of a fixed node), which leaves the free nodes'
        # equations as they are (their rows hold no trailing-edge column)
        W = -C[self.trailing]
        W.data = np.maximum(W.data, 0.0)
        theta[self.trailing] = (W @ theta) / (W @ np.ones(n))
        return p, theta, sol.cavity, -(K @ p + C @ theta), K

    def cell_flows(self, K: sp.csr_matrix, p: np.ndarray, theta: np.ndarray) -> sp.csr_matrix:
        """``M_ij``: the oil flow out of node ``i``'s median-dual cell into ``j``'s [m^3/s] (antisymmetric):
        Poiseuille ``K_ij (p_j - p_i)`` plus the upwind Couette flux of each dual segment; its row sums are
        ``K p + C theta``."""
        i, j, f, up = self._segments
        g = f * theta[up]
        Kc = K.tocoo()
        off = Kc.row != Kc.col
        r, c, k = Kc.row[off], Kc.col[off], Kc.data[off]
        n = self.basis.N
        return sp.coo_matrix((np.concatenate([k * (p[c] - p[r]), g, -g]), (np.concatenate([r, i, j]),
                              np.concatenate([c, j, i]))), shape=(n, n)).tocsr()

    def flux(self, p: np.ndarray, mu_q: np.ndarray, theta_q: np.ndarray | None = None):
        """``q`` (the liquid's, with the fill fraction ``theta_q`` at the quadrature points) and ``grad p``
        at the quadrature points."""
        dp = self.basis.interpolate(p).grad
        return film_flux(self.h, dp, self.pad.speed, viscosity=mu_q, fill=theta_q), dp


class _Anderson:
    """Anderson mixing of a fixed point ``x = G(x)`` (Walker and Ni, SIAM J. Numer. Anal. 49, 2011): the
    relaxed step ``x + omega f`` (``f = G(x) - x``) corrected by the least-squares combination of the last
    ``memory`` differences of iterates and residuals; ``memory = 0`` is the plain relaxed iteration."""

    def __init__(self, omega: float, memory: int):
        self.omega, self.memory = omega, memory
        self.last: tuple[np.ndarray, np.ndarray] | None = None
        self.dx: list[np.ndarray] = []
        self.df: list[np.ndarray] = []

    def step(self, x: np.ndarray, f: np.ndarray) -> np.ndarray:
        plain = x + self.omega * f
        if self.memory == 0:
            return plain
        if self.last is not None:
            self.dx = (self.dx + [x - self.last[0]])[-self.memory:]
            self.df = (self.df + [f - self.last[1]])[-self.memory:]
        self.last = (x.copy(), f.copy())
        if not self.dx:
            return plain
        dX, dF = np.column_stack(self.dx), np.column_stack(self.df)
        gamma = np.linalg.lstsq(dF, f, rcond=1e-12)[0]
        return plain - (dX + self.omega * dF) @ gamma


def film_energy(pad: Pad, mesh: MeshTri, lubricant: Lubricant, supply_temperature: float,
                wall_coefficient: float = 0.0, wall_temperature: float | None = None, relaxation: float = 1.0,
                tolerance: float = 1e-9, max_iterations: int = 200, memory: int = 3, cavitation: str = "reynolds",
                carry_over: float = 0.0) -> FilmEnergy:
    """The pad's pressure and mean film temperature at their fixed point (level 2).

    Parameters
    ----------
    pad : Pad
        Geometry, speed and side condition.
    mesh : skfem.MeshTri
        P1 triangle mesh of ``[0, L] x [0, B]`` [m] (:func:`pad_mesh`).
    lubricant : Lubricant
        The oil: ``mu(T)``; ``rho`` and ``c_p`` at the supply temperature.
    supply_temperature : float
        ``T_s`` of the fresh oil [K], > 0.
    wall_coefficient : float
        ``alpha`` [W/(m^2 K)], >= 0, to both walls together; 0: adiabatic.
    wall_temperature : float, optional
        ``T_w`` [K]; default the supply temperature.
    relaxation : float
        ``omega`` in (0, 1].
    memory : int
        Anderson acceleration of the fixed point over the last ``memory`` iterates (>= 0; 0: the plain
        relaxed iteration).
    tolerance : float
        Largest temperature change of the last iteration [K], > 0.
    max_iterations : int
        >= 1.
    cavitation : str
        One of :data:`CAVITATION`: ``"reynolds"`` (Swift-Stieber) or ``"jfo"`` (mass-conserving; the
        liquid's share of a cavitated gap carries the heat and dissipates).
    carry_over : float
        Hot-oil carry-over ``lambda`` [-] in [0, 1]: that fraction of the trailing edge's outflow
        (``x = L``) re-enters the leading edge (``x = 0``, the groove of :func:`journal_pad`) mixed with
        fresh oil (:func:`bearingfe.thermal.heat_balance.mixed_inlet`).

    Raises
    ------
    ThermalError
        No convergence in ``max_iterations`` (the message gives the last change), a cavitation active
        set that does not settle, or carried-over oil that alone exceeds the leading edge's inflow.
    """
    Ts = positive("supply_temperature", supply_temperature, "K")
    alpha = nonnegative("wall_coefficient", wall_coefficient, "W/(m^2 K)")
    Tw = Ts if wall_temperature is None else positive("wall_temperature", wall_temperature, "K")
    omega = in_range("relaxation", relaxation, Range(0.0, 1.0, lo_open=True))
    lam = in_range("carry_over", carry_over, Range(0.0, 1.0))
    if cavitation not in CAVITATION:
        raise ValueError(f"cavitation must be one of {CAVITATION}, got {cavitation!r}")
    if isinstance(memory, bool) or not isinstance(memory, int) or memory < 0:
        raise ValueError(f"memory must be an integer >= 0, got {memory!r}")
    mixing = _Anderson(omega, memory)
    tol = positive("tolerance", tolerance, "K")
    if isinstance(max_iterations, bool) or not isinstance(max_iterations, int) or max_iterations < 1:
        raise ValueError(f"max_iterations must be an integer >= 1, got {max_iterations!r}")
    f = _Film(pad, mesh)
    rho, cp = lubricant.density_at(Ts), lubricant.specific_heat_at(Ts)
    rc = rho * cp
    beta = alpha / rc
    U = pad.speed
    T = np.full(f.basis.N, Ts)
    grads = [f.basis.basis[a][0].grad for a in range(len(f.basis.basis))]
    normals = f.facets.normals
    leading = (np.abs(np.asarray(f.facets.global_coordinates()[0]).mean(axis=1)) < 1e-9 * pad.length)[:, None]
    jfo = cavitation == "jfo"
    cavity = None
    theta, theta_q = np.ones(f.basis.N), None
    change = np.inf
    for k in range(1, max_iterations + 1):
        mu_q = _viscosity(lubricant, np.asarray(f.basis.interpolate(T)))
        if jfo:
            p, theta, cavity, flows, K = f.jfo(mu_q, cavity)
            cavitated = int(cavity.sum())
            theta_q = np.asarray(f.basis.interpolate(theta))
        else:
            p, cavitated = f.pressure(mu_q)
        (q0, q1), dp = f.flux(p, mu_q, theta_q)
        phi = dissipation(f.h, dp, U, mu_q, fill=theta_q)
        if not jfo:
            spread = sum(np.abs(q0 * g[0] + q1 * g[1]) for g in grads)
            with np.errstate(divide="ignore", invalid="ignore"):
                inv = np.sqrt((spread) ** 2 + beta**2)  # (2|q|/h_e)^2 = spread^2
                tau = np.where(inv > 0, 1.0 / inv, 0.0)
        if jfo:
            # finite volumes on the cells that conserve the oil: each cell's heat flows are its oil flows times
            # the upwind temperature; the oil enters at the nodes that take it in, at the supply (or mixed)
            # temperature; dissipation and wall heat lumped on the cells
            t_in, carried, t_out = _carried_inlet(flows, T, f.leading, f.trailing, Ts, lam)
            t_b = np.where(np.isin(np.arange(f.basis.N), f.leading), t_in, Ts)
            a_in = np.maximum(-flows, 0.0)
            M = f.cell_flows(K, p, theta)
            out, into = M.maximum(0.0), (-M).maximum(0.0)
            A = (sp.diags(np.asarray(out.sum(axis=1)).ravel() + np.maximum(flows, 0.0) + beta * f.cells)
                 - into).tocsr()
            b = load.assemble(f.basis, f=phi) / rc + beta * Tw * f.cells + a_in * t_b
        else:
            A = _energy.assemble(f.basis, q0=q0, q1=q1, beta=beta, tau=tau)
            b = _energy_load.assemble(f.basis, s=phi / rc + beta * Tw, q0=q0, q1=q1, tau=tau)
            flows = gradient_load.assemble(f.basis, f0=q0, f1=q1)
            t_in, carried, t_out = _carried_inlet(flows, T, f.leading, f.trailing, Ts, lam)
            # inflow: q . n < 0 on boundary facets (q from the nodal pressure, viscosity at the facet points),
            # the inlet's temperature entering weakly
            muf = _viscosity(lubricant, np.asarray(f.facets.interpolate(T)))
            dpf = f.facets.interpolate(p).grad
            qf = film_flux(f.hf, dpf, U, viscosity=muf)
            qn = qf[0] * normals[0] + qf[1] * normals[1]
            a_in = np.maximum(-qn, 0.0)
            t_b = np.where(leading, t_in, Ts) * np.ones(qn.shape)
            A = A + _inlet.assemble(f.facets, a=a_in)
            b = b + _inlet_load.assemble(f.facets, a=a_in, t=t_b)
        T_new = sp.linalg.spsolve(A.tocsc(), b)
        if not np.all(np.isfinite(T_new)):
            raise ThermalError("the energy equation gave non-finite temperatures")
        f_k = T_new - T
        change = float(np.abs(f_k).max())
        if change <= tol:
            break
        T = mixing.step(T, f_k)
        if not (np.all(np.isfinite(T)) and T.min() > 0):  # an extrapolation too far: the plain step instead
            T, mixing = T_new - (1.0 - omega) * f_k, _Anderson(omega, memory)
    else:
        raise ThermalError(f"level 2 did not converge in {max_iterations} iterations (last change {change:.3g} K); "
                           f"lower the relaxation")
    # the balance of the last energy solve (its q, Phi, flows, inlet and T_new; T differs from T_new by < tolerance)
    T = T_new
    dx = f.basis.dx
    power = float((phi * dx).sum())
    if jfo:  # the nodal inlet: the oil enters at t_b exactly (no weak share), and leaves at its cell's temperature
        convected = rc * float(np.maximum(flows, 0.0) @ (T - Ts) - a_in @ (t_b - Ts))
        inflow_heat = 0.0
        outflow = float(np.maximum(flows, 0.0).sum())
        outlet = float(np.maximum(flows, 0.0) @ T) / outflow if outflow > 0 else float("nan")
    else:
        convected = rc * float(flows @ (T - Ts))
        tf = np.asarray(f.facets.interpolate(T))
        inflow_heat = rc * float((a_in * (tf - t_b) * f.facets.dx).sum())
        out = np.maximum(qn, 0.0)
        outflow = float((out * f.facets.dx).sum())
        outlet = float((out * tf * f.facets.dx).sum()) / outflow if outflow > 0 else float("nan")
    tq = np.asarray(f.basis.interpolate(T))
    conducted = alpha * float(f.cells @ (T - Tw)) if jfo else float((alpha * (tq - Tw) * dx).sum())
    residual = abs(power - convected - inflow_heat - conducted) / power
    tau_runner = shear(f.h, dp, U, viscosity=mu_q, fill=theta_q)
    friction = float((tau_runner * dx).sum())
    return FilmEnergy(mesh=mesh, pressure=p, temperature=T, viscosity=_viscosity(lubricant, T),
                      load=float((np.asarray(f.basis.interpolate(p)) * dx).sum()), friction=friction, power=power,
                      friction_power=U * friction, inflow=float(-flows[flows < 0].sum()), convected=convected,
                      inflow_heat=inflow_heat, conducted=conducted, balance_residual=residual,
                      mean_temperature=float((tq * dx).sum()) / f.area, max_temperature=float(T.max()),
                      outlet_temperature=outlet, density=rho, specific_heat=cp, iterations=k, change=change,
                      cavitated=cavitated, fill=theta, inlet_temperature=t_in, carried_flow=carried,
                      trailing_temperature=t_out)


def _carried_inlet(flows: np.ndarray, T: np.ndarray, leading: np.ndarray, trailing: np.ndarray, Ts: float,
                   lam: float) -> tuple[float, float, float]:
    """The leading edge's inlet temperature with carry-over: ``T_in`` [K] mixed from the fresh oil and
    ``lambda`` of the trailing edge's outflow ``Q_t`` [m^3/s] at its flow-weighted temperature ``T_t`` [K],
    from the consistent nodal boundary flows [m^3/s] and temperatures [K] of the leading and trailing
    nodes; returns ``T_in``, ``lambda Q_t``, ``T_t``."""
    out = np.maximum(flows[trailing], 0.0)
    q_t = float(out.sum())
    t_t = float(out @ T[trailing]) / q_t if q_t > 0 else Ts
    if lam == 0.0:
        return Ts, 0.0, t_t
    q_lead = float(np.maximum(-flows[leading], 0.0).sum())
    fresh = q_lead - lam * q_t
    if not fresh > 1e-9 * q_lead:  # (round-off of the flows aside)
        raise ThermalError(f"the carried-over oil ({lam:g} x {q_t:.4g} m^3/s of the trailing edge) is not less than "
                           f"the leading edge's inflow ({q_lead:.4g} m^3/s): no fresh oil enters; lower carry_over")
    return mixed_inlet(fresh, Ts, q_t, t_t, lam), lam * q_t, t_t


@dataclass(frozen=True)
class PadLevel1:
    """The pad at the fixed point of the level-1 balance (one effective temperature, SI).

    Attributes
    ----------
    temperature : float
        ``T_eff`` [K].
    viscosity : float
        ``mu(T_eff)`` [Pa s].
    pressure : ndarray
        The isoviscous nodal pressure at ``mu(T_eff)`` [Pa].
    load, power : float
        ``int p`` [N] and the dissipated power ``int Phi`` [W] of that film.
    leading_flow, side_flow : float
        Oil in through the leading edge and out through the sides [m^3/s].
    rise : float
        ``dT`` across the film [K].
    evaluations : int
        Isoviscous solves.
    """

    temperature: float
    viscosity: float
    pressure: np.ndarray
    load: float
    power: float
    leading_flow: float
    side_flow: float
    rise: float
    evaluations: int


def pad_level1(pad: Pad, mesh: MeshTri, lubricant: Lubricant, balance: HeatBalance) -> PadLevel1:
    """Level 1 on the pad: ``T_eff = T_in + k dT`` with ``dT`` from the whole film's power and flows
    (:func:`bearingfe.thermal.heat_balance.film_temperatures`: side flow leaves at ``T_in + dT/2``), at
    the fixed point of :func:`~bearingfe.thermal.heat_balance.fixed_point`; one isoviscous Reynolds
    solve of the same forms per trial temperature."""
    f = _Film(pad, mesh)
    U = pad.speed
    x, y = mesh.p
    tol = 1e-9 * max(pad.length, pad.width)
    lead = np.abs(x) < tol
    side = ((np.abs(y) < tol) | (np.abs(y - pad.width) < tol)) & ~lead & ~(np.abs(x - pad.length) < tol)
    dx = f.basis.dx

    class _State:
        def __init__(self, t: float):
            self.viscosity = mu = lubricant.viscosity(t)
            mu_q = np.full(f.h.shape, mu)
            self.pressure, _ = f.pressure(mu_q)
            (q0, q1), dp = f.flux(self.pressure, mu_q)
            self.power = float((dissipation(f.h, dp, U, mu_q) * dx).sum())
            r = gradient_load.assemble(f.basis, f0=q0, f1=q1)
            self.leading, self.side = float(-r[lead].sum()), float(max(r[side].sum(), 0.0))
            self.load = float((np.asarray(f.basis.interpolate(self.pressure)) * dx).sum())
            self.heat = film_temperatures(self.power, self.leading, self.side, lubricant.density_at(t),
                                          lubricant.specific_heat_at(t), balance)

    root, _, states = fixed_point(_State, balance)
    end = states[root]
    return PadLevel1(temperature=root, viscosity=end.viscosity, pressure=end.pressure, load=end.load,
                     power=end.power, leading_flow=end.leading, side_flow=end.side, rise=end.heat.rise,
                     evaluations=len(states))


@dataclass(frozen=True)
class SliderReference:
    """The infinitely wide adiabatic slider of viscosity ``mu(T)`` by ODE quadrature (SI, per unit width).

    Attributes
    ----------
    flow : float
        ``q`` [m^2/s], the film's flux per unit width.
    x : ndarray
        Abscissae [m] of the dense output.
    pressure, temperature : callable
        ``p(x)`` [Pa], ``T(x)`` [K].
    load : float
        ``int p dx`` [N/m].
    power : float
        ``int Phi dx`` [W/m].
    """

    flow: float
    x: np.ndarray
    pressure: Callable
    temperature: Callable
    load: float
    power: float


def slider_reference(length: float, thickness: Callable[[np.ndarray], np.ndarray], speed: float,
                     lubricant: Lubricant, supply_temperature: float, rtol: float = 1e-11) -> SliderReference:
    r"""The reference of level 2: an infinitely wide slider, adiabatic, viscosity ``mu(T)``.

    With no side flow the flux per unit width ``q = -h^3/(12 mu) p' + U h/2`` is constant, so
    ``p' = 12 mu(T) (U h/2 - q)/h^3`` and the energy equation ``rho c_p q T' = Phi`` with
    ``Phi = mu U^2/h + 12 mu (U h/2 - q)^2/h^3``; ``T(0) = T_s``, ``p(0) = p(L) = 0``. The unknown
    ``q`` is found by shooting (Brent on ``p(L; q) = 0``, ``q`` between ``U h(L)/2`` and ``U h(0)/2``
    for a converging film), each shot an adaptive Runge-Kutta integration (scipy ``solve_ivp``, DOP853)
    to ``rtol``. ``rho`` and ``c_p`` at the supply temperature, as in :func:`film_energy`.
    """
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    L = positive("length", length, "m")
    U = positive("speed", speed, "m/s")
    Ts = positive("supply_temperature", supply_temperature, "K")
    rc = lubricant.density_at(Ts) * lubricant.specific_heat_at(Ts)

    def rhs(x, y, q):
        h = float(thickness(x))
        mu = lubricant.viscosity(float(y[1]))
        g = U * h / 2.0 - q
        return [12.0 * mu * g / h**3, (mu * U**2 / h + 12.0 * mu * g * g / h**3) / (rc * q),
                mu * U**2 / h + 12.0 * mu * g * g / h**3, y[0]]

    def shot(q, dense=False):
        return solve_ivp(rhs, (0.0, L), [0.0, Ts, 0.0, 0.0], args=(q,), method="DOP853", rtol=rtol,
                         atol=1e-14, dense_output=dense)

    h0, h1 = float(thickness(0.0)), float(thickness(L))
    if not h0 > h1 > 0:
        raise ValueError("thickness must converge (h(0) > h(L) > 0) for the slider reference")
    q = brentq(lambda q: shot(q).y[0, -1], U * h1 / 2.0 * (1 + 1e-12), U * h0 / 2.0 * (1 - 1e-12),
               xtol=1e-16, rtol=1e-14)
    sol = shot(q, dense=True)
    return SliderReference(flow=q, x=sol.t, pressure=lambda x: sol.sol(x)[0], temperature=lambda x: sol.sol(x)[1],
                           load=float(sol.y[3, -1]), power=float(sol.y[2, -1]))
