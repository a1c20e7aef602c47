"""Run the benchmarks and write ``docs/benchmarks.md`` (+ PNGs in ``docs/img/``).

Usage (from the repository root)::

    PYTHONPATH=. python benchmarks/run_all.py                     # every part, ~15 min on an idle 2-core machine
    PYTHONPATH=. python benchmarks/run_all.py --only journal,scene # rerun these parts, reuse the others
    PYTHONPATH=. python benchmarks/run_all.py --quick             # small sizes (a check of the scripts)

The page is assembled from parts; each part's text and the numbers the
summary quotes are stored in ``docs/benchmarks_parts/<part>.md`` and
``.json`` when the part runs, so ``--only`` reruns some parts (e.g. on a
loaded machine, or after a change that concerns only them) and the page is
rebuilt from the stored others; each part says when and on what it ran.

The parts, in the page's order, are the rows of :data:`PART_TABLE` (name, runner,
title and what the part measures): a new part is one new row there. The operator cost floor is measured
by ``benchmarks/operator_floor.py`` into ``docs/benchmarks_operator.md`` (linked, not rerun here).
"""

from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import sys
import time
from pathlib import Path
from typing import Callable, NamedTuple

import numpy as np

if __package__ in (None, ""):  # run as a script: make the repository root importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks import (cavitation_cost, elastic_fft, hard_cases, journal_case, journal_pads, journal_ross,  # noqa: E402
                        orderings,
                        pump_revolution, scaling, solver_kinds, targets, thermal_levels, thrust_speed,
                        tilting_pad_speed, work_precision)
from benchmarks.common import DOCS, host_speed, host_speed_text, machine, md_table, optional_versions  # noqa: E402

PARTS_DIR = DOCS / "benchmarks_parts"


def _log(msg) -> None:
    print(msg, flush=True)


# -- the parts: each returns (markdown, facts) ------------------------------------------------

def part_precision(quick: bool) -> tuple[str, dict]:
    results = []
    for make in (work_precision.case_a, work_precision.case_b):
        case = make(quick)
        t = time.perf_counter()
        results.append(work_precision.run_case(case, quick))
        _log(f"case {case.name}: {time.perf_counter() - t:.1f} s")
    b = next(r for r in results if r["case"].name == "b")
    rows, verdicts, facts = [], [], {}
    for target in (1e-3, 1e-4):
        for force_only, what in ((False, "`solve_reynolds`"), (True, "`superpose(...).force`")):
            best, tf, fd, seidel = work_precision.best_fem_vs_fd(b["runs"], target, force_only=force_only)
            _, tfm, _, _ = work_precision.best_fem_vs_fd(b["runs"], target, with_meshing=True,
                                                         force_only=force_only)
            rows.append([f"{target:.0e}", what, best or "-", tf, tfm, fd, fd / tf, fd / tfm, seidel])
            facts[f"fd_speedup_{target:.0e}_{'force' if force_only else 'solve'}"] = float(fd / tf)
            if np.isfinite(fd / tf):
                verdicts.append(f"at {target:.0e} with {what}: {fd / tf:.2g}x")
            else:
                verdicts.append(f"at {target:.0e} with {what}: not measured (target error outside a sweep)")
    lines = ["### FEM against the FD reference at equal load error, case (b)", "",
             "Best FEM method against the FD reference (FD LU, pi form: the paper's scheme with a direct solve) "
             "at equal load error on case (b). FEM timed two ways on a fresh mesh (each timed run on its own copy "
             "of the mesh as meshing returned it, so the operators, the element maps and scikit-fem's facet tables "
             "are built inside the timing; meshing is the separate column): the full `solve_reynolds` "
             "(pressure field, loads, flows, friction) and `superpose(...).force` (loads only, what the pump "
             "transient calls at every step). Each time is the best of 7 runs below 5000 unknowns (3 below "
             "20000, else 1), for FEM and FD alike; times at an error are interpolated (log-log) between the "
             "two measured points of a method that bracket it:", "",
             md_table(["load error", "FEM call", "best FEM", "FEM s", "FEM+meshing s", "FD LU pi s", "speed-up",
                       "speed-up incl. meshing", "FD Seidel pi s"], rows), "",
             "Speed-ups (computed from the table): " + "; ".join(verdicts) + ".", "",
             "### Work-precision diagrams", ""]
    lines += [work_precision.report(r) for r in results]
    lines += ["### Cost split (finest mesh of each FEM method, seconds)", "", work_precision.cost_split(results), ""]
    return "\n".join(lines), facts


