r"""A tilting-pad journal bearing: equilibrium, coefficients against whirl frequency, a rotor's stability.

1. Someya's four-pad bearing (L/D 0.5, 80-degree pads, centred pivots, no preload, load between pads):
   at eccentricity 0.5 the Journal-Bearing Databook (1989) gives S = 0.756, K = 1.94, B = 3.33
   (synchronous, K C/W and B C omega/W); the package's converged values are 0.7578, 1.912, 3.408
   (docs/tilting_pad_validation.md: the table is matched to 0.3 %, 1.5 % and 2.4 %).
2. A five-pad bearing in SI units carrying half of an 800 kg rigid rotor: the shaft's position and the
   pads' rotations, the synchronous and non-synchronous coefficients, and the rotor's stability map
   (log decrement against speed). Massless pads carry their load through the pivots and have no
   cross-coupled stiffness: the rotor is stable at every speed (Lund's threshold is infinite).

Set BEARINGFE_QUICK=1 for coarse meshes and BEARINGFE_OUT for the output directory
(default ``examples/output/05_tilting_pad/``, next to this file).
"""

import math
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import bearingfe as bf  # noqa: E402
from bearingfe.bearings.stability import log_decrement_map, lund_threshold  # noqa: E402
from bearingfe.bearings.tilting_pad import (pad_assembly_coefficients, tilting_pad_equilibrium,  # noqa: E402
                                            tilting_pad_meshes)

QUICK = os.environ.get("BEARINGFE_QUICK") == "1"
OUT = Path(os.environ.get("BEARINGFE_OUT") or Path(__file__).resolve().parent / "output" / Path(__file__).stem)
REFINE = 0 if QUICK else 2  # pad element size 0.1 or 0.025
TOL_S, TOL_K, TOL_B = 0.02, 0.02, 0.04  # against the table: measured 0.3 % (0.1 % quick), 1.5 %, 2.4 %

def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    # 1. Someya's row: find the load that puts the shaft at eps 0.5 (the secant method on log W).
    someya = bf.TiltingPadGeometry(0.5, n_pads=4, arc=math.radians(80), offset=0.5, preload=0.0)
    meshes = tilting_pad_meshes(someya, 0.1, refine=REFINE)
    logs, misses, eq = [math.log(0.5), 0.0], [], None
    for log_w in logs:
        eq = tilting_pad_equilibrium(someya, (0.0, -math.exp(log_w)), meshes=meshes, start=eq)
        misses.append(eq.eps - 0.5)
    while abs(misses[-1]) > 1e-8:
        logs.append(logs[-1] - misses[-1] * (logs[-1] - logs[-2]) / (misses[-1] - misses[-2]))
        eq = tilting_pad_equilibrium(someya, (0.0, -math.exp(logs[-1])), meshes=meshes, start=eq)
        misses.append(eq.eps - 0.5)
    red = pad_assembly_coefficients(eq).reduced()
    print(f"Someya, eps 0.5: S = {eq.sommerfeld:.4f} (table 0.756), K = {red.K[1, 1]:.3f} (1.94), "
          f"B = {red.C[1, 1]:.3f} (3.33)")
    assert abs(eq.sommerfeld / 0.756 - 1) < TOL_S
    assert abs(red.K[1, 1] / 1.94 - 1) < TOL_K and abs(red.C[1, 1] / 3.33 - 1) < TOL_B

    # 2. Five pads, 60 degrees, offset 0.6, preload 0.25, in SI.
    bearing = bf.TiltingPadBearing(radius=0.05, length=0.05, pad_clearance=80e-6, n_pads=5, arc=math.radians(60),
                                   offset=0.6, preload=0.25, pad_inertia=2e-5, pad_thickness=0.012)
    mu, mass, g = 0.015, 800.0, 9.81
    load = mass * g / 2
    geometry = bearing.geometry
    pad_meshes = tilting_pad_meshes(geometry, 0.1, refine=0 if QUICK else 1)
    cache = {}


    def state(speed):
        if speed not in cache:
            w = load / bearing.force_scale(mu, speed)
            previous = cache[max(cache)][0] if cache else None
            eq = tilting_pad_equilibrium(geometry, (0.0, -w), meshes=pad_meshes, start=previous)
            cache[speed] = (eq, pad_assembly_coefficients(eq))
        return cache[speed]


    speed = 2 * math.pi * 100.0  # 6000 rpm
    eq5, full = state(speed)
    print(f"5 pads at 6000 rpm: eps = {eq5.eps:.4f}, attitude = {eq5.attitude:.3g} deg, S = {eq5.sommerfeld:.4f}, "
          f"pad rotations {np.round(eq5.tilts, 4).tolist()} [C_p]")
    sync = full.reduced(1.0, pad_mass=bearing.pad_mass(mu, speed))
    K, C = sync.to_si(viscosity=mu, speed=speed, radius=bearing.radius, clearance=bearing.pad_clearance)
    print(f"synchronous K [N/m] {K.round(-3).tolist()}, C [N s/m] {C.round(1).tolist()}")
    assert math.isinf(lund_threshold(full.reduced())[0])  # no cross-coupled stiffness: never unstable

    speeds = 2 * math.pi * np.linspace(20.0, 200.0, 4 if QUICK else 10)
    delta = log_decrement_map(speeds, lambda s: state(s)[1], lambda s: bearing.pad_clearance * s**2 / g)
    print("log decrement against speed:", np.round(delta, 3).tolist())
    assert np.all(delta > 0)

    # the picture: the pads' pressure (unwrapped, each pad on its own arc) and the stability map
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7))
    for state_i, mesh, q in zip(eq5.pads.states, pad_meshes, eq5.tilts):
        if state_i is None:  # an unloaded pad
            continue
        res = state_i.results[0]
        p = np.asarray(res.pressure)[: mesh.mesh.nvertices]
        art = top.tripcolor(np.degrees(mesh.mesh.p[0]), mesh.mesh.p[1], mesh.mesh.t.T, p, shading="gouraud",
                            cmap="viridis", vmin=0.0, vmax=max(float(s.results[0].pressure.max())
                                                               for s in eq5.pads.states if s is not None))
        top.text(np.degrees(mesh.mesh.p[0].mean()), geometry.length_ratio * 1.1, f"q = {q:.3f}", ha="center")
    for start, end in geometry.arcs:
        top.add_patch(plt.Rectangle((math.degrees(start), -geometry.length_ratio), math.degrees(end - start),
                                    2 * geometry.length_ratio, fill=False, lw=0.8))
    top.set_xlim(-120, 260)
    top.set_ylim(-0.7, 0.75)
    top.set_xlabel("angle [deg]")
    top.set_ylabel("z = Z/R")
    top.set_title("pad pressure P C_p^2/(mu omega R^2) at 6000 rpm")
    fig.colorbar(art, ax=top)
    bottom.fill_between(speeds * 30 / math.pi, 0.0, delta, color="tab:green", alpha=0.6)
    bottom.plot(speeds * 30 / math.pi, delta, "o-", color="tab:green")
    bottom.set_xlabel("speed [rpm]")
    bottom.set_ylabel("smallest log decrement")
    bottom.set_title("rigid 800 kg rotor on two such bearings")
    fig.tight_layout()
    path = OUT / "05_tilting_pad.png"
    fig.savefig(path, dpi=90)
    print("wrote", path)


if __name__ == "__main__":
    main()
