"""Checks that keep answers honest: ranges of solver inputs and the mesh resolution of the thin film.

A finite number is not always a usable one: ``phi0 = 1e300`` leaves no digit
of ``cos(phi - phi0)``, ``inlet_pressure = 1e308`` overflows the flows, and a
film that closes to ``h_min = 1e-6`` inside one element gives a pressure peak
(which grows like ``1/h^2``) that changes by orders of magnitude with the
mesh. The input checks raise ``ValueError`` naming the parameter and its
allowed range; the resolution check issues a :class:`ResolutionWarning` and
returns the message (the Reynolds solver also puts it in the result's
``notes``).

Limits
------
``MAX_SOURCE`` (1e12)
    Largest magnitude of the non-dimensional operating point: ``wedge``,
    the squeeze rates and ``inlet_pressure`` (products with ``1/h^2`` and
    the areas must stay far from overflow).
``MAX_ANGLE`` (1e6 rad)
    Largest ``|phi0|``: at 1e6 rad the angle keeps 1e-10 rad of precision.
``MAX_GAMMA`` (1e3)
    Largest relative eccentricity of :class:`bearingfe.CosineFilm`: a film
    a thousand clearances thick is outside the thin-film model.
``MAX_CAVITY_PRESSURE`` (1e6)
    Largest ``|cavitation_pressure|`` [-] (it must also be ``<= 0``): the
    solvers work with ``p - p_c``, whose round-off (``1e-16 |p_c|``) beyond
    it swamps the film's own pressure (``-1e20`` gave a mass balance of
    4 000 times the flows).
``MAX_PRESSURE_PA`` (1e10 Pa)
    Largest dimensional pressure of a machine (a pump's discharge): ten
    times the yield stress of hardened steel; beyond it no film model of
    this package applies (``1e15`` Pa drove the film angle to ``1e300``).
``MAX_DEPTH`` (1e3)
    Largest recess depth [c]: like ``MAX_GAMMA``, a film a thousand
    clearances deep is outside the thin-film model.
``MAX_DEFLECTION`` (10 c), ``MAX_DEFLECTION_RADIUS`` (0.01 R0), ``MAX_STRAIN`` (0.01)
    Elastic supports: a deflection above 10 clearances gets a note (the
    film is then mostly the support's shape, check the modulus); above
    1 % of the radius, or a largest pressure above 1 % of the contact
    modulus ``E*`` (the strain ``p/E*``), the linear small-strain elasticity
    of the compliances does not hold: :class:`OutOfRangeError` (a mistyped
    modulus, ``E* = 1e6 Pa`` on a steel shoe, made films thousands of
    clearances thick).
``RESOLUTION_LIMIT`` (1.0)
    Largest relative change of the film thickness across one element where
    the film is thinnest (``(h_max - h_min) / h_min`` over its vertices).
    Near a cosine minimum it is ``(s / w)^2`` for elements of size ``s``
    and a pressure spike of width ``w = sqrt(2 h_min / gamma)``: the limit
    asks for elements no larger than the spike.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

__all__ = [
    "MAX_CAVITY_PRESSURE",
    "MAX_DEPTH",
    "MAX_PRESSURE_PA",
    "check_pressure_pa",
    "MAX_DEFLECTION",
    "MAX_DEFLECTION_RADIUS",
    "MAX_STRAIN",
    "OutOfRangeError",
    "OutOfRangeWarning",
    "check_cavitation_pressure",
    "check_depth",
    "check_elastic",
    "note_resolution",
    "MAX_SOURCE",
    "MAX_ANGLE",
    "MAX_GAMMA",
    "RESOLUTION_LIMIT",
    "ResolutionWarning",
    "check_operating_point",
    "check_angle",
    "film_variation",
    "check_resolution",
]

MAX_SOURCE = 1e12
MAX_ANGLE = 1e6
MAX_GAMMA = 1e3
RESOLUTION_LIMIT = 1.0
MAX_CAVITY_PRESSURE = 1e6
MAX_DEPTH = 1e3
MAX_PRESSURE_PA = 1e10
MAX_DEFLECTION = 10.0
MAX_DEFLECTION_RADIUS = 0.01
MAX_STRAIN = 0.01


class ResolutionWarning(UserWarning):
    """The mesh does not resolve the thin-film pressure peak to the requested accuracy."""


class OutOfRangeWarning(UserWarning):
    """A solution near the edge of the range the model describes (e.g. an elastic opening of many clearances)."""


class OutOfRangeError(ValueError):
    """The inputs give a solution outside the range the model describes (e.g. strains of linear elasticity)."""


def check_operating_point(wedge: float, squeeze, inlet_pressure: float, cavitation_pressure: float = 0.0) -> None:
    """Refuse an operating point whose magnitudes exceed :data:`MAX_SOURCE` or a bad cavity pressure.

    Every solver path calls it (finite elements, finite volumes, elastic,
    finite differences).

    Parameters
    ----------
    wedge : float
        Entrainment factor [-].
    squeeze : (float, float)
        ``(gamma_rate, phi0_rate)`` [-].
    inlet_pressure : float
        Pocket pressure [-].
    cavitation_pressure : float
        Cavity pressure [-] (:func:`check_cavitation_pressure`).

    Raises
    ------
    ValueError
        Naming the parameter and the allowed range (finiteness is checked
        by the solvers' own argument checks, NaN and inf fail here too).
    """
    check_cavitation_pressure(cavitation_pressure)
    try:
        rates = [float(s) for s in squeeze]
    except (TypeError, ValueError):
        return  # the solver's own check names the shape problem
    named = [("wedge", wedge), ("inlet_pressure", inlet_pressure)]
    named += [(f"squeeze[{k}]", v) for k, v in enumerate(rates)]
    for name, value in named:
        try:
            value = float(value)
        except (TypeError, ValueError):
            continue  # reported by the solver's own check
        if not abs(value) <= MAX_SOURCE:
            raise ValueError(f"{name} must be a finite number with |{name}| <= {MAX_SOURCE:g} (non-dimensional; "
                             f"larger values overflow the flows and forces), got {value!r}")


def _number(value, name: str) -> float:
    """``float(value)``, or a ValueError naming ``name`` where it is not a number."""
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None


def check_cavitation_pressure(value: float, name: str = "cavitation_pressure") -> float:
    """``float(value)`` if ``-MAX_CAVITY_PRESSURE <= value <= 0`` [-], else a ValueError naming ``name``."""
    value = _number(value, name)
    if not -MAX_CAVITY_PRESSURE <= value <= 0.0:
        raise ValueError(f"{name} must be a cavity pressure in [-{MAX_CAVITY_PRESSURE:g}, 0] (non-dimensional, gauge: "
                         f"at most the edge pressure 0; beyond -{MAX_CAVITY_PRESSURE:g} round-off swamps the film's "
                         f"pressure), got {value!r}")
    return value


def check_pressure_pa(value: float, name: str) -> float:
    """``float(value)`` if ``0 <= value <= MAX_PRESSURE_PA`` [Pa], else a ValueError naming ``name``."""
    value = _number(value, name)
    if not 0.0 <= value <= MAX_PRESSURE_PA:
        raise ValueError(f"{name} must be a pressure in [0, {MAX_PRESSURE_PA:g}] Pa (ten times the yield stress of "
                         f"hardened steel), got {value!r}")
    return value


def check_depth(value: float, name: str) -> float:
    """``float(value)`` if ``0 < value <= MAX_DEPTH`` [c], else a ValueError naming ``name``."""
    value = _number(value, name)
    if not 0.0 < value <= MAX_DEPTH:
        raise ValueError(f"{name} must be a depth in (0, {MAX_DEPTH:g}] (units of the clearance; a deeper film is "
                         f"outside the thin-film model), got {value!r}")
    return value


def check_elastic(deflection: np.ndarray, pressure: np.ndarray, scale, modulus: float) -> str | None:
    """Check an elastic support's solution against the range of linear small-strain elasticity.

    Parameters
    ----------
    deflection : ndarray
        Film opening at the dofs [c].
    pressure : ndarray
        Film pressure at the dofs [-].
    scale : Scale
        Dimensional scales (``clearance``, ``radius`` [m], ``pressure`` [Pa]).
    modulus : float
        Contact modulus ``E*`` [Pa] (``inf``: rigid).

    Returns
    -------
    str or None
        A note if the largest opening exceeds :data:`MAX_DEFLECTION` clearances.

    Raises
    ------
    OutOfRangeError
        The largest opening exceeds :data:`MAX_DEFLECTION_RADIUS` of the radius,
        or the largest pressure :data:`MAX_STRAIN` of ``E*``.
    """
    w = float(np.max(np.abs(deflection), initial=0.0))
    p = float(np.max(np.abs(pressure), initial=0.0)) * float(scale.pressure)
    strain = p / float(modulus) if math.isfinite(modulus) and modulus > 0 else 0.0
    if not (math.isfinite(w) and math.isfinite(strain)):
        raise OutOfRangeError(f"the elastic film's deflection or pressure is not finite (deflection {w!r} c, "
                              f"pressure {p!r} Pa)")
    if strain > MAX_STRAIN:
        raise OutOfRangeError(f"the largest film pressure {p:.3g} Pa is {strain:.3g} of the contact modulus "
                              f"E* = {modulus:.3g} Pa (limit {MAX_STRAIN:g}: linear small-strain elasticity); "
                              f"check the materials' youngs_modulus (steel is about 210e9 Pa)")
    if w * scale.clearance > MAX_DEFLECTION_RADIUS * scale.radius:
        raise OutOfRangeError(f"the largest elastic deflection {w:.3g} c = {w * scale.clearance:.3g} m is more than "
                              f"{MAX_DEFLECTION_RADIUS:g} of the radius R0 = {scale.radius:.3g} m (outside linear "
                              f"small-strain elasticity); check the materials' youngs_modulus")
    if w > MAX_DEFLECTION:
        return (f"elastic support: the largest deflection is {w:.3g} clearances (above {MAX_DEFLECTION:g}: the film is "
                f"mostly the support's shape; check the materials' youngs_modulus, E* = {modulus:.3g} Pa)")
    return None


def check_angle(value: float, name: str) -> float:
    """``float(value)`` if finite with ``|value| <= MAX_ANGLE`` [rad], else a ValueError naming ``name``."""
    value = float(value)
    if not (math.isfinite(value) and abs(value) <= MAX_ANGLE):
        raise ValueError(f"{name} must be an angle [rad] with |{name}| <= {MAX_ANGLE:g} (beyond, cos and sin "
                         f"lose their digits; reduce it modulo 2 pi), got {value!r}")
    return value


def film_variation(mesh, film) -> tuple[float, float, float]:
    """How well the mesh resolves the film where it is thinnest.

    Parameters
    ----------
    mesh : SupportMesh
        The mesh of the surface (its straight-sided vertices are used).
    film : Film
        Anything with ``thickness(phi, z)``.

    Returns
    -------
    variation : float
        ``max over elements of (h_max - h_min) / h_min`` over each element's
        vertices; in the element where the film is thinnest ``h_min`` is the
        film's exact minimum if it reports one (``film.minimum``) [-].
    h_min : float
        Smallest vertex thickness of that element [c].
    size : float
        Its longest edge [-].
    """
    m = mesh.mesh
    t = np.asarray(m.t[:3])
    p = np.asarray(m.p)
    with np.errstate(all="ignore"):
        h = np.asarray(film.thickness(p[0], p[1]), dtype=float)[t]  # once per vertex
        lo, hi = h.min(axis=0), h.max(axis=0)
        exact = film.minimum((float(p[0].min()), float(p[0].max()))) if hasattr(film, "minimum") else None
        if exact is not None and lo.size:
            k = int(np.argmin(lo))  # the element around the thinnest film
            lo[k] = min(lo[k], float(exact))
        rel = np.where(lo > 0, (hi - lo) / lo, np.inf)
    k = int(np.argmax(rel))
    a, b, c = (p[:, t[j, k]] for j in range(3))
    size = float(max(np.hypot(*(b - a)), np.hypot(*(c - b)), np.hypot(*(a - c))))
    return float(rel[k]), float(lo[k]), size


def note_resolution(result, mesh, film, *, stacklevel: int = 2):
    """``result`` with the :func:`check_resolution` message added to its ``notes`` (and warned) if any.

    The one resolution check every solver path runs on its result
    (finite elements, finite volumes, elastic); ``result`` is a dataclass
    with a ``notes`` tuple. A film with steps or kinks (``film.smooth`` False,
    :func:`bearingfe.film.thickness.is_smooth`) is not checked: its jumps are
    not a thin film to resolve (the schemes take a step exactly).
    """
    import dataclasses

    if not getattr(film, "smooth", True):
        return result
    message = check_resolution(mesh, film, stacklevel=stacklevel + 1)
    if message is None or message in result.notes:
        return result
    return dataclasses.replace(result, notes=(*result.notes, message))


def check_resolution(mesh, film, limit: float = RESOLUTION_LIMIT, *, stacklevel: int = 2) -> str | None:
    """Warn if the film changes too much across one element where it is thin.

    Parameters
    ----------
    mesh : SupportMesh
    film : Film
    limit : float
        Largest accepted :func:`film_variation` [-], > 0.
    stacklevel : int
        Passed to :func:`warnings.warn`.

    Returns
    -------
    str or None
        The warning's message, or None if the film is resolved.
    """
    if not (math.isfinite(limit) and limit > 0):
        raise ValueError(f"limit must be a finite number > 0, got {limit!r}")
    variation, h_min, size = film_variation(mesh, film)
    if variation <= limit:
        return None
    smaller = size * math.sqrt(limit / variation) if math.isfinite(variation) else math.nan
    message = (f"the thin film is not resolved: across an element of size {size:.3g} where h = {h_min:.3g}, the "
               f"film thickness changes by {variation:.3g} x h (limit {limit:g}); the pressure peak (~1/h^2) "
               f"depends on the mesh there: use elements of about {smaller:.2g} or smaller near the thinnest film "
               f"(e.g. mesh_surface(..., size_function=film_graded_size(film, size, min_size)))")
    warnings.warn(ResolutionWarning(message), stacklevel=stacklevel + 1)
    return message
