"""Kinematics and inertia forces of the central crank-slider (paper 000).

Conventions
-----------
Crank angle ``phi = omega t`` from the outer dead centre (slider farthest from
the shaft), crank turning counter-clockwise; crank pin A = r (cos phi, sin phi),
wrist pin B = (x, 0) with ``x = r cos phi + l cos beta``, rod angle
``beta = asin(lambda sin phi)``, ``lambda = r/l``. The rod's centre of mass S
lies on AB at ``l_a`` from A (``l_b = l - l_a`` from B).

The slider *position* ``x`` is measured from the shaft axis; the paper's
*displacement* ``X = r + l - x`` is measured from the outer dead centre.
Paper 000 (Table 1) prints ``X`` but its velocity and acceleration columns are
the derivatives of ``x`` (opposite sign); the package gives both and uses
``x`` for velocities and accelerations.

Slider acceleration as a Fourier series (exact for ``lambda < 1``)::

    x'' = -r omega^2 * sum_k c_k cos(k phi),  c_1 = 1, c_2 = A2, c_4 = -A4, c_6 = A6, ...
    A2 = lam + lam^3/4 + 15 lam^5/128,  A4 = lam^3/4 + 3 lam^5/16,  A6 = 9 lam^5/128

Paper 000's eq. (1) prints ``cos phi - A2 cos 2phi + A4 cos 4phi - A6 cos 6phi``
with ``A4 = -lam^3/4 + ...``: both signs are slips (checked against the exact
motion, see tests). The reciprocating inertia force is
``P = -m_n x'' = m_n r omega^2 sum_k c_k cos(k phi)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping

import numpy as np

from .machines import CrankMechanism, CrankSlider

__all__ = [
    "rod_angle",
    "slider_position",
    "slider_displacement",
    "slider_displacement_series",
    "slider_velocity",
    "slider_velocity_series",
    "slider_acceleration",
    "slider_acceleration_series",
    "rod_cg_position",
    "rod_cg_velocity",
    "rod_cg_acceleration",
    "rod_cg_acceleration_series",
    "rod_angular_velocity",
    "rod_angular_acceleration",
    "rod_angular_velocity_series",
    "rod_angular_acceleration_series",
    "rod_series_coefficients",
    "harmonic_coefficients_series",
    "acceleration_harmonics",
    "two_mass_replacement",
    "reduced_crank_mass",
    "rotating_mass",
    "reciprocating_mass",
    "residual_inertia",
    "rotating_force",
    "reciprocating_force",
    "inertia_moment",
    "resultant_inertia",
    "resultant_inertia_moment",
    "theoretical_flow",
    "min_transmission_angle",
    "CrankSummary",
    "analyze",
]

_GRID = 2**14  # crank-angle samples for maxima and Fourier analysis


def _omega(omega: float) -> float:
    if not (isinstance(omega, (int, float)) and math.isfinite(omega) and omega > 0):
        raise ValueError(f"omega must be > 0 rad/s, got {omega!r}")
    return float(omega)


def rod_angle(cs: CrankSlider, phi) -> np.ndarray:
    """Rod angle beta = asin(lambda sin phi) [rad]."""
    return np.arcsin(cs.lam * np.sin(phi))


# --- slider -----------------------------------------------------------------


def slider_position(cs: CrankSlider, phi) -> np.ndarray:
    """Exact wrist-pin position from the shaft axis, x = r cos phi + l cos beta [m]."""
    return cs.crank * np.cos(phi) + cs.rod * np.cos(rod_angle(cs, phi))


def slider_displacement(cs: CrankSlider, phi) -> np.ndarray:
    """Exact displacement from the outer dead centre, X = r[1 - cos phi + (1 - cos beta)/lam] [m]."""
    return cs.crank + cs.rod - slider_position(cs, phi)


def slider_displacement_series(cs: CrankSlider, phi) -> np.ndarray:
    """Second-order series X ~ r[1 - cos phi + lam/4 (1 - cos 2 phi)] [m] (paper 000, Table 1)."""
    return cs.crank * (1 - np.cos(phi) + cs.lam / 4 * (1 - np.cos(2 * phi)))


def slider_velocity(cs: CrankSlider, omega: float, phi) -> np.ndarray:
    """Exact slider velocity dx/dt = -r omega (sin phi + cos phi tan beta) [m/s]."""
    beta = rod_angle(cs, phi)
    return -cs.crank * _omega(omega) * (np.sin(phi) + np.cos(phi) * np.tan(beta))


def slider_velocity_series(cs: CrankSlider, omega: float, phi) -> np.ndarray:
    """Series dx/dt ~ -r omega (sin phi + lam/2 sin 2 phi) [m/s]."""
    return -cs.crank * _omega(omega) * (np.sin(phi) + cs.lam / 2 * np.sin(2 * phi))


def slider_acceleration(cs: CrankSlider, omega: float, phi) -> np.ndarray:
    """Exact slider acceleration at constant omega [m/s^2].

    ``x'' = -r omega^2 (cos phi - sin phi tan beta + lam cos^2 phi / cos^3 beta)``.
    """
    lam = cs.lam
    beta = rod_angle(cs, phi)
    return -cs.crank * _omega(omega) ** 2 * (
        np.cos(phi) - np.sin(phi) * np.tan(beta) + lam * np.cos(phi) ** 2 / np.cos(beta) ** 3
    )


def slider_acceleration_series(cs: CrankSlider, omega: float, phi, order: int = 6) -> np.ndarray:
    """Slider acceleration from the closed-form harmonic series up to ``order`` (2, 4 or 6) [m/s^2]."""
    coeffs = harmonic_coefficients_series(cs.lam, order)
    total = sum(c * np.cos(k * np.asarray(phi, dtype=float)) for k, c in coeffs.items())
    return -cs.crank * _omega(omega) ** 2 * total


def harmonic_coefficients_series(lam: float, order: int = 6) -> dict:
    """Closed-form coefficients c_k of ``x'' = -r w^2 sum c_k cos k phi``, to O(lam^5).

    Returns ``{1: 1, 2: A2, 4: -A4, 6: A6}`` truncated at ``order`` (2, 4 or 6).
    """
    if order not in (2, 4, 6):
        raise ValueError(f"order must be 2, 4 or 6, got {order!r}")
    if not 0 < lam < 1:
        raise ValueError(f"lam must be in (0, 1), got {lam!r}")
    coeffs = {1: 1.0, 2: lam + lam**3 / 4 + 15 * lam**5 / 128}
    if order >= 4:
        coeffs[4] = -(lam**3 / 4 + 3 * lam**5 / 16)
    if order >= 6:
        coeffs[6] = 9 * lam**5 / 128
    return coeffs


def acceleration_harmonics(cs: CrankSlider, max_order: int = 8, samples: int = _GRID) -> dict:
    """Fourier coefficients c_k (k = 1..max_order) of the exact slider acceleration.

    ``x''(phi) = -r omega^2 sum_k c_k cos(k phi)``; the motion is even in phi,
    so there are no sine terms. Odd orders above 1 vanish (to round-off).
    """
    if max_order < 1:
        raise ValueError(f"max_order must be >= 1, got {max_order!r}")
    phi = 2 * np.pi * np.arange(samples) / samples
    y = -slider_acceleration(cs, 1.0, phi) / cs.crank
    spec = np.fft.rfft(y) / samples
    return {k: float(2 * spec[k].real) for k in range(1, max_order + 1)}


# --- rod ----------------------------------------------------------------------


def rod_cg_position(cs: CrankSlider, phi):
    """Rod centre of mass (x_s, y_s) [m]: x_s = r cos phi + l_a cos beta, y_s = l_b lam sin phi."""
    beta = rod_angle(cs, phi)
    xs = cs.crank * np.cos(phi) + cs.rod_cg_from_crank_pin * np.cos(beta)
    ys = cs.rod_cg_from_wrist_pin * cs.lam * np.sin(phi)
    return xs, ys


def rod_cg_velocity(cs: CrankSlider, omega: float, phi):
    """Rod centre-of-mass velocity (v_x, v_y) [m/s], exact."""
    w = _omega(omega)
    beta = rod_angle(cs, phi)
    ka = cs.rod_cg_from_crank_pin / cs.rod
    vx = -cs.crank * w * (np.sin(phi) + ka * np.cos(phi) * np.tan(beta))
    vy = cs.crank * w * (1 - ka) * np.cos(phi)
    return vx, vy


def rod_cg_acceleration(cs: CrankSlider, omega: float, phi):
    """Rod centre-of-mass acceleration (a_x, a_y) [m/s^2], exact at constant omega.

    ``a_x = -r w^2 [cos phi + (l_a/l)(lam cos^2 phi/cos^3 beta - sin phi tan beta)]``.
    Paper 000 (Table 1) omits the factor ``l_a/l`` here (it repeats the
    slider formula) and its series uses ``l_b/l``; with l_a measured from the
    crank pin the factor is ``l_a/l`` (checked by differentiation in the tests).
    """
    w = _omega(omega)
    beta = rod_angle(cs, phi)
    ka = cs.rod_cg_from_crank_pin / cs.rod
    ax = -cs.crank * w**2 * (
        np.cos(phi) + ka * (cs.lam * np.cos(phi) ** 2 / np.cos(beta) ** 3 - np.sin(phi) * np.tan(beta))
    )
    ay = -cs.crank * w**2 * (1 - ka) * np.sin(phi)
    return ax, ay


def rod_cg_acceleration_series(cs: CrankSlider, omega: float, phi):
    """Series (a_x, a_y) ~ -r w^2 (cos phi + (l_a/l) lam cos 2phi, (l_b/l) sin phi) [m/s^2]."""
    w = _omega(omega)
    ka = cs.rod_cg_from_crank_pin / cs.rod
    ax = -cs.crank * w**2 * (np.cos(phi) + ka * cs.lam * np.cos(2 * phi))
    ay = -cs.crank * w**2 * (1 - ka) * np.sin(phi)
    return ax, ay


def rod_angular_velocity(cs: CrankSlider, omega: float, phi) -> np.ndarray:
    """Rod angular velocity d(beta)/dt = omega lam cos phi / cos beta [rad/s] (paper's sign)."""
    return _omega(omega) * cs.lam * np.cos(phi) / np.cos(rod_angle(cs, phi))


def rod_angular_acceleration(cs: CrankSlider, omega: float, phi) -> np.ndarray:
    """Rod angular acceleration -omega^2 tan beta [1 - (lam cos phi / cos beta)^2] [rad/s^2]."""
    beta = rod_angle(cs, phi)
    return -_omega(omega) ** 2 * np.tan(beta) * (1 - (cs.lam * np.cos(phi) / np.cos(beta)) ** 2)


def rod_series_coefficients(lam: float) -> tuple:
    """Coefficients (C1, C3, C5) of the rod series (Kozesnik form), to O(lam^4).

    ``omega_rod ~ lam w (C1 cos phi - C3/3 cos 3phi + C5/5 cos 5phi)``,
    ``eps_rod ~ -lam w^2 (C1 sin phi - C3 sin 3phi + C5 sin 5phi)`` with
    ``C1 = 1 + lam^2/8 + 3 lam^4/64``, ``C3 = 3 lam^2/8 + 27 lam^4/128``,
    ``C5 = 15 lam^4/128``.
    """
    return (1 + lam**2 / 8 + 3 * lam**4 / 64, 3 * lam**2 / 8 + 27 * lam**4 / 128, 15 * lam**4 / 128)


def rod_angular_velocity_series(cs: CrankSlider, omega: float, phi) -> np.ndarray:
    """Series rod angular velocity [rad/s], error O(lam^7)."""
    c1, c3, c5 = rod_series_coefficients(cs.lam)
    phi = np.asarray(phi, dtype=float)
    return cs.lam * _omega(omega) * (c1 * np.cos(phi) - c3 / 3 * np.cos(3 * phi) + c5 / 5 * np.cos(5 * phi))


def rod_angular_acceleration_series(cs: CrankSlider, omega: float, phi) -> np.ndarray:
    """Series rod angular acceleration [rad/s^2], error O(lam^7)."""
    c1, c3, c5 = rod_series_coefficients(cs.lam)
    phi = np.asarray(phi, dtype=float)
    return -cs.lam * _omega(omega) ** 2 * (c1 * np.sin(phi) - c3 * np.sin(3 * phi) + c5 * np.sin(5 * phi))


# --- masses and inertia forces ---------------------------------------------------


def two_mass_replacement(cs: CrankSlider) -> tuple:
    """Statically equivalent point masses of the rod (m_a at A, m_b at B) [kg].

    ``m_a = M3 l_b / l``, ``m_b = M3 l_a / l`` (same total mass, same centre of mass).
    """
    return cs.rod_mass * cs.rod_cg_from_wrist_pin / cs.rod, cs.rod_mass * cs.rod_cg_from_crank_pin / cs.rod


def reduced_crank_mass(cs: CrankSlider) -> float:
    """Crank assembly mass reduced to the crank pin, m1 = M1 rho1 / r [kg]."""
    return cs.crank_mass * cs.crank_cg_radius / cs.crank


def rotating_mass(cs: CrankSlider) -> float:
    """Rotating mass at the crank pin, m_B = m1 + m_a [kg]."""
    return reduced_crank_mass(cs) + two_mass_replacement(cs)[0]


def reciprocating_mass(cs: CrankSlider) -> float:
    """Reciprocating mass at the wrist pin, m_n = M2 + m_b [kg]."""
    return cs.slider_mass + two_mass_replacement(cs)[1]


def residual_inertia(cs: CrankSlider) -> float:
    """Residual rod moment of inertia dJ = J_S - M3 l_a l_b [kg m^2].

    The two point masses carry ``m_a l_a^2 + m_b l_b^2 = M3 l_a l_b`` about S;
    dJ is what they miss. Paper 000 prints ``dJ = M3 (l_a^2 - l_a l_b)`` and
    substitutes ``l_b^2 - l_a l_b``: that is this formula with the (unprinted)
    assumption ``J_S = M3 l_b^2``.

    Raises
    ------
    ValueError
        If ``cs.rod_inertia`` is not given.
    """
    if cs.rod_inertia is None:
        raise ValueError("rod_inertia (J_S about the rod's centre of mass) is required for the residual inertia")
    return cs.rod_inertia - cs.rod_mass * cs.rod_cg_from_crank_pin * cs.rod_cg_from_wrist_pin


def rotating_force(cs: CrankSlider, omega: float, phi):
    """Centrifugal force of m_B along the crank, components (P_x, P_y) [N]."""
    p = rotating_mass(cs) * cs.crank * _omega(omega) ** 2
    return p * np.cos(phi), p * np.sin(phi)


def reciprocating_force(cs: CrankSlider, omega: float, phi) -> np.ndarray:
    """Reciprocating inertia force P_n = -m_n x'' along the slider axis [N] (exact motion)."""
    return -reciprocating_mass(cs) * slider_acceleration(cs, omega, phi)


def inertia_moment(cs: CrankSlider, omega: float, phi) -> np.ndarray:
    """Residual inertia moment of the rod, M0 = dJ eps_rod [N m] (paper 000's eq. 3).

    ``eps_rod`` as :func:`rod_angular_acceleration` (about ``-lam w^2 sin phi``,
    the paper's Table 1). The paper's Tables 4 and 5 print the opposite sign
    (``+lam w^2 sin phi``); the amplitudes are the same (docs/papers.md).
    """
    return residual_inertia(cs) * rod_angular_acceleration(cs, omega, phi)


def _phase_sums(z: int, k: int, weights=None) -> tuple:
    gam = 2 * np.pi * np.arange(z) / z
    w = np.ones(z) if weights is None else np.asarray(weights, dtype=float)
    return abs(np.sum(w * np.exp(1j * k * gam))), abs(np.sum(w * np.exp(-1j * k * gam)))


def _order_amplitude(mech: CrankMechanism, cranks: int, k: int, coeff: float, weights=None) -> float:
    cs = mech.linkage
    base = cs.crank * mech.drive.omega**2
    mr, mn = rotating_mass(cs), reciprocating_mass(cs)
    fwd, bwd = _phase_sums(cranks, k, weights)
    forward = (mr if k == 1 else 0.0) + 0.5 * mn * coeff
    return base * (abs(forward) * fwd + abs(0.5 * mn * coeff) * bwd)


def resultant_inertia(mech: CrankMechanism, cranks: int | None = None, max_order: int = 6) -> dict:
    """Amplitude of the resultant inertia force of each order for z cranks at 360/z deg [N].

    Complex-vector sum of paper 000's eq. (7): order k contributes a forward
    vector ``(delta_k1 m_B + m_n c_k/2) r w^2 e^{ik phi} sum_j e^{ik gamma_j}``
    and a backward one ``m_n c_k/2 r w^2 e^{-ik phi} sum_j e^{-ik gamma_j}``;
    the amplitude is the largest magnitude of their sum, ``|fwd| + |bwd|``.
    Coefficients c_k come from the Fourier analysis of the exact motion.
    Orders that balance give 0 (to round-off).
    """
    z = mech.cylinders if cranks is None else int(cranks)
    if z < 1:
        raise ValueError(f"cranks must be >= 1, got {cranks!r}")
    coeffs = acceleration_harmonics(mech.linkage, max_order)
    out = {}
    for k in range(1, max_order + 1):
        amp = _order_amplitude(mech, z, k, coeffs[k])
        out[k] = 0.0 if amp < 1e-9 * mech.linkage.crank * mech.drive.omega**2 * (1 + rotating_mass(mech.linkage)) else amp
    return out


def resultant_inertia_moment(
    mech: CrankMechanism, cranks: int | None = None, spacing: float | None = None, max_order: int = 6
) -> dict:
    """Amplitude of the resultant inertia moment of each order (eq. 8) [N m].

    Crank planes at ``Y_j = j * spacing`` from the first (j = 0..z-1); the
    moment is taken about the first plane. Paper 000 prints no spacing for
    SNT-32, so it gives no numbers for this.
    """
    z = mech.cylinders if cranks is None else int(cranks)
    s = mech.cylinder_spacing if spacing is None else float(spacing)
    if s < 0:
        raise ValueError(f"spacing must be >= 0 m, got {spacing!r}")
    coeffs = acceleration_harmonics(mech.linkage, max_order)
    y = s * np.arange(z)
    return {k: _order_amplitude(mech, z, k, coeffs[k], weights=y) for k in range(1, max_order + 1)}


# --- pump and summary --------------------------------------------------------------


def theoretical_flow(mech: CrankMechanism) -> float:
    """Theoretical flow of a plunger pump, Q = z (pi d^2/4) (2 r) n [m^3/s]."""
    if mech.plunger_diameter <= 0:
        raise ValueError(f"plunger_diameter must be > 0 m for a pump, got {mech.plunger_diameter!r}")
    area = math.pi * mech.plunger_diameter**2 / 4
    return mech.cylinders * area * mech.linkage.stroke * mech.drive.omega / (2 * math.pi)


def min_transmission_angle(lam: float) -> float:
    """Smallest transmission angle of a central crank-slider, acos(lam) [rad]."""
    if not 0 < lam < 1:
        raise ValueError(f"lam must be in (0, 1), got {lam!r}")
    return math.acos(lam)


@dataclass(frozen=True)
class CrankSummary:
    """Kinematic and inertia summary of one crank-slider machine (SI).

    Maxima are over the exact motion (2^14 crank angles). ``harmonics`` maps
    order k -> c_k of ``x'' = -r w^2 sum c_k cos k phi`` (Fourier of the exact
    motion); ``P_rec1``, ``P_rec2`` are ``m_n r w^2 |c_1|``, ``|c_2|``.
    ``delta_J`` and ``M0_max`` are NaN-free: ``None`` when J_S is unknown.
    """

    omega: float
    lam: float
    v_max: float
    v_mean: float
    v_ratio: float
    a_max: float
    rod_omega_max: float
    rod_eps_max: float
    m_a: float
    m_b: float
    m_1: float
    m_rot: float
    m_rec: float
    P_rot: float
    P_rec1: float
    P_rec2: float
    flow_theoretical: float
    min_transmission_angle: float
    delta_J: float | None = None
    M0_max: float | None = None
    harmonics: Mapping[int, float] = field(default_factory=dict)


def analyze(mech: CrankMechanism, max_order: int = 8) -> CrankSummary:
    """Kinematics, replacement masses, inertia forces and flow of ``mech``."""
    cs, w = mech.linkage, mech.drive.omega
    phi = 2 * np.pi * np.arange(_GRID) / _GRID
    v = slider_velocity(cs, w, phi)
    v_mean = 2 * cs.stroke * w / (2 * np.pi)
    m_a, m_b = two_mass_replacement(cs)
    m_rec = reciprocating_mass(cs)
    harm = acceleration_harmonics(cs, max_order)
    base = cs.crank * w**2
    eps_max = float(np.max(np.abs(rod_angular_acceleration(cs, w, phi))))
    dj = residual_inertia(cs) if cs.rod_inertia is not None else None
    return CrankSummary(
        omega=w,
        lam=cs.lam,
        v_max=float(np.max(np.abs(v))),
        v_mean=v_mean,
        v_ratio=float(np.max(np.abs(v))) / v_mean,
        a_max=float(np.max(np.abs(slider_acceleration(cs, w, phi)))),
        rod_omega_max=float(np.max(np.abs(rod_angular_velocity(cs, w, phi)))),
        rod_eps_max=eps_max,
        m_a=m_a,
        m_b=m_b,
        m_1=reduced_crank_mass(cs),
        m_rot=rotating_mass(cs),
        m_rec=m_rec,
        P_rot=rotating_mass(cs) * base,
        P_rec1=m_rec * base * abs(harm[1]),
        P_rec2=m_rec * base * abs(harm[2]),
        flow_theoretical=theoretical_flow(mech) if mech.plunger_diameter > 0 else 0.0,
        min_transmission_angle=min_transmission_angle(cs.lam),
        delta_J=dj,
        M0_max=None if dj is None else abs(dj) * eps_max,
        harmonics=MappingProxyType(dict(harm)),
    )
