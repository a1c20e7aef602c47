"""Write docs/thrust.md: thrust bearings, the model and its checks against references nobody here wrote.

Runs the checks of the sector-pad film and the thrust bearing (the infinite-width optima of the inclined
slider and the Rayleigh step, a polar finite-difference reference of a sector pad, the centre of pressure
of a wide tilting pad, the Swift-Stieber and JFO equilibria of a tilting pad, the shipped scene and its
level-1 heat balance) and writes the page with the numbers. ``tests/docs/test_thrust_page.py`` (slow)
regenerates it and fails when the committed page differs. Run::

    PYTHONPATH=. python scripts/make_thrust_page.py            # writes docs/thrust.md (about 30 s)
    PYTHONPATH=. python scripts/make_thrust_page.py --check    # exit 1 if the page is stale
"""

from __future__ import annotations

import math
import sys
import tomllib
from pathlib import Path

import numpy as np
from scipy.integrate import quad

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "thrust.md"
SIZES = (0.1, 0.05, 0.025)


def _g(x: float, digits: int = 4) -> str:
    return f"{x:.{digits}g}"


def _e(x: float) -> str:
    return f"{x:.1e}"


def _order(errors) -> list[str]:
    return ["-"] + [f"{math.log2(a / b):.2f}" for a, b in zip(errors, errors[1:])]


# -- the checks --------------------------------------------------------------------------------------

def wide_pad(film, size: float) -> tuple[float, float]:
    """Load and runner friction per unit width of an infinitely wide pad (periodic across the sliding)."""
    import bearingfe as bf

    surface = bf.Surface(arc=(-math.pi, math.pi), half_width=0.5, periodic=True, runner=bf.Translating(math.pi / 2))
    res = bf.solve_reynolds(bf.mesh_surface(surface, size), film, formulation="direct")
    return res.integral / (2 * math.pi), res.friction / (2 * math.pi)


def optima_section() -> list[str]:
    import bearingfe as bf

    K, L1, ratio = 2.1887, 0.7182, 1.8660
    w_slider = 6.0 / (K - 1) ** 2 * (math.log(K) - 2 * (K - 1) / (K + 1))
    w_step = 3 * (ratio - 1) * L1 * (1 - L1) / (ratio**3 * (1 - L1) + L1)
    cases = [("inclined slider, K = 2.1887", bf.TaperFilm(K, 1.0, start=-0.5, end=0.5, direction=math.pi / 2),
              w_slider, (4 * math.log(K) - 6 * (K - 1) / (K + 1)) / (K - 1)),
             ("Rayleigh step, land 0.7182, ratio 1.8660",
              bf.ProfileFilm(((-0.5, ratio), (L1 - 0.5, ratio), (L1 - 0.5, 1.0), (0.5, 1.0)), direction=math.pi / 2),
              w_step, L1 / ratio + (1 - L1) + (ratio - 1) * w_step)]
    lines = ["## Infinitely wide pads: the classic optima", "",
             "A pad periodic across the sliding (width 2 pi, no side leakage) with the runner sliding along `z`",
             "(`Translating(pi/2)`): the load per unit width `W h_out^2 / (mu U L^2 B)` against the closed forms",
             "(inclined slider `6/(K-1)^2 (ln K - 2 (K-1)/(K+1))`; Rayleigh step",
             "`3 (h1-h2) h2^2 L1 L2 / (L (h1^3 L2 + h2^3 L1))`) and the runner's friction `F h_out / (mu U L B)`",
             "(slider `(4 ln K - 6 (K-1)/(K+1))/(K-1)`; step `L1/h1 + L2/h2 + (h1 - h2) W`, both from",
             "`int (1/h + h/2 dp/dx)`), P1 on gmsh meshes, direct form:", "",
             "| case | quantity | exact | size | computed | error | order |", "|---|---|---|---|---|---|---|"]
    for name, film, load, friction in cases:
        runs = [wide_pad(film, h) for h in SIZES]
        for k, (what, exact) in enumerate((("load", load), ("friction", friction))):
            values = [r[k] for r in runs]
            errors = [abs(v / exact - 1) for v in values]
            for h, v, e, o in zip(SIZES, values, errors, _order(errors)):
                lines.append(f"| {name} | {what} | {exact:.5f} | {h} | {v:.5f} | {_e(e)} | {o} |")
            rich = values[-1] + (values[-1] - values[-2]) / 3
            lines.append(f"| {name} | {what} | {exact:.5f} | Richardson | {rich:.5f} | {_e(abs(rich / exact - 1))} | |")
    return lines + ["", "The load of the step converges at order 2 (the Couette source in conservative form takes the",
                    "step exactly); its friction at order 1 to 1.5 only: the Couette shear `mu U / h` is integrated at",
                    "the quadrature points of the elements the step line cuts. A mesh with the step line on element",
                    "edges (a `Recess` contour, or a sector pad's profile step on a radial line of the mesh) recovers",
                    "order 2; not yet automatic for a profile film.", ""]


