"""Case (c): a full 360-degree journal bearing at eccentricity 0.95 with Swift-Stieber cavitation.

The Raimondi-Boyd full bearing of :mod:`bearingfe.bearings.journal` (``L/D = 1``,
``p = 0`` at the axial edges and along the line of largest film), meshed in
the frame of the line of centres (arc ``(0, 2 pi)`` from the largest film,
``h = 1 + 0.95 cos(phi)``, thinnest film 0.05 at ``phi = pi``), solved with
``cavitation="reynolds"`` (primal-dual active set on the obstacle problem,
direct form) for P1 and P2, on uniform meshes and on meshes graded towards
the thin film with :func:`bearingfe.bearings.journal.film_graded_size`
(``min_size = size sqrt(1 - eps)``, the journal module's default).

Error: relative error of the load vector ``int p (cos, sin)`` against a
converged reference: P2 on a graded curved (order-2) mesh finer than any in
the sweep; its own error is estimated by the change from the mesh twice as
coarse. FD curve: :func:`bearingfe.film.fd.solve_reynolds_fd` with Christopherson's
projected SOR (``cavitation="reynolds"``, five-point direct scheme, uniform grid,
SOR factor ``2 / (1 + sin(pi d / 2))``). Nested series: P1 on the graded meshes,
each solve started from the previous (coarser) mesh's rupture set; its time is
cumulative over the levels, as nested iteration must pay for the coarse solves.
"""

from __future__ import annotations

import math

import numpy as np

import bearingfe as bf
from bearingfe.bearings.journal import default_min_size, film_graded_size

from .common import IMG, loglog_plot, md_table, time_at_error, timed
from .work_precision import Run

EPS = 0.95
LENGTH_RATIO = 1.0


def setup(quick: bool) -> dict:
    return {
        "film": bf.CosineFilm(EPS, 0.0),
        "surface": bf.JournalBearing(LENGTH_RATIO).surfaces()[0],
        "sizes": {"P1": (0.2, 0.1, 0.05) if quick else (0.2, 0.1, 0.05, 0.025),
                  "P2": (0.4, 0.2) if quick else (0.4, 0.2, 0.1)},
        "fd_spacings": (0.08, 0.04, 0.02) if quick else (0.08, 0.04, 0.02, 0.01),
        "ref_size": 0.05 if quick else 0.04,
    }


def _mesh(cfg: dict, size: float, graded: bool, order: int):
    extra = {"size_function": film_graded_size(cfg["film"], size, default_min_size(size, EPS))} if graded else {}
    return timed(bf.mesh_surface, cfg["surface"], size, order=order, **extra)


def _solve(cfg: dict, mesh, element: str):
    def once():
        mesh._cache.clear()  # each timing pays for its own operators, as a first solve on a mesh does
        return bf.solve_reynolds(mesh, cfg["film"], formulation="direct", element=element, cavitation="reynolds")
    return timed(once, repeat=3 if mesh.n_nodes < 20000 else 1)


def reference(cfg: dict) -> dict:
    out = {}
    for s in (2 * cfg["ref_size"], cfg["ref_size"]):
        mesh, tm = _mesh(cfg, s, True, 2)
        res, t = timed(bf.solve_reynolds, mesh, cfg["film"], formulation="direct", element="P2",
                       cavitation="reynolds")
        out[s] = (res.force.copy(), int(res.cost["dofs"]), tm + t, res.iterations)
    fine, coarse = out[cfg["ref_size"]][0], out[2 * cfg["ref_size"]][0]
    return {"force": fine, "dofs": out[cfg["ref_size"]][1], "seconds": out[cfg["ref_size"]][2],
            "iterations": out[cfg["ref_size"]][3],
            "change": float(np.linalg.norm(fine - coarse) / np.linalg.norm(fine))}


def run(quick: bool, log=print) -> dict:
    cfg = setup(quick)
    ref = reference(cfg)
    log(f"  case c reference: {ref['dofs']} dofs, {ref['seconds']:.1f} s, change {ref['change']:.1e}")
    F = ref["force"]
    runs: dict[str, Run] = {}
    for graded in (False, True):
        for element in ("P1", "P2"):
            label = f"FEM {element} {'graded' if graded else 'uniform'}"
            run_ = runs.setdefault(label, Run(label))
            for size in cfg["sizes"][element]:
                mesh, tm = _mesh(cfg, size, graded, 2 if element == "P2" else 1)
                res, t = _solve(cfg, mesh, element)
                _record(run_, res, t, tm, size, F)
                log(f"  case c {label} {size}: {run_.dofs[-1]} dofs {t:.3f} s err {run_.error[-1]:.1e} "
                    f"it {res.iterations}")
    runs["FEM P1 graded nested"] = _nested(cfg, F, log)
    runs["FD projected SOR"] = _fd(cfg, F, log)
    return {"config": cfg, "reference": ref, "runs": runs}


