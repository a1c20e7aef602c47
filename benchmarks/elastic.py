"""Elastic support (EHD) of the pump shoe: validation, cost, and whether the pocket's gain survives.

1. The half-space compliance against Love's closed form (uniform 32 MPa on the 60 x 40 mm shoe,
   steel on steel): deflection at the centre and at a corner.
2. The coupled film ``h = h_rigid + C p`` (Newton) under refinement: a pump-like state (gamma 0.6,
   32 MPa pocket, Swift-Stieber) on curved P2 meshes, with the Richardson estimate of the limit.
3. Cost: building the compliance (dense, exact integrals) and applying it, and one pump revolution
   rigid against elastic (quasi-static ``simulate(elastic=)`` and the model with the deflection's
   squeeze, :func:`bearingfe.transient.elastic.simulate_elastic`).
4. The headline: smallest film over the periodic revolution, rigid against elastic, with and without
   the 10 % pocket (P2, mesh 0.15 R0, cavitation "none" as in the main scene).

Writes ``docs/elastic.md`` and ``docs/elastic.json`` (the numbers the page quotes; the test
``tests/test_elastic_docs.py`` checks the page against them and recomputes the cheap ones). Run:
``PYTHONPATH=. python benchmarks/elastic.py`` (``--quick``: coarse meshes, for a check of the script).
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import json
import math
import platform
import time
from pathlib import Path

import numpy as np

import bearingfe as bf
from bearingfe.elastic import (combined_modulus, half_space, influence_matrix, rectangle_deflection,
                               block_compliance, solve_elastic)
from bearingfe.transient.elastic import simulate_elastic
from bearingfe.core.linalg import dense_threads
from benchmarks.run_all import OtherLoad

ROOT = Path(__file__).resolve().parents[1]


def love(pump) -> dict:
    """Deflection under uniform discharge pressure on the whole shoe: the compliance against Love."""
    sc, e_star = pump.scale, combined_modulus(pump.shoe_material, pump.eccentric_material)
    plain = bf.Surface(arc=pump.surface.arc, half_width=pump.surface.half_width)
    mesh = bf.mesh_surface(plain, 0.1)
    a, b = pump.surface.arc[1] * sc.radius, pump.surface.half_width * sc.radius
    out = {"modulus_Pa": e_star, "pressure_Pa": pump.cycle.discharge}
    for name, (phi, z) in (("centre", (0.0, 0.0)), ("corner", (pump.surface.arc[1], pump.surface.half_width))):
        G, _ = influence_matrix(mesh, "P2", np.array([[phi], [z]]))
        w = float(G.sum()) * pump.cycle.discharge * sc.radius / (math.pi * e_star)
        ref = pump.cycle.discharge / (math.pi * e_star) * float(rectangle_deflection(phi * sc.radius,
                                                                                     z * sc.radius, a, b))
        out[name] = {"computed_um": w * 1e6, "love_um": ref * 1e6, "relative_error": abs(w - ref) / ref}
    return out


def convergence(pump, sizes) -> dict:
    sc = pump.scale
    film, ps = bf.CosineFilm(0.6, math.pi), sc.from_pressure(pump.cycle.discharge)
    rows = []
    for size in sizes:
        mesh = bf.transient.pump_mesh(pump, size, order=2)
        t0 = time.perf_counter()
        C = half_space(mesh, sc, (pump.shoe_material, pump.eccentric_material), "P2")
        t1 = time.perf_counter()
        sol = solve_elastic(mesh, film, C, inlet_pressure=ps, element="P2", cavitation="reynolds")
        t2 = time.perf_counter()
        rows.append({"size": size, "dofs": C.n_dofs, "force": float(sol.result.force[0]),
                     "max_deflection_um": sc.to_thickness(sol.max_deflection) * 1e6,
                     "h_min_um": sc.to_thickness(sol.result.h_min) * 1e6, "solves": sol.iterations,
                     "build_s": t1 - t0, "solve_s": t2 - t1})
        print(rows[-1], flush=True)
    f = [r["force"] for r in rows]
    order = math.log2(abs(f[1] - f[0]) / abs(f[2] - f[1]))
    limit = f[2] + (f[2] - f[1]) / (2**order - 1)
    return {"rows": rows, "order": order, "limit": limit}


def _hmin_diff(a, b, clearance: float) -> tuple[float, float]:
    """Largest difference of two runs' smallest film over the samples, and of their minima [c]."""
    return (float(np.max(np.abs(a.h_min - b.h_min))) / clearance,
            abs(a.smallest_film - b.smallest_film) / clearance)