def _sector_film(sector):
    from bearingfe.film.thickness import PlaneFilm

    a = 0.6 * sector.extent
    t, r = np.array([-math.sin(a), math.cos(a)]), np.array([math.cos(a), math.sin(a)])
    return PlaneFilm(1.0, (0.75 * math.cos(a), 0.75 * math.sin(a)), tuple(-2.0 * t + 0.3 * r))


def sector_section() -> list[str]:
    import bearingfe as bf
    from bearingfe.film.polar_fd import solve_sector_fd

    sector = bf.AnnularSector(0.5, 1.0, start=0.0, extent=math.radians(40))
    film = _sector_film(sector)
    fd = [solve_sector_fd(sector, film, n, n).load for n in (64, 128, 256)]
    reference = fd[-1] + (fd[-1] - fd[-2]) / 3
    fd_order = math.log2((fd[1] - fd[0]) / (fd[2] - fd[1]))
    surface = bf.Surface(outer=sector, runner=bf.Rotating())
    lines = ["## A sector pad on a rotating collar against polar finite differences", "",
             "A 40-degree pad (radii 0.5 and 1) tilted to converge along the rotation, `Rotating()` runner. The",
             "reference solves the Reynolds equation in polar coordinates on a uniform `(r, theta)` grid",
             "(`bearingfe.film.polar_fd`: other coordinates, unknowns and quadrature than the FEM), at 64, 128,",
             f"256 cells a side, observed order {fd_order:.2f}, Richardson: load {reference:.7f}.", "",
             "| element | size | nodes | load | error | order |", "|---|---|---|---|---|---|"]
    for element, order in (("P1", 1), ("P2", 2)):
        errors, rows = [], []
        for h in (0.08, 0.04, 0.02):
            mesh = bf.mesh_surface(surface, h, order=order)
            res = bf.solve_reynolds(mesh, film, formulation="direct", element=element)
            errors.append(abs(res.integral / reference - 1))
            rows.append((h, mesh.n_nodes, res.integral))
        for (h, n, v), e, o in zip(rows, errors, _order(errors)):
            lines.append(f"| {element} | {h} | {n} | {v:.7f} | {_e(e)} | {o} |")
    return lines + [""]


def centre_of_pressure(K: float) -> float:
    def h(x):
        return K + (1 - K) * x
    h_star = quad(lambda x: h(x) ** -2, 0, 1, epsabs=1e-14)[0] / quad(lambda x: h(x) ** -3, 0, 1, epsabs=1e-14)[0]

    def p(x):
        return 6 * quad(lambda s: (h(s) - h_star) / h(s) ** 3, 0, x, epsabs=1e-14)[0]
    return quad(lambda x: p(x) * x, 0, 1, epsabs=1e-13)[0] / quad(p, 0, 1, epsabs=1e-13)[0]


