"""simulate(..., cavitation="jfo"): backward-Euler steps that carry the fill fraction over the pump cycle."""

import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe import transient
from tests.helpers import ROOT


@pytest.fixture(scope="module")
def pump_and_mesh():
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    return pump, transient.pump_mesh(pump, 0.08)


@pytest.mark.slow
def test_jfo_transient_converges_to_the_full_film_trajectory(pump_and_mesh):
    # the shipped pump's film never ruptures (its smallest nodal pressure over the cycle is the edge's 0),
    # so JFO must follow the paper's model ("none", integrated by LSODA at rtol 1e-6) up to the
    # backward-Euler error, first order in the step: measured max |d gamma| 0.0131 (18 steps per
    # quarter turn) and 0.0067 (36)
    pump, mesh = pump_and_mesh
    ref = bf.simulate(pump, mesh, 0.25, cavitation="none", points_per_revolution=144)
    errors = []
    for per_rev in (72, 144):
        run = bf.simulate(pump, mesh, 0.25, cavitation="jfo", points_per_revolution=per_rev)
        assert run.status == "completed" and run.stats["cavitated_fraction_max"] == 0.0
        assert run.mass_balance_relative < 1e-12            # each step conserves mass
        gamma_ref = np.interp(run.beta, ref.beta, ref.gamma)
        errors.append(np.abs(run.gamma - gamma_ref).max())
    assert errors[1] < 0.03 and 1.6 < errors[0] / errors[1] < 2.5


def test_jfo_transient_bad_input(pump_and_mesh):
    pump, mesh = pump_and_mesh
    with pytest.raises(ValueError, match="P1"):
        bf.simulate(pump, mesh, 0.1, cavitation="jfo", element="P2")
    with pytest.raises(ValueError, match="start"):
        bf.simulate(pump, mesh, 0.1, cavitation="jfo", start="cold")


@pytest.mark.slow
def test_pump_scene_runs_with_jfo(tmp_path, scene_file):
    import json

    from bearingfe.cli import main
    scene = scene_file("pump", title="JFO scene", pump={"compare_plain": False}, elastic=None, output={"pictures": []},
                       run={"revolutions": 0.1, "start": "steady", "mesh_size": 0.15, "element": "P1", "rtol": None,
                            "frames": 2, "cavitation": "jfo"})
    assert main(["run", str(scene), "--out", str(tmp_path / "out")]) == 0
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    text = json.dumps(summary)
    assert "smallest film" in text and (tmp_path / "out" / "pressure.pvd").exists()
