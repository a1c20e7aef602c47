r"""ASTM D2270: the viscosity index (VI) of an oil from its kinematic viscosities at 40 and 100 degC, and back.

Notation of the standard, all kinematic viscosities in mm^2/s (cSt): ``U`` at 40 degC and ``Y`` at
100 degC of the oil; ``L`` and ``H`` the 40 degC viscosities of the VI 0 and VI 100 reference oils that
have the same ``Y``.

- ``U >= H`` (VI up to 100), procedure A: ``VI = 100 (L - U) / (L - H)``;
- ``U < H`` (VI of 100 and above), procedure B: ``N = (log10 H - log10 U) / log10 Y``,
  ``VI = (10^N - 1) / 0.00715 + 100``.

``L`` and ``H``: the standard tables them (its Table 1) for ``Y`` from 2 to 70 mm^2/s and gives
quadratics ``L = a Y^2 + b Y + c``, ``H = d Y^2 + e Y + f`` above 70. This module does not carry
Table 1: for ``2 <= Y <= 70`` it uses the standard's own fitted equations (its Appendix X2,
Table X2.1: sixteen quadratics in ``Y``, each on a range of ``Y``, that reproduce Table 1 to within
0.1 %), and above 70 the formula of the body of the standard (the last row of :data:`LH_QUADRATICS`).
Below 2 mm^2/s the standard has no reference oils: an error.

The results are the exact (unrounded) values; the standard reports the VI rounded to an integer
(:func:`viscosity_index` with ``rounded=True``, round half to even as ASTM E29).

Inverse (:func:`viscosity_40`, :func:`viscosity_100`): the 40 degC viscosity of a given ``Y`` and VI
in closed form (each procedure solved for ``U``); the 100 degC viscosity of a given ``U`` and VI by
bracketed root finding in ``Y`` (the VI rises with ``Y`` at fixed ``U``).
"""

from __future__ import annotations

import math

from scipy.optimize import brentq

__all__ = ["LH_QUADRATICS", "reference_viscosities", "viscosity_index", "viscosity_40", "viscosity_100"]

#: ``(Y_low, Y_high, a, b, c, d, e, f)``: ``L = a Y^2 + b Y + c`` and ``H = d Y^2 + e Y + f`` [mm^2/s] for
#: ``Y_low <= Y < Y_high`` (ASTM D2270, Table X2.1 up to 70 mm^2/s; the body's formulas above).
LH_QUADRATICS: tuple[tuple[float, ...], ...] = (
    (2.0, 3.8, 1.14673, 1.7576, -0.109, 0.84155, 1.5521, -0.077),
    (3.8, 4.4, 3.38095, -15.4952, 33.196, 0.78571, 1.7929, -0.183),
    (4.4, 5.0, 2.5, -7.2143, 13.812, 0.82143, 1.5679, 0.119),
    (5.0, 6.4, 0.101, 16.635, -45.469, 0.04985, 9.1613, -18.557),
    (6.4, 7.0, 3.35714, -23.5643, 78.466, 0.22619, 7.7369, -16.656),
    (7.0, 7.7, 0.01191, 21.475, -72.870, 0.79762, -0.7321, 14.61),
    (7.7, 9.0, 0.41858, 16.1558, -56.040, 0.05794, 10.5156, -28.240),
    (9.0, 12.0, 0.88779, 7.5527, -16.600, 0.26665, 6.7015, -10.810),
    (12.0, 15.0, 0.7672, 10.7972, -38.180, 0.20073, 8.4658, -22.490),
    (15.0, 18.0, 0.97305, 5.3135, -2.200, 0.28889, 5.9741, -4.930),
    (18.0, 22.0, 0.97256, 5.25, -0.980, 0.24504, 7.416, -16.730),
    (22.0, 28.0, 0.91413, 7.4759, -21.820, 0.20323, 9.1267, -34.230),
    (28.0, 40.0, 0.87031, 9.7157, -50.770, 0.18411, 10.1015, -46.750),
    (40.0, 55.0, 0.84703, 12.6752, -133.310, 0.17029, 11.4866, -80.620),
    (55.0, 70.0, 0.85921, 11.1009, -83.19, 0.1713, 11.368, -76.940),
    (70.0, math.inf, 0.83531, 14.6731, -216.246, 0.16841, 11.8493, -96.947),
)

#: The procedure B constant of ASTM D2270 [-].
_B = 0.00715
#: m^2/s per mm^2/s.
_CST = 1e-6
#: Upper end of the root search for the 100 degC viscosity [mm^2/s].
_Y_MAX = 2000.0


