"""Efficiency of a crank-slider with joint and guide friction (paper 003, cold pilger mill).

Quasi-static free-body analysis of a massless crank (1), rod (2) and slider
(3, the stand) with friction moments ``mu_i |F| d_i/2`` in the joints O
(main bearing), A (crank pin), B (stand pin) and Coulomb friction ``mu4 |N|``
on the guide. The technological force T opposes the stand's motion.
Crank angle ``theta`` from the outer dead centre, crank turning
counter-clockwise at ``omega1 > 0``; geometry as :mod:`bearingfe.mechanisms.crank`.

Rod force P (acting on the slider at B, and -P on the crank at A). Slider
and rod equilibrium give, with ``s = sign(v)``::

    P_x = s (T + mu4 |P_y|)
    l cos(beta) P_y + l sin(beta) P_x = -|P| [mu2 d2/2 sgn(w2 - w1) + mu3 d3/2 sgn(w2)]

solved by fixed-point iteration (a contraction for realistic friction);
crank equilibrium then gives the driving moment. The instantaneous loss
coefficient is friction power / driving power and ``eta = 1 - loss``;
energy balance ``M_d w1 = T |v| + friction power`` is an independent check.

Paper 003 derives its formulas from a velocity plan with slips (e.g. its
``omega2/V`` step and ``F = T/(2 psi)``, and ``N = T/tg(phi)`` instead of
``T tan(beta)``); the package uses exact kinematics and the free-body
analysis above. Transmission angle ``psi = 90 deg - |beta|``: the paper's
"pressure angle" whose approach to 90 deg raises efficiency.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .machines import Linkage, MillDrive

__all__ = [
    "Linkage",
    "JointForces",
    "joint_forces",
    "transmission_angle",
    "loss_coefficient",
    "efficiency",
    "loss_first_order",
    "working_mask",
    "CycleResult",
    "cycle",
]


def _angles(link: Linkage, theta):
    th = np.asarray(theta, dtype=float)
    if np.any(~np.isfinite(th)):
        raise ValueError(f"theta must be finite (rad), got {theta!r}")
    beta = np.arcsin(link.lam * np.sin(th))
    w2 = -link.lam * np.cos(th) / np.cos(beta)          # rod angular velocity per unit w1
    v = -link.crank * (np.sin(th) + np.cos(th) * np.tan(beta))  # slider velocity per unit w1
    return th, beta, w2, v


def transmission_angle(link: Linkage, theta) -> np.ndarray:
    """Transmission angle psi = 90 deg - |beta| between rod and guide normal [rad]."""
    _, beta, _, _ = _angles(link, theta)
    return np.pi / 2 - np.abs(beta)


@dataclass(frozen=True)
class JointForces:
    """Quasi-static forces at crank angles theta for load T (arrays, SI; per unit w1 for powers).

    Attributes
    ----------
    px, py : ndarray
        Rod force on the slider [N].
    force : ndarray
        |P|, the load on each joint [N].
    normal : ndarray
        Guide normal force |N| = |P_y| [N].
    drive_moment : ndarray
        Driving moment on the crank M_d [N m].
    useful_power, friction_power, drive_power : ndarray
        T |v|, total friction power and M_d w1 [W] at w1 = omega.
    """

    px: np.ndarray
    py: np.ndarray
    force: np.ndarray
    normal: np.ndarray
    drive_moment: np.ndarray
    useful_power: np.ndarray
    friction_power: np.ndarray
    drive_power: np.ndarray


def joint_forces(link: Linkage, theta, load: float = 1.0, omega: float = 1.0,
                 tol: float = 1e-13, max_iter: int = 500) -> JointForces:
    """Free-body solution of the crank-slider with friction (see module docstring).

    Parameters
    ----------
    link : Linkage
    theta : float or array
        Crank angle from the outer dead centre [rad].
    load : float
        Technological force T [N], > 0.
    omega : float
        Crank speed w1 [rad/s], > 0 (scales the powers only).
    """
    if not (math.isfinite(load) and load > 0):
        raise ValueError(f"load must be > 0 N, got {load!r}")
    if not (math.isfinite(omega) and omega > 0):
        raise ValueError(f"omega must be > 0 rad/s, got {omega!r}")
    th, beta, w2, v = _angles(link, theta)
    (d1, d2, d3), (mu1, mu2, mu3), mu4 = link.pin_diameters, link.pin_friction, link.guide_friction
    s = np.where(v >= 0, 1.0, -1.0)
    k_rod = mu2 * d2 / 2 * np.sign(w2 - 1.0) + mu3 * d3 / 2 * np.sign(w2)
    px = s * load * np.ones_like(th)
    py = -np.tan(beta) * px
    for _ in range(max_iter):
        mag = np.hypot(px, py)
        px_new = s * (load + mu4 * np.abs(py))
        py_new = (-k_rod * mag / link.rod - np.sin(beta) * px_new) / np.cos(beta)
        change = np.max(np.abs(px_new - px) + np.abs(py_new - py))
        px, py = px_new, py_new
        if change <= tol * load:
            break
    else:
        raise ValueError("friction too large: force iteration did not converge (reduce friction coefficients)")
    mag = np.hypot(px, py)
    ax, ay = link.crank * np.cos(th), link.crank * np.sin(th)
    m_drive = ax * py - ay * px + mu1 * d1 / 2 * mag + mu2 * d2 / 2 * mag * np.sign(1.0 - w2)
    fric = (mu1 * d1 / 2 * mag + mu2 * d2 / 2 * mag * np.abs(1.0 - w2) + mu3 * d3 / 2 * mag * np.abs(w2)
            + mu4 * np.abs(py) * np.abs(v))
    return JointForces(px, py, mag, np.abs(py), m_drive, load * np.abs(v) * omega, fric * omega, m_drive * omega)


def loss_coefficient(link: Linkage, theta) -> np.ndarray:
    """Instantaneous loss coefficient = friction power / driving power [-] (1 at the dead centres)."""
    jf = joint_forces(link, theta)
    return jf.friction_power / jf.drive_power


def efficiency(link: Linkage, theta) -> np.ndarray:
    """Instantaneous efficiency eta = useful power / driving power [-] (independent of T).

    ``theta`` from the outer dead centre [rad]; 0 at the dead centres where
    the stand is at rest.
    """
    jf = joint_forces(link, theta)
    return jf.useful_power / jf.drive_power


def loss_first_order(link: Linkage, theta) -> np.ndarray:
    """Loss coefficient to first order in friction (paper 003's structure, corrected) [-].

    Joint load from the frictionless analysis ``F = T/sin(psi)``, guide
    normal force ``T tan(beta)``, driving power ``T |v|`` (plus friction);
    valid away from the dead centres. Agrees with :func:`loss_coefficient`
    to O(mu^2).
    """
    th, beta, w2, v = _angles(link, theta)
    (d1, d2, d3), (mu1, mu2, mu3), mu4 = link.pin_diameters, link.pin_friction, link.guide_friction
    f = 1.0 / np.cos(beta)
    fric = f * (mu1 * d1 / 2 + mu2 * d2 / 2 * np.abs(1.0 - w2) + mu3 * d3 / 2 * np.abs(w2)) \
        + mu4 * np.abs(np.tan(beta)) * np.abs(v)
    return fric / (np.abs(v) + fric)


def working_mask(theta, idle_zone: float) -> np.ndarray:
    """True where the crank angle is outside the idle zones (width ``idle_zone``, centred on 0 and pi)."""
    th = np.mod(np.asarray(theta, dtype=float), 2 * np.pi)
    half = idle_zone / 2
    near0 = (th < half) | (th > 2 * np.pi - half)
    near_pi = np.abs(th - np.pi) < half
    return ~(near0 | near_pi)


@dataclass(frozen=True)
class CycleResult:
    """Work per revolution over the working zones (idle zones carry no load).

    Attributes
    ----------
    friction_work, useful_work, drive_work : float
        [J] per revolution.
    efficiency : float
        useful_work / drive_work [-].
    min_transmission_angle : float
        Smallest transmission angle in the working zones [rad].
    """

    friction_work: float
    useful_work: float
    drive_work: float
    efficiency: float
    min_transmission_angle: float


def cycle(mill: MillDrive, samples: int = 4001) -> CycleResult:
    """Friction, useful and driving work per crank revolution over the working zones.

    Work is ``int P d(theta)/w1`` over the two working zones (Simpson's rule
    on each zone), the paper's ``A = int mu_x T/sin(psi) dH``.
    """
    if mill.load <= 0:
        raise ValueError(f"load must be > 0 N for the work per cycle, got {mill.load!r}")
    from scipy.integrate import simpson

    half = mill.idle_zone / 2
    totals = np.zeros(3)
    psi_min = np.pi / 2
    for a, b in ((half, np.pi - half), (np.pi + half, 2 * np.pi - half)):
        th = np.linspace(a, b, samples)
        jf = joint_forces(mill.linkage, th, mill.load, 1.0)
        for i, p in enumerate((jf.friction_power, jf.useful_power, jf.drive_power)):
            totals[i] += simpson(p, x=th)
        psi_min = min(psi_min, float(np.min(transmission_angle(mill.linkage, th))))
    return CycleResult(float(totals[0]), float(totals[1]), float(totals[2]), float(totals[1] / totals[2]), psi_min)