def part_journal_c(quick: bool) -> tuple[str, dict]:
    res = journal_case.run(quick, log=_log)
    return "### (c) full journal bearing, eccentricity 0.95, cavitation\n\n" + journal_case.report(res) + "\n", {}


def part_journal(quick: bool) -> tuple[str, dict]:
    return targets.journal_report(targets.journal_run(quick, log=_log))


def part_journal_pads(quick: bool) -> tuple[str, dict]:
    return journal_pads.report(journal_pads.run(quick, log=_log))


def part_journal_ross(quick: bool) -> tuple[str, dict]:
    # ROSS runs in its own environment: ROSS_PYTHON names its interpreter (else the recorded ROSS run is reused)
    return journal_ross.report(journal_ross.run(quick, log=_log))


def part_pump(quick: bool) -> tuple[str, dict]:
    if quick:
        path = DOCS / "benchmarks_pump.json"
        facts = json.loads(path.read_text()) if path.exists() else {}
        how = "reused from the last run of `benchmarks/pump_revolution.py` (`--quick` does not rerun it)"
    else:
        text, facts = pump_revolution.report(pump_revolution.run(log=_log))
        (DOCS / "benchmarks_pump.md").write_text(text)
        (DOCS / "benchmarks_pump.json").write_text(json.dumps(facts, indent=1) + "\n")
        how = "rerun by this part"
    body = (DOCS / "benchmarks_pump.md").read_text().splitlines() if (DOCS / "benchmarks_pump.md").exists() else []
    body = [("##" + l) if l.startswith("#") else l for l in body if not l.startswith("# ")]
    return (f"Included from [benchmarks_pump.md](benchmarks_pump.md) ({how}):\n\n" + "\n".join(body).strip()
            + "\n", facts)


def part_tilting(quick: bool) -> tuple[str, dict]:
    return tilting_pad_speed.report(tilting_pad_speed.run(quick, log=_log))


def part_scene(quick: bool) -> tuple[str, dict]:
    return targets.scene_report(targets.scene_run(log=_log))


def part_scaling(quick: bool) -> tuple[str, dict]:
    from bearingfe.core.linalg import DEFAULT_SOLVER

    sc = scaling.run(quick, log=_log)
    (best, why), (core, core_why) = scaling.recommend(sc), scaling.recommend(sc, among=scaling.CORE)
    choice = (f"Fastest sparse solver in the comparison below: **{best}** ({why}). Fastest of those that "
              f"need only scipy ({', '.join(scaling.CORE)}): **{core}** ({core_why}). The package default "
              f"is `DEFAULT_SOLVER = \"{DEFAULT_SOLVER}\"`"
              + (", which agrees." if DEFAULT_SOLVER == core else
                 f", which does NOT agree with these numbers (scipy-only best: {core})."))
    return choice + "\n\n" + scaling.report(sc) + "\n", {}


def part_cavitation(quick: bool) -> tuple[str, dict]:
    rows = cavitation_cost.run(quick, log=_log)
    if not quick:  # with the larger sizes run separately (e.g. 1e6 in the background) and merged into the file
        rows = json.loads(cavitation_cost.RUNS.read_text())
    return cavitation_cost.report(rows)


def part_elastic_fft(quick: bool) -> tuple[str, dict]:
    return elastic_fft.report(elastic_fft.run(quick, log=_log))


def part_hard(quick: bool) -> tuple[str, dict]:
    return hard_cases.report() + "\n", {}


class Part(NamedTuple):
    """One part of the page: its name (``--only``), the function that runs it, its section title and what it
    measures."""

    name: str
    run: Callable[[bool], tuple[str, dict]]
    title: str
    measures: str


