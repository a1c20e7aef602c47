"""Write docs/thermal.md: is the isothermal assumption right for the shipped pump? Level-1 numbers.

Runs the shipped pump (``mechanisms/eccentric_pump.toml``, both shoes: with the 10 % pocket and plain)
with the run settings of ``scenes/pump.toml`` at the viscosity of the level-1 heat balance
(:func:`bearingfe.thermal.cycle_temperature`) for three conducted shares of the heat, and the shipped
journal scene's bearing with an ISO VG 32 oil (:func:`bearingfe.thermal.effective_temperature`), and
writes the page with the numbers. ``tests/docs/test_thermal_page.py`` (slow) regenerates it and fails
when the committed page differs. Run::

    PYTHONPATH=. python scripts/make_thermal_page.py            # writes docs/thermal.md (a few minutes)
    PYTHONPATH=. python scripts/make_thermal_page.py --check    # exit 1 if the page is stale
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "thermal.md"

#: The pump's oil: ISO VG 46 with 6.8 mm^2/s at 100 degC (a VI ~ 100 mineral oil's data sheet),
#: 870 kg/m^3 at 15 degC, Cragoe's specific heat.
PUMP_OIL = ("VG 46", 6.8e-6, 870.0)
#: The journal's oil: the shipped scene's ISO VG 32 (5.4 mm^2/s at 100 degC, 860 kg/m^3), fed at 40 degC.
JOURNAL_OIL = ("VG 32", 5.4e-6, 860.0, 40.0)
#: Shares of the friction heat conducted away through the shoe, plunger and eccentric.
CONDUCTED = (0.0, 0.5, 0.8)


def _f(x: float, digits: int = 3) -> str:
    return f"{x:.{digits}g}"


def pump_results() -> tuple[dict, float, float]:
    """``{(shoe, chi): CycleTemperature}`` for both shoes and every conducted share; the supply
    temperature [degC] and the machine file's viscosity [Pa s]."""
    from bearingfe.geometry.surface import Surface
    from bearingfe.mechanisms.files import load_mechanism
    from bearingfe.thermal import HeatBalance, celsius, cycle_temperature, iso_vg
    from bearingfe.transient import pump_mesh

    scene = tomllib.loads((ROOT / "scenes" / "pump.toml").read_text(encoding="utf-8"))["run"]
    pump = load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    oil = iso_vg(PUMP_OIL[0], PUMP_OIL[1], density=PUMP_OIL[2])
    # the supply temperature at which the oil has the machine file's viscosity: the isothermal column is the
    # shipped (paper's) model itself
    supply = oil.temperature_at(pump.viscosity)
    plain = dataclasses.replace(pump, surface=Surface(arc=pump.surface.arc, half_width=pump.surface.half_width))
    order = 2 if scene["element"] == "P2" else 1
    out = {}
    for name, p in (("pocket", pump), ("plain", plain)):
        mesh = pump_mesh(p, scene["mesh_size"], order=order)
        for chi in CONDUCTED:
            balance = HeatBalance(supply, conducted_fraction=chi, tolerance=1e-2)
            out[name, chi] = cycle_temperature(p, mesh, oil, balance, start=scene["start"], rtol=scene["rtol"],
                                               element=scene["element"])
    return out, celsius(supply), pump.viscosity


def _change(r) -> float:
    """Change of the smallest film from the isothermal run [%]."""
    return 100 * (r.smallest_film / r.isothermal_smallest_film - 1)


def _row(name: str, chi: float, r) -> str:
    from bearingfe.thermal import celsius

    return (f"| {name} | {chi:g} | {_f(celsius(r.temperature))} | {_f(r.temperature_rise)} | "
            f"{_f(celsius(r.peak_temperature))} | {_f(r.viscosity * 1e3)} | {_f(r.friction_power)} | "
            f"{_f(r.isothermal_smallest_film * 1e6)} | {_f(r.smallest_film * 1e6)} | {_change(r):+.0f} % | "
            f"{r.evaluations} |")


