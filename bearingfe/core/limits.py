"""Size limits: guards against runaway work, checked before the work starts.

A mistyped number (``revolutions = 1e6``, ``frames = 1e9``, a grid of a
million cases) would otherwise run for days or die out of memory. Each guard
has a documented default; beyond it the error names the parameter, its value,
the limit and how to raise it.

================  =========  =============================================  ============================
name              default    what                                           checked by
================  =========  =============================================  ============================
``revolutions``   100        shaft turns of one transient run               ``simulate``, the pump scene
``frames``        1000       fields of one ParaView (PVD) series            ``write_pvd``, the pump scene
``cases``         10000      cases of one design study                      ``expand_cases``, ``sweep``
``elements``      1000000    estimated triangles of one study case's mesh   ``sweep``
``case_seconds``  3600       time limit of one study case [s] (default)     ``sweep``
``compliance``    4000       film dofs of a dense compliance (elastic        ``half_space``,
                             support): memory and time grow as n^2 and n^3   ``simulate_elastic``,
                                                                             the coupled solves
``samples``       100000     output samples of one transient run             ``simulate``,
                             (``points_per_revolution x revolutions``)       ``simulate_elastic``
================  =========  =============================================  ============================

Raise a limit for one call with the function's keyword (``simulate(...,
max_revolutions=1000)``, ``sweep(..., max_cases=..., time_limit=...)``), or
for a whole run, command line and sweep worker processes included, with the
environment variable ``BEARINGFE_MAX_<NAME>`` (e.g.
``BEARINGFE_MAX_REVOLUTIONS=1000``).
"""

from __future__ import annotations

import math
import os
from types import MappingProxyType
from typing import Mapping

__all__ = ["DEFAULT_LIMITS", "LimitError", "check_limit", "limit"]

#: Default limits by name (see the module table).
DEFAULT_LIMITS: Mapping[str, float] = MappingProxyType({
    "revolutions": 100, "frames": 1000, "cases": 10_000, "elements": 1_000_000, "case_seconds": 3600,
    "compliance": 4000, "samples": 100_000,
})


class LimitError(ValueError):
    """A size parameter is above its limit; the message says how to raise the limit."""


def _env_name(name: str) -> str:
    return f"BEARINGFE_MAX_{name.upper()}"


def limit(name: str) -> float:
    """The limit in force: ``BEARINGFE_MAX_<NAME>`` if set, else :data:`DEFAULT_LIMITS`.

    Raises
    ------
    ValueError
        Unknown name, or an environment value that is not a number > 0.
    """
    if name not in DEFAULT_LIMITS:
        raise ValueError(f"unknown limit {name!r}; known: {', '.join(DEFAULT_LIMITS)}")
    text = os.environ.get(_env_name(name))
    if text is None:
        return DEFAULT_LIMITS[name]
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not value > 0:
        raise ValueError(f"environment variable {_env_name(name)} must be a number > 0, got {text!r}")
    return value


def check_limit(name: str, value: float, override: float | None = None, keyword: str | None = None) -> None:
    """Raise :class:`LimitError` if ``value`` is above the limit ``name``.

    Parameters
    ----------
    name : str
        Key of :data:`DEFAULT_LIMITS`.
    value : float
        The requested size (same unit as the limit).
    override : float, optional
        The caller's own limit (a function keyword); default :func:`limit`.
    keyword : str, optional
        The function keyword that raises this limit, named in the message.
    """
    cap = limit(name) if override is None else float(override)
    if not cap > 0:
        raise ValueError(f"{keyword or 'the limit of ' + name} must be > 0, got {override!r}")
    if value > cap:
        how = f"{keyword}=... or " if keyword else ""
        raise LimitError(f"{name} = {value:.6g} is above the limit of {cap:.6g} (a guard against runaway work); "
                         f"raise it with {how}the environment variable {_env_name(name)}=...")
