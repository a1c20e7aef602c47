"""Work-precision of error-driven adaptive meshes against uniform and film-graded ones; writes docs/adaptivity.md.

Usage (from the repository root)::

    PYTHONPATH=. python benchmarks/adaptivity.py           # full run, ~4-5 min on 2 cores
    PYTHONPATH=. python benchmarks/adaptivity.py --quick   # small sizes, ~1 min (smoke test)

Cases:

(b) the sharp rectangular recess at p_s = 1000 of ``benchmarks/work_precision.py``
    (re-entrant corners: singular pressure gradients);
(j) the full Raimondi-Boyd journal, L/D 1, eccentricity 0.99, Swift-Stieber
    cavitation (thinnest film 0.01 c: a pressure spike of width ~0.1 rad);
(c) the full journal of ``tests/test_adaptivity.py``: L/D 0.5 (half-width 0.5),
    eccentricity 0.9, Swift-Stieber; only its reference value is computed.

Methods: uniform gmsh meshes (P1, P2 on curved order-2 geometry), for the
journal also meshes graded towards the thin film with
:func:`bearingfe.bearings.journal.film_graded_size` (``min_size = size sqrt(1 - eps)``,
passed to ``mesh_surface`` as its floor), and :func:`bearingfe.adaptivity.adapt`
(P1, P2; load indicator, growth 2.5). Error: relative error of the load
``|F|`` against a reference value that is computed in the same run by
Richardson extrapolation of two independent P2 sequences (see the report).
Time of a uniform or graded point: meshing + one ``solve_reynolds`` on the
fresh mesh; of an adaptive point: all levels up to it (meshing, solves,
indicators, size fields), since that is what it costs to get there.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

if __package__ in (None, ""):  # run as a script: make the repository root importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import bearingfe as bf  # noqa: E402
from bearingfe.adaptivity import adapt  # noqa: E402
from bearingfe.bearings.journal import ResolutionWarning, film_graded_size  # noqa: E402

from benchmarks.common import DOCS, IMG, loglog_plot, machine, md_table, time_at_error  # noqa: E402

TARGETS = (1e-3, 1e-4)
EPS_FD = 1e-9  # benchmarks/work_precision.py case (b): pocket edges a hair outside the FD grid lines
FD_RICHARDSON_B = 508.74994  # docs/benchmarks.md case (b): Richardson of the FD LU (direct) sequence


def _log(msg: str) -> None:
    print(msg, flush=True)


@dataclass(frozen=True)
class Case:
    name: str
    title: str
    surface: bf.Surface
    film: bf.CosineFilm
    inlet_pressure: float
    cavitation: str
    adapt_size: float                      # first (coarsest) mesh of adapt()
    uniform: dict                          # element -> sizes
    graded: dict                           # element -> sizes (film_graded_size; journal only)
    reference_graded: tuple                # P2 sizes of the graded reference sequence
    graded_kwargs: object = None           # size -> extra mesh_surface arguments of the graded family
    adaptive_nodes: dict = field(default_factory=dict)  # element -> max_nodes of the adaptive sweep


@dataclass
class Series:
    label: str
    nodes: list = field(default_factory=list)
    dofs: list = field(default_factory=list)
    seconds: list = field(default_factory=list)
    loads: list = field(default_factory=list)
    estimates: list = field(default_factory=list)
    iterations: list = field(default_factory=list)

    def add(self, nodes, dofs, seconds, load, estimate=math.nan, iterations=0):
        self.nodes.append(int(nodes))
        self.dofs.append(int(dofs))
        self.seconds.append(float(seconds))
        self.loads.append(float(load))
        self.estimates.append(float(estimate))
        self.iterations.append(int(iterations))

    def errors(self, reference: float) -> np.ndarray:
        return np.abs(np.asarray(self.loads) / reference - 1.0)


def case_b(quick: bool) -> Case:
    pocket = bf.Rectangle((0.0, 0.0), (0.48 + 2 * EPS_FD, 0.4 + 2 * EPS_FD))
    return Case(
        name="b", title="(b) rectangular recess, p_s = 1000",
        surface=bf.Surface(arc=(-0.6, 0.6), half_width=0.5, inlets=(pocket,)),
        film=bf.CosineFilm(0.5, math.pi), inlet_pressure=1000.0, cavitation="none", adapt_size=0.1,
        uniform={"P1": (0.1, 0.05, 0.025) if quick else (0.1, 0.05, 0.025, 0.0125, 0.00625),
                 "P2": (0.1, 0.05) if quick else (0.1, 0.05, 0.025, 0.0125, 0.00625)},
        graded={},
        # corner-graded P2 (benchmarks/work_precision.py case (b) "graded"): an independent sequence
        reference_graded=(0.05, 0.025, 0.0125) if quick else (0.025, 0.0125, 0.00625),
        graded_kwargs=lambda s: {"corner_size": s / 8, "inlet_size": s / 2, "grading_distance": 0.15},
        adaptive_nodes={"P1": 20000 if quick else 60000, "P2": 8000 if quick else 70000})


def case_j(quick: bool) -> Case:
    return Case(
        name="j", title="(j) full journal, L/D 1, eps 0.99, Swift-Stieber",
        surface=bf.JournalBearing(1.0).surfaces()[0], film=bf.CosineFilm(0.99, 0.0), inlet_pressure=0.0,
        cavitation="reynolds", adapt_size=0.3,
        uniform={"P1": (0.2, 0.1) if quick else (0.2, 0.1, 0.05, 0.025),
                 "P2": (0.4, 0.2) if quick else (0.4, 0.2, 0.1, 0.05)},
        graded={"P1": (0.2, 0.1) if quick else (0.2, 0.1, 0.05),
                "P2": (0.4, 0.2) if quick else (0.4, 0.2, 0.1)},
        reference_graded=(0.4, 0.2, 0.1) if quick else (0.2, 0.1, 0.05),
        adaptive_nodes={"P1": 8000 if quick else 60000, "P2": 3000 if quick else 30000})


def case_c(quick: bool) -> Case:
    return Case(
        name="c", title="(c) full journal, L/D 0.5, eps 0.9, Swift-Stieber (reference of tests/test_adaptivity.py)",
        surface=bf.Surface(arc=(0.0, 2 * math.pi), half_width=0.5), film=bf.CosineFilm(0.9, 0.0),
        inlet_pressure=0.0, cavitation="reynolds", adapt_size=0.3, uniform={}, graded={},
        reference_graded=(0.2, 0.1, 0.05) if quick else (0.1, 0.05, 0.025),
        adaptive_nodes={"P2": 5000 if quick else 50000})


# -- runs ----------------------------------------------------------------------------------

def _graded_mesh_args(case: Case, size: float) -> dict:
    if case.graded_kwargs is not None:
        return case.graded_kwargs(size)
    floor = size * math.sqrt(1.0 - case.film.gamma)
    return {"size_function": film_graded_size(case.film, size, floor), "min_size": floor}


def fixed_meshes(case: Case, element: str, sizes, graded: bool) -> Series:
    """One mesh per size: meshing + a first solve, timed together."""
    label = f"{element} {'graded' if graded else 'uniform'}"
    out = Series(label)
    for size in sizes:
        start = time.perf_counter()
        extra = _graded_mesh_args(case, size) if graded else {}
        mesh = bf.mesh_surface(case.surface, size, order=2 if element == "P2" else 1, **extra)
        res = bf.solve_reynolds(mesh, case.film, inlet_pressure=case.inlet_pressure, formulation="direct",
                                element=element, cavitation=case.cavitation)
        out.add(mesh.n_nodes, res.basis.N, time.perf_counter() - start, np.linalg.norm(res.force),
                iterations=res.iterations)
        _log(f"  {case.name} {label} {size}: {mesh.n_nodes} nodes {out.seconds[-1]:.2f} s |F| {out.loads[-1]:.10g}")
    return out


def adaptive(case: Case, element: str) -> Series:
    """adapt() run past convergence to max_nodes; every level is a point at its cumulative time."""
    out = Series(f"{element} adaptive")
    total = [0.0]

    def record(level):
        total[0] += level.seconds
        out.add(level.n_nodes, level.n_dofs, total[0], level.load, level.estimate, level.iterations)
        _log(f"  {case.name} {out.label}: {level.n_nodes} nodes {total[0]:.2f} s |F| {level.load:.10g} "
             f"change {level.estimate:.1e}")

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ResolutionWarning)  # stopping at max_nodes is the plan here
        adapt(case.surface, case.film, size=case.adapt_size, tol=1e-12, max_levels=30,
              inlet_pressure=case.inlet_pressure, element=element, cavitation=case.cavitation,
              formulation="direct", max_nodes=case.adaptive_nodes[element], on_level=record)
    return out


def richardson(loads) -> dict:
    """Extrapolation of the last three values of a sequence with its observed ratio of changes
    ``r = d1/d2``: ``L + d2/(r - 1)``; ``correction`` is that last term."""
    a, b, c = loads[-3:]
    d1, d2 = b - a, c - b
    ratio = d1 / d2 if d2 != 0 else math.inf
    correction = d2 / (ratio - 1) if ratio > 1 else math.nan
    return {"value": c + correction if math.isfinite(correction) else math.nan, "ratio": ratio,
            "correction": correction, "last": c}


def reference(case: Case, adaptive_p2: Series) -> dict:
    """Richardson extrapolations of two P2 sequences, the adaptive levels and an independent graded
    family; the reference is the better converged one (smaller correction), its uncertainty the larger
    of that correction and the difference between the two extrapolations."""
    graded = Series("P2 graded (reference)")
    for size in case.reference_graded:
        start = time.perf_counter()
        mesh = bf.mesh_surface(case.surface, size, order=2, **_graded_mesh_args(case, size))
        res = bf.solve_reynolds(mesh, case.film, inlet_pressure=case.inlet_pressure, formulation="direct",
                                element="P2", cavitation=case.cavitation)
        graded.add(mesh.n_nodes, res.basis.N, time.perf_counter() - start, np.linalg.norm(res.force))
        _log(f"  {case.name} reference graded P2 {size}: {mesh.n_nodes} nodes {graded.seconds[-1]:.1f} s "
             f"|F| {graded.loads[-1]:.10g}")
    ra, rg = richardson(adaptive_p2.loads), richardson(graded.loads)
    candidates = [(abs(r["correction"]), name, r) for name, r in (("adaptive", ra), ("graded", rg))
                  if math.isfinite(r["value"])]
    if not candidates:
        raise RuntimeError(f"case {case.name}: neither P2 sequence is in its asymptotic range (ratios "
                           f"{ra['ratio']:.3g}, {rg['ratio']:.3g}); no reference")
    _, best, chosen = min(candidates)
    value = chosen["value"]
    other = rg if best == "adaptive" else ra
    difference = abs(other["value"] - value) / value if math.isfinite(other["value"]) else math.nan
    return {"value": value, "uncertainty": float(np.nanmax([abs(chosen["correction"]) / value, difference])),
            "best": best, "difference": difference,
            "adaptive": ra, "graded": rg, "graded_series": graded, "adaptive_series": adaptive_p2}


def run_case(case: Case) -> dict:
    t = time.perf_counter()
    series = {}
    for element in ("P1", "P2"):
        if element in case.adaptive_nodes:
            series[f"{element} adaptive"] = adaptive(case, element)
        if element in case.uniform:
            series[f"{element} uniform"] = fixed_meshes(case, element, case.uniform[element], graded=False)
        if element in case.graded:
            series[f"{element} graded"] = fixed_meshes(case, element, case.graded[element], graded=True)
    ref = reference(case, series["P2 adaptive"])
    return {"case": case, "series": series, "reference": ref, "seconds": time.perf_counter() - t}


# -- report -------------------------------------------------------------------------------

def reference_text(case: Case, ref: dict) -> str:
    ra, rg = ref["adaptive"], ref["graded"]
    a, g = ref["adaptive_series"], ref["graded_series"]
    text = (f"**Reference** |F| = {ref['value']:.10g}, relative uncertainty {ref['uncertainty']:.1e} (errors "
            f"below it are not resolved). Richardson extrapolation of the last three values of two P2 "
            f"sequences with their observed ratio of changes r (limit = last + last change/(r - 1)): the "
            f"adaptive P2 levels with {', '.join(map(str, a.nodes[-3:]))} nodes (|F| "
            f"{', '.join(f'{v:.10g}' for v in a.loads[-3:])}; r = {ra['ratio']:.3g}) give {ra['value']:.10g}; "
            f"an independent graded P2 family, sizes {', '.join(map(str, case.reference_graded))} "
            f"({', '.join(map(str, g.nodes))} nodes; |F| {', '.join(f'{v:.10g}' for v in g.loads)}; "
            f"r = {rg['ratio']:.3g}) gives {rg['value']:.10g}. The reference is the {ref['best']} one (the "
            f"smaller correction); the other differs by {ref['difference']:.1e}; the uncertainty is the larger "
            f"of that difference and the correction.")
    if case.name == "b":
        text += (f" The FD LU Richardson value of docs/benchmarks.md, {FD_RICHARDSON_B}, differs by "
                 f"{abs(FD_RICHARDSON_B / ref['value'] - 1):.1e}.")
    return text


def _at(series: Series, errors: np.ndarray, target: float, what: str) -> float:
    x = series.nodes if what == "nodes" else series.seconds
    return time_at_error(x, errors, target)


def _beyond(series: Series, errors: np.ndarray, target: float, what: str) -> float:
    """Extrapolation past the sweep on the log-log line through its last two points, only if the
    sweep is in its asymptotic range: three falling errors whose two last log-log slopes agree
    within 25 % (NaN otherwise)."""
    x = np.asarray(series.nodes if what == "nodes" else series.seconds, float)
    e = np.asarray(errors, float)
    if x.size < 3 or not (0 < e[-1] < e[-2] < e[-3]):
        return math.nan
    slopes = np.diff(np.log(e[-3:])) / np.diff(np.log(x[-3:]))
    if not (slopes[1] < 0 and abs(slopes[1] / slopes[0] - 1) < 0.25):
        return math.nan
    return float(x[-1] * (target / e[-1]) ** (1 / slopes[1]))


def _cell(series: Series, errors: np.ndarray, target: float, what: str):
    value = _at(series, errors, target, what)
    if np.isfinite(value):
        return value
    guess = _beyond(series, errors, target, what)
    return f"~{guess:.3g} (extrapolated)" if np.isfinite(guess) else "-"


def case_report(result: dict) -> tuple[str, list[str]]:
    case, series, ref = result["case"], result["series"], result["reference"]
    R = ref["value"]
    lines = [f"## {case.title}", ""]
    film = f"CosineFilm({case.film.gamma}, {case.film.phi0:.4g})"
    lines.append(f"Surface arc {tuple(round(v, 4) for v in case.surface.arc)}, half-width "
                 f"{case.surface.half_width}, pockets {[type(s).__name__ for s in case.surface.inlets] or 'none'}; "
                 f"film {film}, wedge 1, p_s = {case.inlet_pressure:g}, cavitation {case.cavitation!r}, direct "
                 f"form. adapt(): first mesh size {case.adapt_size}, load indicator, growth 2.5, run past "
                 f"convergence until the next mesh would exceed max_nodes {case.adaptive_nodes}. Case run time "
                 f"{result['seconds']:.0f} s.")
    lines += ["", reference_text(case, ref), ""]
    if not case.uniform:
        a = ref["adaptive_series"]
        rows = [[n, d, s, f"{v:.10g}", e, abs(v / R - 1)]
                for n, d, s, v, e in zip(a.nodes, a.dofs, a.seconds, a.loads, a.estimates)]
        lines.append(md_table(["adaptive P2 nodes", "dofs", "cumulative s", "|F|", "load change", "error"], rows))
        lines += ["", estimate_check("P2 adaptive", a, a.errors(R), ref["uncertainty"])]
        return "\n".join(lines) + "\n", []
    errs = {k: s.errors(R) for k, s in series.items()}
    floor = ref["uncertainty"]
    img = []
    for what, xlabel in (("nodes", "mesh nodes"), ("seconds", "wall time [s] (adaptive: cumulative)")):
        # points whose error is below the reference's uncertainty are not resolved: left out
        pts = {k: (s.nodes if what == "nodes" else s.seconds, np.where(errs[k] > floor, errs[k], np.nan))
               for k, s in series.items()}
        name = f"adaptivity_{case.name}_{what}.png"
        img.append(loglog_plot(IMG / name, pts, xlabel=xlabel, ylabel="relative load error", title=case.title))
    lines += [f"![{case.name} nodes]({img[0]}) ![{case.name} seconds]({img[1]})", "",
              f"(Points with an error below the reference's uncertainty {floor:.1e} are not plotted.)", ""]
    rows = []
    for k, s in series.items():
        for n, d, sec, v, est, it, e in zip(s.nodes, s.dofs, s.seconds, s.loads, s.estimates, s.iterations, errs[k]):
            rows.append([k, n, d, sec, f"{v:.10g}", est, it, f"{v / R - 1:+.2e}" + ("" if e > floor else " (n.r.)")])
    lines.append("<details><summary>All points (signed error |F|/reference - 1; n.r.: below the reference's "
                 "uncertainty, not resolved)</summary>\n")
    lines.append(md_table(["method", "nodes", "dofs", "seconds", "|F|", "load change (adaptive)",
                           "active-set iterations", "error"], rows))
    lines += ["", "</details>", ""]
    rows = []
    for k, s in series.items():
        rows.append([k] + [_cell(s, errs[k], t, "nodes") for t in TARGETS]
                    + [_cell(s, errs[k], t, "seconds") for t in TARGETS])
    lines.append("Nodes and seconds to reach a relative load error (log-log interpolation between measured "
                 "points; '~ (extrapolated)': beyond the sweep, on the line through its last two points; "
                 "'-': not reached and the sweep not in its asymptotic range):")
    lines.append("")
    lines.append(md_table(["method"] + [f"nodes at {t:.0e}" for t in TARGETS]
                          + [f"s at {t:.0e}" for t in TARGETS], rows))
    lines.append("")
    verdicts = verdict(case, series, errs)
    verdicts += [estimate_check(k, s, errs[k], floor) for k, s in series.items() if k.endswith("adaptive")]
    signs = [k for k, s in series.items() if len(set(np.sign(np.asarray(s.loads) - R))) > 1]
    if signs:
        verdicts.append(f"The error changes sign along {', '.join(signs)}: near the crossing such a sweep meets a "
                        "target partly by cancellation, which favours it.")
    lines.append("Verdict (computed from the table): " + " ".join(verdicts))
    lines.append("")
    return "\n".join(lines), verdicts


def estimate_check(label: str, series: Series, errors: np.ndarray, floor: float) -> str:
    """How the load change between levels (adapt's error estimate) compares with the true error."""
    est, err = np.asarray(series.estimates[1:]), np.asarray(errors[1:])
    ok = err > floor
    if not ok.any():
        return f"{label}: no level with a resolved error to check the estimate against."
    ratio = est[ok] / err[ok]
    return (f"{label}: the load change from the previous level (adapt's error estimate) exceeded the true "
            f"error at {int(np.sum(ratio > 1))} of {ratio.size} levels (estimate/error "
            f"{ratio.min():.2g} to {ratio.max():.2g}).")


def verdict(case: Case, series: dict, errs: dict) -> list[str]:
    out = []
    for target in TARGETS:
        for element in ("P1", "P2"):
            key = f"{element} adaptive"
            if key not in series:
                continue
            na, sa = _at(series[key], errs[key], target, "nodes"), _at(series[key], errs[key], target, "seconds")
            if not np.isfinite(na):
                out.append(f"{case.name}, {element}, {target:.0e}: adaptive did not reach it in the sweep.")
                continue
            parts = []
            for other in ("uniform", "graded"):
                k = f"{element} {other}"
                if k not in series:
                    continue
                no, so = _at(series[k], errs[k], target, "nodes"), _at(series[k], errs[k], target, "seconds")
                if np.isfinite(no):
                    parts.append(f"{other} needs {no / na:.2g}x the nodes ({no:.0f}) and {so / sa:.2g}x the "
                                 f"time ({so:.3g} s)")
                else:
                    guess = _beyond(series[k], errs[k], target, "nodes")
                    parts.append(f"{other} did not reach it in the sweep (finest error "
                                 f"{errs[k][-1]:.1e} at {series[k].nodes[-1]} nodes"
                                 + (f"; extrapolated ~{guess / na:.2g}x the nodes)" if np.isfinite(guess) else ")"))
            out.append(f"{case.name}, {element}, load error {target:.0e}: adaptive needs {na:.0f} nodes, "
                       f"{sa:.3g} s (all levels); " + "; ".join(parts) + ".")
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes only (smoke test)")
    ap.add_argument("--output", default=str(DOCS / "adaptivity.md"))
    args = ap.parse_args(argv)
    start = time.perf_counter()
    info = machine()
    results = []
    for make in (case_b, case_j, case_c):
        case = make(args.quick)
        _log(f"case {case.name}")
        results.append(run_case(case))
        _log(f"case {case.name}: {results[-1]['seconds']:.1f} s")
    body = [case_report(r)[0] for r in results]
    total = time.perf_counter() - start
    parts = [
        "# Adaptive meshes: load error against nodes and time",
        "",
        f"Generated by `PYTHONPATH=. python benchmarks/adaptivity.py{' --quick' if args.quick else ''}` "
        f"({'QUICK run: small sizes' if args.quick else 'full run'}, {total:.0f} s). Do not edit by hand.",
        "",
        "Machine: " + ", ".join(f"{k} {v}" for k, v in info.items()),
        "",
        "`bearingfe.adapt` meshes the surface with gmsh, solves, computes `load_indicators` (the energy-norm "
        "residual indicators of the pressure times those of the dual pressure of the load), equidistributes "
        "them at 2.5x the elements of the previous level (sizes clipped to [h/4, 2h]), grades the size "
        "field (slope 0.4) and remeshes, until the load changes by less than `tol` between two levels. "
        "Here each run continues past any `tol` to a node budget, so that every level is a point of the "
        "curve. Seconds are wall-clock: uniform/graded = meshing + first `solve_reynolds` on that mesh; "
        "adaptive = all levels up to that point (meshing with the size-field callback, solves, indicators "
        "including one dual solve per level). Errors: relative error of |F|.",
        "",
        *body,
        "## Notes",
        "",
        "- `bearingfe.bearings.journal.journal_mesh` (hence `performance`, `equilibrium`) calls `mesh_surface` without "
        "`min_size`, so gmsh's default floor (a quarter of `size`) overrides `film_graded_size`'s "
        "`min_size = size sqrt(1 - eps)` when eps > 15/16; the graded meshes here pass the floor explicitly "
        "(`mesh_surface(..., min_size=...)`).",
        "",
    ]
    out = Path(args.output)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("\n".join(parts))
    _log(f"wrote {out} in {total:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