#: The parts in the page's order.
PART_TABLE: tuple[Part, ...] = (
    Part("precision", part_precision, "Speed against error: FEM and the FD reference",
         "work-precision diagrams of (a) a smooth partial arc and (b) a rectangular recess at high inlet pressure "
         "against the FD reference, with the cost split"),
    Part("journal_c", part_journal_c, "Journal bearing with cavitation",
         "(c) a full journal bearing at eccentricity 0.95 with cavitation (benchmarks.journal_case)"),
    Part("journal", part_journal, "Journal equilibrium and dynamic coefficients (eps 0.6)",
         "journal equilibrium + 8 coefficients at eps 0.6, before and after the P2/warm-start path "
         "(benchmarks.targets)"),
    Part("journal_pads", part_journal_pads, "Journal equilibrium and coefficients on pads and grooves (structured path)",
         "the same on pads and grooves, the structured rupture-refined path against gmsh (benchmarks.journal_pads)"),
    Part("journal_ross", part_journal_ross, "Journal equilibrium and coefficients against ROSS",
         "against ROSS on ROSS's plain-journal fixture (benchmarks.journal_ross; ROSS_PYTHON names the interpreter "
         "of an environment with ROSS, else its recorded run is reused)"),
    Part("tilting", part_tilting, "Tilting-pad bearing: equilibrium and reduced coefficients (five pads)",
         "a five-pad tilting-pad bearing's equilibrium and reduced coefficients at 1e-3 beside the plain bearing "
         "and the floor (benchmarks.tilting_pad_speed)"),
    Part("pump", part_pump, "One pump revolution (h_min error against time)",
         "one pump revolution against its error (benchmarks/pump_revolution.py, which also writes "
         "docs/benchmarks_pump.md)"),
    Part("scene", part_scene, "The main scene end to end",
         "the main scene end to end against its yardstick (SuperLU on a 90k-unknown Laplacian)"),
    Part("scaling", part_scaling, "Growth with the number of unknowns; linear solvers",
         "growth with the unknowns and the linear solvers"),
    Part("cavitation", part_cavitation, "Cost of the cavitating solves (Swift-Stieber, Gumbel) up to 1e6 unknowns",
         "the cavitating solves against the non-cavitating one and the floor, 1e3 .. 3e5 unknowns "
         "(benchmarks.cavitation_cost; larger sizes by python -m benchmarks.cavitation_cost run --sizes 1e6, merged)"),
    Part("hard", part_hard, "Hard cases", "hard cases"),
    Part("thermal", thermal_levels.run, "Thermal levels: cost of level 1 and level 2 against the isothermal solve",
         "the cost of a level-1 and a level-2 thermal solve against the isothermal one (benchmarks.thermal_levels)"),
    Part("elastic_fft", part_elastic_fft, "Elastic half-space support from 1e3 to 1e5 unknowns: dense against FFT",
         "the film on the elastic half-space from 1e3 to 1e5 unknowns, dense compliance against its FFT product, "
         "beside the floor, and the pump transient with the deflection's squeeze (simulate_elastic) dense against "
         "matrix-free beside the rigid one (benchmarks.elastic_fft)"),
    Part("thrust", lambda quick: thrust_speed.report(thrust_speed.run(quick, log=_log)),
         "Thrust bearing: tilting-pad equilibrium at 1e-3 in load (six pads)",
         "a six-pad tilting-pad thrust bearing's equilibrium at 1e-3 in load beside its floor "
         "(benchmarks.thrust_speed)"),
    Part("kinds", lambda quick: solver_kinds.report(solver_kinds.run(quick, log=_log)),
         "Every solver kind: time and memory against the unknowns, and where each stops",
         "time and memory against the unknowns for every solver kind, fitted exponents and where each stops "
         "(benchmarks.solver_kinds)"),
    Part("orderings", lambda quick: orderings.report(orderings.run(quick, log=_log)),
         "Fill-reducing orderings: minimum degree against nested dissection, 1e4 to 1e6 unknowns",
         "SuperLU's minimum degree against nested dissection (graph alone, and by the dofs' coordinates) on P1 and "
         "P2 matrices of grid and gmsh meshes: fill, ordering and factorization time, peak memory "
         "(benchmarks.orderings)"),
)
#: Parts also written as a page of their own: part -> (file in docs/, heading).
OWN_PAGES = {"kinds": ("scaling.md", "Scaling: time and memory of every solver kind against the unknowns")}


def own_page(name: str, heading: str, text: str) -> str:
    """The page of its own of a part (:data:`OWN_PAGES`): its heading, where it comes from, its stored text."""
    return (f"# {heading}\n\nGenerated by `PYTHONPATH=. python benchmarks/run_all.py --only {name}` (part `{name}` of "
            f"[the benchmark page](benchmarks.md), which carries the same section). Do not edit by hand.\n\n{text}")


PARTS = tuple(p.name for p in PART_TABLE)
RUNNERS = {p.name: p.run for p in PART_TABLE}
TITLES = {p.name: p.title for p in PART_TABLE}


# -- storage and the page ------------------------------------------------------------------------