def revolution_cost(pump, size: float, full: bool = True) -> dict:
    """One revolution rigid against elastic (squeeze model), each from its own periodic state.

    Elastic: the fast defaults, the settings before the fast path (LSODA with the raw pressures to 1e-8,
    rtol 1e-6, threaded BLAS) and a tight reference (LSODA, rtol 1e-8) that the accuracy is measured on.
    """
    import bearingfe.transient.elastic as et

    mesh = bf.transient.pump_mesh(pump, size, order=2)
    C = half_space(mesh, pump.scale, (pump.shoe_material, pump.eccentric_material), "P2")
    rigid = bf.simulate(pump, mesh, 1.0, start="periodic", element="P2")
    t0 = time.perf_counter()
    rigid1 = bf.simulate(pump, mesh, 1.0, start=rigid.start, element="P2")
    rigid_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    periodic = simulate_elastic(pump, C, 1.0, start="periodic")
    periodic_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    fast = simulate_elastic(pump, C, 1.0, start=periodic)
    fast_s = time.perf_counter() - t0
    if not full:
        return {"size": size, "dofs": C.n_dofs, "rigid_s": rigid_s, "periodic_s": periodic_s,
                "periodic_iterations": periodic.periodic_iterations,
                "fast": {"s": fast_s, "ratio": fast_s / rigid_s, "steps": fast.stats["steps"]}}
    weight = float(np.abs(C.matrix).sum(axis=1).max())
    threads = et.dense_threads
    et.dense_threads = lambda limit: contextlib.nullcontext()  # the BLAS threads as they were before
    try:
        t0 = time.perf_counter()
        before = simulate_elastic(pump, C, 1.0, start=periodic, method="LSODA", rtol=1e-6, atol=1e-8,
                                  deflection_atol=1e-8 * weight)
        before_s = time.perf_counter() - t0
    finally:
        et.dense_threads = threads
    ref = simulate_elastic(pump, C, 1.0, start=periodic, method="LSODA", rtol=1e-8, atol=1e-10,
                           deflection_atol=1e-9)
    c = pump.clearance
    out = {"size": size, "dofs": C.n_dofs, "rigid_s": rigid_s, "rigid_nfev": rigid1.stats["nfev"],
           "rigid_steps": rigid1.stats["steps"], "periodic_s": periodic_s,
           "periodic_iterations": periodic.periodic_iterations, "smallest_film_um": fast.smallest_film * 1e6,
           "reference_smallest_film_um": ref.smallest_film * 1e6}
    for name, run, secs in (("fast", fast, fast_s), ("before", before, before_s)):
        curve, smallest = _hmin_diff(run, ref, c)
        out[name] = {"s": secs, "nfev": run.stats["nfev"], "steps": run.stats["steps"],
                     "jacobians": run.stats["jacobians"], "factorizations": run.stats["factorizations"],
                     "curve_error_c": curve, "smallest_error_c": smallest, "ratio": secs / rigid_s}
    print(out, flush=True)
    return out


def _apply_seconds(C, repeat: int) -> float:
    """Time of one ``C.deflection`` on one BLAS thread (as the solvers call it)."""
    p = np.random.default_rng(0).random(C.n_dofs)
    with dense_threads(1):
        t0 = time.perf_counter()
        for _ in range(repeat):
            C.deflection(p, 1.0)
        return (time.perf_counter() - t0) / repeat


def dense_sizes(pump, sizes) -> list[dict]:
    """Build and apply cost, memory and spectrum of the dense half-space compliance by mesh size."""
    rows = []
    for size in sizes:
        mesh = bf.transient.pump_mesh(pump, size, order=2)
        t0 = time.perf_counter()
        C = half_space(mesh, pump.scale, (pump.shoe_material, pump.eccentric_material), "P2")
        build = time.perf_counter() - t0
        apply = _apply_seconds(C, 20)
        sv = np.linalg.svd(C.matrix, compute_uv=False)
        ranks = {str(tol): int(np.searchsorted(-sv, -tol * sv[0])) for tol in (1e-1, 1e-2, 1e-3)}
        rows.append({"size": size, "dofs": C.n_dofs, "build_s": build, "apply_s": apply,
                     "matrix_mb": C.matrix.nbytes / 2**20, "transient_mb": 64 * C.n_dofs**2 / 2**20,
                     "ranks": ranks})
        print(rows[-1], flush=True)
    return rows


def cost(pump, size: float) -> dict:
    """Compliance build/apply, the quasi-static model's quarter turn, and the revolutions rigid against elastic."""
    mesh = bf.transient.pump_mesh(pump, size, order=2)
    t0 = time.perf_counter()
    C = half_space(mesh, pump.scale, (pump.shoe_material, pump.eccentric_material), "P2")
    build = time.perf_counter() - t0
    apply = _apply_seconds(C, 100)
    rigid = bf.simulate(pump, mesh, 1.0, start="periodic", element="P2")
    t0 = time.perf_counter()
    rigid1 = bf.simulate(pump, mesh, 1.0, start=rigid.start, element="P2")
    rigid_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    quasi = bf.simulate(pump, mesh, 1.0, start=rigid.start, element="P2", elastic=C)
    quasi_s = time.perf_counter() - t0
    return {"dofs": C.n_dofs, "build_s": build, "apply_s": apply, "rigid_s": rigid_s,
            "quasi_static_s": quasi_s, "quasi_static_nfev": quasi.stats["nfev"],
            "quasi_static_status": quasi.status, "quasi_static_smallest_um": quasi.smallest_film * 1e6,
            "quasi_static_iterations": quasi.stats["factorizations"], "quasi_static_jacobians": quasi.stats["jacobians"]}


