"""Work-precision benchmarks of the Reynolds solvers: load error against wall time.

Case (a): a smooth partial arc (no pocket) with wedge and squeeze.
Case (b): a rectangular recess (sharp re-entrant corners: singular pressure
gradients) at an inlet pressure 1000 times the hydrodynamic scale.

Methods, side by side: FEM P1 and P2 in both formulations (pi, direct) on
uniform and graded gmsh meshes, the FD reference with a sparse LU solve
(pi and direct five-point schemes) and the paper's FD Seidel iteration.
The error is the relative error of the load vector ``int p (cos, sin)``
against a converged reference: P2, direct form, second-order geometry, on a
mesh finer than any in the sweep (for (b) graded toward the corners), whose
own error is estimated from the next coarser reference mesh and from the
Richardson extrapolation of the FD LU sequence.
"""

from __future__ import annotations

import copy
import math
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

import bearingfe as bf
from bearingfe.film.fd import solve_reynolds_fd
from bearingfe.core.linalg import available_solvers

from .common import IMG, loglog_plot, md_table, time_at_error, timed

EPS = 1e-9  # pocket edges a hair outside the FD grid lines, so edge nodes count as pocket nodes


@dataclass(frozen=True)
class Case:
    name: str
    title: str
    surface: bf.Surface
    film: bf.CosineFilm
    wedge: float
    squeeze: tuple[float, float]
    inlet_pressure: float
    sizes: tuple[float, ...]                  # FEM nominal element sizes, coarse to fine
    fd_cells: tuple[int, ...]                 # FD cells along z (grid-aligned with the pocket)
    fd_shape: Callable[[int], tuple[int, int]]
    graded: Callable[[float], dict]           # extra mesh_surface arguments of the graded family
    graded_text: str                          # what the graded family is, for the page
    ref_size: float
    seidel_max: int                           # largest FD cells along z for Seidel


def case_a(quick: bool) -> Case:
    film = bf.CosineFilm(0.6, math.pi + 0.3)  # thinnest film h = 0.4 at phi = 0.3, inside the arc

    def graded(size):
        def f(phi, z):
            h = 1.0 + 0.6 * np.cos(phi - film.phi0)
            return size * np.clip(h / 1.2, 0.35, 1.0)
        return {"size_function": f}

    return Case(
        name="a", title="(a) smooth partial arc, wedge + squeeze",
        surface=bf.Surface(arc=(-1.0, 1.0), half_width=0.5), film=film, wedge=1.0, squeeze=(0.3, 0.2),
        inlet_pressure=0.0,
        sizes=(0.2, 0.1, 0.05) if quick else (0.2, 0.1, 0.05, 0.025),
        fd_cells=(10, 20, 40, 80) if quick else (10, 20, 40, 80, 160, 320, 640),
        fd_shape=lambda k: (2 * k + 1, k + 1), graded=graded,
        graded_text="`size_function`: the nominal size times h/1.2 clipped to [0.35, 1] (finer where the film is thin)",
        ref_size=0.025 if quick else 0.0125, seidel_max=40 if quick else 80)  # Seidel at 160: ~95 s alone


def case_b(quick: bool) -> Case:
    pocket = bf.Rectangle((0.0, 0.0), (0.48 + 2 * EPS, 0.4 + 2 * EPS))  # 16 % of the area

    def graded(size):
        return {"corner_size": size / 8, "inlet_size": size / 2, "grading_distance": 0.15}

    return Case(
        name="b", title="(b) rectangular recess, p_s = 1000",
        surface=bf.Surface(arc=(-0.6, 0.6), half_width=0.5, inlets=(pocket,)),
        film=bf.CosineFilm(0.5, math.pi), wedge=1.0, squeeze=(0.0, 0.0), inlet_pressure=1000.0,
        # 0.2 and 0.15: the coarse graded P2 meshes whose load errors bracket 1e-3 (the FEM-FD target)
        sizes=(0.2, 0.15, 0.1, 0.05, 0.025) if quick else (0.2, 0.15, 0.1, 0.05, 0.025, 0.0125),
        fd_cells=(10, 20, 40, 80) if quick else (10, 20, 40, 80, 160, 320, 640),
        fd_shape=lambda k: (k + 1, k + 1), graded=graded,
        graded_text=("`corner_size` = size/8 at the pocket corners, `inlet_size` = size/2 on the pocket contours, "
                     "both growing linearly to the nominal size over `grading_distance` = 0.15"),
        ref_size=0.0125 if quick else 0.00625, seidel_max=40 if quick else 160)


