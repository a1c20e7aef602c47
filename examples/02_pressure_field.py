r"""Pressure under a shoe with a central inlet pocket: the picture and two checks.

The film between the eccentric (radius R0) and the shoe bored to R0 + c is

    h = 1 + gamma cos(phi - phi0),
    div(h^3 grad p) = 6 dh/dphi   on the film,  p = 0 on the outline,  p = p_s on the pocket,

in the unwrapped plane (phi [rad], z = Z/R0), p = P c^2/(mu omega R0^2).

1. Hydrostatic check. With a circular outline r_o, a concentric pocket r_i
   and a uniform film (gamma = 0, no motion) the pressure is
   p = p_s ln(r_o/r)/ln(r_o/r_i) and the load (pocket included) is
   W = pi p_s (r_o^2 - r_i^2) / (2 ln(r_o/r_i))
   (Hamrock, Schmid & Jacobson, Fundamentals of Fluid Film Lubrication, ch. 6).

2. The default shoe: arc [-0.5, 0.5] rad, a = 0.4, a central circular pocket
   of 10 % of the surface (r = sqrt(0.08/pi)) at p_s = 2, gamma = 0.6,
   phi0 = 0.3. Converged reference (P2 on curved second-order meshes of
   size 0.02, 0.01, 0.005, changes below 3e-8 between the last two):
   force int p cos(phi) = 0.5836022, int p = 0.5954357,
   pocket flow 3.705373 [omega R0^2 c].

Set BEARINGFE_QUICK=1 for a coarse mesh and BEARINGFE_OUT for the output
directory (default ``examples/output/02_pressure_field/``, next to this file).
"""

import math
import os
from pathlib import Path

import bearingfe as bf
from bearingfe.plot.fields import pressure_picture
from bearingfe.plot.maps import Panel, field_panels

QUICK = os.environ.get("BEARINGFE_QUICK") == "1"
OUT = Path(os.environ.get("BEARINGFE_OUT") or Path(__file__).resolve().parent / "output" / Path(__file__).stem)
OUT.mkdir(parents=True, exist_ok=True)
SIZE = 0.08 if QUICK else 0.02
TOL = 5e-4 if QUICK else 1e-5  # relative; measured errors 1e-4 (quick) and 1e-6
R_POCKET = math.sqrt(0.08 / math.pi)

# 1. Annular hydrostatic pad against the closed form.
r_o, p_s = 0.4, 2.0
pad = bf.Surface(outer=bf.Circle((0.0, 0.0), r_o), inlets=[bf.Circle((0.0, 0.0), R_POCKET)])
res = bf.solve_reynolds(bf.mesh_surface(pad, SIZE, order=2), bf.CosineFilm(0.0), wedge=0.0,
                        inlet_pressure=p_s, element="P2")
W = math.pi * p_s * (r_o**2 - R_POCKET**2) / (2 * math.log(r_o / R_POCKET))
print(f"annular pad: int p = {res.integral:.6f}, closed form {W:.6f}")
assert abs(res.integral - W) < TOL * W

# 2. The pocketed shoe with a hydrodynamic wedge.
shoe = bf.Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[bf.Circle((0.0, 0.0), R_POCKET)])
mesh = bf.mesh_surface(shoe, SIZE, order=2)
res = bf.solve_reynolds(mesh, bf.CosineFilm(gamma=0.6, phi0=0.3), wedge=1.0, inlet_pressure=p_s, element="P2")
print(f"shoe: force = {res.force}, int p = {res.integral:.6f}, pocket flow = {res.flows['inlet']:.6f}, "
      f"h_min = {res.h_min:.4f}, mass balance = {res.mass_balance:.2e}")
assert abs(res.force[0] - 0.5836022) < TOL * 0.5836022
assert abs(res.integral - 0.5954357) < TOL * 0.5954357
assert abs(res.flows["inlet"] - 3.705373) < TOL * 3.705373

# maps over phi [deg] and z [R0] (non-dimensional: no scales here; the scenes' [scale] gives SI), the P2
# field sampled on a refined display mesh; the wrapped view on the shoe's cylinder
title = f"shoe, gamma = 0.6, p_s = {p_s:g}: p_max = {res.max_pressure:.3g} [mu omega R0^2/c^2]"
field_panels([[Panel(res, "pressure", 1.0, "mu omega R0^2/c^2", radius=None, title=title, surface=shoe)]],
             OUT / "02_pressure.png")
field_panels([[Panel(res, "film", 1.0, "c", radius=None, title=f"shoe, gamma = 0.6: h_min = {res.h_min:.3f} c",
                     surface=shoe)]], OUT / "02_film.png")
pressure_picture(res, OUT / "02_pressure_wrapped.png", view="wrapped", warp=0.15, surface=shoe, title=title)
for name in ("02_pressure.png", "02_pressure_wrapped.png", "02_film.png"):
    print("wrote", OUT / name)
