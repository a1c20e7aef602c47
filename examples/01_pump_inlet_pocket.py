r"""Plunger shoe of an eccentric radial-plunger pump: plain surface against a 10 %-area inlet pocket.

Reference: paper 004 (Tokar', Krioni, Dangyan, *On the dynamics of the support
of eccentric pumps*, 1978; see ``docs/papers.md``), the swinging-plunger
support of an eccentric pump; formulation in ``docs/formulations.md``.

The shoe (bore radius R0 + c) rides on the eccentric; in the shoe frame the
film is ``h = 1 + gamma cos(psi - delta)`` and the Reynolds equation

    div(h^3 grad p) = 6 (1 - phi2') dh/dpsi + 12 (gamma' cos(psi - delta) + gamma delta' sin(psi - delta))

holds with ``p = 0`` on the outline and ``p = p_s(beta)`` (chamber pressure)
on the pocket. Neglecting the plunger's inertia, the film force balances the
plunger force ``F = P(beta) pi d^2/4 + preload`` at every shaft angle
(paper eq. 13-14): a 2x2 linear system for ``(gamma', delta')``, integrated
over the cycle. The paper reports that a pocket of 10 % of the surface raised
the smallest film over the cycle by almost 40 % (its pump's data are not
printed; ``mechanisms/eccentric_pump.toml`` is a representative pump).

Run::

    PYTHONPATH=. python examples/01_pump_inlet_pocket.py [out_dir] [--size 0.08] [--sweep]

It runs both designs with the settings of the main scene ``scenes/pump.toml``
(through its ``simulate_design``: the gain printed is the one the scene
prints and ``docs/papers.md`` quotes; ``--size`` changes the mesh), prints
the ratio of smallest films and the gain, writes ``pump_inlet_pocket.csv`` and
``pump_inlet_pocket.png`` into ``out_dir`` (default ``examples/output/01_pump_inlet_pocket/``), and checks
its own result: ratio > 1 and a closed mass balance.
"""

from __future__ import annotations

import argparse
import os
import dataclasses
import math
from pathlib import Path

import numpy as np

import bearingfe as bf

ROOT = Path(__file__).resolve().parents[1]
#: This example's own output folder (next to it, whatever the working directory).
OUT = Path(__file__).resolve().parent / "output" / Path(__file__).stem


def designs(pump: bf.EccentricPump) -> dict[str, bf.EccentricPump]:
    """The shipped pump (central 10 % pocket) and the same shoe without the pocket."""
    s = pump.surface
    return {"plain": dataclasses.replace(pump, surface=bf.Surface(arc=s.arc, half_width=s.half_width)),
            "pocket 10 %": pump}


def scene_run() -> dict:
    """The ``[run]`` settings of the main scene ``scenes/pump.toml`` (mesh, element, tolerance, start)."""
    from bearingfe.scenes import load_scene
    from bearingfe.scenes.pump import settings

    scene = ROOT / "scenes" / "pump.toml"
    data, label = load_scene(scene)
    return settings(data, label, scene.parent)["run"]


def run(size: float | None = None) -> dict[str, bf.Trajectory]:
    """Both designs with the main scene's settings (its mesh size unless ``size`` [R0] is given): the same
    computation as ``bearingfe run scenes/pump.toml``, so the gain printed is the documented one."""
    from bearingfe.scenes.pump import simulate_design

    settings = scene_run()
    if size is not None:
        settings["mesh_size"] = size
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    return {name: simulate_design(p, settings)[1] for name, p in designs(pump).items()}


