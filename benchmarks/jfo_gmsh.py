"""JFO cavitation on gmsh meshes against the phi-aligned grid: convergence in load and flows; writes docs/jfo_gmsh.md.

Usage (from the repository root)::

    PYTHONPATH=. nice python benchmarks/jfo_gmsh.py            # full run, ~3 min idle, ~5 on a loaded machine
    PYTHONPATH=. python benchmarks/jfo_gmsh.py --quick         # coarse meshes only (a check of the script)

Three cases, each solved with ``cavitation="jfo"`` (:data:`KINDS`) on

- gmsh meshes of uniform size (:func:`bearingfe.mesh_surface` with ``recess_size=size``, pocket and recess
  contours on element edges, the Couette
  flux through the median-dual segments, first order: ``couette="median"``, the default before),
- the same gmsh meshes with theta at the streamline foot (``couette="streamline"``, the default), and gmsh meshes refined
  at the pocket and recess contours with it (``graded``; for the dimple, which has no pocket, the default mesh of
  ``mesh_surface``, whose recess contours are refined), and
- phi-aligned tensor grids (:func:`bearingfe.geometry.meshing.grid_mesh`, grid lines through the pocket
  edges, recess contours cut through the cells: ``couette="grid"``).

The reference of each quantity is the Richardson extrapolation of the three finest grids (their fitted
order is printed). The cases (:data:`CASES`) are also the tests' (``tests/film/test_finite_volume_pockets.py``):

- ``pocket_pad``: a square pad (1 x 1, edges at 0) with a square pocket (0.2 x 0.2, at 0) in the diverging
  half of a converging-diverging film (2 -> 1 -> 2 along phi), cavity at -0.02: the pocket feeds a streak
  of full film into the cavity (the two-dimensional pocket case of Hansen's FBNS code, our parameters);
- ``dimple``: a parallel slider (film 1, 1 x 1, i.e. 10 x 10 mm at R0 = 10 mm) with one circular dimple
  (radius 0.25, depth 1), cavity at -0.05;
- ``grooved_journal``: a 360-degree journal, L/D 1, eps 0.6 (``CosineFilm(0.6, 0)``), one 20-degree axial
  groove over 80 % of the length at pi/2 fed at 0.2, periodic seam.
"""

from __future__ import annotations

import argparse
import math
import os
import pickle
import statistics
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.common import DOCS, host_speed, host_speed_text, machine, md_table  # noqa: E402

import bearingfe as bf  # noqa: E402
from bearingfe.bearings.journal import Groove, JournalBearing  # noqa: E402
from bearingfe.core.linalg import dense_threads, factorize_splu  # noqa: E402
from bearingfe.film.finite_volume import solve_jfo  # noqa: E402
from bearingfe.geometry.meshing import grid_mesh  # noqa: E402

#: Mesh kinds compared: (mesher, Couette flux of :func:`bearingfe.film.finite_volume.solve_jfo`, title).
#: ``graded``: :func:`bearingfe.mesh_surface` refined at pocket and recess contours (``inlet_size = size / 8``,
#: ``grading_distance = 2 size``, :data:`GRADED`).
KINDS = {
    "grid": ("grid", "grid", "`grid_mesh` + `couette=\"grid\"` (phi-aligned box faces)"),
    "streamline": ("gmsh", "streamline",
                   "`mesh_surface` + `couette=\"streamline\"` (median dual, theta at the streamline foot; the default on gmsh meshes)"),
    "graded": ("graded", "streamline",
               "`mesh_surface` refined at the contours + `couette=\"streamline\"`"),
    "gmsh": ("gmsh", "median",
             "`mesh_surface` + `couette=\"median\"` (median dual, first-order upwind; the default before the streamline flux)"),
}
#: Contour refinement of the ``graded`` kind: inlet (and recess contour) size and grading distance per size.
GRADED = dict(inlet=1 / 8, grading=2.0)


@dataclass(frozen=True)
class Case:
    """One JFO surface: its film, its solve options, the quantities compared and the mesh sizes."""

    name: str
    title: str
    surface: bf.Surface
    film: object
    options: dict
    quantities: tuple[str, ...]        # keys of :func:`quantities`
    gmsh_sizes: tuple[float, ...]
    grid_sizes: tuple[float, ...]      # the last three give the reference
    scales: dict = field(default_factory=dict)   # quantity -> the quantity whose reference scales its error


