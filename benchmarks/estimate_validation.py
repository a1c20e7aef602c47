"""The load error estimate of every solve against true errors, with the observed orders and the times:
the section "Error estimates" of docs/validation.md.

Run: ``PYTHONPATH=. python benchmarks/estimate_validation.py`` (about a minute): rewrites that section of
docs/validation.md in place (between its markers), leaving the journal sections of
``benchmarks/journal_validation.py`` (which also writes this section when it writes the whole page) as they
are.

Each case is solved on a mesh and on that mesh refined once and twice
(:func:`bearingfe.geometry.meshing.refine_once`); the true errors against the
case's reference give the observed order, and ``solve_reynolds(...,
estimate_error=True)`` on the first two meshes gives the estimate
(:mod:`bearingfe.film.estimate`) and its effectivity (estimate over true error).
"""

from __future__ import annotations

import dataclasses
import math
import platform
import sys
import time
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

if __package__ in (None, ""):  # run as a script: make the repository root importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import bearingfe as bf  # noqa: E402
from bearingfe.bearings.journal import default_min_size, journal_mesh  # noqa: E402
from bearingfe.film.estimate import load_order  # noqa: E402
from bearingfe.geometry.meshing import SupportMesh, grid_mesh, refine_once, strip_mesh  # noqa: E402
from bearingfe.validation import PocketSlider, inclined_slider_load, rayleigh_step_load  # noqa: E402

PAGE = Path(__file__).resolve().parents[1] / "docs" / "validation.md"
BEGIN, END = "<!-- error estimates: begin -->", "<!-- error estimates: end -->"
LEVELS = 3  # the mesh and its refinements once and twice


@dataclass(frozen=True)
class Case:
    """One validation case: how to mesh it, how to solve it, its reference load and where that comes from."""

    name: str
    reference: str
    element: str
    mesh: Callable[[], SupportMesh]
    solve: dict
    exact: Callable[[SupportMesh], float]  # the reference value of the measured quantity on this mesh
    quantity: str = "integral"  # or "load" (|force|) or "force_x" (force[0])
    elastic: Callable[[SupportMesh], object] | None = None  # the support's compliance on a mesh


def _width(mesh: SupportMesh) -> float:
    return float(np.ptp(mesh.mesh.p[1]))


def _incline(element: str) -> Case:
    return Case(f"Inclined slider, h_in/h_out = 2.1887, strip of 10 cells ({element})",
                "closed form, infinitely wide inclined slider (`validation.inclined_slider_load`)", element,
                lambda: strip_mesh(10, rows=1), dict(film=bf.TaperFilm(h_in=2.1887, h_out=1.0), element=element),
                lambda m: inclined_slider_load(2.1887, 1.0) * _width(m))


def _rayleigh(element: str) -> Case:
    film = bf.ProfileFilm(((0.0, 1.866), (0.7, 1.866), (0.7, 1.0), (1.0, 1.0)))
    return Case(f"Rayleigh step of finite width B = L, grid of size 0.1 ({element})",
                "Fourier series of the step (`validation.rayleigh_step_load`)", element,
                lambda: grid_mesh(bf.Surface(arc=(0.0, 1.0), half_width=0.5), 0.1),
                dict(film=film, element=element, formulation="direct"),
                lambda m: rayleigh_step_load(1.866, 1.0, 0.7, 1.0, 1.0))


def _annular(element: str) -> Case:
    r_in, r_out = 0.1, 0.4
    surface = bf.Surface(outer=bf.Circle((0.0, 0.0), r_out), inlets=(bf.Circle((0.0, 0.0), r_in),))
    order = 2 if element == "P2" else 1
    return Case(f"Annular recess pad, r_i/r_o = 0.1/0.4, gmsh size 0.1, geometry order {order} ({element})",
                "closed form, annular step pad (Hamrock, Schmid & Jacobson ch. 6)", element,
                lambda: bf.mesh_surface(surface, 0.1, inlet_size=0.1 / 3, order=order),
                dict(film=bf.UniformFilm(1.0), wedge=0.0, inlet_pressure=1.0, element=element, formulation="direct"),
                lambda m: math.pi * (r_out**2 - r_in**2) / (2 * math.log(r_out / r_in)))