def headline(pump, size: float) -> dict:
    plain = dataclasses.replace(pump, surface=bf.Surface(arc=pump.surface.arc, half_width=pump.surface.half_width))
    out = {}
    for name, p in (("pocket", pump), ("plain", plain)):
        mesh = bf.transient.pump_mesh(p, size, order=2)
        C = half_space(mesh, p.scale, (p.shoe_material, p.eccentric_material), "P2")
        rigid = bf.simulate(p, mesh, 1.0, start="periodic", element="P2")
        elastic = simulate_elastic(p, C, 1.0, start="periodic")
        B = block_compliance(mesh, p.scale, p.shoe_material, p.shoe_thickness, counterpart=p.eccentric_material,
                      element="P2")
        body = simulate_elastic(p, B, 1.0, start="periodic")
        kb = int(np.argmin(body.h_min))
        k, ke = int(np.argmin(rigid.h_min)), int(np.argmin(elastic.h_min))
        out[name] = {"rigid_um": rigid.smallest_film * 1e6, "rigid_beta_deg": math.degrees(rigid.beta[k]) % 360,
                     "elastic_um": elastic.smallest_film * 1e6,
                     "elastic_beta_deg": math.degrees(elastic.beta[ke]) % 360,
                     "largest_deflection_um": float(np.max(elastic.max_deflection)) * 1e6,
                     "elastic_status": elastic.status, "periodic_iterations": elastic.periodic_iterations,
                     "elastic_mass_balance": elastic.mass_balance_relative,
                     "body_um": body.smallest_film * 1e6, "body_beta_deg": math.degrees(body.beta[kb]) % 360,
                     "body_deflection_um": float(np.max(body.max_deflection)) * 1e6, "body_status": body.status}
        print(name, out[name], flush=True)
    out["rigid_ratio"] = out["pocket"]["rigid_um"] / out["plain"]["rigid_um"]
    out["elastic_ratio"] = out["pocket"]["elastic_um"] / out["plain"]["elastic_um"]
    out["body_ratio"] = out["pocket"]["body_um"] / out["plain"]["body_um"]
    out["shoe_thickness_mm"] = pump.shoe_thickness * 1e3
    return out


def real_shoe(pump, size: float, rigid: dict) -> dict:
    """Smallest film on the real shoe body of the machine file (gmsh tetrahedra), with and without the pocket."""
    from bearingfe.elastic.shoe import shoe_compliance

    plain = dataclasses.replace(pump, surface=bf.Surface(arc=pump.surface.arc, half_width=pump.surface.half_width))
    out = {}
    for name, p in (("pocket", pump), ("plain", plain)):
        mesh = bf.transient.pump_mesh(p, size, order=2)
        C = shoe_compliance(mesh, p.scale, p.shoe_material, p.shoe_body, counterpart=p.eccentric_material,
                            element="P2")
        run = simulate_elastic(p, C, 1.0, start="periodic")
        k = int(np.argmin(run.h_min))
        out[name] = {"rigid_um": rigid[name]["rigid_um"], "shoe_um": run.smallest_film * 1e6,
                     "shoe_beta_deg": math.degrees(run.beta[k]) % 360,
                     "shoe_deflection_um": float(np.max(run.max_deflection)) * 1e6, "status": run.status,
                     "build_s": C.seconds, "seconds": run.stats["seconds"]}
        print(name, out[name], flush=True)
    out["rigid_ratio"] = out["pocket"]["rigid_um"] / out["plain"]["rigid_um"]
    out["shoe_ratio"] = out["pocket"]["shoe_um"] / out["plain"]["shoe_um"]
    b = pump.shoe_body
    out["body"] = {"thickness_mm": b.thickness * 1e3, "back": b.back, "seat": b.seat,
                   "seat_radius_mm": None if b.seat_radius is None else b.seat_radius * 1e3}
    return out