@dataclass
class Run:
    label: str
    dofs: list = field(default_factory=list)
    seconds: list = field(default_factory=list)       # solve (operators..postprocess, or FD total)
    force_seconds: list = field(default_factory=list) # FEM force only: superpose(...).force(...)
    meshing: list = field(default_factory=list)       # gmsh time (FEM only)
    force: list = field(default_factory=list)
    error: list = field(default_factory=list)
    costs: list = field(default_factory=list)
    notes: list = field(default_factory=list)


def _mesh(case: Case, size: float, graded: bool, order: int):
    extra = case.graded(size) if graded else {}
    return timed(bf.mesh_surface, case.surface, size, order=order, **extra)


def _repeats(unknowns: int) -> int:
    """Timed repetitions (the best is kept) of one FEM or FD solve: more for the small ones, whose
    milliseconds a loaded machine disturbs most; the same rule for both."""
    return 7 if unknowns < 5000 else 3 if unknowns < 20000 else 1


def _fresh(mesh, call: Callable, repeat: int):
    """Best wall time of ``call(m)`` over ``repeat`` runs, each on its own copy of ``mesh`` as meshing
    returned it (made before the clock starts): every run pays what a first solve on a new mesh
    pays (operators, the map, the facet tables scikit-fem builds on first use); (last result, time)."""
    best, out = np.inf, None
    for _ in range(repeat):
        fresh = copy.deepcopy(mesh)
        t = time.perf_counter()
        out = call(fresh)
        best = min(best, time.perf_counter() - t)
    return out, best


def _fem(case: Case, mesh, element: str, formulation: str):
    return _fresh(mesh, lambda m: bf.solve_reynolds(m, case.film, wedge=case.wedge, squeeze=case.squeeze,
                                                    inlet_pressure=case.inlet_pressure, formulation=formulation,
                                                    element=element), _repeats(mesh.n_nodes))


def _fem_force(case: Case, mesh, element: str, formulation: str):
    """Force only, as the transient uses it: ``superpose(...).force(...)`` on a fresh mesh
    (no pressure field, flows or friction)."""
    return _fresh(mesh, lambda m: bf.superpose(m, case.film, formulation=formulation, element=element).force(
        case.wedge, case.squeeze, case.inlet_pressure), _repeats(mesh.n_nodes))


def reference(case: Case) -> dict:
    """Converged load: P2 direct, curved geometry, graded, at ref_size and 2*ref_size."""
    out = {}
    for s in (2 * case.ref_size, case.ref_size):
        mesh, t_mesh = _mesh(case, s, True, 2)
        solver = "cholmod" if "cholmod" in available_solvers() else "splu"  # accuracy only: fastest exact solver
        res, t = timed(bf.solve_reynolds, mesh, case.film, wedge=case.wedge, squeeze=case.squeeze,
                       inlet_pressure=case.inlet_pressure, formulation="direct", element="P2", solver=solver)
        out[s] = (res.force.copy(), int(res.cost["dofs"]), t_mesh + t)
    fine, coarse = out[case.ref_size][0], out[2 * case.ref_size][0]
    return {"force": fine, "dofs": out[case.ref_size][1], "seconds": out[case.ref_size][2],
            "change": float(np.linalg.norm(fine - coarse) / np.linalg.norm(fine))}


