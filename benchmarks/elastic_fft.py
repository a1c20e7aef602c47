"""Cost of the elastic (half-space) film from 1e3 to 1e5 unknowns: dense compliance against the FFT product.

The case: the 60 x 40 mm shoe of the shipped pump (``(-0.6, 0.6) x (-0.4, 0.4)`` R0) with a
square recess at 32 MPa, steel on steel, film ``CosineFilm(0.6, pi)``, cavitation ``"none"``,
P1 on :func:`bearingfe.grid_mesh` (uniform lines; largest opening about 0.4 c, so the
coupling is strong). For each size, in one process, interleaved and best of N:

``floor``
    the rigid film's factorization (the package default solver) of its condensed matrix and
    the solve of its unit right sides (what any film solve costs at least);
``rigid``
    the rigid film solve: :func:`bearingfe.superpose` and the result at the operating point;
``fft build`` / ``fft solve``
    :func:`bearingfe.elastic.half_space_fft` (the kernels, exact integrals) and the coupled
    :func:`bearingfe.elastic.solve_elastic` on it (matrix-free Newton-Krylov);
``dense build`` / ``dense solve``
    the same with the dense :func:`bearingfe.elastic.half_space` (only up to the dense limit,
    ``limit("compliance")``: 4000 film unknowns);
``product``
    one product ``C p``: dense matrix against FFT.

A second table does the same on gmsh meshes of the shoe with its circular pocket (the shipped
pump's), where the FFT needs the auxiliary grid of :func:`bearingfe.elastic.half_space_grid`
(an approximation: its difference from the dense map is reported, relative to the largest
opening, with the film force's).

A third table times the pump transient with the squeeze of the deflection
(:func:`bearingfe.transient.simulate_elastic`) on the shipped pump (gmsh mesh of
:func:`bearingfe.transient.pump_mesh`, steel on steel), a quarter revolution across the compression
from the steady start at 5.8 rad: the dense compliance (explicit ``K^-1``, dense Jacobian; up to the
dense limit) against the grid half-space held as its product (GMRES for ``K^-1`` and for the
integrator's Newton matrix), beside the rigid transient of the same window (:func:`bearingfe.simulate`).
At the smallest size the dense compliance is also run held as its product (the same map): its
difference from the dense run is the matrix-free path's own error.

Both paths converge to ``max |C p - w| <= 1e-8`` c; where both run, the largest difference
of their openings is reported. Run ``PYTHONPATH=. python -m benchmarks.elastic_fft`` (or the
``elastic_fft`` part of ``benchmarks/run_all.py``).
"""

from __future__ import annotations

import gc
import math
import os
import time

import numpy as np

from .common import md_table

#: Grid divisions of the recess width (cells of 0.2/k R0, k even: the recess edges on the uniform lines): about 1e3, 3e3, 1e4, 3e4, 1e5 film dofs.
DIVISIONS = (6, 12, 20, 36, 64)
QUICK_DIVISIONS = (6, 12)
#: gmsh element sizes [R0] of the shoe with the circular pocket: about 1e3, 3e3, 1e4, 3e4, 1e5 film dofs.
GMSH_SIZES = (0.032, 0.018, 0.0095, 0.0055, 0.003)
QUICK_GMSH_SIZES = (0.032, 0.018)
#: pump_mesh sizes [R0] of the transient table: about 1e3, 2.7e3, 1e4 film dofs.
TRANSIENT_SIZES = (0.035, 0.02, 0.0105)
QUICK_TRANSIENT_SIZES = (0.035,)
#: The transient window: revolutions from the steady start at ``TRANSIENT_BETA0`` [rad].
TRANSIENT_REVOLUTIONS, TRANSIENT_BETA0 = 0.25, 5.8


def _case():
    import bearingfe as bf

    scale = bf.Scale(radius=0.05, clearance=20e-6, viscosity=0.03, speed=157.08)
    steel = bf.Material("steel", 210e9, poisson_ratio=0.3)
    surface = bf.Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=[bf.Rectangle((0.0, 0.0), (0.2, 0.2))])
    return bf, scale, (steel, steel), surface, bf.CosineFilm(0.6, math.pi), scale.from_pressure(32e6)


