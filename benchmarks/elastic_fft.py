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


def _case():
    import bearingfe as bf

    scale = bf.Scale(radius=0.05, clearance=20e-6, viscosity=0.03, speed=157.08)
    steel = bf.Material("steel", 210e9, poisson_ratio=0.3)
    surface = bf.Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=[bf.Rectangle((0.0, 0.0), (0.2, 0.2))])
    return bf, scale, (steel, steel), surface, bf.CosineFilm(0.6, math.pi), scale.from_pressure(32e6)


def _best(fn, reps: int) -> tuple[float, object]:
    best, out = math.inf, None
    for _ in range(reps):
        gc.collect()
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return best, out


def measure(k: int) -> dict:
    """Times of one size (see the module docstring)."""
    from bearingfe.core.limits import limit
    from bearingfe.core.linalg import DEFAULT_SOLVER, get_linear_solver
    from bearingfe.elastic import half_space, half_space_fft, solve_elastic

    bf, scale, steel, surface, film, ps = _case()
    mesh = bf.grid_mesh(surface, 0.2 / k)
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

    row = {"dofs": n, "reps": reps, "load": os.getloadavg()[0]}
    row["floor"] = min(floor() for _ in range(reps))
    row["rigid"], _ = _best(rigid, reps)
    mesh._cache.pop("half_space_fft", None)
    row["fft_build"], C = _best(lambda: (mesh._cache.pop("half_space_fft", None),
                                          half_space_fft(mesh, scale, steel))[1], reps)
    row["fft_solve"], sol = _best(lambda: solve_elastic(mesh, film, C, inlet_pressure=ps), reps)
    p = sol.result.pressure
    row["fft_product"], _ = _best(lambda: C.apply(p), max(reps, 3))
    row.update(newton=sol.iterations, krylov=sol.krylov_iterations, max_deflection=sol.max_deflection,
               residual=sol.residual)
    row.update(dense_build=None, dense_solve=None, dense_product=None, difference=None)
    if n <= limit("compliance"):
        row["dense_build"], D = _best(lambda: half_space(mesh, scale, steel), reps)
        row["dense_solve"], ref = _best(lambda: solve_elastic(mesh, film, D, inlet_pressure=ps), reps)
        row["dense_product"], _ = _best(lambda: D.apply(p), max(reps, 3))
        row["dense_newton"] = ref.iterations
        row["difference"] = float(np.abs(ref.deflection - sol.deflection).max())
    return row


def run(quick: bool = False, log=print) -> list[dict]:
    rows = []
    for k in (QUICK_DIVISIONS if quick else DIVISIONS):
        t = time.perf_counter()
        rows.append(measure(k))
        log(f"elastic_fft: {rows[-1]['dofs']} dofs in {time.perf_counter() - t:.1f} s")
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
    table = [[r["dofs"], _g(r["floor"]), _g(r["rigid"]), _g(r["fft_build"]), _g(r["fft_solve"]),
              _g(r["fft_solve"] / r["floor"]), f"{r['newton']} / {r['krylov']}", _g(r["dense_build"]),
              _g(r["dense_solve"]), _g(r["dense_product"] and r["dense_product"] * 1e3),
              _g(r["fft_product"] * 1e3), _g(r["difference"]), f"{r['max_deflection']:.4f}", f"{r['load']:.1f}"]
             for r in rows]
    facts = {"rows": rows, "fft_solve_slope": _slope(rows, "fft_solve"), "floor_slope": _slope(rows, "floor"),
             "dense_solve_slope": _slope(rows, "dense_solve"), "largest_dofs": max(r["dofs"] for r in rows),
             "largest_fft_solve": max(rows, key=lambda r: r["dofs"])["fft_solve"],
             "max_difference": max((r["difference"] for r in rows if r["difference"] is not None), default=None)}
    both = [r for r in rows if r["dense_solve"]]
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
    return "\n".join(lines) + "\n", facts


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