def pocket_pad() -> Case:
    surface = bf.Surface(arc=(0.0, 1.0), half_width=0.5, inlets=[bf.Rectangle((0.7, 0.0), (0.2, 0.2))])
    film = bf.ProfileFilm(((0.0, 2.0), (0.5, 1.0), (1.0, 2.0)))
    return Case("pocket_pad", "Square pad with a square pocket in the cavity", surface, film,
                dict(cavitation="jfo", cavitation_pressure=-0.02, inlet_pressure=0.0),
                ("load", "inlet", "side", "arc_end"), (0.05, 0.025, 0.0125, 0.00625),
                (0.05, 0.025, 0.0125, 0.00625, 0.003125))


def dimple() -> Case:
    surface = bf.Surface(arc=(0.0, 1.0), half_width=0.5, recesses=[bf.Recess(bf.Circle((0.5, 0.0), 0.25), 1.0)])
    return Case("dimple", "Parallel slider with one circular dimple", surface, bf.UniformFilm(1.0),
                dict(cavitation="jfo", cavitation_pressure=-0.05), ("load", "friction", "arc_end", "side"),
                (0.04, 0.02, 0.01, 0.005), (0.04, 0.02, 0.01, 0.005, 0.0025), scales={"side": "arc_end"})


def grooved_journal() -> Case:
    bearing = JournalBearing(1.0, periodic=True, grooves=(Groove(math.pi / 2, math.radians(20.0), 0.8),))
    (surface,) = bearing.surfaces()
    return Case("grooved_journal", "Grooved 360-degree journal, L/D 1, eps 0.6", surface, bf.CosineFilm(0.6, 0.0),
                dict(cavitation="jfo", inlet_pressure=0.2), ("load", "side"), (0.1, 0.05, 0.025),
                (0.1, 0.05, 0.025, 0.0125, 0.00625))


CASES = {"pocket_pad": pocket_pad, "dimple": dimple, "grooved_journal": grooved_journal}


def quantities(res) -> dict[str, float]:
    """Load (``integral`` of p, pockets included; the force magnitude on a journal), friction and the
    boundary flows of a result."""
    out = {"load": float(res.integral), "friction": float(res.friction)}
    if res.flows.get("arc_start") is None:   # periodic journal: the load is the force
        out["load"] = float(np.hypot(*res.force))
    out.update({k: float(v) for k, v in res.flows.items()})
    return out


def make_mesh(case: Case, kind: str, size: float):
    """The mesh of ``case`` that :data:`KINDS` names for ``kind``, of nominal size ``size``."""
    mesher = KINDS[kind][0]
    if mesher == "gmsh":
        return bf.mesh_surface(case.surface, size, recess_size=size)   # uniform size, also at recess contours
    if mesher == "graded":
        return bf.mesh_surface(case.surface, size, inlet_size=GRADED["inlet"] * size,
                               grading_distance=GRADED["grading"] * size)
    return grid_mesh(case.surface, size)


#: Each timed quantity of a row (the JFO solve, the floor, the linear solve) is run again until its runs took
#: this many CPU seconds together (read at call time): the small rows, whose milliseconds swing with the load
#: and with first-call effects, repeat many times, a row whose one run takes longer runs only its minimum ...
ROW_CPU_SECONDS = 0.2
#: ... and at most this many times.
MAX_REPEATS = 50


@dataclass(frozen=True)
class Timing:
    """Repeated runs of one timed quantity.

    Attributes
    ----------
    best, median : float
        CPU seconds (``time.process_time``) of the fastest and the median run.
    wall : float
        Wall-clock seconds (``time.perf_counter``) of the fastest run by that clock.
    repeats : int
        Runs timed.
    """

    best: float
    median: float
    wall: float
    repeats: int


def cpu_timing(run: Callable[[object], object], prepare: Callable[[], object] | None = None,
               min_repeats: int = 1) -> tuple[Timing, object]:
    """Time ``run(prepare())`` (``prepare`` untimed, e.g. a fresh mesh), at least ``min_repeats`` times and
    again while the runs took less than :data:`ROW_CPU_SECONDS` of CPU together, at most :data:`MAX_REPEATS`
    times. Returns the :class:`Timing` and the last run's result."""
    if not (isinstance(min_repeats, int) and min_repeats >= 1):
        raise ValueError(f"min_repeats must be an integer >= 1, got {min_repeats!r}")
    cpu, wall = [], []
    while True:
        out = arg = None   # the last run's result and input freed here, outside the timing
        arg = prepare() if prepare is not None else None
        t0, c0 = time.perf_counter(), time.process_time()
        out = run(arg)
        c1, t1 = time.process_time(), time.perf_counter()
        cpu.append(c1 - c0)
        wall.append(t1 - t0)
        if len(cpu) >= min_repeats and (sum(cpu) >= ROW_CPU_SECONDS or len(cpu) >= MAX_REPEATS):
            return Timing(min(cpu), statistics.median(cpu), min(wall), len(cpu)), out