def _pocket_surface(bf):
    return bf.Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=[bf.Circle((0.0, 0.0), 0.1748)])


def _best(fn, reps: int) -> tuple[float, object]:
    best, out = math.inf, None
    for _ in range(reps):
        gc.collect()
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


def measure(k: int | None = None, gmsh_size: float | None = None) -> dict:
    """Times of one size (see the module docstring): the grid mesh of ``k`` divisions, or a gmsh mesh."""
    from bearingfe.core.limits import limit
    from bearingfe.core.linalg import DEFAULT_SOLVER, get_linear_solver
    from bearingfe.elastic import half_space, half_space_fft, half_space_grid, solve_elastic

    bf, scale, steel, surface, film, ps = _case()
    if gmsh_size is None:
        mesh, build, kind = bf.grid_mesh(surface, 0.2 / k), half_space_fft, "grid"
    else:
        mesh = bf.mesh_surface(_pocket_surface(bf), gmsh_size, max_elements=1_000_000)
        build, kind = half_space_grid, "gmsh"
    n = mesh.mesh.p.shape[1]
    reps = 3 if n < 5e3 else (2 if n < 3e4 else 1)
    factorize = get_linear_solver(DEFAULT_SOLVER)
    bf.superpose(mesh, film, formulation="direct")  # untimed: the mesh operators, built once

    def rigid():
        sup = bf.superpose(mesh, film, formulation="direct")
        return sup.combine(1.0, (0.0, 0.0), ps)

    def floor():
        sup = bf.superpose(mesh, film, formulation="direct")
        t = time.perf_counter()
        factorize(sup.system.matrix)(sup.system.rhs)
        return time.perf_counter() - t

    row = {"mesh": kind, "dofs": n, "reps": reps, "load": os.getloadavg()[0]}
    row["floor"] = min(floor() for _ in range(reps))
    row["rigid"], _ = _best(rigid, reps)
    mesh._cache.pop("half_space_fft", None)
    row["fft_build"], C = _best(lambda: (mesh._cache.pop("half_space_fft", None),
                                          build(mesh, scale, steel))[1], reps)
    row["fft_solve"], sol = _best(lambda: solve_elastic(mesh, film, C, inlet_pressure=ps), reps)
    p = sol.result.pressure
    row["fft_product"], _ = _best(lambda: C.apply(p), max(reps, 3))
    row.update(newton=sol.iterations, krylov=sol.krylov_iterations, max_deflection=sol.max_deflection,
               residual=sol.residual)
    row.update(dense_build=None, dense_solve=None, dense_product=None, difference=None, force=float(sol.result.force[0]),
               force_difference=None)
    if n <= limit("compliance"):
        row["dense_build"], D = _best(lambda: half_space(mesh, scale, steel), reps)
        row["dense_solve"], ref = _best(lambda: solve_elastic(mesh, film, D, inlet_pressure=ps), reps)
        row["dense_product"], _ = _best(lambda: D.apply(p), max(reps, 3))
        row["dense_newton"] = ref.iterations
        row["difference"] = float(np.abs(ref.deflection - sol.deflection).max())
        row["force_difference"] = float(abs(sol.result.force[0] / ref.result.force[0] - 1.0))
    return row


