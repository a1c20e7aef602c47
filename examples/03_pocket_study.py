"""Pocket study for the eccentric pump: area fraction x position along the arc.

Designers place a high-pressure inlet pocket in the shoe surface to carry part
of the load hydrostatically (source paper 004: a pocket of 10 % of the surface
raised the smallest film over the pump cycle by almost 40 % against the plain
surface). This script sweeps the pocket's area fraction ``A_pocket / A_shoe``
and the position of its centroid along the arc, ``s = (phi_c - alpha1) /
(alpha2 - alpha1)``, for the shipped pump (``mechanisms/eccentric_pump.toml``)
with :func:`bearingfe.sweep.sweep`: every case is one converged periodic
revolution of the plunger shoe (``bearingfe.simulate``: the quasi-static
equilibrium of paper eq. 13-14). It draws a contour plot of the smallest film
over the cycle and reports the best design, with the oil it draws from the
pocket (the price of the thicker film).

Sanity bounds (stated, then asserted): a central pocket of a few per cent of
the area thickens the smallest film against the plain shoe (the paper's
headline, and examples/01 for the 10 % pocket); failed cases are only shoes
that lift off (pocket lift above the plunger force) or whose film closes at an
arc edge (an off-centre pocket tilts the shoe), each recorded with its reason.

``BEARINGFE_QUICK=1`` runs a 2x2 grid on a coarse P1 mesh from the steady
state (for the test suite).
Run: ``PYTHONPATH=. python examples/03_pocket_study.py [OUT_DIR]`` (default
``examples/output/03_pocket_study/``).
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from bearingfe.sweep import apply_changes, best_design, csv_headers, read_study, sweep

STUDY = Path(__file__).resolve().parents[1] / "studies" / "pump_pocket_study.toml"


def contour_figure(table, output: str, label: str, scale: float = 1.0):
    """Filled contours of ``scale * output`` over (pocket position, pocket fraction); failed and ruptured
    cases blank and marked, with a legend."""
    from matplotlib.figure import Figure

    grid = table.pivot_table(index="pocket_fraction", columns="pocket_position", values=output,
                             dropna=False)
    fig = Figure(figsize=(6.0, 4.5), layout="constrained")
    ax = fig.add_subplot()
    x, y = grid.columns.to_numpy(float), 100 * grid.index.to_numpy(float)
    z = scale * grid.to_numpy(float)
    filled = ax.contourf(x, y, z, levels=12, cmap="viridis")
    ax.contour(x, y, z, levels=12, colors="k", linewidths=0.4)
    bar = fig.colorbar(filled, ax=ax, label=label)
    bar.formatter.set_useOffset(False)  # absolute values on the bar, no "1e-5 + ..." offset
    for status, marker, what in (("completed", "w.", "completed"), ("ruptured", "rx", "film ruptured"),
                                 ("failed", "m+", "failed")):
        rows = table["status"] == status
        if rows.any():
            ax.plot(table.loc[rows, "pocket_position"], 100 * table.loc[rows, "pocket_fraction"], marker, ms=6,
                    label=what)
    ax.legend(loc="upper right", fontsize="small", facecolor="0.85")
    ax.set_xlabel("pocket position along the arc, s [-]")
    ax.set_ylabel("pocket area fraction [%]")
    ax.set_title("pocket study")
    return fig


#: This example's own output folder (next to it, whatever the working directory).
OUT = Path(__file__).resolve().parent / "output" / Path(__file__).stem


def main(out_dir: str | Path = OUT) -> None:
    study = read_study(STUDY)
    changes, base = study.changes, study.base
    if os.environ.get("BEARINGFE_QUICK") == "1":
        changes = {"pocket_fraction": [0.0, 0.06], "pocket_position": [0.45, 0.5]}
        base = apply_changes(base, {"mesh_size": 0.3, "element": "P1", "start": "steady"})
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    table = sweep(base, changes, study.outputs, run=study.run, cache=out / "cache", progress=True)
    table.rename(columns=csv_headers(table.columns, study.run)).to_csv(out / "pocket_study.csv", index=False)

    best = best_design(table, study.objective, study.sense)
    ok = table["error"].isna()
    plain = table[(table["pocket_fraction"] == 0.0) & ok]["h_min"].iloc[0]
    central = table[(table["pocket_fraction"] > 0.0) & (table["pocket_position"] == 0.5) & ok]
    print(table.drop(columns=["key"]).to_string())
    print(f"best design ({study.sense} {study.objective}): pocket fraction {best['pocket_fraction']:.0%}, "
          f"position s = {best['pocket_position']:.2f}: smallest film {best['h_min'] * 1e6:.2f} um "
          f"(plain shoe {plain * 1e6:.2f} um), pocket oil {best['flow_inlet'] * 6e4:.3f} l/min")
    ruptured = int((table["status"] == "ruptured").sum())
    print(f"{len(table)} cases: {ruptured} ruptured (the film closes: not viable designs), "
          f"{int((table['status'] == 'failed').sum())} failed")
    fig = contour_figure(table, "h_min", "smallest film over the cycle [um]", scale=1e6)
    fig.savefig(out / "pocket_study.png", dpi=120)

    # the sanity bounds stated in the docstring
    failures = table.loc[table["error"].notna(), "error"]
    assert all(("LiftOffError" in e) or ("film" in e) for e in failures), failures.tolist()
    assert len(central) > 0 and (central["h_min"] > plain).all(), (central["h_min"].tolist(), plain)


if __name__ == "__main__":  # required: the sweep starts worker processes with "spawn"
    main(os.environ.get("BEARINGFE_OUT") or (sys.argv[1] if len(sys.argv) == 2 else OUT))