def run_case(case: Case, quick: bool) -> dict:
    ref = reference(case)
    F = ref["force"]
    err = lambda f: float(np.linalg.norm(np.asarray(f) - F) / np.linalg.norm(F))
    runs: dict[str, Run] = {}
    for graded in (False, True):
        for element in ("P1", "P2"):
            order = 2 if element == "P2" else 1
            for size in case.sizes:
                mesh, t_mesh = _mesh(case, size, graded, order)
                for formulation in ("pi", "direct"):
                    label = f"FEM {element} {formulation} {'graded' if graded else 'uniform'}"
                    run = runs.setdefault(label, Run(label))
                    res, t = _fem(case, mesh, element, formulation)
                    f_only, t_force = _fem_force(case, mesh, element, formulation)
                    if not np.allclose(f_only, res.force, rtol=1e-10, atol=0.0):
                        raise RuntimeError(f"{label}: superpose().force disagrees with solve_reynolds().force")
                    run.dofs.append(int(res.cost["dofs"]))
                    run.seconds.append(t)
                    run.force_seconds.append(t_force)
                    run.meshing.append(t_mesh)
                    run.force.append(res.force.copy())
                    run.error.append(err(res.force))
                    run.costs.append(dict(res.cost, meshing=t_mesh))
                    run.notes.extend(res.notes)
    for formulation in ("pi", "direct"):
        for method in ("direct", "seidel"):
            if method == "seidel" and formulation == "direct":
                continue
            label = f"FD {'LU' if method == 'direct' else 'Seidel'} {formulation}"
            run = runs.setdefault(label, Run(label))
            for k in case.fd_cells:
                if method == "seidel" and k > case.seidel_max:
                    break
                shape = case.fd_shape(k)
                r, t = timed(solve_reynolds_fd, case.surface, case.film, shape, wedge=case.wedge,
                             squeeze=case.squeeze, inlet_pressure=case.inlet_pressure,
                             formulation=formulation, method=method, tol=1e-10,
                             repeat=_repeats(shape[0] * shape[1]))
                run.dofs.append(shape[0] * shape[1])
                run.seconds.append(t)
                run.meshing.append(0.0)
                run.force.append(r.force.copy())
                run.error.append(err(r.force))
                run.costs.append({"iterations": r.iterations})
    fd = runs["FD LU direct"].force
    rich = None
    if len(fd) >= 3:  # Richardson with the observed order from the three finest FD LU grids
        f1, f2, f3 = (np.linalg.norm(v) for v in fd[-3:])
        q = math.log2(abs((f1 - f2) / (f2 - f3))) if (f2 - f3) != 0 and (f1 - f2) != 0 else float("nan")
        rich = {"order": q, "extrapolated": f3 + (f3 - f2) / (2**q - 1) if math.isfinite(q) else float("nan")}
    return {"case": case, "reference": ref, "runs": runs, "richardson": rich}


def report(result: dict) -> str:
    case, ref, runs = result["case"], result["reference"], result["runs"]
    lines = [f"### {case.title}", ""]
    lines.append(
        f"Surface arc {case.surface.arc}, half-width {case.surface.half_width}, pockets "
        f"{[type(s).__name__ for s in case.surface.inlets] or 'none'} "
        f"({100 * case.surface.inlet_fraction:.0f} % of the area); film gamma = {case.film.gamma}, "
        f"phi0 = {case.film.phi0:.4g}; wedge {case.wedge}, squeeze {case.squeeze}, p_s = {case.inlet_pressure:g}. "
        f"Graded meshes: {case.graded_text}.")
    lines.append("")
    rich = result["richardson"]
    rtxt = ""
    if rich:
        rtxt = (f" The FD LU (direct) sequence extrapolates (Richardson, observed order {rich['order']:.2f}) to "
                f"|F| = {rich['extrapolated']:.8g}, {abs(rich['extrapolated'] / np.linalg.norm(ref['force']) - 1):.1e} "
                f"from the reference.")
    lines.append(
        f"**Reference**: P2, direct form, curved (order 2) geometry, graded mesh of nominal size {case.ref_size} "
        f"({ref['dofs']} dofs, {ref['seconds']:.1f} s): F = ({ref['force'][0]:.10g}, {ref['force'][1]:.10g}). "
        f"It moved by {ref['change']:.1e} (relative) from the mesh twice as coarse, so errors below "
        f"~{max(ref['change'] / 10, 1e-12):.0e} are not resolved.{rtxt}")
    lines.append("")
    series = {r.label: (r.seconds, r.error) for r in runs.values()}
    img = loglog_plot(IMG / f"work_precision_{case.name}.png", series, xlabel="wall time per solve [s]",
                      ylabel="relative load error", title=case.title)
    lines += [f"![work-precision {case.name}]({img})", ""]
    rows = []
    for r in runs.values():
        tf = r.force_seconds or [np.nan] * len(r.dofs)
        for k, (n, t, t_f, tm, e) in enumerate(zip(r.dofs, r.seconds, tf, r.meshing, r.error)):
            rows.append([r.label, n, t, t_f, tm, e, observed_order(r.dofs, r.error, k)])
    lines.append("<details><summary>All points (dofs = FEM unknowns incl. boundary, FD grid nodes; order q: "
                 "load error ~ dofs^-q from the previous point of the method, 1 for h^2 and 2 for h^4)</summary>\n")
    lines.append(md_table(["method", "dofs", "solve s", "force-only s", "meshing s", "load error", "order q"], rows))
    lines += ["", "</details>", ""]
    # time to reach given errors
    targets = (1e-2, 1e-3, 1e-4, 1e-5)
    rows = []
    for r in runs.values():
        rows.append([r.label] + [time_at_error(r.seconds, r.error, t) for t in targets]
                    + [time_at_error(np.add(r.seconds, r.meshing), r.error, t) for t in targets[1:3]])
    lines.append("Wall time [s] to reach a relative load error (log-log interpolation between measured points; "
                 "'-' = not reached in the sweep); last two columns include gmsh meshing:")
    lines.append("")
    lines.append(md_table(["method"] + [f"{t:.0e}" for t in targets] + ["1e-03 +mesh", "1e-04 +mesh"], rows))
    lines.append("")
    lines.append(speedup_text(runs, targets))
    notes = sorted({n for r in runs.values() for n in r.notes})
    if notes:
        lines += ["", "Solver notes: " + "; ".join(notes)]
    lines.append("")
    return "\n".join(lines)