def tilting_section() -> list[str]:
    from bearingfe.bearings.thrust import SliderPad, ThrustPad, tilting_equilibrium
    from bearingfe.core.scales import Scale

    scale = Scale(radius=0.1, clearance=20e-6, viscosity=0.03, speed=2 * math.pi * 3000 / 60)
    lines = ["## Tilting pads", "",
             "**Centre of pressure.** A wide pad (`SliderPad`, periodic across the sliding) on a line pivot at the",
             "1-D centre of pressure of an inclined film of ratio K tilts until its film ratio is K (1-D Reynolds",
             "solution by quadrature):", "",
             "| K | pivot (1-D) | size | film ratio found | error | order |", "|---|---|---|---|---|---|"]
    for K in (1.5, 2.0, 3.0):
        pivot = centre_of_pressure(K)
        pad = SliderPad(1.0, pivot_offset=pivot)
        ratios = []
        for h in SIZES[:2]:
            q = tilting_equilibrium(pad, pad.mesh(h), scale, 1000.0, pivot="line").pad.state
            ratios.append((q[0] + q[1] * pivot) / (q[0] - q[1] * (1 - pivot)))
        errors = [abs(r / K - 1) for r in ratios]
        for h, r, e, o in zip(SIZES, ratios, errors, _order(errors)):
            lines.append(f"| {K} | {pivot:.5f} | {h} | {r:.5f} | {_e(e)} | {o} |")
        rich = ratios[-1] + (ratios[-1] - ratios[-2]) / 3
        lines.append(f"| {K} | {pivot:.5f} | Richardson | {rich:.5f} | {_e(abs(rich / K - 1))} | |")
    pad = ThrustPad(0.05, 0.1, math.radians(40), n_pads=6, pivot_offset=0.6)
    mesh = pad.mesh(0.05)
    ss = tilting_equilibrium(pad, mesh, scale, 2e4, cavitation="reynolds", formulation="direct")
    jfo = tilting_equilibrium(pad, mesh, scale, 2e4, cavitation="jfo", start=(ss.h_pivot, ss.pitch, ss.roll))
    rel = {k: abs(getattr(jfo, k) / getattr(ss, k) - 1) for k in ("h_pivot", "pitch", "roll")}
    lines += ["", "**Two cavitation models.** Six 40-degree pads (radii 50 and 100 mm, pivot at 0.6), 3000 rpm,",
              "30 mPa s, 20 kN: the Swift-Stieber (Galerkin) and JFO (finite-volume) equilibria, where nothing",
              "ruptures, differ by the two discretizations only (170 nodes a pad):", "",
              "| | film at pivot [um] | pitch [urad] | roll [urad] |", "|---|---|---|---|",
              f"| Swift-Stieber | {ss.h_pivot * 1e6:.4f} | {ss.pitch * 1e6:.3f} | {ss.roll * 1e6:.3f} |",
              f"| JFO | {jfo.h_pivot * 1e6:.4f} | {jfo.pitch * 1e6:.3f} | {jfo.roll * 1e6:.3f} |",
              f"| relative difference | {_e(rel['h_pivot'])} | {_e(rel['pitch'])} | {_e(rel['roll'])} |", ""]
    return lines


def scene_section() -> list[str]:
    import bearingfe as bf
    from bearingfe.scenes.thrust import settings

    data = tomllib.loads((ROOT / "scenes" / "thrust.toml").read_text(encoding="utf-8"))
    s = settings(data, "thrust.toml")
    from bearingfe.scenes.thrust import _pad

    pad = _pad(s, "thrust.toml")
    op = s["operating"]
    omega = 2 * math.pi * op["speed"] / 60
    lines = ["## The shipped scene and its mesh", "",
             "`scenes/thrust.toml` (six pads, 100/200 mm, 45 degrees, point pivots at 0.6, 3000 rpm, 30 mPa s,",
             "20 kN) at three element sizes, P1 and P2 (the scene's choice: "
             f"{s['solver']['element']} at {s['solver']['size']}); the error against the P2 solution at 0.025:", "",
             "| element | size | nodes | film at pivot [um] | smallest film [um] | power loss [W] | peak pressure [MPa] | "
             "error (film at pivot, smallest film, power, peak pressure) |",
             "|---|---|---|---|---|---|---|---|"]
    scale = bf.Scale(pad.outer_radius, s["solver"]["reference_film"], op["viscosity"], omega)
    runs = []
    for element, order in (("P1", 1), ("P2", 2)):
        for h in SIZES:
            mesh = pad.mesh(h, order=order)
            perf = bf.tilting_equilibrium(pad, mesh, scale, op["load"], cavitation="reynolds", element=element)
            runs.append((element, h, mesh.n_nodes, perf))
    best = runs[-1][3]
    for element, h, n, perf in runs:
        err = ", ".join(_e(abs(getattr(perf, k) / getattr(best, k) - 1)) for k in ("h_pivot", "h_min", "power", "p_max"))
        lines.append(f"| {element} | {h} | {n} | {perf.h_pivot * 1e6:.4f} | {perf.h_min * 1e6:.4f} | "
                     f"{perf.power:.2f} | {perf.p_max / 1e6:.4f} | {err if perf is not best else 'reference'} |")
    oil = bf.thermal.iso_vg("VG 46", 6.8e-6)
    balance = bf.thermal.HeatBalance(bf.thermal.kelvin(45.0))
    th = bf.thermal.thrust_temperature(pad, pad.mesh(0.05), op["load"], omega, oil, balance,
                                       reference_film=s["solver"]["reference_film"])
    lines += ["", "**Level-1 heat balance** (`bearingfe.thermal.thrust_temperature`) with an ISO VG 46 oil",
              "(6.8 mm^2/s at 100 degC) fed at 45 degC, no carry-over, nothing conducted:", "",
              "| | isothermal at supply | at the effective temperature |", "|---|---|---|",
              f"| temperature [degC] | 45 | {bf.thermal.celsius(th.temperature):.2f} |",
              f"| viscosity [mPa s] | {th.supply_viscosity * 1e3:.2f} | {th.viscosity * 1e3:.2f} |",
              f"| smallest film [um] | {th.isothermal.h_min * 1e6:.3f} | {th.performance.h_min * 1e6:.3f} |",
              f"| power loss [W] | {th.isothermal.power:.1f} | {th.performance.power:.1f} |",
              f"| temperature rise across the film [K] | | {th.heat.rise:.2f} |", ""]
    return lines