def fresh_copies(mesh) -> Callable[[], object]:
    """A maker of copies of ``mesh`` as it is now, without its per-mesh caches (pickled: ``SupportMesh`` drops
    them): each copy takes a cold solve, as a fresh mesh, without meshing again. Take it from a mesh no solve
    has touched (its scikit-fem mesh's own lazily built arrays travel with it)."""
    blob = pickle.dumps(mesh)
    return lambda: pickle.loads(blob)


def solve(case: Case, kind: str, size: float):
    """Mesh and solve as :data:`KINDS` says; returns (nodes, mesh seconds, solve :class:`Timing`, quantities,
    result). The mesh is timed once (wall clock); the solve (:func:`cpu_timing`) on fresh copies of it
    (:func:`fresh_copies`), each a cold solve."""
    couette = KINDS[kind][1]
    t0 = time.perf_counter()
    mesh = make_mesh(case, kind, size)
    t1 = time.perf_counter()
    options = {k: v for k, v in case.options.items() if k != "cavitation"}   # cavitation="jfo"
    copies = fresh_copies(mesh)
    timing, res = cpu_timing(lambda m: solve_jfo(m, case.film, couette=couette, **options), copies)
    solve.mesh, solve.copies = mesh, copies   # the mesh as made, for the floor; its copies, for the linear solve
    return mesh.n_nodes, t1 - t0, timing, quantities(res), res


def floor_timing(mesh, film, min_repeats: int = 2) -> Timing:
    """The linear floor: sparse LU factorizations (SuperLU, COLAMD) plus one solve of the full-film matrix of
    the same unknowns, one factorization's worth, the assembly and the set-up of the mesh left out
    (:func:`linear_timing` times the whole linear solve); CPU time, with one BLAS thread as :func:`solve_jfo`
    runs, repeated as :func:`cpu_timing` says."""
    from bearingfe.film import finite_volume as fv

    ops = fv.operators(mesh, "P1")
    unk = fv._unknowns(mesh, ops)
    system = fv._assemble(ops, mesh, film, 1.0, (0.0, 0.0), None, None, "median")
    K, _, b = fv._reduced(system, unk, np.zeros(ops.n_dofs), 0.0)
    K = K.tocsc()
    with dense_threads(1):
        return cpu_timing(lambda _: factorize_splu(K)(b), min_repeats=min_repeats)[0]


def linear_timing(make: Callable[[], object], film, options: dict) -> Timing:
    """The linear solve of the same problem on a fresh mesh from ``make()`` (untimed): the same
    :func:`solve_jfo` call with ``cavitation="none"`` (assembly with the recess geometry, one factorization,
    postprocessing), cold runs repeated as :func:`cpu_timing` says. Beside :func:`floor_timing` it shows how much
    of a cold solve on a fresh mesh is set-up that the bare factorization of an assembled matrix leaves out."""
    options = {k: v for k, v in options.items() if k != "cavitation"}
    return cpu_timing(lambda mesh: solve_jfo(mesh, film, cavitation="none", **options), make)[0]


#: Mesh kinds whose rows also time the linear solve on a fresh mesh (:func:`linear_timing`).
LINEAR_KINDS = ("grid", "streamline")


def richardson(values) -> tuple[float, float]:
    """Reference and fitted order from the last three values on meshes halved each time: the Richardson
    extrapolation where the fitted order lies in [0.5, 3], else (irregular convergence) the finest value."""
    f1, f2, f3 = values[-3:]
    ratio = (f1 - f2) / (f2 - f3) if f2 != f3 else math.inf
    p = math.log2(ratio) if ratio > 1 else math.nan
    if not 0.5 <= p <= 3.0:
        return f3, p
    return f3 + (f3 - f2) / (2**p - 1), p


