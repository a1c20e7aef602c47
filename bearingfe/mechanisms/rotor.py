"""Unbalanced rotor on an elastic frame and the column-height design method (paper 002).

Model: frame (plate mass M, lateral column stiffness C) with coordinate x1,
rotor shaft centre x2 on a shaft of stiffness c, rotor mass m with its centre
of mass at e from the shaft centre::

    M x1'' + C x1 + c (x1 - x2) = 0,    m x2'' + c (x2 - x1) = m e w^2 cos(w t)

so ``det(K - p^2 Mass) = (C - M p^2)(c - m p^2) - c m p^2`` (paper eq. 1).
Vertically the frame is rigid. The rotor's *mass centre* moves on an ellipse
with semi-axes ``a = c e (C - M w^2)/Delta`` (horizontal, eq. 6) and
``b = c e/(c - m w^2)`` (vertical).

Bearing reaction: the shaft force on the rotor is ``m w^2`` times the
mass-centre amplitude, i.e. ``m w^2 |a|`` (rigid supports: ``m w^2 e``).
Paper 002 writes ``m w^2 (a + e)``, counting e twice when a is the
mass-centre semi-axis of eq. (6); the package uses ``m w^2 |a|`` and gives
the paper's expression separately (:func:`paper_reaction`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.machine import Material
from .machines import Frame, Rotor, RotorFrame, Section

__all__ = [
    "shaft_stiffness",
    "column_stiffness",
    "frame_for",
    "natural_frequencies",
    "orbit",
    "Orbit",
    "bearing_reaction",
    "reaction_increase",
    "paper_reaction",
    "ExclusionRow",
    "exclusion_table",
    "natural_frequency_curves",
]


def _omega(omega: float) -> float:
    if not (isinstance(omega, (int, float)) and math.isfinite(omega) and omega > 0):
        raise ValueError(f"omega must be > 0 rad/s, got {omega!r}")
    return float(omega)


def shaft_stiffness(rotor: Rotor) -> float:
    """Lateral stiffness at mid-span of a simply supported round shaft [N/m].

    ``c = 48 E I / l^3`` with ``I = pi d^4/64``, i.e. ``3 E pi d^4/(4 l^3)`` (paper eq. 7).
    """
    e = rotor.material.youngs_modulus
    return 3.0 * e * math.pi * rotor.shaft_diameter**4 / (4.0 * rotor.shaft_length**3)


def column_stiffness(section: Section, height: float, material: Material, axis: str = "x", columns: int = 1):
    """Lateral stiffness of ``columns`` cantilever columns in parallel, ``n 3 E I/L^3`` [N/m].

    ``height`` may be an array; it must be > 0.
    """
    h = np.asarray(height, dtype=float)
    if np.any(~np.isfinite(h)) or np.any(h <= 0):
        raise ValueError(f"height must be > 0 m, got {height!r}")
    if not isinstance(columns, int) or columns < 1:
        raise ValueError(f"columns must be an integer >= 1, got {columns!r}")
    k = columns * 3.0 * material.youngs_modulus * section.second_moment(axis) / h**3
    return float(k) if k.ndim == 0 else k


def frame_for(system: RotorFrame, section: Section | None = None, height: float | None = None,
              columns: int | None = None, axis: str | None = None) -> Frame:
    """The :class:`~bearingfe.mechanisms.machines.Frame` of ``system`` with any design value overridden."""
    sec = system.section if section is None else section
    return Frame(
        mass=system.plate_mass,
        stiffness=column_stiffness(
            sec,
            system.height if height is None else height,
            system.column_material,
            system.axis if axis is None else axis,
            system.columns if columns is None else columns,
        ),
    )


def _pq(rotor: Rotor, mass: float, stiff):
    c, m = shaft_stiffness(rotor), rotor.mass
    big_c = np.asarray(stiff, dtype=float)
    b = big_c * m + c * (m + mass)
    disc = np.sqrt(np.maximum(b * b - 4.0 * big_c * c * mass * m, 0.0))
    return b, disc, m * mass


def natural_frequencies(rotor: Rotor, frame: Frame) -> tuple:
    """Natural frequencies (p1, p2), p1 >= p2 [rad/s], closed form of paper eq. (2)."""
    b, disc, mm = _pq(rotor, frame.mass, frame.stiffness)
    return float(np.sqrt((b + disc) / (2 * mm))), float(np.sqrt((b - disc) / (2 * mm)))


def _delta(rotor: Rotor, frame: Frame, w: float) -> float:
    c, m = shaft_stiffness(rotor), rotor.mass
    return (frame.stiffness - frame.mass * w**2) * (c - m * w**2) - c * m * w**2


@dataclass(frozen=True)
class Orbit:
    """Steady forced response at one speed (signed amplitudes, in phase with the unbalance).

    Attributes
    ----------
    a : float
        Horizontal semi-axis of the rotor mass-centre ellipse [m].
    b : float
        Vertical semi-axis [m].
    x1 : float
        Frame (plate) amplitude [m].
    """

    a: float
    b: float
    x1: float


def orbit(rotor: Rotor, frame: Frame, omega: float) -> Orbit:
    """Forced response (paper eqs. 3, 4, 6) at speed ``omega`` [rad/s].

    Raises
    ------
    ValueError
        If ``omega`` is not > 0 or coincides with a natural frequency
        (undamped resonance: infinite amplitude).
    """
    w = _omega(omega)
    c, m = shaft_stiffness(rotor), rotor.mass
    delta = _delta(rotor, frame, w)
    scale = abs(frame.stiffness * c) + abs(c * m * w**2) + abs(frame.mass * m * w**4)
    if abs(delta) <= 1e-12 * scale or abs(c - m * w**2) <= 1e-12 * c:
        raise ValueError(f"omega = {w!r} rad/s is a natural frequency: undamped resonance, amplitude unbounded")
    e = rotor.eccentricity
    return Orbit(
        a=c * e * (frame.stiffness - frame.mass * w**2) / delta,
        b=c * e / (c - m * w**2),
        x1=e * c * m * w**2 / delta,
    )


def bearing_reaction(rotor: Rotor, frame: Frame, omega: float) -> tuple:
    """Amplitudes of the dynamic bearing reaction (horizontal, vertical) [N]: m w^2 |a|, m w^2 |b|."""
    o = orbit(rotor, frame, omega)
    k = rotor.mass * omega**2
    return k * abs(o.a), k * abs(o.b)


def reaction_increase(rotor: Rotor, frame: Frame, omega: float) -> tuple:
    """Relative increase of the bearing reaction over rigid supports, (|a|/e - 1, |b|/e - 1) [-].

    Independent of e (the model is linear in e).
    """
    if rotor.eccentricity <= 0:
        raise ValueError("eccentricity must be > 0 m for a relative reaction increase")
    o = orbit(rotor, frame, omega)
    e = rotor.eccentricity
    return abs(o.a) / e - 1.0, abs(o.b) / e - 1.0


def paper_reaction(rotor: Rotor, frame: Frame, omega: float) -> tuple:
    """Paper 002's centrifugal forces m w^2 (a + e), m w^2 (b + e) [N] (see module note)."""
    o = orbit(rotor, frame, omega)
    k = rotor.mass * omega**2
    return k * (o.a + rotor.eccentricity), k * (o.b + rotor.eccentricity)


