r"""A thrust bearing: tilting pads against fixed taper-land pads, and a check against the wide-pad optimum.

1. The infinitely wide inclined slider at its optimum film ratio K = 2.1887 carries the classic load
   coefficient W h_out^2/(mu U L^2 B) = 6/(K-1)^2 (ln K - 2 (K-1)/(K+1)) = 0.16024: the package's pad,
   periodic across the sliding, meets it to 1e-3 (Richardson over two meshes).
2. Six 45-degree pads (100/200 mm) on a collar at 3000 rpm, 30 mPa s, from 5 to 40 kN: tilting pads on
   point pivots at 0.6 of the pad angle against fixed pads with a 20 um taper over 70 % of the angle.
   The smallest film and the power loss against load, and the axial stiffness of both at 20 kN.

Set BEARINGFE_QUICK=1 for coarse meshes and BEARINGFE_OUT for the output directory
(default ``examples/output/06_thrust/``, next to this file).
"""

import math
import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import bearingfe as bf  # noqa: E402
from bearingfe.bearings.thrust import axial_coefficients, load_curve  # noqa: E402

QUICK = os.environ.get("BEARINGFE_QUICK") == "1"
OUT = Path(os.environ.get("BEARINGFE_OUT") or Path(__file__).resolve().parent / "output" / Path(__file__).stem)


def wide_slider_load(size: float, K: float) -> float:
    surface = bf.Surface(arc=(-math.pi, math.pi), half_width=0.5, periodic=True, runner=bf.Translating(math.pi / 2))
    film = bf.TaperFilm(K, 1.0, start=-0.5, end=0.5, direction=math.pi / 2)
    return bf.solve_reynolds(bf.mesh_surface(surface, size), film, formulation="direct").integral / (2 * math.pi)


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    # 1. the wide inclined slider at its optimum
    K = 2.1887
    exact = 6.0 / (K - 1) ** 2 * (math.log(K) - 2 * (K - 1) / (K + 1))
    coarse, fine = wide_slider_load(0.1, K), wide_slider_load(0.05, K)
    richardson = fine + (fine - coarse) / 3
    print(f"wide inclined slider, K = {K}: load coefficient {richardson:.5f} (exact {exact:.5f})")
    assert abs(richardson / exact - 1) < 1e-3

    # 2. six pads: tilting against fixed taper-land
    scale = bf.Scale(radius=0.1, clearance=20e-6, viscosity=0.03, speed=2 * math.pi * 3000 / 60)
    tilting = bf.ThrustPad(0.05, 0.1, math.radians(45), n_pads=6, pivot_offset=0.6)
    fixed = bf.ThrustPad(0.05, 0.1, math.radians(45), n_pads=6, pivot_offset=0.5,
                         profile=((0.0, 20e-6), (0.7, 0.0), (1.0, 0.0)))
    order, size = (1, 0.1) if QUICK else (2, 0.05)
    element = "P1" if QUICK else "P2"
    loads = np.linspace(5e3, 40e3, 4 if QUICK else 8)
    curves = {}
    for name, pad, pivot in (("tilting pads", tilting, "point"), ("taper-land pads", fixed, None)):
        mesh = pad.mesh(size, order=order)
        curves[name] = load_curve(pad, mesh, scale, loads, pivot=pivot, element=element, cavitation="reynolds")
        at = load_curve(pad, mesh, scale, [20e3], pivot=pivot, element=element, cavitation="reynolds")[0]
        k = axial_coefficients(pad, mesh, scale, at, pivot=pivot, element=element, cavitation="reynolds")
        print(f"{name} at 20 kN: smallest film {at.h_min * 1e6:.2f} um, power loss {at.power:.0f} W, "
              f"k_zz {k.k_zz:.3g} N/m, c_zz {k.c_zz:.3g} N s/m")
        assert at.h_min > 0 and k.k_zz > 0 and k.c_zz > 0

    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for name, curve in curves.items():
        left.plot(loads / 1e3, [p.h_min * 1e6 for p in curve], "o-", label=name)
        right.plot(loads / 1e3, [p.power for p in curve], "s-", label=name)
    left.set_xlabel("axial load [kN]")
    left.set_ylabel("smallest film [um]")
    right.set_xlabel("axial load [kN]")
    right.set_ylabel("power loss [W]")
    for ax in (left, right):
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.suptitle("six 45-degree pads, 100/200 mm, 3000 rpm, 30 mPa s")
    fig.tight_layout()
    path = OUT / "06_thrust.png"
    fig.savefig(path, dpi=90)
    print("wrote", path)


if __name__ == "__main__":
    main()
