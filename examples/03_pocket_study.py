"""Pocket study: area fraction 0-20 % x position along the arc.

Designers place a high-pressure inlet pocket in the shoe surface to carry part
of the load hydrostatically (source paper 004: a pocket of 10 % of the surface
raised the smallest film over the pump cycle by almost 40 % against the plain
surface). This script sweeps the pocket's area fraction ``A_pocket / A_shoe``
and the position of its centroid along the arc, ``s = (phi_c - alpha1) /
(alpha2 - alpha1)``, with :func:`bearingfe.sweep.sweep`, draws a contour plot
of the ranking output over the grid and reports the best design.

The run is the study file's (``studies/pocket_study.toml``): while the pump
transient is not in the package the run is the static shoe of
:class:`bearingfe.sweep.ShoeCase` (a fixed cosine film ``h = 1 + gamma
cos(phi - phi0)``, pocket at ``p_s``), whose smallest film is fixed by
``gamma`` and whose ranking output is the film force ``|int p (cos phi, sin
phi)|`` [mu omega R0^4 / c^2] (pockets included).

Sanity bound (stated, then asserted): at fixed film, any pocket at a positive
pressure carries at least what the plain shoe carries plus ``p_s`` times the
pocket's own projected area (the land pressure around a pocket is positive);
so the best design must carry more than the plain one, and the failures may
only be pockets that do not fit on the surface.

``BEARINGFE_QUICK=1`` runs a 2x2 grid on a coarse mesh (for the test suite).
Run: ``PYTHONPATH=. python examples/03_pocket_study.py [OUT_DIR]``.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from bearingfe.sweep import apply_changes, best_design, read_study, sweep

STUDY = Path(__file__).resolve().parents[1] / "studies" / "pocket_study.toml"


def contour_figure(table, output: str, label: str):
    """Filled contours of ``output`` over (pocket position, pocket fraction); failed cases blank."""
    from matplotlib.figure import Figure

    grid = table.pivot_table(index="pocket_fraction", columns="pocket_position", values=output,
                             dropna=False)
    fig = Figure(figsize=(6.0, 4.5), layout="constrained")
    ax = fig.add_subplot()
    x, y = grid.columns.to_numpy(float), 100 * grid.index.to_numpy(float)
    filled = ax.contourf(x, y, grid.to_numpy(float), levels=12, cmap="viridis")
    ax.contour(x, y, grid.to_numpy(float), levels=12, colors="k", linewidths=0.4)
    fig.colorbar(filled, ax=ax, label=label)
    ok = table["error"].isna()
    ax.plot(table.loc[ok, "pocket_position"], 100 * table.loc[ok, "pocket_fraction"], "w.", ms=4)
    ax.plot(table.loc[~ok, "pocket_position"], 100 * table.loc[~ok, "pocket_fraction"], "rx", ms=6,
            label="failed")
    ax.set_xlabel("pocket position along the arc, s [-]")
    ax.set_ylabel("pocket area fraction [%]")
    ax.set_title("pocket study")
    return fig


def main(out_dir: str = "runs/pocket_study") -> None:
    study = read_study(STUDY)
    changes, base = study.changes, study.base
    if os.environ.get("BEARINGFE_QUICK") == "1":
        changes = {"pocket_fraction": [0.0, 0.1], "pocket_position": [0.4, 0.6]}
        base = apply_changes(base, {"mesh_size": 0.2}) if hasattr(base, "mesh_size") else base
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    table = sweep(base, changes, study.outputs, run=study.run, cache=out / "cache", progress=True)
    table.to_csv(out / "pocket_study.csv", index=False)

    best = best_design(table, study.objective, study.sense)
    plain = table[(table["pocket_fraction"] == 0.0) & table["error"].isna()][study.objective]
    print(table.drop(columns=["key"]).to_string())
    print(f"best design ({study.sense} {study.objective}): pocket fraction {best['pocket_fraction']:.0%}, "
          f"position s = {best['pocket_position']:.2f}: {study.objective} = {best[study.objective]:.4g} "
          f"(plain shoe {plain.iloc[0]:.4g})")
    fig = contour_figure(table, study.objective, study.objective)
    fig.savefig(out / "pocket_study.png", dpi=120)

    # the sanity bounds stated in the docstring
    failures = table.loc[table["error"].notna(), "error"]
    assert all("Surface.inlets" in e for e in failures), failures.tolist()
    assert best[study.objective] > plain.iloc[0], (best[study.objective], plain.iloc[0])


if __name__ == "__main__":  # required: the sweep starts worker processes with "spawn"
    main(os.environ.get("BEARINGFE_OUT") or (sys.argv[1] if len(sys.argv) == 2 else "runs/pocket_study"))
