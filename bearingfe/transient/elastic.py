r"""The plunger shoe on an elastic support over the pump cycle, with the squeeze of the deflection.

On an elastic support the film is ``h = h_rigid(gamma, delta) + w`` with
``w = C p`` (:mod:`bearingfe.elastic.coupled`), and the squeeze term of the Reynolds
equation contains the rate of the deflection::

    div(h^3 grad p) = 6 wedge dh/dphi + 12 (gamma' s_gamma + delta' s_delta + dw/dbeta),
    dw/dbeta = C dp/dbeta.

When the chamber pressure falls (decompression) the deflection springs back
and the film between the surfaces is squeezed: that squeeze pressure slows
the spring-back. Dropping ``dw/dbeta`` (the quasi-static model of
:func:`bearingfe.simulate` with ``elastic=``) lets the film collapse with the
deflection; on the shipped pump the plain shoe's film then closes just after
the inner dead centre. Here the pressure is a state variable.

Model
-----
The state is ``y = (gamma, delta, p_I)`` with ``p_I`` the pressure at the
interior dofs (pocket dofs at the chamber pressure ``p_s(beta)``, outline at
0). The weak form on the interior test functions is

    R(p, h) + S r + K p_I' + c_s p_s' = 0,
    R = int h^3 grad p . grad v + int 6 wedge dh/dphi v,   S = int 12 (s_gamma, s_delta) v,
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
machine). The periodic start mixes the last revolutions (Anderson). The
compliance stays dense: a low-rank form does not pay, because its
singular values fall to 1 % of the largest only near the full rank
(``docs/elastic.md`` gives the measured ranks); beyond
the ``compliance`` limit of :mod:`bearingfe.core.limits` (4000 dofs) the dense forms are refused.

Cavitation: the pressure may go negative (the source paper's model,
``cavitation="none"``); a complementarity condition on a state variable is
not covered here. The start is the quasi-static elastic equilibrium
(:func:`bearingfe.elastic.coupled.balance_load`) at the rigid steady state, or the
periodic state by fixed-point iteration of revolutions.

Flows are the consistent boundary residuals of the flux
``q = -h^3/12 grad p + wedge h/2 e_phi`` with ``dh/dt`` including ``dw/dbeta``
(corner dofs shared equally between their edges).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
import scipy.integrate as si
import scipy.linalg as sla
import scipy.sparse as sp

from ..elastic.coupled import Compliance, DeflectedFilm, ElasticError, balance_load, check_dense_size
from ..film.thickness import CosineFilm
from ..bearings.pump import EccentricPump
from ..film import build_result, operators, source_weights, superpose
from ..core.linalg import dense_threads
from .quasi_static import IMPLICIT_INTEGRATORS, LiftOffError, Trajectory, balance_ratio, steady_state

__all__ = ["simulate_elastic", "state_result", "BAUMGARTE", "PERIODIC_METHODS"]

#: Periodic-start methods of :func:`simulate_elastic`.
PERIODIC_METHODS = ("anderson", "fixed-point")

#: Default stabilization rate of the load balance [1/rad]: a load residual decays like exp(-kappa beta).
BAUMGARTE = 50.0


@dataclass
class _Dynamics:
    """The ODE of one run (not public). Works on the compiled film-independent maps of the mesh
    (:mod:`bearingfe.film.compiled`): a state costs sparse products with the quadrature points, one
    product with the compliance and one solve with the factors of ``K``; no assembly and no
    factorization."""

    pump: EccentricPump
    compliance: Compliance
    kappa: float
    nfev: int = 0
    jacobians: int = 0

    def __post_init__(self) -> None:
        ops = operators(self.compliance.mesh, self.compliance.element)
        co = ops.compiled
        self.ops, self.basis, self.co = ops, ops.basis, co
        self.I, self.inlet = ops.interior, ops.inlet
        C = np.asarray(self.compliance.matrix, float)
        self.C_I = np.ascontiguousarray(C[:, self.I])
        self.c_in = C[:, self.inlet].sum(axis=1) + self.compliance.pocket  # opening per unit pocket pressure
        M = ops.mass.tocsr()[self.I]
        # K^-1 explicitly (K is dense anyway): a state then costs one product with it
        self.Kinv = sla.inv(12.0 * (M @ self.C_I), check_finite=False)
        self.a_s = self.Kinv @ (12.0 * (M @ self.c_in))  # K^-1 c_s
        self.E, self.Gp, self.Gz = co.value, co.grad[0], co.grad[1]
        self.dx = co.dx
        self.src = co.sources  # (E^T dx)[I]
        self.GpT, self.GzT = self.Gp.T.tocsr()[self.I], self.Gz.T.tocsr()[self.I]
        self.src_grad = (self.src @ self.Gp).tocsr()  # int (dw/dphi) phi_i for the interior i
        self.cos_q, self.sin_q = np.cos(co.x[0]), np.sin(co.x[0])
        self.src_cos, self.src_sin = self.src @ self.cos_q, self.src @ self.sin_q
        self.k_cos, self.k_sin = 12.0 * (self.Kinv @ self.src_cos), 12.0 * (self.Kinv @ self.src_sin)
        d = self.basis.doflocs
        self.cos_d, self.sin_d = np.cos(d[0]), np.sin(d[0])
        L = np.asarray(co.loads[:2] @ co.value)  # (2, n_dofs): int phi_j (cos, sin) dphi dz
        self.LI = L[:, self.I]
        self.L_in = L[:, self.inlet].sum(axis=1) + np.asarray(ops.pocket_moments[1:], float)
        self._drive = (None, None)

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
        p = np.zeros(self.compliance.n_dofs)
        p[self.inlet] = self.pump.inlet_pressure(beta)
        p[self.I] = p_interior
        return p

    def rates(self, beta: float, y: np.ndarray):
        """``(gamma', delta')``, ``p_I'`` and the pieces of the film at state ``y``."""
        self.nfev += 1
        gamma, delta = float(y[0]), float(y[1])
        ps, dps, load, dload, wedge = self.drive(beta)
        pI = y[2:]
        p = np.zeros(self.compliance.n_dofs)
        p[self.inlet] = ps
        p[self.I] = pI
        w = self.C_I @ pI + ps * self.c_in
        g = max(gamma, 0.0)
        cd, sd = math.cos(delta), math.sin(delta)
        cos_m = self.cos_q * cd + self.sin_q * sd  # cos(phi - delta) at the points
        sin_m = self.sin_q * cd - self.cos_q * sd
        h = 1.0 + g * cos_m + self.E @ w
        h_dofs = 1.0 + g * (self.cos_d * cd + self.sin_d * sd) + w
        if not (np.all(h > 0) and np.all(h_dofs > 0)):
            raise ElasticError(f"film closed (h_min = {min(h.min(), h_dofs.min()):.3g} c <= 0) at beta = {beta:.4f} rad")
        dh = -g * sin_m + self.Gp @ w
        gp, gz = self.Gp @ p, self.Gz @ p
        h3 = h**3 * self.dx
        src_dh = self.src_grad @ w - g * (cd * self.src_sin - sd * self.src_cos)  # int dh/dphi v
        R = self.GpT @ (h3 * gp) + self.GzT @ (h3 * gz) + 6.0 * wedge * src_dh
        a = -(self.Kinv @ R) - dps * self.a_s
        B = np.column_stack([cd * self.k_cos + sd * self.k_sin, g * (cd * self.k_sin - sd * self.k_cos)])
        res = self.LI @ pI + ps * self.L_in + load
        rhs = self.LI @ a + self.kappa * res + self.L_in * dps + dload
        try:
            r = np.linalg.solve(self.LI @ B, rhs)
        except np.linalg.LinAlgError:
            raise ElasticError(f"load balance singular at beta = {beta:.4f} rad (gamma = {gamma:.4g})") from None
        return r, a - B @ r, dict(p=p, w=w, h=h, dh=dh, h_dofs=h_dofs, wedge=wedge, dps=dps,
                                  shapes=(cos_m, g * sin_m), gp=gp, gz=gz, B=B)

    def __call__(self, beta: float, y: np.ndarray) -> np.ndarray:
        r, dp, _ = self.rates(beta, y)
        return np.concatenate([r, dp])

    def jacobian(self, beta: float, y: np.ndarray) -> np.ndarray:
        """``d(rhs)/dy``: analytic in the pressures, central differences in ``(gamma, delta)``.

        ``a = -K^-1 (R + c_s p_s')`` has ``da/dp_I = -K^-1 (A_II + B_h C_I)`` with
        ``B_h`` the film sensitivity of the residual
        (``int 3 h^2 u grad p . grad v + 6 wedge du/dphi v``); ``r = G (L_I a + kappa g + ...)``
        with ``G = (L_I B)^-1`` gives ``dr/dp_I = G L_I (da/dp_I + kappa)``.
        """
        self.jacobians += 1
        r, dp, st = self.rates(beta, y)
        n = y.size
        J = np.empty((n, n))
        h2 = 3.0 * st["h"] ** 2 * self.dx
        Bh = (self.GpT @ sp.diags(h2 * st["gp"]) + self.GzT @ sp.diags(h2 * st["gz"])) @ self.E \
            + 6.0 * st["wedge"] * self.src_grad
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
            J[:, k] = (self(beta, yp) - self(beta, ym)) / (2 * e)
        return J

    def sample(self, beta: float, y: np.ndarray) -> dict:
        """SI figures of one state: rates, smallest film, friction, flows, largest deflection."""
        r, dp, st = self.rates(beta, y)
        sc = self.pump.scale
        w, h = st["w"], st["h"]
        dw = self.C_I @ dp + self.c_in * st["dps"]
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
                "max_deflection": sc.to_thickness(float(w.max()))}


