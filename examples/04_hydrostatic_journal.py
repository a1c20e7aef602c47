r"""A four-recess hydrostatic journal fed through capillaries: load, flow and stiffness against eccentricity.

The journal (R0 = 25 mm, c = 25 um, L/D = 1, oil 0.03 Pa s, not turning) is carried by four
pads of 86 deg separated by axial drain grooves of 4 deg (at ambient pressure). Each pad has a
central rectangular recess fed from a 5 MPa supply through its own capillary, sized so that the
concentric recess sits at beta = p_r/p_s = 0.5 (the stiffest ratio of a capillary-fed recess).
The journal is displaced towards 270 deg, between two recesses. The pads are alike, so one
mesh serves all four: pad k, centred at phi_k, sees the film ``h = 1 + e cos(phi + phi_k - 90 deg)``
in its own frame.

Checks (printed, and asserted):

1. Concentric, each recess sits at beta = 0.5 and its restrictor flow equals its film flow: the
   capillary was sized from the pad's own computed film conductance, so this checks the balance
   (1e-9 on the flows, 1e-3 on beta).
2. The load grows linearly at small eccentricity: the secant W/e at the smallest eccentricity
   (0.05) equals the stiffness there within 0.5 % (the curvature of W(e) over 0.05 c).
3. For comparison only (not a reference: the film is not uniform over a pad of 86 deg), the
   flat-pad estimate of two opposed pads' stiffness ``2 A_eff 3 beta (1 - beta) p_s / c``
   (``A_eff = W/p_r`` of one concentric pad; Rowe, *Hydrostatic, Aerostatic and Hybrid Bearing
   Design*, 2012, ch. 5) is printed next to the computed one: the curved pads are about 19 % softer.
4. The journal's 2x2 stiffness and damping at the smallest eccentricity with each recess responding
   through its capillary and its compressible oil (:func:`bearingfe.journal_dynamics`,
   recesses 0.5 mm deep), at a few frequencies of the motion: at omega -> 0 the stiffness along the
   load axis is the one of check 2 (1e-4: the two difference steps), and the damping falls from the slow
   motion's (the restrictors' share) towards the held recesses' squeeze film as the pockets' oil stiffens.

Set BEARINGFE_QUICK=1 for a coarse mesh and BEARINGFE_OUT for the output directory (default
``examples/output/04_hydrostatic_journal/``, next to this file).
"""

import math
import os
from pathlib import Path

import numpy as np

import bearingfe as bf

QUICK = os.environ.get("BEARINGFE_QUICK") == "1"
OUT = Path(os.environ.get("BEARINGFE_OUT") or Path(__file__).resolve().parent / "output" / Path(__file__).stem)
OUT.mkdir(parents=True, exist_ok=True)

SCALE = bf.Scale(radius=0.025, clearance=25e-6, viscosity=0.03, speed=1.0)  # speed: 1 rad/s, the journal still
PS = 5e6
GROOVE = math.radians(4.0)
PAD = math.pi / 2 - GROOVE
DISC = bf.Discretization(element="P2", formulation="direct")
SIZE = 0.12 if QUICK else 0.05
ECCENTRICITY = np.linspace(0.05, 0.6, 4 if QUICK else 12)
#: the film h = 1 + e cos(phi - LOAD_AXIS) is thickest at 90 deg: the journal is displaced towards 270 deg (between
#: two recesses) and the film pushes it back towards 90 deg
LOAD_AXIS = math.pi / 2
CENTRES = [math.pi / 4 + k * math.pi / 2 for k in range(4)]
#: frequencies of the journal's motion for its dynamic coefficients [rad/s]
FREQUENCIES = (0.0, 100.0, 1000.0, 10000.0)
DEPTH = 0.5e-3  # recess depth [m]: its oil volume is its area times this


def pad_mesh() -> bf.SupportMesh:
    recess = bf.Rectangle((0.0, 0.0), (0.6 * PAD, 0.6))
    surface = bf.Surface(arc=(-PAD / 2, PAD / 2), half_width=1.0, inlets=(recess,))
    return bf.mesh_surface(surface, SIZE, inlet_size=SIZE / 2, order=2)