def fitted_order(nodes, errors) -> float:
    """Order of the error in the mesh size (``h ~ nodes^-1/2``), least squares in log-log."""
    e = np.asarray(errors, float)
    ok = e > 0
    if ok.sum() < 2:
        return math.nan
    return float(-2 * np.polyfit(np.log(np.asarray(nodes, float)[ok]), np.log(e[ok]), 1)[0])


def run_case(case: Case, quick: bool) -> dict:
    gmsh_sizes = case.gmsh_sizes[:2] if quick else case.gmsh_sizes
    grid_sizes = case.grid_sizes[:3] if quick else case.grid_sizes
    rows = {kind: [] for kind in KINDS}
    for kind, sizes in (("grid", grid_sizes), ("streamline", gmsh_sizes), ("graded", gmsh_sizes[:3]),
                        ("gmsh", gmsh_sizes)):
        for s in sizes:
            n, tm, ts, q, res = solve(case, kind, s)
            floor = floor_timing(solve.mesh, case.film)
            linear = (linear_timing(solve.copies, case.film, dict(case.options, couette=KINDS[kind][1]))
                      if kind in LINEAR_KINDS else None)
            rows[kind].append(dict(size=s, nodes=n, mesh_s=tm, solve_s=ts.best, q=q, noted=len(res.notes) > 1,
                                   floor=ts.best / floor.best, floor_median=ts.median / floor.median,
                                   repeats=(ts.repeats, floor.repeats),
                                   linear=linear.best / floor.best if linear else math.nan,
                                   iterations=res.iterations))
            print(f"{case.name} {kind} {s}: {n} nodes, {tm + ts.best:.2f} s, solve / floor {ts.best / floor.best:.2f} "
                  f"(runs {ts.repeats}, {floor.repeats}), "
                  + ", ".join(f"{k} {q[k]:.8g}" for k in case.quantities), flush=True)
    ref = {k: richardson([r["q"][k] for r in rows["grid"]]) for k in case.quantities}
    for kind in rows:
        for r in rows[kind]:
            r["err"] = {k: abs(r["q"][k] - ref[k][0]) / abs(ref[case.scales.get(k, k)][0]) for k in case.quantities}
    return dict(case=case, rows=rows, ref=ref)


def first_within(rows, tol: float = 0.01):
    """The coarsest row from which on every error of every finer row is within ``tol``, or None."""
    ok = [max(r["err"].values()) <= tol for r in rows]
    return next((r for k, r in enumerate(rows) if all(ok[k:])), None)


def _table(case: Case, rows) -> str:
    head = (["size", "nodes", "mesh [s]", "solve [s]"] + [f"{k}" for k in case.quantities]
            + [f"{k} error" for k in case.quantities]
            + ["note", "active-set iterations", "solve / floor", "median solve / median floor", "runs (solve, floor)",
               "linear / floor"])
    body = [[r["size"], r["nodes"], f"{r['mesh_s']:.2f}", f"{r['solve_s']:.2f}"]
            + [f"{r['q'][k]:.7g}" for k in case.quantities] + [f"{r['err'][k]:.2e}" for k in case.quantities]
            + ["yes" if r["noted"] else "-", r["iterations"], f"{r['floor']:.1f}",
               f"{r['floor_median']:.1f}", "{}, {}".format(*r["repeats"]),
               f"{r['linear']:.1f}" if math.isfinite(r.get("linear", math.nan)) else "-"] for r in rows]
    return md_table(head, body)


def section(result: dict) -> list[str]:
    case, rows, ref = result["case"], result["rows"], result["ref"]
    lines = [f"## {case.title} (`{case.name}`)", "",
             "Reference (Richardson extrapolation of the three finest grids where their fitted order lies in "
             "[0.5, 3], else the finest grid): "
             + ", ".join(f"{k} {v:.8g} (order {p:.2f})" for k, (v, p) in ref.items()) + "."
             + "".join(f" The {k} error is relative to the {v} reference." for k, v in case.scales.items()), ""]
    for kind, (_, _, what) in KINDS.items():
        rs = rows[kind]
        orders = ", ".join(f"{k} {fitted_order([r['nodes'] for r in rs], [r['err'][k] for r in rs]):.2f}"
                           for k in case.quantities)
        hit = first_within(rs)
        verdict = (f"every quantity within 1 % from {hit['nodes']} nodes on ({hit['mesh_s'] + hit['solve_s']:.2f} s, "
                   f"meshing included)" if hit else "not within 1 % on these meshes")
        lines += [f"### {what}", "", _table(case, rs), "",
                  f"Fitted orders of the errors in the mesh size: {orders}; {verdict}.", ""]
    return lines