#: Converged Sommerfeld numbers of the journal sections above (FEM and FD, Richardson, agree to 1e-5).
JOURNAL_S = {(1.0, 0.6): 0.120941, (1.0, 0.9): 0.0188201, (0.5, 0.6): 0.319288}


def _journal(ld: float, eps: float) -> Case:
    bearing = bf.JournalBearing(length_ratio=ld)
    return Case(f"Journal, L/D = {ld:g}, eps = {eps:g}, Swift-Stieber, graded gmsh size 0.2 (P1)",
                f"converged S = {JOURNAL_S[(ld, eps)]} of the sections above", "P1",
                lambda: journal_mesh(bearing, 0.2, min_size=default_min_size(0.2, eps), eps=eps)[0],
                dict(film=bf.CosineFilm(eps), cavitation="reynolds", formulation="direct", element="P1"),
                lambda m: 2 * bearing.half_width / (math.pi * JOURNAL_S[(ld, eps)]), "load")


#: |force| of the L/D = 1, eps = 0.6 journal converged beyond the six digits of ``JOURNAL_S``, for the P2
#: case: P1 on the graded size-0.2 mesh refined four and five times (136,689 and 545,905 nodes),
#: Richardson-extrapolated at order 2 (P1's observed order there: 2.00); the extrapolation from the
#: levels three and four differs from it by REFERENCE_SPREAD.
JOURNAL_P2_FORCE = 5.263915
REFERENCE_SPREAD = 1.6e-6


def _journal_p2() -> Case:
    bearing, eps = bf.JournalBearing(length_ratio=1.0), 0.6
    return Case("Journal, L/D = 1, eps = 0.6, Swift-Stieber, graded gmsh size 0.2 (P2)",
                f"|force| = {JOURNAL_P2_FORCE} (P1 on the mesh refined four and five times, Richardson; "
                f"{REFERENCE_SPREAD:.0e} from the extrapolation one level coarser)", "P2",
                lambda: journal_mesh(bearing, 0.2, min_size=default_min_size(0.2, eps), eps=eps)[0],
                dict(film=bf.CosineFilm(eps), cavitation="reynolds", formulation="direct", element="P2"),
                lambda m: JOURNAL_P2_FORCE, "load")


def _pocket() -> Case:
    case = PocketSlider()
    scale = case.pressure_scale
    return Case("JFO pocket slider (mass-conserving cavitation, finite volumes), strip of 160 cells (P1)",
                "closed form, 1-D pocket slider with JFO (`validation.PocketSlider`, docs/jfo.md)", "P1",
                lambda: strip_mesh(160), dict(film=case.film(), cavitation="jfo",
                                             cavitation_pressure=(case.p_cav - case.p_edge) / scale),
                lambda m: case.exact().load / (scale * case.length) * _width(m))


#: The converged film force along phi = 0 of the pump-like elastic case (tests/elastic/test_coupled.py: curved P2
#: meshes 0.16 / 0.08 / 0.04 R0 Richardson-extrapolated; an Anderson-mixed fixed point reproduced them to 8 digits).
ELASTIC_FORCE = 0.4176956


def _elastic() -> Case:
    from bearingfe.elastic import half_space

    scale = bf.Scale(radius=0.05, clearance=20e-6, viscosity=0.03, speed=157.08)
    steel = bf.Material("steel", 210e9, poisson_ratio=0.3)
    surface = bf.Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=[bf.Circle((0.0, 0.0), 0.1748)])
    return Case("Elastic shoe (half-space, steel on steel, 32 MPa pocket, gamma = 0.6, Swift-Stieber), gmsh size "
                "0.16 (P1)", f"converged force along phi = 0, {ELASTIC_FORCE} (tests/elastic/test_coupled.py)", "P1",
                lambda: bf.mesh_surface(surface, 0.16),
                dict(film=bf.CosineFilm(0.6, math.pi), inlet_pressure=scale.from_pressure(32e6),
                     cavitation="reynolds"),
                lambda m: ELASTIC_FORCE, "force_x", lambda m: half_space(m, scale, (steel, steel), "P1"))


