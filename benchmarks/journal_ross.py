"""Journal equilibrium + 8 coefficients against ROSS on ROSS's own plain-journal fixture.

ROSS (``ross-rotordynamics``, :class:`ross.bearings.plain_journal.PlainJournal`) is not a dependency of
this package: it runs in its own Python environment, given by ``--ross-python`` or the environment
variable ``ROSS_PYTHON`` (e.g. a venv made with ``python -m venv ross-venv && ross-venv/bin/pip install
ross-rotordynamics``). Without one, the ROSS numbers recorded by the last run with ROSS
(``docs/benchmarks_parts/journal_ross.json``) are reused, and the page says so.

The fixture (ROSS's ``tests/test_plain_journal.py``, ``plain_journal_perturbation``): two 176-degree
pads (axial grooves of 4 degrees at 0 and 180 degrees), L = 0.263144 m, R = 0.2 m, c = 0.195 mm,
900 rpm, 112814.91 N downwards, ISO VG 32 at a reference temperature of 50 degC, its default grid of
11 x 3 elements per pad, the perturbation method. Constructing the ``PlainJournal`` computes the
equilibrium (Nelder-Mead on the thermo-hydro-dynamic forces) and the 8 coefficients: that is what is
timed (best of ``repeat`` after one warm-up construction that compiles ROSS's numba kernels). ROSS's
error at its default grid is its change from its own finer grids (22 x 6, 44 x 12).

This package solves the same bearing isothermally (ROSS's only model is thermo-hydro-dynamic, whose
film heats up): at the viscosity of ROSS's ISO VG 32 law (``mu = a T^b`` through its 40 and 100 degC
points) at the 50 degC reference temperature, so the numbers differ by the thermal effect; the
comparison is of the time of the same job at equal discretization accuracy (each against its own
converged answer). Ours: ``equilibrium(..., element="P2", structured=True, size=h, rupture_size=r)``
then ``dynamic_coefficients``, best of three, errors against P2 on a gmsh mesh of size ``REF_SIZE``.
Error measure as in part ``journal``: max(relative eps error, max |K - K_ref| / max |K_ref|,
max |C - C_ref| / max |C_ref|).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import time

import numpy as np

from bearingfe.bearings.journal import JournalBearing, _mesh, dynamic_coefficients, equilibrium

from .common import DOCS, md_table

#: ROSS's fixture in SI.
LENGTH = 10.3600055944 * 0.0254
RADIUS = 0.2
CLEARANCE = 1.95e-4
RPM = 900.0
LOAD = 112814.91
PAD_ARC = 176.0
#: ROSS's ISO VG 32 (``ross.bearings.lubricants``): dynamic viscosity at 40 and 100 degC [Pa s] (reyn x 6894.757).
MU_40, MU_100 = 4.05640e-06 * 6894.757293168, 6.76911e-07 * 6894.757293168
T_REF = 50.0
REF_SIZE = 0.035
RUNS = [dict(size=0.4), dict(size=0.3), dict(size=0.3, rupture_size=0.1), dict(size=0.3, rupture_size=0.05),
        dict(size=0.2, rupture_size=0.04)]
ROSS_GRIDS = ((11, 3), (22, 6), (44, 12))
TARGET = 1e-3

ROSS_SCRIPT = r"""
import json, sys, time, warnings
warnings.filterwarnings("ignore")
from ross.bearings.plain_journal import PlainJournal
from ross.units import Q_
import ross
grids, repeat = json.loads(sys.argv[1]), int(sys.argv[2])
def make(nc, na):
    return PlainJournal(n=3, axial_length=Q_(10.3600055944, "in"), journal_radius=0.2, radial_clearance=1.95e-4,
        elements_circumferential=nc, elements_axial=na, n_pad=2, pad_arc_length=176, preload=0, geometry="circular",
        reference_temperature=50, frequency=Q_([900], "RPM"), fxs_load=0, fys_load=-112814.91,
        groove_factor=[0.52, 0.48], lubricant="ISOVG32", sommerfeld_type=2, initial_guess=[0.1, -0.1],
        method="perturbation", operating_type="flooded", oil_supply_pressure=0, oil_flow_v=Q_(37.86, "l/min"))
make(*grids[0])  # warm-up: numba compiles ROSS's kernels on the first construction
out = {"version": ross.__version__, "grids": {}}
for k, (nc, na) in enumerate(grids):
    times = []
    for _ in range(repeat if k == 0 else 1):
        t = time.perf_counter(); b = make(nc, na); times.append(time.perf_counter() - t)
    out["grids"][f"{nc}x{na}"] = dict(seconds=min(times), times=times, eq=[float(v) for v in b.equilibrium_pos],
        K=[[float(b.kxx[0]), float(b.kxy[0])], [float(b.kyx[0]), float(b.kyy[0])]],
        C=[[float(b.cxx[0]), float(b.cxy[0])], [float(b.cyx[0]), float(b.cyy[0])]])
