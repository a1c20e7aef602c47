"""Numbers behind the hard-case tests (``tests/test_hard_cases.py``), for the report.

The tests assert bounds; this module prints the measured values they bound.
"""

from __future__ import annotations

import math

import numpy as np

import bearingfe as bf
from bearingfe.reynolds import operators

from .common import md_table


def eccentricity_rows() -> list[list]:
    rows = []
    for gamma in (0.99, 0.995):
        for arc, name in (((-1.0, 1.0), "partial 2 rad"), ((0.0, 2 * math.pi), "full 2 pi")):
            thin = 0.5 * (arc[0] + arc[1])
            film = bf.CosineFilm(gamma, thin + math.pi)
            out = []
            for size in (0.1, 0.05):
                def graded(phi, z, size=size):
                    return size * np.clip(np.sqrt(0.25 * (phi - thin) ** 2 + 1 - gamma) / 0.5, 0.02, 1.0)
                mesh = bf.mesh_surface(bf.Surface(arc=arc, half_width=0.5), size, order=2, size_function=graded)
                pi = bf.solve_reynolds(mesh, film, element="P2", formulation="pi")
                d = bf.solve_reynolds(mesh, film, element="P2", formulation="direct")
                out.append((pi, d, mesh.n_nodes))
            (pi0, d0, n0), (pi1, d1, n1) = out
            rel = lambda a, b: float(np.linalg.norm(a - b) / np.linalg.norm(b))
            rows.append([gamma, name, n0, rel(pi0.force, d0.force), rel(d0.force, d1.force),
                         rel(pi1.force, d1.force), d1.max_pressure, pi1.notes == ()])
    return rows


def long_domain_rows() -> list[list]:
    surface = bf.Surface(arc=(-math.pi, math.pi), half_width=3.0)
    film = bf.CosineFilm(0.9, math.pi)
    ref_mesh = bf.mesh_surface(surface, 0.1, order=2)
    ref = bf.solve_reynolds(ref_mesh, film, element="P2", formulation="direct").force
    rows = []
    for size in (1.2, 0.6, 0.3):
        for element in ("P1", "P2"):
            mesh = bf.mesh_surface(surface, size, order=2 if element == "P2" else 1)
            ops = operators(mesh, element)
            h = film.thickness(ops.x[0], ops.x[1])
            d_max = float(np.max(0.75 * (3 * h**2 - 4 * h + 1 - film.gamma**2) / h**2))
            pi = bf.solve_reynolds(mesh, film, element=element, formulation="pi")
            d = bf.solve_reynolds(mesh, film, element=element, formulation="direct")
            err = lambda f: float(np.linalg.norm(f - ref) / np.linalg.norm(ref))
            rows.append([size, element, mesh.n_nodes, ops.eigen_bound - d_max, pi.coercivity, pi.formulation,
                         err(pi.force), err(d.force)])
    return rows


def curved_p2_rows() -> tuple[list[list], dict]:
    surface = bf.Surface(arc=(-0.6, 0.6), half_width=0.5, inlets=(bf.Circle((0.0, 0.0), 0.2),))
    film = bf.CosineFilm(0.0)
    ref = bf.solve_reynolds(bf.mesh_surface(surface, 0.0125, order=2), film, element="P2", wedge=0.0,
                            inlet_pressure=1.0).integral
    sizes = (0.1, 0.05, 0.025)
    rows, slopes = [], {}
    for order in (1, 2):
        errs = []
        for size in sizes:
            r = bf.solve_reynolds(bf.mesh_surface(surface, size, order=order), film, element="P2", wedge=0.0,
                                  inlet_pressure=1.0)
            errs.append(abs(r.integral / ref - 1))
        slopes[order] = float(np.polyfit(np.log(sizes), np.log(errs), 1)[0])
        rows.append([f"order {order}"] + errs + [slopes[order]])
    return rows, slopes


def corner_rows() -> list[list]:
    eps = 1e-9
    surface = bf.Surface(arc=(-0.6, 0.6), half_width=0.5,
                         inlets=(bf.Rectangle((0.0, 0.0), (0.48 + 2 * eps, 0.4 + 2 * eps)),))
    film = bf.CosineFilm(0.5, math.pi)
    reference = 508.7522  # case (b) reference (P2 direct curved graded), see above
    rows = []
    for corner in (0.05, 0.025, 0.0125, 0.00625, 0.003125):
        mesh = bf.mesh_surface(surface, 0.05, corner_size=corner, grading_distance=0.15)
        r = bf.solve_reynolds(mesh, film, element="P1", inlet_pressure=1000.0)
        rows.append([corner, mesh.n_nodes, abs(r.force[0] / reference - 1)])
    return rows


def report() -> str:
    parts = ["Each case is a test in `tests/test_hard_cases.py` (fast sizes, run in CI); these are the values "
             "those tests bound.", ""]
    parts += ["**Eccentricity 0.99 / 0.995, no cavitation** (P2, curved, graded toward the gap; size 0.1 and "
              "0.05): relative load differences as error estimates.", ""]
    parts.append(md_table(["gamma", "arc", "nodes (0.1)", "pi vs direct (0.1)", "direct 0.1 vs 0.05",
                           "pi vs direct (0.05)", "max p", "pi kept (no fallback)"], eccentricity_rows()))
    parts += ["", "**Long domain, pi operator** (arc 2 pi, half-width 3, gamma 0.9; error vs P2 direct on a "
              "size-0.1 mesh). 'bound - max D' < 0 means the cheap eigenvalue bound cannot decide; the exact "
              "shift-invert check then gives the smallest eigenvalue:", ""]
    parts.append(md_table(["size", "element", "nodes", "bound - max D", "exact lambda_min", "used",
                           "load error pi", "load error direct"], long_domain_rows()))
    rows, slopes = curved_p2_rows()
    parts += ["", "**P2 on a curved (circular) pocket**, load error of `int p` against a fine curved P2 "
              "reference, at sizes 0.1, 0.05, 0.025, and the fitted log-log slope:", ""]
    parts.append(md_table(["geometry", "err 0.1", "err 0.05", "err 0.025", "slope"], rows))
    parts += ["", "**Rectangular recess corners** (case (b), P1, element size 0.05 elsewhere, corner size "
              "varied): relative error of the load:", ""]
    parts.append(md_table(["corner size", "nodes", "load error"], corner_rows()))
    parts.append("")
    return "\n".join(parts)