def cases() -> tuple[Case, ...]:
    """Every case of the section, in its order."""
    return (_incline("P1"), _incline("P2"), _rayleigh("P1"), _rayleigh("P2"), _annular("P1"), _annular("P2"),
            _journal(1.0, 0.6), _journal_p2(), _journal(1.0, 0.9), _journal(0.5, 0.6), _pocket(), _elastic())


@dataclass(frozen=True)
class Level:
    nodes: int
    dofs: int
    value: float
    error: float  # relative, against the reference
    estimate: float  # relative estimated error of this level (NaN on the last)
    effectivity: float
    solve_seconds: float
    estimate_seconds: float


def _value(res, quantity: str) -> tuple[float, float]:
    est = res.load_error
    if quantity == "integral":
        return float(res.integral), (est.integral_error if est else math.nan)
    if quantity == "force_x":  # the coarse value's distance to Richardson's is its estimated error
        return float(res.force[0]), (abs(res.force[0] - est.extrapolated_force[0]) if est else math.nan)
    return float(np.linalg.norm(res.force)), (est.force_error if est else math.nan)


def run(case: Case, levels: int = LEVELS) -> list[Level]:
    """The case on ``levels`` meshes, each the previous one refined once; estimates on all but the last."""
    out, mesh = [], case.mesh()
    for k in range(levels):
        kwargs = dict(case.solve)
        film = kwargs.pop("film")
        start = time.perf_counter()
        if case.elastic is not None:
            kwargs["elastic"] = case.elastic(mesh)
        res = bf.solve_reynolds(mesh, film, **kwargs)
        solved = time.perf_counter() - start
        exact = case.exact(mesh)
        estimated, est_s = math.nan, math.nan
        if k < levels - 1:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", bf.ResolutionWarning)
                est = res.estimate_load_error()
            res = dataclasses.replace(res, load_error=est)
            est_s = est.seconds
        value, estimated = _value(res, case.quantity)
        error = abs(value - exact)
        out.append(Level(nodes=mesh.n_nodes, dofs=int(res.basis.N), value=value, error=error / abs(exact),
                         estimate=estimated / abs(exact), effectivity=estimated / error if error > 0 else math.nan,
                         solve_seconds=solved, estimate_seconds=est_s))
        if k < levels - 1:
            mesh = refine_once(mesh)
    return out


def orders(levels: list[Level]) -> list[float]:
    """Observed order between successive levels (``log2`` of the error ratio), NaN on the first."""
    return [math.nan] + [math.log2(a.error / b.error) if a.error > 0 and b.error > 0 else math.nan
                         for a, b in zip(levels, levels[1:])]


def _f(x: float, fmt: str) -> str:
    return "-" if not math.isfinite(x) else format(x, fmt)