def observed_order(dofs, errors, k: int) -> float:
    """``q`` in ``error ~ dofs^-q`` between points ``k-1`` and ``k`` of a method (NaN for the first)."""
    if k == 0 or errors[k] <= 0 or errors[k - 1] <= 0 or dofs[k] == dofs[k - 1]:
        return float("nan")
    return float(-math.log(errors[k] / errors[k - 1]) / math.log(dofs[k] / dofs[k - 1]))


def best_fem_vs_fd(runs: dict[str, Run], target: float, with_meshing: bool = False, force_only: bool = False):
    def t(r):
        s = r.force_seconds if force_only else r.seconds
        return np.add(s, r.meshing) if with_meshing else s
    fem = {k: time_at_error(t(r), r.error, target) for k, r in runs.items() if k.startswith("FEM")}
    fem = {k: v for k, v in fem.items() if np.isfinite(v)}
    fd = time_at_error(runs["FD LU pi"].seconds, runs["FD LU pi"].error, target)
    seidel = time_at_error(runs["FD Seidel pi"].seconds, runs["FD Seidel pi"].error, target)
    if not fem:
        return None, np.nan, fd, seidel
    best = min(fem, key=fem.get)
    return best, fem[best], fd, seidel


def speedup_text(runs: dict[str, Run], targets) -> str:
    rows = []
    for t in targets:
        best, tf, fd, seidel = best_fem_vs_fd(runs, t)
        _, tfm, _, _ = best_fem_vs_fd(runs, t, with_meshing=True)
        rows.append([f"{t:.0e}", best or "-", tf, tfm, fd, seidel, fd / tf if best else np.nan,
                     seidel / tf if best else np.nan])
    return ("Best FEM method against the FD reference at equal load error (speed-up = FD time / FEM time, "
            "FEM without meshing; the paper's scheme is FD pi):\n\n"
            + md_table(["error", "best FEM", "FEM s", "FEM+mesh s", "FD LU pi s", "FD Seidel pi s",
                        "speed-up vs FD LU", "speed-up vs Seidel"], rows))


def cost_split(results: list[dict]) -> str:
    rows = []
    for res in results:
        for r in res["runs"].values():
            if not r.label.startswith("FEM") or not r.costs:
                continue
            c = r.costs[-1]
            rows.append([res["case"].name, r.label, int(c["dofs"]), c["meshing"], c["mesh_operators"],
                         c["assembly"], c["factorization"], c["solve"], c.get("postprocess", np.nan)])
    return md_table(["case", "method (finest mesh)", "dofs", "meshing", "operators", "assembly",
                     "factorization", "solves (4 rhs)", "integrals+flows"], rows)
