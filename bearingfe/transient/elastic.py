r"""The plunger shoe on an elastic support: the squeeze of the deflection (pressure as a state), and the quasi-static option.

On an elastic support the film is ``h = h_rigid(gamma, delta) + w`` with
``w = C p`` (:mod:`bearingfe.elastic`), and the squeeze term of the Reynolds
equation contains the rate of the deflection::

    div(h^3 grad p) = 6 wedge dh/dphi + 12 (gamma' s_gamma + delta' s_delta + dw/dbeta),
    dw/dbeta = C dp/dbeta.

When the chamber pressure falls (decompression) the deflection springs back
and the film between the surfaces is squeezed: that squeeze pressure slows
the spring-back. Dropping ``dw/dbeta`` (:class:`QuasiStaticElastic`, the
model of :func:`bearingfe.simulate` with ``elastic=``) lets the film collapse
with the deflection; on the shipped pump the plain shoe's film then closes
just after the inner dead centre. :class:`ElasticSqueeze` (the model of
:func:`simulate_elastic`) keeps it: the pressure is a state variable.

Model
-----
The state is ``y = (gamma, delta, p_I)`` with ``p_I`` the pressure at the
interior dofs (pocket dofs at the chamber pressure ``p_s(beta)``, outline at
0). The weak form on the interior test functions is

    R(p, h) + S r + K p_I' + c_s p_s' = 0,
    R = int h^3 grad p . grad v - int 6 wedge h dv/dphi,   S = int 12 (s_gamma, s_delta) v,
    K = 12 M_I C_I (constant, factorized once),            c_s = 12 M_I (C_inlet 1 + pocket),

so ``p_I' = a - B r`` with ``a = -K^-1 (R + c_s p_s')`` and ``B = K^-1 S``. The
rates ``r = (gamma', delta')`` follow from the load balance
``g = L p + p_s F_pocket + load = 0`` (plunger inertia neglected, paper 004
eq. 13-14), differentiated once and stabilized (Baumgarte, rate ``kappa``):
``L_I p_I' + (L_inlet 1 + F_pocket) p_s' + load' = -kappa g``, a 2x2 system
for ``r``. No factorization of the Reynolds operator is needed at all; the
ODE is stiff (the fine pressure modes relax fast) and goes to scipy's BDF
(or LSODA/Radau) with the Jacobian analytic in the pressures.

Cost
----
A right side costs one product with the dense compliance, one solve with
the factors of ``K`` and sparse products with the quadrature points: no
assembly, no factorization (well under a millisecond at 300 dofs). The
integrator's error is measured on ``gamma``, ``delta`` and on the film
opening the pressures make (``deflection_atol``, in clearances), not on the
raw pressures: that and BDF take about 190 steps per revolution where LSODA
on the raw pressures took 850. The dense algebra runs on one BLAS thread
(threads of a few-hundred-row matrix only wait for each other on a busy
machine). The periodic start mixes the last revolutions (Anderson). A
dense compliance is refused beyond the ``compliance`` limit of
:mod:`bearingfe.core.limits` (4000 dofs; a low-rank form does not pay, its
singular values fall to 1 % of the largest only near the full rank:
``docs/elastic.md``).

Compliance held as its product
------------------------------
With a compliance held as its product only (``Compliance.matrix is None``:
the FFT half-space of :mod:`bearingfe.elastic.convolution`) nothing dense of
size ``n`` is formed, and there is no size cap:

* ``K^-1 b`` is GMRES on the products ``K x = 12 M_I C_I x`` (one compliance
  product each), warm-started from the last right side's, to
  :data:`K_TOLERANCE`, preconditioned on two levels: about
  :data:`COARSE_PATCHES` patches of interior dofs solved exactly (dense
  ``Z^T K Z``, from ``C_I Z`` computed once), the rest by a shifted film
  Laplacian (``K`` is of order -1, ``K^-1`` of order +1: :data:`K_LOCAL_SHIFTS`),
  which keeps the iterations per solve flat in the mesh size;
* the integrator is scipy's BDF with its Newton matrix ``I - c J`` solved
  matrix-free: the pressure block is ``K^-1 (K + c Jr)`` (``Jr = A_II + B_h
  C_I``), so its solve is GMRES on ``K + c Jr`` (right side ``K v``; no
  ``K^-1`` inside) with the same two-level preconditioner around the sparse
  factors of ``K``'s shifted-Laplacian model plus ``c A_II``, and the rates'
  rows and the ``(gamma, delta)`` columns are a rank-4 correction taken exactly (four such
  solves per Newton matrix, one per Newton iteration), to
  :data:`NEWTON_TOLERANCE`. Only ``method="BDF"`` runs this way.

The run is the dense path's up to these inner tolerances (the same steps;
measured 6e-8 in ``gamma``, ``delta`` and the film [c] on the dense map
held as a product, tests/transient/test_elastic.py); the cost is GMRES
iterations times compliance products (``stats``: ``krylov_iterations``,
``compliance_products``), measured against the dense path in the
``elastic_fft`` part of ``docs/benchmarks.md``.

Cavitation: the pressure may go negative (the source paper's model,
``cavitation="none"``); a complementarity condition on a state variable is
not covered here. The start is the quasi-static elastic equilibrium
(:func:`bearingfe.elastic.balance_load`) at the rigid steady state, or the
periodic state by Anderson-mixed revolutions.

Flows are the consistent boundary residuals of the flux
``q = -h^3/12 grad p + wedge h/2 e_phi`` with ``dh/dt`` including ``dw/dbeta``
(corner dofs shared equally between their edges).
"""

from __future__ import annotations

import math
import time
from typing import Callable, Sequence

import numpy as np
import scipy
import scipy.linalg as sla
import scipy.integrate as si
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..bearings.pump import EccentricPump
from ..core import DEFAULT_SOLVER
from ..core.linalg import dense_threads
from ..elastic import Compliance, ElasticError, balance_load, check_dense_size
from ..elastic.krylov import gmres
from ..film import CosineFilm, operators
from ..cavitation import CavitationError
from .base import FilmClosed, Model, NoEquilibrium, TrialRejected
from .driver import run_transient
from .fed import Fed
from .rigid import Rigid, balance_ratio, scipy_stepper, steady_state
from .settings import IMPLICIT_INTEGRATORS, Integration, positive
from .trajectory import LiftOffError, Trajectory

__all__ = ["simulate_elastic", "ElasticSqueeze", "QuasiStaticElastic", "FedQuasiStaticElastic", "BAUMGARTE"]

#: Default stabilization rate of the load balance [1/rad]: a load residual decays like exp(-kappa beta).
BAUMGARTE = 50.0