def capillary(mesh: bf.SupportMesh, beta: float) -> bf.Capillary:
    """The capillary that puts a concentric recess at ``beta``: its conductance is the film's times beta/(1 - beta)."""
    unit = bf.solve_reynolds(mesh, bf.UniformFilm(1.0), wedge=0.0, inlet_pressure=1.0, discretization=DISC)
    film_si = SCALE.to_flow(unit.flows["inlet"]) / SCALE.to_pressure(1.0)  # m^3/s per Pa
    kc = film_si * beta / (1 - beta)
    d = 0.5e-3
    return bf.Capillary(diameter=d, length=math.pi * d**4 / (128 * SCALE.viscosity * kc), supply_pressure=PS)


def journal(mesh, cap, e: float):
    """The four pads at eccentricity ``e`` away from LOAD_AXIS: the load carried [N] (the film's push on the
    journal along LOAD_AXIS), flow [m^3/s], recess ratios, and the stiffness d(load)/d(displacement) [N/m]."""
    force, flow, ratios, stiff = np.zeros(2), 0.0, [], 0.0
    for centre in CENTRES:
        st = bf.supply_stiffness(mesh, lambda x, c=centre: bf.CosineFilm(x, LOAD_AXIS - c), e, cap, SCALE,
                                 step=min(1e-3, e / 2), discretization=DISC)
        c, s = math.cos(centre), math.sin(centre)
        rot = np.array([[c, -s], [s, c]])  # pad frame -> global
        force += rot @ st.result.force
        axis = np.array([math.cos(LOAD_AXIS), math.sin(LOAD_AXIS)])
        stiff += axis @ (rot @ st.force_stiffness)
        flow += st.result.total_flow
        ratios.append(st.result.pockets[0].ratio)
    # force = int p (cos, sin) points from the journal's centre into the film; the film pushes the journal
    # the other way, towards LOAD_AXIS: the load it carries is -force . axis
    load = -force @ np.array([math.cos(LOAD_AXIS), math.sin(LOAD_AXIS)])
    return load, flow, np.array(ratios), stiff


def main() -> None:
    mesh = pad_mesh()
    cap = capillary(mesh, 0.5)
    concentric = bf.solve_supplied(mesh, bf.UniformFilm(1.0), cap, SCALE, discretization=DISC)
    pocket = concentric.pockets[0]
    print(f"concentric recess: beta = {pocket.ratio:.5f}, flow {pocket.film_flow * 6e4:.4f} l/min "
          f"(restrictor {pocket.restrictor_flow * 6e4:.4f})")
    assert abs(pocket.ratio - 0.5) < 1e-3
    assert abs(pocket.restrictor_flow / pocket.film_flow - 1) < 1e-9
    area = concentric.load / pocket.pressure  # effective area of one pad [m^2]
    rows = [journal(mesh, cap, e) for e in ECCENTRICITY]
    load = np.array([r[0] for r in rows])
    flow = np.array([r[1] for r in rows])
    ratios = np.array([r[2] for r in rows])
    stiff = np.array([r[3] for r in rows])
    k0 = 2 * area * 3 * 0.5 * 0.5 * PS / SCALE.clearance
    print(f"stiffness at e = {ECCENTRICITY[0]:.2f}: {stiff[0] / 1e6:.2f} N/um; flat-pad estimate "
          f"{k0 / 1e6:.2f} N/um ({stiff[0] / k0 - 1:+.1%}); secant W/e {load[0] / (ECCENTRICITY[0] * SCALE.clearance) / 1e6:.2f} N/um")
    assert abs(load[0] / (ECCENTRICITY[0] * SCALE.clearance) / stiff[0] - 1) < 5e-3
    for e, w, q, k, b in zip(ECCENTRICITY, load, flow, stiff, ratios):
        print(f"e = {e:.2f}: load {w:8.1f} N, flow {q * 6e4:.4f} l/min, stiffness {k / 1e6:6.2f} N/um, "
              f"beta {np.round(b, 3)}")
    draw(ECCENTRICITY, load, flow, stiff, ratios, OUT / "hydrostatic_journal.png")
    volume = DEPTH * recess_area(mesh)
    K, C, B = dynamics(mesh, cap, ECCENTRICITY[0], volume)
    axis = np.array([math.cos(LOAD_AXIS), math.sin(LOAD_AXIS)])
    print(f"journal at e = {ECCENTRICITY[0]:.2f}, recesses of {volume * 1e6:.3f} cm^3: held recesses' squeeze "
          f"damping {axis @ B @ axis / 1e3:.2f} N s/mm along the load axis")
    for w, k, c in zip(FREQUENCIES, K, C):
        print(f"  omega {w:7.0f} rad/s: K_xx {k[0, 0] / 1e6:7.2f}, K_yy {k[1, 1] / 1e6:7.2f}, K_xy {k[0, 1] / 1e6:6.2f} "
              f"N/um; C_xx {c[0, 0] / 1e3:7.2f}, C_yy {c[1, 1] / 1e3:7.2f} N s/mm")
    assert abs(axis @ K[0] @ axis / stiff[0] - 1) < 1e-4