def shoe_convergence(pump, size: float, body_sizes) -> list:
    """The pocketed shoe's smallest film on the real shoe body as its mesh is refined (film mesh fixed)."""
    from bearingfe.elastic.shoe import shoe_compliance

    mesh = bf.transient.pump_mesh(pump, size, order=2)
    rows = []
    for h in body_sizes:
        C = shoe_compliance(mesh, pump.scale, pump.shoe_material, pump.shoe_body, counterpart=pump.eccentric_material,
                            element="P2", film_size=h, size=2 * h)
        run = simulate_elastic(pump, C, 1.0, start="periodic")
        k = int(np.argmin(run.h_min))
        rows.append({"body_size": h, "film_size": size, "build_s": C.seconds, "shoe_um": run.smallest_film * 1e6,
                     "shoe_beta_deg": math.degrees(run.beta[k]) % 360,
                     "shoe_deflection_um": float(np.max(run.max_deflection)) * 1e6, "status": run.status})
        print(rows[-1], flush=True)
    return rows


def seated_block(pump, sizes) -> list:
    """Compliance energy ``int w`` under a uniform pressure of a flat block clamped on the pump's seat disc
    (and over its whole back), as the body mesh is refined: how fast a seated body converges."""
    from bearingfe.elastic.shoe import ShoeBody
    from bearingfe.elastic.shoe import shoe_compliance

    plain = bf.Surface(arc=pump.surface.arc, half_width=pump.surface.half_width)
    mesh = bf.mesh_surface(plain, 0.2)
    ops = bf.operators(mesh, "P1")
    ones = np.ones(ops.basis.N)
    rows = []
    for h in sizes:
        row = {"body_size": h}
        for name, body in (("seat", ShoeBody(pump.shoe_thickness, seat_radius=pump.shoe_body.seat_radius)),
                           ("whole_back", ShoeBody(pump.shoe_thickness))):
            C = shoe_compliance(mesh, pump.scale, pump.shoe_material, body, flat_film=True, film_size=h, size=2 * h)
            row[name] = float(ones @ ops.mass @ C.deflection(ones))
        rows.append(row)
        print(row, flush=True)
    return rows


def _real_shoe_answer(data: dict) -> str:
    if "shoe" not in data:
        return ""
    sh = data["shoe"]
    return (f"\n\n**On the real shoe body** (its bore, its back and its seat on the plunger: next section) "
            f"**the pocket's gain {_shoe_verdict(sh)}**: the smallest film is {sh['pocket']['shoe_um']:.2f} um "
            f"with the pocket and {sh['plain']['shoe_um']:.2f} um without (pocket / plain {sh['shoe_ratio']:.3f}).")


def _shoe_verdict(sh: dict) -> str:
    return ("survives and grows" if sh["shoe_ratio"] > sh["rigid_ratio"] + 0.05 else
            "survives" if sh["shoe_ratio"] >= sh["rigid_ratio"] - 0.05 else
            "survives only in part" if sh["shoe_ratio"] > 1.05 else "does not survive")


def _real_shoe_section(data: dict) -> str:
    if "shoe" not in data:
        return ""
    sh = data["shoe"]
    b = sh["body"]
    gain = lambda r: 100 * (r - 1)  # noqa: E731
    verdict = _shoe_verdict(sh)
    seat = ("clamped over the whole back" if b["seat_radius_mm"] is None else
            f"held by a {b['seat']} seat of {b['seat_radius_mm']:.1f} mm radius (the plunger's end face)")
    return f"""
## The real shoe body

The shoe of the mechanism file as a 3-D body (`bearingfe.elastic.shoe.shoe_compliance`): the bore (the
film surface, 60 x 40 mm), a {b['back']} back {b['thickness_mm']:.0f} mm behind the bore's apex,
{seat}; gmsh (OpenCASCADE) tetrahedra, P2, {data['size']} R0 on the film and twice that behind it,
condensed to the film dofs, on the eccentric as a half-space. The mechanism file describes the body:
`[shoe] thickness` and `back` ("flat": a slipper block whose back is a plane across the plunger axis,
thicker at the ends of the arc; "concentric": a shell of uniform thickness), `[shoe.seat]` (how the
plunger holds it: `kind = "clamped"` fixes the seat, a shoe bonded to a rigid plunger head;
`"frictionless"` lets the seat slide across the plunger's end face but not into it, the sideways
motion and the spin held only on average over the seat, so the body is held without being
over-constrained; `radius`: the seat disc about the plunger axis) and an optional `[shoe.lining]`
(thickness and material of a bearing lining on the bore). The displacement is measured from the
plunger; the shoe's rigid motion is the film balance's (the eccentricity and attitude of the
transient). Smallest film over the periodic revolution (squeeze model, as above):

| shoe | rigid | real shoe body (angle, largest deflection) |
|---|---|---|
| 10 % pocket | {sh['pocket']['rigid_um']:.2f} um | {sh['pocket']['shoe_um']:.2f} um ({sh['pocket']['shoe_beta_deg']:.0f} deg, {sh['pocket']['shoe_deflection_um']:.2f} um) |
| plain | {sh['plain']['rigid_um']:.2f} um | {sh['plain']['shoe_um']:.2f} um ({sh['plain']['shoe_beta_deg']:.0f} deg, {sh['plain']['shoe_deflection_um']:.2f} um) |
| pocket / plain | {sh['rigid_ratio']:.3f} | {sh['shoe_ratio']:.3f} |

**On the real shoe the pocket's gain {verdict}** ({gain(sh['shoe_ratio']):+.0f} % against {gain(sh['rigid_ratio']):+.0f} %
on rigid surfaces). Unlike the block, the real shoe is held only in its middle (the seat), so its ends
bend open under pressure (under a uniform pressure the opening is largest at the ends of the arc);
why this favours the pocketed shoe over the cycle is not analysed here.
The compliance builds in {sh['pocket']['build_s']:.1f} s; the revolution took {sh['pocket']['seconds']:.0f} s with the pocket
and {sh['plain']['seconds']:.0f} s without (machine load as in the cost section).
Validation of the body (tests/test_shoe_body.py): the flat block clamped at its back matches the tensor-mesh
block within that model's own mesh error; the body approaches the half-space as it grows; the
compliance is reciprocal (`M C` symmetric) to round-off; the deflection under uniform pressure
converges under refinement.
{_shoe_convergence_table(sh)}"""