print("RESULT " + json.dumps(out))
"""


def viscosity() -> float:
    """ROSS's law for its lubricants, ``mu = a T^b`` [T in K] through the 40 and 100 degC points, at ``T_REF``."""
    t40, t100, t = 313.15, 373.15, T_REF + 273.15
    b = math.log(MU_100 / MU_40) / math.log(t100 / t40)
    return MU_40 * (t / t40) ** b


def bearing_and_load() -> tuple[JournalBearing, tuple[float, float], dict]:
    """The fixture as this package's non-dimensional bearing and load (pads centred at 90 and 270 degrees,
    ROSS's ``theta`` measured from +x as ours, ``h = 1 - X cos - Y sin`` in both)."""
    half = math.radians(PAD_ARC / 2)
    pads = tuple((math.radians(c) - half, math.radians(c) + half) for c in (90.0, 270.0))
    mu, omega = viscosity(), RPM * 2 * math.pi / 60
    w = LOAD * CLEARANCE**2 / (mu * omega * RADIUS**4)
    return (JournalBearing(LENGTH / (2 * RADIUS), pads=pads), (0.0, -w),
            dict(viscosity=mu, omega=omega, load=w, length_ratio=LENGTH / (2 * RADIUS)))


def run_ross(python: str | None, repeat: int = 3, log=print) -> dict:
    """ROSS's timings and answers on :data:`ROSS_GRIDS`: run in ``python`` or, without one, the recorded ones."""
    if python:
        r = subprocess.run([python, "-c", ROSS_SCRIPT, json.dumps(ROSS_GRIDS), str(repeat)], capture_output=True,
                           text=True, timeout=3600)
        line = next((l for l in r.stdout.splitlines() if l.startswith("RESULT ")), None)
        if line is None:
            raise RuntimeError(f"ROSS run failed: {(r.stderr or r.stdout).strip().splitlines()[-3:]}")
        out = json.loads(line[len("RESULT "):])
        out["source"] = f"run now ({python})"
        return out
    stored = DOCS / "benchmarks_parts" / "journal_ross.json"
    if stored.exists() and "ross" in json.loads(stored.read_text()):
        out = json.loads(stored.read_text())["ross"]
        out["source"] = f"recorded by the run of {out.get('date', '?')} (no ROSS interpreter given now)"
        return out
    raise RuntimeError("no ROSS interpreter (--ross-python or ROSS_PYTHON) and no recorded ROSS run")


def _ross_error(grid: dict, ref: dict) -> float:
    eps, eps_r = grid["eq"][0], ref["eq"][0]
    K, C, Kr, Cr = (np.asarray(grid["K"]), np.asarray(grid["C"]), np.asarray(ref["K"]), np.asarray(ref["C"]))
    return float(max(abs(eps - eps_r) / eps_r, np.abs(K - Kr).max() / np.abs(Kr).max(),
                     np.abs(C - Cr).max() / np.abs(Cr).max()))


def _solve(bearing, load, **options):
    _mesh.cache_clear()
    eq = equilibrium(bearing, load, **options)
    return eq, dynamic_coefficients(eq)


def _error(run, ref) -> float:
    (eq, dc), (eq_r, dc_r) = run, ref
    return float(max(abs(eq.eps - eq_r.eps) / eq_r.eps, np.max(np.abs(dc.K - dc_r.K)) / np.max(np.abs(dc_r.K)),
                     np.max(np.abs(dc.C - dc_r.C)) / np.max(np.abs(dc_r.C))))


def run(quick: bool = False, log=print, ross_python: str | None = None) -> dict:
    load_start = list(os.getloadavg())
    ross = run_ross(ross_python or os.environ.get("ROSS_PYTHON"), repeat=1 if quick else 3, log=log)
    ross.setdefault("date", time.strftime("%Y-%m-%d %H:%M"))
    log(f"journal_ross ROSS: {ross}")
    bearing, load, info = bearing_and_load()
    ref_size = 0.07 if quick else REF_SIZE
    ref = _solve(bearing, load, element="P2", size=ref_size)
    ours = []
    for options in RUNS[:2] if quick else RUNS:
        best = math.inf
        for _ in range(3):
            t = time.perf_counter()
            eq, dc = _solve(bearing, load, element="P2", structured=True, **options)
            best = min(best, time.perf_counter() - t)
        ours.append(dict(options=options, seconds=best, error=_error((eq, dc), ref), eps=eq.eps,
                         attitude=eq.attitude, nodes=sum(m.n_nodes for m in eq.meshes)))
        log(f"journal_ross ours {ours[-1]}")
    K, C = dynamic_coefficients(ref[0]).to_si(viscosity=info["viscosity"], speed=info["omega"], radius=RADIUS,
                                              clearance=CLEARANCE)
    return dict(ross=ross, ours=ours, info=info, ref_size=ref_size, ref_eps=ref[0].eps,
                ref_attitude=ref[0].attitude, ref_K=K.tolist(), ref_C=C.tolist(),
                load=load_start + list(os.getloadavg()))


