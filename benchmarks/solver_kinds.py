"""Growth of time and memory with the unknowns for every solver kind, fitted exponents, where each stops.

Each measurement runs in its own Python process (its peak memory, ``VmHWM``, is its own): a film on
``grid_mesh`` of the plain arc of the precision case ``(-1, 1) x (-0.5, 0.5)`` (no meshing cost to speak of,
so the solver is what grows), the journal-like film ``h = 1 + 0.6 cos(phi - pi - 0.3)`` (it ruptures over
about half the arc), from a cold start and empty caches, one solve:

======================  =============================================================================
kind                    what is timed
======================  =============================================================================
``linear P1/P2``        ``solve_reynolds`` without cavitation (direct form)
``swift-stieber P1``    ``cavitation="reynolds"`` (the nested cold start and the CG-preconditioned steps)
``gumbel P1``           ``cavitation="gumbel"``
``jfo P1``              ``cavitation="jfo"`` (grid flux on the phi-aligned grid)
``thrust pad P1``       a tilting thrust pad's equilibrium (``tilting_equilibrium``, point pivot) on a
                        gmsh sector mesh of the same unknowns
``elastic P1``          the same film on two steel half-spaces (``half_space_fft``: the compliance as its
                        FFT product, built inside the timing) by ``solve_elastic`` (matrix-free
                        Newton-Krylov, Swift-Stieber), at the shipped pump's scale: largest opening
                        about 0.27 c
======================  =============================================================================

The linear P1 solve also runs at 1e6 unknowns, against a budget of 4 GiB for the whole process. Where the
memory of a linear solve goes: the same solve at 1e5 and 3e5 unknowns (P1 and P2; P1 also at 1e6) with a mark after each
stage (mesh, the operators and basis, the compiled maps, the film at the quadrature points, the matrix
values, the right sides, the factorization, the solves, the result), the process's resident memory after it
and its peak during it (``VmHWM`` reset between the marks).

The exponent ``b`` of ``time ~ n^b`` and ``memory ~ n^b`` is fitted over the sizes at and above 1e4 unknowns
(below, fixed costs dominate). Where a kind stops on this machine kind: the first size that failed or
timed out, and the size at which the fitted growth would reach the machine's memory or a minute.

Run: ``PYTHONPATH=. python benchmarks/run_all.py --only kinds`` (a few minutes; ``--quick`` up to 1e4).
Internal: ``python -m benchmarks.solver_kinds one KIND DOFS`` and ``... stages ELEMENT DOFS``.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from .common import IMG, ROOT, loglog_plot, md_table, proc_status_mib

KINDS = ("linear P1", "linear P2", "swift-stieber P1", "gumbel P1", "jfo P1", "thrust pad P1", "elastic P1")
SIZES = (1e3, 1e4, 1e5, 3e5, 1e6)
#: Largest size per kind where it is smaller than the last of SIZES: the tilting pad's cold Newton (about
#: 30 film solves with finite-difference Jacobians) takes minutes beyond 1e5 unknowns (part ``thrust`` has its
#: cost at the accuracy a design needs); the elastic film's Newton (6 steps, each a new film and its
#: Swift-Stieber active set) takes about 15 s of CPU at 1e5 (part ``elastic_fft`` has the coupled solve without
#: cavitation to 1e5); 1e6 unknowns is the linear P1 solve's memory goal (``BUDGET_MIB``).
LARGEST = {"thrust pad P1": 1e5, "linear P2": 3e5, "swift-stieber P1": 3e5, "gumbel P1": 3e5, "jfo P1": 3e5,
           "elastic P1": 1e5}
#: The memory a linear P1 solve of 1e6 unknowns should fit in (the whole process) [MiB].
BUDGET_MIB = 4096.0
#: Sizes of the memory breakdown of a linear solve (``stages``), per element (P1 also at the goal's size).
STAGE_SIZES = {"P1": (1e5, 3e5, 1e6), "P2": (1e5, 3e5)}
QUICK_SIZES = (1e3, 1e4)
TIMEOUT = 300.0
#: A minute: the time the "where it stops" column projects to.
MINUTE = 60.0


def one(kind: str, dofs: float) -> dict:
    """One measurement in this process: seconds of the solve (meshing apart), peak memory [MiB], unknowns."""
    import bearingfe as bf

    element = "P2" if kind.endswith("P2") else "P1"
    per = 4.0 if element == "P2" else 1.0
    if kind == "thrust pad P1":
        import math as m

        pad = bf.ThrustPad(0.05, 0.1, m.radians(45), n_pads=6, pivot_offset=0.6)
        area = 0.5 * pad.extent * (1 - 0.25)
        size = m.sqrt(2 * area / (m.sqrt(3) * dofs))
        mesh = pad.mesh(size)
        scale = bf.Scale(0.1, 20e-6, 0.03, 2 * m.pi * 50)
        t = time.perf_counter()
        perf = bf.tilting_equilibrium(pad, mesh, scale, 20e3, cavitation="reynolds")
        seconds = time.perf_counter() - t
        return {"seconds": seconds, "peak_mib": proc_status_mib("VmHWM"), "dofs": int(perf.pad.result.basis.N)}
    mesh = _grid(dofs, per)
    film = bf.CosineFilm(0.6, math.pi + 0.3)
    if kind == "elastic P1":
        from bearingfe.elastic import half_space_fft, solve_elastic

        steel = bf.Material("steel", 210e9, poisson_ratio=0.3)
        scale = bf.Scale(radius=0.05, clearance=20e-6, viscosity=0.03, speed=157.08)
        t = time.perf_counter()
        sol = solve_elastic(mesh, film, half_space_fft(mesh, scale, (steel, steel)), cavitation="reynolds")
        seconds = time.perf_counter() - t
        return {"seconds": seconds, "peak_mib": proc_status_mib("VmHWM"), "dofs": int(sol.result.basis.N)}
    cavitation = {"linear": "none", "swift-stieber": "reynolds", "gumbel": "gumbel", "jfo": "jfo"}[kind.split()[0]]
    t = time.perf_counter()
    res = bf.solve_reynolds(mesh, film, formulation="direct", element=element, cavitation=cavitation)
    seconds = time.perf_counter() - t
    return {"seconds": seconds, "peak_mib": proc_status_mib("VmHWM"), "dofs": int(res.basis.N)}


def _grid(dofs: float, per: float):
    """``grid_mesh`` of the arc with about ``dofs`` unknowns (``per`` unknowns per vertex)."""
    import bearingfe as bf

    n = max(4, int(round(math.sqrt(dofs / per / 2.0))))
    return bf.grid_mesh(bf.Surface(arc=(-1.0, 1.0), half_width=0.5), 1.0 / n, max_elements=4 * n * n + 1000)


def stages(element: str, dofs: float) -> dict:
    """Resident memory after, and peak during, each stage of a cold linear direct solve [MiB] (this process).

    The stages are marked by wrapping the compiled path's steps in this process only; the peak of a stage is
    ``VmHWM`` after resetting it at the previous mark (``/proc/self/clear_refs``)."""
    import bearingfe as bf
    from bearingfe.film import compiled, superposition
    from bearingfe.film.mesh_operators import operators

    marks = []

    def mark(name: str) -> None:
        marks.append({"stage": name, "rss": proc_status_mib("VmRSS"), "peak": proc_status_mib("VmHWM")})
        Path("/proc/self/clear_refs").write_text("5")

    def after(name: str, f):
        def wrapped(*args, **kwargs):
            out = f(*args, **kwargs)
            mark(name)
            return out
        return wrapped

    def before(name: str, f):
        def wrapped(*args, **kwargs):
            mark(name)
            return f(*args, **kwargs)
        return wrapped

    C, S = compiled.CompiledOperator, compiled.CompiledSystem
    C.film_at = after("film at the points", C.film_at)
    C.system = after("matrix values", C.system)
    S.rhs = after("right sides", S.rhs)
    S.factorize = after("factorization", S.factorize)
    S.unit_loads = before("solves", S.unit_loads)
    superposition.build_result = after("result (flows, friction)", superposition.build_result)
    mark("imports")
    per = 4.0 if element == "P2" else 1.0
    mesh = _grid(dofs, per)
    mark("mesh")
    ops = operators(mesh, element)
    mark("operators (basis, dofs)")
    co = ops.compiled
    mark("compiled maps")
    del co
    res = bf.solve_reynolds(mesh, bf.CosineFilm(0.6, math.pi + 0.3), formulation="direct", element=element)
    return {"element": element, "dofs": int(res.basis.N), "marks": marks}


def _measure(kind: str, dofs: float, timeout: float, mode: str = "one") -> dict:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    try:
        r = subprocess.run([sys.executable, "-m", "benchmarks.solver_kinds", mode, kind, str(dofs)],
                           capture_output=True, text=True, timeout=timeout, cwd=ROOT, env=env)
    except subprocess.TimeoutExpired:
        return {"error": f"timeout after {timeout:.0f} s"}
    if r.returncode != 0:
        return {"error": (r.stderr.strip().splitlines() or ["failed"])[-1][:160]}
    return json.loads(r.stdout.strip().splitlines()[-1])


def _baseline() -> float:
    """Peak memory of a process that imported the package and nothing else [MiB]."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    code = "import bearingfe, bearingfe.reynolds; from benchmarks.common import proc_status_mib; print(proc_status_mib('VmHWM'))"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, env=env)
    return float(r.stdout.strip().splitlines()[-1])