class OtherLoad:
    """CPU used by other processes while a part runs, in cores (Linux ``/proc/stat``; NaN elsewhere).

    The machine's busy time over the part minus this process's and its children's CPU time, divided by
    the wall time: 0 on an idle machine, up to the number of cores when other jobs saturate it.
    """

    def __init__(self) -> None:
        self._start = self._sample()

    @staticmethod
    def _sample() -> tuple[float, float, float]:
        import resource

        usage = [resource.getrusage(who) for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN)]
        own = sum(u.ru_utime + u.ru_stime for u in usage)
        try:
            fields = [float(x) for x in Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:]]
            busy = (sum(fields) - fields[3] - (fields[4] if len(fields) > 4 else 0.0)) / os.sysconf("SC_CLK_TCK")
        except (OSError, ValueError, IndexError):
            busy = math.nan
        return time.perf_counter(), busy, own

    def cores(self) -> float:
        (t0, b0, o0), (t1, b1, o1) = self._start, self._sample()
        return max(0.0, ((b1 - b0) - (o1 - o0)) / (t1 - t0)) if t1 > t0 else math.nan


def _store(name: str, text: str, facts: dict, seconds: float, quick: bool, other: float,
           kind: str | None = None, speed: tuple[float, float] | None = None) -> None:
    """Write part ``name``'s section with its stamp; ``kind`` replaces "full run of" (e.g. a part published from
    rows measured separately: its date is then the publication's, ``seconds`` the rows' measuring time);
    ``speed``: :func:`~benchmarks.common.host_speed` before and after the part's runs [s]."""
    PARTS_DIR.mkdir(parents=True, exist_ok=True)
    info = machine()
    kind = kind or ('QUICK run (small sizes) of' if quick else 'full run of')
    stamp = (f"*Part `{name}`: {kind} "
             f"{info['date']} on {info['cpu']} ({info['cores']} cores), {seconds:.0f} s; other processes "
             f"used {other:.2f} cores meanwhile ("
             f"{'idle machine' if other < 0.25 else 'SHARED machine: absolute times are inflated'})"
             f"{'' if speed is None else '; ' + host_speed_text(*speed)}.*\n\n")
    (PARTS_DIR / f"{name}.md").write_text(stamp + text)
    if speed is not None:
        facts = dict(facts, host_speed_before=speed[0], host_speed_after=speed[1])
    (PARTS_DIR / f"{name}.json").write_text(json.dumps(dict(facts, seconds=seconds, quick=quick), indent=1,
                                                       default=str) + "\n")


def _load(name: str) -> tuple[str, dict]:
    md, js = PARTS_DIR / f"{name}.md", PARTS_DIR / f"{name}.json"
    if not md.exists():
        return f"**Not available**: part `{name}` has not been run (`run_all.py --only {name}`).\n", {}
    return md.read_text(), json.loads(js.read_text()) if js.exists() else {}


def _fmt(x, unit: str = " s") -> str:
    return "not measured" if x is None or not math.isfinite(x) else f"{x:.3g}{unit}"