def recess_area(mesh: bf.SupportMesh) -> float:
    """The recess's area [m^2] (the mesh's hole: its pocket moment)."""
    from bearingfe.film import operators
    return float(operators(mesh, "P2").pocket_moments[0]) * SCALE.radius**2


def dynamics(mesh, cap, e: float, volume: float):
    """The journal's stiffness [N/m] and damping [N s/m] (F, 2, 2) at eccentricity ``e`` away from LOAD_AXIS, each
    recess responding, and the held recesses' squeeze damping (2, 2): the four pads' coefficients turned into the
    journal's frame and added."""
    K, C, B = np.zeros((len(FREQUENCIES), 2, 2)), np.zeros((len(FREQUENCIES), 2, 2)), np.zeros((2, 2))
    shift = -e * np.array([math.cos(LOAD_AXIS), math.sin(LOAD_AXIS)])  # the journal's centre [c]
    for centre in CENTRES:
        c, s = math.cos(centre), math.sin(centre)
        rot = np.array([[c, -s], [s, c]])  # pad frame -> global
        dyn = bf.journal_dynamics(mesh, rot.T @ shift, cap, SCALE, frequencies=FREQUENCIES,
                                                       volumes=volume, step=min(1e-3, e / 2), discretization=DISC)
        K += rot @ dyn.stiffness @ rot.T
        C += rot @ dyn.damping @ rot.T
        B += rot @ dyn.squeeze_damping @ rot.T
    return K, C, B


def draw(e, load, flow, stiff, ratios, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(9, 6.5), constrained_layout=True)
    axes[0, 0].plot(e, load / 1e3, "o-")
    axes[0, 0].set(xlabel="eccentricity e/c", ylabel="load [kN]", title="load")
    axes[0, 1].plot(e, flow * 6e4, "o-")
    axes[0, 1].set(xlabel="eccentricity e/c", ylabel="flow [l/min]", title="supply flow (four recesses)")
    axes[1, 0].plot(e, stiff / 1e6, "o-")
    axes[1, 0].set(xlabel="eccentricity e/c", ylabel="stiffness [N/um]", title="stiffness dW/de at fixed supply")
    for k in range(ratios.shape[1]):
        axes[1, 1].plot(e, ratios[:, k], "o-" if k < 2 else "x--",  # pairs coincide by symmetry
                        label=f"recess at {math.degrees(CENTRES[k]):.0f} deg")
    axes[1, 1].set(xlabel="eccentricity e/c", ylabel="p_r / p_s", title="recess pressure ratios")
    axes[1, 1].legend(fontsize=8)
    for ax in axes.flat:
        ax.grid(alpha=0.3)
    fig.suptitle("Four-recess hydrostatic journal, capillaries sized for beta = 0.5 (p_s = 5 MPa)")
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    main()
