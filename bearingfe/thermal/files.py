"""The ``[oil]`` fields of scene files: their schema and the lubricant and heat balance they build.

One lubricant, given as exactly one of

- ``grade`` (an ISO 3448 grade, :data:`bearingfe.thermal.lubricant.ISO_VG`) with
  ``kinematic_viscosity_100C`` [m^2/s] (its data sheet's) or ``viscosity_index`` (ASTM D2270: the 100 degC
  viscosity of the grade's 40 degC mid-point and that index, :func:`bearingfe.thermal.viscosity_100`);
- ``kinematic_viscosity = [[t1_C, nu1], [t2_C, nu2]]``: the Walther (ASTM D341) law through two points
  [degC, m^2/s];
- ``vogel = [a, b, c]``: ``mu = a exp(b/(T - c))`` [Pa s, K, K];

with ``density_15C`` [kg/m^3] and an optional constant ``specific_heat`` [J/(kg K)] (default Cragoe's
correlation), and the heat balance: ``supply_temperature_C`` [degC], ``carry_over``,
``conducted_fraction``, ``effective_fraction`` (:class:`bearingfe.thermal.HeatBalance`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..core.schema import (Range, SchemaError, build, choice, number, numbers, positive_number)
from .lubricant import ISO_VG, Lubricant, VogelViscosity, WaltherViscosity, iso_vg, kelvin
from .viscosity_index import viscosity_100

if TYPE_CHECKING:  # imported where used: the heat balance pulls in the journal solver
    from .heat_balance import HeatBalance

__all__ = ["OIL", "check_oil", "lubricant_of", "balance_of"]

#: What the ``kinematic_viscosity`` field accepts.
_POINTS_RULE = "two points [[temperature_degC, kinematic_viscosity_m2s], ...] of the Walther (ASTM D341) law"


def _viscosity_points(where, value):
    """Two ``[temperature_C, nu_m2s]`` pairs."""
    if not (isinstance(value, list) and len(value) == 2):
        raise SchemaError(f"{where}: expected {_POINTS_RULE}; got {value!r}")
    return tuple(numbers(2, _POINTS_RULE)(where, v) for v in value)


_viscosity_points.accepts = _POINTS_RULE

#: The oil's fields (``{name: (check, default)}``, :mod:`bearingfe.core.schema`): the lubricant and the balance.
OIL = {
    "grade": (choice(lambda: ISO_VG), None, "ISO 3448 viscosity grade (with kinematic_viscosity_100C)"),
    "kinematic_viscosity_100C": (positive_number, None, "kinematic viscosity at 100 degC [m^2/s] (with grade)"),
    "viscosity_index": (number(Range(-100.0, 400.0)), None,
                        "ASTM D2270 viscosity index [-] (with grade, instead of kinematic_viscosity_100C)"),
    "kinematic_viscosity": (_viscosity_points, None, "two points [[T_degC, nu_m2_s], ...] of a Walther fit"),
    "vogel": (numbers(3, "Vogel's [a_Pa_s, b_K, c_K] of mu = a exp(b/(T - c))"), None,
              "Vogel's coefficients [Pa s, K, K]"),
    "density_15C": (number(Range(600.0, 1100.0)), 870.0, "density at 15 degC [kg/m^3]"),
    "specific_heat": (number(Range(500.0, 5000.0)), None,
                      "specific heat [J/(kg K)] (default: Cragoe's correlation over temperature)"),
    "supply_temperature_C": (number(Range(-50.0, 200.0)), None, "oil supply temperature [degC]"),
    "carry_over": (number(Range(0.0, 1.0)), 0.0, "fraction of the trailing-edge flow that re-enters the leading edge [-]"),
    "conducted_fraction": (number(Range(0.0, 1.0, hi_open=True)), 0.0,
                           "share of the friction heat conducted away, not carried by the oil [-]"),
    "effective_fraction": (number(Range(0.0, 1.0, lo_open=True)), 0.5,
                           "k in T_eff = T_in + k dT (1/2: the mean of inlet and outlet) [-]"),
}


def check_oil(oil: dict, label: str, section: str, need_supply: bool = True) -> None:
    """One lubricant (and, with ``need_supply``, a supply temperature) in the read ``[section]`` table.

    Raises
    ------
    SchemaError
        Naming the file, the table and what is wrong.
    """
    given = [k for k in ("grade", "kinematic_viscosity", "vogel") if oil[k] is not None]
    if len(given) != 1:
        raise SchemaError(f"{label}: [{section}]: give exactly one of grade (with kinematic_viscosity_100C or viscosity_index), "
                          f"kinematic_viscosity or vogel; got {given or 'none'}")
    index = oil.get("viscosity_index")
    nu100 = oil["kinematic_viscosity_100C"]
    if index is not None and nu100 is not None:
        raise SchemaError(f"{label}: [{section}] viscosity_index: give it or kinematic_viscosity_100C, not both")
    if oil["grade"] is None and (nu100 is not None or index is not None):
        name = "kinematic_viscosity_100C" if nu100 is not None else "viscosity_index"
        raise SchemaError(f"{label}: [{section}] {name}: goes with grade; got {oil[name]!r}")
    if oil["grade"] is not None and nu100 is None and index is None:
        raise SchemaError(f"{label}: [{section}] kinematic_viscosity_100C: goes with grade (or viscosity_index); "
                          f"got None")
    if need_supply and oil["supply_temperature_C"] is None:
        raise SchemaError(f"{label}: [{section}] supply_temperature_C: missing (required)")


def lubricant_of(oil: dict, label: str, section: str) -> Lubricant:
    """The :class:`Lubricant` of a checked ``[section]`` table (a constructor's error as a :class:`SchemaError`)."""
    props = dict(density=oil["density_15C"], specific_heat=oil["specific_heat"])
    if oil["grade"] is not None:
        nu100 = oil["kinematic_viscosity_100C"]
        if nu100 is None:  # from the grade's 40 degC viscosity and the viscosity index (ASTM D2270)
            nu100 = build(label, section, viscosity_100, ISO_VG[oil["grade"]], oil["viscosity_index"])
        return build(label, section, iso_vg, oil["grade"], nu100, **props)
    if oil["kinematic_viscosity"] is not None:
        (t1, n1), (t2, n2) = oil["kinematic_viscosity"]
        law = build(label, section, WaltherViscosity.through, (kelvin(t1), n1), (kelvin(t2), n2))
    else:
        law = build(label, section, VogelViscosity, *oil["vogel"])
    return build(label, section, Lubricant, law, name="oil", **props)


def balance_of(oil: dict, label: str, section: str, supply_temperature: float | None = None) -> HeatBalance:
    """The :class:`HeatBalance` of a checked ``[section]`` table; ``supply_temperature`` [K] when the table
    gives none."""
    from .heat_balance import HeatBalance

    t = kelvin(oil["supply_temperature_C"]) if oil["supply_temperature_C"] is not None else supply_temperature
    return build(label, section, HeatBalance, t, carry_over=oil["carry_over"],
                 conducted_fraction=oil["conducted_fraction"], effective_fraction=oil["effective_fraction"])