def _label(options: dict) -> str:
    return f"size {options['size']}" + (f", rupture_size {options['rupture_size']}" if "rupture_size" in options
                                        else ", no rupture refinement")


def report(res: dict) -> tuple[str, dict]:
    ross, ours, info = res["ross"], res["ours"], res["info"]
    grids = ross["grids"]
    names = list(grids)
    finest = grids[names[-1]]
    default = grids[names[0]]
    ross_error = _ross_error(default, finest)
    lines = [f"ROSS {ross.get('version', '?')} (`PlainJournal`, {ross['source']}) on its own plain-journal test fixture "
             "against this package on the same bearing (`benchmarks/journal_ross.py`, which says what each side "
             f"solves). L/D = {info['length_ratio']:.4f}, two {PAD_ARC:g}-degree pads, non-dimensional load "
             f"{info['load']:.4f} (viscosity {info['viscosity']:.5g} Pa s, ROSS's ISO VG 32 at {T_REF:g} degC). "
             f"Load average at start and end: {', '.join(f'{x:.2f}' for x in res['load'])}.", ""]
    rows = [[f"ROSS {k} elements per pad", v["seconds"], v["eq"][0], math.degrees(v["eq"][1]),
             _ross_error(v, finest) if k != names[-1] else "(its reference)"] for k, v in grids.items()]
    lines.append(md_table(["run", "s (equilibrium + 8 coefficients)", "eps", "position angle [deg]",
                           f"error against ROSS {names[-1]}"], rows))
    lines.append("")
    lines.append(md_table(["this package (P2, structured)", "nodes", "s", "eps", "error against P2 gmsh "
                           f"{res['ref_size']}"], [[_label(o["options"]), o["nodes"], o["seconds"], o["eps"], o["error"]]
                                                  for o in ours]))
    lines.append("")
    kr, cr = np.asarray(res["ref_K"]), np.asarray(res["ref_C"])
    kd, cd = np.asarray(default["K"]), np.asarray(default["C"])
    lines += [f"This package's converged isothermal answer: eps {res['ref_eps']:.4f}, attitude {res['ref_attitude']:.2f} deg, "
              f"K = [[{kr[0, 0]:.4g}, {kr[0, 1]:.4g}], [{kr[1, 0]:.4g}, {kr[1, 1]:.4g}]] N/m, C = [[{cr[0, 0]:.4g}, "
              f"{cr[0, 1]:.4g}], [{cr[1, 0]:.4g}, {cr[1, 1]:.4g}]] N s/m; ROSS's (thermo-hydro-dynamic, default grid): "
              f"eps {default['eq'][0]:.4f}, K = [[{kd[0, 0]:.4g}, {kd[0, 1]:.4g}], [{kd[1, 0]:.4g}, {kd[1, 1]:.4g}]], "
              f"C = [[{cd[0, 0]:.4g}, {cd[0, 1]:.4g}], [{cd[1, 0]:.4g}, {cd[1, 1]:.4g}]] (the thermal model thins the "
              "oil: a larger eps).", ""]
    facts = {"ross": {k: v for k, v in ross.items() if k != "source"}, "ross_default_error": ross_error,
             "ross_seconds": default["seconds"]}
    for name, target in (("ross_accuracy", ross_error), ("1e-03", TARGET)):
        ok = [o for o in ours if o["error"] <= target]
        if not ok:
            lines.append(f"- error <= {target:.1e}: not reached by this package's runs.")
            facts[name] = None
            continue
        best = min(ok, key=lambda o: o["seconds"])
        speedup = default["seconds"] / best["seconds"]
        facts[name] = dict(seconds=best["seconds"], speedup=speedup, label=_label(best["options"]))
        what = (f"ROSS's own accuracy at its default grid ({target:.1e}, its change to {names[-1]})"
                if name == "ross_accuracy" else f"{target:.0e}")
        lines.append(f"- error <= {what}: this package {best['seconds']:.3g} s ({_label(best['options'])}, error "
                     f"{best['error']:.1e}) against ROSS's {default['seconds']:.3g} s at its default grid: "
                     f"**{speedup:.1f}x** faster (goal 5x: {'met' if speedup >= 5 else 'NOT met'}).")
    lines.append("")
    return "\n".join(lines), facts


if __name__ == "__main__":
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ross-python", default=None)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    print(report(run(args.quick, ross_python=args.ross_python))[0])
