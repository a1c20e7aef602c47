r"""Stability of a rigid symmetric rotor on two identical bearings: damped eigenvalues, logarithmic
decrement, Lund's threshold.

The rotor (mass ``m``, rigid, symmetric: the Jeffcott model of a rigid rotor) puts ``m/2`` and the
load ``W`` on each bearing; with the bearing's non-dimensional coefficients ``K c/W`` and
``C c omega/W`` and the time ``tau = omega t``, the journal's small motion ``u = x/c`` obeys

``M u'' + C u' + K u = 0``, ``M = (m/2) c omega^2 / W`` (the mass parameter; ``c omega^2/g`` for a
rotor carried by its weight).

A tilting-pad bearing keeps its pads' freedoms (:class:`~bearingfe.bearings.tilting_pad.PadAssemblyCoefficients`:
the eigenvalue problem is then exact at every whirl frequency, instead of the reduced coefficients at
one) with the pads' mass ``M_p/W`` on their rows. The eigenvalues ``lambda`` are in units of
``omega``; the logarithmic decrement of a mode is ``-2 pi Re(lambda) / |Im(lambda)|`` (negative:
unstable). For frequency-independent 2x2 coefficients Lund's closed form gives the threshold: the
whirl ratio ``gamma`` and the mass parameter ``M_crit`` at which a mode crosses the imaginary axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg

from .journal import DynamicCoefficients
from .tilting_pad import PadAssemblyCoefficients

__all__ = ["RotorModes", "rotor_modes", "lund_threshold", "log_decrement_map", "threshold_speed"]


@dataclass(frozen=True)
class RotorModes:
    """Damped eigenvalues of the rotor on its bearings.

    Attributes
    ----------
    eigenvalues : ndarray of complex
        ``lambda / omega`` [-] of the oscillating modes (``Im > 0``), least damped first.
    log_decrements : ndarray
        ``-2 pi Re(lambda) / Im(lambda)`` [-] of the same modes.
    stable : bool
        Every finite eigenvalue (oscillating or not) has a negative real part.
    """

    eigenvalues: np.ndarray
    log_decrements: np.ndarray
    stable: bool


def rotor_modes(coefficients: DynamicCoefficients | PadAssemblyCoefficients, mass_parameter: float,
                pad_mass: float = 0.0) -> RotorModes:
    """The damped modes of a rigid symmetric rotor on two identical bearings.

    Parameters
    ----------
    coefficients : DynamicCoefficients or PadAssemblyCoefficients
        Of one bearing at the rotor's operating point (``K c/W``, ``C c omega/W``).
    mass_parameter : float
        ``(m/2) c omega^2 / W`` [-], > 0.
    pad_mass : float
        Tilting pads only: each pad's non-dimensional mass
        (:meth:`~bearingfe.bearings.tilting_pad.TiltingPadBearing.pad_mass`), >= 0, on the rotation rows;
        zero-mass pads (and pivot deflections) follow the shaft without lag (their rows are constraints).
    """
    if not (math.isfinite(mass_parameter) and mass_parameter > 0):
        raise ValueError(f"mass_parameter must be > 0, got {mass_parameter!r}")
    if not (math.isfinite(pad_mass) and pad_mass >= 0):
        raise ValueError(f"pad_mass must be >= 0, got {pad_mass!r}")
    if isinstance(coefficients, PadAssemblyCoefficients):
        K, C, rotations = coefficients.system()
        masses = np.where(rotations, pad_mass / coefficients.load, 0.0)
    elif pad_mass:
        raise ValueError("pad_mass is for tilting pads (PadAssemblyCoefficients)")
    else:
        K, C = np.asarray(coefficients.K, float), np.asarray(coefficients.C, float)
        masses = np.zeros(K.shape[0])
    masses[:2] = mass_parameter
    n = K.shape[0]
    # first order: [u, v]' with v = u'; B [u, v]' = A [u, v]; massless pad rows are constraints
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -C]])
    B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), np.diag(masses)]])
    values = scipy.linalg.eig(A, B, right=False)
    finite = values[np.isfinite(values) & (np.abs(values) < 1e12)]
    scale = max(float(np.abs(finite).max()), 1.0)
    oscillating = finite[finite.imag > 1e-9 * scale]
    order = np.argsort(-oscillating.real / oscillating.imag)
    oscillating = oscillating[order]
    return RotorModes(eigenvalues=oscillating, log_decrements=-2 * math.pi * oscillating.real / oscillating.imag,
                      stable=bool(np.all(finite.real < 0)))


def lund_threshold(coefficients: DynamicCoefficients) -> tuple[float, float]:
    """Lund's stability threshold of a rigid rotor on frequency-independent coefficients.

    At the onset of instability the rotor whirls at ``lambda = i gamma``; the real and imaginary parts
    of ``det(K - M gamma^2 + i gamma C) = 0`` give the equivalent stiffness
    ``K_eq = (Kxx Cyy + Kyy Cxx - Kxy Cyx - Kyx Cxy) / (Cxx + Cyy)``, the whirl ratio
    ``gamma^2 = ((K_eq - Kxx)(K_eq - Kyy) - Kxy Kyx) / (Cxx Cyy - Cxy Cyx)`` and the critical mass
    parameter ``M_crit = K_eq / gamma^2``; the rotor is stable below it.

    Returns
    -------
    (float, float)
        ``M_crit`` [-] (``inf`` if no real whirl ratio exists: stable at every mass) and ``gamma`` [-].
    """
    K, C = np.asarray(coefficients.K, float), np.asarray(coefficients.C, float)
    if K.shape != (2, 2):
        raise ValueError("Lund's closed form is for 2x2 coefficients")
    k_eq = (K[0, 0] * C[1, 1] + K[1, 1] * C[0, 0] - K[0, 1] * C[1, 0] - K[1, 0] * C[0, 1]) / (C[0, 0] + C[1, 1])
    gamma2 = ((k_eq - K[0, 0]) * (k_eq - K[1, 1]) - K[0, 1] * K[1, 0]) / (C[0, 0] * C[1, 1] - C[0, 1] * C[1, 0])
    if not gamma2 > 0 or not k_eq > 0:
        return math.inf, math.nan
    return float(k_eq / gamma2), float(math.sqrt(gamma2))


def log_decrement_map(speeds, coefficients_at, mass_parameter_at, pad_mass_at=None) -> np.ndarray:
    """The smallest logarithmic decrement at each speed (a stability map).

    Parameters
    ----------
    speeds : sequence of float
        Shaft speeds [rad/s], increasing.
    coefficients_at : callable
        ``speed -> DynamicCoefficients or PadAssemblyCoefficients`` of one bearing at that speed (its
        equilibrium under the rotor's load: the Sommerfeld number changes with the speed).
    mass_parameter_at : callable
        ``speed -> (m/2) c omega^2 / W`` [-] (``c omega^2 / g`` for a rotor carried by its weight).
    pad_mass_at : callable, optional
        ``speed -> pad mass``: the pads' non-dimensional mass (tilting pads).

    Returns
    -------
    ndarray
        Smallest log decrement of the oscillating modes [-] at each speed (``inf`` with none).
    """
    out = []
    for speed in speeds:
        modes = rotor_modes(coefficients_at(speed), mass_parameter_at(speed),
                            0.0 if pad_mass_at is None else pad_mass_at(speed))
        out.append(float(modes.log_decrements.min()) if modes.log_decrements.size else math.inf)
    return np.array(out)


def threshold_speed(speeds, log_decrements) -> float:
    """The first speed at which the smallest log decrement turns negative, interpolated linearly between
    the two speeds around the sign change [rad/s]; ``inf`` if it never does, ``speeds[0]`` if it
    already is."""
    speeds, delta = np.asarray(speeds, float), np.asarray(log_decrements, float)
    if speeds.shape != delta.shape or speeds.ndim != 1 or not np.all(np.diff(speeds) > 0):
        raise ValueError("speeds must increase and match log_decrements")
    unstable = np.flatnonzero(delta < 0)
    if not unstable.size:
        return math.inf
    k = int(unstable[0])
    if k == 0:
        return float(speeds[0])
    a, b = delta[k - 1], delta[k]
    if not math.isfinite(a):
        return float(speeds[k])
    return float(speeds[k - 1] + (speeds[k] - speeds[k - 1]) * a / (a - b))