def targets_summary(facts: dict) -> str:
    """The fast-path targets, each with its measured number and a verdict computed from it."""
    rows = []

    def add(what, goal, measured, ok, note=""):
        verdict = ok if isinstance(ok, str) else "not measured" if ok is None else ("met" if ok else "NOT met")
        rows.append([what, goal, measured, verdict, note])

    j = facts.get("journal", {})
    for target in ("1e-02", "1e-03"):
        v = j.get(f"journal_{target}", {})
        b, a = v.get("before", math.nan), v.get("after", math.nan)
        b = math.nan if b is None else b
        a = math.nan if a is None else a
        sp = b / a if math.isfinite(a) and math.isfinite(b) and a > 0 else math.nan
        more = "more than " if v.get("before_bound") else ""
        add(f"journal equilibrium + 8 coefficients, error {target}", "5x faster at 1e-03" if target == "1e-03" else
            "(reported)", f"{_fmt(a)} (before {more}{_fmt(b)}): {more}{_fmt(sp, 'x')}",
            ("no goal" if target != "1e-03" else (sp >= 5) if math.isfinite(sp) else None),
            f"after: {v.get('after_label') or (str(v.get('after_element', 'P2')) + ' size ' + str(v.get('after_size')))}"
            f", before: P1 size {v.get('before_size')}")
    r = facts.get("journal_ross", {})
    for key, what in (("ross_accuracy", "ROSS's default-grid accuracy"), ("1e-03", "error 1e-03")):
        v = r.get(key) or {}
        sp, t, tr = v.get("speedup", math.nan), v.get("seconds", math.nan), r.get("ross_seconds", math.nan)
        add(f"journal equilibrium + 8 coefficients against ROSS on its fixture, {what}", ">= 5x",
            f"{_fmt(t)} against ROSS {_fmt(tr)}: {_fmt(sp, 'x')}" if math.isfinite(sp) else "not measured",
            (sp >= 5) if math.isfinite(sp) else None, str(v.get("label", "")))
    sc = facts.get("scene", {})
    r = sc.get("scene_yardsticks", math.nan)
    add("main scene end to end (2 designs, periodic, pictures)", f"<= {targets.SCENE_GOAL:g} yardsticks",
        f"{_fmt(r, '')} yardsticks ({_fmt(sc.get('scene_best', math.nan))}, yardstick "
        f"{_fmt(sc.get('yardstick', math.nan))})", (r <= targets.SCENE_GOAL) if math.isfinite(r) else None,
        "fresh process, imports included; yardstick: SuperLU factorization of a 90k-unknown Laplacian")
    p = facts.get("pump", {})
    pb = p.get("pump_best_seconds", math.nan)
    add("one pump revolution within 0.1 % of the converged smallest film", "<= 0.1 s", _fmt(pb),
        (pb <= 0.1) if math.isfinite(pb) else None, str(p.get("pump_best", "")))
    pd = p.get("pump_defaults_seconds", math.nan)
    pe = p.get("pump_defaults_error", math.nan)
    add("`simulate()` defaults: one revolution", "within 0.1 %", f"{_fmt(pd)}, error {_fmt(pe, '')}",
        (pe < 1e-3) if math.isfinite(pe) else None)
    f = facts.get("precision", {}).get("fd_speedup_1e-03_solve", math.nan)
    ff = facts.get("precision", {}).get("fd_speedup_1e-03_force", math.nan)
    # three decimals: near the goal a rounded "3x" would hide a 2.995x that is not met
    add("FEM vs FD at load error 1e-3, case (b)", ">= 3x", f"{f:.3f}x (`solve_reynolds`), "
        f"{ff:.3f}x (`superpose(...).force`)" if math.isfinite(f) and math.isfinite(ff) else "not measured",
        (max(f, ff) >= 3) if math.isfinite(f) and math.isfinite(ff) else None)
    return md_table(["target", "goal", "measured", "verdict", "note"], rows)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes only (a check of the scripts)")
    ap.add_argument("--only", default=None, help="comma-separated parts to rerun (of: " + "; ".join(
                    f"{p.name}: {p.measures}" for p in PART_TABLE) + "); "
                    "the others are reused from docs/benchmarks_parts/")
    ap.add_argument("--output", default=str(DOCS / "benchmarks.md"))
    args = ap.parse_args(argv)
    todo = PARTS if args.only is None else tuple(p.strip() for p in args.only.split(",") if p.strip())
    unknown = [p for p in todo if p not in PARTS]
    if unknown:
        ap.error(f"unknown part {unknown[0]!r}; parts: {', '.join(PARTS)}")
    start = time.perf_counter()
    for name in todo:
        before = host_speed()
        t, other = time.perf_counter(), OtherLoad()
        text, facts = RUNNERS[name](args.quick)
        seconds, cores = time.perf_counter() - t, other.cores()
        _store(name, text, facts, seconds, args.quick, cores, speed=(before, host_speed()))
        _log(f"part {name}: {time.perf_counter() - t:.1f} s")
    parts = {name: _load(name) for name in PARTS}
    for name, (page_name, heading) in OWN_PAGES.items():
        (DOCS / page_name).write_text(own_page(name, heading, parts[name][0]))
    info = machine()
    page = [
        "# bearingfe benchmarks: speed against error",
        "",
        f"Generated by `PYTHONPATH=. python benchmarks/run_all.py` from its stored parts (this assembly "
        f"{datetime.datetime.now().strftime('%Y-%m-%d %H:%M')}; rerun: {', '.join(todo) or 'none'}). Do not edit by hand; "
        "each part states when it ran.",
        "",
        "Machine: " + ", ".join(f"{k} {v}" for k, v in info.items()),
        "",
        "Optional solver packages: " + ", ".join(f"{k} {v}" for k, v in optional_versions().items()),
        "",
        "Times are wall-clock seconds of one process (numpy/BLAS may use both cores). Each part states how many "
        "cores other processes used while it ran: on a shared machine absolute times are inflated, up to several times; ratios measured within one part (before/after, FEM/FD) are "
        "less affected.",
        "",
        "The cost floor of one film state (the compiled operator against its sparse LU and solves) is measured "
        "separately: [benchmarks_operator.md](benchmarks_operator.md) (`benchmarks/operator_floor.py`).",
        "",
        "## Targets of the fast inner loop",
        "",
        targets_summary({name: facts for name, (_, facts) in parts.items()}),
        "",
    ]
    for name in PARTS:
        page += [f"## {TITLES[name]}", "", parts[name][0]]
    page += [f"Time of this command: {time.perf_counter() - start:.0f} s.", ""]
    Path(args.output).write_text("\n".join(page))
    _log(f"wrote {args.output} in {time.perf_counter() - start:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