class QuasiStaticElastic(Rigid):
    """The quasi-static elastic support: the deflection follows the pressure (``dw/dt`` not in the squeeze term).

    At every state the film ``h_rigid + w`` and the rates are found together
    (:func:`bearingfe.elastic.balance_load`, the direct form): without
    cavitation by a chord Newton from the last answer whose dense Jacobian is
    kept over the right sides (``factorizations`` then counts its
    residuals), else by the damped Newton on the deflection; a compliance held
    as its product (no dense matrix, no size cap) always takes the latter,
    matrix-free (Newton-Krylov). The start is the
    rigid film's (steady or given); a state where no deflection carries the
    load stops the run (``"no-equilibrium"``).

    Parameters
    ----------
    pump : EccentricPump
    compliance : Compliance
        Of the support, on the run's mesh and element.
    cavitation : str
        A model of :data:`bearingfe.cavitation.MODELS` (not ``"jfo"``).
    formulation, solver
        Of the rigid film of the start.
    """

    name = "quasi-static elastic"

    def __init__(self, pump: EccentricPump, compliance: Compliance, *, cavitation: str = "none",
                 formulation: str = "pi", solver: str = DEFAULT_SOLVER) -> None:
        super().__init__(pump, compliance.mesh, formulation=formulation, element=compliance.element, solver=solver)
        self.compliance, self.cavitation = compliance, cavitation
        self._w = None  # last film opening of the support [c]
        self._reuse: dict = {}

    def smallest_film(self, beta: float, y: np.ndarray) -> float:
        """The rigid film opened by the last deflection found (the rigid one before the first)."""
        if self._w is None:
            return super().smallest_film(beta, y)
        d = self.compliance.basis_doflocs
        return float(np.min(CosineFilm(max(y[0], 0.0), y[1]).thickness(d[0], d[1]) + self._w))

    def balance(self, beta: float, y: np.ndarray, full: bool = True):
        """Rates and film opening on the elastic support (Newton on the deflection, warm-started)."""
        self.nfev += 1
        gamma, delta = float(y[0]), float(y[1])
        if not (math.isfinite(gamma) and math.isfinite(delta)) or gamma < 0 or self.smallest_film(beta, y) <= 0:
            raise FilmClosed((gamma, delta))
        pump = self.pump
        start = time.perf_counter()

        def solve(initial, reuse):
            return balance_load(self.mesh, CosineFilm(gamma, delta), self.compliance, pump.load_vector(beta),
                                wedge=float(pump.wedge(beta)), inlet_pressure=self.pocket_pressure(beta, y),
                                element=self.element, cavitation=self.cavitation, solver=self.solver,
                                initial=initial, reuse=reuse, full_result=full)

        try:
            try:
                found = solve(self._w, self._reuse)
            except (ElasticError, CavitationError) as exc:
                if self._w is None or self.cavitation == "none" or "h_min" in str(exc):
                    raise
                # under rupture the deflection's Newton from the last state's may pass through films whose rupture
                # set leaves the rates' force one direction only (the orifice pump's fed pocket on steel at
                # 194.5 deg): once more from the undeflected film, the Jacobian's factors dropped
                self._reuse.clear()
                found = solve(None, self._reuse)
        except ElasticError as exc:
            if "h_min" in str(exc):
                raise FilmClosed((gamma, delta)) from None
            raise NoEquilibrium(f"no equilibrium of the elastic film at beta = {beta:.4f} rad "
                                f"({math.degrees(beta) % 360:.1f} deg), gamma = {gamma:.4g}: {exc}") from None
        except CavitationError as exc:  # the cavitated rates' Newton from a trial state: retaken shorter
            raise TrialRejected(f"beta = {beta:.4f} rad ({math.degrees(beta) % 360:.1f} deg), gamma = {gamma:.4g}: "
                                f"the cavitated film on the elastic support has no balancing rates there ({exc})") \
                from None
        self.seconds += time.perf_counter() - start
        self.factorizations += found.iterations
        self.jacobians += found.jacobians
        self._w = found.deflection
        return found.rates, found.result

    def sample_state(self, beta: float, y: np.ndarray):
        rates, res = self.balance(beta, y)
        return rates, res, None, {"max_deflection": self.pump.scale.to_thickness(float(np.max(self._w)))}

    def statistics(self, output, runs: Sequence) -> dict[str, float]:
        """The rigid model's counters and ``jacobians`` of the coupled Newton."""
        return dict(super().statistics(output, runs), jacobians=self.jacobians)


class FedQuasiStaticElastic(QuasiStaticElastic):
    """The quasi-static elastic support with the shoe pocket fed through the plunger's restrictor.

    The state is ``(gamma, delta, p_r)`` as in :class:`~bearingfe.transient.fed.Fed`: at every state the
    deflected film is balanced with the pocket at ``p_r`` (:meth:`QuasiStaticElastic.balance`), and the pocket
    pressure follows ``V/K dp_r/dt = Q_restrictor - Q_film - dV/dt`` with ``Q_film`` the deflected film's outflow
    from the pocket (its result's ``inlet`` flow) and ``dV/dt`` the rigid squeeze over the pocket (the
    deflection's rate is left out of the pocket's gap as it is of the film's squeeze: quasi-static). The pocket
    needs its ``pocket_volume`` (balanced at each instant it would need the coupled film solved inside the
    pocket's balance). The start is :class:`~bearingfe.transient.fed.Fed`'s: the rigid steady state with the
    pocket balanced on it; the first steps take the pocket to the deflected film's balance. Under rupture, a
    state where the pocket and the elements around its contour push harder than the load even with the film
    ruptured everywhere else (:attr:`least`) has no balancing rates: the run ends ``"no-equilibrium"`` saying so
    (the shoe lifts off; on the shipped orifice pump on steel at 194.6 deg).

    Parameters
    ----------
    pump : EccentricPump
        With ``shoe_supply`` and its ``pocket_volume``.
    compliance, cavitation, formulation, solver
        As :class:`QuasiStaticElastic`.
    """

    name = "fed quasi-static elastic"
    periodic_methods = Fed.periodic_methods
    periodic_default = Fed.periodic_default

    def __init__(self, pump: EccentricPump, compliance: Compliance, *, cavitation: str = "none",
                 formulation: str = "pi", solver: str = DEFAULT_SOLVER) -> None:
        if pump.shoe_supply is not None and pump.shoe_supply.pocket_volume is None:
            raise ValueError(f"{pump.name!r}: a pocket fed through a restrictor on the elastic support needs "
                             "[shoe.supply] pocket_volume: its pressure is then a state; balanced at each instant it "
                             "would need the coupled film solved inside the pocket's balance")
        super().__init__(pump, compliance, cavitation=cavitation, formulation=formulation, solver=solver)
        self.fed = Fed(pump, compliance.mesh, formulation=formulation, element=compliance.element, solver=solver)
        ops = operators(compliance.mesh, compliance.element)
        self.moments = np.asarray(ops.pocket_moments, float)
        #: the force per unit pocket pressure of the film that holds no pressure outside its pocket's contour on this
        #: mesh (every free dof at 0): the pocket on its own area and the elements around it, where the pressure
        #: falls from the pocket's to 0 [-]. A film without tension pushes at least this hard.
        x = np.array(ops.basis.global_coordinates())
        from ..film.forms import load as load_form
        cos = load_form.assemble(ops.basis, f=np.cos(x[0]))
        sin = load_form.assemble(ops.basis, f=np.sin(x[0]))
        self.least = np.array([cos[ops.inlet].sum(), sin[ops.inlet].sum()]) + self.moments[1:]

    def pocket_pressure(self, beta: float, y: np.ndarray) -> float:
        return float(y[2])

    def initial_state(self, settings) -> tuple[float, np.ndarray]:
        return self.fed.initial_state(settings)

    def balance(self, beta: float, y: np.ndarray, full: bool = True):
        """:meth:`QuasiStaticElastic.balance`; where a film without tension has no balancing rates because the pocket
        and the elements around it alone push harder than the load (:attr:`least`), a
        :class:`~bearingfe.transient.base.NoEquilibrium` that says so (the shoe lifts off)."""
        try:
            return super().balance(beta, y, full)
        except TrialRejected as exc:
            if self.cavitation == "none":
                raise
            load = np.asarray(self.pump.load_vector(beta), float)
            size = max(float(np.linalg.norm(load)), 1e-300)
            least = float(y[2]) * float(self.least @ (-load / size))
            if least <= size:  # near it the balancing rates of separation grow without bound: say how near
                raise TrialRejected(f"{exc}; the pocket with the elements around its contour pushes with "
                                    f"{least / size:.4g} times the plunger load even with the film ruptured "
                                    "everywhere else (1: the shoe lifts off)") from None
            sc = self.pump.scale
            own = float(y[2]) * float(self.moments[1:] @ (-load / size))
            raise NoEquilibrium(
                f"no film without tension carries the load at beta = {beta:.4f} rad ({math.degrees(beta) % 360:.1f} "
                f"deg): the pocket at {sc.to_pressure(float(y[2])) / 1e6:.4g} MPa pushes with {least / size:.4g} times "
                f"the plunger load even with the film ruptured everywhere outside it ({own / size:.4g} on its own "
                "area, the rest on the elements around its contour, where the pressure falls to 0 over one element: "
                "a finer mesh there lowers it); the shoe lifts off") from None

    def _gap_rate(self, y: np.ndarray, rates: np.ndarray) -> float:
        """``dV/dbeta = int_pocket dh_rigid/dbeta dA`` [omega R0^2 c]."""
        _, mc, ms = self.moments
        c, s = math.cos(y[1]), math.sin(y[1])
        return float(rates[0] * (c * mc + s * ms) + rates[1] * y[0] * (c * ms - s * mc))

    def rates(self, beta: float, y: np.ndarray) -> np.ndarray:
        rates, result = self.balance(beta, y, full=True)
        p = float(y[2])
        imbalance = self.fed._law(beta).flow(p) - float(result.flows["inlet"]) - self._gap_rate(y, rates)
        return np.array([rates[0], rates[1], self.fed.compressibility * imbalance])

    def sample_state(self, beta: float, y: np.ndarray):
        """The elastic sample with the pocket pressure [-], the restrictor's flow and the pocket's gap rate [m^3/s]."""
        rates, res, sup, more = super().sample_state(beta, y)
        p, sc = float(y[2]), self.pump.scale
        return rates, res, sup, dict(more, inlet_pressure=p, flow_restrictor=sc.to_flow(self.fed._law(beta).flow(p)),
                                     flow_pocket_gap=sc.to_flow(self._gap_rate(y, rates)))


