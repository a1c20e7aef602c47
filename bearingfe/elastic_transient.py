r"""The plunger shoe on an elastic support over the pump cycle, with the squeeze of the deflection.

On an elastic support the film is ``h = h_rigid(gamma, delta) + w`` with
``w = C p`` (:mod:`bearingfe.elastic`), and the squeeze term of the Reynolds
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
ODE is stiff (the fine pressure modes relax fast) and goes to scipy's LSODA
(or BDF/Radau) with finite-difference Jacobians.

Cavitation: the pressure may go negative (the source paper's model,
``cavitation="none"``); a complementarity condition on a state variable is
not covered here. The start is the quasi-static elastic equilibrium
(:func:`bearingfe.elastic.balance_load`) at the rigid steady state, or the
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

from .elastic import Compliance, DeflectedFilm, ElasticError, balance_load
from .film import CosineFilm
from .pump import EccentricPump
from .superposition import build_result, operators, source_weights, superpose
from .transient import INTEGRATORS, LiftOffError, Trajectory, balance_ratio, steady_state

__all__ = ["simulate_elastic", "state_result", "BAUMGARTE"]

#: Default stabilization rate of the load balance [1/rad]: a load residual decays like exp(-kappa beta).
BAUMGARTE = 50.0


@dataclass
class _Dynamics:
    """The ODE of one run (not public). Works on the compiled film-independent maps of the mesh
    (:mod:`bearingfe.compiled`): a state costs sparse products, no assembly and no factorization."""

    pump: EccentricPump
    compliance: Compliance
    kappa: float
    nfev: int = 0

    def __post_init__(self) -> None:
        ops = operators(self.compliance.mesh, self.compliance.element)
        co = ops.compiled
        self.ops, self.basis, self.co = ops, ops.basis, co
        self.I, self.inlet = ops.interior, ops.inlet
        self.x = co.x
        C = self.compliance.matrix
        M = ops.mass.tocsr()[self.I]
        self.K = sla.lu_factor(12.0 * (M @ C[:, self.I]), check_finite=False)
        self.c_s = 12.0 * (M @ (C[:, self.inlet].sum(axis=1) + self.compliance.pocket))
        self.L = np.asarray(co.loads[:2] @ co.value)  # (2, n_dofs): int phi_j (cos, sin) dphi dz
        self.F_pocket = np.asarray(ops.pocket_moments[1:], float)
        self.E, self.Gp, self.Gz = co.value, co.grad[0], co.grad[1]
        self.dx = co.dx
        self.src = co.sources  # (E^T dx)[I]

    def pressure(self, beta: float, p_interior: np.ndarray) -> np.ndarray:
        p = np.zeros(self.compliance.n_dofs)
        p[self.inlet] = self.pump.inlet_pressure(beta)
        p[self.I] = p_interior
        return p

    def rates(self, beta: float, y: np.ndarray):
        """``(gamma', delta')``, ``p_I'`` and the pieces of the film at state ``y``."""
        self.nfev += 1
        pump, eps = self.pump, 1e-6
        gamma, delta = float(y[0]), float(y[1])
        p = self.pressure(beta, y[2:])
        ps = float(pump.inlet_pressure(beta))
        dps = (float(pump.inlet_pressure(beta + eps)) - float(pump.inlet_pressure(beta - eps))) / (2 * eps)
        load = pump.load_vector(beta)
        dload = (pump.load_vector(beta + eps) - pump.load_vector(beta - eps)) / (2 * eps)
        w = self.compliance.deflection(p, ps)
        rigid = CosineFilm(max(gamma, 0.0), delta)
        h = rigid.thickness(self.x[0], self.x[1]) + self.E @ w
        dh = rigid.gradient(self.x[0], self.x[1])[0] + self.Gp @ w
        d = self.basis.doflocs
        h_dofs = rigid.thickness(d[0], d[1]) + w
        if not (np.all(h > 0) and np.all(h_dofs > 0)):
            raise ElasticError(f"film closed (h_min = {min(h.min(), h_dofs.min()):.3g} c <= 0) at beta = {beta:.4f} rad")
        wedge = float(pump.wedge(beta))
        A = self.co.matrix(self.co.matrix_data("direct", h, None))
        R = (A @ p)[self.I] + self.src @ (6.0 * wedge * dh)
        shapes = rigid.rate_shapes(self.x[0], self.x[1])
        S = np.column_stack([self.src @ (12.0 * sh) for sh in shapes])
        a = -sla.lu_solve(self.K, R + self.c_s * dps, check_finite=False)
        B = sla.lu_solve(self.K, S, check_finite=False)
        LI = self.L[:, self.I]
        g = self.L @ p + ps * self.F_pocket + load
        rhs = LI @ a + self.kappa * g + (self.L[:, self.inlet].sum(axis=1) + self.F_pocket) * dps + dload
        try:
            r = np.linalg.solve(LI @ B, rhs)
        except np.linalg.LinAlgError:
            raise ElasticError(f"load balance singular at beta = {beta:.4f} rad (gamma = {gamma:.4g})") from None
        return r, a - B @ r, dict(p=p, w=w, h=h, dh=dh, h_dofs=h_dofs, wedge=wedge, dps=dps, shapes=shapes, A=A,
                                  B=B)

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
        r, dp, st = self.rates(beta, y)
        n, I = y.size, self.I
        J = np.empty((n, n))
        p, h = st["p"], st["h"]
        a0 = 3.0 * h**2 * (self.Gp @ p) * self.dx
        a1 = 3.0 * h**2 * (self.Gz @ p) * self.dx
        Bh = (self.Gp.T @ sp.diags(a0) + self.Gz.T @ sp.diags(a1)) @ self.E \
            + 6.0 * st["wedge"] * (self.E.T @ sp.diags(self.dx) @ self.Gp)
        Bh = sp.csr_matrix(Bh)[I]
        Da = -sla.lu_solve(self.K, st["A"].tocsr()[I][:, I].toarray() + Bh @ self.compliance.matrix[:, I],
                           check_finite=False)
        LI = self.L[:, I]
        dr = np.linalg.solve(LI @ st["B"], LI @ Da + self.kappa * LI)
        J[:2, 2:] = dr
        J[2:, 2:] = Da - st["B"] @ dr
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
        p, w, h = st["p"], st["w"], st["h"]
        C = self.compliance
        dw = C.matrix[:, self.I] @ dp + (C.matrix[:, self.inlet].sum(axis=1) + C.pocket) * st["dps"]
        hdot = r[0] * st["shapes"][0] + r[1] * st["shapes"][1] + self.E @ dw
        gp0, gp1 = self.Gp @ p, self.Gz @ p
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
                     start: str = "periodic", beta0: float = 0.0, method: str = "LSODA", rtol: float = 1e-6,
                     atol: float = 1e-8, max_step: float = math.pi / 16, points_per_revolution: int = 180,
                     periodic_tol: float = 1e-5, periodic_max_iter: int = 30,
                     kappa: float = BAUMGARTE) -> Trajectory:
    """Integrate the plunger shoe on an elastic support over the pump cycle, deflection squeeze included.

    Parameters
    ----------
    pump : EccentricPump
    compliance : Compliance
        Of the support, on the mesh of ``pump.surface`` (:func:`bearingfe.elastic.half_space`).
    revolutions : float
        Length of the run in shaft turns, > 0.
    start : {"periodic", "steady"}
        ``"steady"``: the quasi-static elastic equilibrium at the rigid steady
        state of ``beta0``; ``"periodic"``: from there, revolutions are
        repeated until ``max |(gamma, delta)(2 pi) - (gamma, delta)(0)| < periodic_tol``.
    method : {"LSODA", "Radau", "BDF"}
    rtol, atol : float
        Integrator tolerances (on ``gamma``, ``delta`` and the pressures).
    max_step : float
        Largest step [rad].
    points_per_revolution : int
        Output samples per turn, >= 8.
    kappa : float
        Baumgarte rate of the load balance [1/rad], > 0.

    Returns
    -------
    Trajectory
        With ``max_deflection``; ``status`` is ``"ruptured"`` if the film closes.
    """
    if not isinstance(pump, EccentricPump):
        raise ValueError(f"pump must be a bearingfe.EccentricPump, got {type(pump).__name__}")
    if not isinstance(compliance, Compliance):
        raise ValueError(f"compliance must be a bearingfe.elastic.Compliance, got {type(compliance).__name__}")
    if not math.isfinite(compliance.modulus):
        raise ValueError("compliance needs a finite modulus: on a rigid support (modulus inf) the pressure is "
                         "not a state; use bearingfe.simulate without elastic")
    if not (math.isfinite(revolutions) and revolutions > 0):
        raise ValueError(f"revolutions must be a finite number > 0, got {revolutions!r}")
    if start not in ("periodic", "steady"):
        raise ValueError(f"start must be 'periodic' or 'steady', got {start!r}")
    if method not in INTEGRATORS:
        raise ValueError(f"method must be one of {list(INTEGRATORS)}, got {method!r}")
    for name, v in (("rtol", rtol), ("atol", atol), ("max_step", max_step), ("kappa", kappa)):
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {v!r}")
    if int(points_per_revolution) < 8:
        raise ValueError(f"points_per_revolution must be >= 8, got {points_per_revolution!r}")
    mesh = compliance.mesh
    ratio = balance_ratio(pump, mesh, element=compliance.element)
    if ratio >= 1.0:
        raise LiftOffError(f"{pump.name!r}: balance ratio {ratio:.3f} >= 1: the shoe lifts off")
    t_start = time.perf_counter()
    dyn = _Dynamics(pump, compliance, float(kappa))
    gamma, delta = steady_state(pump, mesh, beta0, element=compliance.element)
    y0 = _start(pump, dyn, beta0, gamma, delta)
    iterations, residual = 0, math.nan
    if start == "periodic":
        while True:
            sol = _run(dyn, beta0, y0, beta0 + 2 * math.pi, method, rtol, atol, max_step)
            iterations += 1
            if sol.status != 0:
                break
            d = sol.y[:2, -1] - y0[:2]
            residual = float(np.max(np.abs(d)))
            y0 = sol.y[:, -1].copy()
            if residual < periodic_tol:
                break
            if iterations >= periodic_max_iter:
                raise RuntimeError(f"periodic start did not converge in {iterations} revolutions "
                                   f"(last residual {residual:.3g} >= periodic_tol = {periodic_tol})")
    beta1 = beta0 + 2 * math.pi * revolutions
    sol = _run(dyn, beta0, y0, beta1, method, rtol, atol, max_step)
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
        periodic_iterations=iterations, periodic_residual=residual,
        stats=MappingProxyType({"nfev": dyn.nfev, "factorizations": 0, "steps": int(sol.t.size),
                                "seconds": seconds, "solver_seconds": seconds, "dofs": float(mesh.n_nodes),
                                "balance_ratio": ratio}),
        max_deflection=cols["max_deflection"],
        pressures=np.array([dyn.pressure(b, y[2:]) for b, y in zip(betas, ys)]))


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