def measure_transient(size: float) -> dict:
    """The transient row of one ``pump_mesh`` size (see the module docstring); one run each."""
    import bearingfe as bf
    from bearingfe.core.limits import limit
    from bearingfe.elastic import Compliance, half_space, half_space_grid
    from bearingfe.transient import simulate_elastic
    from tests.helpers import ROOT

    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    mesh = bf.transient.pump_mesh(pump, size)
    mats = (pump.shoe_material, pump.eccentric_material)
    kw = dict(start="steady", beta0=TRANSIENT_BETA0, points_per_revolution=72)
    n = mesh.n_nodes
    row = {"mesh": "transient", "dofs": n, "load": os.getloadavg()[0]}
    gc.collect()
    row["rigid"], rigid = _best(lambda: bf.simulate(pump, mesh, TRANSIENT_REVOLUTIONS, **kw), 1)
    row["product_build"], G = _best(lambda: half_space_grid(mesh, pump.scale, mats), 1)
    row["product"], prod = _best(lambda: simulate_elastic(pump, G, TRANSIENT_REVOLUTIONS, **kw), 1)
    row.update(status=prod.status, rigid_status=rigid.status, steps=prod.stats["steps"],
               krylov=prod.stats["krylov_iterations"], products=prod.stats["compliance_products"],
               solves=prod.stats["nfev"], h_min=float(prod.h_min.min() / pump.clearance),
               dense_build=None, dense=None, dense_steps=None, difference=None, same_map=None)
    if n <= limit("compliance"):
        row["dense_build"], D = _best(lambda: half_space(mesh, pump.scale, mats), 1)
        row["dense"], dense = _best(lambda: simulate_elastic(pump, D, TRANSIENT_REVOLUTIONS, **kw), 1)
        row.update(dense_steps=dense.stats["steps"], dense_status=dense.status,
                   difference=float(np.abs(dense.h_min - prod.h_min).max() / pump.clearance))
        if size == max(TRANSIENT_SIZES):
            same = Compliance(mesh=D.mesh, element=D.element, model="dense-as-product", matrix=None,
                              pocket=D.pocket, modulus=D.modulus, scale=D.scale, seconds=0.0,
                              operator=lambda p: D.matrix @ p)
            row["same_map_seconds"], again = _best(lambda: simulate_elastic(pump, same, TRANSIENT_REVOLUTIONS, **kw),
                                                   1)
            row["same_map"] = float(max(np.abs(dense.h_min - again.h_min).max() / pump.clearance,
                                        np.abs(dense.gamma - again.gamma).max(),
                                        np.abs(dense.delta - again.delta).max()))
    return row


def run(quick: bool = False, log=print) -> list[dict]:
    rows = []
    for k in (QUICK_DIVISIONS if quick else DIVISIONS):
        t = time.perf_counter()
        rows.append(measure(k))
        log(f"elastic_fft: grid, {rows[-1]['dofs']} dofs in {time.perf_counter() - t:.1f} s")
    for size in (QUICK_GMSH_SIZES if quick else GMSH_SIZES):
        t = time.perf_counter()
        rows.append(measure(gmsh_size=size))
        log(f"elastic_fft: gmsh, {rows[-1]['dofs']} dofs in {time.perf_counter() - t:.1f} s")
    for size in (QUICK_TRANSIENT_SIZES if quick else TRANSIENT_SIZES):
        t = time.perf_counter()
        rows.append(measure_transient(size))
        log(f"elastic_fft: transient, {rows[-1]['dofs']} dofs in {time.perf_counter() - t:.1f} s")
    return rows


def _g(x, unit="") -> str:
    return "-" if x is None or not math.isfinite(x) else f"{x:.3g}{unit}"


def _slope(rows, key) -> float:
    pts = [(r["dofs"], r[key]) for r in rows if r.get(key)]
    if len(pts) < 2:
        return math.nan
    x, y = np.log([p[0] for p in pts]), np.log([p[1] for p in pts])
    return float(np.polyfit(x, y, 1)[0])