def _start(pump: EccentricPump, dyn: _Dynamics, beta0: float, gamma: float, delta: float) -> np.ndarray:
    """The quasi-static elastic equilibrium at ``(gamma, delta)`` as the initial pressure."""
    c = dyn.compliance
    found = balance_load(c.mesh, CosineFilm(gamma, delta), c, pump.load_vector(beta0),
                         wedge=float(pump.wedge(beta0)), inlet_pressure=float(pump.inlet_pressure(beta0)),
                         element=c.element)
    return np.concatenate([[gamma, delta], found.result.pressure[dyn.I]])


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
        matrix on the film dofs (:func:`bearingfe.elastic.coupled.half_space`,
        :func:`bearingfe.elastic.coupled.shoe_body`).
    revolutions : float
        Length of the run in shaft turns, > 0.
    start : {"periodic", "steady"} or Trajectory
        ``"steady"``: the quasi-static elastic equilibrium at the rigid steady
        state of ``beta0``; ``"periodic"``: from there, revolutions are
        repeated until ``max |(gamma, delta)(2 pi) - (gamma, delta)(0)| <
        periodic_tol``; a :class:`~bearingfe.transient.quasi_static.Trajectory` of this
        function on the same compliance: continue from its last sample
        (angle, ``gamma``, ``delta`` and pressure; ``beta0`` is then its angle).
    method : {"BDF", "LSODA", "Radau"}
        Integrator (implicit: the fine pressure modes are stiff).
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
    periodic_method : {"anderson", "fixed-point"}
        ``"fixed-point"``: iterate the return map (eleven revolutions on the
        shipped pump with the pocket). ``"anderson"`` (default): Anderson
        mixing of the last three revolutions (the state weighted as the
        error control is: ``gamma``, ``delta`` and the film opening), which
        falls back to the plain iterate when a mixed state would close the
        film. The revolution that meets the tolerance is the output revolution
        when ``revolutions == 1``.
    kappa : float
        Baumgarte rate of the load balance [1/rad], > 0.

    Returns
    -------
    Trajectory
        With ``max_deflection`` and ``pressures``; ``status`` is
        ``"ruptured"`` if the film closes. ``stats``: ``nfev``,
        ``jacobians``, ``factorizations`` (of the integrator's Newton
        matrix), ``steps``, ``seconds``.

    Notes
    -----
    The defaults (BDF, ``rtol = 1e-5``, ``deflection_atol = 1e-5`` c) keep the
    film of a revolution on the shipped pump within 2e-4 c (4 nm, 0.1 % of
    its smallest film) of a run at ``rtol = 1e-8`` (measured 1e-4 c and
    less: ``docs/elastic.md``, tests/test_elastic_transient.py), in a
    fourth of the steps. The dense linear algebra runs on one
    BLAS thread (:func:`bearingfe.core.linalg.dense_threads`).
    """
    if not isinstance(pump, EccentricPump):
        raise ValueError(f"pump must be a bearingfe.EccentricPump, got {type(pump).__name__}")
    if not isinstance(compliance, Compliance):
        raise ValueError(f"compliance must be a bearingfe.elastic.coupled.Compliance, got {type(compliance).__name__}")
    if not math.isfinite(compliance.modulus):
        raise ValueError("compliance needs a finite modulus: on a rigid support (modulus inf) the pressure is "
                         "not a state; use bearingfe.simulate without elastic")
    if not (math.isfinite(revolutions) and revolutions > 0):
        raise ValueError(f"revolutions must be a finite number > 0, got {revolutions!r}")
    if not (isinstance(start, Trajectory) or start in ("periodic", "steady")):
        raise ValueError(f"start must be 'periodic', 'steady' or a Trajectory of simulate_elastic, got {start!r}")
    if method not in IMPLICIT_INTEGRATORS:  # the pressure modes are stiff: no explicit Runge-Kutta
        raise ValueError(f"method must be one of {list(IMPLICIT_INTEGRATORS)}, got {method!r}")
    if periodic_method not in PERIODIC_METHODS:
        raise ValueError(f"periodic_method must be one of {PERIODIC_METHODS}, got {periodic_method!r}")
    for name, v in (("rtol", rtol), ("atol", atol), ("deflection_atol", deflection_atol), ("max_step", max_step),
                    ("kappa", kappa)):
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {v!r}")
    if not rtol < 1:
        raise ValueError(f"rtol must be in (0, 1), got {rtol!r}")
    if int(points_per_revolution) < 8:
        raise ValueError(f"points_per_revolution must be >= 8, got {points_per_revolution!r}")
    check_dense_size(compliance.n_dofs)
    mesh = compliance.mesh
    ratio = balance_ratio(pump, mesh, element=compliance.element)
    if ratio >= 1.0:
        raise LiftOffError(f"{pump.name!r}: balance ratio {ratio:.3f} >= 1: the shoe lifts off")
    with dense_threads(1):
        t_start = time.perf_counter()
        dyn = _Dynamics(pump, compliance, float(kappa))
        if isinstance(start, Trajectory):
            y0, beta0 = _continued(start, dyn)
        else:
            gamma, delta = steady_state(pump, mesh, beta0, element=compliance.element)
            y0 = _start(pump, dyn, beta0, gamma, delta)
        weights = np.r_[1.0, 1.0, np.full(y0.size - 2, float(np.abs(compliance.matrix).sum(axis=1).max()))]
        tols = (rtol, np.r_[atol, atol, deflection_atol / weights[2:]])
        opts = dict(method=method, rtol=tols[0], atol=tols[1], max_step=max_step)
        iterations, residual, sol, steps, lus = 0, math.nan, None, 0, 0
        if start == "periodic":
            y0, sol, iterations, residual, steps, lus = _periodic(dyn, beta0, y0, opts, weights, periodic_method,
                                                                  periodic_tol, periodic_max_iter)
            if revolutions != 1 or sol.status != 0:
                sol = None
        beta1 = beta0 + 2 * math.pi * revolutions
        if sol is None:
            sol = _run(dyn, beta0, y0, beta1, **opts)
            steps, lus = steps + int(sol.t.size) - 1, lus + int(sol.nlu)
        seconds = time.perf_counter() - t_start
        end = float(sol.t[-1])
        n = max(int(round(points_per_revolution * revolutions)), 2) + 1
        betas = np.linspace(beta0, beta1, n)
        betas = betas[betas <= end + 1e-12]
        ys = sol.sol(betas).T if betas.size else np.zeros((0, y0.size))
        status = "completed" if sol.status == 0 else "ruptured"
        message = (f"completed {revolutions:.4g} revolutions" if status == "completed"
                   else f"stopped at beta = {end:.4f} rad ({math.degrees(end) % 360:.1f} deg): {sol.message}")
        samples = [dyn.sample(b, y) for b, y in zip(betas, ys)]
    cols = {k: np.array([s[k] for s in samples]) for k in samples[0]} if samples else {}
    f = pump.load(betas)
    return Trajectory(
        t=(betas - beta0) / pump.drive.omega, beta=betas, gamma=ys[:, 0], delta=ys[:, 1],
        gamma_rate=cols["gamma_rate"], delta_rate=cols["delta_rate"], wedge=pump.wedge(betas),
        inlet_pressure=pump.inlet_pressure(betas), chamber_pressure=pump.chamber_pressure(betas),
        load=np.column_stack([-f, np.zeros_like(f)]), h_min=cols["h_min"], friction_moment=cols["friction_moment"],
        flow_inlet=cols["flow_inlet"], flow_side=cols["flow_side"], flow_arc=cols["flow_arc"],
        flow_squeeze=cols["flow_squeeze"], mass_balance=cols["mass_balance"], status=status, message=message,
        rupture_beta=math.nan if status == "completed" else end, start=(float(y0[0]), float(y0[1])),
        periodic_iterations=iterations, periodic_residual=residual, element=compliance.element,
        stats=MappingProxyType({"nfev": dyn.nfev, "jacobians": dyn.jacobians, "factorizations": lus,
                                "steps": steps, "seconds": seconds, "solver_seconds": seconds,
                                "dofs": float(compliance.n_dofs), "balance_ratio": ratio}),
        max_deflection=cols["max_deflection"],
        pressures=np.array([dyn.pressure(b, y[2:]) for b, y in zip(betas, ys)]))


def _continued(traj: Trajectory, dyn: _Dynamics) -> tuple[np.ndarray, float]:
    """State and angle of the last sample of a :func:`simulate_elastic` run on the same compliance."""
    if traj.pressures is None or np.shape(traj.pressures)[-1] != dyn.compliance.n_dofs or not traj.beta.size:
        raise ValueError("start: a Trajectory must come from simulate_elastic on a compliance with "
                         f"{dyn.compliance.n_dofs} dofs (its pressures are the state)")
    if traj.status != "completed":
        raise ValueError(f"start: the Trajectory did not complete ({traj.message}); it has no state to continue")
    y = np.concatenate([[traj.gamma[-1], traj.delta[-1]], np.asarray(traj.pressures[-1], float)[dyn.I]])
    return y, float(traj.beta[-1])


def _periodic(dyn: _Dynamics, beta0: float, y0: np.ndarray, opts: dict, weights: np.ndarray, method: str,
              tol: float, max_iter: int, memory: int = 3):
    """Start of a periodic revolution: fixed point of the return map, plain or Anderson-mixed.

    Returns the start, the revolution run from it, the revolutions run, the
    residual ``max |(gamma, delta)(2 pi) - (gamma, delta)(0)|``, the steps and
    the Newton-matrix factorizations of all of them.
    """
    y, xs, fs = y0, [], []
    iterations, steps, lus = 0, 0, 0
    while True:
        try:
            sol = _run(dyn, beta0, y, beta0 + 2 * math.pi, **opts)
        except ElasticError:
            if not xs:
                raise
            y, xs, fs = xs[-1] + fs[-1], [], []  # the mixed state failed: back to the plain iterate
            continue
        iterations += 1
        steps, lus = steps + int(sol.t.size) - 1, lus + int(sol.nlu)
        if sol.status != 0:
            return y, sol, iterations, math.nan, steps, lus
        f = sol.y[:, -1] - y
        residual = float(np.max(np.abs(f[:2])))
        if residual < tol:
            return y, sol, iterations, residual, steps, lus
        if iterations >= max_iter:
            raise RuntimeError(f"periodic start did not converge in {iterations} revolutions "
                               f"(last residual {residual:.3g} >= periodic_tol = {tol})")
        xs, fs = (xs + [y])[-(memory + 1):], (fs + [f])[-(memory + 1):]
        nxt = y + f
        if method == "anderson" and len(xs) > 1:
            dX = np.diff(np.array(xs), axis=0).T
            dF = np.diff(np.array(fs), axis=0).T
            coef = np.linalg.lstsq(dF * weights[:, None], f * weights, rcond=None)[0]
            mixed = y + f - (dX + dF) @ coef
            if np.all(np.isfinite(mixed)) and mixed[0] >= 0:
                nxt = mixed
        y = nxt


def state_result(pump: EccentricPump, compliance: Compliance, traj: Trajectory, k: int):
    """The film of sample ``k`` of a :func:`simulate_elastic` run as a :class:`bearingfe.ReynoldsResult`.

    Pressure, deflected film, force and friction are those of the run (the
    force balances ``-traj.load[k]``); the flows of this result leave out the
    deflection's squeeze (``traj`` has the complete ones).
    """
    if traj.pressures is None:
        raise ValueError("traj has no pressures: it is not a simulate_elastic run")
    p = np.asarray(traj.pressures[k], float)
    ps = float(traj.inlet_pressure[k])
    w = compliance.deflection(p, ps)
    basis = operators(compliance.mesh, compliance.element).basis
    film = DeflectedFilm(CosineFilm(float(traj.gamma[k]), float(traj.delta[k])), basis, w)
    sup = superpose(compliance.mesh, film, formulation="direct", element=compliance.element)
    weights = source_weights(float(traj.wedge[k]), (float(traj.gamma_rate[k]), float(traj.delta_rate[k])), ps)
    res = build_result(sup, p, weights, cavitated=np.zeros(p.size, bool))
    return dataclasses.replace(res, deflection=w)


def _run(dyn: _Dynamics, beta0: float, y0: np.ndarray, beta1: float, method: str, rtol: float, atol: float,
         max_step: float):
    """``solve_ivp`` with dense output; a closing film ends the run (status -1) instead of failing."""
    state = {"closed": None}

    def rhs(beta, y):
        try:
            return dyn(beta, y)
        except ElasticError as exc:
            state["closed"] = str(exc)
            raise

    try:
        return si.solve_ivp(rhs, (beta0, beta1), y0, method=method, rtol=rtol, atol=atol, max_step=max_step,
                            dense_output=True, jac=dyn.jacobian)
    except ElasticError:
        raise ElasticError(f"the elastic transient stopped: {state['closed']}") from None