def _record(run_: Run, res, seconds: float, meshing: float, size: float, F: np.ndarray) -> None:
    """Append one FEM solve to a work-precision series."""
    run_.dofs.append(int(res.cost["dofs"]))
    run_.seconds.append(seconds)
    run_.meshing.append(meshing)
    run_.force.append(res.force.copy())
    run_.error.append(float(np.linalg.norm(res.force - F) / np.linalg.norm(F)))
    run_.costs.append({"iterations": res.iterations, "size": size,
                       "factorizations": res.cost.get("cavitation_factorizations", np.nan),
                       "cavitation": res.cost.get("cavitation", np.nan)})
    run_.notes.extend(res.notes)


def _nested(cfg: dict, F: np.ndarray, log) -> Run:
    run_, previous, total = Run("FEM P1 graded nested"), None, 0.0
    for size in cfg["sizes"]["P1"]:
        mesh, tm = _mesh(cfg, size, True, 1)
        mesh._cache.clear()
        res, t = timed(bf.solve_reynolds, mesh, cfg["film"], formulation="direct", cavitation="reynolds",
                       warm_start=previous)
        total += t
        previous = res
        _record(run_, res, total, tm, size, F)
        log(f"  case c nested {size}: {run_.dofs[-1]} dofs {total:.3f} s err {run_.error[-1]:.1e} "
            f"it {res.iterations}")
    return run_


def _fd(cfg: dict, F: np.ndarray, log) -> Run:
    run_ = Run("FD projected SOR")
    for d in cfg["fd_spacings"]:
        shape = (int(round(2 * math.pi / d)) + 1, int(round(2 * LENGTH_RATIO / d)) + 1)
        res, t = timed(bf.solve_reynolds_fd, cfg["surface"], cfg["film"], shape, formulation="direct",
                       method="seidel", cavitation="reynolds", omega_relax=2 / (1 + math.sin(math.pi * d / 2)),
                       tol=1e-12, max_iter=5_000_000)
        run_.dofs.append(int(np.prod(np.array(shape) - 2)))
        run_.seconds.append(t)
        run_.meshing.append(0.0)
        run_.force.append(np.asarray(res.force, float))
        run_.error.append(float(np.linalg.norm(res.force - F) / np.linalg.norm(F)))
        run_.costs.append({"iterations": res.iterations, "size": d, "factorizations": 0, "cavitation": t})
        log(f"  case c FD {d}: {shape} {t:.3f} s err {run_.error[-1]:.1e} sweeps {res.iterations}")
    return run_