def report(rows: list[dict]) -> tuple[str, dict]:
    """The part's markdown and the facts it quotes."""
    grid = [r for r in rows if r.get("mesh", "grid") == "grid"]
    gmsh = [r for r in rows if r.get("mesh") == "gmsh"]
    table = [[r["dofs"], _g(r["floor"]), _g(r["rigid"]), _g(r["fft_build"]), _g(r["fft_solve"]),
              _g(r["fft_solve"] / r["floor"]), f"{r['newton']} / {r['krylov']}", _g(r["dense_build"]),
              _g(r["dense_solve"]), _g(r["dense_product"] and r["dense_product"] * 1e3),
              _g(r["fft_product"] * 1e3), _g(r["difference"]), f"{r['max_deflection']:.4f}", f"{r['load']:.1f}"]
             for r in grid]
    facts = {"rows": rows, "fft_solve_slope": _slope(grid, "fft_solve"), "floor_slope": _slope(grid, "floor"),
             "dense_solve_slope": _slope(grid, "dense_solve"), "largest_dofs": max(r["dofs"] for r in grid),
             "largest_fft_solve": max(grid, key=lambda r: r["dofs"])["fft_solve"],
             "max_difference": max((r["difference"] for r in grid if r["difference"] is not None), default=None)}
    both = [r for r in grid if r["dense_solve"]]
    lines = [
        "The coupled film on the half-space (Boussinesq) support, pump shoe with a 32 MPa recess, steel on steel "
        "(largest opening about 0.4 c: a strong coupling), P1 on a uniform grid, cavitation \"none\", to "
        "`max |C p - w| <= 1e-8` c. *fft*: the compliance held as its FFT product "
        "(`half_space_fft`, `COMPLIANCES[\"half-space-fft\"]`) and the matrix-free Newton-Krylov; *dense*: the "
        "dense compliance and the dense Newton (refused above 4000 film unknowns). *floor*: factorization + "
        "solves of the rigid film's condensed matrix; *rigid*: the rigid film solve. Times in s (products in ms), "
        "best of the repetitions; *Newton / GMRES*: Reynolds solves and Jacobian products of the fft path; "
        "*difference*: largest `|w_fft - w_dense|` [c]; *load*: 1-minute load average when the size ran "
        "(2 cores; above ~1 other helpers share the machine and absolute times are inflated, the ratios "
        "within a row less so).", "",
        md_table(["dofs", "floor", "rigid", "fft build", "fft solve", "fft solve / floor", "Newton / GMRES",
                  "dense build", "dense solve", "dense C p ms", "fft C p ms", "difference [c]", "max w [c]", "load"],
                 table), "",
        f"Growth (log-log slope against the dofs): fft solve {facts['fft_solve_slope']:.2f}, floor "
        f"{facts['floor_slope']:.2f}" + (f", dense solve {facts['dense_solve_slope']:.2f}" if len(both) > 1 else "")
        + f". The fft path solves {facts['largest_dofs']} film unknowns in {facts['largest_fft_solve']:.3g} s.",
    ]
    if both:
        lines += ["", "Where both run: " + "; ".join(
            f"{r['dofs']} dofs, dense {r['dense_build'] + r['dense_solve']:.3g} s (build + solve) against fft "
            f"{r['fft_build'] + r['fft_solve']:.3g} s" for r in both) + "."]
    if gmsh:
        facts.update(gmsh_solve_slope=_slope(gmsh, "fft_solve"), gmsh_largest_dofs=max(r["dofs"] for r in gmsh),
                     gmsh_largest_solve=max(gmsh, key=lambda r: r["dofs"])["fft_solve"])
        table = [[r["dofs"], _g(r["floor"]), _g(r["rigid"]), _g(r["fft_build"]), _g(r["fft_solve"]),
                  _g(r["fft_solve"] / r["floor"]), f"{r['newton']} / {r['krylov']}", _g(r["dense_build"]),
                  _g(r["dense_solve"]),
                  _g(r["difference"] and r["difference"] / r["max_deflection"]), _g(r["force_difference"]),
                  f"{r['max_deflection']:.4f}", f"{r['load']:.1f}"] for r in gmsh]
        lines += ["", "### Unstructured (gmsh) meshes: the FFT through an auxiliary grid", "",
                  "The same case on gmsh meshes of the shoe with its circular pocket (the shipped pump's), P1: "
                  "the compliance through a uniform grid of half the median edge of the mesh (`half_space_grid`, "
                  "`COMPLIANCES[\"half-space-grid\"]`, an approximation of the dense map, second order in the "
                  "grid spacing). *difference*: largest `|w_grid - w_dense|` over the largest opening; *force "
                  "difference*: relative difference of the film force (both converged to 1e-8 c).", "",
                  md_table(["dofs", "floor", "rigid", "grid build", "grid solve", "grid solve / floor",
                            "Newton / GMRES", "dense build", "dense solve", "difference", "force difference",
                            "max w [c]", "load"], table), "",
                  f"Growth: grid solve {facts['gmsh_solve_slope']:.2f} (log-log slope); "
                  f"{facts['gmsh_largest_dofs']} film unknowns in {facts['gmsh_largest_solve']:.3g} s."]
    transient = sorted((r for r in rows if r.get("mesh") == "transient"), key=lambda r: r["dofs"])
    if transient:
        lines += ["", *_transient_report(transient, facts)]
    return "\n".join(lines) + "\n", facts


