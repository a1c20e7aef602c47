"""Cost of one pump revolution against the error of the smallest film.

Reference: the shipped pump (``mechanisms/eccentric_pump.toml``, 10 % pocket)
with P2 elements on a curved (order-2) mesh of size 0.03 R0, LSODA
rtol = 1e-9, from its periodic state. Each case integrates one revolution
from the reference's periodic start and compares ``min h_min`` over the turn
(sampled at 1 degree). Wall time is the integration only
(``stats['seconds']``: factorizations included, mesh and post-processing
excluded; meshing is reported separately). P1 runs on straight-sided
meshes, P2 on curved ones (on straight-sided triangles P2 stalls at the
geometric error of the polygonal pocket edge).

Writes ``docs/benchmarks_pump.md`` (and the numbers that ``benchmarks/run_all.py``
quotes in ``docs/benchmarks_pump.json``). Run:
``PYTHONPATH=. python benchmarks/pump_revolution.py``
"""

from __future__ import annotations

import json
import platform
import time
from pathlib import Path

import bearingfe as bf

ROOT = Path(__file__).resolve().parents[1]
CASES = [("P1", 0.15), ("P1", 0.08), ("P1", 0.045), ("P2", 0.2), ("P2", 0.15), ("P2", 0.1), ("P2", 0.07)]
#: Integrators and tolerances run on every mesh: LSODA (the default), Radau, and the explicit RK23
#: pair (the film is not stiff on this pump, so its steps are set by accuracy).
METHODS = [("LSODA", 1e-4), ("LSODA", 1e-5), ("LSODA", 1e-6), ("Radau", 1e-6),
           ("RK23", 1e-3), ("RK23", 3e-4), ("RK23", 1e-4)]


def _mesh(pump, element: str, size: float):
    t0 = time.perf_counter()
    mesh = bf.transient.pump_mesh(pump, size, order=2 if element == "P2" else 1)
    return mesh, time.perf_counter() - t0


def run(log=print) -> dict:
    """The reference, every case of ``CASES`` and the ``simulate()`` defaults."""
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    fine, mesh_s = _mesh(pump, "P2", 0.03)
    ref = bf.simulate(pump, fine, 1.0, start="periodic", element="P2", rtol=1e-9, atol=1e-12,
                      points_per_revolution=360)
    start, h_ref = ref.start, ref.smallest_film
    rows = []
    for element, size in CASES:
        mesh, msh = _mesh(pump, element, size)
        for method, rtol in METHODS:
            tr = bf.simulate(pump, mesh, 1.0, start=start, rtol=rtol, atol=1e-3 * rtol, method=method,
                             element=element, points_per_revolution=360)
            err = abs(tr.smallest_film - h_ref) / h_ref
            rows.append((element, size, mesh.n_nodes, method, rtol, tr.stats["seconds"],
                         tr.stats["factorizations"], err, msh))
            log(rows[-1])
    # the defaults, exactly as a caller gets them (mesh built by simulate)
    t = time.perf_counter()
    default = bf.simulate(pump, None, 1.0, start=start, points_per_revolution=360)
    default_total = time.perf_counter() - t
    defaults = dict(seconds=default.stats["seconds"], total=default_total,
                    error=abs(default.smallest_film - h_ref) / h_ref, nodes=int(default.stats["dofs"]),
                    factorizations=default.stats["factorizations"], settings=_default_settings())
    log(("defaults", defaults))
    # the periodic start at the default mesh: the default rtol against the next looser one
    periodic = []
    for rtol in (1e-4, 1e-5):
        t = time.perf_counter()
        tr = bf.simulate(pump, None, 1.0, start="periodic", rtol=rtol, points_per_revolution=360)
        periodic.append(dict(rtol=rtol, turns=tr.periodic_iterations, seconds=time.perf_counter() - t,
                             error=abs(tr.smallest_film - h_ref) / h_ref, nfev=tr.stats["nfev"]))
        log(("periodic", periodic[-1]))
    return dict(rows=rows, h_ref=h_ref, ref_nodes=fine.n_nodes, mesh_s=mesh_s, ref_turns=ref.periodic_iterations,
                defaults=defaults, periodic=periodic, designs=designs(pump, log))


#: Integrator settings compared across designs: the default and the cheap explicit ones.
DESIGN_METHODS = [("LSODA", 1e-5), ("LSODA", 1e-4), ("RK23", 1e-3), ("RK23", 1e-4)]


def designs(pump, log=print) -> list[dict]:
    """Time-integration error of the smallest film on other designs than the shipped pump.

    The shoe without its pocket and both with a thinner oil (viscosity
    divided by 3 and by 6: thinner films), each on its default mesh (P2,
    0.2 R0) against LSODA at rtol 1e-9 on the same mesh from the same steady
    start: the error is the integrator's alone (the mesh error is the
    table's above).
    """
    import dataclasses

    plain = dataclasses.replace(pump, surface=bf.Surface(arc=pump.surface.arc, half_width=pump.surface.half_width))
    out = []
    for shoe, base in (("pocket", pump), ("plain", plain)):
        for thin in (1, 3, 6):
            p = dataclasses.replace(base, viscosity=base.viscosity / thin)
            mesh = bf.transient.pump_mesh(p, 0.2, order=2)
            ref = bf.simulate(p, mesh, 1.0, rtol=1e-9, atol=1e-12, points_per_revolution=360)
            row = dict(shoe=shoe, viscosity=p.viscosity, h_ref=ref.smallest_film / p.clearance, runs=[])
            for method, rtol in DESIGN_METHODS:
                tr = bf.simulate(p, mesh, 1.0, method=method, rtol=rtol, points_per_revolution=360)
                row["runs"].append(dict(method=method, rtol=rtol, nfev=tr.stats["nfev"],
                                        error=abs(tr.smallest_film - ref.smallest_film) / ref.smallest_film))
            log(("design", row))
            out.append(row)
    return out