def run(quick: bool = False, log=print) -> dict:
    load0 = os.getloadavg()[0]
    base = _baseline()
    sizes = QUICK_SIZES if quick else SIZES
    rows = []
    for kind in KINDS:
        failed = False
        for dofs in sizes:
            if dofs > LARGEST.get(kind, math.inf):
                continue
            if failed:
                rows.append({"kind": kind, "target": dofs, "error": "skipped (a smaller size failed)"})
                continue
            r = _measure(kind, dofs, TIMEOUT)
            r.update(kind=kind, target=dofs)
            rows.append(r)
            failed = "error" in r
            log(f"kinds {kind} {dofs:.0e}: " + (r["error"] if failed else
                                               f"{r['seconds']:.3g} s, {r['peak_mib']:.0f} MiB, {r['dofs']} dofs"))
    breakdown = []
    for element in ("P1", "P2"):
        for dofs in (QUICK_SIZES[-1:] if quick else STAGE_SIZES[element]):
            r = _measure(element, dofs, TIMEOUT, mode="stages")
            r.update(element=element, target=dofs)
            breakdown.append(r)
            log(f"kinds stages {element} {dofs:.0e}: " + r.get("error", f"{len(r.get('marks', []))} marks"))
    memory = _machine_memory()
    return dict(rows=rows, baseline=base, memory_mib=memory, load=(load0 + os.getloadavg()[0]) / 2, quick=quick,
                breakdown=breakdown)