def _answer(results: dict, mu: float) -> list[str]:
    """The answer, in words, from the numbers."""
    hot, cool = results["pocket", CONDUCTED[0]], results["pocket", CONDUCTED[-1]]
    plain = results["plain", CONDUCTED[0]]
    return [
        f"**Answer.** Not as a matter of course. The oil that passes through the shoe's film is only "
        f"{_f(hot.leading_flow * 1e6, 2)} ml/s on the cycle mean against {_f(hot.friction_power)} W of heat: if it "
        f"alone carried the heat (`chi = 0`), the pocketed shoe's film would run at {_f(hot.temperature - 273.15)} "
        f"degC, {_f(hot.temperature - hot.supply_temperature)} K above the supply, its viscosity would be "
        f"{_f(hot.viscosity / mu * 100, 2)} % of the machine file's, and its smallest film would be "
        f"{_f(-_change(hot), 2)} % thinner than the isothermal model says ({_f(-_change(plain), 2)} % for the plain "
        f"shoe). Even with {_f(CONDUCTED[-1] * 100, 2)} % of the heat conducted away through the steel shoe, "
        f"plunger and eccentric the film is {_f(cool.temperature - cool.supply_temperature, 2)} K warmer and "
        f"{_f(-_change(cool), 2)} % thinner. How much is conducted is what level 1 cannot tell (it needs the "
        "level-2 energy equation with heat transfer to the walls, below); until then the isothermal films of the "
        "pump scene are an upper bound on the film. The pocket's advantage stands: its smallest film over the "
        f"plain shoe's is {_f(hot.isothermal_smallest_film / plain.isothermal_smallest_film)} isothermal and "
        f"{_f(hot.smallest_film / plain.smallest_film)} at `chi = 0`.",
    ]


def journal_row() -> str:
    """The shipped journal scene's bearing at the effective temperature of its VG 32 oil."""
    from bearingfe.bearings.journal import JournalBearing
    from bearingfe.thermal import HeatBalance, JournalDuty, celsius, effective_temperature, iso_vg, kelvin

    d = tomllib.loads((ROOT / "scenes" / "journal.toml").read_text(encoding="utf-8"))
    b, op = d["bearing"], d["operating"]
    duty = JournalDuty(radius=b["diameter"] / 2, clearance=b["radial_clearance"],
                       speed=2 * math.pi * op["speed"] / 60, load=op["load"])
    grade, nu100, rho, supply = JOURNAL_OIL
    r = effective_temperature(JournalBearing(b["length"] / b["diameter"]), duty, iso_vg(grade, nu100, density=rho),
                              HeatBalance(kelvin(supply), tolerance=1e-2), size=d["solver"]["size"])
    return (f"| {_f(celsius(r.supply_temperature))} | {_f(celsius(r.temperature))} | {_f(r.temperature_rise)} | "
            f"{_f(r.viscosity * 1e3)} | {_f(r.friction_power)} | {_f(r.isothermal_min_film * 1e6)} | "
            f"{_f(r.min_film * 1e6)} | {r.evaluations} |")