class ElasticSqueeze(Model):
    """The elastic support with the squeeze of the deflection: the interior pressures are states.

    Works on the compiled film-independent maps of the mesh
    (:mod:`bearingfe.film.compiled`): a state costs sparse products with the
    quadrature points, one product with the compliance and one product with
    the explicit ``K^-1`` (a dense compliance) or a preconditioned GMRES solve
    with ``K`` (a compliance held as its product: see the module notes); no
    assembly and no factorization of the film. Counters: ``nfev``
    and ``jacobians`` over the whole run (samples included), ``factorizations``
    (of the integrator's Newton matrix) and ``steps`` over every revolution
    integrated (the periodic start's included).

    Parameters
    ----------
    pump : EccentricPump
    compliance : Compliance
        Of the support, on the mesh of ``pump.surface``, with a finite modulus.
    kappa : float
        Baumgarte rate of the load balance [1/rad], > 0.
    deflection_atol : float
        Absolute tolerance on the film opening ``C p`` [c], > 0: the pressures
        are weighted by the largest row sum of the compliance.
    """

    name = "elastic"
    periodic_methods = ("anderson", "fixed-point", "one-revolution")
    periodic_default = "anderson"
    integrators = IMPLICIT_INTEGRATORS  # the pressure modes are stiff: no explicit Runge-Kutta
    starts = ("trajectory",)

    def __init__(self, pump: EccentricPump, compliance: Compliance, *, kappa: float = BAUMGARTE,
                 deflection_atol: float = 1e-5) -> None:
        self.pump, self.compliance = pump, compliance
        self.kappa, self.deflection_atol = positive("kappa", kappa), positive("deflection_atol", deflection_atol)
        self.element, self.dofs = compliance.element, float(compliance.n_dofs)
        self.nfev = self.jacobians = 0
        ops = operators(compliance.mesh, compliance.element)
        co = ops.compiled
        self.ops, self.basis, self.co = ops, ops.basis, co
        self.I, self.inlet = ops.interior, ops.inlet
        self.E, self.Gp, self.Gz = co.value, co.grad[0], co.grad[1]
        self.dx = co.dx
        self.src = co.sources  # (E^T dx)[I]
        self.src_cos, self.src_sin = self.src @ np.cos(co.x[0]), self.src @ np.sin(co.x[0])
        M = ops.mass.tocsr()[self.I]
        self.product = None if compliance.dense else _InteriorCompliance(compliance, ops)
        if self.product is None:
            C = np.asarray(compliance.matrix, float)
            self.C_I = np.ascontiguousarray(C[:, self.I])
            self.c_in = C[:, self.inlet].sum(axis=1) + compliance.pocket  # opening per unit pocket pressure
            # K^-1 explicitly (K is dense anyway): a state then costs one product with it
            self.Kinv = sla.inv(12.0 * (M @ self.C_I), check_finite=False)
            self.a_s = self.Kinv @ (12.0 * (M @ self.c_in))  # K^-1 c_s
            self.k_cos, self.k_sin = 12.0 * (self.Kinv @ self.src_cos), 12.0 * (self.Kinv @ self.src_sin)
            self.opening_weight = float(np.abs(compliance.matrix).sum(axis=1).max())
        else:  # products only: K^-1 by preconditioned GMRES (_InteriorCompliance)
            pc = self.product
            self.C_I = self.Kinv = None
            on_inlet = np.zeros(compliance.n_dofs)
            on_inlet[self.inlet] = 1.0
            self.c_in = compliance.apply(on_inlet) + compliance.pocket
            self.a_s = pc.solve_K(12.0 * (M @ self.c_in))
            self.k_cos, self.k_sin = 12.0 * pc.solve_K(self.src_cos), 12.0 * pc.solve_K(self.src_sin)
            # the largest opening of a unit pressure everywhere: the dense row sum of |C| for a positive kernel
            self.opening_weight = float(np.abs(compliance.apply(np.ones(compliance.n_dofs))).max())
        self.GpT, self.GzT = self.Gp.T.tocsr()[self.I], self.Gz.T.tocsr()[self.I]
        # the wedge source in conservative form, -int 6 wedge h dv/dphi (bearingfe.film.forms.couette_source):
        # the points -> interior map, and its derivative in the nodal opening w (h = h_rigid + E w)
        self.phi_src = co.phi_sources
        self.phi_src_E = (self.phi_src @ self.E).tocsr()
        self.cos_q, self.sin_q = np.cos(co.x[0]), np.sin(co.x[0])
        d = self.basis.doflocs
        self.cos_d, self.sin_d = np.cos(d[0]), np.sin(d[0])
        L = np.asarray(co.loads[:2] @ co.value)  # (2, n_dofs): int phi_j (cos, sin) dphi dz
        self.LI = L[:, self.I]
        self.L_in = L[:, self.inlet].sum(axis=1) + np.asarray(ops.pocket_moments[1:], float)
        self._drive = (None, None)

    # -- start -------------------------------------------------------------------------------------

    def initial_state(self, settings) -> tuple[float, np.ndarray]:
        """The last sample of a trajectory to continue, or the quasi-static elastic equilibrium at the
        rigid steady state of ``beta0``."""
        if isinstance(settings.start, Trajectory):
            return self._continued(settings.start)
        beta0 = float(settings.beta0)
        c = self.compliance
        gamma, delta = steady_state(self.pump, c.mesh, beta0, element=c.element)
        found = balance_load(c.mesh, CosineFilm(gamma, delta), c, self.pump.load_vector(beta0),
                             wedge=float(self.pump.wedge(beta0)), inlet_pressure=float(self.pump.inlet_pressure(beta0)),
                             element=c.element)
        return beta0, np.concatenate([[gamma, delta], found.result.pressure[self.I]])

    def _continued(self, traj: Trajectory) -> tuple[float, np.ndarray]:
        """Angle and state of the last sample of a :func:`simulate_elastic` run on the same compliance."""
        if traj.pressures is None or np.shape(traj.pressures)[-1] != self.compliance.n_dofs or not traj.beta.size:
            raise ValueError("start: a Trajectory must come from simulate_elastic on a compliance with "
                             f"{self.compliance.n_dofs} dofs (its pressures are the state)")
        if traj.status != "completed":
            raise ValueError(f"start: the Trajectory did not complete ({traj.message}); it has no state to continue")
        y = np.concatenate([[traj.gamma[-1], traj.delta[-1]], np.asarray(traj.pressures[-1], float)[self.I]])
        return float(traj.beta[-1]), y

    # -- the right side ----------------------------------------------------------------------------

    def drive(self, beta: float) -> tuple:
        """Pocket pressure, its rate, load, its rate and wedge at ``beta`` (the last one kept)."""
        if self._drive[0] != beta:
            eps = 1e-6
            b = np.array([beta - eps, beta, beta + eps])
            ps, f = self.pump.inlet_pressure(b), self.pump.load(b)
            self._drive = (beta, (float(ps[1]), float(ps[2] - ps[0]) / (2 * eps), np.array([-float(f[1]), 0.0]),
                                  np.array([-float(f[2] - f[0]) / (2 * eps), 0.0]), float(self.pump.wedge(beta))))
        return self._drive[1]

    def pressure(self, beta: float, p_interior: np.ndarray) -> np.ndarray:
        """Nodal pressure [-]: the interior state, the pocket at the chamber pressure, the outline at 0."""
        p = np.zeros(self.compliance.n_dofs)
        p[self.inlet] = self.pump.inlet_pressure(beta)
        p[self.I] = p_interior
        return p

    def _films(self, beta: float, y: np.ndarray):
        """Opening ``w``, film at the quadrature points and at the dofs, and ``cos``, ``sin`` of ``phi - delta``."""
        gamma, delta = float(y[0]), float(y[1])
        ps = self.drive(beta)[0]
        w = self._open(y[2:]) + ps * self.c_in
        g = max(gamma, 0.0)
        cd, sd = math.cos(delta), math.sin(delta)
        cos_m = self.cos_q * cd + self.sin_q * sd  # cos(phi - delta) at the points
        sin_m = self.sin_q * cd - self.cos_q * sd
        h = 1.0 + g * cos_m + self.E @ w
        h_dofs = 1.0 + g * (self.cos_d * cd + self.sin_d * sd) + w
        return w, h, h_dofs, cos_m, sin_m

    def smallest_film(self, beta: float, y: np.ndarray) -> float:
        """Smallest deflected film at the quadrature points and the dofs [c]."""
        _, h, h_dofs, _, _ = self._films(beta, y)
        return float(min(h.min(), h_dofs.min()))

    def _rates(self, beta: float, y: np.ndarray):
        """``(gamma', delta')``, ``p_I'`` and the pieces of the film at state ``y``."""
        self.nfev += 1
        gamma, delta = float(y[0]), float(y[1])
        ps, dps, load, dload, wedge = self.drive(beta)
        pI = y[2:]
        p = np.zeros(self.compliance.n_dofs)
        p[self.inlet] = ps
        p[self.I] = pI
        w, h, h_dofs, cos_m, sin_m = self._films(beta, y)
        g = max(gamma, 0.0)
        cd, sd = math.cos(delta), math.sin(delta)
        if not (np.all(h > 0) and np.all(h_dofs > 0)):
            raise FilmClosed((gamma, delta))
        dh = -g * sin_m + self.Gp @ w
        gp, gz = self.Gp @ p, self.Gz @ p
        h3 = h**3 * self.dx
        R = self.GpT @ (h3 * gp) + self.GzT @ (h3 * gz) - 6.0 * wedge * (self.phi_src @ h)
        a = -self._solve_K(R) - dps * self.a_s
        B = np.column_stack([cd * self.k_cos + sd * self.k_sin, g * (cd * self.k_sin - sd * self.k_cos)])
        res = self.LI @ pI + ps * self.L_in + load
        rhs = self.LI @ a + self.kappa * res + self.L_in * dps + dload
        try:
            r = np.linalg.solve(self.LI @ B, rhs)
        except np.linalg.LinAlgError:
            raise NoEquilibrium(f"load balance singular at beta = {beta:.4f} rad "
                                f"({math.degrees(beta) % 360:.1f} deg), gamma = {gamma:.4g}") from None
        return r, a - B @ r, dict(p=p, w=w, h=h, dh=dh, h_dofs=h_dofs, wedge=wedge, dps=dps,
                                  shapes=(cos_m, g * sin_m), gp=gp, gz=gz, B=B)

    def _open(self, p_interior: np.ndarray) -> np.ndarray:
        """``C_I p_I``: the film opening [c] of the interior pressures."""
        return self.C_I @ p_interior if self.product is None else self.product.columns(p_interior)

    def _solve_K(self, R: np.ndarray) -> np.ndarray:
        """``K^-1 R``: one product with the explicit inverse, or GMRES on the products (warm: the last solution)."""
        if self.product is None:
            return self.Kinv @ R
        return self.product.solve_K(R, warm=True)

    def rates(self, beta: float, y: np.ndarray) -> np.ndarray:
        r, dp, _ = self._rates(beta, y)
        return np.concatenate([r, dp])

    def jacobian(self, beta: float, y: np.ndarray) -> np.ndarray:
        """``d(rhs)/dy``: analytic in the pressures, central differences in ``(gamma, delta)``.

        ``a = -K^-1 (R + c_s p_s')`` has ``da/dp_I = -K^-1 (A_II + B_h C_I)`` with
        ``B_h`` the film sensitivity of the residual
        (``int 3 h^2 u grad p . grad v - 6 wedge u dv/dphi``); ``r = G (L_I a + kappa g + ...)``
        with ``G = (L_I B)^-1`` gives ``dr/dp_I = G L_I (da/dp_I + kappa)``.
        """
        self.jacobians += 1
        if self.product is not None:
            return _SqueezeJacobian(self, beta, y)
        r, dp, st = self._rates(beta, y)
        n = y.size
        J = np.empty((n, n))
        h2 = 3.0 * st["h"] ** 2 * self.dx
        Bh = (self.GpT @ sp.diags(h2 * st["gp"]) + self.GzT @ sp.diags(h2 * st["gz"])) @ self.E \
            - 6.0 * st["wedge"] * self.phi_src_E
        A_II = self.co.condensed(self.co.matrix_data("direct", st["h"], None))
        Da = -(self.Kinv @ (A_II.toarray() + Bh @ self.C_I))
        B = st["B"]
        dr = np.linalg.solve(self.LI @ B, self.LI @ Da + self.kappa * self.LI)
        J[:2, 2:] = dr
        J[2:, 2:] = Da - B @ dr
        for k in range(2):
            e = 1e-7 * max(1.0, abs(y[k]))
            yp, ym = y.copy(), y.copy()
            yp[k] += e
            ym[k] -= e
            J[:, k] = (self.rates(beta, yp) - self.rates(beta, ym)) / (2 * e)
        return J

    # -- stepping and samples ----------------------------------------------------------------------

    def weights(self, y: np.ndarray) -> np.ndarray:
        """``gamma``, ``delta`` and the film opening the pressures make (the largest row sum of ``C``)."""
        return np.r_[1.0, 1.0, np.full(np.size(y) - 2, self.opening_weight)]

    def stepper(self, beta0, y0, angles, settings, first_step, max_step):
        atol = np.r_[settings.absolute_tolerance, settings.absolute_tolerance,
                     self.deflection_atol / self.weights(y0)[2:]]
        if self.product is not None:  # BDF with its Newton solves by GMRES (settings: BDF only)
            first_step = None if first_step is None else min(float(first_step), float(angles[-1]) - beta0)
            return _KrylovBDF(self.rates, beta0, np.asarray(y0, float), float(angles[-1]), rtol=settings.rtol,
                              atol=atol, max_step=settings.max_step if max_step is None else max_step,
                              first_step=first_step, jac=self.jacobian)
        return scipy_stepper(self.rates, beta0, y0, float(angles[-1]), settings, first_step, max_step, atol=atol,
                             jac=self.jacobian)

    def sample(self, beta: float, y: np.ndarray) -> dict[str, object]:
        """SI figures of one state: rates, smallest film, friction, flows, largest deflection, pressure."""
        r, dp, st = self._rates(beta, y)
        sc = self.pump.scale
        w, h = st["w"], st["h"]
        dw = self._open(dp) + self.c_in * st["dps"]
        hdot = r[0] * st["shapes"][0] + r[1] * st["shapes"][1] + self.E @ dw
        gp0, gp1 = st["gp"], st["gz"]
        friction = float(np.sum((st["wedge"] / h + 0.5 * h * gp0) * self.dx))
        q0 = (-h**3 / 12.0 * gp0 + 0.5 * st["wedge"] * h) * self.dx
        q1 = -h**3 / 12.0 * gp1 * self.dx
        res = self.Gp.T @ q0 + self.Gz.T @ q1 - self.E.T @ (hdot * self.dx)
        flows = {name: float(np.sum(res[d] * wt)) for name, (d, wt) in self.ops.flow_groups.items()}
        inlet = -flows.pop("inlet", 0.0)
        squeeze = float(np.sum(hdot * self.dx))
        side = flows.pop("side", 0.0)
        arc = sum(flows.values())
        return {"gamma_rate": r[0], "delta_rate": r[1],
                "h_min": sc.to_thickness(float(min(h.min(), st["h_dofs"].min()))),
                "friction_moment": sc.to_moment(friction), "flow_inlet": sc.to_flow(inlet),
                "flow_side": sc.to_flow(side), "flow_arc": sc.to_flow(arc), "flow_squeeze": sc.to_flow(squeeze),
                "mass_balance": sc.to_flow(inlet - side - arc - squeeze),
                "max_deflection": sc.to_thickness(float(w.max())), "pressures": st["p"]}

    def statistics(self, output, runs: Sequence) -> dict[str, float]:
        stats = {"nfev": self.nfev, "jacobians": self.jacobians,
                 "factorizations": sum(run.factorizations for run in runs), "steps": sum(run.steps for run in runs)}
        if self.product is not None:
            stats.update(compliance_products=self.product.products, krylov_iterations=self.product.iterations)
        return stats


