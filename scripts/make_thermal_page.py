"""Write docs/thermal.md: is the isothermal assumption right for the shipped pump? Level-1 numbers.

Runs the shipped pump (``mechanisms/eccentric_pump.toml``, both shoes: with the 10 % pocket and plain)
with the run settings of ``scenes/pump.toml`` at the viscosity of the level-1 heat balance
(:func:`bearingfe.thermal.cycle_temperature`) for three conducted shares of the heat, the shipped
journal scene's bearing with an ISO VG 32 oil (:func:`bearingfe.thermal.effective_temperature`), and the
checks of level 2 (:mod:`bearingfe.thermal.film_energy`: a wide slider against its ODE reference on refined
meshes, the energy balance, level 1 against level 2, the journal with JFO and carry-over), level 2 on the plain
pump shoe at its most loaded and thinnest states, and writes the page with the numbers. ``tests/docs/test_thermal_page.py`` (slow) regenerates it and fails
when the committed page differs. Run::

    PYTHONPATH=. python scripts/make_thermal_page.py            # writes docs/thermal.md (a few minutes)
    PYTHONPATH=. python scripts/make_thermal_page.py --check    # exit 1 if the page is stale
"""

from __future__ import annotations

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
        f"{_f(-_change(cool), 2)} % thinner. How much is conducted is what level 1 cannot tell; level 2 on the "
        "plain shoe's most loaded and thinnest states (below) says the same with walls; until a level 2 over the "
        "whole cycle "
        "(with the heat stored in the metal) the isothermal films of the pump scene are an upper bound on the "
        "film. The pocket's advantage stands: its smallest film over the "
        f"plain shoe's is {_f(hot.isothermal_smallest_film / plain.isothermal_smallest_film)} isothermal and "
        f"{_f(hot.smallest_film / plain.smallest_film)} at `chi = 0`.",
    ]


#: Heat-transfer coefficients of the pump shoe's level 2 [W/(m^2 K)]: adiabatic; two steel walls (45 W/(m K))
#: conducting across the shoe's 15 mm to a sink at the supply temperature (2 x 45/0.015 = 6000); ten times that.
PUMP_WALLS = (0.0, 6000.0, 60000.0)
#: Cells of the unrolled shoe (along the arc, across).
PUMP_CELLS = (60, 30)