def _transient_report(rows: list[dict], facts: dict) -> list[str]:
    """The transient table (:func:`measure_transient`) and its facts."""
    table = [[r["dofs"], _g(r["rigid"]), _g(r["dense_build"] and r["dense_build"] + r["dense"]),
              _g(r["product_build"] + r["product"]),
              _g(r["dense"] and (r["product_build"] + r["product"]) / (r["dense_build"] + r["dense"])),
              f"{r['steps']}" + ("" if r["dense_steps"] is None else f" / {r['dense_steps']}"),
              _g(r["krylov"] / max(r["solves"], 1)),
              r["products"], _g(r["difference"]), _g(r["same_map"]), f"{r['h_min']:.4f}", r["status"],
              f"{r['load']:.1f}"] for r in rows]
    both = [r for r in rows if r["dense"] is not None]
    facts.update(transient_largest_dofs=rows[-1]["dofs"], transient_largest_seconds=rows[-1]["product"],
                 transient_product_slope=_slope(rows, "product"),
                 transient_same_map=max((r["same_map"] for r in rows if r["same_map"] is not None), default=None))
    lines = ["### The pump transient with the squeeze of the deflection: dense against matrix-free", "",
             f"`simulate_elastic` on the shipped pump (steel on steel, `pump_mesh`, P1), {TRANSIENT_REVOLUTIONS} "
             f"revolution from the steady start at {TRANSIENT_BETA0} rad (across the compression), one run each. "
             "*dense*: the dense half-space, the explicit `K^-1` and the integrator's dense Jacobian (refused above "
             "4000 film unknowns); *product*: the grid half-space (`half_space_grid`) held as its FFT product, `K^-1` "
             "and the integrator's Newton matrix by GMRES with the two-level preconditioner; *rigid*: "
             "`bearingfe.simulate` of the same window. Times in s, builds of the compliance included. *steps*: "
             "product / dense; *GMRES per right side*: GMRES iterations over the right sides evaluated; *difference*: "
             "largest `|h_min(product) - h_min(dense)|` [c] (the grid half-space approximates the dense map); *same "
             "map*: the dense compliance run as a product, largest difference from the dense run in `h_min` [c], "
             "`gamma`, `delta` (the matrix-free path's own error, against rtol 1e-5); *h_min*: smallest film [c].", "",
             md_table(["dofs", "rigid", "dense", "product", "product / dense", "steps", "GMRES per right side",
                       "C products", "difference [c]", "same map", "h_min [c]", "status", "load"], table), ""]
    text = f"Growth: product {facts['transient_product_slope']:.2f} (log-log slope of the run time)"
    if both:
        text += "; where both run: " + "; ".join(
            f"{r['dofs']} dofs, product {(r['product_build'] + r['product']) / (r['dense_build'] + r['dense']):.2g} "
            "times the dense run" for r in both)
    above = ", above the dense limit," if rows[-1]["dense"] is None else ""
    lines.append(text + f". The matrix-free squeeze runs {facts['transient_largest_dofs']} film unknowns{above} in "
                 f"{facts['transient_largest_seconds']:.3g} s ({rows[-1]['status']}).")
    return lines


if __name__ == "__main__":
    import argparse
    import json

    from .common import DOCS

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    text, facts = report(run(args.quick))
    print(text)
    print(json.dumps(facts, indent=1, default=str))