#: Relative tolerance of the GMRES solves with ``K`` in a right side of a product compliance.
K_TOLERANCE = 1e-9
#: Relative step of the central differences in ``(gamma, delta)`` of the product path's Jacobian: the rates
#: carry about ``K_TOLERANCE`` relative noise, so the differences keep about ``log10(FD_STEP / K_TOLERANCE)`` digits.
FD_STEP = 1e-6
#: Relative tolerance of the GMRES solves with the integrator's Newton matrix (its simplified Newton takes the rest).
NEWTON_TOLERANCE = 1e-6
#: Largest number of GMRES iterations of one solve (restarts included).
KRYLOV_MAX_ITERATIONS = 2000


#: Patches of the coarse space of the product path's preconditioners (about; fewer on small meshes). With the
#: shifted-Laplacian local level (:class:`_ShiftedLaplacian`) the coarse space takes only the smoothest modes: on the
#: shipped pump's K^-1 solves (2,423 and 8,897 interior dofs, three cold right sides) 32 patches took 19 and 20
#: iterations a solve against 17.3 and 18.7 with 256, whose build (256 compliance products) cost 5 times more; the
#: elastic_fft part's transient (CPU time, one run each) 9.2 s against 10.7 s at 2,678 dofs, 50.3 s against 60.5 s
#: at 9,386 dofs (16 patches: 5 % more iterations than 32).
COARSE_PATCHES = 32