def _machine_memory() -> float:
    try:
        kb = int(next(l for l in Path("/proc/meminfo").read_text().splitlines() if l.startswith("MemTotal")).split()[1])
        return kb / 1024.0
    except (OSError, StopIteration, ValueError):
        return math.nan


def _breakdown(runs: list) -> list[str]:
    """The memory breakdown table of the linear solves (``stages``)."""
    ok = [r for r in runs if "error" not in r]
    if not ok:
        return [f"Memory breakdown: {r['element']} ~{r['target']:.0e}: {r['error']}" for r in runs] + [""]
    names = list(dict.fromkeys(m["stage"] for r in ok for m in r["marks"] if m["stage"] != "imports"))
    head = ["stage"] + [f"{r['element']} {r['dofs']}: after / peak MiB" for r in ok]
    table = []
    for name in names:
        row = [name]
        for r in ok:
            m = next((m for m in r["marks"] if m["stage"] == name), None)
            row.append("-" if m is None else f"{m['rss']:.0f} / {m['peak']:.0f}")
        table.append(row)
    top = [f"{r['element']} {r['dofs']}: {max(m['peak'] for m in r['marks']):.0f} MiB at the "
           f"{max(r['marks'], key=lambda m: m['peak'])['stage']} "
           f"({max(m['peak'] for m in r['marks']) * 2**20 / r['dofs']:.0f} bytes per unknown)" for r in ok]
    return ["Where the memory of a linear direct solve goes: the process's resident memory after each stage and "
            "its peak during it (each run in its own process, the stages marked in the compiled path). Largest "
            "peaks: " + "; ".join(top) + ".", "", md_table(head, table), ""]


def _fit(n, y) -> tuple[float, float]:
    """Exponent and prefactor of ``y = a n^b`` by least squares in logs."""
    b, log_a = np.polyfit(np.log(n), np.log(y), 1)
    return float(b), float(math.exp(log_a))


