"""Fill-reducing orderings side by side: SuperLU's minimum degree against nested dissection.

For the condensed matrix of a film (its pattern: interior dofs coupled through the elements; the
values here are ``grad u . grad v + 1e-3 u v``, which have that pattern and keep SuperLU's
symmetric mode free of pivoting, so fill and time are those of any film on the mesh), on
``grid_mesh`` and on ``mesh_surface`` (gmsh) of the arc ``(-1, 1) x (-0.5, 0.5)``, P1 and P2, at
1e4 .. 1e6 unknowns:

=========  ====================================================================================
order      how the matrix is factored
=========  ====================================================================================
``mmd``    ``splu(A, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0, SymmetricMode=True)``:
           SuperLU's minimum degree on ``A^T + A`` (``factorize_splu_sym`` below the crossover)
``nd``     :func:`bearingfe.core.ordering.nested_dissection` from the graph alone, then
           ``splu(A[o][:, o], permc_spec="NATURAL", ...)``
``nd_xy``  the same with the dofs' coordinates (the compiled path's order from
           :data:`~bearingfe.core.ordering.NESTED_DISSECTION_FROM` unknowns)
=========  ====================================================================================

Each measurement in its own process: ordering seconds, factorization seconds, ``nnz(L) + nnz(U)``,
and the peak memory ``VmHWM`` of the process above what it held before the ordering (the mesh and
the matrix). The floor of the page is the factorization itself: the ordering is reported beside it.

Run: ``PYTHONPATH=. python benchmarks/run_all.py --only orderings`` (1e4 .. 3e5; ``--quick`` up to
1e5); 1e6 unknowns apart: ``python -m benchmarks.orderings run 1e6 --case grid P1`` (rows merged into
``docs/benchmarks_parts/orderings_runs.json``, from which the page is written). Internal:
``python -m benchmarks.orderings one SOURCE ELEMENT DOFS ORDER``.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import time

from .common import DOCS, ROOT, md_table, proc_status_mib

ORDERS = ("mmd", "nd", "nd_xy")
CASES = (("grid", "P1"), ("gmsh", "P1"), ("grid", "P2"), ("gmsh", "P2"))
SIZES = (1e4, 1e5, 3e5)
QUICK_SIZES = (1e4, 1e5)
#: Every measurement is merged into this file as it ends; the page is written from it, so sizes run
#: apart (``python -m benchmarks.orderings run 1e6``: 1e6 unknowns take many minutes each) join it.
RUNS = DOCS / "benchmarks_parts" / "orderings_runs.json"
TIMEOUT = 900.0


def matrix(source: str, element: str, dofs: float):
    """The interior block of ``grad u . grad v + 1e-3 u v`` and the interior dofs' coordinates."""
    import numpy as np
    import skfem
    from skfem.helpers import dot, grad

    import bearingfe as bf

    per = 4.0 if element == "P2" else 1.0
    surface = bf.Surface(arc=(-1.0, 1.0), half_width=0.5)
    if source == "grid":
        mesh = bf.grid_mesh(surface, 1.0 / max(4, int(round(math.sqrt(dofs / per / 2.0)))),
                            max_elements=int(4 * dofs)).mesh
    else:
        mesh = bf.mesh_surface(surface, math.sqrt(2 * 2.0 / (math.sqrt(3) * dofs / per)),
                               max_elements=int(4 * dofs)).mesh
    basis = skfem.Basis(mesh, skfem.ElementTriP2() if element == "P2" else skfem.ElementTriP1())

    @skfem.BilinearForm
    def form(u, v, w):
        return dot(grad(u), grad(v)) + 1e-3 * u * v

    interior = basis.complement_dofs(basis.get_dofs())
    A = form.assemble(basis)[interior][:, interior].tocsc()
    A.sort_indices()
    return A, np.asarray(basis.doflocs)[:, interior]


