"""Comparisons of the FEM solver with closed forms and published data.

:data:`CHECKS` maps a name to a function ``(quick: bool) -> list[Check]``;
``bearingfe validate`` runs them all and prints the table. To add a
comparison (e.g. the journal-bearing tables), add one entry.

Closed forms used
-----------------
Annular hydrostatic pad (pocket radius ``r_i`` at ``p_s``, outline radius
``r_o`` at 0, uniform film ``h = 1``, no motion): ``p = p_s ln(r_o/r) / ln(r_o/r_i)``,
load ``W = pi p_s (r_o^2 - r_i^2) / (2 ln(r_o/r_i))`` (pocket included) and
flow ``Q = pi h^3 p_s / (6 ln(r_o/r_i))`` (Hamrock, Schmid & Jacobson,
*Fundamentals of Fluid Film Lubrication*, 2nd ed., ch. 6, circular step
pad).

Short-bearing (Ocvirk) limit: for ``a -> 0`` the journal-bearing equation
reduces to ``h^3 p_zz = 6 dh/dphi`` so ``p = 3 gamma sin(phi) (a^2 - z^2) / h^3``
with ``h = 1 + gamma cos(phi)``; over the full 360 deg film with no
cavitation the force is ``(0, 4 pi a^3 gamma / (1 - gamma^2)^(3/2))``
(Ocvirk 1952, NACA TN 2808; Hamrock et al. ch. 10). ``p = 0`` at
``phi = 0, 2 pi`` is exact for it, so an arc ``[0, 2 pi]`` with zero
pressure at its ends is the same problem; the finite-width correction is
``O(a^2)``: measured 0.06 %, 0.22 %, 0.89 % below Ocvirk at a = 0.025, 0.05, 0.1
(gamma = 0.5), hence the 0.5 % tolerance at a = 0.05.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType
from typing import Callable, Mapping

__all__ = ["Check", "CHECKS", "run_checks", "annular_pad", "short_bearing"]


@dataclass(frozen=True)
class Check:
    """One computed quantity against its reference.

    Attributes
    ----------
    name : str
    reference : str
        Where the expected value comes from.
    computed, expected : float
    tolerance : float
        Allowed relative error.
    """

    name: str
    reference: str
    computed: float
    expected: float
    tolerance: float

    @property
    def error(self) -> float:
        """Relative error ``|computed - expected| / |expected|``."""
        return abs(self.computed - self.expected) / abs(self.expected)

    @property
    def passed(self) -> bool:
        return math.isfinite(self.computed) and self.error <= self.tolerance


def annular_pad(quick: bool = False, r_in: float = 0.1, r_out: float = 0.4) -> list[Check]:
    """Hydrostatic annular pad: load and flow against the closed form (P2 elements)."""
    from .film import CosineFilm
    from .geometry import Circle, Surface
    from .meshing import mesh_surface
    from .reynolds import solve_reynolds

    surface = Surface(outer=Circle((0.0, 0.0), r_out), inlets=(Circle((0.0, 0.0), r_in),))
    size = 0.05 if quick else 0.02
    mesh = mesh_surface(surface, size, inlet_size=size / 3, order=2)
    res = solve_reynolds(mesh, CosineFilm(0.0), wedge=0.0, inlet_pressure=1.0, element="P2",
                         formulation="direct")
    log = math.log(r_out / r_in)
    ref = "closed form, annular step pad (Hamrock ch. 6)"
    return [Check("annular pad load W", ref, res.integral, math.pi * (r_out**2 - r_in**2) / (2 * log), 1e-4),
            Check("annular pad flow Q", ref, res.flows["inlet"], math.pi / (6 * log), 1e-4)]


def short_bearing(quick: bool = False, half_width: float = 0.05, gamma: float = 0.5) -> list[Check]:
    """Narrow full journal bearing against the Ocvirk short-bearing load."""
    from .film import CosineFilm
    from .geometry import Surface
    from .meshing import mesh_surface
    from .reynolds import solve_reynolds

    surface = Surface(arc=(0.0, 2 * math.pi), half_width=half_width)
    size = half_width / (2 if quick else 4)
    mesh = mesh_surface(surface, size, order=1)
    res = solve_reynolds(mesh, CosineFilm(gamma), wedge=1.0, element="P2")
    expected = 4 * math.pi * half_width**3 * gamma / (1 - gamma**2) ** 1.5
    return [Check(f"short bearing load, a = {half_width}, gamma = {gamma}",
                  "Ocvirk short-bearing limit (NACA TN 2808)", float(res.force[1]), expected, 5e-3)]


#: Validation checks by name.
CHECKS: Mapping[str, Callable[[bool], list[Check]]] = MappingProxyType({
    "annular_pad": annular_pad,
    "short_bearing": short_bearing,
})


def run_checks(quick: bool = False, names=None) -> list[Check]:
    """Run the named checks (default: all) and return their rows."""
    names = list(CHECKS) if names is None else list(names)
    for name in names:
        if name not in CHECKS:
            raise ValueError(f"unknown check {name!r}; allowed: {', '.join(CHECKS)}")
    return [row for name in names for row in CHECKS[name](quick)]