def _shoe_convergence_table(sh: dict) -> str:
    if "convergence" not in sh:
        return ""
    cv = sh["convergence"]
    rows = "\n".join(f"| {r['body_size']} | {r['build_s']:.1f} | {r['shoe_um']:.3f} | {r['shoe_beta_deg']:.0f} | "
                     f"{r['shoe_deflection_um']:.3f} |" for r in cv)
    diffs = [b["shoe_um"] - a["shoe_um"] for a, b in zip(cv, cv[1:])]
    steps = ", ".join(f"{d:+.3f} um" for d in diffs)
    pace = "hardly shrink" if abs(diffs[-1]) > 0.5 * abs(diffs[0]) else "shrink"
    return f"""
The pocketed shoe as the body mesh is refined (element size on the film face and on the seat's rim,
twice that elsewhere; the film mesh stays at {cv[0]['film_size']} R0):

| body mesh [R0] | compliance [s] | smallest film [um] | at [deg] | largest deflection [um] |
|---|---|---|---|---|
{rows}

The smallest film moves by {steps} per refinement: slowly (the steps {pace}, so these meshes
may not yet be in the asymptotic range: the rim of the seat concentrates the stresses). A seated body
converges slowly: the compliance energy (`int w` under a uniform unit pressure) of a flat
{sh['body']['thickness_mm']:.0f} mm block clamped on a seat disc of the same radius, against the same block clamped over its
whole back, as the body mesh is refined:

| body mesh [R0] | on the seat disc | change | over the whole back | change |
|---|---|---|---|---|
{_seated_rows(sh.get('seated_block', []))}

The body's mesh error at the default size is therefore not bounded by the film's steps above: were
the film to keep moving at that pace over several more refinements, it would reach a few tenths of a
micrometre, still small against the {sh['pocket']['shoe_um'] - sh['plain']['shoe_um']:.2f} um
the pocket adds to the smallest film.
"""


def _seated_rows(rows: list) -> str:
    out = []
    for k, r in enumerate(rows):
        change = (lambda key: f"{100 * (r[key] / rows[k - 1][key] - 1):+.2f} %" if k else "")
        out.append(f"| {r['body_size']} | {r['seat']:.5f} | {change('seat')} | {r['whole_back']:.5f} | "
                   f"{change('whole_back')} |")
    return "\n".join(out)