def report(res: dict) -> tuple[str, dict]:
    rows, base = res["rows"], res["baseline"]
    lines = [f"Each measurement in its own process: a cold solve (caches empty, meshing apart) of the film "
             f"`h = 1 + 0.6 cos(phi - pi - 0.3)` on `grid_mesh` of the arc (-1, 1) x (-0.5, 0.5), direct form "
             f"(the thrust pad: its tilting equilibrium on a gmsh sector mesh; elastic: the same film on two steel "
             f"half-spaces, the compliance as its FFT product built inside the timing, matrix-free Newton-Krylov, "
             f"Swift-Stieber, largest opening about 0.27 c); peak memory `VmHWM` of the "
             f"process, of which {base:.0f} MiB are the interpreter and the imports. Load average during the "
             f"part: {res['load']:.2f}.", "",
             md_table(["kind", "dofs", "seconds", "peak MiB", "note"],
                      [[r["kind"], r.get("dofs", f"~{r['target']:.0e}"),
                        "-" if "error" in r else f"{r['seconds']:.3g}",
                        "-" if "error" in r else f"{r['peak_mib']:.0f}", r.get("error", "")] for r in rows]), ""]
    fits, facts, series_t, series_m = [], {}, {}, {}
    goal = next((r for r in rows if r["kind"] == "linear P1" and r["target"] >= 1e6), None)
    if goal is not None:
        if "error" in goal:
            lines += [f"Linear P1 at 1e6 unknowns: {goal['error']}.", ""]
        else:
            fits_budget = goal["peak_mib"] <= BUDGET_MIB
            lines += [f"Linear P1 at {goal['dofs']} unknowns: peak {goal['peak_mib']:.0f} MiB of the process, "
                      f"{'within' if fits_budget else 'over'} the budget of {BUDGET_MIB:.0f} MiB (4 GiB); "
                      f"{goal['seconds']:.3g} s.", ""]
            facts["linear P1 1e6 peak MiB"] = goal["peak_mib"]
            facts["linear P1 1e6 within 4 GiB"] = bool(fits_budget)
    lines += _breakdown(res.get("breakdown", []))
    for kind in KINDS:
        ok = [r for r in rows if r["kind"] == kind and "error" not in r]
        big = [r for r in ok if r["dofs"] >= 0.9e4]
        if ok:
            series_t[kind] = ([r["dofs"] for r in ok], [r["seconds"] for r in ok])
            series_m[kind] = ([r["dofs"] for r in ok], [max(r["peak_mib"] - base, 1.0) for r in ok])
        failed = next((r for r in rows if r["kind"] == kind and "error" in r and "skipped" not in r["error"]), None)
        if len(big) >= 2:
            n = np.array([r["dofs"] for r in big], float)
            bt, at = _fit(n, [r["seconds"] for r in big])
            bm, am = _fit(n, [max(r["peak_mib"] - base, 1.0) for r in big])
            minute = (MINUTE / at) ** (1 / bt) if bt > 0 else math.inf
            full = ((res["memory_mib"] - base) / am) ** (1 / bm) if bm > 0 else math.inf
            stop = (f"failed at ~{failed['target']:.0e}: {failed['error']}" if failed else
                    f"a minute at ~{minute:.1e}, the machine's memory at ~{full:.1e} dofs (fitted growth)")
            fits.append([kind, f"{bt:.2f}", f"{bm:.2f}", stop])
            facts[f"{kind} time exponent"] = bt
        else:
            fits.append([kind, "-", "-", f"failed at ~{failed['target']:.0e}: {failed['error']}" if failed else
                         "too few sizes to fit"])
    lines += ["Fitted growth over the sizes from 1e4 unknowns (memory above the interpreter's), and where each kind "
              "stops on this machine kind:", "",
              md_table(["kind", "time exponent", "memory exponent", "where it stops"], fits), ""]
    if series_t:
        IMG.mkdir(parents=True, exist_ok=True)
        loglog_plot(IMG / "scaling_kinds_time.png", series_t, xlabel="dofs", ylabel="seconds",
                    title="cold solve time vs dofs")
        loglog_plot(IMG / "scaling_kinds_memory.png", series_m, xlabel="dofs", ylabel="peak MiB above imports",
                    title="peak memory vs dofs")
        lines += ["![time](img/scaling_kinds_time.png) ![memory](img/scaling_kinds_memory.png)", ""]
    return "\n".join(lines) + "\n", facts


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "one":
        print(json.dumps(one(sys.argv[2], float(sys.argv[3]))))
    elif len(sys.argv) == 4 and sys.argv[1] == "stages":
        print(json.dumps(stages(sys.argv[2], float(sys.argv[3]))))
    else:
        sys.exit("usage: python -m benchmarks.solver_kinds one KIND DOFS | stages ELEMENT DOFS")