def _cst(name: str, value: float, low: float = 0.0) -> float:
    """A kinematic viscosity [m^2/s] -> [mm^2/s], checked finite and above ``low`` [mm^2/s]."""
    try:
        v = float(value) / _CST
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number [m^2/s], got {value!r}") from None
    if not (math.isfinite(v) and v >= low and v > 0.0):
        raise ValueError(f"{name} must be finite and >= {max(low, 0.0) * _CST:g} m^2/s "
                         f"(ASTM D2270 has no reference oils below), got {value!r}")
    return v


def reference_viscosities(viscosity_100: float) -> tuple[float, float]:
    """``(L, H)`` [m^2/s]: the 40 degC viscosities of the VI 0 and VI 100 oils of this 100 degC viscosity.

    Parameters
    ----------
    viscosity_100 : float
        Kinematic viscosity at 100 degC [m^2/s], >= 2e-6.
    """
    y = _cst("viscosity_100", viscosity_100, low=2.0)
    for lo, hi, a, b, c, d, e, f in LH_QUADRATICS:
        if lo <= y < hi:
            return (a * y * y + b * y + c) * _CST, (d * y * y + e * y + f) * _CST
    raise AssertionError("unreachable: the last range is open")  # pragma: no cover


def _index(u: float, y: float) -> float:
    """VI of ``U``, ``Y`` [mm^2/s]."""
    lo, hi = reference_viscosities(y * _CST)
    big_l, big_h = lo / _CST, hi / _CST
    if u >= big_h:
        return 100.0 * (big_l - u) / (big_l - big_h)
    n = (math.log10(big_h) - math.log10(u)) / math.log10(y)
    return (10.0**n - 1.0) / _B + 100.0


def viscosity_index(viscosity_40: float, viscosity_100: float, rounded: bool = False) -> float:
    """The viscosity index of an oil (ASTM D2270, procedures A and B).

    Parameters
    ----------
    viscosity_40, viscosity_100 : float
        Kinematic viscosities at 40 and 100 degC [m^2/s]; ``viscosity_100 >= 2e-6`` and
        ``viscosity_40 > viscosity_100``.
    rounded : bool
        Round to the nearest integer, half to even, as the standard reports it.

    Returns
    -------
    float
        The VI [-].
    """
    u, y = _cst("viscosity_40", viscosity_40), _cst("viscosity_100", viscosity_100, low=2.0)
    if not u > y:
        raise ValueError(f"viscosity_40 must exceed viscosity_100 ({viscosity_100!r} m^2/s), got {viscosity_40!r}")
    vi = _index(u, y)
    return float(round(vi)) if rounded else vi


def _vi(name: str, value) -> float:
    try:
        vi = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not (math.isfinite(vi) and -100.0 <= vi <= 400.0):
        raise ValueError(f"{name} must be in [-100, 400], got {value!r}")
    return vi


def viscosity_40(viscosity_100: float, index: float) -> float:
    """The 40 degC kinematic viscosity [m^2/s] of an oil of this 100 degC viscosity [m^2/s] and VI."""
    y = _cst("viscosity_100", viscosity_100, low=2.0)
    vi = _vi("index", index)
    lo, hi = reference_viscosities(y * _CST)
    big_l, big_h = lo / _CST, hi / _CST
    if vi <= 100.0:
        u = big_l - vi / 100.0 * (big_l - big_h)
    else:
        u = big_h / y ** math.log10(1.0 + _B * (vi - 100.0))
    return u * _CST


def viscosity_100(viscosity_40_value: float, index: float) -> float:
    """The 100 degC kinematic viscosity [m^2/s] of an oil of this 40 degC viscosity [m^2/s] and VI.

    Raises
    ------
    ValueError
        If no 100 degC viscosity in [2, 2000] mm^2/s gives that VI.
    """
    u = _cst("viscosity_40", viscosity_40_value)
    vi = _vi("index", index)
    lo, hi = 2.0, min(_Y_MAX, u * (1.0 - 1e-9))
    if hi <= lo:
        raise ValueError(f"viscosity_40 must exceed 2e-6 m^2/s (ASTM D2270's smallest reference oil), "
                         f"got {viscosity_40_value!r}")
    g = lambda y: _index(u, y) - vi  # noqa: E731 - rises with y
    ends = g(lo), g(hi)
    if ends[0] >= 0.0 and ends[0] <= 1e-9:  # the smallest reference oil itself, to round-off
        return lo * _CST
    if ends[0] > 0.0 or ends[1] < 0.0:
        raise ValueError(f"index must be in [{ends[0] + vi:.4g}, {ends[1] + vi:.4g}] for viscosity_40 = "
                         f"{viscosity_40_value!r} m^2/s (100 degC viscosities from 2 mm^2/s up), got {index!r}")
    return brentq(g, lo, hi, xtol=1e-12, rtol=1e-13) * _CST