def page(data: dict) -> str:
    lv, cv, co, hd = data["love"], data["convergence"], data["cost"], data["headline"]
    rv, rv2 = data["revolution"]
    dense = "\n".join(f"| {r['size']} | {r['dofs']} | {r['build_s']:.2f} | {r['apply_s'] * 1e6:.0f} | "
                      f"{r['matrix_mb']:.1f} | {r['transient_mb']:.0f} | {r['ranks']['0.1']} / {r['ranks']['0.01']} / "
                      f"{r['ranks']['0.001']} |" for r in data["dense"])
    def verdict(ratio):
        if ratio >= hd["rigid_ratio"] - 0.05:
            return "survives"
        return "survives only in part" if ratio > 1.05 else "does not survive"
    rows = "\n".join(f"| {r['size']} | {r['dofs']} | {r['force']:.7f} | {r['max_deflection_um']:.4f} | "
                     f"{r['h_min_um']:.4f} | {r['solves']} | {r['build_s']:.2f} | {r['solve_s']:.2f} |"
                     for r in cv["rows"])
    return f"""# Elastic support (EHD): does the pocket's gain survive a deforming shoe at 32 MPa?

Generated by `benchmarks/elastic.py` ({data['machine']}; see the cost section for the machine's load); numbers in `docs/elastic.json`, checked by `tests/test_elastic_docs.py`.
Model: `bearingfe.elastic.coupled` (half-space compliance, coupled film by Newton) and
`bearingfe.transient.elastic` (the pump cycle with the squeeze of the deflection).

## Answer

On the shipped pump (steel shoe on a steel eccentric, E* = {lv['modulus_Pa'] / 1e9:.1f} GPa, P2, mesh
{data['size']} R0, periodic revolution, pressures allowed negative as in the main scene):

| shoe | rigid | half-space (angle, largest deflection) | {hd['shoe_thickness_mm']:.0f} mm block (angle, largest deflection) |
|---|---|---|---|
| 10 % pocket | {hd['pocket']['rigid_um']:.2f} um | {hd['pocket']['elastic_um']:.2f} um ({hd['pocket']['elastic_beta_deg']:.0f} deg, {hd['pocket']['largest_deflection_um']:.2f} um) | {hd['pocket']['body_um']:.2f} um ({hd['pocket']['body_beta_deg']:.0f} deg, {hd['pocket']['body_deflection_um']:.2f} um) |
| plain | {hd['plain']['rigid_um']:.2f} um | {hd['plain']['elastic_um']:.2f} um ({hd['plain']['elastic_beta_deg']:.0f} deg, {hd['plain']['largest_deflection_um']:.2f} um) | {hd['plain']['body_um']:.2f} um ({hd['plain']['body_beta_deg']:.0f} deg, {hd['plain']['body_deflection_um']:.2f} um) |
| pocket / plain | {hd['rigid_ratio']:.3f} | {hd['elastic_ratio']:.3f} | {hd['body_ratio']:.3f} |

Smallest film over the revolution. "Half-space": both surfaces elastic half-spaces
(`bearingfe.elastic.half_space`, the softest estimate). "Block": the shoe as a flat
{hd['shoe_thickness_mm']:.0f} mm steel block clamped over its back (`[shoe] thickness` of the
mechanism file; `bearingfe.elastic.block_compliance`, 3-D linear elasticity condensed to the film dofs)
on the eccentric as a half-space.

**The pocket's gain {verdict(hd['body_ratio'])} on the block** ({100 * (hd['body_ratio'] - 1):+.0f} % against
{100 * (hd['rigid_ratio'] - 1):+.0f} % on rigid surfaces) **and {verdict(hd['elastic_ratio'])} on the half-space**
({100 * (hd['elastic_ratio'] - 1):+.0f} %): the answer depends on how stiff the shoe really is, and the film itself
is much thinner than on rigid surfaces in both.{_real_shoe_answer(data)}

Why: at 32 MPa the surfaces give way by up to {hd['pocket']['largest_deflection_um']:.1f} um (plain shoe: {hd['plain']['largest_deflection_um']:.1f} um), the order
of the film. On rigid surfaces the film is thinnest at the end of the high-pressure phase
({hd['pocket']['rigid_beta_deg']:.0f} deg with the pocket, {hd['plain']['rigid_beta_deg']:.0f} deg without): the discharge load squeezes the film for half a
turn, and the pocket's hydrostatic lift (balance ratio 0.87) takes most of that load off the film,
so the shoe approaches more slowly. On the elastic support the deflection opens the film during
discharge and lets the shoe sit closer to the eccentric for the same film pressure; when the
chamber pressure falls after the inner dead centre the surfaces spring back towards each other
faster than the shoe can lift, and the thinnest film comes right then ({hd['pocket']['elastic_beta_deg']:.0f} deg with the pocket,
{hd['plain']['elastic_beta_deg']:.0f} deg without), limited only by the squeeze of the film between the returning surfaces. That
spring-back is about the same with and without the pocket (the released deflection differs by
{abs(hd['pocket']['largest_deflection_um'] - hd['plain']['largest_deflection_um']):.1f} um), so what the pocket gains during discharge counts for less.

With the block the released deflection is smaller ({hd['pocket']['body_deflection_um']:.1f} um with the pocket,
{hd['plain']['body_deflection_um']:.1f} um without) and the film keeps more of the pocket's gain.

Limits of this answer: the block is clamped over its whole back (the arc's
curvature and the seat on the plunger are left out; the real shoe body, below, has them: a shoe seated
on its plunger's end face bends more); the block is meshed with P1 tetrahedra graded to the film face (size 0.15 R0), which
underestimates its compliance by a few per cent (3 % at the largest deflection under a uniform
pressure when the body mesh is halved twice); the pressure may go negative (no cavitation), as in the source paper's model and the main scene;
isothermal, constant viscosity (no piezoviscosity: at 32 MPa it raises the viscosity by roughly a
factor 2 for mineral oil, which would thicken the film).

The quasi-static model (`simulate(elastic=...)`, the deflection follows the pressure without
squeezing the film) is no answer here: on the plain shoe its film closes just after the inner dead
centre, because without the squeeze of the returning surfaces nothing slows the spring-back.

{_real_shoe_section(data)}
## Range of validity

The compliances are linear small-strain elasticity. Every elastic solve (`solve_reynolds(elastic=)`,
`solve_elastic`) and every elastic transient (`simulate(elastic=)`, `simulate_elastic`) checks its
answer (`bearingfe.core.checks.check_elastic`): a largest film pressure above 1 % of the contact
modulus `E*` (the strain `p/E*`) or a deflection above 1 % of the radius `R0` is an
`OutOfRangeError` naming both numbers, and a deflection above 10 clearances is noted (a warning and
the result's `notes`, or the trajectory's message). A mistyped modulus (`E* = 1e6 Pa` on a steel shoe)
used to give films thousands of clearances thick without a word.

## Validation

Half-space deflection under a uniform {lv['pressure_Pa'] / 1e6:.0f} MPa on the 60 x 40 mm shoe against Love's closed form
(exact influence integrals, so round-off):

| point | computed | Love (1929) | relative error |
|---|---|---|---|
| centre | {lv['centre']['computed_um']:.6f} um | {lv['centre']['love_um']:.6f} um | {lv['centre']['relative_error']:.1e} |
| corner | {lv['corner']['computed_um']:.6f} um | {lv['corner']['love_um']:.6f} um | {lv['corner']['relative_error']:.1e} |

Coupled film (gamma 0.6, delta = pi, 32 MPa pocket, Swift-Stieber) on curved P2 meshes; film force
along phi = 0 converges with observed order {cv['order']:.2f} to {cv['limit']:.7f} (Richardson):

| mesh [R0] | dofs | force [-] | largest deflection [um] | h_min [um] | Reynolds solves | compliance [s] | coupled solve [s] |
|---|---|---|---|---|---|---|---|
{rows}

## Cost

Other processes used {data['other_cores']:.2f} cores while this ran ({'idle machine' if data['other_cores'] < 0.25 else 'SHARED machine: absolute times are inflated, ratios less so'}).
P2, mesh {data['size']} R0 ({co['dofs']} dofs): the compliance (dense, exact integrals) builds in
{co['build_s']:.2f} s and applies in {co['apply_s'] * 1e6:.0f} us (one BLAS thread, as the solvers call it). One revolution of the squeeze model
(`simulate_elastic`) against the rigid one (`simulate`), each from its own periodic state; the film is
compared with a tight reference run (LSODA, rtol 1e-8; smallest film {rv['reference_smallest_film_um']:.4f} um):

| run | seconds | x rigid | right sides | steps | Jacobians | film vs reference, largest [c] | smallest film vs reference [c] |
|---|---|---|---|---|---|---|---|
| rigid (`simulate`, defaults) | {rv['rigid_s']:.2f} | 1 | {rv['rigid_nfev']} | {rv['rigid_steps']} | - | - | - |
| elastic, defaults (BDF, rtol 1e-5, film opening to 1e-5 c, one BLAS thread) | {rv['fast']['s']:.2f} | {rv['fast']['ratio']:.1f} | {rv['fast']['nfev']} | {rv['fast']['steps']} | {rv['fast']['jacobians']} | {rv['fast']['curve_error_c']:.1e} | {rv['fast']['smallest_error_c']:.1e} |
| elastic, settings before the fast path (LSODA, rtol 1e-6, pressures to 1e-8, threaded BLAS) | {rv['before']['s']:.2f} | {rv['before']['ratio']:.1f} | {rv['before']['nfev']} | {rv['before']['steps']} | {rv['before']['jacobians']} | {rv['before']['curve_error_c']:.1e} | {rv['before']['smallest_error_c']:.1e} |

The elastic state is the interior pressure ({co['dofs']} dofs less the outline and pocket), so each
right side costs one product with the dense compliance, one with `K^-1` and sparse products with the
quadrature points (no assembly, no sparse factorization); what made the revolution expensive was the
step count (the integrator controlled the raw pressures) and OpenBLAS threads waiting for each other on
a shared machine. On the finer mesh {rv2['size']} R0 ({rv2['dofs']} dofs) a revolution costs
{rv2['fast']['s']:.2f} s against {rv2['rigid_s']:.2f} s rigid ({rv2['fast']['ratio']:.1f} x): the dense
Jacobian (`n^3`) starts to count. The periodic start (Anderson mixing of the revolutions) took
{rv['periodic_iterations']} revolutions, {rv['periodic_s']:.1f} s. The quasi-static model
(`simulate(elastic=)`: at each right side the coupled film and the rates by a chord Newton,
`bearingfe.elastic.coupled.ChordBalance`, whose dense Jacobian is kept over the iterations and the right sides)
took {co['quasi_static_s']:.2f} s for a revolution from the rigid periodic state against {co['rigid_s']:.2f} s rigid
({co['quasi_static_s'] / co['rigid_s']:.1f} x; {co['quasi_static_nfev']} right sides, {co['quasi_static_iterations']} coupled residuals, {co['quasi_static_jacobians']} Jacobians
built; {co['quasi_static_status']}, smallest film {co['quasi_static_smallest_um']:.2f} um).

### Dense compliance by mesh size

| mesh [R0] | dofs | build [s] | apply [us] | matrix [MB] | transient [MB] | rank for 10 % / 1 % / 0.1 % |
|---|---|---|---|---|---|---|
{dense}

"Transient": what `simulate_elastic` holds (about 64 n^2 bytes: the compliance, `K^-1`, the Jacobian
and the integrator's Newton matrix and factors). "Rank": singular values of the compliance above that
fraction of the largest; a truncated (low-rank) compliance with a spectral error of 1 % would keep that
many modes. The singular values fall to 10 % within a few dozen modes but to 1 % only near the full
rank on every mesh (the kernel `1/r` is singular, so the fine pressure modes keep their share of the
deflection): a truncation with a useful error bound keeps almost everything, and compression does not
pay at these sizes. Dense is used up to the `compliance` limit of
`bearingfe.core.limits` (4000 dofs: a 122 MB matrix, about 1 GB in the transient); beyond it `half_space`,
`block_compliance`, `solve_elastic`, `balance_load` and `simulate_elastic` refuse a dense compliance with a `LimitError` that
names `BEARINGFE_MAX_COMPLIANCE` (raise it for one run if the memory is there). The quasi-static solves
need no dense matrix on a uniform grid: `bearingfe.elastic.half_space_fft` (P1 on `grid_mesh` with uniform
lines, the `"half-space-fft"` row of `COMPLIANCES`) holds the same half-space as its FFT product, and
`solve_elastic` and `balance_load` then run matrix-free (Newton-Krylov), with no size limit. On any
other mesh (gmsh, curved P2) `half_space_grid` (`"half-space-grid"`) does the same through an auxiliary
uniform grid, an approximation of the dense map of second order in the grid spacing. Their cost from 1e3
to 1e5 unknowns, and the grid transfer's difference from the dense map, are the `elastic_fft` part of
[benchmarks.md](benchmarks.md). `simulate_elastic` (the deflection's squeeze) takes them too: `K^-1` and the
integrator's Newton matrix are then solved by GMRES with a two-level preconditioner instead of the explicit
inverse and the dense Jacobian (the same run as the dense path to the inner tolerance; about the dense
run's time at 2700 unknowns, several times slower at 1000, and not capped; timed in the same part).
"""


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--shoe-only", action="store_true",
                        help="recompute only the real shoe body's part, keep the rest of docs/elastic.json")
    args = parser.parse_args(argv)
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    size = 0.3 if args.quick else 0.15
    if args.shoe_only:
        data = json.loads((ROOT / "docs" / "elastic.json").read_text())
        data["shoe"] = real_shoe(pump, data["size"], data["headline"])
        data["shoe"]["convergence"] = shoe_convergence(pump, data["size"], (0.15, 0.1, 0.075))
        data["shoe"]["seated_block"] = seated_block(pump, (0.14, 0.1, 0.07, 0.05, 0.035))
        (ROOT / "docs" / "elastic.json").write_text(json.dumps(data, indent=1))
        (ROOT / "docs" / "elastic.md").write_text(page(data))
        return
    other = OtherLoad()
    data = {"machine": f"{platform.processor() or platform.machine()}, Python {platform.python_version()}",
            "size": size, "love": love(pump),
            "convergence": convergence(pump, (0.3, 0.2, 0.15) if args.quick else (0.16, 0.08, 0.04)),
            "cost": cost(pump, size), "headline": headline(pump, size)}
    data["shoe"] = real_shoe(pump, size, data["headline"])
    data["shoe"]["convergence"] = shoe_convergence(pump, size, (0.3, 0.2) if args.quick else (0.15, 0.1, 0.075))
    data["shoe"]["seated_block"] = seated_block(pump, (0.2, 0.14) if args.quick else (0.14, 0.1, 0.07, 0.05, 0.035))
    data["revolution"] = [revolution_cost(pump, size), revolution_cost(pump, 0.2 if args.quick else 0.08, full=False)]
    data["dense"] = dense_sizes(pump, (0.3, 0.2) if args.quick else (0.3, 0.15, 0.08))
    data["other_cores"] = other.cores()
    (ROOT / "docs" / "elastic.json").write_text(json.dumps(data, indent=1))
    (ROOT / "docs" / "elastic.md").write_text(page(data))


if __name__ == "__main__":
    main()