def one(source: str, element: str, dofs: float, order: str) -> dict:
    """One measurement in this process (see the module docstring)."""
    import numpy as np
    import scipy.sparse.linalg as spla

    from bearingfe.core.ordering import nested_dissection

    A, xy = matrix(source, element, dofs)
    before = proc_status_mib("VmHWM")
    options = dict(diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    t0 = time.perf_counter()
    if order == "mmd":
        t1 = t0
        lu = spla.splu(A, permc_spec="MMD_AT_PLUS_A", **options)
        perm = None
    else:
        perm = nested_dissection(A, xy if order == "nd_xy" else None)
        t1 = time.perf_counter()
        lu = spla.splu(A[perm][:, perm].tocsc(), permc_spec="NATURAL", **options)
    t2 = time.perf_counter()
    b = np.ones(A.shape[0])
    x = lu.solve(b) if perm is None else lu.solve(b[perm])[np.argsort(perm)]
    residual = float(np.linalg.norm(A @ x - b) / np.linalg.norm(b))
    return {"dofs": int(A.shape[0]), "order_s": t1 - t0, "factor_s": t2 - t1, "fill": int(lu.L.nnz + lu.U.nnz),
            "peak_mib": proc_status_mib("VmHWM"), "before_mib": before, "residual": residual}


def _measure(source: str, element: str, dofs: float, order: str) -> dict:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    try:
        r = subprocess.run([sys.executable, "-m", "benchmarks.orderings", "one", source, element, str(dofs), order],
                           capture_output=True, text=True, timeout=TIMEOUT, cwd=ROOT, env=env)
    except subprocess.TimeoutExpired:
        return {"error": f"timeout after {TIMEOUT:.0f} s"}
    if r.returncode != 0:
        return {"error": (r.stderr.strip().splitlines() or ["failed"])[-1][:160]}
    return json.loads(r.stdout.strip().splitlines()[-1])


def _merge(rows: list[dict]) -> None:
    old = json.loads(RUNS.read_text()) if RUNS.exists() else []
    new = {(r["source"], r["element"], r["target"], r["order"]) for r in rows}
    keep = [r for r in old if (r["source"], r["element"], r["target"], r["order"]) not in new]
    order = {name: k for k, name in enumerate(ORDERS)}
    cases = {case: k for k, case in enumerate(CASES)}
    RUNS.parent.mkdir(parents=True, exist_ok=True)
    RUNS.write_text(json.dumps(sorted(keep + rows, key=lambda r: (cases[(r["source"], r["element"])], r["target"],
                                                                  order[r["order"]])), indent=1) + "\n")


def run(quick: bool = False, log=print, sizes=None, cases=CASES, orders=ORDERS) -> dict:
    """Measure each case, size and order in its own process; every row is merged into :data:`RUNS`
    (a quick run only reports, it does not merge)."""
    load0 = os.getloadavg()[0]
    rows = []
    for source, element in cases:
        for dofs in sizes or (QUICK_SIZES if quick else SIZES):
            for order in orders:
                r = _measure(source, element, dofs, order)
                r.update(source=source, element=element, target=dofs, order=order, load=os.getloadavg()[0])
                rows.append(r)
                if not quick:
                    _merge([r])
                log(f"orderings {source} {element} {dofs:.0e} {order}: " + (
                    r["error"] if "error" in r else
                    f"order {r['order_s']:.3g} s, factor {r['factor_s']:.3g} s, fill {r['fill']}, "
                    f"peak {r['peak_mib']:.0f} MiB"))
    return dict(rows=rows, load=(load0 + os.getloadavg()[0]) / 2, quick=quick)


def report(res: dict) -> tuple[str, dict]:
    """The part's page from the rows of this run and, unless quick, every row in :data:`RUNS`."""
    rows = res["rows"] if res.get("quick") or not RUNS.exists() else json.loads(RUNS.read_text())
    measured = [r["load"] for r in rows if "load" in r] or [res["load"]]
    loads = (min(measured), max(measured))
    lines = ["Each row in its own process; `fill` is nnz(L) + nnz(U) of SuperLU's factors, `factor` the "
             "numeric factorization (for `mmd` with its own ordering inside), `order` the nested dissection "
             "before it, `MiB` the rise of the process's peak memory (VmHWM) over what it held with the mesh "
             "and the matrix. Ratios are against `mmd` on the same matrix. Load average during the measurements: "
             f"{loads[0]:.1f} to {loads[1]:.1f} on 2 cores (times are noisy, up to several times; fill is "
             "exact). Rows of 1e6 unknowns are measured apart (`python -m benchmarks.orderings run 1e6 --case grid "
             "P1`) and merged.", ""]
    table, facts = [], {}
    keyed = {(r["source"], r["element"], r["target"], r["order"]): r for r in rows}
    for r in rows:
        base = keyed.get((r["source"], r["element"], r["target"], "mmd"), {})
        if "error" in r:
            table.append([f"{r['source']} {r['element']}", f"~{r['target']:.0e}", r["order"], "-", "-", "-", "-",
                          "-", "-", r["error"]])
            continue
        ok = "error" not in base
        fill_ratio = r["fill"] / base["fill"] if ok and base else math.nan
        total = r["order_s"] + r["factor_s"]
        time_ratio = total / (base["order_s"] + base["factor_s"]) if ok and base else math.nan
        rise = r["peak_mib"] - r["before_mib"]
        table.append([f"{r['source']} {r['element']}", r["dofs"], r["order"], f"{r['order_s']:.3g}",
                      f"{r['factor_s']:.3g}", r["fill"], "-" if math.isnan(fill_ratio) else f"{fill_ratio:.3f}",
                      "-" if math.isnan(time_ratio) else f"{time_ratio:.2f}",
                      f"{rise:.0f}", ""])
        facts[f"{r['source']} {r['element']} {r['target']:.0e} {r['order']} fill ratio"] = fill_ratio
    lines += [md_table(["mesh", "dofs", "order", "order s", "factor s", "fill", "fill / mmd", "time / mmd",
                        "MiB", "note"], table), ""]
    # the crossover: per mesh and order, the smallest measured size from which on it fills less than mmd
    said = []
    for source, element in CASES:
        for order in ORDERS[1:]:
            ratios = sorted((r["target"], r["fill"] / keyed[(r["source"], r["element"], r["target"], "mmd")]["fill"])
                            for r in rows if (r["source"], r["element"], r["order"]) == (source, element, order)
                            and "error" not in r and "error" not in keyed.get(
                                (r["source"], r["element"], r["target"], "mmd"), {"error": 1}))
            if not ratios:
                continue
            start = None
            for target, ratio in reversed(ratios):
                if ratio >= 1.0:
                    break
                start = target
            said.append(f"{source} {element} {order} " + (f"from ~{start:.0e}" if start is not None else "never"))
            facts[f"{source} {element} {order} fills less from"] = start
    lines += ["Fills less than `mmd` at this and every larger measured size: " + "; ".join(said) + ".", ""]
    return "\n".join(lines) + "\n", facts


if __name__ == "__main__":
    if len(sys.argv) == 6 and sys.argv[1] == "one":
        print(json.dumps(one(sys.argv[2], sys.argv[3], float(sys.argv[4]), sys.argv[5])))
    elif len(sys.argv) >= 2 and sys.argv[1] == "run":  # rows merged into RUNS
        import argparse

        ap = argparse.ArgumentParser(prog="python -m benchmarks.orderings run")
        ap.add_argument("sizes", nargs="+", type=float)
        ap.add_argument("--case", nargs=2, metavar=("SOURCE", "ELEMENT"), default=None)
        ap.add_argument("--orders", nargs="+", choices=ORDERS, default=ORDERS)
        args = ap.parse_args(sys.argv[2:])
        run(log=lambda s: print(s, file=sys.stderr, flush=True), sizes=tuple(args.sizes),
            cases=(tuple(args.case),) if args.case else CASES, orders=tuple(args.orders))
    else:
        sys.exit("usage: python -m benchmarks.orderings one SOURCE ELEMENT DOFS ORDER | run [SIZES...]")
