"""Growth of time and memory with the number of unknowns, and the linear-solver comparison.

Each measurement runs in its own Python process so that its peak memory is
its own: ``build`` meshes the plain partial arc of case (a), builds the
operators, assembles the direct-form Reynolds matrix and the four unit right
sides, condenses them and saves them (``.npz``); ``factor`` loads one such
system and factorizes and solves it with one solver from
:data:`bearingfe.core.linalg.LINEAR_SOLVERS`, then (where the backend supports
it) refactorizes new values on the same pattern through
:class:`bearingfe.core.linalg.PatternFactorizer`, as every step of a transient does.

Run as ``python -m benchmarks.scaling build|factor ...`` (internal); the
driver is :func:`run`.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from .common import IMG, ROOT, loglog_plot, md_table, proc_status_mib

AREA = 2.0  # plain arc (-1, 1) x (-0.5, 0.5)


def build(element: str, dofs: float, path: str) -> dict:
    import scipy.sparse as sp

    import bearingfe as bf
    from bearingfe.film.forms import film_at
    from bearingfe.film import operators
    from bearingfe.film.reference import system_matrix, unit_sources

    vertices = dofs / (4.0 if element == "P2" else 1.0)
    size = math.sqrt(2 * AREA / (math.sqrt(3) * vertices))
    refine = 0 if vertices < 60e3 else (1 if vertices < 300e3 else 2)
    t0 = time.perf_counter()
    mesh = bf.mesh_surface(bf.Surface(arc=(-1.0, 1.0), half_width=0.5), size * 2**refine, refine=refine)
    t1 = time.perf_counter()
    ops = operators(mesh, element)
    t2 = time.perf_counter()
    film = bf.CosineFilm(0.6, math.pi + 0.3)
    at = film_at(film, ops.x)
    A = system_matrix(ops, at, "direct")
    F = unit_sources(ops, at, "direct")
    I = ops.interior
    AI = A[I][:, I].tocsc()
    rhs = -F[I]
    t3 = time.perf_counter()
    at2 = film_at(bf.CosineFilm(0.5, math.pi), ops.x)  # a second film state: same pattern, new values
    A2 = system_matrix(ops, at2, "direct")[I][:, I].tocsc()
    sp.save_npz(path + "_A.npz", AI)
    sp.save_npz(path + "_A2.npz", A2)
    np.save(path + "_b.npy", rhs)
    return {"element": element, "dofs": int(ops.n_dofs), "unknowns": int(I.size), "nnz": int(AI.nnz),
            "meshing": t1 - t0, "operators": t2 - t1, "assembly": t3 - t2, "peak_mib": proc_status_mib("VmHWM")}


def factor(solver: str, path: str) -> dict:
    import scipy.sparse as sp

    from bearingfe.core.linalg import LINEAR_SOLVERS, PatternFactorizer

    A = sp.load_npz(path + "_A.npz").tocsc()
    A2 = sp.load_npz(path + "_A2.npz").tocsc()
    b = np.load(path + "_b.npy")
    if solver in ("pardiso", "cholmod", "cholespy", "amg"):
        LINEAR_SOLVERS[solver](sp.identity(4, format="csc"))  # library load outside the timing
    rss0 = proc_status_mib("VmRSS")
    t0 = time.perf_counter()
    solve = LINEAR_SOLVERS[solver](A)
    t1 = time.perf_counter()
    x = solve(b)
    t2 = time.perf_counter()
    out = {"solver": solver, "factorization": t1 - t0, "solve": t2 - t1,
           "residual": float(np.abs(A @ x - b).max() / np.abs(b).max()), "memory_mib": proc_status_mib("VmHWM") - rss0}
    del solve
    if solver in PatternFactorizer.BACKENDS:
        fac = PatternFactorizer(solver)
        fac(A)
        t3 = time.perf_counter()
        s2 = fac(A2)
        t4 = time.perf_counter()
        x2 = s2(b)
        out["refactor"] = t4 - t3
        out["refactor_residual"] = float(np.abs(A2 @ x2 - b).max() / np.abs(b).max())
        out["analyses"] = fac.analyses
    return out


def _child(args: list[str], timeout: float) -> dict:
    env = {"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin", "OMP_NUM_THREADS": "2", "MKL_NUM_THREADS": "2"}
    try:
        r = subprocess.run([sys.executable, "-m", "benchmarks.scaling", *args], capture_output=True, text=True,
                           timeout=timeout, cwd=ROOT, env=env)
    except subprocess.TimeoutExpired:
        return {"error": f"timeout after {timeout:.0f} s"}
    if r.returncode != 0:
        return {"error": (r.stderr.strip().splitlines() or ["failed"])[-1][:200]}
    return json.loads(r.stdout.strip().splitlines()[-1])


#: Largest number of unknowns each solver is run at (beyond: not measured, time would break the
#: ~15 min budget of the full run on 2 cores; the slow ones stop after the 3e5 systems).
CAPS = {"splu": 4e5, "splu_sym": 1.2e6, "amg": 3.1e5, "cholmod": 1.2e6, "pardiso": 1.2e6, "cholespy": 3.1e5}


def run(quick: bool, log=print) -> dict:
    from bearingfe.core.linalg import available_solvers

    solvers = available_solvers()
    targets = {"P1": (1e4, 5e4), "P2": (5e4,)} if quick else \
        {"P1": (1e4, 1e5, 3e5, 1e6), "P2": (1e4, 1e5, 3e5)}  # P2 at 1e6 (~110 s) dropped: 15 min budget
    builds, factors = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for element, sizes in targets.items():
            for n in sizes:
                path = str(Path(tmp) / f"{element}_{int(n)}")
                b = _child(["build", element, str(n), path], 600)
                log(f"  build {element} {n:.0e}: {b}")
                if "error" in b:
                    builds.append({"element": element, "dofs": n, **b})
                    continue
                builds.append(b)
                for s in solvers:
                    if b["unknowns"] > CAPS.get(s, 1e5):
                        factors.append({"element": element, "dofs": b["dofs"], "solver": s, "error": "not run (cap)"})
                        continue
                    f = _child(["factor", s, path], 400)
                    log(f"    {s}: {f}")
                    factors.append({"element": element, "dofs": b["dofs"], "unknowns": b["unknowns"], **f,
                                    "solver": s})
    return {"builds": builds, "factors": factors, "solvers": solvers}


def report(res: dict) -> str:
    builds, factors = res["builds"], res["factors"]
    lines = ["Meshing, operators and assembly (plain arc of case (a), direct form, one process per size):", ""]
    rows = [[b["element"], b.get("dofs"), b.get("nnz", "-"), b.get("meshing", np.nan), b.get("operators", np.nan),
             b.get("assembly", np.nan), b.get("peak_mib", np.nan), b.get("error", "")] for b in builds]
    lines.append(md_table(["element", "dofs", "nnz (condensed)", "meshing s", "operators s", "assembly s",
                           "peak RSS MiB", "note"], rows))
    lines += ["", "Linear solvers on the condensed systems (factorization, 4 right sides, memory growth of "
              "the process during factorization; refactor = numeric factorization of a new film on the same "
              "pattern with the symbolic analysis reused):", ""]
    rows = []
    for f in factors:
        rows.append([f["element"], f["dofs"], f["solver"], f.get("factorization", np.nan), f.get("solve", np.nan),
                     f.get("refactor", np.nan), f.get("memory_mib", np.nan),
                     f"{f['residual']:.0e}" if "residual" in f else "-", f.get("error", "")])
    lines.append(md_table(["element", "dofs", "solver", "factor s", "solve s (4 rhs)", "refactor s",
                           "memory MiB", "residual", "note"], rows))
    lines.append("")
    for what, key in (("factorization", "factorization"), ("memory", "memory_mib")):
        series = {}
        for f in factors:
            if key in f:
                series.setdefault(f"{f['solver']} {f['element']}", ([], []))
                series[f"{f['solver']} {f['element']}"][0].append(f["dofs"])
                series[f"{f['solver']} {f['element']}"][1].append(max(f[key], 1e-3))
        if what == "factorization":
            for el in ("P1", "P2"):
                pts = [b for b in builds if b["element"] == el and "meshing" in b]
                series[f"gmsh meshing {el}"] = ([b["dofs"] for b in pts], [b["meshing"] for b in pts])
        img = loglog_plot(IMG / f"scaling_{what}.png", series, xlabel="dofs",
                          ylabel=f"{what} [{'s' if key != 'memory_mib' else 'MiB'}]", title=f"{what} vs dofs")
        lines += [f"![{what} vs dofs]({img})", ""]
    return "\n".join(lines)


#: Solvers that need nothing beyond scipy (candidates for the default).
CORE = ("splu", "splu_sym", "amg")


def recommend(res: dict, among=None) -> tuple[str, str]:
    """Fastest solver by total (factor + solve) time summed over the sizes all solvers
    (of ``among``, default all available) completed."""
    solvers = [s for s in res["solvers"] if among is None or s in among]
    by = {}
    for f in res["factors"]:
        if "factorization" in f and f["solver"] in solvers:
            by.setdefault((f["element"], f["dofs"]), {})[f["solver"]] = f["factorization"] + f["solve"]
    common = [v for v in by.values() if set(v) >= set(solvers)]
    if not common:
        return "splu", "no size completed with every solver"
    total = {s: sum(v[s] for v in common) for s in solvers}
    best = min(total, key=total.get)
    text = ", ".join(f"{s} {t:.2f} s" for s, t in sorted(total.items(), key=lambda kv: kv[1]))
    return best, f"total factor+solve time over the {len(common)} systems every solver ran: {text}"


def main(argv=None) -> None:
    argv = sys.argv[1:] if argv is None else argv
    if argv[0] == "build":
        print(json.dumps(build(argv[1], float(argv[2]), argv[3])))
    elif argv[0] == "factor":
        print(json.dumps(factor(argv[1], argv[2])))
    else:
        raise SystemExit("usage: python -m benchmarks.scaling build ELEMENT DOFS PATH | factor SOLVER PATH")


if __name__ == "__main__":
    main()