def page() -> str:
    """The whole page, as the committed ``docs/thermal.md`` must read."""
    results, supply, mu = pump_results()
    rows = [_row(name, chi, r) for (name, chi), r in results.items()]
    return "\n".join([
        "# Thermal: is the isothermal assumption right for the shipped pump?",
        "",
        "*Generated by `scripts/make_thermal_page.py`; do not edit by hand.*",
        "",
        "The paper behind the pump support solves its film at one viscosity and states that the support",
        "heats very little in normal operation. The level-1 model of `bearingfe.thermal` checks that: the",
        "film is solved isoviscously at the viscosity of an *effective temperature*, and that temperature",
        "comes from the heat balance of the whole film (friction power against the heat carried by the",
        "oil through the film, a share `chi` of it conducted away through the shoe, plunger and",
        "eccentric), iterated to a fixed point (Brent). Over the pump cycle the balance is of the",
        "cycle means: the shear power on the sliding eccentric plus the pocket's pressure work, against",
        "the oil dragged in at the leading edge and fed by the pocket, leaving through the sides and the",
        "trailing edge (`bearingfe.thermal.cycle_temperature`).",
        "",
        "## The shipped pump",
        "",
        f"Oil: ISO {PUMP_OIL[0]} with {PUMP_OIL[1] * 1e6:g} mm^2/s at 100 degC (a viscosity index about 100",
        f"mineral oil's data sheet), {PUMP_OIL[2]:g} kg/m^3 at 15 degC, Cragoe's specific heat. It is fed",
        f"at {supply:.1f} degC, where it has the machine file's viscosity {mu:g} Pa s, so the column",
        "*isothermal* is the shipped model itself. Runs as `scenes/pump.toml` (periodic start, P2 on",
        "its mesh, its tolerance). `chi = 0`: all the heat leaves with the oil (the upper bound of the",
        "film's temperature).",
        "",
        "| shoe | chi | T_eff [degC] | mean rise [K] | quasi-steady peak [degC] | mu_eff [mPa s] | "
        "heat [W] | smallest film, isothermal [um] | smallest film, level 1 [um] | change | runs |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
        *rows,
        "",
        "Columns: `T_eff` the effective film temperature, `mean rise` the cycle-mean temperature rise",
        "across the film, `quasi-steady peak` the largest outlet temperature of the balance taken at",
        "each instant (an upper bound: it ignores the heat stored in the oil and the metal over a",
        "cycle), `heat` the cycle-mean heat into the film, `runs` the isoviscous pump runs the fixed",
        "point took (the cost of level 1 against the one run of the isothermal model; each run's",
        "samples are re-solved once more for the flows through the leading edge).",
        "",
        *_answer(results, mu),
        "",
        "## The shipped journal bearing",
        "",
        f"`scenes/journal.toml`'s bearing with its ISO {JOURNAL_OIL[0]} oil ({JOURNAL_OIL[1] * 1e6:g} mm^2/s at",
        f"100 degC, {JOURNAL_OIL[2]:g} kg/m^3) fed at {JOURNAL_OIL[3]:g} degC, nothing conducted, the side",
        "flow leaving at the mean rise (Raimondi-Boyd's design procedure, validated against it in",
        "`tests/thermal/test_heat_balance.py`). The journal scene does this with an `[oil]` table.",
        "",
        "| supply [degC] | T_eff [degC] | rise [K] | mu_eff [mPa s] | power loss [W] | "
        "smallest film at the supply temperature [um] | smallest film, level 1 [um] | equilibria |",
        "|---|---|---|---|---|---|---|---|",
        journal_row(),
        "",
        "## Level 2 (not yet in the package)",
        "",
        "The film's mean temperature as a 2-D field from the energy equation on the film's mesh:",
        "convection by the mean film flux `-h^3/12 grad p + U h/2`, viscous heating",
        "`mu U^2/h + h^3/(12 mu) |grad p|^2`, adiabatic walls or a heat-transfer coefficient to them;",
        "stabilised against the convection (SUPG, or finite volumes as the JFO solver's); coupled to",
        "a Reynolds equation whose viscosity varies over the film, which needs the direct form's",
        "coefficient `h^3` to become `h^3 / mu(T)` in the assembly (today one viscosity is the",
        "pressure scale); the cavitated region carrying its fill fraction's share of the heat under",
        "JFO. Its checks: a 1-D adiabatic slider against its quadrature solution, mesh convergence of",
        "the temperature, and the level-1 effective temperature against the level-2 mean.",
        "",
    ])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="exit 1 if the committed page is stale")
    args = parser.parse_args(argv)
    text = page()
    if args.check:
        stale = not PAGE.is_file() or PAGE.read_text(encoding="utf-8") != text
        print(f"{PAGE.relative_to(ROOT)}: {'stale' if stale else 'current'}")
        return 1 if stale else 0
    PAGE.write_text(text, encoding="utf-8")
    print(f"wrote {PAGE.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