def report(result: dict) -> str:
    cfg, ref, runs = result["config"], result["reference"], result["runs"]
    F = ref["force"]
    w = float(np.linalg.norm(F))
    attitude = math.degrees(math.atan2(abs(F[1]), -F[0]))
    lines = [
        f"Full 360-degree bearing (`bearingfe.bearings.journal.JournalBearing({LENGTH_RATIO})`, L/D = {LENGTH_RATIO}), "
        f"eccentricity {EPS} (thinnest film {1 - EPS:.2g} c), wedge 1, Swift-Stieber cavitation "
        "(`solve_reynolds(..., formulation=\"direct\", cavitation=\"reynolds\")`, primal-dual active set). "
        "Graded meshes: `film_graded_size(film, size, size*sqrt(1-eps))`. Time = one `solve_reynolds` call "
        "on a fresh mesh (operators, assembly, all active-set factorizations, flows), meshing separate.",
        "",
        f"**Reference**: P2 on a graded curved (order 2) mesh of nominal size {cfg['ref_size']} "
        f"({ref['dofs']} dofs, {ref['iterations']} active-set iterations, {ref['seconds']:.1f} s): "
        f"F = ({F[0]:.10g}, {F[1]:.10g}), load {w:.8g}, attitude {attitude:.4f} deg, Sommerfeld number "
        f"{2 * LENGTH_RATIO / (math.pi * w):.6g}. It moved by {ref['change']:.1e} (relative) from the graded "
        f"P2 mesh twice as coarse, so errors below ~{max(ref['change'] / 10, 1e-12):.0e} are not resolved.",
        "",
        "**FD curve**: `bearingfe.film.fd` with Christopherson's projected SOR on uniform grids of spacing d "
        "(column 'size'; 'active-set iterations' are its SOR sweeps there). **Nested**: P1 on the graded "
        "meshes, each level started from the previous level's rupture set (`warm_start=`), time cumulative.",
        "",
    ]
    series = {r.label: (r.seconds, r.error) for r in runs.values()}
    img = loglog_plot(IMG / "work_precision_c.png", series, xlabel="wall time per solve [s]",
                      ylabel="relative load error", title="(c) full journal, eps 0.95, Swift-Stieber")
    lines += [f"![work-precision c]({img})", ""]
    rows = []
    for r in runs.values():
        for n, t, tm, e, c in zip(r.dofs, r.seconds, r.meshing, r.error, r.costs):
            rows.append([r.label, c["size"], n, t, tm, c["iterations"], int(c["factorizations"]),
                         c["cavitation"], e])
    lines.append(md_table(["method", "size", "dofs", "solve s", "meshing s", "active-set iterations",
                           "factorizations", "of which cavitation s", "load error"], rows))
    lines.append("")
    targets = (1e-2, 1e-3, 1e-4)
    rows = [[r.label] + [time_at_error(r.seconds, r.error, t) for t in targets]
            + [time_at_error(np.add(r.seconds, r.meshing), r.error, 1e-3)] for r in runs.values()]
    lines.append("Wall time [s] to reach a relative load error (log-log interpolation; '-' = not reached):")
    lines.append("")
    lines.append(md_table(["method"] + [f"{t:.0e}" for t in targets] + ["1e-03 +mesh"], rows))
    lines.append("")
    lines.append(conclusions(runs))
    notes = sorted({n for r in runs.values() for n in r.notes})
    if notes:
        lines += ["", "Solver notes: " + "; ".join(notes)]
    lines.append("")
    return "\n".join(lines)


def conclusions(runs: dict[str, Run]) -> str:
    """Sentences computed from the tables above."""
    out = []
    for target in (1e-2, 1e-3):
        t = {k: time_at_error(r.seconds, r.error, target) for k, r in runs.items()}
        t = {k: v for k, v in t.items() if np.isfinite(v)}
        if not t:
            out.append(f"No method reached a load error of {target:.0e} in the sweep.")
            continue
        best = min(t, key=t.get)
        others = ", ".join(f"{k} {v / t[best]:.1f}x" for k, v in sorted(t.items(), key=lambda kv: kv[1])
                           if k != best)
        out.append(f"At a load error of {target:.0e} the cheapest is **{best}** ({t[best]:.3g} s)"
                   + (f"; the others take (time ratio) {others}." if others else "."))
    cold = {k: r for k, r in runs.items() if k.startswith("FEM") and "nested" not in k}
    it = {k: [c["iterations"] for c in r.costs] for k, r in cold.items()}
    grows = all(np.all(np.diff(v) >= 0) for v in it.values())
    out.append("Active-set iterations over each sweep, coarse to fine, each solve started cold: "
               + "; ".join(f"{k} {', '.join(map(str, v))}" for k, v in it.items())
               + (" (never fewer on a finer mesh)" if grows else "")
               + ".")
    nested = [r for k, r in runs.items() if "nested" in k]
    if nested:
        out.append("Started from the previous mesh's rupture set (nested): "
                   + ", ".join(str(c["iterations"]) for c in nested[0].costs) + " iterations.")
    same = all(int(c["factorizations"]) == c["iterations"] for r in cold.values() for c in r.costs)
    out.append("Every active-set iteration needed a new factorization (column 'factorizations')." if same else
               "Some active-set iterations reused a cached factorization (column 'factorizations').")
    share = [c["cavitation"] / t for r in cold.values() for c, t in zip(r.costs, r.seconds) if t > 0]
    if share:
        out.append(f"The cavitation iteration takes {100 * min(share):.0f}-{100 * max(share):.0f} % of the "
                   "solve time (column 'of which cavitation s').")
    return "\n\n".join(out)