def natural_frequency_curves(system: RotorFrame, section: Section, heights) -> tuple:
    """(p1(L), p2(L)) arrays [rad/s] for column heights ``heights`` [m]."""
    k = column_stiffness(section, heights, system.column_material, system.axis, system.columns)
    b, disc, mm = _pq(system.rotor, system.plate_mass, k)
    return np.sqrt((b + disc) / (2 * mm)), np.sqrt((b - disc) / (2 * mm))


@dataclass(frozen=True)
class ExclusionRow:
    """Heights to exclude for one section, mode and critical speed.

    Attributes
    ----------
    section : str
        Section designation.
    mode : int
        1 (upper, rotor-on-shaft mode) or 2 (lower, frame mode).
    critical_speed : float
        w_cr [rad/s].
    intervals : tuple of (float, float)
        Column heights [m] where ``band[0] w_cr <= p_mode(L) <= band[1] w_cr``.
    """

    section: str
    mode: int
    critical_speed: float
    intervals: tuple


def _intervals(mask: np.ndarray, heights: np.ndarray, p: np.ndarray, lo: float, hi: float) -> tuple:
    """Contiguous runs of ``mask``, ends refined by linear interpolation to the band edges."""
    out = []
    idx = np.flatnonzero(mask)
    if idx.size == 0:
        return ()
    runs = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)

    def edge(i_in: int, i_out: int) -> float:
        target = lo if (p[i_out] < lo) else hi
        t = (target - p[i_in]) / (p[i_out] - p[i_in])
        return float(heights[i_in] + t * (heights[i_out] - heights[i_in]))

    for run in runs:
        a, b = run[0], run[-1]
        start = edge(a, a - 1) if a > 0 else float(heights[a])
        end = edge(b, b + 1) if b + 1 < heights.size else float(heights[b])
        out.append((start, end))
    return tuple(out)


def exclusion_table(system: RotorFrame, critical_speeds=None, sections=None, heights=None,
                    band: tuple = (0.9, 1.1), modes: tuple = (1, 2)) -> tuple:
    """The paper's design method: column heights to exclude, per section, mode and critical speed.

    Parameters
    ----------
    system : RotorFrame
        Rotor, plate and column design.
    critical_speeds : sequence of float, optional
        w_cr [rad/s]. Default: the natural frequencies (p1, p2) of the
        reference design (``system.section`` at ``system.height``), as the
        paper takes them from its Figs. 1-2.
    sections : sequence of Section, optional
        Default ``system.sections`` (or the reference section).
    heights : array, optional
        Heights scanned [m]; default 3801 points over ``system.height_range``.
    band : (float, float)
        Relative band around each critical speed (paper: 0.9 ... 1.1).
    modes : tuple of int
        Which natural-frequency curves to test (1 upper, 2 lower).

    Returns
    -------
    tuple of ExclusionRow
    """
    lo_f, hi_f = band
    if not 0 < lo_f < 1 < hi_f:
        raise ValueError(f"band must be (lo, hi) with 0 < lo < 1 < hi, got {band!r}")
    if critical_speeds is None:
        critical_speeds = natural_frequencies(system.rotor, frame_for(system))
    secs = sections if sections is not None else (system.sections or (system.section,))
    h = np.linspace(*system.height_range, 3801) if heights is None else np.asarray(heights, dtype=float)
    rows = []
    for sec in secs:
        curves = natural_frequency_curves(system, sec, h)
        for mode in modes:
            p = curves[mode - 1]
            for wc in critical_speeds:
                lo, hi = lo_f * wc, hi_f * wc
                rows.append(ExclusionRow(sec.name, mode, float(wc), _intervals((p >= lo) & (p <= hi), h, p, lo, hi)))
    return tuple(rows)