def pump_level2_section(results: dict) -> list[str]:
    """Level 2 on the plain shoe's film at two states of its isothermal run (:func:`shoe_pad`): the largest
    plunger force and the thinnest film."""
    import numpy as np
    import skfem

    from bearingfe.geometry.surface import Surface
    from bearingfe.mechanisms.files import load_mechanism
    from bearingfe.thermal import ConstantViscosity, Lubricant, iso_vg, shoe_pad
    from bearingfe.thermal.film_energy import film_energy, pad_mesh

    pump = load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    plain = dataclasses.replace(pump, surface=Surface(arc=pump.surface.arc, half_width=pump.surface.half_width))
    oil = iso_vg(PUMP_OIL[0], PUMP_OIL[1], density=PUMP_OIL[2])
    run = results["plain", CONDUCTED[0]]
    traj, supply, mu = run.isothermal_trajectory, run.supply_temperature, run.supply_viscosity
    force_n = plain.plunger_force(traj.beta)
    states = {"largest force": int(np.argmax(force_n)), "thinnest film": int(np.argmin(traj.h_min))}
    rows, out, out_force = [], {}, {}
    for name, k in states.items():
        pad = shoe_pad(plain, traj, k)
        mesh = pad_mesh(pad, *PUMP_CELLS)
        basis = skfem.Basis(mesh, skfem.ElementTriP1())
        a0, a1 = plain.surface.arc
        psi = ((a0 if traj.wedge[k] > 0 else a1)
               + np.sign(traj.wedge[k]) * np.asarray(basis.global_coordinates()[0]) / plain.radius)

        def force(e) -> float:   # the film's force on the shoe, |int p (cos psi, sin psi) dA| [N]
            p = np.asarray(basis.interpolate(e.pressure))
            return math.hypot(float((p * np.cos(psi) * basis.dx).sum()), float((p * np.sin(psi) * basis.dx).sum()))
        iso = film_energy(pad, mesh, Lubricant(ConstantViscosity(mu)), supply, cavitation="jfo")
        w_iso = out_force[k] = force(iso)
        rows.append(f"| {name} | {math.degrees(traj.beta[k]) % 360:.0f} | {_f(float(force_n[k]) / 1e3)} | "
                    f"{_f(traj.h_min[k] * 1e6)} | {_f(pad.speed)} | isothermal | {_f(iso.power)} | | 0 | 0 | 1 | 1 | "
                    f"{_f(w_iso / 1e3)} | 100 % | {iso.cavitated} |")
        for a in PUMP_WALLS:
            e = film_energy(pad, mesh, oil, supply, wall_coefficient=a, cavitation="jfo")
            out[name, a] = (e, force(e) / w_iso)
            rows.append(f"| | | | | | {'adiabatic' if a == 0 else f'{a:g}'} | {_f(e.power)} | "
                        f"{_f(e.conducted / e.power * 100, 2)} % | {_f(e.mean_temperature - supply)} | "
                        f"{_f(e.max_temperature - supply)} | {_f(oil.viscosity(e.mean_temperature) / mu, 2)} | "
                        f"{_f(e.viscosity.min() / mu, 2)} | {_f(force(e) / 1e3)} | {_f(force(e) / w_iso * 100, 2)} % | "
                        f"{e.cavitated} |")
    (hot, hot_share), (cold, _) = out["largest force", PUMP_WALLS[0]], out["largest force", PUMP_WALLS[-1]]
    (thin, thin_share), (thin_cold, _) = out["thinnest film", PUMP_WALLS[0]], out["thinnest film", PUMP_WALLS[-1]]
    kf, kt = states["largest force"], states["thinnest film"]
    return [
        "## Level 2 on the pump shoe at two states of its cycle",
        "",
        "The plain shoe's film at two samples of its isothermal run (the table's plain rows): where the",
        "plunger force is largest and where the film is thinnest, each frozen (`bearingfe.thermal.shoe_pad`:",
        "the film `c (1 + gamma cos(psi - delta))` of that state unrolled into a pad "
        f"{_f(plain.radius * (plain.surface.arc[1] - plain.surface.arc[0]) * 1e3)} mm along the arc",
        f"and {_f(2 * plain.surface.half_width * plain.radius * 1e3)} mm wide, the eccentric sliding past it, "
        "its squeeze rates left out) and",
        f"solved by level 2 with JFO cavitation on {PUMP_CELLS[0]} x {PUMP_CELLS[1]} cells, oil fed at "
        f"{_f(supply - 273.15)} degC. The isothermal row is",
        f"the frozen film at the machine file's {mu:g} Pa s; its force differs from the plunger's by what",
        "the film's squeeze carries at that instant. The other rows: the same film with the oil's viscosity",
        "of its local temperature.",
        "",
        "| state | shaft angle [deg] | plunger force [kN] | smallest film [um] | sliding [m/s] | walls [W/(m^2 K)] | "
        "dissipated [W] | conducted | mean rise [K] | max rise [K] | mu(mean)/mu_s | mu(max)/mu_s | "
        "film force [kN] | of the isothermal | cavitated nodes |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
        *rows,
        "",
        f"Walls: {PUMP_WALLS[1]:g} W/(m^2 K) is two steel walls (45 W/(m K)) conducting across the shoe's 15 mm",
        f"to a sink at the supply temperature; {PUMP_WALLS[2]:g} ten times that.",
        "",
        "**Answer.** The sliding alone heats the film well beyond what the isothermal model assumes: adiabatic,",
        f"the mean rise is {_f(hot.mean_temperature - supply)} K at the largest force and "
        f"{_f(thin.mean_temperature - supply)} K at the thinnest film (the hottest",
        f"points {_f(hot.max_temperature - supply)} and {_f(thin.max_temperature - supply)} K), the viscosity at "
        f"the mean {_f(oil.viscosity(hot.mean_temperature) / mu * 100, 2)} % and "
        f"{_f(oil.viscosity(thin.mean_temperature) / mu * 100, 2)} % of the isothermal",
        f"model's, and the same frozen film carries {_f(hot_share * 100, 2)} % and {_f(thin_share * 100, 2)} % of "
        "its isothermal force; with walls ten",
        f"times the steel's conduction the mean rise is still {_f(cold.mean_temperature - supply, 2)} and "
        f"{_f(thin_cold.mean_temperature - supply, 2)} K. What this does not settle: the",
        "frozen films are not in equilibrium with the plunger. At the largest force the wedge carries "
        f"{_f(out_force[kf] / 1e3)} kN",
        f"of {_f(float(force_n[kf]) / 1e3)} kN (the squeeze of the closing film carries the rest), at the thinnest "
        f"film {_f(out_force[kt] / 1e3)} kN against {_f(float(force_n[kt]) / 1e3)} kN",
        "(the film starts to open); the squeeze's own flow and dissipation and the heat stored in the shoe and",
        "eccentric over a cycle are outside the steady level 2. A level 2 with the squeeze over the cycle",
        "would settle it; until then level 1 over the cycle (above) and these frozen states agree that the",
        "isothermal film is an upper bound on the real one.",
        "",
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


#: The level-2 pad (SI): 50 mm long, outlet film 20 um, convergence ratio 1, 10 m/s; ISO VG 32 (5.4 mm^2/s at
#: 100 degC) with a constant specific heat of 2000 J/(kg K), fed at 40 degC.
PAD = (0.05, 20e-6, 1.0, 10.0, 40.0)
#: Meshes of the slider study (cells along the sliding direction, one across) and of the 2-D pad.
SLIDER_CELLS = (10, 20, 40, 80, 160)
PAD_CELLS = (40, 20)
#: Heat-transfer coefficient to the walls of the balance example [W/(m^2 K)].
WALLS = 2000.0


def level2_results() -> dict:
    """The level-2 checks: the wide slider against its ODE reference on refined meshes, the 2-D pad's balance
    with and without walls, and level 1 against level 2 on it."""
    import numpy as np

    from bearingfe.thermal import HeatBalance, iso_vg, kelvin
    from bearingfe.thermal.film_energy import Pad, film_energy, pad_level1, pad_mesh, slider_reference

    L, h0, K, U, supply = PAD
    oil = iso_vg("VG 32", 5.4e-6, specific_heat=2000.0)
    ts = kelvin(supply)
    ref = slider_reference(L, lambda x: h0 * (1 + K * (1 - x / L)), U, oil, ts)
    wide = Pad.inclined(L, 0.01, h0, K, U, sides="closed")
    slider = []
    for nx in SLIDER_CELLS:
        r = film_energy(wide, pad_mesh(wide, nx, 1), oil, ts)
        x = r.mesh.p[0]
        slider.append((nx, float(np.abs(r.temperature - ref.temperature(x)).max()),
                       r.load / 0.01 / ref.load - 1, r.power / 0.01 / ref.power - 1, r.iterations))
    pad = Pad.inclined(L, L, h0, K, U)
    mesh = pad_mesh(pad, *PAD_CELLS)
    adiabatic = film_energy(pad, mesh, oil, ts)
    walls = film_energy(pad, mesh, oil, ts, wall_coefficient=WALLS)
    level1 = pad_level1(pad, mesh, oil, HeatBalance(ts, tolerance=1e-4))
    return {"reference": ref, "slider": slider, "adiabatic": adiabatic, "walls": walls, "level1": level1,
            "supply": ts}


#: The level-2 journal (SI): R = 25 mm, L = 25 mm, c = 25 um, eps 0.6, 3000 rpm; its cells (around, along).
JOURNAL2 = (0.025, 0.025, 25e-6, 0.6, 3000.0)
JOURNAL2_CELLS = (120, 20)
#: Hot-oil carry-over of the journal's runs with each cavitation model [-].
CARRY_OVER = 0.5


def journal2_results() -> dict:
    """The full journal unwrapped (``journal_pad``): isoviscous against the package's journal solver, and
    level 2 (adiabatic and with walls) against level 1 on it, with the journal oil."""
    import numpy as np
    import skfem

    from bearingfe.bearings.journal import JournalBearing, performance
    from bearingfe.thermal import ConstantViscosity, HeatBalance, Lubricant, iso_vg, kelvin
    from bearingfe.thermal.film_energy import film_energy, journal_pad, pad_level1, pad_mesh

    R, length, c, eps, rpm = JOURNAL2
    omega = 2 * math.pi * rpm / 60
    pad = journal_pad(R, length, c, eps, omega)
    mesh = pad_mesh(pad, *JOURNAL2_CELLS)
    mu = 0.02
    iso = film_energy(pad, mesh, Lubricant(ConstantViscosity(mu)), kelvin(40.0))
    basis = skfem.Basis(mesh, skfem.ElementTriP1())
    p, phi = np.asarray(basis.interpolate(iso.pressure)), np.asarray(basis.global_coordinates()[0]) / R
    load = math.hypot(float((p * np.cos(phi) * basis.dx).sum()), float((p * np.sin(phi) * basis.dx).sum()))
    perf = performance(JournalBearing(length / (2 * R)), eps, size=0.05)
    grade, nu100, rho, supply = JOURNAL_OIL
    oil = iso_vg(grade, nu100, density=rho)
    runs = {a: film_energy(pad, mesh, oil, kelvin(supply), wall_coefficient=a) for a in (0.0, WALLS)}
    models = {(model, lam): film_energy(pad, mesh, oil, kelvin(supply), cavitation=model, carry_over=lam)
              for model in ("reynolds", "jfo") for lam in (0.0, CARRY_OVER)}
    level1 = pad_level1(pad, mesh, oil, HeatBalance(kelvin(supply), tolerance=1e-4))
    return {"load": load, "friction_variable": iso.friction / load * R / c,
            "package_load": perf.load * mu * omega * R**4 / c**2, "package_friction_variable": perf.friction_variable,
            "runs": runs, "models": models, "level1": level1, "mu": mu}


def level2_section() -> list[str]:
    """The level-2 section of the page: the model, its checks and their numbers."""
    import math

    r = level2_results()
    ref, slider, ad, wa, l1, ts = (r[k] for k in ("reference", "slider", "adiabatic", "walls", "level1", "supply"))
    L, h0, K, U, supply = PAD
    rise = ref.temperature(L) - ts
    rows = []
    for i, (nx, et, ew, ep, it) in enumerate(slider):
        order = "" if i == 0 else f"{math.log2(slider[i - 1][1] / et):.2f}"
        rows.append(f"| {nx} | {_f(et)} | {order} | {ew:+.2e} | {ep:+.2e} | {it} |")

    def bal(e, name):
        return (f"| {name} | {_f(e.power)} | {_f(e.convected)} | {_f(e.inflow_heat)} | {_f(e.conducted)} | "
                f"{'< 1e-12' if e.balance_residual < 1e-12 else _f(e.balance_residual)} | "
                f"{_f(e.mean_temperature - 273.15)} | {_f(e.max_temperature - 273.15)} | "
                f"{_f(e.outlet_temperature - 273.15)} | {e.iterations} |")
    return [
        "## Level 2: the film's temperature field",
        "",
        "`bearingfe.thermal.film_energy` solves the film's mean temperature as a field on the film's own",
        "mesh, coupled to a Reynolds equation whose viscosity is that of the local temperature (a plane pad",
        "under a sliding runner, SI). Reynolds: `div(h^3/(12 mu(T)) grad p) = U/2 dh/dx` with the package's",
        "weak forms (`weighted_laplace` with the coefficient `h^3/(12 mu)` as a field at the quadrature",
        "points); the energy equation of the mean temperature",
        "`rho c_p q . grad T = mu U^2/h + h^3/(12 mu) |grad p|^2 - alpha (T - T_w)` with the mean film flux",
        "`q = -h^3/(12 mu) grad p + U h/2`, no conduction in the film, so stabilised by SUPG; the supply",
        "temperature enters weakly where `q . n < 0`. The two are iterated to a fixed point (to 1e-9 K).",
        "Swift-Stieber cavitation (`cavitation=\"reynolds\"`, an active set) convects the heat of a ruptured",
        "zone by the full-film flux. Mass-conserving cavitation (`cavitation=\"jfo\"`: JFO with the fill",
        "fraction `theta`, Galerkin Poiseuille and median-dual upwind Couette flux as the package's JFO)",
        "lets only the liquid's share of a cavitated gap carry heat and dissipate: flux `U theta h/2`,",
        "dissipation `theta mu U^2/h`; its energy equation is solved on the same conserving cells (upwind",
        "finite volumes, first order), so its balance closes to round-off too. Hot-oil carry-over",
        "(`carry_over = lambda`) feeds the leading edge with the mix",
        "`T_in = (Q_supply T_s + lambda Q_t T_t)/(Q_supply + lambda Q_t)` of fresh oil and the trailing",
        "edge's outflow. The isoviscous solvers of the rest of",
        "the package are not touched: with a constant viscosity level 2 gives the isoviscous pressure of",
        "the same forms, bitwise (`tests/thermal/test_film_energy.py`).",
        "",
        "### Check 1: the adiabatic infinitely wide slider",
        "",
        f"An inclined slider, {L * 1e3:g} mm long, outlet film {h0 * 1e6:g} um, convergence ratio {K:g},",
        f"{U:g} m/s, ISO VG 32 (5.4 mm^2/s at 100 degC, `c_p` 2000 J/(kg K)) fed at {supply:g} degC: with no",
        "side flow the flux per unit width `q` is constant and the problem is two ODEs,",
        "`p' = 12 mu(T) (U h/2 - q)/h^3` and `rho c_p q T' = Phi`, with `T(0) = T_s`, `p(0) = p(L) = 0`;",
        "the reference (`slider_reference`) integrates them to 1e-11 (DOP853) and finds `q` by shooting.",
        f"It gives `q` = {_f(ref.flow * 1e6, 5)} mm^2/s, a load of {_f(ref.load / 1e3, 5)} kN/m and an outlet",
        f"{_f(rise)} K above the supply. Level 2 on the closed-sided pad, cells along the slider (one across):",
        "",
        "| cells | max temperature error [K] | observed order | load error | power error | iterations |",
        "|---|---|---|---|---|---|",
        *rows,
        "",
        "The temperature converges at first order in the largest error (SUPG on P1 with the weak inlet);",
        "load and dissipation converge faster.",
        "",
        "### Check 2: the energy balance",
        "",
        f"The {L * 1e3:g} x {L * 1e3:g} mm pad with ambient sides on {PAD_CELLS[0]} x {PAD_CELLS[1]} cells,",
        f"adiabatic and with a heat-transfer coefficient of {WALLS:g} W/(m^2 K) to walls at the supply",
        "temperature. The dissipated power equals the heat carried out by the boundary flows (Reynolds'",
        "consistent nodal flows times the temperature above the supply), the weak inlet's share, and the",
        "heat conducted to the walls, to round-off: it is the energy equation tested with `v = 1`.",
        "",
        "| walls | dissipated [W] | carried by the flows [W] | inlet share [W] | conducted [W] | "
        "residual | mean [degC] | max [degC] | outflow mean [degC] | iterations |",
        "|---|---|---|---|---|---|---|---|---|---|",
        bal(ad, "adiabatic"),
        bal(wa, f"{WALLS:g} W/(m^2 K)"),
        "",
        "### Check 3: level 1 against level 2",
        "",
        "Level 1 on the same pad (one effective temperature `T_in + dT/2` from the whole film's power and",
        "flows, the side flow leaving at the mean rise, the fixed point of Brent's method) against the",
        "area mean of the level-2 field:",
        "",
        "| level 1 T_eff [degC] | level 2 mean [degC] | difference [K] | level 1 rise [K] | "
        "level 1 load [N] | level 2 load [N] | isothermal solves of level 1 | level 2 iterations |",
        "|---|---|---|---|---|---|---|---|",
        f"| {_f(l1.temperature - 273.15)} | {_f(ad.mean_temperature - 273.15)} | "
        f"{_f(l1.temperature - ad.mean_temperature, 2)} | {_f(l1.rise)} | {_f(l1.load)} | {_f(ad.load)} | "
        f"{l1.evaluations} | {ad.iterations} |",
        "",
        "On this pad the one-temperature model is close to the field's mean; the field's hot spot (the",
        "trailing edge, above) is what level 1 cannot give. Cost of both levels against the isothermal",
        "solve: the part *thermal* of [the benchmarks](benchmarks.md) (`benchmarks/thermal_levels.py`).",
        "",
        *journal2_section(),
    ]


def journal2_section() -> list[str]:
    """The level-2 journal: the isoviscous check against the package's journal solver and the thermal runs."""
    j = journal2_results()
    R, length, c, eps, rpm = JOURNAL2
    grade, nu100, rho, supply = JOURNAL_OIL
    l1 = j["level1"]
    ss0, ss, jf0, jf = (j["models"][m, lam] for m in ("reynolds", "jfo") for lam in (0.0, CARRY_OVER))

    def rel(a, b):
        return f"{100 * (a / b - 1):+.2f} %"

    def row(alpha, e):
        return (f"| {'adiabatic' if alpha == 0 else f'{alpha:g} W/(m^2 K)'} | {_f(e.power)} | "
                f"{_f(e.conducted / e.power * 100, 2)} % | {_f(e.mean_temperature - 273.15)} | "
                f"{_f(e.max_temperature - 273.15)} | {_f(e.outlet_temperature - 273.15)} | {e.cavitated} | "
                f"{e.iterations} |")
    return [
        "### Check 4: the full journal bearing",
        "",
        f"A full 360-degree journal bearing unwrapped from its line of largest film (`journal_pad`): R = "
        f"{R * 1e3:g} mm,",
        f"L = {length * 1e3:g} mm, c = {c * 1e6:g} um, eccentricity ratio {eps:g}, {rpm:g} rpm, oil fed at the line",
        "of largest film at the supply temperature (no hot-oil carry-over), Swift-Stieber cavitation, on",
        f"{JOURNAL2_CELLS[0]} x {JOURNAL2_CELLS[1]} cells. Isoviscous ({j['mu']:g} Pa s) against the package's "
        "journal solver",
        "(`bearingfe.bearings.journal.performance`, P1 on its own graded mesh of size 0.05):",
        "",
        "| | level 2, isoviscous | journal solver | difference |",
        "|---|---|---|---|",
        f"| load [N] | {_f(j['load'], 5)} | {_f(j['package_load'], 5)} | {rel(j['load'], j['package_load'])} |",
        f"| friction variable (R/c) f [-] | {_f(j['friction_variable'], 4)} | "
        f"{_f(j['package_friction_variable'], 4)} | {rel(j['friction_variable'], j['package_friction_variable'])} |",
        "",
        f"With the journal's ISO {grade} oil fed at {supply:g} degC, level 2 adiabatic and with walls against level 1",
        f"(`pad_level1` on the same film: T_eff {_f(l1.temperature - 273.15)} degC, rise {_f(l1.rise)} K, "
        f"{_f(l1.power)} W):",
        "",
        "| walls | dissipated [W] | conducted | mean [degC] | max [degC] | outflow mean [degC] | "
        "cavitated nodes | iterations |",
        "|---|---|---|---|---|---|---|---|",
        *[row(a, e) for a, e in j["runs"].items()],
        "",
        f"The adiabatic field's mean is {_f(j['runs'][0.0].mean_temperature - l1.temperature, 2)} K above level 1's "
        "effective temperature on this",
        "film, about half of it ruptured: level 2 convects the ruptured zone's heat by the Couette flow",
        "`U h/2` of a full film (Swift-Stieber), level 1 lets the side flow leave at the mean rise. These",
        "rows compare the two models on one film; they are not a validation against a measured bearing.",
        "",
        "The same film adiabatic with each cavitation model, without and with hot-oil carry-over of",
        f"{CARRY_OVER:g} of the outflow at the groove (the trailing edge's oil mixed into the leading edge's):",
        "",
        "| cavitation | carry-over | dissipated [W] | inlet [degC] | mean [degC] | max [degC] | "
        "trailing outflow [degC] | smallest fill fraction | load [N] | balance residual | iterations |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
        *[f"| {m} | {lam:g} | {_f(e.power)} | {_f(e.inlet_temperature - 273.15)} | {_f(e.mean_temperature - 273.15)} | "
          f"{_f(e.max_temperature - 273.15)} | {_f(e.trailing_temperature - 273.15)} | {_f(e.fill.min(), 2)} | "
          f"{_f(_journal_load(e, R), 4)} | {'< 1e-12' if e.balance_residual < 1e-12 else _f(e.balance_residual)} | "
          f"{e.iterations} |" for (m, lam), e in j["models"].items()],
        "",
        "With JFO the ruptured film's streamers carry and make less heat than the full film Swift-Stieber",
        "pretends to convect: the gas in the cavity shears nothing, and the oil that leaves at the groove is",
        "the streamers' (fill fraction times the Couette flow), not a full film's. Carry-over heats the inlet",
        "and with it the whole film; with Swift-Stieber the oil carried over leaves the ruptured zone at the",
        f"trailing full film's {_f(ss.trailing_temperature - 273.15)} degC "
        f"(JFO: {_f(jf.trailing_temperature - 273.15)} "
        f"degC), so the same carry-over heats the inlet by {_f(ss.inlet_temperature - ss0.inlet_temperature)} K "
        f"against {_f(jf.inlet_temperature - jf0.inlet_temperature, 2)} K.",
        "",
    ]


def _journal_load(e, R: float) -> float:
    """The journal film's load ``|int p (cos phi, sin phi) dA|`` [N] (``phi = x/R``)."""
    import numpy as np
    import skfem

    basis = skfem.Basis(e.mesh, skfem.ElementTriP1())
    p, phi = np.asarray(basis.interpolate(e.pressure)), np.asarray(basis.global_coordinates()[0]) / R
    return math.hypot(float((p * np.cos(phi) * basis.dx).sum()), float((p * np.sin(phi) * basis.dx).sum()))


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
        *pump_level2_section(results),
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
        *level2_section(),
    ])


def main(argv: list[str] | None = None) -> int:
    from scripts.page_tool import page_main

    return page_main(PAGE, page, __doc__.splitlines()[0], argv)


if __name__ == "__main__":
    sys.exit(main())