#: Shifts ``(a, b)`` of the local level of ``K^-1``'s preconditioner, ``(S + b lam M)^-1 (S + a lam M) D^-1``, as
#: fractions of ``lam``, the largest ``S_ii / D_ii`` (``D`` the mass matrix's diagonal; about the largest eigenvalue of
#: the film's Laplacian). Measured on the shipped pump's shoe (pump_mesh 0.035, 0.02, 0.0105 of the grid half-space:
#: 781, 2,423, 8,897 interior dofs; three right sides, cold starts, to K_TOLERANCE; 256 coarse patches then): GMRES
#: iterations per solve 17, 17.3, 18.7 against 25.3, 34, 48.3 with the former local level ``(12 sigma M)^-1``; CPU
#: time of the three solves (one BLAS thread) 28, 71, 341 ms against 42, 129, 743 ms. With the lumped mass for ``D``:
#: a in 0.001-0.01 and b in 3-100 within three iterations of each other, b = 0.3 or a = 0.1 up to twice as many.
K_LOCAL_SHIFTS = (0.003, 30.0)


def _patches(points: np.ndarray, count: int) -> sp.csr_matrix:
    """Indicators (columns) of about ``count`` patches of the points ``(2, m)``: the non-empty cells of a grid
    over their bounding box, at most one patch per four points."""
    m = points.shape[1]
    count = max(1, min(count, m // 4))
    lo, hi = points.min(axis=1), points.max(axis=1)
    span = np.maximum(hi - lo, 1e-300)
    nx = max(1, int(round(math.sqrt(count * span[0] / span[1]))))
    nz = max(1, int(round(count / nx)))
    ix = np.minimum((nx * (points[0] - lo[0]) / span[0]).astype(int), nx - 1)
    iz = np.minimum((nz * (points[1] - lo[1]) / span[1]).astype(int), nz - 1)
    _, patch = np.unique(ix * nz + iz, return_inverse=True)
    patch = np.asarray(patch).ravel()
    return sp.csr_matrix((np.ones(m), (np.arange(m), patch)), shape=(m, int(patch.max()) + 1))


class _TwoLevel:
    """The preconditioner ``Q + S^-1 (I - A Q)``, ``Q = Z (Z^T A Z)^-1 Z^T``: the coarse patches solved exactly
    (dense, from the stored ``A Z``), the rest by the local ``S^-1`` (sparse factors).

    A local part alone misjudges the smoothest modes, on which the compliance's influence adds up over the whole
    film (the row sums of ``C`` are about 30 times its diagonal on the pump shoe): the coarse space takes them."""

    def __init__(self, Z: sp.csr_matrix, AZ: np.ndarray, local) -> None:
        self.Z, self.AZ, self.local = Z, AZ, local
        self.ZT = Z.T.tocsr()
        self.lu = sla.lu_factor(self.ZT @ AZ, check_finite=False)

    def __call__(self, v: np.ndarray) -> np.ndarray:
        e = sla.lu_solve(self.lu, self.ZT @ v, check_finite=False)
        return self.Z @ e + self.local(v - self.AZ @ e)


class _ShiftedLaplacian:
    """The sparse model ``K ~ alpha^-1 D N^-1 F`` of ``K = 12 M_I C_I``, whose inverse is the local level of the
    product path's preconditioners.

    ``F = S + b lam M``, ``N = S + a lam M`` on the interior dofs (``S``, ``M``: the film's stiffness and mass
    matrices [-], ``D`` the diagonal of ``M``, ``(a, b)`` :data:`K_LOCAL_SHIFTS` of ``lam``, the largest
    ``S_ii / D_ii``), ``alpha`` making ``v . K P v = v . v`` on a fixed pseudo-random ``v`` (one compliance
    product). ``K`` is of order -1 (the Boussinesq kernel ``1/r``), so ``K^-1`` is of order +1: between the
    coarse patches' scale and the mesh's the model weighs a mode by a shifted Laplacian's eigenvalue, where the
    former ``12 sigma M`` weighed all alike; the iterations per solve then stay flat in the mesh size.
    """

    def __init__(self, alpha: float, F: sp.csc_matrix, N: sp.csr_matrix, D: np.ndarray) -> None:
        self.alpha, self.F, self.N, self.D = alpha, F, N, D
        self._F = spla.splu(F)

    @classmethod
    def of(cls, pc: "_InteriorCompliance", ops) -> "_ShiftedLaplacian":
        """The model of ``pc``'s ``K`` on the operators ``ops`` of its mesh.

        Raises
        ------
        ValueError
            The compliance does not open the film under the probe's pressure (``alpha`` not positive).
        """
        a, b = K_LOCAL_SHIFTS
        S = ops.laplace.tocsr()[pc.I][:, pc.I]
        M = ops.mass.tocsr()[pc.I][:, pc.I]
        D = M.diagonal()
        lam = float((S.diagonal() / D).max())
        model = cls(1.0, (S + b * lam * M).tocsc(), (S + a * lam * M).tocsr(), D)
        v = np.random.default_rng(0).standard_normal(pc.I.size)
        alpha = float(v @ v) / float(v @ pc.K(model.solve(v)))
        if not (math.isfinite(alpha) and alpha > 0):
            raise ValueError(f"the {pc.compliance.model!r} compliance gives v . K P v <= 0 on the interior dofs: "
                             "the deflection squeeze needs a compliance that opens the film under its own pressure")
        model.alpha = alpha
        return model

    def solve(self, v: np.ndarray) -> np.ndarray:
        """``alpha F^-1 N D^-1 v``: the model's ``K^-1 v``."""
        return self.alpha * self._F.solve(self.N @ (v / self.D))

    def newton(self, A: sp.spmatrix, c: float) -> Callable[[np.ndarray], np.ndarray]:
        """``v -> (model K + c A)^-1 v = (F / alpha + c N D^-1 A)^-1 N D^-1 v`` (one sparse factorization of a
        matrix of two rings of neighbours): the local level of the integrator's Newton matrix ``K + c Jr``."""
        ND = (self.N @ sp.diags(1.0 / self.D)).tocsr()
        lu = spla.splu((self.F / self.alpha + c * (ND @ A)).tocsc())
        return lambda v: lu.solve(ND @ v)


class _InteriorCompliance:
    """A compliance held as its product, on the interior pressures: ``C_I x``, ``K x = 12 M_I C_I x`` and ``K^-1``.

    ``K^-1 b`` is GMRES on the products, preconditioned on two levels
    (:class:`_TwoLevel`): about :data:`COARSE_PATCHES` patches of interior dofs
    solved exactly, the rest by the inverse of ``K``'s sparse model
    (:class:`_ShiftedLaplacian`, :attr:`model`). ``K`` is a smoothing map of
    order -1 (the Boussinesq kernel ``1/r``): its condition grows only like
    ``sqrt(N)``, and the model takes its fine modes as an operator of order
    +1, so the iterations per solve stay flat in the mesh size
    (:data:`K_LOCAL_SHIFTS`). ``sigma``: the mean self-influence of a few
    interior dofs (the compliance's diagonal, read off its products), which
    must be positive. Memory: ``C_I Z`` and ``K Z``, ``O(N k)``. Counters:
    ``products`` (of the compliance, columns counted) and ``iterations`` (of
    GMRES).
    """

    def __init__(self, compliance: Compliance, ops) -> None:
        self.compliance, self.I, self.n = compliance, ops.interior, compliance.n_dofs
        mass = ops.mass.tocsr()
        self.M_I = mass[self.I]
        m = self.I.size
        probes = self.I[np.unique(np.linspace(0, m - 1, min(m, 5)).astype(int))]
        unit = np.zeros((self.n, probes.size))
        unit[probes, np.arange(probes.size)] = 1.0
        self.sigma = float(np.mean(compliance.apply(unit)[probes, np.arange(probes.size)]))
        if not self.sigma > 0:
            raise ValueError(f"the {compliance.model!r} compliance has a self-influence {self.sigma:.3g} <= 0 at "
                             "interior dofs: the deflection squeeze needs a compliance that opens the film under "
                             "its own pressure")
        self.products = probes.size
        self.iterations = 0
        # the coarse space: indicators of patches of interior dofs, and the compliance's columns on them
        self.Z = _patches(ops.basis.doflocs[:, self.I], COARSE_PATCHES)
        self.CZ = self.columns(self.Z.toarray())            # (n, k): C_I Z
        KZ = 12.0 * (self.M_I @ self.CZ)
        #: the sparse model of K whose inverse is the local level of the preconditioners
        self.model = _ShiftedLaplacian.of(self, ops)
        self._K_pre = _TwoLevel(self.Z, KZ, self.model.solve)
        self._last = None

    def columns(self, x: np.ndarray) -> np.ndarray:
        """``C_I x`` [c] for interior pressures ``x``, shape ``(m,)`` or ``(m, k)``."""
        full = np.zeros((self.n,) + np.shape(x)[1:])
        full[self.I] = x
        self.products += 1 if np.ndim(x) == 1 else np.shape(x)[1]
        return self.compliance.apply(full)

    def K(self, x: np.ndarray) -> np.ndarray:
        return 12.0 * (self.M_I @ self.columns(x))

    def solve_K(self, b: np.ndarray, warm: bool = False) -> np.ndarray:
        """``K^-1 b`` to :data:`K_TOLERANCE` (``warm``: from the last such solution, the right sides' run)."""
        x0 = self._last if warm and self._last is not None else None
        x, its = gmres(self.K, np.asarray(b, float), preconditioner=self._K_pre, x0=x0, rtol=K_TOLERANCE,
                       max_iterations=KRYLOV_MAX_ITERATIONS,
                       what="the squeeze of the deflection's K^-1 (12 M C on the interior pressures; singular when "
                            "some interior pressure opens no film, e.g. an auxiliary grid coarser than the mesh: a "
                            "smaller spacing)")
        self.iterations += its
        if warm:
            self._last = x
        return x


class _SqueezeJacobian:
    """``d(rhs)/dy`` of :class:`ElasticSqueeze` at one state for a product compliance, held as its pieces.

    With ``Da = -K^-1 Jr``, ``Jr = A_II + B_h C_I`` (the residual's derivative in
    the interior pressures, sparse plus one compliance product),
    ``Rp = G L_I (Da + kappa)`` (the rates' derivative, ``G = (L_I B)^-1``) and the
    columns of ``(gamma, delta)`` by central differences (``J_g``), the
    Jacobian is ``[[J_gg, Rp], [J_pg, Da - B Rp]]``: the dense one of
    :meth:`ElasticSqueeze.jacobian`, never formed. The integrator's Newton
    matrix ``I - c J`` is solved by :meth:`newton` (:class:`_NewtonSolve`).
    """

    __array_ufunc__ = None  # numpy scalars times this defer to __rmul__

    def __init__(self, model: ElasticSqueeze, beta: float, y: np.ndarray) -> None:
        self.model = model
        _, _, st = model._rates(beta, y)
        co = model.co
        h2 = 3.0 * st["h"] ** 2 * model.dx
        self.A = co.condensed(co.matrix_data("direct", st["h"], None)).tocsc()
        self.Bh = ((model.GpT @ sp.diags(h2 * st["gp"]) + model.GzT @ sp.diags(h2 * st["gz"])) @ model.E
                   - 6.0 * st["wedge"] * model.phi_src_E).tocsr()
        self.B = st["B"]
        self.G = np.linalg.inv(model.LI @ self.B)
        self.Jg = np.empty((y.size, 2))
        for k in range(2):
            e = FD_STEP * max(1.0, abs(y[k]))
            yp, ym = y.copy(), y.copy()
            yp[k] += e
            ym[k] -= e
            self.Jg[:, k] = (model.rates(beta, yp) - model.rates(beta, ym)) / (2 * e)

    def __rmul__(self, c) -> tuple:
        return (self, float(c))


class _NewtonIdentity:
    """The identity of :class:`_KrylovBDF`: ``I - c J`` is the :class:`_NewtonSolve` of ``(J, c)``."""

    def __sub__(self, scaled: tuple) -> tuple:
        return scaled


class _NewtonSolve:
    """Solves with the integrator's Newton matrix ``N = I - c J`` of a :class:`_SqueezeJacobian`, exactly up to GMRES.

    The pressure block is ``T = I - c Da = K^-1 (K + c Jr)``, so ``T^-1 v = (K + c Jr)^-1 K v``: GMRES on
    ``K + c Jr`` (one compliance product per iteration, no ``K^-1``), right-preconditioned on two levels: the
    coarse patches exactly, the rest by the sparse factors of ``K``'s model plus ``c A_II``
    (:meth:`_ShiftedLaplacian.newton`; the film's operator for the fine modes, the compliance's for the
    coarser). The rest of ``N`` is a rank-4 correction (the rates' rows ``Rp`` and the columns of
    ``(gamma, delta)``), taken exactly: with ``x = T^-1 v``, ``Da x = (x - v)/c`` gives ``Rp x`` with no
    further solve, and a 4x4 system joins the pieces (four solves with ``T`` per Newton matrix, one per solve).
    """

    def __init__(self, J: _SqueezeJacobian, c: float) -> None:
        self.J, self.c = J, c
        model = J.model
        pc = model.product
        TZ = 12.0 * (pc.M_I @ pc.CZ) + c * (J.A @ pc.Z + J.Bh @ pc.CZ)
        self._pre = _TwoLevel(pc.Z, np.asarray(TZ), pc.model.newton(J.A, c))
        cols = np.column_stack([J.Jg[2:], J.B])
        X = np.column_stack([self._T_solve(cols[:, k]) for k in range(4)])
        rho = np.column_stack([self._rho(cols[:, k], X[:, k]) for k in range(4)])
        self.X_J, self.X_B, rho_J, rho_B = X[:, :2], X[:, 2:], rho[:, :2], rho[:, 2:]
        eye = np.eye(2)
        self.S = np.linalg.inv(np.block([[eye - c * J.Jg[:2], -c * eye], [-c * rho_J, eye + c * rho_B]]))

    def _T_solve(self, v: np.ndarray) -> np.ndarray:
        J, c = self.J, self.c
        pc = J.model.product

        def matvec(x):
            w = pc.columns(x)
            return 12.0 * (pc.M_I @ w) + c * (J.A @ x + J.Bh @ w)

        try:
            x, its = gmres(matvec, pc.K(v), preconditioner=self._pre, x0=v.copy(), rtol=NEWTON_TOLERANCE,
                           max_iterations=KRYLOV_MAX_ITERATIONS,
                           what="the integrator's Newton matrix of the deflection squeeze")
        except ElasticError as exc:  # a shorter step brings the matrix nearer K, which GMRES does solve
            raise TrialRejected(str(exc)) from None
        pc.iterations += its
        return x

    def _rho(self, v: np.ndarray, x: np.ndarray) -> np.ndarray:
        """``Rp x`` for ``x = T^-1 v``."""
        J = self.J
        return J.G @ (J.model.LI @ ((x - v) / self.c + J.model.kappa * x))

    def solve(self, b: np.ndarray) -> np.ndarray:
        c = self.c
        bg, bp = b[:2], b[2:]
        x = self._T_solve(bp)
        zs = self.S @ np.r_[bg, self._rho(bp, x)]
        zg, s = zs[:2], zs[2:]
        return np.r_[zg, x + c * (self.X_J @ zg) - c * (self.X_B @ s)]


#: scipy BDF internals that :class:`_KrylovBDF` replaces (its simplified Newton's matrix, factorization and solve).
_BDF_INTERNALS = ("J", "I", "lu", "solve_lu", "nlu")


class _KrylovBDF(si.BDF):
    """scipy's BDF with the Newton matrix of a :class:`_SqueezeJacobian` solved by :class:`_NewtonSolve`.

    The steps, error control and dense output are scipy's; only the linear algebra of its simplified Newton
    changes (``nlu`` counts the Newton matrices set up). ``jac`` returns :class:`_SqueezeJacobian`.
    """

    def __init__(self, fun, t0, y0, t_bound, *, jac, **options) -> None:
        super().__init__(fun, t0, y0, t_bound, jac=jac, **options)
        missing = [name for name in _BDF_INTERNALS if not hasattr(self, name)]
        if missing:
            raise RuntimeError(f"scipy {scipy.__version__}'s BDF has no {', '.join(missing)}: the deflection squeeze's "
                               "matrix-free Newton matrix replaces these internals; use a dense compliance or a "
                               "scipy release whose BDF has them (1.17 does)")
        self.J, self.I = self._first_jacobian, _NewtonIdentity()

        def lu(pair):
            self.nlu += 1
            return _NewtonSolve(*pair)

        self.lu = lu
        self.solve_lu = lambda newton, b: newton.solve(b)

    def _validate_jac(self, jac, sparsity):
        self._first_jacobian = jac(self.t, self.y)
        self.njev += 1

        def wrapped(t, y):
            self.njev += 1
            return jac(t, y)

        # a sparse stand-in while scipy's constructor runs: its sparse branch makes no dense identity
        return wrapped, sp.csc_matrix((self.n, self.n))


def simulate_elastic(pump: EccentricPump, compliance: Compliance, revolutions: float = 1.0, *,
                     start="periodic", beta0: float = 0.0, method: str = "BDF", rtol: float = 1e-5,
                     atol: float = 1e-8, deflection_atol: float = 1e-5, max_step: float = math.pi / 16,
                     points_per_revolution: int = 180, periodic_tol: float = 1e-5, periodic_max_iter: int = 30,
                     periodic_method: str = "anderson", kappa: float = BAUMGARTE) -> Trajectory:
    """Integrate the plunger shoe on an elastic support over the pump cycle, deflection squeeze included.

    Parameters
    ----------
    pump : EccentricPump
    compliance : Compliance
        Of the support, on the mesh of ``pump.surface``: any compliance
        matrix on the film dofs (:func:`bearingfe.elastic.half_space`,
        :func:`bearingfe.elastic.shoe_body`; up to the dense limit), or one
        held as its product (:func:`bearingfe.elastic.half_space_fft`,
        :func:`bearingfe.elastic.half_space_grid`; matrix-free, no size
        limit, ``method="BDF"``: see the module notes).
    revolutions : float
        Length of the run in shaft turns, > 0.
    start : {"periodic", "steady"} or Trajectory
        ``"steady"``: the quasi-static elastic equilibrium at the rigid steady
        state of ``beta0``; ``"periodic"``: from there, revolutions are
        repeated until ``max |(gamma, delta)(2 pi) - (gamma, delta)(0)| <
        periodic_tol``; a :class:`~bearingfe.Trajectory` of this function on
        the same compliance: continue from its last sample (angle, ``gamma``,
        ``delta`` and pressure; ``beta0`` is then its angle).
    method : {"BDF", "LSODA", "Radau"}
        Integrator (implicit: the fine pressure modes are stiff); "BDF" only
        with a compliance held as its product.
    rtol : float
        Relative tolerance of the integrator.
    atol : float
        Absolute tolerance on ``gamma`` [-] and ``delta`` [rad].
    deflection_atol : float
        Absolute tolerance on the film opening ``C p`` [c]: the pressures are
        weighted by the largest row sum of the compliance, so that their
        error moves the film by at most about this much.
    max_step : float
        Largest step [rad].
    points_per_revolution : int
        Output samples per turn, >= 8.
    periodic_tol, periodic_max_iter
        Periodic start: tolerance on ``(gamma [-], delta [rad])`` over one
        revolution, and the largest number of revolutions.
    periodic_method : {"anderson", "fixed-point", "one-revolution"}
        ``"anderson"`` (default): Anderson mixing of the last three
        revolutions (the state weighted as the error control is: ``gamma``,
        ``delta`` and the film opening), which falls back to the plain iterate
        when a mixed state's revolution does not complete; the revolution that
        meets the tolerance is the output revolution when ``revolutions == 1``.
        ``"fixed-point"``: iterate the return map (eleven revolutions on the
        shipped pump with the pocket). See :data:`bearingfe.transient.PERIODIC_METHODS`.
    kappa : float
        Baumgarte rate of the load balance [1/rad], > 0.

    Returns
    -------
    Trajectory
        With ``max_deflection`` and ``pressures``; ``status`` is
        ``"ruptured"`` when an accepted state's film reaches 2 % of the
        clearance (a trial step that closes the film is retaken shorter).
        ``stats``: ``nfev``, ``jacobians``, ``factorizations`` (of the
        integrator's Newton matrix; set up matrix-free with a product
        compliance), ``steps``, ``seconds``; with a product compliance also
        ``krylov_iterations`` and ``compliance_products``.

    Notes
    -----
    The defaults (BDF, ``rtol = 1e-5``, ``deflection_atol = 1e-5`` c) keep the
    film of a revolution on the shipped pump within 2e-4 c (4 nm, 0.1 % of
    its smallest film) of a run at ``rtol = 1e-8`` (measured 1e-4 c and
    less: ``docs/elastic.md``, tests/test_elastic_transient.py), in a
    fourth of the steps. The dense linear algebra runs on one
    BLAS thread (:func:`bearingfe.core.linalg.dense_threads`). A compliance
    held as its product gives the same run up to the inner GMRES tolerances
    (:data:`K_TOLERANCE`, :data:`NEWTON_TOLERANCE`).
    """
    if not isinstance(pump, EccentricPump):
        raise ValueError(f"pump must be a bearingfe.EccentricPump, got {type(pump).__name__}")
    if not isinstance(compliance, Compliance):
        raise ValueError(f"compliance must be a bearingfe.elastic.Compliance, got {type(compliance).__name__}")
    if pump.shoe_supply is not None:
        raise ValueError(f"{pump.name!r} feeds its pocket through a restrictor ([shoe.supply]): the deflection squeeze "
                         "model holds the pocket at the chamber pressure; bearingfe.simulate(elastic=...) runs the fed "
                         "pocket on the quasi-static elastic support")
    if not math.isfinite(compliance.modulus):
        raise ValueError("compliance needs a finite modulus: on a rigid support (modulus inf) the pressure is "
                         "not a state; use bearingfe.simulate without elastic")
    settings = Integration(revolutions=revolutions, start=start, beta0=beta0, method=method, rtol=rtol, atol=atol,
                           max_step=max_step, points_per_revolution=points_per_revolution,
                           periodic_method=periodic_method, periodic_tol=periodic_tol,
                           periodic_max_iter=periodic_max_iter)
    ElasticSqueeze.check(settings)
    positive("kappa", kappa), positive("deflection_atol", deflection_atol)
    if compliance.dense:
        check_dense_size(compliance.n_dofs)
    elif method != "BDF":
        raise ValueError(f"method must be 'BDF' with the {compliance.model!r} compliance held as its product: the "
                         f"integrator's Newton solves are then matrix-free (GMRES inside BDF), got {method!r}")
    ratio = balance_ratio(pump, compliance.mesh, element=compliance.element)
    if ratio >= 1.0:
        raise LiftOffError(f"{pump.name!r}: balance ratio {ratio:.3f} >= 1: the shoe lifts off")
    with dense_threads(1):
        model = ElasticSqueeze(pump, compliance, kappa=kappa, deflection_atol=deflection_atol)
        return run_transient(model, settings, balance_ratio=ratio)