INTRO = """# Thrust bearings

A thrust bearing here is `n_pads` identical annular sector pads facing a collar that rotates about the
shaft axis. The film lives on the plane of the pad; the collar's velocity `omega x r` grows with the radius
and turns with the angle, and the package carries it as a velocity field of the runner
(`bearingfe.Rotating`; `bearingfe.Translating` for a slider, the journal's default along `phi`) through the
Couette source (in conservative form, so steps and pockets keep their load), the flows, the friction, every
cavitation model (Swift-Stieber, Gumbel, JFO with its streamline flux) and the error indicators. The
journal and pump paths are unchanged to the bit (their runner is the default one).

- **Pads** (`bearingfe.ThrustPad`, SI): inner and outer radius, angle, number of pads, pivot radius and
  angular offset, a machined profile (taper-land, Rayleigh step: `PolarProfileFilm` along the angle or the
  radius), pockets of any shape. Meshed by gmsh with exact circular rims; the flows are reported per edge
  (leading, trailing, inner rim, outer rim).
- **Fixed-geometry pads**: the film at the pivot that carries a load, by Newton (`bearingfe.pad_for_load`).
- **Tilting pads** (`bearingfe.tilting_equilibrium`): point pivot (film, pitch, roll) or line pivot (film,
  pitch), zero moments about the pivot and the load through it, by damped Newton with a finite-difference
  Jacobian, warm-started across loads (`bearings.thrust.load_curve`).
- **Stiffness and damping** (`bearings.thrust.axial_coefficients`): the pad's 3x3 matrices over (film,
  pitch, roll) and the bearing's axial `k_zz`, `c_zz` at a vibration frequency with massless pads
  following (the impedance `K + i Omega C` reduced onto the axial motion), or with the pads held.
- **Heat**: the level-1 balance of the pads (`bearingfe.thermal.thrust_temperature`): leading-edge inflow,
  rim outflow leaving at the mean temperature, carry-over of the trailing flow into the next pad.
- **Scene** `kind = "thrust"` (`scenes/thrust.toml`, SI): one pad's pressure and film, a table per pad,
  the smallest film and power loss against load; `examples/06_thrust.py`.

Not modelled yet: elastic or thermally deformed pads (the elastic support takes a runner along `phi` only
and says so), level-2 temperature fields on pads, pivot stiffness, pad inertia in the axial dynamics.

All numbers below are computed by `scripts/make_thrust_page.py`; a test regenerates the page.
"""


def page() -> str:
    lines = [INTRO, *optima_section(), *sector_section(), *tilting_section(), *scene_section()]
    return "\n".join(lines).rstrip() + "\n"


def main(argv: list[str] | None = None) -> int:
    from scripts.page_tool import page_main

    return page_main(PAGE, page, __doc__.splitlines()[0], argv)


if __name__ == "__main__":
    sys.exit(main())