#: The goals: every case within 1 % of its converged load and flows at no more than this many nodes ...
GOAL_NODES = 20_000
#: ... and the grooved journal within 1 % in less than this many seconds (meshing included).
GOAL_JOURNAL_SECONDS = 2.0


def goals(results) -> list[str]:
    """The goals table: for each case and mesh kind, the coarsest mesh within 1 % and the verdict."""
    rows = []
    for res in results:
        case = res["case"]
        for kind in KINDS:
            hit = first_within(res["rows"][kind])
            seconds = hit["mesh_s"] + hit["solve_s"] if hit else math.nan
            journal = case.name == "grooved_journal"
            goal = f"<= {GOAL_NODES} nodes" + (f", < {GOAL_JOURNAL_SECONDS:g} s" if journal else "")
            met = hit is not None and hit["nodes"] <= GOAL_NODES and (
                case.name != "grooved_journal" or seconds < GOAL_JOURNAL_SECONDS)
            rows.append([case.name, kind, goal, hit["nodes"] if hit else "-", f"{seconds:.2f}" if hit else "-",
                         "met" if met else "NOT met"])
    return ["## Goals: within 1 % of the converged load and flows", "",
            md_table(["case", "mesh", "goal", "coarsest mesh within 1 % [nodes]", "its time [s]", "verdict"], rows),
            "", "`grid`: `grid_mesh` with the phi-aligned grid flux; `streamline`: `mesh_surface` of uniform size "
            "(`recess_size=size`) with `couette=\"streamline\"` (the default flux); `graded`: the same on meshes refined "
            f"at the pocket and recess contours (`inlet_size={GRADED['inlet']:g} * size`, "
            f"`grading_distance={GRADED['grading']:g} * size`): on a surface with recesses and no pockets (the dimple) "
            "this is `mesh_surface`'s default mesh, which refines recess contours (`recess_size = size / 8` over "
            "`2 * size`); `gmsh`: "
            "`mesh_surface` with the first-order median-dual flux (`couette=\"median\"`). A case not within 1 % on the meshes "
            "measured below is NOT met.", ""]


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--out", default=str(DOCS / "jfo_gmsh.md"))
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    load0 = os.getloadavg()[0]
    speed = [host_speed()]
    results = [run_case(make(), args.quick) for make in CASES.values()]
    speed.append(host_speed())
    m = machine()
    lines = ["# JFO cavitation on gmsh meshes and on phi-aligned grids: convergence in load and flows", "",
             f"Generated by `benchmarks/jfo_gmsh.py`{' --quick' if args.quick else ''} ({m['cpu']}, {m['cores']} "
             f"cores, Python {m['python']}, {m['date']}; total {time.perf_counter() - t0:.0f} s). Model and "
             "discretizations: [jfo.md](jfo.md). Errors are relative to the reference of each case. `mesh [s]`: "
             "wall-clock, one run. `solve [s]`: the CPU time (`time.process_time`) of the fastest of several cold "
             "solves (the `solve_jfo` call alone, on a fresh copy of the mesh as made, without the per-mesh caches "
             "of a previous solve; copying is untimed), repeated until the runs took "
             f"{ROW_CPU_SECONDS:g} s of CPU together (at most {MAX_REPEATS} runs; `runs`). `floor`: the linear "
             "floor of the same mesh, one sparse LU factorization (SuperLU, COLAMD) plus one solve of the "
             "full-film matrix of the same unknowns (assembled before, untimed), timed the same way (at least two "
             "runs). Both run in one process on one core with one BLAS thread, as `solve_jfo` runs. `solve / floor` "
             "divides the fastest solve by the fastest floor, `median solve / median floor` the medians (the "
             "spread of the timing). `linear / floor` divides the fastest linear solve of the same problem on "
             "fresh copies of the same mesh (the same call with `cavitation=\"none\"`: recess geometry, assembly, "
             "one factorization, postprocessing; timed the same way) by the fastest floor: what the set-up of a "
             "fresh mesh adds to one factorization before any cavitation. The `note` column says whether the "
             "result carries a note on JFO on an unstructured "
             f"mesh. Load average at the start: {load0:.1f} on {m['cores']} cores; {host_speed_text(*speed)}.", ""]
    lines += goals(results)
    for r in results:
        lines += section(r)
    Path(args.out).write_text("\n".join(lines) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