def _default_settings() -> str:
    import inspect

    sig = inspect.signature(bf.simulate).parameters
    return ", ".join(f"{k}={sig[k].default!r}" for k in ("element", "mesh_size", "rtol", "atol", "method"))


def report(res: dict) -> tuple[str, dict]:
    """The page's markdown and the numbers the summary quotes."""
    rows, h_ref, d = res["rows"], res["h_ref"], res["defaults"]
    lines = [
        "# Benchmark: one revolution of the pump transient",
        "",
        f"Machine: {platform.processor() or platform.machine()}, Python {platform.python_version()}; "
        "`benchmarks/pump_revolution.py`.",
        f"Pump: `mechanisms/eccentric_pump.toml` (10 % central pocket). Reference: P2 on a curved mesh of "
        f"size 0.03 R0 ({res['ref_nodes']} nodes, meshed in {res['mesh_s']:.2f} s), LSODA rtol 1e-9, periodic "
        f"start ({res['ref_turns']} turns): smallest film {h_ref * 1e6:.4f} um.",
        "Error: |min h_min - reference| / reference over one turn from the same start (1-degree sampling).",
        f"Time: integration of one revolution (all factorizations), sparse solver "
        f"`{bf.DEFAULT_SOLVER}` (the default); mesh and output post-processing excluded.",
        "",
        "| element | mesh size [R0] | nodes | method | rtol | s / revolution | factorizations | h_min error |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for element, size, n, method, rtol, sec, fac, err, _ in rows:
        lines.append(f"| {element} | {size} | {n} | {method} | {rtol:.0e} | {sec:.3f} | {fac} | {err:.2e} |")
    ok = [r for r in rows if r[7] < 1e-3]
    facts = {"pump_defaults_error": d["error"], "pump_defaults_seconds": d["seconds"]}
    if ok:
        best = min(ok, key=lambda r: r[5])
        facts.update(pump_best_seconds=best[5], pump_best=f"{best[0]} on {best[1]} R0, {best[3]} rtol {best[4]:.0e}")
        lines += ["", f"Cheapest run within 0.1 % of the converged smallest film: {best[0]} on mesh {best[1]} R0 "
                  f"({best[2]} nodes), {best[3]} rtol {best[4]:.0e}: **{best[5]:.3f} s per revolution** "
                  f"(error {best[7]:.1e})."]
    else:
        facts.update(pump_best_seconds=float("nan"), pump_best="none")
        lines += ["", "No case reached 0.1 % of the converged smallest film."]
    lines += ["", f"`simulate()` defaults ({d['settings']}; mesh built by `simulate`, {d['nodes']} nodes): "
              f"error {d['error']:.1e} "
              f"({'within' if d['error'] < 1e-3 else 'NOT within'} 0.1 %), {d['seconds']:.3f} s per revolution "
              f"({d['factorizations']} factorizations; {d['total']:.2f} s with meshing, hydrostatic check and "
              "output post-processing)."]
    for r in res.get("periodic", []):
        lines += ["", f"Periodic start with the default mesh at rtol {r['rtol']:.0e} (`simulate(pump, start="
                  f"'periodic', rtol={r['rtol']:.0e})`): {r['turns']} revolutions before the output revolution, "
                  f"{r['nfev']} right-side evaluations, {r['seconds']:.2f} s in all, smallest-film error "
                  f"{r['error']:.1e} against the converged reference."]
    if res.get("designs"):
        head = [f"{m} {r:.0e}" for m, r in DESIGN_METHODS]
        lines += ["", "Integrator error across designs (the smallest film over one turn from the steady start, "
                  "P2 on the default 0.2 R0 mesh, against LSODA rtol 1e-9 on the same mesh: the integrator's "
                  "error alone; right-side evaluations in brackets):", "",
                  "| shoe | viscosity [Pa s] | smallest film [c] | " + " | ".join(head) + " |",
                  "|---|---|---|" + "---|" * len(head)]
        for d in res["designs"]:
            lines.append(f"| {d['shoe']} | {d['viscosity']:.3g} | {d['h_ref']:.3f} | "
                         + " | ".join(f"{r['error']:.1e} ({r['nfev']})" for r in d["runs"]) + " |")
        worst = {f"{m} {r:.0e}": max(d["runs"][k]["error"] for d in res["designs"])
                 for k, (m, r) in enumerate(DESIGN_METHODS)}
        lines += ["", "Worst over these designs: " + ", ".join(f"{k}: {v:.1e}" for k, v in worst.items()) + "."]
    p1 = [r for r in rows if r[0] == "P1"]
    p2 = [r for r in rows if r[0] == "P2"]
    if p1 and p2:
        best_p1, worst_p1 = min(r[7] for r in p1), max(r[7] for r in p1)
        best_p2, worst_p2 = min(r[7] for r in p2), max(r[7] for r in p2)
        lines += ["", f"P1 errors on these meshes: {best_p1:.1e} to {worst_p1:.1e}; P2 (curved): {best_p2:.1e} "
                  f"to {worst_p2:.1e}"
                  + ("; every P2 run is more accurate than every P1 run." if worst_p2 < best_p1 else ".")]
    return "\n".join(lines) + "\n", facts


def main(argv=None) -> None:
    text, facts = report(run())
    (ROOT / "docs" / "benchmarks_pump.md").write_text(text)
    (ROOT / "docs" / "benchmarks_pump.json").write_text(json.dumps(facts, indent=1) + "\n")


if __name__ == "__main__":
    main()