def section(out: Callable[[str], None]) -> list[tuple[Case, list[Level]]]:
    """Write the section (markdown lines to ``out``) and return the measured rows."""
    rows = []
    out(BEGIN)
    out("## Error estimates: observed orders, effectivities and times\n")
    out("Written by `benchmarks/estimate_validation.py`. `solve_reynolds(..., estimate_error=True)` (or "
        "`result.estimate_load_error()` afterwards) solves again on the mesh refined once and takes "
        "`|F_s - F_s/2| / (1 - 2^-k)` as the error of the load (`bearingfe.film.estimate`, `k` from "
        "`LOAD_ORDERS`: 2 for P1 and the finite volumes, 4 for P2). Each case is solved on a mesh and on "
        "that mesh refined once and twice (`refine_once`: gmsh refines its own mesh, new nodes on the curved "
        "outlines). `error`: relative error against the reference; `order`: observed from the previous "
        "level; `estimate`: the estimated relative error of that level; `eff`: estimate / true error "
        "(acceptance 0.5 to 2); `solve s`: the solve; `estimate s`: the refined solve the estimate costs. "
        "The tests of these effectivities: `tests/film/test_estimate.py`. (The `err` column of the journal "
        "tables above is another measure, `performance(estimate_error=True).error_estimate`: the load change "
        "under one refinement, reported with the refined values, whose error it overstates by about "
        "`2^k - 1 = 3`; its `load_error` is the estimate of those values: last table.)\n")
    for case in cases():
        levels = run(case)
        rows.append((case, levels))
        out(f"### {case.name}\n")
        scheme = "finite-volume" if case.solve.get("cavitation") == "jfo" else "finite-element"
        quantity = {"integral": "int p", "load": "|force|", "force_x": "force along phi = 0"}[case.quantity]
        out(f"Reference: {case.reference}. Quantity: {quantity}; order used: {load_order(scheme, case.element):g}.\n")
        out("| level | nodes | dofs | value | error | order | estimate | eff | solve s | estimate s |")
        out("|---|---|---|---|---|---|---|---|---|---|")
        for k, (lv, p) in enumerate(zip(levels, orders(levels))):
            out(f"| {k} | {lv.nodes} | {lv.dofs} | {lv.value:.10g} | {lv.error:.3e} | {_f(p, '.2f')} | "
                f"{_f(lv.estimate, '.3e')} | {_f(lv.effectivity, '.3f')} | {lv.solve_seconds:.3f} | "
                f"{_f(lv.estimate_seconds, '.3f')} |")
        out("")
    performance_rows(out)
    effs = [lv.effectivity for _, levels in rows for lv in levels if math.isfinite(lv.effectivity)]
    out(f"Effectivities over all cases and levels: {min(effs):.3f} to {max(effs):.3f}. Machine: "
        f"{platform.processor() or platform.machine()}, Python {platform.python_version()}.\n")
    out("P2 with Swift-Stieber cavitation bounds the Bernstein coefficients of the pressure (its values at "
        "the vertices and, on each edge between free vertices, twice the midside value less the mean of the "
        "ends), so the discrete pressure is non-negative on whole elements and the discrete sets are nested "
        "under refinement (`bearingfe.cavitation.swift_stieber`). Bounding only the nodal values, as the "
        "package did before, let the load converge irregularly at the 1e-5 level (|force| = 5.2638572, "
        "5.2638675, 5.2639222, 5.2639150 on the meshes of the P2 journal above and one more refinement), and "
        "the estimate measured 0.19 and 1.23 of the error there.\n")
    out(END)
    return rows


PERFORMANCE_HEADING = "### Journal chart answers: `performance(..., estimate_error=True)`"


def performance_rows(out: Callable[[str], None]) -> None:
    """The journal tables' everyday answer (refined once, reporting the refined values) and its two measures."""
    from bearingfe.bearings.journal import performance

    out(f"{PERFORMANCE_HEADING}\n")
    out("The everyday answer of the journal tables above (default size, graded, refined once; the values "
        "reported are the refined mesh's). `load_error`: the estimated error of those values (the change "
        "scaled by `1 / (2^k - 1)`, `LoadError.refined_relative`); `error_estimate` (the tables' `err`): "
        "the plain change. True error against the converged S.\n")
    out("| L/D | eps | nodes | S | true error | load_error | eff | error_estimate | eff | s |")
    out("|---|---|---|---|---|---|---|---|---|---|")
    for (ld, eps), S in JOURNAL_S.items():
        start = time.perf_counter()
        p = performance(bf.JournalBearing(ld), eps, size=min(0.1, ld / 5), estimate_error=True)
        seconds = time.perf_counter() - start
        true = abs(S / p.sommerfeld - 1)  # the load is 2a / (pi S)
        out(f"| {ld:g} | {eps:g} | {p.n_nodes} | {p.sommerfeld:.6g} | {true:.3e} | {p.load_error:.3e} | "
            f"{p.load_error / true:.3f} | {p.error_estimate:.3e} | {p.error_estimate / true:.3f} | {seconds:.2f} |")
    out("")


def main() -> None:
    lines: list[str] = []
    section(lines.append)
    text = PAGE.read_text()
    new = "\n".join(lines)
    if BEGIN in text:
        head, rest = text.split(BEGIN, 1)
        text = head + new + rest.split(END, 1)[1]
    else:
        marker = "\nTotal run time"
        head, tail = text.rsplit(marker, 1) if marker in text else (text, None)
        text = head.rstrip("\n") + "\n\n\n" + new + "\n" + (marker + tail if tail is not None else "")
    PAGE.write_text(text)


if __name__ == "__main__":
    main()