def sweep(size: float | None = None) -> list[tuple[str, float, float, str]]:
    """Pocket place and size: (label, balance ratio, smallest film [m], status) per design.

    Circular pockets at the shoe centre of 5, 10 and 15 % of the area, and
    10 % pockets moved up- and downstream by 0.3 rad (the eccentric slides
    towards +psi under the shoe); the main scene's settings, as :func:`run`.
    """
    from bearingfe.scenes.pump import simulate_design

    settings = scene_run()
    if size is not None:
        settings["mesh_size"] = size
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    s = pump.surface
    cases = [("plain", ())]
    for frac in (0.05, 0.10, 0.15):
        cases.append((f"centre {frac:.0%}", (bf.Circle((0.0, 0.0), math.sqrt(frac * s.area / math.pi)),)))
    r10 = math.sqrt(0.10 * s.area / math.pi)
    cases += [("upstream 10 %", (bf.Circle((-0.3, 0.0), r10),)), ("downstream 10 %", (bf.Circle((0.3, 0.0), r10),))]
    rows = []
    for label, inlets in cases:
        p = dataclasses.replace(pump, surface=bf.Surface(arc=s.arc, half_width=s.half_width, inlets=inlets))
        mesh = bf.transient.pump_mesh(p, settings["mesh_size"], order=2 if settings["element"] == "P2" else 1)
        ratio = bf.balance_ratio(p, mesh)
        try:
            tr = simulate_design(p, settings)[1]
            rows.append((label, ratio, tr.smallest_film, tr.status))
        except bf.LiftOffError:
            rows.append((label, ratio, math.nan, "lift-off"))
    return rows


def write_csv(runs: dict[str, bf.Trajectory], path: Path) -> None:
    """Both trajectories in one table, headers ``"name [unit]"`` (SI, angles in degrees)."""
    import pandas as pd
    from bearingfe.transient.trajectory import report_columns

    scale = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml").scale  # the same for both designs
    frames = [pd.DataFrame(report_columns(tr, scale)).assign(design=name) for name, tr in runs.items()]
    pd.concat(frames).to_csv(path, index=False)


def plot(runs: dict[str, bf.Trajectory], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(7, 8))
    for name, tr in runs.items():
        deg = np.degrees(tr.beta)
        axes[0].plot(deg, tr.h_min * 1e6, label=name)
        axes[1].plot(deg, tr.gamma, label=name)
        axes[2].plot(deg, np.degrees(tr.delta), label=name)
    for ax, lab in zip(axes, ("smallest film h_min [um]", "eccentricity gamma [-]", "attitude delta [deg]")):
        ax.set_ylabel(lab)
        ax.grid(True, alpha=0.3)
    axes[0].legend()
    axes[2].set_xlabel("shaft angle beta [deg] (discharge 0-180)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None) -> float:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", nargs="?", default=os.environ.get("BEARINGFE_OUT", str(OUT)),
                        help="output folder (default examples/output/01_pump_inlet_pocket/, or $BEARINGFE_OUT)")
    parser.add_argument("--size", type=float, default=None,
                        help="mesh size [R0] (default: the main scene's, scenes/pump.toml)")
    parser.add_argument("--sweep", action="store_true", help="also sweep pocket place and size")
    args = parser.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    runs = run(args.size)
    for name, tr in runs.items():
        print(f"{name:12s} smallest film {tr.smallest_film * 1e6:6.3f} um  balance ratio "
              f"{tr.stats['balance_ratio']:.3f}  mass balance {tr.mass_balance_relative:.1e}  "
              f"periodic in {tr.periodic_iterations} turns  {tr.stats['seconds']:.1f} s")
    from bearingfe.scenes.pump import pocket_gain

    gain = pocket_gain(runs["pocket 10 %"], runs["plain"])
    ratio = 1.0 + gain
    print(f"ratio of smallest films (pocket / plain): {ratio:.4f}, pocket gain {100 * gain:+.0f} %  "
          "(paper 004: almost +40 % for its pump)")
    write_csv(runs, out / "pump_inlet_pocket.csv")
    plot(runs, out / "pump_inlet_pocket.png")
    assert all(tr.status == "completed" for tr in runs.values())
    assert ratio > 1.0, "the 10 % pocket should raise the smallest film of this pump"
    assert max(tr.mass_balance_relative for tr in runs.values()) < 1e-3
    if args.sweep:
        rows = sweep(args.size)
        plain = rows[0][2]
        print("design            balance  h_min [um]  vs plain")
        for label, br, h, status in rows:
            print(f"{label:16s}  {br:6.3f}   {h * 1e6:8.3f}   {h / plain:6.3f}  {status}")
    return ratio


if __name__ == "__main__":
    # under the test runner (BEARINGFE_OUT set) the command line is the runner's, not ours
    main([] if "BEARINGFE_OUT" in os.environ else None)
