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


class ResolutionWarning(UserWarning):
    """The mesh does not resolve the thin-film pressure peak to the requested accuracy."""


def check_operating_point(wedge: float, squeeze, inlet_pressure: float) -> None:
    """Refuse an operating point whose magnitudes exceed :data:`MAX_SOURCE`.

    Parameters
    ----------
    wedge : float
        Entrainment factor [-].
    squeeze : (float, float)
        ``(gamma_rate, phi0_rate)`` [-].
    inlet_pressure : float
        Pocket pressure [-].

    Raises
    ------
    ValueError
        Naming the parameter and the allowed range (finiteness is checked
        by the solvers' own argument checks, NaN and inf fail here too).
    """
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
